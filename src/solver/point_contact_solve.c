/* The Newton of the point contact and its results (point_contact.h).
 *
 * KINSOL on the residual and Jacobian of point_contact.c, with the line
 * contact's reduced linear solver (linsol_reduced.h): the rows of the
 * cells out of contact are identity rows, solved on their own, and only
 * the cells in contact and the rigid approach go through an LU, updated
 * (Sherman-Morrison-Woodbury, bordering) for the cells that change set at
 * one speed. The Newton is the line contact's for a dry smooth contact
 * (docs/NUMERICS.md section 7): min(P, U) rows with full steps, the first
 * step on the contact set of the state; where full steps do not converge,
 * Fischer-Burmeister with a line search from the same start; then both
 * again from the Hertz guess. */
#include "point_contact_internal.h"

#include <float.h>
#include <kinsol/kinsol.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "blas_threads.h"
#include "linsol_reduced.h"

static int residual_fn(N_Vector yv, N_Vector fv, void *user) {
  vl_point_contact *c = user;
  double t0 = vl_point_contact_now_s();
  int r = vl_point_contact_residual(c, N_VGetArrayPointer(yv), N_VGetArrayPointer(fv));
  c->timing.t_residual_s += vl_point_contact_now_s() - t0;
  c->timing.residuals++;
  return r;
}

static int jacobian_fn(N_Vector yv, N_Vector fv, SUNMatrix J, void *user, N_Vector t1,
                       N_Vector t2) {
  (void)fv, (void)t1, (void)t2;
  vl_point_contact *c = user;
  double t0 = vl_point_contact_now_s();
  c->gap_rows_only = c->min_rows;
  vl_point_contact_jacobian(c, N_VGetArrayPointer(yv), SUNDenseMatrix_Data(J));
  c->gap_rows_only = false;
  c->timing.t_jacobian_s += vl_point_contact_now_s() - t0;
  c->timing.jacobians++;
  return 0;
}

/* The Jacobian writes what the solver reads: no zeroing pass. */
static int skip_zero(SUNMatrix A) {
  (void)A;
  return SUNMAT_SUCCESS;
}

/* The library never prints: KINSOL's messages are dropped (its flags go
 * into vl_error). */
static void silent(int code, const char *module, const char *function, char *msg, void *user) {
  (void)code, (void)module, (void)function, (void)msg, (void)user;
}

/* SUNDIALS context, vectors, matrix, the reduced linear solver and KINSOL
 * of c. VL_ENOMEM or VL_EINTERNAL with the reason in err. */
static vl_status kinsol_init(vl_point_contact *c, vl_error *err) {
  sunindextype m = (sunindextype)c->nunk;
  if (SUNContext_Create(NULL, &c->ctx) != 0) goto nomem;
  c->y = N_VNew_Serial(m, c->ctx);
  c->y_saved = N_VNew_Serial(m, c->ctx);
  c->y_start = N_VNew_Serial(m, c->ctx);
  c->ones = N_VNew_Serial(m, c->ctx);
  c->fwork = N_VNew_Serial(m, c->ctx);
  c->J = SUNDenseMatrix(m, m, c->ctx);
  if (!c->y || !c->y_saved || !c->y_start || !c->ones || !c->fwork || !c->J) goto nomem;
  N_VConst(1.0, c->ones);
  c->J->ops->zero = skip_zero;
  c->LS = vl_linsol_reduced_create((long)c->nunk, c->ctx);
  if (!c->LS) goto nomem;
  /* min(P, U): a cell out of contact has an exact identity row, known from
   * du; the block's LU is updated while the influence stays (a speed) */
  vl_linsol_reduced_set_rows(c->LS, c->du, (long)c->n, &c->min_rows, &c->kernel_builds);
  c->kmem = KINCreate(c->ctx);
  if (!c->kmem) goto nomem;
  if (KINInit(c->kmem, residual_fn, c->y) != KIN_SUCCESS ||
      KINSetUserData(c->kmem, c) != KIN_SUCCESS ||
      KINSetLinearSolver(c->kmem, c->LS, c->J) != KIN_SUCCESS ||
      KINSetJacFn(c->kmem, jacobian_fn) != KIN_SUCCESS ||
      KINSetFuncNormTol(c->kmem, c->cfg.tolerance) != KIN_SUCCESS ||
      KINSetScaledStepTol(c->kmem, 1e-14) != KIN_SUCCESS ||
      KINSetMaxSetupCalls(c->kmem, 1) != KIN_SUCCESS ||
      KINSetNumMaxIters(c->kmem, c->cfg.max_iterations) != KIN_SUCCESS ||
      KINSetPrintLevel(c->kmem, 0) != KIN_SUCCESS ||
      KINSetErrHandlerFn(c->kmem, silent, NULL) != KIN_SUCCESS) {
    vl_error_set(err, "KINSOL set-up failed for the point contact");
    return VL_EINTERNAL;
  }
  c->min_rows = true;
  return VL_OK;
nomem:
  vl_error_set(err, "out of memory for a %zu-cell point contact solver", c->n);
  return VL_ENOMEM;
}

