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

#include "kernel.h"
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

/* ---- the active-set Newton's update of one LU (set_rows with a matrix
 * generation): Sherman-Morrison-Woodbury for the cells that left the base
 * set, bordering for those that joined ---- */

/* A sequence of systems as the active-set Newton builds them: nc cells and
 * a last unknown (the rigid approach); the rows of the cells in the set and
 * the last row are those of F (column-major, (nc + 1)^2, the same while
 * the generation stays), every other cell's row is its own (P_i = 0: 1 on
 * the diagonal, exact zeros elsewhere), as d/dU says (du). */
typedef struct {
  int nc, n;
  const double *F;
  SUNContext ctx;
  SUNMatrix A;
  N_Vector x, b;
  SUNLinearSolver LS;
  double *du, *copy, *ref;
  int *piv;
  bool on;
  size_t generation;
} update_case;

static void update_case_open(update_case *u, int nc, const double *F) {
  u->nc = nc, u->n = nc + 1, u->F = F;
  assert_int_equal(SUNContext_Create(NULL, &u->ctx), 0);
  u->A = SUNDenseMatrix(u->n, u->n, u->ctx);
  u->x = N_VNew_Serial(u->n, u->ctx), u->b = N_VNew_Serial(u->n, u->ctx);
  u->LS = vl_linsol_reduced_create(u->n, u->ctx);
  size_t N = (size_t)u->n;
  u->du = calloc(N, sizeof *u->du);
  u->copy = malloc(N * N * sizeof *u->copy);
  u->ref = malloc(N * sizeof *u->ref);
  u->piv = malloc(N * sizeof *u->piv);
  assert_non_null(u->A), assert_non_null(u->LS), assert_non_null(u->du), assert_non_null(u->copy);
  assert_non_null(u->ref), assert_non_null(u->piv);
  u->on = true, u->generation = 1;
  vl_linsol_reduced_set_rows(u->LS, u->du, nc, &u->on, &u->generation);
}

static void update_case_close(update_case *u) {
  SUNLinSolFree(u->LS);
  N_VDestroy(u->x), N_VDestroy(u->b);
  SUNMatDestroy(u->A);
  SUNContext_Free(&u->ctx);
  free(u->du), free(u->copy), free(u->ref), free(u->piv);
}

/* The system of the set in[] (nc flags), solved by the reduced solver and
 * by LAPACK's LU of the whole matrix: returns the largest difference
 * relative to max |x|, and what the set-up did in *how. */
static double update_solve(update_case *u, const bool *in, unsigned seed, vl_reduced_setup *how) {
  int n = u->n, one = 1, info = 0;
  size_t N = (size_t)n;
  double *a = SUNDenseMatrix_Data(u->A), *bd = N_VGetArrayPointer(u->b);
  for (int i = 0; i < n; i++) {
    bool coupled = i == u->nc || in[i];
    if (i < u->nc) u->du[i] = in[i] ? 1.0 : 0.0;
    for (int j = 0; j < n; j++) {
      size_t at = (size_t)j * N + (size_t)i;
      a[at] = coupled ? u->F[at] : (i == j ? 1.0 : 0.0);
    }
    bd[i] = uniform(&seed) - 0.5;
  }
  memcpy(u->copy, a, N * N * sizeof *a);
  memcpy(u->ref, bd, N * sizeof *bd);
  dgesv_(&n, &one, u->copy, &n, u->piv, u->ref, &n, &info);
  assert_int_equal(info, 0);
  assert_int_equal(SUNLinSolSetup(u->LS, u->A), SUNLS_SUCCESS);
  *how = vl_linsol_reduced_last_setup(u->LS);
  assert_int_equal(SUNLinSolSolve(u->LS, u->A, u->x, u->b, 0.0), SUNLS_SUCCESS);
  return vl_test_max_rel_diff(N_VGetArrayPointer(u->x), u->ref, N);
}

/* Cells lo <= i < hi in the set, the others out. */
static void set_range(bool *in, int nc, int lo, int hi) {
  for (int i = 0; i < nc; i++)
    in[i] = i >= lo && i < hi;
}

/* One step of a sequence: the set, what the set-up must do, the error
 * bound. */
static void update_step(update_case *u, const bool *in, vl_reduced_setup want, double bound,
                        unsigned seed) {
  vl_reduced_setup how;
  double err = update_solve(u, in, seed, &how);
  assert_int_equal(how, want);
  if (!(err <= bound)) fail_msg("set-up %d: %.3g above %.3g", (int)how, err, bound);
}

/* The sequence both matrices go through: a base, cells leaving (the
 * update's columns kept from step to step), cells joining and leaving,
 * cells coming back, a hole, more changes than the update takes (a new
 * base), a new matrix generation (a new base). */
