/* The material commands of the command line (`viscolube compound|surface|
 * fluid VERB`), run as a separate program through vl_test_cli. Checks the
 * output against the paper and closed forms, the JSON with an independent
 * validator, and every class of bad input: one message on stderr naming
 * file, line and column (or the option), a non-zero exit status, and the
 * database file byte-for-byte unchanged. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <math.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define PI 3.14159265358979323846

static size_t count_of(const char *s, const char *needle) {
  size_t n = 0;
  for (const char *p = s; (p = strstr(p, needle)); p += strlen(needle))
    n++;
  return n;
}

/* ---- running the program ---------------------------------------------- */

/* Runs and requires success; returns stdout (caller frees). */
static char *run_ok(const char *fmt, const char *arg) {
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, fmt, arg);
  if (rc != 0) fail_msg("`%s` (%s) exited %d: %s", fmt, arg, rc, err ? err : "");
  assert_string_equal(err, "");
  free(err);
  return out;
}

static void create_db(void) { free(run_ok("compound list%s", "")); }

/* Self-affine closed forms (see test_database.c). */
static double closed_c0(double H, double q0, double q1, double h) {
  return H * h * h / (PI * q0 * q0 * (1.0 - pow(q0 / q1, 2.0 * H)));
}
static double closed_slope(double H, double q0, double q1, double h) {
  return sqrt(2.0 * PI * closed_c0(H, q0, q1, h) * pow(q0, 2.0 + 2.0 * H) *
              (pow(q1, 2.0 - 2.0 * H) - pow(q0, 2.0 - 2.0 * H)) / (2.0 - 2.0 * H));
}

/* ---- help and listing ------------------------------------------------- */

static void test_help_everywhere(void **state) {
  (void)state;
  const char *nouns[] = {"compound", "surface", "fluid"};
  const char *verbs[] = {"list", "show", "add", "remove"};
  char *out, *err;
  assert_int_equal(vl_test_run(&out, &err, "--help"), 0);
  assert_non_null(strstr(out, "usage: viscolube"));
  free(out), free(err);
  for (int n = 0; n < 3; n++) {
    assert_int_equal(vl_test_run(&out, &err, "%s --help", nouns[n]), 0);
    assert_non_null(strstr(out, "usage: viscolube"));
    for (int v = 0; v < 4; v++)
      assert_non_null(strstr(out, verbs[v]));
    assert_string_equal(err, "");
    free(out), free(err);
    for (int v = 0; v < 4; v++) {
      /* help wins over anything else on the line, and opens no database */
      assert_int_equal(vl_test_run(&out, &err, "%s %s --bogus --help", nouns[n], verbs[v]), 0);
      char want[64];
      snprintf(want, sizeof want, "%s %s", nouns[n], verbs[v]);
      if (!strstr(out, want)) fail_msg("help of %s lacks '%s': %s", want, want, out);
      assert_string_equal(err, "");
      free(out), free(err);
    }
    /* a noun without a verb: usage on stderr, status 2 */
    assert_int_equal(vl_test_run(&out, &err, "%s", nouns[n]), 2);
    assert_string_equal(out, "");
    assert_non_null(strstr(err, "usage:"));
    free(out), free(err);
  }
  assert_int_not_equal(access(vl_test_db, F_OK), 0);
  /* the add help documents the file formats */
  assert_int_equal(vl_test_run(&out, &err, "compound add --help"), 0);
  assert_non_null(strstr(out, "A,tau_s"));
  free(out), free(err);
  assert_int_equal(vl_test_run(&out, &err, "surface add --help"), 0);
  assert_non_null(strstr(out, "q_per_m,C_m4"));
  free(out), free(err);
}

