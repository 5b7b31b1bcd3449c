/* Fuzz target: a Prony file (`compound add --prony FILE`), read by
 * vl_csv_read_prony exactly as the command line reads it, then checked the
 * way `compound add` and `compound show` use it. Properties: a refused file
 * gets VL_EINPUT and one line naming the file; an accepted one holds 1..128
 * terms with A >= 0 and tau_s > 0, finite, which vl_prony_validate accepts. */
#include "vl_fuzz.h"

#include <math.h>
#include <string.h>

#include "viscolube/csv.h"
#include "viscolube/rheology.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *path = vl_fuzz_file(data, size);
  vl_prony p;
  memset(&p, 0, sizeof p);
  p.e_inf_pa = 1e7; /* --e-inf and --nu are not in the file */
  p.nu = 0.5;
  vl_error err = {{0}};
  vl_status st = vl_csv_read_prony(path, &p, &err);
  if (st != VL_OK) {
    FUZZ_CHECK_REFUSED(st, path, err.msg);
    return 0;
  }
  FUZZ_CHECK(p.n_terms >= 1 && p.n_terms <= VL_PRONY_MAX_TERMS, "n_terms %zu", p.n_terms);
  for (size_t i = 0; i < p.n_terms; i++) {
    FUZZ_CHECK(isfinite(p.A[i]) && p.A[i] >= 0.0, "A[%zu] = %g", i, p.A[i]);
    FUZZ_CHECK(isfinite(p.tau_s[i]) && p.tau_s[i] > 0.0, "tau_s[%zu] = %g", i, p.tau_s[i]);
  }
  FUZZ_CHECK(p.e_inf_pa == 1e7 && p.nu == 0.5, "the reader changed Einf or nu");
  FUZZ_CHECK(vl_prony_validate(&p, &err) == VL_OK, "validate refuses what the reader accepted: %s",
             err.msg);
  /* what `compound show` derives from the terms: must not crash or hang */
  double omega = 0.0, tan_delta = 0.0;
  (void)vl_prony_e0(&p);
  (void)vl_prony_loss_peak(&p, &omega, &tan_delta, NULL);
  return 0;
}
