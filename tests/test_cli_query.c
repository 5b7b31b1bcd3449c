/* `viscolube friction` and `viscolube compare` end to end, on the shipped
 * materials: answers, their consistency with a scene run, the filled vs
 * unfilled statement of the seed (Figs. 15-17), figures, and bad input. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static char g_db[4200];

static int setup(void **state) {
  (void)state;
  snprintf(g_db, sizeof g_db, "%s/materials.db", vl_test_tmpdir());
  return 0;
}

/* Value of "key": number in a flat JSON object (NAN if absent or null). */
static double json_number(const char *json, const char *key) {
  char pat[128];
  snprintf(pat, sizeof pat, "\"%s\": ", key);
  const char *p = strstr(json, pat);
  if (!p) return NAN;
  p += strlen(pat);
  if (!strncmp(p, "null", 4)) return NAN;
  return strtod(p, NULL);
}

static void test_friction_point(void **state) {
  (void)state;
  char args[8192], *out = NULL, *err = NULL;
  /* the fig05 contact at v0 eta = 1e-6 Pa m (the mu_Rc peak region) */
  snprintf(args, sizeof args,
           "--db %s friction --compound model-rubber --surface paper-3um --fluid model-1e-4 "
           "--speed 0.01 --radius 0.01 --load 1000 --grid 128 --json",
           g_db);
  int rc = vl_test_cli(NULL, args, &out, &err);
  /* 128 cells are coarse for this point: it converges, and says it is above
   * its 1 % target (exit status 8, accuracy above_target); the parts must
   * sum to mu either way */
  if (rc != 0 && rc != 8) fail_msg("exit %d: %s", rc, err);
  if (rc == 8) assert_non_null(strstr(out, "\"accuracy\": \"above_target\""));
  double mu = json_number(out, "mu"), rc_ = json_number(out, "mu_Rc"),
         rf = json_number(out, "mu_Rf"), sc = json_number(out, "mu_Sc"),
         sf = json_number(out, "mu_Sf");
  printf("  friction: mu %.5f = Rc %.5f + Rf %.2g + Sc %.5f + Sf %.2g\n", mu, rc_, rf, sc, sf);
  assert_true(strstr(out, "\"converged\": true") != NULL);
  assert_true(fabs(mu - (rc_ + rf + sc + sf)) < 1e-9);
  /* boundary regime, rolling friction dominant near its peak (fig05) */
  assert_true(strstr(out, "\"regime\": \"boundary\"") != NULL);
  assert_true(rc_ > sc && rc_ > 0.03);
  free(out);
  free(err);

  /* the text form names the components */
  snprintf(args, sizeof args,
           "--db %s friction --compound model-rubber --surface paper-3um --fluid model-1e-4 "
           "--speed 0.01 --radius 0.01 --load 1000 --grid 128",
           g_db);
  rc = vl_test_cli(NULL, args, &out, &err);
  assert_true(rc == 0 || rc == 8); /* as above: coarse cells */
  if (rc == 8) assert_non_null(strstr(out, "ABOVE the target"));
  assert_non_null(strstr(out, "mu_Rc"));
  assert_non_null(strstr(out, "regime: boundary"));
  free(out);
  free(err);
}

