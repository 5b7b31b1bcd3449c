/* viscolube: a scene file (INI) names the materials, the operating
 * conditions, the effects to simulate and the numerics. Only the effects
 * switched on are built and solved. See README.md for every key. */
#ifndef VISCOLUBE_SCENE_H
#define VISCOLUBE_SCENE_H

#include <stdbool.h>
#include <stddef.h>

#include "viscolube/contact.h"
#include "viscolube/flow_factors.h"
#include "viscolube/status.h"

#define VL_NAME_MAX 128
#define VL_FIELDS_AT_MAX 32
#define VL_FLUIDS_MAX 8
/* Numerics of wet scenes when the scene does not set them (dry: grid 512,
 * domain -1.5, 1.5, tolerance 1e-9), from the accuracy study (bench/,
 * README "Accuracy and cost"): the cheapest setting with mu within 1 % of a
 * reference at N 1536 / inlet 32 a0 over the fig05, fig10 and real-rubber
 * sweeps. The inlet must hold the film's inlet zone at the top of the
 * Stribeck curve (fig05 at v0 eta = 1 Pa m: 6.1 % / 1.5 % short with 5 /
 * 12 a0 against 20 a0); the grid then resolves the contact (N 512: fig10
 * 1.9 %); the tolerance does not move mu between 1e-3 and 1e-9, 1e-6 keeps a
 * margin on the load balance. */
#define VL_WET_DOMAIN_MIN_A0 -24.0
#define VL_WET_DOMAIN_MAX_A0 1.6
#define VL_WET_GRID 768
#define VL_WET_TOLERANCE 1e-6
/* Largest [numerics] grid: uniform, and with a graded inlet (whose cells
 * are far fewer; the contact refuses more than VL_CONTACT_MAX_CELLS of them). */
#define VL_GRID_UNIFORM_MAX 8192
#define VL_GRID_GRADED_MAX VL_CONTACT_MAX_GRID_GRADED
/* Rough wet scenes take a graded inlet (vl_contact_config.grid_growth):
 * uniform cells of a0/30 near the contact (as grid 768 on [-24, 1.6] a0
 * gives), merged into cells growing by 5 % upstream of -2 a0, on an inlet of
 * 96 a0; about 200 cells in all. From the study with graded grids (bench/,
 * README "Accuracy and cost"): against a reference with a0/60 cells, a
 * 192 a0 inlet and growth 1.02, mu is within 0.75 % on fig05, fig10 and the
 * real rubber, where the uniform 768 / 24 a0 grid was 1.2-1.6 % off (its
 * inlet too short: mu converges like 1/X in the inlet length). */
#define VL_WET_ROUGH_DOMAIN_MIN_A0 -96.0
#define VL_WET_ROUGH_GRID 2928 /* 97.6 a0 / (a0/30) */
#define VL_WET_GRID_GROWTH 1.05

typedef enum {
  VL_SWEEP_V0 = 0,     /* sliding speed, m/s */
  VL_SWEEP_V0_ETA,     /* v0 * eta, Pa m */
  VL_SWEEP_DEBORAH     /* v0 tau / a0, one-term compounds */
} vl_sweep_quantity;


typedef enum {
  VL_ELASTIC_RELAXED = 0, /* viscoelastic = off: E = E0 of the compound */
  VL_ELASTIC_GLASSY,      /* E = Einf */
  VL_ELASTIC_GIVEN        /* E = elastic_modulus_pa */
} vl_elastic_choice;

typedef struct {
  char path[1024];
  char title[256];
  /* [materials] */
  char compound[VL_NAME_MAX], surface[VL_NAME_MAX];
  char fluid[VL_NAME_MAX];                  /* the fluid of this run: fluids[0] */
  size_t n_fluids;                          /* `fluid = a, b, ...`: one curve each */
  char fluids[VL_FLUIDS_MAX][VL_NAME_MAX];
  vl_elastic_choice elastic;
  double elastic_modulus_pa;
  /* [contact] */
  double radius_m, load_n_per_m, sigma_s_pa;
  /* [sweep] */
  vl_sweep_quantity quantity;
  double from, to;
  size_t points;
  size_t n_fields_at;
  double fields_at[VL_FIELDS_AT_MAX]; /* in the sweep quantity's units */
  /* [effects]: only those on are built and solved */
  struct {
    bool viscoelastic, roughness, fluid, solid_shear, viscous_flattening, temperature;
    vl_flow_factor_kind flow_factors;
    double temperature_c;
  } effects;
  /* [numerics] */
  size_t grid;
  double grid_growth;  /* vl_contact_config.grid_growth; 1 = uniform */
  double domain_min_a0, domain_max_a0;
  double tolerance;
  vl_linear_solver linear_solver;
  size_t persson_table;
} vl_scene;

/* The defaults of every optional key (README.md), with no materials named:
 * for scenes built in code (the `friction` and `compare` commands). */
void vl_scene_defaults(vl_scene *scene);

/* The numerics a scene gets from its effects when it does not set them
 * (grid, grid_growth, domain, tolerance): dry as vl_scene_defaults; wet
 * with VL_WET_TOLERANCE and a long inlet, graded on a rough surface
 * (VL_WET_ROUGH_GRID on [VL_WET_ROUGH_DOMAIN_MIN_A0, VL_WET_DOMAIN_MAX_A0],
 * growth VL_WET_GRID_GROWTH) and uniform on a smooth one (VL_WET_GRID on
 * [VL_WET_DOMAIN_MIN_A0, VL_WET_DOMAIN_MAX_A0]). */
void vl_scene_default_numerics(vl_scene *scene);

/* Parses a scene file. Errors (unknown section or key, missing required key,
 * bad value, inconsistent effects) name "file:line: [section] key: why". */
vl_status vl_scene_load(const char *path, vl_scene *scene, vl_error *err);

/* The same from text (path is used in messages only). */
vl_status vl_scene_parse(const char *text, const char *path, vl_scene *scene, vl_error *err);

const char *vl_sweep_quantity_name(vl_sweep_quantity q);

#endif