vl_status vl_point_contact_create(const vl_point_contact_config *cfg, vl_point_contact **out,
                                  vl_error *err) {
  vl_point_contact *c = NULL;
  vl_status st = vl_point_contact_build(cfg, &c, err);
  if (st == VL_OK && c->graded) {
    *out = c;
    return VL_OK;
  }
  if (st == VL_OK) st = kinsol_init(c, err);
  if (st != VL_OK) {
    vl_point_contact_free(c);
    return st;
  }
  vl_point_contact_reset(c);
  *out = c;
  return VL_OK;
}

void vl_point_contact_free(vl_point_contact *c) {
  if (!c) return;
  if (c->kmem) KINFree(&c->kmem);
  if (c->LS) SUNLinSolFree(c->LS);
  if (c->J) SUNMatDestroy(c->J);
  N_Vector vs[] = {c->y, c->y_saved, c->y_start, c->ones, c->fwork};
  for (size_t i = 0; i < sizeof vs / sizeof vs[0]; i++)
    if (vs[i]) N_VDestroy(vs[i]);
  if (c->ctx) SUNContext_Free(&c->ctx);
  vl_point_contact_release(c);
}

/* One KINSol from the current y: adds its iterations to *nni; true when
 * our own check of the residual (max norm) passes (KINSOL also stops when
 * the step becomes small). */
static bool kinsol_once(vl_point_contact *c, int strategy, long *nni, int *flag, double *fnorm) {
  *flag = KINSol(c->kmem, c->y, strategy, c->ones, c->ones);
  c->warm_set = false;
  long it = 0;
  KINGetNumNonlinSolvIters(c->kmem, &it);
  *nni += it;
  c->timing.newton_iterations += it;
  *fnorm = INFINITY;
  if (residual_fn(c->y, c->fwork, c) == 0) *fnorm = N_VMaxNorm(c->fwork);
  return *flag >= 0 && *fnorm <= c->cfg.tolerance;
}

/* The active-set Newton from the current y (its first step on the set of
 * y), else Fischer-Burmeister with line search from the same y. */
static bool newton(vl_point_contact *c, long *nni, int *flag, double *fnorm) {
  N_VScale(1.0, c->y, c->y_start);
  c->min_rows = true, c->warm_set = true;
  if (kinsol_once(c, KIN_NONE, nni, flag, fnorm)) return true;
  N_VScale(1.0, c->y_start, c->y);
  c->min_rows = false;
  bool ok = kinsol_once(c, KIN_LINESEARCH, nni, flag, fnorm);
  c->min_rows = true;
  return ok;
}

static void add_warning(vl_point *pt, const char *w) {
  size_t len = strlen(pt->warnings);
  snprintf(pt->warnings + len, sizeof pt->warnings - len, "%s%s", len ? ";" : "", w);
}

/* Where the pressure of a run of contact cells vanishes beyond its end
 * cell e (pressure pe) next to the inner cell pi: p^2 is linear in the
 * distance near a smooth contact edge (Hertz: p ~ sqrt(distance)), so
 * its secant through the two cells is followed to zero; the edge lies
 * between the end cell and the first cell out of contact (0 .. h). */
static double edge_beyond(double pe, double pi, double h) {
  double qe = pe * pe, qi = pi * pi;
  if (!(qi > qe)) return 0.5 * h;
  double d = h * qe / (qi - qe);
  return d < h ? d : h;
}

/* The solved half's contact area (a0^2), as chords along x of every row
 * of cells, each run of contact cells extended to where p^2 extrapolates
 * to zero; *len the chord of row 0 through the peak of that row. */
