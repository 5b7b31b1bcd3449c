/* Non-negative least squares by Lawson & Hanson's active-set method (nnls.h).
 *
 * Notation: P is the passive set (variables free to be positive), Z the
 * active set (held at zero). Each outer step moves the variable of Z with
 * the largest gradient w_j = a_j^T (b - A x) into P; the inner loop solves
 * the unconstrained problem on P and, while that solution z has a
 * non-positive entry, moves x towards z as far as feasibility allows and
 * returns the variables that hit zero to Z. */
#include "nnls.h"

#include "gsl_errors.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>

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

/* The state of one solve. Columns are scaled to unit norm (as = A / scale);
 * after reduce_tall, as and bv are the n x n system (R, c) and m == n. */
typedef struct {
  size_t m, n;
  gsl_matrix *as, *qr; /* scaled matrix; QR workspace of the sub-problems */
  gsl_vector *bv, *r;  /* right-hand side; residual b - As x */
  gsl_vector *xs, *w;  /* iterate in scaled variables; gradient As^T r */
  gsl_vector *z, *tau; /* solution of the sub-problem on P; its QR factors */
  double *scale;       /* column norms of A: x_j = xs_j / scale_j */
  size_t *p, np;       /* the passive set P, in order of entry */
  unsigned char *in_p; /* membership of P */
  /* 1: skipped until another variable has entered; 2: zero column, x_j = 0 */
  unsigned char *rejected;
} nnls_work;

/* Allocates every array of ws for an m x n problem; 0 if one failed (the
 * others are freed by work_free). */
static int work_alloc(nnls_work *ws, size_t m, size_t n) {
  ws->m = m;
  ws->n = n;
  ws->as = gsl_matrix_alloc(m, n);
  ws->qr = gsl_matrix_alloc(m, n);
  ws->bv = gsl_vector_alloc(m);
  ws->r = gsl_vector_alloc(m);
  ws->xs = gsl_vector_calloc(n);
  ws->w = gsl_vector_alloc(n);
  ws->z = gsl_vector_alloc(n);
  ws->tau = gsl_vector_alloc(n);
  ws->scale = malloc(n * sizeof *ws->scale);
  ws->p = malloc(n * sizeof *ws->p);
  ws->in_p = calloc(n, 1);
  ws->rejected = calloc(n, 1);
  return ws->as && ws->qr && ws->bv && ws->r && ws->xs && ws->w && ws->z && ws->tau && ws->scale &&
         ws->p && ws->in_p && ws->rejected;
}

static void work_free(nnls_work *ws) {
  gsl_matrix_free(ws->as);
  gsl_matrix_free(ws->qr);
  gsl_vector_free(ws->bv);
  gsl_vector_free(ws->r);
  gsl_vector_free(ws->xs);
  gsl_vector_free(ws->w);
  gsl_vector_free(ws->z);
  gsl_vector_free(ws->tau);
  free(ws->scale);
  free(ws->p);
  free(ws->in_p);
  free(ws->rejected);
}

/* The message of a failed QR step (solve_subset or the reduction). */
static vl_status qr_failure(vl_status st, const nnls_work *ws, vl_error *err) {
  if (st == VL_ENOMEM)
    vl_error_set(err, "nnls: out of memory");
  else
    vl_error_set(err, "nnls: QR factorisation failed (%zu x %zu)", ws->m, ws->n);
  return st;
}

/* VL_EINPUT for an empty problem or a non-finite entry. */
static vl_status check_input(size_t m, size_t n, const double *a, const double *b, const double *x,
                             vl_error *err) {
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
  return VL_OK;
}

/* Fills as with the columns of a scaled to unit norm (the Prony columns
 * differ by orders of magnitude in some rows, and the tolerances are then
 * relative) and bv with b; returns ||b||. A zero column is rejected for
 * good. */
static double scale_columns(nnls_work *ws, const double *a, const double *b) {
  size_t m = ws->m, n = ws->n;
  for (size_t j = 0; j < n; j++) {
    double big = 0.0, ss = 0.0;
    for (size_t i = 0; i < m; i++)
      big = fmax(big, fabs(a[i * n + j]));
    for (size_t i = 0; big > 0.0 && i < m; i++) /* scaled: no overflow for huge entries */
      ss += (a[i * n + j] / big) * (a[i * n + j] / big);
    double s = big * sqrt(ss);
    ws->scale[j] = s;
    for (size_t i = 0; i < m; i++)
      gsl_matrix_set(ws->as, i, j, s > 0.0 ? a[i * n + j] / s : 0.0);
    if (!(s > 0.0)) ws->rejected[j] = 2; /* permanently: x_j = 0 */
  }
  for (size_t i = 0; i < m; i++)
    gsl_vector_set(ws->bv, i, b[i]);
  return gsl_blas_dnrm2(ws->bv);
}

