/* The lubricated ball behind point_contact.h (cfg.eta_pa_s > 0): the
 * point contact's numerics mapped onto the soft-EHL solver (point_ehl.h)
 * and its figures onto a vl_point (docs/POINT_CONTACT.md section 9).
 *
 * The grid: finest cells 1/cells_per_a0 (units of a0) at the contact's
 * rim, growing at 25 times that rate per a0 away from it up to 7.5 times
 * the finest, so that halving cells_per_a0 doubles every cell (the
 * sweep's error estimate is a nested coarser solve); zones and domain
 * ([-3, 1.6] x [0, 1.8] units) in units of y_max_a0/VL_BALL_DOMAIN_A0 a0,
 * the contact's planned size. */
#include "point_contact_internal.h"

#include "contact_private.h"
#include "persson_internal.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define WET_COARSE 7.5  /* coarsest cell / finest */
#define WET_GROWTH 25.0 /* growth rate / finest cell (per a0) */
#define WET_INLET 3.0   /* the domain, in units: [-WET_INLET, WET_OUTLET] x [0, WET_SIDE] */
#define WET_OUTLET 1.6
#define WET_SIDE 1.8
/* the soft-EHL solver's continuation needs more steps than a dry point */
#define WET_MIN_ITERATIONS 60

static void wet_config(const vl_point_contact_config *cfg, double v0, vl_point_ehl_config *e) {
  vl_point_ehl_config_defaults(e);
  e->radius_m = cfg->radius_x_m, e->load_n = cfg->load_n;
  e->rubber = cfg->rubber;
  e->eta_pa_s = cfg->eta_pa_s, e->v0_m_s = v0;
  e->roughness = cfg->roughness;
  e->flow_factors = cfg->flow_factors, e->flow_table = cfg->flow_table;
  e->sigma_s_pa = cfg->sigma_s_pa;
  double unit = cfg->y_max_a0 / VL_BALL_DOMAIN_A0, h = 1.0 / cfg->cells_per_a0;
  e->unit = unit;
  e->x_in = -WET_INLET * unit, e->x_out = WET_OUTLET * unit, e->y_max = WET_SIDE * unit;
  e->h_fine = h, e->h_coarse = WET_COARSE * h, e->growth = WET_GROWTH * h;
  e->tolerance = cfg->tolerance;
  e->max_iterations =
      cfg->max_iterations > WET_MIN_ITERATIONS ? cfg->max_iterations : WET_MIN_ITERATIONS;
}

size_t vl_point_contact_wet_cells(const vl_point_contact_config *cfg) {
  vl_point_ehl_config e;
  wet_config(cfg, 1.0, &e);
  return vl_point_ehl_cells(&e);
}

/* The soft-EHL (and rough) figures as a point of the curve (both halves). */
static void wet_report(const vl_point_contact *c, const vl_point_ehl_result *r, vl_point *pt) {
  pt->converged = r->converged;
  pt->iterations = r->iterations;
  pt->residual = isfinite(r->residual) ? r->residual : DBL_MAX;
  if (!r->converged) return;
  /* smooth: the solids apart, no contact pressure (both terms 0) */
  pt->mu_Rc = r->mu_Rc, pt->mu_Sc = r->mu_Sc;
  pt->mu_Rf = r->mu_Rf, pt->mu_Sf = r->mu_Sf;
  pt->mu_Sf_couette = r->mu_Sf_couette, pt->mu_Sf_poiseuille = r->mu_Sf_poiseuille;
  pt->mu = pt->mu_Rc + pt->mu_Rf + pt->mu_Sc + pt->mu_Sf;
  pt->u_min_m = r->h_min_m, pt->x_min_film_m = r->x_min_m;
  pt->u_central_m = r->h_centroid_m;
  pt->x_centroid_m = r->x_centroid_m;
  pt->contact_width_m = 0.0;
  pt->fluid_load_fraction = c->cfg.roughness ? r->fluid_load_fraction : 1.0;
  pt->load_error = fabs(r->load_error);
  pt->E_wH_pa = c->cfg.roughness ? r->e_abs_pa : c->er0, pt->a_H_m = c->a0;
  pt->peak_pressure_pa = r->p_max_pa, pt->x_peak_m = r->x_pmax_m;
  /* smooth and lubricated: the fluid carries the whole load */
  pt->eps_f_min = 1.0;
  if (c->cfg.roughness) { /* the line contact's regimes (results.h) */
    pt->u_min_over_h_rms = r->h_min_m / vl_persson_hrms(c->cfg.roughness);
    pt->regime = vl_regime_of(c->cfg.eta_pa_s > 0.0, pt->fluid_load_fraction, pt->u_min_over_h_rms);
    /* the line contact's check (assumptions.c): Persson's table ends at
     * 1e-3 h_rms; below, and at u <= 0, its continuation stands for full
     * contact */
    if (pt->u_min_over_h_rms < 1e-3)
      snprintf(pt->warnings, sizeof pt->warnings,
               "u_min = %.3g h_rms below the Persson table (1e-3 h_rms)", pt->u_min_over_h_rms);
  }
  vl_ball_result *ball = &pt->ball;
  /* rough: the real contact area (where the asperities touch) and the
   * nominal contact's extents (docs/POINT_CONTACT.md section 10) */
  ball->contact_area_m2 = r->real_area_m2;
  ball->contact_length_m = r->contact_length_m, ball->contact_breadth_m = r->contact_breadth_m;
  ball->y_min_film_m = r->y_min_m, ball->y_peak_m = r->y_pmax_m;
  ball->cells_in_contact = 0;
  ball->cells_per_a0 = c->cfg.cells_per_a0;
  ball->x_half_a0 = WET_INLET * c->cfg.y_max_a0 / VL_BALL_DOMAIN_A0;
  ball->y_max_a0 = WET_SIDE * c->cfg.y_max_a0 / VL_BALL_DOMAIN_A0;
}

vl_status vl_point_contact_wet_solve(vl_point_contact *c, double v0, vl_point *pt, vl_error *err) {
  memset(pt, 0, sizeof *pt);
  pt->ball.geometry = c->geometry;
  pt->error_estimate = NAN, pt->flux_error_estimate = NAN;
  pt->u_min_over_h_rms = NAN;
  pt->v0_m_s = v0;
  pt->regime = VL_REGIME_HYDRODYNAMIC;
  if (!(v0 > 0.0 && isfinite(v0))) {
    vl_error_set(err, "%s ball: speed must be finite and > 0 (got %g m/s)",
                 c->cfg.roughness ? "rough" : "lubricated", v0);
    return VL_EINPUT;
  }
  vl_point_ehl_config e;
  wet_config(&c->cfg, v0, &e);
  vl_point_ehl_result r;
  vl_point_ehl_map solved = {0};
  vl_status st = vl_point_ehl_solve(&e, c->start, &r, &solved, err);
  vl_point_ehl_map_free(&c->map);
  c->map = solved;
  if (st != VL_OK && st != VL_ENOCONV) return st;
  wet_report(c, &r, pt);
  return st;
}

void vl_point_contact_wet_start_from(vl_point_contact *c, const vl_point_contact *from) {
  c->start = from && from->graded && from->map.nx ? &from->map : NULL;
}
