/* Scene files: INI parsed by libinih, with line numbers for every error. */
#include "viscolube/scene.h"
#include "scene_internal.h"

#include "slurp.h"

#include "viscolube/edit_distance.h"
#include "viscolube/point_contact.h"

#include <ctype.h>
#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A macro's value as a string literal (the limits in messages). */
#define VL_STR_(x) #x
#define VL_STR(x) VL_STR_(x)

/* Every key a scene may hold. The parser records the line of each, so that
 * errors found after the whole file is read (inconsistent effects) still
 * name the line, and a key given twice is refused instead of silently
 * overriding the first. */
typedef enum {
  K_TITLE,
  K_COMPOUND,
  K_SURFACE,
  K_FLUID_NAME,
  K_ELASTIC_MODULUS,
  K_GEOMETRY,
  K_RADIUS,
  K_RADII,
  K_LOAD,
  K_LOAD_N,
  K_SIGMA_S,
  K_MOVING,
  K_SEALED_PRESSURE,
  K_PROFILE_FILE,
  K_PROFILE,
  K_PRESSURE_PROFILE_FILE,
  K_LIP_TIP_RADIUS,
  K_LIP_OIL_ANGLE,
  K_LIP_AIR_ANGLE,
  K_STROKE,
  K_ROD_DIAMETER,
  K_STROKE_LENGTH,
  K_QUANTITY,
  K_FROM,
  K_TO,
  K_POINTS,
  K_DIRECTION,
  K_FIELDS_AT,
  K_VISCOELASTIC,
  K_ROUGHNESS,
  K_FLUID,
  K_SOLID_SHEAR,
  K_VISCOUS_FLATTENING,
  K_TEMPERATURE,
  K_FLOW_FACTORS,
  K_FILM_CUTOFF,
  K_TEMPERATURE_C,
  K_GRID,
  K_GRID_GROWTH,
  K_DOMAIN,
  K_TOLERANCE,
  K_LINEAR_SOLVER,
  K_TARGET_ERROR,
  K_PERSSON_TABLE,
  K_COUNT
} key_id;

static const struct {
  const char *section, *key;
  bool required;
} keys[K_COUNT] = {
    [K_TITLE] = {"scene", "title", false},
    [K_COMPOUND] = {"materials", "compound", true},
    [K_SURFACE] = {"materials", "surface", false},
    [K_FLUID_NAME] = {"materials", "fluid", false},
    [K_ELASTIC_MODULUS] = {"materials", "elastic_modulus", false},
    [K_GEOMETRY] = {"contact", "geometry", false},
    /* required by geometry (scene_check): radius_m and load_n_per_m for a
     * cylinder (radius_m not with profile = lip, neither with
     * pressure_profile_file), radius_m and load_n for a ball, radii_m and
     * load_n for an ellipsoid */
    [K_RADIUS] = {"contact", "radius_m", false},
    [K_RADII] = {"contact", "radii_m", false},
    [K_LOAD] = {"contact", "load_n_per_m", false},
    [K_LOAD_N] = {"contact", "load_n", false},
    [K_SIGMA_S] = {"contact", "sigma_s_pa", false},
    [K_MOVING] = {"contact", "moving", false},
    [K_SEALED_PRESSURE] = {"contact", "sealed_pressure_pa", false},
    [K_PROFILE_FILE] = {"contact", "profile_file", false},
    [K_PROFILE] = {"contact", "profile", false},
    [K_PRESSURE_PROFILE_FILE] = {"contact", "pressure_profile_file", false},
    [K_LIP_TIP_RADIUS] = {"contact", "lip_tip_radius_m", false},
    [K_LIP_OIL_ANGLE] = {"contact", "lip_oil_angle_deg", false},
    [K_LIP_AIR_ANGLE] = {"contact", "lip_air_angle_deg", false},
    [K_STROKE] = {"seal", "stroke", false},
    [K_ROD_DIAMETER] = {"seal", "rod_diameter_m", false},
    [K_STROKE_LENGTH] = {"seal", "stroke_length_m", false},
    [K_QUANTITY] = {"sweep", "quantity", true},
    [K_FROM] = {"sweep", "from", true},
    [K_TO] = {"sweep", "to", true},
    [K_POINTS] = {"sweep", "points", true},
    [K_DIRECTION] = {"sweep", "direction", false},
    [K_FIELDS_AT] = {"sweep", "fields_at", false},
    [K_VISCOELASTIC] = {"effects", "viscoelastic", false},
    [K_ROUGHNESS] = {"effects", "roughness", false},
    [K_FLUID] = {"effects", "fluid", false},
    [K_SOLID_SHEAR] = {"effects", "solid_shear", false},
    [K_VISCOUS_FLATTENING] = {"effects", "viscous_flattening", false},
    [K_TEMPERATURE] = {"effects", "temperature", false},
    [K_FLOW_FACTORS] = {"effects", "flow_factors", false},
    [K_FILM_CUTOFF] = {"effects", "film_cutoff_m", false},
    [K_TEMPERATURE_C] = {"effects", "temperature_c", false},
    [K_GRID] = {"numerics", "grid", false},
    [K_GRID_GROWTH] = {"numerics", "grid_growth", false},
    [K_DOMAIN] = {"numerics", "domain_a0", false},
    [K_TOLERANCE] = {"numerics", "tolerance", false},
    [K_LINEAR_SOLVER] = {"numerics", "linear_solver", false},
    [K_TARGET_ERROR] = {"numerics", "target_error", false},
    [K_PERSSON_TABLE] = {"numerics", "persson_table", false},
};

typedef struct {
  vl_scene *scene;
  const char *path;
  vl_error *err;
  vl_status status;
  int line;               /* line being parsed (counted by our reader) */
  int err_line;           /* line of the error in status (0 if none) */
  const char *cursor;     /* reader position in the text */
  int key_line[K_COUNT];  /* where each key was set; 0 = not in the file */
  const char *failed_key; /* the key check_fail named (NULL: none) */
} parse_state;

/* Sets key id (of section) from value, or records why it cannot: returns 1
 * to go on, 0 to stop inih. */
typedef int (*section_fn)(parse_state *ps, key_id id, const char *section, const char *key,
                          const char *value);
static int scene_key(parse_state *, key_id, const char *, const char *, const char *);
static int materials_key(parse_state *, key_id, const char *, const char *, const char *);
static int contact_key(parse_state *, key_id, const char *, const char *, const char *);
static int sweep_key(parse_state *, key_id, const char *, const char *, const char *);
static int effects_key(parse_state *, key_id, const char *, const char *, const char *);
static int numerics_key(parse_state *, key_id, const char *, const char *, const char *);
static int seal_key(parse_state *, key_id, const char *, const char *, const char *);

