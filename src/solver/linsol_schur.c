/* Schur-complement solver of the rough wet Jacobian (linsol_schur.h). */
#include "linsol_schur.h"
#include "lapack_abi.h"

#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sundials/sundials_nvector.h>
#include <sunmatrix/sunmatrix_dense.h>

/* Relative residual a solve must reach (after refinement) before its
 * result is used; Newton needs far less, the check guards the elimination
 * order, not the accuracy of the step. */
#define SCHUR_RESIDUAL 1e-10
#define SCHUR_REFINE 3

typedef struct {
  int n, of, ih, N;      /* grid, offsets, full size 2n + 1 */
  double *lo, *up, *sup; /* Bp = L U: L unit lower (lo), U diag up, super sup */
  int *c_lo, *c_hi;      /* nonzero rows (within the Reynolds block) of C's columns */
  /* C's u column j is zero outside rows j-band_lo .. j+band_hi (-1: unknown) */
  int band_lo, band_hi;
  double *X; /* B Bp^{-1}, (n+1) x n column-major */
  double *S; /* Schur complement (n+1)^2, then its LU */
  int *piv;
  double *r, *w, *res, *dx; /* work vectors */
  double *full;             /* fallback: LU of the full matrix (allocated on first use) */
  int *full_piv;
  bool use_full; /* this set-up fell back */
  long fallbacks;
  sunindextype last_flag;
} schur_content;

static SUNLinearSolver_Type schur_gettype(SUNLinearSolver S) {
  (void)S;
  return SUNLINEARSOLVER_DIRECT;
}
static SUNLinearSolver_ID schur_getid(SUNLinearSolver S) {
  (void)S;
  return SUNLINEARSOLVER_CUSTOM;
}
static int schur_initialize(SUNLinearSolver S) {
  ((schur_content *)S->content)->last_flag = 0;
  return SUNLS_SUCCESS;
}

/* Row r of the reduced system (0..n) is row/column d(r) of the full one. */
static int d_index(const schur_content *c, int r) { return r < c->n ? r : c->ih; }

static int full_setup(schur_content *c, const double *J) {
  size_t NN = (size_t)c->N * (size_t)c->N;
  if (!c->full) {
    c->full = malloc(NN * sizeof *c->full);
    c->full_piv = malloc((size_t)c->N * sizeof *c->full_piv);
    if (!c->full || !c->full_piv) return SUNLS_MEM_FAIL;
  }
  memcpy(c->full, J, NN * sizeof *J);
  int info = 0;
  dgetrf_(&c->N, &c->N, c->full, &c->N, c->full_piv, &info);
  c->use_full = true;
  c->fallbacks++;
  c->last_flag = info;
  if (info < 0) return SUNLS_PACKAGE_FAIL_UNREC;
  return info > 0 ? SUNLS_LUFACT_FAIL : SUNLS_SUCCESS;
}

/* Factorises the tridiagonal Reynolds block Bp = L U (Thomas, no
 * pivoting) from its three diagonals; false if a pivot is not positive (not
 * an M-matrix: let the full LU pivot instead). Entries off the three
 * diagonals are not read: the residual check of every solve would catch
 * them (and tests/test_linsol_schur.c checks the structure). */
static bool factor_block(schur_content *c, const double *J) {
  int n = c->n, of = c->of;
  size_t ld = (size_t)c->N;
  double prev_up = 0.0;
  for (int k = 0; k < n; k++) {
    const double *col = J + (size_t)(of + k) * ld + of;
    double diag = col[k];
    if (k > 0) {
      double sub = J[(size_t)(of + k - 1) * ld + (size_t)(of + k)]; /* Bp[k][k-1] */
      c->sup[k - 1] = col[k - 1];                                   /* Bp[k-1][k] */
      c->lo[k] = sub / prev_up;
      diag -= c->lo[k] * c->sup[k - 1];
    }
    if (!(diag > 0.0) || !isfinite(diag)) return false;
    c->up[k] = diag;
    prev_up = diag;
  }
  return true;
}

/* v <- Bp^{-1} v */
static void block_solve(const schur_content *c, double *v) {
  int n = c->n;
  for (int k = 1; k < n; k++)
    v[k] -= c->lo[k] * v[k - 1];
  v[n - 1] /= c->up[n - 1];
  for (int k = n - 2; k >= 0; k--)
    v[k] = (v[k] - c->sup[k] * v[k + 1]) / c->up[k];
}

