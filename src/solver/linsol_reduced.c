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
  /* active-set Newton (hint on): the double LU of a base block (coupled set
   * c0, m0 of them) at the matrix generation *gen, updated for the cells
   * that left it (kr, positions rpos) and joined it (kn, indices nidx):
   * mode 1 solves with the base LU, mode 2 through the update, 0 as above */
  const size_t *gen;
  size_t gen0;
  bool have0;
  int mode, m0, kr, kn, zk; /* zk: valid columns of Z */
  char *zin;                /* n: base position a has its column in Z */
  int *c0, *pos0, *posn, *rpos, *nidx, *piv0, *pivc, *pivs;
  double *LU0, *Z, *cap, *AB, *Cm, *Sm, *y0, *yr;
} reduced_content;

/* Cells that may change set against the base LU before it is refactorised
 * (each costs two triangular solves at set-up, against m/3 for an LU). */
#define UPDATE_MAX 64

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

/* A new base: the block's double LU, kept while the matrix generation and
 * most of the set stay (mode 1). */
static int setup_base(reduced_content *c) {
  int m = c->m, info = 0;
  for (int a = 0; a < c->m0; a++)
    c->pos0[c->c0[a]] = -1;
  c->m0 = m;
  for (int a = 0; a < m; a++)
    c->c0[a] = c->coupled[a], c->pos0[c->coupled[a]] = a;
  memcpy(c->LU0, c->R, (size_t)m * (size_t)m * sizeof *c->R);
  dgetrf_(&m, &m, c->LU0, &m, c->piv0, &info);
  memset(c->zin, 0, (size_t)c->n);
  c->have0 = info == 0, c->gen0 = *c->gen, c->mode = 1, c->kr = c->kn = c->zk = 0;
  c->last_flag = info;
  if (info < 0) return SUNLS_PACKAGE_FAIL_UNREC;
  return info > 0 ? SUNLS_LUFACT_FAIL : SUNLS_SUCCESS;
}

/* Y (m0 x k) := A^-1 Y, A the base block with the rows of the cells that
 * left replaced by identity rows: B0^-1 Y corrected by Sherman-Morrison-
 * Woodbury, whose capacitance matrix is (B0^-1)_RR (cap, factorised). */
static void apply_inverse(reduced_content *c, double *Y, int k) {
  int m0 = c->m0, kr = c->kr, info = 0;
  for (int q = 0; q < k; q++)
    for (int p = 0; p < kr; p++)
      c->yr[p + q * kr] = Y[c->rpos[p] + q * m0];
  dgetrs_("N", &m0, &k, c->LU0, &m0, c->piv0, Y, &m0, &info, 1);
  if (kr == 0) return;
  for (int q = 0; q < k; q++) /* w = cap^-1 (z_R - y_R) */
    for (int p = 0; p < kr; p++)
      c->yr[p + q * kr] = Y[c->rpos[p] + q * m0] - c->yr[p + q * kr];
  dgetrs_("N", &kr, &k, c->cap, &kr, c->pivc, c->yr, &kr, &info, 1);
  double minus = -1.0, one = 1.0;
  dgemm_("N", "N", &m0, &k, &kr, &minus, c->Z, &m0, c->yr, &kr, &one, Y, &m0, 1, 1);
}

/* The set's cells against the base: those that left (kr) and joined (kn);
 * false when the base does not apply or too many changed. */
static bool set_changes(reduced_content *c) {
  if (!c->have0 || *c->gen != c->gen0) return false;
  size_t M0 = (size_t)c->m0;
  int k = 0;
  for (int p = 0; p < c->zk; p++) { /* Z's columns of cells still out, in order */
    int a = c->rpos[p];
    if (!c->free_row[c->c0[a]]) {
      c->zin[a] = 0;
      continue;
    }
    if (k != p) memcpy(c->Z + (size_t)k * M0, c->Z + (size_t)p * M0, M0 * sizeof *c->Z);
    c->rpos[k++] = a;
  }
  c->zk = k; /* the columns still valid; the new ones follow */
  for (int a = 0; a < c->m0; a++)
    if (c->free_row[c->c0[a]] && !c->zin[a]) {
      if (k == UPDATE_MAX) return false;
      c->rpos[k++] = a, c->zin[a] = 1;
    }
  c->kr = k, c->kn = 0;
  for (int a = 0; a < c->m; a++) {
    int i = c->coupled[a];
    if (c->pos0[i] >= 0) continue;
    if (c->kn == UPDATE_MAX) return false;
    c->posn[i] = c->kn, c->nidx[c->kn++] = i;
  }
  return true;
}

