/* Tests of the influence coefficients (include/viscolube/kernel.h).
 *
 * References are independent of the closed form in src/kernel.c:
 *  - Ke(d) against adaptive GSL quadrature of \int log|d - y| dy;
 *  - Kve(d, b) against adaptive GSL quadrature of \int_0^inf e^{-s} Ke(d - b s) ds
 *    (the inner cell integral is Ke, itself checked against quadrature first);
 *  - limits against first-order expansions derived by hand (not from the code);
 *  - the elastic matrix against the Hertz solution (parabolic displacement).
 *
 * Error scale: Kve crosses zero, so a relative error against |K| alone is
 * meaningless there. The solver uses the coefficients in sums
 * w_i ~ sum_j p_j K_ij whose natural size is delta (times a log): an absolute
 * error e in one coefficient changes w by e/delta of the size of one cell's
 * contribution. So errors are measured against max(|K|, delta). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
/* cmocka.h needs the four above first (own block: not re-sorted) */
#include <cmocka.h>

#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include "kernel.h"
#include "kernel_expint.h"

#define EULER_GAMMA 0.57721566490153286060651209008240243
#define WS_SIZE 2000

/* ---------- quadrature references ---------- */

typedef struct {
  double d, delta, b;
} qpar;

static double f_log(double y, void *p) {
  const qpar *q = p;
  double u = fabs(q->d - y);
  return u > 0.0 ? log(u) : 0.0; /* the single point y = d has measure zero */
}

/* \int_{-delta/2}^{delta/2} log|d - y| dy; *abserr gets GSL's estimate. */
static double ke_quad(double d, double delta, double *abserr) {
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(WS_SIZE);
  assert_non_null(ws);
  qpar par = {d, delta, 0.0};
  gsl_function f = {f_log, &par};
  double lo = -0.5 * delta, hi = 0.5 * delta, r = 0.0, e = 0.0;
  int st;
  /* Tight absolute floor relative to the size of the answer's pieces. */
  double epsabs = 1e-17 * delta * (1.0 + fabs(log(delta)) + log1p(fabs(d) / delta));
  if (d > lo && d < hi) {
    /* log singularity at y = d: split there so that it sits at an end point
     * of each piece, where qags' extrapolation handles it */
    double r2, e2;
    st = gsl_integration_qags(&f, lo, d, epsabs, 1e-14, WS_SIZE, ws, &r, &e);
    assert_true(st == GSL_SUCCESS || st == GSL_EROUND);
    st = gsl_integration_qags(&f, d, hi, epsabs, 1e-14, WS_SIZE, ws, &r2, &e2);
    r += r2;
    e += e2;
  } else {
    st = gsl_integration_qags(&f, lo, hi, epsabs, 1e-14, WS_SIZE, ws, &r, &e);
  }
  gsl_integration_workspace_free(ws);
  assert_true(st == GSL_SUCCESS || st == GSL_EROUND);
  *abserr = e;
  return r;
}

