/* Creep-form Prony fit by weighted non-negative least squares (prony_fit.h). */
#include "viscolube/prony_fit.h"
#include "prony_fit_internal.h"

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

/* The options and data of vl_prony_fit (terms_per_decade already
 * defaulted): VL_EINPUT unless every point is finite and positive; *wmin
 * and *wmax get the frequency range. */
static vl_status check_fit_input(size_t n, const double *omega_rad_s, const double *storage_pa,
                                 const double *loss_pa, double terms_per_decade,
                                 vl_prony_weights weights, double nu, double *wmin, double *wmax,
                                 vl_error *err) {
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
  *wmin = INFINITY;
  *wmax = 0.0;
  for (size_t k = 0; k < n; k++) {
    double w = omega_rad_s[k], e1 = storage_pa[k], e2 = loss_pa[k];
    if (!(isfinite(w) && w > 0.0 && isfinite(e1) && e1 > 0.0 && isfinite(e2) && e2 > 0.0)) {
      vl_error_set(err,
                   "point %zu: frequency, E' and E'' must be finite and > 0 "
                   "(got %g rad/s, %g Pa, %g Pa)",
                   k + 1, w, e1, e2);
      return VL_EINPUT;
    }
    *wmin = fmin(*wmin, w);
    *wmax = fmax(*wmax, w);
  }
  return VL_OK;
}

/* The relaxation times tau[0..*ng) for n points spanning wmin..wmax:
 * VL_EINPUT if the data span less than a decade, if the grid needs more
 * than VL_PRONY_MAX_TERMS terms, or if the points cannot determine them. */
static vl_status fit_grid(size_t n, double wmin, double wmax, double terms_per_decade, double *tau,
                          size_t *ng, vl_error *err) {
  /* A Prony series has one free shape per decade at most; less than a
   * decade of data cannot tell a relaxation from a constant. */
  if (!(wmax >= 10.0 * wmin * (1.0 - 1e-12))) {
    vl_error_set(err,
                 "the data span %.3g decades of frequency (%g to %g rad/s): a Prony fit needs "
                 "at least one decade",
                 log10(wmax / wmin), wmin, wmax);
    return VL_EINPUT;
  }
  *ng = vl_prony_fit_grid(wmin, wmax, terms_per_decade, NULL, 0);
  if (*ng == 0 || *ng > VL_PRONY_MAX_TERMS) {
    vl_error_set(err,
                 "%.3g decades at %g terms per decade need %zu terms, more than the %d a "
                 "compound may have: use fewer terms per decade",
                 log10(wmax / wmin), terms_per_decade, *ng, VL_PRONY_MAX_TERMS);
    return VL_EINPUT;
  }
  vl_prony_fit_grid(wmin, wmax, terms_per_decade, tau, VL_PRONY_MAX_TERMS);
  if (n < *ng + 1) {
    vl_error_set(err,
                 "%zu points cannot determine %zu Prony terms and Einf over %.3g decades: "
                 "give more points or fewer terms per decade",
                 n, *ng, log10(wmax / wmin));
    return VL_EINPUT;
  }
  return VL_OK;
}

/* The weighted least-squares system of the creep form: for point k, rows
 * 2k (J') and 2k+1 (J'') of a (2n x (ng+1), row-major) and b; column 0 is
 * the glassy compliance c0, column i+1 the term of tau[i]. */
static void fill_system(size_t n, const double *omega_rad_s, const double *storage_pa,
                        const double *loss_pa, vl_prony_weights weights, const double *tau,
                        size_t ng, double *a, double *b) {
  size_t cols = ng + 1;
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
}

/* The Prony series of the NNLS solution x (c0, then one coefficient per
 * tau): Einf = 1/c0, A_i = c_i/c0, terms below DROP_REL of the largest
 * dropped. VL_EINPUT if c0 is not positive (wmax, the highest frequency,
 * goes in the message) or the series is invalid. */
