/* Persson contact mechanics (roughness.h, src/persson.c) against
 * independent quadrature of the paper's Eq. (7)-(8) (docs/VALIDATION.md §4).
 *
 * The oracles here never call the library's u(s): the PSD, the moment
 * M(q) = \int_{q0}^{q} q'^3 C dq' (closed form of docs/VALIDATION.md §4 for a
 * self-affine PSD; GSL quadrature of our own power-law interpolation for a
 * tabulated one), w(q) and Eq. (8)'s inner integral over p' are all computed
 * in this file with GSL adaptive quadrature, with no exponential integral. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "vl_test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_math.h>

#include "persson_internal.h"
#include "viscolube/persson.h"

#define HRMS 3e-6 /* the paper's surface */
#define Q0 2e5
#define Q1 7.8e9

/* ----------------------------------------------------- independent oracle */

typedef struct {
  int tab;
  double H, q0, q1, c0;                /* self-affine */
  size_t n;                            /* tabulated knots */
  double q[64], C[64], tk[64], mk[64]; /* tk = ln(q_k/q0), mk = M at q_k */
} surf;

static gsl_integration_workspace *g_ws_outer, *g_ws_inner, *g_ws_m;

static double surf_C(const surf *f, double q) {
  if (!f->tab) return f->c0 * pow(q / f->q0, -2.0 * (1.0 + f->H));
  size_t k = 0;
  while (k + 2 < f->n && f->q[k + 1] <= q)
    k++;
  double a = log(f->C[k + 1] / f->C[k]) / log(f->q[k + 1] / f->q[k]);
  return f->C[k] * pow(q / f->q[k], a);
}

static double m_integrand(double t, void *p) { /* q^4 C(q) in t = ln(q/q0) */
  const surf *f = p;
  double q = f->q0 * exp(t);
  return q * q * q * q * surf_C(f, q);
}

static double quad(gsl_function *fn, double a, double b, gsl_integration_workspace *ws,
                   double epsrel) {
  double r = 0.0, e;
  int st = gsl_integration_qag(fn, a, b, 0.0, epsrel, 1000, GSL_INTEG_GAUSS21, ws, &r, &e);
  if (st != GSL_SUCCESS && st != GSL_EROUND) fail_msg("qag failed: %s", gsl_strerror(st));
  return r;
}

/* M(q0 e^dt), parametrised by dt so that small dt keeps its precision. */
static double surf_M(const surf *f, double dt) {
  if (!f->tab) { /* docs/VALIDATION.md §4: C0 q0^4 [(q/q0)^(2(1-H)) - 1] / (2(1-H)) */
    double p = 2.0 * (1.0 - f->H), q04 = pow(f->q0, 4.0);
    return p == 0.0 ? f->c0 * q04 * dt : f->c0 * q04 * expm1(p * dt) / p;
  }
  size_t k = 0;
  while (k + 2 < f->n && f->tk[k + 1] <= dt)
    k++;
  gsl_function fn = {m_integrand, (void *)f};
  return f->mk[k] + quad(&fn, f->tk[k], dt, g_ws_m, 1e-13);
}

static void surf_self_affine(surf *f, double H, double q0, double q1, double hrms) {
  memset(f, 0, sizeof *f);
  f->H = H;
  f->q0 = q0;
  f->q1 = q1;
  /* docs/VALIDATION.md §4 */
  f->c0 = H * hrms * hrms / (M_PI * q0 * q0 * (1.0 - pow(q0 / q1, 2.0 * H)));
}

/* A roll-off PSD C ~ (1 + (q/qr)^2)^-(1+H) sampled at n log-spaced knots,
 * scaled to h_rms by our own quadrature of 2 pi \int q C dq. */
static double q_integrand(double t, void *p) {
  const surf *f = p;
  double q = f->q0 * exp(t);
  return q * q * surf_C(f, q);
}

