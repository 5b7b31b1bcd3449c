/* Non-negative least squares (nnls.h) against problems with known
 * solutions, a published example, the optimality (KKT) conditions, and an
 * independent brute force over every active set. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "nnls.h"

/* ---- an independent reference: least squares on a column subset by the
 * normal equations and Gauss-Jordan elimination (no GSL, no QR) --------- */

/* Solves min ||A_S z - b|| for the columns in mask (bit j = column j);
 * returns 0 if the normal matrix is singular. z is full length (zeros off
 * the subset). */
static int subset_ls(size_t m, size_t n, const double *a, const double *b, unsigned mask,
                     double *z) {
  size_t idx[16], p = 0;
  for (size_t j = 0; j < n; j++)
    if (mask & (1u << j)) idx[p++] = j;
  double g[16][17];
  for (size_t r = 0; r < p; r++) {
    for (size_t c = 0; c < p; c++) {
      double s = 0.0;
      for (size_t i = 0; i < m; i++)
        s += a[i * n + idx[r]] * a[i * n + idx[c]];
      g[r][c] = s;
    }
    double s = 0.0;
    for (size_t i = 0; i < m; i++)
      s += a[i * n + idx[r]] * b[i];
    g[r][p] = s;
  }
  for (size_t c = 0; c < p; c++) {
    size_t piv = c;
    for (size_t r = c + 1; r < p; r++)
      if (fabs(g[r][c]) > fabs(g[piv][c])) piv = r;
    if (fabs(g[piv][c]) < 1e-12) return 0;
    for (size_t k = 0; k <= p; k++) {
      double t = g[c][k];
      g[c][k] = g[piv][k];
      g[piv][k] = t;
    }
    for (size_t r = 0; r < p; r++) {
      if (r == c) continue;
      double f = g[r][c] / g[c][c];
      for (size_t k = c; k <= p; k++)
        g[r][k] -= f * g[c][k];
    }
  }
  memset(z, 0, n * sizeof *z);
  for (size_t r = 0; r < p; r++)
    z[idx[r]] = g[r][p] / g[r][r];
  return 1;
}

static double resid(size_t m, size_t n, const double *a, const double *b, const double *x) {
  double s = 0.0;
  for (size_t i = 0; i < m; i++) {
    double r = -b[i];
    for (size_t j = 0; j < n; j++)
      r += a[i * n + j] * x[j];
    s += r * r;
  }
  return sqrt(s);
}

/* The NNLS optimum is the least-squares solution on its support, with all
 * entries there positive; so the best residual over every subset whose LS
 * solution is non-negative is the optimum (2^n subsets, n <= 10). */
static double brute_force(size_t m, size_t n, const double *a, const double *b, double *xbest) {
  double best = resid(m, n, a, b, (double[16]){0});
  memset(xbest, 0, n * sizeof *xbest);
  double z[16];
  for (unsigned mask = 1; mask < (1u << n); mask++) {
    if (!subset_ls(m, n, a, b, mask, z)) continue;
    int feasible = 1;
    for (size_t j = 0; j < n; j++)
      if (z[j] < 0.0) feasible = 0;
    if (!feasible) continue;
    double r = resid(m, n, a, b, z);
    if (r < best) best = r, memcpy(xbest, z, n * sizeof *z);
  }
  return best;
}

/* KKT: w = A^T (b - A x); w_j <= tol where x_j = 0, |w_j| <= tol where
 * x_j > 0, x >= 0. */
static void assert_kkt(size_t m, size_t n, const double *a, const double *b, const double *x,
                       double tol) {
  for (size_t j = 0; j < n; j++) {
    if (!(x[j] >= 0.0)) fail_msg("x[%zu] = %g < 0", j, x[j]);
    double w = 0.0;
    for (size_t i = 0; i < m; i++) {
      double r = b[i];
      for (size_t k = 0; k < n; k++)
        r -= a[i * n + k] * x[k];
      w += a[i * n + j] * r;
    }
    if (x[j] > 0.0 ? fabs(w) > tol : w > tol)
      fail_msg("KKT violated at %zu: x = %g, w = %g (tol %g)", j, x[j], w, tol);
  }
}

static uint64_t rng_state = 88172645463325252ULL;
static double uniform(void) { /* xorshift64*: reproducible */
  rng_state ^= rng_state >> 12, rng_state ^= rng_state << 25, rng_state ^= rng_state >> 27;
  return (double)((rng_state * 2685821657736338717ULL) >> 11) / 9007199254740992.0;
}

/* ---- tests ------------------------------------------------------------ */