static void test_friction_bad_input(void **state) {
  (void)state;
  struct {
    const char *args;
    int rc;
    const char *needle;
  } cases[] = {
      {"friction --compound nope --surface paper-3um --fluid water --speed 1 --grid 64", 3, "nope"},
      {"friction --compound model-rubber --surface nope --fluid water --speed 1 --grid 64", 3,
       "nope"},
      {"friction --compound model-rubber --surface paper-3um --fluid nope --speed 1 --grid 64", 3,
       "nope"},
      {"friction --compound model-rubber --surface paper-3um --fluid water", 2, "--speed"},
      {"friction --compound model-rubber --surface paper-3um --fluid water --speed -1", 2,
       "--speed"},
      {"friction --compound model-rubber --surface paper-3um --fluid water --speed 1 --load 0", 2,
       "--load"},
      {"friction --compound model-rubber --surface paper-3um --fluid water --speed 1 --grid 3", 2,
       "--grid"},
      {"friction --compound model-rubber --surface paper-3um --fluid water --speed 1 --bogus", 2,
       "--bogus"},
      {"compare --surface paper-3um --fluid water", 2, "--compounds"},
      {"compare --compounds model-rubber,nope --surface paper-3um --fluid water --points 3 "
       "--grid 64 --from 1e-12 --to 1e-10",
       3, "nope"},
      {"compare --compounds model-rubber --surface paper-3um --fluid water --from 0.1 --to 0.1", 2,
       "--from"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char args[8192], *out = NULL, *err = NULL;
    snprintf(args, sizeof args, "--db %s %s", g_db, cases[i].args);
    int rc = vl_test_cli(NULL, args, &out, &err);
    if (rc != cases[i].rc || !strstr(err, cases[i].needle))
      fail_msg("'%s': exit %d (wanted %d), stderr: %s", cases[i].args, rc, cases[i].rc, err);
    free(out);
    free(err);
  }
  char *out = NULL;
  assert_int_equal(vl_test_cli(NULL, "friction --help", &out, NULL), 0);
  assert_non_null(strstr(out, "--compound"));
  free(out);
  assert_int_equal(vl_test_cli(NULL, "compare --help", &out, NULL), 0);
  assert_non_null(strstr(out, "--compounds"));
  free(out);
}

/* Seed Figs. 15-17: the unfilled rubber has larger friction than the filled
 * one over (almost) all speeds, and the filled one's u_min/h_rms grows
 * monotonically with speed. Coarse (grid 96, 7 points over 10 decades)
 * but every point must converge; the default flow factors (persson-emt),
 * which the file says in its first line. */
static void test_compare_filled_unfilled(void **state) {
  (void)state;
  char dir[2048], args[8192], path[4400], *out = NULL, *err = NULL;
  snprintf(dir, sizeof dir, "%s/cmp", vl_test_tmpdir());
  snprintf(args, sizeof args,
           "--db %s compare --compounds sbr-unfilled,sbr-filled --surface paper-0.5um --fluid "
           "water --from 1e-11 --to 1e-1 --points 6 --grid 384 --plot "
           "--out %s",
           g_db, dir);
  int rc = vl_test_cli(NULL, args, &out, &err);
  if (rc != 0) fail_msg("exit %d: %s", rc, err);
  snprintf(path, sizeof path, "%s/compare.csv", dir);
  char *csv = vl_test_read_file(path);
  assert_non_null(csv);
  const char *model = "# flow_factors = persson-emt, film_cutoff_m = 1e-09\n";
  assert_memory_equal(csv, model, strlen(model));
  /* the axis: the speed (m/s), the default for one fluid */
  assert_non_null(strstr(csv, "\nv0_m_s,mu_sbr-unfilled,"));
  /* rows: v0, then 7 columns per compound */
  int rows = 0, above = 0;
  double filled_umin_before = 0.0;
  char *line = strchr(csv + strlen(model), '\n');
  while (line && line[1]) {
    double v[15];
    char *p = line + 1;
    for (int k = 0; k < 15; k++) {
      v[k] = strtod(p, &p);
      if (*p == ',') p++;
    }
    assert_true(v[7] == 1.0 && v[14] == 1.0);                   /* converged */
    if (rows == 0) assert_true(fabs(v[0] / 1e-8 - 1.0) < 1e-9); /* 1e-11 Pa m in water */
    rows++;
    if (v[1] > v[8]) above++;
    /* Seed Fig. 16: the filled rubber's u_min/h_rms grows monotonically */
    assert_true(v[13] > filled_umin_before);
    filled_umin_before = v[13];
    line = strchr(line + 1, '\n');
  }
  printf("  unfilled above filled at %d of %d speeds\n", above, rows);
  assert_int_equal(rows, 6);
  assert_true(above >= rows - 1);
  free(csv);
  /* figures, both formats */
  const char *files[] = {"compare-mu.png",   "compare-mu.svg",       "compare-umin.png",
                         "compare-umin.svg", "sbr-filled/curve.csv", "sbr-unfilled/curve.csv"};
  for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
    struct stat st;
    snprintf(path, sizeof path, "%s/%s", dir, files[i]);
    if (stat(path, &st) != 0 || st.st_size < 100) fail_msg("missing or empty: %s", path);
  }
  snprintf(path, sizeof path, "%s/compare-mu.png", dir);
  char *png = vl_test_read_file(path);
  assert_true(png && !memcmp(png, "\x89PNG\r\n\x1a\n", 8));
  free(png);
  free(out);
  free(err);
}

/* --from and --to given high to low: the same speeds, swept upward from the
 * boundary regime, so the same compare.csv byte for byte (rows in
 * increasing speed) as the range given low to high. */
static void test_compare_range_either_way(void **state) {
  (void)state;
  char *csv[2];
  const char *range[2] = {"--from 1e-12 --to 1e-9", "--from 1e-9 --to 1e-12"};
  for (int k = 0; k < 2; k++) {
    char dir[2048], args[8192], path[4400], *out = NULL, *err = NULL;
    snprintf(dir, sizeof dir, "%s/range%d", vl_test_tmpdir(), k);
    snprintf(args, sizeof args,
             "--db %s compare --compounds model-rubber --surface paper-3um --fluid water %s "
             "--points 4 --grid 64 --out %s --quiet",
             g_db, range[k], dir);
    int rc = vl_test_cli(NULL, args, &out, &err);
    if (rc != 0) fail_msg("%s: exit %d: %s", range[k], rc, err);
    snprintf(path, sizeof path, "%s/compare.csv", dir);
    csv[k] = vl_test_read_file(path);
    assert_non_null(csv[k]);
    free(out);
    free(err);
  }
  assert_string_equal(csv[0], csv[1]);
  free(csv[0]);
  free(csv[1]);
}

