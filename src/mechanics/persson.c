/* Persson's contact mechanics for one rough surface (roughness.h):
 * A/A0 = erf(s / (2 sqrt(g))) and the mean separation u(s), tabulated once
 * and inverted to s(u) = pc/|Er| for the solver.
 *
 * Quadrature over q. With t = ln q the integrand of u(s) is
 *   (sqrt(pi)/2) q^3 C w E1((w s)^2),   w = (pi M(q))^(-1/2),
 *   M(q) = \int_{q0}^{q} q'^3 C dq'.
 * Near q0, M ~ q0^4 C(q0) (t - t0), so w ~ (t - t0)^(-1/2): an integrable
 * singularity when s is small. The substitution t = t0 + sigma^2 (for
 * t - t0 <= 1; linear t = t0 + 1 + 2 (sigma - 1) beyond, C1 at sigma = 1)
 * removes it; the sliver sigma in [0, sm], sm = 1e-4 min(1, sigma_end), is
 * done in closed form with the leading local behaviour
 * (q^3 C w dt/dsigma -> 2 q0 sqrt(C(q0)) / sqrt(pi)). The table uses a fixed
 * composite Gauss-Legendre rule (panels geometric near q0, <= 0.25 wide in
 * t, split at tabulated knots), so the nodes' w and weights are computed
 * once and each u(s) costs one E1 per node; vl_persson_separation_exact uses
 * GSL's adaptive QAGP instead (independent of that rule).
 *
 * The table. Each node stores u_k and the exact derivative du/d ln s (same
 * quadrature, e^{-x} in place of E1), so the interpolant is cubic Hermite
 * with exact slopes (4th order; slopes limited by the Fritsch-Carlson
 * condition, which keeps every piece monotone). It interpolates y = ln s
 * against x = ln(expm1(u/u*)): x ~ u/u* at large u, where y is linear in u,
 * and x ~ ln(u/u*) at small u, where y is smooth in ln u but not in u.
 * Nodes equidistribute a monitor (arc length in the (ln s, x) plane, damped
 * where y(x) is linear: see monitor()), found by a cheap pilot march.
 *
 * Range: u from U_MAX_HRMS h_rms (s ~ exp(-50 h_rms/u*)) down to
 * U_MIN_HRMS h_rms (for the paper's surface s ~ 3, A/A0 ~ 0.45: far above
 * any pressure the solver reaches; s ~ 30 already means u ~ 1e-20 m, so a
 * range "up to s ~ 1e3" would only add nodes at u ~ 0). Outside:
 * for u > u_max, ln s continues linearly with the end slope (-> -1/u*, the
 * exact asymptote); for u < u_min, s continues linearly in u with the end
 * slope ds/du, so s stays finite and positive for every finite u (a stiff
 * linear wall for Newton iterates at u <= 0; linear in ln s would overflow
 * near u = -3 h_rms for the paper's surface). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_math.h> /* M_PI, which strict C17 <math.h> lacks */
#include <gsl/gsl_sf_expint.h>

#include "bracket.h"
#include "gsl_errors.h"
#include "persson_internal.h"
#include "roughness_internal.h"
#include "viscolube/persson.h"

#include "blob.h"

#define DEFAULT_N_TABLE VL_PERSSON_DEFAULT_N_TABLE
#define MIN_N_TABLE VL_PERSSON_MIN_N_TABLE
#define MAX_N_TABLE VL_PERSSON_MAX_N_TABLE
#define U_MAX_HRMS 50.0 /* table top, in h_rms */
#define U_MIN_HRMS 1e-3 /* table bottom, in h_rms */
#define GL_ORDER 8      /* Gauss-Legendre points per panel */
#define PANEL_DT 0.25   /* largest panel width in t = ln q */
#define PANEL_RATIO 2.0 /* geometric growth of panels near q0 (in sigma) */
#define MONITOR_XI0 2.0 /* -ln(s b0) beyond which y(x) is ~linear */
#define MONITOR_FLOOR 0.1
#define PILOT_DMU 0.25 /* pilot step in monitor units */
#define EULER_GAMMA 0.57721566490153286061

struct vl_persson {
  vl_psd psd; /* private copy (the exact quadrature needs it) */
  double g, ustar, hrms, uc;
  size_t n;
  double *x, *y, *d; /* nodes: x(u) increasing, y = ln s decreasing, d = dy/dx */
  double *u;         /* u_k, increasing */
  double dsdu_lo;    /* ds/du at u[0] (< 0): the linear wall below */
  double slope_hi;   /* d ln s/du at u[n-1]: the exponential tail above */
};

/* ---------------------------------------------------------------- helpers */

/* E1((ws)^2) and, in *emx, exp(-(ws)^2); ws >= 0. Small ws uses the series
 * (also avoids (ws)^2 underflowing to 0 when s is tiny); huge arguments
 * give 0 (E1(690) ~ 1e-302). Returns NaN if GSL reports an error. */
static double e1_sq(double ws, double *emx) {
  if (ws < 1e-8) {
    *emx = 1.0 - ws * ws;
    return -EULER_GAMMA - 2.0 * log(ws) + ws * ws;
  }
  double x = ws * ws;
  if (x > 690.0) {
    *emx = 0.0;
    return 0.0;
  }
  gsl_sf_result r;
  *emx = exp(-x);
  if (gsl_sf_expint_E1_e(x, &r) != GSL_SUCCESS) return NAN;
  return r.val;
}

/* (e^{p x} - 1)/(p x) -> 1 for p x -> 0. */
static double expm1_ratio(double px) { return fabs(px) < 1e-300 ? 1.0 : expm1(px) / px; }

