/* Results of a converged state (docs/MODEL.md sections 7 and 8): the friction
 * integrals mu_Rc, mu_Rf (the pressures against the slope of the gap),
 * mu_Sc (sigma_s over the real contact area) and mu_Sf (the film's shear,
 * Couette weighted by the film fraction theta in the cavitated zone, and
 * Poiseuille), the derived quantities of a point (films, centroid, contact
 * width, fluid load share, regime, warnings), and the fields on the grid. */
#include "contact_internal.h"
#include "contact_private.h"
#include "flow_factors_internal.h"
#include "numerics_plan.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

const char *vl_accuracy_name(int accuracy) {
  switch (accuracy) {
  case VL_ACCURACY_UNCHECKED: return "";
  case VL_ACCURACY_MET: return "met";
  case VL_ACCURACY_ABOVE_TARGET: return "above_target";
  case VL_ACCURACY_NO_ESTIMATE: return "no_estimate";
  }
  return "?";
}

bool vl_point_unreliable(const vl_point *pt) {
  return pt->converged &&
         (pt->accuracy == VL_ACCURACY_ABOVE_TARGET || pt->accuracy == VL_ACCURACY_NO_ESTIMATE);
}

const char *vl_regime_name(int regime) {
  switch (regime) {
  case VL_REGIME_DRY: return "dry";
  case VL_REGIME_BOUNDARY: return "boundary";
  case VL_REGIME_MIXED: return "mixed";
  case VL_REGIME_HYDRODYNAMIC: return "hydrodynamic";
  }
  return "?";
}

int vl_regime_of(int wet, double fluid_load_fraction, double u_min_over_h_rms) {
  if (!wet) return VL_REGIME_DRY;
  int smooth = isnan(u_min_over_h_rms);
  if (fluid_load_fraction > VL_REGIME_LOAD_HYDRODYNAMIC &&
      (smooth || u_min_over_h_rms >= VL_REGIME_FILM_FULL))
    return VL_REGIME_HYDRODYNAMIC;
  if (fluid_load_fraction < VL_REGIME_LOAD_BOUNDARY &&
      (smooth || u_min_over_h_rms < VL_REGIME_FILM_FULL))
    return VL_REGIME_BOUNDARY;
  return VL_REGIME_MIXED;
}

static void add_warning(vl_point *pt, const char *w) {
  size_t len = strlen(pt->warnings);
  snprintf(pt->warnings + len, sizeof pt->warnings - len, "%s%s", len ? ";" : "", w);
}

/* Film fraction theta per node (1 in the full film): downstream of film
 * rupture the flux stays that of the last full-film face while the
 * full-film Couette flux grows, so the gap is only partly filled (mass
 * conservation). Needs vl_contact_eval_state. */
static void film_fraction(const vl_contact *c, const double *y, double *theta) {
  size_t n = c->n;
  double jcur = c->Jf[0];
  for (size_t i = 0; i < n; i++) {
    bool cavitated =
        c->wet && y[c->of + i] <= 1e-12 && vl_contact_reynolds_residual(c, i) > c->cfg.tolerance;
    if (!cavitated) {
      theta[i] = 1.0;
      jcur = c->Jf[i + 1];
    } else {
      theta[i] = c->cf[i] > 0.0 ? fmin(1.0, fmax(jcur, 0.0) / c->cf[i]) : 1.0;
    }
  }
}

/* Real contact area ratio of node i (needs vl_contact_eval_state). Rough: Persson's
 * A/A0 at pc/|Er|; flattened (flat_scale) at pc/(|Er| s), the unflattened
 * surface's area at separation u/s (0 where s = 0: no contact pressure). */
static double area_at(const vl_contact *c, size_t i) {
  if (!c->rough) return c->P[i] > 1e-9 ? 1.0 : 0.0;
  double s = c->sf ? c->sf[i] : 1.0;
  return s > 0.0 ? vl_persson_area_ratio(c->cfg.roughness, c->P[i] / (c->sfac * s), NULL) : 0.0;
}