static double f_kve(double s, void *p) {
  const qpar *q = p;
  return exp(-s) * vl_kernel_elastic(q->d - q->b * s, q->delta);
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* \int_0^inf e^{-s} Ke(d - b s) ds split at every feature of the integrand:
 * the kinks s = (d -+ delta/2)/b where the derivative is log-singular, then
 * decades from the smallest length scale up to s = 1 (the integrand behaves
 * like log(b s) across them), and qagiu for the exponential tail. */
static double kve_quad(double d, double delta, double b, double *abserr) {
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(WS_SIZE);
  assert_non_null(ws);
  qpar par = {d, delta, b};
  gsl_function f = {f_kve, &par};
  double pts[64];
  int np = 0;
  pts[np++] = 0.0;
  double kinks[2] = {(d - 0.5 * delta) / b, (d + 0.5 * delta) / b};
  double smin = delta / b;
  for (int i = 0; i < 2; i++) {
    if (kinks[i] > 0.0 && kinks[i] < 600.0) pts[np++] = kinks[i];
    if (fabs(kinks[i]) > 0.0 && fabs(kinks[i]) < smin) smin = fabs(kinks[i]);
  }
  for (double s = smin; s < 1.0 && np < 60; s *= 10.0)
    pts[np++] = s;
  pts[np++] = 1.0;
  qsort(pts, (size_t)np, sizeof pts[0], cmp_double);
  double scale = fmax(fabs(vl_kernel_elastic(d, delta)), delta) + delta * fabs(log(b / delta));
  double epsabs = 1e-17 * scale;
  double total = 0.0, err = 0.0;
  for (int i = 0; i + 1 < np; i++) {
    if (!(pts[i + 1] > pts[i])) continue;
    double r, e;
    int st = gsl_integration_qags(&f, pts[i], pts[i + 1], epsabs, 1e-14, WS_SIZE, ws, &r, &e);
    assert_true(st == GSL_SUCCESS || st == GSL_EROUND);
    total += r;
    err += e;
  }
  double r, e;
  int st = gsl_integration_qagiu(&f, pts[np - 1], epsabs, 1e-14, WS_SIZE, ws, &r, &e);
  assert_true(st == GSL_SUCCESS || st == GSL_EROUND);
  total += r;
  err += e;
  gsl_integration_workspace_free(ws);
  *abserr = err;
  return total;
}

static double scaled_err(double k, double ref, double delta) {
  return fabs(k - ref) / fmax(fabs(ref), delta);
}

/* ---------- Ke ---------- */

static void test_elastic_vs_quadrature(void **state) {
  (void)state;
  gsl_set_error_handler_off();
  const double deltas[] = {1.0, 1e-5, 3.7};
  const double xs[] = {0.0,     0.25,   -0.3,    0.5,  -0.5, 1.0,   -1.0,      1.5,    2.0,
                       -2.0,    3.0,    5.0,     -5.0, 10.0, -10.0, 100.0,     -100.0, 1000.0,
                       -1000.0, 4096.0, -4096.0, 1e5,  1e6,  -1e6,  0.5000001, 7.999};
  double worst = 0.0, worst_q = 0.0;
  for (size_t i = 0; i < sizeof deltas / sizeof deltas[0]; i++) {
    for (size_t j = 0; j < sizeof xs / sizeof xs[0]; j++) {
      double delta = deltas[i], d = xs[j] * delta, qe;
      double q = ke_quad(d, delta, &qe);
      double k = vl_kernel_elastic(d, delta);
      /* The reference must itself be good to 2e-14 of the scale (GSL's
       * estimate never drops below its roundoff floor 50 eps \int|f|). */
      if (qe > 2e-14 * fmax(fabs(q), delta))
        fail_msg("quadrature of Ke(%g, %g): error estimate %.3g", d, delta, qe);
      double e = scaled_err(k, q, delta);
      if (e > worst) worst = e;
      if (qe / fmax(fabs(q), delta) > worst_q) worst_q = qe / fmax(fabs(q), delta);
      /* 1e-13: the closed form is exact; quadrature and rounding of the
       * O(log) pieces leave ~1e-15, so this leaves room only for real bugs. */
      if (e > 1e-13) fail_msg("Ke(%g, %g) = %.17g, quadrature %.17g (err %.3g)", d, delta, k, q, e);
    }
  }
  printf(
      "# Ke vs quadrature: max error %.3g (quadrature estimate <= %.3g), scale max(|K|, delta)\n",
      worst, worst_q);
  /* Cell edges are finite: Ke(+-delta/2) = delta (log delta - 1). */
  assert_true(fabs(vl_kernel_elastic(0.5, 1.0) - (-1.0)) < 1e-15);
  assert_true(fabs(vl_kernel_elastic(-0.5, 1.0) - (-1.0)) < 1e-15);
  assert_true(isnan(vl_kernel_elastic(1.0, 0.0)));
}

/* ---------- Kve ---------- */

static void test_viscoelastic_vs_quadrature(void **state) {
  (void)state;
  gsl_set_error_handler_off();
  const double xs[] = {0.0,   1.0,   -1.0,   2.0,    -2.0,    5.0,    -5.0,   10.0,
                       -10.0, 100.0, -100.0, 1000.0, -1000.0, 4096.0, -4096.0};
  double worst = 0.0, worst_q = 0.0, wx = 0.0, wb = 0.0;
  for (int e10 = -12; e10 <= 12; e10++) {
    double beta = pow(10.0, e10);
    for (size_t j = 0; j < sizeof xs / sizeof xs[0]; j++) {
      const double delta = 1.0;
      double d = xs[j] * delta, b = beta * delta, qe;
      double q = kve_quad(d, delta, b, &qe);
      double k = vl_kernel_viscoelastic(d, delta, b);
      double qrel = qe / fmax(fabs(q), delta);
      if (qrel > worst_q) worst_q = qrel;
      /* the reference must be an order better than the tolerance below */
      if (qrel > 1e-13)
        fail_msg("quadrature not converged at x=%g beta=%g (%.3g)", xs[j], beta, qrel);
      double e = scaled_err(k, q, delta);
      if (e > worst) {
        worst = e;
        wx = xs[j];
        wb = beta;
      }
      /* 1e-12 (the brief asks 1e-10): both sides are good to ~1e-14, so a
       * wrong branch or a lost term (>= 1e-12 at these scales) fails. */
      if (e > 1e-12)
        fail_msg("Kve(x=%g, beta=%g) = %.17g, quadrature %.17g (err %.3g)", xs[j], beta, k, q, e);
    }
  }
  printf("# Kve vs quadrature (beta 1e-12..1e12, 375 points): max error %.3g at x=%g beta=%g;"
         " quadrature estimate <= %.3g\n",
         worst, wx, wb, worst_q);

  /* Dimensions: a non-unit cell (SI-like 10 um) at a few points; the scale
   * now includes delta |log delta| since Kve = delta (log delta + kve). */
  const double delta = 1e-5;
  const double xs2[] = {0.0, 3.0, -3.0, 250.0, -250.0};
  const double betas2[] = {1e-9, 0.3, 7.0, 40.0, 1e7};
  for (size_t i = 0; i < 5; i++)
    for (size_t j = 0; j < 5; j++) {
      double d = xs2[i] * delta, b = betas2[j] * delta, qe;
      double q = kve_quad(d, delta, b, &qe);
      double k = vl_kernel_viscoelastic(d, delta, b);
      double sc = fmax(fabs(q), delta * (1.0 + fabs(log(delta))));
      assert_true(qe <= 1e-13 * sc);
      if (fabs(k - q) > 1e-12 * sc)
        fail_msg("Kve(%g, %g, %g) = %.17g vs quadrature %.17g", d, delta, b, k, q);
    }
}

/* ---------- limits ---------- */

static void test_small_b_limit(void **state) {
  (void)state;
  const double xs[] = {0.0, 1.0, -1.0, 2.0, -3.0, 10.0, -100.0, 4096.0, -4096.0, 0.5, -0.5};
  for (size_t i = 0; i < sizeof xs / sizeof xs[0]; i++) {
    double delta = 0.7, d = xs[i] * delta;
    double ke = vl_kernel_elastic(d, delta);
    /* b == 0 is exactly the elastic coefficient (relaxed response). */
    assert_true(vl_kernel_viscoelastic(d, delta, 0.0) == ke);
    /* absurdly small b stays finite (no overflow of d/b) */
    assert_true(vl_kernel_viscoelastic(d, delta, 1e-300 * delta) == ke);
    /* b -> 0: Kve = Ke - b Ke'(d) + O(b^2 log b), Ke'(d) = log|d+delta/2| -
     * log|d-delta/2| (infinite at the edges, so those only get the bound).
     * At b = 1e-12 delta the difference is below 1e-10 delta. */
    double k12 = vl_kernel_viscoelastic(d, delta, 1e-12 * delta);
    assert_true(fabs(k12 - ke) < 1e-10 * delta);
    if (fabs(xs[i]) > 0.5) {
      double b = 1e-7 * delta;
      double kp = log(fabs(d + 0.5 * delta)) - log(fabs(d - 0.5 * delta));
      double slope = (vl_kernel_viscoelastic(d, delta, b) - ke) / b;
      /* 1e-5: the O(b) remainder is ~b/delta = 1e-7 relative and the
       * difference quotient loses ~7 of 16 digits. */
      if (fabs(slope + kp) > 1e-5 * fmax(fabs(kp), 1.0))
        fail_msg("dKve/db at b=0, x=%g: %.10g, expected %.10g", xs[i], slope, -kp);
    }
  }
}

/* First-order large-b expansion (derived in closed form, by hand):
 * kve = lambda - (x/beta)(lambda + 3/2) + [a+^2 log|a+| - a-^2 log|a-|]/(2 beta)
 *       + O(x^2 log(beta)/beta^2),  lambda = log(beta) - gamma, a+- = x +- 1/2. */
static double large_b_first_order(double x, double beta) {
  double lam = log(beta) - EULER_GAMMA, ap = x + 0.5, am = x - 0.5;
  double tp = ap != 0.0 ? ap * ap * log(fabs(ap)) : 0.0;
  double tm = am != 0.0 ? am * am * log(fabs(am)) : 0.0;
  return -(x / beta) * (lam + 1.5) + (tp - tm) / (2.0 * beta);
}

static void test_large_b_limit(void **state) {
  (void)state;
  const double xs[] = {0.0, 1.0, -1.0, 2.0, -5.0, 10.0, -100.0, 1000.0, 4096.0, -4096.0, 0.5};
  const double betas[] = {1e6, 1e8, 1e10, 1e12};
  double worst = 0.0;
  for (size_t i = 0; i < sizeof xs / sizeof xs[0]; i++)
    for (size_t j = 0; j < sizeof betas / sizeof betas[0]; j++) {
      double delta = 1.0, x = xs[i], beta = betas[j];
      double k = vl_kernel_viscoelastic(x * delta, delta, beta * delta);
      double glassy = delta * (log(beta * delta) - EULER_GAMMA);
      double dev = k - glassy; /* -> 0: the glassy constant */
      double first = delta * large_b_first_order(x, beta);
      double ax = fabs(x) + 1.0;
      /* remainder bound: x^2 log(beta)/beta^2 with a safety factor 4, plus
       * rounding of Kve (~1e-15 of its size log(beta)). */
      double bound = 4.0 * ax * ax * log(beta) / (beta * beta) + 1e-14 * fabs(glassy);
      if (fabs(dev - first) > bound)
        fail_msg("x=%g beta=%g: Kve - glassy = %.6g, first order %.6g", x, beta, dev, first);
      if (fabs(dev) > worst && beta == 1e12) worst = fabs(dev);
    }
  /* At b = 1e12 delta the coefficient is within 1e-6 delta of the constant
   * for every offset up to 4096 cells. */
  assert_true(worst < 1e-6);
  printf("# b = 1e12 delta: max |Kve - delta (log b - gamma)| = %.3g delta (|d| <= 4096 delta)\n",
         worst);
}

/* Kernel asymmetry pins the convention: the rubber moves to +x, so the
 * surface downstream of a load (d > 0) remembers it and stays more
 * depressed: Kve(+d) < Kve(-d) (w = -(2/(pi E)) sum p K, so a more negative
 * K means a larger w, a deeper dent). */
static void test_memory_looks_upstream(void **state) {
  (void)state;
  const double betas[] = {0.01, 0.3, 1.0, 5.0, 30.0, 1e3};
  for (size_t j = 0; j < sizeof betas / sizeof betas[0]; j++)
    for (int k = 1; k <= 50; k++) {
      double kp = vl_kernel_viscoelastic((double)k, 1.0, betas[j]);
      double km = vl_kernel_viscoelastic(-(double)k, 1.0, betas[j]);
      assert_true(kp < km);
    }
}

/* Continuity across every branch switch of kernel.c: evaluate a few ulps on
 * either side and require agreement to 1e-13 of max(|K|, delta). The true
 * change over 16 ulps is ~1e-15, so a jump means two branches disagree. */
static double nudge(double v, int ulps) {
  for (int i = 0; i < abs(ulps); i++)
    v = nextafter(v, ulps > 0 ? INFINITY : -INFINITY);
  return v;
}

static void check_jump_beta(double x, double beta, double *worst) {
  double lo = vl_kernel_viscoelastic(x, 1.0, nudge(beta, -8));
  double hi = vl_kernel_viscoelastic(x, 1.0, nudge(beta, 8));
  double e = fabs(hi - lo) / fmax(fabs(hi), 1.0);
  if (e > *worst) *worst = e;
  if (e > 1e-13) fail_msg("jump %.3g across beta=%.17g at x=%.17g", e, beta, x);
}

static void check_jump_x(double x, double beta, double *worst) {
  double lo = vl_kernel_viscoelastic(nudge(x, -8), 1.0, beta);
  double hi = vl_kernel_viscoelastic(nudge(x, 8), 1.0, beta);
  double e = fabs(hi - lo) / fmax(fabs(hi), 1.0);
  if (e > *worst) *worst = e;
  if (e > 1e-13) fail_msg("jump %.3g across x=%.17g at beta=%.17g", e, x, beta);
}

static void test_branch_continuity(void **state) {
  (void)state;
  double worst = 0.0;
  /* closed form (I) <-> series (II) in beta, at many offsets */
  const double xs[] = {0.0, 0.3, 0.5, -0.5, 1.0, -1.0, 3.0, -3.0, 7.5, 8.0, -8.0, 100.0, -4096.0};
  for (size_t i = 0; i < sizeof xs / sizeof xs[0]; i++)
    check_jump_beta(xs[i], VL_KERNEL_BETA_SWITCH, &worst);
  /* power series <-> midpoint series in x (beta above the switch) */
  const double bs[] = {8.5, 10.0, 100.0, 1e4, 1e8, 1e12};
  for (size_t j = 0; j < sizeof bs / sizeof bs[0]; j++) {
    check_jump_x(VL_KERNEL_X_SWITCH, bs[j], &worst);
    check_jump_x(-VL_KERNEL_X_SWITCH, bs[j], &worst);
  }
  /* internal switches of kernel.c (mirrored here; if they move the checks
   * still pass, they just probe smooth points):
   * - in (I), log|a+/a-| + g difference <-> m series when an end |z| = 1/2,
   *   i.e. x = +-(1/2 + beta/2); at x = 0 the ends are at |z| = 1/2 when beta = 1;
   * - midpoint series: leading term by series when |x/beta| < 1/2;
   * - k(x): series for |x| >= 2, log form for 1/2 < |x| < 2, F difference below;
   * - log|a+/a-|: two logs below |x| = 2, atanh above. */
  const double bI[] = {0.1, 1.0, 4.0, 7.9};
  for (size_t j = 0; j < 4; j++) {
    check_jump_x(0.5 + 0.5 * bI[j], bI[j], &worst);
    check_jump_x(-0.5 - 0.5 * bI[j], bI[j], &worst);
  }
  check_jump_beta(0.0, 1.0, &worst);
  check_jump_beta(10.0, 20.0, &worst);
  check_jump_beta(-100.0, 200.0, &worst);
  check_jump_beta(4096.0, 8192.0, &worst);
  const double bk[] = {1e-6, 0.5, 3.0, 20.0, 1e6};
  for (size_t j = 0; j < 5; j++) {
    check_jump_x(2.0, bk[j], &worst);
    check_jump_x(-2.0, bk[j], &worst);
  }
  /* The cell edges x = +-1/2 are a switch too, but there Ke itself has a
   * log-singular slope: over 16 ulps it moves by ~16 ulp * 36 ~ 6e-14 in
   * truth, so they get their own (looser) count. */
  double worst_edge = 0.0;
  for (size_t j = 0; j < 5; j++) {
    check_jump_x(0.5, bk[j], &worst_edge);
    check_jump_x(-0.5, bk[j], &worst_edge);
  }
  /* GSL's own E1/Ei branches at |z| = 1, 4, 10 (z = (x + 1/2)/beta). */
  const double zs[] = {1.0, 4.0, 10.0};
  for (size_t j = 0; j < 3; j++) {
    check_jump_beta(3.0, 3.5 / zs[j], &worst);
    check_jump_beta(-4.0, 3.5 / zs[j], &worst);
  }
  printf("# largest jump across branch switches: %.3g (at the cell edges: %.3g)\n", worst,
         worst_edge);
}

/* ---------- Toeplitz ---------- */

static double direct_total(double d, double delta, const double *A, const double *b, size_t nt) {
  double s = vl_kernel_elastic(d, delta);
  for (size_t k = 0; k < nt; k++)
    s += A[k] * vl_kernel_viscoelastic(d, delta, b[k]);
  return s;
}

/* g(z) = -e^{-z} Ei(z) by the tabulated interpolant (kernel_expint.c) against
 * GSL, which it is built from, away from the interpolation nodes: 2e5 points
 * spread over 0.4 <= |z| <= 80 (both signs, past both ends of the table) and
 * both sides of every piece edge. The interpolation error is ~1e-18 of |g|;
 * GSL's own error reaches 1.4e-15 of |g| near z = 1 (checked against 30-digit
 * values: there the table is the closer of the two, as interpolation smooths
 * GSL's rounding). 2e-15 leaves that room, while a wrong piece, a wrong local
 * variable or a lost coefficient (>= 1e-12 here) fails. */
static void test_expint_table(void **state) {
  (void)state;
  double worst = 0.0, at = 0.0;
  for (int s = -1; s <= 1; s += 2)
    for (int i = 0; i <= 100000; i++) {
      double az = 0.4 * pow(200.0, i / 100000.0);
      double z = s * az, ref = vl_expint_g_gsl(z), e = fabs(vl_expint_g(z) - ref) / fabs(ref);
      if (e > worst) worst = e, at = z;
      if (e > 2e-15) fail_msg("g(%.17g): table %.17g, GSL %.17g", z, vl_expint_g(z), ref);
    }
  for (int e = -1; e <= 6; e++)
    for (int p = 0; p <= 16; p++) {
      double edge = ldexp(1.0 + p / 16.0, e);
      for (int s = -1; s <= 1; s += 2)
        for (int side = -1; side <= 1; side++) { /* below, at, above the edge */
          double z = s * (side == 0 ? edge : nextafter(edge, side * 1e300));
          double ref = vl_expint_g_gsl(z), err = fabs(vl_expint_g(z) - ref) / fabs(ref);
          if (err > worst) worst = err, at = z;
          if (err > 2e-15) fail_msg("g(%.17g) at a piece edge: %.3g off", z, err);
        }
    }
  printf("# g(z) table vs GSL: max relative error %.3g at z = %g\n", worst, at);
}

static void test_toeplitz_matches_direct(void **state) {
  (void)state;
  /* terms span every branch: b = 0, A = 0, b/delta from 1e-12 to 1e12 */
  const double delta = 0.013;
  double A[12], b[12];
  for (int k = 0; k < 12; k++) {
    A[k] = 0.2 + 0.37 * k;
    b[k] = delta * pow(10.0, -12.0 + 24.0 * k / 11.0);
  }
  b[3] = 0.0;
  A[5] = 0.0;
  b[6] = 7.9 * delta; /* just below the beta switch */
  const size_t n = 300, nt = 12;
  vl_toeplitz t;
  vl_error err;
  assert_int_equal(vl_toeplitz_build(&t, n, delta, A, b, nt, &err), VL_OK);
  assert_int_equal(t.n, n);
  double worst = 0.0;
  for (size_t i = 0; i < 2 * n - 1; i++) {
    double d = ((double)i - (double)(n - 1)) * delta;
    double ref = direct_total(d, delta, A, b, nt);
    double e = scaled_err(t.coef[i], ref, delta);
    if (e > worst) worst = e;
    /* 1e-13: same closed form, summed in a different order (sum A ~ 25) */
    if (e > 1e-13) fail_msg("offset %g: toeplitz %.17g direct %.17g", d / delta, t.coef[i], ref);
  }
  /* element access: (i, j) is offset (i - j) delta */
  assert_true(vl_toeplitz_at(&t, 7, 2) == t.coef[5 + n - 1]);
  assert_true(scaled_err(vl_toeplitz_at(&t, 2, 7), direct_total(-5 * delta, delta, A, b, nt),
                         delta) < 1e-13);
  printf("# toeplitz vs direct summation: max error %.3g\n", worst);

  /* refill with the same inputs is bit-identical; with new inputs it equals a
   * fresh build */
  double *copy = malloc((2 * n - 1) * sizeof *copy);
  assert_non_null(copy);
  memcpy(copy, t.coef, (2 * n - 1) * sizeof *copy);
  vl_toeplitz_refill(&t, A, b, nt);
  assert_memory_equal(copy, t.coef, (2 * n - 1) * sizeof *copy);
  for (int k = 0; k < 12; k++)
    b[k] *= 3.3;
  vl_toeplitz_refill(&t, A, b, nt);
  vl_toeplitz t2;
  assert_int_equal(vl_toeplitz_build(&t2, n, delta, A, b, nt, &err), VL_OK);
  assert_memory_equal(t2.coef, t.coef, (2 * n - 1) * sizeof *copy);
  free(copy);
  vl_toeplitz_free(&t);
  vl_toeplitz_free(&t2);
  vl_toeplitz_free(&t2); /* idempotent */

  /* elastic only */
  assert_int_equal(vl_toeplitz_build(&t, 5, 2.0, NULL, NULL, 0, &err), VL_OK);
  for (size_t i = 0; i < 9; i++)
    assert_true(t.coef[i] == vl_kernel_elastic(((double)i - 4.0) * 2.0, 2.0));
  vl_toeplitz_free(&t);
}

static void test_toeplitz_rejects_bad_input(void **state) {
  (void)state;
  vl_toeplitz t;
  vl_error err;
  double A[1] = {1.0}, bneg[1] = {-1.0}, bnan[1] = {NAN}, ok[1] = {1.0}, Ainf[1] = {INFINITY};
  assert_int_equal(vl_toeplitz_build(&t, 0, 1.0, A, ok, 1, &err), VL_EINPUT);
  assert_null(t.coef);
  assert_int_equal(vl_toeplitz_build(&t, 4, 0.0, A, ok, 1, &err), VL_EINPUT);
  assert_null(t.coef);
  assert_int_equal(vl_toeplitz_build(&t, 4, 1.0, A, bneg, 1, &err), VL_EINPUT);
  assert_null(t.coef);
  assert_non_null(strstr(err.msg, "term 1"));
  assert_int_equal(vl_toeplitz_build(&t, 4, 1.0, A, bnan, 1, &err), VL_EINPUT);
  assert_int_equal(vl_toeplitz_build(&t, 4, 1.0, Ainf, ok, 1, &err), VL_EINPUT);
  assert_null(t.coef);
  assert_true(isnan(vl_kernel_viscoelastic(1.0, 1.0, -1.0)));
  static double many_a[VL_KERNEL_MAX_TERMS + 1], many_b[VL_KERNEL_MAX_TERMS + 1];
  assert_int_equal(vl_toeplitz_build(&t, 4, 1.0, many_a, many_b, VL_KERNEL_MAX_TERMS + 1, &err),
                   VL_EINPUT);
  assert_null(t.coef);
  assert_non_null(strstr(err.msg, "Prony terms"));
}

/* 60 Prony terms, n = 2048 (4095 offsets): the rebuild the solver does per
 * speed. Reported, not asserted (shared machine; sanitizer builds). */
/* A dense series (2.5 terms a decade over 24 decades, as a fitted rubber's)
 * on a long grid: every term passes through the three groups of the
 * refill (relaxed, window, frozen: kernel.c) somewhere along the offsets,
 * and each offset is checked against the term-by-term direct sum. */
static void test_toeplitz_dense_series(void **state) {
  (void)state;
  double A[60], b[60];
  for (int k = 0; k < 60; k++) {
    A[k] = 0.1 + 0.01 * k;
    b[k] = pow(10.0, -12.0 + 24.0 * k / 59.0);
  }
  const size_t n = 2048;
  vl_toeplitz t;
  vl_error err;
  struct timespec t0, t1;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  assert_int_equal(vl_toeplitz_build(&t, n, 1.0, A, b, 60, &err), VL_OK);
  clock_gettime(CLOCK_MONOTONIC, &t1);
  double ms = 1e3 * (double)(t1.tv_sec - t0.tv_sec) + 1e-6 * (double)(t1.tv_nsec - t0.tv_nsec);
  double worst = 0.0;
  for (size_t i = 0; i < 2 * n - 1; i++) {
    double d = (double)i - (double)(n - 1);
    double e = scaled_err(t.coef[i], direct_total(d, 1.0, A, b, 60), 1.0);
    if (e > worst) worst = e;
    /* 1e-13 as above: the groups' series truncate at 4e-18 (kernel.c) */
    if (e > 1e-13) fail_msg("offset %g: error %.3g", d, e);
  }
  printf("# toeplitz build, 60 terms x 4095 offsets: %.1f ms, max error %.3g\n", ms, worst);
  vl_toeplitz_free(&t);
}

/* ---------- physics ---------- */

static void test_relaxed_and_glassy_limits(void **state) {
  (void)state;
  const size_t n = 256, nt = 3;
  const double delta = 0.02, A[3] = {2.0, 4.5, 2.5};
  double sum_a = A[0] + A[1] + A[2];
  vl_toeplitz te, t;
  vl_error err;
  assert_int_equal(vl_toeplitz_build(&te, n, delta, NULL, NULL, 0, &err), VL_OK);
  /* b = 0: relaxed response, (1 + sum A) times the elastic matrix */
  double b0[3] = {0.0, 0.0, 0.0};
  assert_int_equal(vl_toeplitz_build(&t, n, delta, A, b0, nt, &err), VL_OK);
  for (size_t i = 0; i < 2 * n - 1; i++)
    assert_true(scaled_err(t.coef[i], (1.0 + sum_a) * te.coef[i], delta) < 1e-15 * (1.0 + sum_a));
  /* b = 1e-12 delta: still relaxed to ~1e-12 (the first-order change) */
  double bs[3] = {1e-12 * delta, 3e-13 * delta, 1e-12 * delta};
  vl_toeplitz_refill(&t, A, bs, nt);
  for (size_t i = 0; i < 2 * n - 1; i++)
    assert_true(fabs(t.coef[i] - (1.0 + sum_a) * te.coef[i]) < 1e-10 * delta);
  /* b = 1e12 delta: glassy, elastic + a constant sum A delta (log b - gamma)
   * up to (|d|/b) log b ~ 1e-7 delta */
  double bl[3] = {1e12 * delta, 1e12 * delta, 1e12 * delta};
  vl_toeplitz_refill(&t, A, bl, nt);
  double c = sum_a * delta * (log(1e12 * delta) - EULER_GAMMA);
  for (size_t i = 0; i < 2 * n - 1; i++)
    assert_true(fabs(t.coef[i] - te.coef[i] - c) < 1e-7 * delta);
  vl_toeplitz_free(&t);
  vl_toeplitz_free(&te);
}

/* Hertz: p = p0 sqrt(1 - x^2/a^2) under a cylinder of radius R with
 * p0/(Er a) = 1/(2R) gives, inside |x| < a,
 *   w(x) = -(2/(pi Er)) \int p(x') log|x - x'| dx' = const - x^2/(2R),
 * i.e. f + w = x^2/(2R) + w is constant: the contact is flat. Returns the
 * half range of x^2/(2R) + w over the nodes with |x| < frac a, in units of
 * a^2/(2R). The pressure is sampled at the nodes (cell_avg = 0) or is the
 * exact cell average (cell_avg = 1). */
static double hertz_flatness(size_t n, int cell_avg, double frac) {
  const double a = 1.0, er = 1.0, p0 = 1.0, R = a * er / (2.0 * p0), L = 1.5 * a;
  double delta = 2.0 * L / (double)n;
  vl_toeplitz t;
  vl_error err;
  assert_int_equal(vl_toeplitz_build(&t, n, delta, NULL, NULL, 0, &err), VL_OK);
  double *x = malloc(n * sizeof *x), *p = malloc(n * sizeof *p);
  assert_non_null(x);
  assert_non_null(p);
  for (size_t i = 0; i < n; i++) {
    x[i] = -L + ((double)i + 0.5) * delta;
    if (cell_avg) {
      /* \int sqrt(1 - u^2) du = (u sqrt(1 - u^2) + asin u)/2 over the cell
       * clipped to the contact */
      double l = fmax(-1.0, fmin(1.0, (x[i] - 0.5 * delta) / a));
      double h = fmax(-1.0, fmin(1.0, (x[i] + 0.5 * delta) / a));
      double prim_h = h * sqrt(1.0 - h * h) + asin(h), prim_l = l * sqrt(1.0 - l * l) + asin(l);
      p[i] = p0 * a * 0.5 * (prim_h - prim_l) / delta;
    } else {
      p[i] = fabs(x[i]) < a ? p0 * sqrt(1.0 - x[i] * x[i] / (a * a)) : 0.0;
    }
  }
  double lo = INFINITY, hi = -INFINITY;
  for (size_t i = 0; i < n; i++) {
    if (fabs(x[i]) >= frac * a) continue;
    double w = 0.0;
    for (size_t j = 0; j < n; j++)
      w += p[j] * vl_toeplitz_at(&t, i, j);
    w *= -2.0 / (M_PI * er);
    double r = x[i] * x[i] / (2.0 * R) + w;
    lo = fmin(lo, r);
    hi = fmax(hi, r);
  }
  free(x);
  free(p);
  vl_toeplitz_free(&t);
  return 0.5 * (hi - lo) / (a * a / (2.0 * R));
}

static void test_hertz_parabolic_displacement(void **state) {
  (void)state;
  double s256 = hertz_flatness(256, 0, 1.0), s1024 = hertz_flatness(1024, 0, 1.0);
  double si256 = hertz_flatness(256, 0, 0.9), si1024 = hertz_flatness(1024, 0, 0.9);
  double c256 = hertz_flatness(256, 1, 0.9), c1024 = hertz_flatness(1024, 1, 0.9);
  double o_s = log(s256 / s1024) / log(4.0), o_si = log(si256 / si1024) / log(4.0);
  double o_c = log(c256 / c1024) / log(4.0);
  printf("# Hertz, deviation of x^2/2R + w from a constant (units a^2/2R):\n"
         "#   sampled p, |x| < a:          N=256 %.3g  N=1024 %.3g  order %.2f\n"
         "#   sampled p, |x| < 0.9a:       N=256 %.3g  N=1024 %.3g  order %.2f\n"
         "#   cell-averaged p, |x| < 0.9a: N=256 %.3g  N=1024 %.3g  order %.2f\n",
         s256, s1024, o_s, si256, si1024, o_si, c256, c1024, o_c);
  /* The kernel is exact for piecewise-constant pressure, so what remains is
   * the pressure's discretisation. Sampling misses ~delta^{3/2} of load in
   * the cells cut by the sqrt edges: order 3/2 in the interior (a little
   * less on the edge nodes). With exact cell averages the load is right and
   * the interior error is second order or better. */
  assert_true(s256 < 1e-3);
  assert_true(o_s > 1.2);
  assert_true(o_si > 1.4);
  assert_true(o_c > 2.0);
  assert_true(c1024 < 1e-6);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_elastic_vs_quadrature),
      cmocka_unit_test(test_viscoelastic_vs_quadrature),
      cmocka_unit_test(test_small_b_limit),
      cmocka_unit_test(test_large_b_limit),
      cmocka_unit_test(test_memory_looks_upstream),
      cmocka_unit_test(test_branch_continuity),
      cmocka_unit_test(test_expint_table),
      cmocka_unit_test(test_toeplitz_matches_direct),
      cmocka_unit_test(test_toeplitz_rejects_bad_input),
      cmocka_unit_test(test_toeplitz_dense_series),
      cmocka_unit_test(test_relaxed_and_glassy_limits),
      cmocka_unit_test(test_hertz_parabolic_displacement),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