static void surf_tabulated(surf *f, size_t n, double q0, double q1, double qr, double H,
                           double hrms) {
  memset(f, 0, sizeof *f);
  f->tab = 1;
  f->n = n;
  f->q0 = q0;
  f->q1 = q1;
  for (size_t k = 0; k < n; k++) {
    f->q[k] = q0 * pow(q1 / q0, (double)k / (double)(n - 1));
    f->C[k] = pow(1.0 + pow(f->q[k] / qr, 2.0), -(1.0 + H));
    f->tk[k] = log(f->q[k] / q0);
  }
  f->q[n - 1] = q1;
  gsl_function fn = {q_integrand, f};
  double h2 = 0.0;
  for (size_t k = 0; k + 1 < n; k++)
    h2 += 2.0 * M_PI * quad(&fn, f->tk[k], f->tk[k + 1], g_ws_m, 1e-13);
  for (size_t k = 0; k < n; k++)
    f->C[k] *= hrms * hrms / h2;
  gsl_function fm = {m_integrand, f};
  f->mk[0] = 0.0;
  for (size_t k = 0; k + 1 < n; k++)
    f->mk[k + 1] = f->mk[k] + quad(&fm, f->tk[k], f->tk[k + 1], g_ws_m, 1e-13);
}

static void make_psd(const surf *f, double hrms, vl_psd *psd) {
  vl_error err;
  vl_status st = f->tab ? vl_psd_init_tabulated(psd, f->n, f->q, f->C, &err)
                        : vl_psd_init_self_affine(psd, f->H, f->q0, f->q1, hrms, &err);
  assert_int_equal(st, VL_OK);
}

static vl_persson *make_table(const surf *f, double hrms, size_t n) {
  vl_psd psd;
  vl_error err;
  vl_persson *t = NULL;
  make_psd(f, hrms, &psd);
  vl_status st = vl_persson_build(&psd, n, &t, &err);
  vl_psd_free(&psd);
  if (st != VL_OK) fail_msg("build failed: %s", err.msg);
  return t;
}

/* Inner integral of Eq. (8) with y = w p: \int_z^inf e^{-y^2}/y dy, z = w s,
 * done as \int_{ln z}^{inf} exp(-e^{2v}) dv by GSL (no E1). Beyond
 * v = ln(28) the integrand is < e^{-780}: zero in double. */
static double inner_integrand(double v, void *p) {
  (void)p;
  return exp(-exp(2.0 * v));
}

static double inner(double z) {
  if (z * z > 740.0) return 0.0; /* integrand < e^{-740} everywhere */
  double a = log(z), vhi = log(28.0);
  gsl_function fn = {inner_integrand, NULL};
  double r = 0.0;
  if (a < -3.0) {
    r += quad(&fn, a, -3.0, g_ws_inner, 1e-13);
    a = -3.0;
  }
  return r + quad(&fn, a, vhi, g_ws_inner, 1e-13);
}

typedef struct {
  const surf *f;
  double s;
  int ustar; /* 1: integrand of u* instead */
} outer_ctx;

/* Outer integral of Eq. (8) over q with t = ln(q/q0) = tau^2 (removes the
 * tau^-1 of w at q0): sqrt(pi) q^3 C w inner(w s) 2 tau. */
static double outer_integrand(double tau, void *p) {
  const outer_ctx *c = p;
  const surf *f = c->f;
  double dt = tau * tau, q = f->q0 * exp(dt);
  if (tau == 0.0) /* limit: 2 tau w -> 2 / sqrt(pi q0^4 C(q0)) */
    return c->ustar ? sqrt(M_PI) * pow(f->q0, 3.0) * surf_C(f, f->q0) * 2.0 /
                          sqrt(M_PI * pow(f->q0, 4.0) * surf_C(f, f->q0))
                    : 0.0;
  double w = 1.0 / sqrt(M_PI * surf_M(f, dt));
  double base = sqrt(M_PI) * q * q * q * surf_C(f, q) * 2.0 * tau * w;
  return c->ustar ? base : base * inner(w * c->s);
}

