/* The contact solver's private state and the functions its files share.
 * Private to src/solver; the public API is viscolube/contact.h.
 *
 * The solver is split by responsibility (each file says which equations of
 * docs/MODEL.md it implements):
 *   contact.c           creation (scales, unknowns, allocation) and release;
 *   contact_config.c    numerics defaults and limits, validation of a
 *                       configuration, the film and inlet-length estimates;
 *   contact_grid.c      the grid (uniform or graded cells) and the influence
 *                       coefficients at a speed;
 *   contact_equations.c the discretised equations: state, residual and
 *                       Jacobian, Fischer-Burmeister, Couette faces,
 *                       Reynolds row weights and fluid scales;
 *   contact_film.c      the film pressure balanced at a Newton step's gap;
 *   contact_start.c     initial guesses, which solve nothing: Hertz, the
 *                       rigid cylinder, a state from the coarse grid, the
 *                       dry contact or the smooth film (solved by the
 *                       caller), a state from other cells, the speed
 *                       predictor;
 *   contact_newton.c    KINSOL glue: the Newton variants, the linear solvers
 *                       and their cost, the states a failed solve returns to;
 *   contact_report.c    results: the point's friction integrals and derived
 *                       quantities, the fields;
 *   contact.c           (again) creation calls the grid, the start and the
 *                       KINSOL set-up;
 *   contact_solve.c     the solve of a point: the ladder of starts and Newton
 *                       variants at one speed, and the paths that reach a
 *                       speed from a converged state;
 *   contact_estimate.c  the error estimate of a point (numerics.h);
 *   contact_test.c      the test aids of contact_test.h.
 * Calls go one way: a file calls only files listed before it (contact.c
 * counted where it appears again), then the sweeps (sweep.c, sweep_auto.c)
 * call them all. */
#ifndef VISCOLUBE_CONTACT_INTERNAL_H
#define VISCOLUBE_CONTACT_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <time.h>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include "viscolube/contact.h"
#include "viscolube/sweep.h"

#include "contact_test.h"
#include "kernel.h"

/* Smoothing of the Fischer-Burmeister function: p u = FB_EPS at the contact
 * edge instead of 0, far below the tolerance, but the function stays
 * differentiable where both p and u vanish. */
#define FB_EPS 1e-18

/* The same for the cavitation of a smooth film, where it must be far
 * smaller: FB(pf, R) = 0 means pf R = eps/2, and the far inlet of a stiff
 * contact has pf ~ 1e-7 (of its peak) with R = (flux imbalance)/(its
 * sensitivity to pf), a sensitivity of ~1e11 there: 1e-18 left the inlet
 * flux off by 1 %. */
#define FB_EPS_FILM 1e-200

/* The Newton cap of a rough wet film's first solve from the Hertz guess
 * (the dry and smooth-film starts that follow keep the scene's cap). In
 * the hard-case matrix the same 1772 of 1845 wet points converged with 50
 * as with 200, the sweeps took 40.6 s instead of 52.2 s; a cap of 30 on
 * every fresh start lost 33 points. The Newton from Hertz also stops
 * earlier when it crawls (newton_from_hertz in contact_newton.c). */
#define VL_FRESH_HERTZ_ITERATIONS 50

/* Smallest grid of the coarse levels used to start smooth wet solves. */
#define VL_COARSE_MIN 96