static void test_list_fresh_database(void **state) {
  (void)state;
  char *out = run_ok("compound list --json%s", "");
  if (!vl_test_json_valid(out)) fail_msg("invalid JSON: %s", out);
  assert_true(out[0] == '[');
  assert_int_equal(count_of(out, "\"name\""), 3); /* + the shipped sbr-filled, sbr-unfilled */
  assert_non_null(strstr(out, "\"model-rubber\""));
  free(out);
  /* the paper's 7 surfaces and the seal cases' 2 (materials/0008_later_shipped_materials.sql) */
  out = run_ok("surface list --json%s", "");
  if (!vl_test_json_valid(out)) fail_msg("invalid JSON: %s", out);
  assert_int_equal(count_of(out, "\"name\""), 9);
  free(out);
  /* 7, the seal cases' oil and glycerol-water-85 (materials/0007_glycerol_water.sql) */
  out = run_ok("fluid list --json%s", "");
  if (!vl_test_json_valid(out)) fail_msg("invalid JSON: %s", out);
  assert_int_equal(count_of(out, "\"name\""), 9);
  free(out);

  /* text: one line per item, starting with the name */
  const char *nouns[] = {"compound", "surface", "fluid"};
  /* compounds: + the shipped sbr-filled, sbr-unfilled; surfaces and fluids: + the seal
   * cases' (materials/0008_later_shipped_materials.sql); fluids: + glycerol-water-85 */
  const size_t lines[] = {3, 9, 9};
  for (int n = 0; n < 3; n++) {
    out = run_ok("%s list", nouns[n]);
    assert_int_equal(count_of(out, "\n"), lines[n]);
    free(out);
  }
  out = run_ok("surface list%s", "");
  assert_non_null(strstr(out, "\npaper-3um "));
  assert_non_null(strstr(out, "self-affine"));
  free(out);
  out = run_ok("fluid list%s", "");
  assert_non_null(strstr(out, "\nwater "));
  free(out);
}

/* ---- show: derived quantities against the paper and closed forms ------ */

static void test_show_model_rubber(void **state) {
  (void)state;
  char *out = run_ok("compound show model-rubber --json%s", "");
  if (!vl_test_json_valid(out)) fail_msg("invalid JSON: %s", out);
  /* Fig. 5 caption: E0 = 3.6 MPa, Einf/E0 = 10, nu = 0.5, tau = 0.1 s */
  assert_true(vl_test_rel(vl_test_json_number(out, "e0_pa", 0), 3.6e6) < 1e-14);
  assert_true(vl_test_rel(vl_test_json_number(out, "e_inf_pa", 0), 36e6) < 1e-14);
  assert_true(vl_test_json_number(out, "nu", 0) == 0.5);
  assert_true(vl_test_json_number(out, "A", 0) == 9.0);
  assert_true(vl_test_json_number(out, "tau_s", 0) == 0.1);
  assert_non_null(strstr(out, "\"class\": \"model\""));
  free(out);
  out = run_ok("compound show model-rubber%s", "");
  assert_non_null(strstr(out, "E0"));
  assert_non_null(strstr(out, "3.6e+06 Pa"));
  assert_non_null(strstr(out, "3.6e+07 Pa"));
  assert_non_null(strstr(out, "rad/s"));
  assert_non_null(strstr(out, "Hz"));
  free(out);
}

/* The loss-tangent peak of a one-term solid. With
 * 1/E = (1/Einf)(1 + A/(1 - i w tau)): |tan delta| = A w tau / (1 + A + (w tau)^2),
 * maximal at w tau = sqrt(1 + A) with height A / (2 sqrt(1 + A)).
 * For the model rubber: w = sqrt(10)/0.1 = 31.62 rad/s, tan delta = 1.4230.
 * Tolerances: the peak is flat, so its location is found to ~1e-6 relative
 * by a golden-section search on floating-point values; the height is
 * second-order insensitive to that and is checked to 1e-9. */
static void test_show_loss_peak(void **state) {
  (void)state;
  char *out = run_ok("compound show model-rubber --json%s", "");
  const double A = 9.0, tau = 0.1;
  double w = sqrt(1.0 + A) / tau, td = A / (2.0 * sqrt(1.0 + A));
  double w_got = vl_test_json_number(out, "omega_rad_s", 0),
         td_got = vl_test_json_number(out, "tan_delta", 0);
  if (!(vl_test_rel(w_got, w) < 1e-6 && vl_test_rel(td_got, td) < 1e-9))
    fail_msg("loss peak %g at %g rad/s; closed form %.10g at %.10g rad/s", td_got, w_got, td, w);
  assert_true(vl_test_rel(vl_test_json_number(out, "frequency_hz", 0), w / (2.0 * PI)) < 1e-6);
  free(out);
}

