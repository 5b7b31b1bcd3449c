/* Calibrating a pair's sigma_s law on a measured Stribeck curve
 * (calibrate.h): one sweep at the measured speeds splits mu into the part
 * sigma_s does not touch and the area integral it multiplies; the law's
 * parameters are then fitted in log10 mu. */
#include "viscolube/calibrate.h"
#include "shear_law_private.h"
#include "simulation_internal.h"
#include "viscolube/simulation.h"

#include "gsl_errors.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_multifit_nlinear.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_s(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void vl_calibration_sweep_free(vl_calibration_sweep *s) {
  if (!s) return;
  free(s->v_m_s);
  free(s->mu);
  free(s->mu_other);
  free(s->area);
  free(s->converged);
  memset(s, 0, sizeof *s);
}

void vl_calibration_fit_free(vl_calibration_fit *f) {
  if (!f) return;
  free(f->uninformative);
  f->uninformative = NULL;
}

typedef struct {
  double v, mu;
} vm_pair;

static int cmp_speed(const void *a, const void *b) {
  double x = ((const vm_pair *)a)->v, y = ((const vm_pair *)b)->v;
  return (x > y) - (x < y);
}

static vl_status sweep_alloc(vl_calibration_sweep *s, size_t n, vl_error *err) {
  memset(s, 0, sizeof *s);
  s->n = n;
  s->v_m_s = malloc(n * sizeof *s->v_m_s);
  s->mu = malloc(n * sizeof *s->mu);
  s->mu_other = malloc(n * sizeof *s->mu_other);
  s->area = malloc(n * sizeof *s->area);
  s->converged = calloc(n, sizeof *s->converged);
  if (s->v_m_s && s->mu && s->mu_other && s->area && s->converged) return VL_OK;
  vl_calibration_sweep_free(s);
  vl_error_set(err, "out of memory for %zu calibration points", n);
  return VL_ENOMEM;
}

/* Solves the distinct speeds of s (sorted) and fills mu_other, area. */
static vl_status sweep_solve(vl_db *db, const vl_query *q, vl_calibration_sweep *s, vl_error *err) {
  vl_query qr = *q;
  qr.sigma_s_given = true;
  qr.sigma_s_pa = VL_CALIBRATION_SIGMA_REF_PA;
  vl_scene *sc = malloc(sizeof *sc);
  double *uniq = malloc(s->n * sizeof *uniq);
  vl_point *pts = calloc(s->n, sizeof *pts);
  vl_simulation *sim = NULL;
  vl_status st = VL_OK;
  if (!sc || !uniq || !pts) {
    vl_error_set(err, "out of memory");
    st = VL_ENOMEM;
    goto cleanup;
  }
  size_t m = 0;
  for (size_t i = 0; i < s->n; i++)
    if (m == 0 || s->v_m_s[i] > uniq[m - 1]) uniq[m++] = s->v_m_s[i];
  if ((st = vl_query_scene(&qr, "calibration", sc, err)) != VL_OK) goto cleanup;
  if ((st = vl_query_check_compound(db, &qr, qr.compound, err)) != VL_OK) goto cleanup;
  if ((st = vl_query_fluid_eta(db, &qr, &s->eta_pa_s, err)) != VL_OK) goto cleanup;
  sc->from = uniq[0] * s->eta_pa_s, sc->to = uniq[m - 1] * s->eta_pa_s;
  sc->points = 1;
  if ((st = vl_simulation_create(sc, db, &sim, err)) != VL_OK) goto cleanup;
  s->temperature_c = vl_simulation_temperature_c(sim);
  vl_sweep_stats stats;
  if ((st = vl_simulation_run_speeds(sim, m, uniq, pts, &stats, err)) != VL_OK) goto cleanup;
  for (size_t i = 0, k = 0; i < s->n; i++) {
    while (uniq[k] < s->v_m_s[i])
      k++;
    const vl_point *p = &pts[k];
    s->converged[i] = p->converged;
    s->mu_other[i] = p->mu - p->mu_Sc;
    s->area[i] = p->mu_Sc / VL_CALIBRATION_SIGMA_REF_PA;
  }

cleanup:
  vl_simulation_free(sim);
  free(pts);
  free(uniq);
  free(sc);
  return st;
}

