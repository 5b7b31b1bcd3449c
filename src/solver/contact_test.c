/* The test aids of contact_test.h: the Jacobian checked against finite
 * differences of the residual, the face fluxes of the Reynolds equation
 * (docs/MODEL.md section 5) as discretised, the cells and influence coefficients
 * (section 3), and the cost counters. */
#include "contact_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "lapack_abi.h"
#include "linsol_schur.h"

/* The finite-difference comparison of vl_contact_jacobian_check, per block
 * of rows (contact, Reynolds, load): max |J_fd - J| in worst[b], max |J| in
 * scale[b]. Returns false on allocation failure. */
static bool jacobian_compare(vl_contact *c, double v0_m_s, double worst[3], double scale[3]) {
  vl_contact_set_speed(c, v0_m_s);
  size_t m = c->nunk;
  SUNMatrix J = SUNDenseMatrix((sunindextype)m, (sunindextype)m, c->ctx);
  N_Vector yp = N_VClone(c->y), fp = N_VClone(c->y), fm = N_VClone(c->y);
  if (!J || !yp || !fp || !fm) {
    if (J) SUNMatDestroy(J);
    if (yp) N_VDestroy(yp);
    if (fp) N_VDestroy(fp);
    if (fm) N_VDestroy(fm);
    return false;
  }
  vl_contact_jacobian_fn(c->y, c->fwork, J, c, NULL, NULL);
  double *Jd = SUNDenseMatrix_Data(J);
  for (int b = 0; b < 3; b++)
    worst[b] = scale[b] = 0.0;
#define BLOCK(i) ((i) < c->nc ? 0 : (i) < c->ih ? 1 : 2)
  for (size_t j = 0; j < m; j++)
    for (size_t i = 0; i < m; i++)
      scale[BLOCK(i)] = fmax(scale[BLOCK(i)], fabs(Jd[j * m + i]));
  double *y = N_VGetArrayPointer(yp);
  for (size_t j = 0; j < m; j++) {
    N_VScale(1.0, c->y, yp);
    double h = 1e-6 * fmax(fabs(y[j]), 1e-3);
    y[j] += h;
    vl_contact_residual_fn(yp, fp, c);
    y[j] -= 2.0 * h;
    vl_contact_residual_fn(yp, fm, c);
    const double *a = N_VGetArrayPointer(fp), *b = N_VGetArrayPointer(fm);
    for (size_t i = 0; i < m; i++)
      worst[BLOCK(i)] = fmax(worst[BLOCK(i)], fabs((a[i] - b[i]) / (2.0 * h) - Jd[j * m + i]));
  }
#undef BLOCK
  SUNMatDestroy(J);
  N_VDestroy(yp);
  N_VDestroy(fp);
  N_VDestroy(fm);
  return true;
}

double vl_contact_jacobian_check(vl_contact *c, double v0_m_s) {
  double worst[3], scale[3];
  if (!jacobian_compare(c, v0_m_s, worst, scale)) return -1.0;
  return fmax(worst[0], fmax(worst[1], worst[2])) / fmax(scale[0], fmax(scale[1], scale[2]));
}

double vl_contact_jacobian_check_blocks(vl_contact *c, double v0_m_s, double rel[3]) {
  double worst[3], scale[3];
  if (!jacobian_compare(c, v0_m_s, worst, scale)) return -1.0;
  double r = 0.0;
  for (int b = 0; b < 3; b++) {
    rel[b] = scale[b] > 0.0 ? worst[b] / scale[b] : 0.0;
    r = fmax(r, rel[b]);
  }
  return r;
}

/* The state the next solve of a sweep starts from (the first rung of
 * contact_solve.c's ladder): kernel, predicted pf and fluid scales at v0. */
static void start_next_solve(vl_contact *c, double v0_m_s) {
  vl_contact_set_speed(c, v0_m_s);
  vl_contact_predict_state(c, v0_m_s);
  vl_contact_fluid_scales(c, v0_m_s);
}

/* The plain Newton step at c->y into step (dense LU); false on failure. */
static bool plain_step(vl_contact *c, double *step) {
  int N = (int)c->nunk, one = 1, info = 0;
  double *A = malloc((size_t)N * (size_t)N * sizeof *A);
  int *piv = malloc((size_t)N * sizeof *piv);
  bool ok = A && piv;
  if (ok) {
    const double *y = N_VGetArrayPointer(c->y);
    vl_contact_jacobian(c, y, A);
    vl_contact_residual(c, y, step);
    for (int i = 0; i < N; i++)
      step[i] = -step[i];
    dgetrf_(&N, &N, A, &N, piv, &info);
    if (info == 0) dgetrs_("N", &N, &one, A, &N, piv, step, &N, &info, 1);
    ok = info == 0;
  }
  free(A);
  free(piv);
  return ok;
}

