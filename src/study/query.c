/* The queries `friction` and `compare` (query.h): a wet rough scene built
 * in code from a compound, a surface, a fluid and the operating conditions,
 * and one operating point solved robustly. The command line and the Python
 * package both answer through here, so they answer alike. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"
#include "simulation_internal.h"
#include "viscolube/query.h"
#include "viscolube/simulation.h"

void vl_query_defaults(vl_query *q) {
  memset(q, 0, sizeof *q);
  q->load_n_per_m = VL_QUERY_LOAD_N_PER_M;
  q->radius_m = VL_QUERY_RADIUS_M;
  q->sigma_s_pa = VL_QUERY_SIGMA_S_PA;
  q->flow_factors = VL_SCENE_ROUGH_FLOW_FACTORS;
  q->temperature_c = NAN;
}

const char *vl_query_flow_factors(const vl_query *q, double *film_cutoff_m) {
  vl_flow_factor_kind k = q->flow_factors;
  *film_cutoff_m = k != VL_FLOW_FACTORS_PERSSON_EMT ? 0.0
                   : q->film_cutoff_m > 0.0         ? q->film_cutoff_m
                                                    : VL_FILM_CUTOFF_DEFAULT_M;
  return vl_flow_factors_name(k);
}

/* The material names of q: a cylinder needs all three, a point contact
 * the compound (its surface and fluid are optional). */
static vl_status check_names(const vl_query *q, vl_error *err) {
  const char *names[3] = {q->compound, q->surface, q->fluid};
  const char *keys[3] = {"compound", "surface", "fluid"};
  for (size_t k = 0; k < 3; k++) {
    if (!names[k] && (k == 0 || q->geometry == VL_GEOMETRY_CYLINDER)) {
      vl_error_set(err, "no %s named", keys[k]);
      return VL_EINPUT;
    }
    if (names[k] && vl_db_check_name(names[k], err) != VL_OK) {
      vl_error_prefix(err, "%s", keys[k]);
      return VL_EINPUT;
    }
  }
  return VL_OK;
}

static bool positive(double x) { return x > 0.0 && isfinite(x); }

/* The rigid body's keys (NULL when they fit, else why not). */
static const char *geometry_trouble(const vl_query *q) {
  int g = q->geometry;
  if (g != VL_GEOMETRY_CYLINDER && g != VL_GEOMETRY_BALL && g != VL_GEOMETRY_ELLIPSOID)
    return "geometry: expected cylinder, ball or ellipsoid";
  if (g == VL_GEOMETRY_CYLINDER && !positive(q->load_n_per_m))
    return "load_n_per_m: needs a positive number";
  if (g == VL_GEOMETRY_CYLINDER && q->load_n != 0.0)
    return "load_n: a cylinder takes load_n_per_m (N per metre of its length)";
  if (g != VL_GEOMETRY_CYLINDER && !positive(q->load_n))
    return "load_n: needs a positive number (a ball's or an ellipsoid's total load, N)";
  if (!positive(q->radius_m)) return "radius_m: needs a positive number";
  if (g == VL_GEOMETRY_ELLIPSOID && !positive(q->radius_y_m))
    return "radius_y_m: needs a positive number (an ellipsoid's radius across the sliding "
           "direction)";
  if (g != VL_GEOMETRY_ELLIPSOID && q->radius_y_m != 0.0) return "radius_y_m: an ellipsoid's only";
  if (g != VL_GEOMETRY_CYLINDER && q->grid)
    return "grid: a line contact's cells (a point contact's are planned per point)";
  return NULL;
}

/* Why the conditions of q are out of range (the field first), NULL when
 * they are not. */
static const char *conditions_trouble(const vl_query *q) {
  const char *bad = geometry_trouble(q);
  if (bad) return bad;
  if (!(q->sigma_s_pa >= 0.0 && isfinite(q->sigma_s_pa)))
    return "sigma_s_pa: needs a non-negative number";
  if (q->grid && (q->grid < VL_GRID_MIN || q->grid > VL_GRID_GRADED_MAX))
    return "grid: out of range";
  if (q->film_cutoff_m != 0.0 &&
      !(q->film_cutoff_m > 0.0 && q->film_cutoff_m <= VL_FILM_CUTOFF_MAX_M))
    return "film_cutoff_m: needs a length in (0, 1e-6] m";
  if (q->film_cutoff_m > 0.0 && q->flow_factors != VL_FLOW_FACTORS_PERSSON_EMT)
    return "film_cutoff_m: applies to the persson-emt flow factors only";
  if (q->film_cutoff_m > 0.0 && !q->surface)
    return "film_cutoff_m: applies to a rough contact (a surface) only";
  if (q->at_temperature && !(q->temperature_c >= -273.15 && isfinite(q->temperature_c)))
    return "temperature_c: needs a temperature in C above absolute zero";
  return NULL;
}

