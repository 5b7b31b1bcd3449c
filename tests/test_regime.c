/* The lubrication regime label (results.h, vl_regime; docs/MODEL.md
 * section 8): load share and film ratio lambda = u_min / h_rms together,
 * at and around every boundary of the definition; and the film ratio in
 * curve.csv and the JSON of a point (empty/null on smooth surfaces). */
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
#include <unistd.h>

#include "contact_private.h"
#include "viscolube/json.h"
#include "viscolube/output.h"
#include "viscolube/results.h"

static void test_regime_boundaries(void **state) {
  (void)state;
  /* no fluid: dry whatever the numbers */
  assert_int_equal(vl_regime_of(0, 1.0, 10.0), VL_REGIME_DRY);
  /* hydrodynamic: share > 0.95 and lambda >= 3, both needed */
  assert_int_equal(vl_regime_of(1, 0.951, 3.0), VL_REGIME_HYDRODYNAMIC);
  assert_int_equal(vl_regime_of(1, 0.999, 50.0), VL_REGIME_HYDRODYNAMIC);
  assert_int_equal(vl_regime_of(1, 0.95, 3.0), VL_REGIME_MIXED);    /* share at the bound */
  assert_int_equal(vl_regime_of(1, 0.999, 2.999), VL_REGIME_MIXED); /* film just short */
  assert_int_equal(vl_regime_of(1, 0.999, 0.58), VL_REGIME_MIXED);  /* the case */
  /* boundary: share < 0.05 and lambda < 3, both needed */
  assert_int_equal(vl_regime_of(1, 0.049, 2.999), VL_REGIME_BOUNDARY);
  assert_int_equal(vl_regime_of(1, 0.0, 0.1), VL_REGIME_BOUNDARY);
  assert_int_equal(vl_regime_of(1, 3e-7, 1.86), VL_REGIME_BOUNDARY); /* fig05 near mu_Rc's peak */
  assert_int_equal(vl_regime_of(1, 0.05, 0.5), VL_REGIME_MIXED);     /* share at the bound */
  assert_int_equal(vl_regime_of(1, 0.01, 3.0), VL_REGIME_MIXED);     /* film at the bound */
  assert_int_equal(vl_regime_of(1, 0.02, 3.8), VL_REGIME_MIXED);     /* the case */
  /* in between on either axis: mixed */
  assert_int_equal(vl_regime_of(1, 0.5, 0.5), VL_REGIME_MIXED);
  assert_int_equal(vl_regime_of(1, 0.5, 3.0), VL_REGIME_MIXED);
  assert_int_equal(vl_regime_of(1, 0.5, 5.0), VL_REGIME_MIXED);
  assert_int_equal(vl_regime_of(1, 0.99, 1.5), VL_REGIME_MIXED);
  /* smooth surfaces (lambda NAN): the load share alone, as before */
  assert_int_equal(vl_regime_of(1, 0.96, NAN), VL_REGIME_HYDRODYNAMIC);
  assert_int_equal(vl_regime_of(1, 0.04, NAN), VL_REGIME_BOUNDARY);
  assert_int_equal(vl_regime_of(1, 0.5, NAN), VL_REGIME_MIXED);
}

static char *slurp_tmp(FILE *f) {
  long len = ftell(f);
  rewind(f);
  char *s = calloc((size_t)len + 1, 1);
  assert_non_null(s);
  assert_int_equal(fread(s, 1, (size_t)len, f), (size_t)len);
  return s;
}

/* The column after fluid_load_fraction: lambda of a rough point, empty for
 * a smooth one; the JSON member likewise (null). */
static void test_film_ratio_written(void **state) {
  (void)state;
  vl_point p[2];
  memset(p, 0, sizeof p);
  for (int i = 0; i < 2; i++) {
    p[i].v0_m_s = 0.01 * (i + 1);
    p[i].converged = true;
    p[i].fluid_load_fraction = 0.99;
    p[i].error_estimate = NAN;
  }
  p[0].u_min_m = 1.5e-6, p[0].u_min_over_h_rms = 3.0, p[0].regime = VL_REGIME_HYDRODYNAMIC;
  p[1].u_min_m = 1e-8, p[1].u_min_over_h_rms = NAN, p[1].regime = VL_REGIME_HYDRODYNAMIC;
  vl_curve_meta meta;
  memset(&meta, 0, sizeof meta);
  char path[64];
  snprintf(path, sizeof path, "/tmp/vl_test_regime_%ld.csv", (long)getpid());
  vl_error err;
  assert_int_equal(vl_write_curve_csv(path, 2, p, &meta, &err), VL_OK);
  FILE *f = fopen(path, "rb");
  assert_non_null(f);
  fseek(f, 0, SEEK_END);
  char *csv = slurp_tmp(f);
  fclose(f);
  remove(path);
  assert_non_null(strstr(csv, ",fluid_load_fraction,u_min_over_h_rms,regime,"));
  assert_non_null(strstr(csv, ",0.99,3,hydrodynamic,"));
  assert_non_null(strstr(csv, ",0.99,,hydrodynamic,"));
  free(csv);
  f = tmpfile();
  assert_non_null(f);
  vl_json w;
  vl_json_init(&w, f, 10);
  vl_curve_json(&w, 2, p, &meta);
  char *js = slurp_tmp(f);
  fclose(f);
  assert_non_null(strstr(js, "\"u_min_over_h_rms\": 3,"));
  assert_non_null(strstr(js, "\"u_min_over_h_rms\": null,"));
  free(js);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_regime_boundaries),
      cmocka_unit_test(test_film_ratio_written),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
