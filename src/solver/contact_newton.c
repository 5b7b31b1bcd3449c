/* KINSOL glue: the Newton iteration on the residual and Jacobian of
 * contact_equations.c (with line search, and the step refused where a
 * smooth film would close), the linear solvers (LAPACK, SUNDIALS, the
 * Schur complement of the Reynolds rows, the active set of a dry contact)
 * wrapped to count their cost and to give a continued rough film's steps
 * the balanced film pressure of contact_film.c; the Newton variants the
 * solve's ladder uses (contact_solve.c); and the saved states a failed
 * solve goes back to. */
#include "contact_internal.h"

#include <float.h>
#include <kinsol/kinsol.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "blas_threads.h"
#include "flattening_internal.h"
#include "linsol_lapack.h"
#include "linsol_reduced.h"
#include "linsol_schur.h"

/* A SUNLinearSolver that forwards to an inner one and times its set-up
 * (factorisation) and solves: the cost split of vl_contact_timing. It
 * holds the contact, whose film_correct has each step corrected. */
typedef struct {
  SUNLinearSolver inner;
  vl_contact *c;
} timed_ls;

static SUNLinearSolver_Type timed_gettype(SUNLinearSolver S) {
  return SUNLinSolGetType(((timed_ls *)S->content)->inner);
}
static SUNLinearSolver_ID timed_getid(SUNLinearSolver S) {
  return SUNLinSolGetID(((timed_ls *)S->content)->inner);
}
static int timed_initialize(SUNLinearSolver S) {
  return SUNLinSolInitialize(((timed_ls *)S->content)->inner);
}
static int timed_setup(SUNLinearSolver S, SUNMatrix A) {
  timed_ls *t = S->content;
  double t0 = vl_contact_now_s();
  int r = SUNLinSolSetup(t->inner, A);
  t->c->timing.t_setup_s += vl_contact_now_s() - t0;
  t->c->timing.setups++;
  return r;
}
static int timed_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, realtype tol) {
  timed_ls *t = S->content;
  double t0 = vl_contact_now_s();
  int r = SUNLinSolSolve(t->inner, A, x, b, tol);
  /* KINSOL iterates on c->y in place: the step is taken from there. A rough
   * film's step gets the pf that balances its flow (contact_film.c) */
  if (r == SUNLS_SUCCESS && t->c->film_correct)
    vl_contact_film_correct(t->c, N_VGetArrayPointer(t->c->y), sqrt(N_VDotProd(b, b)),
                            N_VGetArrayPointer(x));
  t->c->timing.t_solve_s += vl_contact_now_s() - t0;
  t->c->timing.solves++;
  return r;
}
static sunindextype timed_lastflag(SUNLinearSolver S) {
  return SUNLinSolLastFlag(((timed_ls *)S->content)->inner);
}
static int timed_space(SUNLinearSolver S, long *lenrw, long *leniw) {
  return SUNLinSolSpace(((timed_ls *)S->content)->inner, lenrw, leniw);
}
static int timed_free(SUNLinearSolver S) {
  if (!S) return SUNLS_SUCCESS;
  if (S->content) {
    SUNLinSolFree(((timed_ls *)S->content)->inner);
    free(S->content);
    S->content = NULL;
  }
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

/* Wraps inner (owned from here on, freed with the wrapper, also on failure). */
static SUNLinearSolver timed_ls_create(SUNLinearSolver inner, vl_contact *c, SUNContext ctx) {
  if (!inner) return NULL;
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  timed_ls *t = S ? malloc(sizeof *t) : NULL;
  if (!t) {
    if (S) SUNLinSolFreeEmpty(S);
    SUNLinSolFree(inner);
    return NULL;
  }
  t->inner = inner, t->c = c;
  S->content = t;
  S->ops->gettype = timed_gettype;
  S->ops->getid = timed_getid;
  S->ops->initialize = timed_initialize;
  S->ops->setup = timed_setup;
  S->ops->solve = timed_solve;
  S->ops->lastflag = timed_lastflag;
  S->ops->space = timed_space;
  S->ops->free = timed_free;
  return S;
}

int vl_contact_residual_fn(N_Vector yv, N_Vector fv, void *user) {
  vl_contact *c = user;
  double t0 = vl_contact_now_s();
  int r = vl_contact_residual(c, N_VGetArrayPointer(yv), N_VGetArrayPointer(fv));
  c->timing.t_residual_s += vl_contact_now_s() - t0;
  c->timing.residuals++;
  return r;
}

int vl_contact_jacobian_fn(N_Vector yv, N_Vector fv, SUNMatrix J, void *user, N_Vector t1,
                           N_Vector t2) {
  (void)fv, (void)t1, (void)t2;
  vl_contact *c = user;
  double t0 = vl_contact_now_s();
  c->gap_rows_only = c->min_rows && c->reduced_rows;
  vl_contact_jacobian(c, N_VGetArrayPointer(yv), SUNDenseMatrix_Data(J));
  c->gap_rows_only = false;
  c->timing.t_jacobian_s += vl_contact_now_s() - t0;
  c->timing.jacobians++;
  return 0;
}

static int skip_zero(SUNMatrix A) {
  (void)A;
  return SUNMAT_SUCCESS;
}

/* The library never prints: KINSOL's messages are dropped, its return flags
 * reported in vl_error instead. */
static void silent_error_handler(int code, const char *module, const char *function, char *msg,
                                 void *user) {
  (void)code, (void)module, (void)function, (void)msg, (void)user;
}

vl_status vl_contact_kinsol_init(vl_contact *c, vl_error *err) {
  const vl_contact_config *cfg = &c->cfg;
  sunindextype m = (sunindextype)c->nunk;
  if (SUNContext_Create(NULL, &c->ctx) != 0) return vl_contact_nomem(c, err);
  c->y = N_VNew_Serial(m, c->ctx);
  c->y_saved = N_VNew_Serial(m, c->ctx);
  c->y_outer = N_VNew_Serial(m, c->ctx);
  c->ones = N_VNew_Serial(m, c->ctx);
  c->fwork = N_VNew_Serial(m, c->ctx);
  if (c->min_rows && !(c->y_min = N_VNew_Serial(m, c->ctx))) return vl_contact_nomem(c, err);
  c->J = SUNDenseMatrix(m, m, c->ctx);
  if (!c->y || !c->y_saved || !c->y_outer || !c->ones || !c->fwork || !c->J)
    return vl_contact_nomem(c, err);
  N_VConst(1.0, c->ones);
  /* KINSOL zeroes the matrix before every Jacobian call, element by
   * element (a fifth of a rough wet solve's time at N = 512);
   * vl_contact_jacobian writes every entry itself (rough) or zeroes by
   * memset */
  c->J->ops->zero = skip_zero;
  SUNLinearSolver inner;
  if (cfg->linear_solver == VL_LINSOL_SUNDIALS) {
    inner = SUNLinSol_Dense(c->y, c->J, c->ctx);
  } else if (cfg->linear_solver == VL_LINSOL_SCHUR && c->rough && c->wet) {
    inner = c->schur = vl_linsol_schur_create((long)c->n, (long)c->of, (long)c->ih, c->ctx);
    /* Reynolds row i depends on u of cells i-2 .. i+1 (its two faces'
     * upwinded films: jacobian_reynolds_row) */
    if (inner) vl_linsol_schur_set_band(inner, 1, 2);
  } else if (cfg->linear_solver == VL_LINSOL_SCHUR && !c->rough && !c->wet) {
    /* the default on a dry smooth contact: only the cells in contact are
     * coupled (linsol_reduced.h) */
    inner = vl_linsol_reduced_create((long)c->nunk, c->ctx);
    /* min(P, U): the rows of the cells out of contact are exact identity
     * rows, known from the Jacobian's d/dU (no scan of the matrix) */
    if (inner && c->min_rows) {
      vl_linsol_reduced_set_rows(inner, c->fb_work + c->n, (long)c->n, &c->min_rows,
                                 &c->kernel_builds);
      c->reduced_rows = true;
    }
  } else {
    inner = vl_linsol_lapack_create((long)c->nunk, c->ctx);
  }
  c->LS = timed_ls_create(inner, c, c->ctx);
  if (!c->LS) return vl_contact_nomem(c, err);
  c->kmem = KINCreate(c->ctx);
  if (!c->kmem) return vl_contact_nomem(c, err);
  if (KINInit(c->kmem, vl_contact_residual_fn, c->y) != KIN_SUCCESS ||
      KINSetUserData(c->kmem, c) != KIN_SUCCESS ||
      KINSetLinearSolver(c->kmem, c->LS, c->J) != KIN_SUCCESS ||
      KINSetJacFn(c->kmem, vl_contact_jacobian_fn) != KIN_SUCCESS ||
      KINSetFuncNormTol(c->kmem, cfg->tolerance) != KIN_SUCCESS ||
      KINSetScaledStepTol(c->kmem, 1e-14) != KIN_SUCCESS ||
      KINSetMaxSetupCalls(c->kmem, 1) != KIN_SUCCESS ||
      KINSetNumMaxIters(c->kmem, cfg->max_iterations) != KIN_SUCCESS ||
      KINSetPrintLevel(c->kmem, 0) != KIN_SUCCESS) {
    vl_error_set(err, "KINSOL set-up failed");
    return VL_EINTERNAL;
  }
  KINSetErrHandlerFn(c->kmem, silent_error_handler, NULL);
  return VL_OK;
}

/* One KINSol call from the current y with the scales as they are: adds the
 * iterations to *nni; returns whether our own residual check passed
 * (KINSOL also returns success when the step, not the residual, became
 * small). */
static bool kinsol_once(vl_contact *c, int strategy, long *nni, int *flag, double *fnorm) {
  double t0 = vl_contact_now_s();
  *flag = KINSol(c->kmem, c->y, strategy, c->ones, c->ones);
  c->warm_set = false;
  c->timing.t_newton_s += vl_contact_now_s() - t0;
  c->timing.newtons++;
  long it = 0;
  KINGetNumNonlinSolvIters(c->kmem, &it);
  *nni += it;
  *fnorm = INFINITY;
  if (vl_contact_residual_fn(c->y, c->fwork, c) == 0) *fnorm = N_VMaxNorm(c->fwork);
  return *flag >= 0 && *fnorm <= c->cfg.tolerance;
}

/* A smooth dry contact: the active-set Newton on min(P, U) with full steps,
 * its first step on the set of the state (the last solution), as an active
 * set method continues (4.5 steps per point on fig03-smooth against 11.7
 * with Fischer-Burmeister and line search). Full steps can cycle where the
 * set jumps far (the hard-case matrix's Einf/E0 = 1e4 at 64 cells): then
 * the Fischer-Burmeister Newton with line search from the same start. */
static bool kinsol_run(vl_contact *c, long *nni, int *flag, double *fnorm) {
  if (!c->min_rows) return kinsol_once(c, KIN_LINESEARCH, nni, flag, fnorm);
  N_VScale(1.0, c->y, c->y_min);
  c->warm_set = true;
  if (kinsol_once(c, KIN_NONE, nni, flag, fnorm)) return true;
  N_VScale(1.0, c->y_min, c->y);
  c->min_rows = false;
  bool ok = kinsol_once(c, KIN_LINESEARCH, nni, flag, fnorm);
  c->min_rows = true;
  return ok;
}

/* A rough film's Newton from Hertz, given up early when it crawls: run in
 * chunks of HERTZ_CHUNK iterations (KINSol resumes from the iterate it left
 * in c->y; the scales are set once), stopped when a chunk has not lowered
 * the residual (max norm) below HERTZ_MIN_DROP of where it began, or at
 * max_iterations. Such a start either converges soon or crawls: `friction`
 * on sbr-unfilled at 1e-2 m/s took 50 iterations from 2.2e4 to 1.1e4 (1.4e4
 * after 10), then converged from the dry contact in 13 + 7. */
#define HERTZ_CHUNK 10
#define HERTZ_MIN_DROP 0.5

static bool newton_from_hertz(vl_contact *c, int max_iterations, long *nni, int *flag,
                              double *fnorm) {
  *flag = KIN_MAXITER_REACHED, *fnorm = INFINITY;
  double start = INFINITY;
  if (vl_contact_residual_fn(c->y, c->fwork, c) == 0) start = N_VMaxNorm(c->fwork);
  bool ok = false;
  for (long done = 0; done < max_iterations && !ok;) {
    long before = *nni;
    int chunk = max_iterations - done < HERTZ_CHUNK ? (int)(max_iterations - done) : HERTZ_CHUNK;
    KINSetNumMaxIters(c->kmem, chunk);
    ok = kinsol_run(c, nni, flag, fnorm);
    done += *nni - before;
    if (*flag != KIN_MAXITER_REACHED || !(*fnorm < HERTZ_MIN_DROP * start)) break;
    start = *fnorm;
  }
  KINSetNumMaxIters(c->kmem, c->cfg.max_iterations);
  return ok;
}

bool vl_contact_newton(vl_contact *c, vl_newton_kind kind, double v0, long *nni, int *flag,
                       double *fnorm) {
  /* a rough film's Newton, from Hertz or from the predicted state, either
   * converges soon or crawls to the cap, and has starts to fall back on:
   * capped lower, they come sooner (sbr-unfilled on paper-0.5um at 1e-4
   * ... 0.1 m/s: 200 iterations lost from Hertz, then the dry start below
   * converged in 20; fig05 on a 30 nm surface: 60 of 285 continued solves
   * crawled to the 200-iteration cap, 12 converged after 50) */
  int capped = c->cfg.max_iterations < VL_FRESH_HERTZ_ITERATIONS ? c->cfg.max_iterations
                                                                 : VL_FRESH_HERTZ_ITERATIONS;
  /* continuation from a converged film: the film pressure of every step
   * balances its flow (contact_film.c). A fresh start from Hertz is far from
   * any balance, and the plain steps found their way more often */
  c->film_correct = kind == VL_NEWTON_CONTINUED || kind == VL_NEWTON_FILM;
  if (kind == VL_NEWTON_CONTINUED) KINSetNumMaxIters(c->kmem, capped);
  vl_contact_fluid_scales(c, v0);
  bool ok = kind == VL_NEWTON_FROM_HERTZ ? newton_from_hertz(c, capped, nni, flag, fnorm)
                                         : kinsol_run(c, nni, flag, fnorm);
  if (kind == VL_NEWTON_CONTINUED) KINSetNumMaxIters(c->kmem, c->cfg.max_iterations);
  c->film_correct = false;
  return ok;
}

void vl_contact_restore(vl_contact *c, N_Vector y, const vl_contact_scales *s) {
  N_VScale(1.0, y, c->y);
  if (s->v0 == s->v0) vl_contact_set_speed(c, s->v0);
  vl_contact_scales_put(c, s);
  if (c->wet) {
    vl_contact_eval_state(c, N_VGetArrayPointer(c->y));
    vl_contact_reynolds_weights(c);
  }
}

bool vl_contact_mark_take(const vl_contact *c, vl_contact_mark *m) {
  if (!m->y && !(m->y = N_VClone(c->y))) return false;
  N_VScale(1.0, c->y, m->y);
  m->s = vl_contact_scales_get(c);
  m->v_state = c->v_state;
  return true;
}

void vl_contact_mark_return(vl_contact *c, const vl_contact_mark *m) {
  vl_contact_restore(c, m->y, &m->s);
  c->v_state = m->v_state;
}

void vl_contact_mark_free(vl_contact_mark *m) {
  if (m->y) N_VDestroy(m->y);
  m->y = NULL;
}

void vl_contact_set_max_iterations(vl_contact *c, int n) {
  c->cfg.max_iterations = n;
  KINSetNumMaxIters(c->kmem, n);
}
