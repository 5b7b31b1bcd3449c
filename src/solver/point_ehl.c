/* The lubricated smooth ball, isoviscous and elastic (point_ehl.h;
 * docs/POINT_CONTACT.md section 9).
 *
 * Dimensionless: X = x/a, P = p/p0, H = u R/a^2 (Hertz's a and p0 at the
 * same load), so that H = H0 + (X^2 + Y^2)/2 + sum_l M_kl P_l with
 * M_kl = (2/pi^2) [Kel(cell l) + Kel(its mirror image)] (Love's rectangle
 * in units of a, docs/POINT_CONTACT.md section 2), the load
 * sum_half P dA = pi/3, and Reynolds
 *   div(H^3 grad P) = lambda dH/dX,  lambda = 6 eta v0 R^2/(a^3 p0).
 * Finite volumes: the flux out of a cell through its faces,
 *   r_k = sum_faces [lambda H_face n_x - H^3_face dP/dn] * face length,
 * is zero where the fluid is pressurised and >= 0 (the fluid would need a
 * tension) where it has cavitated: min(P_k, r_k/(lambda dx dy)) = 0 is the
 * row of cell k (Reynolds' condition as a complementarity, the line
 * contact's route). The face film carried by the entrainment is the line
 * contact's limited second-order upwind (contact_equations.c:
 * couette_face), the conductance the harmonic mean of the two cells' H^3
 * (the two half cells in series). Every row depends on the films of its
 * stencil cells, each of which depends on every pressure through M: the
 * Jacobian is dense (sum over the stencil of dr/dH_m times M's row m),
 * solved by LAPACK's LU (linsol_lapack.h) under KINSOL. */
#include "point_ehl.h"

#include <kinsol/kinsol.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <time.h>

#include <gsl/gsl_sf_expint.h>

#include "blas_threads.h"
#include "bracket.h"
#include "flow_factors_internal.h"
#include "kernel2d.h"
#include "linsol_lapack.h"
#include "persson_internal.h"
#include "rheology_internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Zones of finest cells (units of a times cfg->unit): the inlet's edge, the outlet's edge
 * with the side lobes of the horseshoe (the rim from x = 0.2 a round to
 * x = a), and across, the rim from y = 0.3 a to beyond a. */
static const double ZONE_X[2][2] = {{-1.1, -0.8}, {0.2, 1.1}};
static const double ZONE_Y[1][2] = {{0.3, 1.1}};

/* A parabola's vertex (the film's minimum between cells) below this
 * fraction of the cells' smallest value is not trusted. */
#define TRUST_VERTEX 0.5

/* A cell is pressurised above this pressure (p0): the cavitated cells keep
 * a residue of the complementarity's tolerance (measured 1e-19). */
#define PRESSURISED 1e-7

/* Newton steps allowed from another grid's solution (measured: 6-23
 * when it converges). */
#define MAP_ITERATIONS 40
/* ... and from the dry rough contact at a slower entrainment (measured:
 * 9-44 when it converges) */
#define DRY_START_ITERATIONS 50

/* A rough contact's nominal extents: where the asperities' pressure
 * exceeds this share of its peak. */
#define NOMINAL_SHARE 0.01

/* Stencil of a row: at most 6 cells whose film enters it. */
#define STENCIL 8

typedef struct {
  size_t nx, ny, n;
  double *xf, *yf; /* faces: nx + 1, ny + 1 */
  double *xc, *yc; /* centres */
  double *dx, *dy; /* widths */
  double *M;       /* influence, row-major n x n: H_k per P_l */
  double *f;       /* undeformed gap (X^2 + Y^2)/2 */
  double *H, *g;   /* film and conductance H^3 of the last evaluation */
  double lambda;
  double load_share; /* the load solved for, per W (1; less on a path to it) */
  double v0_m_s;     /* the speed */
  double *row;       /* a Jacobian row (n + 1) */
  /* per cell, of the last evaluation: the film carried by the entrainment
   * (H; rough: the mean film u + h_rms phi_s) and the derivatives of it and
   * of g with respect to H; the fluid pressure (y itself when smooth) */
  double *cf, *dcf, *dg;
  const double *Pf;
  /* a rough surface (point_ehl.h; NULL: smooth) and, dry, no fluid */
  const vl_persson *roughness;
  bool dry;
  vl_flow_factor_kind flow_factors;
  const vl_emt_table *flow_table;
  double sfac;           /* Pc per Persson's s = pc/|Er|: |Er|/p0 */
  double us_m;           /* the film's unit a^2/R (m) */
  double hrms_m;         /* of the surface */
  double g_floor;        /* conductance floor: a closed cell still fixes its pressure */
  double *Pc, *dPc, *pf; /* contact pressure (p0), dPc/dH, the fluid's */
} ehl;

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void vl_point_ehl_config_defaults(vl_point_ehl_config *cfg) {
  memset(cfg, 0, sizeof *cfg);
  cfg->rubber.nu = 0.5;
  cfg->unit = 1.0;
  cfg->x_in = -3.0, cfg->x_out = 1.6, cfg->y_max = 1.8;
  cfg->h_fine = 0.02, cfg->h_coarse = 0.2, cfg->growth = 1.0;
  cfg->tolerance = 1e-9;
  cfg->max_iterations = 60;
}

/* Distance from t to the nearest zone (0 inside one). */
static double zone_distance(double t, const double (*z)[2], size_t nz, double unit) {
  double d = INFINITY;
  for (size_t i = 0; i < nz; i++) {
    double lo = unit * z[i][0], hi = unit * z[i][1];
    double di = t < lo ? lo - t : t > hi ? t - hi : 0.0;
    d = fmin(d, di);
  }
  return d;
}

/* Faces of a graded 1-D grid on [lo, hi]: the cell size s(t) = min(coarse,
 * fine + growth * distance to a zone); the faces sit at equal steps of
 * N(t) = \int dt/s (trapezoid on 20000 samples, inverted linearly), their
 * number the ceiling of N(hi). Returns the cells, or 0 on allocation
 * failure; *faces malloc'd. */
static size_t graded_faces(double lo, double hi, const double (*z)[2], size_t nz,
                           const vl_point_ehl_config *cfg, double **faces) {
  const size_t ns = 20000;
  double *N = malloc((ns + 1) * sizeof *N);
  if (!N) return 0;
  double dt = (hi - lo) / (double)ns, prev = 0.0;
  N[0] = 0.0;
  for (size_t i = 0; i <= ns; i++) {
    double t = lo + dt * (double)i;
    double s = fmin(cfg->h_coarse, cfg->h_fine + cfg->growth * zone_distance(t, z, nz, cfg->unit));
    if (i > 0) N[i] = N[i - 1] + 0.5 * dt * (1.0 / prev + 1.0 / s);
    prev = s;
  }
  size_t n = (size_t)ceil(N[ns] - 1e-9);
  double *fc = malloc((n + 1) * sizeof *fc);
  if (!fc) {
    free(N);
    return 0;
  }
  size_t j = 0;
  for (size_t k = 0; k <= n; k++) {
    double target = N[ns] * (double)k / (double)n;
    while (j + 1 < ns && N[j + 1] < target)
      j++;
    double w = (target - N[j]) / (N[j + 1] - N[j]);
    fc[k] = lo + dt * ((double)j + w);
  }
  fc[0] = lo, fc[n] = hi;
  free(N);
  *faces = fc;
  return n;
}

static void ehl_free(ehl *e) {
  free(e->xf), free(e->yf), free(e->xc), free(e->yc), free(e->dx), free(e->dy);
  free(e->M), free(e->f), free(e->H), free(e->g), free(e->row);
  free(e->cf), free(e->dcf), free(e->dg), free(e->Pc), free(e->dPc), free(e->pf);
}

/* Hertz's scales of the relaxed rubber: the reduced moduli, a and p0. */
typedef struct {
  double er0, er_inf, a, p0;
} ehl_scales;

static ehl_scales scales_of(const vl_point_ehl_config *cfg) {
  ehl_scales sc;
  double red = 1.0 / (1.0 - cfg->rubber.nu * cfg->rubber.nu);
  sc.er_inf = cfg->rubber.e_inf_pa * red;
  sc.er0 = vl_prony_e0(&cfg->rubber) * red;
  sc.a = cbrt(3.0 * cfg->load_n * cfg->radius_m / (4.0 * sc.er0));
  sc.p0 = 3.0 * cfg->load_n / (2.0 * M_PI * sc.a * sc.a);
  return sc;
}

/* Love's rectangle of source cell l seen from (X, Y), plus its mirror
 * image in y = 0. */
static double love_pair(const ehl *e, double X, double Y, size_t l) {
  size_t il = l / e->ny, jl = l % e->ny;
  double ax = 0.5 * e->dx[il], ay = 0.5 * e->dy[jl], d = X - e->xc[il];
  return vl_kernel2d_rect(d, Y - e->yc[jl], ax, ay) + vl_kernel2d_rect(d, Y + e->yc[jl], ax, ay);
}

