/* viscolube: a scene file (INI) names the materials, the operating
 * conditions, the effects to simulate and the numerics. Only the effects
 * switched on are built and solved. See docs/FORMATS.md for every key. */
#ifndef VISCOLUBE_SCENE_H
#define VISCOLUBE_SCENE_H

#include <stdbool.h>
#include <stddef.h>

#include "viscolube/contact.h"
#include "viscolube/flow_factors.h"
#include "viscolube/status.h"
#include "viscolube/sweep.h"

#define VL_NAME_MAX 128
/* The flow factors of a rough wet scene that does not name them, and of
 * `friction` and `compare` (docs/FLOW_FACTORS.md). */
#define VL_SCENE_ROUGH_FLOW_FACTORS VL_FLOW_FACTORS_PERSSON_EMT
/* Largest film cut-off a scene takes (m): beyond a micrometre it is no
 * longer a boundary layer. */
#define VL_FILM_CUTOFF_MAX_M 1e-6
#define VL_FIELDS_AT_MAX 32
#define VL_FLUIDS_MAX 8

/* The defaults and limits of the [numerics] keys (VL_DRY_*, VL_WET_*,
 * VL_GRID_MIN, VL_GRID_UNIFORM_MAX, VL_GRID_GRADED_MAX, VL_GRID_GROWTH_MAX)
 * are the solver's: contact.h. */

typedef enum {
  VL_SWEEP_V0 = 0, /* sliding speed, m/s */
  VL_SWEEP_V0_ETA, /* v0 * eta, Pa m */
  VL_SWEEP_DEBORAH /* v0 tau / a0, one-term compounds */
} vl_sweep_quantity;

/* The order a sweep visits its speeds ([sweep] direction): upward (the
 * default: from the boundary regime, where any start converges), downward
 * (from the lifted film), or both, one after the other, to find speeds
 * where the model has two states (a fold of the Stribeck curve: a film
 * that lifts off at a higher speed on the way up than it collapses on the
 * way down). */
typedef enum { VL_DIRECTION_UP = 0, VL_DIRECTION_DOWN, VL_DIRECTION_BOTH } vl_sweep_direction;

typedef enum {
  VL_ELASTIC_RELAXED = 0, /* viscoelastic = off: E = E0 of the compound */
  VL_ELASTIC_GLASSY,      /* E = Einf */
  VL_ELASTIC_GIVEN        /* E = elastic_modulus_pa */
} vl_elastic_choice;

/* sigma_s of a scene with solid_shear = on and no [contact] sigma_s_pa, and
 * no stored pair for its materials: the seed's 1 MPa. */
#define VL_SCENE_SIGMA_S_PA 1e6

typedef struct {
  char path[1024];
  char title[256];
  /* [materials] */
  char compound[VL_NAME_MAX], surface[VL_NAME_MAX];
  char fluid[VL_NAME_MAX]; /* the fluid of this run: fluids[0] */
  size_t n_fluids;         /* `fluid = a, b, ...`: one curve each */
  char fluids[VL_FLUIDS_MAX][VL_NAME_MAX];
  vl_elastic_choice elastic;
  double elastic_modulus_pa;
  /* [contact] */
  int geometry; /* vl_geometry (results.h): cylinder (0, the default), ball, ellipsoid */
  /* a cylinder's radius and load per unit length; a ball's radius (radius_y_m
   * the same) and total load load_n; an ellipsoid's radii radius_m (along
   * the sliding direction, x) and radius_y_m (across) and load_n */
  double radius_m, radius_y_m, load_n_per_m, load_n, sigma_s_pa;
  /* sigma_s_pa was given (the scene's key, a query's sigma_s): without it,
   * a scene with solid_shear takes the law of the stored pair of its
   * compound, surface and fluid when there is one (vl_simulation_create) */
  bool sigma_s_given;
  vl_moving moving;          /* which body moves (contact.h); VL_MOVING_RUBBER by default */
  double sealed_pressure_pa; /* fluid pressure on the oil side (Pa; 0: none) */
  /* the rubber's profile (x_m, z_m table, docs/FORMATS.md), the path as
   * given joined to the scene's folder; empty: the cylinder's parabola */
  char profile_file[2048];
  int profile_line; /* the key's line in the scene (for messages) */
  /* profile = lip: a parametric lip (docs/MODEL.md section 13) of tip
   * radius lip_tip_radius_m (radius_m then unset: the scales' radius is
   * computed, vl_contact_profile_contact) and flank angles (degrees) on the
   * oil side (an outstroke's inlet) and the air side */
  bool lip;
  double lip_tip_radius_m, lip_oil_angle_deg, lip_air_angle_deg;
  /* an imposed static contact pressure (x_m, p_pa table; docs/MODEL.md
   * section 14), the path joined to the scene's folder; empty: none. With
   * it radius_m and load_n_per_m are unset (the table gives them) */
  char pressure_file[2048];
  int pressure_line;
  /* [seal]: a seal's strokes (results.h vl_stroke; VL_STROKE_NONE without
   * the section), the rod diameter and stroke length (m; 0: not given, no
   * volumes per cycle) */
  int stroke;
  double rod_diameter_m, stroke_length_m;
  /* [sweep] */
  vl_sweep_quantity quantity;
  double from, to;
  size_t points;
  vl_sweep_direction direction;
  size_t n_fields_at;
  double fields_at[VL_FIELDS_AT_MAX]; /* in the sweep quantity's units */
  /* [effects]: only those on are built and solved */
  struct {
    bool viscoelastic, roughness, fluid, solid_shear, viscous_flattening, temperature;
    vl_flow_factor_kind flow_factors; /* rough wet scenes without the key:
                                       * VL_SCENE_ROUGH_FLOW_FACTORS */
    double film_cutoff_m;             /* persson-emt's g_cut (m) */
    double temperature_c;
  } effects;
  /* [numerics] */
  size_t grid;
  double grid_growth; /* vl_contact_config.grid_growth; 1 = uniform */
  double domain_min_a0, domain_max_a0;
  double tolerance;
  vl_linear_solver linear_solver;
  size_t persson_table;
  /* Automatic numerics (sweep.h: domain and cells per run of points, an
   * error estimate on every point, refinement to target_error): on unless
   * the scene sets grid, grid_growth or domain_a0 (then the grid, growth
   * and domain are the scene's, and each point still gets its estimate). */
  bool auto_numerics;
  double target_error; /* relative, of mu; VL_TARGET_ERROR_DEFAULT */
} vl_scene;

/* The defaults of every optional key (README.md), with no materials named:
 * for scenes built in code (the `friction` and `compare` commands). */
void vl_scene_defaults(vl_scene *scene);

/* Parses a scene file. Errors (unknown section or key, missing required key,
 * bad value, inconsistent effects) name "file:line: [section] key: why". */
vl_status vl_scene_load(const char *path, vl_scene *scene, vl_error *err);

/* The same from text (path is used in messages only). */
vl_status vl_scene_parse(const char *text, const char *path, vl_scene *scene, vl_error *err);

/* Makes a loaded scene solve a seal's two strokes (`viscolube seal`, the
 * Python seal()): [seal] stroke = both whatever it said. VL_EINPUT (err
 * names the scene and why) unless the scene is one of a seal: [contact]
 * moving = counterface (the seal at rest, the rod moving) and [effects]
 * fluid = on. */
vl_status vl_scene_as_seal(vl_scene *scene, vl_error *err);

const char *vl_sweep_quantity_name(vl_sweep_quantity q);

#endif