vl_status vl_calibration_sweep_run(vl_db *db, const vl_query *q, size_t n, const double *v_m_s,
                                   const double *mu_measured, vl_calibration_sweep *out,
                                   vl_error *err) {
  memset(out, 0, sizeof *out);
  if (n == 0) {
    vl_error_set(err, "no measured points");
    return VL_EINPUT;
  }
  for (size_t i = 0; i < n; i++)
    if (!(v_m_s[i] > 0.0 && isfinite(v_m_s[i]))) {
      vl_error_set(err, "point %zu: the sliding speed must be a positive number of m/s (got %g)",
                   i + 1, v_m_s[i]);
      return VL_EINPUT;
    }
  double t0 = now_s();
  vm_pair *vm = malloc(n * sizeof *vm);
  if (!vm) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  for (size_t i = 0; i < n; i++)
    vm[i] = (vm_pair){v_m_s[i], mu_measured ? mu_measured[i] : NAN};
  qsort(vm, n, sizeof *vm, cmp_speed);
  vl_status st = sweep_alloc(out, n, err);
  if (st == VL_OK) {
    for (size_t i = 0; i < n; i++)
      out->v_m_s[i] = vm[i].v, out->mu[i] = vm[i].mu;
    st = sweep_solve(db, q, out, err);
  }
  free(vm);
  if (st != VL_OK) {
    vl_calibration_sweep_free(out);
    return st;
  }
  if (!mu_measured)
    for (size_t i = 0; i < n; i++)
      out->mu[i] = out->mu_other[i] + VL_CALIBRATION_SIGMA_REF_PA * out->area[i];
  out->seconds = now_s() - t0;
  return VL_OK;
}

double vl_calibration_model_mu(const vl_calibration_sweep *s, size_t i, const vl_shear_law *law) {
  return s->mu_other[i] + vl_shear_law_eval(law, s->v_m_s[i], NULL) * s->area[i];
}

static bool usable(const vl_calibration_sweep *s, size_t i) {
  return s->converged[i] && s->mu[i] > 0.0 && isfinite(s->mu[i]);
}

double vl_calibration_misfit(const vl_calibration_sweep *s, const vl_shear_law *law) {
  vl_shear_law at;
  if (vl_shear_law_at(law, s->temperature_c, s->eta_pa_s, &at, NULL) != VL_OK) return NAN;
  double sum = 0.0;
  size_t m = 0;
  for (size_t i = 0; i < s->n; i++) {
    if (!usable(s, i)) continue;
    double model = vl_calibration_model_mu(s, i, &at);
    double r = model > 0.0 ? log10(model / s->mu[i]) : INFINITY;
    sum += r * r, m++;
  }
  return m ? sqrt(sum / (double)m) : NAN;
}

/* ---- the fit ---------------------------------------------------------- */

/* What the fit sees: the usable points, the law's kind, and how the fit's
 * unknowns x map to the parameters p (stresses p = S x, speeds p = e^x;
 * eyring's sigma_e too, so that it stays positive). */
typedef struct {
  const vl_calibration_sweep *s;
  size_t *idx, m;
  vl_shear_law_kind kind;
  double scale; /* S, Pa */
} fit_data;

static bool is_log(vl_shear_law_kind kind, size_t k) {
  return (kind == VL_SHEAR_EYRING && k >= 1) || (kind == VL_SHEAR_DEWETTING && k == 2);
}

static vl_shear_law law_of(const fit_data *d, const double *x) {
  vl_shear_law l = {d->kind, {0.0, 0.0, 0.0}, d->s->temperature_c, d->s->eta_pa_s};
  for (size_t k = 0; k < vl_shear_law_n_params(d->kind); k++)
    l.p[k] = is_log(d->kind, k) ? exp(x[k]) : d->scale * x[k];
  return l;
}

static double model_at(const fit_data *d, size_t j, const vl_shear_law *l, double *grad) {
  size_t i = d->idx[j];
  double sigma = vl_shear_law_eval(l, d->s->v_m_s[i], grad);
  return d->s->mu_other[i] + sigma * d->s->area[i];
}