/* Upstream of the domain the memory filter starts at X_FAR (units of a)
 * and runs over nodes spaced by at most EXT_RATIO times their distance
 * from the domain's first centre. */
#define X_FAR 200.0
#define EXT_RATIO 0.2

/* One step of the memory filter F' = (K - F)/b along x over a step t =
 * dx/b, K linear between the nodes: F_i = r F_{i-1} + (1 - r - q) K_i +
 * q K_{i-1}, r = e^{-t}, q = (1 - r)/t - r. */
static void filter_step(double t, double *r, double *q) {
  *r = exp(-t);
  *q = t < 1e-3 ? t * (0.5 - t * (1.0 / 3.0 - t / 8.0)) : -expm1(-t) / t - *r;
}

/* The memory: M_kl += sum_m A_m F_m, F_m the displacement of source cell
 * l along the row of its target k filtered by e^{-s/b_m}/b_m over the
 * upstream distance s (docs/POINT_CONTACT.md section 3). The filter runs
 * along each row of targets (K copied before M is added to) from X_FAR upstream, where the source
 * is a point load (the start: its filtered 1/rho, area e^{D/b} E1(D/b)/b), over a geometric
 * extension into the domain's cell centres. Linear interpolation of the displacement between nodes:
 * second order in the cells, checked against the uniform grid's exact cell integrals (kernel2d.c)
 * in tests/test_ball_ehl.c. */
static vl_status add_memory(ehl *e, const double *A, const double *b, size_t nk) {
  size_t nx = e->nx, ny = e->ny, n = e->n, next = 0;
  double x0 = e->xc[0];
  /* extension nodes: upstream of x0, coarsening geometrically */
  double xe[256];
  for (double d = e->dx[0]; next < 255; d *= 1.0 + EXT_RATIO) {
    xe[next++] = x0 - d;
    if (d > X_FAR) break;
  }
  size_t nn = next + nx; /* nodes along a row: extension (far to near), then the domain */
  double *xn = malloc(nn * sizeof *xn), *K = malloc(nn * sizeof *K);
  double *rq = malloc(2 * nk * nn * sizeof *rq);
  if (!xn || !K || !rq) {
    free(xn), free(K), free(rq);
    return VL_ENOMEM;
  }
  for (size_t i = 0; i < next; i++)
    xn[i] = xe[next - 1 - i];
  for (size_t i = 0; i < nx; i++)
    xn[next + i] = e->xc[i];
  for (size_t m = 0; m < nk; m++)
    for (size_t i = 1; i < nn; i++)
      filter_step((xn[i] - xn[i - 1]) / b[m], &rq[2 * (m * nn + i)], &rq[2 * (m * nn + i) + 1]);
  for (size_t j = 0; j < ny; j++)
    for (size_t l = 0; l < n; l++) {
      double Y = e->yc[j], xl = e->xc[l / ny], yl = e->yc[l % ny];
      double area = e->dx[l / ny] * e->dy[l % ny];
      for (size_t i = 0; i < nn; i++)
        K[i] = i < next ? love_pair(e, xn[i], Y, l) : e->M[((i - next) * ny + j) * n + l];
      double D1 = hypot(xl - xn[0], Y - yl), D2 = hypot(xl - xn[0], Y + yl);
      for (size_t m = 0; m < nk; m++) {
        if (!(A[m] > 0.0) || !isfinite(b[m])) continue;
        double F = K[0];
        if (b[m] > 0.0)
          F = area / b[m] *
              (gsl_sf_expint_E1_scaled(D1 / b[m]) + gsl_sf_expint_E1_scaled(D2 / b[m]));
        const double *c = rq + 2 * m * nn;
        for (size_t i = 1; i < nn; i++) {
          if (b[m] > 0.0) {
            double r = c[2 * i], q = c[2 * i + 1];
            F = r * F + (1.0 - r - q) * K[i] + q * K[i - 1];
          } else
            F = K[i];
          if (i >= next) e->M[((i - next) * ny + j) * n + l] += A[m] * F;
        }
      }
    }
  free(xn), free(K), free(rq);
  return VL_OK;
}

/* A rough surface's constants and per-cell arrays: the asperity modulus
 * |Er| at the frequency pi v0/a_H of the contact (the line contact's fixed
 * point, docs/MODEL.md section 4, with a ball's Hertz radius). */
static vl_status rough_build(ehl *e, const vl_point_ehl_config *cfg) {
  size_t n = e->n;
  ehl_scales sc = scales_of(cfg);
  double e_abs;
  vl_asperity_state_ball(&cfg->rubber, cfg->load_n, cfg->radius_m, cfg->v0_m_s, &e_abs, NULL, NULL);
  e->roughness = cfg->roughness, e->dry = !(cfg->eta_pa_s > 0.0);
  e->flow_factors = cfg->flow_factors, e->flow_table = cfg->flow_table;
  e->sfac = e_abs / sc.p0;
  e->us_m = sc.a * sc.a / cfg->radius_m;
  e->hrms_m = vl_persson_hrms(cfg->roughness);
  e->g_floor = 1e-12 * pow(e->hrms_m / e->us_m, 3.0);
  e->Pc = malloc(n * sizeof(double)), e->dPc = malloc(n * sizeof(double));
  e->pf = malloc(n * sizeof(double));
  return e->Pc && e->dPc && e->pf ? VL_OK : VL_ENOMEM;
}

/* The grid, the undeformed gap and the dense influence matrix. */
static vl_status ehl_build(ehl *e, const vl_point_ehl_config *cfg, vl_error *err) {
  memset(e, 0, sizeof *e);
  e->nx = graded_faces(cfg->x_in, cfg->x_out, ZONE_X, 2, cfg, &e->xf);
  e->ny = graded_faces(0.0, cfg->y_max, ZONE_Y, 1, cfg, &e->yf);
  if (!e->nx || !e->ny) goto nomem;
  size_t nx = e->nx, ny = e->ny, n = nx * ny;
  e->n = n;
  e->xc = malloc(nx * sizeof(double)), e->dx = malloc(nx * sizeof(double));
  e->yc = malloc(ny * sizeof(double)), e->dy = malloc(ny * sizeof(double));
  e->M = malloc(n * n * sizeof(double));
  e->f = malloc(n * sizeof(double)), e->H = malloc(n * sizeof(double));
  e->g = malloc(n * sizeof(double)), e->row = malloc((n + 1) * sizeof(double));
  e->cf = malloc(n * sizeof(double)), e->dcf = malloc(n * sizeof(double));
  e->dg = malloc(n * sizeof(double));
  if (!e->xc || !e->dx || !e->yc || !e->dy || !e->M || !e->f || !e->H || !e->g || !e->row ||
      !e->cf || !e->dcf || !e->dg)
    goto nomem;
  if (cfg->roughness && rough_build(e, cfg) != VL_OK) goto nomem;
  for (size_t i = 0; i < nx; i++)
    e->xc[i] = 0.5 * (e->xf[i] + e->xf[i + 1]), e->dx[i] = e->xf[i + 1] - e->xf[i];
  for (size_t j = 0; j < ny; j++)
    e->yc[j] = 0.5 * (e->yf[j] + e->yf[j + 1]), e->dy[j] = e->yf[j + 1] - e->yf[j];
  for (size_t k = 0; k < n; k++) {
    double X = e->xc[k / ny], Y = e->yc[k % ny];
    e->f[k] = 0.5 * (X * X + Y * Y);
  }
  for (size_t k = 0; k < n; k++)
    for (size_t l = 0; l < n; l++)
      e->M[k * n + l] = love_pair(e, e->xc[k / ny], e->yc[k % ny], l);
  /* the Prony terms' strengths and memory lengths v0 tau/a */
  const vl_prony *rb = &cfg->rubber;
  double b[VL_PRONY_MAX_TERMS];
  ehl_scales sc = scales_of(cfg);
  for (size_t m = 0; m < rb->n_terms; m++)
    b[m] = cfg->v0_m_s * rb->tau_s[m] / sc.a;
  if (rb->n_terms && add_memory(e, rb->A, b, rb->n_terms) != VL_OK) goto nomem;
  /* H per P: 2/pi^2 Er0/Er_inf (Hertz's scales are the relaxed rubber's) */
  double c = 2.0 / (M_PI * M_PI) * sc.er0 / sc.er_inf;
  for (size_t k = 0; k < n * n; k++)
    e->M[k] *= c;
  return VL_OK;
nomem:
  ehl_free(e);
  vl_error_set(err, "out of memory for the lubricated ball's grid and influence matrix");
  return VL_ENOMEM;
}