static int cmp_d(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Brute-force Eq. (8) (ustar = 0) or u* = sqrt(pi) \int q^2 C w dq
 * (ustar = 1). Breakpoints: the knots, and near tau = 0 the scale
 * b = s / (sqrt(pi) q0^2 sqrt(C(q0))) below which w s > 1 cuts the
 * integrand off, plus decades down to b/10, so the adaptive rule sees the
 * log-like feature there (without them it misses a piece O(s)). */
static double brute_u(const surf *f, double s, int ustar) {
  double L = log(f->q1 / f->q0), end = sqrt(L);
  double pts[128];
  size_t np = 0;
  pts[np++] = 0.0;
  pts[np++] = end;
  for (size_t k = 1; f->tab && k + 1 < f->n; k++)
    pts[np++] = sqrt(f->tk[k]);
  if (!ustar) {
    double b = s / (sqrt(M_PI) * f->q0 * f->q0 * sqrt(surf_C(f, f->q0)));
    double extra[3] = {0.25 * b, b, 4.0 * b};
    for (int k = 0; k < 3; k++)
      if (extra[k] > 1e-20 && extra[k] < end) pts[np++] = extra[k];
    for (double d = 0.1; d > fmax(0.1 * b, 1e-20) && np < 120; d *= 0.1)
      if (d < end) pts[np++] = d;
  }
  qsort(pts, np, sizeof *pts, cmp_d);
  size_t m = 1;
  for (size_t k = 1; k < np; k++)
    if (pts[k] > pts[m - 1] * (1.0 + 1e-9)) pts[m++] = pts[k];
  outer_ctx c = {f, s, ustar};
  gsl_function fn = {outer_integrand, &c};
  double r = 0.0, e;
  int st = gsl_integration_qagp(&fn, pts, m, 0.0, 1e-11, 2000, g_ws_outer, &r, &e);
  if (st != GSL_SUCCESS && st != GSL_EROUND) fail_msg("qagp failed: %s", gsl_strerror(st));
  return r;
}

static double g_integrand(double t, void *p) { /* q^4 C for g = (pi/4) \int q^3 C dq */
  return m_integrand(t, p);
}

static double brute_g(const surf *f) {
  gsl_function fn = {g_integrand, (void *)f};
  double L = log(f->q1 / f->q0), r = 0.0;
  if (!f->tab) return 0.25 * M_PI * quad(&fn, 0.0, L, g_ws_m, 1e-13);
  for (size_t k = 0; k + 1 < f->n; k++)
    r += quad(&fn, f->tk[k], f->tk[k + 1], g_ws_m, 1e-13);
  return 0.25 * M_PI * r;
}

/* ------------------------------------------------------------------ tests */

static int setup(void **state) {
  (void)state;
  gsl_set_error_handler_off();
  g_ws_outer = gsl_integration_workspace_alloc(2000);
  g_ws_inner = gsl_integration_workspace_alloc(1000);
  g_ws_m = gsl_integration_workspace_alloc(1000);
  return 0;
}

static int teardown(void **state) {
  (void)state;
  gsl_integration_workspace_free(g_ws_outer);
  gsl_integration_workspace_free(g_ws_inner);
  gsl_integration_workspace_free(g_ws_m);
  return 0;
}

/* The three surfaces of the checks: the paper's (H = 0.8), a rough small-H
 * one and a tabulated roll-off spectrum. */
static void the_surfaces(surf f[3], double hrms[3]) {
  surf_self_affine(&f[0], 0.8, Q0, Q1, HRMS);
  surf_self_affine(&f[1], 0.3, Q0, Q1, HRMS);
  surf_tabulated(&f[2], 24, 1e4, 1e9, 1e6, 0.7, 2e-6);
  hrms[0] = hrms[1] = HRMS;
  hrms[2] = 2e-6;
}

/* Eq. (8) with the inner integral in closed form (E1) against the
 * brute-force double integral. Both quadratures run at relative tolerance
 * ~1e-11 (Gauss-Kronrod on these smooth integrands lands near rounding:
 * measured agreement ~1e-15), so 1e-8 (brief: ~1e-7) checks the E1
 * reduction, the endpoint handling at q0 and w(q) with margin; the table's
 * u(s) must agree to 1e-7 (its interpolation error, measured 2-7e-9). Points span the
 * table, u from 45 h_rms to 2e-3 h_rms. */
static void test_u_vs_double_integral(void **state) {
  (void)state;
  surf f[3];
  double h[3];
  the_surfaces(f, h);
  const double uu[] = {45.0, 10.0, 2.0, 0.5, 0.1, 0.02, 0.002};
  for (int i = 0; i < 3; i++) {
    vl_persson *t = make_table(&f[i], h[i], 0);
    double worst = 0.0, worst_tab = 0.0;
    for (size_t k = 0; k < sizeof uu / sizeof uu[0]; k++) {
      double s = vl_persson_pressure(t, uu[k] * h[i], NULL);
      double ub = brute_u(&f[i], s, 0);
      double ue = vl_persson_separation_exact(t, s);
      double ut = vl_persson_separation(t, s);
      worst = fmax(worst, vl_test_rel(ue, ub));
      worst_tab = fmax(worst_tab, vl_test_rel(ut, ub));
      assert_true(vl_test_rel(ue, ub) < 1e-8);
      assert_true(vl_test_rel(ut, ub) < 1e-7);
    }
    print_message("surface %d: |u_E1 - u_double|/u <= %.2e, table %.2e\n", i, worst, worst_tab);
    vl_persson_free(t);
  }
}

/* u* = sqrt(pi) \int q^2 C w dq by our quadrature; the library's u* to 1e-9
 * (quadrature tolerance). For H = 1 it has a closed form,
 * u* = q0 sqrt(pi C0) erf(sqrt(ln(q1/q0))) (then q^2 C w dq = ... e^{-t}
 * t^{-1/2} dt). The slope of the exact u against ln s at small s (u ~ 30
 * h_rms, where corrections are O(s) ~ e^-28) is -u* to 1e-8, and the
 * table's d ln s/du at and beyond its end (40, 50, 80 h_rms) is -1/u* to
 * 1e-6 (the cubic's derivative error, measured ~1e-9). */
static void test_large_u_asymptote(void **state) {
  (void)state;
  surf f[3];
  double h[3];
  the_surfaces(f, h);
  for (int i = 0; i < 3; i++) {
    vl_persson *t = make_table(&f[i], h[i], 0);
    double us = brute_u(&f[i], 0.0, 1);
    assert_true(vl_test_rel(vl_persson_ustar(t), us) < 1e-9);
    double s1 = vl_persson_pressure(t, 30.0 * h[i], NULL), s2 = s1 * exp(-1.0);
    double slope = vl_persson_separation_exact(t, s1) - vl_persson_separation_exact(t, s2);
    assert_true(vl_test_rel(-slope, us) < 1e-8);
    const double uu[] = {40.0, 50.0, 80.0};
    for (int k = 0; k < 3; k++) {
      double d, s = vl_persson_pressure(t, uu[k] * h[i], &d);
      assert_true(vl_test_rel(d / s, -1.0 / us) < 1e-6);
    }
    vl_persson_free(t);
  }
  surf one;
  surf_self_affine(&one, 1.0, Q0, Q1, HRMS);
  vl_persson *t = make_table(&one, HRMS, 0);
  double closed = Q0 * sqrt(M_PI * one.c0) * erf(sqrt(log(Q1 / Q0)));
  assert_true(vl_test_rel(vl_persson_ustar(t), closed) < 1e-9);
  vl_persson_free(t);
}

/* Table s(u) against the exact quadrature over the whole table: for s on a
 * grid uniform in ln s (u from ~50 to ~1e-3 h_rms), u = exact(s) and the
 * table must give back s. Measured max relative error with the default 256
 * points: 4.3e-9 (paper), 4.8e-9 (H = 0.3), 1.0e-8 (tabulated); bound 5e-8.
 * Cubic Hermite with exact slopes is 4th order: halving the table must
 * multiply the error by ~16 (asserted > 6). */
static double table_error(const surf *f, double hrms, size_t n, size_t npts) {
  vl_persson *t = make_table(f, hrms, n);
  double lo = log(vl_persson_pressure(t, 49.9 * hrms, NULL));
  double hi = log(vl_persson_pressure(t, 1.001e-3 * hrms, NULL));
  double worst = 0.0;
  for (size_t k = 0; k < npts; k++) {
    double s = exp(lo + (hi - lo) * ((double)k + 0.5) / (double)npts);
    double ue = vl_persson_separation_exact(t, s);
    worst = fmax(worst, vl_test_rel(vl_persson_pressure(t, ue, NULL), s));
  }
  vl_persson_free(t);
  return worst;
}

static void test_table_vs_exact(void **state) {
  (void)state;
  surf f[3];
  double h[3];
  the_surfaces(f, h);
  for (int i = 0; i < 3; i++) {
    double e = table_error(&f[i], h[i], 0, 400);
    print_message("surface %d: max |s_table(u)/s - 1| = %.2e (256 points)\n", i, e);
    assert_true(e < 5e-8);
  }
  double e64 = table_error(&f[0], HRMS, 64, 300);
  double e128 = table_error(&f[0], HRMS, 128, 300);
  double e256 = table_error(&f[0], HRMS, 256, 300);
  print_message("paper surface: error vs n: 64 %.2e, 128 %.2e, 256 %.2e\n", e64, e128, e256);
  assert_true(e64 / e128 > 6.0 && e128 / e256 > 6.0);
}

/* Inverse consistency and shape on a dense grid u in [-h_rms, 100 h_rms],
 * including both extrapolations: s(u(s)) = s to 1e-12 (the inverse solves
 * the same cubic), s finite, > 0 and strictly decreasing, ds/du < 0 and
 * equal to a centred difference to 1e-6 (step 1e-4 of the local length
 * s/|ds/du|: truncation ~1e-8, roundoff ~1e-12). */
static void test_inverse_monotone_derivative(void **state) {
  (void)state;
  surf f[3];
  double h[3];
  the_surfaces(f, h);
  for (int i = 0; i < 3; i++) {
    vl_persson *t = make_table(&f[i], h[i], 0);
    double prev = INFINITY, worst_fd = 0.0;
    const size_t N = 40000;
    for (size_t k = 0; k <= N; k++) {
      double u = h[i] * (-1.0 + 101.0 * (double)k / (double)N);
      double d, s = vl_persson_pressure(t, u, &d);
      assert_true(isfinite(s) && s > 0.0 && d < 0.0);
      assert_true(s < prev);
      prev = s;
      double ub = vl_persson_separation(t, s);
      assert_true(fabs(ub - u) <= 1e-12 * fmax(fabs(u), h[i]));
      if (k % 20 == 0) {
        double del = 1e-4 * s / fabs(d);
        double fd =
            (vl_persson_pressure(t, u + del, NULL) - vl_persson_pressure(t, u - del, NULL)) /
            (2.0 * del);
        worst_fd = fmax(worst_fd, vl_test_rel(fd, d));
        assert_true(vl_test_rel(fd, d) < 1e-6);
      }
    }
    /* also s -> u -> s across the whole s range, both extrapolations */
    for (double ls = -300.0; ls < 10.0; ls += 0.37) {
      double s = exp(ls);
      assert_true(vl_test_rel(vl_persson_pressure(t, vl_persson_separation(t, s), NULL), s) <
                  1e-12);
    }
    print_message("surface %d: max |FD/ds/du - 1| = %.2e\n", i, worst_fd);
    vl_persson_free(t);
  }
}

/* C1 at the table ends (u ~ 1e-3 h_rms and ~50 h_rms, MODEL/roughness.h)
 * and at interior nodes: on a grid of step delta, a jump in s or ds/du
 * shows as an increment far larger than its neighbours' (which are
 * O(delta s'')). Asserted: no increment exceeds 4 times the larger of its
 * neighbours plus roundoff. */
static void scan_c1(const vl_persson *t, double ua, double ub, size_t n) {
  double del = (ub - ua) / (double)n;
  double *sv = malloc((n + 1) * sizeof *sv), *dv = malloc((n + 1) * sizeof *dv);
  assert_non_null(sv);
  assert_non_null(dv);
  for (size_t k = 0; k <= n; k++)
    sv[k] = vl_persson_pressure(t, ua + del * (double)k, &dv[k]);
  for (size_t k = 1; k + 2 <= n; k++) {
    double jd = fabs(dv[k + 1] - dv[k]);
    double nd = fmax(fabs(dv[k] - dv[k - 1]), fabs(dv[k + 2] - dv[k + 1]));
    assert_true(jd <= 4.0 * nd + 1e-12 * fabs(dv[k]));
    double js = fabs(sv[k + 1] - sv[k]);
    double ns = fmax(fabs(sv[k] - sv[k - 1]), fabs(sv[k + 2] - sv[k + 1]));
    assert_true(js <= 4.0 * ns + 1e-14 * sv[k]);
  }
  free(sv);
  free(dv);
}

static void test_c1_at_ends(void **state) {
  (void)state;
  surf f;
  surf_self_affine(&f, 0.8, Q0, Q1, HRMS);
  vl_persson *t = make_table(&f, HRMS, 0);
  scan_c1(t, 0.9e-3 * HRMS, 1.1e-3 * HRMS, 100000);
  scan_c1(t, 49.0 * HRMS, 51.0 * HRMS, 100000);
  scan_c1(t, 0.5 * HRMS, 0.6 * HRMS, 100000);
  vl_persson_free(t);
}

/* Eq. (7): A/A0 = (pi g)^{-1/2} \int_0^s e^{-sig^2/(4g)} dsig, with g by our
 * quadrature, against the library's erf form to 1e-10 (quadrature
 * tolerance); d(A/A0)/ds against a centred difference to 1e-7. */
typedef struct {
  double g;
} area_ctx;

static double area_integrand(double sig, void *p) {
  const area_ctx *c = p;
  return exp(-sig * sig / (4.0 * c->g)) / sqrt(M_PI * c->g);
}

static void test_area_ratio(void **state) {
  (void)state;
  surf f[3];
  double h[3];
  the_surfaces(f, h);
  for (int i = 0; i < 3; i++) {
    vl_persson *t = make_table(&f[i], h[i], 0);
    area_ctx c = {brute_g(&f[i])};
    assert_true(vl_test_rel(vl_persson_g(t), c.g) < 1e-10);
    gsl_function fn = {area_integrand, &c};
    for (double a = 1e-3; a < 4.0; a *= 1.7) { /* s / (2 sqrt(g)) */
      double s = 2.0 * sqrt(c.g) * a;
      double da, ar = vl_persson_area_ratio(t, s, &da);
      assert_true(vl_test_rel(ar, quad(&fn, 0.0, s, g_ws_m, 1e-13)) < 1e-10);
      double del = 1e-5 * s;
      double fd =
          (vl_persson_area_ratio(t, s + del, NULL) - vl_persson_area_ratio(t, s - del, NULL)) /
          (2.0 * del);
      assert_true(vl_test_rel(fd, da) < 1e-7);
    }
    double d0;
    assert_true(vl_persson_area_ratio(t, 0.0, &d0) == 0.0);
    assert_true(vl_persson_area_ratio(t, 1e6, NULL) > 1.0 - 1e-15);
    vl_persson_free(t);
  }
}

/* Scalings derived from the formulas.
 * (a) C -> k^2 C (h_rms -> k h_rms, H, q0, q1 fixed): M -> k^2 M, w -> w/k,
 *     so u_k(s) = (sqrt(pi)/2) \int q^2 k^2 C (w/k) E1(w^2 s^2/k^2) dq
 *     = k u_1(s/k); g -> k^2 g; u* -> k u*. Tables: s_k(u) = k s_1(u/k).
 * (b) q -> lambda q at fixed h_rms, H (self-affine: C0 -> C0/lambda^2,
 *     C'(q) = lambda^-2 C(q/lambda), M'(q) = lambda^2 M(q/lambda)):
 *     w' = w/lambda and u'(s) = u(s/lambda): only the slope scale changes.
 * Exact quadratures to 1e-9, tables to 1e-7. */
static void test_scalings(void **state) {
  (void)state;
  surf f;
  surf_self_affine(&f, 0.8, Q0, Q1, HRMS);
  vl_persson *t1 = make_table(&f, HRMS, 0);
  vl_persson *t2 = make_table(&f, 2.0 * HRMS, 0);
  surf fl;
  surf_self_affine(&fl, 0.8, 10.0 * Q0, 10.0 * Q1, HRMS);
  vl_persson *tl = make_table(&fl, HRMS, 0);
  assert_true(vl_test_rel(vl_persson_g(t2), 4.0 * vl_persson_g(t1)) < 1e-12);
  assert_true(vl_test_rel(vl_persson_ustar(t2), 2.0 * vl_persson_ustar(t1)) < 1e-9);
  assert_true(vl_test_rel(vl_persson_hrms(t2), 2.0 * HRMS) < 1e-12);
  assert_true(vl_test_rel(vl_persson_g(tl), 100.0 * vl_persson_g(t1)) < 1e-12);
  assert_true(vl_test_rel(vl_persson_ustar(tl), vl_persson_ustar(t1)) < 1e-9);
  for (double ls = -40.0; ls < 3.0; ls += 3.1) {
    double s = exp(ls);
    assert_true(vl_test_rel(vl_persson_separation_exact(t2, 2.0 * s),
                            2.0 * vl_persson_separation_exact(t1, s)) < 1e-9);
    assert_true(vl_test_rel(vl_persson_separation_exact(tl, 10.0 * s),
                            vl_persson_separation_exact(t1, s)) < 1e-9);
  }
  for (double u = 0.002; u < 45.0; u *= 1.9) {
    assert_true(vl_test_rel(vl_persson_pressure(t2, 2.0 * u * HRMS, NULL),
                            2.0 * vl_persson_pressure(t1, u * HRMS, NULL)) < 1e-7);
    assert_true(vl_test_rel(vl_persson_pressure(tl, u * HRMS, NULL),
                            10.0 * vl_persson_pressure(t1, u * HRMS, NULL)) < 1e-7);
  }
  vl_persson_free(t1);
  vl_persson_free(t2);
  vl_persson_free(tl);
}

/* Edge behaviour: s <= 0 means no contact (u infinite, no area), NaN
 * propagates, and bad arguments to build are rejected with a message. */
static void test_edges_and_errors(void **state) {
  (void)state;
  surf f;
  surf_self_affine(&f, 0.8, Q0, Q1, HRMS);
  vl_persson *t = make_table(&f, HRMS, 0);
  assert_true(isinf(vl_persson_separation(t, 0.0)) && vl_persson_separation(t, 0.0) > 0.0);
  assert_true(isinf(vl_persson_separation_exact(t, 0.0)));
  assert_true(isnan(vl_persson_pressure(t, NAN, NULL)));
  assert_true(isnan(vl_persson_separation(t, NAN)));
  double d;
  double s_far = vl_persson_pressure(t, -1.0, &d); /* 1 m of interpenetration */
  assert_true(isfinite(s_far) && s_far > 0.0 && isfinite(d) && d < 0.0);
  assert_true(vl_test_rel(vl_persson_hrms(t), HRMS) < 1e-13);
  vl_persson_free(t);

  vl_psd psd;
  vl_error err;
  vl_persson *out = (vl_persson *)&err; /* must be reset to NULL */
  make_psd(&f, HRMS, &psd);
  err.msg[0] = '\0';
  assert_int_equal(vl_persson_build(&psd, 10, &out, &err), VL_EINPUT);
  assert_null(out);
  assert_true(strlen(err.msg) > 0);
  vl_psd bad;
  memset(&bad, 0, sizeof bad);
  assert_int_equal(vl_persson_build(&bad, 0, &out, &err), VL_EINPUT);
  assert_null(out);
  vl_psd_free(&psd);
  vl_persson_free(NULL);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_u_vs_double_integral),
      cmocka_unit_test(test_large_u_asymptote),
      cmocka_unit_test(test_table_vs_exact),
      cmocka_unit_test(test_inverse_monotone_derivative),
      cmocka_unit_test(test_c1_at_ends),
      cmocka_unit_test(test_area_ratio),
      cmocka_unit_test(test_scalings),
      cmocka_unit_test(test_edges_and_errors),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
