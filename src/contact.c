/* One operating point of the dry contact: KINSOL Newton on dimensionless
 * unknowns (contact.h). */
#include "viscolube/contact.h"

#include <float.h>
#include <kinsol/kinsol.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "linsol_lapack.h"
#include "viscolube/kernel.h"

/* Smoothing of the Fischer-Burmeister function: p u = FB_EPS at the contact
 * edge instead of 0, far below the tolerance, but the function stays
 * differentiable where both p and u vanish. */
#define FB_EPS 1e-18

struct vl_contact {
  vl_contact_config cfg;
  bool rough;
  size_t n;        /* grid nodes */
  size_t nunk;     /* unknowns: n field values + rigid approach */
  double er_ref;   /* reduced modulus defining a0 (relaxed, or the elastic one) */
  double er_inf;   /* reduced glassy modulus (kernel prefactor) */
  double a0, p0, uscale, dxi, kfac;
  double *xi;      /* node positions x/a0 */
  double *A, *beta;/* Prony strengths and v0 tau_k / a0 */
  vl_toeplitz kern;
  double *M;       /* dense influence matrix, row-major: U_i += M[i n + j] P_j */
  double v0;       /* speed the kernel is built for (NAN: not yet) */
  bool kernel_ready;
  double e_abs, a_h, omega_h, sfac; /* asperity state; P = sfac * s(u) */
  double *P, *U, *dPdU;             /* work: pressure, gap, dP/dU on the grid */
  SUNContext ctx;
  N_Vector y, y_saved, ones, fwork;
  SUNMatrix J;
  SUNLinearSolver LS;
  void *kmem;
};

void vl_contact_config_defaults(vl_contact_config *cfg) {
  memset(cfg, 0, sizeof *cfg);
  cfg->grid = 512;
  cfg->x_min_a0 = -1.6;
  cfg->x_max_a0 = 1.4;
  cfg->tolerance = 1e-9;
  cfg->max_iterations = 100;
  cfg->linear_solver = VL_LINSOL_LAPACK;
}

void vl_asperity_state(const vl_prony *rubber, double load_n_per_m, double radius_m,
                       double v0_m_s, double *E_abs_pa, double *a_H_m, double *omega_H) {
  double red = vl_prony_reduced_factor(rubber);
  double lo = log(vl_prony_e0(rubber) * red), hi = log(rubber->e_inf_pa * red);
  double x = lo;
  if (rubber->n_terms > 0 && v0_m_s > 0.0 && hi > lo) {
    /* f(x) = ln|Er(w(e^x))| - x is decreasing: |Er| grows slower than w, and
     * w ~ sqrt(|Er|); bisection in ln|Er| is robust over all speeds. */
    for (int it = 0; it < 200 && hi - lo > 1e-15 * fabs(hi); it++) {
      double mid = 0.5 * (lo + hi);
      double w = M_PI * v0_m_s / sqrt(4.0 * load_n_per_m * radius_m / (M_PI * exp(mid)));
      double f = log(cabs(vl_prony_modulus(rubber, w)) * red) - mid;
      if (f > 0.0) lo = mid; else hi = mid;
    }
    x = 0.5 * (lo + hi);
  }
  double e = exp(x);
  double a = sqrt(4.0 * load_n_per_m * radius_m / (M_PI * e));
  if (E_abs_pa) *E_abs_pa = e;
  if (a_H_m) *a_H_m = a;
  if (omega_H) *omega_H = M_PI * v0_m_s / a;
}

/* Pressure P (dimensionless) and dP/dU from the unknowns. */
static void contact_pressure(vl_contact *c, const double *y) {
  size_t n = c->n;
  if (!c->rough) {
    memcpy(c->P, y, n * sizeof *c->P);
    return;
  }
  for (size_t i = 0; i < n; i++) {
    double dsdu;
    double s = vl_persson_pressure(c->cfg.roughness, y[i] * c->uscale, &dsdu);
    c->P[i] = c->sfac * s;
    c->dPdU[i] = c->sfac * dsdu * c->uscale;
  }
}

