/* viscolube: one operating point of a rigid smooth cylinder on a (rough)
 * viscoelastic half-space, solved by KINSOL (Newton, dense Jacobian).
 *
 * Frame and signs (MODEL.md section 1): cylinder frame, rubber moving at +v0
 * along x, inlet at x < 0. Friction components are positive when they resist
 * the motion.
 *
 * Unknowns are dimensionless: x/a0, p/p0, u/(a0^2/R), with a0, p0 the Hertz
 * half-width and peak pressure of the low-speed (relaxed) modulus.
 *   smooth, dry: pressure p_i on the grid + rigid approach h0; the contact
 *                condition p >= 0, u >= 0, p u = 0 by a (slightly smoothed)
 *                Fischer-Burmeister function;
 *   rough, dry:  separation u_i + h0, with pc = |Er(wH)| s(u) from Persson.
 *   rough, wet:  plus the fluid pressure pf_i, scaled by its current
 *                magnitude; the averaged Reynolds equation in conservative
 *                finite-volume form (second-order upwind Couette flux,
 *                centred Poiseuille flux), pf = 0 at both ends of the
 *                domain, and the Reynolds cavitation condition pf >= 0,
 *                dJ/dx >= 0, pf dJ/dx = 0 by Fischer-Burmeister.
 *   smooth, wet: the same Reynolds equation and cavitation condition, but
 *                no contact unknowns (a smooth film stays open at any
 *                v0 > 0: pc = 0): pf_i and the rigid approach only, with a
 *                film that must stay positive (a Newton step that closes it
 *                is shortened). The Reynolds rows are flux imbalances
 *                divided by their sensitivity to pf_i (a pressure
 *                measure, as the complementarity needs, free of any length
 *                scale: stiff solids, whose inlet length sqrt(2 R h) far
 *                exceeds a0, are as well posed as soft ones). A fresh start
 *                (first solve, or a continuation step that failed) solves
 *                on a chain of half-size grids first: cavitation is a free
 *                boundary that one Newton step moves by about one cell.
 *                The coarsest level starts from Martin's rigid solution or,
 *                for soft EHL, from Hertz.
 * The rigid approach h0 (the displacement kernel's free constant) is the
 * load-balance unknown; the separation at the pressure centroid u0 is
 * reported afterwards (MODEL.md section 3: measured to converge better than
 * u0 as the unknown). */
#ifndef VISCOLUBE_CONTACT_H
#define VISCOLUBE_CONTACT_H

#include <stdbool.h>
#include <stddef.h>

#include "viscolube/flattening.h"
#include "viscolube/flow_factors.h"
#include "viscolube/rheology.h"
#include "viscolube/persson.h"
#include "viscolube/status.h"

typedef enum {
  VL_LINSOL_LAPACK = 0, /* LAPACK dgetrf/dgetrs on the SUNDIALS dense matrix */
  VL_LINSOL_SUNDIALS,   /* SUNLinSol_Dense (SUNDIALS' own dense LU) */
  VL_LINSOL_SCHUR       /* rough wet contacts: the Reynolds rows (a tridiagonal block in pf)
                         * eliminated first, LAPACK LU of the (N+1)^2 Schur complement, the
                         * residual checked against the full matrix (plain LAPACK when that
                         * fails, and for every other contact). The default. */
} vl_linear_solver;

/* Newton iterations a solve may take. A film lifting off from mixed to full
 * lubrication within one step of a sweep (u_min x35 on a 5 nm surface) took
 * 92 iterations on a uniform grid and 110-128 on graded ones; at 100 such a
 * point failed, and the sweep after it. Raising the cap from 100 to 200
 * turned 25 of the hard-case matrix's failed wet rough points (16 of them
 * on graded grids) into converged ones (tests/hard); points that converge
 * within 100 iterations are unchanged. */
#define VL_NEWTON_MAX_ITERATIONS 200

/* Largest solver grid: the dense matrices grow as the square of the cells
 * (56 bytes per cell squared: 15 GB at the limit). A graded grid may start
 * from far more uniform cells, since they are merged. */
