/* Viscous flattening of the asperities: epsilon_f (seed Appendix C).
 *
 * Derivation (the seed's Eqs. 23-27, written out because its printed
 * Eqs. 29 and 31 are garbled). Only the rubber is rough, it moves at v0 e1
 * relative to the smooth cylinder (v_1 = v0 e1 = v_R, v_2 = 0). The film
 * obeys d h/dt + div(v_m h - h^3/(12 eta) grad p) = 0, v_m = v0 e1 / 2.
 * Perturbing around the mean separation u with grad pf ~ 0, a component
 * h1 exp(i(q.x - w t)) gives p1 = K^f h1 with
 *   K^f = -12 i eta (q.v_m - w) / (u^3 q^2),
 * and for the roughness carried by the rubber w = q.v_1, so
 *   q.v_m - w = -q.v_1/2 = -(q v0 cos theta)/2:  |K^f| = 6 eta v0 |cos| / (u^3 q).
 * The rubber surface moves by K^c p1 with K^c = -2 J_r / q (half-space,
 * reduced compliance J_r = 1/Er), hence h1 = h_r / (1 - K^c K^f) and
 *   1/lambda = |1 - K^c K^f|^-2,  K^c K^f = i (J'_r - i J''_r) s cos(theta) (up to sign),
 *   s = 12 eta v0 / (u^3 q^2),
 *   lambda = (1 + J''_r s cos)^2 + (J'_r s cos)^2  (the sign of the cos term
 *                                                  drops out of the average).
 * With K(q) = -2/(Er_inf q), k_re + i k_im = Er_inf J_r and F_s = 6 eta v0 /
 * (q0^2 h_rms^3 Er_inf) this is lambda = (1 + 2 k_im F_s X)^2 + (2 k_re F_s X)^2,
 * X = cos/((u/h_rms)^3 zeta^2): the seed's Eq. 31 has the factor 2 in the
 * first bracket and lost it in the second (Eq. 29 likewise). The seed
 * evaluates the compliance at wH = pi v0/aH instead of the relaxed value
 * the steady pattern would see (its own remark), so it carries the phase
 * tan delta(wH) = J''/J'; VL_FLATTENING_MODULUS keeps only |J_r(wH)|. */
#include "viscolube/flattening.h"

#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include "flattening_internal.h"
#include "gsl_errors.h"
#include "rheology_internal.h"
#include "roughness_internal.h"
#include "viscolube/flattening.h"
#include "viscolube/rheology.h"

/* Gauss-Legendre in ln q: 8 nodes on panels of at most a quarter decade.
 * The integrand q^2 C(q) A(T/q^2) turns over within about a decade of q
 * (A goes from 1/t to 1 as t = T/q^2 drops through 1), so a quarter-decade
 * 8-point rule is converged to rounding (measured < 1e-13 against QAG). */
#define GL_ORDER 8
#define PANEL_DECADES 0.25

#define DEFAULT_PER_DECADE 64
#define DEFAULT_U_MIN_HRMS 1e-3
#define DEFAULT_U_MAX_HRMS 1e2

struct vl_flattening {
  vl_flattening_config cfg;
  double hrms_m, q0;
  size_t nq;
  double *w;   /* normalised weights of q^2 C(q) d(ln q): sum w = 1 */
  double *iq2; /* 1/q^2 at the nodes */
  /* current speed */
  vl_flattening_state st;
  double t_coef; /* 12 eta |v0| j_eff, so t_k = t_coef / (u^3 q_k^2) */
  double delta;  /* tan delta used in lambda */
  /* table in x = ln(u/h_rms) */
  size_t nt;
  double x_min, x_max, hx;
  double *ty, *tg; /* ln epsilon_f and d ln epsilon_f / dx at the nodes */
};

vl_status vl_flattening_response_parse(const char *text, vl_flattening_response *out,
                                       vl_error *err) {
  if (text && !strcmp(text, "complex"))
    *out = VL_FLATTENING_COMPLEX;
  else if (text && !strcmp(text, "modulus"))
    *out = VL_FLATTENING_MODULUS;
  else {
    vl_error_set(err, "unknown flattening response '%s' (known: complex, modulus)",
                 text ? text : "");
    return VL_EINPUT;
  }
  return VL_OK;
}

const char *vl_flattening_response_name(vl_flattening_response response) {
  return response == VL_FLATTENING_MODULUS ? "modulus" : "complex";
}

void vl_flattening_config_defaults(vl_flattening_config *cfg) {
  memset(cfg, 0, sizeof *cfg);
  cfg->load_n_per_m = 117.0;
  cfg->radius_m = 1e-3;
  cfg->eta_pa_s = 0.0;
  cfg->response = VL_FLATTENING_MODULUS;
}