/* U_i = h0 + xi_i^2/2 + sum_j M_ij P_j (the elastic/viscoelastic gap). */
static void contact_gap(vl_contact *c, double h0) {
  size_t n = c->n;
  for (size_t i = 0; i < n; i++) {
    const double *row = c->M + i * n;
    double s = 0.0;
    for (size_t j = 0; j < n; j++) s += row[j] * c->P[j];
    c->U[i] = h0 + 0.5 * c->xi[i] * c->xi[i] + s;
  }
}

static double load_sum(const vl_contact *c) {
  double s = 0.0;
  for (size_t i = 0; i < c->n; i++) s += c->P[i];
  return s * c->dxi / (0.5 * M_PI);
}

static int residual_fn(N_Vector yv, N_Vector fv, void *user) {
  vl_contact *c = user;
  const double *y = N_VGetArrayPointer(yv);
  double *f = N_VGetArrayPointer(fv);
  size_t n = c->n;
  contact_pressure(c, y);
  contact_gap(c, y[n]);
  if (!c->rough) {
    for (size_t i = 0; i < n; i++) {
      double p = c->P[i], u = c->U[i];
      f[i] = p + u - sqrt(p * p + u * u + FB_EPS);
    }
  } else {
    for (size_t i = 0; i < n; i++) f[i] = y[i] - c->U[i];
  }
  f[n] = load_sum(c) - 1.0;
  for (size_t i = 0; i <= n; i++)
    if (!isfinite(f[i])) return 1; /* recoverable: KINSOL shortens the step */
  return 0;
}

static int jacobian_fn(N_Vector yv, N_Vector fv, SUNMatrix J, void *user, N_Vector t1,
                       N_Vector t2) {
  (void)fv, (void)t1, (void)t2;
  vl_contact *c = user;
  const double *y = N_VGetArrayPointer(yv);
  size_t n = c->n;
  double *Jd = SUNDenseMatrix_Data(J);
  size_t ld = n + 1;
  contact_pressure(c, y);
  contact_gap(c, y[n]);
  double lw = c->dxi / (0.5 * M_PI);
  if (!c->rough) {
    for (size_t i = 0; i < n; i++) {
      double p = c->P[i], u = c->U[i];
      double r = sqrt(p * p + u * u + FB_EPS);
      double dfdp = 1.0 - p / r, dfdu = 1.0 - u / r;
      const double *row = c->M + i * n;
      for (size_t j = 0; j < n; j++) Jd[j * ld + i] = dfdu * row[j];
      Jd[i * ld + i] += dfdp;
      Jd[n * ld + i] = dfdu;
    }
    for (size_t j = 0; j < n; j++) Jd[j * ld + n] = lw;
  } else {
    for (size_t i = 0; i < n; i++) {
      const double *row = c->M + i * n;
      for (size_t j = 0; j < n; j++) Jd[j * ld + i] = -row[j] * c->dPdU[j];
      Jd[i * ld + i] += 1.0;
      Jd[n * ld + i] = -1.0;
    }
    for (size_t j = 0; j < n; j++) Jd[j * ld + n] = lw * c->dPdU[j];
  }
  Jd[n * ld + n] = 0.0;
  return 0;
}

/* Rebuilds the influence matrix for speed v0 (viscoelastic kernels only). */
static void contact_set_speed(vl_contact *c, double v0) {
  if (c->v0 == v0) return;
  c->v0 = v0;
  vl_asperity_state(&c->cfg.rubber, c->cfg.load_n_per_m, c->cfg.radius_m, v0, &c->e_abs, &c->a_h,
                    &c->omega_h);
  c->sfac = c->e_abs / c->p0;
  size_t nt = c->cfg.rubber.n_terms;
  if (nt == 0 && c->kernel_ready) return; /* elastic: one kernel for all speeds */
  c->kernel_ready = true;
  for (size_t k = 0; k < nt; k++) c->beta[k] = v0 * c->cfg.rubber.tau_s[k] / c->a0;
  vl_toeplitz_refill(&c->kern, c->A, c->beta, nt);
  size_t n = c->n;
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) c->M[i * n + j] = -c->kfac * vl_toeplitz_at(&c->kern, i, j);
}

/* Hertz gap outside a contact of half-width 1 (units a0^2/R, x in a0). */
static double hertz_gap(double xi) {
  double ax = fabs(xi);
  if (ax <= 1.0) return 0.0;
  double r = sqrt(ax * ax - 1.0);
  return 0.5 * (ax * r - log(ax + r));
}