static void test_show_surface_and_fluid(void **state) {
  (void)state;
  char *out = run_ok("surface show %s --json", "paper-3um");
  if (!vl_test_json_valid(out)) fail_msg("invalid JSON: %s", out);
  assert_true(vl_test_rel(vl_test_json_number(out, "hrms_m", 0), 3e-6) < 1e-12);
  assert_true(vl_test_rel(vl_test_json_number(out, "c0_m4", 0), closed_c0(0.8, 2e5, 7.8e9, 3e-6)) <
              1e-12);
  assert_true(vl_test_rel(vl_test_json_number(out, "rms_slope", 0),
                          closed_slope(0.8, 2e5, 7.8e9, 3e-6)) < 1e-12);
  assert_true(vl_test_json_number(out, "hurst", 0) == 0.8);
  assert_true(vl_test_json_number(out, "q0_per_m", 0) == 2e5 &&
              vl_test_json_number(out, "q1_per_m", 0) == 7.8e9);
  free(out);
  out = run_ok("surface show %s", "paper-0.5um");
  assert_non_null(strstr(out, "h_rms"));
  assert_non_null(strstr(out, "rms slope"));
  assert_non_null(strstr(out, "C0"));
  free(out);
  out = run_ok("fluid show %s --json", "water");
  if (!vl_test_json_valid(out)) fail_msg("invalid JSON: %s", out);
  assert_true(vl_test_json_number(out, "viscosity_pa_s", 0) == 1e-3);
  assert_true(vl_test_json_number(out, "tref_c", 0) == 20.0);
  free(out);
  out = run_ok("fluid show %s", "glycerol");
  assert_non_null(strstr(out, "1.41 Pa s at 20 C"));
  free(out);
}

/* ---- add, show, remove ------------------------------------------------ */

static void test_compound_add_show_remove(void **state) {
  (void)state;
  const char *csv =
      vl_test_scratch("terms.csv", "# fitted 2024\nA,tau_s\n1,s\n2.5,1e-4\n7.5,0.02\n");
  char *out, *err;
  int rc = vl_test_run(&out, &err,
                       "compound add sbr-1 --prony %s --e-inf 1e9 --nu 0.49 --class filled "
                       "--description 'lab \"B\" \\ 2024' --tref 25 --wlf-c1 8.86 --wlf-c2 101.6",
                       csv);
  if (rc != 0) fail_msg("add failed (%d): %s", rc, err);
  assert_non_null(strstr(out, "sbr-1"));
  free(out), free(err);
  out = run_ok("compound show %s --json", "sbr-1");
  if (!vl_test_json_valid(out)) fail_msg("invalid JSON: %s", out);
  /* E0 = Einf / (1 + sum A) = 1e9 / 11 */
  assert_true(vl_test_rel(vl_test_json_number(out, "e0_pa", 0), 1e9 / 11.0) < 1e-14);
  assert_true(vl_test_json_number(out, "A", 1) == 7.5 &&
              vl_test_json_number(out, "tau_s", 1) == 0.02);
  assert_true(vl_test_json_number(out, "wlf_c1", 0) == 8.86 &&
              vl_test_json_number(out, "tref_c", 0) == 25.0);
  assert_non_null(strstr(out, "\"class\": \"filled\""));
  assert_non_null(strstr(out, "lab \\\"B\\\" \\\\ 2024")); /* escaped in JSON */
  assert_non_null(strstr(out, "terms.csv"));
  free(out);
  out = run_ok("compound list%s", "");
  assert_int_equal(count_of(out, "\n"), 4);
  free(out);
  out = run_ok("compound list --json%s", "");
  if (!vl_test_json_valid(out)) fail_msg("invalid JSON: %s", out);
  free(out);
  free(run_ok("compound remove %s", "sbr-1"));
  vl_test_expect_fail(3, "'sbr-1'", NULL, "compound show sbr-1");
}