/* VL_OK when the conditions of q are in range, else VL_EINPUT naming the
 * field. The command line checks its options first with messages of its
 * own; this is the contract for every other caller. */
static vl_status check_conditions(const vl_query *q, vl_error *err) {
  vl_status st = check_names(q, err);
  if (st != VL_OK) return st;
  const char *bad = conditions_trouble(q);
  if (!bad) return VL_OK;
  vl_error_set(err, "%s", bad);
  return VL_EINPUT;
}

/* A ball or an ellipsoid (q checked): the keys a scene file would set,
 * then the scene parser's checks of a point contact, whose refusal names
 * the query's field behind the scene's key. */
static vl_status point_scene(const vl_query *q, vl_scene *sc, vl_error *err) {
  sc->geometry = q->geometry;
  sc->radius_m = q->radius_m;
  sc->radius_y_m = q->geometry == VL_GEOMETRY_BALL ? q->radius_m : q->radius_y_m;
  sc->load_n_per_m = 0.0;
  sc->load_n = q->load_n;
  sc->effects.roughness = q->surface != NULL;
  sc->effects.fluid = q->fluid != NULL;
  sc->effects.flow_factors = sc->effects.roughness && sc->effects.fluid
                                 ? q->flow_factors
                                 : VL_FLOW_FACTORS_SMOOTH; /* the scene's without the key */
  /* the sweep in v0 eta needs a viscosity: a dry contact's is in m/s */
  sc->quantity = sc->effects.fluid ? VL_SWEEP_V0_ETA : VL_SWEEP_V0;
  vl_scene_default_numerics(sc);
  const char *key;
  vl_status st = vl_scene_check_point_contact(sc, &key, err);
  if (st != VL_OK && key && !strcmp(key, "roughness"))
    vl_error_prefix(err, "surface '%s'", q->surface);
  else if (st != VL_OK && key && !strcmp(key, "fluid"))
    vl_error_prefix(err, "fluid '%s'", q->fluid);
  return st;
}

vl_status vl_query_scene(const vl_query *q, const char *label, vl_scene *sc, vl_error *err) {
  vl_status st = check_conditions(q, err);
  if (st != VL_OK) return st;
  vl_scene_defaults(sc);
  /* no path: built in code, its messages name no scene file (simulation.c) */
  sc->path[0] = '\0';
  snprintf(sc->title, sizeof sc->title, "%s", label ? label : "");
  snprintf(sc->compound, sizeof sc->compound, "%s", q->compound);
  snprintf(sc->surface, sizeof sc->surface, "%s", q->surface ? q->surface : "");
  snprintf(sc->fluid, sizeof sc->fluid, "%s", q->fluid ? q->fluid : "");
  snprintf(sc->fluids[0], sizeof sc->fluids[0], "%s", sc->fluid);
  sc->n_fluids = 1;
  sc->sigma_s_pa = q->sigma_s_pa;
  sc->sigma_s_given = q->sigma_s_given;
  sc->effects.solid_shear = q->sigma_s_pa > 0.0;
  if (q->film_cutoff_m > 0.0) sc->effects.film_cutoff_m = q->film_cutoff_m;
  if (q->at_temperature) {
    sc->effects.temperature = true;
    sc->effects.temperature_c = q->temperature_c;
  }
  if (q->geometry != VL_GEOMETRY_CYLINDER) {
    st = point_scene(q, sc, err);
  } else {
    sc->radius_m = q->radius_m;
    sc->load_n_per_m = q->load_n_per_m;
    sc->effects.roughness = true;
    sc->effects.fluid = true;
    sc->effects.flow_factors = q->flow_factors;
    vl_scene_default_numerics(sc);
    if (q->grid) sc->grid = q->grid, sc->auto_numerics = false; /* 0: automatic numerics */
    sc->quantity = VL_SWEEP_V0_ETA;
  }
  if (q->target_error > 0.0) sc->target_error = q->target_error;
  return st;
}

vl_status vl_query_check_compound(vl_db *db, const vl_query *q, const char *compound,
                                  vl_error *err) {
  if (!q->at_temperature) return VL_OK;
  vl_db_compound info;
  vl_prony shifted;
  double a_T;
  vl_status st = vl_db_compound_info(db, compound, &info, err);
  if (st == VL_OK) st = vl_compound_at_temperature(&info, q->temperature_c, &shifted, &a_T, err);
  return st;
}

