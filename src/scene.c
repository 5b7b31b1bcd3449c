/* Scene files: INI parsed by libinih, with line numbers for every error. */
#include "viscolube/scene.h"

#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  vl_scene *scene;
  const char *path;
  vl_error *err;
  vl_status status;
  int line;              /* line being parsed (counted by our reader) */
  const char *cursor;    /* reader position in the text */
  unsigned seen;         /* bit set of required keys seen */
  int fields_line;
} parse_state;

enum {
  SEEN_COMPOUND = 1u << 0,
  SEEN_RADIUS = 1u << 1,
  SEEN_LOAD = 1u << 2,
  SEEN_FROM = 1u << 3,
  SEEN_TO = 1u << 4,
  SEEN_POINTS = 1u << 5,
  SEEN_QUANTITY = 1u << 6,
};

const char *vl_sweep_quantity_name(vl_sweep_quantity q) {
  switch (q) {
  case VL_SWEEP_V0: return "v0";
  case VL_SWEEP_V0_ETA: return "v0_eta";
  case VL_SWEEP_DEBORAH: return "deborah";
  }
  return "?";
}


static int fail(parse_state *ps, const char *section, const char *key, const char *fmt,
                const char *value) {
  char why[512];
  snprintf(why, sizeof why, fmt, value);
  vl_error_set(ps->err, "%s:%d: [%s] %s: %s", ps->path, ps->line, section, key, why);
  ps->status = VL_EINPUT;
  return 0; /* stops inih */
}

static bool parse_double(const char *v, double *out) {
  char *end;
  errno = 0;
  double d = strtod(v, &end);
  while (*end == ' ' || *end == '\t') end++;
  if (end == v || *end != '\0' || errno == ERANGE || !isfinite(d)) return false;
  *out = d;
  return true;
}

static bool parse_size(const char *v, size_t *out) {
  char *end;
  errno = 0;
  long long d = strtoll(v, &end, 10);
  while (*end == ' ' || *end == '\t') end++;
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

/* Up to max comma-separated numbers. Returns the count or -1. */
static int parse_list(const char *v, double *out, int max) {
  char buf[2048];
  snprintf(buf, sizeof buf, "%s", v);
  int n = 0;
  for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
    while (*tok == ' ' || *tok == '\t') tok++;
    if (n >= max || !parse_double(tok, &out[n])) return -1;
    n++;
  }
  return n;
}

static int copy_name(parse_state *ps, const char *section, const char *key, char *dst,
                     const char *value) {
  if (!*value || strlen(value) >= VL_NAME_MAX) return fail(ps, section, key, "bad name '%s'", value);
  snprintf(dst, VL_NAME_MAX, "%s", value);
  return 1;
}

#define POSITIVE(field, bit)                                                                       \
  do {                                                                                             \
    if (!parse_double(value, &sc->field) || !(sc->field > 0.0))                                    \
      return fail(ps, section, key, "expected a positive number, got '%s'", value);               \
    ps->seen |= (bit);                                                                             \
    return 1;                                                                                      \
  } while (0)