static double contact_chords(const vl_point_contact *c, double *len) {
  size_t nx = c->nx, ny = c->ny;
  double area = 0.0, h = c->h;
  *len = 0.0;
  for (size_t iy = 0; iy < ny; iy++) {
    for (size_t ix = 0; ix < nx;) {
      if (!(c->P[ix * ny + iy] > 0.0)) {
        ix++;
        continue;
      }
      size_t a = ix, b = ix;
      while (b + 1 < nx && c->P[(b + 1) * ny + iy] > 0.0)
        b++;
      double chord = h;
      if (b > a)
        chord = c->X[b * ny] - c->X[a * ny] +
                edge_beyond(c->P[a * ny + iy], c->P[(a + 1) * ny + iy], h) +
                edge_beyond(c->P[b * ny + iy], c->P[(b - 1) * ny + iy], h);
      area += chord * h;
      if (iy == 0 && chord > *len) *len = chord;
      ix = b + 1;
    }
  }
  return area;
}

/* The widest extent across (a0, both halves): per column, the last cell in
 * contact from the axis plus its extrapolated edge. */
static double contact_breadth(const vl_point_contact *c) {
  size_t ny = c->ny;
  double top = 0.0;
  for (size_t ix = 0; ix < c->nx; ix++) {
    const double *p = c->P + ix * ny;
    if (!(p[0] > 0.0)) continue;
    size_t b = 0;
    while (b + 1 < ny && p[b + 1] > 0.0)
      b++;
    double edge = c->Y[b] + (b > 0 ? edge_beyond(p[b], p[b - 1], c->h) : 0.5 * c->h);
    top = edge > top ? edge : top;
  }
  return 2.0 * top;
}

/* Fills pt (and pt->ball) from the converged state. */
static void report(vl_point_contact *c, vl_point *pt) {
  vl_point_contact_eval(c, N_VGetArrayPointer(c->y));
  const vl_point_contact_config *cfg = &c->cfg;
  size_t n = c->n, ny = c->ny, imax = 0, iumin = 0, in = 0;
  double sum_p = 0.0, sum_px = 0.0;
  bool edge = false;
  for (size_t k = 0; k < n; k++) {
    sum_p += c->P[k], sum_px += c->P[k] * c->X[k];
    if (c->P[k] > c->P[imax]) imax = k;
    if (c->U[k] < c->U[iumin]) iumin = k;
    if (c->P[k] > 0.0) {
      in++;
      size_t ix = k / ny, iy = k % ny;
      edge = edge || ix == 0 || ix + 1 == c->nx || iy + 1 == ny;
    }
  }
  double len, area = 2.0 * contact_chords(c, &len) * c->a0 * c->a0;
  double W = cfg->load_n;
  /* the rolling term: the pressure against the slope x/Rx, both halves */
  pt->mu_Rc = -2.0 * c->h * c->h * sum_px * c->p0 * c->a0 * c->a0 * c->a0 / (W * cfg->radius_x_m);
  pt->mu_Sc = cfg->sigma_s_pa * area / W;
  pt->mu = pt->mu_Rc + pt->mu_Sc;
  pt->x_centroid_m = sum_p > 0.0 ? c->a0 * sum_px / sum_p : 0.0;
  pt->u_min_m = fmax(c->U[iumin], 0.0) * c->uscale;
  pt->x_min_film_m = c->X[iumin] * c->a0;
  pt->u_central_m = 0.0; /* dry: the solids touch at the pressure centroid */
  pt->contact_width_m = len * c->a0;
  pt->fluid_load_fraction = 0.0;
  pt->u_min_over_h_rms = NAN;
  pt->load_error = fabs(c->load_unit * sum_p - 1.0);
  pt->E_wH_pa = c->er0;
  pt->a_H_m = c->a0;
  pt->peak_pressure_pa = c->P[imax] * c->p0;
  pt->x_peak_m = c->X[imax] * c->a0;
  pt->regime = VL_REGIME_DRY;
  pt->eps_f_min = 1.0;
  if (edge) add_warning(pt, "contact reaches the domain edge (domain too small)");
  if (len < 8.0 * c->h) add_warning(pt, "fewer than 8 cells across the contact");
  vl_ball_result *ball = &pt->ball;
  ball->contact_area_m2 = area;
  ball->contact_length_m = len * c->a0;
  ball->contact_breadth_m = contact_breadth(c) * c->a0;
  ball->y_min_film_m = c->Y[iumin] * c->a0;
  ball->y_peak_m = c->Y[imax] * c->a0;
  ball->cells_in_contact = in;
  ball->cells_per_a0 = cfg->cells_per_a0;
  ball->x_half_a0 = cfg->x_half_a0, ball->y_max_a0 = cfg->y_max_a0;
}

/* A failed solve: says why, goes back to the state before the call (and
 * its speed), reports the point as not converged (never NaN). */