static const struct {
  const char *name;
  section_fn set;
} sections[] = {
    {"scene", scene_key}, {"materials", materials_key}, {"contact", contact_key},
    {"sweep", sweep_key}, {"effects", effects_key},     {"numerics", numerics_key},
    {"seal", seal_key},
};

const char *vl_sweep_quantity_name(vl_sweep_quantity q) {
  switch (q) {
  case VL_SWEEP_V0: return "v0";
  case VL_SWEEP_V0_ETA: return "v0_eta";
  case VL_SWEEP_DEBORAH: return "deborah";
  }
  return "?";
}

/* Records "file:line: [section] key: why" (why = fmt with value) and
 * returns 0, which stops inih. */
static int fail(parse_state *ps, const char *section, const char *key, const char *fmt,
                const char *value) {
  char why[512];
  snprintf(why, sizeof why, fmt, value);
  vl_error_set(ps->err, "%s:%d: [%s] %s: %s", ps->path, ps->line, section, key, why);
  ps->status = VL_EINPUT;
  ps->err_line = ps->line;
  return 0;
}

/* A finite number and nothing else (trailing blanks allowed): "1cm", "nan",
 * "inf", "1e999" and "" are refused. */
static bool parse_double(const char *v, double *out) {
  char *end;
  errno = 0;
  double d = strtod(v, &end);
  while (*end == ' ' || *end == '\t')
    end++;
  if (end == v || *end != '\0' || errno == ERANGE || !isfinite(d)) return false;
  *out = d;
  return true;
}

static bool parse_size(const char *v, size_t *out) {
  char *end;
  errno = 0;
  long long d = strtoll(v, &end, 10);
  while (*end == ' ' || *end == '\t')
    end++;
  if (end == v || *end != '\0' || errno == ERANGE || d <= 0) return false;
  *out = (size_t)d;
  return true;
}

static bool parse_switch(const char *v, bool *out) {
  if (!strcmp(v, "on") || !strcmp(v, "true") || !strcmp(v, "yes") || !strcmp(v, "1")) {
    *out = true;
    return true;
  }
  if (!strcmp(v, "off") || !strcmp(v, "false") || !strcmp(v, "no") || !strcmp(v, "0")) {
    *out = false;
    return true;
  }
  return false;
}

/* 1 to max comma-separated numbers. Returns the count, or -1 for an empty
 * value, an empty item ("1,,2", "1,"), a bad number or more than max. */
static int parse_list(const char *v, double *out, int max) {
  int n = 0;
  for (const char *p = v;; n++) {
    size_t len = strcspn(p, ",");
    char tok[64];
    if (n >= max || len == 0 || len >= sizeof tok) return -1;
    memcpy(tok, p, len);
    tok[len] = '\0';
    const char *t = tok;
    while (*t == ' ' || *t == '\t')
      t++;
    if (!parse_double(t, &out[n])) return -1;
    if (p[len] == '\0') return n + 1;
    p += len + 1;
  }
}

/* Edit distance with transpositions (optimal string alignment): for "did
 * you mean" hints only. */
static size_t edit_distance(const char *a, const char *b) {
  return vl_edit_distance(a, strlen(a), b, strlen(b), true);
}

/* The hint for an unknown key: the same key in another section, else the
 * nearest key of this section (at most 2 edits). Empty when none fits. */
static void key_hint(const char *section, const char *key, char *hint, size_t size) {
  hint[0] = '\0';
  for (int k = 0; k < K_COUNT; k++) {
    if (!strcmp(keys[k].key, key)) {
      snprintf(hint, size, " (it belongs in [%s])", keys[k].section);
      return;
    }
  }
  size_t best = 3;
  for (int k = 0; k < K_COUNT; k++) {
    if (strcmp(keys[k].section, section)) continue;
    size_t d = edit_distance(key, keys[k].key);
    if (d < best) {
      best = d;
      snprintf(hint, size, " (did you mean '%s'?)", keys[k].key);
    }
  }
}

static void unknown_section(parse_state *ps, const char *section) {
  char hint[64] = "";
  for (size_t s = 0; s < sizeof sections / sizeof sections[0]; s++)
    if (edit_distance(section, sections[s].name) <= 2)
      snprintf(hint, sizeof hint, " (did you mean [%s]?)", sections[s].name);
  vl_error_set(ps->err,
               "%s:%d: unknown section [%s]%s (known: scene, materials, contact, "
               "sweep, effects, numerics, seal)",
               ps->path, ps->line, section, hint);
  ps->status = VL_EINPUT;
  ps->err_line = ps->line;
}

static int copy_name(parse_state *ps, const char *section, const char *key, char *dst,
                     const char *value) {
  if (!*value || strlen(value) >= VL_NAME_MAX)
    return fail(ps, section, key, "bad name '%s'", value);
  snprintf(dst, VL_NAME_MAX, "%s", value);
  return 1;
}

#define POSITIVE(field)                                                                            \
  do {                                                                                             \
    if (!parse_double(value, &sc->field) || !(sc->field > 0.0))                                    \
      return fail(ps, section, key, "expected a positive number, got '%s'", value);                \
    return 1;                                                                                      \
  } while (0)

static int scene_key(parse_state *ps, key_id id, const char *section, const char *key,
                     const char *value) {
  switch (id) {
  case K_TITLE: snprintf(ps->scene->title, sizeof ps->scene->title, "%s", value); return 1;
  default: return fail(ps, section, key, "unknown key%s", "");
  }
}

/* A comma-separated list runs one curve per fluid (e.g. a viscosity series). */
static int fluid_names(parse_state *ps, const char *section, const char *key, const char *value) {
  vl_scene *sc = ps->scene;
  char buf[VL_FLUIDS_MAX * VL_NAME_MAX];
  snprintf(buf, sizeof buf, "%s", value);
  sc->n_fluids = 0;
  char *save = NULL;
  for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
    while (*tok == ' ' || *tok == '\t')
      tok++;
    size_t len = strlen(tok);
    while (len && (tok[len - 1] == ' ' || tok[len - 1] == '\t'))
      tok[--len] = '\0';
    if (sc->n_fluids >= VL_FLUIDS_MAX)
      return fail(ps, section, key, "at most 8 fluids, got '%s'", value);
    if (!copy_name(ps, section, key, sc->fluids[sc->n_fluids], tok)) return 0;
    sc->n_fluids++;
  }
  if (sc->n_fluids == 0) return fail(ps, section, key, "bad name '%s'", value);
  snprintf(sc->fluid, sizeof sc->fluid, "%s", sc->fluids[0]);
  return 1;
}

