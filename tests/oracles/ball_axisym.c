/* The axisymmetric rough ball oracle (ball_axisym.h). */
#include "ball_axisym.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_ellint.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv, double *b,
            const int *ldb, int *info);

typedef struct {
  double r;
} kernel_at;

/* s/(r + s) K(2 sqrt(r s)/(r + s)): the displacement at r of a unit ring
 * load at s per ds (times 4/(pi Er)); log-singular at s = r. */
static double ring_kernel(double s, void *p) {
  double r = ((kernel_at *)p)->r;
  if (s <= 0.0) return 0.0;
  double k = 2.0 * sqrt(r * s) / (r + s);
  if (k >= 1.0) k = 1.0 - 1e-16;
  return s / (r + s) * gsl_sf_ellint_Kcomp(k, GSL_PREC_DOUBLE);
}

/* \int_a^b ring_kernel ds, split at r (the singularity) when inside. */
static double ring_integral(double r, double a, double b, gsl_integration_workspace *ws) {
  kernel_at at = {r};
  gsl_function f = {ring_kernel, &at};
  double sum = 0.0, res, err;
  double cut[3] = {a, b, b};
  int parts = 1;
  if (r > a && r < b) cut[1] = r, parts = 2;
  for (int q = 0; q < parts; q++) {
    gsl_integration_qags(&f, cut[q], cut[q + 1], 0.0, 1e-10, 200, ws, &res, &err);
    sum += res;
  }
  return sum;
}

int vl_oracle_axisym_solve(const vl_oracle_axisym_problem *pb, vl_oracle_axisym_solution *sol,
                           double *p_out, double *r_out) {
  size_t n = pb->rings;
  if (n < 4 || !(pb->radius_m > 0) || !(pb->load_n > 0) || !(pb->er_pa > 0) || !(pb->r_max_m > 0) ||
      !pb->law)
    return -1;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  size_t m = n + 1;
  double *G = malloc(n * n * sizeof *G), *J = malloc(m * m * sizeof *J);
  double *y = malloc(m * sizeof *y), *f = malloc(m * sizeof *f), *r = malloc(n * sizeof *r);
  double *ya = malloc(m * sizeof *ya), *area = malloc(n * sizeof *area);
  double *u = malloc(n * sizeof *u), *dp = malloc(n * sizeof *dp);
  int *piv = malloc(m * sizeof *piv);
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(200);
  int status = -3;
  if (!G || !J || !y || !f || !r || !ya || !area || !u || !dp || !piv || !ws) goto done;
  double h = pb->r_max_m / (double)n, c = 4.0 / (M_PI * pb->er_pa);
  for (size_t i = 0; i < n; i++) {
    double di = (double)i;
    r[i] = (di + 0.5) * h;
    area[i] = M_PI * (2.0 * di + 1.0) * h * h;
  }
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      G[i * n + j] = c * ring_integral(r[i], (double)j * h, (double)(j + 1) * h, ws);
  /* start: Hertz's pressure, the approach where the centre's law meets it */
  double a = cbrt(0.75 * pb->load_n * pb->radius_m / pb->er_pa);
  double p0 = 1.5 * pb->load_n / (M_PI * a * a);
  for (size_t i = 0; i < n; i++)
    y[i] = r[i] < a ? p0 * sqrt(1.0 - r[i] * r[i] / (a * a)) : 0.0;
  double lo = -1.0, hi = 1.0; /* u0 with law(u0) = p0: bisection on a bracket grown */
  while (pb->law(pb->user, lo, NULL) < p0)
    lo *= 2.0;
  while (pb->law(pb->user, hi, NULL) > p0)
    hi *= 2.0;
  for (int it = 0; it < 200; it++) {
    double mid = 0.5 * (lo + hi);
    if (pb->law(pb->user, mid, NULL) > p0)
      lo = mid;
    else
      hi = mid;
  }
  double w0 = 0.0;
  for (size_t j = 0; j < n; j++)
    w0 += G[j] * y[j];
  y[n] = 0.5 * (lo + hi) - w0;
  status = -2;
  double fnorm = INFINITY;
  for (int it = 0; it < 100; it++) {
    /* residual: p_i - law(u_i), and the load in units of W */
    double load = 0.0;
    for (size_t i = 0; i < n; i++) {
      double w = 0.0;
      for (size_t j = 0; j < n; j++)
        w += G[i * n + j] * y[j];
      u[i] = y[n] + 0.5 * r[i] * r[i] / pb->radius_m + w;
      f[i] = (y[i] - pb->law(pb->user, u[i], &dp[i])) / p0;
      load += y[i] * area[i];
    }
    f[n] = load / pb->load_n - 1.0;
    double norm = 0.0;
    for (size_t i = 0; i < m; i++)
      norm = fmax(norm, fabs(f[i]));
    if (norm < 1e-11) {
      sol->iterations = it;
      status = 0;
      break;
    }
    if (it > 0 && !(norm < fnorm)) { /* a step that did not reduce: halve it */
      for (size_t i = 0; i < m; i++)
        y[i] = 0.5 * (y[i] + ya[i]);
      continue;
    }
    fnorm = norm;
    memcpy(ya, y, m * sizeof *y);
    /* Jacobian, column-major: d f_i/d p_j = (delta_ij - law' G_ij)/p0, d/dh0 = -law'/p0 */
    for (size_t i = 0; i < n; i++) {
      for (size_t j = 0; j < n; j++)
        J[j * m + i] = ((i == j ? 1.0 : 0.0) - dp[i] * G[i * n + j]) / p0;
      J[n * m + i] = -dp[i] / p0;
    }
    for (size_t j = 0; j < n; j++)
      J[j * m + n] = area[j] / pb->load_n;
    J[n * m + n] = 0.0;
    int mi = (int)m, one = 1, info = 0;
    for (size_t i = 0; i < m; i++)
      f[i] = -f[i];
    dgesv_(&mi, &one, J, &mi, piv, f, &mi, &info);
    if (info != 0) {
      status = -3;
      break;
    }
    for (size_t i = 0; i < m; i++)
      y[i] += f[i];
  }
  if (status == 0) {
    sol->h0_m = y[n], sol->u0_m = u[0], sol->p_max_pa = 0.0;
    for (size_t i = 0; i < n; i++) {
      sol->p_max_pa = fmax(sol->p_max_pa, y[i]);
      if (p_out) p_out[i] = y[i];
      if (r_out) r_out[i] = r[i];
    }
  }
done:
  gsl_set_error_handler(old);
  if (ws) gsl_integration_workspace_free(ws);
  free(G), free(J), free(y), free(f), free(r), free(ya), free(area), free(u), free(dp), free(piv);
  return status;
}
