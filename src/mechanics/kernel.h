/* viscolube: surface-displacement influence coefficients on a uniform grid.
 *
 * Sign convention (docs/MODEL.md section 1 and 3): cylinder frame, rubber moving
 * at +v0 along x. The surface displacement from a pressure p0(x) is
 *   w(x) = -(2/(pi Erinf)) \int dx' p0(x') [ log|x-x'|
 *            + sum_i A_i \int_0^inf ds e^{-s} log|x - x' - b_i s| ],  b_i = v0 tau_i.
 * With p0 piecewise constant on cells of width delta centred on the nodes,
 * w(x_i) = -(2/(pi Erinf)) sum_j p_j [ Ke(d) + sum_k A_k Kve(d, b_k) ],
 * d = x_i - x_j, where
 *   Ke(d)     = \int_{-delta/2}^{delta/2} log|d - y| dy
 *   Kve(d, b) = \int_0^inf ds e^{-s} \int_{-delta/2}^{delta/2} log|d - y - b s| dy.
 * Both are exact closed forms (with exp(z) E1(z) / Ei functions) evaluated
 * with series or asymptotic branches so that full double precision holds for
 * b/delta from 1e-12 to 1e12 and for |d|/delta up to 1e6.
 * Limits: Kve(d, 0) = Ke(d); as b -> inf,
 *   Kve(d, b) = delta (log b - gamma) + O((|d| + delta)/b * log(b/delta)),
 * a constant in d (the glassy response; gamma = Euler's constant). The closed
 * form and its branches are derived at the top of src/kernel.c. */
#ifndef VISCOLUBE_KERNEL_H
#define VISCOLUBE_KERNEL_H

#include <stddef.h>

#include "viscolube/status.h"

/* Branch switches of the evaluation (in units of delta), exposed so that tests
 * can probe continuity across them: b/delta <= VL_KERNEL_BETA_SWITCH uses the
 * closed form directly; above it, |d|/delta < VL_KERNEL_X_SWITCH uses a power
 * series and |d|/delta >= VL_KERNEL_X_SWITCH a cell-midpoint Taylor series. */
#define VL_KERNEL_BETA_SWITCH 8.0
#define VL_KERNEL_X_SWITCH 8.0

/* The most Prony terms a Toeplitz matrix takes (VL_PRONY_MAX_TERMS). */
#define VL_KERNEL_MAX_TERMS 128

/* Ke(d): elastic coefficient of a cell of width delta > 0 at offset d (any
 * finite d, including the cell edges d = +-delta/2). NaN if delta <= 0. */
double vl_kernel_elastic(double d, double delta);

/* Kve(d, b): viscoelastic (memory) coefficient for one Prony term, b = v0*tau >= 0
 * (same length unit as d and delta). b == 0 returns Ke(d). Accurate to a few
 * ulps of max(|Kve|, delta) for b/delta in [1e-12, 1e12], |d|/delta <= 1e6.
 * NaN if delta <= 0 or b < 0. Turns GSL's abort handler off. */
double vl_kernel_viscoelastic(double d, double delta, double b);

/* Toeplitz influence matrix of an n-node grid: coef[k], k = (i - j) + n - 1,
 * holds the coefficient for offset d = (i - j) delta; 2n-1 values.
 * total(d) = Ke(d) + sum_k A_k Kve(d, b_k); when n_terms == 0 only Ke. */
typedef struct {
  size_t n;
  double delta;
  double *coef; /* 2n-1 values, owned */
} vl_toeplitz;

/* Fills t (allocating coef) for n >= 1 nodes with spacing delta > 0 and Prony
 * terms (A[k] finite, b[k] = v0 tau_k >= 0 finite, same length unit as delta).
 * Frees nothing on entry; on failure t->coef == NULL and err says why
 * (VL_EINPUT, VL_ENOMEM). The caller releases t with vl_toeplitz_free.
 * n_terms <= VL_KERNEL_MAX_TERMS. Cost: per offset, exponential integrals for
 * the terms whose memory length b is within about two decades of the
 * offset, and two short series for all the others; offsets from 256 cells on
 * come from Chebyshev interpolants in the offset, 16 evaluations per quarter
 * octave, accurate to a few 1e-15 of the coefficient (kernel.c). Turns GSL's
 * abort handler off. */
vl_status vl_toeplitz_build(vl_toeplitz *t, size_t n, double delta, const double *A,
                            const double *b, size_t n_terms, vl_error *err);

/* Refills an already built t for new A, b (same n, delta): no allocation.
 * The inputs must satisfy vl_toeplitz_build's conditions (not rechecked).
 * Gives bit-for-bit the coefficients vl_toeplitz_build would give. */
void vl_toeplitz_refill(vl_toeplitz *t, const double *A, const double *b, size_t n_terms);

/* Releases t->coef (t may be NULL; safe to call twice). */
void vl_toeplitz_free(vl_toeplitz *t);

/* Matrix element (i, j). */
static inline double vl_toeplitz_at(const vl_toeplitz *t, size_t i, size_t j) {
  return t->coef[i + t->n - 1 - j];
}

#endif
