/* Study files (study.h): the [study] section read here, line by line; the
 * rest of the file is a scene's defaults, parsed by the scene parser for
 * every task with the task's factors added as the [materials], [contact]
 * and [effects] keys they stand for. The [study] lines are emptied, not
 * removed, so the scene parser's messages name the study file's lines. */
#include "viscolube/study.h"
#include "study_private.h"

#include "viscolube/simulation.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "slurp.h"

enum { F_COMPOUNDS, F_SURFACES, F_FLUIDS, F_LOADS, F_RADII, F_TEMPS, F_CASES, F_TITLE, F_COUNT };
static const char *const study_keys[F_COUNT] = {"compounds",     "surfaces", "fluids",
                                                "loads_n_per_m", "radii_m",  "temperatures_c",
                                                "cases",         "title"};

/* A list of one factor: names or numbers. */
typedef struct {
  size_t n;
  char (*names)[VL_NAME_MAX];
  double *values;
} factor_list;

struct vl_study {
  char path[1024];
  char title[200];
  char *text;       /* the file as read */
  char *scene_text; /* the file with the [study] lines emptied (their line
                     * breaks kept, so the lines keep their numbers) */
  uint64_t fingerprint;
  size_t n_tasks;
  vl_study_task *tasks;
  int key_line[F_COUNT];
  char *values[F_COUNT]; /* the [study] values (cases: the rows, '\n'-separated) */
  int *case_lines;       /* line of each row of cases */
  size_t n_case_lines;
  bool has_temperature; /* tasks carry temperatures */
  /* the rigid body: [contact] geometry of the file (vl_geometry) and its
   * line; a point contact's loads are total forces, [study] loads_n (kept
   * in the slot of F_LOADS, loads_total set) */
  int geometry, geometry_line;
  bool loads_total;
  const char **materials[3];
  size_t n_materials[3];
};

/* The name of field f's key as the file gave it (loads_n for total loads). */
static const char *key_name(const vl_study *s, int f) {
  return f == F_LOADS && s->loads_total ? "loads_n" : study_keys[f];
}

/* ---- small parsers ------------------------------------------------------ */

static char *trim(char *s) {
  while (*s == ' ' || *s == '\t')
    s++;
  size_t n = strlen(s);
  while (n && isspace((unsigned char)s[n - 1]))
    s[--n] = '\0';
  return s;
}

/* A finite number and nothing else. */
static bool parse_number(const char *v, double *out) {
  char *end;
  errno = 0;
  double d = strtod(v, &end);
  if (end == v || *end != '\0' || errno == ERANGE || !isfinite(d)) return false;
  *out = d;
  return true;
}

static vl_status fail_at(vl_study *s, vl_error *err, int line, const char *key, const char *fmt,
                         ...) __attribute__((format(printf, 5, 6)));
static vl_status fail_at(vl_study *s, vl_error *err, int line, const char *key, const char *fmt,
                         ...) {
  char why[700];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(why, sizeof why, fmt, ap);
  va_end(ap);
  vl_error_set(err, "%s:%d: [study] %s: %s", s->path, line, key, why);
  return VL_EINPUT;
}

/* One item of a list or a row: a material name ("-" is none when
 * may_be_none) or a number with its range. */
static vl_status check_name(vl_study *s, int line, const char *key, const char *item,
                            bool may_be_none, vl_error *err) {
  if (may_be_none && !strcmp(item, "-")) return VL_OK;
  vl_error why;
  if (strlen(item) >= VL_NAME_MAX || vl_db_check_name(item, &why) != VL_OK)
    return fail_at(s, err, line, key, "bad material name '%s'", item);
  return VL_OK;
}

static vl_status check_number(vl_study *s, int line, const char *key, const char *item, int field,
                              double *out, vl_error *err) {
  if (!parse_number(item, out))
    return fail_at(s, err, line, key, "expected a number, got '%s'", item);
  if (field == F_TEMPS ? *out < -273.15 : !(*out > 0.0))
    return fail_at(s, err, line, key, "%s, got '%s'",
                   field == F_TEMPS ? "expected a temperature in C" : "expected a positive number",
                   item);
  return VL_OK;
}