static int materials_key(parse_state *ps, key_id id, const char *section, const char *key,
                         const char *value) {
  vl_scene *sc = ps->scene;
  switch (id) {
  case K_COMPOUND: return copy_name(ps, section, key, sc->compound, value);
  case K_SURFACE: return copy_name(ps, section, key, sc->surface, value);
  case K_FLUID_NAME: return fluid_names(ps, section, key, value);
  case K_ELASTIC_MODULUS:
    if (!strcmp(value, "relaxed"))
      sc->elastic = VL_ELASTIC_RELAXED;
    else if (!strcmp(value, "glassy"))
      sc->elastic = VL_ELASTIC_GLASSY;
    else if (parse_double(value, &sc->elastic_modulus_pa) && sc->elastic_modulus_pa > 0.0)
      sc->elastic = VL_ELASTIC_GIVEN;
    else
      return fail(ps, section, key, "expected relaxed, glassy or a modulus in Pa, got '%s'", value);
    return 1;
  default: return fail(ps, section, key, "unknown key%s", "");
  }
}

static int contact_key(parse_state *ps, key_id id, const char *section, const char *key,
                       const char *value) {
  vl_scene *sc = ps->scene;
  switch (id) {
  case K_GEOMETRY:
    if (!strcmp(value, "cylinder"))
      sc->geometry = VL_GEOMETRY_CYLINDER;
    else if (!strcmp(value, "ball"))
      sc->geometry = VL_GEOMETRY_BALL;
    else if (!strcmp(value, "ellipsoid"))
      sc->geometry = VL_GEOMETRY_ELLIPSOID;
    else
      return fail(ps, section, key, "expected cylinder, ball or ellipsoid, got '%s'", value);
    return 1;
  case K_RADIUS: POSITIVE(radius_m);
  case K_RADII: {
    double r[2];
    if (parse_list(value, r, 2) != 2 || !(r[0] > 0.0 && r[1] > 0.0))
      return fail(ps, section, key,
                  "expected 'Rx, Ry': two positive radii (m), along the sliding direction and "
                  "across it, got '%s'",
                  value);
    sc->radius_m = r[0], sc->radius_y_m = r[1];
    return 1;
  }
  case K_LOAD: POSITIVE(load_n_per_m);
  case K_LOAD_N: POSITIVE(load_n);
  case K_SIGMA_S:
    if (!parse_double(value, &sc->sigma_s_pa) || sc->sigma_s_pa < 0.0)
      return fail(ps, section, key, "expected a number >= 0, got '%s'", value);
    return 1;
  case K_MOVING:
    if (!strcmp(value, "rubber"))
      sc->moving = VL_MOVING_RUBBER;
    else if (!strcmp(value, "counterface"))
      sc->moving = VL_MOVING_COUNTERFACE;
    else
      return fail(ps, section, key, "expected rubber or counterface, got '%s'", value);
    return 1;
  case K_PROFILE_FILE:
  case K_PRESSURE_PROFILE_FILE: {
    /* relative to the scene file's folder */
    char *dst = id == K_PROFILE_FILE ? sc->profile_file : sc->pressure_file;
    size_t size = id == K_PROFILE_FILE ? sizeof sc->profile_file : sizeof sc->pressure_file;
    const char *slash = strrchr(ps->path, '/');
    int dir = value[0] != '/' && slash ? (int)(slash - ps->path + 1) : 0;
    if (!*value || strlen(value) + (size_t)dir >= size)
      return fail(ps, section, key, "bad file name '%s'", value);
    snprintf(dst, size, "%.*s%s", dir, ps->path, value);
    if (id == K_PROFILE_FILE)
      sc->profile_line = ps->line;
    else
      sc->pressure_line = ps->line;
    return 1;
  }
  case K_PROFILE:
    if (!strcmp(value, "cylinder") || !strcmp(value, "lip"))
      sc->lip = value[0] == 'l';
    else
      return fail(ps, section, key, "expected cylinder or lip, got '%s'", value);
    return 1;
  case K_LIP_TIP_RADIUS: POSITIVE(lip_tip_radius_m);
  case K_LIP_OIL_ANGLE:
  case K_LIP_AIR_ANGLE: {
    double *a = id == K_LIP_OIL_ANGLE ? &sc->lip_oil_angle_deg : &sc->lip_air_angle_deg;
    if (!parse_double(value, a) || !(*a > 0.0 && *a < 90.0))
      return fail(ps, section, key, "expected a flank angle in (0, 90) degrees, got '%s'", value);
    return 1;
  }
  case K_SEALED_PRESSURE:
    if (!parse_double(value, &sc->sealed_pressure_pa) || sc->sealed_pressure_pa < 0.0)
      return fail(ps, section, key, "expected a pressure >= 0 (Pa), got '%s'", value);
    return 1;
  default: return fail(ps, section, key, "unknown key%s", "");
  }
}

static int sweep_key(parse_state *ps, key_id id, const char *section, const char *key,
                     const char *value) {
  vl_scene *sc = ps->scene;
  switch (id) {
  case K_QUANTITY:
    if (!strcmp(value, "v0"))
      sc->quantity = VL_SWEEP_V0;
    else if (!strcmp(value, "v0_eta"))
      sc->quantity = VL_SWEEP_V0_ETA;
    else if (!strcmp(value, "deborah"))
      sc->quantity = VL_SWEEP_DEBORAH;
    else
      return fail(ps, section, key, "expected v0, v0_eta or deborah, got '%s'", value);
    return 1;
  case K_FROM: POSITIVE(from);
  case K_TO: POSITIVE(to);
  case K_POINTS:
    if (!parse_size(value, &sc->points) || sc->points > 100000)
      return fail(ps, section, key, "expected a whole number in [1, 100000], got '%s'", value);
    return 1;
  case K_DIRECTION:
    if (!strcmp(value, "up"))
      sc->direction = VL_DIRECTION_UP;
    else if (!strcmp(value, "down"))
      sc->direction = VL_DIRECTION_DOWN;
    else if (!strcmp(value, "both"))
      sc->direction = VL_DIRECTION_BOTH;
    else
      return fail(ps, section, key, "expected up, down or both, got '%s'", value);
    return 1;
  case K_FIELDS_AT: {
    int n = parse_list(value, sc->fields_at, VL_FIELDS_AT_MAX);
    if (n < 0)
      return fail(ps, section, key, "expected 1 to 32 comma-separated numbers, got '%s'", value);
    for (int i = 0; i < n; i++)
      if (!(sc->fields_at[i] > 0.0))
        return fail(ps, section, key, "values must be positive: '%s'", value);
    sc->n_fields_at = (size_t)n;
    return 1;
  }
  default: return fail(ps, section, key, "unknown key%s", "");
  }
}