static int handler(void *user, const char *section, const char *key, const char *value) {
  parse_state *ps = user;
  vl_scene *sc = ps->scene;
  if (ps->status != VL_OK) return 0; /* inih goes on after an error: keep the first */
  if (!strcmp(section, "scene")) {
    if (!strcmp(key, "title")) {
      snprintf(sc->title, sizeof sc->title, "%s", value);
      return 1;
    }
  } else if (!strcmp(section, "materials")) {
    if (!strcmp(key, "compound")) {
      ps->seen |= SEEN_COMPOUND;
      return copy_name(ps, section, key, sc->compound, value);
    }
    if (!strcmp(key, "surface")) return copy_name(ps, section, key, sc->surface, value);
    if (!strcmp(key, "fluid")) return copy_name(ps, section, key, sc->fluid, value);
    if (!strcmp(key, "elastic_modulus")) {
      if (!strcmp(value, "relaxed")) sc->elastic = VL_ELASTIC_RELAXED;
      else if (!strcmp(value, "glassy")) sc->elastic = VL_ELASTIC_GLASSY;
      else if (parse_double(value, &sc->elastic_modulus_pa) && sc->elastic_modulus_pa > 0.0)
        sc->elastic = VL_ELASTIC_GIVEN;
      else
        return fail(ps, section, key, "expected relaxed, glassy or a modulus in Pa, got '%s'",
                    value);
      return 1;
    }
  } else if (!strcmp(section, "contact")) {
    if (!strcmp(key, "radius_m")) POSITIVE(radius_m, SEEN_RADIUS);
    if (!strcmp(key, "load_n_per_m")) POSITIVE(load_n_per_m, SEEN_LOAD);
    if (!strcmp(key, "sigma_s_pa")) {
      if (!parse_double(value, &sc->sigma_s_pa) || sc->sigma_s_pa < 0.0)
        return fail(ps, section, key, "expected a number >= 0, got '%s'", value);
      return 1;
    }
  } else if (!strcmp(section, "sweep")) {
    if (!strcmp(key, "quantity")) {
      ps->seen |= SEEN_QUANTITY;
      if (!strcmp(value, "v0")) sc->quantity = VL_SWEEP_V0;
      else if (!strcmp(value, "v0_eta")) sc->quantity = VL_SWEEP_V0_ETA;
      else if (!strcmp(value, "deborah")) sc->quantity = VL_SWEEP_DEBORAH;
      else return fail(ps, section, key, "expected v0, v0_eta or deborah, got '%s'", value);
      return 1;
    }
    if (!strcmp(key, "from")) POSITIVE(from, SEEN_FROM);
    if (!strcmp(key, "to")) POSITIVE(to, SEEN_TO);
    if (!strcmp(key, "points")) {
      if (!parse_size(value, &sc->points) || sc->points > 100000)
        return fail(ps, section, key, "expected a whole number in [1, 100000], got '%s'", value);
      ps->seen |= SEEN_POINTS;
      return 1;
    }
    if (!strcmp(key, "fields_at")) {
      int n = parse_list(value, sc->fields_at, VL_FIELDS_AT_MAX);
      if (n < 0) return fail(ps, section, key, "expected up to 32 comma-separated numbers, got '%s'", value);
      for (int i = 0; i < n; i++)
        if (!(sc->fields_at[i] > 0.0)) return fail(ps, section, key, "values must be positive: '%s'", value);
      sc->n_fields_at = (size_t)n;
      ps->fields_line = ps->line;
      return 1;
    }
  } else if (!strcmp(section, "effects")) {
    bool *sw = NULL;
    if (!strcmp(key, "viscoelastic")) sw = &sc->effects.viscoelastic;
    else if (!strcmp(key, "roughness")) sw = &sc->effects.roughness;
    else if (!strcmp(key, "fluid")) sw = &sc->effects.fluid;
    else if (!strcmp(key, "solid_shear")) sw = &sc->effects.solid_shear;
    else if (!strcmp(key, "viscous_flattening")) sw = &sc->effects.viscous_flattening;
    else if (!strcmp(key, "temperature")) sw = &sc->effects.temperature;
    if (sw) {
      if (!parse_switch(value, sw)) return fail(ps, section, key, "expected on or off, got '%s'", value);
      return 1;
    }
    if (!strcmp(key, "flow_factors")) {
      if (vl_flow_factors_parse(value, &sc->effects.flow_factors, NULL) != VL_OK)
        return fail(ps, section, key, "expected smooth or patir-cheng, got '%s'", value);
      return 1;
    }
    if (!strcmp(key, "temperature_c")) {
      if (!parse_double(value, &sc->effects.temperature_c) || sc->effects.temperature_c < -273.15)
        return fail(ps, section, key, "expected a temperature in C, got '%s'", value);
      return 1;
    }
  } else if (!strcmp(section, "numerics")) {
    if (!strcmp(key, "grid")) {
      if (!parse_size(value, &sc->grid) || sc->grid < 16 || sc->grid > 8192)
        return fail(ps, section, key, "expected a whole number in [16, 8192], got '%s'", value);
      return 1;
    }
    if (!strcmp(key, "domain_a0")) {
      double d[2];
      if (parse_list(value, d, 2) != 2 || !(d[1] > d[0]))
        return fail(ps, section, key, "expected two increasing numbers 'start, end', got '%s'", value);
      sc->domain_min_a0 = d[0];
      sc->domain_max_a0 = d[1];
      return 1;
    }
    if (!strcmp(key, "tolerance")) {
      if (!parse_double(value, &sc->tolerance) || !(sc->tolerance > 0.0 && sc->tolerance < 1.0))
        return fail(ps, section, key, "expected a number in (0, 1), got '%s'", value);
      return 1;
    }
    if (!strcmp(key, "linear_solver")) {
      if (!strcmp(value, "lapack")) sc->linear_solver = VL_LINSOL_LAPACK;
      else if (!strcmp(value, "sundials")) sc->linear_solver = VL_LINSOL_SUNDIALS;
      else return fail(ps, section, key, "expected lapack or sundials, got '%s'", value);
      return 1;
    }
    if (!strcmp(key, "persson_table")) {
      if (!parse_size(value, &sc->persson_table) || sc->persson_table < 64 || sc->persson_table > 100000)
        return fail(ps, section, key, "expected a whole number in [64, 100000], got '%s'", value);
      return 1;
    }
  } else {
    char what[300];
    snprintf(what, sizeof what, "unknown section [%s] (known: scene, materials, contact, sweep, "
             "effects, numerics)", section);
    vl_error_set(ps->err, "%s:%d: %s", ps->path, ps->line, what);
    ps->status = VL_EINPUT;
    return 0;
  }
  return fail(ps, section, key, "unknown key%s", "");
}

