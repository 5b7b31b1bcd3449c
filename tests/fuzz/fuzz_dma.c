/* Fuzz target: measured DMA files (`compound add NAME --measured FILE`),
 * read, shifted and fitted by vl_measured_read_text as the command line
 * does through vl_measured_read_file. The first input byte picks the
 * options the command line can give (--freq-unit, --modulus-unit,
 * --temp-unit, --tref, --fit-weights); the rest is the file, not
 * NUL-terminated, so ASan sees any read past its end.
 * The input's length picks tensile or shear moduli for names that say
 * neither (--moduli), and nu 0.5 or 0.3.
 * Properties: a refused file gets VL_EINPUT or VL_ENOCONV, an emptied
 * result and lines (one per offending line of the file) each starting with
 * the file name, without control characters; an accepted one has finite
 * positive frequencies and moduli, every point in an isotherm, isotherm
 * temperatures increasing and a Prony series that vl_prony_validate
 * accepts. */
#include "dma_private.h"
#include "vl_fuzz.h"

#include <math.h>
#include <string.h>

#include "viscolube/dma.h"
#include "viscolube/rheology.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 1) return 0;
  static const char *const freq[] = {NULL, "Hz", "rad/s", NULL};
  static const char *const mod[] = {NULL, "Pa", "MPa", NULL};
  static const char *const temp[] = {NULL, "C", "K", NULL};
  uint8_t b = data[0];
  vl_dma_options o = vl_dma_options_default();
  o.freq_unit = freq[b & 3];
  o.modulus_unit = mod[(b >> 2) & 3];
  o.temp_unit = temp[(b >> 4) & 3];
  o.tref_c = (b >> 6) & 1 ? 20.0 : NAN;
  o.weights = (b >> 7) & 1 ? VL_PRONY_WEIGHTS_MODULUS : VL_PRONY_WEIGHTS_RELATIVE;
  o.moduli = size % 3 == 0   ? VL_DMA_MODULI_AUTO
             : size % 3 == 1 ? VL_DMA_MODULI_SHEAR
                             : VL_DMA_MODULI_TENSILE;
  o.nu = size % 2 ? 0.5 : 0.3;

  vl_measured m;
  vl_error err = {{0}};
  vl_status st = vl_measured_read_text((const char *)data + 1, size - 1, "fuzz.csv", &o, &m, &err);
  if (st != VL_OK) {
    FUZZ_CHECK(st == VL_EINPUT || st == VL_ENOCONV, "status %d: %s", (int)st, err.msg);
    FUZZ_CHECK(!strncmp(err.msg, "fuzz.csv", 8), "message does not name the file: %s", err.msg);
    FUZZ_CHECK(vl_fuzz_message_clean(err.msg, "fuzz.csv"), "control byte in message: %s", err.msg);
    FUZZ_CHECK(m.n == 0 && !m.omega_rad_s && !m.storage_pa && !m.source,
               "a refused file left data behind");
    vl_measured_free(&m); /* documented as safe */
    return 0;
  }
  FUZZ_CHECK(m.n >= 2 && m.n_isotherms >= 1 && m.n_isotherms <= m.n, "n %zu, isotherms %zu", m.n,
             m.n_isotherms);
  for (size_t k = 0; k < m.n; k++) {
    FUZZ_CHECK(isfinite(m.omega_rad_s[k]) && m.omega_rad_s[k] > 0.0, "omega[%zu] = %g", k,
               m.omega_rad_s[k]);
    FUZZ_CHECK(isfinite(m.reduced_omega_rad_s[k]) && m.reduced_omega_rad_s[k] > 0.0,
               "reduced omega[%zu] = %g", k, m.reduced_omega_rad_s[k]);
    FUZZ_CHECK(isfinite(m.storage_pa[k]) && m.storage_pa[k] > 0.0, "E'[%zu] = %g", k,
               m.storage_pa[k]);
    FUZZ_CHECK(isfinite(m.loss_pa[k]) && m.loss_pa[k] > 0.0, "E''[%zu] = %g", k, m.loss_pa[k]);
    FUZZ_CHECK(isfinite(m.temperature_c[k]) && m.temperature_c[k] >= -273.15, "T[%zu] = %g", k,
               m.temperature_c[k]);
    FUZZ_CHECK(m.isotherm[k] < m.n_isotherms, "point %zu in isotherm %zu of %zu", k, m.isotherm[k],
               m.n_isotherms);
  }
  for (size_t i = 0; i < m.n_isotherms; i++) {
    FUZZ_CHECK(isfinite(m.iso_log10_a_t[i]), "log10 aT[%zu] = %g", i, m.iso_log10_a_t[i]);
    FUZZ_CHECK(i == 0 || m.iso_temperature_c[i] > m.iso_temperature_c[i - 1],
               "isotherm temperatures not increasing at %zu", i);
  }
  FUZZ_CHECK(isfinite(m.tref_c), "tref %g", m.tref_c);
  FUZZ_CHECK(isnan(m.wlf_c1) == isnan(m.wlf_c2_k), "one WLF constant without the other");
  FUZZ_CHECK(vl_prony_validate(&m.prony, &err) == VL_OK, "fitted series invalid: %s", err.msg);
  vl_measured_free(&m);
  FUZZ_CHECK(m.n == 0 && !m.omega_rad_s, "vl_measured_free did not empty the result");
  return 0;
}