static int effects_key(parse_state *ps, key_id id, const char *section, const char *key,
                       const char *value) {
  vl_scene *sc = ps->scene;
  switch (id) {
  case K_VISCOELASTIC:
  case K_ROUGHNESS:
  case K_FLUID:
  case K_SOLID_SHEAR:
  case K_VISCOUS_FLATTENING:
  case K_TEMPERATURE: {
    bool *sw = id == K_VISCOELASTIC         ? &sc->effects.viscoelastic
               : id == K_ROUGHNESS          ? &sc->effects.roughness
               : id == K_FLUID              ? &sc->effects.fluid
               : id == K_SOLID_SHEAR        ? &sc->effects.solid_shear
               : id == K_VISCOUS_FLATTENING ? &sc->effects.viscous_flattening
                                            : &sc->effects.temperature;
    if (!parse_switch(value, sw))
      return fail(ps, section, key, "expected on or off, got '%s'", value);
    return 1;
  }
  case K_FLOW_FACTORS:
    if (vl_flow_factors_parse(value, &sc->effects.flow_factors, NULL) != VL_OK)
      return fail(ps, section, key, "expected smooth, patir-cheng or persson-emt, got '%s'", value);
    return 1;
  case K_FILM_CUTOFF:
    if (!parse_double(value, &sc->effects.film_cutoff_m) ||
        !(sc->effects.film_cutoff_m > 0.0 && sc->effects.film_cutoff_m <= VL_FILM_CUTOFF_MAX_M))
      return fail(ps, section, key, "expected a film cut-off in (0, 1e-6] m, got '%s'", value);
    return 1;
  case K_TEMPERATURE_C:
    if (!parse_double(value, &sc->effects.temperature_c) || sc->effects.temperature_c < -273.15)
      return fail(ps, section, key, "expected a temperature in C, got '%s'", value);
    return 1;
  default: return fail(ps, section, key, "unknown key%s", "");
  }
}

/* A seal's strokes and the rod (docs/MODEL.md section 12). */
static int seal_key(parse_state *ps, key_id id, const char *section, const char *key,
                    const char *value) {
  vl_scene *sc = ps->scene;
  switch (id) {
  case K_STROKE:
    if (!strcmp(value, "out"))
      sc->stroke = VL_STROKE_OUT;
    else if (!strcmp(value, "in"))
      sc->stroke = VL_STROKE_IN;
    else if (!strcmp(value, "both"))
      sc->stroke = VL_STROKE_BOTH;
    else
      return fail(ps, section, key, "expected out, in or both, got '%s'", value);
    return 1;
  case K_ROD_DIAMETER: POSITIVE(rod_diameter_m);
  case K_STROKE_LENGTH: POSITIVE(stroke_length_m);
  default: return fail(ps, section, key, "unknown key%s", "");
  }
}

/* The limits are the solver's (contact.h). */
static int numerics_key(parse_state *ps, key_id id, const char *section, const char *key,
                        const char *value) {
  vl_scene *sc = ps->scene;
  switch (id) {
  case K_GRID:
    if (!parse_size(value, &sc->grid) || sc->grid < VL_GRID_MIN || sc->grid > VL_GRID_GRADED_MAX)
      return fail(ps, section, key,
                  "expected a whole number in [" VL_STR(VL_GRID_MIN) ", " VL_STR(
                      VL_GRID_GRADED_MAX) "], got '%s'",
                  value);
    return 1;
  case K_GRID_GROWTH:
    if (!parse_double(value, &sc->grid_growth) ||
        !(sc->grid_growth >= 1.0 && sc->grid_growth <= VL_GRID_GROWTH_MAX)) {
      char why[96];
      snprintf(why, sizeof why, "expected a ratio in [1, %g] (1: uniform grid), got '%%s'",
               VL_GRID_GROWTH_MAX);
      return fail(ps, section, key, why, value);
    }
    return 1;
  case K_DOMAIN: {
    double d[2];
    /* the cylinder axis x = 0 lies in every contact: a domain without it
     * cannot hold the solution */
    if (parse_list(value, d, 2) != 2 || !(d[0] < 0.0 && d[1] > 0.0))
      return fail(ps, section, key,
                  "expected 'start, end' with start < 0 < end (in units of a0), got '%s'", value);
    sc->domain_min_a0 = d[0];
    sc->domain_max_a0 = d[1];
    return 1;
  }
  case K_TOLERANCE:
    if (!parse_double(value, &sc->tolerance) || !(sc->tolerance > 0.0 && sc->tolerance < 1.0))
      return fail(ps, section, key, "expected a number in (0, 1), got '%s'", value);
    return 1;
  case K_TARGET_ERROR:
    if (!parse_double(value, &sc->target_error) ||
        !(sc->target_error >= 1e-6 && sc->target_error <= 0.5))
      return fail(ps, section, key, "expected a relative error in [1e-6, 0.5], got '%s'", value);
    return 1;
  case K_LINEAR_SOLVER:
    if (!strcmp(value, "lapack"))
      sc->linear_solver = VL_LINSOL_LAPACK;
    else if (!strcmp(value, "sundials"))
      sc->linear_solver = VL_LINSOL_SUNDIALS;
    else if (!strcmp(value, "schur"))
      sc->linear_solver = VL_LINSOL_SCHUR;
    else
      return fail(ps, section, key, "expected schur, lapack or sundials, got '%s'", value);
    return 1;
  case K_PERSSON_TABLE:
    if (!parse_size(value, &sc->persson_table) || sc->persson_table < 64 ||
        sc->persson_table > 100000)
      return fail(ps, section, key, "expected a whole number in [64, 100000], got '%s'", value);
    return 1;
  default: return fail(ps, section, key, "unknown key%s", "");
  }
}

/* One key = value: inih calls this for every assignment, in file order.
 * Finds the section and the key, refuses a key given twice, and hands the
 * value to the section's handler. */