/* The first power-law piece of the PSD: C(q) = c_first (q/q0)^alpha for
 * t - t0 <= dt_first. */
static void first_piece(const vl_psd *psd, double *c_first, double *alpha, double *dt_first) {
  if (psd->kind == VL_PSD_SELF_AFFINE) {
    *c_first = psd->c0;
    *alpha = -2.0 * (1.0 + psd->hurst);
    *dt_first = log(psd->q1 / psd->q0);
  } else {
    *c_first = psd->C[0];
    *alpha = log(psd->C[1] / psd->C[0]) / log(psd->q[1] / psd->q[0]);
    *dt_first = log(psd->q[1] / psd->q[0]);
  }
}

/* M(q0 e^dt) = \int_{q0}^{q} q'^3 C dq' given dt = ln(q/q0) directly, so it
 * keeps full relative precision when dt is tiny (forming q/q0 would not). */
static double moment3(const vl_psd *psd, double dt) {
  double c_first, alpha, dt_first;
  first_piece(psd, &c_first, &alpha, &dt_first);
  double q0 = psd->q0, q04c = c_first * q0 * q0 * q0 * q0;
  if (dt <= dt_first) return q04c * dt * expm1_ratio((4.0 + alpha) * dt);
  double m_first = q04c * dt_first * expm1_ratio((4.0 + alpha) * dt_first);
  return m_first + vl_psd_moment(psd, 3, q0 * exp(dt_first), q0 * exp(dt));
}

/* The integration variable sigma and dt/dsigma. */
static double dt_of_sigma(double sigma, double *jac) {
  if (sigma <= 1.0) {
    *jac = 2.0 * sigma;
    return sigma * sigma;
  }
  *jac = 2.0;
  return 1.0 + 2.0 * (sigma - 1.0);
}

static double sigma_of_dt(double dt) { return dt <= 1.0 ? sqrt(dt) : 1.0 + 0.5 * (dt - 1.0); }

/* Integrand pieces at sigma: returns (sqrt(pi)/2) q^3 C w dt/dsigma and
 * sets *w. */
static double kernel(const vl_psd *psd, double sigma, double *w) {
  double jac, dt = dt_of_sigma(sigma, &jac);
  double q = psd->q0 * exp(dt);
  double m = moment3(psd, dt);
  *w = 1.0 / sqrt(M_PI * m);
  return 0.5 * sqrt(M_PI) * q * q * q * vl_psd_value(psd, q) * *w * jac;
}

/* Closed form of the endpoint piece sigma in [0, sm]: there the integrand is
 * c E1(b^2/sigma^2) with c = q0 sqrt(C(q0)), b = s / (sqrt(pi) q0^2
 * sqrt(C(q0))), up to relative corrections O(sm^2). Returns its u and adds
 * its du/d ln s to *dlns. */
static double endpoint_piece(double c, double b, double sm, double *dlns) {
  double y = b / sm, emx;
  double e1 = e1_sq(y, &emx);
  double gauss = sm * emx - sqrt(M_PI) * b * erfc(y); /* \int_0^sm e^{-b^2/t^2} dt */
  *dlns += -2.0 * c * gauss;
  return c * (sm * e1 - 2.0 * gauss);
}

/* ------------------------------------------------------ fixed quadrature */

typedef struct {
  size_t n;
  double *w;        /* w at each node */
  double *wt;       /* quadrature weight times the kernel */
  double c, b0;     /* endpoint piece: c and b = s b0 */
  double sm;        /* end of the closed-form piece */
  double sigma_ref; /* min(1, sigma_end): the band's extent in sigma */
} rule;

static void rule_free(rule *r) {
  free(r->w);
  free(r->wt);
  r->w = r->wt = NULL;
}

/* Where the integrand's derivative jumps, in sigma: the seam sigma = 1 and
 * the tabulated knots, then sigma_end. Returns the count; out (may be NULL)
 * receives them sorted and distinct, all in (0, sigma_end]. */
static size_t kinks(const vl_psd *psd, double sigma_end, double *out) {
  size_t m = 0;
  int seam = sigma_end > 1.0;
  size_t nk = psd->kind == VL_PSD_TABULATED ? psd->n - 1 : 1;
  for (size_t k = 1; k < nk; k++) { /* interior knots, increasing */
    double sk = sigma_of_dt(log(psd->q[k] / psd->q0));
    if (seam && sk >= 1.0) {
      if (out) out[m] = 1.0;
      m++;
      seam = 0;
    }
    if (sk > 1.0 + 1e-12 || sk < 1.0 - 1e-12) {
      if (!(sk > 0.0 && sk < sigma_end * (1.0 - 1e-12))) continue;
      if (out) out[m] = sk;
      m++;
    }
  }
  if (seam) {
    if (out) out[m] = 1.0;
    m++;
  }
  if (out) out[m] = sigma_end;
  return m + 1;
}

/* Panels from sm to sigma_end: geometric (ratio PANEL_RATIO) near q0, at
 * most PANEL_DT wide in t, and never straddling a kink. Returns the panel
 * count and the node count in *nodes; edges and order (may be NULL) receive
 * count + 1 edges and each panel's Gauss-Legendre order. A panel cut short
 * by a kink to a fraction f of its natural width gets fewer points: the
 * error of n points scales like (f kappa)^(2n), kappa the natural panel's
 * width over the integrand's scale; n = GL_ORDER / (1 - ln f) keeps that at
 * the full panel's kappa^(2 GL_ORDER) for kappa ~ 1/e (dense tabulated
 * PSDs would otherwise cost GL_ORDER points per knot). */
