/* The persson-emt flow and shear-stress factors (FLOW_FACTORS.md, model
 * `persson-emt`; flow_factors_emt.h). All lengths inside are in units of
 * h_rms, so u = x.
 *
 * Gap distribution at one x. With s = pc/|Er| and M(q) = \int_{q0}^{q} q'^3 C,
 * everything is a function of the magnification through y = ln M(zeta q0):
 *   A(y)    = erf(z),  z = s / sqrt(pi e^y)                        (Eq. 7)
 *   ubar(y) = Eq. 8 for the roughness q > zeta q0 alone (its own M, from
 *             zeta q0) at the pressure p = s/A(y):
 *           = (1/2) \int_y^{y_max} e^{y'} / (q sqrt(dM)) E1(p^2/(pi dM)) dy',
 *             dM = e^{y'} - e^{y}
 * (Eq. 8's inner integral done in closed form, dq = e^y dy/(q^3 C): smooth
 * in y'; the integrand vanishes with all its derivatives at y' = y.) At
 * zeta = 1 this is Persson's u(s), and s is its root for u = x.
 *   This sub-surface reading of Eq. 8 (not Persson's ubar(zeta), whose w(q)
 * keeps M from q0) is what the FLOW_FACTORS.md table was computed with: it
 * reproduces the table's x >= 1 rows to 1e-4. It has a consequence the
 * definition leaves open: removing the longest wavelengths lowers ubar
 * while A/A0 is still ~1, so the first components to detach carry
 * u1 = d(A ubar)/dA of tens to 1e6 h_rms on masses of 1e-9 to 1e-4 (at
 * x <= 0.3 for the seed surface), far beyond any gap of a Gaussian surface.
 * The bins end at G_BODY = VL_EMT_X_MAX + 10 h_rms, beyond every gap the
 * table's separations can have, and what lies beyond is dropped (the mean
 * rescale hands its share of u to the rest). That is what the table's
 * x = 0.1 and 0.3 rows (and its "1.72x at x = 0.1") were computed with;
 * keeping the tail instead lowers phi_p there by 1.4e-3 and 2.5e-3. The
 * price: the factors step where a component's u1 crosses G_BODY, e.g.
 * phi_p of the seed surface is 0.0939 at x = 0.295 and 0.0927 at x = 0.3
 * (between two table nodes, which the interpolant smooths over).
 *
 * Components. The grid is uniform in y from y_pool, where hr^2 = (1 - 0.075)
 * h_rms^2, to y_max = ln M(q1) (N_Y intervals). Everything that detaches
 * before y_pool is one component, which is exactly the set repair (1) pools
 * by hr (its hr^2 mass-weighted on a finer grid below y_pool), so the grid
 * spends no points there. Each interval gives dA = A_i - A_{i+1} (from erfc,
 * exact when A ~ 1), the mean u1 = (A_i ubar_i - A_{i+1} ubar_{i+1})/dA and
 * hr^2 at the interval's mid-point; repair (1) then pools runs lighter than
 * POOL_MASS (the mean from the telescoped sum, so exactly preserved).
 *
 * Quadrature. Each grid node needs its own ubar integral (p and the lower
 * limit differ): N_Y^2 E1 evaluations per x, so E1(e^v) is a cubic Hermite
 * table in v with exact slopes (1e-12 absolute), built with the workspace.
 * Gauss-Legendre, 2 points per grid interval (<= 0.05 wide in y, where the
 * integrand varies on a scale of 0.1-1; the result moves by < 1e-6 from 200
 * to 1600 intervals); on a uniform grid ln(dM/e^{y'}) depends on the node's
 * offset from y only, so it is a table too. Persson's u(s) integrates also
 * below y_pool (4 points per EXT_DY) down to EXT_SPAN below y_max: the
 * integrand carries e^{y/2}, what lies below is < 1e-15 of u. Checked
 * against vl_persson_separation_exact of the truncated surface (1e-12).
 *
 * Binning (repair 2). Each component is a normal N(u1, hr^2) reflected at 0.
 * Fixed bins: [0, G_FIRST], then N_BINS geometric bins to G_BODY (1.2 %
 * wide). Masses are differences of the normal cdf at the edges (a Hermite
 * table of Phi, 1e-13 absolute); below TAYLOR_EPS hr, where the density is
 * flat (it is even in g), its Taylor series to g^2 integrated exactly,
 * accumulated over components (else each would cost an erfc per bin down to
 * G_FIRST). A bin's gap is its mid-point; the gaps are then scaled so the
 * mean of P is u. The film cut-off counts the bin it falls in by the share
 * of the bin above it, so phi_f is continuous in x (an all-or-nothing bin
 * would make it jump by ~1 % from one x to the next).
 *
 * The table. Nodes geometric in x from x_perc/X_BELOW_PERC to VL_EMT_X_MAX,
 * the node nearest the percolation point x_perc moved onto it (phi_p and
 * phi_fp are set to exactly 0 there, the medium's limit). phi_p, phi_fp,
 * phi_fs, phi_f are interpolated in ln x by monotone cubic Hermite
 * (Fritsch-Butland slopes: C1, no overshoot, zero slope at the percolation
 * kink); phi_s = x (1 - phi_fp) is derived, so the reciprocity identity
 * holds everywhere, inside and out. Above the table the Tripp forms
 *   phi_p = 1 - a/x^2, phi_fp = 1 - a/x^2, phi_fs = a/x^2, phi_f = 1 + a/x^2
 * (hence phi_s = a_fp/x), each a matched to the last node's value; the
 * interpolant's slope at that node is the tail's (2 (1 - phi) etc. in ln x),
 * so the whole curve is C1. Below the table (two decades under percolation)
 * phi_p = phi_fp = 0 (they are 0 at the first nodes already), and phi_fs,
 * phi_f continue as the power laws phi_0 (x/x_0)^k with k = the
 * interpolant's end slope d ln phi/d ln x (C1 by construction). */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h> /* M_PI, which strict C17 <math.h> lacks */
#include <gsl/gsl_sf_expint.h>

#include "blob.h"
#include "bracket.h"
#include "flow_factors_emt.h"
#include "roughness_internal.h"

#define POOL_MASS 1e-9                     /* repair 1: lighter components are pooled */
#define POOL_HR2 (1.0 - 0.075)             /* repair 1: ... and those detaching above it */
#define N_Y 300                            /* y intervals from y_pool to y_max */
#define EXT_DY 0.25                        /* quadrature panels below y_pool */
#define EXT_SPAN 70.0                      /* the quadrature starts at y_max - EXT_SPAN */
#define G_FIRST 1e-8                       /* the first bin, [0, G_FIRST] */
#define G_BODY (VL_EMT_X_MAX + 10.0)       /* the bins end here */
#define N_BINS 1800                        /* geometric bins from G_FIRST to G_BODY */
#define Z_TAIL 8.5                         /* normal tails beyond 8.5 sd (1e-17) are dropped */
#define TAYLOR_EPS 0.05                    /* below it (in hr) the density is its Taylor series */
#define E1_VLO (-20.0)                     /* E1(e^v) table: series below */
#define E1_VHI 4.1                         /* ... and 0 above (E1(60) = 1.5e-28) */
#define TAB_PER_UNIT 256.0                 /* nodes per unit of the special-function tables */
#define X_BELOW_PERC 100.0                 /* the table starts at x_perc / 100 */
#define ERFINV_HALF 0.47693627620446987338 /* erf(z) = 1/2 */
#define EULER_GAMMA 0.57721566490153286061

/* ------------------------------------------------ special-function tables */

/* A cubic Hermite table of f on [lo, lo + (n-1) h]: f and h f' at nodes. */
typedef struct {
  double lo, inv_h;
  size_t n;
  double *f, *hd;
} ftab;