/* Fills the derived quantities of pt from the current state. */
void vl_contact_report(vl_contact *c, vl_point *pt) {
  size_t n = c->n;
  const double *y = N_VGetArrayPointer(c->y);
  vl_contact_eval_state(c, y);
  const vl_contact_config *cfg = &c->cfg;
  double fN = cfg->load_n_per_m, R = cfg->radius_m;
  double sum_pcx = 0.0, sum_pfx = 0.0, sum_pf = 0.0, sum_area = 0.0;
  double sum_pcs = 0.0, sum_pfs = 0.0; /* a tabulated profile: the pressures against f' */
  double pmax = 0.0, pfmax = 0.0, umin = INFINITY, couette = 0.0, poiseuille = 0.0;
  size_t imax = 0, iumin = 0, ipf = 0;
  bool counterface = cfg->moving == VL_MOVING_COUNTERFACE;
  double *theta = c->theta;
  if (c->wet) film_fraction(c, y, theta);
  pt->eps_f_min = c->sf ? INFINITY : 1.0;
  if (c->sf)
    for (size_t i = 0; i < n; i++)
      pt->eps_f_min = fmin(pt->eps_f_min, c->sf[i] * c->sf[i]);
  double pin, pout; /* beyond the ends: a sealed side's pressure, else 0 (kappa p0) */
  vl_contact_end_pressures(c, &pin, &pout);
  pin *= c->kappa, pout *= c->kappa;
  for (size_t i = 0; i < n; i++) {
    /* pf above a sealed side's ambient: what the rubber and the load see */
    double amb = c->pamb ? c->pamb[i] : 0.0;
    double pc = c->P[i] * c->p0, pf = (c->F[i] - amb) * c->p0, x = c->xi[i] * c->a0;
    double dx = c->wc[i] * c->a0;
    sum_pcx += pc * x * dx;
    sum_pfx += pf * x * dx;
    if (c->sprof) sum_pcs += pc * c->sprof[i] * dx, sum_pfs += pf * c->sprof[i] * dx;
    sum_pf += pf * dx;
    double area = area_at(c, i);
    sum_area += area * dx;
    if (pc + pf > pmax) pmax = pc + pf, imax = i;
    if (pf > pfmax) pfmax = pf, ipf = i;
    if (c->U[i] < umin) umin = c->U[i], iumin = i;
    if (c->wet) {
      double u = fmax(c->U[i], 0.0) * c->uscale;
      vl_flow_factor_values v;
      /* flattened: the factors of h_rms s (as in vl_contact_eval_state) */
      vl_flow_factors_eval_table(cfg->flow_factors, cfg->flow_table, u,
                                 c->sf ? c->hrms * c->sf[i] : c->hrms, &v, NULL);
      /* node gradient: mean of the two face gradients (pf = 0 beyond the ends) */
      double left = (c->F[i] - (i > 0 ? c->F[i - 1] : pin)) / (c->hf[i] * c->a0);
      double right = ((i + 1 < n ? c->F[i + 1] : pout) - c->F[i]) / (c->hf[i + 1] * c->a0);
      double dpdx = 0.5 * (left + right) * c->p0;
      /* a smooth hard contact (u = 0) carries no fluid shear: sigma_s acts there */
      if (!(!c->rough && area > 0.0) && u > 0.0)
        couette += theta[i] * (v.phi_f + v.phi_fs) * cfg->eta_pa_s * c->v0 / u * dx;
      /* on the rigid curved body: its wall shear; on a moving flat
       * counter-surface: the same wall shear on the rubber plus the fluid
       * pressure on the rubber's slope, -\int pf u' = \int u pf' (the film's
       * tangential balance, docs/MODEL.md section 11) */
      poiseuille += (counterface ? 1.0 - 0.5 * v.phi_fp : -0.5 * v.phi_fp) * u * dpdx * dx;
    }
  }
  pt->x_centroid_m = (sum_pcx + sum_pfx) / fN;
  /* rolling terms: the pressures against the slope x/R of the rigid body;
   * a flat counter-surface has none (docs/MODEL.md section 11) */
  pt->rolling_na = counterface;
  pt->mu_Rc = counterface ? 0.0 : c->sprof ? -sum_pcs / fN : -sum_pcx / (fN * R);
  pt->mu_Rf = counterface ? 0.0 : c->sprof ? -sum_pfs / fN : -sum_pfx / (fN * R);
  /* the line contact slides at v0 everywhere: one sigma_s for all nodes */
  double sigma_s =
      cfg->shear_law ? vl_shear_law_eval(cfg->shear_law, c->v0, NULL) : cfg->sigma_s_pa;
  pt->mu_Sc = sigma_s * sum_area / fN;
  pt->mu_Sf_couette = couette / fN;
  pt->mu_Sf_poiseuille = poiseuille / fN;
  pt->mu_Sf = pt->mu_Sf_couette + pt->mu_Sf_poiseuille;
  pt->mu = pt->mu_Rc + pt->mu_Rf + pt->mu_Sc + pt->mu_Sf;
  pt->u_min_m = fmax(umin, 0.0) * c->uscale;
  pt->x_min_film_m = c->xi[iumin] * c->a0;
  /* separation at the pressure centroid (linear interpolation on nodes) */
  double xc = pt->x_centroid_m / c->a0;
  size_t k = 0;
  while (k + 2 < n && c->xi[k + 1] <= xc)
    k++;
  double w = fmin(fmax((xc - c->xi[k]) / c->hf[k + 1], 0.0), 1.0);
  pt->u_central_m = fmax((1 - w) * c->U[k] + w * c->U[k + 1], 0.0) * c->uscale;
  /* contact extent where the total pressure >= 1% of its peak, interpolated */
  double thr = 0.01 * pmax / c->p0;
#define PTOT(j) (c->P[j] + c->F[j] - (c->pamb ? c->pamb[j] : 0.0))
  size_t lo = imax, hi = imax;
  while (lo > 0 && PTOT(lo - 1) >= thr)
    lo--;
  while (hi + 1 < n && PTOT(hi + 1) >= thr)
    hi++;
  double xl = c->xi[lo], xr = c->xi[hi];
  if (lo > 0) xl -= c->hf[lo] * (PTOT(lo) - thr) / (PTOT(lo) - PTOT(lo - 1));
  if (hi + 1 < n) xr += c->hf[hi + 1] * (PTOT(hi) - thr) / (PTOT(hi) - PTOT(hi + 1));
  pt->contact_width_m = pmax > 0 ? (xr - xl) * c->a0 : 0.0;
  /* the half-space model wants small slopes (docs/MODEL.md section 13) */
  double smax = 0.0;
  for (size_t i = lo; c->sprof && i <= hi; i++)
    smax = fmax(smax, fabs(c->sprof[i]));
  if (atan(smax) > VL_PROFILE_SLOPE_MAX) {
    char msg[96];
    snprintf(msg, sizeof msg,
             "profile slope %.2g rad > %.1f in the pressure zone (half-space model)", atan(smax),
             VL_PROFILE_SLOPE_MAX);
    add_warning(pt, msg);
  }
  pt->fluid_load_fraction = sum_pf / fN;
  pt->load_error = fabs(vl_contact_load_sum(c) - 1.0);
  /* the flux through the face at the fluid pressure's maximum: constant
   * along the full film, but best resolved there, where it is the Couette
   * flux alone (the far inlet's thick film carries Couette and Poiseuille
   * fluxes far larger than their difference, resolved only to the Reynolds
   * rows' tolerance relative to them) */
  pt->flux_m2_s = c->wet ? c->Jf[ipf] * 0.5 * c->v0 * c->uscale : 0.0;
  pt->E_wH_pa = c->e_abs;
  pt->a_H_m = c->a_h;
  pt->Q = c->q_rolling;
  pt->peak_pressure_pa = pmax;
  pt->x_peak_m = c->xi[imax] * c->a0;
  pt->u_min_over_h_rms = c->hrms > 0.0 ? pt->u_min_m / c->hrms : NAN;
  pt->regime = vl_regime_of(c->wet, pt->fluid_load_fraction, pt->u_min_over_h_rms);
  if (pmax > 0 && (PTOT(0) > 1e-3 * pmax / c->p0 || PTOT(n - 1) > 1e-3 * pmax / c->p0))
    add_warning(pt, "pressure reaches the domain edge (domain too short)");
  /* a smooth film is fed from far upstream: with the inlet end less than 5
   * inlet lengths sqrt(2 R u_min) ahead of the pressure zone (where the
   * pressure reaches 1 % of its peak) the film is short by about a percent
   * or more (rigid cylinder, closed form: 2 %; soft EHL, measured: 0.1 to
   * 0.4 %, 1.2 % at 2.5 lengths) */
  if (c->wet && !c->rough && pmax > 0 &&
      (xl - c->xi[0] + c->hf[0]) * c->a0 < 5.0 * sqrt(2.0 * cfg->radius_m * pt->u_min_m))
    add_warning(pt, "inlet shorter than 5 inlet lengths sqrt(2 R u_min) ahead of the pressure "
                    "(fully flooded film underestimated)");
#undef PTOT
}

