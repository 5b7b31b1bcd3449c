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

/* A single-term "standard linear solid" with relaxed modulus E0 and ratio
 * Einf/E0 (>= 1), retardation time tau. */
vl_prony vl_prony_single(double e0_pa, double einf_over_e0, double tau_s, double nu);

double vl_prony_sum_A(const vl_prony *prony);
double vl_prony_e0(const vl_prony *prony);             /* relaxed modulus */
double vl_prony_reduced_factor(const vl_prony *prony); /* 1/(1 - nu^2) */

double complex vl_prony_compliance(const vl_prony *prony, double omega); /* J' - i J'' */
double complex vl_prony_modulus(const vl_prony *prony, double omega);    /* E' + i E'' */
double vl_prony_tan_delta(const vl_prony *prony, double omega);

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

/* Multiplies every tau_i by a_T (time-temperature superposition). */
void vl_prony_shift(vl_prony *prony, double a_T);

/* WLF: log10 a_T = -C1 (T - Tref) / (C2 + T - Tref). Returns NAN when the
 * denominator is not positive (outside the WLF domain). */
double vl_wlf_log10_shift(double c1, double c2_k, double t_c, double tref_c);

/* |Er(wH)| and a_H at speed v0 from the fixed point wH = pi v0 / a_H,
 * a_H^2 = 4 fN R/(pi |Er(wH)|) (docs/MODEL.md section 4). Reduced moduli. */
void vl_asperity_state(const vl_prony *rubber, double load_n_per_m, double radius_m, double v0_m_s,
                       double *E_abs_pa, double *a_H_m, double *omega_H);

#endif