/* inih reader over a string that counts lines, so the handler knows where it is. */
static char *reader(char *str, int num, void *stream) {
  parse_state *ps = stream;
  if (!*ps->cursor) return NULL;
  int i = 0;
  while (i < num - 1 && ps->cursor[i] && ps->cursor[i] != '\n') i++;
  if (ps->cursor[i] == '\n' && i < num - 1) i++;
  memcpy(str, ps->cursor, (size_t)i);
  str[i] = '\0';
  ps->cursor += i;
  ps->line++;
  return str;
}

static void scene_defaults(vl_scene *sc) {
  memset(sc, 0, sizeof *sc);
  sc->effects.viscoelastic = true;
  sc->elastic = VL_ELASTIC_RELAXED;
  sc->effects.temperature_c = NAN;
  sc->grid = 512;
  /* symmetric about the axis: an elastic contact then has exactly zero
   * rolling friction on the grid, so small viscoelastic shifts are resolved */
  sc->domain_min_a0 = -1.5;
  sc->domain_max_a0 = 1.5;
  sc->tolerance = 1e-9;
  sc->linear_solver = VL_LINSOL_LAPACK;
  sc->persson_table = 0;
}

/* Requirements between keys, checked once the whole file is read. */
static vl_status scene_check(parse_state *ps) {
  vl_scene *sc = ps->scene;
  struct { unsigned bit; const char *what; } req[] = {
      {SEEN_COMPOUND, "[materials] compound"}, {SEEN_RADIUS, "[contact] radius_m"},
      {SEEN_LOAD, "[contact] load_n_per_m"},   {SEEN_QUANTITY, "[sweep] quantity"},
      {SEEN_FROM, "[sweep] from"},             {SEEN_TO, "[sweep] to"},
      {SEEN_POINTS, "[sweep] points"}};
  for (size_t i = 0; i < sizeof req / sizeof req[0]; i++) {
    if (!(ps->seen & req[i].bit)) {
      vl_error_set(ps->err, "%s: missing required key %s", ps->path, req[i].what);
      return VL_EINPUT;
    }
  }
  if (sc->effects.roughness && !sc->surface[0]) {
    vl_error_set(ps->err, "%s: [effects] roughness = on needs [materials] surface", ps->path);
    return VL_EINPUT;
  }
  if (sc->effects.fluid && !sc->fluid[0]) {
    vl_error_set(ps->err, "%s: [effects] fluid = on needs [materials] fluid", ps->path);
    return VL_EINPUT;
  }
  if (sc->quantity == VL_SWEEP_V0_ETA && !sc->effects.fluid) {
    vl_error_set(ps->err, "%s: [sweep] quantity = v0_eta needs [effects] fluid = on", ps->path);
    return VL_EINPUT;
  }
  if (sc->quantity == VL_SWEEP_DEBORAH && !sc->effects.viscoelastic) {
    vl_error_set(ps->err, "%s: [sweep] quantity = deborah needs [effects] viscoelastic = on",
                 ps->path);
    return VL_EINPUT;
  }
  if (sc->effects.solid_shear && !(sc->sigma_s_pa > 0.0)) {
    vl_error_set(ps->err, "%s: [effects] solid_shear = on needs [contact] sigma_s_pa > 0",
                 ps->path);
    return VL_EINPUT;
  }
  if (!sc->effects.solid_shear) sc->sigma_s_pa = 0.0;
  if (sc->effects.flow_factors != VL_FLOW_FACTORS_SMOOTH && !sc->effects.roughness) {
    vl_error_set(ps->err, "%s: [effects] flow_factors = %s needs roughness = on", ps->path,
                 vl_flow_factors_name(sc->effects.flow_factors));
    return VL_EINPUT;
  }
  if (sc->points > 1 && !(sc->to > sc->from)) {
    vl_error_set(ps->err, "%s: [sweep] to (%g) must exceed from (%g)", ps->path, sc->to, sc->from);
    return VL_EINPUT;
  }
  for (size_t i = 0; i < sc->n_fields_at; i++) {
    if (sc->fields_at[i] < sc->from * (1 - 1e-9) || sc->fields_at[i] > sc->to * (1 + 1e-9)) {
      vl_error_set(ps->err, "%s:%d: [sweep] fields_at: %g lies outside [from, to] = [%g, %g]",
                   ps->path, ps->fields_line, sc->fields_at[i], sc->from, sc->to);
      return VL_EINPUT;
    }
  }
  /* Effects of later issues: refuse rather than silently ignore them. */
  if (sc->effects.viscous_flattening || sc->effects.temperature) {
    vl_error_set(ps->err, "%s: [effects] %s = on is not available in this version", ps->path,
                 sc->effects.viscous_flattening ? "viscous_flattening" : "temperature");
    return VL_EINPUT;
  }
  return VL_OK;
}

vl_status vl_scene_parse(const char *text, const char *path, vl_scene *scene, vl_error *err) {
  scene_defaults(scene);
  snprintf(scene->path, sizeof scene->path, "%s", path);
  parse_state ps = {.scene = scene, .path = path, .err = err, .status = VL_OK, .cursor = text};
  int rc = ini_parse_stream(reader, &ps, handler, &ps);
  if (ps.status != VL_OK) return ps.status;
  if (rc != 0) {
    vl_error_set(err, "%s:%d: syntax error (expected [section] or key = value)", path, rc);
    return VL_EINPUT;
  }
  return scene_check(&ps);
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
  text[len] = '\0';
  if (memchr(text, '\0', len)) {
    vl_error_set(err, "%s: not a text file (contains a NUL byte)", path);
    st = VL_EINPUT;
    goto done;
  }
  st = vl_scene_parse(text, path, scene, err);
done:
  if (st == VL_ENOMEM) vl_error_set(err, "%s: out of memory", path);
  free(text);
  fclose(f);
  return st;
}
