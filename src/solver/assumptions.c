/* Checks of the model's assumptions for one operating point (assumptions.h). */
#include "viscolube/assumptions.h"
#include "assumptions_internal.h"
#include "persson_internal.h"
#include "rheology_internal.h"
#include "viscolube/persson.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI /* strict C17 <math.h> does not define it */
#define M_PI 3.14159265358979323846
#endif

/* Thresholds (assumptions.h says why each). */
#define SLOPE_MAX 1.0
#define HOMOGENISATION_WAVELENGTHS 5.0 /* a_H >= 5 lambda0 */
#define PERSSON_TABLE_MIN_HRMS 1e-3    /* roughness.h: the table's bottom */
#define PRONY_MARGIN 10.0              /* one decade beyond the tau_i */
#define GRID_MIN_CELLS 8.0
#define HALF_SPACE_MAX 0.2 /* half-width / R */
#define CONTINUUM_MIN_M 1e-9
#define THIN_FILM_MAX 0.1       /* u / half-width */
#define FLUID_DENSITY 1000.0    /* kg/m^3 */
#define INERTIA_MAX 1.0         /* reduced Reynolds number */
#define FLUID_MATTERS 0.05      /* fluid load fraction */
#define SMOOTH_FACTORS_HRMS 3.0 /* u_min / h_rms */
#define PATIR_CHENG_HRMS 0.7    /* u/sigma at h/sigma = 0.5 (0.698) */

/* Appends w to warnings unless it is already there or does not fit whole. */
static void append(char *warnings, size_t cap, const char *w) {
  if (!warnings || cap == 0) return;
  size_t len = strnlen(warnings, cap);
  if (len == cap) return; /* not terminated: leave it alone */
  /* already present as a whole item? */
  size_t wl = strlen(w);
  for (const char *s = warnings; (s = strstr(s, w)) != NULL; s += wl) {
    bool starts = s == warnings || s[-1] == ';';
    bool ends = s[wl] == '\0' || s[wl] == ';';
    if (starts && ends) return;
  }
  size_t need = wl + (len ? 1 : 0);
  if (len + need + 1 > cap) return;
  if (len) warnings[len++] = ';';
  memcpy(warnings + len, w, wl + 1);
}

/* v for a message that compares it with limit ("contact half-width
 * 0.2004 R > 0.2 R", not "0.2 R > 0.2 R"): the fewest significant digits,
 * 2 to 6, that do not print it as limit prints ("%g"). Returns buf. */
static const char *beside(char *buf, size_t size, double v, double limit) {
  char lim[32];
  snprintf(lim, sizeof lim, "%g", limit);
  for (int digits = 2; digits <= 6; digits++) {
    snprintf(buf, size, "%.*g", digits, v);
    if (strcmp(buf, lim)) break;
  }
  return buf;
}

/* The span of the relaxation times that carry strength (A_i > 0). */
void vl_warnings_append(char *warnings, size_t cap, const char *w) { append(warnings, cap, w); }

static int prony_span(const vl_prony *r, double *tau_min, double *tau_max) {
  int k = 0;
  *tau_min = INFINITY, *tau_max = 0.0;
  for (size_t i = 0; i < r->n_terms; i++) {
    if (!(r->A[i] > 0.0)) continue;
    *tau_min = fmin(*tau_min, r->tau_s[i]);
    *tau_max = fmax(*tau_max, r->tau_s[i]);
    k++;
  }
  return k;
}