static void test_surface_add_show_remove(void **state) {
  (void)state;
  free(run_ok("surface add %s --self-affine --hurst 0.7 --q0 1e4 --q1 1e9 --hrms 2e-6", "road"));
  char *out = run_ok("surface show %s --json", "road");
  if (!vl_test_json_valid(out)) fail_msg("invalid JSON: %s", out);
  assert_true(vl_test_rel(vl_test_json_number(out, "c0_m4", 0), closed_c0(0.7, 1e4, 1e9, 2e-6)) <
              1e-12);
  assert_true(vl_test_rel(vl_test_json_number(out, "rms_slope", 0),
                          closed_slope(0.7, 1e4, 1e9, 2e-6)) < 1e-12);
  free(out);

  /* A two-point table is an exact power law C = Cs (q/qa)^(-2(1+H)), so
   * h_rms^2 = (pi Cs qa^2 / H) (1 - (qa/qb)^(2H)) (closed form, 1e-12). */
  const double H = 0.8, qa = 1e5, qb = 1e8, Cs = 1e-22, Cb = Cs * pow(qb / qa, -2.0 * (1.0 + H));
  char text[256];
  snprintf(text, sizeof text, "q_per_m,C_m4\n1/m,m^4\n%.17g,%.17g\n%.17g,%.17g\n", qa, Cs, qb, Cb);
  const char *csv = vl_test_scratch("psd.csv", text);
  char *err;
  int rc = vl_test_run(&out, &err, "surface add measured --psd %s --description 'scan 3'", csv);
  if (rc != 0) fail_msg("add failed (%d): %s", rc, err);
  free(out), free(err);
  out = run_ok("surface show %s --json", "measured");
  if (!vl_test_json_valid(out)) fail_msg("invalid JSON: %s", out);
  double h2 = PI * Cs * qa * qa / H * (1.0 - pow(qa / qb, 2.0 * H));
  assert_true(vl_test_rel(vl_test_json_number(out, "hrms_m", 0), sqrt(h2)) < 1e-12);
  assert_true(vl_test_json_number(out, "n_points", 0) == 2.0);
  assert_true(isnan(vl_test_json_number(out, "c0_m4", 0)) &&
              isnan(vl_test_json_number(out, "hurst", 0)));
  assert_non_null(strstr(out, "\"kind\": \"tabulated\""));
  free(out);
  out = run_ok("surface show %s", "measured");
  assert_non_null(strstr(out, "points        2"));
  free(out);
  free(run_ok("surface remove %s", "measured"));
  free(run_ok("surface remove %s", "road"));
  out = run_ok("surface list%s", "");
  assert_int_equal(count_of(out, "\n"), 9); /* the shipped ones, one line each */
  free(out);
}

static void test_fluid_add_show_remove(void **state) {
  (void)state;
  free(run_ok("fluid add %s --viscosity 0.35 --tref 40 --description 'PAO 40'", "pao-40"));
  char *out = run_ok("fluid show %s --json", "pao-40");
  if (!vl_test_json_valid(out)) fail_msg("invalid JSON: %s", out);
  assert_true(vl_test_json_number(out, "viscosity_pa_s", 0) == 0.35);
  assert_true(vl_test_json_number(out, "tref_c", 0) == 40.0);
  free(out);
  free(run_ok("fluid remove %s", "pao-40"));
  vl_test_expect_fail(3, "pao-40", NULL, "fluid show pao-40");
}

/* ---- bad input: one message, non-zero status, file unchanged --------- */

