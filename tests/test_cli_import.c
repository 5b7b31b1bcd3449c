/* The command line of issue 18's imports, run as a separate program
 * (vl_test_run): compound add --measured prints its notes and warnings on
 * stderr and takes --moduli; surface add --psd-kind; compound show the loss
 * peak within the measured window and the model's outside it; friction's
 * warning when a point's frequencies leave that window; surface show
 * --plot [--out DIR]. Refusals leave the database unchanged. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define PI 3.14159265358979323846

/* A shear master curve (G', G'' in MPa against f in Hz) of a three-term
 * creep series, 0.1..100 rad/s: below its loss peak (~1e3 rad/s). */
static const char *write_master(void) {
  static char text[4096];
  size_t k = (size_t)snprintf(text, sizeof text, "f [Hz],G' [MPa],G'' [MPa]\n");
  const double a[3] = {5, 10, 20}, tau[3] = {1e-2, 1e-3, 1e-4};
  for (int i = 0; i <= 18; i++) {
    double w = pow(10.0, -1.0 + i / 6.0);
    double complex j = 1.0;
    for (int t = 0; t < 3; t++)
      j += a[t] / (1.0 - I * w * tau[t]);
    double complex e = 1e9 / j;
    k += (size_t)snprintf(text + k, sizeof text - k, "%.9g,%.9g,%.9g\n", w / (2 * PI),
                          creal(e) / 3e6, fabs(cimag(e)) / 3e6);
  }
  return vl_test_scratch("master.csv", text);
}

static char *run2(char **err, int want, const char *args) {
  char *out = NULL;
  int rc = vl_test_run(&out, err, "%s", args);
  if (rc != want) fail_msg("`%s` exited %d: %s", args, rc, *err ? *err : "");
  return out;
}

static void test_measured_notes_and_moduli(void **state) {
  (void)state;
  const char *f = write_master();
  char args[2048], *err = NULL, *out;
  snprintf(args, sizeof args, "compound add m --measured %s --tref 20", f);
  out = run2(&err, 0, args);
  assert_non_null(strstr(out, "added compound 'm'"));
  /* the conversion is said, on stderr, as a note */
  assert_non_null(strstr(err, "note: shear moduli ('G' [MPa]', 'G'' [MPa]') converted"));
  free(out), free(err);
  /* --quiet drops the notes */
  snprintf(args, sizeof args, "--quiet compound add q --measured %s --tref 20", f);
  out = run2(&err, 0, args);
  assert_string_equal(err, "");
  free(out), free(err);
  /* --moduli tensile on G columns: refused, nothing stored */
  vl_test_expect_fail(2, "holds shear moduli but the options say tensile", NULL,
                      "compound add t --measured %s --tref 20 --moduli tensile", f);
  vl_test_expect_fail(2, "--moduli: 'bulk' is not tensile or shear", NULL,
                      "compound add t --measured %s --tref 20 --moduli bulk", f);
  vl_test_expect_fail(2, "option --moduli belongs to --measured FILE", NULL,
                      "compound add t --prony x.csv --e-inf 1e9 --nu 0.5 --moduli shear");
  /* --moduli shear on generic names: converted (3 x the tensile reading) */
  const char *g = vl_test_scratch("generic.csv", "omega [rad/s],storage [Pa],loss [Pa]\n"
                                                 "1,1e6,1e5\n10,1.2e6,1.5e5\n100,1.5e6,2e5\n");
  snprintf(args, sizeof args,
           "compound add s --measured %s --tref 20 --moduli shear --terms-per-decade 0.5", g);
  out = run2(&err, 0, args);
  assert_non_null(strstr(err, "converted to tensile ones"));
  free(out), free(err);
}

static void test_show_window_peak(void **state) {
  (void)state;
  char args[2048], *err = NULL, *out;
  snprintf(args, sizeof args, "compound add m --measured %s --tref 20", write_master());
  free(run2(&err, 0, args)), free(err);
  out = run2(&err, 0, "compound show m");
  /* the data stop before the peak: the window's upper end, still rising */
  assert_non_null(strstr(out, "at 100 rad/s (15.9155 Hz) within the measured window (its upper "
                              "end: still rising)"));
  assert_non_null(strstr(out, "represented   well"));
  free(out), free(err);
  out = run2(&err, 0, "compound show m --json");
  assert_true(vl_test_json_valid(out));
  assert_non_null(strstr(out, "\"at_edge\": \"upper\""));
  assert_non_null(strstr(out, "\"loss_peak_outside_decades\""));
  free(out), free(err);
  /* a Prony compound: the one peak line as before, no window */
  out = run2(&err, 0, "compound show model-rubber");
  assert_non_null(strstr(out, "tan delta max"));
  assert_null(strstr(out, "measured window"));
  free(out), free(err);
  /* friction on the measured compound: v0 q1 far above 100 rad/s */
  out = run2(&err, 0,
             "friction --compound m --surface paper-0.1um --fluid water --speed 1e-3 --load 117");
  assert_non_null(strstr(err, "warning: asperity frequency v0 q1 7.8e+06 rad/s over a decade "
                              "above the measured window (top 1e+02 rad/s)"));
  free(out), free(err);
  out = run2(&err, 0,
             "friction --compound model-rubber --surface paper-0.1um --fluid water "
             "--speed 1e-3");
  assert_null(strstr(err, "measured"));
  free(out), free(err);
}

/* The real shear export (../shared/data/real, never copied here): its
 * model peak lies beyond the window and is labelled so. */