#define VL_CONTACT_MAX_CELLS 16384
#define VL_CONTACT_MAX_GRID_GRADED 262144

/* Where a graded grid (vl_contact_config.grid_growth) starts to coarsen: the
 * relaxed Hertz contact ends at x = -a0, and rough or viscoelastic pressure
 * tails reach a little beyond. */
#define VL_GRADE_START_A0 2.0

typedef struct {
  vl_prony rubber;            /* n_terms = 0: elastic with E = e_inf_pa */
  double radius_m;
  double load_n_per_m;
  double sigma_s_pa;          /* shear stress in the real contact area; 0 = off */
  const vl_persson *roughness;/* NULL = smooth (hard contact); not owned */
  double eta_pa_s;            /* fluid viscosity; 0 = dry (no fluid unknowns at all) */
  vl_flow_factor_kind flow_factors; /* with roughness; smooth surfaces use smooth */
  size_t grid;                /* cells of the uniform grid on the domain (the resolution) */
  /* Graded inlet (rough contacts only; <= 1: uniform grid): upstream of
   * x = -VL_GRADE_START_A0 a0 the uniform cells are merged into cells that
   * grow by this ratio towards the inlet end (an odd number of uniform cells
   * each, so that every node sits on a node of the uniform grid and the
   * influence coefficients stay exact sums of the uniform ones). The contact
   * keeps the uniform resolution; the long inlet a lubricated contact needs
   * costs tens of cells instead of hundreds. The last cell may end up to
   * one uniform cell beyond x_min_a0. */
  double grid_growth;
  double x_min_a0, x_max_a0;  /* domain in units of a0 (the relaxed Hertz half-width, however
                               * stiff the solid): smooth wet contacts need an inlet of tens
                               * of vl_contact_inlet_length_m beyond the contact */
  double tolerance;           /* scaled residual norm for convergence */
  int max_iterations;         /* Newton iterations per solve (0 = VL_NEWTON_MAX_ITERATIONS) */
  vl_linear_solver linear_solver;
  /* Viscous flattening of the asperities (seed Appendix C; NULL = off; not
   * owned, must outlive the contact). The PSD both the contact and the
   * flow factors see becomes epsilon_f(u, v0) C(q) at each node, u the local
   * separation: pc(u) -> s pc(u/s), A/A0 at pc -> A/A0 at pc/s, h_rms ->
   * s h_rms in the flow factors and the Couette film, s = sqrt(epsilon_f)
   * (contact.c derives the scaling), with the chain rule through
   * epsilon_f(u) in the Jacobian. Needs roughness and a fluid (eta > 0):
   * vl_contact_create refuses it otherwise, and when its surface's h_rms
   * differs from the roughness table's. Not const: the contact sets the
   * evaluator's speed (vl_flattening_set_speed) at every new v0 and its
   * viscosity at create and in vl_contact_set_viscosity, so one evaluator
   * must not serve two contacts at once. */
  vl_flattening *flattening;
} vl_contact_config;

/* Fills cfg with the defaults (grid 512, domain [-1.6, 1.4] a0, tolerance 1e-9,
 * VL_LINSOL_SCHUR) for the given rubber and geometry; the caller sets the rest. */
void vl_contact_config_defaults(vl_contact_config *cfg);

#define VL_WARN_MAX 256

