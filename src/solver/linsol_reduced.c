/* The reduced (active-set) dense solver (linsol_reduced.h). */
#include "linsol_reduced.h"
#include "lapack_abi.h"

#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdbool.h>
#include <stdlib.h>
#include <sundials/sundials_nvector.h>
#include <sunmatrix/sunmatrix_dense.h>

typedef struct {
  int n;          /* full size */
  int m;          /* coupled rows of the last set-up */
  int *coupled;   /* their indices, m of them */
  bool *free_row; /* row solved on its own */
  double *off;    /* largest off-diagonal magnitude per row (set-up work) */
  double *R;      /* the coupled block, m x m column-major, then its LU */
  int *piv;
  double *rhs; /* m */
  sunindextype last_flag;
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

/* Marks the rows whose off-diagonal entries are negligible (read down the
 * columns: the matrix is column-major). */
static void find_free_rows(reduced_content *c, const double *J) {
  int n = c->n;
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
  c->m = 0;
  for (int i = 0; i < n; i++) {
    double d = fabs(J[(size_t)i * (size_t)n + (size_t)i]);
    c->free_row[i] = d > 0.0 && c->off[i] <= VL_REDUCED_ROW_TOL * d;
    if (!c->free_row[i]) c->coupled[c->m++] = i;
  }
}

static int reduced_setup(SUNLinearSolver S, SUNMatrix A) {
  reduced_content *c = S->content;
  if (SUNDenseMatrix_Rows(A) != c->n) return SUNLS_ILL_INPUT;
  const double *J = SUNDenseMatrix_Data(A);
  find_free_rows(c, J);
  int m = c->m, info = 0;
  for (int b = 0; b < m; b++) {
    const double *col = J + (size_t)c->coupled[b] * (size_t)c->n;
    for (int a = 0; a < m; a++)
      c->R[(size_t)b * (size_t)m + (size_t)a] = col[c->coupled[a]];
  }
  if (m > 0) dgetrf_(&m, &m, c->R, &m, c->piv, &info);
  c->last_flag = info;
  if (info < 0) return SUNLS_PACKAGE_FAIL_UNREC;
  if (info > 0) return SUNLS_LUFACT_FAIL;
  return SUNLS_SUCCESS;
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
    for (int a = 0; a < m; a++)
      c->rhs[a] -= col[c->coupled[a]] * x[j];
  }
  if (m > 0) dgetrs_("N", &m, &one, c->R, &m, c->piv, c->rhs, &m, &info, 1);
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
  *lenrw = n * n + 2 * n;
  *leniw = 3 * n + 2;
  return SUNLS_SUCCESS;
}

static int reduced_free(SUNLinearSolver S) {
  if (!S) return SUNLS_SUCCESS;
  reduced_content *c = S->content;
  if (c) {
    free(c->coupled);
    free(c->free_row);
    free(c->off);
    free(c->R);
    free(c->piv);
    free(c->rhs);
    free(c);
    S->content = NULL;
  }
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
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
  c->free_row = malloc(N * sizeof *c->free_row);
  c->off = malloc(N * sizeof *c->off);
  c->R = malloc(N * N * sizeof *c->R);
  c->piv = malloc(N * sizeof *c->piv);
  c->rhs = malloc(N * sizeof *c->rhs);
  if (!c->coupled || !c->free_row || !c->off || !c->R || !c->piv || !c->rhs) {
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
