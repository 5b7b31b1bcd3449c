/* The contact's configuration: the one owner of the numerics defaults
 * (contact.h: grid, domain, growth, tolerance, Newton iterations), the
 * validation of a configuration before anything is allocated, and the film
 * and inlet-length estimates that size a smooth wet contact's domain
 * (docs/MODEL.md section 9: the domain must follow the inlet length sqrt(2 R h)
 * when it exceeds a0). */
#include "contact_internal.h"
#include "contact_private.h"
#include "flow_factors_emt.h"
#include "persson_internal.h"
#include "profile.h"
#include "rheology_internal.h"
#include "shear_law_private.h"

#include <math.h>
#include <string.h>

void vl_contact_numerics_defaults(bool rough, bool wet, vl_contact_config *cfg) {
  cfg->grid = VL_DRY_GRID;
  cfg->grid_growth = 1.0;
  cfg->x_min_a0 = VL_DRY_DOMAIN_MIN_A0;
  cfg->x_max_a0 = VL_DRY_DOMAIN_MAX_A0;
  cfg->tolerance = VL_DRY_TOLERANCE;
  cfg->max_iterations = VL_NEWTON_MAX_ITERATIONS;
  cfg->linear_solver = VL_LINSOL_SCHUR;
  if (!wet) return;
  cfg->tolerance = VL_WET_TOLERANCE;
  cfg->x_max_a0 = VL_WET_DOMAIN_MAX_A0;
  if (rough) {
    cfg->grid = VL_WET_ROUGH_GRID, cfg->grid_growth = VL_WET_GRID_GROWTH;
    cfg->x_min_a0 = VL_WET_ROUGH_DOMAIN_MIN_A0;
  } else {
    cfg->grid = VL_WET_GRID, cfg->x_min_a0 = VL_WET_DOMAIN_MIN_A0;
  }
}

void vl_contact_config_defaults(vl_contact_config *cfg) {
  memset(cfg, 0, sizeof *cfg);
  vl_contact_numerics_defaults(false, false, cfg);
}

/* Radius, load and solid shear stress. */
static vl_status check_geometry(const vl_contact_config *cfg, vl_error *err) {
  if (!(cfg->radius_m > 0.0 && isfinite(cfg->radius_m))) {
    vl_error_set(err, "radius_m must be positive (got %g)", cfg->radius_m);
    return VL_EINPUT;
  }
  if (!(cfg->load_n_per_m > 0.0 && isfinite(cfg->load_n_per_m))) {
    vl_error_set(err, "load_n_per_m must be positive (got %g)", cfg->load_n_per_m);
    return VL_EINPUT;
  }
  if (cfg->shear_law && vl_shear_law_validate(cfg->shear_law, err) != VL_OK) return VL_EINPUT;
  if (!(cfg->sigma_s_pa >= 0.0 && isfinite(cfg->sigma_s_pa))) {
    vl_error_set(err, "sigma_s_pa must be >= 0 (got %g)", cfg->sigma_s_pa);
    return VL_EINPUT;
  }
  return VL_OK;
}

static vl_status check_domain(const vl_contact_config *cfg, vl_error *err);

