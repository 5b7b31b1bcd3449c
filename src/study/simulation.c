/* Scene -> solver (simulation.h). */
#include "viscolube/simulation.h"
#include "shear_law_private.h"
#include "viscolube/persson.h"
#include "viscolube/sweep.h"

#include "flow_factors_emt.h"

#include "viscolube/assumptions.h"
#include "viscolube/dma.h"

#include "assumptions_internal.h"
#include "contact_private.h"
#include "point_contact_internal.h"
#include "rheology_internal.h"
#include "simulation_internal.h"
#include "viscolube/flattening.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "slurp.h"

struct vl_simulation {
  vl_scene scene;
  vl_contact_config cfg;    /* as given to the contact (the assumption checks read it) */
  vl_contact_config cfg_in; /* [seal] stroke = both: the instroke's (mirrored, sealed outlet) */
  vl_sweep_stats in_stats;  /* the last run's instroke (zero without one) */
  vl_prony rubber;
  bool have_psd;
  vl_psd psd;
  vl_persson *table;
  vl_emt_table *flow_table;        /* persson-emt only */
  vl_flattening_config flattening; /* [effects] viscous_flattening = on: its settings */
  double eta_pa_s;
  double temperature_c; /* [effects] temperature: the scene's; NAN when off */
  double a_T;           /* WLF shift applied to the compound's times (1 when off) */
  /* the measured master curve's window at the temperature used (rad/s);
   * NAN for a compound entered as a Prony series or an elastic scene */
  double window_min_rad_s, window_max_rad_s;
  /* the measured isotherms' temperatures (C); NAN for a compound entered
   * as a Prony series or measured as one master curve */
  double measured_tmin_c, measured_tmax_c;
  vl_contact *contact; /* NULL for a point contact */
  /* [contact] geometry = ball or ellipsoid: the point contact's base
   * configuration (each point gets its own cells: vl_point_contact_sweep)
   * and its Hertz scales */
  bool point;
  vl_point_contact_config point_cfg;
  double a0_m, p0_pa;
  bool has_pair;
  vl_db_pair pair;
  vl_shear_law shear_law; /* in use: the pair's at temperature, or the constant */
  char shear_law_text[VL_DB_TEXT_MAX + 512];
  size_t n;
  double *v0;
  bool *fields;
  double *profile; /* [contact] profile_file (x, z in m) or pressure_profile_file (x in m, p in
                    * Pa): x then the values, profile_n each; NULL without */
  size_t profile_n;
};

/* Largest profile table (points) and file a scene may name. */
#define VL_PROFILE_MAX_POINTS 100000
#define VL_PROFILE_MAX_BYTES (16u << 20)

/* Context for a message about scene sc, added once: for a scene read from
 * a file, "PATH: WHERE" (the key to look at; WHERE may be NULL); for a
 * scene built in code (no path: a query), code_where or nothing, as the
 * caller names its own command and options and the message names the
 * material already ("no compound named 'x' in ..."). */
static void scene_context(vl_error *err, const vl_scene *sc, const char *where,
                          const char *code_where) {
  if (sc->path[0] && where)
    vl_error_prefix(err, "%s: %s", sc->path, where);
  else if (sc->path[0])
    vl_error_prefix(err, "%s", sc->path);
  else if (code_where)
    vl_error_prefix(err, "%s", code_where);
}

/* One row "x, z" of a profile table: two finite numbers separated by a
 * comma (blanks around them allowed). */
static bool profile_row(const char *line, double *x, double *z) {
  char *end;
  errno = 0;
  *x = strtod(line, &end);
  if (end == line || errno) return false;
  while (*end == ' ' || *end == '\t')
    end++;
  if (*end != ',') return false;
  const char *p = end + 1;
  *z = strtod(p, &end);
  if (end == p || errno) return false;
  while (*end == ' ' || *end == '\t' || *end == '\r')
    end++;
  return *end == '\0' && isfinite(*x) && isfinite(*z);
}

/* A two-column table of the scene (docs/FORMATS.md: '#' comments, blank
 * lines, the header, then rows of two numbers): a profile (x_m,z_m) or a
 * static pressure (x_m,p_pa). */
typedef struct {
  const char *file;    /* the table's path */
  int key_line;        /* the scene's line naming it */
  const char *key;     /* its key, for messages */
  const char *header;  /* "x_m,z_m" */
  const char *columns; /* "x, z" */
  const char *units;   /* "two numbers in m" */
} table_spec;

/* Reads the table of t into *out (x then the values, *n each; malloc'd) and
 * the line of each row into *lines (malloc'd; NULL: not kept). Errors name
 * FILE:LINE. */