void vl_contact_reset(vl_contact *c) {
  size_t n = c->n;
  double *y = N_VGetArrayPointer(c->y);
  contact_set_speed(c, c->v0 == c->v0 ? c->v0 : 0.0);
  for (size_t i = 0; i < n; i++) {
    double x = c->xi[i];
    double p = fabs(x) < 1.0 ? sqrt(1.0 - x * x) : 0.0;
    if (!c->rough) {
      y[i] = p;
    } else {
      /* Separation of the rough contact under the Hertz pressure, plus the
       * Hertz gap outside. */
      double s = p * c->p0 / c->e_abs;
      double u = s > 0.0 ? vl_persson_separation(c->cfg.roughness, s) : 0.0;
      if (s <= 0.0) u = vl_persson_separation(c->cfg.roughness, 1e-12);
      y[i] = u / c->uscale + hertz_gap(x);
    }
  }
  /* h0 that best satisfies the gap equation inside the contact. */
  contact_pressure(c, y);
  contact_gap(c, 0.0);
  double sum = 0.0;
  size_t cnt = 0;
  for (size_t i = 0; i < n; i++) {
    if (fabs(c->xi[i]) < 1.0) {
      sum += (c->rough ? y[i] : 0.0) - c->U[i];
      cnt++;
    }
  }
  y[n] = cnt ? sum / (double)cnt : 0.0;
}