/* A rough cell k at film H_k and total pressure q: Persson's contact
 * pressure at the mean separation u (docs/MODEL.md section 4), the fluid's
 * q - Pc, and with a fluid the flow quantities of the averaged Reynolds
 * equation: the conductance u^3 phi_p and the film u + h_rms phi_s carried
 * by the entrainment (docs/FLOW_FACTORS.md; the line contact's
 * contact_equations.c: eval_flow). A Newton iterate that crosses u < 0 gets
 * no flow there (the contact pressure is then enormous but finite). */
static void rough_cell(ehl *e, size_t k, double q) {
  double us = e->us_m, u = e->H[k] * us, dsdu;
  double s = vl_persson_pressure(e->roughness, u, &dsdu);
  e->Pc[k] = e->sfac * s, e->dPc[k] = e->sfac * dsdu * us;
  if (e->dry) { /* the asperities carry q (to the solver's tolerance) */
    e->pf[k] = 0.0;
    return;
  }
  e->pf[k] = q - e->Pc[k];
  vl_flow_factor_values v, d;
  double up = fmax(u, 0.0), on = u > 0.0 ? 1.0 : 0.0, u3 = up * up * up;
  vl_flow_factors_eval_table(e->flow_factors, e->flow_table, up, e->hrms_m, &v, &d);
  e->g[k] = u3 * v.phi_p / (us * us * us) + e->g_floor;
  e->dg[k] = on * (3.0 * up * up * v.phi_p + u3 * d.phi_p) / (us * us);
  e->cf[k] = (up + e->hrms_m * v.phi_s) / us;
  e->dcf[k] = on * (1.0 + e->hrms_m * d.phi_s);
}

/* H = H0 + f + M y; smooth: g = H^3 (H floored at 1e-12 in g: a closing
 * film during the iterations), the entrained film H and the fluid pressure
 * y; rough: rough_cell. */
static void ehl_eval(ehl *e, const double *y) {
  size_t n = e->n;
  double H0 = y[n];
  for (size_t k = 0; k < n; k++) {
    const double *Mk = e->M + k * n;
    double s = 0.0;
    for (size_t l = 0; l < n; l++)
      s += Mk[l] * y[l];
    e->H[k] = H0 + e->f[k] + s;
    if (e->roughness) {
      rough_cell(e, k, y[k]);
      continue;
    }
    double h = fmax(e->H[k], 1e-12);
    e->g[k] = h * h * h;
    e->dg[k] = e->H[k] > 1e-12 ? 3.0 * h * h : 0.0;
    e->cf[k] = e->H[k], e->dcf[k] = 1.0;
  }
  e->Pf = e->roughness ? e->pf : y;
}

/* Film carried across the x face between cells i - 1 and i of row j
 * (i = 0 .. nx): the line contact's couette_face on this grid (the
 * van Albada limited extrapolation from the upwind cell; the inlet faces 0
 * and 1 unlimited, the outlet face the upwind cell) of the cells' films
 * cf. Writes the cells and the derivatives of the value per film. */
static double couette_value(const ehl *e, size_t i, size_t j, size_t kk[3], double w[3], int *m) {
  size_t nx = e->nx, ny = e->ny;
  const double *H = e->cf;
  if (i == nx) {
    kk[0] = (nx - 1) * ny + j, w[0] = 1.0, *m = 1;
    return H[kk[0]];
  }
  if (i <= 1) {
    double t = e->dx[0] / (e->dx[0] + e->dx[1]);
    kk[0] = j, kk[1] = ny + j, w[0] = i ? 1.0 - t : 1.0 + t, w[1] = i ? t : -t, *m = 2;
    return w[0] * H[kk[0]] + w[1] * H[kk[1]];
  }
  size_t C = (i - 1) * ny + j, U = (i - 2) * ny + j, D = i * ny + j;
  double a = H[D] - H[C], b = H[C] - H[U];
  kk[0] = C, kk[1] = U, kk[2] = D, *m = 3;
  if (!(a * b > 0.0)) {
    w[0] = 1.0, w[1] = 0.0, w[2] = 0.0;
    return H[C];
  }
  double s = a * a + b * b, inc = 0.5 * a * b * (a + b) / s;
  double da = 0.5 * b * b * (2.0 * a * b - a * a + b * b) / (s * s);
  double db = 0.5 * a * a * (2.0 * a * b - b * b + a * a) / (s * s);
  w[0] = 1.0 - da + db, w[1] = -db, w[2] = da;
  return H[C] + inc;
}

/* The same with the derivatives per H (the film's own). */
static double couette_face(const ehl *e, size_t i, size_t j, size_t kk[3], double w[3], int *m) {
  double v = couette_value(e, i, j, kk, w, m);
  for (int q = 0; q < *m; q++)
    w[q] *= e->dcf[kk[q]]; /* per H: the entrained film's own derivative */
  return v;
}

/* Conductance of the face between cells k and l (harmonic mean of g)
 * and its derivatives with respect to g_k and g_l. */
static double face_g(const ehl *e, size_t k, size_t l, double *dk, double *dl) {
  double gk = e->g[k], gl = e->g[l], s = gk + gl;
  if (!(s > 0.0)) {
    *dk = *dl = 0.0;
    return 0.0;
  }
  *dk = 2.0 * gl * gl / (s * s), *dl = 2.0 * gk * gk / (s * s);
  return 2.0 * gk * gl / s;
}

/* A row's dependences: direct on pressures (P, up to 5) and on films. */
typedef struct {
  size_t pk[5];
  double pw[5];
  int np;
  size_t hk[3 * STENCIL];
  double hw[3 * STENCIL];
  int nh;
} row_deps;

/* Adds w to the weight of cell k in the sparse list (keys, weights, *n). */
static void add_dep(size_t *keys, double *weights, int *n, size_t k, double w) {
  for (int q = 0; q < *n; q++)
    if (keys[q] == k) {
      weights[q] += w;
      return;
    }
  keys[*n] = k, weights[*n] = w, (*n)++;
}

static void add_h(row_deps *d, size_t k, double w) { add_dep(d->hk, d->hw, &d->nh, k, w); }
static void add_p(row_deps *d, size_t k, double w) { add_dep(d->pk, d->pw, &d->np, k, w); }

/* Poiseuille flux out of cell k towards neighbour l (or the boundary,
 * l = SIZE_MAX, P = 0 at the face), over distance dist and face length
 * len: -g (P_l - P_k)/dist len, with its dependences. */
static double poiseuille_out(const ehl *e, const double *P, size_t k, size_t l, double dist,
                             double len, row_deps *d) {
  if (l == SIZE_MAX) { /* to the boundary: the cell's own conductance */
    double c = len / dist;
    if (d) add_p(d, k, e->g[k] * c), add_h(d, k, e->dg[k] * P[k] * c);
    return e->g[k] * P[k] * c;
  }
  double dk, dl, gf = face_g(e, k, l, &dk, &dl), c = len / dist, dP = P[l] - P[k];
  if (d) {
    add_p(d, k, gf * c), add_p(d, l, -gf * c);
    add_h(d, k, -dk * e->dg[k] * dP * c), add_h(d, l, -dl * e->dg[l] * dP * c);
  }
  return -gf * dP * c;
}

/* The flux out of cell (i, j), r/(lambda dx dy) (scaled to about dH/dX),
 * with its dependences when d is not NULL. */
static double flow_row(const ehl *e, const double *P, size_t i, size_t j, row_deps *d) {
  size_t nx = e->nx, ny = e->ny, k = i * ny + j;
  double dx = e->dx[i], dy = e->dy[j], lam = e->lambda, scale = 1.0 / (lam * dx * dy);
  if (d) d->np = 0, d->nh = 0;
  size_t kk[3];
  double w[3];
  int m;
  /* Couette: out through the east face, in through the west */
  double r = 0.0;
  double he = couette_face(e, i + 1, j, kk, w, &m);
  r += lam * he * dy;
  if (d)
    for (int q = 0; q < m; q++)
      add_h(d, kk[q], lam * dy * w[q]);
  double hw = couette_face(e, i, j, kk, w, &m);
  r -= lam * hw * dy;
  if (d)
    for (int q = 0; q < m; q++)
      add_h(d, kk[q], -lam * dy * w[q]);
  /* Poiseuille through the four faces (none through y = 0) */
  if (i + 1 < nx)
    r += poiseuille_out(e, P, k, k + ny, e->xc[i + 1] - e->xc[i], dy, d);
  else
    r += poiseuille_out(e, P, k, SIZE_MAX, 0.5 * dx, dy, d);
  if (i > 0)
    r += poiseuille_out(e, P, k, k - ny, e->xc[i] - e->xc[i - 1], dy, d);
  else
    r += poiseuille_out(e, P, k, SIZE_MAX, 0.5 * dx, dy, d);
  if (j + 1 < ny)
    r += poiseuille_out(e, P, k, k + 1, e->yc[j + 1] - e->yc[j], dx, d);
  else
    r += poiseuille_out(e, P, k, SIZE_MAX, 0.5 * dy, dx, d);
  if (j > 0) r += poiseuille_out(e, P, k, k - 1, e->yc[j] - e->yc[j - 1], dx, d);
  if (d) {
    for (int q = 0; q < d->np; q++)
      d->pw[q] *= scale;
    for (int q = 0; q < d->nh; q++)
      d->hw[q] *= scale;
  }
  return r * scale;
}