static vl_status series_from_solution(const double *x, const double *tau, size_t ng, double nu,
                                      double wmax, vl_prony *p, vl_error *err) {
  double c0 = x[0], cmax = 0.0;
  for (size_t i = 0; i < ng; i++)
    cmax = fmax(cmax, x[i + 1]);
  if (!(c0 > 0.0)) {
    vl_error_set(err,
                 "the fit finds no glassy compliance: the data (up to %g rad/s) never level "
                 "off at high frequency, so Einf is undetermined; extend the measurement to "
                 "higher frequencies (or lower temperatures)",
                 wmax);
    return VL_EINPUT;
  }
  memset(p, 0, sizeof *p);
  p->e_inf_pa = 1.0 / c0;
  p->nu = nu;
  for (size_t i = 0; i < ng; i++) {
    if (!(x[i + 1] > DROP_REL * cmax)) continue;
    p->A[p->n_terms] = x[i + 1] / c0;
    p->tau_s[p->n_terms] = tau[i];
    p->n_terms++;
  }
  if (vl_prony_validate(p, err) != VL_OK) {
    vl_error_prefix(err, "Prony fit produced an invalid series (Einf %g Pa)", p->e_inf_pa);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* The relative misfit of p at the n points into rep (rms and largest, of
 * E' and E'' apart and together). */
static void fit_misfit(const vl_prony *p, size_t n, const double *omega_rad_s,
                       const double *storage_pa, const double *loss_pa, vl_prony_fit_report *rep) {
  double s1 = 0.0, s2 = 0.0;
  for (size_t k = 0; k < n; k++) {
    double complex e = vl_prony_modulus(p, omega_rad_s[k]);
    double r1 = (creal(e) - storage_pa[k]) / storage_pa[k];
    double r2 = (cimag(e) - loss_pa[k]) / loss_pa[k];
    s1 += r1 * r1;
    s2 += r2 * r2;
    if (fabs(r1) > rep->max_rel_storage)
      rep->max_rel_storage = fabs(r1), rep->max_storage_index = k;
    if (fabs(r2) > rep->max_rel_loss) rep->max_rel_loss = fabs(r2), rep->max_loss_index = k;
  }
  rep->rms_rel_storage = sqrt(s1 / (double)n);
  rep->rms_rel_loss = sqrt(s2 / (double)n);
  rep->rms_rel = sqrt((s1 + s2) / (2.0 * (double)n));
}

vl_status vl_prony_fit(size_t n, const double *omega_rad_s, const double *storage_pa,
                       const double *loss_pa, double terms_per_decade, vl_prony_weights weights,
                       double nu, vl_prony *out, vl_prony_fit_report *report, vl_error *err) {
  vl_status st = VL_OK;
  double *a = NULL, *b = NULL, *x = NULL;
  double tau[VL_PRONY_MAX_TERMS], wmin, wmax;
  size_t ng;
  vl_prony_fit_report rep;
  memset(&rep, 0, sizeof rep);
  if (terms_per_decade == 0.0) terms_per_decade = VL_PRONY_FIT_DEFAULT_PER_DECADE;
  st = check_fit_input(n, omega_rad_s, storage_pa, loss_pa, terms_per_decade, weights, nu, &wmin,
                       &wmax, err);
  if (st != VL_OK) return st;
  rep.n_points = n;
  rep.omega_min_rad_s = wmin;
  rep.omega_max_rad_s = wmax;
  rep.terms_per_decade = terms_per_decade;
  rep.weights = weights;
  if ((st = fit_grid(n, wmin, wmax, terms_per_decade, tau, &ng, err)) != VL_OK) return st;
  rep.n_grid = ng;

  size_t rows = 2 * n, cols = ng + 1;
  a = malloc(rows * cols * sizeof *a);
  b = malloc(rows * sizeof *b);
  x = malloc(cols * sizeof *x);
  if (!a || !b || !x) {
    vl_error_set(err, "out of memory fitting %zu points", n);
    st = VL_ENOMEM;
    goto cleanup;
  }
  fill_system(n, omega_rad_s, storage_pa, loss_pa, weights, tau, ng, a, b);
  if ((st = vl_nnls_solve(rows, cols, a, b, x, NULL, err)) != VL_OK) {
    vl_error_prefix(err, "Prony fit");
    goto cleanup;
  }
  vl_prony p;
  if ((st = series_from_solution(x, tau, ng, nu, wmax, &p, err)) != VL_OK) goto cleanup;
  rep.n_terms = p.n_terms;
  fit_misfit(&p, n, omega_rad_s, storage_pa, loss_pa, &rep);
  *out = p;
  if (report) *report = rep;

cleanup:
  free(a);
  free(b);
  free(x);
  return st;
}