static int handler(void *user, const char *section, const char *key, const char *value) {
  parse_state *ps = user;
  if (ps->status != VL_OK) return 0; /* inih goes on after an error: keep the first */

  if (!section[0]) {
    vl_error_set(ps->err, "%s:%d: key '%s' before any [section]", ps->path, ps->line, key);
    ps->status = VL_EINPUT;
    ps->err_line = ps->line;
    return 0;
  }
  int sec = -1;
  for (size_t s = 0; s < sizeof sections / sizeof sections[0]; s++)
    if (!strcmp(section, sections[s].name)) sec = (int)s;
  if (sec < 0) { /* normally caught by the reader at the header line */
    unknown_section(ps, section);
    return 0;
  }
  int id = -1;
  for (int k = 0; k < K_COUNT; k++)
    if (!strcmp(keys[k].section, section) && !strcmp(keys[k].key, key)) id = k;
  if (id < 0) {
    char hint[128];
    key_hint(section, key, hint, sizeof hint);
    return fail(ps, section, key, "unknown key%s", hint);
  }
  if (ps->key_line[id]) {
    char why[64];
    snprintf(why, sizeof why, "given twice (first on line %d)", ps->key_line[id]);
    return fail(ps, section, key, "%s", why);
  }
  ps->key_line[id] = ps->line;
  return sections[sec].set(ps, (key_id)id, section, key, value);
}

/* inih reader over a string that counts lines, so the handler knows where
 * it is. It hands inih each line trimmed, which matters twice:
 * - leading blanks would make inih take an indented line for the
 *   continuation of the previous value (its multi-line mode, compiled in);
 * - inih cuts lines longer than its buffer (num) into pieces and parses the
 *   rest as a new line: comment lines of any length are passed as empty,
 *   any other line too long is an error at its line. */
static char *reader(char *str, int num, void *stream) {
  parse_state *ps = stream;
  if (ps->status != VL_OK || !*ps->cursor) return NULL;
  const char *text = ps->cursor;
  size_t len = strcspn(text, "\n");
  ps->cursor += len + (text[len] == '\n');
  ps->line++;
  size_t b = 0, e = len;
  while (b < e && (text[b] == ' ' || text[b] == '\t'))
    b++;
  while (e > b && isspace((unsigned char)text[e - 1]))
    e--;
  if (b < e && (text[b] == ';' || text[b] == '#')) e = b;
  /* a section header is checked here, at its own line, as inih tells the
   * handler nothing of a section without keys */
  const char *close = b < e && text[b] == '[' ? memchr(text + b, ']', e - b) : NULL;
  if (close) {
    size_t n = (size_t)(close - (text + b)) - 1;
    bool known = false;
    for (size_t s = 0; s < sizeof sections / sizeof sections[0]; s++)
      if (strlen(sections[s].name) == n && !strncmp(text + b + 1, sections[s].name, n))
        known = true;
    if (!known) {
      char name[64];
      snprintf(name, sizeof name, "%.*s", (int)(n < 60 ? n : 60), text + b + 1);
      unknown_section(ps, name);
      return NULL;
    }
  }
  if (e - b + 2 > (size_t)num) {
    vl_error_set(ps->err, "%s:%d: line too long (at most %d characters)", ps->path, ps->line,
                 num - 2);
    ps->status = VL_EINPUT;
    ps->err_line = ps->line;
    return NULL;
  }
  memcpy(str, text + b, e - b);
  str[e - b] = '\n';
  str[e - b + 1] = '\0';
  return str;
}

/* A contact configuration's numerics as a scene's [numerics] keys. */
static void numerics_from(vl_scene *sc, const vl_contact_config *cfg) {
  sc->grid = cfg->grid, sc->grid_growth = cfg->grid_growth, sc->tolerance = cfg->tolerance;
  sc->domain_min_a0 = cfg->x_min_a0, sc->domain_max_a0 = cfg->x_max_a0;
}

void vl_scene_defaults(vl_scene *sc) {
  memset(sc, 0, sizeof *sc);
  sc->effects.viscoelastic = true;
  sc->elastic = VL_ELASTIC_RELAXED;
  sc->effects.temperature_c = NAN;
  sc->effects.film_cutoff_m = VL_FILM_CUTOFF_DEFAULT_M;
  vl_contact_config cfg; /* the solver's numerics of a dry contact */
  vl_contact_config_defaults(&cfg);
  numerics_from(sc, &cfg);
  sc->linear_solver = cfg.linear_solver;
  sc->persson_table = 0;
  sc->auto_numerics = true;
  sc->target_error = VL_TARGET_ERROR_DEFAULT;
}

void vl_scene_default_numerics(vl_scene *sc) {
  vl_contact_config cfg;
  vl_contact_config_defaults(&cfg);
  vl_contact_numerics_defaults(sc->effects.roughness, sc->effects.fluid, &cfg);
  numerics_from(sc, &cfg);
}

/* An error about key id found after the whole file is read: it names the
 * line where the key was set. */