struct vl_contact {
  vl_contact_config cfg;
  bool rough, wet;
  size_t n;                         /* grid nodes */
  size_t nc;                        /* contact unknowns (n; 0 for a smooth wet contact) */
  size_t nf;                        /* fluid unknowns (n when wet, else 0) */
  size_t nunk;                      /* unknowns: nc contact + nf fluid + rigid approach */
  size_t of, ih;                    /* offsets of the fluid unknowns and of the rigid approach */
  double er_ref;                    /* reduced modulus defining a0 (relaxed, or the elastic one) */
  double er_inf;                    /* reduced glassy modulus (kernel prefactor) */
  double a0, p0, uscale, dxi, kfac; /* dxi: width of the uniform cells */
  double hrms;                      /* rms roughness (m), 0 when smooth */
  double *xi;                       /* node positions x/a0 (cell centres) */
  double *wc;                       /* cell widths /a0 */
  double *hf; /* n + 1 face distances /a0: node to node, half a cell at both ends */
  /* graded grid (vl_contact_config.grid_growth): cell i is uniform cells
   * first[i] .. first[i] + span[i] - 1 of an nv-cell uniform grid (span odd,
   * so its node is uniform node first[i] + span[i]/2); psum: prefix sums of
   * the uniform Toeplitz coefficients. All NULL on a uniform grid (nv = n). */
  size_t nv, *first, *span;
  double *psum;
  size_t nk;        /* Prony terms of the macroscopic kernel: cfg.rubber's, or 0 (elastic,
                     * relaxed) when the counter-surface moves (vl_moving) */
  double *A, *beta; /* Prony strengths and v0 tau_k / a0 */
  vl_toeplitz kern;
  double *M;       /* dense influence matrix, row-major: U_i += M[i n + j] P_j; built with every
                    * kernel, except where mcoef is set: then when first read
                    * (vl_contact_influence_matrix) */
  double *mcoef;   /* a smooth dry contact on a uniform grid: M as its 2n - 1 Toeplitz
                    * coefficients, M_ij = mcoef[i - j + n - 1] (the gap of the active-set
                    * Newton is summed from them), else NULL */
  size_t m_kernel; /* the kernel_builds M was built for */
  double v0;       /* speed the kernel is built for (NAN: not yet) */
  bool kernel_ready;
  double e_abs, a_h, omega_h, sfac; /* asperity state; P = sfac * s(u) */
  /* fluid scales of the current solve: pf = kappa p0 Pf; flux in units of
   * v0 us/2 (lambda: its Poiseuille coefficient); rough Reynolds rows per
   * Couette flux v0 u_ref/2 (rscale = 1/u_ref), see vl_contact_reynolds_weights */
  double kappa, lambda, rscale, u_ref;
  double *rw;                /* weight of Reynolds row i (frozen during a solve) */
  double v_state;            /* speed at which y was last converged (0: initial guess) */
  double q_rolling;          /* rolling number (wet, rough, viscoelastic), else 0 */
  double *P, *dPdU;          /* contact pressure (p0) and dP/dU on the grid */
  double *q;                 /* P + F, the load on the grid (gap work vector) */
  double *F;                 /* fluid pressure (p0) */
  double *U;                 /* separation (a0^2/R) */
  double *g, *dg, *cf, *dcf; /* conductance u^3 phi_p and Couette film u + h phi_s, /us^3, /us */
  double *Jf;                /* face fluxes, n + 1 */
  double *D;                 /* rough: elasticity residual U - G */
  vl_flattening *flattening; /* owned; NULL when cfg.flattening is NULL */
  double *sf, *dsf;          /* viscous flattening: sqrt(epsilon_f(u)) per node and its d/du (1/m);
                              * NULL when off */
  double *theta;             /* film fraction (report only) */
  double *fb_work;           /* smooth dry: d FB/dp and d FB/du per node (2 n, Jacobian work),
                              * else NULL */
  double *state_y;           /* smooth dry: the y of the last vl_contact_eval_state, else NULL */
  bool min_rows;             /* smooth dry: complementarity min(P, U) (a semismooth, active-set
                              * Newton) instead of Fischer-Burmeister; off on the dry helper of a
                              * smooth film (its results stay those of FB) */
  bool warm_set;             /* min_rows: the next Jacobian takes the contact set {P > 0} of the
                              * state (the last converged solution), whatever the gap */
  size_t kernel_builds;      /* influence matrices built (vl_contact_set_speed) */
  size_t state_kernel;       /* the one state_y was evaluated with */
  double *fprof, *sprof;     /* a tabulated profile at the nodes (contact.h): f/(a0^2/R) and its
                              * slope f'; NULL for the parabola */
  double *ptab;              /* the contact's copy of the profile's table (cfg points to it, so
                              * that the helper contacts it creates later may read it) */
  double *stab;              /* the same for a static pressure's table (cfg.static_x_m) */
  double *pamb;              /* ambient fluid pressure per cell (p0) with a sealed pressure
                              * (cfg.p_inlet_pa for x < 0, p_outlet_pa beyond), else NULL */
  double *film_work;         /* rough wet: 2 nunk + 3 n work values of contact_film.c, else NULL */
  bool film_correct;         /* Newton's steps get the film pressure of contact_film.c (during
                              * the Newton variants that continue a converged rough film) */
  vl_contact *coarse;        /* smooth wet: half-size grid for fresh starts (NULL when small);
                              * rough wet: the smooth film whose solution starts a lifted rough
                              * film (created on first use by contact_solve.c) */
  vl_contact *dry;           /* smooth wet viscoelastic, coarsest level: the dry contact on the same
                              * grid, whose solution starts the wet one (NULL otherwise) */
  vl_contact *estimator;     /* the same contact on cells three times as wide (error estimate;
                              * created on first use, contact_estimate.c) */
  vl_contact_timing timing;  /* cost counters (vl_contact_timing_get) */
  SUNContext ctx;
  N_Vector y, y_saved, y_outer, ones, fwork;
  bool reduced_rows;  /* min_rows and the reduced solver knows the rows from d/dU */
  bool gap_rows_only; /* min_rows, KINSOL's Jacobian for the reduced solver: the identity rows
                       * get their diagonal only (the solver reads no more of them) */
  N_Vector y_min;     /* min_rows: the start of the active-set Newton, for its fallback */
  SUNMatrix J;
  SUNLinearSolver LS;
  SUNLinearSolver schur; /* the inner solver of LS when VL_LINSOL_SCHUR applies (not owned) */
  void *kmem;
};