/* The update of the base for the set's changes (mode 2): Z = B0^-1 E_R (the
 * columns of the cells that left, kept from step to step: the set mostly
 * shrinks within a speed) and its capacitance matrix, then the joined
 * cells' bordering: AB = A^-1 J[C0, N] (rows R zero), Cm = J[N, C0],
 * Sm = J[N, N] - Cm AB, factorised. */
static int setup_update(reduced_content *c, const double *J) {
  if (!set_changes(c)) return setup_base(c);
  int m0 = c->m0, kr = c->kr, kn = c->kn, n = c->n, info = 0, fresh = kr - c->zk;
  size_t M0 = (size_t)m0;
  if (fresh > 0) {
    double *Zf = c->Z + (size_t)c->zk * M0;
    memset(Zf, 0, M0 * (size_t)fresh * sizeof *Zf);
    for (int p = 0; p < fresh; p++)
      Zf[(size_t)c->rpos[c->zk + p] + (size_t)p * M0] = 1.0;
    dgetrs_("N", &m0, &fresh, c->LU0, &m0, c->piv0, Zf, &m0, &info, 1);
  }
  c->zk = kr;
  if (kr > 0) {
    for (int q = 0; q < kr; q++)
      for (int p = 0; p < kr; p++)
        c->cap[p + q * kr] = c->Z[(size_t)c->rpos[p] + (size_t)q * M0];
    dgetrf_(&kr, &kr, c->cap, &kr, c->pivc, &info);
    if (info != 0) return setup_base(c);
  }
  for (int q = 0; q < kn; q++) {
    const double *col = J + (size_t)c->nidx[q] * (size_t)n;
    for (int a = 0; a < m0; a++)
      c->AB[(size_t)a + (size_t)q * M0] = c->free_row[c->c0[a]] ? 0.0 : col[c->c0[a]];
  }
  if (kn > 0) {
    apply_inverse(c, c->AB, kn);
    for (int a = 0; a < m0; a++) {
      const double *col = J + (size_t)c->c0[a] * (size_t)n;
      for (int p = 0; p < kn; p++)
        c->Cm[(size_t)p + (size_t)a * (size_t)kn] = col[c->nidx[p]];
    }
    for (int q = 0; q < kn; q++)
      for (int p = 0; p < kn; p++)
        c->Sm[p + q * kn] = J[(size_t)c->nidx[q] * (size_t)n + (size_t)c->nidx[p]];
    double minus = -1.0, one = 1.0;
    dgemm_("N", "N", &kn, &kn, &m0, &minus, c->Cm, &kn, c->AB, &m0, &one, c->Sm, &kn, 1, 1);
    dgetrf_(&kn, &kn, c->Sm, &kn, c->pivs, &info);
    if (info != 0) return setup_base(c);
  }
  c->mode = 2;
  c->last_flag = 0;
  return SUNLS_SUCCESS;
}

/* The coupled unknowns through the base LU (mode 1) or its update (mode
 * 2), checked against the block itself (R): the block's own double LU
 * where the update lost accuracy. */