static void update_sequence(update_case *u, double bound) {
  int nc = u->nc, q = nc / 8; /* 240 cells: q = 30 */
  assert_int_equal(nc, 240);
  bool *in = calloc((size_t)nc, sizeof *in);
  assert_non_null(in);
  set_range(in, nc, 2 * q, 6 * q); /* half the cells: the base */
  update_step(u, in, VL_REDUCED_BASE, bound, 1u);
  set_range(in, nc, 2 * q + 3, 6 * q - 2); /* 5 leave */
  update_step(u, in, VL_REDUCED_UPDATED, bound, 2u);
  set_range(in, nc, 2 * q + 6, 6 * q + 4); /* 3 more leave, 2 come back, 4 join */
  update_step(u, in, VL_REDUCED_UPDATED, bound, 3u);
  set_range(in, nc, 2 * q + 1, 6 * q + 4); /* 5 of those that left come back */
  in[4 * q] = in[4 * q + 1] = false;       /* a hole: two runs */
  update_step(u, in, VL_REDUCED_UPDATED, bound, 4u);
  set_range(in, nc, q, 7 * q); /* 60 joined the base's set: the update takes 64 */
  update_step(u, in, VL_REDUCED_UPDATED, bound, 5u);
  set_range(in, nc, 5 * q, 8 * q); /* most of them left: a new base */
  update_step(u, in, VL_REDUCED_BASE, bound, 6u);
  set_range(in, nc, 5 * q + 2, 8 * q);
  update_step(u, in, VL_REDUCED_UPDATED, bound, 7u);
  u->generation++; /* a new matrix (here the same values): a new base */
  update_step(u, in, VL_REDUCED_BASE, bound, 8u);
  assert_int_equal(vl_linsol_reduced_fallbacks(u->LS), 0); /* no update failed its check */
  free(in);
}

/* A random well-conditioned matrix (the coupled rows diagonally dominant;
 * condition numbers ~300 in the 1-norm with the cells' own rows): the
 * update gives the whole LU's solution to 1e-14 of max |x|. Two backward-
 * stable solves may differ by ~2 kappa eps = 7e-14 here; both the base and
 * the updates measured 1e-17 to 3e-17 (OpenBLAS, 2026-11): an update that
 * loses accuracy (a capacitance matrix badly conditioned, a column missed)
 * shows above 1e-14. */
static void test_update_random(void **state) {
  (void)state;
  int nc = 240, n = nc + 1;
  size_t N = (size_t)n;
  double *F = malloc(N * N * sizeof *F);
  assert_non_null(F);
  unsigned seed = 11u;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++)
      F[(size_t)j * N + (size_t)i] = i == j ? (double)n : uniform(&seed) - 0.5;
  update_case u;
  update_case_open(&u, nc, F);
  update_sequence(&u, 1e-14);
  update_case_close(&u);
  free(F);
}

/* The active-set Newton's own matrix: the gap rows of a viscoelastic
 * rolling contact (the influence coefficients of one Prony term, Einf/E0 =
 * 10, v0 tau = a0: the middle of the transition, where the kernel is least
 * symmetric) on 240 cells over [-1.5, 1.5] a0, 1 in the rigid approach's
 * column, and the load row (cell widths / (pi/2)). Condition numbers 2e5
 * to 4.5e5 (1-norm): two backward-stable solves may differ by ~1e-10; the
 * base LU and the updates measured 1e-14 to 4e-14 of max |x| against the
 * whole LU, held to 1e-12 (an update 30 times less accurate than the
 * base's own LU fails). */
static void test_update_contact(void **state) {
  (void)state;
  int nc = 240, n = nc + 1;
  size_t N = (size_t)n;
  double delta = 3.0 / nc, A = 9.0, beta = 1.0, kfac = 1.0 / (M_PI * (1.0 + A));
  vl_toeplitz t;
  vl_error err;
  assert_int_equal(vl_toeplitz_build(&t, (size_t)nc, delta, &A, &beta, 1, &err), VL_OK);
  double *F = malloc(N * N * sizeof *F);
  assert_non_null(F);
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      double v;
      if (i < nc)
        v = j < nc ? -kfac * vl_toeplitz_at(&t, (size_t)i, (size_t)j) : 1.0;
      else
        v = j < nc ? delta / (0.5 * M_PI) : 0.0;
      F[(size_t)j * N + (size_t)i] = v;
    }
  vl_toeplitz_free(&t);
  update_case u;
  update_case_open(&u, nc, F);
  update_sequence(&u, 1e-12);
  update_case_close(&u);
  free(F);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_agrees_with_full_lu),
      cmocka_unit_test(test_dry_contact_same_as_lapack),
      cmocka_unit_test(test_update_random),
      cmocka_unit_test(test_update_contact),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
