/* viscolube (private): fitting the Prony series (the model and its report
 * are public, viscolube/prony_fit.h). The fit itself, for the import of
 * measured data (dma.c), the benchmarks and tests. */
#ifndef VISCOLUBE_PRONY_FIT_INTERNAL_H
#define VISCOLUBE_PRONY_FIT_INTERNAL_H

#include <stddef.h>

#include "viscolube/prony_fit.h"
#include "viscolube/rheology.h"
#include "viscolube/status.h"

/* Fits the series to n points (omega_rad_s[k] > 0, storage_pa[k] > 0,
 * loss_pa[k] > 0; any order, repeats allowed), with terms_per_decade in
 * (0, VL_PRONY_FIT_MAX_PER_DECADE] (0 = default), the given row weights,
 * and Poisson ratio nu stored in the result. On VL_OK *out holds Einf, nu and the kept terms
 * sorted by tau, and *report (may be NULL) the fit's errors.
 *
 * Refused with VL_EINPUT and the reason: a non-positive or non-finite
 * value (names the point index), a window narrower than one decade, fewer
 * points than grid terms + 1, a grid over VL_PRONY_MAX_TERMS terms, and a
 * fit whose glassy compliance c0 comes out zero (the data never level off
 * at high frequency, so Einf is undetermined). VL_ENOMEM, VL_ENOCONV
 * (from the NNLS solver). */
vl_status vl_prony_fit(size_t n, const double *omega_rad_s, const double *storage_pa,
                       const double *loss_pa, double terms_per_decade, vl_prony_weights weights,
                       double nu, vl_prony *out, vl_prony_fit_report *report, vl_error *err);

/* The tau grid vl_prony_fit uses for the window [omega_min, omega_max]:
 * n = ceil(decades * per_decade) + 1 points, log-uniform from
 * 1/omega_max to 1/omega_min. Returns n (0 if the window is invalid);
 * writes min(n, cap) values into tau_s (may be NULL). */
size_t vl_prony_fit_grid(double omega_min_rad_s, double omega_max_rad_s, double terms_per_decade,
                         double *tau_s, size_t cap);

#endif