/* log10 of a model value kept finite where a trial step makes it <= 0 */
#define MU_FLOOR 1e-12

static int fit_f(const gsl_vector *xv, void *params, gsl_vector *f) {
  const fit_data *d = params;
  vl_shear_law l = law_of(d, xv->data);
  for (size_t j = 0; j < d->m; j++) {
    double model = fmax(model_at(d, j, &l, NULL), MU_FLOOR);
    gsl_vector_set(f, j, log10(model / d->s->mu[d->idx[j]]));
  }
  return GSL_SUCCESS;
}

static int fit_df(const gsl_vector *xv, void *params, gsl_matrix *J) {
  const fit_data *d = params;
  vl_shear_law l = law_of(d, xv->data);
  size_t np = vl_shear_law_n_params(d->kind);
  for (size_t j = 0; j < d->m; j++) {
    double g[VL_SHEAR_LAW_MAX_PARAMS];
    double model = model_at(d, j, &l, g);
    double a = d->s->area[d->idx[j]] / (M_LN10 * fmax(model, MU_FLOOR));
    for (size_t k = 0; k < np; k++)
      gsl_matrix_set(J, j, k, a * g[k] * (is_log(d->kind, k) ? l.p[k] : d->scale));
  }
  return GSL_SUCCESS;
}

static double rms_of(const fit_data *d, const double *x) {
  vl_shear_law l = law_of(d, x);
  double sum = 0.0;
  for (size_t j = 0; j < d->m; j++) {
    double r = log10(fmax(model_at(d, j, &l, NULL), MU_FLOOR) / d->s->mu[d->idx[j]]);
    sum += r * r;
  }
  return sqrt(sum / (double)d->m);
}

/* Weighted (relative error) linear least squares of mu - mu_other =
 * I (a g0 + b g1) over the points: the start of every fit. g1 NULL: one
 * basis function. */
static void linear_fit(const fit_data *d, double (*g0)(const fit_data *, size_t, double),
                       double (*g1)(const fit_data *, size_t, double), double c, double *a,
                       double *b) {
  double s00 = 0, s01 = 0, s11 = 0, r0 = 0, r1 = 0;
  for (size_t j = 0; j < d->m; j++) {
    size_t i = d->idx[j];
    double w = 1.0 / (d->s->mu[i] * d->s->mu[i]), y = d->s->mu[i] - d->s->mu_other[i];
    double u0 = d->s->area[i] * g0(d, i, c), u1 = g1 ? d->s->area[i] * g1(d, i, c) : 0.0;
    s00 += w * u0 * u0, s01 += w * u0 * u1, s11 += w * u1 * u1;
    r0 += w * u0 * y, r1 += w * u1 * y;
  }
  if (!g1) {
    *a = s00 > 0 ? r0 / s00 : 0.0, *b = 0.0;
    return;
  }
  double det = s00 * s11 - s01 * s01;
  if (!(fabs(det) > 0.0)) {
    *a = *b = 0.0;
    return;
  }
  *a = (r0 * s11 - r1 * s01) / det;
  *b = (s00 * r1 - s01 * r0) / det;
}

static double g_one(const fit_data *d, size_t i, double c) {
  (void)d, (void)i, (void)c;
  return 1.0;
}
static double g_asinh(const fit_data *d, size_t i, double ve) { return asinh(d->s->v_m_s[i] / ve); }
static double g_wet(const fit_data *d, size_t i, double vd) {
  return 1.0 / (1.0 + pow(vd / d->s->v_m_s[i], VL_DEWETTING_SWITCH_N));
}
static double g_dry(const fit_data *d, size_t i, double vd) { return 1.0 - g_wet(d, i, vd); }

/* The start x: linear for the constant law; for the others the best of a
 * grid in the speed parameter (a quarter decade apart, from a decade below
 * to a decade above the measured speeds), each with its linear stresses. */