static void test_identity(void **state) {
  (void)state;
  const double a[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, b[3] = {1, -2, 3};
  double x[3], r;
  vl_error err;
  assert_int_equal(vl_nnls_solve(3, 3, a, b, x, &r, &err), VL_OK);
  /* exact: the negative component is clipped, residual = 2 */
  assert_true(x[0] == 1.0 && x[1] == 0.0 && x[2] == 3.0);
  assert_true(fabs(r - 2.0) < 1e-15);
}

/* The example of MATLAB's lsqnonneg documentation (also Lawson & Hanson's
 * style of test): C = [0.0372 0.2869; 0.6861 0.7071; 0.6233 0.6245;
 * 0.6344 0.6170], d = [0.8587; 0.1781; 0.0747; 0.8405] gives x = [0; 0.6929]
 * (printed to 4 digits; tolerance 5e-5 = half a unit of the last digit),
 * while the unconstrained solution has a negative first entry. */
static void test_published_example(void **state) {
  (void)state;
  const double c[8] = {0.0372, 0.2869, 0.6861, 0.7071, 0.6233, 0.6245, 0.6344, 0.6170};
  const double d[4] = {0.8587, 0.1781, 0.0747, 0.8405};
  double x[2], z[2];
  vl_error err;
  assert_int_equal(vl_nnls_solve(4, 2, c, d, x, NULL, &err), VL_OK);
  assert_true(x[0] == 0.0);
  assert_true(fabs(x[1] - 0.6929) < 5e-5);
  assert_true(subset_ls(4, 2, c, d, 3u, z) && z[0] < 0.0); /* the constraint is active */
  assert_kkt(4, 2, c, d, x, 1e-12);
}

/* When the unconstrained solution is positive, NNLS returns it. */
static void test_interior_solution(void **state) {
  (void)state;
  const size_t m = 6, n = 3;
  double a[18], b[6], x[3], z[3];
  const double truth[3] = {0.5, 2.0, 7.0};
  for (size_t i = 0; i < m; i++) {
    for (size_t j = 0; j < n; j++)
      a[i * n + j] = 1.0 / (1.0 + (double)i + 2.0 * (double)j); /* Hilbert-like */
    b[i] = 0.0;
    for (size_t j = 0; j < n; j++)
      b[i] += a[i * n + j] * truth[j];
  }
  vl_error err;
  double r;
  assert_int_equal(vl_nnls_solve(m, n, a, b, x, &r, &err), VL_OK);
  assert_true(subset_ls(m, n, a, b, 7u, z));
  /* Hilbert-like conditioning (~1e4): 1e-9 relative to the solution */
  for (size_t j = 0; j < n; j++)
    if (fabs(x[j] - truth[j]) > 1e-9 * truth[j]) fail_msg("x[%zu] = %.17g", j, x[j]);
  assert_true(r < 1e-12);
}

/* Random problems, tall and wide, against the brute force: the residual
 * must equal the best over all feasible active sets (to 1e-10 of ||b||, a
 * few hundred roundings of O(1) numbers), and for full column rank (m >= n,
 * random entries) the minimiser is unique, so x must match too (1e-8:
 * the normal equations square the condition number). */
static void test_against_brute_force(void **state) {
  (void)state;
  double a[12 * 9], b[12], x[9], xb[9];
  vl_error err;
  int active_seen = 0;
  for (int trial = 0; trial < 400; trial++) {
    size_t m = 2 + (size_t)(uniform() * 11.0), n = 1 + (size_t)(uniform() * 8.0);
    for (size_t i = 0; i < m * n; i++)
      a[i] = 2.0 * uniform() - 1.0;
    for (size_t i = 0; i < m; i++)
      b[i] = 2.0 * uniform() - 1.0;
    double r;
    assert_int_equal(vl_nnls_solve(m, n, a, b, x, &r, &err), VL_OK);
    double best = brute_force(m, n, a, b, xb);
    double bn = resid(m, n, a, b, (double[9]){0});
    if (fabs(r - best) > 1e-10 * bn || fabs(resid(m, n, a, b, x) - r) > 1e-10 * bn)
      fail_msg("trial %d (%zu x %zu): residual %.17g, brute force %.17g", trial, m, n, r, best);
    if (m >= n) {
      for (size_t j = 0; j < n; j++)
        if (fabs(x[j] - xb[j]) > 1e-8 * (1.0 + fabs(xb[j])))
          fail_msg("trial %d: x[%zu] = %.17g, brute force %.17g", trial, j, x[j], xb[j]);
    }
    for (size_t j = 0; j < n; j++)
      active_seen += x[j] == 0.0;
    assert_kkt(m, n, a, b, x, 1e-10 * (1.0 + bn));
  }
  assert_true(active_seen > 100); /* the constraints were really exercised */
}

/* Degenerate input: a zero column, two equal columns, b = 0, b in the cone
 * of more columns than rows (residual 0), and a column scaled by 1e8
 * (scale invariance: x_j scales by 1e-8). */
static void test_degenerate(void **state) {
  (void)state;
  vl_error err;
  double x[4], r;
  const double a1[6] = {1, 0, 2, 0, 3, 0}; /* 3 x 2, column 1 zero */
  const double b1[3] = {1, 2, 3};
  assert_int_equal(vl_nnls_solve(3, 2, a1, b1, x, &r, &err), VL_OK);
  assert_true(x[1] == 0.0);
  assert_true(fabs(x[0] - 1.0) < 1e-14 && r < 1e-14);
  assert_kkt(3, 2, a1, b1, x, 1e-12);

  const double a2[6] = {1, 1, 2, 2, 3, 3}; /* equal columns */
  const double b2[3] = {2, 4, 6};
  assert_int_equal(vl_nnls_solve(3, 2, a2, b2, x, &r, &err), VL_OK);
  assert_true(fabs(x[0] + x[1] - 2.0) < 1e-12 && x[0] >= 0.0 && x[1] >= 0.0 && r < 1e-12);

  const double b0[3] = {0, 0, 0};
  assert_int_equal(vl_nnls_solve(3, 2, a2, b0, x, &r, &err), VL_OK);
  assert_true(x[0] == 0.0 && x[1] == 0.0 && r == 0.0);

  const double a3[8] = {1, 0, 1, 2, 0, 1, 1, 1}; /* 2 x 4 */
  const double b3[2] = {3, 2};
  assert_int_equal(vl_nnls_solve(2, 4, a3, b3, x, &r, &err), VL_OK);
  assert_true(r < 1e-12);
  assert_kkt(2, 4, a3, b3, x, 1e-12);

  double a4[12], b4[4], x4[3], y4[3];
  for (size_t i = 0; i < 12; i++)
    a4[i] = 2.0 * uniform() - 1.0;
  for (size_t i = 0; i < 4; i++)
    b4[i] = 2.0 * uniform() - 1.0;
  assert_int_equal(vl_nnls_solve(4, 3, a4, b4, x4, NULL, &err), VL_OK);
  for (size_t i = 0; i < 4; i++)
    a4[i * 3 + 1] *= 1e8;
  assert_int_equal(vl_nnls_solve(4, 3, a4, b4, y4, NULL, &err), VL_OK);
  assert_true(fabs(y4[0] - x4[0]) <= 1e-12 * (1.0 + x4[0]));
  assert_true(fabs(y4[1] * 1e8 - x4[1]) <= 1e-12 * (1.0 + x4[1]));
}

/* A Prony-like problem (Debye columns, 2 per decade over 12 decades, rows
 * weighted to unit magnitude): strongly collinear columns. KKT must hold and
 * the residual be no worse than the brute force on the 10 most used columns
 * could say; here just KKT and a data fit to rounding for data made from
 * the columns themselves. */
static void test_prony_like(void **state) {
  (void)state;
  enum { NW = 60, NT = 25 };
  static double a[2 * NW * NT], b[2 * NW], x[NT];
  const double c_true[NT] = {[3] = 1.0, [9] = 0.3, [10] = 2.0, [17] = 0.05, [24] = 1.0};
  for (int k = 0; k < NW; k++) {
    double w = pow(10.0, -1.0 + 12.0 * k / (NW - 1));
    double j1 = 0.0, j2 = 0.0;
    for (int i = 0; i < NT; i++) {
      double tau = pow(10.0, -11.0 + 0.5 * i), wt = w * tau, d = 1.0 / (1.0 + wt * wt);
      a[(2 * k) * NT + i] = d;
      a[(2 * k + 1) * NT + i] = wt * d;
      j1 += c_true[i] * d;
      j2 += c_true[i] * wt * d;
    }
    for (int i = 0; i < NT; i++) { /* relative weights: unit-magnitude rows */
      a[(2 * k) * NT + i] /= j1;
      a[(2 * k + 1) * NT + i] /= j2;
    }
    b[2 * k] = 1.0;
    b[2 * k + 1] = 1.0;
  }
  vl_error err;
  double r;
  assert_int_equal(vl_nnls_solve(2 * NW, NT, a, b, x, &r, &err), VL_OK);
  assert_kkt(2 * NW, NT, a, b, x, 1e-9);
  /* the generating coefficients are feasible with residual 0 */
  if (!(r < 1e-8)) fail_msg("residual %g for consistent data", r);
}

static void test_bad_input(void **state) {
  (void)state;
  vl_error err;
  double a[4] = {1, 2, 3, NAN}, b[2] = {1, 2}, x[2] = {7, 7};
  assert_int_equal(vl_nnls_solve(2, 2, a, b, x, NULL, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "not finite"));
  assert_true(x[0] == 0.0 && x[1] == 0.0);
  a[3] = 4.0;
  b[1] = INFINITY;
  assert_int_equal(vl_nnls_solve(2, 2, a, b, x, NULL, &err), VL_EINPUT);
  assert_int_equal(vl_nnls_solve(0, 2, a, b, x, NULL, &err), VL_EINPUT);
  assert_int_equal(vl_nnls_solve(2, 0, a, b, x, NULL, &err), VL_EINPUT);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_identity),          cmocka_unit_test(test_published_example),
      cmocka_unit_test(test_interior_solution), cmocka_unit_test(test_against_brute_force),
      cmocka_unit_test(test_degenerate),        cmocka_unit_test(test_prony_like),
      cmocka_unit_test(test_bad_input),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
