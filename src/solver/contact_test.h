/* Test aids of the contact solver (private: the tests and the benchmarks
 * see it through viscolube_internal; the program does not). They read the
 * discretisation the solver uses (cells, influence coefficients, face
 * fluxes), check its analytic Jacobian and count its cost. Implemented in
 * contact_test.c. */
#ifndef VISCOLUBE_CONTACT_TEST_H
#define VISCOLUBE_CONTACT_TEST_H

#include <stdbool.h>
#include <stddef.h>

#include "viscolube/contact.h"

/* Compares the analytic Jacobian at the current state (speed v0) with
 * central finite differences of the residual; returns the largest
 * |J_fd - J| over all entries divided by the largest |J|, or a negative
 * value on allocation failure. Leaves the state unchanged. */
double vl_contact_jacobian_check(vl_contact *c, double v0_m_s);

/* The same comparison per block of rows, each normalised by its own largest
 * |J| (the global one is set by the Reynolds rows of a wet contact, which
 * hides errors in the others): rel[0] the contact rows (elasticity or
 * complementarity), rel[1] the Reynolds rows, rel[2] the load balance (0
 * for an empty block). Returns the largest, or a negative value on
 * allocation failure. Leaves the state unchanged. */
double vl_contact_jacobian_check_blocks(vl_contact *c, double v0_m_s, double rel[3]);

/* The film-pressure correction of a Newton step (contact_film.c), tried
 * where a sweep's next solve starts: the state converged at its last speed,
 * moved to speed v0 as the solve does (kernel, predicted pf, fluid scales).
 * There the plain Newton step (LU of the analytic Jacobian) and the
 * corrected one are compared. Leaves the state unchanged. */
typedef struct {
  bool applied;        /* the correction was taken (else the two steps are equal) */
  double plain_norm;   /* 2-norm of the residual after the full plain step */
  double corr_norm;    /* ... after the full corrected step */
  double reynolds_max; /* max |Reynolds row| after the full corrected step */
  double gap_change;   /* max |corrected - plain| over the gap and approach unknowns */
  double pf_step;      /* max |pf part| of the plain step */
  double pf_diff;      /* max |corrected - plain| over the pf unknowns */
} vl_contact_film_check_result;

/* Fills *r; false on allocation failure or a failed factorisation. */
bool vl_contact_film_check(vl_contact *c, double v0_m_s, vl_contact_film_check_result *r);

/* The fluid flux per unit length J (m^2/s) through the n + 1 cell faces of
 * the current state, as discretised by the solver (face 0 is the inlet end
 * of the domain, face n the outlet end;
 * J = -(u^3 phi_p/(12 eta)) dpf/dx + v0 (u + h_rms phi_s)/2). Writes
 * min(cap, n + 1) values; returns n + 1, or 0 for a dry contact. */
size_t vl_contact_face_fluxes(const vl_contact *c, double *flux_m2_s, size_t cap);

/* The contact's own viscous-flattening evaluator (NULL when the effect is
 * off), at the speed of its last solve and its current viscosity. */
const vl_flattening *vl_contact_flattening(const vl_contact *c);

/* Cell i < vl_contact_grid(c): its node (the cell centre) and width, in a0. */
void vl_contact_cell(const vl_contact *c, size_t i, double *x_a0, double *width_a0);

/* The influence coefficient the solver uses at speed v0 (builds the kernel
 * for v0, as a solve would): d(gap at node i)/d(pressure on cell j), gap in
 * a0^2/R, pressure in p0 (vl_contact_p0). */
double vl_contact_influence(vl_contact *c, double v0_m_s, size_t i, size_t j);

/* Cost instrumentation (benchmarks): wall-clock seconds (CLOCK_MONOTONIC)
 * and call counts of the solver's parts since creation or the last reset,
 * summed over the coarse-grid and dry helper contacts a smooth wet contact
 * owns. Reading the clock costs ~50 ns per call and allocates nothing. */
typedef struct {
  long residuals, jacobians, setups, solves, kernels, newtons;
  double t_residual_s;   /* residual evaluations (including KINSOL's line search) */
  double t_jacobian_s;   /* analytic Jacobian assembly */
  double t_setup_s;      /* linear solver set-up: the LU factorisation */
  double t_solve_s;      /* linear solver solves: the triangular solves */
  double t_kernel_s;     /* influence-matrix builds at a new speed */
  double t_newton_s;     /* KINSol calls in total (includes the four above) */
  long linsol_fallbacks; /* VL_LINSOL_SCHUR: set-ups or solves that fell back to the full LU */
} vl_contact_timing;

/* Sums the counters of c (and its helper contacts) into *t (overwritten). */
void vl_contact_timing_get(const vl_contact *c, vl_contact_timing *t);
/* Zeroes the counters of c and its helper contacts. */
void vl_contact_timing_reset(vl_contact *c);

#endif