static double load_row(const ehl *e, const double *P) {
  double s = 0.0;
  for (size_t k = 0; k < e->n; k++)
    s += P[k] * e->dx[k / e->ny] * e->dy[k % e->ny];
  return s * 3.0 / M_PI - e->load_share;
}

/* Fischer-Burmeister: a + b - sqrt(a^2 + b^2) = 0 iff a, b >= 0 and
 * a b = 0; smooth but at the origin (there the min's derivative), so a
 * line search on its norm works where one on min(a, b) stalls at the
 * switches of the cavitation boundary. */
static double fb(double a, double b, double *da, double *db) {
  double rho = hypot(a, b);
  if (da) {
    if (rho > 0.0)
      *da = 1.0 - a / rho, *db = 1.0 - b / rho;
    else
      *da = a <= b ? 1.0 : 0.0, *db = a <= b ? 0.0 : 1.0;
  }
  return a + b - rho;
}

/* Row k's residual: dry rough, the contact law y_k = Pc(H_k); else the
 * cavitation complementarity of the fluid pressure and the flux out. */
static double row_residual(ehl *e, const double *y, size_t i, size_t j, row_deps *d, double *dp,
                           double *dr) {
  size_t k = i * e->ny + j;
  if (e->dry) {
    if (d) d->np = 0, d->nh = 0;
    return y[k] - e->Pc[k];
  }
  double r = flow_row(e, e->Pf, i, j, d);
  return fb(e->Pf[k], r, d ? dp : NULL, dr);
}

static int residual_fn(N_Vector yv, N_Vector fv, void *user) {
  ehl *e = user;
  const double *y = N_VGetArrayPointer(yv);
  double *f = N_VGetArrayPointer(fv);
  ehl_eval(e, y);
  /* a closed film is no state of a smooth lubricated contact: a
   * recoverable failure, on which KINSOL's line search shortens the step
   * (a rough one is held open by the asperities' pressure) */
  for (size_t k = 0; k < e->n && !e->roughness; k++)
    if (!(e->H[k] > 0.0)) return 1;
  for (size_t i = 0; i < e->nx; i++)
    for (size_t j = 0; j < e->ny; j++) {
      size_t k = i * e->ny + j;
      f[k] = row_residual(e, y, i, j, NULL, NULL, NULL);
      if (!isfinite(f[k])) return 1;
    }
  f[e->n] = load_row(e, y);
  return 0;
}

/* row += sum_q w[q] (row m[q] of M, and 1 in the column of H0): the
 * derivative of the films H_m. */
static void add_film_rows(const ehl *e, double *row, const size_t *m, const double *w, int nw) {
  size_t n = e->n;
  for (int q = 0; q < nw; q++) {
    if (w[q] == 0.0) continue;
    const double *Mm = e->M + m[q] * n;
    for (size_t l = 0; l < n; l++)
      row[l] += w[q] * Mm[l];
    row[n] += w[q];
  }
}

/* Row k of the Jacobian per the unknowns y (the total pressure; smooth:
 * the fluid's) and H0, into e->row: the direct dependence on the fluid
 * pressures dPf/dy = 1, and the films' through M, to which a rough cell's
 * fluid pressure y - Pc(H) adds -dPc/dH. */
static void jacobian_row(ehl *e, const double *y, size_t i, size_t j) {
  size_t n = e->n, k = i * e->ny + j, cells[4 * STENCIL];
  double *row = e->row, dp = 0.0, dr = 0.0, w[4 * STENCIL];
  int nw = 0;
  row_deps d;
  memset(row, 0, (n + 1) * sizeof *row);
  row_residual(e, y, i, j, &d, &dp, &dr);
  if (e->dry) dp = 1.0; /* y_k - Pc(H_k) */
  row[k] += dp;
  if (e->roughness) cells[nw] = k, w[nw++] = -dp * e->dPc[k];
  if (dr == 0.0) {
    add_film_rows(e, row, cells, w, nw);
    return;
  }
  for (int q = 0; q < d.nh; q++)
    cells[nw] = d.hk[q], w[nw++] = dr * d.hw[q];
  for (int q = 0; q < d.np && e->roughness; q++)
    cells[nw] = d.pk[q], w[nw++] = -dr * d.pw[q] * e->dPc[d.pk[q]];
  add_film_rows(e, row, cells, w, nw);
  for (int q = 0; q < d.np; q++)
    row[d.pk[q]] += dr * d.pw[q];
}

static int jacobian_fn(N_Vector yv, N_Vector fv, SUNMatrix J, void *user, N_Vector t1,
                       N_Vector t2) {
  (void)fv, (void)t1, (void)t2;
  ehl *e = user;
  const double *y = N_VGetArrayPointer(yv);
  size_t n = e->n, ld = n + 1;
  double *Jd = SUNDenseMatrix_Data(J);
  ehl_eval(e, y);
  for (size_t i = 0; i < e->nx; i++)
    for (size_t j = 0; j < e->ny; j++) {
      size_t k = i * e->ny + j;
      jacobian_row(e, y, i, j);
      for (size_t l = 0; l <= n; l++)
        Jd[l * ld + k] = e->row[l];
    }
  for (size_t l = 0; l < n; l++)
    Jd[l * ld + n] = e->dx[l / e->ny] * e->dy[l % e->ny] * 3.0 / M_PI;
  Jd[n * ld + n] = 0.0;
  return 0;
}

static void silent(int code, const char *module, const char *function, char *msg, void *user) {
  (void)code, (void)module, (void)function, (void)msg, (void)user;
}

static vl_status check_config(const vl_point_ehl_config *c, vl_error *err) {
  vl_status st = vl_prony_validate(&c->rubber, err);
  if (st != VL_OK) return st;
  struct {
    const char *name;
    double v;
  } pos[] = {{"radius_m", c->radius_m},
             {"load_n", c->load_n},
             {"e_inf_pa", c->rubber.e_inf_pa},
             /* a smooth ball needs a fluid; a rough one may be dry */
             {"eta_pa_s", c->roughness && c->eta_pa_s == 0.0 ? 1.0 : c->eta_pa_s},
             {"v0_m_s", c->v0_m_s},
             {"h_fine", c->h_fine},
             {"h_coarse", c->h_coarse},
             {"growth", c->growth},
             {"x_out", c->x_out},
             {"y_max", c->y_max},
             {"tolerance", c->tolerance},
             {"unit", c->unit}};
  for (size_t i = 0; i < sizeof pos / sizeof pos[0]; i++)
    if (!(pos[i].v > 0.0) || !isfinite(pos[i].v)) {
      vl_error_set(err, "point EHL: %s must be positive and finite (got %g)", pos[i].name,
                   pos[i].v);
      return VL_EINPUT;
    }
  if (!(c->x_in < -1.2 * c->unit) || !(c->x_out > 1.2 * c->unit) || !(c->y_max > 1.2 * c->unit)) {
    vl_error_set(err,
                 "point EHL: the domain x_in %g, x_out %g, y_max %g must reach beyond "
                 "1.2 units (%g Hertz radii)",
                 c->x_in, c->x_out, c->y_max, c->unit);
    return VL_EINPUT;
  }
  if (!(c->rubber.nu >= 0.0 && c->rubber.nu <= 0.5)) {
    vl_error_set(err, "point EHL: nu must be in [0, 0.5] (got %g)", c->rubber.nu);
    return VL_EINPUT;
  }
  if (c->roughness && !(c->sigma_s_pa >= 0.0 && isfinite(c->sigma_s_pa))) {
    vl_error_set(err, "point EHL: sigma_s_pa must be finite and >= 0 (got %g)", c->sigma_s_pa);
    return VL_EINPUT;
  }
  if (!(c->h_fine <= c->h_coarse) || c->max_iterations < 1) {
    vl_error_set(err, "point EHL: h_fine %g must not exceed h_coarse %g, max_iterations >= 1",
                 c->h_fine, c->h_coarse);
    return VL_EINPUT;
  }
  return VL_OK;
}

void vl_point_ehl_hamrock_dowson(const vl_point_ehl_config *cfg, double *h_min_m, double *h_c_m) {
  double Ep = 2.0 * scales_of(cfg).er0, R = cfg->radius_m;
  double U = cfg->eta_pa_s * 0.5 * cfg->v0_m_s / (Ep * R), W = cfg->load_n / (Ep * R * R);
  *h_min_m = R * 7.43 * pow(U, 0.65) * pow(W, -0.21) * (1.0 - 0.85 * exp(-0.31));
  *h_c_m = R * 7.32 * pow(U, 0.64) * pow(W, -0.22) * (1.0 - 0.72 * exp(-0.28));
}

