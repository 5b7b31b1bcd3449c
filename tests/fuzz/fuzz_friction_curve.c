/* Fuzz target: a measured Stribeck curve (`pair calibrate --measured
 * FILE`), read by vl_friction_curve_read_file. Properties: a refused file
 * gets lines each naming the file and no arrays; an accepted one has n >= 1
 * finite speeds and friction coefficients. */
#include "vl_fuzz.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "viscolube/csv.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *path = vl_fuzz_file(data, size);
  double *v = NULL, *mu = NULL;
  size_t n = 0;
  vl_error err = {{0}};
  vl_status st = vl_friction_curve_read_file(path, &v, &mu, &n, &err);
  if (st != VL_OK) {
    FUZZ_CHECK_REFUSED(st, path, err.msg);
    FUZZ_CHECK(v == NULL && mu == NULL && n == 0, "a refused file left arrays behind");
    return 0;
  }
  FUZZ_CHECK(n >= 1 && v && mu, "accepted with n %zu", n);
  for (size_t k = 0; k < n; k++)
    FUZZ_CHECK(isfinite(v[k]) && isfinite(mu[k]), "row %zu: v %g, mu %g", k, v[k], mu[k]);
  free(v);
  free(mu);
  return 0;
}
