/* Creep-form Prony fit by weighted non-negative least squares (prony_fit.h). */
#include "viscolube/prony_fit.h"

#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "nnls.h"

/* Below this fraction of the largest c_i a term changes no fitted value by
 * more than rounding: it is dropped rather than stored as noise. */
#define DROP_REL 1e-12

const char *vl_prony_weights_name(vl_prony_weights w) {
  return w == VL_PRONY_WEIGHTS_MODULUS    ? "modulus"
         : w == VL_PRONY_WEIGHTS_RELATIVE ? "relative"
                                          : "?";
}

size_t vl_prony_fit_grid(double omega_min_rad_s, double omega_max_rad_s, double terms_per_decade,
                         double *tau_s, size_t cap) {
  if (!(omega_min_rad_s > 0.0 && omega_max_rad_s > omega_min_rad_s && isfinite(omega_max_rad_s) &&
        terms_per_decade > 0.0 && isfinite(terms_per_decade)))
    return 0;
  double decades = log10(omega_max_rad_s / omega_min_rad_s);
  /* 1e-9 keeps an exact 3.0 decades x 2 from rounding up to 8 points */
  double steps = ceil(decades * terms_per_decade - 1e-9);
  if (steps < 1.0) steps = 1.0;
  if (steps > 1e6) return 0;
  size_t n = (size_t)steps + 1;
  double lo = -log10(omega_max_rad_s), hi = -log10(omega_min_rad_s);
  for (size_t i = 0; tau_s && i < n && i < cap; i++)
    tau_s[i] = pow(10.0, lo + (hi - lo) * (double)i / (double)(n - 1));
  return n;
}