/* A tall problem (m > n) is first reduced by one QR, A = Q [R; 0]: since Q
 * is orthogonal, ||A x - b||^2 = ||R x - c||^2 + ||d||^2 with Q^T b = [c; d],
 * so the active-set iteration runs on the n x n system (R, c), which
 * replaces as and bv, and each of its sub-problems costs O(n p^2) instead
 * of O(m p^2). *rest gets ||d||. */
static vl_status reduce_tall(nnls_work *ws, double *rest, vl_error *err) {
  size_t m = ws->m, n = ws->n;
  if (gsl_linalg_QR_decomp(ws->as, ws->tau) != GSL_SUCCESS ||
      gsl_linalg_QR_QTvec(ws->as, ws->tau, ws->bv) != GSL_SUCCESS)
    return qr_failure(VL_EINTERNAL, ws, err);
  gsl_vector_view tail = gsl_vector_subvector(ws->bv, n, m - n);
  *rest = gsl_blas_dnrm2(&tail.vector);
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < i; j++)
      gsl_matrix_set(ws->as, i, j, 0.0);
  gsl_matrix_view top = gsl_matrix_submatrix(ws->as, 0, 0, n, n);
  gsl_vector_view ctop = gsl_vector_subvector(ws->bv, 0, n);
  gsl_matrix *red_a = gsl_matrix_alloc(n, n);
  gsl_vector *red_b = gsl_vector_alloc(n);
  if (!red_a || !red_b) {
    gsl_matrix_free(red_a);
    gsl_vector_free(red_b);
    vl_error_set(err, "nnls: out of memory (%zu x %zu)", m, n);
    return VL_ENOMEM;
  }
  gsl_matrix_memcpy(red_a, &top.matrix);
  gsl_vector_memcpy(red_b, &ctop.vector);
  gsl_matrix_free(ws->as);
  gsl_vector_free(ws->bv);
  ws->as = red_a;
  ws->bv = red_b;
  ws->m = n;
  gsl_matrix_free(ws->qr);
  gsl_vector_free(ws->r);
  ws->qr = gsl_matrix_alloc(n, n);
  ws->r = gsl_vector_alloc(n);
  if (!ws->qr || !ws->r) {
    vl_error_set(err, "nnls: out of memory (%zu x %zu)", n, n);
    return VL_ENOMEM;
  }
  return VL_OK;
}

/* The variable of Z (neither in P nor rejected) of the steepest descent,
 * its gradient above tol; n if there is none. */
static size_t steepest_free(const nnls_work *ws, double tol) {
  size_t best = ws->n;
  double wmax = tol;
  for (size_t j = 0; j < ws->n; j++) {
    if (ws->in_p[j] || ws->rejected[j]) continue;
    if (gsl_vector_get(ws->w, j) > wmax) wmax = gsl_vector_get(ws->w, j), best = j;
  }
  return best;
}

/* Moves variable j into P and solves the sub-problem on P into z.
 * Lawson & Hanson's safeguard: a column dependent on P, or one whose own
 * coefficient would come out non-positive, cannot reduce the residual; it
 * is then taken out again and skipped until another variable has entered
 * (*entered = 0). Errors of solve_subset, without a message. */
static vl_status enter(nnls_work *ws, size_t j, int *entered) {
  ws->p[ws->np++] = j;
  ws->in_p[j] = 1;
  double r_last = 0.0;
  vl_status st = solve_subset(ws->as, ws->bv, ws->p, ws->np, ws->qr, ws->tau, ws->z, &r_last);
  if (st != VL_OK) return st;
  *entered = r_last > DEPENDENT_TOL && gsl_vector_get(ws->z, ws->np - 1) > 0.0;
  if (!*entered) {
    ws->in_p[j] = 0;
    ws->np--;
    ws->rejected[j] = 1;
    return VL_OK;
  }
  for (size_t k = 0; k < ws->n; k++)
    if (ws->rejected[k] == 1) ws->rejected[k] = 0;
  return VL_OK;
}

/* 1 if every entry of z on P is positive. */
static int z_positive(const nnls_work *ws) {
  int all_positive = 1;
  for (size_t k = 0; k < ws->np; k++)
    if (!(gsl_vector_get(ws->z, k) > 0.0)) all_positive = 0;
  return all_positive;
}

/* The longest step from x towards z, at most 1, that keeps x >= 0. */
static double feasible_step(const nnls_work *ws) {
  double alpha = 1.0;
  for (size_t k = 0; k < ws->np; k++) {
    double zk = gsl_vector_get(ws->z, k), xk = gsl_vector_get(ws->xs, ws->p[k]);
    if (zk <= 0.0) {
      double t = xk / (xk - zk);
      if (t < alpha) alpha = t;
    }
  }
  return alpha;
}