/* H at the centre: linear in x between the cells that bracket 0, even in y
 * (a + b y^2 through the first two rows). */
static double centre_film(const ehl *e) {
  size_t ny = e->ny, i = 0;
  while (i + 2 < e->nx && e->xc[i + 1] < 0.0)
    i++;
  double t = (0.0 - e->xc[i]) / (e->xc[i + 1] - e->xc[i]), y0 = e->yc[0], y1 = e->yc[1];
  double h0 = (1.0 - t) * e->H[i * ny] + t * e->H[(i + 1) * ny];
  double h1 = (1.0 - t) * e->H[i * ny + 1] + t * e->H[(i + 1) * ny + 1];
  double b = (h1 - h0) / (y1 * y1 - y0 * y0), h = h0 - b * y0 * y0;
  return h >= TRUST_VERTEX * h0 ? h : h0; /* (as a parabola's vertex, min_film) */
}

/* The film on the centre line at X (units of a): linear between the
 * first row's cells. */
static double axis_film_at(const ehl *e, double X) {
  size_t ny = e->ny, i = 0;
  while (i + 2 < e->nx && e->xc[i + 1] < X)
    i++;
  double t = fmin(1.0, fmax(0.0, (X - e->xc[i]) / (e->xc[i + 1] - e->xc[i])));
  return (1.0 - t) * e->H[i * ny] + t * e->H[(i + 1) * ny];
}

/* Vertex of the parabola through (t0, v0), (t1, v1), (t2, v2) (t1 the
 * smallest value): the value and position; the middle point when flat. */
static double parabola_min(double t0, double t1, double t2, double v0, double v1, double v2,
                           double *tmin) {
  double d0 = (v1 - v0) / (t1 - t0), d1 = (v2 - v1) / (t2 - t1), c = (d1 - d0) / (t2 - t0);
  *tmin = t1;
  if (!(c > 0.0)) return v1;
  double b = d0 - c * (t1 - t0); /* slope at t1 of the parabola */
  double s = -b / (2.0 * c);
  if (fabs(s) > 0.5 * (t2 - t0)) return v1;
  *tmin = t1 + s;
  return v1 + b * s + c * s * s;
}

/* The minimum film along row j (fixed y): the smallest cell film refined
 * by the parabola through it and its two neighbours along x. */
static double row_min(const ehl *e, size_t j, double *xm) {
  size_t nx = e->nx, ny = e->ny, ib = 0;
  for (size_t i = 1; i < nx; i++)
    if (e->H[i * ny + j] < e->H[ib * ny + j]) ib = i;
  *xm = e->xc[ib];
  double cell = e->H[ib * ny + j];
  if (ib == 0 || ib + 1 == nx) return cell;
  double v = parabola_min(e->xc[ib - 1], e->xc[ib], e->xc[ib + 1], e->H[(ib - 1) * ny + j], cell,
                          e->H[(ib + 1) * ny + j], xm);
  /* a vertex far below the cells is a valley the cells do not resolve (a
   * kink, not a parabola): the cell's own value, which the error estimate
   * then sees change with the cells */
  if (!(v >= TRUST_VERTEX * cell)) {
    *xm = e->xc[ib];
    return cell;
  }
  return v;
}

/* The minimum film, following the valley of the film: each row's minimum
 * along x (row_min), then the parabola across through the smallest row
 * minimum and its neighbours' (on the centre line: the row's own). The
 * cells' own minimum jumps between cells as the grid changes where the
 * valley crosses the cells obliquely (the side lobes). */
static double min_film(const ehl *e, double *xm, double *ym, bool axis_only) {
  size_t ny = e->ny, jb = 0;
  double best = row_min(e, 0, xm);
  *ym = 0.0;
  if (axis_only) return best;
  for (size_t j = 1; j < ny; j++) {
    double x, v = row_min(e, j, &x);
    if (v < best) best = v, jb = j, *xm = x;
  }
  *ym = e->yc[jb];
  if (jb == 0 || jb + 1 == ny) return best;
  double x0, x2, v0 = row_min(e, jb - 1, &x0), v2 = row_min(e, jb + 1, &x2), y;
  double v = parabola_min(e->yc[jb - 1], e->yc[jb], e->yc[jb + 1], v0, best, v2, &y);
  if (!(v >= TRUST_VERTEX * best)) return best; /* see row_min */
  /* the x of the valley at y: linear between the rows' minima */
  if (y < e->yc[jb])
    *xm += (x0 - *xm) * (e->yc[jb] - y) / (e->yc[jb] - e->yc[jb - 1]);
  else
    *xm += (x2 - *xm) * (y - e->yc[jb]) / (e->yc[jb + 1] - e->yc[jb]);
  *ym = y;
  return v;
}

/* The film fraction of a cell along a row run upstream to downstream
 * (P its pressure in p0, u its gap, X its centre; *hrupture the gap at the
 * last pressurised cell, NAN before one): 1 up to the pressure's end;
 * beyond it, in the cavitated outlet, the flow is Couette only and the film
 * fills theta = u_rupture/u of the gap. */
static double film_fraction(double P, double u, double X, double *hrupture) {
  if (P > PRESSURISED) {
    *hrupture = u;
    return 1.0;
  }
  return isfinite(*hrupture) && X > 0.0 ? fmin(1.0, *hrupture / u) : 1.0;
}

/* The derivative of v (cell values, stride `stride`, n cells along a
 * line, centres t) at cell i: the mean of its two face differences, the
 * boundary value 0 beyond the ends (at the domain's faces lo, hi). */
static double cell_slope(const double *v, size_t stride, const double *t, size_t n, size_t i,
                         double lo, double hi, bool zero_beyond) {
  double c = v[i * stride];
  double vw = i > 0 ? v[(i - 1) * stride] : (zero_beyond ? 0.0 : c);
  double ve = i + 1 < n ? v[(i + 1) * stride] : (zero_beyond ? 0.0 : c);
  double tw = i > 0 ? t[i - 1] : lo, te = i + 1 < n ? t[i + 1] : hi;
  return 0.5 * ((c - vw) / (t[i] - tw) + (ve - c) / (te - t[i]));
}

/* The energy balance's terms (both halves, W): the viscous dissipation in
 * the film, eta v0^2/u (in the cavitated outlet theta of it, as the shear)
 * plus u^3/(12 eta) |grad p|^2, and the power the pressure puts into the
 * rubber, v0 \int p dw/dx dA (0 for an elastic rubber in steady sliding,
 * the hysteresis for a viscoelastic one; y the total pressure). Their sum is (mu_Rf + mu_Sf) W v0
 * up to the discretisation (tests/test_ball_ehl.c). */
static void energy(const ehl *e, const vl_point_ehl_config *cfg, const double *y, double a,
                   double p0, vl_point_ehl_result *res) {
  size_t nx = e->nx, ny = e->ny, n = e->n;
  double R = cfg->radius_m, us = a * a / R, eta = cfg->eta_pa_s, v0 = cfg->v0_m_s;
  double *w = malloc(n * sizeof *w);
  if (!w) {
    res->dissipation_w = res->hysteresis_w = NAN;
    return;
  }
  for (size_t k = 0; k < n; k++)
    w[k] = e->H[k] - y[n] - e->f[k];
  double visc = 0.0, hyst = 0.0;
  for (size_t j = 0; j < ny; j++) {
    double hrupture = NAN;
    for (size_t i = 0; i < nx; i++) {
      size_t k = i * ny + j;
      double dA = e->dx[i] * e->dy[j] * a * a, u = e->H[k] * us;
      const double *Pf = e->Pf;
      double theta = film_fraction(Pf[k], u, e->xc[i], &hrupture);
      double gx = cell_slope(Pf + j, ny, e->xc, nx, i, e->xf[0], e->xf[nx], true) * p0 / a;
      double gy = cell_slope(Pf + i * ny, 1, e->yc, ny, j, -e->yc[0], e->yf[ny], true) * p0 / a;
      if (j == 0) gy = 0.5 * (Pf[k + 1] - Pf[k]) / (e->yc[1] - e->yc[0]) * p0 / a; /* symmetric */
      visc += (theta * eta * v0 * v0 / u + u * u * u / (12.0 * eta) * (gx * gx + gy * gy)) * dA;
      double dw = cell_slope(w + j, ny, e->xc, nx, i, e->xf[0], e->xf[nx], false) * us / a;
      hyst += v0 * y[k] * p0 * dw * dA;
    }
  }
  free(w);
  /* (a rough film's dissipation would need its flow factors: not reported) */
  res->dissipation_w = e->roughness ? NAN : 2.0 * visc, res->hysteresis_w = 2.0 * hyst;
}