static void test_bad_files(void **state) {
  (void)state;
  create_db();
  const char *add = "compound add r --e-inf 36e6 --nu 0.5 --prony";
  struct {
    const char *file, *text, *where, *what;
  } prony[] = {
      {"nonnum.csv", "A,tau_s\n9,0.1\n1,abc\n", "nonnum.csv:3:", "'tau_s'"},
      {"nan.csv", "A,tau_s\n9,NaN\n", "nan.csv:2:", "NaN"},
      {"inf.csv", "A,tau_s\n9,0.1\nInf,1\n", "inf.csv:3:", "'A'"},
      {"negtau.csv", "A,tau_s\n9,-0.1\n", "negtau.csv:2:", "'tau_s'"},
      {"zerotau.csv", "A,tau_s\n9,0\n", "zerotau.csv:2:", "> 0"},
      {"negA.csv", "A,tau_s\n-9,0.1\n", "negA.csv:2:", "'A'"},
      {"empty.csv", "", "empty.csv:1:", "empty file"},
      {"blank.csv", "\n\n", "blank.csv:2:", "empty file"},
      {"nohdr.csv", "9,0.1\n", "nohdr.csv:1:", "missing header"},
      {"misspelt.csv", "A,tau_sec\n9,0.1\n", "misspelt.csv:1:", "did you mean 'tau_s'"},
      {"lacks.csv", "A\n9\n", "lacks.csv:1:", "'tau_s'"},
      {"units.csv", "A,tau_s\nPa,s\n9,0.1\n", "units.csv:2:", "'1,s'"},
      {"fields.csv", "A,tau_s\n9,0.1,3\n", "fields.csv:2:", "found 3"},
      {"header.csv", "A,tau_s\n", "header.csv:1:", "no data rows"},
  };
  for (size_t i = 0; i < sizeof prony / sizeof *prony; i++)
    vl_test_expect_fail(2, prony[i].where, prony[i].what, "%s %s", add,
                        vl_test_scratch(prony[i].file, prony[i].text));

  struct {
    const char *file, *text, *where, *what;
  } psd[] = {
      {"steep.csv", "q_per_m,C_m4\n1e6,1e-22\n1e5,1e-20\n", "steep.csv:", "rms slope"},
      {"dupq.csv", "q_per_m,C_m4\n1e5,1e-20\n1e5,1e-21\n", "dupq.csv:3:", "distinct q"},
      {"negq.csv", "q_per_m,C_m4\n-1e5,1e-20\n1e6,1e-21\n", "negq.csv:2:", "'q_per_m'"},
      {"zeroc.csv", "q_per_m,C_m4\n1e5,0\n1e6,1e-21\n", "zeroc.csv:2:", "'C_m4'"},
      {"negc.csv", "q_per_m,C_m4\n1e5,1e-20\n1e6,-1e-21\n", "negc.csv:3:", "'C_m4'"},
      {"psdunits.csv", "q_per_m,C_m4\n1/m,m^2\n1e5,1e-20\n1e6,1e-21\n", "psdunits.csv:2:", "'m^2'"},
      {"psdhdr.csv", "q,C\n1e5,1e-20\n1e6,1e-21\n", "psdhdr.csv:1:", "no unit"},
      {"one.csv", "q_per_m,C_m4\n1e5,1e-20\n", "one.csv:2:", "at least 2"},
      {"psdempty.csv", "", "psdempty.csv:1:", "empty file"},
      {"psdnan.csv", "q_per_m,C_m4\n1e5,nan\n1e6,1e-21\n", "psdnan.csv:2:", "NaN"},
  };
  for (size_t i = 0; i < sizeof psd / sizeof *psd; i++)
    vl_test_expect_fail(2, psd[i].where, psd[i].what, "surface add s --psd %s",
                        vl_test_scratch(psd[i].file, psd[i].text));

  vl_test_expect_fail(6, "missing.csv", "cannot open", "%s %s/missing.csv", add, vl_test_dir);
  vl_test_expect_fail(6, "missing.csv", NULL, "surface add s --psd %s/missing.csv", vl_test_dir);
}

