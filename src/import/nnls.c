/* Non-negative least squares by Lawson & Hanson's active-set method (nnls.h).
 *
 * Notation: P is the passive set (variables free to be positive), Z the
 * active set (held at zero). Each outer step moves the variable of Z with
 * the largest gradient w_j = a_j^T (b - A x) into P; the inner loop solves
 * the unconstrained problem on P and, while that solution z has a
 * non-positive entry, moves x towards z as far as feasibility allows and
 * returns the variables that hit zero to Z. */
#include "nnls.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>

#include "gsl_errors.h"

/* A newly added column whose component orthogonal to the columns already in
 * P is below this (columns have unit norm) is numerically dependent on them:
 * adding it would only add rounding noise, so it is rejected for this step. */
#define DEPENDENT_TOL 1e-12

/* Solves min ||A_P z - b|| for the ordered index list p[0..np) (np <= m) by
 * QR in the workspace qr (m x n, first np columns used) and tau (>= np).
 * On return z[k] is the coefficient of column p[k]; *r_last is |R(np-1,np-1)|,
 * the norm of the last column's part orthogonal to the others. */
static vl_status solve_subset(const gsl_matrix *as, const gsl_vector *b, const size_t *p, size_t np,
                              gsl_matrix *qr, gsl_vector *tau, gsl_vector *z, double *r_last) {
  size_t m = as->size1;
  gsl_matrix_view sub = gsl_matrix_submatrix(qr, 0, 0, m, np);
  for (size_t k = 0; k < np; k++) {
    gsl_vector_const_view src = gsl_matrix_const_column(as, p[k]);
    gsl_vector_view dst = gsl_matrix_column(&sub.matrix, k);
    gsl_vector_memcpy(&dst.vector, &src.vector);
  }
  gsl_vector_view t = gsl_vector_subvector(tau, 0, np);
  gsl_vector_view zz = gsl_vector_subvector(z, 0, np);
  if (gsl_linalg_QR_decomp(&sub.matrix, &t.vector) != GSL_SUCCESS) return VL_EINTERNAL;
  *r_last = fabs(gsl_matrix_get(&sub.matrix, np - 1, np - 1));
  if (!(*r_last > DEPENDENT_TOL)) return VL_OK; /* caller rejects; z is not used */
  gsl_vector *res = gsl_vector_alloc(m);
  if (!res) return VL_ENOMEM;
  int rc = gsl_linalg_QR_lssolve(&sub.matrix, &t.vector, b, &zz.vector, res);
  gsl_vector_free(res);
  return rc == GSL_SUCCESS ? VL_OK : VL_EINTERNAL;
}

/* w = As^T (b - As x); returns ||b - As x||. */
static double gradient(const gsl_matrix *as, const gsl_vector *b, const gsl_vector *x,
                       gsl_vector *r, gsl_vector *w) {
  gsl_vector_memcpy(r, b);
  gsl_blas_dgemv(CblasNoTrans, -1.0, as, x, 1.0, r);
  gsl_blas_dgemv(CblasTrans, 1.0, as, r, 0.0, w);
  return gsl_blas_dnrm2(r);
}

