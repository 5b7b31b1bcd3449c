/* viscolube: what a DMA import measured and how well it hangs together
 * (dma.h, "What was measured"): the ranges of the data, the join of
 * neighbouring shifted isotherms, a rise of tan delta at the top of each
 * isotherm's window (an instrument resonance), and Einf/E0 against the
 * measured moduli. Each check adds a note; each threshold exceeded a
 * "warning: " note that says where, by how much, the threshold and why. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dma_private.h"
#include "import_text.h"
#include "rheology_internal.h"

#define TWO_PI 6.283185307179586476925287
/* tan delta's trend at the top of a window: the points of the decade
 * below the highest frequency (at least 3 of them). */
#define TAN_TREND_DECADES 1.0
#define TAN_TREND_MIN_POINTS 3
/* A rise counts when it also exceeds this many times the trend's scatter. */
#define TAN_RISE_SIGMAS 4.0

static void note(vl_measured *m, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void note(vl_measured *m, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vl_import_note_v(m->notes, sizeof m->notes, fmt, ap);
  va_end(ap);
}

static void measured_ranges(vl_measured *m) {
  m->storage_min_pa = m->omega_min_rad_s = INFINITY;
  m->storage_max_pa = m->omega_max_rad_s = 0.0;
  for (size_t k = 0; k < m->n; k++) {
    m->storage_min_pa = fmin(m->storage_min_pa, m->storage_pa[k]);
    m->storage_max_pa = fmax(m->storage_max_pa, m->storage_pa[k]);
    m->omega_min_rad_s = fmin(m->omega_min_rad_s, m->omega_rad_s[k]);
    m->omega_max_rad_s = fmax(m->omega_max_rad_s, m->omega_rad_s[k]);
  }
  m->temperature_min_c = m->iso_temperature_c[0];
  m->temperature_max_c = m->iso_temperature_c[m->n_isotherms - 1];
}

/* log10 E' of the curve (x[0..n) increasing) at x0 by linear interpolation. */
static double interp(const double *x, const double *y, size_t n, double x0) {
  size_t i = 1;
  while (i + 1 < n && x[i] < x0)
    i++;
  double t = x[i] > x[i - 1] ? (x0 - x[i - 1]) / (x[i] - x[i - 1]) : 0.0;
  return y[i - 1] + t * (y[i] - y[i - 1]);
}

/* rms log10 E' difference of two shifted curves (x reduced log w) over
 * their overlap, each point of one against the other; NAN without one. */
static double join_rms(const double *xa, const double *ya, size_t na, const double *xb,
                       const double *yb, size_t nb) {
  if (na < 2 || nb < 2) return NAN;
  double lo = fmax(xa[0], xb[0]), hi = fmin(xa[na - 1], xb[nb - 1]);
  if (!(hi > lo)) return NAN;
  double s = 0.0;
  size_t c = 0;
  for (size_t i = 0; i < na; i++)
    if (xa[i] >= lo && xa[i] <= hi) {
      double d = ya[i] - interp(xb, yb, nb, xa[i]);
      s += d * d, c++;
    }
  for (size_t i = 0; i < nb; i++)
    if (xb[i] >= lo && xb[i] <= hi) {
      double d = yb[i] - interp(xa, ya, na, xb[i]);
      s += d * d, c++;
    }
  return c >= 2 ? sqrt(s / (double)c) : NAN;
}

/* Rise of log10 tan delta (y) at the top point of x[0..n) above the
 * straight line through the points of the decade below; *scatter gets the
 * line's rms residual. NAN with too few points. */
static double tan_rise(const double *x, const double *y, size_t n, double *scatter) {
  *scatter = NAN;
  if (n < TAN_TREND_MIN_POINTS + 1) return NAN;
  double top = x[n - 1], sx = 0.0, sy = 0.0;
  size_t c = 0, first = n - 1;
  while (first > 0 && x[first - 1] >= top - TAN_TREND_DECADES - 1e-9)
    first--;
  for (size_t i = first; i + 1 < n; i++)
    sx += x[i], sy += y[i], c++;
  if (c < TAN_TREND_MIN_POINTS) return NAN;
  double mx = sx / (double)c, my = sy / (double)c, sxx = 0.0, sxy = 0.0;
  for (size_t i = first; i + 1 < n; i++)
    sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my);
  if (!(sxx > 0.0)) return NAN;
  double slope = sxy / sxx, rr = 0.0;
  for (size_t i = first; i + 1 < n; i++) {
    double r = y[i] - (my + slope * (x[i] - mx));
    rr += r * r;
  }
  *scatter = c > 2 ? sqrt(rr / (double)(c - 2)) : 0.0;
  return y[n - 1] - (my + slope * (top - mx));
}

/* Departure of the shift step between isotherms g and g + 1 from the
 * step the WLF law fitted to all of them gives (decades); NAN without WLF. */