/* Wall-clock seconds (CLOCK_MONOTONIC), for the cost counters. */
static inline double vl_contact_now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Out of memory while building c: says so in err (every step of
 * vl_contact_create explains its own failure) and returns VL_ENOMEM. */
static inline vl_status vl_contact_nomem(const vl_contact *c, vl_error *err) {
  vl_error_set(err, "out of memory for a %zu-node contact solver", c->cfg.grid);
  return VL_ENOMEM;
}

/* contact.c */

/* The cells of a layout three times coarser: spans span[0..n-1] merged in
 * threes (the one or two left at the end kept) into out (room for n).
 * Returns the number of cells. */
size_t vl_contact_merge_cells(const size_t *span, size_t n, size_t *out);

/* contact_config.c */

/* VL_OK when cfg describes a contact vl_contact_create can build, else
 * VL_EINPUT (or the rubber's own status) with the reason in err. Changes
 * nothing. */
vl_status vl_contact_config_check(const vl_contact_config *cfg, vl_error *err);

/* Minimum film (m) of a smooth wet contact of cfg at v0, estimated as the
 * larger of Martin's rigid film and the isoviscous-elastic one (contact.h,
 * vl_contact_inlet_length_m). */
double vl_contact_film_estimate(const vl_contact_config *cfg, double v0);

/* contact_grid.c */

/* The dense influence matrix M of the current kernel, built first when it
 * is not (a contact with mcoef builds it only on demand). */
const double *vl_contact_influence_matrix(vl_contact *c);

/* Lays out the cells of c->cfg's grid (uniform, or graded when grid_growth
 * > 1): sets n, nv, span, first, xi, wc, hf, dxi and allocates psum.
 * VL_EINPUT (message in err) when the graded grid has more than
 * VL_CONTACT_MAX_CELLS cells, VL_ENOMEM. */
vl_status vl_contact_grid_init(vl_contact *c, vl_error *err);

/* Builds the Toeplitz kernel of the uniform grid for the Prony strengths
 * (c->A must be filled); the influence matrix follows at each speed. */
vl_status vl_contact_kernel_init(vl_contact *c, vl_error *err);

/* Makes the asperity state, the flattening's speed and the influence
 * matrix those of speed v0 (a no-op when v0 is the current speed; the
 * elastic kernel is built once). */
void vl_contact_set_speed(vl_contact *c, double v0);

/* contact_equations.c */

/* Everything the residual needs from the unknowns y: contact pressure P
 * (and dP/dU), fluid pressure F, separation U, flow quantities and face
 * fluxes. */
void vl_contact_eval_state(vl_contact *c, const double *y);

/* \int (pf + pc) dx / fN from the current state (needs vl_contact_eval_state). */
double vl_contact_load_sum(const vl_contact *c);

/* The fluid pressure beyond the inlet and outlet ends of the domain, in
 * the units of the fluid unknowns (kappa p0): the sealed pressures of
 * cfg, 0 without. */
void vl_contact_end_pressures(const vl_contact *c, double *pin, double *pout);

/* Reynolds row i before complementarity (needs vl_contact_eval_state). */
double vl_contact_reynolds_residual(const vl_contact *c, size_t i);