static void test_real_model_peak(void **state) {
  (void)state;
  char path[2048];
  struct stat sb;
  const char *up[2] = {"..", "../.."}; /* beside the checkout, or beside its worktree folder */
  for (int i = 0; i < 2; i++) {
    snprintf(path, sizeof path, "%s/%s/shared/data/real/marcusni96_material_a_tf_015p.csv",
             vl_test_source_path("."), up[i]);
    if (stat(path, &sb) == 0) break;
  }
  if (stat(path, &sb) != 0) {
    fprintf(stderr, "SKIPPED: %s absent (the real exports live outside the repository)\n", path);
    skip();
  }
  char args[2400], *err = NULL, *out;
  snprintf(args, sizeof args, "compound add a --measured %s --nu 0.494", path);
  free(run2(&err, 0, args));
  assert_non_null(strstr(err, "note: ignored 3 columns"));
  free(err);
  out = run2(&err, 0, "compound show a");
  fprintf(stderr, "%s", out);
  assert_non_null(strstr(out, "within the measured window (its upper end: still rising)"));
  assert_non_null(strstr(out, "model peak"));
  assert_non_null(strstr(out, "decades above the measured window: extrapolated"));
  free(out), free(err);
}

static void test_psd_kind_and_plot(void **state) {
  (void)state;
  /* C1 = 1e-24 m^3 (q/1e6)^-3 over 1e6..1e8 1/m as a 1-D spectrum */
  const char *p = vl_test_scratch("c1.csv", "q [1/um],C1 [m^3]\n1,1e-24\n10,1e-27\n100,1e-30\n");
  char args[2048], *err = NULL, *out;
  snprintf(args, sizeof args, "surface add one --psd %s --psd-kind 1d", p);
  out = run2(&err, 0, args);
  assert_non_null(strstr(out, "added surface 'one'"));
  assert_non_null(strstr(err, "note: 1-D (profile) spectrum converted"));
  free(out), free(err);
  vl_test_expect_fail(2, "--psd-kind: '3d' is not 1d or 2d", NULL,
                      "surface add two --psd %s --psd-kind 3d", p);
  vl_test_expect_fail(2, "option --psd-kind belongs to --psd FILE", NULL,
                      "surface add two --self-affine --hurst 0.8 --q0 1e4 --q1 1e8 --hrms 1e-6 "
                      "--psd-kind 1d");
  /* an exact self-affine table: the fit gives its H back */
  char text[4096];
  size_t k = (size_t)snprintf(text, sizeof text, "q_per_m,C_m4\n");
  for (int i = 0; i <= 20; i++) {
    double q = 1e5 * pow(10.0, 0.2 * i);
    k += (size_t)snprintf(text + k, sizeof text - k, "%.17g,%.17g\n", q,
                          1e-26 * pow(q / 1e5, -2.0 * 1.7));
  }
  snprintf(args, sizeof args, "surface add tab --psd %s", vl_test_scratch("tab.csv", text));
  free(run2(&err, 0, args)), free(err);
  /* --plot is a flag and --out DIR its folder, as in every command */
  const char *dir = vl_test_scratch("psd-tab", NULL);
  snprintf(args, sizeof args, "surface show tab --plot --out %s", dir);
  out = run2(&err, 0, args);
  assert_non_null(strstr(out, "(self-affine fit: H 0.7, rms"));
  free(out), free(err);
  char png[1200], svg[1200];
  snprintf(png, sizeof png, "%s/psd.png", dir);
  snprintf(svg, sizeof svg, "%s/psd.svg", dir);
  struct stat sb;
  assert_int_equal(stat(png, &sb), 0);
  assert_true(sb.st_size > 1000);
  assert_int_equal(stat(svg, &sb), 0);
  /* the figure has a title naming the surface (the PSD had none) */
  char *svg_text = vl_test_read_file(svg);
  assert_non_null(strstr(svg_text, "<title>Roughness power spectrum — surface tab</title>"));
  assert_non_null(strstr(svg_text, "<desc>tabulated, 21 points"));
  free(svg_text);
  /* a self-affine surface draws its own law; without --out the figure goes
   * to out/surface-NAME, as compound show's to out/compound-NAME */
  char env[1400];
  snprintf(env, sizeof env, "cd %s && env -u VISCOLUBE_DB", vl_test_dir);
  snprintf(args, sizeof args, "--db %s surface show paper-0.1um --plot", vl_test_db);
  assert_int_equal(vl_test_cli(env, args, &out, NULL), 0);
  assert_non_null(strstr(out, "plot (png, svg) in out/surface-paper-0.1um: psd"));
  assert_null(strstr(out, "fit"));
  free(out);
  svg_text = vl_test_read_file(vl_test_scratch("out/surface-paper-0.1um/psd.svg", NULL));
  assert_non_null(svg_text);
  assert_non_null(
      strstr(svg_text, "<title>Roughness power spectrum — surface paper-0.1um</title>"));
  assert_non_null(strstr(svg_text, "<desc>self-affine, H 0.8"));
  free(svg_text);
  vl_test_expect_fail(2, "unknown option '--curve'", NULL, "surface show tab --curve x.csv");
  /* the old spelling --plot FILE: said what changed, nothing written */
  vl_test_expect_fail(2, "--plot takes no file: it draws DIR/psd.png and .svg", "(got 'psd.png')",
                      "surface show tab --plot psd.png");
  vl_test_expect_fail(2, "--plot takes no file", "(got 'psd')", "surface show --plot psd tab");
  vl_test_expect_fail(2, "option --out goes with --plot", NULL, "surface show tab --out d");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_measured_notes_and_moduli, vl_test_setup_db),
      cmocka_unit_test_setup(test_show_window_peak, vl_test_setup_db),
      cmocka_unit_test_setup(test_real_model_peak, vl_test_setup_db),
      cmocka_unit_test_setup(test_psd_kind_and_plot, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