static double step_departure(const vl_measured *m, size_t g) {
  if (isnan(m->wlf_c1) || !(m->wlf_rms <= VL_DMA_WARN_WLF_RMS)) return NAN;
  const double *t = m->iso_temperature_c, *lat = m->iso_log10_a_t;
  double wlf = vl_wlf_log10_shift(m->wlf_c1, m->wlf_c2_k, t[g + 1], m->tref_c) -
               vl_wlf_log10_shift(m->wlf_c1, m->wlf_c2_k, t[g], m->tref_c);
  return (lat[g + 1] - lat[g]) - wlf;
}

/* The join of each neighbouring pair: a warning for an overlap misfit
 * above VL_DMA_WARN_JOIN_RMS or a step off the WLF law by more than
 * VL_DMA_WARN_JOIN_STEP, a note with the worst pair otherwise. */
static void join_notes(vl_measured *m, const size_t *start, const double *xr, const double *ls) {
  size_t ni = m->n_isotherms, worst = 0, wstep = 0, bad = 0;
  double wr = -1.0, ws = -1.0;
  for (size_t g = 0; g + 1 < ni; g++) {
    size_t a = start[g], b = start[g + 1];
    double r = join_rms(xr + a, ls + a, b - a, xr + b, ls + b, start[g + 2] - b);
    double d = step_departure(m, g);
    const double *t = m->iso_temperature_c;
    m->iso_join_rms[g] = r;
    m->iso_join_step[g] = d;
    if (!isnan(r) && r > wr) wr = r, worst = g;
    if (!isnan(d) && fabs(d) > ws) ws = fabs(d), wstep = g;
    if (r > VL_DMA_WARN_JOIN_RMS) {
      bad++;
      note(m,
           "warning: the isotherms at %.4g and %.4g C do not join: shifted onto each other "
           "their E' differ by %.3f decades rms (%.1f %%) where they overlap, above %.2g (a "
           "DMA's scatter is about 0.004): two runs or a specimen that changed between them? "
           "The master curve steps there and the fit averages across the step",
           t[g], t[g + 1], r, 100.0 * (pow(10.0, r) - 1.0), VL_DMA_WARN_JOIN_RMS);
      m->n_warnings++;
    }
    if (fabs(d) > VL_DMA_WARN_JOIN_STEP) {
      bad++;
      note(m,
           "warning: the isotherms at %.4g and %.4g C do not join smoothly: the shift between "
           "them (%.2f decades) is %.2f decades off the WLF law fitted to all isotherms "
           "(%.2f; warned above %.2g): two runs, or moduli offset between them, that the "
           "horizontal shift absorbed? Friction there follows the WLF law, not that shift",
           t[g], t[g + 1], m->iso_log10_a_t[g + 1] - m->iso_log10_a_t[g], fabs(d),
           m->iso_log10_a_t[g + 1] - m->iso_log10_a_t[g] - d, VL_DMA_WARN_JOIN_STEP);
      m->n_warnings++;
    }
  }
  if (bad || wr < 0.0) return;
  if (ws >= 0.0)
    note(m,
         "the shifted isotherms join within %.3f decades rms in E' (worst: %.4g and %.4g C) and "
         "their shift steps follow the WLF law within %.2f decades (worst: %.4g and %.4g C); "
         "warned above %.2g and %.2g",
         wr, m->iso_temperature_c[worst], m->iso_temperature_c[worst + 1], ws,
         m->iso_temperature_c[wstep], m->iso_temperature_c[wstep + 1], VL_DMA_WARN_JOIN_RMS,
         VL_DMA_WARN_JOIN_STEP);
  else
    note(m,
         "the shifted isotherms join within %.3f decades rms in E' (worst: %.4g and %.4g C; "
         "warned above %.2g)",
         wr, m->iso_temperature_c[worst], m->iso_temperature_c[worst + 1], VL_DMA_WARN_JOIN_RMS);
}

/* The tan delta rise at the top of each isotherm, one warning listing
 * those above the thresholds. */
static void tan_notes(vl_measured *m, const size_t *start, const double *xw, const double *lt) {
  char list[768] = "";
  size_t bad = 0, len = 0;
  double f_hz = 0.0;
  for (size_t g = 0; g < m->n_isotherms; g++) {
    size_t a = start[g], n = start[g + 1] - a;
    double sc, r = tan_rise(xw + a, lt + a, n, &sc);
    m->iso_tan_delta_rise[g] = r;
    if (!(r > VL_DMA_WARN_TAN_RISE && r > TAN_RISE_SIGMAS * sc)) continue;
    f_hz = fmax(f_hz, pow(10.0, xw[a + n - 1]) / TWO_PI);
    if (len < sizeof list)
      len += (size_t)snprintf(list + len, sizeof list - len, "%s%.4g C (+%.0f %% at %.4g Hz)",
                              bad ? ", " : "", m->iso_temperature_c[g],
                              100.0 * (pow(10.0, r) - 1.0), pow(10.0, xw[a + n - 1]) / TWO_PI);
    bad++;
  }
  if (!bad) return;
  note(m,
       "warning: tan delta rises at the top of the frequency window (up to %.4g Hz) above the "
       "trend of the decade below, by more than %.0f %% and 4 times that trend's scatter, in "
       "%zu of %zu isotherms: %s. An instrument resonance near the top of its range? Those "
       "points are fitted as measured: leave them out of the file if they are an artefact",
       f_hz, 100.0 * (pow(10.0, VL_DMA_WARN_TAN_RISE) - 1.0), bad, m->n_isotherms, list);
  m->n_warnings++;
}

