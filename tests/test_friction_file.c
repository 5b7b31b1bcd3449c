/* The measured Stribeck curve reader (csv.h, vl_friction_curve_read_text):
 * units from the header, dialects, and what it refuses. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "csv_private.h"
#include "viscolube/csv.h"

static vl_status read(const char *text, double **v, double **mu, size_t *n, vl_error *err) {
  return vl_friction_curve_read_text(text, strlen(text), "c.csv", v, mu, n, err);
}

static void test_units_and_dialects(void **state) {
  (void)state;
  const struct {
    const char *text;
    double v1, mu1;
  } ok[] = {
      {"v [m/s],mu\n1e-3,0.5\n2e-3,0.4\n", 2e-3, 0.4},
      {"# rig 3\nspeed (mm/s);CoF;force [N]\n1;0,5;3\n2,5;0,25;3\n", 2.5e-3, 0.25},
      {"Sliding speed [um/s]\tfriction\n10\t0.5\n20\t0.125\n", 20e-6, 0.125},
      {"v_m_s,mu\n0.1,0.5\n0.2,0.3\n", 0.2, 0.3},
      {"\"v [m/min]\",\"mu [-]\"\n6,0.5\n12,0.2\n", 0.2, 0.2},
  };
  for (size_t k = 0; k < sizeof ok / sizeof *ok; k++) {
    double *v = NULL, *mu = NULL;
    size_t n = 0;
    vl_error err;
    if (read(ok[k].text, &v, &mu, &n, &err) != VL_OK) fail_msg("case %zu: %s", k, err.msg);
    assert_int_equal(n, 2);
    if (!(fabs(v[1] - ok[k].v1) <= 1e-15 * ok[k].v1 && mu[1] == ok[k].mu1))
      fail_msg("case %zu: got v %g mu %g", k, v[1], mu[1]);
    free(v), free(mu);
  }
}

static void test_refused(void **state) {
  (void)state;
  const struct {
    const char *text, *needle;
  } bad[] = {
      {"v,mu\n1,0.5\n", "needs its unit"},
      {"v [furlong/s],mu\n1,0.5\n", "unknown speed unit"},
      {"v [m/s],force\n1,0.5\n", "no mu column"},
      {"time,mu\n1,0.5\n", "no speed column"},
      {"v [m/s],mu\n1,abc\n2,0.3\n3\n", "c.csv:2"},
      {"v [m/s],mu\n", "no data rows"},
  };
  for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
    double *v = NULL, *mu = NULL;
    size_t n = 0;
    vl_error err = {{0}};
    assert_int_equal(read(bad[k].text, &v, &mu, &n, &err), VL_EINPUT);
    if (!strstr(err.msg, bad[k].needle))
      fail_msg("case %zu: '%s' lacks '%s'", k, err.msg, bad[k].needle);
    assert_null(v);
    assert_int_equal(n, 0);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_units_and_dialects),
      cmocka_unit_test(test_refused),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