static vl_status read_table(const vl_scene *sc, const table_spec *t, double **out, size_t *n_out,
                            int **lines, vl_error *err) {
  char *text = NULL;
  size_t len = 0;
  vl_status st = vl_slurp(t->file, VL_PROFILE_MAX_BYTES, "a table", &text, &len, err);
  if (st == VL_OK) st = vl_text_refuse_nul(text, len, t->file, err);
  if (st != VL_OK) {
    free(text);
    vl_error_prefix(err, "%s:%d: [contact] %s", sc->path, t->key_line, t->key);
    return st;
  }
  size_t cap = 1024, n = 0;
  double *x = malloc(cap * sizeof *x), *z = malloc(cap * sizeof *z);
  int *ln = malloc(cap * sizeof *ln);
  bool header = false;
  int line = 0;
  char spaced[64];
  snprintf(spaced, sizeof spaced, "%s", t->header);
  char *comma = strchr(spaced, ',');
  if (comma) memmove(comma + 2, comma + 1, strlen(comma + 1) + 1), comma[1] = ' ';
  st = x && z && ln ? VL_OK : VL_ENOMEM;
  for (char *s = text, *next; st == VL_OK && s && *s; s = next) {
    line++;
    next = strchr(s, '\n');
    if (next) *next++ = '\0';
    while (*s == ' ' || *s == '\t')
      s++;
    size_t l = strlen(s);
    while (l && (s[l - 1] == '\r' || s[l - 1] == ' ' || s[l - 1] == '\t'))
      s[--l] = '\0';
    if (!*s || *s == '#') continue;
    if (!header) {
      header = true;
      if (strcmp(s, t->header) && strcmp(s, spaced)) {
        vl_error_set(err, "%s:%d: expected the header %s, got '%.40s'", t->file, line, t->header,
                     s);
        st = VL_EINPUT;
      }
      continue;
    }
    if (n == cap) {
      double *nx = n < VL_PROFILE_MAX_POINTS ? realloc(x, 2 * cap * sizeof *x) : NULL;
      if (nx) x = nx;
      double *nz = nx ? realloc(z, 2 * cap * sizeof *z) : NULL;
      if (nz) z = nz;
      int *nl = nz ? realloc(ln, 2 * cap * sizeof *ln) : NULL;
      if (nl) ln = nl, cap *= 2;
      if (!nx || !nz || !nl) {
        vl_error_set(err, "%s:%d: more than %d points or out of memory", t->file, line,
                     VL_PROFILE_MAX_POINTS);
        st = VL_EINPUT;
        break;
      }
    }
    if (!profile_row(s, &x[n], &z[n])) {
      vl_error_set(err, "%s:%d: expected '%s' (%s), got '%.40s'", t->file, line, t->columns,
                   t->units, s);
      st = VL_EINPUT;
      break;
    }
    for (size_t k = 0; k < n; k++)
      if (x[k] == x[n]) {
        vl_error_set(err, "%s:%d: x = %g m given twice (line %d)", t->file, line, x[n], ln[k]);
        st = VL_EINPUT;
      }
    ln[n++] = line;
  }
  if (st == VL_OK && n < 3) {
    vl_error_set(err, "%s: a table of at least 3 points is needed (got %zu)", t->file, n);
    st = VL_EINPUT;
  }
  if (st == VL_OK && !(*out = malloc(2 * n * sizeof **out))) st = VL_ENOMEM;
  if (st == VL_OK) {
    memcpy(*out, x, n * sizeof *x);
    memcpy(*out + n, z, n * sizeof *z);
    *n_out = n;
    if (lines) *lines = ln, ln = NULL;
  }
  if (st == VL_ENOMEM) vl_error_set(err, "%s: out of memory", t->file);
  free(x), free(z), free(ln), free(text);
  return st;
}

/* The scene's profile table (x_m,z_m) into sim->profile. */
static vl_status read_profile(vl_simulation *sim, vl_error *err) {
  const vl_scene *sc = &sim->scene;
  table_spec t = {sc->profile_file, sc->profile_line, "profile_file",
                  "x_m,z_m",        "x, z",           "two numbers in m"};
  return read_table(sc, &t, &sim->profile, &sim->profile_n, NULL, err);
}

/* The scene's static pressure (x_m,p_pa) into sim->profile: each pressure
 * >= 0, and 0 at the lowest and highest x (the contact's edges); errors
 * name the table's line. */
