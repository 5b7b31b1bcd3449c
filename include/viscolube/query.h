/* viscolube: the queries `friction` and `compare` of the command line, for
 * any caller (the Python package uses them too): a stored compound on a
 * stored surface in a stored fluid, at operating conditions whose defaults
 * are the seed's real-rubber scenes (Figs. 15-18), built into a wet rough
 * scene in code, and one operating point solved robustly.
 *
 * Typical use:
 *   vl_query q;
 *   vl_query_defaults(&q);
 *   q.compound = "sbr-unfilled", q.surface = "paper-0.5um", q.fluid = "water";
 *   vl_query_friction(db, &q, 1e-2, &res, &err);   -> res.point.mu ...
 * A Stribeck sweep of the same conditions: vl_query_scene, then set
 * from/to/points (in v0*eta, Pa m) and run it as any scene (simulation.h). */
#ifndef VISCOLUBE_QUERY_H
#define VISCOLUBE_QUERY_H

#include <stdbool.h>
#include <stddef.h>

#include "viscolube/database.h"
#include "viscolube/results.h"
#include "viscolube/scene.h"
#include "viscolube/status.h"

/* Defaults of vl_query_defaults: R = 1 mm, fN = 117 N/m, sigma_s = 1 MPa. */
#define VL_QUERY_LOAD_N_PER_M 117.0
#define VL_QUERY_RADIUS_M 1e-3
#define VL_QUERY_SIGMA_S_PA 1e6
/* The default Stribeck sweep of `compare`: v0*eta (Pa m) from the boundary
 * regime to full film, log-spaced points. */
#define VL_QUERY_FROM_PA_M 1e-12
#define VL_QUERY_TO_PA_M 0.1
#define VL_QUERY_POINTS 45

/* The conditions of a query. The names are borrowed (the caller keeps them
 * alive while the query is used). */
typedef struct {
  /* a cylinder needs all three; a ball or an ellipsoid (geometry) may go
   * without a surface (smooth) and without a fluid (dry) */
  const char *compound, *surface, *fluid;
  /* the rigid body (vl_geometry of results.h): VL_GEOMETRY_CYLINDER (0, the
   * default) takes radius_m and load_n_per_m; VL_GEOMETRY_BALL radius_m and
   * load_n (the total load, N; load_n_per_m is not used); an
   * VL_GEOMETRY_ELLIPSOID radius_m along the sliding direction, radius_y_m
   * across it, and load_n. A point contact's scene is the one `run` parses
   * from `[contact] geometry = ball` and the same keys
   * (docs/POINT_CONTACT.md). */
  int geometry;
  double load_n_per_m, radius_m;
  double load_n, radius_y_m; /* a point contact's; 0 by default (no default load) */
  double sigma_s_pa;         /* solid shear stress; 0 switches the effect off */
  /* sigma_s_pa was chosen by the caller; false (the default): the stored
   * pair's law of compound, surface and fluid when one exists, else
   * sigma_s_pa */
  bool sigma_s_given;
  size_t grid; /* uniform cells of the wet rough numerics; 0: default (a cylinder's only) */
  vl_flow_factor_kind flow_factors; /* default VL_SCENE_ROUGH_FLOW_FACTORS */
  double film_cutoff_m;             /* persson-emt only; 0: VL_FILM_CUTOFF_DEFAULT_M */
  bool at_temperature;              /* compound (WLF) and fluid (its law) at temperature_c */
  double temperature_c;
  double target_error; /* relative error of mu each point should meet; 0: VL_TARGET_ERROR_DEFAULT */
} vl_query;

/* One answered operating point. */
typedef struct {
  vl_point point;           /* mu, its four parts, u_min, regime, converged, warnings */
  double eta_pa_s;          /* the fluid's viscosity used (at temperature_c if asked) */
  double shift_factor;      /* a_T of the compound's times (1 without temperature) */
  double a0_m;              /* the Hertz half-width the domain is scaled by */
  double hrms_m;            /* the surface's h_rms (0 when smooth) */
  const char *flow_factors; /* vl_flow_factors_name of the model used (static) */
  double film_cutoff_m;     /* persson-emt's cut-off, else 0 */
  size_t points_solved;     /* 1 for a direct solve, more after continuation */
  /* the stored pair whose law gave sigma_s (has_pair), and that law at the
   * query's temperature; without a pair the constant q->sigma_s_pa */
  bool has_pair;
  vl_db_pair pair;
  vl_shear_law shear_law;
  double sigma_s_pa;                         /* sigma_s at the point's speed */
  char shear_law_text[VL_DB_TEXT_MAX + 512]; /* vl_simulation_shear_law_text ("" without) */
} vl_query_result;

/* The defaults above, no materials named, no temperature (NAN). */
void vl_query_defaults(vl_query *q);

/* The flow-factor model of q (vl_flow_factors_name) and its film cut-off
 * in *film_cutoff_m (persson-emt: q's or the default; else 0). */
const char *vl_query_flow_factors(const vl_query *q, double *film_cutoff_m);

/* The scene of q for q->compound: a cylinder's wet rough scene (sweep
 * quantity v0*eta); a ball's or an ellipsoid's scene as `run` parses it
 * from the same keys (roughness with a surface, the fluid effect with a
 * fluid; sweep quantity v0*eta with a fluid, else v0), checked as a scene
 * file's point contact is (what a point contact does not
 * take yet: its message "surface 'S': [effects] roughness: not with
 * [contact] geometry = ball: ..."). The caller sets from, to and points.
 * VL_EINPUT naming the field (geometry, load_n_per_m, load_n, radius_m,
 * radius_y_m, sigma_s_pa, grid, film_cutoff_m, temperature_c, a material
 * name) when q is out of range. label (may be NULL) is the scene's title.
 * The scene has no path: the simulation's messages about it name no scene
 * file or key ("no surface named 'x' in DB"), so that the caller adds its
 * own context (a command, an option) once. */
vl_status vl_query_scene(const vl_query *q, const char *label, vl_scene *scene, vl_error *err);

/* With q->at_temperature: VL_OK if compound can be taken there (WLF
 * constants, above the WLF singularity), else VL_EINPUT (the message names
 * the compound) or VL_ENOTFOUND. Without: VL_OK. Cheap; lets a caller
 * refuse before anything is computed. */
vl_status vl_query_check_compound(vl_db *db, const vl_query *q, const char *compound,
                                  vl_error *err);

/* The viscosity the query runs with: the stored one, or with
 * at_temperature the fluid's law there (the same call the simulation
 * makes, so both agree exactly). VL_EINPUT prefixed "fluid 'NAME'",
 * VL_ENOTFOUND. */
vl_status vl_query_fluid_eta(vl_db *db, const vl_query *q, double *eta_pa_s, vl_error *err);

/* The point at v0 = speed_m_s: first a direct solve from the Hertz guess;
 * if it does not converge, continuation from the boundary regime (v0 eta =
 * 1e-12 Pa m), 4 points a decade (a point contact: one sweep of one point,
 * vl_point_contact_sweep, whose own starts are tried instead, as `run` of
 * the scene from = to = speed_m_s does). A point that still does not converge is
 * VL_OK with out->point.converged false (iterations and residual set);
 * a status other than VL_OK means nothing was solved (bad conditions,
 * unknown material, database). The checks of vl_query_check_compound and
 * vl_query_fluid_eta come first (their messages name the material and the
 * temperature). */
vl_status vl_query_friction(vl_db *db, const vl_query *q, double speed_m_s, vl_query_result *out,
                            vl_error *err);

#endif