unsigned vl_assumptions_check(const vl_contact_config *cfg, const vl_psd *psd, const vl_point *pt,
                              char *warnings, size_t cap) {
  unsigned mask = 0;
  char w[160], v[32];
  double hrms = psd ? vl_psd_hrms(psd) : cfg->roughness ? vl_persson_hrms(cfg->roughness) : 0.0;
  bool rough = cfg->roughness != NULL || psd != NULL;
  bool wet = cfg->eta_pa_s > 0.0;
  double v0 = pt->v0_m_s;

  if (rough) {
    double slope = psd ? vl_psd_rms_slope(psd) : sqrt(8.0 * vl_persson_g(cfg->roughness));
    if (slope > SLOPE_MAX) {
      mask |= VL_ASSUME_RMS_SLOPE;
      snprintf(w, sizeof w, "rms slope %s > 1 (small-slope contact theory)",
               beside(v, sizeof v, slope, SLOPE_MAX));
      append(warnings, cap, w);
    }
  }
  /* a_H from the configuration and speed, so that it is known also for a
   * point that did not converge */
  double e_h = 0.0, a_h = 0.0, omega_h = 0.0;
  vl_asperity_state(&cfg->rubber, cfg->load_n_per_m, cfg->radius_m, v0 >= 0.0 ? v0 : 0.0, &e_h,
                    &a_h, &omega_h);
  if (psd && psd->q0 > 0.0) {
    double lambda0 = 2.0 * M_PI / psd->q0;
    if (a_h < HOMOGENISATION_WAVELENGTHS * lambda0) {
      mask |= VL_ASSUME_HOMOGENISATION;
      snprintf(w, sizeof w, "a_H = %s lambda0 < 5 (contact too small for mean-field roughness)",
               beside(v, sizeof v, a_h / lambda0, HOMOGENISATION_WAVELENGTHS));
      append(warnings, cap, w);
    }
  }
  double tau_min, tau_max;
  if (v0 > 0.0 && prony_span(&cfg->rubber, &tau_min, &tau_max) >= 2 && omega_h > 0.0) {
    if (omega_h * tau_max < 1.0 / PRONY_MARGIN || omega_h * tau_min > PRONY_MARGIN) {
      mask |= VL_ASSUME_PRONY_WINDOW;
      char lo[16], hi[16];
      snprintf(lo, sizeof lo, "%.2g", 1.0 / (PRONY_MARGIN * tau_max));
      snprintf(hi, sizeof hi, "%.2g", PRONY_MARGIN / tau_min);
      /* wH to the digits that set it apart from the end it passed, as shown */
      double edge = strtod(omega_h * tau_max < 1.0 / PRONY_MARGIN ? lo : hi, NULL);
      snprintf(w, sizeof w,
               "wH = %s rad/s outside the Prony window %s..%s rad/s (plateau extrapolated)",
               beside(v, sizeof v, omega_h, edge), lo, hi);
      append(warnings, cap, w);
    }
  }
  if (!pt->converged) return mask;

  /* the grid: cell size from the relaxed Hertz half-width a0 */
  double er0 = vl_prony_e0(&cfg->rubber) * vl_prony_reduced_factor(&cfg->rubber);
  double a0 = sqrt(4.0 * cfg->load_n_per_m * cfg->radius_m / (M_PI * er0));
  double dx = (cfg->x_max_a0 - cfg->x_min_a0) * a0 / (double)(cfg->grid ? cfg->grid : 1);
  double width = pt->contact_width_m, half = 0.5 * width;
  if (width < GRID_MIN_CELLS * dx) {
    mask |= VL_ASSUME_GRID;
    snprintf(w, sizeof w, "contact spans %s cells < 8 (refine the grid)",
             beside(v, sizeof v, width / dx, GRID_MIN_CELLS));
    append(warnings, cap, w);
  }
  /* a lip's, a table's or a static pressure's radius_m only sets the scales: its small slopes
   * are checked on the profile itself (the solver's profile slope warning) */
  bool profile = cfg->profile_x_m || cfg->lip_tip_radius_m > 0.0 || cfg->static_x_m;
  if (!profile && half > HALF_SPACE_MAX * cfg->radius_m) {
    mask |= VL_ASSUME_HALF_SPACE;
    snprintf(w, sizeof w, "contact half-width %s R > 0.2 R (parabolic gap and small strain)",
             beside(v, sizeof v, half / cfg->radius_m, HALF_SPACE_MAX));
    append(warnings, cap, w);
  }
  if (rough && hrms > 0.0 && pt->u_min_m < PERSSON_TABLE_MIN_HRMS * hrms) {
    mask |= VL_ASSUME_PERSSON_TABLE;
    snprintf(w, sizeof w, "u_min = %s h_rms below the Persson table (1e-3 h_rms)",
             beside(v, sizeof v, pt->u_min_m / hrms, PERSSON_TABLE_MIN_HRMS));
    append(warnings, cap, w);
  }
  if (!wet) return mask;

  if (pt->u_min_m < CONTINUUM_MIN_M) {
    mask |= VL_ASSUME_CONTINUUM_FILM;
    snprintf(w, sizeof w, "u_min = %s m < 1 nm (continuum Newtonian film)",
             beside(v, sizeof v, pt->u_min_m, CONTINUUM_MIN_M));
    append(warnings, cap, w);
  }
  double len = half > 0.0 ? half : a_h;
  double u = pt->u_central_m;
  if (len > 0.0 && u > THIN_FILM_MAX * len) {
    mask |= VL_ASSUME_THIN_FILM;
    snprintf(w, sizeof w, "film %s x the contact half-width (Reynolds thin-film equation)",
             beside(v, sizeof v, u / len, THIN_FILM_MAX));
    append(warnings, cap, w);
  }
  double re = len > 0.0 ? FLUID_DENSITY * v0 * u * u / (cfg->eta_pa_s * len) : 0.0;
  if (re > INERTIA_MAX) {
    mask |= VL_ASSUME_INERTIA;
    snprintf(w, sizeof w, "reduced Reynolds number %s > 1 at 1000 kg/m^3 (fluid inertia)",
             beside(v, sizeof v, re, INERTIA_MAX));
    append(warnings, cap, w);
  }
  /* persson-emt is defined at every separation, down to the contact's own
   * percolation (its limits are those of the mean-field contact law) */
  if (rough && hrms > 0.0 && pt->fluid_load_fraction > FLUID_MATTERS &&
      cfg->flow_factors != VL_FLOW_FACTORS_PERSSON_EMT) {
    bool smooth = cfg->flow_factors == VL_FLOW_FACTORS_SMOOTH;
    double lim = smooth ? SMOOTH_FACTORS_HRMS : PATIR_CHENG_HRMS;
    if (pt->u_min_m < lim * hrms) {
      mask |= VL_ASSUME_FLOW_FACTORS;
      snprintf(w, sizeof w, "u_min = %s h_rms %s", beside(v, sizeof v, pt->u_min_m / hrms, lim),
               smooth ? "with smooth flow factors (roughness changes the flow)"
                      : "below the Patir-Cheng fits (h/sigma < 0.5)");
      append(warnings, cap, w);
    }
  }
  return mask;
}