static void test_bad_options(void **state) {
  (void)state;
  create_db();
  const char *ok = vl_test_scratch("ok.csv", "A,tau_s\n9,0.1\n");
  const char *pre = "compound add r --prony";
  vl_test_expect_fail(2, "--e-inf", "> 0", "%s %s --e-inf -1 --nu 0.5", pre, ok);
  vl_test_expect_fail(2, "--e-inf", "> 0", "%s %s --e-inf 0 --nu 0.5", pre, ok);
  vl_test_expect_fail(2, "--e-inf", "not a number", "%s %s --e-inf 36MPa --nu 0.5", pre, ok);
  vl_test_expect_fail(2, "--e-inf", "NaN", "%s %s --e-inf nan --nu 0.5", pre, ok);
  vl_test_expect_fail(2, "--e-inf", "needs a value", "%s %s --nu 0.5 --e-inf", pre, ok);
  vl_test_expect_fail(2, "--e-inf", "needs a value", "%s %s --e-inf --nu 0.5", pre, ok);
  vl_test_expect_fail(2, "--nu", "[0, 0.5]", "%s %s --e-inf 1e6 --nu -0.3", pre, ok);
  vl_test_expect_fail(2, "--nu", "[0, 0.5]", "%s %s --e-inf 1e6 --nu 0.7", pre, ok);
  vl_test_expect_fail(2, "--nu", "required", "%s %s --e-inf 1e6", pre, ok);
  vl_test_expect_fail(2, "--prony", "required", "compound add r --e-inf 1e6 --nu 0.5");
  vl_test_expect_fail(2, "--class", "rubbery", "%s %s --e-inf 1e6 --nu 0.5 --class rubbery", pre,
                      ok);
  vl_test_expect_fail(2, "unknown option '--frobnicate'", NULL,
                      "%s %s --e-inf 1e6 --nu 0.5 --frobnicate", pre, ok);
  vl_test_expect_fail(2, "--nu", "twice", "%s %s --e-inf 1e6 --nu 0.5 --nu 0.4", pre, ok);
  vl_test_expect_fail(2, "--wlf-c1", "--wlf-c2", "%s %s --e-inf 1e6 --nu 0.5 --wlf-c1 8", pre, ok);
  vl_test_expect_fail(2, "missing NAME", NULL, "compound add --prony %s --e-inf 1e6 --nu 0.5", ok);
  vl_test_expect_fail(2, "'a/b'", NULL, "compound add a/b --prony %s --e-inf 1e6 --nu 0.5", ok);
  vl_test_expect_fail(2, "unexpected argument 'extra'", NULL, "fluid show water extra");
  vl_test_expect_fail(2, "unknown verb 'frob'", NULL, "compound frob");
  vl_test_expect_fail(2, "missing NAME", NULL, "surface show");
  vl_test_expect_fail(2, "unknown option '--xml'", NULL, "fluid list --xml");

  const char *sa = "surface add s --self-affine";
  vl_test_expect_fail(2, "--hurst", "(0, 1]", "%s --hurst 0 --q0 2e5 --q1 7.8e9 --hrms 1e-6", sa);
  vl_test_expect_fail(2, "--hurst", "(0, 1]", "%s --hurst 1.5 --q0 2e5 --q1 7.8e9 --hrms 1e-6", sa);
  vl_test_expect_fail(2, "--hurst", "(0, 1]", "%s --hurst -0.2 --q0 2e5 --q1 7.8e9 --hrms 1e-6",
                      sa);
  vl_test_expect_fail(2, "--q1", "--q0", "%s --hurst 0.8 --q0 7.8e9 --q1 2e5 --hrms 1e-6", sa);
  vl_test_expect_fail(2, "--q1", "--q0", "%s --hurst 0.8 --q0 2e5 --q1 2e5 --hrms 1e-6", sa);
  vl_test_expect_fail(2, "--q0", "> 0", "%s --hurst 0.8 --q0 -2e5 --q1 7.8e9 --hrms 1e-6", sa);
  vl_test_expect_fail(2, "--q0", "> 0", "%s --hurst 0.8 --q0 0 --q1 7.8e9 --hrms 1e-6", sa);
  vl_test_expect_fail(2, "--hrms", "> 0", "%s --hurst 0.8 --q0 2e5 --q1 7.8e9 --hrms 0", sa);
  vl_test_expect_fail(2, "--hrms", "> 0", "%s --hurst 0.8 --q0 2e5 --q1 7.8e9 --hrms -1e-6", sa);
  vl_test_expect_fail(2, "--hrms", NULL, "%s --hurst 0.8 --q0 2e5 --q1 7.8e9", sa);
  vl_test_expect_fail(2, "--q1", "infinity", "%s --hurst 0.8 --q0 2e5 --q1 inf --hrms 1e-6", sa);
  vl_test_expect_fail(2, "--psd", "--self-affine", "surface add s --self-affine --psd %s", ok);
  vl_test_expect_fail(2, "--hurst", "--psd", "surface add s --psd %s --hurst 0.8", ok);
  vl_test_expect_fail(2, "--self-affine", "--psd", "surface add s --description x");

  vl_test_expect_fail(2, "--viscosity", "> 0", "fluid add oil --viscosity 0");
  vl_test_expect_fail(2, "--viscosity", "> 0", "fluid add oil --viscosity -1e-3");
  vl_test_expect_fail(2, "--viscosity", "infinity", "fluid add oil --viscosity inf");
  vl_test_expect_fail(2, "--viscosity", "not a number", "fluid add oil --viscosity thick");
  vl_test_expect_fail(2, "--viscosity", "required", "fluid add oil");
  vl_test_expect_fail(2, "--tref", "absolute zero", "fluid add oil --viscosity 1 --tref -300");
}