vl_status vl_contact_create(const vl_contact_config *cfg, vl_contact **out, vl_error *err) {
  *out = NULL;
  vl_status st = vl_prony_validate(&cfg->rubber, err);
  if (st != VL_OK) return st;
  if (!(cfg->radius_m > 0.0 && isfinite(cfg->radius_m))) {
    vl_error_set(err, "radius_m must be positive (got %g)", cfg->radius_m);
    return VL_EINPUT;
  }
  if (!(cfg->load_n_per_m > 0.0 && isfinite(cfg->load_n_per_m))) {
    vl_error_set(err, "load_n_per_m must be positive (got %g)", cfg->load_n_per_m);
    return VL_EINPUT;
  }
  if (!(cfg->sigma_s_pa >= 0.0 && isfinite(cfg->sigma_s_pa))) {
    vl_error_set(err, "sigma_s_pa must be >= 0 (got %g)", cfg->sigma_s_pa);
    return VL_EINPUT;
  }
  if (cfg->grid < 8 || cfg->grid > 16384) {
    vl_error_set(err, "grid must lie in [8, 16384] (got %zu)", cfg->grid);
    return VL_EINPUT;
  }
  if (!(cfg->x_max_a0 > cfg->x_min_a0)) {
    vl_error_set(err, "domain_a0: the end must exceed the start (got %g, %g)", cfg->x_min_a0,
                 cfg->x_max_a0);
    return VL_EINPUT;
  }
  if (!(cfg->tolerance > 0.0 && cfg->tolerance < 1.0)) {
    vl_error_set(err, "tolerance must lie in (0, 1) (got %g)", cfg->tolerance);
    return VL_EINPUT;
  }
  vl_contact *c = calloc(1, sizeof *c);
  if (!c) goto nomem;
  c->cfg = *cfg;
  if (c->cfg.max_iterations <= 0) c->cfg.max_iterations = 100;
  c->rough = cfg->roughness != NULL;
  c->n = cfg->grid;
  c->nunk = c->n + 1;
  double red = vl_prony_reduced_factor(&cfg->rubber);
  c->er_ref = vl_prony_e0(&cfg->rubber) * red;
  c->er_inf = cfg->rubber.e_inf_pa * red;
  c->a0 = sqrt(4.0 * cfg->load_n_per_m * cfg->radius_m / (M_PI * c->er_ref));
  c->p0 = 2.0 * cfg->load_n_per_m / (M_PI * c->a0);
  c->uscale = c->a0 * c->a0 / cfg->radius_m;
  c->dxi = (cfg->x_max_a0 - cfg->x_min_a0) / (double)c->n;
  /* w/(a0^2/R) = -(Er_ref/(pi Er_inf)) sum_j P_j Khat_ij, Khat in units of a0. */
  c->kfac = c->er_ref / (M_PI * c->er_inf);
  c->v0 = NAN;
  size_t n = c->n, nt = cfg->rubber.n_terms;
  c->xi = malloc(n * sizeof *c->xi);
  c->A = malloc((nt ? nt : 1) * sizeof *c->A);
  c->beta = calloc(nt ? nt : 1, sizeof *c->beta);
  c->M = calloc(n * n, sizeof *c->M);
  c->P = calloc(n, sizeof *c->P);
  c->U = calloc(n, sizeof *c->U);
  c->dPdU = calloc(n, sizeof *c->dPdU);
  if (!c->xi || !c->A || !c->beta || !c->M || !c->P || !c->U || !c->dPdU) goto nomem;
  for (size_t i = 0; i < n; i++) c->xi[i] = cfg->x_min_a0 + ((double)i + 0.5) * c->dxi;
  for (size_t k = 0; k < nt; k++) c->A[k] = cfg->rubber.A[k];
  st = vl_toeplitz_build(&c->kern, n, c->dxi, c->A, c->beta, nt, err);
  if (st != VL_OK) goto fail;

  if (SUNContext_Create(NULL, &c->ctx) != 0) goto nomem;
  c->y = N_VNew_Serial((sunindextype)c->nunk, c->ctx);
  c->y_saved = N_VNew_Serial((sunindextype)c->nunk, c->ctx);
  c->ones = N_VNew_Serial((sunindextype)c->nunk, c->ctx);
  c->fwork = N_VNew_Serial((sunindextype)c->nunk, c->ctx);
  c->J = SUNDenseMatrix((sunindextype)c->nunk, (sunindextype)c->nunk, c->ctx);
  if (!c->y || !c->y_saved || !c->ones || !c->fwork || !c->J) goto nomem;
  N_VConst(1.0, c->ones);
  c->LS = cfg->linear_solver == VL_LINSOL_SUNDIALS ? SUNLinSol_Dense(c->y, c->J, c->ctx)
                                                   : vl_linsol_lapack_create((long)c->nunk, c->ctx);
  if (!c->LS) goto nomem;
  c->kmem = KINCreate(c->ctx);
  if (!c->kmem) goto nomem;
  if (KINInit(c->kmem, residual_fn, c->y) != KIN_SUCCESS ||
      KINSetUserData(c->kmem, c) != KIN_SUCCESS ||
      KINSetLinearSolver(c->kmem, c->LS, c->J) != KIN_SUCCESS ||
      KINSetJacFn(c->kmem, jacobian_fn) != KIN_SUCCESS ||
      KINSetFuncNormTol(c->kmem, cfg->tolerance) != KIN_SUCCESS ||
      KINSetScaledStepTol(c->kmem, 1e-14) != KIN_SUCCESS ||
      KINSetMaxSetupCalls(c->kmem, 1) != KIN_SUCCESS ||
      KINSetNumMaxIters(c->kmem, c->cfg.max_iterations) != KIN_SUCCESS ||
      KINSetPrintLevel(c->kmem, 0) != KIN_SUCCESS) {
    vl_error_set(err, "KINSOL set-up failed");
    st = VL_EINTERNAL;
    goto fail;
  }
  KINSetErrHandlerFn(c->kmem, NULL, NULL);
  contact_set_speed(c, 0.0);
  vl_contact_reset(c);
  *out = c;
  return VL_OK;
nomem:
  vl_error_set(err, "out of memory for a %zu-node contact solver", cfg->grid);
  st = VL_ENOMEM;
fail:
  vl_contact_free(c);
  return st;
}

void vl_contact_free(vl_contact *c) {
  if (!c) return;
  if (c->kmem) KINFree(&c->kmem);
  if (c->LS) SUNLinSolFree(c->LS);
  if (c->J) SUNMatDestroy(c->J);
  if (c->ones) N_VDestroy(c->ones);
  if (c->fwork) N_VDestroy(c->fwork);
  if (c->y_saved) N_VDestroy(c->y_saved);
  if (c->y) N_VDestroy(c->y);
  if (c->ctx) SUNContext_Free(&c->ctx);
  vl_toeplitz_free(&c->kern);
  free(c->xi);
  free(c->A);
  free(c->beta);
  free(c->M);
  free(c->P);
  free(c->U);
  free(c->dPdU);
  free(c);
}

