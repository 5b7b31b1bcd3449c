/* The reduced (active-set) dense solver (linsol_reduced.h). */
#include "linsol_reduced.h"
#include "lapack_abi.h"

#include <float.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sundials/sundials_nvector.h>
#include <sunmatrix/sunmatrix_dense.h>

/* The coupled block is factorised in single precision (LAPACK's sgetrf:
 * 0.53 against 0.83 ms for dgetrf at m = 280, one core) and each solve
 * refined in double, as LAPACK's dsgesv does, to its stopping test: the
 * residual below ||R||_inf ||x||_inf eps sqrt(m), the backward error of a
 * double LU (fig03-smooth at N 400: 2-3 steps per solve). At most
 * REFINE_MAX steps, given up when a step does not halve the residual; a
 * block whose single factorisation fails or whose refinement does not
 * converge is factorised in double (dgetrf/dgetrs on the block, as
 * before). */
#define REFINE_MAX 30

typedef struct {
  int n;            /* full size */
  int m;            /* coupled rows of the last set-up */
  int *coupled;     /* their indices, m of them */
  int *runs, nruns; /* the coupled indices as runs of consecutive ones: first index, its
                     * position in coupled, length (3 ints a run) */
  bool *free_row;   /* row solved on its own */
  double *off;      /* largest off-diagonal magnitude per row (set-up work) */
  double *R;        /* the coupled block, m x m column-major (its LU when in double) */
  float *RS;        /* its LU in single precision */
  float *rf;        /* m: a refinement step's right-hand side and correction */
  double *x, *r;    /* m: the refined solution and its residual */
  double anrm;      /* ||R||_inf */
  bool single;      /* RS holds the LU (else R does) */
  int *piv;
  double *rhs; /* m */
  sunindextype last_flag;
  const double *hint_du; /* set_rows: rows i < hint_n with hint_du[i] == 0 are free */
  const bool *hint_on;   /* ... while *hint_on */
  int hint_n;
} reduced_content;

static SUNLinearSolver_Type reduced_gettype(SUNLinearSolver S) {
  (void)S;
  return SUNLINEARSOLVER_DIRECT;
}
static SUNLinearSolver_ID reduced_getid(SUNLinearSolver S) {
  (void)S;
  return SUNLINEARSOLVER_CUSTOM;
}
static int reduced_initialize(SUNLinearSolver S) {
  ((reduced_content *)S->content)->last_flag = 0;
  return SUNLS_SUCCESS;
}

static void mark_rows(reduced_content *c, const double *J);

/* Marks the rows whose off-diagonal entries are negligible (read down the
 * columns: the matrix is column-major). */
static void find_free_rows(reduced_content *c, const double *J) {
  int n = c->n;
  if (c->hint_on && *c->hint_on) {
    for (int i = 0; i < n; i++)
      c->off[i] = i < c->hint_n && c->hint_du[i] == 0.0 ? 0.0 : INFINITY;
    mark_rows(c, J);
    return;
  }
  for (int i = 0; i < n; i++)
    c->off[i] = 0.0;
  double *off = c->off;
  for (int j = 0; j < n; j++) { /* two branch-free runs around the diagonal */
    const double *col = J + (size_t)j * (size_t)n;
    for (int i = 0; i < j; i++) {
      double a = fabs(col[i]);
      off[i] = a > off[i] ? a : off[i];
    }
    for (int i = j + 1; i < n; i++) {
      double a = fabs(col[i]);
      off[i] = a > off[i] ? a : off[i];
    }
  }
  mark_rows(c, J);
}

/* The free rows from off (the largest off-diagonal magnitude per row), the
 * coupled ones as runs. */
static void mark_rows(reduced_content *c, const double *J) {
  int n = c->n;
  c->m = 0, c->nruns = 0;
  for (int i = 0; i < n; i++) {
    double d = fabs(J[(size_t)i * (size_t)n + (size_t)i]);
    c->free_row[i] = d > 0.0 && c->off[i] <= VL_REDUCED_ROW_TOL * d;
    if (c->free_row[i]) continue;
    int *run = c->runs + 3 * (c->nruns - 1);
    if (c->nruns > 0 && run[0] + run[2] == i) {
      run[2]++;
    } else {
      run += 3, c->nruns++;
      run[0] = i, run[1] = c->m, run[2] = 1;
    }
    c->coupled[c->m++] = i;
  }
}