/* Steps x by alpha towards z; the variables reaching zero leave P (and at
 * least one does: if rounding kept them all, the limiting one). */
static void step_towards_z(nnls_work *ws, double alpha) {
  size_t np = ws->np, keep = 0, *p = ws->p;
  gsl_vector *xs = ws->xs, *z = ws->z;
  for (size_t k = 0; k < np; k++) {
    double xk = gsl_vector_get(xs, p[k]);
    double xn = xk + alpha * (gsl_vector_get(z, k) - xk);
    if (xn <= DBL_EPSILON * fabs(xk) || xn <= 0.0) {
      gsl_vector_set(xs, p[k], 0.0);
      ws->in_p[p[k]] = 0;
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
      if (zk <= 0.0 && gsl_vector_get(xs, p[k]) < vmin) vmin = gsl_vector_get(xs, p[k]), kmin = k;
    }
    gsl_vector_set(xs, p[kmin], 0.0);
    ws->in_p[p[kmin]] = 0;
    for (size_t k = kmin; k + 1 < np; k++)
      p[k] = p[k + 1];
    keep = np - 1;
  }
  ws->np = keep;
}

/* The inner loop: while z has a non-positive entry, moves x towards z as
 * far as feasibility allows, returns the variables that hit zero to Z and
 * solves again on the smaller P; then x = z on P. */
static vl_status keep_feasible(nnls_work *ws, vl_error *err) {
  for (size_t inner = 0;; inner++) {
    if (z_positive(ws)) {
      for (size_t k = 0; k < ws->np; k++)
        gsl_vector_set(ws->xs, ws->p[k], gsl_vector_get(ws->z, k));
      return VL_OK;
    }
    if (inner > ws->n) {
      vl_error_set(err, "nnls: the feasibility loop did not terminate (%zu x %zu)", ws->m, ws->n);
      return VL_ENOCONV;
    }
    step_towards_z(ws, feasible_step(ws));
    if (ws->np == 0) return VL_OK;
    double r_last = 0.0;
    vl_status st = solve_subset(ws->as, ws->bv, ws->p, ws->np, ws->qr, ws->tau, ws->z, &r_last);
    if (st != VL_OK) return qr_failure(st, ws, err);
  }
}

/* The outer loop: moves the variable of steepest descent into P until the
 * optimality conditions hold to tol (or P fills the rows); *rnorm gets
 * ||b - As x|| of the reduced problem. */
static vl_status active_set(nnls_work *ws, double tol, double *rnorm, vl_error *err) {
  size_t n = ws->n, max_outer = 3 * n + 30, outer = 0;
  *rnorm = gradient(ws->as, ws->bv, ws->xs, ws->r, ws->w);
  for (;;) {
    size_t best = steepest_free(ws, tol);
    if (best == n || ws->np == ws->m) break; /* KKT conditions hold (or b is in range) */
    if (++outer > max_outer) {
      vl_error_set(err, "nnls: no convergence after %zu steps (%zu x %zu, ill-conditioned?)",
                   max_outer, ws->m, n);
      return VL_ENOCONV;
    }
    int entered = 0;
    vl_status st = enter(ws, best, &entered);
    if (st != VL_OK) return qr_failure(st, ws, err);
    if (!entered) continue;
    if ((st = keep_feasible(ws, err)) != VL_OK) return st;
    *rnorm = gradient(ws->as, ws->bv, ws->xs, ws->r, ws->w);
  }
  return VL_OK;
}

vl_status vl_nnls_solve(size_t m, size_t n, const double *a, const double *b, double *x,
                        double *residual_norm, vl_error *err) {
  nnls_work ws;
  memset(&ws, 0, sizeof ws);
  if (x && n) memset(x, 0, n * sizeof *x);
  vl_status st = check_input(m, n, a, b, x, err);
  if (st != VL_OK) return st;
  vl_gsl_errors_off();
  if (!work_alloc(&ws, m, n)) {
    vl_error_set(err, "nnls: out of memory (%zu x %zu)", m, n);
    st = VL_ENOMEM;
    goto cleanup;
  }
  double bnorm = scale_columns(&ws, a, b), rest = 0.0, rnorm = 0.0;
  if (m > n && (st = reduce_tall(&ws, &rest, err)) != VL_OK) goto cleanup;
  double tol = 10.0 * DBL_EPSILON * (double)(m > n ? m : n) * bnorm;
  if ((st = active_set(&ws, tol, &rnorm, err)) != VL_OK) goto cleanup;
  for (size_t j = 0; j < n; j++)
    x[j] = ws.scale[j] > 0.0 ? gsl_vector_get(ws.xs, j) / ws.scale[j] : 0.0;
  if (residual_norm) *residual_norm = hypot(rnorm, rest);

cleanup:
  if (st != VL_OK) memset(x, 0, n * sizeof *x);
  work_free(&ws);
  return st;
}