/* Einf and E0 of the series against the measured E'. */
static void extrapolation_notes(vl_measured *m) {
  double einf = m->prony.e_inf_pa, e0 = vl_prony_e0(&m->prony);
  if (einf > VL_DMA_WARN_EXTRAPOLATION * m->storage_max_pa) {
    note(m,
         "warning: the fitted Einf %.3g Pa is %.1f times the largest measured E' (%.3g Pa; "
         "warned above %.0f times): the glassy limit is extrapolated, set by the fit's tail and "
         "not by data, and so is friction at frequencies above the master curve's top (%.3g "
         "rad/s at %.4g C)",
         einf, einf / m->storage_max_pa, m->storage_max_pa, VL_DMA_WARN_EXTRAPOLATION,
         m->fit.omega_max_rad_s, m->tref_c);
    m->n_warnings++;
  }
  if (e0 * VL_DMA_WARN_EXTRAPOLATION < m->storage_min_pa) {
    note(m,
         "warning: the fitted E0 %.3g Pa is %.1f times below the smallest measured E' (%.3g "
         "Pa; warned beyond %.0f times): the rubbery limit is extrapolated, set by the fit's "
         "tail and not by data, and so is friction at frequencies below the master curve's "
         "bottom (%.3g rad/s at %.4g C)",
         e0, m->storage_min_pa / e0, m->storage_min_pa, VL_DMA_WARN_EXTRAPOLATION,
         m->fit.omega_min_rad_s, m->tref_c);
    m->n_warnings++;
  }
}

vl_status vl_dma_quality(vl_measured *m, const vl_dma_order *ord, vl_error *err) {
  vl_status st = VL_OK;
  size_t n = m->n, ni = m->n_isotherms;
  size_t *start = calloc(ni + 2, sizeof *start);
  double *xr = malloc(n * sizeof *xr), *xw = malloc(n * sizeof *xw);
  double *ls = malloc(n * sizeof *ls), *lt = malloc(n * sizeof *lt);
  m->iso_join_rms = ni > 1 ? malloc((ni - 1) * sizeof *m->iso_join_rms) : NULL;
  m->iso_join_step = ni > 1 ? malloc((ni - 1) * sizeof *m->iso_join_step) : NULL;
  m->iso_tan_delta_rise = malloc(ni * sizeof *m->iso_tan_delta_rise);
  if (!start || !xr || !xw || !ls || !lt || (ni > 1 && (!m->iso_join_rms || !m->iso_join_step)) ||
      !m->iso_tan_delta_rise) {
    vl_error_set(err, "%s: out of memory", m->source);
    st = VL_ENOMEM;
    goto cleanup;
  }
  for (size_t i = 0; i < n; i++) {
    size_t k = ord[i].idx;
    xr[i] = log10(m->reduced_omega_rad_s[k]);
    xw[i] = log10(m->omega_rad_s[k]);
    ls[i] = log10(m->storage_pa[k]);
    lt[i] = log10(m->loss_pa[k] / m->storage_pa[k]);
    start[ord[i].iso + 1]++;
  }
  for (size_t g = 0; g < ni; g++)
    start[g + 1] += start[g];
  start[ni + 1] = start[ni];
  measured_ranges(m);
  if (m->has_temperature)
    note(m, "measured: E' %.3g to %.3g Pa, %.4g to %.4g Hz, %.4g to %.4g C (%zu isotherm%s)",
         m->storage_min_pa, m->storage_max_pa, m->omega_min_rad_s / TWO_PI,
         m->omega_max_rad_s / TWO_PI, m->temperature_min_c, m->temperature_max_c, ni,
         ni == 1 ? "" : "s");
  else
    note(m, "measured: E' %.3g to %.3g Pa, %.4g to %.4g Hz (a master curve at %.4g C)",
         m->storage_min_pa, m->storage_max_pa, m->omega_min_rad_s / TWO_PI,
         m->omega_max_rad_s / TWO_PI, m->tref_c);
  if (ni > 1) join_notes(m, start, xr, ls);
  tan_notes(m, start, xw, lt);
  extrapolation_notes(m);

cleanup:
  free(start);
  free(xr);
  free(xw);
  free(ls);
  free(lt);
  return st;
}
