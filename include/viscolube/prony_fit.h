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

/* How a fit went (an import of measured data reports one, dma.h). */
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

#endif