static void add_warning(vl_point *pt, const char *w) {
  size_t len = strlen(pt->warnings);
  snprintf(pt->warnings + len, sizeof pt->warnings - len, "%s%s", len ? ";" : "", w);
}

/* Fills the derived quantities of pt from the current fields. */
static void contact_report(vl_contact *c, vl_point *pt) {
  size_t n = c->n;
  const double *y = N_VGetArrayPointer(c->y);
  contact_pressure(c, y);
  contact_gap(c, y[n]);
  if (c->rough)
    for (size_t i = 0; i < n; i++) c->U[i] = y[i];
  const vl_contact_config *cfg = &c->cfg;
  double fN = cfg->load_n_per_m, dx = c->dxi * c->a0;
  double sum_px = 0.0, sum_area = 0.0, pmax = 0.0, umin = INFINITY;
  size_t imax = 0;
  for (size_t i = 0; i < n; i++) {
    double p = c->P[i] * c->p0, x = c->xi[i] * c->a0;
    sum_px += p * x * dx;
    double area;
    if (c->rough)
      area = vl_persson_area_ratio(cfg->roughness, c->P[i] / c->sfac, NULL);
    else
      area = c->P[i] > 1e-9 ? 1.0 : 0.0;
    sum_area += area * dx;
    if (p > pmax) pmax = p, imax = i;
    if (c->U[i] < umin) umin = c->U[i];
  }
  pt->x_centroid_m = sum_px / fN;
  pt->mu_Rc = -sum_px / (fN * cfg->radius_m);
  pt->mu_Rf = 0.0;
  pt->mu_Sc = cfg->sigma_s_pa * sum_area / fN;
  pt->mu_Sf = 0.0;
  pt->mu = pt->mu_Rc + pt->mu_Rf + pt->mu_Sc + pt->mu_Sf;
  pt->u_min_m = fmax(umin, 0.0) * c->uscale;
  /* separation at the pressure centroid (linear interpolation on nodes) */
  double xc = pt->x_centroid_m / c->a0;
  double t = (xc - c->xi[0]) / c->dxi;
  size_t k = t <= 0 ? 0 : (size_t)t;
  if (k >= n - 1) k = n - 2;
  double w = fmin(fmax(t - (double)k, 0.0), 1.0);
  pt->u_central_m = fmax((1 - w) * c->U[k] + w * c->U[k + 1], 0.0) * c->uscale;
  /* contact extent where p >= 1% of its peak, interpolated between nodes */
  double thr = 0.01 * pmax / c->p0;
  size_t lo = imax, hi = imax;
  while (lo > 0 && c->P[lo - 1] >= thr) lo--;
  while (hi + 1 < n && c->P[hi + 1] >= thr) hi++;
  double xl = c->xi[lo], xr = c->xi[hi];
  if (lo > 0) xl -= c->dxi * (c->P[lo] - thr) / (c->P[lo] - c->P[lo - 1]);
  if (hi + 1 < n) xr += c->dxi * (c->P[hi] - thr) / (c->P[hi] - c->P[hi + 1]);
  pt->contact_width_m = pmax > 0 ? (xr - xl) * c->a0 : 0.0;
  pt->fluid_load_fraction = 0.0;
  pt->load_error = fabs(load_sum(c) - 1.0);
  pt->E_wH_pa = c->e_abs;
  pt->a_H_m = c->a_h;
  pt->Q = 0.0;
  pt->peak_pressure_pa = pmax;
  pt->x_peak_m = c->xi[imax] * c->a0;
  if (pmax > 0 && (c->P[0] > 1e-3 * pmax / c->p0 || c->P[n - 1] > 1e-3 * pmax / c->p0))
    add_warning(pt, "contact reaches the domain edge");
}