static size_t make_panels(const double *kk, size_t nkk, double sm, double *edges, unsigned *order,
                          size_t *nodes) {
  size_t np = 0, j = 0;
  double h = 0.5 * PANEL_DT; /* dt/dsigma <= 2 */
  double a = sm, end = kk[nkk - 1];
  *nodes = 0;
  if (edges) edges[0] = a;
  while (a < end) {
    while (kk[j] <= a)
      j++; /* kk[nkk-1] = end > a stops this */
    double natural = fmin(a * (PANEL_RATIO - 1.0), h);
    double b = a + natural;
    if (b >= kk[j] || kk[j] - b < 1e-9 * h) b = kk[j];
    double f = fmin(1.0, (b - a) / natural);
    unsigned n = (unsigned)ceil(GL_ORDER / (1.0 - log(f)) - 1e-9);
    n = n < 2 ? 2 : n > GL_ORDER ? GL_ORDER : n;
    if (edges) edges[np + 1] = b;
    if (order) order[np] = n;
    *nodes += n;
    np++;
    a = b;
  }
  return np;
}

static vl_status rule_build(const vl_psd *psd, rule *r, vl_error *err) {
  vl_status st = VL_OK;
  double *edges = NULL, *kk = NULL;
  unsigned *order = NULL;
  gsl_integration_glfixed_table *gl[GL_ORDER + 1] = {NULL};
  memset(r, 0, sizeof *r);
  double c_first, alpha, dt_first;
  first_piece(psd, &c_first, &alpha, &dt_first);
  double sigma_end = sigma_of_dt(log(psd->q1 / psd->q0));
  r->sigma_ref = fmin(1.0, sigma_end);
  r->sm = 1e-4 * r->sigma_ref; /* closed-form piece: relative error O(sm^2) */
  r->c = psd->q0 * sqrt(c_first);
  r->b0 = 1.0 / (sqrt(M_PI) * psd->q0 * psd->q0 * sqrt(c_first));

  size_t nkk = kinks(psd, sigma_end, NULL);
  kk = malloc(nkk * sizeof *kk);
  if (!kk) {
    vl_error_set(err, "out of memory for %zu PSD knots", nkk);
    return VL_ENOMEM;
  }
  kinks(psd, sigma_end, kk);
  size_t nodes, np = make_panels(kk, nkk, r->sm, NULL, NULL, &nodes);
  edges = malloc((np + 1) * sizeof *edges);
  order = malloc(np * sizeof *order);
  r->n = nodes;
  r->w = malloc(r->n * sizeof *r->w);
  r->wt = malloc(r->n * sizeof *r->wt);
  if (!edges || !order || !r->w || !r->wt) {
    vl_error_set(err, "out of memory for a %zu-node quadrature rule", r->n);
    st = VL_ENOMEM;
    goto cleanup;
  }
  make_panels(kk, nkk, r->sm, edges, order, &nodes);
  size_t k = 0;
  for (size_t p = 0; p < np; p++) {
    unsigned n = order[p];
    if (!gl[n]) gl[n] = gsl_integration_glfixed_table_alloc(n);
    if (!gl[n]) {
      vl_error_set(err, "out of memory for a Gauss-Legendre table");
      st = VL_ENOMEM;
      goto cleanup;
    }
    for (size_t i = 0; i < n; i++, k++) {
      double xi, wi;
      if (gsl_integration_glfixed_point(edges[p], edges[p + 1], i, &xi, &wi, gl[n]) !=
          GSL_SUCCESS) {
        vl_error_set(err, "Gauss-Legendre node %zu failed", i);
        st = VL_EINTERNAL;
        goto cleanup;
      }
      r->wt[k] = wi * kernel(psd, xi, &r->w[k]);
      if (!(isfinite(r->wt[k]) && isfinite(r->w[k]))) {
        double jac;
        vl_error_set(err, "PSD gives a non-finite Persson integrand at q = %g 1/m",
                     psd->q0 * exp(dt_of_sigma(xi, &jac)));
        st = VL_EINPUT;
        goto cleanup;
      }
    }
  }
cleanup:
  free(edges);
  free(kk);
  free(order);
  for (unsigned n = 0; n <= GL_ORDER; n++)
    if (gl[n]) gsl_integration_glfixed_table_free(gl[n]);
  if (st != VL_OK) rule_free(r);
  return st;
}

/* u(s) and du/d ln s from the fixed rule. */
static double rule_u(const rule *r, double s, double *dlns) {
  double u = 0.0, du = 0.0;
  for (size_t k = 0; k < r->n; k++) {
    double emx, e1 = e1_sq(r->w[k] * s, &emx);
    u += r->wt[k] * e1;
    du += r->wt[k] * emx;
  }
  du *= -2.0;
  u += endpoint_piece(r->c, s * r->b0, r->sm, &du);
  *dlns = du;
  return u;
}

/* Newton in ln s for ln u(s) = ln target; ln u is smooth and monotone in
 * ln s. Steps are capped so a far start cannot overshoot into underflow. */
static double solve_lns(const rule *r, double target, double lns) {
  for (int it = 0; it < 200; it++) {
    double dlns, u = rule_u(r, exp(lns), &dlns);
    if (!(u > 0.0) || !(dlns < 0.0)) { /* underflowed: far beyond u_min */
      lns -= 1.0;
      continue;
    }
    double step = -(log(u) - log(target)) / (dlns / u);
    step = fmax(-5.0, fmin(5.0, step));
    lns += step;
    if (lns < -690.0) return -690.0; /* s ~ 1e-300: the table stops there */
    if (fabs(step) < 1e-6) break;
  }
  return lns;
}

/* ------------------------------------------------------------- the table */

