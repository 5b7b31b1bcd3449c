/* The Schur-complement linear solver of the rough wet Jacobian
 * (src/solver/linsol_schur.h, private) against LAPACK's full
 * LU, on synthetic systems with the contact's block structure and on the
 * real fig05 contact. */
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

#include "contact_test.h"
#include "linsol_schur.h"
#include "sweep_internal.h"
#include "viscolube/contact.h"
#include "viscolube/persson.h"
#include "viscolube/sweep.h"
#include "vl_test_scenes.h"
#include "vl_test_util.h"

extern void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv, double *b,
                   const int *ldb, int *info);

static double uniform(unsigned *s) {
  *s = *s * 1103515245u + 12345u;
  return (double)((*s >> 8) & 0xffffff) / 16777216.0;
}

typedef enum { M_MATRIX, NEGATIVE_PIVOT, OFF_TRIDIAGONAL } kind;

/* A (2n+1)^2 system laid out as the rough wet contact's: rows/columns
 * 0..n-1 separation, n..2n-1 fluid pressure, 2n rigid approach. Elasticity
 * rows: I - M D on u, -kappa M on pf, -1 on h0 (M dense, decaying off the
 * diagonal like the kernel); Reynolds rows: banded on u (i-2..i+1),
 * tridiagonal M-matrix on pf (Fischer-Burmeister weights da, db >= 0);
 * load row: positive weights. `k` breaks the structure on purpose. */
static void build(double *J, int n, kind k, unsigned seed) {
  int N = 2 * n + 1;
  memset(J, 0, (size_t)N * (size_t)N * sizeof *J);
#define E(r, c) J[(size_t)(c) * (size_t)N + (size_t)(r)]
  for (int i = 0; i < n; i++) {
    for (int j = 0; j < n; j++) {
      double m = 1.0 / (1.0 + fabs((double)(i - j))) * (0.5 + uniform(&seed));
      E(i, j) = (i == j) - m * (1.0 + 10.0 * uniform(&seed));
      E(i, n + j) = -1e-3 * m;
    }
    E(i, 2 * n) = -1.0;
  }
  for (int i = 0; i < n; i++) {
    double da = uniform(&seed) < 0.3 ? 1.0 : 1e-6, db = 1.0 - 0.5 * da;
    double gl = 0.1 + uniform(&seed), gr = 0.1 + uniform(&seed);
    E(n + i, n + i) = da + db * (gl + gr);
    if (i > 0) E(n + i, n + i - 1) = -db * gl;
    if (i + 1 < n) E(n + i, n + i + 1) = -db * gr;
    for (int q = -2; q <= 1; q++)
      if (i + q >= 0 && i + q < n) E(n + i, i + q) = db * (uniform(&seed) - 0.5);
  }
  for (int j = 0; j < 2 * n; j++)
    E(2 * n, j) = 0.01 * (1.0 + uniform(&seed));
  if (k == NEGATIVE_PIVOT) E(n + n / 2, n + n / 2) = -E(n + n / 2, n + n / 2);
  if (k == OFF_TRIDIAGONAL) E(n + 3, n + 9) = 0.5;
#undef E
}

/* Solves with the Schur solver (C's band declared as lower, upper when
 * lower >= 0) and with dgesv; returns the largest |x_schur - x_lapack| / max
 * |x_lapack| and the fallback count. */
static double compare_band(int n, kind k, int lower, int upper, long *fallbacks) {
  SUNContext ctx;
  assert_int_equal(SUNContext_Create(NULL, &ctx), 0);
  int N = 2 * n + 1, one = 1, info = 0;
  SUNMatrix A = SUNDenseMatrix(N, N, ctx);
  N_Vector x = N_VNew_Serial(N, ctx), b = N_VNew_Serial(N, ctx);
  build(SUNDenseMatrix_Data(A), n, k, 12345u + (unsigned)n);
  unsigned seed = 99;
  double *bd = N_VGetArrayPointer(b);
  for (int i = 0; i < N; i++)
    bd[i] = uniform(&seed) - 0.5;
  /* reference: LAPACK on copies */
  double *Ac = malloc((size_t)N * (size_t)N * sizeof *Ac), *xr = malloc((size_t)N * sizeof *xr);
  int *piv = malloc((size_t)N * sizeof *piv);
  memcpy(Ac, SUNDenseMatrix_Data(A), (size_t)N * (size_t)N * sizeof *Ac);
  memcpy(xr, bd, (size_t)N * sizeof *xr);
  dgesv_(&N, &one, Ac, &N, piv, xr, &N, &info);
  assert_int_equal(info, 0);
  double *Acopy = malloc((size_t)N * (size_t)N * sizeof *Acopy);
  memcpy(Acopy, SUNDenseMatrix_Data(A), (size_t)N * (size_t)N * sizeof *Acopy);

  SUNLinearSolver LS = vl_linsol_schur_create(n, n, 2 * n, ctx);
  assert_non_null(LS);
  if (lower >= 0) vl_linsol_schur_set_band(LS, lower, upper);
  assert_int_equal(SUNLinSolSetup(LS, A), 0);
  assert_int_equal(SUNLinSolSolve(LS, A, x, b, 0.0), 0);
  /* the matrix is left as it was (the fallback and the check need it) */
  assert_memory_equal(Acopy, SUNDenseMatrix_Data(A), (size_t)N * (size_t)N * sizeof *Acopy);
  double rel = vl_test_max_rel_diff(N_VGetArrayPointer(x), xr, (size_t)N);
  *fallbacks = vl_linsol_schur_fallbacks(LS);
  SUNLinSolFree(LS);
  free(Ac), free(xr), free(piv), free(Acopy);
  N_VDestroy(x), N_VDestroy(b);
  SUNMatDestroy(A);
  SUNContext_Free(&ctx);
  return rel;
}