/* The block's LU in double, in place of R (no longer needed for
 * refinement). */
static int factorise_double(reduced_content *c) {
  int m = c->m, info = 0;
  dgetrf_(&m, &m, c->R, &m, c->piv, &info);
  c->single = false;
  return info;
}

static int reduced_setup(SUNLinearSolver S, SUNMatrix A) {
  reduced_content *c = S->content;
  if (SUNDenseMatrix_Rows(A) != c->n) return SUNLS_ILL_INPUT;
  const double *J = SUNDenseMatrix_Data(A);
  find_free_rows(c, J);
  int m = c->m, info = 0;
  size_t M = (size_t)m;
  double *rowsum = c->off; /* free again */
  for (size_t a = 0; a < M; a++)
    rowsum[a] = 0.0;
  for (size_t b = 0; b < M; b++) { /* the block, run by run (contiguous copies) */
    const double *col = J + (size_t)c->coupled[b] * (size_t)c->n;
    for (int k = 0; k < c->nruns; k++) {
      const int *run = c->runs + 3 * k;
      const double *src = col + run[0];
      size_t at = b * M + (size_t)run[1], len = (size_t)run[2];
      double *R = c->R + at, *sum = rowsum + run[1];
      float *RS = c->RS + at;
      for (size_t a = 0; a < len; a++) {
        R[a] = src[a], RS[a] = (float)src[a];
        sum[a] += fabs(src[a]);
      }
    }
  }
  c->anrm = 0.0;
  for (size_t a = 0; a < M; a++)
    c->anrm = rowsum[a] > c->anrm ? rowsum[a] : c->anrm;
  c->single = true;
  if (m > 0) sgetrf_(&m, &m, c->RS, &m, c->piv, &info);
  if (m > 0 && info != 0) info = factorise_double(c);
  c->last_flag = info;
  if (info < 0) return SUNLS_PACKAGE_FAIL_UNREC;
  if (info > 0) return SUNLS_LUFACT_FAIL;
  return SUNLS_SUCCESS;
}

/* R x = rhs by the single LU and refinement in double; x into rhs. False
 * (rhs unchanged) when it does not converge within REFINE_MAX steps. */
static bool refine(reduced_content *c) {
  int m = c->m, one = 1, info = 0;
  size_t M = (size_t)m;
  double *x = c->x, *r = c->r, minus = -1.0, plus = 1.0;
  double tol = c->anrm * DBL_EPSILON * 0.5 * sqrt((double)m), last = INFINITY;
  for (size_t a = 0; a < M; a++)
    x[a] = 0.0, r[a] = c->rhs[a];
  for (int it = 0; it < REFINE_MAX; it++) {
    for (size_t a = 0; a < M; a++)
      c->rf[a] = (float)r[a];
    sgetrs_("N", &m, &one, c->RS, &m, c->piv, c->rf, &m, &info, 1);
    for (size_t a = 0; a < M; a++)
      x[a] += (double)c->rf[a];
    memcpy(r, c->rhs, M * sizeof *r); /* r = rhs - R x */
    dgemv_("N", &m, &m, &minus, c->R, &m, x, &one, &plus, r, &one, 1);
    double rnrm = 0.0, xnrm = 0.0;
    for (size_t a = 0; a < M; a++) {
      rnrm = fabs(r[a]) > rnrm ? fabs(r[a]) : rnrm;
      xnrm = fabs(x[a]) > xnrm ? fabs(x[a]) : xnrm;
    }
    if (!isfinite(rnrm) || !isfinite(xnrm)) return false;
    if (rnrm <= xnrm * tol) {
      memcpy(c->rhs, x, M * sizeof *x);
      return true;
    }
    if (!(rnrm < 0.5 * last)) return false; /* stagnates: single precision cannot resolve R */
    last = rnrm;
  }
  return false;
}

/* Free unknowns from their own rows; the coupled ones from the LU of their
 * block, with the free unknowns' columns moved to the right-hand side. */