/* The nominal contact of a rough state (e evaluated): the extents of the
 * cells whose asperity pressure exceeds NOMINAL_SHARE of its peak. */
static void nominal_extents(const ehl *e, double a, vl_point_ehl_result *res) {
  res->contact_length_m = res->contact_breadth_m = 0.0;
  if (!e->roughness) return;
  double peak = 0.0, x0 = INFINITY, x1 = -INFINITY, y1 = 0.0;
  for (size_t k = 0; k < e->n; k++)
    peak = fmax(peak, e->Pc[k]);
  for (size_t k = 0; k < e->n; k++) {
    if (!(e->Pc[k] > NOMINAL_SHARE * peak)) continue;
    size_t i = k / e->ny, j = k % e->ny;
    x0 = fmin(x0, e->xf[i]), x1 = fmax(x1, e->xf[i + 1]), y1 = fmax(y1, e->yf[j + 1]);
  }
  if (x1 > x0) res->contact_length_m = (x1 - x0) * a, res->contact_breadth_m = 2.0 * y1 * a;
}

/* Figures of the converged (or last) state y into res. */
static void report(ehl *e, const vl_point_ehl_config *cfg, const double *y, double a, double p0,
                   vl_point_ehl_result *res) {
  size_t n = e->n, ny = e->ny;
  double R = cfg->radius_m, us = a * a / R, W = cfg->load_n;
  ehl_eval(e, y);
  res->h_c_m = centre_film(e) * us;
  double xm, ym;
  res->h_min_m = min_film(e, &xm, &ym, false) * us;
  res->x_min_m = xm * a, res->y_min_m = ym * a;
  res->h_min_axis_m = min_film(e, &xm, &ym, true) * us;
  res->h0_m = y[n] * us;
  res->load_error = load_row(e, y);
  /* friction (docs/POINT_CONTACT.md sections 9 and 10): both halves, per W */
  const double *Pf = e->Pf;
  double spx = 0.0, scx = 0.0, couette = 0.0, pois = 0.0, area = 0.0, sf = 0.0;
  for (size_t j = 0; j < ny; j++) {
    double hrupture = NAN;
    for (size_t i = 0; i < e->nx; i++) {
      size_t k = i * ny + j;
      double dA = e->dx[i] * e->dy[j] * a * a, p = Pf[k] * p0, u = e->H[k] * us;
      spx += p * e->xc[i] * a * dA;
      sf += Pf[k] * e->dx[i] * e->dy[j];
      /* the wall shear's flow factors (smooth: 1, 0 and 1) */
      vl_flow_factor_values v = {1.0, 0.0, 1.0, 0.0, 1.0};
      if (e->roughness) {
        scx += e->Pc[k] * p0 * e->xc[i] * a * dA;
        area += vl_persson_area_ratio(e->roughness, e->Pc[k] / e->sfac, NULL) * dA;
        if (e->dry) continue;
        vl_flow_factors_eval_table(e->flow_factors, e->flow_table, fmax(u, 0.0), e->hrms_m, &v,
                                   NULL);
      }
      double theta = film_fraction(Pf[k], u, e->xc[i], &hrupture);
      if (u > 0.0) couette += theta * (v.phi_f + v.phi_fs) * cfg->eta_pa_s * cfg->v0_m_s / u * dA;
      double dpdx = cell_slope(Pf + j, ny, e->xc, e->nx, i, e->xf[0], e->xf[e->nx], true) * p0 / a;
      pois += -0.5 * v.phi_fp * u * dpdx * dA;
    }
  }
  nominal_extents(e, a, res);
  res->x_centroid_m = 2.0 * (spx + scx) / W;
  res->h_centroid_m = axis_film_at(e, res->x_centroid_m / a) * us;
  size_t kmax = 0;
  for (size_t k = 1; k < n; k++)
    if (y[k] > y[kmax]) kmax = k;
  res->p_max_pa = y[kmax] * p0;
  res->x_pmax_m = e->xc[kmax / ny] * a, res->y_pmax_m = e->yc[kmax % ny] * a;
  res->mu_Rf = -2.0 * spx / (W * R);
  res->mu_Rc = -2.0 * scx / (W * R);
  res->real_area_m2 = 2.0 * area;
  res->mu_Sc = cfg->sigma_s_pa * res->real_area_m2 / W;
  res->fluid_load_fraction = sf * 3.0 / M_PI;
  res->e_abs_pa = e->roughness ? e->sfac * p0 : 0.0;
  res->mu_Sf_couette = 2.0 * couette / W;
  res->mu_Sf_poiseuille = 2.0 * pois / W;
  res->mu_Sf = res->mu_Sf_couette + res->mu_Sf_poiseuille;
  energy(e, cfg, y, a, p0, res);
}

/* The fields of state y (SI units) into map. */
static vl_status map_of(ehl *e, const double *y, double a, double p0, double us,
                        vl_point_ehl_map *map, vl_error *err) {
  size_t n = e->n;
  memset(map, 0, sizeof *map);
  map->x_m = malloc(5 * n * sizeof *map->x_m);
  if (!map->x_m) {
    vl_error_set(err, "out of memory for the lubricated ball's fields (%zu cells)", n);
    return VL_ENOMEM;
  }
  map->y_m = map->x_m + n, map->p_pa = map->x_m + 2 * n, map->u_m = map->x_m + 3 * n;
  map->pc_pa = map->x_m + 4 * n;
  map->nx = e->nx, map->ny = e->ny;
  map->h0_m = y[n] * us;
  map->v0_m_s = e->v0_m_s;
  ehl_eval(e, y);
  for (size_t k = 0; k < n; k++) {
    map->x_m[k] = e->xc[k / e->ny] * a, map->y_m[k] = e->yc[k % e->ny] * a;
    map->p_pa[k] = e->Pf[k] * p0, map->u_m[k] = e->H[k] * us;
    map->pc_pa[k] = e->roughness ? e->Pc[k] * p0 : 0.0;
  }
  return VL_OK;
}

void vl_point_ehl_map_free(vl_point_ehl_map *map) {
  if (map) free(map->x_m), memset(map, 0, sizeof *map);
}

/* Raises the rigid approach yd[n] so that the film of state yd is nowhere
 * below `floor` (units of a^2/R). */
static void raise_min_film(ehl *e, double *yd, double floor) {
  ehl_eval(e, yd);
  double hmin = INFINITY;
  for (size_t k = 0; k < e->n; k++)
    hmin = fmin(hmin, e->H[k]);
  yd[e->n] += fmax(0.0, floor - hmin);
}

/* The state of another grid's solution `from` (the same contact) on e's
 * cells: its pressure bilinear between its cell centres (0 beyond them),
 * its rigid approach raised where needed to keep half its smallest film
 * open. False when from has too few cells (or memory ran out). */
static bool start_from_map(ehl *e, double *yd, const vl_point_ehl_map *from, double a, double p0,
                           double us) {
  size_t fx = from->nx, fy = from->ny, n = e->n;
  if (fx < 2 || fy < 2) return false;
  double *xs = malloc((fx + fy) * sizeof *xs), *ys = xs + fx; /* its centres, units of a */
  if (!xs) return false;
  for (size_t i = 0; i < fx; i++)
    xs[i] = from->x_m[i * fy] / a;
  for (size_t j = 0; j < fy; j++)
    ys[j] = from->y_m[j] / a;
  for (size_t k = 0; k < n; k++) {
    double X = e->xc[k / e->ny], Y = e->yc[k % e->ny];
    if (X < xs[0] || X > xs[fx - 1] || Y > ys[fy - 1]) {
      yd[k] = 0.0;
      continue;
    }
    size_t i = vl_bracket(xs, fx, X), j = Y < ys[0] ? 0 : vl_bracket(ys, fy, Y);
    double t = (X - xs[i]) / (xs[i + 1] - xs[i]), u = fmax(0.0, (Y - ys[j]) / (ys[j + 1] - ys[j]));
    const double *p = from->p_pa, *pc = from->pc_pa;
    size_t c00 = i * fy + j, c01 = c00 + 1, c10 = c00 + fy, c11 = c10 + 1;
    yd[k] = ((1 - t) * ((1 - u) * (p[c00] + pc[c00]) + u * (p[c01] + pc[c01])) +
             t * ((1 - u) * (p[c10] + pc[c10]) + u * (p[c11] + pc[c11]))) /
            p0;
  }
  free(xs);
  yd[n] = from->h0_m / us;
  if (e->roughness)
    return true; /* the asperities hold the film open; a lift
                  * would take their pressure off by orders */
  double hfrom = INFINITY;
  for (size_t k = 0; k < fx * fy; k++)
    hfrom = fmin(hfrom, from->u_m[k] / us);
  raise_min_film(e, yd, 0.5 * hfrom);
  return true;
}