static double x_of_u(const vl_persson *t, double u, double *dxdu) {
  double r = u / t->uc;
  double em = -expm1(-r); /* 1 - e^{-r} */
  if (dxdu) *dxdu = 1.0 / (t->uc * em);
  return r + log(em);
}

static double u_of_x(const vl_persson *t, double x) {
  return t->uc * (x > 0.0 ? x + log1p(exp(-x)) : log1p(exp(x)));
}

/* Segment k with x[k] <= x <= x[k+1] (x inside the table). */
static size_t find_x(const vl_persson *t, double x) { return vl_bracket(t->x, t->n, x); }

/* Cubic Hermite on segment k at local h in [0,1]: value and dy/dx. */
static double hermite(const vl_persson *t, size_t k, double h, double *dydx) {
  double dx = t->x[k + 1] - t->x[k];
  double y0 = t->y[k], y1 = t->y[k + 1], m0 = t->d[k] * dx, m1 = t->d[k + 1] * dx;
  double h2 = h * h, h3 = h2 * h;
  double val = (2 * h3 - 3 * h2 + 1) * y0 + (h3 - 2 * h2 + h) * m0 + (-2 * h3 + 3 * h2) * y1 +
               (h3 - h2) * m1;
  if (dydx) {
    double der = (6 * h2 - 6 * h) * y0 + (3 * h2 - 4 * h + 1) * m0 + (-6 * h2 + 6 * h) * y1 +
                 (3 * h2 - 2 * h) * m1;
    *dydx = der / dx;
  }
  return val;
}

/* Fritsch-Carlson: with slopes of the secant's sign and
 * alpha^2 + beta^2 <= 9 each cubic piece is monotone. Exact slopes on a
 * fine grid already satisfy it; this only guards odd PSDs. */
static void limit_slopes(vl_persson *t) {
  for (size_t k = 0; k + 1 < t->n; k++) {
    double sec = (t->y[k + 1] - t->y[k]) / (t->x[k + 1] - t->x[k]);
    if (sec == 0.0) {
      t->d[k] = t->d[k + 1] = 0.0;
      continue;
    }
    double a = t->d[k] / sec, b = t->d[k + 1] / sec;
    if (a < 0.0) t->d[k] = a = 0.0;
    if (b < 0.0) t->d[k + 1] = b = 0.0;
    double r2 = a * a + b * b;
    if (r2 > 9.0) {
      double f = 3.0 / sqrt(r2);
      t->d[k] = f * a * sec;
      t->d[k + 1] = f * b * sec;
    }
  }
}

static int psd_usable(const vl_psd *psd) {
  if (!psd || !(isfinite(psd->q0) && isfinite(psd->q1) && psd->q0 > 0.0 && psd->q1 > psd->q0))
    return 0;
  if (psd->kind == VL_PSD_SELF_AFFINE)
    return isfinite(psd->c0) && psd->c0 > 0.0 && psd->hurst > 0.0 && psd->hurst <= 1.0;
  return psd->kind == VL_PSD_TABULATED && psd->n >= 2 && psd->q && psd->C;
}

static vl_status copy_psd(vl_psd *dst, const vl_psd *src, vl_error *err) {
  if (src->kind == VL_PSD_SELF_AFFINE)
    return vl_psd_init_self_affine(dst, src->hurst, src->q0, src->q1, src->hrms_m, err);
  return vl_psd_init_tabulated(dst, src->n, src->q, src->C, err);
}

/* Node density per unit ln s (the monitor): arc length in the (ln s, x)
 * plane, damped where y(x) is nearly linear. The deviation of u from its
 * asymptote -u* ln s + const comes from q near q0 where w s > 1, i.e. from
 * sigma < b = s b0 (endpoint_piece), and is O(b / sigma_ref) (sigma_ref =
 * min(1, sigma_end) for narrow bands); so once xi = -ln(s b0 / sigma_ref)
 * exceeds MONITOR_XI0, y^(4) ~ e^{-xi} and the cubic's error
 * h^4 y^(4) allows steps growing like e^{xi/4}. A floor keeps steps bounded. */
static double monitor(double lns, double lnb0, double dxdlns) {
  double damp = exp(-fmax(0.0, -(lns + lnb0) - MONITOR_XI0) / 4.0);
  return sqrt(1.0 + dxdlns * dxdlns) * fmax(damp, MONITOR_FLOOR);
}

/* Evaluates the rule at ln s: u, x and dx/d ln s. */
static int eval_node(const vl_persson *t, const rule *r, double lns, double *u, double *x,
                     double *dxdlns) {
  double dlns, dxdu;
  *u = rule_u(r, exp(lns), &dlns);
  if (!(*u > 0.0 && isfinite(*u) && dlns < 0.0 && isfinite(dlns))) return 0;
  *x = x_of_u(t, *u, &dxdu);
  *dxdlns = dxdu * dlns;
  return 1;
}

/* Places n nodes between lns_min and lns_max equidistributing the monitor.
 * A pilot march (steps of about PILOT_DMU in monitor units) measures the
 * cumulative monitor; nodes are then uniform in it. */
