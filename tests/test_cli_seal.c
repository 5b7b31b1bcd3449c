/* `viscolube seal` end to end (issue 33): a seal scene without a [seal]
 * section gets both strokes; seal.csv, seal.json and stdout's JSON agree
 * with each other and with the volumes' definition pi D L q / v; the
 * figure is written and recorded; the console table of `run` shows the
 * rolling terms of a moving counter-surface as n/a, curve.csv says why its
 * cells are empty; a seal scene whose [seal] says stroke = out still gets
 * both; the instroke's points above their target are listed
 * and set the exit status; a scene that is not a seal's is refused. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* A soft elastic O-ring-like contact on a smooth rod (the film of
 * tests/test_seals.c), coarse cells, two speeds, a sealed pressure (so the
 * strokes differ); extra goes into [contact]. */
static const char *scene(const char *name, const char *extra, const char *numerics) {
  char text[1024];
  snprintf(text, sizeof text,
           "[materials]\ncompound = model-rubber\nfluid = model-1e-1\n"
           "[contact]\nradius_m = 0.01\nload_n_per_m = 1000\n%s"
           "[sweep]\nquantity = v0\nfrom = 0.01\nto = 0.1\npoints = 2\n"
           "[effects]\nviscoelastic = off\nfluid = on\n"
           "[numerics]\ngrid = 256\ndomain_a0 = -3, 1.5\n%s",
           extra, numerics);
  return vl_test_scratch(name, text);
}

static int exists(const char *path) {
  struct stat sb;
  return stat(path, &sb) == 0;
}

/* The k-th comma-separated field of the line of csv that starts with the
 * (row + 1)-th data line after the header (0: first), as a number. */
static double csv_cell(const char *csv, size_t row, size_t k) {
  const char *l = csv;
  while (*l == '#')
    l = strchr(l, '\n') + 1;
  l = strchr(l, '\n') + 1; /* the header */
  for (size_t r = 0; r < row; r++)
    l = strchr(l, '\n') + 1;
  for (size_t c = 0; c < k; c++)
    l = strchr(l, ',') + 1;
  return *l == ',' || *l == '\n' ? NAN : strtod(l, NULL);
}

static void test_seal_outputs(void **state) {
  (void)state;
  const char *s = scene("oring.ini", "moving = counterface\nsealed_pressure_pa = 3.9e4\n",
                        "target_error = 0.5\n");
  char *out = NULL, *err = NULL, dir[1200];
  snprintf(dir, sizeof dir, "%s/o", vl_test_dir);
  int rc = vl_test_run(&out, &err, "seal %s --out %s --json --plot --quiet", s, dir);
  if (rc != 0) fail_msg("seal exited %d: %s", rc, err);
  size_t objects = 0;
  assert_true(vl_test_json_array_valid(out, &objects));
  assert_int_equal(objects, 2);
  char path[1300];
  snprintf(path, sizeof path, "%s/seal.json", dir);
  char *file = vl_test_read_file(path);
  assert_string_equal(file, out); /* the same writer, the same numbers */
  snprintf(path, sizeof path, "%s/seal.csv", dir);
  char *csv = vl_test_read_file(path);
  assert_non_null(strstr(csv, "v0_m_s,friction_out_n_per_m,friction_in_n_per_m,mu_out,mu_in"));
  for (size_t i = 0; i < 2; i++) {
    double v = vl_test_json_number(out, "v0_m_s", i);
    double qo = vl_test_json_number(out, "flux_m2_s", 2 * i),
           qi = vl_test_json_number(out, "flux_m2_s", 2 * i + 1);
    double vo = vl_test_json_number(out, "volume_out_m3", i),
           vb = vl_test_json_number(out, "volume_back_m3", i);
    double fo = vl_test_json_number(out, "friction_n_per_m", 2 * i),
           mo = vl_test_json_number(out, "mu", 2 * i);
    printf("  v0 %g m/s: flux %.6g out, %.6g in; volumes %.6g, %.6g; F %.6g N/m; CSV %.10g %.10g\n",
           v, qo, qi, vo, vb, fo, csv_cell(csv, i, 9), csv_cell(csv, i, 10));
    /* the sealed pressure's flow is with the outstroke, against the instroke */
    assert_true(qo > qi);
    assert_true(fabs(fo / (1000.0 * mo) - 1.0) < 1e-12);
    assert_true(fabs(csv_cell(csv, i, 9) / qo - 1.0) < 1e-9);
    assert_true(fabs(csv_cell(csv, i, 10) / qi - 1.0) < 1e-9);
    assert_true(fabs(csv_cell(csv, i, 1) / fo - 1.0) < 1e-9);
  }
  /* no [seal] rod_diameter_m: no volumes, tightness unknown */
  assert_non_null(strstr(out, "\"volume_out_m3\": null"));
  assert_non_null(strstr(out, "\"tight\": null"));
  /* with a rod: the volumes per cycle pi D L q / v, and the sealed
   * pressure's seal lets out more than it carries back */
  free(out), free(err);
  const char *s2;
  {
    char *t = vl_test_read_file(s);
    vl_test_text tx = {0};
    vl_test_text_add(&tx, "%s[seal]\nrod_diameter_m = 0.02\nstroke_length_m = 0.1\nstroke = out\n",
                     t);
    s2 = vl_test_scratch("rod.ini", tx.s);
    free(t), free(tx.s);
  }
  rc = vl_test_run(&out, &err, "seal %s --out %s/rod --json --quiet", s2, vl_test_dir);
  if (rc != 0) fail_msg("seal exited %d: %s", rc, err);
  for (size_t i = 0; i < 2; i++) {
    double v = vl_test_json_number(out, "v0_m_s", i);
    double qo = vl_test_json_number(out, "flux_m2_s", 2 * i),
           qi = vl_test_json_number(out, "flux_m2_s", 2 * i + 1);
    double vo = vl_test_json_number(out, "volume_out_m3", i),
           vb = vl_test_json_number(out, "volume_back_m3", i);
    printf("  with the rod: %.6g m^3 out, %.6g back per cycle\n", vo, vb);
    assert_true(fabs(vo / (M_PI * 0.02 * 0.1 * qo / v) - 1.0) < 1e-12);
    assert_true(fabs(vb / (M_PI * 0.02 * 0.1 * qi / v) - 1.0) < 1e-12);
    assert_true(vo > vb);
  }
  assert_non_null(strstr(out, "\"tight\": false"));
  snprintf(path, sizeof path, "%s/seal.png", dir);
  assert_true(exists(path));
  snprintf(path, sizeof path, "%s/run.json", dir);
  char *man = vl_test_read_file(path);
  assert_non_null(strstr(man, "seal.csv"));
  assert_non_null(strstr(man, "seal.svg"));
  free(man), free(csv), free(file), free(out), free(err);
}