static void start_point(const fit_data *d, double *x) {
  double a, b;
  if (d->kind == VL_SHEAR_CONSTANT) {
    linear_fit(d, g_one, NULL, 0.0, &a, &b);
    x[0] = fmax(a, 1e-6 * d->scale) / d->scale;
    return;
  }
  double vmin = d->s->v_m_s[d->idx[0]], vmax = d->s->v_m_s[d->idx[d->m - 1]];
  double best = INFINITY;
  for (double lv = log10(vmin) - 1.0; lv <= log10(vmax) + 1.0; lv += 0.25) {
    double vc = pow(10.0, lv), t[3];
    if (d->kind == VL_SHEAR_EYRING) {
      linear_fit(d, g_one, g_asinh, vc, &a, &b);
      t[0] = fmax(a, 0.0) / d->scale, t[1] = log(fmax(b, 1e-4 * d->scale));
    } else {
      linear_fit(d, g_dry, g_wet, vc, &a, &b);
      t[0] = fmax(a, 0.0) / d->scale, t[1] = fmax(b, 0.0) / d->scale;
    }
    t[2] = log(vc);
    double r = rms_of(d, t);
    if (r < best) best = r, memcpy(x, t, sizeof t);
  }
}

/* The driver from x; *rms and the covariance of x (p by p) on success. */
static int nonlinear(fit_data *d, double *x, gsl_matrix *covar, int *iterations) {
  size_t np = vl_shear_law_n_params(d->kind);
  gsl_multifit_nlinear_fdf fdf = {fit_f, fit_df, NULL, d->m, np, d, 0, 0, 0};
  gsl_multifit_nlinear_parameters par = gsl_multifit_nlinear_default_parameters();
  gsl_multifit_nlinear_workspace *w =
      gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &par, d->m, np);
  if (!w) return GSL_ENOMEM;
  gsl_vector_view xv = gsl_vector_view_array(x, np);
  int info = 0, status = gsl_multifit_nlinear_init(&xv.vector, &fdf, w);
  if (status == GSL_SUCCESS)
    status = gsl_multifit_nlinear_driver(200, 1e-12, 1e-12, 0.0, NULL, NULL, &info, w);
  /* a fit that stops on its iteration limit near a flat optimum is kept:
   * the intervals will say how well it is determined */
  if (status == GSL_SUCCESS || status == GSL_EMAXITER) {
    memcpy(x, gsl_multifit_nlinear_position(w)->data, np * sizeof *x);
    status = gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(w), 0.0, covar);
    *iterations = (int)gsl_multifit_nlinear_niter(w);
  }
  gsl_multifit_nlinear_free(w);
  return status;
}