static int solve_update(reduced_content *c, double *x) {
  int m = c->m, m0 = c->m0, kn = c->kn, one = 1, info = 0;
  double *y0 = c->y0, *xn = c->y0 + m0, minus = -1.0, plus = 1.0;
  memcpy(c->r, c->rhs, (size_t)m * sizeof *c->r);
  if (c->mode == 1) {
    dgetrs_("N", &m, &one, c->LU0, &m, c->piv0, c->rhs, &m, &info, 1);
  } else {
    memset(y0, 0, (size_t)m0 * sizeof *y0);
    for (int a = 0; a < m; a++) {
      int i = c->coupled[a];
      if (c->pos0[i] >= 0)
        y0[c->pos0[i]] = c->rhs[a];
      else
        xn[c->posn[i]] = c->rhs[a];
    }
    apply_inverse(c, y0, 1);
    if (kn > 0) {
      dgemv_("N", &kn, &m0, &minus, c->Cm, &kn, y0, &one, &plus, xn, &one, 1);
      dgetrs_("N", &kn, &one, c->Sm, &kn, c->pivs, xn, &kn, &info, 1);
      dgemv_("N", &m0, &kn, &minus, c->AB, &m0, xn, &one, &plus, y0, &one, 1);
    }
    for (int a = 0; a < m; a++) {
      int i = c->coupled[a];
      c->rhs[a] = c->pos0[i] >= 0 ? y0[c->pos0[i]] : xn[c->posn[i]];
    }
    /* r - R x: the update's accuracy (the base LU itself is exact to a
     * double LU's backward error) */
    double *res = c->x;
    memcpy(res, c->r, (size_t)m * sizeof *res);
    dgemv_("N", &m, &m, &minus, c->R, &m, c->rhs, &one, &plus, res, &one, 1);
    double rnrm = 0.0, xnrm = 0.0;
    for (int a = 0; a < m; a++) {
      rnrm = fabs(res[a]) > rnrm ? fabs(res[a]) : rnrm;
      xnrm = fabs(c->rhs[a]) > xnrm ? fabs(c->rhs[a]) : xnrm;
    }
    if (!(rnrm <= 1e3 * c->anrm * xnrm * DBL_EPSILON * sqrt((double)m))) {
      memcpy(c->rhs, c->r, (size_t)m * sizeof *c->rhs);
      if (factorise_double(c) != 0) return SUNLS_PACKAGE_FAIL_UNREC;
      dgetrs_("N", &m, &one, c->R, &m, c->piv, c->rhs, &m, &info, 1);
    }
  }
  c->last_flag = info;
  if (info != 0) return SUNLS_PACKAGE_FAIL_UNREC;
  for (int a = 0; a < m; a++)
    x[c->coupled[a]] = c->rhs[a];
  return SUNLS_SUCCESS;
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
  c->mode = 0;
  if (m > 0 && c->gen && c->hint_on && *c->hint_on) return setup_update(c, J);
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
  if (c->mode) return solve_update(c, x);
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
    free(c->c0);
    free(c->pos0);
    free(c->nidx);
    free(c->LU0);
    free(c->zin);
    free(c->Z);
    free(c);
    S->content = NULL;
  }
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

void vl_linsol_reduced_set_rows(SUNLinearSolver S, const double *du, long n, const bool *on,
                                const size_t *generation) {
  reduced_content *c = S->content;
  c->hint_du = du, c->hint_n = (int)n, c->hint_on = on, c->gen = generation;
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
  c->m0 = 0;
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
  size_t K = UPDATE_MAX;
  c->c0 = malloc(N * sizeof *c->c0);
  c->pos0 = malloc(4 * N * sizeof *c->pos0);
  c->posn = c->pos0 ? c->pos0 + N : NULL;
  c->piv0 = c->pos0 ? c->pos0 + 2 * N : NULL;
  c->rpos = c->pos0 ? c->pos0 + 3 * N : NULL;
  c->nidx = malloc(3 * K * sizeof *c->nidx);
  c->pivc = c->nidx ? c->nidx + K : NULL;
  c->pivs = c->nidx ? c->nidx + 2 * K : NULL;
  c->LU0 = malloc(N * N * sizeof *c->LU0);
  c->zin = calloc(N, 1);
  c->Z = malloc((3 * N * K + 3 * K * K + 2 * N) * sizeof *c->Z);
  c->AB = c->Z ? c->Z + N * K : NULL;
  c->Cm = c->Z ? c->Z + 2 * N * K : NULL;
  c->cap = c->Z ? c->Z + 3 * N * K : NULL;
  c->Sm = c->Z ? c->cap + K * K : NULL;
  c->y0 = c->Z ? c->Sm + K * K : NULL; /* m0 + kn */
  c->yr = c->Z ? c->y0 + 2 * N : NULL; /* kr x k, both at most K */
  if (c->pos0)
    for (size_t i = 0; i < N; i++)
      c->pos0[i] = -1;
  if (!c->c0 || !c->zin || !c->pos0 || !c->nidx || !c->LU0 || !c->Z || !c->coupled || !c->runs ||
      !c->free_row || !c->off || !c->R || !c->RS || !c->rf || !c->x || !c->piv || !c->rhs) {
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