/* The 2-norm of the residual at y + step and its max Reynolds row. */
static double stepped_norm(vl_contact *c, const double *step, double *work, double *reynolds) {
  const double *y = N_VGetArrayPointer(c->y);
  size_t N = c->nunk;
  double *yt = work, *f = work + N, s = 0.0;
  for (size_t i = 0; i < N; i++)
    yt[i] = y[i] + step[i];
  if (vl_contact_residual(c, yt, f) != 0) return INFINITY;
  *reynolds = 0.0;
  for (size_t i = 0; i < N; i++) {
    s += f[i] * f[i];
    if (i >= c->of && i < c->ih) *reynolds = fmax(*reynolds, fabs(f[i]));
  }
  return sqrt(s);
}

bool vl_contact_film_check(vl_contact *c, double v0_m_s, vl_contact_film_check_result *r) {
  memset(r, 0, sizeof *r);
  size_t N = c->nunk;
  double *plain = malloc(4 * N * sizeof *plain), *corr = plain ? plain + N : NULL;
  if (!plain) return false;
  N_VScale(1.0, c->y, c->y_saved);
  vl_contact_scales saved = vl_contact_scales_get(c);
  start_next_solve(c, v0_m_s);
  bool ok = plain_step(c, plain);
  if (ok) {
    memcpy(corr, plain, N * sizeof *corr);
    const double *y = N_VGetArrayPointer(c->y);
    bool was = c->film_correct;
    c->film_correct = true;
    double *f = corr + N, fnorm = 0.0;
    vl_contact_residual(c, y, f);
    for (size_t i = 0; i < N; i++)
      fnorm += f[i] * f[i];
    r->applied = vl_contact_film_correct(c, y, sqrt(fnorm), corr);
    c->film_correct = was;
    double rey;
    r->plain_norm = stepped_norm(c, plain, corr + N, &rey);
    r->corr_norm = stepped_norm(c, corr, corr + N, &r->reynolds_max);
    for (size_t i = 0; i < N; i++) {
      double d = fabs(corr[i] - plain[i]);
      bool fluid = i >= c->of && i < c->ih;
      if (fluid)
        r->pf_diff = fmax(r->pf_diff, d), r->pf_step = fmax(r->pf_step, fabs(plain[i]));
      else
        r->gap_change = fmax(r->gap_change, d);
    }
  }
  vl_contact_restore(c, c->y_saved, &saved); /* the state, speed and scales as they were */
  free(plain);
  return ok;
}

size_t vl_contact_face_fluxes(const vl_contact *c, double *flux_m2_s, size_t cap) {
  if (!c->wet) return 0;
  vl_contact *mc = (vl_contact *)c; /* work arrays only */
  vl_contact_eval_state(mc, N_VGetArrayPointer(c->y));
  double unit = 0.5 * c->v0 * c->uscale; /* J is stored in units of v0 us/2 */
  for (size_t f = 0; f <= c->n && f < cap; f++)
    flux_m2_s[f] = c->Jf[f] * unit;
  return c->n + 1;
}

void vl_contact_timing_get(const vl_contact *c, vl_contact_timing *t) {
  memset(t, 0, sizeof *t);
  for (int k = 0; k < 3; k++) {
    /* c, then its helper contacts (which may own helpers in turn) */
    const vl_contact *h = k == 0 ? c : k == 1 ? c->coarse : c->dry;
    if (!h) continue;
    vl_contact_timing s = h->timing;
    if (k > 0) vl_contact_timing_get(h, &s);
    t->residuals += s.residuals, t->jacobians += s.jacobians, t->setups += s.setups;
    t->solves += s.solves, t->kernels += s.kernels, t->newtons += s.newtons;
    t->t_residual_s += s.t_residual_s, t->t_jacobian_s += s.t_jacobian_s;
    t->t_setup_s += s.t_setup_s, t->t_solve_s += s.t_solve_s;
    t->t_kernel_s += s.t_kernel_s, t->t_newton_s += s.t_newton_s;
    t->linsol_fallbacks += k > 0 ? s.linsol_fallbacks : vl_linsol_schur_fallbacks(h->schur);
  }
}

void vl_contact_timing_reset(vl_contact *c) {
  memset(&c->timing, 0, sizeof c->timing);
  if (c->coarse) vl_contact_timing_reset(c->coarse);
  if (c->dry) vl_contact_timing_reset(c->dry);
}

void vl_contact_cell(const vl_contact *c, size_t i, double *x_a0, double *width_a0) {
  *x_a0 = c->xi[i], *width_a0 = c->wc[i];
}
double vl_contact_influence(vl_contact *c, double v0_m_s, size_t i, size_t j) {
  vl_contact_set_speed(c, v0_m_s);
  return vl_contact_influence_matrix(c)[i * c->n + j];
}

const vl_flattening *vl_contact_flattening(const vl_contact *c) { return c->flattening; }