double vl_flattening_angular(double t, double tan_delta, double *dA_dt) {
  double A, dA;
  if (!(t > 0.0)) {
    A = 1.0, dA = 0.0;
  } else if (t > 1e100) {
    /* t^2 would overflow; the next term is O(1/t^3) */
    A = 1.0 / t, dA = -1.0 / (t * t);
  } else if (tan_delta == 0.0) {
    double r = 1.0 / sqrt(1.0 + t * t);
    A = r, dA = -t * r * r * r;
  } else {
    /* lambda(c) = r^2 (c - c+)(c - c-), c = cos, r^2 = (1 + delta^2) t^2,
     * c+- = (-delta t +- i t)/r^2, so 1/lambda = Im[1/(c - c+)]/t; with
     * (1/2pi) \int dtheta/(cos - c+) = -1/sqrt(c+^2 - 1) (the root with
     * |c+ + sqrt| > 1) and z = t c+ this is A = Re[1/sqrt(t^2 - z^2)].
     * t^2 - z^2 keeps Im >= 0 for every t >= 0, so the principal root is
     * the right branch along the whole real t axis (no crossing). */
    double d = tan_delta, n = 1.0 + d * d;
    double zr = (d * d - 1.0) / (n * n), zi = -2.0 * d / (n * n); /* z^2 */
    double complex m = csqrt((t * t - zr) - zi * I);
    double complex r = 1.0 / m;
    A = creal(r);
    dA = -t * creal(r * r * r);
  }
  if (dA_dt) *dA_dt = dA;
  return A;
}

/* The q quadrature: panel ends in ln q (uniform, plus the tabulated points
 * where the PSD's slope jumps), 8 Gauss-Legendre nodes each. */