static double compare(int n, kind k, long *fallbacks) {
  return compare_band(n, k, -1, -1, fallbacks);
}

/* The block elimination is exact algebra: with an M-matrix pivot block it
 * agrees with partial-pivoting LU to rounding. Tolerance 1e-11: the
 * condition numbers of these systems are ~1e3, so both solutions carry
 * ~1e-13 of error; the solver's own acceptance is a residual of 1e-10. */
static void test_agrees_with_full_lu(void **state) {
  (void)state;
  int sizes[] = {2, 3, 17, 64, 200};
  for (size_t s = 0; s < sizeof sizes / sizeof *sizes; s++) {
    long fb = -1;
    double e = compare(sizes[s], M_MATRIX, &fb);
    assert_true(e < 1e-11);
    assert_int_equal(fb, 0); /* no fallback needed */
  }
}

/* A Reynolds block that is not an M-matrix (a negative pivot) or that has
 * an entry off the three diagonals is not eliminated blindly: the solver
 * falls back to the full LU (counted) and still returns the right answer. */
static void test_falls_back_when_structure_breaks(void **state) {
  (void)state;
  long fb = 0;
  double e = compare(64, NEGATIVE_PIVOT, &fb);
  assert_true(e < 1e-11);
  assert_int_equal(fb, 1);
  e = compare(64, OFF_TRIDIAGONAL, &fb);
  assert_true(e < 1e-11);
  assert_int_equal(fb, 1);
}

/* C's declared band (build(): column j of C is nonzero in rows j-1 .. j+2,
 * the contact's stencil): with the true band the solve reads only the band
 * and agrees with the full LU without a fallback; with a band too narrow
 * (entries left out of the Schur complement) the residual check sends it to
 * the full LU, and the answer is still right. */
static void test_declared_band(void **state) {
  (void)state;
  long fb = -1;
  double e = compare_band(200, M_MATRIX, 1, 2, &fb);
  assert_true(e < 1e-11);
  assert_int_equal(fb, 0);
  e = compare_band(200, M_MATRIX, 0, 1, &fb);
  assert_true(e < 1e-11);
  assert_int_equal(fb, 1);
}

/* Layouts other than contact.c's are refused. */
static void test_bad_layout(void **state) {
  (void)state;
  SUNContext ctx;
  assert_int_equal(SUNContext_Create(NULL, &ctx), 0);
  assert_null(vl_linsol_schur_create(1, 1, 2, ctx));
  assert_null(vl_linsol_schur_create(10, 11, 20, ctx));
  assert_null(vl_linsol_schur_create(10, 10, 21, ctx));
  SUNContext_Free(&ctx);
}

/* The real rough wet contact (fig05 scene, N 128): the Schur solver gives
 * the same Stribeck points as the full LAPACK LU (same Newton path up to
 * rounding: mu within 1e-8 relative, an order above the 1e-9 residual
 * tolerance's effect on mu) and never needs its fallback, which proves the
 * contact's Reynolds block is tridiagonal and an M-matrix along the way. */
static void test_fig05_same_as_lapack(void **state) {
  (void)state;
  vl_psd psd;
  vl_persson *tab;
  vl_error err;
  tab = vl_test_paper_surface(3e-6, &psd);
  enum { NP = 13 };
  double v0[NP];
  for (int i = 0; i < NP; i++)
    v0[i] = 1e-8 * pow(10.0, (double)i); /* v0 eta 1e-12 ... 1 Pa m */
  vl_point pts[2][NP];
  long fallbacks = -1;
  for (int k = 0; k < 2; k++) {
    vl_contact_config cfg;
    vl_test_fig05_config(&cfg, tab, 1e-4, 128, -3.0);
    cfg.linear_solver = k ? VL_LINSOL_LAPACK : VL_LINSOL_SCHUR;
    vl_contact *c;
    assert_int_equal(vl_contact_create(&cfg, &c, &err), VL_OK);
    vl_sweep_stats st;
    assert_int_equal(vl_sweep_run(c, NP, v0, NULL, pts[k], NULL, NULL, &st, &err), VL_OK);
    assert_int_equal(st.failed, 0);
    if (k == 0) {
      vl_contact_timing t;
      vl_contact_timing_get(c, &t);
      fallbacks = t.linsol_fallbacks;
    }
    vl_contact_free(c);
  }
  assert_int_equal(fallbacks, 0);
  for (int i = 0; i < NP; i++) {
    assert_true(pts[0][i].converged && pts[1][i].converged);
    assert_true(fabs(pts[0][i].mu - pts[1][i].mu) <= 1e-8 * pts[1][i].mu);
    assert_true(fabs(pts[0][i].u_min_m - pts[1][i].u_min_m) <= 1e-8 * pts[1][i].u_min_m);
  }
  vl_persson_free(tab);
  vl_psd_free(&psd);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_agrees_with_full_lu),
      cmocka_unit_test(test_falls_back_when_structure_breaks),
      cmocka_unit_test(test_declared_band),
      cmocka_unit_test(test_bad_layout),
      cmocka_unit_test(test_fig05_same_as_lapack),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