static double ftab_eval(const ftab *t, double x) {
  double r = (x - t->lo) * t->inv_h;
  size_t i = (size_t)r;
  if (i > t->n - 2) i = t->n - 2;
  double h = r - (double)i, h2 = h * h, h3 = h2 * h;
  return (2 * h3 - 3 * h2 + 1) * t->f[i] + (h3 - 2 * h2 + h) * t->hd[i] +
         (-2 * h3 + 3 * h2) * t->f[i + 1] + (h3 - h2) * t->hd[i + 1];
}

/* E1(e^v): the series -gamma - v + e^v - e^{2v}/4 below E1_VLO (next term
 * e^{3v}/18 ~ 1e-27), 0 above E1_VHI, the table between. */
static double e1_exp(const ftab *t, double v) {
  if (v >= E1_VHI) return 0.0;
  if (v <= E1_VLO) {
    double ev = exp(v);
    return -EULER_GAMMA - v + ev * (1.0 - 0.25 * ev);
  }
  return ftab_eval(t, v);
}

/* The standard normal cdf: 0 and 1 beyond Z_TAIL, the table between. */
static double cdf(const ftab *t, double z) {
  if (z <= -Z_TAIL) return 0.0;
  if (z >= Z_TAIL) return 1.0;
  return ftab_eval(t, z);
}

enum { TAB_E1, TAB_PHI }; /* what ftab_fill tabulates */

/* Fills t with E1(e^v) (TAB_E1) or Phi(z) (TAB_PHI) on [lo, hi]; 0 when
 * out of memory or GSL fails (t half filled: ftab_free it). */
static int ftab_fill(ftab *t, double lo, double hi, int which) {
  t->lo = lo;
  t->inv_h = TAB_PER_UNIT;
  t->n = (size_t)ceil((hi - lo) * TAB_PER_UNIT) + 1;
  t->f = malloc(t->n * sizeof *t->f);
  t->hd = malloc(t->n * sizeof *t->hd);
  if (!t->f || !t->hd) return 0;
  double h = 1.0 / TAB_PER_UNIT;
  for (size_t i = 0; i < t->n; i++) {
    double v = lo + (double)i * h;
    if (which == TAB_E1) { /* E1(e^v), d/dv = -exp(-e^v) */
      double ev = exp(v);
      gsl_sf_result r;
      if (gsl_sf_expint_E1_e(ev, &r) != GSL_SUCCESS) return 0;
      t->f[i] = r.val;
      t->hd[i] = -h * exp(-ev);
    } else { /* Phi(z), d/dz = phi(z) */
      t->f[i] = 0.5 * erfc(-v * M_SQRT1_2);
      t->hd[i] = h * exp(-0.5 * v * v) / sqrt(2.0 * M_PI);
    }
  }
  return 1;
}

static void ftab_free(ftab *t) {
  free(t->f);
  free(t->hd);
  t->f = t->hd = NULL;
}

/* ------------------------------------------------------ the PSD in y = ln M */

/* The PSD as power-law pieces C = c (q/q_k)^alpha on [q_k, q_{k+1}], with
 * M at each piece's start: M(q) and its inverse in closed form. */
typedef struct {
  size_t n;                  /* pieces */
  double *q, *c, *alpha, *m; /* q, m: n + 1 values (m[n] = M(q1)) */
} pieces;

/* (e^{p} - 1)/p, -> 1 as p -> 0 */
static double expm1_ratio(double p) { return fabs(p) < 1e-300 ? 1.0 : expm1(p) / p; }

static int pieces_init(pieces *pc, const vl_psd *psd) {
  size_t n = psd->kind == VL_PSD_SELF_AFFINE ? 1 : psd->n - 1;
  pc->n = n;
  pc->q = malloc((n + 1) * sizeof *pc->q);
  pc->c = malloc(n * sizeof *pc->c);
  pc->alpha = malloc(n * sizeof *pc->alpha);
  pc->m = malloc((n + 1) * sizeof *pc->m);
  if (!pc->q || !pc->c || !pc->alpha || !pc->m) return 0;
  if (psd->kind == VL_PSD_SELF_AFFINE) {
    pc->q[0] = psd->q0;
    pc->q[1] = psd->q1;
    pc->c[0] = psd->c0;
    pc->alpha[0] = -2.0 * (1.0 + psd->hurst);
  } else {
    for (size_t k = 0; k < n; k++) {
      pc->q[k] = psd->q[k];
      pc->c[k] = psd->C[k];
      pc->alpha[k] = log(psd->C[k + 1] / psd->C[k]) / log(psd->q[k + 1] / psd->q[k]);
    }
    pc->q[n] = psd->q[n];
  }
  pc->m[0] = 0.0;
  for (size_t k = 0; k < n; k++) {
    double q4c = pc->c[k] * pow(pc->q[k], 4.0), l = log(pc->q[k + 1] / pc->q[k]);
    pc->m[k + 1] = pc->m[k] + q4c * l * expm1_ratio((4.0 + pc->alpha[k]) * l);
  }
  return 1;
}

static void pieces_free(pieces *pc) {
  free(pc->q);
  free(pc->c);
  free(pc->alpha);
  free(pc->m);
}

static double m_of_q(const pieces *pc, double q) {
  size_t k = 0;
  while (k + 1 < pc->n && pc->q[k + 1] <= q)
    k++;
  double q4c = pc->c[k] * pow(pc->q[k], 4.0), l = log(q / pc->q[k]);
  return pc->m[k] + q4c * l * expm1_ratio((4.0 + pc->alpha[k]) * l);
}

/* q with M(q) = e^y (y <= ln M(q1)). */
static double q_of_y(const pieces *pc, double y) {
  double m = exp(y);
  size_t lo = vl_bracket(pc->m, pc->n + 1, m); /* the piece k with m[k] <= m < m[k+1] */
  double r = (m - pc->m[lo]) / (pc->c[lo] * pow(pc->q[lo], 4.0)), beta = 4.0 + pc->alpha[lo];
  double l = fabs(beta * r) < 1e-300 ? r : log1p(beta * r) / beta;
  return fmin(pc->q[lo] * exp(l), pc->q[pc->n]);
}

/* ------------------------------------------------------------ workspace */

/* What one PSD needs for any x (grids, quadrature, tables) and the scratch
 * of one x. */
typedef struct {
  double hrms, gcut; /* m; the film cut-off in h_rms */
  double y_max, y_pool, m1;
  ftab e1, phi;
  size_t ny;         /* main intervals */
  double *yg, *hr2g; /* ny + 1 nodes; hr^2 at the ny mid-points */
  double *lnf, *rf;  /* 2 ny: ln(1 - e^{y_i - Y}) and its e^{-1/2} by node offset */
  size_t ne;         /* panels below y_pool */
  double *ye, *hr2e; /* ne + 1 edges (ye[ne] = y_pool); hr^2 at mid-points */
  size_t nq, q_main; /* quadrature nodes (ascending in Y), first main one */
  double *Y, *W;
  size_t nb_max;      /* N_BINS + 1 bins, up to G_BODY */
  double dlog, *edge; /* nb_max + 1 edges */
  /* one x */
  double *A, *Ac, *ub; /* ny + 1 */
  size_t ng;
  double *gw, *gF, *gh2; /* groups (pooled components): mass, mass u1, mass hr^2 */
  size_t nb;             /* bins in use */
  double *mass, *gap;    /* nb_max */
  double *t0, *t2;       /* Taylor coefficients by last bin, nb_max */
} ws;

static void ws_free(ws *w) {
  ftab_free(&w->e1);
  ftab_free(&w->phi);
  double **arrays[] = {&w->yg,  &w->hr2g, &w->lnf, &w->rf, &w->ye, &w->hr2e, &w->Y,
                       &w->W,   &w->edge, &w->A,   &w->Ac, &w->ub, &w->gw,   &w->gF,
                       &w->gh2, &w->mass, &w->gap, &w->t0, &w->t2};
  for (size_t i = 0; i < sizeof arrays / sizeof *arrays; i++) {
    free(*arrays[i]);
    *arrays[i] = NULL;
  }
}