static int schur_setup(SUNLinearSolver LS, SUNMatrix A) {
  schur_content *c = LS->content;
  if (SUNDenseMatrix_Rows(A) != c->N) return SUNLS_ILL_INPUT;
  const double *J = SUNDenseMatrix_Data(A);
  int n = c->n, of = c->of, m = n + 1;
  size_t ld = (size_t)c->N, mm = (size_t)m;
  c->use_full = false;
  if (!factor_block(c, J)) return full_setup(c, J);
  /* X = B Bp^{-1}: X L U = B. W U = B column by column (ascending), then
   * X L = W (descending); columns of B are the pf columns of J on the rows
   * d(0..n), contiguous but for the load row. */
  for (int j = 0; j < n; j++) {
    const double *bcol = J + (size_t)(of + j) * ld;
    double *x = c->X + (size_t)j * mm, *xp = c->X + (size_t)(j - 1) * mm;
    double s = j > 0 ? c->sup[j - 1] : 0.0, inv = 1.0 / c->up[j];
    for (int r = 0; r < n; r++)
      x[r] = (bcol[r] - (j > 0 ? s * xp[r] : 0.0)) * inv;
    x[n] = (bcol[c->ih] - (j > 0 ? s * xp[n] : 0.0)) * inv;
  }
  for (int j = n - 2; j >= 0; j--) {
    double *x = c->X + (size_t)j * mm;
    const double *xn = c->X + (size_t)(j + 1) * mm;
    double l = c->lo[j + 1];
    for (int r = 0; r < m; r++)
      x[r] -= l * xn[r];
  }
  /* S = A - X C, C by the nonzeros of its columns (Reynolds rows of the
   * u and h0 columns of J) */
  for (int j = 0; j < m; j++) {
    const double *jcol = J + (size_t)d_index(c, j) * ld;
    double *scol = c->S + (size_t)j * mm;
    for (int r = 0; r < n; r++)
      scol[r] = jcol[r];
    scol[n] = jcol[c->ih];
    const double *ccol = jcol + of;
    int lo = n, hi = -1, k0 = 0, k1 = n;
    if (c->band_lo >= 0 && j < n) { /* only the band can hold nonzeros */
      k0 = j - c->band_lo > 0 ? j - c->band_lo : 0;
      k1 = j + c->band_hi + 1 < n ? j + c->band_hi + 1 : n;
    }
    for (int k = k0; k < k1; k++) {
      if (ccol[k] == 0.0) continue;
      if (lo == n) lo = k;
      hi = k;
      const double *x = c->X + (size_t)k * mm;
      double ck = ccol[k];
      for (int r = 0; r < m; r++)
        scol[r] -= ck * x[r];
    }
    c->c_lo[j] = lo, c->c_hi[j] = hi;
  }
  int info = 0;
  dgetrf_(&m, &m, c->S, &m, c->piv, &info);
  c->last_flag = info;
  if (info != 0) return full_setup(c, J); /* singular complement: let the full LU decide */
  return SUNLS_SUCCESS;
}

/* One block solve of J x = b (no check). */
static void schur_apply(schur_content *c, const double *J, const double *b, double *x) {
  int n = c->n, of = c->of, m = n + 1, one = 1, info = 0;
  size_t ld = (size_t)c->N;
  double *z = c->w, *r = c->r;
  memcpy(z, b + of, (size_t)n * sizeof *z);
  block_solve(c, z); /* z = Bp^{-1} b_T */
  for (int i = 0; i < n; i++)
    r[i] = b[i];
  r[n] = b[c->ih];
  for (int k = 0; k < n; k++) { /* r = b_D - B z */
    const double *bcol = J + (size_t)(of + k) * ld;
    double zk = z[k];
    if (zk == 0.0) continue;
    for (int i = 0; i < n; i++)
      r[i] -= zk * bcol[i];
    r[n] -= zk * bcol[c->ih];
  }
  dgetrs_("N", &m, &one, c->S, &m, c->piv, r, &m, &info, 1);
  for (int j = 0; j < m; j++)
    x[d_index(c, j)] = r[j];
  /* x_T = Bp^{-1} (b_T - C x_D) */
  double *t = x + of;
  memcpy(t, b + of, (size_t)n * sizeof *t);
  for (int j = 0; j < m; j++) {
    const double *ccol = J + (size_t)d_index(c, j) * ld + of;
    double xj = r[j];
    for (int k = c->c_lo[j]; k <= c->c_hi[j]; k++)
      t[k] -= ccol[k] * xj;
  }
  block_solve(c, t);
}

/* res = b - J x; returns its max norm */
static double residual(const schur_content *c, const double *J, const double *b, const double *x,
                       double *res) {
  size_t N = (size_t)c->N;
  memcpy(res, b, N * sizeof *res);
  for (size_t j = 0; j < N; j++) {
    const double *col = J + j * N;
    double xj = x[j];
    if (xj == 0.0) continue;
    for (size_t i = 0; i < N; i++)
      res[i] -= col[i] * xj;
  }
  double mx = 0.0;
  for (size_t i = 0; i < N; i++)
    mx = fmax(mx, fabs(res[i]));
  return isfinite(mx) ? mx : INFINITY;
}