/* Points used: converged, mu > 0; VL_EINPUT on a mu <= 0 or too few. */
static vl_status pick_points(const vl_calibration_sweep *s, vl_shear_law_kind kind, fit_data *d,
                             vl_calibration_fit *out, vl_error *err) {
  size_t np = vl_shear_law_n_params(kind);
  for (size_t i = 0; i < s->n; i++)
    if (!(s->mu[i] > 0.0 && isfinite(s->mu[i]))) {
      vl_error_set(err,
                   "measured point %zu (v = %g m/s): the friction coefficient must be a positive "
                   "number (got %g)",
                   i + 1, s->v_m_s[i], s->mu[i]);
      return VL_EINPUT;
    }
  d->idx = malloc(s->n * sizeof *d->idx);
  if (!d->idx) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  for (size_t i = 0; i < s->n; i++) {
    if (usable(s, i) && s->area[i] > 0.0)
      d->idx[d->m++] = i;
    else
      out->n_unreached++;
  }
  if (d->m <= np) {
    vl_error_set(err,
                 "the %s law has %zu parameter%s: it needs at least %zu points the solver "
                 "reaches with solid contact (got %zu of %zu)",
                 vl_shear_law_name(kind), np, np > 1 ? "s" : "", np + 1, d->m, s->n);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* The intervals, shares and verdict of the fitted x. */
static void report(const fit_data *d, const double *x, const gsl_matrix *covar,
                   vl_calibration_fit *out) {
  size_t np = vl_shear_law_n_params(d->kind);
  out->law = law_of(d, x);
  out->n_used = d->m;
  out->rms_log10_mu = rms_of(d, x);
  double dof = (double)(d->m - np), s2 = out->rms_log10_mu * out->rms_log10_mu * (double)d->m / dof;
  double t = gsl_cdf_tdist_Pinv(0.975, dof);
  for (size_t k = 0; k < np; k++) {
    double se_x = sqrt(s2 * gsl_matrix_get(covar, k, k));
    out->ci95[k] = t * se_x * (is_log(d->kind, k) ? out->law.p[k] : d->scale);
  }
  for (size_t k = np; k < VL_SHEAR_LAW_MAX_PARAMS; k++)
    out->ci95[k] = NAN;
  for (size_t j = 0; j < d->m; j++) {
    size_t i = d->idx[j];
    double sc = vl_shear_law_eval(&out->law, d->s->v_m_s[i], NULL) * d->s->area[i];
    double share = sc / fmax(model_at(d, j, &out->law, NULL), MU_FLOOR);
    if (share < VL_CALIBRATION_MIN_SC_SHARE) out->uninformative[i] = true, out->n_uninformative++;
  }
  vl_error why;
  out->fits = false;
  if (!(out->rms_log10_mu <= VL_CALIBRATION_MAX_RMS_LOG10))
    snprintf(out->why, sizeof out->why,
             "rms misfit %.3g in log10 mu is above %g (a factor %.2f): the %s law does not "
             "describe this curve",
             out->rms_log10_mu, VL_CALIBRATION_MAX_RMS_LOG10,
             pow(10.0, VL_CALIBRATION_MAX_RMS_LOG10), vl_shear_law_name(d->kind));
  else if (vl_shear_law_validate(&out->law, &why) != VL_OK)
    snprintf(out->why, sizeof out->why, "the best fit is not a valid law: %.200s", why.msg);
  else if (out->n_uninformative + np > d->m)
    snprintf(out->why, sizeof out->why,
             "mu_Sc is below %g %% of mu at %zu of %zu points: too few points inform the fit",
             100 * VL_CALIBRATION_MIN_SC_SHARE, out->n_uninformative, d->m);
  else
    out->fits = true;
}

vl_status vl_calibration_fit_law(const vl_calibration_sweep *s, vl_shear_law_kind kind,
                                 vl_calibration_fit *out, vl_error *err) {
  memset(out, 0, sizeof *out);
  vl_gsl_errors_off();
  double t0 = now_s();
  fit_data d = {s, NULL, 0, kind, VL_CALIBRATION_SIGMA_REF_PA};
  size_t np = vl_shear_law_n_params(kind);
  gsl_matrix *covar = NULL;
  vl_status st = VL_OK;
  if (np == 0) {
    vl_error_set(err, "unknown shear-stress law (kind %d)", (int)kind);
    return VL_EINPUT;
  }
  out->uninformative = calloc(s->n, sizeof *out->uninformative);
  covar = gsl_matrix_alloc(np, np);
  if (!out->uninformative || !covar) {
    vl_error_set(err, "out of memory");
    st = VL_ENOMEM;
    goto cleanup;
  }
  if ((st = pick_points(s, kind, &d, out, err)) != VL_OK) goto cleanup;
  double x[VL_SHEAR_LAW_MAX_PARAMS] = {0.0, 0.0, 0.0};
  start_point(&d, x);
  int status = nonlinear(&d, x, covar, &out->iterations);
  if (status != GSL_SUCCESS) {
    out->law = law_of(&d, x);
    out->rms_log10_mu = rms_of(&d, x);
    out->n_used = d.m;
    for (size_t k = 0; k < VL_SHEAR_LAW_MAX_PARAMS; k++)
      out->ci95[k] = NAN;
    snprintf(out->why, sizeof out->why, "the nonlinear least-squares fit failed (%s)",
             gsl_strerror(status));
  } else {
    report(&d, x, covar, out);
  }
  out->seconds = now_s() - t0;

cleanup:
  gsl_matrix_free(covar);
  free(d.idx);
  if (st != VL_OK) vl_calibration_fit_free(out);
  return st;
}
