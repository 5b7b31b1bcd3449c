/* Test oracle: the dry smooth sliding ball on a viscoelastic half-space
 * with the surface displacement taken in Fourier space,
 *   w(q) = 2 p(q) / (|q| Er(omega)),   1/Er(omega) = Jr_inf [1 + sum_k A_k/(1 + i q_x b_k)],
 * b_k = v0 tau_k (the steady-sliding form of the creep series, docs/MODEL.md
 * section 2 with omega = -q_x v0 for the rubber moving along +x), on a
 * padded periodic grid (FFTW), the pressure as point values on the cells
 * (a spectral discretisation, not the solver's cell-averaged one), the
 * hard contact solved by a plain primal-dual active set with LAPACK's
 * dgesv. Independent of the library on purpose: it shares no code with
 * src/mechanics/kernel2d.c nor with the point-contact solver.
 *
 * Units as the solver's: lengths in a0, pressures in p0, the gap in
 * a0^2/Re, a0 and p0 the Hertz scales of the relaxed modulus; the grid is
 * the solver's half grid (y >= 0, the mirror image added), nx odd. */
#ifndef VL_ORACLE_BALL_FFT_H
#define VL_ORACLE_BALL_FFT_H

#include <stddef.h>

typedef struct {
  size_t nx, ny;       /* cells along x (odd, a column on x = 0) and across (y >= 0) */
  double h;            /* cell size / a0 */
  double gx, gy;       /* the gap f = (gx x^2 + gy y^2)/2 (a ball: 1, 1) */
  size_t n_terms;      /* Prony terms (0: elastic, relaxed) */
  const double *A;     /* their strengths (Einf/E0 = 1 + sum A) */
  const double *de;    /* their memory lengths v0 tau_k / a0 */
  double pad_x, pad_y; /* the FFT period as a multiple of the grid's extent (>= 2) */
} vl_oracle_ball_problem;

typedef struct {
  double mu_R_over_a0; /* rolling friction mu Rx/a0 = -(1/W) \int p x dA / a0 */
  double p_max;        /* largest cell pressure / p0 */
  double area;         /* cells in contact times their area, both halves / a0^2 */
  double h0;           /* rigid approach / (a0^2/Re) */
  int iterations;      /* active-set iterations */
  int converged;       /* 1 when the set stopped changing */
} vl_oracle_ball_solution;

/* Solves; 0 on success, -1 on bad input, -2 no convergence, -3 allocation
 * or LAPACK failure. */
int vl_oracle_ball_fft_solve(const vl_oracle_ball_problem *pb, vl_oracle_ball_solution *out);

#endif
