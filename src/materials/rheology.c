#include "viscolube/rheology.h"
#include "rheology_internal.h"

#include <complex.h>
#include <math.h>
#include <stdbool.h>

vl_status vl_prony_validate(const vl_prony *prony, vl_error *err) {
  if (!(isfinite(prony->e_inf_pa) && prony->e_inf_pa > 0.0)) {
    vl_error_set(err, "Einf must be a positive finite modulus (got %g Pa)", prony->e_inf_pa);
    return VL_EINPUT;
  }
  if (!(isfinite(prony->nu) && prony->nu >= 0.0 && prony->nu <= 0.5)) {
    vl_error_set(err, "nu must lie in [0, 0.5] (got %g)", prony->nu);
    return VL_EINPUT;
  }
  if (prony->n_terms > VL_PRONY_MAX_TERMS) {
    vl_error_set(err, "too many Prony terms (%zu > %d)", prony->n_terms, VL_PRONY_MAX_TERMS);
    return VL_EINPUT;
  }
  for (size_t i = 0; i < prony->n_terms; i++) {
    if (!(isfinite(prony->A[i]) && prony->A[i] >= 0.0)) {
      vl_error_set(err, "Prony term %zu: A must be finite and >= 0 (got %g)", i + 1, prony->A[i]);
      return VL_EINPUT;
    }
    if (!(isfinite(prony->tau_s[i]) && prony->tau_s[i] > 0.0)) {
      vl_error_set(err, "Prony term %zu: tau_s must be finite and > 0 (got %g)", i + 1,
                   prony->tau_s[i]);
      return VL_EINPUT;
    }
  }
  return VL_OK;
}

vl_prony vl_prony_single(double e0_pa, double einf_over_e0, double tau_s, double nu) {
  vl_prony p = {0};
  p.e_inf_pa = e0_pa * einf_over_e0;
  p.nu = nu;
  if (einf_over_e0 > 1.0) {
    p.n_terms = 1;
    p.A[0] = einf_over_e0 - 1.0;
    p.tau_s[0] = tau_s;
  }
  return p;
}

double vl_prony_sum_A(const vl_prony *prony) {
  double s = 0.0;
  for (size_t i = 0; i < prony->n_terms; i++)
    s += prony->A[i];
  return s;
}

double vl_prony_e0(const vl_prony *prony) {
  return prony->e_inf_pa / (1.0 + vl_prony_sum_A(prony));
}

double vl_prony_reduced_factor(const vl_prony *prony) {
  return 1.0 / (1.0 - prony->nu * prony->nu);
}

double complex vl_prony_compliance(const vl_prony *prony, double omega) {
  double complex s = 1.0;
  /* conjugate of the creep form: J' - i J'' (see rheology.h) */
  for (size_t i = 0; i < prony->n_terms; i++)
    s += prony->A[i] / (1.0 + I * omega * prony->tau_s[i]);
  return s / prony->e_inf_pa;
}

double complex vl_prony_modulus(const vl_prony *prony, double omega) {
  return 1.0 / vl_prony_compliance(prony, omega);
}

double vl_prony_tan_delta(const vl_prony *prony, double omega) {
  double complex e = vl_prony_modulus(prony, omega);
  return cimag(e) / creal(e);
}

/* The tan delta maximum over ln w in [lo, hi]: a 400-point log grid, then
 * golden section within a cell of the best point (clamped to [lo, hi]). */
static double peak_between(const vl_prony *prony, double lo, double hi, double *td_peak) {
  const int n = 400;
  double best = lo, best_td = -1.0;
  for (int k = 0; k <= n; k++) {
    double lw = lo + (hi - lo) * k / n;
    double td = vl_prony_tan_delta(prony, exp(lw));
    if (td > best_td) best_td = td, best = lw;
  }
  double step = (hi - lo) / n;
  double a = fmax(lo, best - step), b = fmin(hi, best + step);
  const double g = 0.5 * (sqrt(5.0) - 1.0);
  for (int it = 0; it < 100 && b - a > 1e-12; it++) {
    double c = b - g * (b - a), d = a + g * (b - a);
    if (vl_prony_tan_delta(prony, exp(c)) > vl_prony_tan_delta(prony, exp(d)))
      b = d;
    else
      a = c;
  }
  double lw = 0.5 * (a + b);
  *td_peak = vl_prony_tan_delta(prony, exp(lw));
  if (best_td > *td_peak) lw = best, *td_peak = best_td; /* a grid end beats the interior */
  return lw;
}