vl_status vl_contact_solve(vl_contact *c, double v0_m_s, vl_point *pt, vl_error *err) {
  memset(pt, 0, sizeof *pt);
  pt->v0_m_s = v0_m_s;
  if (!(v0_m_s >= 0.0 && isfinite(v0_m_s))) {
    vl_error_set(err, "speed must be finite and >= 0 (got %g m/s)", v0_m_s);
    return VL_EINPUT;
  }
  N_VScale(1.0, c->y, c->y_saved);
  contact_set_speed(c, v0_m_s);
  int flag = KINSol(c->kmem, c->y, KIN_LINESEARCH, c->ones, c->ones);
  long nni = 0;
  KINGetNumNonlinSolvIters(c->kmem, &nni);
  /* Our own residual check: KINSOL also returns success when the step, not
   * the residual, became small. */
  double fnorm = INFINITY;
  if (residual_fn(c->y, c->fwork, c) == 0) fnorm = N_VMaxNorm(c->fwork);
  pt->iterations = nni;
  pt->residual = fnorm;
  pt->converged = flag >= 0 && fnorm <= c->cfg.tolerance;
  if (!pt->converged) {
    vl_error_set(err, "no convergence at v0 = %g m/s: KINSOL flag %d (%s), %ld iterations, "
                      "residual %.3g",
                 v0_m_s, flag, KINGetReturnFlagName(flag), nni, fnorm);
    N_VScale(1.0, c->y_saved, c->y);
    contact_report(c, pt);
    pt->v0_m_s = v0_m_s;
    pt->converged = false;
    pt->iterations = nni;
    pt->residual = isfinite(fnorm) ? fnorm : DBL_MAX;
    return VL_ENOCONV;
  }
  contact_report(c, pt);
  return VL_OK;
}

void vl_contact_fields(const vl_contact *c, vl_fields *f) {
  size_t n = c->n;
  const double *y = N_VGetArrayPointer(c->y);
  vl_contact *mc = (vl_contact *)c; /* work arrays only */
  contact_pressure(mc, y);
  contact_gap(mc, y[n]);
  for (size_t i = 0; i < n && i < f->n; i++) {
    double u = c->rough ? y[i] : c->U[i];
    f->x_m[i] = c->xi[i] * c->a0;
    f->p_c_pa[i] = c->P[i] * c->p0;
    f->p_f_pa[i] = 0.0;
    f->u_m[i] = fmax(u, 0.0) * c->uscale;
    f->area_ratio[i] = c->rough ? vl_persson_area_ratio(c->cfg.roughness, c->P[i] / c->sfac, NULL)
                                : (c->P[i] > 1e-9 ? 1.0 : 0.0);
  }
}

double vl_contact_jacobian_check(vl_contact *c, double v0_m_s) {
  contact_set_speed(c, v0_m_s);
  size_t m = c->nunk;
  SUNMatrix J = SUNDenseMatrix((sunindextype)m, (sunindextype)m, c->ctx);
  N_Vector yp = N_VClone(c->y), fp = N_VClone(c->y), fm = N_VClone(c->y);
  if (!J || !yp || !fp || !fm) {
    if (J) SUNMatDestroy(J);
    if (yp) N_VDestroy(yp);
    if (fp) N_VDestroy(fp);
    if (fm) N_VDestroy(fm);
    return -1.0;
  }
  jacobian_fn(c->y, c->fwork, J, c, NULL, NULL);
  double *Jd = SUNDenseMatrix_Data(J), jmax = 0.0, dmax = 0.0;
  for (size_t k = 0; k < m * m; k++) jmax = fmax(jmax, fabs(Jd[k]));
  double *y = N_VGetArrayPointer(yp);
  for (size_t j = 0; j < m; j++) {
    N_VScale(1.0, c->y, yp);
    double h = 1e-6 * fmax(fabs(y[j]), 1e-3);
    y[j] += h;
    residual_fn(yp, fp, c);
    y[j] -= 2.0 * h;
    residual_fn(yp, fm, c);
    const double *a = N_VGetArrayPointer(fp), *b = N_VGetArrayPointer(fm);
    for (size_t i = 0; i < m; i++)
      dmax = fmax(dmax, fabs((a[i] - b[i]) / (2.0 * h) - Jd[j * m + i]));
  }
  SUNMatDestroy(J);
  N_VDestroy(yp);
  N_VDestroy(fp);
  N_VDestroy(fm);
  return dmax / jmax;
}

size_t vl_contact_grid(const vl_contact *c) { return c->n; }
double vl_contact_a0(const vl_contact *c) { return c->a0; }
double vl_contact_p0(const vl_contact *c) { return c->p0; }