static void test_unknown_and_duplicate_names(void **state) {
  (void)state;
  create_db();
  vl_test_expect_fail(3, "'model-ruber'", "did you mean 'model-rubber'",
                      "compound show model-ruber");
  vl_test_expect_fail(3, "'paper-3umm'", "did you mean 'paper-3um'",
                      "surface show paper-3umm --json");
  vl_test_expect_fail(3, "'watr'", "did you mean 'water'", "fluid show watr");
  vl_test_expect_fail(3, "'nothing'", NULL, "compound remove nothing");
  vl_test_expect_fail(3, "'nothing'", NULL, "surface remove nothing");
  vl_test_expect_fail(3, "'nothing'", NULL, "fluid remove nothing");
  const char *ok = vl_test_scratch("ok.csv", "A,tau_s\n9,0.1\n");
  vl_test_expect_fail(4, "'model-rubber'", "already exists",
                      "compound add model-rubber --prony %s --e-inf 1e6 --nu 0.5", ok);
  vl_test_expect_fail(
      4, "'paper-1um'", "already exists",
      "surface add paper-1um --self-affine --hurst 0.8 --q0 2e5 --q1 7.8e9 --hrms 1e-6");
  vl_test_expect_fail(4, "'water'", "already exists", "fluid add water --viscosity 1e-3");
}

/* ---- database files the program must not touch ------------------------ */

static void test_newer_schema(void **state) {
  (void)state;
  create_db();
  sqlite3 *h;
  assert_int_equal(sqlite3_open(vl_test_db, &h), SQLITE_OK);
  assert_int_equal(sqlite3_exec(h, "PRAGMA user_version = 999", NULL, NULL, NULL), SQLITE_OK);
  sqlite3_close(h);
  vl_test_expect_fail(5, "newer", "999", "compound list");
  vl_test_expect_fail(5, "newer", NULL, "fluid add oil --viscosity 1");
  vl_test_expect_fail(5, "newer", NULL, "fluid remove water");
}

/* chmod 0444 on the database. The tests run as root, for whom the kernel
 * would allow the write anyway: the program must honour the bits. */
static void test_readonly_database(void **state) {
  (void)state;
  create_db();
  assert_int_equal(chmod(vl_test_db, 0444), 0);
  vl_test_snapshot before = vl_test_take(vl_test_db);
  char *out = run_ok("fluid list%s", "");
  assert_int_equal(count_of(out, "\n"), 9);
  free(out);
  vl_test_expect_fail(5, "read-only", NULL, "fluid add oil --viscosity 0.1");
  vl_test_expect_fail(5, "read-only", NULL, "compound remove model-rubber");
  vl_test_expect_fail(5, "read-only", NULL,
                      "surface add s --self-affine --hurst 0.8 --q0 2e5 --q1 7.8e9 --hrms 1e-6");
  vl_test_expect_fail(5, "read-only", NULL, "fluid remove water");
  assert_true(vl_test_same_db(vl_test_db, &before));
  free(before.bytes);
  chmod(vl_test_db, 0644);
}

static void test_corrupt_database(void **state) {
  (void)state;
  unsigned char junk[16384];
  unsigned long x = 2463534242UL;
  for (size_t i = 0; i < sizeof junk; i++) {
    x ^= x << 13, x ^= x >> 17, x ^= x << 5;
    junk[i] = (unsigned char)(x >> 3);
  }
  FILE *f = fopen(vl_test_db, "wb");
  fwrite(junk, 1, sizeof junk, f);
  fclose(f);
  vl_test_expect_fail(5, vl_test_db, "not a valid viscolube database", "compound list --json");
  vl_test_expect_fail(5, vl_test_db, NULL, "fluid add oil --viscosity 0.1");
  vl_test_expect_fail(5, vl_test_db, NULL, "surface remove paper-1um");
  /* another program's SQLite file */
  unlink(vl_test_db);
  sqlite3 *h;
  assert_int_equal(sqlite3_open(vl_test_db, &h), SQLITE_OK);
  assert_int_equal(sqlite3_exec(h, "CREATE TABLE t (x)", NULL, NULL, NULL), SQLITE_OK);
  sqlite3_close(h);
  vl_test_expect_fail(5, "not a viscolube database", NULL, "fluid list");
}

