/* `viscolube pair` end to end (issue 34): add, show, list, remove with the
 * nouns' messages; calibrate on a measured file in mm/s with decimal
 * commas, --json, --save and its provenance, friction then using the pair
 * and saying so; refusals leaving the database unchanged. */
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

#define TRIPLE "--compound sbr-unfilled --surface paper-0.5um --fluid water"

static void test_add_show_remove(void **state) {
  (void)state;
  char *out, *err;
  assert_int_equal(vl_test_run(&out, &err, "pair list"), 0);
  assert_non_null(strstr(out, "no pairs"));
  free(out), free(err);
  assert_int_equal(vl_test_run(&out, &err,
                               "pair add " TRIPLE " --law dewetting --sigma-dry 2e6 "
                               "--sigma-wet 3e5 --v-d 1e-4 --eta-ref 1e-3 --description handbook"),
                   0);
  free(out), free(err);
  assert_int_equal(vl_test_run(&out, &err, "pair show " TRIPLE " --json"), 0);
  assert_true(vl_test_json_valid(out));
  assert_non_null(strstr(out, "\"law\": \"dewetting\""));
  assert_true(vl_test_json_number(out, "v_d_m_s", 0) == 1e-4);
  assert_non_null(strstr(out, "\"source\": \"typed\""));
  free(out), free(err);
  /* friction takes it and says so; --sigma-s overrides it */
  assert_int_equal(vl_test_run(&out, &err, "friction " TRIPLE " --speed 1e-3 --json"), 0);
  assert_non_null(strstr(out, "\"sigma_s_law\": \"dewetting: sigma_dry_pa = 2e+06"));
  free(out), free(err);
  assert_int_equal(vl_test_run(&out, &err, "friction " TRIPLE " --speed 1e-3 --sigma-s 1e6 --json"),
                   0);
  assert_null(strstr(out, "sigma_s_law"));
  free(out), free(err);
  vl_test_expect_fail(4, "already exists", "remove it first",
                      "pair add " TRIPLE " --law constant --sigma-s 1e6");
  vl_test_expect_fail(3, "no fluid named 'watr'", "did you mean 'water'",
                      "pair show --compound sbr-unfilled --surface paper-0.5um --fluid watr");
  vl_test_expect_fail(3, "no pair", "has pairs on paper-0.5um in water",
                      "pair remove --compound sbr-unfilled --surface paper-1um --fluid water");
  vl_test_expect_fail(2, "needs sigma_wet_pa", NULL,
                      "pair add " TRIPLE " --law dewetting --sigma-dry 1e6 --v-d 1");
  vl_test_expect_fail(2, "unknown shear-stress law", NULL, "pair add " TRIPLE " --law eyrin");
  /* a mistyped option gets the nearest one, as in the other commands */
  vl_test_expect_fail(2, "unknown option '--sigma-ss'", "did you mean --sigma-s?",
                      "pair add " TRIPLE " --law constant --sigma-ss 1e6");
  /* removing the fluid removes the pair, and says so */
  assert_int_equal(vl_test_run(&out, &err, "fluid remove water"), 0);
  assert_non_null(strstr(out, "removed fluid 'water'"));
  assert_non_null(strstr(out, "and its 1 pair\n"));
  free(out), free(err);
  assert_int_equal(vl_test_run(&out, &err, "pair list --json"), 0);
  size_t objects = 99;
  assert_true(vl_test_json_array_valid(out, &objects) && objects == 0);
  free(out), free(err);
}

/* A measured curve the program made with sigma_s = 6e5 (a typed pair),
 * times a fixed +-2 % pattern, written in mm/s with decimal commas. */
static const char *measured_file(void) {
  char *out, *err, text[4096];
  assert_int_equal(vl_test_run(&out, &err, "pair add " TRIPLE " --law constant --sigma-s 6e5"), 0);
  free(out), free(err);
  int len = snprintf(text, sizeof text, "# made by viscolube\nv [mm/s];mu\n");
  for (int k = 0; k < 8; k++) {
    double v = pow(10.0, -6.0 + 0.5 * k);
    assert_int_equal(vl_test_run(&out, &err, "friction " TRIPLE " --speed %g --json", v), 0);
    double mu = vl_test_json_number(out, "mu", 0) * (1.0 + (k % 2 ? 0.02 : -0.02));
    free(out), free(err);
    char row[128];
    snprintf(row, sizeof row, "%.6g;%.6g\n", v * 1e3, mu);
    for (char *c = row; *c; c++)
      if (*c == '.') *c = ',';
    len += snprintf(text + len, sizeof text - (size_t)len, "%s", row);
  }
  assert_int_equal(vl_test_run(&out, &err, "pair remove " TRIPLE), 0);
  free(out), free(err);
  return vl_test_scratch("measured.csv", text);
}