vl_status vl_prony_fit(size_t n, const double *omega_rad_s, const double *storage_pa,
                       const double *loss_pa, double terms_per_decade, vl_prony_weights weights,
                       double nu, vl_prony *out, vl_prony_fit_report *report, vl_error *err) {
  vl_status st = VL_OK;
  double *a = NULL, *b = NULL, *x = NULL;
  double tau[VL_PRONY_MAX_TERMS];
  vl_prony_fit_report rep;
  memset(&rep, 0, sizeof rep);
  if (terms_per_decade == 0.0) terms_per_decade = VL_PRONY_FIT_DEFAULT_PER_DECADE;
  if (!(terms_per_decade > 0.0 && terms_per_decade <= VL_PRONY_FIT_MAX_PER_DECADE)) {
    vl_error_set(err, "terms per decade must lie in (0, %g] (got %g)", VL_PRONY_FIT_MAX_PER_DECADE,
                 terms_per_decade);
    return VL_EINPUT;
  }
  if (weights != VL_PRONY_WEIGHTS_RELATIVE && weights != VL_PRONY_WEIGHTS_MODULUS) {
    vl_error_set(err, "unknown fit weighting %d", (int)weights);
    return VL_EINPUT;
  }
  if (!(isfinite(nu) && nu >= 0.0 && nu <= 0.5)) {
    vl_error_set(err, "nu must lie in [0, 0.5] (got %g)", nu);
    return VL_EINPUT;
  }
  if (n < 2) {
    vl_error_set(err, "a Prony fit needs at least 2 points (got %zu)", n);
    return VL_EINPUT;
  }
  double wmin = INFINITY, wmax = 0.0;
  for (size_t k = 0; k < n; k++) {
    double w = omega_rad_s[k], e1 = storage_pa[k], e2 = loss_pa[k];
    if (!(isfinite(w) && w > 0.0 && isfinite(e1) && e1 > 0.0 && isfinite(e2) && e2 > 0.0)) {
      vl_error_set(err,
                   "point %zu: frequency, E' and E'' must be finite and > 0 "
                   "(got %g rad/s, %g Pa, %g Pa)",
                   k + 1, w, e1, e2);
      return VL_EINPUT;
    }
    wmin = fmin(wmin, w);
    wmax = fmax(wmax, w);
  }
  rep.n_points = n;
  rep.omega_min_rad_s = wmin;
  rep.omega_max_rad_s = wmax;
  rep.terms_per_decade = terms_per_decade;
  rep.weights = weights;
  /* A Prony series has one free shape per decade at most; less than a
   * decade of data cannot tell a relaxation from a constant. */
  if (!(wmax >= 10.0 * wmin * (1.0 - 1e-12))) {
    vl_error_set(err,
                 "the data span %.3g decades of frequency (%g to %g rad/s): a Prony fit needs "
                 "at least one decade",
                 log10(wmax / wmin), wmin, wmax);
    return VL_EINPUT;
  }
  size_t ng = vl_prony_fit_grid(wmin, wmax, terms_per_decade, NULL, 0);
  if (ng == 0 || ng > VL_PRONY_MAX_TERMS) {
    vl_error_set(err,
                 "%.3g decades at %g terms per decade need %zu terms, more than the %d a "
                 "compound may have: use fewer terms per decade",
                 log10(wmax / wmin), terms_per_decade, ng, VL_PRONY_MAX_TERMS);
    return VL_EINPUT;
  }
  vl_prony_fit_grid(wmin, wmax, terms_per_decade, tau, VL_PRONY_MAX_TERMS);
  rep.n_grid = ng;
  if (n < ng + 1) {
    vl_error_set(err,
                 "%zu points cannot determine %zu Prony terms and Einf over %.3g decades: "
                 "give more points or fewer terms per decade",
                 n, ng, log10(wmax / wmin));
    return VL_EINPUT;
  }

  size_t rows = 2 * n, cols = ng + 1;
  a = malloc(rows * cols * sizeof *a);
  b = malloc(rows * sizeof *b);
  x = malloc(cols * sizeof *x);
  if (!a || !b || !x) {
    vl_error_set(err, "out of memory fitting %zu points", n);
    st = VL_ENOMEM;
    goto cleanup;
  }
  for (size_t k = 0; k < n; k++) {
    double w = omega_rad_s[k], e1 = storage_pa[k], e2 = loss_pa[k];
    double m2 = e1 * e1 + e2 * e2;
    double j1 = e1 / m2, j2 = e2 / m2; /* J = 1/E = J' - i J'' */
    double wt = sqrt(m2);              /* 1/|J| */
    int rel = weights == VL_PRONY_WEIGHTS_RELATIVE;
    double wt1 = rel ? 1.0 / j1 : wt, wt2 = rel ? 1.0 / j2 : wt;
    double *r1 = a + (2 * k) * cols, *r2 = a + (2 * k + 1) * cols;
    r1[0] = wt1;
    r2[0] = 0.0;
    for (size_t i = 0; i < ng; i++) {
      double wtau = w * tau[i], d = 1.0 / (1.0 + wtau * wtau);
      r1[i + 1] = wt1 * d;
      r2[i + 1] = wt2 * wtau * d;
    }
    b[2 * k] = wt1 * j1;
    b[2 * k + 1] = wt2 * j2;
  }
  if ((st = vl_nnls_solve(rows, cols, a, b, x, NULL, err)) != VL_OK) {
    vl_error_prefix(err, "Prony fit");
    goto cleanup;
  }
  double c0 = x[0], cmax = 0.0;
  for (size_t i = 0; i < ng; i++)
    cmax = fmax(cmax, x[i + 1]);
  if (!(c0 > 0.0)) {
    vl_error_set(err,
                 "the fit finds no glassy compliance: the data (up to %g rad/s) never level "
                 "off at high frequency, so Einf is undetermined; extend the measurement to "
                 "higher frequencies (or lower temperatures)",
                 wmax);
    st = VL_EINPUT;
    goto cleanup;
  }
  vl_prony p;
  memset(&p, 0, sizeof p);
  p.e_inf_pa = 1.0 / c0;
  p.nu = nu;
  for (size_t i = 0; i < ng; i++) {
    if (!(x[i + 1] > DROP_REL * cmax)) continue;
    p.A[p.n_terms] = x[i + 1] / c0;
    p.tau_s[p.n_terms] = tau[i];
    p.n_terms++;
  }
  if ((st = vl_prony_validate(&p, err)) != VL_OK) {
    vl_error_prefix(err, "Prony fit produced an invalid series (Einf %g Pa)", p.e_inf_pa);
    st = VL_EINPUT;
    goto cleanup;
  }
  rep.n_terms = p.n_terms;
  double s1 = 0.0, s2 = 0.0;
  for (size_t k = 0; k < n; k++) {
    double complex e = vl_prony_modulus(&p, omega_rad_s[k]);
    double r1 = (creal(e) - storage_pa[k]) / storage_pa[k];
    double r2 = (cimag(e) - loss_pa[k]) / loss_pa[k];
    s1 += r1 * r1;
    s2 += r2 * r2;
    if (fabs(r1) > rep.max_rel_storage) rep.max_rel_storage = fabs(r1), rep.max_storage_index = k;
    if (fabs(r2) > rep.max_rel_loss) rep.max_rel_loss = fabs(r2), rep.max_loss_index = k;
  }
  rep.rms_rel_storage = sqrt(s1 / (double)n);
  rep.rms_rel_loss = sqrt(s2 / (double)n);
  rep.rms_rel = sqrt((s1 + s2) / (2.0 * (double)n));
  *out = p;
  if (report) *report = rep;

cleanup:
  free(a);
  free(b);
  free(x);
  return st;
}