vl_status vl_query_fluid_eta(vl_db *db, const vl_query *q, double *eta, vl_error *err) {
  *eta = 0.0;
  if (!q->fluid) return VL_OK; /* a dry point contact */
  if (!q->at_temperature) return vl_db_fluid_get(db, q->fluid, eta, err);
  vl_db_fluid f;
  vl_status st = vl_db_fluid_info(db, q->fluid, &f, err);
  if (st == VL_OK)
    st = vl_fluid_viscosity(&f.law, f.viscosity_pa_s, f.tref_c, q->temperature_c, eta, err);
  if (st == VL_EINPUT) vl_error_prefix(err, "fluid '%s'", q->fluid);
  return st;
}

/* One attempt at the point: the scene's sweep from sc->from to sc->to
 * (points as set), its last point into *pt. *sim is replaced. */
static vl_status attempt(vl_scene *sc, vl_db *db, vl_simulation **sim, vl_point *pt, size_t *solved,
                         vl_error *err) {
  vl_simulation_free(*sim);
  *sim = NULL;
  vl_status st = vl_simulation_create(sc, db, sim, err);
  if (st != VL_OK) return st;
  size_t n = vl_simulation_points(*sim);
  vl_point *pts = calloc(n, sizeof *pts);
  if (!pts) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  vl_sweep_stats one;
  st = vl_simulation_run(*sim, pts, NULL, NULL, &one, err);
  *solved += one.converged + one.failed;
  *pt = pts[n - 1];
  free(pts);
  return st;
}

/* The point at v0 = speed: first a direct solve from the Hertz guess; if it
 * fails, continuation from the boundary regime (v0 eta = 1e-12 Pa m), 4
 * points a decade. *sim is the simulation of the last attempt. */
static vl_status solve_point(vl_scene *sc, vl_db *db, double speed, double eta, vl_simulation **sim,
                             vl_point *pt, size_t *solved, vl_error *err) {
  vl_status st = VL_OK;
  if (sc->geometry != VL_GEOMETRY_CYLINDER) { /* its own starts (vl_point_contact_sweep) */
    sc->quantity = VL_SWEEP_V0, sc->from = sc->to = speed, sc->points = 1;
    return attempt(sc, db, sim, pt, solved, err);
  }
  for (int k = 0; st == VL_OK && k < 2; k++) {
    sc->to = speed * eta;
    sc->from = k == 0 ? sc->to : fmin(1e-12, 0.1 * sc->to);
    sc->points = k == 0 ? 1 : (size_t)ceil(4.0 * log10(sc->to / sc->from)) + 1;
    st = attempt(sc, db, sim, pt, solved, err);
    if (pt->converged) break;
  }
  return st;
}

vl_status vl_query_friction(vl_db *db, const vl_query *q, double speed_m_s, vl_query_result *out,
                            vl_error *err) {
  memset(out, 0, sizeof *out);
  vl_scene *sc = malloc(sizeof *sc);
  vl_simulation *sim = NULL;
  if (!sc) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  vl_status st = vl_query_scene(q, NULL, sc, err);
  if (st == VL_OK && !(speed_m_s > 0.0 && isfinite(speed_m_s))) {
    vl_error_set(err, "speed: needs a positive number of m/s");
    st = VL_EINPUT;
  }
  if (st == VL_OK) st = vl_query_check_compound(db, q, q->compound, err);
  /* their messages name the temperature and the material: nothing to add */
  if (st == VL_OK) st = vl_query_fluid_eta(db, q, &out->eta_pa_s, err);
  if (st == VL_OK)
    st = solve_point(sc, db, speed_m_s, out->eta_pa_s, &sim, &out->point, &out->points_solved, err);
  if (st == VL_OK) {
    const vl_psd *psd = vl_simulation_psd(sim);
    out->shift_factor = vl_simulation_shift_factor(sim);
    out->a0_m = vl_simulation_a0(sim);
    out->hrms_m = psd ? psd->hrms_m : 0.0;
    out->flow_factors = vl_simulation_flow_factors(sim, &out->film_cutoff_m);
    const vl_db_pair *pair = vl_simulation_pair(sim);
    out->has_pair = pair != NULL;
    if (pair) out->pair = *pair;
    out->shear_law = *vl_simulation_shear_law(sim);
    out->sigma_s_pa = vl_shear_law_eval(&out->shear_law, speed_m_s, NULL);
    const char *text = vl_simulation_shear_law_text(sim);
    snprintf(out->shear_law_text, sizeof out->shear_law_text, "%s", text ? text : "");
  }
  vl_simulation_free(sim);
  free(sc);
  return st;
}