/* The console: both strokes' table; `run`'s table of a moving
 * counter-surface shows n/a for the rolling terms, curve.csv says why its
 * cells are empty; a moving rubber's still shows numbers. */
static void test_seal_console(void **state) {
  (void)state;
  const char *s = scene("c.ini", "moving = counterface\n", "target_error = 0.5\n");
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "seal %s --out %s/c --quiet", s, vl_test_dir);
  if (rc != 0) fail_msg("seal exited %d: %s", rc, err);
  printf("%s", out);
  assert_non_null(strstr(out, "F_out_N/m"));
  assert_non_null(strstr(out, "instroke: 2 converged"));
  free(out), free(err);
  rc = vl_test_run(&out, &err, "run %s --out %s/r --quiet", s, vl_test_dir);
  assert_int_equal(rc, 0);
  const char *row = strstr(out, "\n       0.01");
  assert_non_null(row);
  printf("%.120s\n", row + 1);
  assert_non_null(strstr(row, " n/a        n/a "));
  char path[1300];
  snprintf(path, sizeof path, "%s/r/curve.csv", vl_test_dir);
  char *csv = vl_test_read_file(path);
  assert_true(strncmp(csv, "# mu_Rc, mu_Rf: not applicable", 30) == 0);
  free(csv), free(out), free(err);
  const char *rubber = scene("rubber.ini", "", "target_error = 0.5\n");
  rc = vl_test_run(&out, &err, "run %s --out %s/rr --quiet", rubber, vl_test_dir);
  assert_int_equal(rc, 0);
  assert_null(strstr(out, "n/a"));
  free(out), free(err);
  /* not a seal's scene: refused, nothing computed */
  rc = vl_test_run(&out, &err, "seal %s --out %s/x", rubber, vl_test_dir);
  printf("  %s", err);
  assert_int_equal(rc, 2);
  assert_non_null(strstr(err, "a seal needs [contact] moving = counterface"));
  free(out), free(err);
}

/* Points above their error target in the instroke are listed as the
 * instroke's and give exit status 8 (target 1e-6: every point of both
 * strokes is above it), by `seal` and by `run` of a stroke = both scene. */
static void test_seal_status(void **state) {
  (void)state;
  const char *s = scene("t.ini", "moving = counterface\n", "target_error = 1e-6\n");
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "seal %s --out %s/t", s, vl_test_dir);
  printf("  exit %d\n%s", rc, err);
  assert_int_equal(rc, 8);
  assert_non_null(strstr(err, "viscolube seal: instroke: 2 of 2 points are not known"));
  free(out), free(err);
  /* `run` of a scene with both strokes counts its instroke the same way */
  s = scene("b.ini", "moving = counterface\n", "target_error = 1e-6\n[seal]\nstroke = both\n");
  rc = vl_test_run(&out, &err, "run %s --out %s/b", s, vl_test_dir);
  printf("  exit %d\n%s", rc, err);
  assert_int_equal(rc, 8);
  assert_non_null(strstr(err, "viscolube run: instroke: 2 of 2 points are not known"));
  free(out), free(err);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_seal_outputs, vl_test_setup_db),
      cmocka_unit_test_setup(test_seal_console, vl_test_setup_db),
      cmocka_unit_test_setup(test_seal_status, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