static int psd_usable(const vl_psd *psd) {
  if (!psd || !(isfinite(psd->q0) && isfinite(psd->q1) && psd->q0 > 0.0 && psd->q1 > psd->q0))
    return 0;
  if (psd->kind == VL_PSD_SELF_AFFINE)
    return isfinite(psd->c0) && psd->c0 > 0.0 && psd->hurst > 0.0 && psd->hurst <= 1.0;
  return psd->kind == VL_PSD_TABULATED && psd->n >= 2 && psd->q && psd->C;
}

/* hr^2/h_rms^2 = \int_q^{q1} q C / \int_{q0}^{q1} q C. */
static double hr2_at(const vl_psd *psd, double total1, double q) {
  return vl_psd_moment(psd, 1, q, psd->q1) / total1;
}

/* The quadrature nodes: GL4 on the panels below y_pool, GL2 on the main
 * intervals; W = weight x (1/2) e^{Y/2} / (q h_rms). And the tables of
 * ln(1 - e^{y_i - Y}) by offset of Y from y_i (uniform grid). */
static void place_quadrature(ws *w, const pieces *pc) {
  static const double x4[4] = {-0.86113631159405258, -0.33998104358485626, 0.33998104358485626,
                               0.86113631159405258};
  static const double w4[4] = {0.34785484513745386, 0.65214515486254614, 0.65214515486254614,
                               0.34785484513745386};
  size_t k = 0;
  for (size_t j = 0; j < w->ne; j++) {
    double c = 0.5 * (w->ye[j] + w->ye[j + 1]), h = 0.5 * (w->ye[j + 1] - w->ye[j]);
    for (int i = 0; i < 4; i++, k++) {
      w->Y[k] = c + h * x4[i];
      w->W[k] = h * w4[i];
    }
  }
  w->q_main = k;
  double dy = (w->y_max - w->y_pool) / (double)w->ny;
  for (size_t j = 0; j < w->ny; j++) {
    double c = 0.5 * (w->yg[j] + w->yg[j + 1]), h = 0.5 * (w->yg[j + 1] - w->yg[j]);
    for (int i = 0; i < 2; i++, k++) {
      double xi = (i ? 1.0 : -1.0) / sqrt(3.0);
      w->Y[k] = c + h * xi;
      w->W[k] = h;
      w->lnf[2 * j + (size_t)i] = log(-expm1(-((double)j + 0.5 + 0.5 * xi) * dy));
      w->rf[2 * j + (size_t)i] = exp(-0.5 * w->lnf[2 * j + (size_t)i]);
    }
  }
  for (k = 0; k < w->nq; k++)
    w->W[k] *= 0.5 * exp(0.5 * w->Y[k]) / (q_of_y(pc, w->Y[k]) * w->hrms);
}

/* y_pool: hr^2 = POOL_HR2 h_rms^2, by bisection in ln q. */
static double pool_point(const vl_psd *psd, const pieces *pc, double total1) {
  double la = log(psd->q0), lb = log(psd->q1);
  for (int it = 0; it < 200 && lb - la > 1e-15 * fabs(lb); it++) {
    double lm = 0.5 * (la + lb);
    if (hr2_at(psd, total1, exp(lm)) > POOL_HR2)
      la = lm;
    else
      lb = lm;
  }
  return log(m_of_q(pc, exp(0.5 * (la + lb))));
}

static int ws_alloc(ws *w) {
  size_t n1 = w->ny + 1, nb = w->nb_max;
  double **grid[] = {&w->yg, &w->A, &w->Ac, &w->ub, &w->gw, &w->gF, &w->gh2};
  double **bins[] = {&w->mass, &w->gap, &w->t0, &w->t2};
  for (size_t i = 0; i < sizeof grid / sizeof *grid; i++)
    if (!(*grid[i] = malloc(n1 * sizeof **grid[i]))) return 0;
  for (size_t i = 0; i < sizeof bins / sizeof *bins; i++)
    if (!(*bins[i] = malloc(nb * sizeof **bins[i]))) return 0;
  w->hr2g = malloc(w->ny * sizeof *w->hr2g);
  w->lnf = malloc(2 * w->ny * sizeof *w->lnf);
  w->rf = malloc(2 * w->ny * sizeof *w->rf);
  w->ye = malloc((w->ne + 1) * sizeof *w->ye);
  w->hr2e = malloc(w->ne * sizeof *w->hr2e);
  w->Y = malloc(w->nq * sizeof *w->Y);
  w->W = malloc(w->nq * sizeof *w->W);
  w->edge = malloc((nb + 1) * sizeof *w->edge);
  return w->hr2g && w->lnf && w->rf && w->ye && w->hr2e && w->Y && w->W && w->edge;
}

/* The grids of a usable PSD (hr^2, quadrature, bin edges). */
static void ws_grids(ws *w, const vl_psd *psd, const pieces *pc, double total1, double y_lo) {
  for (size_t i = 0; i <= w->ny; i++)
    w->yg[i] =
        i == w->ny ? w->y_max : w->y_pool + (w->y_max - w->y_pool) * (double)i / (double)w->ny;
  for (size_t i = 0; i < w->ny; i++)
    w->hr2g[i] = hr2_at(psd, total1, q_of_y(pc, 0.5 * (w->yg[i] + w->yg[i + 1])));
  for (size_t j = 0; j <= w->ne; j++)
    w->ye[j] = j == w->ne ? w->y_pool : y_lo + (w->y_pool - y_lo) * (double)j / (double)w->ne;
  for (size_t j = 0; j < w->ne; j++)
    w->hr2e[j] = hr2_at(psd, total1, q_of_y(pc, 0.5 * (w->ye[j] + w->ye[j + 1])));
  place_quadrature(w, pc);
  w->edge[0] = 0.0;
  for (size_t j = 1; j <= w->nb_max; j++)
    w->edge[j] = G_FIRST * exp((double)(j - 1) * w->dlog);
}

static vl_status ws_init(ws *w, const vl_psd *psd, double film_cutoff_m, vl_error *err) {
  vl_status st = VL_OK;
  pieces pc = {0};
  memset(w, 0, sizeof *w);
  gsl_set_error_handler_off();
  if (!psd_usable(psd)) {
    vl_error_set(err, "persson-emt: the PSD is not initialised or invalid");
    return VL_EINPUT;
  }
  if (!(isfinite(film_cutoff_m) && film_cutoff_m > 0.0)) {
    vl_error_set(err, "persson-emt: the film cut-off must be a positive length (got %g m)",
                 film_cutoff_m);
    return VL_EINPUT;
  }
  if (!pieces_init(&pc, psd)) goto nomem;
  double total1 = vl_psd_moment(psd, 1, psd->q0, psd->q1);
  w->hrms = vl_psd_hrms(psd);
  w->gcut = film_cutoff_m / w->hrms;
  w->m1 = pc.m[pc.n];
  w->y_max = log(w->m1);
  if (!(total1 > 0.0 && isfinite(w->hrms) && w->hrms > 0.0 && isfinite(w->y_max))) {
    vl_error_set(err, "persson-emt: degenerate PSD (h_rms = %g m, M(q1) = %g)", w->hrms, w->m1);
    st = VL_EINPUT;
    goto cleanup;
  }
  w->y_pool = pool_point(psd, &pc, total1);
  if (!(w->y_pool < w->y_max)) {
    vl_error_set(err, "persson-emt: degenerate PSD (no roughness above the pooling scale)");
    st = VL_EINPUT;
    goto cleanup;
  }
  double y_lo = fmin(w->y_max - EXT_SPAN, w->y_pool - 10.0);
  w->ny = N_Y;
  w->ne = (size_t)ceil((w->y_pool - y_lo) / EXT_DY);
  w->nq = 4 * w->ne + 2 * w->ny;
  w->dlog = log(G_BODY / G_FIRST) / N_BINS;
  w->nb_max = N_BINS + 1;
  if (!ws_alloc(w)) goto nomem;
  ws_grids(w, psd, &pc, total1, y_lo);
  for (size_t k = 0; k < w->nq; k++) {
    if (!(isfinite(w->W[k]) && w->W[k] >= 0.0)) {
      vl_error_set(err, "persson-emt: the PSD gives a non-finite separation integrand");
      st = VL_EINPUT;
      goto cleanup;
    }
  }
  if (!ftab_fill(&w->e1, E1_VLO, E1_VHI, TAB_E1) || !ftab_fill(&w->phi, -Z_TAIL, Z_TAIL, TAB_PHI)) {
    if (!w->e1.f || !w->e1.hd || !w->phi.f || !w->phi.hd) goto nomem;
    vl_error_set(err, "persson-emt: E1 failed while tabulating it");
    st = VL_EINTERNAL;
    goto cleanup;
  }
  goto cleanup;
nomem:
  vl_error_set(err, "persson-emt: out of memory for the gap-distribution workspace");
  st = VL_ENOMEM;
cleanup:
  pieces_free(&pc);
  if (st != VL_OK) ws_free(w);
  return st;
}