/* One warning when w (named what) lies over VL_WINDOW_MARGIN above hi
 * (up) or below lo (!up): that side and that end, one number each (the
 * console shows the ranges of a kind's numbers over the points). */
static unsigned window_warn(const char *what, double w, bool up, double lo, double hi,
                            char *warnings, size_t cap) {
  char t[160];
  if (up && w > VL_WINDOW_MARGIN * hi)
    snprintf(t, sizeof t, "%s %.2g rad/s over a decade above the measured window (top %.2g rad/s)",
             what, w, hi);
  else if (!up && w < lo / VL_WINDOW_MARGIN)
    snprintf(t, sizeof t,
             "%s %.2g rad/s over a decade below the measured window (bottom %.2g rad/s)", what, w,
             lo);
  else
    return 0;
  append(warnings, cap, t);
  return VL_ASSUME_MEASURED_WINDOW;
}

unsigned vl_assumptions_check_window(const vl_contact_config *cfg, const vl_psd *psd,
                                     const vl_point *pt, double omega_min_rad_s,
                                     double omega_max_rad_s, char *warnings, size_t cap) {
  double v0 = pt->v0_m_s, lo = omega_min_rad_s, hi = omega_max_rad_s;
  if (!(v0 > 0.0 && lo > 0.0 && hi > lo && isfinite(hi))) return 0;
  unsigned mask = 0;
  if (psd && psd->q0 > 0.0 && psd->q1 > psd->q0) {
    /* the band's ends: were the whole band above the window, its top is;
     * were it below, its bottom is */
    mask |= window_warn("asperity frequency v0 q1", v0 * psd->q1, true, lo, hi, warnings, cap);
    mask |= window_warn("asperity frequency v0 q0", v0 * psd->q0, false, lo, hi, warnings, cap);
  }
  double a = 0.5 * pt->contact_width_m;
  if (!(pt->converged && a > 0.0)) {
    double e_h, omega_h;
    vl_asperity_state(&cfg->rubber, cfg->load_n_per_m, cfg->radius_m, v0, &e_h, &a, &omega_h);
  }
  if (a > 0.0) {
    mask |= window_warn("contact frequency v0/a", v0 / a, true, lo, hi, warnings, cap);
    mask |= window_warn("contact frequency v0/a", v0 / a, false, lo, hi, warnings, cap);
  }
  return mask;
}

const char *vl_assumption_name(unsigned bit) {
  switch (bit) {
  case VL_ASSUME_RMS_SLOPE: return "rms slope";
  case VL_ASSUME_HOMOGENISATION: return "homogenisation";
  case VL_ASSUME_PERSSON_TABLE: return "Persson table";
  case VL_ASSUME_PRONY_WINDOW: return "Prony window";
  case VL_ASSUME_GRID: return "grid";
  case VL_ASSUME_HALF_SPACE: return "half-space";
  case VL_ASSUME_CONTINUUM_FILM: return "continuum film";
  case VL_ASSUME_THIN_FILM: return "thin film";
  case VL_ASSUME_INERTIA: return "inertia";
  case VL_ASSUME_FLOW_FACTORS: return "flow factors";
  case VL_ASSUME_MEASURED_WINDOW: return "measured window";
  default: return "unknown";
  }
}
