/* viscolube: fitting the creep-form Prony series to a master curve.
 *
 * Model (docs/MODEL.md section 2, DMA sign convention of rheology.h):
 *   J(w) = 1/E(w) = J' - i J'',
 *   J'(w)  = c0 + sum_i c_i / (1 + w^2 tau_i^2),
 *   J''(w) =      sum_i c_i w tau_i / (1 + w^2 tau_i^2),
 * with c0 = 1/Einf and c_i = A_i/Einf. For fixed tau_i the model is linear
 * in (c0, c_i) and every coefficient must be >= 0, so the fit is one
 * non-negative least-squares problem (nnls.h): no starting guess, no local
 * minima. The tau_i sit on a logarithmic grid covering the data window
 * [1/w_max, 1/w_min] with a chosen number of terms per decade; terms the
 * data do not need come out zero and are dropped.
 *
 * Weights (each row of the least-squares problem is divided by a measured
 * magnitude, so that points count by relative error over the four decades
 * of modulus from rubbery to glassy):
 *   VL_PRONY_WEIGHTS_RELATIVE  J' rows by J', J'' rows by J'': relative
 *     errors of both components count alike. Fits data that obey
 *     Kramers-Kronig to their noise in E' and E'' (synthetic HN data: 1.0 %
 *     and 2.1 % rms at 1 % noise), including the tails where tan delta is
 *     1e-4. The default.
 *   VL_PRONY_WEIGHTS_MODULUS  both rows by |J|: relative error of the
 *     complex modulus, i.e. tan delta to an absolute accuracy. Keeps E'
 *     accurate when E'' is inconsistent with it (the pyvisco master curve:
 *     E' 2.7 % rms instead of 14 %), but leaves E'' loose where tan delta
 *     is small (94 % rms on the synthetic tails).
 * Then Einf = 1/c0 and A_i = c_i/c0. */
#ifndef VISCOLUBE_PRONY_FIT_H
#define VISCOLUBE_PRONY_FIT_H

#include <stddef.h>

#include "viscolube/rheology.h"
#include "viscolube/status.h"

/* Default grid density: two terms per decade keep the ripple a discrete
 * spectrum leaves in E'' well under 1 % (one per decade leaves a few %). */
#define VL_PRONY_FIT_DEFAULT_PER_DECADE 2.0
#define VL_PRONY_FIT_MAX_PER_DECADE 8.0

typedef enum {
  VL_PRONY_WEIGHTS_RELATIVE = 0, /* J' rows / J', J'' rows / J'' */
  VL_PRONY_WEIGHTS_MODULUS = 1   /* both rows / |J| */
} vl_prony_weights;

/* "relative", "modulus". */
const char *vl_prony_weights_name(vl_prony_weights w);

typedef struct {
  size_t n_points;        /* data points fitted */
  double omega_min_rad_s; /* data window */
  double omega_max_rad_s;
  double terms_per_decade;  /* grid density used */
  vl_prony_weights weights; /* row weighting used */
  size_t n_grid;            /* tau_i on the grid (unknowns = n_grid + 1) */
  size_t n_terms;           /* terms with A_i > 0 kept in the series */
  double rms_rel_storage;   /* rms over points of (E'fit - E')/E' */
  double max_rel_storage;   /* largest |(E'fit - E')/E'| */
  size_t max_storage_index; /* the point where it occurs */
  double rms_rel_loss;      /* the same for E'' */
  double max_rel_loss;
  size_t max_loss_index;
  double rms_rel; /* sqrt of the mean of both squared errors */
} vl_prony_fit_report;

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