static vl_status failed(vl_point_contact *c, double v0, double v_before, long nni, int flag,
                        double fnorm, vl_point *pt, vl_error *err) {
  char *name = KINGetReturnFlagName(flag); /* malloc'd by SUNDIALS */
  vl_error_set(err,
               "point contact: no convergence at v0 = %g m/s: KINSOL flag %d (%s), %ld "
               "iterations, residual %.3g",
               v0, flag, name ? name : "?", nni, fnorm);
  free(name);
  N_VScale(1.0, c->y_saved, c->y);
  if (v_before == v_before) vl_point_contact_set_speed(c, v_before);
  pt->converged = false;
  pt->iterations = nni;
  pt->residual = isfinite(fnorm) ? fnorm : DBL_MAX;
  return VL_ENOCONV;
}

static vl_status solve_at(vl_point_contact *c, double v0, vl_point *pt, vl_error *err) {
  memset(pt, 0, sizeof *pt);
  pt->ball.geometry = c->geometry;
  pt->error_estimate = NAN;
  pt->u_min_over_h_rms = NAN;
  pt->v0_m_s = v0;
  pt->regime = VL_REGIME_DRY;
  if (!(v0 >= 0.0 && isfinite(v0))) {
    vl_error_set(err, "point contact: speed must be finite and >= 0 (got %g m/s)", v0);
    return VL_EINPUT;
  }
  double v_before = c->v0, v_state = c->v_state;
  N_VScale(1.0, c->y, c->y_saved);
  vl_point_contact_set_speed(c, v0);
  long nni = 0;
  int flag = 0;
  double fnorm = INFINITY;
  bool ok = newton(c, &nni, &flag, &fnorm);
  if (!ok && v_state == v_state) { /* a converged state did not lead here: Hertz */
    vl_point_contact_reset(c);
    ok = newton(c, &nni, &flag, &fnorm);
  }
  if (!ok) {
    c->v_state = v_state;
    return failed(c, v0, v_before, nni, flag, fnorm, pt, err);
  }
  pt->converged = true;
  pt->iterations = nni;
  pt->residual = fnorm;
  c->v_state = v0;
  report(c, pt);
  return VL_OK;
}

vl_status vl_point_contact_solve(vl_point_contact *c, double v0_m_s, vl_point *pt, vl_error *err) {
  int threads = vl_blas_pin_one_thread(); /* the same rounding at any OPENBLAS_NUM_THREADS */
  vl_status st =
      c->graded ? vl_point_contact_wet_solve(c, v0_m_s, pt, err) : solve_at(c, v0_m_s, pt, err);
  vl_blas_restore_threads(threads);
  return st;
}

void vl_point_contact_fields(const vl_point_contact *c, vl_fields2d *f) {
  if (c->graded) {
    const vl_point_ehl_map *m = &c->map;
    for (size_t k = 0; k < m->nx * m->ny; k++) {
      if (f->x_m) f->x_m[k] = m->x_m[k];
      if (f->y_m) f->y_m[k] = m->y_m[k];
      if (f->p_c_pa) f->p_c_pa[k] = m->pc_pa[k];
      if (f->u_m) f->u_m[k] = m->u_m[k];
      if (f->p_f_pa) f->p_f_pa[k] = m->p_pa[k];
    }
    return;
  }
  vl_point_contact *mc = (vl_point_contact *)c; /* work arrays only */
  vl_point_contact_eval(mc, N_VGetArrayPointer(c->y));
  for (size_t k = 0; k < c->n; k++) {
    if (f->x_m) f->x_m[k] = c->X[k] * c->a0;
    if (f->y_m) f->y_m[k] = c->Y[k] * c->a0;
    if (f->p_c_pa) f->p_c_pa[k] = c->P[k] * c->p0;
    if (f->u_m) f->u_m[k] = fmax(c->U[k], 0.0) * c->uscale;
    if (f->p_f_pa) f->p_f_pa[k] = 0.0;
  }
}

size_t vl_point_contact_cells(const vl_point_contact *c) {
  return c->graded ? c->map.nx * c->map.ny : c->n;
}

const char *vl_geometry_name(int geometry) {
  switch (geometry) {
  case VL_GEOMETRY_CYLINDER: return "cylinder";
  case VL_GEOMETRY_BALL: return "ball";
  case VL_GEOMETRY_ELLIPSOID: return "ellipsoid";
  }
  return "?";
}

double vl_point_contact_a0(const vl_point_contact *c) { return c->a0; }
double vl_point_contact_p0(const vl_point_contact *c) { return c->p0; }