/* Reynolds row i after complementarity, Fischer-Burmeister of pf_i and the
 * row above, with its partial derivatives in *da (by pf_i) and *db (by the
 * row) when not NULL (needs the fluxes of y). */
double vl_contact_reynolds_row(const vl_contact *c, const double *y, size_t i, double *da,
                               double *db);

/* The face fluxes of y (vl_contact_eval_state does this too), from the flow
 * quantities already evaluated. */
void vl_contact_eval_fluxes(vl_contact *c, const double *y);

/* d(face flux f)/d(pf) across face f (0..n), lambda g_f / hf_f: the flux
 * through an interior face is -that times pf[f] - pf[f-1]; pf = 0 beyond
 * the ends. */
double vl_contact_face_poiseuille(const vl_contact *c, size_t f);

/* Weights of the Reynolds rows for the next solve, from the current state
 * (needs vl_contact_eval_state). */
void vl_contact_reynolds_weights(vl_contact *c);

/* Scales of the fluid unknowns for a solve at v0, from the current state,
 * then the Reynolds row weights; rescales c->y accordingly. */
void vl_contact_fluid_scales(vl_contact *c, double v0);

/* The residual f(y) (nunk values). Returns 0, or 1 when y is not
 * admissible (a non-finite entry, or a closed smooth film): KINSOL then
 * shortens the step. */
int vl_contact_residual(vl_contact *c, const double *y, double *f);

/* The analytic Jacobian at y into the column-major nunk x nunk matrix Jd,
 * every entry written. */
void vl_contact_jacobian(vl_contact *c, const double *y, double *Jd);

/* contact_film.c */

/* Nonlinear elimination of the fluid pressure from the Newton step `step`
 * at y (whose residual has the 2-norm fnorm), for a rough film: keeps the
 * step's gap and rigid approach and replaces its pf by the one that
 * satisfies the Reynolds rows at that gap. Returns false (step unchanged)
 * when c->film_correct is off, the fluid carries more than half the load,
 * the inner solve does not converge, or the full corrected step lands on a
 * residual above the plain full step's or too large for KINSOL's
 * sufficient decrease. Leaves c's state evaluated at an arbitrary point:
 * the caller evaluates again. */
bool vl_contact_film_correct(vl_contact *c, const double *y, double fnorm, double *step);

/* contact_start.c: guesses, which set c's unknowns and solve nothing */

/* Whether a smooth film of c at v0 is expected rigid (the film estimate no
 * thicker than Martin's rigid film): its start is then Martin's pressure. */
bool vl_contact_film_rigid(const vl_contact *c, double v0);

/* The analytic start of a smooth film at v0 (the film estimate with
 * Martin's pressure; else the pressure of dry, the dry contact of a
 * viscoelastic solid solved at v0 on the same cells, when not NULL, or
 * Hertz's). */
void vl_contact_guess_smooth_film(vl_contact *c, double v0, const vl_contact *dry);

/* A smooth film's start from the solution of the coarser level cc. */
void vl_contact_guess_from_coarse(vl_contact *c, vl_contact *cc);

/* A smooth dry contact's start at the speed its companion e (the same
 * contact on other cells) has just been solved at, from e_before, e's
 * contact pressures at c's converged speed (e's earlier state): c's own
 * contact set, except at the nodes where e's set changed from e_before to
 * its solution, which take e's (its pressure interpolated, or 0). */
void vl_contact_guess_from_companion(vl_contact *c, const vl_contact *e, const double *e_before);

/* Predictor of a continuation step to speed v0 (rough films). */
void vl_contact_predict_state(vl_contact *c, double v0);

/* A rough film's start from d, the dry contact solved at the same speed
 * on the same cells (separations and rigid approach; no fluid pressure):
 * the limit of a film that carries nothing. */
void vl_contact_guess_from_dry(vl_contact *c, const vl_contact *d);

/* A rough film's start from s, the smooth film solved at the same speed on
 * a uniform grid over the same domain (separation and fluid pressure
 * interpolated): the limit of a film that has lifted the solid off the
 * asperities. */
void vl_contact_guess_from_film(vl_contact *c, vl_contact *s);

/* Starts dst from src's converged state at its speed src->v_state (the
 * same contact on other cells: the unknowns interpolated between the
 * nodes, the rigid approach and the fluid scales copied), as a
 * continuation from there. False, with dst unchanged, when src holds no
 * converged state, the two differ in roughness or fluid, or a rough dst
 * reaches beyond src's domain. */