static vl_status build_quadrature(vl_flattening *f, const vl_psd *psd, vl_error *err) {
  double la = log(psd->q0), lb = log(psd->q1);
  size_t nu = (size_t)ceil((lb - la) / (PANEL_DECADES * M_LN10));
  if (nu < 1) nu = 1;
  size_t nb_max = nu + 1 + (psd->kind == VL_PSD_TABULATED ? psd->n : 0);
  double *b = malloc(nb_max * sizeof *b);
  if (!b) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  size_t nb = 0;
  for (size_t i = 0; i <= nu; i++)
    b[nb++] = la + (lb - la) * (double)i / (double)nu;
  if (psd->kind == VL_PSD_TABULATED)
    for (size_t i = 0; i < psd->n; i++) {
      double l = log(psd->q[i]);
      if (l > la && l < lb) b[nb++] = l;
    }
  /* insertion sort (tens of points), then drop near-duplicates */
  for (size_t i = 1; i < nb; i++)
    for (size_t j = i; j > 0 && b[j - 1] > b[j]; j--) {
      double tmp = b[j];
      b[j] = b[j - 1], b[j - 1] = tmp;
    }
  size_t m = 1;
  for (size_t i = 1; i < nb; i++)
    if (b[i] - b[m - 1] > 1e-12 * (lb - la)) b[m++] = b[i];
  b[m - 1] = lb;
  size_t np = m - 1;

  vl_gsl_errors_off();
  gsl_integration_glfixed_table *gl = gsl_integration_glfixed_table_alloc(GL_ORDER);
  f->nq = np * GL_ORDER;
  f->w = malloc(f->nq * sizeof *f->w);
  f->iq2 = malloc(f->nq * sizeof *f->iq2);
  if (!gl || !f->w || !f->iq2) {
    if (gl) gsl_integration_glfixed_table_free(gl);
    free(b);
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  double sum = 0.0;
  size_t k = 0;
  for (size_t p = 0; p < np; p++)
    for (size_t i = 0; i < GL_ORDER; i++, k++) {
      double x, wi;
      gsl_integration_glfixed_point(b[p], b[p + 1], i, &x, &wi, gl);
      double q = exp(x);
      f->w[k] = wi * q * q * vl_psd_value(psd, q);
      f->iq2[k] = 1.0 / (q * q);
      sum += f->w[k];
    }
  gsl_integration_glfixed_table_free(gl);
  free(b);
  /* normalised by the same rule, so epsilon_f = 1 exactly when A = 1 */
  if (!(sum > 0.0) || !isfinite(sum)) {
    vl_error_set(err, "the surface's spectrum has no weight in [q0, q1]");
    return VL_EINPUT;
  }
  for (k = 0; k < f->nq; k++)
    f->w[k] /= sum;
  return VL_OK;
}

/* Speed-dependent constants, no table. */
static void set_state(vl_flattening *f, double v0) {
  vl_flattening_state *s = &f->st;
  v0 = fabs(v0);
  s->v0_m_s = v0;
  s->hrms_m = f->hrms_m;
  vl_asperity_state(&f->cfg.rubber, f->cfg.load_n_per_m, f->cfg.radius_m, v0, &s->e_abs_pa,
                    &s->a_h_m, &s->omega_h_rad_s);
  double red = vl_prony_reduced_factor(&f->cfg.rubber);
  /* vl_prony_compliance gives J' - i J'' of E; 1/Er = (1 - nu^2)/E */
  double complex j = vl_prony_compliance(&f->cfg.rubber, s->omega_h_rad_s) / red;
  double jr = creal(j), ji = -cimag(j);
  if (f->cfg.response == VL_FLATTENING_MODULUS) {
    s->j_eff_per_pa = cabs(j);
    s->tan_delta = 0.0;
  } else {
    s->j_eff_per_pa = jr;
    s->tan_delta = ji > 0.0 ? ji / jr : 0.0;
  }
  f->delta = s->tan_delta;
  f->t_coef = 12.0 * f->cfg.eta_pa_s * v0 * s->j_eff_per_pa;
  s->u_onset_m = cbrt(f->t_coef / (f->q0 * f->q0));
}

double vl_flattening_eps_exact(const vl_flattening *f, double u_m, double *deps_du) {
  if (deps_du) *deps_du = 0.0;
  if (f->t_coef == 0.0) return 1.0;
  if (!(u_m > 0.0)) return 0.0;
  double T = f->t_coef / (u_m * u_m * u_m);
  if (!isfinite(T)) return 0.0;
  double e = 0.0, de = 0.0;
  for (size_t k = 0; k < f->nq; k++) {
    double t = T * f->iq2[k], dA;
    e += f->w[k] * vl_flattening_angular(t, f->delta, &dA);
    de += f->w[k] * dA * t;
  }
  /* dt/du = -3 t/u */
  if (deps_du) *deps_du = -3.0 * de / u_m;
  return e;
}

vl_status vl_flattening_create(const vl_flattening_config *cfg, const vl_psd *psd,
                               vl_flattening **out, vl_error *err) {
  *out = NULL;
  vl_status st = vl_prony_validate(&cfg->rubber, err);
  if (st != VL_OK) return st;
  if (!(isfinite(cfg->load_n_per_m) && cfg->load_n_per_m > 0.0) ||
      !(isfinite(cfg->radius_m) && cfg->radius_m > 0.0)) {
    vl_error_set(err, "flattening: load (%g N/m) and radius (%g m) must be positive and finite",
                 cfg->load_n_per_m, cfg->radius_m);
    return VL_EINPUT;
  }
  if (!(isfinite(cfg->eta_pa_s) && cfg->eta_pa_s >= 0.0)) {
    vl_error_set(err, "flattening: viscosity must be finite and >= 0 (got %g Pa s)", cfg->eta_pa_s);
    return VL_EINPUT;
  }
  if (cfg->response != VL_FLATTENING_MODULUS && cfg->response != VL_FLATTENING_COMPLEX) {
    vl_error_set(err, "flattening: unknown response %d", (int)cfg->response);
    return VL_EINPUT;
  }
  double umin = cfg->table_u_min_hrms, umax = cfg->table_u_max_hrms;
  if (umin == 0.0 && umax == 0.0) umin = DEFAULT_U_MIN_HRMS, umax = DEFAULT_U_MAX_HRMS;
  size_t per = cfg->table_per_decade ? cfg->table_per_decade : DEFAULT_PER_DECADE;
  if (!(isfinite(umin) && isfinite(umax) && umin > 0.0 && umax > umin) || per > 1000) {
    vl_error_set(err,
                 "flattening: table range needs 0 < u_min < u_max (got %g, %g h_rms) and at "
                 "most 1000 nodes per decade (got %zu)",
                 umin, umax, per);
    return VL_EINPUT;
  }
  if (!psd || !(psd->q0 > 0.0 && psd->q1 > psd->q0 && isfinite(psd->q1)) ||
      !(psd->hrms_m > 0.0 && isfinite(psd->hrms_m))) {
    vl_error_set(err, "flattening: the surface needs 0 < q0 < q1 and h_rms > 0");
    return VL_EINPUT;
  }
  vl_flattening *f = calloc(1, sizeof *f);
  if (!f) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  f->cfg = *cfg;
  f->cfg.table_per_decade = per;
  f->cfg.table_u_min_hrms = umin;
  f->cfg.table_u_max_hrms = umax;
  f->hrms_m = psd->hrms_m;
  f->q0 = psd->q0;
  st = build_quadrature(f, psd, err);
  if (st == VL_OK) {
    f->x_min = log(umin);
    f->x_max = log(umax);
    f->nt = (size_t)ceil((f->x_max - f->x_min) / M_LN10 * (double)per - 1e-9) + 1;
    if (f->nt < 2) f->nt = 2;
    f->hx = (f->x_max - f->x_min) / (double)(f->nt - 1);
    f->ty = malloc(f->nt * sizeof *f->ty);
    f->tg = malloc(f->nt * sizeof *f->tg);
    if (!f->ty || !f->tg) {
      vl_error_set(err, "out of memory");
      st = VL_ENOMEM;
    }
  }
  if (st != VL_OK) {
    vl_flattening_free(f);
    return st;
  }
  vl_error scratch;
  vl_flattening_set_speed(f, 0.0, &scratch); /* cannot fail */
  *out = f;
  return VL_OK;
}

void vl_flattening_free(vl_flattening *f) {
  if (!f) return;
  free(f->w);
  free(f->iq2);
  free(f->ty);
  free(f->tg);
  free(f);
}

vl_status vl_flattening_set_speed(vl_flattening *f, double v0_m_s, vl_error *err) {
  if (!isfinite(v0_m_s)) {
    vl_error_set(err, "flattening: the speed must be finite (got %g m/s)", v0_m_s);
    return VL_EINPUT;
  }
  set_state(f, v0_m_s);
  for (size_t j = 0; j < f->nt; j++) {
    double x = j + 1 == f->nt ? f->x_max : f->x_min + f->hx * (double)j;
    double u = f->hrms_m * exp(x), d;
    double e = vl_flattening_eps_exact(f, u, &d);
    f->ty[j] = log(e);
    f->tg[j] = d * u / e; /* d ln epsilon / d ln u */
  }
  return VL_OK;
}

vl_status vl_flattening_set_viscosity(vl_flattening *f, double eta_pa_s, vl_error *err) {
  if (!(isfinite(eta_pa_s) && eta_pa_s >= 0.0)) {
    vl_error_set(err, "flattening: viscosity must be finite and >= 0 (got %g Pa s)", eta_pa_s);
    return VL_EINPUT;
  }
  f->cfg.eta_pa_s = eta_pa_s;
  return vl_flattening_set_speed(f, f->st.v0_m_s, err);
}

double vl_flattening_eps(const vl_flattening *f, double u_m, double *deps_du) {
  if (f->t_coef == 0.0) {
    if (deps_du) *deps_du = 0.0;
    return 1.0;
  }
  if (!(u_m > 0.0)) return vl_flattening_eps_exact(f, u_m, deps_du);
  double x = log(u_m / f->hrms_m);
  if (!(x >= f->x_min && x <= f->x_max)) return vl_flattening_eps_exact(f, u_m, deps_du);
  double r = (x - f->x_min) / f->hx;
  size_t j = (size_t)r;
  if (j > f->nt - 2) j = f->nt - 2;
  double s = r - (double)j, h = f->hx;
  double s2 = s * s, s3 = s2 * s;
  double y0 = f->ty[j], y1 = f->ty[j + 1], g0 = h * f->tg[j], g1 = h * f->tg[j + 1];
  double y = (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * g0 + (-2 * s3 + 3 * s2) * y1 +
             (s3 - s2) * g1;
  double e = exp(y);
  if (deps_du) {
    double dyds = (6 * s2 - 6 * s) * (y0 - y1) + (3 * s2 - 4 * s + 1) * g0 + (3 * s2 - 2 * s) * g1;
    *deps_du = e * dyds / (h * u_m); /* ds/du = 1/(h u) */
  }
  return e;
}

void vl_flattening_state_get(const vl_flattening *f, vl_flattening_state *out) { *out = f->st; }

double vl_flattening_epsilon(const vl_flattening_config *cfg, const vl_psd *psd, double v0_m_s,
                             double u_m, double *deps_du, vl_error *err) {
  if (deps_du) *deps_du = NAN;
  if (!isfinite(v0_m_s) || isnan(u_m)) {
    vl_error_set(err, "flattening: speed and separation must be numbers (got %g m/s, %g m)", v0_m_s,
                 u_m);
    return NAN;
  }
  vl_flattening_config c = *cfg;
  c.table_per_decade = 1, c.table_u_min_hrms = 1.0, c.table_u_max_hrms = 10.0; /* unused */
  vl_flattening *f = NULL;
  if (vl_flattening_create(&c, psd, &f, err) != VL_OK) return NAN;
  set_state(f, v0_m_s);
  double e = vl_flattening_eps_exact(f, u_m, deps_du);
  vl_flattening_free(f);
  return e;
}
