/* viscolube: linear viscoelasticity of a rubber from a Prony series.
 *
 * Creep form (docs/MODEL.md section 2):
 *   1/E(w) = (1/Einf) [ 1 + sum_i A_i / (1 - i w tau_i) ],  A_i >= 0, tau_i > 0,
 * E(0) = E0 = Einf/(1 + sum A_i), E(inf) = Einf; tau_i are retardation
 * (creep) times. All quantities SI.
 *
 * Sign of the imaginary part: with the e^{-i w t} convention of docs/MODEL.md
 * section 2 this form gives Im E < 0; like docs/MODEL.md, the functions below
 * return the DMA convention instead, E = E' + i E'' and 1/E = J' - i J''
 * with the loss
 * moduli E'', J'' >= 0, i.e. the complex conjugate of the creep form above;
 * |E| and tan delta = E''/E' are the same in both conventions. */
#ifndef VISCOLUBE_RHEOLOGY_H
#define VISCOLUBE_RHEOLOGY_H

#include <complex.h>
#include <stddef.h>

#include "viscolube/status.h"

#define VL_PRONY_MAX_TERMS 128

typedef struct {
  double e_inf_pa;                  /* glassy (high-frequency) modulus */
  double nu;                        /* Poisson ratio, frequency independent */
  size_t n_terms;                   /* 0 = purely elastic with E = Einf */
  double A[VL_PRONY_MAX_TERMS];     /* dimensionless creep strengths */
  double tau_s[VL_PRONY_MAX_TERMS]; /* retardation times */
} vl_prony;

/* Checks Einf > 0, 0 <= nu < 0.5 (nu = 0.5 allowed), A_i >= 0, tau_i > 0, all
 * finite, n_terms <= VL_PRONY_MAX_TERMS. Names the first bad field in err. */
vl_status vl_prony_validate(const vl_prony *prony, vl_error *err);

double vl_prony_e0(const vl_prony *prony);                            /* relaxed modulus */
double complex vl_prony_modulus(const vl_prony *prony, double omega); /* E' + i E'' */

/* Frequency (rad/s) and height of the loss-tangent maximum, found on a log
 * grid over the span of the tau_i and refined by golden section. For an
 * elastic material returns VL_EINPUT. */
vl_status vl_prony_loss_peak(const vl_prony *prony, double *omega_peak, double *tan_delta_peak,
                             vl_error *err);

/* The loss-tangent maximum within [omega_min, omega_max] (rad/s), e.g. a
 * measured window, where the series is backed by data: *omega_peak and
 * *tan_delta_peak (either may be NULL) as vl_prony_loss_peak, and *at_edge
 * (may be NULL) -1 or +1 when the maximum sits at the lower or upper end
 * (tan delta still rising beyond it), else 0. VL_EINPUT for an elastic
 * material or a window that is not 0 < omega_min < omega_max < inf. */
vl_status vl_prony_loss_peak_in(const vl_prony *prony, double omega_min, double omega_max,
                                double *omega_peak, double *tan_delta_peak, int *at_edge,
                                vl_error *err);

#endif
