/* The reduced (active-set) linear solver of the dry smooth contact
 * (src/solver/linsol_reduced.h, private) against LAPACK's full LU: on
 * synthetic systems with free rows, and on Hunter's dry rolling contact. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdlib.h>
#include <string.h>
#include <sundials/sundials_context.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "linsol_reduced.h"
#include "sweep_internal.h"
#include "viscolube/contact.h"
#include "viscolube/sweep.h"
#include "vl_test_scenes.h"
#include "vl_test_util.h"

extern void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv, double *b,
                   const int *ldb, int *info);

static double uniform(unsigned *s) {
  *s = *s * 1103515245u + 12345u;
  return (double)((*s >> 8) & 0xffffff) / 16777216.0;
}

/* An n x n system whose even rows (below n - 1) carry only their diagonal
 * plus off-diagonal entries of `leak` times it, the others dense and
 * diagonally dominant (as the cells out of contact and in contact).
 * Returns the largest |x_reduced - x_lu| / max|x_lu| and the reduced
 * size. */
static double compare(int n, double leak, long *reduced) {
  SUNContext ctx;
  assert_int_equal(SUNContext_Create(NULL, &ctx), 0);
  SUNMatrix A = SUNDenseMatrix(n, n, ctx);
  N_Vector x = N_VNew_Serial(n, ctx), b = N_VNew_Serial(n, ctx);
  double *a = SUNDenseMatrix_Data(A), *bd = N_VGetArrayPointer(b);
  unsigned seed = 7u;
  for (int i = 0; i < n; i++) {
    bool free_row = i % 2 == 0 && i < n - 1;
    double d = 1.0 + uniform(&seed);
    for (int j = 0; j < n; j++) {
      double v = uniform(&seed) - 0.5;
      a[(size_t)j * (size_t)n + (size_t)i] =
          i == j ? (free_row ? d : (double)n) : (free_row ? leak * d * v : v);
    }
    bd[i] = uniform(&seed) - 0.5;
  }
  double *copy = malloc((size_t)n * (size_t)n * sizeof *copy), *xr = malloc((size_t)n * sizeof *xr);
  int *piv = malloc((size_t)n * sizeof *piv), one = 1, info = 0;
  assert_non_null(copy), assert_non_null(xr), assert_non_null(piv);
  memcpy(copy, a, (size_t)n * (size_t)n * sizeof *copy);
  memcpy(xr, bd, (size_t)n * sizeof *xr);
  dgesv_(&n, &one, copy, &n, piv, xr, &n, &info);
  assert_int_equal(info, 0);
  SUNLinearSolver LS = vl_linsol_reduced_create(n, ctx);
  assert_non_null(LS);
  assert_int_equal(SUNLinSolSetup(LS, A), SUNLS_SUCCESS);
  assert_int_equal(SUNLinSolSolve(LS, A, x, b, 0.0), SUNLS_SUCCESS);
  *reduced = vl_linsol_reduced_size(LS);
  double rel = vl_test_max_rel_diff(N_VGetArrayPointer(x), xr, (size_t)n);
  SUNLinSolFree(LS);
  free(copy), free(xr), free(piv);
  N_VDestroy(x), N_VDestroy(b);
  SUNMatDestroy(A);
  SUNContext_Free(&ctx);
  return rel;
}

/* Free rows with exact zeros off the diagonal: the elimination is exact
 * algebra (1e-12: both solutions carry rounding of ~1e-14 at these
 * condition numbers). Leaks at 1e-15 of the diagonal are dropped (the
 * step then changes by ~1e-15); at 1e-9 they are kept (the row stays
 * coupled) and the answer is still the full LU's. */
static void test_agrees_with_full_lu(void **state) {
  (void)state;
  const int sizes[] = {2, 3, 17, 200};
  long m = -1;
  assert_true(compare(1, 0.0, &m) < 1e-12); /* a 1 x 1 system: its row is free */
  assert_int_equal(m, 0);
  for (size_t s = 0; s < sizeof sizes / sizeof *sizes; s++) {
    int n = sizes[s];
    assert_true(compare(n, 0.0, &m) < 1e-12);
    assert_int_equal(m, n - n / 2); /* the even rows below n - 1 are free */
    assert_true(compare(n, 1e-15, &m) < 1e-12);
    assert_int_equal(m, n - n / 2);
    assert_true(compare(n, 1e-9, &m) < 1e-12);
    assert_int_equal(m, n);
  }
}

/* Hunter's dry rolling contact (the model rubber, N 400 on [-1.5, 1.5]
 * a0): the reduced solver, the default, gives the points of the full LU
 * (mu within 1e-10 relative: the dropped entries are ~1e-14 of their
 * rows; the tolerance is 1e-9 in the residual) in the same iterations. */
static void test_dry_contact_same_as_lapack(void **state) {
  (void)state;
  enum { NP = 9 };
  double v0[NP];
  for (int i = 0; i < NP; i++)
    v0[i] = 1.6e-5 * pow(10.0, 0.75 * (double)i); /* Deborah 1e-3 ... 1e3 */
  vl_point pts[2][NP];
  vl_error err;
  for (int k = 0; k < 2; k++) {
    vl_contact_config cfg;
    vl_test_fig05_config(&cfg, NULL, 0.0, 400, -1.5);
    cfg.sigma_s_pa = 0.0;
    cfg.x_max_a0 = 1.5;
    cfg.tolerance = 1e-9;
    cfg.linear_solver = k ? VL_LINSOL_LAPACK : VL_LINSOL_SCHUR;
    vl_contact *c;
    assert_int_equal(vl_contact_create(&cfg, &c, &err), VL_OK);
    vl_sweep_stats st;
    assert_int_equal(vl_sweep_run(c, NP, v0, NULL, pts[k], NULL, NULL, &st, &err), VL_OK);
    assert_int_equal(st.failed, 0);
    vl_contact_free(c);
  }
  for (int i = 0; i < NP; i++) {
    assert_true(pts[0][i].converged && pts[1][i].converged);
    assert_true(fabs(pts[0][i].mu - pts[1][i].mu) <= 1e-10 * pts[1][i].mu);
    assert_int_equal(pts[0][i].iterations, pts[1][i].iterations);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_agrees_with_full_lu),
      cmocka_unit_test(test_dry_contact_same_as_lapack),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