/* ------------------------------------------------ Persson: s, ubar, A(y) */

/* First quadrature node at or after k0 with Y >= y (nodes ascending). */
static size_t first_node(const ws *w, size_t k0, double y) {
  size_t lo = k0, hi = w->nq;
  while (lo < hi) {
    size_t mid = (lo + hi) / 2;
    if (w->Y[mid] < y)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

/* Persson's u(s) (in h_rms) for L = ln(s^2/pi), and in *dl (when not NULL)
 * -du/dL = (1/2) \int e^{y/2}/q exp(-e^{L-y}) dy (for Newton). */
static double separation(const ws *w, double L, double *dl) {
  double u = 0.0, du = 0.0;
  for (size_t k = first_node(w, 0, L - E1_VHI); k < w->nq; k++) {
    double v = L - w->Y[k];
    u += w->W[k] * e1_exp(&w->e1, v);
    if (dl) du += w->W[k] * exp(-exp(v));
  }
  if (dl) *dl = du;
  return u;
}

/* ln s at which Persson's u(s) = x (in h_rms), from the guess lns (may be
 * NaN). u decreases in s: Newton on ln u(ln s), kept inside a bracket. */
static double solve_lns(const ws *w, double x, double lns) {
  double lo = -INFINITY, hi = INFINITY; /* u(lo) > x > u(hi) */
  if (!isfinite(lns)) lns = log(ERFINV_HALF * sqrt(M_PI * w->m1));
  for (int it = 0; it < 200; it++) {
    double dl, u = separation(w, 2.0 * lns - log(M_PI), &dl);
    double f = log(u) - log(x);
    if (f == 0.0) return lns;
    if (f > 0.0)
      lo = lns;
    else
      hi = lns;
    double step = (dl > 0.0 && u > 0.0) ? f / (2.0 * dl / u) : 5.0; /* d ln u/d ln s = -2 dl/u */
    step = fmax(-5.0, fmin(5.0, step));
    double next = lns + step;
    if (!(next > lo && next < hi)) next = (isfinite(lo) && isfinite(hi)) ? 0.5 * (lo + hi) : next;
    if (fabs(next - lns) < 1e-14 * fmax(1.0, fabs(lns))) return next;
    lns = next;
  }
  return lns;
}

/* ubar at main grid node i for L = ln(p^2/pi): the sub-surface above
 * zeta_i q0, dM = e^Y (1 - e^{y_i - Y}) = e^{Y + lnf[offset]}. */
static double sub_separation(const ws *w, size_t i, double L) {
  size_t k0 = w->q_main + 2 * i, lo = k0, hi = w->nq;
  while (lo < hi) { /* first node with ln dM >= L - E1_VHI (ln dM increases) */
    size_t mid = (lo + hi) / 2;
    if (w->Y[mid] + w->lnf[mid - k0] < L - E1_VHI)
      lo = mid + 1;
    else
      hi = mid;
  }
  double u = 0.0;
  for (size_t k = lo; k < w->nq; k++)
    u += w->W[k] * w->rf[k - k0] * e1_exp(&w->e1, L - w->Y[k] - w->lnf[k - k0]);
  return u;
}

/* A, erfc and ubar at the main grid nodes for s. */
static void persson_grid(ws *w, double s) {
  for (size_t i = 0; i <= w->ny; i++) {
    double z = s * exp(-0.5 * w->yg[i]) / sqrt(M_PI);
    w->A[i] = erf(z);
    w->Ac[i] = erfc(z);
    w->ub[i] = 0.0;
    if (i < w->ny && w->A[i] > 0.0)
      w->ub[i] = sub_separation(w, i, 2.0 * log(s / w->A[i]) - log(M_PI));
  }
}

/* The components and repair (1): groups of (mass, mass u1, mass hr^2). */
static void components(ws *w, double x, double s) {
  /* component 0: all that detaches before y_pool (the hr pool); its hr^2 is
   * mass-weighted on the panels below y_pool, 1 before them */
  double cprev = erfc(s * exp(-0.5 * w->ye[0]) / sqrt(M_PI)), wh2 = cprev;
  for (size_t j = 0; j < w->ne; j++) {
    double c = erfc(s * exp(-0.5 * w->ye[j + 1]) / sqrt(M_PI));
    wh2 += (c - cprev) * w->hr2e[j];
    cprev = c;
  }
  double m = w->Ac[0], F = x - w->A[0] * w->ub[0], mh = m > 0.0 ? wh2 : 0.0;
  w->ng = 0;
  for (size_t i = 0;; i++) {
    if (m >= POOL_MASS || i == w->ny) {
      if (m < POOL_MASS && w->ng > 0) { /* a light tail joins the last group */
        w->ng--;
        m += w->gw[w->ng];
        F += w->gF[w->ng];
        mh += w->gh2[w->ng];
      }
      w->gw[w->ng] = m;
      w->gF[w->ng] = F;
      w->gh2[w->ng] = mh;
      w->ng++;
      m = F = mh = 0.0;
    }
    if (i == w->ny) break;
    double dm = w->Ac[i + 1] - w->Ac[i];
    m += dm;
    F += w->A[i] * w->ub[i] - w->A[i + 1] * w->ub[i + 1];
    mh += dm * w->hr2g[i];
  }
}

/* ------------------------------------------------------------ binning */

/* Index of the largest edge <= g (g >= 0); nb_max from G_BODY on. */
static size_t edge_below(const ws *w, double g) {
  if (g < G_FIRST) return 0;
  if (g >= w->edge[w->nb_max]) return w->nb_max;
  double r = floor(log(g / G_FIRST) / w->dlog);
  return r >= (double)(w->nb_max - 1) ? w->nb_max - 1 : 1 + (size_t)r;
}

/* P(|X| <= g), X ~ N(mu, sig^2). */
static double folded_cdf(const ws *w, double g, double mu, double sig) {
  return cdf(&w->phi, (g - mu) / sig) - cdf(&w->phi, (-g - mu) / sig);
}

/* Adds mass wt of |X|, X ~ N(mu, sig^2), to the bins (nb set to cover it). */
static void bin_component(ws *w, double wt, double mu, double sig) {
  double ma = fabs(mu);
  if (!(sig > 0.0)) {
    size_t j = edge_below(w, ma);
    if (j == w->nb_max) return; /* beyond G_BODY: dropped */
    w->mass[j] += wt;
    if (j + 1 > w->nb) w->nb = j + 1;
    return;
  }
  size_t jlo = 0, jhi = edge_below(w, ma + Z_TAIL * sig) + 1; /* edges jlo..jhi */
  if (jhi > w->nb_max) jhi = w->nb_max; /* what lies beyond G_BODY is dropped */
  if (ma - Z_TAIL * sig > 0.0) {
    jlo = edge_below(w, ma - Z_TAIL * sig);
  } else if (TAYLOR_EPS * sig > w->edge[1]) {
    /* density f0 (1 + kappa g^2) on [0, edge[K]] */
    size_t K = edge_below(w, TAYLOR_EPS * sig);
    double r = ma / sig, f0 = 2.0 * exp(-0.5 * r * r) / (sqrt(2.0 * M_PI) * sig);
    w->t0[K - 1] += wt * f0; /* summed from the top down: see bin_groups */
    w->t2[K - 1] += wt * f0 * (r * r - 1.0) / (2.0 * sig * sig);
    jlo = K;
  }
  if (jlo >= jhi) return; /* wholly beyond G_BODY */
  double Fa = jlo == 0 ? 0.0 : folded_cdf(w, w->edge[jlo], mu, sig);
  for (size_t j = jlo; j < jhi; j++) {
    double Fb = folded_cdf(w, w->edge[j + 1], mu, sig);
    w->mass[j] += wt * (Fb - Fa);
    Fa = Fb;
  }
  if (jhi > w->nb) w->nb = jhi;
}

/* The binned open part of P (repair 2): masses and gaps scaled to mean x.
 * Returns the mean before the scaling. */
static double bin_groups(ws *w, double x) {
  memset(w->mass, 0, w->nb_max * sizeof *w->mass);
  memset(w->t0, 0, w->nb_max * sizeof *w->t0);
  memset(w->t2, 0, w->nb_max * sizeof *w->t2);
  w->nb = 1;
  for (size_t i = 0; i < w->ng; i++)
    if (w->gw[i] > 0.0)
      bin_component(w, w->gw[i], w->gF[i] / w->gw[i], sqrt(fmax(0.0, w->gh2[i] / w->gw[i])));
  /* the Taylor densities act on the bins up to each component's K - 1:
   * summed from the top down, so the bins above every K get exactly 0 (a
   * prefix sum with +/- at both ends would leave rounding residues there,
   * and the g^2 coefficient is large where hr is small) */
  double c0 = 0.0, c2 = 0.0, mean = 0.0;
  for (size_t j = w->nb; j-- > 0;) {
    double a = w->edge[j], b = w->edge[j + 1];
    c0 += w->t0[j];
    c2 += w->t2[j];
    w->mass[j] += c0 * (b - a) + c2 * (b * b * b - a * a * a) / 3.0;
    w->gap[j] = 0.5 * (a + b);
  }
  /* P stays a distribution: the open bins hold 1 - A/A0 (what was dropped
   * beyond G_BODY, and the rounding of the Taylor pieces, is spread) */
  double open = 0.0;
  for (size_t j = 0; j < w->nb; j++)
    open += w->mass[j];
  for (size_t j = 0; j < w->nb && open > 0.0; j++)
    w->mass[j] *= w->Ac[w->ny] / open;
  for (size_t j = 0; j < w->nb; j++)
    mean += w->mass[j] * w->gap[j];
  for (size_t j = 0; j < w->nb; j++)
    w->gap[j] *= x / mean;
  return mean;
}

/* phi_f = x sum_{g > gcut} m/g, the bin holding gcut counted by the share
 * of its (scaled) width above gcut. */
static double couette_factor(const ws *w, double x, double scale) {
  double f = 0.0;
  for (size_t j = 0; j < w->nb; j++) {
    double a = scale * w->edge[j], b = scale * w->edge[j + 1];
    if (b <= w->gcut || !(w->mass[j] > 0.0)) continue;
    f += (a >= w->gcut ? 1.0 : (b - w->gcut) / (b - a)) * w->mass[j] / w->gap[j];
  }
  return x * f;
}

/* ------------------------------------------------------ effective medium */

/* sum_j m_j c/(g_j^3 + c) and c d/dc of it. */
static double bruggeman_sum(size_t n, const double *g, const double *m, double c, double *cd) {
  double s = 0.0, d = 0.0;
  for (size_t j = 0; j < n; j++) {
    double g3 = g[j] * g[j] * g[j], r = 1.0 / (g3 + c);
    s += m[j] * c * r;
    d += m[j] * c * g3 * r * r;
  }
  *cd = d;
  return s;
}

/* The root c > 0 of (open - contact) - 2 sum m c/(g^3 + c) = 0, or 0 when
 * percolated (open <= contact). Newton in ln c inside a bracket. */
static double bruggeman_root(size_t n, const double *g, const double *m, double contact) {
  double open = 0.0, inv3 = 0.0, gmax3 = 0.0;
  for (size_t j = 0; j < n; j++) {
    if (!(m[j] > 0.0)) continue;
    double g3 = g[j] * g[j] * g[j];
    open += m[j];
    inv3 += m[j] / g3;
    gmax3 = fmax(gmax3, g3);
  }
  double f0 = open - contact;
  if (!(f0 > 0.0)) return 0.0;
  /* f(c) >= f0 - 2 c inv3 and f(2 gmax3) <= f0 - (4/3) open < 0 */
  double lo = log(0.25 * f0 / inv3), hi = log(2.0 * gmax3), t = 0.5 * (lo + hi);
  for (int it = 0; it < 200; it++) {
    double cd, f = f0 - 2.0 * bruggeman_sum(n, g, m, exp(t), &cd);
    if (f == 0.0) return exp(t);
    if (f > 0.0)
      lo = t;
    else
      hi = t;
    double next = cd > 0.0 ? t + f / (2.0 * cd) : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (fabs(next - t) < 1e-14 * fmax(1.0, fabs(t))) return exp(next);
    t = next;
  }
  return exp(t);
}

/* The factors of a distribution (no checks: see vl_emt_medium). */
static void medium(size_t n, const double *g, const double *m, double contact, double gcut,
                   vl_emt_point *out) {
  double c = bruggeman_root(n, g, m, contact);
  double u = 0.0, uw = 0.0;
  for (size_t j = 0; j < n; j++) {
    double g3 = g[j] * g[j] * g[j];
    u += m[j] * g[j];
    if (c > 0.0) uw += m[j] * g[j] * 2.0 * c / (g3 + c);
  }
  /* Both shear factors count only the gaps wider than the film cut-off:
   * narrower ones are boundary contact, sheared at sigma_s. For phi_fs this
   * is also what keeps it finite: at and below percolation (c = 0) its sum
   * has no lower cut-off and grew without limit as the first bin narrowed
   * (45.8 at the seed PSD's percolation with a 1e-8 h_rms bin, 63.0 with
   * 1e-10); with the cut-off it is 0.038 there, continuous through
   * percolation, and the tabulated rows above x = 0.1 do not move. */
  double fs = 0.0, f = 0.0;
  for (size_t j = 0; j < n; j++) {
    if (!(m[j] > 0.0) || !(g[j] > gcut)) continue;
    double g3 = g[j] * g[j] * g[j];
    fs += m[j] * g[j] * (g[j] - uw) / (g3 + c);
    f += m[j] / g[j];
  }
  out->x = u;
  out->phi_p = c / (u * u * u);
  out->phi_fp = uw / u;
  out->phi_s = u * (1.0 - out->phi_fp);
  out->phi_fs = 3.0 * u * fs;
  out->phi_f = u * f;
  out->area = contact;
  out->s = NAN;
  out->reflect = 1.0;
}

vl_status vl_emt_medium(size_t n, const double *g, const double *m, double contact, double g_cut,
                        vl_emt_point *out, vl_error *err) {
  double u = 0.0;
  if (!(contact >= 0.0 && contact <= 1.0) || !(g_cut >= 0.0)) {
    vl_error_set(err, "emt medium: contact fraction %g or cut-off %g out of range", contact, g_cut);
    return VL_EINPUT;
  }
  for (size_t j = 0; j < n; j++) {
    if (!(isfinite(g[j]) && g[j] > 0.0 && isfinite(m[j]) && m[j] >= 0.0)) {
      vl_error_set(err, "emt medium: gap %zu (%g) or its mass (%g) is invalid", j, g[j], m[j]);
      return VL_EINPUT;
    }
    u += m[j] * g[j];
  }
  if (!(isfinite(u) && u > 0.0)) {
    vl_error_set(err, "emt medium: the mean gap must be positive (got %g)", u);
    return VL_EINPUT;
  }
  medium(n, g, m, contact, g_cut, out);
  return VL_OK;
}

/* ------------------------------------------------------------ one x */

/* The model at x for the nominal pressure s (from solve_lns). */
static void point_at(ws *w, double x, double s, vl_emt_point *out) {
  persson_grid(w, s);
  components(w, x, s);
  double mean = bin_groups(w, x);
  medium(w->nb, w->gap, w->mass, w->A[w->ny], w->gcut, out);
  out->x = x; /* the scaled mean, to rounding */
  out->phi_s = x * (1.0 - out->phi_fp);
  out->phi_f = couette_factor(w, x, x / mean);
  out->s = s;
  out->reflect = mean / x;
}

vl_status vl_emt_point_eval(const vl_psd *psd, double film_cutoff_m, double x, vl_emt_point *out,
                            vl_error *err) {
  if (!(isfinite(x) && x > 0.0)) {
    vl_error_set(err, "persson-emt: x = u/h_rms must be positive (got %g)", x);
    return VL_EINPUT;
  }
  ws w;
  vl_status st = ws_init(&w, psd, film_cutoff_m, err);
  if (st != VL_OK) return st;
  point_at(&w, x, exp(solve_lns(&w, x, NAN)), out);
  ws_free(&w);
  return VL_OK;
}

/* s and x at the percolation point: A(y_max) = 1/2. */
static double percolation_x(const ws *w, double *s) {
  *s = ERFINV_HALF * sqrt(M_PI * w->m1);
  return separation(w, 2.0 * log(*s) - log(M_PI), NULL);
}

double vl_emt_percolation(const vl_psd *psd) {
  ws w;
  double s;
  if (ws_init(&w, psd, VL_EMT_DEFAULT_FILM_CUTOFF_M, NULL) != VL_OK) return NAN;
  double x = percolation_x(&w, &s);
  ws_free(&w);
  return x;
}

/* ------------------------------------------------------------ the table */

enum { F_P, F_FP, F_FS, F_F, NF }; /* the interpolated factors */

struct vl_emt_table {
  double hrms, cutoff, x_perc;
  uint64_t fp[VL_BLOB_PSD_WORDS]; /* the PSD it was built from */
  size_t n;
  double *lx;            /* ln x at the nodes */
  double *v[NF], *d[NF]; /* values and d/d ln x */
  double *area;          /* A/A0 at the nodes */
  double tail[NF];       /* Tripp coefficients above the table */
  double k_lo[NF];       /* power-law exponents below it */
};

void vl_emt_table_free(vl_emt_table *t) {
  if (!t) return;
  free(t->lx);
  for (int f = 0; f < NF; f++) {
    free(t->v[f]);
    free(t->d[f]);
  }
  free(t->area);
  free(t);
}

static vl_status table_alloc(size_t n, vl_emt_table **out, vl_error *err) {
  vl_emt_table *t = calloc(1, sizeof *t);
  *out = NULL;
  if (!t) goto nomem;
  t->n = n;
  t->lx = malloc(n * sizeof *t->lx);
  t->area = malloc(n * sizeof *t->area);
  int ok = t->lx && t->area;
  for (int f = 0; f < NF; f++) {
    t->v[f] = malloc(n * sizeof *t->v[f]);
    t->d[f] = malloc(n * sizeof *t->d[f]);
    ok = ok && t->v[f] && t->d[f];
  }
  if (!ok) goto nomem;
  *out = t;
  return VL_OK;
nomem:
  vl_emt_table_free(t);
  vl_error_set(err, "persson-emt: out of memory for a %zu-point table", n);
  return VL_ENOMEM;
}

static int x_perc_usable(double x_perc) {
  return isfinite(x_perc) && x_perc > 0.0 && x_perc < 0.1 * VL_EMT_X_MAX;
}

/* The nodes (ln x) for percolation point x_perc: n - N_CLUSTER geometric
 * from x_perc/X_BELOW_PERC to VL_EMT_X_MAX, the nearest moved onto x_perc,
 * then N_CLUSTER more just above it, at CLUSTER[i] of the way (in ln x) to
 * the next: phi_fs falls from its percolated value with a logarithmic
 * singularity there (c^{1/3} cuts off the smallest gaps), which a single
 * interval would overshoot by 2x. */
#define N_CLUSTER 3
static const double CLUSTER[N_CLUSTER] = {1e-3, 1e-2, 1e-1};

static void place_nodes(double x_perc, size_t n, double *lx) {
  size_t ng = n - N_CLUSTER, near = 0;
  double a = log(x_perc / X_BELOW_PERC), b = log(VL_EMT_X_MAX), lp = log(x_perc);
  for (size_t k = 0; k < ng; k++) {
    lx[k] = k + 1 == ng ? b : a + (b - a) * (double)k / (double)(ng - 1);
    if (fabs(lx[k] - lp) < fabs(lx[near] - lp)) near = k;
  }
  lx[near] = lp;
  double gap = lx[near + 1] - lp;
  memmove(lx + near + 1 + N_CLUSTER, lx + near + 1, (ng - near - 1) * sizeof *lx);
  for (size_t i = 0; i < N_CLUSTER; i++)
    lx[near + 1 + i] = lp + CLUSTER[i] * gap;
}

/* Fritsch-Butland slope at an interior node from the two secants. */
static double fb_slope(double h0, double s0, double h1, double s1) {
  if (!(s0 * s1 > 0.0)) return 0.0;
  return 3.0 * (h0 + h1) / ((2.0 * h1 + h0) / s0 + (h1 + 2.0 * h0) / s1);
}

/* The interpolant's slopes and the continuations, from the node values. */
static void set_slopes(vl_emt_table *t) {
  size_t n = t->n;
  for (int f = 0; f < NF; f++) {
    double *v = t->v[f], *d = t->d[f];
    for (size_t k = 1; k + 1 < n; k++) {
      double h0 = t->lx[k] - t->lx[k - 1], h1 = t->lx[k + 1] - t->lx[k];
      d[k] = fb_slope(h0, (v[k] - v[k - 1]) / h0, h1, (v[k + 1] - v[k]) / h1);
    }
    /* top: the Tripp tail's slope in ln x, determined by the value */
    double x2 = exp(2.0 * t->lx[n - 1]), vt = v[n - 1];
    if (f == F_P || f == F_FP) {
      t->tail[f] = (1.0 - vt) * x2;
      d[n - 1] = 2.0 * (1.0 - vt);
    } else if (f == F_FS) {
      t->tail[f] = vt * x2;
      d[n - 1] = -2.0 * vt;
    } else {
      t->tail[f] = (vt - 1.0) * x2;
      d[n - 1] = -2.0 * (vt - 1.0);
    }
    /* bottom: the one-sided three-point slope, limited like the interior
     * ones (no overshoot), then the power law phi_0 (x/x_0)^k with that
     * slope (k = 0 and phi = 0 for phi_p, phi_fp, which are 0 there) */
    double h0 = t->lx[1] - t->lx[0], h1 = t->lx[2] - t->lx[1];
    double s0 = (v[1] - v[0]) / h0, s1 = (v[2] - v[1]) / h1;
    double d0 = ((2.0 * h0 + h1) * s0 - h0 * s1) / (h0 + h1);
    if (d0 * s0 <= 0.0)
      d0 = 0.0;
    else if (s0 * s1 <= 0.0 && fabs(d0) > 3.0 * fabs(s0))
      d0 = 3.0 * s0;
    d[0] = d0;
    t->k_lo[f] = v[0] > 0.0 ? d0 / v[0] : 0.0;
  }
}

/* 1 if node k's values are what a build can produce (finite, in range,
 * zero pressure flow exactly up to percolation); 0 with err set if not. */
static int node_ok(const vl_emt_table *t, size_t k, vl_error *err) {
  const char *why = NULL;
  double p = t->v[F_P][k], fp = t->v[F_FP][k], fs = t->v[F_FS][k], f = t->v[F_F][k];
  double a = t->area[k];
  if (!(isfinite(p) && isfinite(fp) && isfinite(fs) && isfinite(f) && isfinite(a)))
    why = "a value is not finite";
  else if (!(p >= 0.0 && fp >= 0.0 && fs >= 0.0 && f >= 0.0 && a >= 0.0 && a <= 1.0))
    why = "a value is out of range";
  else if (t->lx[k] <= log(t->x_perc) ? (p != 0.0 || fp != 0.0) : !(p > 0.0))
    why = "its pressure flow contradicts the percolation point";
  else if (k > 0 && !(a <= t->area[k - 1]))
    why = "its contact area rises with the separation";
  if (why) vl_error_set(err, "node %zu (u/h_rms = %g): %s", k, exp(t->lx[k]), why);
  return why == NULL;
}

static void fill_values(vl_emt_table *t, size_t k, const vl_emt_point *p) {
  t->v[F_P][k] = p->phi_p;
  t->v[F_FP][k] = p->phi_fp;
  t->v[F_FS][k] = p->phi_fs;
  t->v[F_F][k] = p->phi_f;
  t->area[k] = p->area;
}

vl_status vl_emt_table_build(const vl_psd *psd, double film_cutoff_m, size_t n_points,
                             vl_emt_table **out, vl_error *err) {
  vl_emt_table *t = NULL;
  ws w;
  *out = NULL;
  if (n_points == 0) n_points = VL_EMT_DEFAULT_N_POINTS;
  if (n_points < VL_EMT_MIN_N_POINTS || n_points > VL_EMT_MAX_N_POINTS) {
    vl_error_set(err, "persson-emt: the table needs %d to %d points (got %zu)", VL_EMT_MIN_N_POINTS,
                 VL_EMT_MAX_N_POINTS, n_points);
    return VL_EINPUT;
  }
  vl_status st = ws_init(&w, psd, film_cutoff_m, err);
  if (st != VL_OK) return st;
  st = table_alloc(n_points, &t, err);
  if (st != VL_OK) goto cleanup;
  double s_perc;
  t->hrms = w.hrms;
  t->cutoff = film_cutoff_m;
  t->x_perc = percolation_x(&w, &s_perc);
  vl_blob_psd_fingerprint(psd, t->fp);
  if (!x_perc_usable(t->x_perc)) {
    vl_error_set(err, "persson-emt: percolation at u/h_rms = %g is out of range", t->x_perc);
    st = VL_EINPUT;
    goto cleanup;
  }
  place_nodes(t->x_perc, n_points, t->lx);
  double lns = log(s_perc);
  for (size_t k = 0; k < n_points; k++) {
    double x = exp(t->lx[k]);
    int at_perc = t->lx[k] == log(t->x_perc);
    vl_emt_point p;
    lns = at_perc ? log(s_perc) : solve_lns(&w, x, lns);
    point_at(&w, x, exp(lns), &p);
    if (at_perc) p.phi_p = p.phi_fp = 0.0; /* the medium's limit at the threshold */
    fill_values(t, k, &p);
    if (!node_ok(t, k, err)) {
      vl_error_prefix(err, "persson-emt table");
      st = VL_EINTERNAL;
      goto cleanup;
    }
  }
  set_slopes(t);
cleanup:
  ws_free(&w);
  if (st != VL_OK) {
    vl_emt_table_free(t);
    t = NULL;
  }
  *out = t;
  return st;
}

/* ------------------------------------------------------------ queries */

/* Where ln x = l falls inside the table: the interval lo and the Hermite
 * coordinate on it (shared by the factors: one search for all). */
typedef struct {
  size_t lo;
  double dx, h, h2, h3;
} table_spot;

static table_spot locate(const vl_emt_table *t, double l) {
  size_t lo = vl_bracket(t->lx, t->n, l);
  table_spot p = {lo, t->lx[lo + 1] - t->lx[lo], 0.0, 0.0, 0.0};
  p.h = (l - t->lx[lo]) / p.dx, p.h2 = p.h * p.h, p.h3 = p.h2 * p.h;
  return p;
}

/* Value and d/d ln x of factor f at the spot p inside the table. */
static double interp(const vl_emt_table *t, int f, const table_spot *p, double *dl) {
  size_t lo = p->lo;
  double dx = p->dx, h = p->h, h2 = p->h2, h3 = p->h3;
  double y0 = t->v[f][lo], y1 = t->v[f][lo + 1];
  double m0 = t->d[f][lo] * dx, m1 = t->d[f][lo + 1] * dx;
  *dl = ((6 * h2 - 6 * h) * y0 + (3 * h2 - 4 * h + 1) * m0 + (-6 * h2 + 6 * h) * y1 +
         (3 * h2 - 2 * h) * m1) /
        dx;
  return (2 * h3 - 3 * h2 + 1) * y0 + (h3 - 2 * h2 + h) * m0 + (-2 * h3 + 3 * h2) * y1 +
         (h3 - h2) * m1;
}

/* Factor f and d/d ln x at x > 0, l = ln x outside the table. */
static double factor_outside(const vl_emt_table *t, int f, double x, double l, double *dl) {
  if (l >= t->lx[t->n - 1]) { /* Tripp */
    double a = t->tail[f] / (x * x);
    if (f == F_P || f == F_FP) {
      *dl = 2.0 * a;
      return 1.0 - a;
    }
    *dl = -2.0 * a;
    return f == F_FS ? a : 1.0 + a;
  }
  /* power law (k = 0: constant) */
  double k = t->k_lo[f], v = t->v[f][0] * (k == 0.0 ? 1.0 : exp(k * (l - t->lx[0])));
  *dl = k * v;
  return v;
}

void vl_emt_table_eval(const vl_emt_table *t, double u_m, vl_flow_factor_values *v,
                       vl_flow_factor_values *d) {
  if (isnan(u_m)) {
    v->phi_p = v->phi_s = v->phi_f = v->phi_fs = v->phi_fp = NAN;
    if (d) *d = *v;
    return;
  }
  double x = u_m / t->hrms, val[NF], dl[NF];
  if (!(x > 0.0)) { /* the limit u -> 0+: power laws (k > 0) at 0, held values, phi_s = x */
    for (int f = 0; f < NF; f++) {
      double k = t->k_lo[f];
      val[f] = k > 0.0 ? 0.0 : t->v[f][0];
      dl[f] = 0.0;
    }
    x = 0.0;
  } else {
    double l = log(x);
    bool inside = l < t->lx[t->n - 1] && l > t->lx[0];
    table_spot p = inside ? locate(t, l) : (table_spot){0};
    for (int f = 0; f < NF; f++)
      val[f] = inside ? interp(t, f, &p, &dl[f]) : factor_outside(t, f, x, l, &dl[f]);
  }
  v->phi_p = val[F_P];
  v->phi_fp = val[F_FP];
  v->phi_fs = val[F_FS];
  v->phi_f = val[F_F];
  v->phi_s = x * (1.0 - val[F_FP]);
  if (!d) return;
  /* d/du = (d/d ln x)/u; at u -> 0+ the right derivatives (k < 1 would
   * diverge: then the continuation holds and its slope is 0) */
  double inv_u = x > 0.0 ? 1.0 / u_m : 0.0;
  d->phi_p = dl[F_P] * inv_u;
  d->phi_fp = dl[F_FP] * inv_u;
  d->phi_fs = dl[F_FS] * inv_u;
  d->phi_f = dl[F_F] * inv_u;
  d->phi_s = (1.0 - val[F_FP]) / t->hrms - x * d->phi_fp;
}

size_t vl_emt_table_size(const vl_emt_table *t) { return t->n; }

double vl_emt_table_node(const vl_emt_table *t, size_t k, vl_flow_factor_values *v, double *area) {
  double x = exp(t->lx[k]);
  if (v) {
    v->phi_p = t->v[F_P][k];
    v->phi_fp = t->v[F_FP][k];
    v->phi_fs = t->v[F_FS][k];
    v->phi_f = t->v[F_F][k];
    v->phi_s = x * (1.0 - v->phi_fp);
  }
  if (area) *area = t->area[k];
  return x;
}

double vl_emt_table_hrms(const vl_emt_table *t) { return t->hrms; }
double vl_emt_table_film_cutoff(const vl_emt_table *t) { return t->cutoff; }
double vl_emt_table_percolation(const vl_emt_table *t) { return t->x_perc; }

/* ------------------------------------------------------ serialised form */

/* The blob, every field little-endian, doubles as their IEEE-754 bits
 * (blob.h). Formats 1 and 2 share the layout; 2 is the build with
 * FLOW_FACTORS.md's sub-surface Eq. 8 and the bins ending at G_BODY:
 *   "VLEF", u32 format, u64 n                               (16 bytes)
 *   PSD fingerprint (VL_BLOB_PSD_WORDS u64)                 (64 bytes)
 *   f64 h_rms, film cut-off (m), x_perc                     (24 bytes)
 *   f64 phi_p[n], phi_fp[n], phi_fs[n], phi_f[n], area[n]   (40 n bytes)
 *   u64 FNV-1a hash of all the bytes before it              (8 bytes)
 * The nodes follow from x_perc and n, the slopes and continuations from the
 * values: both are recomputed, so a stored table cannot contradict itself. */
#define BLOB_MAGIC "VLEF"
#define BLOB_HEAD (16 + 8 * VL_BLOB_PSD_WORDS + 24)
#define BLOB_SIZE(n) (BLOB_HEAD + 8 * (NF + 1) * (n) + 8)

/* The stored arrays in blob order. */
static void blob_arrays(const vl_emt_table *t, double *a[NF + 1]) {
  a[0] = t->v[F_P];
  a[1] = t->v[F_FP];
  a[2] = t->v[F_FS];
  a[3] = t->v[F_F];
  a[4] = t->area;
}

vl_status vl_emt_table_serialize(const vl_emt_table *t, void **blob, size_t *len, vl_error *err) {
  *blob = NULL;
  *len = 0;
  size_t size = BLOB_SIZE(t->n);
  unsigned char *b = malloc(size), *p = b;
  if (!b) {
    vl_error_set(err, "out of memory serialising a %zu-point persson-emt table", t->n);
    return VL_ENOMEM;
  }
  memcpy(p, BLOB_MAGIC, 4);
  for (int i = 0; i < 4; i++)
    p[4 + i] = (unsigned char)((uint32_t)VL_EMT_FORMAT >> (8 * i));
  vl_blob_put_u64(p + 8, (uint64_t)t->n);
  p += 16;
  for (int i = 0; i < VL_BLOB_PSD_WORDS; i++, p += 8)
    vl_blob_put_u64(p, t->fp[i]);
  const double scalars[3] = {t->hrms, t->cutoff, t->x_perc};
  for (int i = 0; i < 3; i++, p += 8)
    vl_blob_put_u64(p, vl_blob_bits(scalars[i]));
  double *arrays[NF + 1];
  blob_arrays(t, arrays);
  for (int a = 0; a <= NF; a++)
    for (size_t k = 0; k < t->n; k++, p += 8)
      vl_blob_put_u64(p, vl_blob_bits(arrays[a][k]));
  vl_blob_put_u64(p, vl_blob_fnv1a(VL_BLOB_FNV_OFFSET, b, size - 8));
  *blob = b;
  *len = size;
  return VL_OK;
}

/* The header checks of a blob (everything before the values). */
static int blob_header_ok(const unsigned char *b, size_t len, size_t *n, vl_error *err) {
  if (!b || len < BLOB_SIZE(0) || memcmp(b, BLOB_MAGIC, 4) != 0) {
    vl_error_set(err, "not a table (%zu bytes, no '" BLOB_MAGIC "' header)", len);
    return 0;
  }
  uint32_t format = 0;
  for (int i = 0; i < 4; i++)
    format |= (uint32_t)b[4 + i] << (8 * i);
  if (format != VL_EMT_FORMAT) {
    vl_error_set(err, "format %lu, this program's is %d", (unsigned long)format, VL_EMT_FORMAT);
    return 0;
  }
  uint64_t n64 = vl_blob_get_u64(b + 8);
  if (n64 < VL_EMT_MIN_N_POINTS || n64 > VL_EMT_MAX_N_POINTS || len != BLOB_SIZE((size_t)n64)) {
    vl_error_set(err, "%zu bytes do not hold the %llu nodes it announces", len,
                 (unsigned long long)n64);
    return 0;
  }
  if (vl_blob_fnv1a(VL_BLOB_FNV_OFFSET, b, len - 8) != vl_blob_get_u64(b + len - 8)) {
    vl_error_set(err, "checksum mismatch (damaged or edited)");
    return 0;
  }
  *n = (size_t)n64;
  return 1;
}

/* Reads the fingerprint, scalars and values of a checked blob into t and
 * checks them against psd and the cut-off: VL_OK, VL_EINPUT (err says why)
 * or VL_ENOMEM. */
static vl_status blob_read(vl_emt_table *t, const unsigned char *b, const vl_psd *psd,
                           double film_cutoff_m, vl_error *err) {
  const unsigned char *p = b + 16;
  vl_blob_psd_fingerprint(psd, t->fp);
  for (int i = 0; i < VL_BLOB_PSD_WORDS; i++, p += 8) {
    if (vl_blob_get_u64(p) != t->fp[i]) {
      vl_error_set(err, "built for another PSD");
      return VL_EINPUT;
    }
  }
  double *scalars[3] = {&t->hrms, &t->cutoff, &t->x_perc};
  for (int i = 0; i < 3; i++, p += 8)
    *scalars[i] = vl_blob_double(vl_blob_get_u64(p));
  if (vl_blob_bits(t->hrms) != vl_blob_bits(vl_psd_hrms(psd))) {
    vl_error_set(err, "its h_rms is not the surface's");
    return VL_EINPUT;
  }
  if (vl_blob_bits(t->cutoff) != vl_blob_bits(film_cutoff_m)) {
    vl_error_set(err, "built for a film cut-off of %g m, not %g m", t->cutoff, film_cutoff_m);
    return VL_EINPUT;
  }
  /* the percolation point, from which the nodes follow, is recomputed (a
   * few ms: the quadrature of Persson's u(s) once) */
  ws w;
  double s_perc;
  vl_status st = ws_init(&w, psd, film_cutoff_m, err);
  if (st != VL_OK) return st;
  double x_perc = percolation_x(&w, &s_perc);
  ws_free(&w);
  if (vl_blob_bits(t->x_perc) != vl_blob_bits(x_perc) || !x_perc_usable(x_perc)) {
    vl_error_set(err, "its percolation point u/h_rms = %g is not the surface's (%g)", t->x_perc,
                 x_perc);
    return VL_EINPUT;
  }
  double *arrays[NF + 1];
  blob_arrays(t, arrays);
  for (int a = 0; a <= NF; a++)
    for (size_t k = 0; k < t->n; k++, p += 8)
      arrays[a][k] = vl_blob_double(vl_blob_get_u64(p));
  place_nodes(t->x_perc, t->n, t->lx);
  for (size_t k = 0; k < t->n; k++)
    if (!node_ok(t, k, err)) return VL_EINPUT;
  return VL_OK;
}

vl_status vl_emt_table_deserialize(const vl_psd *psd, double film_cutoff_m, const void *blob,
                                   size_t len, vl_emt_table **out, vl_error *err) {
  vl_emt_table *t = NULL;
  size_t n = 0;
  *out = NULL;
  if (!psd_usable(psd) || !(isfinite(film_cutoff_m) && film_cutoff_m > 0.0)) {
    vl_error_set(err, "stored persson-emt table: the PSD or the film cut-off is invalid");
    return VL_EINPUT;
  }
  if (!blob_header_ok(blob, len, &n, err)) {
    vl_error_prefix(err, "stored persson-emt table");
    return VL_EINPUT;
  }
  vl_status st = table_alloc(n, &t, err);
  if (st != VL_OK) return st;
  st = blob_read(t, blob, psd, film_cutoff_m, err);
  if (st != VL_OK) {
    vl_error_prefix(err, "stored persson-emt table");
    vl_emt_table_free(t);
    return st;
  }
  set_slopes(t);
  *out = t;
  return VL_OK;
}