static vl_status place_nodes(vl_persson *t, const rule *r, double lns_min, double lns_max,
                             vl_error *err) {
  vl_status st = VL_OK;
  size_t cap = 64, m = 0;
  double *pl = malloc(cap * sizeof *pl), *pmu = malloc(cap * sizeof *pmu);
  double lns = lns_max, u, x, dxl, rho_prev = 0.0;
  if (!pl || !pmu) goto nomem;
  while (1) {
    if (!eval_node(t, r, lns, &u, &x, &dxl)) goto bad;
    double rho = monitor(lns, log(r->b0 / r->sigma_ref), dxl);
    if (m == cap) {
      cap *= 2;
      double *a = realloc(pl, cap * sizeof *pl);
      if (a) pl = a;
      double *b = a ? realloc(pmu, cap * sizeof *pmu) : NULL;
      if (b) pmu = b;
      if (!a || !b) goto nomem;
    }
    pl[m] = lns;
    pmu[m] = m ? pmu[m - 1] + 0.5 * (rho + rho_prev) * (pl[m - 1] - lns) : 0.0;
    m++;
    rho_prev = rho;
    if (lns <= lns_min) break;
    lns = fmax(lns_min, lns - PILOT_DMU / rho);
  }
  /* pl decreasing, pmu increasing: node j (u increasing) sits at
   * mu = pmu_end j/(n-1), ln s by linear interpolation. */
  size_t seg = 0;
  for (size_t j = 0; j < t->n; j++) {
    double mu = pmu[m - 1] * (double)j / (double)(t->n - 1);
    while (seg + 2 < m && pmu[seg + 1] < mu)
      seg++;
    double f = (pmu[seg + 1] > pmu[seg]) ? (mu - pmu[seg]) / (pmu[seg + 1] - pmu[seg]) : 0.0;
    f = fmin(1.0, fmax(0.0, f));
    lns = j == 0 ? lns_max : j + 1 == t->n ? lns_min : pl[seg] + f * (pl[seg + 1] - pl[seg]);
    if (!eval_node(t, r, lns, &u, &x, &dxl)) goto bad;
    t->u[j] = u;
    t->x[j] = x;
    t->y[j] = lns;
    t->d[j] = 1.0 / dxl;
  }
  goto cleanup;
nomem:
  vl_error_set(err, "out of memory while placing Persson table nodes");
  st = VL_ENOMEM;
  goto cleanup;
bad:
  vl_error_set(err, "Persson table: u(s) not positive and finite at s = %g", exp(lns));
  st = VL_EINTERNAL;
cleanup:
  free(pl);
  free(pmu);
  return st;
}

/* g = (pi/4) \int q^3 C dq over the band (one expression for the build
 * and for checking a stored table). */
static double table_g(const vl_psd *psd) {
  return 0.25 * M_PI * vl_psd_moment(psd, 3, psd->q0, psd->q1);
}

/* The continuations outside the table from its end nodes (C1 there). */
static void set_ends(vl_persson *t) {
  double dxdu_lo, dxdu_hi;
  x_of_u(t, t->u[0], &dxdu_lo);
  x_of_u(t, t->u[t->n - 1], &dxdu_hi);
  t->dsdu_lo = exp(t->y[0]) * t->d[0] * dxdu_lo;
  t->slope_hi = t->d[t->n - 1] * dxdu_hi;
}

/* A table with its PSD copy and n nodes allocated (values unset). */
static vl_status table_alloc(const vl_psd *psd, size_t n, vl_persson **out, vl_error *err) {
  vl_persson *t = calloc(1, sizeof *t);
  *out = NULL;
  if (!t) {
    vl_error_set(err, "out of memory for a Persson table");
    return VL_ENOMEM;
  }
  vl_status st = copy_psd(&t->psd, psd, err);
  if (st != VL_OK) {
    vl_persson_free(t);
    return st;
  }
  t->n = n;
  t->x = malloc(n * sizeof *t->x);
  t->y = malloc(n * sizeof *t->y);
  t->d = malloc(n * sizeof *t->d);
  t->u = malloc(n * sizeof *t->u);
  if (!t->x || !t->y || !t->d || !t->u) {
    vl_error_set(err, "out of memory for a %zu-point Persson table", n);
    vl_persson_free(t);
    return VL_ENOMEM;
  }
  *out = t;
  return VL_OK;
}

void vl_persson_free(vl_persson *table) {
  if (!table) return;
  vl_psd_free(&table->psd);
  free(table->x);
  free(table->y);
  free(table->d);
  free(table->u);
  free(table);
}

vl_status vl_persson_build(const vl_psd *psd, size_t n_table, vl_persson **out, vl_error *err) {
  vl_status st = VL_OK;
  vl_persson *t = NULL;
  rule r = {0};
  *out = NULL;
  vl_gsl_errors_off();
  if (!psd_usable(psd)) {
    vl_error_set(err, "Persson table: the PSD is not initialised or invalid");
    return VL_EINPUT;
  }
  if (n_table == 0) n_table = DEFAULT_N_TABLE;
  if (n_table < MIN_N_TABLE || n_table > MAX_N_TABLE) {
    vl_error_set(err, "Persson table: n_table must lie in [%d, %d] (got %zu)", MIN_N_TABLE,
                 MAX_N_TABLE, n_table);
    return VL_EINPUT;
  }
  st = table_alloc(psd, n_table, &t, err);
  if (st != VL_OK) return st;
  st = rule_build(&t->psd, &r, err);
  if (st != VL_OK) goto cleanup;

  t->hrms = vl_psd_hrms(&t->psd);
  t->g = table_g(&t->psd);
  double wsum = r.c * r.sm;
  for (size_t k = 0; k < r.n; k++)
    wsum += r.wt[k];
  t->ustar = 2.0 * wsum; /* sqrt(pi) \int q^2 C w dq */
  t->uc = t->ustar;
  if (!(t->g > 0.0 && isfinite(t->g) && t->ustar > 0.0 && isfinite(t->ustar) && t->hrms > 0.0)) {
    vl_error_set(err, "Persson table: degenerate PSD (g = %g, u* = %g m)", t->g, t->ustar);
    st = VL_EINPUT;
    goto cleanup;
  }

  /* Range in ln s, from the asymptotes, refined by Newton. */
  double lns_max = solve_lns(&r, U_MIN_HRMS * t->hrms, 0.5 * log(4.0 * t->g));
  double lns_min = solve_lns(&r, U_MAX_HRMS * t->hrms, -U_MAX_HRMS * t->hrms / t->ustar);
  st = place_nodes(t, &r, lns_min, lns_max, err);
  if (st != VL_OK) goto cleanup;
  for (size_t j = 0; j + 1 < n_table; j++) {
    if (!(t->x[j + 1] > t->x[j])) {
      vl_error_set(err, "Persson table: u(s) not strictly decreasing near s = %g", exp(t->y[j]));
      st = VL_EINTERNAL;
      goto cleanup;
    }
  }
  limit_slopes(t);
  set_ends(t);

cleanup:
  rule_free(&r);
  if (st != VL_OK) {
    vl_persson_free(t);
    t = NULL;
  }
  *out = t;
  return st;
}