static vl_status check_fail(parse_state *ps, key_id id, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static vl_status check_fail(parse_state *ps, key_id id, const char *fmt, ...) {
  char why[600];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(why, sizeof why, fmt, ap);
  va_end(ap);
  ps->failed_key = keys[id].key;
  if (ps->key_line[id])
    vl_error_set(ps->err, "%s:%d: [%s] %s: %s", ps->path, ps->key_line[id], keys[id].section,
                 keys[id].key, why);
  else if (ps->path[0])
    vl_error_set(ps->err, "%s: [%s] %s: %s", ps->path, keys[id].section, keys[id].key, why);
  else /* a scene built in code: no file to name */
    vl_error_set(ps->err, "[%s] %s: %s", keys[id].section, keys[id].key, why);
  return VL_EINPUT;
}

/* "missing required key" for key id. */
static vl_status missing(parse_state *ps, key_id id, const char *why) {
  vl_error_set(ps->err, "%s: missing required key [%s] %s%s", ps->path, keys[id].section,
               keys[id].key, why);
  return VL_EINPUT;
}

/* The keys of the rigid body's geometry: a cylinder takes radius_m and
 * load_n_per_m, a ball radius_m and load_n, an ellipsoid radii_m and
 * load_n; any other combination names the key that does not fit. */
static vl_status geometry_check(parse_state *ps) {
  vl_scene *sc = ps->scene;
  int g = sc->geometry;
  const char *name = vl_geometry_name(g);
  key_id radius = g == VL_GEOMETRY_ELLIPSOID ? K_RADII : K_RADIUS;
  key_id load = g == VL_GEOMETRY_CYLINDER ? K_LOAD : K_LOAD_N;
  key_id wrong_radius = g == VL_GEOMETRY_ELLIPSOID ? K_RADIUS : K_RADII;
  key_id wrong_load = g == VL_GEOMETRY_CYLINDER ? K_LOAD_N : K_LOAD;
  if (ps->key_line[wrong_radius])
    return check_fail(ps, wrong_radius, "[contact] geometry = %s takes %s%s instead", name,
                      keys[radius].key, g == VL_GEOMETRY_ELLIPSOID ? " = Rx, Ry" : " (one radius)");
  if (ps->key_line[wrong_load])
    return check_fail(
        ps, wrong_load, "[contact] geometry = %s takes %s%s instead", name, keys[load].key,
        g == VL_GEOMETRY_CYLINDER ? " (N per metre of its length)" : " (the total load, N)");
  if (g == VL_GEOMETRY_CYLINDER) return VL_OK; /* its radius and load: check_profile */
  if (!ps->key_line[radius])
    return missing(ps, radius, g == VL_GEOMETRY_CYLINDER ? "" : " (geometry = ball or ellipsoid)");
  if (!ps->key_line[load])
    return missing(ps, load, g == VL_GEOMETRY_CYLINDER ? "" : " (geometry = ball or ellipsoid)");
  if (g == VL_GEOMETRY_BALL) sc->radius_y_m = sc->radius_m;
  return VL_OK;
}

/* What a point contact (a ball, an ellipsoid) does not take yet: an
 * ellipsoid is dry and smooth, a ball may be rough and lubricated, without
 * viscous flattening (docs/POINT_CONTACT.md). The first key that asks for
 * more is named. */
static vl_status point_contact_check(parse_state *ps) {
  vl_scene *sc = ps->scene;
  struct {
    key_id id;
    bool on;
    const char *why;
  } no[] = {
      {K_FLUID, sc->effects.fluid && sc->geometry != VL_GEOMETRY_BALL,
       "a lubricated ellipsoid is not available yet (a ball only)"},
      {K_ROUGHNESS, sc->effects.roughness && sc->geometry != VL_GEOMETRY_BALL,
       "a rough ellipsoid is not available yet (a ball only)"},
      {K_VISCOUS_FLATTENING, sc->effects.viscous_flattening,
       "viscous flattening is the line contact's only (docs/POINT_CONTACT.md section 10)"},
      {K_MOVING, sc->moving != VL_MOVING_RUBBER, "a ball rolls or slides on a moving rubber only"},
      {K_SEALED_PRESSURE, ps->key_line[K_SEALED_PRESSURE] != 0, "applies to a cylinder only"},
      {K_PROFILE_FILE, ps->key_line[K_PROFILE_FILE] != 0, "applies to a cylinder only"},
      {K_PROFILE, ps->key_line[K_PROFILE] != 0, "applies to a cylinder only"},
      {K_DIRECTION, sc->direction != VL_DIRECTION_UP,
       "a ball's sweep runs upward (its points are independent solves, no branches to follow)"},
      {K_PRESSURE_PROFILE_FILE, ps->key_line[K_PRESSURE_PROFILE_FILE] != 0,
       "applies to a cylinder only"},
      {K_STROKE, ps->key_line[K_STROKE] != 0, "applies to a cylinder only"},
      {K_GRID, ps->key_line[K_GRID] != 0,
       "a line contact's cells: a ball's are planned per point (docs/POINT_CONTACT.md)"},
      {K_GRID_GROWTH, ps->key_line[K_GRID_GROWTH] != 0, "applies to a cylinder only"},
      {K_DOMAIN, ps->key_line[K_DOMAIN] != 0,
       "a line contact's domain: a ball's is planned per point (docs/POINT_CONTACT.md)"},
      {K_LINEAR_SOLVER, ps->key_line[K_LINEAR_SOLVER] != 0, "applies to a cylinder only"},
      {K_PERSSON_TABLE, ps->key_line[K_PERSSON_TABLE] != 0 && !sc->effects.roughness,
       "applies to a rough contact only"},
  };
  for (size_t k = 0; k < sizeof no / sizeof no[0]; k++)
    if (no[k].on)
      return check_fail(ps, no[k].id, "not with [contact] geometry = %s: %s",
                        vl_geometry_name(sc->geometry), no[k].why);
  if (!ps->key_line[K_TOLERANCE]) sc->tolerance = VL_BALL_TOLERANCE;
  sc->auto_numerics = true;
  return VL_OK;
}

/* An imposed static pressure (pressure_profile_file): it stands for the
 * rubber's shape and preload, so no radius_m, load_n_per_m or profile; the
 * rubber at rest (moving = counterface). */
static vl_status check_pressure_profile(parse_state *ps) {
  static const key_id excluded[4] = {K_RADIUS, K_LOAD, K_PROFILE, K_PROFILE_FILE};
  for (int k = 0; k < 4; k++)
    if (ps->key_line[excluded[k]])
      return check_fail(ps, excluded[k],
                        "not with pressure_profile_file (line %d): the imposed pressure gives "
                        "the load and the contact's shape",
                        ps->key_line[K_PRESSURE_PROFILE_FILE]);
  if (ps->scene->moving != VL_MOVING_COUNTERFACE)
    return check_fail(ps, K_PRESSURE_PROFILE_FILE,
                      "needs [contact] moving = counterface (a static pressure: the rubber at "
                      "rest, the counter-surface moving)");
  return VL_OK;
}

/* The profile keys: the cylinder's radius_m, or a lip with all three of
 * its keys and no radius_m (its tip radius is lip_tip_radius_m), or a
 * table (profile_file, radius_m for the scales). */
static vl_status check_profile(parse_state *ps) {
  vl_scene *sc = ps->scene;
  static const key_id lip_keys[3] = {K_LIP_TIP_RADIUS, K_LIP_OIL_ANGLE, K_LIP_AIR_ANGLE};
  for (int k = 0; k < 3; k++) {
    if (sc->lip && !ps->key_line[lip_keys[k]])
      return check_fail(ps, K_PROFILE, "lip needs [contact] %s", keys[lip_keys[k]].key);
    if (!sc->lip && ps->key_line[lip_keys[k]])
      return check_fail(ps, lip_keys[k], "applies to [contact] profile = lip only");
  }
  if (sc->lip && ps->key_line[K_RADIUS])
    return check_fail(ps, K_RADIUS,
                      "not with profile = lip (line %d): the lip's tip radius is "
                      "lip_tip_radius_m; remove radius_m",
                      ps->key_line[K_PROFILE]);
  if (sc->lip && ps->key_line[K_PROFILE_FILE])
    return check_fail(ps, K_PROFILE_FILE,
                      "not with profile = lip (line %d): give the lip or the table",
                      ps->key_line[K_PROFILE]);
  if (ps->key_line[K_PRESSURE_PROFILE_FILE]) return check_pressure_profile(ps);
  static const key_id needed[2] = {K_RADIUS, K_LOAD};
  for (int k = 0; k < 2; k++)
    if (!ps->key_line[needed[k]] && (k == 1 || !sc->lip)) {
      vl_error_set(ps->err, "%s: missing required key [contact] %s", ps->path, keys[needed[k]].key);
      return VL_EINPUT;
    }
  return VL_OK;
}

/* Requirements between keys, checked once the whole file is read. */
static vl_status scene_check(parse_state *ps) {
  vl_scene *sc = ps->scene;
  for (int k = 0; k < K_COUNT; k++) {
    if (keys[k].required && !ps->key_line[k]) {
      vl_error_set(ps->err, "%s: missing required key [%s] %s", ps->path, keys[k].section,
                   keys[k].key);
      return VL_EINPUT;
    }
  }
  vl_status gs = geometry_check(ps);
  if (gs == VL_OK && sc->geometry == VL_GEOMETRY_CYLINDER) gs = check_profile(ps);
  if (gs != VL_OK) return gs;
  /* the numerics the file does not set follow from its effects */
  vl_scene d = *sc;
  vl_scene_default_numerics(&d);
  if (!ps->key_line[K_DOMAIN])
    sc->domain_min_a0 = d.domain_min_a0, sc->domain_max_a0 = d.domain_max_a0;
  if (!ps->key_line[K_GRID]) sc->grid = d.grid;
  if (!ps->key_line[K_GRID_GROWTH]) sc->grid_growth = d.grid_growth;
  if (!ps->key_line[K_TOLERANCE]) sc->tolerance = d.tolerance;
  /* a scene that lays out its own cells or domain keeps them */
  sc->auto_numerics =
      !ps->key_line[K_GRID] && !ps->key_line[K_GRID_GROWTH] && !ps->key_line[K_DOMAIN];
  if (!(sc->grid_growth > 1.0) && sc->grid > VL_GRID_UNIFORM_MAX)
    return check_fail(ps, K_GRID,
                      "a uniform grid takes at most %d cells (its dense matrices grow "
                      "as the square), got %zu; set grid_growth > 1 for a graded inlet",
                      VL_GRID_UNIFORM_MAX, sc->grid);
  if (sc->grid_growth > 1.0 && !sc->effects.roughness)
    return check_fail(ps, K_GRID_GROWTH,
                      "a graded grid needs [effects] roughness = on (smooth "
                      "contacts use a uniform grid: remove the key or set 1)");
  if (sc->effects.roughness && !sc->surface[0])
    return check_fail(ps, K_ROUGHNESS, "roughness = on needs [materials] surface");
  if (sc->effects.fluid && !sc->fluid[0])
    return check_fail(ps, K_FLUID, "fluid = on needs [materials] fluid");
  if (sc->quantity == VL_SWEEP_V0_ETA && !sc->effects.fluid)
    return check_fail(ps, K_QUANTITY, "v0_eta needs [effects] fluid = on");
  if (sc->quantity == VL_SWEEP_DEBORAH && !sc->effects.viscoelastic)
    return check_fail(ps, K_QUANTITY,
                      "deborah needs [effects] viscoelastic = on (line %d sets it off)",
                      ps->key_line[K_VISCOELASTIC]);
  if (sc->sealed_pressure_pa > 0.0 && !sc->effects.fluid)
    return check_fail(ps, K_SEALED_PRESSURE, "a sealed pressure needs [effects] fluid = on");
  if ((ps->key_line[K_ROD_DIAMETER] || ps->key_line[K_STROKE_LENGTH]) && !ps->key_line[K_STROKE])
    return check_fail(ps, ps->key_line[K_ROD_DIAMETER] ? K_ROD_DIAMETER : K_STROKE_LENGTH,
                      "needs [seal] stroke");
  if (!ps->key_line[K_ROD_DIAMETER] != !ps->key_line[K_STROKE_LENGTH])
    return check_fail(ps, ps->key_line[K_ROD_DIAMETER] ? K_ROD_DIAMETER : K_STROKE_LENGTH,
                      "the volumes per cycle need both rod_diameter_m and stroke_length_m");
  if (sc->direction == VL_DIRECTION_BOTH && sc->stroke == VL_STROKE_BOTH)
    return check_fail(ps, K_DIRECTION,
                      "direction = both with [seal] stroke = both would make four curves: "
                      "sweep one stroke both ways, or both strokes one way");
  if (sc->direction != VL_DIRECTION_UP && sc->points < 2)
    return check_fail(ps, K_DIRECTION, "a direction needs points >= 2");
  if (sc->stroke != VL_STROKE_NONE && !sc->effects.fluid)
    return check_fail(ps, K_STROKE, "a seal's strokes need [effects] fluid = on");
  if (sc->stroke != VL_STROKE_NONE && sc->moving != VL_MOVING_COUNTERFACE)
    return check_fail(ps, K_STROKE,
                      "a seal's strokes need [contact] moving = counterface (the seal at rest, "
                      "the rod moving)");
  /* v0 tau/a0 measures the macroscopic memory, which a rubber at rest has not */
  if (sc->quantity == VL_SWEEP_DEBORAH && sc->moving == VL_MOVING_COUNTERFACE)
    return check_fail(ps, K_QUANTITY,
                      "deborah needs [contact] moving = rubber (line %d: with a moving "
                      "counter-surface the rubber deforms statically, without memory)",
                      ps->key_line[K_MOVING]);
  if (ps->key_line[K_ELASTIC_MODULUS] && sc->effects.viscoelastic)
    return check_fail(ps, K_ELASTIC_MODULUS,
                      "applies to [effects] viscoelastic = off only (the rubber is viscoelastic)");
  /* solid shear without the key: the stored pair's law (vl_simulation_create),
   * else the seed's 1 MPa */
  if (sc->effects.solid_shear && !ps->key_line[K_SIGMA_S]) sc->sigma_s_pa = VL_SCENE_SIGMA_S_PA;
  if (sc->effects.solid_shear && !(sc->sigma_s_pa > 0.0))
    return check_fail(ps, K_SOLID_SHEAR, "solid_shear = on needs [contact] sigma_s_pa > 0");
  if (!sc->effects.solid_shear) sc->sigma_s_pa = 0.0;
  sc->sigma_s_given = ps->key_line[K_SIGMA_S] != 0;
  if (sc->effects.flow_factors != VL_FLOW_FACTORS_SMOOTH && !sc->effects.roughness)
    return check_fail(ps, K_FLOW_FACTORS, "%s needs [effects] roughness = on",
                      vl_flow_factors_name(sc->effects.flow_factors));
  /* a range given high to low is the same set of speeds: the sweep runs
   * upward unless [sweep] direction says otherwise, from the boundary
   * regime, where its first solve is the easiest (docs/NUMERICS.md
   * section 8) */
  if (sc->points > 1 && sc->to < sc->from) {
    double high = sc->from;
    sc->from = sc->to, sc->to = high;
  }
  if (sc->points > 1 && !(sc->to > sc->from))
    return check_fail(ps, K_TO, "to (%g) must differ from from (%g) when points > 1", sc->to,
                      sc->from);
  for (size_t i = 0; i < sc->n_fields_at; i++) {
    if (sc->fields_at[i] < sc->from * (1 - 1e-9) || sc->fields_at[i] > sc->to * (1 + 1e-9))
      return check_fail(ps, K_FIELDS_AT, "%g lies outside [from, to] = [%g, %g]", sc->fields_at[i],
                        sc->from, sc->to);
  }
  /* viscous flattening reduces the roughness by the film's pressure
   * (seed Appendix C): it needs both */
  if (sc->effects.viscous_flattening && !sc->effects.roughness)
    return check_fail(ps, K_VISCOUS_FLATTENING, "on needs [effects] roughness = on");
  if (sc->effects.viscous_flattening && !sc->effects.fluid)
    return check_fail(ps, K_VISCOUS_FLATTENING, "on needs [effects] fluid = on");
  /* the temperature effect shifts the compound (WLF) and the fluid (its
   * viscosity law) to one stated temperature: there is no default */
  if (!ps->key_line[K_FLOW_FACTORS] && sc->effects.roughness && sc->effects.fluid)
    sc->effects.flow_factors = VL_SCENE_ROUGH_FLOW_FACTORS;
  if (ps->key_line[K_FILM_CUTOFF] && sc->effects.flow_factors != VL_FLOW_FACTORS_PERSSON_EMT)
    return check_fail(ps, K_FILM_CUTOFF, "applies to [effects] flow_factors = persson-emt only");
  if (sc->effects.temperature && !ps->key_line[K_TEMPERATURE_C])
    return check_fail(ps, K_TEMPERATURE, "on needs [effects] temperature_c (Celsius)");
  if (!sc->effects.temperature && ps->key_line[K_TEMPERATURE_C])
    return check_fail(ps, K_TEMPERATURE_C,
                      "applies to [effects] temperature = on only (the materials are taken "
                      "at their reference temperatures)");
  if (sc->geometry != VL_GEOMETRY_CYLINDER) return point_contact_check(ps);
  return VL_OK;
}

vl_status vl_scene_check_point_contact(vl_scene *sc, const char **failed_key, vl_error *err) {
  parse_state ps = {.scene = sc, .path = sc->path, .err = err, .status = VL_OK};
  *failed_key = NULL;
  if (sc->geometry == VL_GEOMETRY_CYLINDER) return VL_OK;
  vl_status st = point_contact_check(&ps);
  *failed_key = ps.failed_key;
  return st;
}

/* Messages quote the file's text and go to a terminal: a control byte there
 * (an escape sequence, a carriage return) could rewrite what the user sees,
 * so each becomes '?', as in the CSV reader's messages. */
static vl_status printable(vl_status st, vl_error *err) {
  if (st != VL_OK && err)
    for (char *c = err->msg; *c; c++)
      if ((unsigned char)*c < 0x20 || *c == 0x7f) *c = '?';
  return st;
}

static vl_status scene_parse(const char *text, const char *path, vl_scene *scene, vl_error *err) {
  vl_scene_defaults(scene);
  snprintf(scene->path, sizeof scene->path, "%s", path);
  parse_state ps = {.scene = scene, .path = path, .err = err, .status = VL_OK, .cursor = text};
  int rc = ini_parse_stream(reader, &ps, handler, &ps);
  /* rc is the first line inih found wrong, ours included: a syntax error
   * before the line of our error comes first */
  if (rc > 0 && (ps.status == VL_OK || rc < ps.err_line)) {
    vl_error_set(err, "%s:%d: syntax error (expected [section], key = value or a comment)", path,
                 rc);
    return VL_EINPUT;
  }
  if (ps.status != VL_OK) return ps.status;
  if (rc != 0) {
    vl_error_set(err, "%s: cannot parse (inih error %d)", path, rc);
    return VL_EINPUT;
  }
  return scene_check(&ps);
}

vl_status vl_scene_parse(const char *text, const char *path, vl_scene *scene, vl_error *err) {
  return printable(scene_parse(text, path, scene, err), err);
}

vl_status vl_scene_load(const char *path, vl_scene *scene, vl_error *err) {
  FILE *f = fopen(path, "rb");
  if (!f) {
    vl_error_set(err, "%s: cannot open scene file: %s", path, strerror(errno));
    return VL_EIO;
  }
  size_t cap = 1 << 14, len = 0;
  char *text = malloc(cap);
  vl_status st = VL_OK;
  if (!text) {
    st = VL_ENOMEM;
    goto done;
  }
  size_t got;
  while ((got = fread(text + len, 1, cap - len - 1, f)) > 0) {
    len += got;
    if (len + 1 == cap) {
      if (cap > (1u << 24)) {
        vl_error_set(err, "%s: scene file too large", path);
        st = VL_EINPUT;
        goto done;
      }
      char *t = realloc(text, cap *= 2);
      if (!t) {
        st = VL_ENOMEM;
        goto done;
      }
      text = t;
    }
  }
  if (ferror(f)) { /* a directory, for one */
    vl_error_set(err, "%s: cannot read scene file: %s", path, strerror(errno));
    st = VL_EIO;
    goto done;
  }
  text[len] = '\0';
  if ((st = vl_text_refuse_nul(text, len, path, err)) != VL_OK) goto done;
  st = scene_parse(text, path, scene, err);
done:
  if (st == VL_ENOMEM) vl_error_set(err, "%s: out of memory", path);
  free(text);
  fclose(f);
  return printable(st, err);
}

vl_status vl_scene_as_seal(vl_scene *sc, vl_error *err) {
  if (sc->moving != VL_MOVING_COUNTERFACE || !sc->effects.fluid) {
    vl_error_set(err,
                 "%s: a seal needs [contact] moving = counterface (the seal at rest, the rod "
                 "moving) and [effects] fluid = on%s",
                 sc->path, sc->moving != VL_MOVING_COUNTERFACE ? " (moving is rubber)" : "");
    return VL_EINPUT;
  }
  sc->stroke = VL_STROKE_BOTH;
  return VL_OK;
}