/* Result of one operating point, SI units. */
typedef struct {
  double v0_m_s;
  bool converged;
  long iterations;            /* Newton iterations of this call (smooth wet: including a
                               * failed continuation attempt and coarse-grid starts) */
  double residual;            /* final scaled residual norm (max norm) */
  double mu, mu_Rc, mu_Rf, mu_Sc, mu_Sf;
  double u_min_m, u_central_m;/* min separation; separation at the pressure centroid */
  double x_centroid_m;        /* pressure centroid (negative: inlet side) */
  double contact_width_m;     /* extent where pc >= 1% of its maximum */
  double fluid_load_fraction; /* \int pf / fN */
  double load_error;          /* |\int p - fN| / fN */
  double E_wH_pa;             /* |Er(wH)| (rough) or Er of the relaxed state */
  double a_H_m;               /* Hertz half-width with |Er(wH)| */
  double Q;                   /* rolling number (wet rough only; else 0) */
  double peak_pressure_pa, x_peak_m;
  double mu_Sf_couette, mu_Sf_poiseuille; /* the two parts of mu_Sf */
  double x_min_film_m;        /* where u is smallest (EHL constriction: outlet side, x > 0) */
  int regime;                 /* vl_regime */
  double eps_f_min;           /* smallest epsilon_f(u) over the grid (viscous flattening);
                               * 1 when the effect is off */
  char warnings[VL_WARN_MAX]; /* ';'-separated, empty when none */
} vl_point;

/* Lubrication regime by the share of the load carried by the fluid. */
typedef enum {
  VL_REGIME_DRY = 0,     /* no fluid */
  VL_REGIME_BOUNDARY,    /* fluid carries < 5 % of the load */
  VL_REGIME_MIXED,       /* 5 % ... 95 % */
  VL_REGIME_HYDRODYNAMIC /* > 95 % */
} vl_regime;
const char *vl_regime_name(int regime);

/* Fields on the grid, SI; arrays of length n owned by the caller. */
typedef struct {
  size_t n;
  double *x_m, *p_f_pa, *p_c_pa, *u_m, *area_ratio;
  double *film_fraction; /* theta: 1 in the full film, < 1 where cavitated; may be NULL */
  double *width_m;       /* cell widths (graded grids are not uniform); may be NULL */
} vl_fields;

typedef struct vl_contact vl_contact;

/* Allocates the solver (KINSOL, matrices, work) for cfg; no allocation happens
 * inside the Newton loop afterwards. The initial guess is Hertz (relaxed). */
vl_status vl_contact_create(const vl_contact_config *cfg, vl_contact **out, vl_error *err);
void vl_contact_free(vl_contact *c);

/* Solves at sliding speed v0 (m/s) starting from the current state (the
 * previous solution, or Hertz). On return *pt is always filled; pt->converged
 * says whether the solve met the tolerance. When it did not, the internal
 * state is restored to what it was before the call and VL_ENOCONV is
 * returned (err says why); never NaN. */
vl_status vl_contact_solve(vl_contact *c, double v0_m_s, vl_point *pt, vl_error *err);

/* Changes the fluid viscosity of a wet contact (eta > 0; VL_EINPUT for a
 * contact created dry) and keeps the current state: the next
 * vl_contact_solve continues from it (continuation in viscosity). The limit
 * eta -> 0 of a smooth film is the dry contact, reached this way on a
 * fixed grid; a fresh start at small eta would have to find the thin film's
 * inlet and outlet zones from scratch. */
vl_status vl_contact_set_viscosity(vl_contact *c, double eta_pa_s, vl_error *err);
double vl_contact_viscosity(const vl_contact *c); /* Pa s */

/* Continuation in viscosity at speed v0: solves at log-spaced viscosities
 * from the current one to eta_pa_s, steps at most a factor max_ratio (> 1),
 * each from the last converged state; a failed step is halved (in log eta)
 * up to 6 times. On success the contact holds the solution at eta_pa_s and
 * *pt reports it (iterations: the total); on failure the viscosity and
 * state are those of the last converged step, VL_ENOCONV (see err). */
vl_status vl_contact_solve_viscosity(vl_contact *c, double v0_m_s, double eta_pa_s,
                                     double max_ratio, vl_point *pt, vl_error *err);

/* Resets the internal state to the Hertz (relaxed) guess. */
void vl_contact_reset(vl_contact *c);

/* Copies the current fields (n = grid) into f (arrays allocated by caller). */
void vl_contact_fields(const vl_contact *c, vl_fields *f);

/* Test aid: compares the analytic Jacobian at the current state (speed v0)
 * with central finite differences of the residual; returns the largest
 * |J_fd - J| over all entries divided by the largest |J|, or a negative
 * value on allocation failure. Leaves the state unchanged. */