vl_status vl_nnls_solve(size_t m, size_t n, const double *a, const double *b, double *x,
                        double *residual_norm, vl_error *err) {
  vl_status st = VL_OK;
  gsl_matrix *as = NULL, *qr = NULL, *red_a = NULL;
  gsl_vector *bv = NULL, *xs = NULL, *w = NULL, *r = NULL, *z = NULL, *tau = NULL, *red_b = NULL;
  double *scale = NULL;
  size_t *p = NULL;
  unsigned char *in_p = NULL, *rejected = NULL;

  if (x && n) memset(x, 0, n * sizeof *x);
  if (m == 0 || n == 0 || !a || !b || !x) {
    vl_error_set(err, "nnls: empty problem (m = %zu, n = %zu)", m, n);
    return VL_EINPUT;
  }
  for (size_t i = 0; i < m; i++) {
    if (!isfinite(b[i])) {
      vl_error_set(err, "nnls: right-hand side entry %zu is not finite", i);
      return VL_EINPUT;
    }
    for (size_t j = 0; j < n; j++) {
      if (!isfinite(a[i * n + j])) {
        vl_error_set(err, "nnls: matrix entry (%zu, %zu) is not finite", i, j);
        return VL_EINPUT;
      }
    }
  }
  vl_gsl_errors_off();
  as = gsl_matrix_alloc(m, n);
  qr = gsl_matrix_alloc(m, n);
  bv = gsl_vector_alloc(m);
  r = gsl_vector_alloc(m);
  xs = gsl_vector_calloc(n);
  w = gsl_vector_alloc(n);
  z = gsl_vector_alloc(n);
  tau = gsl_vector_alloc(n);
  scale = malloc(n * sizeof *scale);
  p = malloc(n * sizeof *p);
  in_p = calloc(n, 1);
  rejected = calloc(n, 1);
  if (!as || !qr || !bv || !r || !xs || !w || !z || !tau || !scale || !p || !in_p || !rejected) {
    vl_error_set(err, "nnls: out of memory (%zu x %zu)", m, n);
    st = VL_ENOMEM;
    goto cleanup;
  }

  /* Unit-norm columns: the Prony columns differ by orders of magnitude in
   * some rows, and the tolerances below are then relative. */
  for (size_t j = 0; j < n; j++) {
    double big = 0.0, ss = 0.0;
    for (size_t i = 0; i < m; i++)
      big = fmax(big, fabs(a[i * n + j]));
    for (size_t i = 0; big > 0.0 && i < m; i++) /* scaled: no overflow for huge entries */
      ss += (a[i * n + j] / big) * (a[i * n + j] / big);
    double s = big * sqrt(ss);
    scale[j] = s;
    for (size_t i = 0; i < m; i++)
      gsl_matrix_set(as, i, j, s > 0.0 ? a[i * n + j] / s : 0.0);
    if (!(s > 0.0)) rejected[j] = 2; /* permanently: x_j = 0 */
  }
  for (size_t i = 0; i < m; i++)
    gsl_vector_set(bv, i, b[i]);
  double bnorm = gsl_blas_dnrm2(bv);

  /* A tall problem is first reduced by one QR, A = Q [R; 0]: since Q is
   * orthogonal, ||A x - b||^2 = ||R x - c||^2 + ||d||^2 with Q^T b = [c; d],
   * so the active-set iteration below runs on the n x n system (R, c) and
   * each of its sub-problems costs O(n p^2) instead of O(m p^2). */
  double rest = 0.0;
  size_t m_full = m;
  if (m > n) {
    if (gsl_linalg_QR_decomp(as, tau) != GSL_SUCCESS ||
        gsl_linalg_QR_QTvec(as, tau, bv) != GSL_SUCCESS) {
      st = VL_EINTERNAL;
      goto gsl_fail;
    }
    gsl_vector_view tail = gsl_vector_subvector(bv, n, m - n);
    rest = gsl_blas_dnrm2(&tail.vector);
    for (size_t i = 0; i < n; i++)
      for (size_t j = 0; j < i; j++)
        gsl_matrix_set(as, i, j, 0.0);
    gsl_matrix_view top = gsl_matrix_submatrix(as, 0, 0, n, n);
    gsl_vector_view ctop = gsl_vector_subvector(bv, 0, n);
    red_a = gsl_matrix_alloc(n, n);
    red_b = gsl_vector_alloc(n);
    if (!red_a || !red_b) {
      vl_error_set(err, "nnls: out of memory (%zu x %zu)", m, n);
      st = VL_ENOMEM;
      goto cleanup;
    }
    gsl_matrix_memcpy(red_a, &top.matrix);
    gsl_vector_memcpy(red_b, &ctop.vector);
    gsl_matrix_free(as);
    gsl_vector_free(bv);
    as = red_a;
    bv = red_b;
    red_a = NULL;
    red_b = NULL;
    m = n;
    gsl_matrix_free(qr);
    gsl_vector_free(r);
    qr = gsl_matrix_alloc(m, n);
    r = gsl_vector_alloc(m);
    if (!qr || !r) {
      vl_error_set(err, "nnls: out of memory (%zu x %zu)", m, n);
      st = VL_ENOMEM;
      goto cleanup;
    }
  }
  double tol = 10.0 * DBL_EPSILON * (double)(m_full > n ? m_full : n) * bnorm;
  size_t np = 0;
  size_t max_outer = 3 * n + 30, outer = 0;

  double rnorm = gradient(as, bv, xs, r, w);
  for (;;) {
    /* the free variable with the steepest descent */
    size_t best = n;
    double wmax = tol;
    for (size_t j = 0; j < n; j++) {
      if (in_p[j] || rejected[j]) continue;
      if (gsl_vector_get(w, j) > wmax) wmax = gsl_vector_get(w, j), best = j;
    }
    if (best == n || np == m) break; /* KKT conditions hold (or b is in range) */
    if (++outer > max_outer) {
      vl_error_set(err, "nnls: no convergence after %zu steps (%zu x %zu, ill-conditioned?)",
                   max_outer, m, n);
      st = VL_ENOCONV;
      goto cleanup;
    }
    p[np++] = best;
    in_p[best] = 1;
    double r_last = 0.0;
    if ((st = solve_subset(as, bv, p, np, qr, tau, z, &r_last)) != VL_OK) goto gsl_fail;
    /* Lawson & Hanson's safeguard: a column dependent on P, or one whose
     * own coefficient would come out non-positive, cannot reduce the
     * residual; skip it until another variable has entered. */
    if (!(r_last > DEPENDENT_TOL) || !(gsl_vector_get(z, np - 1) > 0.0)) {
      in_p[best] = 0;
      np--;
      rejected[best] = 1;
      continue;
    }
    for (size_t j = 0; j < n; j++)
      if (rejected[j] == 1) rejected[j] = 0;

    /* inner loop: keep x feasible */
    for (size_t inner = 0;; inner++) {
      int all_positive = 1;
      for (size_t k = 0; k < np; k++)
        if (!(gsl_vector_get(z, k) > 0.0)) all_positive = 0;
      if (all_positive) {
        for (size_t k = 0; k < np; k++)
          gsl_vector_set(xs, p[k], gsl_vector_get(z, k));
        break;
      }
      if (inner > n) {
        vl_error_set(err, "nnls: the feasibility loop did not terminate (%zu x %zu)", m, n);
        st = VL_ENOCONV;
        goto cleanup;
      }
      double alpha = 1.0;
      for (size_t k = 0; k < np; k++) {
        double zk = gsl_vector_get(z, k), xk = gsl_vector_get(xs, p[k]);
        if (zk <= 0.0) {
          double t = xk / (xk - zk);
          if (t < alpha) alpha = t;
        }
      }
      /* step towards z; variables reaching zero leave P */
      size_t keep = 0;
      for (size_t k = 0; k < np; k++) {
        double xk = gsl_vector_get(xs, p[k]);
        double xn = xk + alpha * (gsl_vector_get(z, k) - xk);
        if (xn <= DBL_EPSILON * fabs(xk) || xn <= 0.0) {
          gsl_vector_set(xs, p[k], 0.0);
          in_p[p[k]] = 0;
        } else {
          gsl_vector_set(xs, p[k], xn);
          p[keep++] = p[k];
        }
      }
      if (keep == np) { /* rounding kept every one: drop the limiting one */
        size_t kmin = 0;
        double vmin = INFINITY;
        for (size_t k = 0; k < np; k++) {
          double zk = gsl_vector_get(z, k);
          if (zk <= 0.0 && gsl_vector_get(xs, p[k]) < vmin)
            vmin = gsl_vector_get(xs, p[k]), kmin = k;
        }
        gsl_vector_set(xs, p[kmin], 0.0);
        in_p[p[kmin]] = 0;
        for (size_t k = kmin; k + 1 < np; k++)
          p[k] = p[k + 1];
        keep = np - 1;
      }
      np = keep;
      if (np == 0) break;
      if ((st = solve_subset(as, bv, p, np, qr, tau, z, &r_last)) != VL_OK) goto gsl_fail;
    }
    rnorm = gradient(as, bv, xs, r, w);
  }

  for (size_t j = 0; j < n; j++)
    x[j] = scale[j] > 0.0 ? gsl_vector_get(xs, j) / scale[j] : 0.0;
  if (residual_norm) *residual_norm = hypot(rnorm, rest);
  goto cleanup;

gsl_fail:
  if (st == VL_ENOMEM)
    vl_error_set(err, "nnls: out of memory");
  else
    vl_error_set(err, "nnls: QR factorisation failed (%zu x %zu)", m, n);

cleanup:
  if (st != VL_OK) memset(x, 0, n * sizeof *x);
  gsl_matrix_free(as);
  gsl_matrix_free(qr);
  gsl_matrix_free(red_a);
  gsl_vector_free(red_b);
  gsl_vector_free(bv);
  gsl_vector_free(r);
  gsl_vector_free(xs);
  gsl_vector_free(w);
  gsl_vector_free(z);
  gsl_vector_free(tau);
  free(scale);
  free(p);
  free(in_p);
  free(rejected);
  return st;
}