void vl_contact_fields(const vl_contact *c, vl_fields *f) {
  size_t n = c->n;
  const double *y = N_VGetArrayPointer(c->y);
  vl_contact *mc = (vl_contact *)c; /* work arrays only */
  vl_contact_eval_state(mc, y);
  double *theta = mc->theta;
  if (c->wet) film_fraction(c, y, theta);
  for (size_t i = 0; i < n && i < f->n; i++) {
    f->x_m[i] = c->xi[i] * c->a0;
    f->p_c_pa[i] = c->P[i] * c->p0;
    f->p_f_pa[i] = c->F[i] * c->p0;
    f->u_m[i] = fmax(c->U[i], 0.0) * c->uscale;
    f->area_ratio[i] = area_at(c, i);
    if (f->film_fraction) f->film_fraction[i] = c->wet ? theta[i] : 1.0;
    if (f->width_m) f->width_m[i] = c->wc[i] * c->a0;
  }
}

/* The film's shear beyond the outlet end, relative to mu (numerics_plan.h). */
double vl_contact_outlet_tail(vl_contact *c, const vl_point *pt) {
  if (!c->wet || !c->rough || !pt->converged) return 0.0;
  size_t n = c->n;
  const double *y = N_VGetArrayPointer(c->y);
  vl_contact_eval_state(c, y);
  film_fraction(c, y, c->theta);
  const vl_contact_config *cfg = &c->cfg;
  double u_end = fmax(c->U[n - 1], 0.0) * c->uscale;
  if (!(u_end > 0.0)) return 0.0;
  /* the Couette flux theta u is carried on past the end (a cavitated film
   * keeps its flow; a full one cavitates), the gap opens like the Hertz gap
   * x^2/2R, and the factors tend to the smooth film's (1) */
  double q = c->theta[n - 1] * u_end, R = cfg->radius_m;
  double x_end = (c->xi[n - 1] + 0.5 * c->wc[n - 1]) * c->a0;
  double sum = 0.0, t = 1e-3 * c->a0, prev_f = -1.0, prev_t = 0.0;
  for (int k = 0; k < 400 && t < 1e6 * c->a0; k++, t *= 1.05) {
    double x = x_end + t;
    double u = u_end + (x * x - x_end * x_end) / (2.0 * R);
    double f = q / (u * u); /* theta / u */
    if (prev_f >= 0.0)
      sum += 0.5 * (f + prev_f) * (t - prev_t);
    else
      sum += f * t;
    prev_f = f, prev_t = t;
  }
  double tail = cfg->eta_pa_s * c->v0 * sum / cfg->load_n_per_m;
  return tail / fmax(fabs(pt->mu), 1e-9);
}