static void test_calibrate_save(void **state) {
  (void)state;
  const char *file = measured_file();
  char *out, *err;
  assert_int_equal(vl_test_run(&out, &err, "pair calibrate " TRIPLE " --measured %s --json", file),
                   0);
  assert_true(vl_test_json_valid(out));
  double sigma = vl_test_json_number(out, "sigma_s_pa", 0);
  printf("recovered sigma_s %g (6e5 typed)\n", sigma);
  assert_true(fabs(sigma / 6e5 - 1.0) < 0.03);
  assert_true(vl_test_json_number(out, "rms_log10_mu", 0) < 0.02);
  assert_true(isfinite(vl_test_json_number(out, "sigma_s_pa", 1))); /* ci95 */
  free(out), free(err);
  /* nothing stored without --save */
  vl_test_expect_fail(3, "no pair", NULL, "pair show " TRIPLE);
  assert_int_equal(vl_test_run(&out, &err, "pair calibrate " TRIPLE " --measured %s --save", file),
                   0);
  assert_non_null(strstr(out, "95 % intervals"));
  assert_non_null(strstr(out, "stored as the pair"));
  free(out), free(err);
  assert_int_equal(vl_test_run(&out, &err, "pair show " TRIPLE), 0);
  assert_non_null(strstr(out, "calibrated"));
  assert_non_null(strstr(out, "fnv1a64:"));
  assert_non_null(strstr(out, "8 points"));
  free(out), free(err);
  assert_int_equal(vl_test_run(&out, &err, "friction " TRIPLE " --speed 1e-4"), 0);
  assert_non_null(strstr(out, "sigma_s: constant: sigma_s_pa = "));
  assert_non_null(strstr(out, "calibrated"));
  free(out), free(err);
}

static void test_calibrate_refused(void **state) {
  (void)state;
  char *out, *err;
  /* the database and its Persson and flow-factor caches exist before the snapshots */
  assert_int_equal(vl_test_run(&out, &err, "friction " TRIPLE " --speed 1e-3"), 0);
  free(out), free(err);
  const char *few = vl_test_scratch("few.csv", "v [m/s],mu\n1e-5,0.2\n1e-4,0.1\n1e-3,0.08\n");
  vl_test_expect_fail(2, "at least 4 points", NULL,
                      "pair calibrate " TRIPLE " --measured %s --law eyring --save", few);
  const char *neg = vl_test_scratch("neg.csv", "v [m/s],mu\n1e-5,0.2\n1e-4,-0.1\n1e-3,0.08\n");
  vl_test_expect_fail(2, "positive", NULL, "pair calibrate " TRIPLE " --measured %s --save", neg);
  const char *unitless = vl_test_scratch("nounit.csv", "v,mu\n1e-5,0.2\n");
  vl_test_expect_fail(2, "needs its unit", NULL, "pair calibrate " TRIPLE " --measured %s",
                      unitless);
  /* a curve no constant sigma_s makes: reported, exit 2, not stored */
  const char *wild =
      vl_test_scratch("wild.csv", "v [m/s],mu\n1e-5,0.001\n1e-4,0.01\n1e-3,0.1\n1e-2,1\n");
  assert_int_equal(vl_test_run(&out, &err, "pair calibrate " TRIPLE " --measured %s --save", wild),
                   2);
  assert_non_null(strstr(out, "DOES NOT FIT"));
  assert_non_null(strstr(err, "not stored"));
  free(out), free(err);
  vl_test_expect_fail(3, "no pair", NULL, "pair show " TRIPLE);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_add_show_remove, vl_test_setup_db),
      cmocka_unit_test_setup(test_calibrate_save, vl_test_setup_db),
      cmocka_unit_test_setup(test_calibrate_refused, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