vl_status vl_prony_loss_peak(const vl_prony *prony, double *omega_peak, double *tan_delta_peak,
                             vl_error *err) {
  double tmin = INFINITY, tmax = 0.0;
  for (size_t i = 0; i < prony->n_terms; i++) {
    if (prony->A[i] <= 0.0) continue;
    tmin = fmin(tmin, prony->tau_s[i]);
    tmax = fmax(tmax, prony->tau_s[i]);
  }
  if (!(tmax > 0.0)) {
    vl_error_set(err, "an elastic material has no loss-tangent peak");
    return VL_EINPUT;
  }
  /* The peak of a sum of Debye terms lies within a few decades of 1/tau. */
  double td,
      lw = peak_between(prony, log(1.0 / tmax) - 3.0 * M_LN10, log(1.0 / tmin) + 3.0 * M_LN10, &td);
  if (omega_peak) *omega_peak = exp(lw);
  if (tan_delta_peak) *tan_delta_peak = td;
  return VL_OK;
}

vl_status vl_prony_loss_peak_in(const vl_prony *prony, double omega_min, double omega_max,
                                double *omega_peak, double *tan_delta_peak, int *at_edge,
                                vl_error *err) {
  if (!(omega_min > 0.0 && omega_max > omega_min && isfinite(omega_max))) {
    vl_error_set(err, "invalid frequency window %g to %g rad/s", omega_min, omega_max);
    return VL_EINPUT;
  }
  if (prony->n_terms == 0) {
    vl_error_set(err, "an elastic material has no loss-tangent peak");
    return VL_EINPUT;
  }
  double lo = log(omega_min), hi = log(omega_max), td;
  double lw = peak_between(prony, lo, hi, &td);
  /* within a thousandth of the window's log width of an end: the curve
   * still rises there */
  double tol = 1e-3 * (hi - lo);
  int edge = lw <= lo + tol ? -1 : lw >= hi - tol ? 1 : 0;
  if (omega_peak) *omega_peak = exp(lw);
  if (tan_delta_peak) *tan_delta_peak = td;
  if (at_edge) *at_edge = edge;
  return VL_OK;
}

void vl_prony_shift(vl_prony *prony, double a_T) {
  for (size_t i = 0; i < prony->n_terms; i++)
    prony->tau_s[i] *= a_T;
}

double vl_wlf_log10_shift(double c1, double c2_k, double t_c, double tref_c) {
  double den = c2_k + t_c - tref_c;
  if (!(den > 0.0)) return NAN;
  return -c1 * (t_c - tref_c) / den;
}

/* The contact's half-width (line, W per length) or radius (ball, W a
 * force) of Hertz at the reduced modulus e. */
static double hertz_size(double load, double radius_m, bool ball, double e) {
  return ball ? cbrt(0.75 * load * radius_m / e) : sqrt(4.0 * load * radius_m / (M_PI * e));
}

/* The fixed point wH = pi v0 / a_H(|Er(wH)|) (docs/MODEL.md section 4) of
 * a line or a ball. */
static void asperity_fixed_point(const vl_prony *rubber, double load, double radius_m, bool ball,
                                 double v0_m_s, double *E_abs_pa, double *a_H_m, double *omega_H) {
  double red = vl_prony_reduced_factor(rubber);
  double lo = log(vl_prony_e0(rubber) * red), hi = log(rubber->e_inf_pa * red);
  double x = lo;
  if (rubber->n_terms > 0 && v0_m_s > 0.0 && hi > lo) {
    /* f(x) = ln|Er(w(e^x))| - x is decreasing: |Er| grows slower than w, and
     * w ~ e^(x/2) (line) or e^(x/3) (ball); bisection in ln|Er| is robust
     * over all speeds. */
    for (int it = 0; it < 200 && hi - lo > 1e-15 * fabs(hi); it++) {
      double mid = 0.5 * (lo + hi);
      double w = M_PI * v0_m_s / hertz_size(load, radius_m, ball, exp(mid));
      double f = log(cabs(vl_prony_modulus(rubber, w)) * red) - mid;
      if (f > 0.0)
        lo = mid;
      else
        hi = mid;
    }
    x = 0.5 * (lo + hi);
  }
  double e = exp(x);
  double a = hertz_size(load, radius_m, ball, e);
  if (E_abs_pa) *E_abs_pa = e;
  if (a_H_m) *a_H_m = a;
  if (omega_H) *omega_H = M_PI * v0_m_s / a;
}

void vl_asperity_state(const vl_prony *rubber, double load_n_per_m, double radius_m, double v0_m_s,
                       double *E_abs_pa, double *a_H_m, double *omega_H) {
  asperity_fixed_point(rubber, load_n_per_m, radius_m, false, v0_m_s, E_abs_pa, a_H_m, omega_H);
}

void vl_asperity_state_ball(const vl_prony *rubber, double load_n, double radius_m, double v0_m_s,
                            double *E_abs_pa, double *a_H_m, double *omega_H) {
  asperity_fixed_point(rubber, load_n, radius_m, true, v0_m_s, E_abs_pa, a_H_m, omega_H);
}