static vl_status read_pressure(vl_simulation *sim, vl_error *err) {
  const vl_scene *sc = &sim->scene;
  table_spec t = {sc->pressure_file, sc->pressure_line, "pressure_profile_file", "x_m,p_pa", "x, p",
                  "x in m, p in Pa"};
  int *ln = NULL;
  vl_status st = read_table(sc, &t, &sim->profile, &sim->profile_n, &ln, err);
  if (st != VL_OK) return st;
  size_t n = sim->profile_n, lo = 0, hi = 0;
  const double *x = sim->profile, *p = sim->profile + n;
  for (size_t k = 0; k < n && st == VL_OK; k++) {
    if (p[k] < 0.0) {
      vl_error_set(err, "%s:%d: a contact pressure must be >= 0 (got %g Pa)", t.file, ln[k], p[k]);
      st = VL_EINPUT;
    }
    if (x[k] < x[lo]) lo = k;
    if (x[k] > x[hi]) hi = k;
  }
  size_t end = p[lo] != 0.0 ? lo : hi;
  if (st == VL_OK && (p[lo] != 0.0 || p[hi] != 0.0)) {
    vl_error_set(err,
                 "%s:%d: the pressure must fall to 0 at both ends of the table (the edges of "
                 "the contact), got %g Pa at x = %g m",
                 t.file, ln[end], p[end], x[end]);
    st = VL_EINPUT;
  }
  free(ln);
  return st;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Speed (m/s) for a value of the sweep quantity. */
static double speed_of(const vl_simulation *sim, double value) {
  switch (sim->scene.quantity) {
  case VL_SWEEP_V0: return value;
  case VL_SWEEP_V0_ETA: return value / sim->eta_pa_s;
  case VL_SWEEP_DEBORAH: return value * vl_simulation_a0(sim) / sim->rubber.tau_s[0];
  }
  return value;
}

static vl_status build_speeds(vl_simulation *sim, vl_error *err) {
  const vl_scene *sc = &sim->scene;
  size_t n = sc->points + sc->n_fields_at;
  sim->v0 = malloc(n * sizeof *sim->v0);
  double *fv = malloc((sc->n_fields_at + 1) * sizeof *fv);
  sim->fields = calloc(n, sizeof *sim->fields);
  if (!sim->v0 || !fv || !sim->fields) {
    free(fv);
    vl_error_set(err, "out of memory for %zu sweep points", n);
    return VL_ENOMEM;
  }
  for (size_t i = 0; i < sc->points; i++) {
    double t = sc->points > 1 ? (double)i / (double)(sc->points - 1) : 0.0;
    sim->v0[i] = speed_of(sim, sc->from * pow(sc->to / sc->from, t));
  }
  for (size_t k = 0; k < sc->n_fields_at; k++)
    fv[k] = speed_of(sim, sc->fields_at[k]);
  /* merge: a fields_at value within 1e-9 relative of a sweep point uses it */
  size_t m = sc->points;
  for (size_t k = 0; k < sc->n_fields_at; k++) {
    bool found = false;
    for (size_t i = 0; i < m; i++)
      if (fabs(sim->v0[i] - fv[k]) <= 1e-9 * fv[k]) found = true;
    if (!found) sim->v0[m++] = fv[k];
  }
  qsort(sim->v0, m, sizeof *sim->v0, cmp_double);
  for (size_t k = 0; k < sc->n_fields_at; k++)
    for (size_t i = 0; i < m; i++)
      if (fabs(sim->v0[i] - fv[k]) <= 1e-9 * fv[k]) sim->fields[i] = true;
  sim->n = m;
  free(fv);
  /* [sweep] direction = down: the speeds in the order the sweep visits
   * them, from the top (with their fields flags) */
  for (size_t i = 0; sc->direction == VL_DIRECTION_DOWN && i < m / 2; i++) {
    double v = sim->v0[i];
    bool f = sim->fields[i];
    sim->v0[i] = sim->v0[m - 1 - i], sim->fields[i] = sim->fields[m - 1 - i];
    sim->v0[m - 1 - i] = v, sim->fields[m - 1 - i] = f;
  }
  return VL_OK;
}

vl_status vl_compound_at_temperature(const vl_db_compound *c, double t_c, vl_prony *out,
                                     double *a_T, vl_error *err) {
  /* the reference temperature is where the series was measured: no law
   * is needed, and the series comes back bit for bit */
  if (t_c == c->tref_c) {
    *out = c->prony;
    *a_T = 1.0;
    return VL_OK;
  }
  if (!isfinite(t_c)) {
    vl_error_set(err, "invalid temperature %g C", t_c);
    return VL_EINPUT;
  }
  if (!(isfinite(c->wlf_c1) && isfinite(c->wlf_c2_k))) {
    vl_error_set(err,
                 "compound '%s' has no WLF constants: its Prony series is known at %g C only "
                 "(asked for %g C)",
                 c->name, c->tref_c, t_c);
    return VL_EINPUT;
  }
  double log10_a = vl_wlf_log10_shift(c->wlf_c1, c->wlf_c2_k, t_c, c->tref_c);
  if (isnan(log10_a)) {
    vl_error_set(err,
                 "%g C is at or below the WLF singularity Tref - C2 = %g C of compound '%s' "
                 "(C1 %g, C2 %g K at %g C): WLF holds from about the glass transition upwards",
                 t_c, c->tref_c - c->wlf_c2_k, c->name, c->wlf_c1, c->wlf_c2_k, c->tref_c);
    return VL_EINPUT;
  }
  vl_prony p = c->prony;
  double a = pow(10.0, log10_a);
  vl_prony_shift(&p, a);
  /* near the singularity a_T overflows, or a time underflows far above */
  vl_error why;
  if (!(isfinite(a) && a > 0.0) || vl_prony_validate(&p, &why) != VL_OK) {
    vl_error_set(err,
                 "compound '%s' at %g C: the WLF shift log10 a_T = %g puts its times out of "
                 "range",
                 c->name, t_c, log10_a);
    return VL_EINPUT;
  }
  *out = p;
  *a_T = a;
  return VL_OK;
}

/* The stored pair's law when the scene leaves sigma_s to it (solid shear
 * on, no sigma_s_pa given, a fluid and a surface named): at the scene's
 * temperature and viscosity, with its provenance in shear_law_text. */
static vl_status apply_pair(vl_simulation *sim, vl_db *db, vl_error *err) {
  const vl_scene *sc = &sim->scene;
  sim->shear_law = vl_shear_law_constant(sc->effects.solid_shear ? sc->sigma_s_pa : 0.0);
  if (!sc->effects.solid_shear || sc->sigma_s_given || !sc->fluid[0] || !sc->surface[0])
    return VL_OK;
  bool found = false;
  vl_status st = vl_db_pair_get(db, sc->compound, sc->surface, sc->fluid, &sim->pair, &found, err);
  if (st != VL_OK) {
    scene_context(err, sc, "the pair of its materials", "the pair of its materials");
    return st;
  }
  if (!found) return VL_OK;
  st = vl_shear_law_at(&sim->pair.law, sim->temperature_c, sim->eta_pa_s, &sim->shear_law, err);
  if (st != VL_OK) return st;
  sim->has_pair = true;
  const vl_shear_law *l = &sim->shear_law;
  size_t len = 0, size = sizeof sim->shear_law_text;
  char *t = sim->shear_law_text;
  len += (size_t)snprintf(t, size, "%s:", vl_shear_law_name(l->kind));
  for (size_t k = 0; k < vl_shear_law_n_params(l->kind) && len < size; k++)
    len += (size_t)snprintf(t + len, size - len, "%s %s = %.6g", k ? "," : "",
                            vl_shear_law_param_name(l->kind, k), l->p[k]);
  const vl_db_pair *p = &sim->pair;
  if (len < size)
    len += (size_t)snprintf(t + len, size - len, " (pair %s / %s / %s, %s %s", p->compound,
                            p->surface, p->fluid, p->source, p->created_at);
  if (len < size && !strcmp(p->source, VL_DB_SOURCE_CALIBRATED))
    len += (size_t)snprintf(t + len, size - len, " from %s %s", p->measured_file,
                            p->measured_fingerprint);
  if (len < size) snprintf(t + len, size - len, ")");
  return VL_OK;
}

/* [effects] temperature = on: the compound shifted to the scene's
 * temperature by its WLF constants (only when viscoelastic: an elastic
 * scene uses E0 or Einf, which a horizontal shift leaves alone), and the
 * viscosity of the fluid by its law (only when the fluid is simulated: a
 * dry scene needs no viscosity). */
static vl_status apply_temperature(vl_simulation *sim, vl_db *db, vl_error *err) {
  const vl_scene *sc = &sim->scene;
  double t = sc->effects.temperature_c;
  vl_status st = VL_OK;
  if (sc->effects.viscoelastic) {
    vl_db_compound *c = malloc(sizeof *c); /* ~4 kB of names and texts */
    if (!c) {
      vl_error_set(err, "out of memory");
      return VL_ENOMEM;
    }
    st = vl_db_compound_info(db, sc->compound, c, err);
    if (st == VL_OK) st = vl_compound_at_temperature(c, t, &sim->rubber, &sim->a_T, err);
    free(c);
    if (st != VL_OK) {
      char where[96];
      snprintf(where, sizeof where, "[effects] temperature = on at %g C", t);
      scene_context(err, sc, where, NULL); /* the message names compound and temperature */
      return st;
    }
  }
  sim->temperature_c = t;
  if (sc->effects.fluid && sc->fluid[0]) {
    vl_db_fluid f;
    st = vl_db_fluid_info(db, sc->fluid, &f, err);
    if (st == VL_OK)
      st = vl_fluid_viscosity(&f.law, f.viscosity_pa_s, f.tref_c, t, &sim->eta_pa_s, err);
    if (st != VL_OK) {
      char where[96 + VL_NAME_MAX], fluid[16 + VL_NAME_MAX];
      snprintf(where, sizeof where, "[effects] temperature = on at %g C: fluid '%s'", t, sc->fluid);
      snprintf(fluid, sizeof fluid, "fluid '%s'", sc->fluid);
      scene_context(err, sc, where, fluid);
      return st;
    }
  }
  return VL_OK;
}

/* The window of a compound fitted to measured data, moved to the scene's
 * temperature: a frequency w at T is w a_T on the master curve at Tref. */
static vl_status measured_window(vl_simulation *sim, vl_db *db, vl_error *err) {
  vl_db_compound_fit f;
  memset(&f, 0, sizeof f);
  vl_status st = vl_db_compound_fit_info(db, sim->scene.compound, &f, err);
  if (st == VL_OK && f.has_fit) {
    sim->window_min_rad_s = f.omega_min_rad_s / sim->a_T;
    sim->window_max_rad_s = f.omega_max_rad_s / sim->a_T;
  }
  if (st == VL_OK && f.has_fit && f.n_shifts > 0) {
    sim->measured_tmin_c = f.shift_temperature_c[0];
    sim->measured_tmax_c = f.shift_temperature_c[f.n_shifts - 1];
  }
  vl_db_compound_fit_free(&f);
  return st;
}

/* The rubber of the scene's contact: the compound's Prony series, or with
 * [effects] viscoelastic = off an elastic one (relaxed, glassy or given
 * modulus): no Prony kernel is then built or evaluated. */
static vl_prony scene_rubber(const vl_simulation *sim) {
  vl_prony r = sim->rubber;
  const vl_scene *scene = &sim->scene;
  if (!scene->effects.viscoelastic) {
    r.e_inf_pa = scene->elastic == VL_ELASTIC_GLASSY  ? sim->rubber.e_inf_pa
                 : scene->elastic == VL_ELASTIC_GIVEN ? scene->elastic_modulus_pa
                                                      : vl_prony_e0(&sim->rubber);
    r.n_terms = 0;
  }
  return r;
}

/* A ball or an ellipsoid (docs/POINT_CONTACT.md): the rubber, the
 * geometry, the load, sigma_s, (a lubricated ball) the viscosity and (a
 * rough ball) the surface's tables; checked here (a bad radius or load is
 * named now, not at the first point). */
static vl_status point_contact_setup(vl_simulation *sim, vl_error *err) {
  const vl_scene *scene = &sim->scene;
  vl_point_contact_config *pc = &sim->point_cfg;
  vl_point_contact_config_defaults(pc);
  pc->rubber = scene_rubber(sim);
  pc->radius_x_m = scene->radius_m, pc->radius_y_m = scene->radius_y_m;
  pc->load_n = scene->load_n;
  pc->eta_pa_s = scene->effects.fluid ? sim->eta_pa_s : 0.0;
  if (scene->effects.roughness) {
    pc->roughness = sim->table;
    pc->flow_factors = scene->effects.flow_factors;
    pc->flow_table = sim->flow_table;
  }
  pc->sigma_s_pa = scene->effects.solid_shear && !sim->has_pair ? scene->sigma_s_pa : 0.0;
  pc->tolerance = scene->tolerance;
  vl_point_contact *probe = NULL;
  vl_status st = vl_point_contact_build(pc, &probe, err);
  if (st == VL_OK) sim->a0_m = probe->a0, sim->p0_pa = probe->p0;
  vl_point_contact_release(probe);
  if (st != VL_OK) vl_error_prefix(err, "%s", scene->path);
  sim->point = true;
  return st;
}

/* An imposed static pressure: the table, and the load and scales it
 * gives (vl_contact_static_scales), also into the simulation's scene. */
static vl_status static_pressure(vl_simulation *sim, vl_contact_config *cfg, vl_error *err) {
  vl_status st = read_pressure(sim, err);
  if (st != VL_OK) return st;
  cfg->static_x_m = sim->profile, cfg->static_p_pa = sim->profile + sim->profile_n;
  cfg->static_points = sim->profile_n;
  cfg->profile_mirror = sim->scene.stroke == VL_STROKE_IN;
  st = vl_contact_static_scales(cfg, &cfg->load_n_per_m, &cfg->radius_m, err);
  if (st != VL_OK) {
    vl_error_prefix(err, "%s:%d: [contact] pressure_profile_file", sim->scene.path,
                    sim->scene.pressure_line);
    return st;
  }
  sim->scene.load_n_per_m = cfg->load_n_per_m, sim->scene.radius_m = cfg->radius_m;
  return VL_OK;
}

/* A lip's scales and every profile's domain: the lip's contact may be far
 * wider than the tip's Hertz contact (its flanks carry), so the scales are
 * those of the cylinder whose dry contact is as wide (a0 the lip's
 * half-width), and the domain of default numerics reaches past the
 * contact of either stroke (vl_contact_numerics_follow_profile). A
 * table's radius_m stays the scene's. */
static vl_status profile_scales(const vl_scene *scene, vl_contact_config *cfg, vl_error *err) {
  vl_status st = VL_OK;
  double c, a;
  if (scene->lip) st = vl_contact_profile_contact(cfg, &c, &a, &cfg->radius_m, err);
  if (st == VL_OK && scene->auto_numerics) st = vl_contact_numerics_follow_profile(cfg, err);
  if (st != VL_OK) vl_error_prefix(err, "%s: [contact] profile", scene->path);
  return st;
}

vl_status vl_simulation_create(const vl_scene *scene, vl_db *db, vl_simulation **out,
                               vl_error *err) {
  *out = NULL;
  vl_simulation *sim = calloc(1, sizeof *sim);
  if (!sim) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  sim->scene = *scene;
  sim->temperature_c = NAN;
  sim->a_T = 1.0;
  sim->window_min_rad_s = sim->window_max_rad_s = NAN;
  sim->measured_tmin_c = sim->measured_tmax_c = NAN;
  vl_status st = vl_db_compound_get(db, scene->compound, &sim->rubber, err);
  if (st != VL_OK) {
    if (st == VL_ENOTFOUND) scene_context(err, scene, "[materials] compound", NULL);
    goto fail;
  }
  if (scene->quantity == VL_SWEEP_DEBORAH && sim->rubber.n_terms != 1) {
    vl_error_set(err,
                 "%s: [sweep] quantity = deborah needs a one-term compound; '%s' has %zu terms",
                 scene->path, scene->compound, sim->rubber.n_terms);
    st = VL_EINPUT;
    goto fail;
  }
  if (scene->fluid[0]) {
    st = vl_db_fluid_get(db, scene->fluid, &sim->eta_pa_s, err);
    if (st != VL_OK) {
      if (st == VL_ENOTFOUND) scene_context(err, scene, "[materials] fluid", NULL);
      goto fail;
    }
  }
  if (scene->effects.temperature && (st = apply_temperature(sim, db, err)) != VL_OK) goto fail;
  if (scene->effects.viscoelastic && (st = measured_window(sim, db, err)) != VL_OK) goto fail;
  if (scene->effects.roughness) {
    st = vl_db_surface_get(db, scene->surface, &sim->psd, err);
    if (st != VL_OK) {
      if (st == VL_ENOTFOUND) scene_context(err, scene, "[materials] surface", NULL);
      goto fail;
    }
    sim->have_psd = true;
    /* built once per (surface, size), then read from the database */
    st = vl_db_persson_table(db, scene->surface, &sim->psd, scene->persson_table, &sim->table, NULL,
                             err);
    if (st != VL_OK) goto fail;
    if (scene->effects.fluid && scene->effects.flow_factors == VL_FLOW_FACTORS_PERSSON_EMT) {
      st = vl_db_flow_table(db, scene->surface, &sim->psd, scene->effects.film_cutoff_m, 0,
                            &sim->flow_table, NULL, err);
      if (st != VL_OK) {
        scene_context(err, scene, "[effects] flow_factors = persson-emt", NULL);
        goto fail;
      }
    }
  }
  if ((st = apply_pair(sim, db, err)) != VL_OK) goto fail;
  if (scene->geometry != VL_GEOMETRY_CYLINDER) {
    if ((st = point_contact_setup(sim, err)) != VL_OK || (st = build_speeds(sim, err)) != VL_OK)
      goto fail;
    *out = sim;
    return VL_OK;
  }
  vl_contact_config cfg;
  vl_contact_config_defaults(&cfg);
  cfg.rubber = scene_rubber(sim);
  cfg.radius_m = scene->radius_m;
  cfg.load_n_per_m = scene->load_n_per_m;
  if (scene->lip) {
    cfg.lip_tip_radius_m = scene->lip_tip_radius_m;
    cfg.lip_oil_angle_rad = scene->lip_oil_angle_deg * M_PI / 180.0;
    cfg.lip_air_angle_rad = scene->lip_air_angle_deg * M_PI / 180.0;
    cfg.radius_m = cfg.lip_tip_radius_m; /* for the check; the scales' below */
  }
  cfg.sigma_s_pa = scene->effects.solid_shear ? scene->sigma_s_pa : 0.0;
  cfg.shear_law = sim->has_pair ? &sim->shear_law : NULL;
  cfg.moving = scene->moving;
  if (scene->pressure_file[0] && (st = static_pressure(sim, &cfg, err)) != VL_OK) goto fail;
  if (scene->profile_file[0]) {
    if ((st = read_profile(sim, err)) != VL_OK) goto fail;
    cfg.profile_x_m = sim->profile, cfg.profile_z_m = sim->profile + sim->profile_n;
    cfg.profile_points = sim->profile_n;
    cfg.profile_mirror = scene->stroke == VL_STROKE_IN;
  }
  /* the sealed pressure on the oil side: the film's inlet on an outstroke,
   * its outlet on an instroke (the profile mirrored, docs/MODEL.md section 12) */
  if (scene->stroke == VL_STROKE_IN)
    cfg.p_outlet_pa = scene->sealed_pressure_pa;
  else
    cfg.p_inlet_pa = scene->sealed_pressure_pa;
  cfg.roughness = sim->table;
  /* only a scene with the fluid effect gets fluid unknowns */
  cfg.eta_pa_s = scene->effects.fluid ? sim->eta_pa_s : 0.0;
  cfg.flow_factors = scene->effects.flow_factors;
  cfg.flow_table = sim->flow_table;
  cfg.grid = scene->grid;
  cfg.grid_growth = scene->grid_growth;
  cfg.x_min_a0 = scene->domain_min_a0;
  cfg.x_max_a0 = scene->domain_max_a0;
  cfg.tolerance = scene->tolerance;
  cfg.linear_solver = scene->linear_solver;
  if ((st = profile_scales(scene, &cfg, err)) != VL_OK) goto fail;
  if (scene->effects.viscous_flattening) {
    /* epsilon_f of the rubber the contact uses (elastic or at the scene's
     * temperature), the surface, the contact's load and radius (aH, so wH)
     * and the fluid at the scene's temperature; the scene parser has made
     * sure roughness and fluid are on */
    vl_flattening_config *fc = &sim->flattening;
    vl_flattening_config_defaults(fc);
    fc->rubber = cfg.rubber;
    fc->load_n_per_m = cfg.load_n_per_m;
    fc->radius_m = cfg.radius_m;
    fc->eta_pa_s = cfg.eta_pa_s;
    cfg.flattening = fc; /* the contact builds its own evaluator from it */
    cfg.flattening_psd = &sim->psd;
  }
  sim->cfg = cfg;
  sim->cfg_in = cfg;
  sim->cfg_in.p_inlet_pa = 0.0, sim->cfg_in.p_outlet_pa = scene->sealed_pressure_pa;
  sim->cfg_in.profile_mirror = true;
  st = vl_contact_create(&cfg, &sim->contact, err);
  if (st != VL_OK) {
    scene_context(err, scene, NULL, NULL);
    goto fail;
  }
  st = build_speeds(sim, err);
  if (st != VL_OK) goto fail;
  *out = sim;
  return VL_OK;
fail:
  vl_simulation_free(sim);
  return st;
}

void vl_simulation_free(vl_simulation *sim) {
  if (!sim) return;
  vl_contact_free(sim->contact);
  vl_persson_free(sim->table);
  vl_emt_table_free(sim->flow_table);
  if (sim->have_psd) vl_psd_free(&sim->psd);
  free(sim->v0);
  free(sim->fields);
  free(sim->profile);
  free(sim);
}

size_t vl_simulation_points(const vl_simulation *sim) { return sim->n; }
const double *vl_simulation_speeds(const vl_simulation *sim) { return sim->v0; }
bool vl_simulation_wants_fields(const vl_simulation *sim, size_t i) {
  return i < sim->n && sim->fields[i];
}
vl_contact *vl_simulation_contact(vl_simulation *sim) { return sim->contact; }
double vl_simulation_a0(const vl_simulation *sim) {
  return sim->point ? sim->a0_m : vl_contact_a0(sim->contact);
}
double vl_simulation_p0(const vl_simulation *sim) {
  return sim->point ? sim->p0_pa : vl_contact_p0(sim->contact);
}
vl_status vl_simulation_hertz_ellipse(const vl_simulation *sim, double *ax_m, double *by_m) {
  if (!sim->point) return VL_EINPUT;
  const vl_point_contact_config *pc = &sim->point_cfg;
  double er0 = vl_prony_e0(&pc->rubber) * vl_prony_reduced_factor(&pc->rubber);
  return vl_hertz_ellipse(pc->radius_x_m, pc->radius_y_m, pc->load_n, er0, ax_m, by_m, NULL);
}
const vl_scene *vl_simulation_scene(const vl_simulation *sim) { return &sim->scene; }
double vl_simulation_eta(const vl_simulation *sim) { return sim->eta_pa_s; }
double vl_simulation_tau(const vl_simulation *sim) {
  /* a rubber at rest (moving counter-surface) has no macroscopic memory:
   * no Deborah number v0 tau/a0 */
  bool memory = sim->scene.moving == VL_MOVING_RUBBER;
  return sim->rubber.n_terms == 1 && memory ? sim->rubber.tau_s[0] : 0.0;
}
const vl_prony *vl_simulation_rubber(const vl_simulation *sim) { return &sim->rubber; }
const vl_sweep_stats *vl_simulation_instroke_stats(const vl_simulation *sim) {
  return &sim->in_stats;
}
double vl_simulation_temperature_c(const vl_simulation *sim) { return sim->temperature_c; }
double vl_simulation_shift_factor(const vl_simulation *sim) { return sim->a_T; }
const vl_psd *vl_simulation_psd(const vl_simulation *sim) {
  return sim->have_psd ? &sim->psd : NULL;
}

typedef struct {
  vl_simulation *sim;
  vl_point *out;
  vl_sweep_callback cb;
  void *user;
} run_ctx;

/* The instroke's points: the assumption checks only. */
typedef struct {
  vl_simulation *sim;
  vl_point *out;
} vl_simulation_run_ctx_in;

static void check_point_in(void *user, size_t i, size_t total, const vl_point *pt,
                           const vl_contact *c) {
  vl_simulation_run_ctx_in *r = user;
  vl_point *p = &r->out[i];
  vl_assumptions_check(&r->sim->cfg_in, vl_simulation_psd(r->sim), p, p->warnings,
                       sizeof p->warnings);
  (void)pt, (void)total, (void)c;
}

/* A compound used at a temperature over VL_DMA_ISOTHERM_TOL_K outside its
 * measured isotherms: its WLF shift is extrapolated there (the warning
 * of every point; nothing for a compound without measured isotherms). */
static void temperature_warning(const vl_simulation *sim, char *warnings, size_t cap) {
  double t = sim->temperature_c, lo = sim->measured_tmin_c, hi = sim->measured_tmax_c;
  if (isnan(t) || isnan(lo) || (t >= lo - VL_DMA_ISOTHERM_TOL_K && t <= hi + VL_DMA_ISOTHERM_TOL_K))
    return;
  char w[200];
  snprintf(w, sizeof w,
           "temperature %.4g C %s the measured isotherms (%.4g to %.4g C): the WLF shift is "
           "extrapolated %.3g K beyond them",
           t, t < lo ? "below" : "above", lo, hi, t < lo ? lo - t : t - hi);
  vl_warnings_append(warnings, cap, w);
}

/* Every point gets the model-assumption warnings (assumptions.h) and the
 * temperature warning in its warning column before the caller sees it. */
static void check_point(void *user, size_t i, size_t total, const vl_point *pt,
                        const vl_contact *c) {
  run_ctx *r = user;
  vl_point *p = &r->out[i]; /* pt == &out[i]: the sweep fills the caller's array */
  temperature_warning(r->sim, p->warnings, sizeof p->warnings); /* first: it must fit */
  vl_assumptions_check(&r->sim->cfg, vl_simulation_psd(r->sim), p, p->warnings, sizeof p->warnings);
  vl_assumptions_check_window(&r->sim->cfg, vl_simulation_psd(r->sim), p, r->sim->window_min_rad_s,
                              r->sim->window_max_rad_s, p->warnings, sizeof p->warnings);
  (void)pt;
  if (r->cb) r->cb(r->user, i, total, p, c);
}

/* The seal's results of point p (its stroke's friction force), with the
 * instroke q at the same speed for stroke = both: the volumes carried out
 * and back per cycle and whether the seal is tight. */
static void seal_result(const vl_scene *sc, vl_point *p, const vl_point *q) {
  vl_seal_result *s = &p->seal;
  *s = (vl_seal_result){.stroke = sc->stroke,
                        .volume_out_m3 = NAN,
                        .volume_back_m3 = NAN,
                        .in_error_estimate = NAN,
                        .in_flux_error_estimate = NAN};
  s->tight = -1;
  s->friction_n_per_m = p->mu * sc->load_n_per_m; /* a static pressure's: set from its table */
  if (!q) return;
  s->in_converged = q->converged;
  s->in_mu = q->mu, s->in_mu_Sc = q->mu_Sc, s->in_mu_Sf = q->mu_Sf;
  s->in_u_min_m = q->u_min_m, s->in_flux_m2_s = q->flux_m2_s;
  s->in_u_central_m = q->u_central_m;
  s->in_error_estimate = q->error_estimate, s->in_flux_error_estimate = q->flux_error_estimate;
  s->in_accuracy = q->accuracy;
  s->in_iterations = q->iterations, s->in_residual = q->residual;
  snprintf(s->in_warnings, sizeof s->in_warnings, "%s", q->warnings);
  s->in_friction_n_per_m = q->mu * sc->load_n_per_m;
  if (sc->rod_diameter_m > 0.0 && sc->stroke_length_m > 0.0 && p->converged && q->converged) {
    /* a stroke of length L at speed v lasts L/v; q per unit circumference */
    double per_flux = M_PI * sc->rod_diameter_m * sc->stroke_length_m / p->v0_m_s;
    s->volume_out_m3 = per_flux * p->flux_m2_s;
    s->volume_back_m3 = per_flux * q->flux_m2_s;
    s->tight = s->volume_back_m3 >= s->volume_out_m3;
  }
}

/* [seal] stroke = both: the instroke's sweep at the same speeds (its points'
 * warnings checked too, no callback: the curve's rows are the outstroke's),
 * merged into the outstroke's points. */
static vl_status run_instroke(vl_simulation *sim, vl_point *out, vl_error *err) {
  vl_point *in = calloc(sim->n, sizeof *in);
  if (!in) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  vl_simulation_run_ctx_in ctx = {sim, in};
  vl_auto_options o = {sim->scene.target_error, -1, !sim->scene.auto_numerics};
  vl_status s = vl_sweep_run_auto(&sim->cfg_in, &o, sim->n, sim->v0, in, check_point_in, &ctx,
                                  &sim->in_stats, err);
  if (s == VL_OK || s == VL_ENOCONV)
    for (size_t i = 0; i < sim->n; i++)
      seal_result(&sim->scene, &out[i], &in[i]);
  free(in);
  return s == VL_ENOCONV ? VL_OK : s;
}

/* Whether the upward point p and the downward q at its speed are two
 * states: their mu differ by more than the target and both estimates (a
 * point without an estimate counts the target) can explain. */
static bool two_states(const vl_point *p, const vl_point *q, double target) {
  if (!p->converged || !q->converged) return false;
  double e = target > 0.0 ? target : VL_TARGET_ERROR_DEFAULT;
  double ep = isnan(p->error_estimate) ? e : p->error_estimate;
  double eq = isnan(q->error_estimate) ? e : q->error_estimate;
  return fabs(p->mu - q->mu) > (e + ep + eq) * fmax(fabs(p->mu), fabs(q->mu));
}

/* [sweep] direction = both: the sweep again from the top, each of its
 * points merged into the upward point at its speed (vl_down_result); where
 * the two differ beyond their errors the point says so. */
static vl_status run_downward(vl_simulation *sim, vl_point *out, vl_error *err) {
  size_t n = sim->n;
  vl_point *dn = calloc(n, sizeof *dn);
  double *v = malloc(n * sizeof *v);
  if (!dn || !v) {
    free(dn), free(v);
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  for (size_t i = 0; i < n; i++)
    v[i] = sim->v0[n - 1 - i];
  vl_auto_options o = {sim->scene.target_error, -1, !sim->scene.auto_numerics};
  vl_sweep_stats st;
  vl_status s = vl_sweep_run_auto(&sim->cfg, &o, n, v, dn, NULL, NULL, &st, err);
  for (size_t i = 0; (s == VL_OK || s == VL_ENOCONV) && i < n; i++) {
    const vl_point *q = &dn[n - 1 - i];
    vl_down_result *d = &out[i].down;
    *d = (vl_down_result){true,       q->converged,           q->mu, q->error_estimate,
                          q->u_min_m, q->fluid_load_fraction, false};
    d->two_states = two_states(&out[i], q, sim->scene.target_error);
    if (!d->two_states) continue;
    char w[200];
    snprintf(w, sizeof w,
             "two states: mu %.4g sweeping up, %.4g sweeping down (u_min %.3g m and %.3g m): "
             "a fold of the curve",
             out[i].mu, q->mu, out[i].u_min_m, q->u_min_m);
    vl_warnings_append(out[i].warnings, sizeof out[i].warnings, w);
  }
  free(dn), free(v);
  return s == VL_ENOCONV ? VL_OK : s;
}

/* A point contact's point: the temperature warning, and mu_Sc from the
 * stored pair's law at v0 (sigma_s does not enter the solution). */
typedef struct {
  vl_simulation *sim;
  vl_point *out;
  vl_point_contact_callback cb;
  vl_sweep_callback line_cb; /* vl_simulation_run's, called without a contact */
  void *user;
} point_ctx;

static void check_point_contact(void *user, size_t i, size_t total, const vl_point *pt,
                                const vl_point_contact *c) {
  point_ctx *r = user;
  vl_point *p = &r->out[i];
  temperature_warning(r->sim, p->warnings, sizeof p->warnings);
  if (p->converged && r->sim->has_pair && r->sim->scene.effects.solid_shear) {
    double sigma = vl_shear_law_eval(&r->sim->shear_law, p->v0_m_s, NULL);
    p->mu_Sc = sigma * p->ball.contact_area_m2 / r->sim->scene.load_n;
    p->mu = p->mu_Rc + p->mu_Rf + p->mu_Sc + p->mu_Sf;
  }
  (void)pt;
  if (r->cb) r->cb(r->user, i, total, p, c);
  if (r->line_cb) r->line_cb(r->user, i, total, p, NULL);
}

vl_status vl_simulation_run_point_contact(vl_simulation *sim, vl_point *out,
                                          vl_point_contact_callback cb, void *user,
                                          vl_sweep_stats *stats, vl_error *err) {
  if (!sim->point) {
    vl_error_set(err, "%s: not a point contact ([contact] geometry = cylinder)", sim->scene.path);
    return VL_EINPUT;
  }
  point_ctx r = {sim, out, cb, NULL, user};
  vl_auto_options o = {sim->scene.target_error, -1, false};
  return vl_point_contact_sweep(&sim->point_cfg, &o, sim->n, sim->v0, out, check_point_contact, &r,
                                stats, err);
}

vl_status vl_simulation_run(vl_simulation *sim, vl_point *out, vl_sweep_callback cb, void *user,
                            vl_sweep_stats *stats, vl_error *err) {
  if (sim->point) {
    point_ctx p = {sim, out, NULL, cb, user};
    vl_auto_options o = {sim->scene.target_error, -1, false};
    return vl_point_contact_sweep(&sim->point_cfg, &o, sim->n, sim->v0, out, check_point_contact,
                                  &p, stats, err);
  }
  run_ctx r = {sim, out, cb, user};
  vl_auto_options o = {sim->scene.target_error, -1, !sim->scene.auto_numerics};
  memset(&sim->in_stats, 0, sizeof sim->in_stats);
  vl_status st =
      vl_sweep_run_auto(&sim->cfg, &o, sim->n, sim->v0, out, check_point, &r, stats, err);
  if (sim->scene.direction == VL_DIRECTION_BOTH && (st == VL_OK || st == VL_ENOCONV)) {
    vl_status sd = run_downward(sim, out, err);
    if (sd != VL_OK) return sd;
  }
  if (sim->scene.stroke == VL_STROKE_NONE || (st != VL_OK && st != VL_ENOCONV)) return st;
  if (sim->scene.stroke != VL_STROKE_BOTH) {
    for (size_t i = 0; i < sim->n; i++)
      seal_result(&sim->scene, &out[i], NULL);
    return st;
  }
  vl_status si = run_instroke(sim, out, err);
  return si != VL_OK ? si : st;
}

vl_status vl_simulation_run_speeds(vl_simulation *sim, size_t n, const double *v0_m_s,
                                   vl_point *out, vl_sweep_stats *stats, vl_error *err) {
  run_ctx r = {sim, out, NULL, NULL};
  vl_auto_options o = {sim->scene.target_error, -1, !sim->scene.auto_numerics};
  return vl_sweep_run_auto(&sim->cfg, &o, n, v0_m_s, out, check_point, &r, stats, err);
}

const vl_db_pair *vl_simulation_pair(const vl_simulation *sim) {
  return sim->has_pair ? &sim->pair : NULL;
}
const vl_shear_law *vl_simulation_shear_law(const vl_simulation *sim) { return &sim->shear_law; }
const char *vl_simulation_shear_law_text(const vl_simulation *sim) {
  return sim->has_pair ? sim->shear_law_text : NULL;
}

const char *vl_simulation_flow_factors(const vl_simulation *sim, double *film_cutoff_m) {
  const vl_scene *sc = &sim->scene;
  bool rough_film = sc->effects.roughness && sc->effects.fluid;
  bool emt = rough_film && sc->effects.flow_factors == VL_FLOW_FACTORS_PERSSON_EMT;
  if (film_cutoff_m) *film_cutoff_m = emt ? sc->effects.film_cutoff_m : 0.0;
  return rough_film ? vl_flow_factors_name(sc->effects.flow_factors) : NULL;
}
