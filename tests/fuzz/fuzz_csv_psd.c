/* Fuzz target: a tabulated roughness spectrum (`surface add --psd FILE`),
 * read by vl_csv_read_psd_file as the command line reads it (2-D, or 1-D
 * converted, by the input's length), then the derived quantities the
 * command prints and stores. Properties: a refused file gets lines each
 * naming the file and no PSD to free; an accepted one has n >= 2 points,
 * q > 0 strictly increasing, C > 0, all finite, and h_rms and rms slope
 * within the plausible bounds of csv.h. */
#include "vl_fuzz.h"

#include <math.h>
#include <string.h>

#include "roughness_internal.h"
#include "viscolube/csv.h"
#include "viscolube/roughness.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *path = vl_fuzz_file(data, size);
  vl_psd psd;
  vl_error err = {{0}};
  /* the length picks the spectrum kind: 1-D files are converted */
  vl_psd_file_kind kind = size % 2 ? VL_PSD_FILE_1D : VL_PSD_FILE_2D;
  vl_psd_read_report rep;
  vl_status st = vl_csv_read_psd_file(path, kind, &psd, &rep, &err);
  if (st != VL_OK) {
    FUZZ_CHECK_REFUSED(st, path, err.msg);
    FUZZ_CHECK(psd.q == NULL && psd.C == NULL, "a refused file left arrays behind");
    return 0;
  }
  FUZZ_CHECK(psd.kind == VL_PSD_TABULATED && psd.n >= 2, "kind %d, n %zu", (int)psd.kind, psd.n);
  for (size_t k = 0; k < psd.n; k++) {
    FUZZ_CHECK(isfinite(psd.q[k]) && psd.q[k] > 0.0, "q[%zu] = %g", k, psd.q[k]);
    FUZZ_CHECK(isfinite(psd.C[k]) && psd.C[k] > 0.0, "C[%zu] = %g", k, psd.C[k]);
    FUZZ_CHECK(k == 0 || psd.q[k] > psd.q[k - 1], "q not increasing at %zu", k);
  }
  FUZZ_CHECK(psd.q0 == psd.q[0] && psd.q1 == psd.q[psd.n - 1], "band is not [q_first, q_last]");
  /* what `surface add` prints and the database derives: no crash, no hang */
  double h = vl_psd_hrms(&psd), slope = vl_psd_rms_slope(&psd);
  FUZZ_CHECK(h >= VL_PSD_HRMS_MIN_M && h <= VL_PSD_HRMS_MAX_M && slope <= VL_PSD_SLOPE_MAX,
             "implausible spectrum accepted: h_rms %g, slope %g", h, slope);
  FUZZ_CHECK(h == rep.hrms_m && slope == rep.rms_slope, "report disagrees");
  (void)vl_psd_value(&psd, sqrt(psd.q0) * sqrt(psd.q1));
  vl_psd_free(&psd);
  return 0;
}
