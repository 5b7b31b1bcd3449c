#include "linsol_lapack.h"
#include "lapack_abi.h"

#include <nvector/nvector_serial.h>
#include <stdlib.h>
#include <sundials/sundials_nvector.h>
#include <sunmatrix/sunmatrix_dense.h>

typedef struct {
  int n;
  int *pivots;
  sunindextype last_flag;
} lapack_content;

static SUNLinearSolver_Type lapack_gettype(SUNLinearSolver S) {
  (void)S;
  return SUNLINEARSOLVER_DIRECT;
}

static SUNLinearSolver_ID lapack_getid(SUNLinearSolver S) {
  (void)S;
  return SUNLINEARSOLVER_LAPACKDENSE;
}

static int lapack_initialize(SUNLinearSolver S) {
  ((lapack_content *)S->content)->last_flag = 0;
  return SUNLS_SUCCESS;
}

/* Factorises A in place (as SUNLinSol_Dense does). A singular pivot is a
 * recoverable failure: KINSOL then reports it rather than stepping blindly. */
static int lapack_setup(SUNLinearSolver S, SUNMatrix A) {
  lapack_content *c = S->content;
  int n = c->n, info = 0;
  if (SUNDenseMatrix_Rows(A) != n) return SUNLS_ILL_INPUT;
  dgetrf_(&n, &n, SUNDenseMatrix_Data(A), &n, c->pivots, &info);
  c->last_flag = info;
  if (info < 0) return SUNLS_PACKAGE_FAIL_UNREC;
  if (info > 0) return SUNLS_LUFACT_FAIL;
  return SUNLS_SUCCESS;
}

static int lapack_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, realtype tol) {
  (void)tol;
  lapack_content *c = S->content;
  int n = c->n, one = 1, info = 0;
  N_VScale(1.0, b, x);
  dgetrs_("N", &n, &one, SUNDenseMatrix_Data(A), &n, c->pivots, N_VGetArrayPointer(x), &n, &info,
          1);
  c->last_flag = info;
  return info == 0 ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_UNREC;
}

static sunindextype lapack_lastflag(SUNLinearSolver S) {
  return ((lapack_content *)S->content)->last_flag;
}

static int lapack_space(SUNLinearSolver S, long *lenrw, long *leniw) {
  *lenrw = 0;
  *leniw = 2 + ((lapack_content *)S->content)->n;
  return SUNLS_SUCCESS;
}

static int lapack_free(SUNLinearSolver S) {
  if (!S) return SUNLS_SUCCESS;
  if (S->content) {
    free(((lapack_content *)S->content)->pivots);
    free(S->content);
    S->content = NULL;
  }
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

SUNLinearSolver vl_linsol_lapack_create(long n, SUNContext ctx) {
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return NULL;
  lapack_content *c = calloc(1, sizeof *c);
  if (!c) {
    SUNLinSolFreeEmpty(S);
    return NULL;
  }
  c->n = (int)n;
  c->pivots = malloc((size_t)n * sizeof *c->pivots);
  S->content = c;
  if (!c->pivots) {
    lapack_free(S);
    return NULL;
  }
  S->ops->gettype = lapack_gettype;
  S->ops->getid = lapack_getid;
  S->ops->initialize = lapack_initialize;
  S->ops->setup = lapack_setup;
  S->ops->solve = lapack_solve;
  S->ops->lastflag = lapack_lastflag;
  S->ops->space = lapack_space;
  S->ops->free = lapack_free;
  return S;
}