static int reduced_solve(SUNLinearSolver S, SUNMatrix A, N_Vector xv, N_Vector bv, realtype tol) {
  (void)tol;
  reduced_content *c = S->content;
  const double *J = SUNDenseMatrix_Data(A), *b = N_VGetArrayPointer(bv);
  double *x = N_VGetArrayPointer(xv);
  int n = c->n, m = c->m, one = 1, info = 0;
  for (int a = 0; a < m; a++)
    c->rhs[a] = b[c->coupled[a]];
  for (int j = 0; j < n; j++) {
    if (!c->free_row[j]) continue;
    const double *col = J + (size_t)j * (size_t)n;
    x[j] = b[j] / col[j];
    for (int k = 0; k < c->nruns; k++) {
      const int *run = c->runs + 3 * k;
      const double *src = col + run[0];
      double *rhs = c->rhs + run[1];
      for (int a = 0; a < run[2]; a++)
        rhs[a] -= src[a] * x[j];
    }
  }
  if (m > 0 && c->single && !refine(c) && factorise_double(c) != 0) {
    c->last_flag = 1;
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
  if (m > 0 && !c->single) dgetrs_("N", &m, &one, c->R, &m, c->piv, c->rhs, &m, &info, 1);
  c->last_flag = info;
  if (info != 0) return SUNLS_PACKAGE_FAIL_UNREC;
  for (int a = 0; a < m; a++)
    x[c->coupled[a]] = c->rhs[a];
  return SUNLS_SUCCESS;
}

static sunindextype reduced_lastflag(SUNLinearSolver S) {
  return ((reduced_content *)S->content)->last_flag;
}

static int reduced_space(SUNLinearSolver S, long *lenrw, long *leniw) {
  long n = ((reduced_content *)S->content)->n;
  *lenrw = n * n + n * n / 2 + 5 * n; /* R, RS (floats), off, rhs, x, r, rf */
  *leniw = 6 * n + 2;
  return SUNLS_SUCCESS;
}

static int reduced_free(SUNLinearSolver S) {
  if (!S) return SUNLS_SUCCESS;
  reduced_content *c = S->content;
  if (c) {
    free(c->coupled);
    free(c->runs);
    free(c->free_row);
    free(c->off);
    free(c->R);
    free(c->RS);
    free(c->rf);
    free(c->x);
    free(c->piv);
    free(c->rhs);
    free(c);
    S->content = NULL;
  }
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

void vl_linsol_reduced_set_rows(SUNLinearSolver S, const double *du, long n, const bool *on) {
  reduced_content *c = S->content;
  c->hint_du = du, c->hint_n = (int)n, c->hint_on = on;
}

long vl_linsol_reduced_size(SUNLinearSolver S) { return ((reduced_content *)S->content)->m; }

SUNLinearSolver vl_linsol_reduced_create(long n, SUNContext ctx) {
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return NULL;
  reduced_content *c = calloc(1, sizeof *c);
  if (!c) {
    SUNLinSolFreeEmpty(S);
    return NULL;
  }
  size_t N = (size_t)n;
  S->content = c;
  c->n = c->m = (int)n;
  c->coupled = malloc(N * sizeof *c->coupled);
  c->runs = malloc(3 * N * sizeof *c->runs);
  c->free_row = malloc(N * sizeof *c->free_row);
  c->off = malloc(N * sizeof *c->off);
  c->R = malloc(N * N * sizeof *c->R);
  c->RS = malloc(N * N * sizeof *c->RS);
  c->rf = malloc(N * sizeof *c->rf);
  c->x = malloc(2 * N * sizeof *c->x);
  c->r = c->x ? c->x + N : NULL;
  c->piv = malloc(N * sizeof *c->piv);
  c->rhs = malloc(N * sizeof *c->rhs);
  if (!c->coupled || !c->runs || !c->free_row || !c->off || !c->R || !c->RS || !c->rf || !c->x ||
      !c->piv || !c->rhs) {
    reduced_free(S);
    return NULL;
  }
  S->ops->gettype = reduced_gettype;
  S->ops->getid = reduced_getid;
  S->ops->initialize = reduced_initialize;
  S->ops->setup = reduced_setup;
  S->ops->solve = reduced_solve;
  S->ops->lastflag = reduced_lastflag;
  S->ops->space = reduced_space;
  S->ops->free = reduced_free;
  return S;
}