/* ---- which database: --db, $VISCOLUBE_DB, XDG, HOME ------------------- */

static void test_database_selection(void **state) {
  (void)state;
  char env[4096], args[4096], a[1300], b[1300];
  snprintf(a, sizeof a, "%s/a.db", vl_test_dir);
  snprintf(b, sizeof b, "%s/b.db", vl_test_dir);
  /* --db wins over $VISCOLUBE_DB */
  snprintf(env, sizeof env, "VISCOLUBE_DB=%s", a);
  snprintf(args, sizeof args, "--db %s fluid list", b);
  assert_int_equal(vl_test_cli(env, args, NULL, NULL), 0);
  assert_int_equal(access(b, F_OK), 0);
  assert_int_not_equal(access(a, F_OK), 0);
  /* $VISCOLUBE_DB alone */
  assert_int_equal(vl_test_cli(env, "fluid list", NULL, NULL), 0);
  assert_int_equal(access(a, F_OK), 0);
  /* $XDG_DATA_HOME, directories created */
  snprintf(env, sizeof env, "env -u VISCOLUBE_DB XDG_DATA_HOME=%s/xdg HOME=%s/home", vl_test_dir,
           vl_test_dir);
  assert_int_equal(vl_test_cli(env, "compound list", NULL, NULL), 0);
  snprintf(a, sizeof a, "%s/xdg/viscolube/materials.db", vl_test_dir);
  assert_int_equal(access(a, F_OK), 0);
  /* $HOME/.local/share */
  snprintf(env, sizeof env, "env -u VISCOLUBE_DB -u XDG_DATA_HOME HOME=%s/home", vl_test_dir);
  char *out = NULL;
  assert_int_equal(vl_test_cli(env, "compound list --json", &out, NULL), 0);
  assert_non_null(strstr(out, "model-rubber"));
  free(out);
  snprintf(a, sizeof a, "%s/home/.local/share/viscolube/materials.db", vl_test_dir);
  assert_int_equal(access(a, F_OK), 0);
  /* a bad add never creates the database */
  snprintf(b, sizeof b, "%s/never.db", vl_test_dir);
  snprintf(args, sizeof args, "--db %s fluid add oil --viscosity -1", b);
  assert_int_equal(vl_test_cli(NULL, args, NULL, NULL), 2);
  assert_int_not_equal(access(b, F_OK), 0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_help_everywhere, vl_test_setup_db),
      cmocka_unit_test_setup(test_list_fresh_database, vl_test_setup_db),
      cmocka_unit_test_setup(test_show_model_rubber, vl_test_setup_db),
      cmocka_unit_test_setup(test_show_loss_peak, vl_test_setup_db),
      cmocka_unit_test_setup(test_show_surface_and_fluid, vl_test_setup_db),
      cmocka_unit_test_setup(test_compound_add_show_remove, vl_test_setup_db),
      cmocka_unit_test_setup(test_surface_add_show_remove, vl_test_setup_db),
      cmocka_unit_test_setup(test_fluid_add_show_remove, vl_test_setup_db),
      cmocka_unit_test_setup(test_bad_files, vl_test_setup_db),
      cmocka_unit_test_setup(test_bad_options, vl_test_setup_db),
      cmocka_unit_test_setup(test_unknown_and_duplicate_names, vl_test_setup_db),
      cmocka_unit_test_setup(test_newer_schema, vl_test_setup_db),
      cmocka_unit_test_setup(test_readonly_database, vl_test_setup_db),
      cmocka_unit_test_setup(test_corrupt_database, vl_test_setup_db),
      cmocka_unit_test_setup(test_database_selection, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