/* The same range in m/s (--from-speed/--to-speed; water: eta 1e-3 Pa s)
 * gives the same speeds and friction as in v0 eta, and says both; mixing
 * the units, or one end alone, is bad input. */
static void test_compare_range_in_speed(void **state) {
  (void)state;
  const char *range[2] = {"--from 1e-12 --to 1e-9", "--from-speed 1e-9 --to-speed 1e-6"};
  char *out[2];
  for (int k = 0; k < 2; k++) {
    char dir[2048], args[8192], *err = NULL;
    snprintf(dir, sizeof dir, "%s/speed%d", vl_test_tmpdir(), k);
    snprintf(args, sizeof args,
             "--db %s compare --compounds model-rubber --surface paper-3um --fluid water %s "
             "--points 4 --grid 64 --target-error 0.5 --out %s --quiet",
             g_db, range[k], dir);
    int rc = vl_test_cli(NULL, args, &out[k], &err);
    if (rc != 0) fail_msg("%s: exit %d: %s", range[k], rc, err);
    free(err);
    assert_non_null(strstr(out[k], "speeds: 1e-09 .. 1e-06 m/s (v0 eta 1e-12 .. 1e-09 Pa m"));
  }
  /* the table's rows: speed and mu, to the digits printed (speeds 1 ulp apart
   * at most: v0 eta / eta against the given m/s) */
  const char *r0 = strstr(out[0], "\n       1e-09"), *r1 = strstr(out[1], "\n       1e-09");
  assert_non_null(r0);
  assert_non_null(r1);
  double v0, mu0, v1, mu1;
  assert_int_equal(sscanf(r0, "%lf %lf", &v0, &mu0), 2);
  assert_int_equal(sscanf(r1, "%lf %lf", &v1, &mu1), 2);
  assert_true(v0 == v1 && fabs(mu0 / mu1 - 1.0) < 1e-4);
  free(out[0]);
  free(out[1]);
  char args[8192];
  snprintf(args, sizeof args,
           "--db %s compare --compounds model-rubber --surface paper-3um --fluid water "
           "--from 1e-12 --from-speed 1e-9 --to-speed 1e-6",
           g_db);
  char *o = NULL, *e = NULL;
  assert_int_equal(vl_test_cli(NULL, args, &o, &e), 2);
  assert_non_null(strstr(e, "not both"));
  free(o), free(e), o = e = NULL;
  snprintf(args, sizeof args,
           "--db %s compare --compounds model-rubber --surface paper-3um --fluid water "
           "--from-speed 1e-9",
           g_db);
  assert_int_equal(vl_test_cli(NULL, args, &o, &e), 2);
  assert_non_null(strstr(e, "go together"));
  free(o), free(e);
}

/* A point above its error target is a result of its own: exit status 8,
 * listed on stderr with its estimate, `accuracy` in the JSON, the text form
 * saying so; the same point with a target it meets exits 0. */
static void test_friction_above_target(void **state) {
  (void)state;
  char args[8192], *out = NULL, *err = NULL;
  const char *point = "friction --compound model-rubber --surface paper-3um --fluid model-1e-4 "
                      "--speed 0.01 --radius 0.01 --load 1000 --grid 128";
  snprintf(args, sizeof args, "--db %s %s --target-error 1e-6 --json", g_db, point);
  assert_int_equal(vl_test_cli(NULL, args, &out, &err), 8);
  assert_non_null(strstr(out, "\"accuracy\": \"above_target\""));
  assert_non_null(strstr(err, "1 of 1 points are not known to their error target"));
  assert_non_null(strstr(err, "point 1: v0 = 0.01 m/s, error estimate"));
  double est = json_number(out, "error_estimate");
  free(out), free(err), out = err = NULL;
  /* a target above the estimate: met, exit 0 */
  snprintf(args, sizeof args, "--db %s %s --target-error 0.5 --json", g_db, point);
  int rc = vl_test_cli(NULL, args, &out, &err);
  if (est <= 0.5) {
    assert_int_equal(rc, 0);
    assert_non_null(strstr(out, "\"accuracy\": \"met\""));
  }
  free(out), free(err), out = err = NULL;
  /* a target out of range is bad input, named */
  snprintf(args, sizeof args, "--db %s %s --target-error 2", g_db, point);
  assert_int_equal(vl_test_cli(NULL, args, &out, &err), 2);
  assert_non_null(strstr(err, "--target-error"));
  free(out), free(err);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_friction_point),
      cmocka_unit_test(test_friction_above_target),
      cmocka_unit_test(test_friction_bad_input),
      cmocka_unit_test(test_compare_filled_unfilled),
      cmocka_unit_test(test_compare_range_either_way),
      cmocka_unit_test(test_compare_range_in_speed),
  };
  return cmocka_run_group_tests(tests, setup, NULL);
}