/* An explicit cell layout: odd spans that sum to the uniform grid. */
static vl_status check_layout(const vl_contact_config *cfg, vl_error *err) {
  if (cfg->n_cells < VL_CONTACT_MIN_GRID || cfg->n_cells > VL_CONTACT_MAX_CELLS ||
      cfg->grid > VL_CONTACT_MAX_GRID_LAYOUT) {
    vl_error_set(err, "cell layout: %zu cells on a grid of %zu (at most %d cells on %d)",
                 cfg->n_cells, cfg->grid, VL_CONTACT_MAX_CELLS, VL_CONTACT_MAX_GRID_LAYOUT);
    return VL_EINPUT;
  }
  size_t sum = 0;
  for (size_t k = 0; k < cfg->n_cells; k++) {
    if (cfg->cell_spans[k] % 2 == 0) {
      vl_error_set(err, "cell layout: cell %zu spans %zu uniform cells (must be odd)", k,
                   cfg->cell_spans[k]);
      return VL_EINPUT;
    }
    sum += cfg->cell_spans[k];
  }
  if (sum != cfg->grid) {
    vl_error_set(err, "cell layout: the cells span %zu uniform cells, not the grid's %zu", sum,
                 cfg->grid);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* Grid size and growth, and the domain. */
static vl_status check_grid(const vl_contact_config *cfg, vl_error *err) {
  if (cfg->grid_growth != cfg->grid_growth || cfg->grid_growth > VL_GRID_GROWTH_MAX) {
    vl_error_set(err, "grid_growth must be <= %g (1 or less: uniform grid; got %g)",
                 VL_GRID_GROWTH_MAX, cfg->grid_growth);
    return VL_EINPUT;
  }
  if (cfg->cell_spans) {
    vl_status st = check_layout(cfg, err);
    if (st != VL_OK) return st;
    return check_domain(cfg, err);
  }
  size_t max_grid = cfg->grid_growth > 1.0 ? VL_CONTACT_MAX_GRID_GRADED : VL_CONTACT_MAX_CELLS;
  if (cfg->grid < VL_CONTACT_MIN_GRID || cfg->grid > max_grid) {
    vl_error_set(err, "grid must lie in [%d, %zu] (got %zu)", VL_CONTACT_MIN_GRID, max_grid,
                 cfg->grid);
    return VL_EINPUT;
  }
  if (cfg->grid_growth > 1.0 && !cfg->roughness) {
    /* the smooth film's limited upwinding and its coarse-grid starts are
     * written for a uniform grid */
    vl_error_set(err,
                 "grid_growth %g: a graded grid needs a rough surface (smooth contacts use "
                 "a uniform grid; set grid_growth = 1)",
                 cfg->grid_growth);
    return VL_EINPUT;
  }
  return check_domain(cfg, err);
}

/* The domain: around the axis. */
static vl_status check_domain(const vl_contact_config *cfg, vl_error *err) {
  if (!(cfg->x_max_a0 > cfg->x_min_a0)) {
    vl_error_set(err, "domain_a0: the end must exceed the start (got %g, %g)", cfg->x_min_a0,
                 cfg->x_max_a0);
    return VL_EINPUT;
  }
  if (!(cfg->x_min_a0 < 0.0 && cfg->x_max_a0 > 0.0)) {
    /* the contact forms around the cylinder's axis, x = 0 */
    vl_error_set(err, "domain_a0 must contain the axis x = 0 (got %g, %g)", cfg->x_min_a0,
                 cfg->x_max_a0);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* The scales of the dimensionless unknowns must exist in double precision
 * (R = fN = 1e200 gave a0^2/R = inf and a NaN point reported converged). */
static vl_status check_scales(const vl_contact_config *cfg, vl_error *err) {
  double er = vl_prony_e0(&cfg->rubber) * vl_prony_reduced_factor(&cfg->rubber);
  double a0 = sqrt(4.0 * cfg->load_n_per_m * cfg->radius_m / (M_PI * er));
  double p0 = 2.0 * cfg->load_n_per_m / (M_PI * a0), us = a0 * a0 / cfg->radius_m;
  if (!(isfinite(a0) && a0 > 0.0 && isfinite(p0) && p0 > 0.0 && isfinite(us) && us > 0.0 &&
        isfinite(a0 * cfg->x_min_a0) && isfinite(a0 * cfg->x_max_a0))) {
    vl_error_set(err,
                 "the contact's scales overflow: Hertz half-width %g m, peak pressure %g Pa, "
                 "a0^2/R %g m (radius %g m, load %g N/m, reduced modulus %g Pa)",
                 a0, p0, us, cfg->radius_m, cfg->load_n_per_m, er);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* Viscous flattening: epsilon_f modulates the roughness by the film's
 * pressure, so it needs both, and the same surface as the roughness table. */
static vl_status check_flattening(const vl_contact_config *cfg, vl_error *err) {
  if (!cfg->flattening) return VL_OK;
  if (!cfg->roughness || !(cfg->eta_pa_s > 0.0)) {
    vl_error_set(err, "viscous flattening needs %s",
                 !cfg->roughness ? "a rough surface (roughness = NULL: smooth contact)"
                                 : "a fluid (eta > 0: the contact is dry)");
    return VL_EINPUT;
  }
  if (!cfg->flattening_psd) {
    vl_error_set(err, "viscous flattening needs the surface's PSD (flattening_psd = NULL)");
    return VL_EINPUT;
  }
  double h_psd = vl_psd_hrms(cfg->flattening_psd);
  double h_table = vl_persson_hrms(cfg->roughness);
  if (!(fabs(h_psd - h_table) <= 1e-9 * h_table)) {
    vl_error_set(err,
                 "viscous flattening was given a surface of h_rms %g m, the roughness "
                 "table has %g m: both must come from the same PSD",
                 h_psd, h_table);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* persson-emt reads its factors from a table of the same surface. */
static vl_status check_flow_table(const vl_contact_config *cfg, vl_error *err) {
  if (cfg->flow_factors != VL_FLOW_FACTORS_PERSSON_EMT || !cfg->roughness) return VL_OK;
  if (!cfg->flow_table) {
    vl_error_set(err, "persson-emt flow factors need the surface's factor table (flow_table)");
    return VL_EINPUT;
  }
  double h_tab = vl_emt_table_hrms(cfg->flow_table), h = vl_persson_hrms(cfg->roughness);
  if (!(fabs(h_tab - h) <= 1e-9 * h)) {
    vl_error_set(err,
                 "the persson-emt table was built for a surface of h_rms %g m, the roughness "
                 "table has %g m: both must come from the same PSD",
                 h_tab, h);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* A parametric lip: a tip radius and two flank angles in (0, pi/2), or
 * none of them; not with a table. */
static vl_status check_lip(const vl_contact_config *cfg, vl_error *err) {
  bool any = cfg->lip_tip_radius_m != 0.0 || cfg->lip_oil_angle_rad != 0.0 ||
             cfg->lip_air_angle_rad != 0.0;
  if (!any) return VL_OK;
  if (!(cfg->lip_tip_radius_m > 0.0 && isfinite(cfg->lip_tip_radius_m))) {
    vl_error_set(err, "lip: the tip radius must be positive (got %g m)", cfg->lip_tip_radius_m);
    return VL_EINPUT;
  }
  const double angle[2] = {cfg->lip_oil_angle_rad, cfg->lip_air_angle_rad};
  for (int k = 0; k < 2; k++)
    if (!(angle[k] > 0.0 && angle[k] < 0.5 * M_PI)) {
      vl_error_set(err, "lip: the %s-side angle must lie in (0, pi/2) rad (got %g)",
                   k ? "air" : "oil", angle[k]);
      return VL_EINPUT;
    }
  if (cfg->profile_x_m) {
    vl_error_set(err, "a lip and a profile table: give one of them");
    return VL_EINPUT;
  }
  return VL_OK;
}

/* An imposed static pressure: a table that is one, on a rubber at rest
 * (its deformation is static), alone (no profile), carrying the load. */
static vl_status check_static(const vl_contact_config *cfg, vl_error *err) {
  if (!cfg->static_x_m && !cfg->static_p_pa) return VL_OK;
  if (cfg->moving != VL_MOVING_COUNTERFACE || cfg->profile_x_m || cfg->lip_tip_radius_m != 0.0) {
    vl_error_set(err, "a static pressure needs a moving counter-surface and no profile table "
                      "or lip (the pressure stands for the profile)");
    return VL_EINPUT;
  }
  vl_static_pressure t;
  vl_status st = vl_static_pressure_init(&t, cfg, err);
  if (st != VL_OK) return st;
  double load = t.load_n_per_m;
  vl_static_pressure_free(&t);
  if (!(fabs(cfg->load_n_per_m - load) <= 1e-9 * load)) {
    vl_error_set(err, "a static pressure carries %.10g N/m, load_n_per_m is %.10g", load,
                 cfg->load_n_per_m);
    return VL_EINPUT;
  }
  return VL_OK;
}

vl_status vl_contact_config_check(const vl_contact_config *cfg, vl_error *err) {
  vl_status st = vl_prony_validate(&cfg->rubber, err);
  if (st == VL_OK) st = check_geometry(cfg, err);
  if (st == VL_OK) st = check_grid(cfg, err);
  if (st != VL_OK) return st;
  if ((unsigned)cfg->linear_solver > VL_LINSOL_SCHUR ||
      (unsigned)cfg->flow_factors > VL_FLOW_FACTORS_PERSSON_EMT) {
    vl_error_set(err, "unknown %s (%d)",
                 (unsigned)cfg->linear_solver > VL_LINSOL_SCHUR ? "linear solver" : "flow factors",
                 (unsigned)cfg->linear_solver > VL_LINSOL_SCHUR ? (int)cfg->linear_solver
                                                                : (int)cfg->flow_factors);
    return VL_EINPUT;
  }
  if ((unsigned)cfg->moving > VL_MOVING_COUNTERFACE) {
    vl_error_set(err, "unknown moving body (%d)", (int)cfg->moving);
    return VL_EINPUT;
  }
  st = check_scales(cfg, err);
  if (st != VL_OK) return st;
  if (!(cfg->tolerance > 0.0 && cfg->tolerance < 1.0)) {
    vl_error_set(err, "tolerance must lie in (0, 1) (got %g)", cfg->tolerance);
    return VL_EINPUT;
  }
  if (!(cfg->eta_pa_s >= 0.0 && isfinite(cfg->eta_pa_s))) {
    vl_error_set(err, "viscosity must be >= 0 (got %g Pa s)", cfg->eta_pa_s);
    return VL_EINPUT;
  }
  if (!(cfg->p_inlet_pa >= 0.0 && isfinite(cfg->p_inlet_pa) && cfg->p_outlet_pa >= 0.0 &&
        isfinite(cfg->p_outlet_pa))) {
    vl_error_set(err, "end pressures must be >= 0 (got %g Pa at the inlet, %g Pa at the outlet)",
                 cfg->p_inlet_pa, cfg->p_outlet_pa);
    return VL_EINPUT;
  }
  if (cfg->profile_x_m || cfg->profile_z_m) {
    if (!cfg->profile_x_m || !cfg->profile_z_m || cfg->profile_points < 3) {
      vl_error_set(err, "a profile needs x and z of at least 3 points (got %zu)",
                   cfg->profile_points);
      return VL_EINPUT;
    }
    for (size_t k = 0; k < cfg->profile_points; k++) {
      if (!isfinite(cfg->profile_x_m[k]) || !isfinite(cfg->profile_z_m[k])) {
        vl_error_set(err, "profile point %zu is not finite", k);
        return VL_EINPUT;
      }
      for (size_t j = 0; j < k; j++)
        if (cfg->profile_x_m[j] == cfg->profile_x_m[k]) {
          vl_error_set(err, "profile points %zu and %zu have the same x (%g m)", j, k,
                       cfg->profile_x_m[k]);
          return VL_EINPUT;
        }
    }
  }
  st = check_lip(cfg, err);
  if (st == VL_OK) st = check_static(cfg, err);
  if (st != VL_OK) return st;
  if ((cfg->p_inlet_pa > 0.0 || cfg->p_outlet_pa > 0.0) && !(cfg->eta_pa_s > 0.0)) {
    vl_error_set(err, "a sealed pressure needs a fluid (the contact is dry)");
    return VL_EINPUT;
  }
  st = check_flow_table(cfg, err);
  if (st != VL_OK) return st;
  return check_flattening(cfg, err);
}

/* Martin's rigid film 4.894 eta um R/fN and the isoviscous-elastic (soft
 * EHL) one 2.32 (eta um R/fN) g^0.8, g = fN/sqrt(eta um E' R), um = v0/2,
 * E' = 2 Er (relaxed): the larger of the two. */
double vl_contact_film_estimate(const vl_contact_config *cfg, double v0) {
  double er = vl_prony_e0(&cfg->rubber) * vl_prony_reduced_factor(&cfg->rubber);
  double um = 0.5 * v0, eta = cfg->eta_pa_s, R = cfg->radius_m, fN = cfg->load_n_per_m;
  double ge = fN / sqrt(eta * um * 2.0 * er * R);
  return fmax(2.32 * pow(ge, 0.8), 4.894) * eta * um * R / fN;
}

double vl_contact_inlet_length_m(const vl_contact_config *cfg, double v0_m_s) {
  return sqrt(2.0 * cfg->radius_m * vl_contact_film_estimate(cfg, v0_m_s));
}

vl_status vl_contact_profile_contact(const vl_contact_config *cfg, double *centre_m,
                                     double *half_width_m, double *radius_m, vl_error *err) {
  vl_status st = vl_contact_config_check(cfg, err);
  if (st != VL_OK) return st;
  double er = vl_prony_e0(&cfg->rubber) * vl_prony_reduced_factor(&cfg->rubber);
  vl_profile p;
  if ((st = vl_profile_init(&p, cfg, err)) != VL_OK) return st;
  st = vl_profile_dry_contact(&p, cfg->load_n_per_m, er, centre_m, half_width_m, err);
  vl_profile_free(&p);
  if (st == VL_OK && radius_m)
    *radius_m = M_PI * er * *half_width_m * *half_width_m / (4.0 * cfg->load_n_per_m);
  return st;
}

vl_status vl_contact_numerics_follow_profile(vl_contact_config *cfg, vl_error *err) {
  if (!cfg->profile_x_m && !(cfg->lip_tip_radius_m > 0.0)) return VL_OK;
  double c, a;
  vl_status st = vl_contact_profile_contact(cfg, &c, &a, NULL, err);
  if (st != VL_OK) return st;
  double er = vl_prony_e0(&cfg->rubber) * vl_prony_reduced_factor(&cfg->rubber);
  double a0 = sqrt(4.0 * cfg->load_n_per_m * cfg->radius_m / (M_PI * er));
  /* both strokes: the mirrored profile's contact is centred at -c */
  double reach = (fabs(c) + a) / a0;
  bool wet = cfg->eta_pa_s > 0.0;
  double lo = cfg->x_min_a0, hi = cfg->x_max_a0, span = hi - lo;
  if (wet) {
    hi = fmax(hi, reach + (VL_WET_DOMAIN_MAX_A0 - 1.0));
    lo = fmin(lo, -reach - (VL_WET_DOMAIN_MAX_A0 - 1.0));
  } else {
    hi = fmax(hi, reach + (VL_DRY_DOMAIN_MAX_A0 - 1.0));
    lo = fmin(lo, -hi);
  }
  cfg->grid = (size_t)round((double)cfg->grid * (hi - lo) / span);
  /* a graded inlet starts beyond the contact, as it does 1 a0 beyond the
   * cylinder's */
  if (cfg->grid_growth > 1.0)
    cfg->grade_start_a0 = fmax(VL_GRADE_START_A0, reach + (VL_GRADE_START_A0 - 1.0));
  cfg->x_min_a0 = lo, cfg->x_max_a0 = hi;
  return VL_OK;
}

vl_status vl_contact_static_scales(const vl_contact_config *cfg, double *load_n_per_m,
                                   double *radius_m, vl_error *err) {
  vl_static_pressure t;
  vl_status st = vl_static_pressure_init(&t, cfg, err);
  if (st != VL_OK) return st;
  double er = vl_prony_e0(&cfg->rubber) * vl_prony_reduced_factor(&cfg->rubber);
  *load_n_per_m = t.load_n_per_m;
  *radius_m = M_PI * er * t.half_width_m * t.half_width_m / (4.0 * t.load_n_per_m);
  vl_static_pressure_free(&t);
  return VL_OK;
}