static int full_solve(schur_content *c, const double *b, double *x) {
  int one = 1, info = 0;
  memcpy(x, b, (size_t)c->N * sizeof *x);
  dgetrs_("N", &c->N, &one, c->full, &c->N, c->full_piv, x, &c->N, &info, 1);
  c->last_flag = info;
  return info == 0 ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_UNREC;
}

static int schur_solve(SUNLinearSolver LS, SUNMatrix A, N_Vector xv, N_Vector bv, realtype tol) {
  (void)tol;
  schur_content *c = LS->content;
  const double *J = SUNDenseMatrix_Data(A), *b = N_VGetArrayPointer(bv);
  double *x = N_VGetArrayPointer(xv);
  if (c->use_full) return full_solve(c, b, x);
  size_t N = (size_t)c->N;
  double bmax = 0.0;
  for (size_t i = 0; i < N; i++)
    bmax = fmax(bmax, fabs(b[i]));
  schur_apply(c, J, b, x);
  for (int it = 0;; it++) {
    double rmax = residual(c, J, b, x, c->res);
    if (rmax <= SCHUR_RESIDUAL * bmax) return SUNLS_SUCCESS;
    if (it == SCHUR_REFINE) break;
    schur_apply(c, J, c->res, c->dx); /* refinement: x += J^{-1} (b - J x) */
    for (size_t i = 0; i < N; i++)
      x[i] += c->dx[i];
  }
  int st = full_setup(c, J);
  return st == SUNLS_SUCCESS ? full_solve(c, b, x) : st;
}

static sunindextype schur_lastflag(SUNLinearSolver S) {
  return ((schur_content *)S->content)->last_flag;
}

static int schur_space(SUNLinearSolver S, long *lenrw, long *leniw) {
  const schur_content *c = S->content;
  long m = c->n + 1;
  *lenrw = m * c->n + m * m + 3L * c->n + 4L * c->N;
  *leniw = 2 * m + m;
  return SUNLS_SUCCESS;
}

static int schur_free(SUNLinearSolver S) {
  if (!S) return SUNLS_SUCCESS;
  schur_content *c = S->content;
  if (c) {
    free(c->lo), free(c->up), free(c->sup), free(c->c_lo), free(c->c_hi), free(c->X);
    free(c->S), free(c->piv), free(c->r), free(c->w), free(c->res), free(c->dx);
    free(c->full), free(c->full_piv);
    free(c);
    S->content = NULL;
  }
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

SUNLinearSolver vl_linsol_schur_create(long n, long of, long ih, SUNContext ctx) {
  if (n < 2 || of != n || ih != 2 * n) return NULL; /* the contact's layout */
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return NULL;
  schur_content *c = calloc(1, sizeof *c);
  S->content = c;
  S->ops->free = schur_free;
  if (!c) {
    SUNLinSolFreeEmpty(S);
    return NULL;
  }
  c->n = (int)n, c->of = (int)of, c->ih = (int)ih, c->N = (int)(2 * n + 1);
  c->band_lo = c->band_hi = -1;
  size_t un = (size_t)n, m = un + 1, N = (size_t)c->N;
  c->lo = calloc(un, sizeof *c->lo);
  c->up = calloc(un, sizeof *c->up);
  c->sup = calloc(un, sizeof *c->sup);
  c->c_lo = calloc(m, sizeof *c->c_lo);
  c->c_hi = calloc(m, sizeof *c->c_hi);
  c->X = malloc(m * un * sizeof *c->X);
  c->S = malloc(m * m * sizeof *c->S);
  c->piv = malloc(m * sizeof *c->piv);
  c->r = malloc(m * sizeof *c->r);
  c->w = malloc(un * sizeof *c->w);
  c->res = malloc(N * sizeof *c->res);
  c->dx = malloc(N * sizeof *c->dx);
  if (!c->lo || !c->up || !c->sup || !c->c_lo || !c->c_hi || !c->X || !c->S || !c->piv || !c->r ||
      !c->w || !c->res || !c->dx) {
    schur_free(S);
    return NULL;
  }
  S->ops->gettype = schur_gettype;
  S->ops->getid = schur_getid;
  S->ops->initialize = schur_initialize;
  S->ops->setup = schur_setup;
  S->ops->solve = schur_solve;
  S->ops->lastflag = schur_lastflag;
  S->ops->space = schur_space;
  return S;
}

void vl_linsol_schur_set_band(SUNLinearSolver S, int lower, int upper) {
  schur_content *c = S->content;
  c->band_lo = lower >= 0 && upper >= 0 ? lower : -1;
  c->band_hi = c->band_lo >= 0 ? upper : -1;
}

long vl_linsol_schur_fallbacks(SUNLinearSolver S) {
  return S && S->content ? ((schur_content *)S->content)->fallbacks : 0;
}