/* -------------------------------------------------------------- queries */

double vl_persson_pressure(const vl_persson *t, double u_m, double *dsdu) {
  double s, der;
  if (isnan(u_m)) {
    s = der = NAN;
  } else if (u_m <= t->u[0]) { /* linear wall: C1, finite, positive */
    der = t->dsdu_lo;
    s = exp(t->y[0]) + der * (u_m - t->u[0]);
  } else if (u_m >= t->u[t->n - 1]) { /* exponential tail */
    s = exp(t->y[t->n - 1] + t->slope_hi * (u_m - t->u[t->n - 1]));
    der = s * t->slope_hi;
  } else {
    double dxdu, dydx, x = x_of_u(t, u_m, &dxdu);
    x = fmin(fmax(x, t->x[0]), t->x[t->n - 1]);
    size_t k = find_x(t, x);
    double y = hermite(t, k, (x - t->x[k]) / (t->x[k + 1] - t->x[k]), &dydx);
    s = exp(y);
    der = s * dydx * dxdu;
  }
  if (dsdu) *dsdu = der;
  return s;
}

double vl_persson_separation(const vl_persson *t, double s) {
  if (isnan(s)) return NAN;
  if (s <= 0.0) return INFINITY; /* no contact pressure: separation unbounded */
  double s_lo = exp(t->y[0]);
  if (s >= s_lo) return t->u[0] + (s - s_lo) / t->dsdu_lo;
  double y = log(s);
  if (y <= t->y[t->n - 1]) return t->u[t->n - 1] + (y - t->y[t->n - 1]) / t->slope_hi;
  /* y is decreasing in x: find k with y[k] >= y > y[k+1]. */
  size_t lo = 0, hi = t->n - 1;
  while (hi - lo > 1) {
    size_t mid = (lo + hi) / 2;
    if (t->y[mid] >= y)
      lo = mid;
    else
      hi = mid;
  }
  /* Solve the monotone cubic by safeguarded Newton on h in [0,1]. */
  double a = 0.0, b = 1.0, h = (y - t->y[lo]) / (t->y[lo + 1] - t->y[lo]);
  double dx = t->x[lo + 1] - t->x[lo];
  for (int it = 0; it < 60; it++) {
    double dydx, f = hermite(t, lo, h, &dydx) - y;
    if (f > 0.0)
      a = h;
    else
      b = h; /* decreasing: f > 0 means root to the right */
    double hn = (dydx != 0.0) ? h - f / (dydx * dx) : 0.5 * (a + b);
    if (!(hn > a && hn < b)) hn = 0.5 * (a + b);
    if (fabs(hn - h) < 1e-15) {
      h = hn;
      break;
    }
    h = hn;
  }
  return u_of_x(t, t->x[lo] + h * dx);
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Adaptive integrand for the exact u(s). */
typedef struct {
  const vl_psd *psd;
  double s;
} exact_ctx;

static double exact_integrand(double sigma, void *p) {
  const exact_ctx *c = p;
  if (sigma <= 0.0) return 0.0; /* w -> inf: E1 -> 0 for s > 0 */
  double w, emx, k = kernel(c->psd, sigma, &w);
  return k * e1_sq(w * c->s, &emx);
}

double vl_persson_separation_exact(const vl_persson *t, double s) {
  if (isnan(s)) return NAN;
  if (s <= 0.0) return INFINITY;
  const vl_psd *psd = &t->psd;
  double sigma_end = sigma_of_dt(log(psd->q1 / psd->q0));
  /* Near sigma = 0 the integrand is ~ c E1(b^2/sigma^2), b ~ s: a
   * log-like feature of width b that an adaptive rule sampling [0, 1] would
   * miss. Breakpoints at b/4, b, 4b and at every decade down to b/10 expose
   * it (below 1e-20 the integrand's share is ~1e-20 |ln s|: negligible). */
  double bb = s / (sqrt(M_PI) * psd->q0 * psd->q0 * sqrt(vl_psd_value(psd, psd->q0)));
  size_t nkk = kinks(psd, sigma_end, NULL);
  double *pts = malloc((nkk + 40) * sizeof *pts);
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(4000);
  double result = NAN, abserr;
  if (!pts || !ws) goto cleanup;
  size_t np = 0;
  pts[np++] = 0.0;
  kinks(psd, sigma_end, pts + 1);
  np += nkk;
  double extra[3] = {0.25 * bb, bb, 4.0 * bb};
  for (int k = 0; k < 3; k++)
    if (extra[k] > 1e-20 && extra[k] < sigma_end) pts[np++] = extra[k];
  for (double dec = 0.1; dec > fmax(0.1 * bb, 1e-20) && np < nkk + 40; dec *= 0.1)
    if (dec < sigma_end) pts[np++] = dec;
  qsort(pts, np, sizeof *pts, cmp_double);
  size_t m = 1; /* drop near-duplicates: qagp needs increasing points */
  for (size_t k = 1; k < np; k++)
    if (pts[k] > pts[m - 1] * (1.0 + 1e-9)) pts[m++] = pts[k];
  np = m;
  exact_ctx ctx = {psd, s};
  gsl_function f = {exact_integrand, &ctx};
  int status = gsl_integration_qagp(&f, pts, np, 0.0, 1e-12, 4000, ws, &result, &abserr);
  if (status != GSL_SUCCESS && status != GSL_EROUND) result = NAN;
cleanup:
  free(pts);
  if (ws) gsl_integration_workspace_free(ws);
  return result;
}

double vl_persson_area_ratio(const vl_persson *t, double s, double *dads) {
  if (!(s > 0.0)) { /* s <= 0: no contact (NaN propagates) */
    if (dads) *dads = isnan(s) ? NAN : 0.0;
    return isnan(s) ? NAN : 0.0;
  }
  double sg = sqrt(t->g);
  double a = s / (2.0 * sg);
  if (dads) *dads = exp(-a * a) / (sqrt(M_PI) * sg);
  return erf(a);
}

double vl_persson_g(const vl_persson *t) { return t->g; }
double vl_persson_ustar(const vl_persson *t) { return t->ustar; }
double vl_persson_hrms(const vl_persson *t) { return t->hrms; }

size_t vl_persson_size(const vl_persson *t) { return t->n; }

/* ------------------------------------------------------ serialised form */

/* The blob (VL_PERSSON_FORMAT 1), every field little-endian, doubles as
 * their IEEE-754 bits:
 *   "VLPT", u32 format, u64 n                           (16 bytes)
 *   PSD fingerprint: u64 kind, f64 hurst, q0, q1, c0, hrms_m, u64 points,
 *     u64 FNV-1a hash of the points (q_k, C_k bits)     (64 bytes)
 *   f64 hrms, g, ustar                                  (24 bytes)
 *   f64 x[n], y[n], d[n], u[n]                          (32 n bytes)
 *   u64 FNV-1a hash of all the bytes before it          (8 bytes)
 * Written byte by byte so the file reads the same on any machine. What
 * follows from these (uc = u*, the end continuations) is recomputed, so a
 * stored table cannot contradict itself. */
#define BLOB_MAGIC "VLPT"
#define BLOB_HEAD 104 /* bytes before the nodes */
#define FNV_PRIME 0x100000001b3ULL

/* The byte helpers and the PSD fingerprint below are shared with the other
 * cached table, flow_factors_emt.c, through blob.h. */
void vl_blob_put_u64(unsigned char *p, uint64_t v) {
  for (int i = 0; i < 8; i++)
    p[i] = (unsigned char)(v >> (8 * i));
}

uint64_t vl_blob_get_u64(const unsigned char *p) {
  uint64_t v = 0;
  for (int i = 0; i < 8; i++)
    v |= (uint64_t)p[i] << (8 * i);
  return v;
}

uint64_t vl_blob_bits(double v) {
  uint64_t b;
  memcpy(&b, &v, sizeof b);
  return b;
}

double vl_blob_double(uint64_t b) {
  double v;
  memcpy(&v, &b, sizeof v);
  return v;
}

uint64_t vl_blob_fnv1a(uint64_t h, const unsigned char *p, size_t n) {
  for (size_t i = 0; i < n; i++) {
    h ^= p[i];
    h *= FNV_PRIME;
  }
  return h;
}

/* The 8 fingerprint words of a PSD (as vl_psd_init_* left it). */
void vl_blob_psd_fingerprint(const vl_psd *psd, uint64_t fp[VL_BLOB_PSD_WORDS]) {
  uint64_t h = VL_BLOB_FNV_OFFSET;
  for (size_t k = 0; k < psd->n; k++) {
    unsigned char b[16];
    vl_blob_put_u64(b, vl_blob_bits(psd->q[k]));
    vl_blob_put_u64(b + 8, vl_blob_bits(psd->C[k]));
    h = vl_blob_fnv1a(h, b, sizeof b);
  }
  fp[0] = (uint64_t)psd->kind;
  fp[1] = vl_blob_bits(psd->hurst);
  fp[2] = vl_blob_bits(psd->q0);
  fp[3] = vl_blob_bits(psd->q1);
  fp[4] = vl_blob_bits(psd->c0);
  fp[5] = vl_blob_bits(psd->hrms_m);
  fp[6] = (uint64_t)psd->n;
  fp[7] = h;
}

vl_status vl_persson_serialize(const vl_persson *t, void **blob, size_t *len, vl_error *err) {
  *blob = NULL;
  *len = 0;
  size_t size = BLOB_HEAD + 32 * t->n + 8;
  unsigned char *b = malloc(size), *p = b;
  if (!b) {
    vl_error_set(err, "out of memory serialising a %zu-point Persson table", t->n);
    return VL_ENOMEM;
  }
  memcpy(p, BLOB_MAGIC, 4);
  for (int i = 0; i < 4; i++)
    p[4 + i] = (unsigned char)((uint32_t)VL_PERSSON_FORMAT >> (8 * i));
  vl_blob_put_u64(p + 8, (uint64_t)t->n);
  p += 16;
  uint64_t fp[8];
  vl_blob_psd_fingerprint(&t->psd, fp);
  for (int i = 0; i < 8; i++, p += 8)
    vl_blob_put_u64(p, fp[i]);
  const double scalars[3] = {t->hrms, t->g, t->ustar};
  for (int i = 0; i < 3; i++, p += 8)
    vl_blob_put_u64(p, vl_blob_bits(scalars[i]));
  const double *arrays[4] = {t->x, t->y, t->d, t->u};
  for (int a = 0; a < 4; a++)
    for (size_t k = 0; k < t->n; k++, p += 8)
      vl_blob_put_u64(p, vl_blob_bits(arrays[a][k]));
  vl_blob_put_u64(p, vl_blob_fnv1a(VL_BLOB_FNV_OFFSET, b, size - 8));
  *blob = b;
  *len = size;
  return VL_OK;
}

/* Checks the values of a table read from a blob (everything the queries
 * rely on), and sets what follows from them. 0 with err set if any fails. */
static int table_check(vl_persson *t, vl_error *err) {
  if (vl_blob_bits(t->hrms) != vl_blob_bits(vl_psd_hrms(&t->psd)) ||
      vl_blob_bits(t->g) != vl_blob_bits(table_g(&t->psd))) {
    vl_error_set(err, "its h_rms or g is not the surface's: it belongs to another PSD");
    return 0;
  }
  if (!(isfinite(t->ustar) && t->ustar > 0.0)) {
    vl_error_set(err, "u* = %g m is not positive and finite", t->ustar);
    return 0;
  }
  t->uc = t->ustar;
  for (size_t k = 0; k < t->n; k++) {
    double x = t->x[k], y = t->y[k], d = t->d[k], u = t->u[k];
    if (!(isfinite(x) && isfinite(y) && isfinite(d) && isfinite(u) && u > 0.0 && d <= 0.0)) {
      vl_error_set(err, "node %zu is not finite, or has u <= 0 or a rising ln s", k);
      return 0;
    }
    if (k > 0 && !(x > t->x[k - 1] && u > t->u[k - 1] && y < t->y[k - 1])) {
      vl_error_set(err, "node %zu breaks the monotone order of the nodes", k);
      return 0;
    }
    /* the abscissa is a function of u: a stored pair that disagrees was
     * edited (or written by another u* or another libm: rebuilt, no harm) */
    if (vl_blob_bits(x) != vl_blob_bits(x_of_u(t, u, NULL))) {
      vl_error_set(err, "node %zu: its x does not match its u", k);
      return 0;
    }
  }
  set_ends(t);
  if (!(isfinite(t->dsdu_lo) && isfinite(t->slope_hi))) {
    vl_error_set(err, "the continuations beyond its ends are not finite");
    return 0;
  }
  return 1;
}

vl_status vl_persson_deserialize(const vl_psd *psd, const void *blob, size_t len, vl_persson **out,
                                 vl_error *err) {
  const unsigned char *b = blob;
  vl_persson *t = NULL;
  *out = NULL;
  vl_gsl_errors_off();
  if (!psd_usable(psd)) {
    vl_error_set(err, "Persson table: the PSD is not initialised or invalid");
    return VL_EINPUT;
  }
  if (!b || len < BLOB_HEAD + 8 || memcmp(b, BLOB_MAGIC, 4) != 0) {
    vl_error_set(err, "stored Persson table: not a table (%zu bytes, no 'VLPT' header)", len);
    return VL_EINPUT;
  }
  uint32_t format = 0;
  for (int i = 0; i < 4; i++)
    format |= (uint32_t)b[4 + i] << (8 * i);
  if (format != VL_PERSSON_FORMAT) {
    vl_error_set(err, "stored Persson table: format %lu, this program's is %d",
                 (unsigned long)format, VL_PERSSON_FORMAT);
    return VL_EINPUT;
  }
  uint64_t n64 = vl_blob_get_u64(b + 8);
  if (n64 < MIN_N_TABLE || n64 > MAX_N_TABLE || len != BLOB_HEAD + 32 * (size_t)n64 + 8) {
    vl_error_set(err, "stored Persson table: %zu bytes do not hold the %llu nodes it announces",
                 len, (unsigned long long)n64);
    return VL_EINPUT;
  }
  if (vl_blob_fnv1a(VL_BLOB_FNV_OFFSET, b, len - 8) != vl_blob_get_u64(b + len - 8)) {
    vl_error_set(err, "stored Persson table: checksum mismatch (damaged or edited)");
    return VL_EINPUT;
  }
  size_t n = (size_t)n64;
  vl_status st = table_alloc(psd, n, &t, err);
  if (st != VL_OK) return st;
  const unsigned char *p = b + 16;
  uint64_t fp[8];
  vl_blob_psd_fingerprint(&t->psd, fp);
  for (int i = 0; i < 8; i++, p += 8) {
    if (vl_blob_get_u64(p) != fp[i]) {
      vl_error_set(err, "stored Persson table: built for another PSD");
      vl_persson_free(t);
      return VL_EINPUT;
    }
  }
  double *scalars[3] = {&t->hrms, &t->g, &t->ustar};
  for (int i = 0; i < 3; i++, p += 8)
    *scalars[i] = vl_blob_double(vl_blob_get_u64(p));
  double *arrays[4] = {t->x, t->y, t->d, t->u};
  for (int a = 0; a < 4; a++)
    for (size_t k = 0; k < n; k++, p += 8)
      arrays[a][k] = vl_blob_double(vl_blob_get_u64(p));
  if (!table_check(t, err)) {
    vl_error_prefix(err, "stored Persson table");
    vl_persson_free(t);
    return VL_EINPUT;
  }
  *out = t;
  return VL_OK;
}