bool vl_contact_start_from(vl_contact *dst, const vl_contact *src);

/* contact_newton.c */

/* KINSOL's residual and Jacobian callbacks (timed; user is the contact). */
int vl_contact_residual_fn(N_Vector yv, N_Vector fv, void *user);
int vl_contact_jacobian_fn(N_Vector yv, N_Vector fv, SUNMatrix J, void *user, N_Vector t1,
                           N_Vector t2);

/* Creates the SUNDIALS context, vectors, matrix, linear solver and KINSOL
 * memory of c (sizes and configuration set). VL_ENOMEM or VL_EINTERNAL,
 * with the reason in err. */
vl_status vl_contact_kinsol_init(vl_contact *c, vl_error *err);

/* The Newton variants of the solve's ladder (contact_solve.c). */
typedef enum {
  VL_NEWTON_PLAIN,      /* up to the configuration's max_iterations */
  VL_NEWTON_CONTINUED,  /* a converged rough film continued: capped at
                         * VL_FRESH_HERTZ_ITERATIONS, each step's film pressure
                         * balanced (contact_film.c) */
  VL_NEWTON_FILM,       /* the film pressure balanced, not capped */
  VL_NEWTON_FROM_HERTZ, /* a rough film from Hertz: capped, in chunks, given up
                         * when a chunk has not halved the residual */
  VL_NEWTON_KINDS
} vl_newton_kind;

/* Newton (KINSOL) of the given kind from the current y at speed v0 (the
 * fluid scales set for v0 here): adds the iterations to *nni, sets
 * KINSOL's flag and the residual's max norm; true when that residual is
 * within the tolerance. */
bool vl_contact_newton(vl_contact *c, vl_newton_kind kind, double v0, long *nni, int *flag,
                       double *fnorm);

/* The speed and fluid scales of c's state: what a solve changes besides y,
 * and restores with it when it fails. */
typedef struct {
  double kappa, lambda, rscale, u_ref, v0;
} vl_contact_scales;

static inline vl_contact_scales vl_contact_scales_get(const vl_contact *c) {
  return (vl_contact_scales){c->kappa, c->lambda, c->rscale, c->u_ref, c->v0};
}

/* The fluid scales of s back in c (not the speed). */
static inline void vl_contact_scales_put(vl_contact *c, const vl_contact_scales *s) {
  c->kappa = s->kappa, c->lambda = s->lambda, c->rscale = s->rscale, c->u_ref = s->u_ref;
}

/* c's unknowns back from y, with the speed (unless NaN: none yet) and scales
 * of s, and the state evaluated there. */
void vl_contact_restore(vl_contact *c, N_Vector y, const vl_contact_scales *s);

/* A copy of a converged state of c (unknowns, speed, fluid scales) to come
 * back to after a detour of other solves (sweep.c: the recovery of failed
 * points below a converged one). */
typedef struct {
  N_Vector y; /* NULL until taken */
  vl_contact_scales s;
  double v_state;
} vl_contact_mark;

/* Takes c's present state into m (allocating m->y on first use); false when
 * out of memory. */
bool vl_contact_mark_take(const vl_contact *c, vl_contact_mark *m);

/* Puts m's state back in c, evaluated there. */
void vl_contact_mark_return(vl_contact *c, const vl_contact_mark *m);

void vl_contact_mark_free(vl_contact_mark *m);

/* Caps the Newton iterations of c's later solves at n (> 0; the
 * configuration's max_iterations otherwise). */
void vl_contact_set_max_iterations(vl_contact *c, int n);

/* contact_solve.c */

/* Solves point v from c's state (converged at c->v_state; 0: none) by
 * every path of sweep.h in turn (continuation, a fresh start, starts below
 * and above); counts into *st. On VL_ENOCONV c holds the Hertz guess. */
vl_status vl_contact_reach(vl_contact *c, double v, int max_depth, vl_point *pt, vl_sweep_stats *st,
                           vl_error *err);

/* Continuation with step control from c's converged state to `to`
 * (either way); only `to` is reported. */
vl_status vl_contact_ramp(vl_contact *c, double to, int max_depth, vl_point *pt, vl_sweep_stats *st,
                          vl_error *err);

/* contact_report.c */

/* Fills the derived quantities of pt from the current (converged) state. */
void vl_contact_report(vl_contact *c, vl_point *pt);

#endif