double vl_contact_jacobian_check(vl_contact *c, double v0_m_s);

/* Test aid: the same comparison per block of rows, each normalised by its
 * own largest |J| (the global one is set by the Reynolds rows of a wet
 * contact, which hides errors in the others): rel[0] the contact rows
 * (elasticity or complementarity), rel[1] the Reynolds rows, rel[2] the
 * load balance (0 for an empty block). Returns the largest, or a negative
 * value on allocation failure. Leaves the state unchanged. */
double vl_contact_jacobian_check_blocks(vl_contact *c, double v0_m_s, double rel[3]);

/* Test aid: the fluid flux per unit length J (m^2/s) through the n + 1
 * cell faces of the current state, as discretised by the solver (face 0 is
 * the inlet end of the domain, face n the outlet end;
 * J = -(u^3 phi_p/(12 eta)) dpf/dx + v0 (u + h_rms phi_s)/2). Writes
 * min(cap, n + 1) values; returns n + 1, or 0 for a dry contact. */
size_t vl_contact_face_fluxes(const vl_contact *c, double *flux_m2_s, size_t cap);

/* Hydrodynamic inlet length sqrt(2 R h) (m) of a smooth wet contact of cfg
 * at speed v0 > 0, with h the larger of Martin's rigid film
 * 4.894 eta (v0/2) R/fN and the isoviscous-elastic estimate
 * 2.32 (eta (v0/2) R/fN) g^0.8, g = fN/sqrt(eta (v0/2) E' R), E' = 2 Er
 * (relaxed). For sizing the domain (MODEL.md section 9): the pressure of a
 * rigid cylinder spreads over several such lengths, and with the inlet end
 * X lengths upstream its film is short by about 1/(2 X^2) / (1/(4 Hc)),
 * Hc = 1.226 (0.6 % at X = 20). Reads rubber, radius, load, viscosity. */
double vl_contact_inlet_length_m(const vl_contact_config *cfg, double v0_m_s);

/* Cost instrumentation (benchmarks): wall-clock seconds (CLOCK_MONOTONIC)
 * and call counts of the solver's parts since creation or the last reset,
 * summed over the coarse-grid and dry helper contacts a smooth wet contact
 * owns. Reading the clock costs ~50 ns per call and allocates nothing. */
typedef struct {
  long residuals, jacobians, setups, solves, kernels, newtons;
  double t_residual_s;  /* residual evaluations (including KINSOL's line search) */
  double t_jacobian_s;  /* analytic Jacobian assembly */
  double t_setup_s;     /* linear solver set-up: the LU factorisation */
  double t_solve_s;     /* linear solver solves: the triangular solves */
  double t_kernel_s;    /* influence-matrix builds at a new speed */
  double t_newton_s;    /* KINSol calls in total (includes the four above) */
  long linsol_fallbacks;/* VL_LINSOL_SCHUR: set-ups or solves that fell back to the full LU */
} vl_contact_timing;

/* Sums the counters of c (and its helper contacts) into *t (overwritten). */
void vl_contact_timing_get(const vl_contact *c, vl_contact_timing *t);
/* Zeroes the counters of c and its helper contacts. */
void vl_contact_timing_reset(vl_contact *c);

size_t vl_contact_grid(const vl_contact *c); /* cells (fewer than cfg.grid when graded) */
double vl_contact_a0(const vl_contact *c); /* m */
/* Cell i < vl_contact_grid(c): its node (the cell centre) and width, in a0. */
void vl_contact_cell(const vl_contact *c, size_t i, double *x_a0, double *width_a0);
/* The influence coefficient the solver uses at speed v0 (builds the kernel
 * for v0, as a solve would): d(gap at node i)/d(pressure on cell j), gap in
 * a0^2/R, pressure in p0 (vl_contact_p0); for tests. */
double vl_contact_influence(vl_contact *c, double v0_m_s, size_t i, size_t j);
double vl_contact_p0(const vl_contact *c); /* Pa */

#endif