/* The dry Hertz pressure of a circle of radius unit (the load's), plus a
 * tail e^{-r^2} outside it, lifted
 * so that the centre's film is lift (a^2/R), and the film nowhere below
 * half of it (a sliding rubber's lag can close it at the outlet). */
static void hertz_start(ehl *e, double *yd, double unit, double lift, double tail) {
  size_t n = e->n;
  for (size_t k = 0; k < n; k++) {
    double X = e->xc[k / e->ny] / unit, Y = e->yc[k % e->ny] / unit, r2 = X * X + Y * Y;
    yd[k] = (r2 < 1.0 ? sqrt(1.0 - r2) : tail * exp(-r2)) / (unit * unit);
  }
  yd[n] = 0.0;
  ehl_eval(e, yd);
  yd[n] = lift - centre_film(e);
  raise_min_film(e, yd, 0.5 * lift);
}

/* A rough contact's mean separation (a^2/R) where the asperities alone
 * carry the Hertz peak of a contact of radius unit: the start's film at
 * the centre when the fluid carries little (0 when smooth). */
static double asperity_lift(const ehl *e, double unit, double share) {
  if (!e->roughness) return 0.0;
  return vl_persson_separation(e->roughness, share / (unit * unit * e->sfac)) / e->us_m;
}

/* KINSOL's objects for one solve. */
typedef struct {
  SUNContext ctx;
  N_Vector y, ones, fw, y0; /* the unknowns, unit scaling, a residual, a saved state */
  SUNMatrix J;
  SUNLinearSolver LS;
  void *kmem;
} ehl_kin;

static void kin_free(ehl_kin *k) {
  if (k->kmem) KINFree(&k->kmem);
  if (k->LS) SUNLinSolFree(k->LS);
  if (k->J) SUNMatDestroy(k->J);
  N_Vector vs[] = {k->y, k->ones, k->fw, k->y0};
  for (size_t i = 0; i < 4; i++)
    if (vs[i]) N_VDestroy(vs[i]);
  if (k->ctx) SUNContext_Free(&k->ctx);
}

/* KINSOL on e's n + 1 unknowns: the dense Jacobian (LAPACK's LU, set up
 * at every step), a line search's scaled step tolerance. */
static vl_status kin_create(ehl *e, const vl_point_ehl_config *cfg, ehl_kin *k, vl_error *err) {
  memset(k, 0, sizeof *k);
  sunindextype m = (sunindextype)(e->n + 1);
  if (SUNContext_Create(NULL, &k->ctx) != 0) goto nomem;
  k->y = N_VNew_Serial(m, k->ctx), k->ones = N_VNew_Serial(m, k->ctx);
  k->fw = N_VNew_Serial(m, k->ctx), k->y0 = N_VNew_Serial(m, k->ctx);
  k->J = SUNDenseMatrix(m, m, k->ctx);
  if (!k->y || !k->ones || !k->fw || !k->y0 || !k->J) goto nomem;
  k->LS = vl_linsol_lapack_create((long)m, k->ctx);
  k->kmem = KINCreate(k->ctx);
  if (!k->LS || !k->kmem) goto nomem;
  N_VConst(1.0, k->ones);
  void *km = k->kmem;
  if (KINInit(km, residual_fn, k->y) != KIN_SUCCESS || KINSetUserData(km, e) != KIN_SUCCESS ||
      KINSetLinearSolver(km, k->LS, k->J) != KIN_SUCCESS ||
      KINSetJacFn(km, jacobian_fn) != KIN_SUCCESS ||
      KINSetFuncNormTol(km, cfg->tolerance) != KIN_SUCCESS ||
      KINSetScaledStepTol(km, 1e-14) != KIN_SUCCESS || KINSetMaxSetupCalls(km, 1) != KIN_SUCCESS ||
      KINSetNumMaxIters(km, cfg->max_iterations) != KIN_SUCCESS ||
      KINSetErrHandlerFn(km, silent, NULL) != KIN_SUCCESS) {
    kin_free(k);
    vl_error_set(err, "KINSOL set-up failed for the lubricated ball");
    return VL_EINTERNAL;
  }
  return VL_OK;
nomem:
  kin_free(k);
  vl_error_set(err, "out of memory for the lubricated ball's solver (%zu cells)", e->n);
  return VL_ENOMEM;
}

/* One KINSol (line search) from the state in k->y; true when the max norm
 * of the residual ends below the tolerance. */
static bool kin_run(ehl_kin *k, ehl *e, double tol, long *nni, double *fnorm) {
  int flag = KINSol(k->kmem, k->y, KIN_LINESEARCH, k->ones, k->ones);
  long it = 0;
  KINGetNumNonlinSolvIters(k->kmem, &it);
  *nni += it;
  *fnorm = INFINITY;
  if (residual_fn(k->y, k->fw, e) == 0) *fnorm = N_VMaxNorm(k->fw);
  return flag >= 0 && *fnorm <= tol;
}

/* From the state at *param (e->lambda or e->load_share; converged) to
 * target, down or up, by steps of a factor up to 4 (grown 1.5x after a
 * success, its square root after a failure, given up below 1.02). */
static bool continue_to(ehl_kin *k, ehl *e, double *param, double target, double tol,
                        vl_point_ehl_result *res, double *fnorm) {
  double ratio = 4.0;
  bool down = *param > target;
  N_VScale(1.0, k->y, k->y0);
  while (down ? *param > target : *param < target) {
    double from = *param;
    *param = down ? fmax(target, *param / ratio) : fmin(target, *param * ratio);
    /* with a line search: full steps close the film (measured) */
    bool step_ok = kin_run(k, e, tol, &res->iterations, fnorm);
    res->continuation_steps++;
    if (step_ok) {
      N_VScale(1.0, k->y, k->y0);
      ratio = fmin(4.0, ratio * 1.5);
    } else {
      N_VScale(1.0, k->y0, k->y);
      *param = from;
      ratio = sqrt(ratio);
      if (ratio < 1.02) return false;
    }
  }
  return true;
}

/* The dry rough contact from the Hertz start in k->y, else from a lighter
 * load (W/8^j: the asperities further apart, Persson's law less steep)
 * continued up to W. */
static bool dry_rough(ehl_kin *k, ehl *e, const vl_point_ehl_config *cfg, vl_point_ehl_result *res,
                      double *fnorm) {
  double *yd = N_VGetArrayPointer(k->y);
  bool ok = kin_run(k, e, cfg->tolerance, &res->iterations, fnorm);
  KINSetNumMaxIters(k->kmem, DRY_START_ITERATIONS);
  for (int j = 1; j <= 6 && !ok; j++) {
    e->load_share = pow(8.0, -j);
    double unit = cfg->unit * cbrt(e->load_share); /* Hertz's radius at that load */
    hertz_start(e, yd, unit, asperity_lift(e, unit, e->load_share), 0.0);
    for (size_t l = 0; l < e->n; l++)
      yd[l] *= e->load_share;
    ok = kin_run(k, e, cfg->tolerance, &res->iterations, fnorm);
  }
  KINSetNumMaxIters(k->kmem, cfg->max_iterations);
  if (ok && e->load_share < 1.0)
    ok = continue_to(k, e, &e->load_share, 1.0, cfg->tolerance, res, fnorm);
  e->load_share = 1.0;
  return ok;
}

/* A rough lubricated contact from the dry one (its state in k->y): the
 * film at once, else at a slower entrainment (lambda / 8^j, j <= 3: the
 * fluid's share falls towards the dry limit; slower still, the Reynolds
 * rows' Poiseuille terms swamp the Couette and Newton fares no better)
 * continued up to lambda. */
static bool rough_from_dry(ehl_kin *k, ehl *e, const vl_point_ehl_config *cfg,
                           vl_point_ehl_result *res, double *fnorm) {
  double lambda = e->lambda, tol = cfg->tolerance;
  e->dry = true;
  bool ok = dry_rough(k, e, cfg, res, fnorm);
  e->dry = false;
  if (!ok) return false;
  N_Vector dry = N_VClone(k->y);
  if (!dry) return false;
  N_VScale(1.0, k->y, dry);
  KINSetNumMaxIters(k->kmem, DRY_START_ITERATIONS);
  ok = false;
  for (int j = 0; j <= 3 && !ok; j++) {
    e->lambda = lambda / pow(8.0, j);
    N_VScale(1.0, dry, k->y);
    ok = kin_run(k, e, tol, &res->iterations, fnorm);
  }
  KINSetNumMaxIters(k->kmem, cfg->max_iterations);
  N_VDestroy(dry);
  if (ok && e->lambda < lambda) ok = continue_to(k, e, &e->lambda, lambda, tol, res, fnorm);
  e->lambda = lambda;
  return ok;
}