/* Splits value at commas into l (names or numbers by field), refusing
 * empty items and repeats. */
static vl_status parse_factor(vl_study *s, int field, factor_list *l, vl_error *err) {
  const char *key = key_name(s, field);
  int line = s->key_line[field];
  bool names = field <= F_FLUIDS;
  size_t cap = 1;
  for (const char *p = s->values[field]; *p; p++)
    cap += *p == ',';
  l->n = 0;
  l->names = names ? calloc(cap, sizeof *l->names) : NULL;
  l->values = names ? NULL : calloc(cap, sizeof *l->values);
  char *copy = strdup(s->values[field]);
  if (!copy || (names ? !l->names : !l->values)) {
    free(copy);
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  vl_status st = VL_OK;
  char *p = copy;
  for (char *comma; st == VL_OK; p = comma + 1) {
    comma = strchr(p, ',');
    if (comma) *comma = '\0';
    char *item = trim(p);
    if (!*item) {
      st = fail_at(s, err, line, key, "empty item in '%s'", s->values[field]);
    } else if (names) {
      st = check_name(s, line, key, item, false, err);
      for (size_t k = 0; st == VL_OK && k < l->n; k++)
        if (!strcmp(l->names[k], item)) st = fail_at(s, err, line, key, "'%s' given twice", item);
      if (st == VL_OK) snprintf(l->names[l->n++], VL_NAME_MAX, "%s", item);
    } else {
      st = check_number(s, line, key, item, field, &l->values[l->n], err);
      for (size_t k = 0; st == VL_OK && k < l->n; k++)
        if (l->values[k] == l->values[l->n])
          st = fail_at(s, err, line, key, "%s given twice", item);
      if (st == VL_OK) l->n++;
    }
    if (!comma) break;
  }
  free(copy);
  return st;
}

/* ---- the [study] section -------------------------------------------------- */

/* Records key = value of [study] at line (a key given twice, an unknown
 * one: errors). */
static vl_status study_key(vl_study *s, int line, const char *key, const char *value,
                           vl_error *err) {
  int id = -1;
  for (int k = 0; k < F_COUNT; k++)
    if (!strcmp(key, study_keys[k])) id = k;
  bool total = !strcmp(key, "loads_n"); /* a point contact's: in the loads' slot */
  if (total) id = F_LOADS;
  if (id < 0)
    return fail_at(s, err, line, key,
                   "unknown key (known: title, compounds, surfaces, fluids, loads_n_per_m, "
                   "loads_n, radii_m, temperatures_c, cases)");
  if (s->key_line[id] && id == F_LOADS && total != s->loads_total)
    return fail_at(s, err, line, key, "give loads_n or loads_n_per_m, not both (line %d)",
                   s->key_line[id]);
  if (s->key_line[id])
    return fail_at(s, err, line, key, "given twice (first on line %d)", s->key_line[id]);
  if (id == F_LOADS) s->loads_total = total;
  s->key_line[id] = line;
  if (id != F_CASES && !*value) return fail_at(s, err, line, key, "empty value");
  if (!(s->values[id] = strdup(value))) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  return VL_OK;
}

/* Appends a row of cases (its own line, indented under `cases =`). */
static vl_status case_row(vl_study *s, int line, const char *row, vl_error *err) {
  size_t old = strlen(s->values[F_CASES]);
  char *v = realloc(s->values[F_CASES], old + strlen(row) + 2);
  int *lines = realloc(s->case_lines, (s->n_case_lines + 1) * sizeof *lines);
  if (v) s->values[F_CASES] = v;
  if (lines) s->case_lines = lines;
  if (!v || !lines) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  sprintf(v + old, "%s%s", old ? "\n" : "", row);
  s->case_lines[s->n_case_lines++] = line;
  return VL_OK;
}

/* Keys of the scene sections that a study sets itself: a study may not
 * give them (the factors would be given twice). */
static vl_status forbidden_key(vl_study *s, int line, const char *section, const char *key,
                               vl_error *err) {
  const char *why = NULL;
  if (!strcmp(section, "materials"))
    why = "a study names its materials in [study] compounds, surfaces and fluids (or cases)";
  else if (!strcmp(section, "scene"))
    why = "a study's title is [study] title";
  else if (!strcmp(section, "contact") && !strcmp(key, "radius_m"))
    why = "set by [study] radii_m (or cases; an ellipsoid's radii: [contact] radii_m = Rx, Ry)";
  else if (!strcmp(section, "contact") && !strcmp(key, "load_n_per_m"))
    why = "set by [study] loads_n_per_m (or cases)";
  else if (!strcmp(section, "contact") && !strcmp(key, "load_n"))
    why = "set by [study] loads_n (or cases)";
  if (!why) return VL_OK;
  vl_error_set(err, "%s:%d: [%s] %s: %s", s->path, line, section, key, why);
  return VL_EINPUT;
}

/* [contact] geometry = VALUE at line (an inline comment cut): the rigid
 * body every task shares, which decides the study's load and radius keys. */
static vl_status geometry_key(vl_study *s, int line, char *value, vl_error *err) {
  value[strcspn(value, ";#")] = '\0';
  value = trim(value);
  static const char *const names[] = {"cylinder", "ball", "ellipsoid"};
  for (int g = 0; g < 3; g++)
    if (!strcmp(value, names[g])) {
      s->geometry = g, s->geometry_line = line;
      return VL_OK;
    }
  vl_error_set(err, "%s:%d: [contact] geometry: expected cylinder, ball or ellipsoid, got '%s'",
               s->path, line, value);
  return VL_EINPUT;
}

/* Reads the file line by line: [study] keys into s (and emptied in
 * scene_text), keys of other sections checked by forbidden_key and the
 * lines of [effects] temperature keys noted in *temp_line. */
static vl_status split_sections(vl_study *s, int *temp_line, vl_error *err) {
  char section[64] = "";
  int line = 0;
  bool in_cases = false;
  vl_status st = VL_OK;
  char *out = s->scene_text;
  for (const char *p = s->text; *p && st == VL_OK;) {
    size_t len = strcspn(p, "\n");
    const char *next = p + len + (p[len] == '\n');
    line++;
    char buf[8192];
    if (len >= sizeof buf) {
      vl_error_set(err, "%s:%d: line too long (at most %zu characters)", s->path, line,
                   sizeof buf - 1);
      return VL_EINPUT;
    }
    snprintf(buf, sizeof buf, "%.*s", (int)len, p);
    bool indented = buf[0] == ' ' || buf[0] == '\t';
    char *t = trim(buf);
    bool blank = !*t || *t == ';' || *t == '#';
    if (!blank && *t == '[' && strchr(t, ']')) {
      *strchr(t, ']') = '\0';
      snprintf(section, sizeof section, "%s", t + 1);
      in_cases = false;
    } else if (!blank && !strcmp(section, "study") && indented && in_cases) {
      st = case_row(s, line, t, err);
    } else if (!blank && !strcmp(section, "study")) {
      char *eq = strchr(t, '=');
      if (!eq) {
        vl_error_set(err, "%s:%d: [study]: expected key = value, got '%s'", s->path, line, t);
        return VL_EINPUT;
      }
      *eq = '\0';
      char *key = trim(t), *value = trim(eq + 1);
      st = study_key(s, line, key, !strcmp(key, "cases") ? "" : value, err);
      in_cases = !strcmp(key, "cases");
      if (st == VL_OK && in_cases && *value) st = case_row(s, line, value, err);
    } else if (!blank && strchr(t, '=')) {
      char *value = strchr(t, '=') + 1;
      value[-1] = '\0';
      const char *key = trim(t);
      st = forbidden_key(s, line, section, key, err);
      if (st == VL_OK && !strcmp(section, "contact") && !strcmp(key, "geometry"))
        st = geometry_key(s, line, value, err);
      if (!strcmp(section, "effects") &&
          (!strcmp(key, "temperature_c") || !strcmp(key, "temperature")))
        *temp_line = *temp_line ? *temp_line : line;
    }
    /* a [study] line is emptied: the scene parser reads only the defaults */
    size_t keep = !strcmp(section, "study") ? 0 : len;
    memcpy(out, p, keep);
    out += keep;
    if (p[len] == '\n') *out++ = '\n';
    p = next;
  }
  *out = '\0';
  return st;
}

/* The load and radius keys fit the study's geometry: a cylinder's loads
 * per unit length, a point contact's total loads; an ellipsoid's radii
 * are its [contact] radii_m, not a factor. */
static vl_status geometry_fit(vl_study *s, vl_error *err) {
  bool point = s->geometry != VL_GEOMETRY_CYLINDER;
  const char *name = vl_geometry_name(s->geometry);
  if (s->key_line[F_LOADS] && point && !s->loads_total)
    return fail_at(s, err, s->key_line[F_LOADS], "loads_n_per_m",
                   "[contact] geometry = %s (line %d) takes loads_n, total loads (N)", name,
                   s->geometry_line);
  if (s->key_line[F_LOADS] && !point && s->loads_total)
    return fail_at(s, err, s->key_line[F_LOADS], "loads_n",
                   "total loads are a ball's or an ellipsoid's ([contact] geometry); a cylinder "
                   "takes loads_n_per_m (N/m)");
  if (s->key_line[F_RADII] && s->geometry == VL_GEOMETRY_ELLIPSOID)
    return fail_at(s, err, s->key_line[F_RADII], "radii_m",
                   "not with [contact] geometry = ellipsoid (line %d): its radii are [contact] "
                   "radii_m = Rx, Ry, the same for every task",
                   s->geometry_line);
  return VL_OK;
}

/* ---- tasks ---------------------------------------------------------------- */

/* Task id's factors; load is the geometry's (per unit length, or total),
 * radius NAN for an ellipsoid (its radii: the scene's, check_scenes). */
static void set_task(const vl_study *s, vl_study_task *t, size_t id, const char *c, const char *sf,
                     const char *fl, double load, double radius, double temp, int line) {
  bool point = s->geometry != VL_GEOMETRY_CYLINDER;
  *t = (vl_study_task){.id = id,
                       .geometry = s->geometry,
                       .load_n_per_m = point ? 0.0 : load,
                       .load_n = point ? load : 0.0,
                       .radius_m = radius,
                       .radius_y_m = s->geometry == VL_GEOMETRY_BALL ? radius : 0.0,
                       .temperature_c = temp,
                       .line = line};
  snprintf(t->compound, sizeof t->compound, "%s", c);
  snprintf(t->surface, sizeof t->surface, "%s", sf);
  snprintf(t->fluid, sizeof t->fluid, "%s", fl);
}

static vl_status alloc_tasks(vl_study *s, size_t n, vl_error *err) {
  s->n_tasks = n;
  if (!(s->tasks = calloc(n ? n : 1, sizeof *s->tasks))) {
    vl_error_set(err, "out of memory for %zu tasks", n);
    return VL_ENOMEM;
  }
  return VL_OK;
}

/* The full grid of the lists, compounds outermost. */
static vl_status grid_tasks(vl_study *s, vl_error *err) {
  static const int required[] = {F_COMPOUNDS, F_LOADS, F_RADII};
  bool ellipsoid = s->geometry == VL_GEOMETRY_ELLIPSOID; /* its radii: [contact] radii_m */
  for (size_t k = 0; k < (ellipsoid ? 2u : 3u); k++)
    if (!s->key_line[required[k]]) {
      bool total = required[k] == F_LOADS && s->geometry != VL_GEOMETRY_CYLINDER;
      vl_error_set(err, "%s: missing required key [study] %s (or give cases)", s->path,
                   total ? "loads_n" : study_keys[required[k]]);
      return VL_EINPUT;
    }
  factor_list l[F_TEMPS + 1] = {{0}};
  vl_status st = VL_OK;
  double total = 1;
  for (int f = F_COMPOUNDS; f <= F_TEMPS && st == VL_OK; f++) {
    if (s->key_line[f]) st = parse_factor(s, f, &l[f], err);
    total *= l[f].n ? (double)l[f].n : 1.0;
  }
  if (st == VL_OK && total > VL_STUDY_TASKS_MAX) {
    vl_error_set(err, "%s: [study]: the grid has %.0f tasks, more than %d", s->path, total,
                 VL_STUDY_TASKS_MAX);
    st = VL_EINPUT;
  }
  if (st == VL_OK) st = alloc_tasks(s, (size_t)total, err);
  s->has_temperature = l[F_TEMPS].n > 0;
  size_t n[F_TEMPS + 1], i[F_TEMPS + 1] = {0};
  for (int f = 0; f <= F_TEMPS; f++)
    n[f] = l[f].n ? l[f].n : 1;
  for (size_t id = 0; st == VL_OK && id < s->n_tasks; id++) {
    size_t r = id;
    for (int f = F_TEMPS; f >= 0; f--)
      i[f] = r % n[f], r /= n[f];
    set_task(s, &s->tasks[id], id, l[F_COMPOUNDS].names[i[F_COMPOUNDS]],
             l[F_SURFACES].n ? l[F_SURFACES].names[i[F_SURFACES]] : "",
             l[F_FLUIDS].n ? l[F_FLUIDS].names[i[F_FLUIDS]] : "", l[F_LOADS].values[i[F_LOADS]],
             l[F_RADII].n ? l[F_RADII].values[i[F_RADII]] : NAN,
             l[F_TEMPS].n ? l[F_TEMPS].values[i[F_TEMPS]] : NAN, 0);
  }
  for (int f = 0; f <= F_TEMPS; f++) {
    free(l[f].names);
    free(l[f].values);
  }
  return st;
}

static bool same_factors(const vl_study_task *a, const vl_study_task *b) {
  bool same_t =
      a->temperature_c == b->temperature_c || (isnan(a->temperature_c) && isnan(b->temperature_c));
  bool same_r = a->radius_m == b->radius_m || (isnan(a->radius_m) && isnan(b->radius_m));
  return !strcmp(a->compound, b->compound) && !strcmp(a->surface, b->surface) &&
         !strcmp(a->fluid, b->fluid) && a->load_n_per_m == b->load_n_per_m &&
         a->load_n == b->load_n && same_r && same_t;
}

/* What a row of cases holds for the study's geometry. */
static const char *row_form(const vl_study *s) {
  switch (s->geometry) {
  case VL_GEOMETRY_BALL: return "COMPOUND SURFACE FLUID LOAD_N RADIUS_M [TEMPERATURE_C]";
  case VL_GEOMETRY_ELLIPSOID:
    return "COMPOUND SURFACE FLUID LOAD_N [TEMPERATURE_C] (an ellipsoid's radii: [contact] "
           "radii_m)";
  default: return "COMPOUND SURFACE FLUID LOAD_N_PER_M RADIUS_M [TEMPERATURE_C]";
  }
}

/* One row of cases: COMPOUND SURFACE FLUID LOAD RADIUS [TEMPERATURE]
 * (an ellipsoid's without RADIUS), separated by blanks or commas. */
static vl_status case_task(vl_study *s, size_t id, char *row, vl_error *err) {
  int line = s->case_lines[id];
  char *item[7];
  size_t n = 0;
  char *save = NULL;
  for (char *tok = strtok_r(row, " \t,", &save); tok; tok = strtok_r(NULL, " \t,", &save))
    if (n < 7)
      item[n++] = tok;
    else
      n++;
  size_t base = s->geometry == VL_GEOMETRY_ELLIPSOID ? 4 : 5; /* items without a temperature */
  if (n != base && n != base + 1)
    return fail_at(s, err, line, "cases",
                   "a row is %s ('-' for no surface or fluid), got %zu items", row_form(s), n);
  if (id > 0 && (n == base + 1) != s->has_temperature)
    return fail_at(s, err, line, "cases", "every row gives a temperature, or none does");
  s->has_temperature = n == base + 1;
  double v[3] = {0, NAN, NAN}; /* load, radius, temperature */
  vl_status st = check_name(s, line, "cases", item[0], false, err);
  for (int k = 1; st == VL_OK && k < 3; k++)
    st = check_name(s, line, "cases", item[k], true, err);
  for (size_t k = 3; st == VL_OK && k < n; k++) {
    bool temp = k == base;
    size_t slot = temp ? 2 : k - 3;
    st = check_number(s, line, "cases", item[k], temp ? F_TEMPS : F_LOADS, &v[slot], err);
  }
  if (st != VL_OK) return st;
  set_task(s, &s->tasks[id], id, item[0], strcmp(item[1], "-") ? item[1] : "",
           strcmp(item[2], "-") ? item[2] : "", v[0], v[1], v[2], line);
  for (size_t k = 0; k < id; k++)
    if (same_factors(&s->tasks[k], &s->tasks[id]))
      return fail_at(s, err, line, "cases", "the same task as line %d", s->tasks[k].line);
  return VL_OK;
}

static vl_status cases_tasks(vl_study *s, vl_error *err) {
  for (int f = F_COMPOUNDS; f <= F_TEMPS; f++)
    if (s->key_line[f])
      return fail_at(s, err, s->key_line[f], key_name(s, f),
                     "give the factors as lists or as cases (line %d), not both",
                     s->key_line[F_CASES]);
  if (!s->n_case_lines)
    return fail_at(s, err, s->key_line[F_CASES], "cases", "no rows (one per indented line)");
  vl_status st = alloc_tasks(s, s->n_case_lines, err);
  char *save = NULL, *row = strtok_r(s->values[F_CASES], "\n", &save);
  for (size_t id = 0; st == VL_OK && row; id++, row = strtok_r(NULL, "\n", &save))
    st = case_task(s, id, row, err);
  return st;
}

/* ---- the study ------------------------------------------------------------ */

/* The distinct materials of the tasks, in order of first use. */
static vl_status collect_materials(vl_study *s, vl_error *err) {
  for (int kind = 0; kind < 3; kind++) {
    s->materials[kind] = calloc(s->n_tasks + 1, sizeof *s->materials[kind]);
    if (!s->materials[kind]) {
      vl_error_set(err, "out of memory");
      return VL_ENOMEM;
    }
    for (size_t i = 0; i < s->n_tasks; i++) {
      const vl_study_task *t = &s->tasks[i];
      const char *name = kind == 0 ? t->compound : kind == 1 ? t->surface : t->fluid;
      bool seen = !*name;
      for (size_t k = 0; !seen && k < s->n_materials[kind]; k++)
        seen = !strcmp(s->materials[kind][k], name);
      if (!seen) s->materials[kind][s->n_materials[kind]++] = name;
    }
  }
  return VL_OK;
}

static uint64_t fnv1a(const char *text) {
  uint64_t h = 14695981039346656037ull;
  for (const unsigned char *p = (const unsigned char *)text; *p; p++)
    h = (h ^ *p) * 1099511628211ull;
  return h;
}

/* Every task's scene is parsed once here: a study that loads runs. An
 * ellipsoid's radii are taken from it into the tasks (for the factor
 * columns). */
static vl_status check_scenes(vl_study *s, vl_error *err) {
  vl_scene *scene = malloc(sizeof *scene);
  if (!scene) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  vl_status st = VL_OK;
  for (size_t i = 0; st == VL_OK && i < s->n_tasks; i++) {
    st = vl_study_scene(s, i, scene, err);
    if (st == VL_OK && s->geometry == VL_GEOMETRY_ELLIPSOID)
      s->tasks[i].radius_m = scene->radius_m, s->tasks[i].radius_y_m = scene->radius_y_m;
    /* with the lists every task has the same defaults; a row of cases can
     * be wrong alone (no surface for a rough contact) */
    if (st != VL_OK && s->key_line[F_CASES])
      vl_error_prefix(err, "%s:%d: [study] cases (task %zu)", s->path, s->tasks[i].line, i);
  }
  free(scene);
  return st;
}

static vl_status study_parse(vl_study *s, vl_error *err) {
  int temp_line = 0;
  vl_status st = split_sections(s, &temp_line, err);
  if (st != VL_OK || (st = geometry_fit(s, err)) != VL_OK) return st;
  if (s->key_line[F_TITLE]) snprintf(s->title, sizeof s->title, "%s", s->values[F_TITLE]);
  if (!s->key_line[F_CASES] && !s->key_line[F_COMPOUNDS] && !s->key_line[F_LOADS]) {
    vl_error_set(err,
                 "%s: no [study] section with compounds, loads_n_per_m and radii_m (or "
                 "cases): not a study file",
                 s->path);
    return VL_EINPUT;
  }
  st = s->key_line[F_CASES] ? cases_tasks(s, err) : grid_tasks(s, err);
  if (st != VL_OK) return st;
  if (s->has_temperature && temp_line) {
    vl_error_set(err, "%s:%d: [effects] temperature: set by the study's temperatures (line %d)",
                 s->path, temp_line,
                 s->key_line[F_TEMPS] ? s->key_line[F_TEMPS] : s->key_line[F_CASES]);
    return VL_EINPUT;
  }
  if ((st = collect_materials(s, err)) != VL_OK) return st;
  return check_scenes(s, err);
}

vl_status vl_study_parse(const char *text, const char *path, vl_study **out, vl_error *err) {
  *out = NULL;
  vl_study *s = calloc(1, sizeof *s);
  if (!s || !(s->text = strdup(text)) || !(s->scene_text = strdup(text))) {
    vl_study_free(s);
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  snprintf(s->path, sizeof s->path, "%s", path);
  s->fingerprint = fnv1a(text);
  vl_status st = study_parse(s, err);
  if (st != VL_OK) {
    vl_study_free(s);
    return st;
  }
  *out = s;
  return VL_OK;
}

vl_status vl_study_load(const char *path, vl_study **out, vl_error *err) {
  char *text = NULL;
  size_t len = 0;
  *out = NULL;
  vl_status st = vl_slurp(path, (size_t)16 << 20, "a study file", &text, &len, err);
  if (st != VL_OK) return st;
  st = vl_text_refuse_nul(text, len, path, err);
  if (st == VL_OK) st = vl_study_parse(text, path, out, err);
  free(text);
  return st;
}

void vl_study_free(vl_study *s) {
  if (!s) return;
  for (int k = 0; k < F_COUNT; k++)
    free(s->values[k]);
  for (int k = 0; k < 3; k++)
    free(s->materials[k]);
  free(s->case_lines);
  free(s->tasks);
  free(s->scene_text);
  free(s->text);
  free(s);
}

const char *vl_study_path(const vl_study *s) { return s->path; }
const char *vl_study_title(const vl_study *s) { return s->title; }
const char *vl_study_text(const vl_study *s) { return s->text; }
uint64_t vl_study_fingerprint(const vl_study *s) { return s->fingerprint; }
size_t vl_study_n_tasks(const vl_study *s) { return s->n_tasks; }

const vl_study_task *vl_study_task_at(const vl_study *s, size_t i) {
  return i < s->n_tasks ? &s->tasks[i] : NULL;
}

const char *const *vl_study_materials(const vl_study *s, int kind, size_t *n) {
  *n = kind >= 0 && kind < 3 ? s->n_materials[kind] : 0;
  return *n ? s->materials[kind] : NULL;
}

/* The scene text of task t: the study's defaults and, after them, the
 * task's factors as the keys of a scene (numbers to 17 digits: the scene
 * holds the task's doubles exactly). */
static char *task_text(const vl_study *s, const vl_study_task *t) {
  char tail[1024];
  int n =
      snprintf(tail, sizeof tail, "\n[scene]\ntitle = %s%stask %zu\n[materials]\ncompound = %s\n",
               s->title, s->title[0] ? " | " : "", t->id, t->compound);
  if (t->surface[0]) n += snprintf(tail + n, sizeof tail - (size_t)n, "surface = %s\n", t->surface);
  if (t->fluid[0]) n += snprintf(tail + n, sizeof tail - (size_t)n, "fluid = %s\n", t->fluid);
  if (t->geometry == VL_GEOMETRY_CYLINDER)
    n += snprintf(tail + n, sizeof tail - (size_t)n,
                  "[contact]\nradius_m = %.17g\nload_n_per_m = %.17g\n", t->radius_m,
                  t->load_n_per_m);
  else if (t->geometry == VL_GEOMETRY_BALL)
    n += snprintf(tail + n, sizeof tail - (size_t)n,
                  "[contact]\nradius_m = %.17g\nload_n = %.17g\n", t->radius_m, t->load_n);
  else /* an ellipsoid's radii are the study's [contact] radii_m */
    n += snprintf(tail + n, sizeof tail - (size_t)n, "[contact]\nload_n = %.17g\n", t->load_n);
  if (!isnan(t->temperature_c))
    snprintf(tail + n, sizeof tail - (size_t)n,
             "[effects]\ntemperature = on\ntemperature_c = %.17g\n", t->temperature_c);
  size_t len = strlen(s->scene_text);
  char *text = malloc(len + strlen(tail) + 1);
  if (text) {
    memcpy(text, s->scene_text, len);
    strcpy(text + len, tail);
  }
  return text;
}

vl_status vl_study_scene(const vl_study *s, size_t i, vl_scene *out, vl_error *err) {
  if (i >= s->n_tasks) {
    vl_error_set(err, "%s: no task %zu (the study has %zu)", s->path, i, s->n_tasks);
    return VL_EINPUT;
  }
  char *text = task_text(s, &s->tasks[i]);
  if (!text) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  vl_status st = vl_scene_parse(text, s->path, out, err);
  free(text);
  return st;
}

/* The line that named material `name` of kind (its list, or its first row
 * of cases) and the key. */
static int material_line(const vl_study *s, int kind, const char *name, const char **key) {
  *key = s->key_line[F_CASES] ? "cases" : study_keys[kind];
  if (!s->key_line[F_CASES]) return s->key_line[kind];
  for (size_t i = 0; i < s->n_tasks; i++) {
    const vl_study_task *t = &s->tasks[i];
    if (!strcmp(kind == 0 ? t->compound : kind == 1 ? t->surface : t->fluid, name)) return t->line;
  }
  return 0;
}

static vl_status check_materials(const vl_study *s, vl_db *db, vl_error *err) {
  vl_status st = VL_OK;
  for (int kind = 0; kind < 3 && st == VL_OK; kind++) {
    for (size_t k = 0; k < s->n_materials[kind] && st == VL_OK; k++) {
      const char *name = s->materials[kind][k];
      double eta;
      vl_db_surface info;
      vl_prony p;
      st = kind == 0   ? vl_db_compound_get(db, name, &p, err)
           : kind == 1 ? vl_db_surface_info(db, name, &info, err)
                       : vl_db_fluid_get(db, name, &eta, err);
      const char *key;
      int line = material_line(s, kind, name, &key);
      if (st == VL_ENOTFOUND) vl_error_prefix(err, "%s:%d: [study] %s", s->path, line, key);
    }
  }
  return st;
}

vl_status vl_study_prepare(const vl_study *s, vl_db *db, vl_error *err) {
  vl_status st = check_materials(s, db, err);
  vl_scene *scene = malloc(sizeof *scene);
  if (st == VL_OK && !scene) {
    vl_error_set(err, "out of memory");
    st = VL_ENOMEM;
  }
  /* one simulation per distinct (compound, surface, fluid, temperature):
   * it builds (or reads) the tables and checks the temperature shifts */
  for (size_t i = 0; st == VL_OK && i < s->n_tasks; i++) {
    const vl_study_task *t = &s->tasks[i];
    bool seen = false;
    for (size_t k = 0; k < i && !seen; k++) {
      const vl_study_task *u = &s->tasks[k];
      seen = !strcmp(t->compound, u->compound) && !strcmp(t->surface, u->surface) &&
             !strcmp(t->fluid, u->fluid) &&
             (t->temperature_c == u->temperature_c || isnan(t->temperature_c));
    }
    if (seen) continue;
    vl_simulation *sim = NULL;
    st = vl_study_scene(s, i, scene, err);
    /* the study names the line below; the scene's own "PATH: [effects] ..."
     * would repeat the path: created as a scene without a file */
    scene->path[0] = '\0';
    if (st == VL_OK && (st = vl_simulation_create(scene, db, &sim, err)) != VL_OK) {
      /* what differs between the tasks of one triple: the temperature */
      int line = s->key_line[F_CASES] ? t->line : s->key_line[F_TEMPS];
      if (line)
        vl_error_prefix(err, "%s:%d: [study] %s (task %zu)", s->path, line,
                        s->key_line[F_CASES] ? "cases" : "temperatures_c", i);
      else
        vl_error_prefix(err, "task %zu", i);
    }
    vl_simulation_free(sim);
  }
  free(scene);
  return st;
}