/* A run from `start` (another grid's solution), its steps bounded: a
 * start that is going to fail stalls early. */
static bool map_run(ehl_kin *k, ehl *e, const vl_point_ehl_config *cfg,
                    const vl_point_ehl_map *start, const ehl_scales *sc, vl_point_ehl_result *res,
                    double *fnorm) {
  double *yd = N_VGetArrayPointer(k->y), us = sc->a * sc->a / cfg->radius_m;
  if (!start_from_map(e, yd, start, sc->a, sc->p0, us)) return false;
  KINSetNumMaxIters(k->kmem,
                    cfg->max_iterations < MAP_ITERATIONS ? cfg->max_iterations : MAP_ITERATIONS);
  bool ok = kin_run(k, e, cfg->tolerance, &res->iterations, fnorm);
  KINSetNumMaxIters(k->kmem, cfg->max_iterations);
  res->from_start = ok;
  return ok;
}

/* The solve's paths: from `start` (another grid's solution), else from
 * Hertz lifted to Hamrock and Dowson's central film at the target, else
 * at a thicker film (lambda x 4^k: the film's elastic share falls)
 * continued back down in speed. */
static bool solve_paths(ehl_kin *k, ehl *e, const vl_point_ehl_config *cfg,
                        const vl_point_ehl_map *start, const ehl_scales *sc,
                        vl_point_ehl_result *res, double *fnorm) {
  double *yd = N_VGetArrayPointer(k->y), R = cfg->radius_m, us = sc->a * sc->a / R;
  double lambda = e->lambda, tol = cfg->tolerance, hmin_fit, hc_fit;
  *fnorm = INFINITY;
  /* a rough viscoelastic contact's start from another speed is a poor
   * one: its films, through a memory of another length, miss Persson's
   * steep law (measured: no convergence in 200 steps); the dry start first.
   * An elastic one's is good (6-9 steps a point along a curve), and the
   * dry start then a poor one */
  bool near = start && (start->v0_m_s == cfg->v0_m_s || !e->roughness || cfg->rubber.n_terms == 0);
  if (near && map_run(k, e, cfg, start, sc, res, fnorm)) return true;
  double lift = asperity_lift(e, cfg->unit, 1.0);
  hertz_start(e, yd, cfg->unit, lift, 0.0);
  if (e->dry) return dry_rough(k, e, cfg, res, fnorm); /* the asperities alone */
  if (e->roughness) {
    /* the dry rough contact (the fluid's share 0, the limit of slow
     * sliding), then the film from it */
    if (rough_from_dry(k, e, cfg, res, fnorm)) return true;
    if (start && !near && map_run(k, e, cfg, start, sc, res, fnorm)) return true;
  }
  vl_point_ehl_hamrock_dowson(cfg, &hmin_fit, &hc_fit);
  /* a contact shrunk to `unit` by a stiffer rubber: the modulus Er0/unit^3,
   * the fit's film ~ E'^-0.42 */
  hc_fit *= pow(cfg->unit, 1.26);
  bool ok = false;
  double lam = lambda;
  for (int j = 0; !ok && j <= 10; j++, lam *= 4.0) {
    e->lambda = lam;
    /* the smooth film's fit, or the asperities' separation where thicker */
    hertz_start(e, yd, cfg->unit, fmax(lift, hc_fit * pow(lam / lambda, 0.64) / us), 0.0);
    /* an attempt from Hertz that is going to fail stalls early */
    KINSetNumMaxIters(k->kmem, j == 0 ? cfg->max_iterations : 25);
    ok = kin_run(k, e, tol, &res->iterations, fnorm);
  }
  KINSetNumMaxIters(k->kmem, cfg->max_iterations);
  if (ok && e->lambda > lambda) ok = continue_to(k, e, &e->lambda, lambda, tol, res, fnorm);
  e->lambda = lambda;
  return ok;
}

vl_status vl_point_ehl_solve(const vl_point_ehl_config *cfg, const vl_point_ehl_map *start,
                             vl_point_ehl_result *res, vl_point_ehl_map *map, vl_error *err) {
  memset(res, 0, sizeof *res);
  vl_status st = check_config(cfg, err);
  if (st != VL_OK) return st;
  ehl_scales sc = scales_of(cfg);
  double R = cfg->radius_m, a = sc.a, p0 = sc.p0;
  res->a_m = a, res->p0_pa = p0;
  double t0 = now_s();
  ehl e;
  st = ehl_build(&e, cfg, err);
  if (st != VL_OK) return st;
  e.lambda = 6.0 * cfg->eta_pa_s * cfg->v0_m_s * R * R / (a * a * a * p0);
  e.v0_m_s = cfg->v0_m_s;
  e.load_share = 1.0;
  res->nx = e.nx, res->ny = e.ny;
  res->t_influence_s = now_s() - t0;
  t0 = now_s();
  ehl_kin k;
  st = kin_create(&e, cfg, &k, err);
  if (st != VL_OK) {
    ehl_free(&e);
    return st;
  }
  int blas_threads = vl_blas_pin_one_thread();
  double fnorm;
  bool ok = solve_paths(&k, &e, cfg, start, &sc, res, &fnorm);
  vl_blas_restore_threads(blas_threads);
  double *yd = N_VGetArrayPointer(k.y);
  res->converged = ok;
  res->residual = fnorm;
  report(&e, cfg, yd, a, p0, res);
  res->t_solve_s = now_s() - t0;
  if (map) st = map_of(&e, yd, a, p0, a * a / R, map, err);
  if (st == VL_OK && !ok) {
    vl_error_set(err, "the lubricated ball did not converge at v0 = %g m/s (residual %.3g)",
                 cfg->v0_m_s, fnorm);
    st = VL_ENOCONV;
  }
  kin_free(&k);
  ehl_free(&e);
  return st;
}

size_t vl_point_ehl_cells(const vl_point_ehl_config *cfg) {
  double *xf = NULL, *yf = NULL;
  size_t nx = graded_faces(cfg->x_in, cfg->x_out, ZONE_X, 2, cfg, &xf);
  size_t ny = graded_faces(0.0, cfg->y_max, ZONE_Y, 1, cfg, &yf);
  free(xf), free(yf);
  return nx * ny;
}

double *vl_point_ehl_influence(const vl_point_ehl_config *cfg, size_t *nx, size_t *ny, double **xc,
                               double **yc) {
  vl_error err;
  ehl e;
  if (check_config(cfg, &err) != VL_OK || ehl_build(&e, cfg, &err) != VL_OK) return NULL;
  double *M = e.M;
  *nx = e.nx, *ny = e.ny, *xc = e.xc, *yc = e.yc;
  e.M = NULL, e.xc = NULL, e.yc = NULL;
  ehl_free(&e);
  return M;
}

double vl_point_ehl_jacobian_check(const vl_point_ehl_config *cfg, double lift) {
  ehl_scales sc = scales_of(cfg);
  double R = cfg->radius_m, a = sc.a, p0 = sc.p0;
  ehl e;
  vl_error err;
  if (ehl_build(&e, cfg, &err) != VL_OK) return NAN;
  e.lambda = 6.0 * cfg->eta_pa_s * cfg->v0_m_s * R * R / (a * a * a * p0);
  size_t n = e.n, m = n + 1;
  SUNContext ctx;
  SUNContext_Create(NULL, &ctx);
  N_Vector y = N_VNew_Serial((sunindextype)m, ctx), f0 = N_VNew_Serial((sunindextype)m, ctx),
           f1 = N_VNew_Serial((sunindextype)m, ctx);
  SUNMatrix J = SUNDenseMatrix((sunindextype)m, (sunindextype)m, ctx);
  double *yd = N_VGetArrayPointer(y);
  hertz_start(&e, yd, cfg->unit, lift, 0.01);
  jacobian_fn(y, f0, J, &e, NULL, NULL);
  bool closed = residual_fn(y, f0, &e) != 0; /* a closed film: no check at this state */
  double *Jd = SUNDenseMatrix_Data(J), worst = 0.0, *F0 = N_VGetArrayPointer(f0),
         *F1 = N_VGetArrayPointer(f1);
  for (size_t l = 0; l < m; l++) {
    double h = 1e-7 * fmax(1.0, fabs(yd[l])), keep = yd[l];
    yd[l] += h;
    closed = closed || residual_fn(y, f1, &e) != 0;
    yd[l] = keep;
    for (size_t k = 0; k < m; k++) {
      double fd = (F1[k] - F0[k]) / h, an = Jd[l * m + k];
      double d = fabs(fd - an) / fmax(1.0, fabs(an));
      if (d > worst) worst = d;
    }
  }
  N_VDestroy(y), N_VDestroy(f0), N_VDestroy(f1), SUNMatDestroy(J), SUNContext_Free(&ctx);
  ehl_free(&e);
  return closed ? NAN : worst;
}
