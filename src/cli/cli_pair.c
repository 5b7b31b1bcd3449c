/* `viscolube pair VERB ...` (issue 34): a compound, surface and fluid with
 * the law of the shear stress in their real contact area. Self-contained:
 * its own option loop, so that the command line's shared parser can take
 * it over later. */
#include "cli.h"
#include "viscolube/edit_distance.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PAIR_HELP                                                                                  \
  "usage: viscolube pair list [--json]\n"                                                          \
  "       viscolube pair show   --compound C --surface S --fluid F [--json]\n"                     \
  "       viscolube pair remove --compound C --surface S --fluid F\n"                              \
  "       viscolube pair add    --compound C --surface S --fluid F --law LAW PARAMETERS\n"         \
  "                             [--temperature C] [--eta-ref PA_S] [--description TEXT]\n"         \
  "       viscolube pair calibrate --compound C --surface S --fluid F --measured FILE\n"           \
  "                             [--load N_PER_M] [--radius M] [--temperature C] [--law LAW]\n"     \
  "                             [--check FILE [--check-load N_PER_M] [--check-radius M]\n"         \
  "                             [--check-temperature C]] [--out FILE.csv] [--plot STEM]\n"         \
  "                             [--save] [--json]\n"                                               \
  "\n"                                                                                             \
  "A pair gives sigma_s, the shear stress in the real contact area, as a law of the\n"             \
  "sliding speed v (friction, compare, run, study and Python use it when no sigma_s is\n"          \
  "given):\n"                                                                                      \
  "  constant   sigma_s                                 --sigma-s PA\n"                            \
  "  eyring     sigma_0 + sigma_e asinh(v / v_e)         --sigma-0 PA --sigma-e PA --v-e M_S\n"    \
  "             (sigma_e = k_B T / V_a: scales with the absolute temperature)\n"                   \
  "  dewetting  dry below V_d, wet above, over half a decade\n"                                    \
  "                                          --sigma-dry PA --sigma-wet PA --v-d M_S\n"            \
  "             (V_d = k S^2 / (eta E e), the seed's Eq. 6: moves as 1/eta)\n"                     \
  "calibrate fits LAW (default constant) to a measured curve (speed with its unit in the\n"        \
  "header, e.g. 'v [mm/s]', and mu; CSV, TSV, decimal comma) at the conditions given\n"            \
  "(defaults: friction's), in log10 mu, with 95 %% intervals; --check predicts another\n"          \
  "measured curve; --out writes measured, fitted mu and its parts as CSV, --plot\n"                \
  "STEM.png/.svg draws them; --save stores the result (refused when the law does not fit).\n"      \
  "Removing a compound, surface or fluid removes its pairs.\n"

typedef struct {
  const char *verb, *compound, *surface, *fluid, *law, *measured, *check, *out, *description;
  const char *plot;
  double p[VL_SHEAR_LAW_MAX_PARAMS];
  bool p_given[VL_SHEAR_LAW_MAX_PARAMS];
  double load, radius, temperature, eta_ref, check_load, check_radius, check_temperature;
  bool save, json;
} pair_args;

static int usage_error(const char *fmt, const char *what) {
  fprintf(stderr, "viscolube pair: ");
  fprintf(stderr, fmt, what);
  fprintf(stderr, " (see viscolube pair --help)\n");
  return vl_status_exit_code(VL_EINPUT);
}

/* The value options that take a number, and where they go. */
static double *number_slot(pair_args *a, const char *o, int *param) {
  static const char *const params[][VL_SHEAR_LAW_MAX_PARAMS] = {
      {"--sigma-s", "--sigma-0", "--sigma-dry"},
      {"--sigma-e", "--sigma-wet", NULL},
      {"--v-e", "--v-d", NULL}};
  *param = -1;
  for (int k = 0; k < VL_SHEAR_LAW_MAX_PARAMS; k++)
    for (int j = 0; j < 3; j++)
      if (params[k][j] && !strcmp(o, params[k][j])) return *param = k, &a->p[k];
  return !strcmp(o, "--load")                ? &a->load
         : !strcmp(o, "--radius")            ? &a->radius
         : !strcmp(o, "--temperature")       ? &a->temperature
         : !strcmp(o, "--eta-ref")           ? &a->eta_ref
         : !strcmp(o, "--check-load")        ? &a->check_load
         : !strcmp(o, "--check-radius")      ? &a->check_radius
         : !strcmp(o, "--check-temperature") ? &a->check_temperature
                                             : NULL;
}

static const char **text_slot(pair_args *a, const char *o) {
  return !strcmp(o, "--compound")      ? &a->compound
         : !strcmp(o, "--surface")     ? &a->surface
         : !strcmp(o, "--fluid")       ? &a->fluid
         : !strcmp(o, "--law")         ? &a->law
         : !strcmp(o, "--measured")    ? &a->measured
         : !strcmp(o, "--check")       ? &a->check
         : !strcmp(o, "--out")         ? &a->out
         : !strcmp(o, "--plot")        ? &a->plot
         : !strcmp(o, "--description") ? &a->description
                                       : NULL;
}

/* An unknown option, with the nearest known one when it is within two
 * edits (a swap of neighbours counting as one), as the other commands say. */
static int unknown_option(const char *o) {
  static const char *const known[] = {"--sigma-s",      "--sigma-0",
                                      "--sigma-dry",    "--sigma-e",
                                      "--sigma-wet",    "--v-e",
                                      "--v-d",          "--load",
                                      "--radius",       "--temperature",
                                      "--eta-ref",      "--check-load",
                                      "--check-radius", "--check-temperature",
                                      "--compound",     "--surface",
                                      "--fluid",        "--law",
                                      "--measured",     "--check",
                                      "--out",          "--plot",
                                      "--description",  "--save",
                                      "--json"};
  const char *best = NULL;
  size_t best_d = 3;
  for (size_t k = 0; k < sizeof known / sizeof *known; k++) {
    size_t d = vl_edit_distance(o, strlen(o), known[k], strlen(known[k]), true);
    if (d < best_d) best_d = d, best = known[k];
  }
  if (!best) return usage_error("unknown option '%s'", o);
  fprintf(stderr, "viscolube pair: unknown option '%s' (did you mean %s?)\n", o, best);
  return vl_status_exit_code(VL_EINPUT);
}

static int parse_args(int argc, char **argv, pair_args *a) {
  memset(a, 0, sizeof *a);
  a->load = VL_QUERY_LOAD_N_PER_M, a->radius = VL_QUERY_RADIUS_M;
  a->temperature = a->eta_ref = a->check_load = a->check_radius = a->check_temperature = NAN;
  a->verb = argc > 1 ? argv[1] : NULL;
  for (int i = 2; i < argc; i++) {
    const char *o = argv[i];
    if (!strcmp(o, "--save")) {
      a->save = true;
      continue;
    }
    if (!strcmp(o, "--json")) {
      a->json = true;
      continue;
    }
    int param;
    double *num = number_slot(a, o, &param);
    const char **txt = num ? NULL : text_slot(a, o);
    if (!num && !txt) return unknown_option(o);
    if (i + 1 >= argc) return usage_error("option %s needs a value", o);
    const char *v = argv[++i];
    if (txt) {
      *txt = v;
      continue;
    }
    const char *why = NULL;
    if (vl_csv_parse_double(v, num, &why) != VL_OK) {
      fprintf(stderr, "viscolube pair: option %s needs a number (got '%s': %s)\n", o, v, why);
      return vl_status_exit_code(VL_EINPUT);
    }
    if (param >= 0) a->p_given[param] = true;
  }
  return 0;
}

static int need_names(const pair_args *a) {
  if (!a->compound) return usage_error("%s needs --compound", a->verb);
  if (!a->surface) return usage_error("%s needs --surface", a->verb);
  if (!a->fluid) return usage_error("%s needs --fluid", a->verb);
  return 0;
}

static int fail(vl_status st, const vl_error *err) {
  fprintf(stderr, "viscolube pair: %s\n", err->msg);
  return vl_status_exit_code(st);
}

/* ---- list, show ------------------------------------------------------- */

static void law_text(const vl_shear_law *l, const double *ci, char *buf, size_t size) {
  size_t len = (size_t)snprintf(buf, size, "%s", vl_shear_law_name(l->kind));
  for (size_t k = 0; k < vl_shear_law_n_params(l->kind) && len < size; k++) {
    len += (size_t)snprintf(buf + len, size - len, "%s %s = %.5g", k ? "," : ":",
                            vl_shear_law_param_name(l->kind, k), l->p[k]);
    if (ci && isfinite(ci[k]) && len < size)
      len += (size_t)snprintf(buf + len, size - len, " +- %.2g", ci[k]);
  }
}

static void pair_json(vl_json *w, const vl_db_pair *p) {
  vl_json_object_begin(w, VL_JSON_INLINE);
  vl_json_key_string(w, "compound", p->compound);
  vl_json_key_string(w, "surface", p->surface);
  vl_json_key_string(w, "fluid", p->fluid);
  vl_json_key_string(w, "law", vl_shear_law_name(p->law.kind));
  vl_json_key(w, "parameters");
  vl_json_object_begin(w, VL_JSON_INLINE);
  for (size_t k = 0; k < vl_shear_law_n_params(p->law.kind); k++)
    vl_json_key_number(w, vl_shear_law_param_name(p->law.kind, k), p->law.p[k]);
  vl_json_end(w);
  vl_json_key(w, "ci95");
  vl_json_object_begin(w, VL_JSON_INLINE);
  for (size_t k = 0; k < vl_shear_law_n_params(p->law.kind); k++) {
    vl_json_key(w, vl_shear_law_param_name(p->law.kind, k));
    if (isfinite(p->ci95[k]))
      vl_json_number(w, p->ci95[k]);
    else
      vl_json_null(w);
  }
  vl_json_end(w);
  vl_json_key_string(w, "source", p->source);
  vl_json_key_string(w, "description", p->description);
  if (!strcmp(p->source, VL_DB_SOURCE_CALIBRATED)) {
    vl_json_key_string(w, "measured_file", p->measured_file);
    vl_json_key_string(w, "measured_fingerprint", p->measured_fingerprint);
    vl_json_key_integer(w, "n_points", (long long)p->n_points);
    vl_json_key_number(w, "load_n_per_m", p->load_n_per_m);
    vl_json_key_number(w, "radius_m", p->radius_m);
    vl_json_key(w, "temperature_c");
    if (isfinite(p->temperature_c))
      vl_json_number(w, p->temperature_c);
    else
      vl_json_null(w);
    vl_json_key_number(w, "rms_log10_mu", p->rms_log10_mu);
  }
  vl_json_key_string(w, "created_at", p->created_at);
  vl_json_end(w);
}

static void pair_text(const vl_db_pair *p) {
  char law[512];
  law_text(&p->law, p->ci95, law, sizeof law);
  printf("%s / %s / %s: %s\n", p->compound, p->surface, p->fluid, law);
  printf("  %s %s", p->source, p->created_at);
  if (!strcmp(p->source, VL_DB_SOURCE_CALIBRATED)) {
    printf(" from %s (%s, %zu points) at %g N/m, R %g m", p->measured_file, p->measured_fingerprint,
           p->n_points, p->load_n_per_m, p->radius_m);
    if (isfinite(p->temperature_c)) printf(", %g C", p->temperature_c);
    printf(", rms %.3g in log10 mu", p->rms_log10_mu);
  }
  if (p->description[0]) printf(": %s", p->description);
  putchar('\n');
}

static int do_list(vl_db *db, const pair_args *a) {
  vl_db_pair *items = NULL;
  size_t n = 0;
  vl_error err;
  vl_status st = vl_db_pair_list(db, &items, &n, &err);
  if (st != VL_OK) return fail(st, &err);
  if (a->json) {
    vl_json w;
    vl_json_init(&w, stdout, 10);
    vl_json_array_begin(&w, VL_JSON_ROWS);
    for (size_t i = 0; i < n; i++)
      pair_json(&w, &items[i]);
    vl_json_end(&w);
    fputc('\n', stdout);
  } else {
    if (n == 0) printf("no pairs: every run uses its constant sigma_s\n");
    for (size_t i = 0; i < n; i++)
      pair_text(&items[i]);
  }
  free(items);
  return 0;
}

static int do_show(vl_db *db, const pair_args *a) {
  int rc = need_names(a);
  if (rc) return rc;
  vl_db_pair p;
  vl_error err;
  vl_status st = vl_db_pair_get(db, a->compound, a->surface, a->fluid, &p, NULL, &err);
  if (st != VL_OK) return fail(st, &err);
  if (a->json) {
    vl_json w;
    vl_json_init(&w, stdout, 10);
    pair_json(&w, &p);
    fputc('\n', stdout);
  } else {
    pair_text(&p);
  }
  return 0;
}

static int do_remove(vl_db *db, const pair_args *a, int quiet) {
  int rc = need_names(a);
  if (rc) return rc;
  vl_error err;
  vl_status st = vl_db_pair_remove(db, a->compound, a->surface, a->fluid, &err);
  if (st != VL_OK) return fail(st, &err);
  if (!quiet)
    printf("removed pair '%s / %s / %s' from %s\n", a->compound, a->surface, a->fluid,
           vl_db_path(db));
  return 0;
}

/* A pair of a's names, law and source (the rest empty). */
static vl_db_pair pair_of(const pair_args *a, vl_shear_law law, const char *source) {
  vl_db_pair p;
  memset(&p, 0, sizeof p);
  snprintf(p.compound, sizeof p.compound, "%s", a->compound);
  snprintf(p.surface, sizeof p.surface, "%s", a->surface);
  snprintf(p.fluid, sizeof p.fluid, "%s", a->fluid);
  snprintf(p.source, sizeof p.source, "%s", source);
  if (a->description) snprintf(p.description, sizeof p.description, "%s", a->description);
  p.law = law;
  for (int k = 0; k < VL_SHEAR_LAW_MAX_PARAMS; k++)
    p.ci95[k] = NAN;
  p.load_n_per_m = p.radius_m = p.temperature_c = p.rms_log10_mu = NAN;
  return p;
}

static int do_add(vl_db *db, const pair_args *a, int quiet) {
  int rc = need_names(a);
  if (rc) return rc;
  vl_error err;
  vl_shear_law law = {VL_SHEAR_CONSTANT, {0, 0, 0}, a->temperature, a->eta_ref};
  if (!a->law) return usage_error("%s needs --law constant|eyring|dewetting", "add");
  vl_status st = vl_shear_law_parse(a->law, &law.kind, &err);
  if (st != VL_OK) return fail(st, &err);
  for (size_t k = 0; k < vl_shear_law_n_params(law.kind); k++) {
    if (!a->p_given[k]) {
      fprintf(stderr, "viscolube pair: add: the %s law needs %s\n", a->law,
              vl_shear_law_param_name(law.kind, k));
      return vl_status_exit_code(VL_EINPUT);
    }
    law.p[k] = a->p[k];
  }
  vl_db_pair p = pair_of(a, law, VL_DB_SOURCE_TYPED);
  st = vl_db_pair_add(db, &p, &err);
  if (st != VL_OK) return fail(st, &err);
  if (!quiet)
    printf("added pair '%s / %s / %s' to %s: %s law, typed in\n", a->compound, a->surface, a->fluid,
           vl_db_path(db), a->law);
  return 0;
}

int vl_cli_pair_calibrate(vl_db *db, const pair_args *a, int quiet);

int vl_cli_pair(const vl_cli_globals *g, int argc, char **argv) {
  if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    fputs(PAIR_HELP, argc < 2 ? stderr : stdout);
    return argc < 2 ? vl_status_exit_code(VL_EINPUT) : 0;
  }
  pair_args a;
  int rc = parse_args(argc, argv, &a);
  if (rc) return rc;
  static const char *const verbs[] = {"list", "show", "add", "remove", "calibrate"};
  size_t v = 0;
  while (v < 5 && strcmp(a.verb, verbs[v]))
    v++;
  if (v == 5) return usage_error("unknown verb '%s' (list, show, add, remove, calibrate)", a.verb);
  vl_db *db = NULL;
  vl_error err;
  vl_status st = vl_db_open(g->db_path, &db, &err);
  if (st != VL_OK) return fail(st, &err);
  rc = v == 0   ? do_list(db, &a)
       : v == 1 ? do_show(db, &a)
       : v == 2 ? do_add(db, &a, g->quiet)
       : v == 3 ? do_remove(db, &a, g->quiet)
                : vl_cli_pair_calibrate(db, &a, g->quiet);
  vl_db_close(db);
  return rc;
}

/* ---- calibrate -------------------------------------------------------- */

static vl_query calibration_query(const pair_args *a, double load, double radius, double t_c) {
  vl_query q;
  vl_query_defaults(&q);
  q.compound = a->compound, q.surface = a->surface, q.fluid = a->fluid;
  q.load_n_per_m = load, q.radius_m = radius;
  q.at_temperature = isfinite(t_c);
  q.temperature_c = t_c;
  return q;
}

/* A measured curve's sweep: the file read, its fingerprint, the sweep. */
static vl_status measured_sweep(vl_db *db, const char *path, const vl_query *q,
                                vl_calibration_sweep *s, char fingerprint[VL_DB_FINGERPRINT_MAX],
                                vl_error *err) {
  double *v = NULL, *mu = NULL;
  size_t n = 0;
  vl_status st = vl_friction_curve_read_file(path, &v, &mu, &n, err);
  if (st != VL_OK) return st;
  char *text = vl_cli_read_text(path);
  if (text) vl_db_fingerprint_bytes(text, strlen(text), fingerprint);
  free(text);
  st = vl_calibration_sweep_run(db, q, n, v, mu, s, err);
  if (st != VL_OK) vl_error_prefix(err, "%s", path);
  free(v);
  free(mu);
  return st;
}

/* The measured points, the fitted mu and its parts, one row a point. */
static vl_status write_fit_csv(const char *path, const vl_calibration_sweep *s,
                               const vl_calibration_fit *f, vl_error *err) {
  vl_atomic_file af;
  vl_status st = vl_atomic_file_open(&af, path, err);
  if (st != VL_OK) return st;
  char law[512];
  law_text(&f->law, f->ci95, law, sizeof law);
  fprintf(af.f, "# sigma_s = %s; rms %.4g in log10 mu\n", law, f->rms_log10_mu);
  fprintf(af.f, "v_m_s,mu_measured,mu_fit,mu_other,mu_Sc_fit,sigma_s_pa,converged,informative\n");
  for (size_t i = 0; i < s->n; i++) {
    double sigma = vl_shear_law_eval(&f->law, s->v_m_s[i], NULL);
    fprintf(af.f, "%.10g,%.10g", s->v_m_s[i], s->mu[i]);
    if (s->converged[i])
      fprintf(af.f, ",%.10g,%.10g,%.10g", vl_calibration_model_mu(s, i, &f->law), s->mu_other[i],
              sigma * s->area[i]);
    else
      fprintf(af.f, ",,,");
    fprintf(af.f, ",%.10g,%d,%d\n", sigma, s->converged[i], !f->uninformative[i]);
  }
  return vl_atomic_file_commit(&af, err);
}

/* The figure: measured points over the fitted mu and its parts. */
static vl_status plot_fit(const char *stem, const vl_calibration_sweep *s,
                          const vl_calibration_fit *f, vl_error *err) {
  double *y = malloc(3 * s->n * sizeof *y);
  bool *informative = malloc(s->n * sizeof *informative);
  if (!y || !informative) {
    free(y), free(informative);
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  for (size_t i = 0; i < s->n; i++) {
    double sc = vl_shear_law_eval(&f->law, s->v_m_s[i], NULL) * s->area[i];
    y[i] = s->converged[i] ? vl_calibration_model_mu(s, i, &f->law) : NAN;
    y[s->n + i] = s->converged[i] ? s->mu_other[i] : NAN;
    y[2 * s->n + i] = s->converged[i] ? sc : NAN;
    informative[i] = !f->uninformative[i];
  }
  char label[64], title[128];
  snprintf(label, sizeof label, "fitted μ (%s law)", vl_shear_law_name(f->law.kind));
  snprintf(title, sizeof title, "calibration: rms %.3g in log10 μ", f->rms_log10_mu);
  vl_plot_calibration_data d = {s->n,     s->v_m_s,     s->mu,       y,
                                y + s->n, y + 2 * s->n, informative, label};
  vl_plot_options opt;
  vl_plot_options_defaults(&opt);
  opt.title = title;
  vl_status st = vl_plot_calibration(stem, &d, &opt, NULL, err);
  free(y);
  free(informative);
  return st;
}

static void points_list(const vl_calibration_sweep *s, const bool *flag, bool want, char *buf,
                        size_t size) {
  size_t len = 0;
  buf[0] = '\0';
  for (size_t i = 0; i < s->n && len < size; i++)
    if (flag[i] == want)
      len += (size_t)snprintf(buf + len, size - len, "%s%.3g", len ? ", " : "", s->v_m_s[i]);
}

static void print_fit(const pair_args *a, const vl_calibration_sweep *s,
                      const vl_calibration_fit *f, double check_rms) {
  char law[512], list[1024];
  law_text(&f->law, f->ci95, law, sizeof law);
  printf("%s / %s / %s on %s (%zu points, %zu used):\n  %s (95 %% intervals)\n", a->compound,
         a->surface, a->fluid, a->measured, s->n, f->n_used, law);
  printf("  rms misfit %.4g in log10 mu (a factor %.3f)\n", f->rms_log10_mu,
         pow(10.0, f->rms_log10_mu));
  if (f->n_unreached) {
    points_list(s, s->converged, false, list, sizeof list);
    printf("  not reached by the solver (left out): v = %s m/s\n", list);
  }
  if (f->n_uninformative) {
    points_list(s, f->uninformative, true, list, sizeof list);
    printf("  mu_Sc below %g %% of mu (they inform the fit little): v = %s m/s\n",
           100 * VL_CALIBRATION_MIN_SC_SHARE, list);
  }
  if (a->check) printf("  prediction of %s: rms misfit %.4g in log10 mu\n", a->check, check_rms);
  printf("  cost: one sweep %.2f s, fit %.3g s (%d iterations)\n", s->seconds, f->seconds,
         f->iterations);
  if (!f->fits) printf("  DOES NOT FIT: %s\n", f->why);
}

static void fit_json(const vl_calibration_sweep *s, const vl_calibration_fit *f, const pair_args *a,
                     double check_rms) {
  vl_json w;
  vl_json_init(&w, stdout, 10);
  vl_json_object_begin(&w, VL_JSON_INLINE);
  vl_json_key_string(&w, "law", vl_shear_law_name(f->law.kind));
  size_t np = vl_shear_law_n_params(f->law.kind);
  vl_json_key(&w, "parameters");
  vl_json_object_begin(&w, VL_JSON_INLINE);
  for (size_t k = 0; k < np; k++)
    vl_json_key_number(&w, vl_shear_law_param_name(f->law.kind, k), f->law.p[k]);
  vl_json_end(&w);
  vl_json_key(&w, "ci95");
  vl_json_object_begin(&w, VL_JSON_INLINE);
  for (size_t k = 0; k < np; k++)
    vl_json_key_number(&w, vl_shear_law_param_name(f->law.kind, k), f->ci95[k]);
  vl_json_end(&w);
  vl_json_key_number(&w, "rms_log10_mu", f->rms_log10_mu);
  vl_json_key_integer(&w, "n_points", (long long)s->n);
  vl_json_key_integer(&w, "n_used", (long long)f->n_used);
  vl_json_key(&w, "unreached_v_m_s");
  vl_json_array_begin(&w, VL_JSON_INLINE);
  for (size_t i = 0; i < s->n; i++)
    if (!s->converged[i]) vl_json_number(&w, s->v_m_s[i]);
  vl_json_end(&w);
  vl_json_key(&w, "uninformative_v_m_s");
  vl_json_array_begin(&w, VL_JSON_INLINE);
  for (size_t i = 0; i < s->n; i++)
    if (f->uninformative[i]) vl_json_number(&w, s->v_m_s[i]);
  vl_json_end(&w);
  vl_json_key(&w, "fits");
  vl_json_bool(&w, f->fits);
  if (!f->fits) vl_json_key_string(&w, "why", f->why);
  if (a->check) {
    vl_json_key_string(&w, "check_file", a->check);
    vl_json_key_number(&w, "check_rms_log10_mu", check_rms);
  }
  vl_json_key_number(&w, "sweep_seconds", s->seconds);
  vl_json_key_number(&w, "fit_seconds", f->seconds);
  vl_json_end(&w);
  fputc('\n', stdout);
}

static int save_fit(vl_db *db, const pair_args *a, const vl_calibration_sweep *s,
                    const vl_calibration_fit *f, const char *fingerprint, int quiet) {
  vl_error err;
  if (!f->fits) {
    fprintf(stderr, "viscolube pair: calibrate: not stored: %s\n", f->why);
    return vl_status_exit_code(VL_EINPUT);
  }
  vl_db_pair p = pair_of(a, f->law, VL_DB_SOURCE_CALIBRATED);
  memcpy(p.ci95, f->ci95, sizeof p.ci95);
  snprintf(p.measured_file, sizeof p.measured_file, "%s", a->measured);
  snprintf(p.measured_fingerprint, sizeof p.measured_fingerprint, "%s", fingerprint);
  p.n_points = f->n_used;
  p.load_n_per_m = a->load, p.radius_m = a->radius, p.temperature_c = s->temperature_c;
  p.rms_log10_mu = f->rms_log10_mu;
  vl_status st = vl_db_pair_add(db, &p, &err);
  if (st != VL_OK) return fail(st, &err);
  if (!quiet && !a->json)
    printf("stored as the pair: added pair '%s / %s / %s' to %s\n", a->compound, a->surface,
           a->fluid, vl_db_path(db));
  return 0;
}

int vl_cli_pair_calibrate(vl_db *db, const pair_args *a, int quiet) {
  int rc = need_names(a);
  if (rc) return rc;
  if (!a->measured) return usage_error("%s needs --measured FILE", "calibrate");
  vl_error err;
  vl_shear_law_kind kind = VL_SHEAR_CONSTANT;
  vl_status st = a->law ? vl_shear_law_parse(a->law, &kind, &err) : VL_OK;
  if (st != VL_OK) return fail(st, &err);
  vl_query q = calibration_query(a, a->load, a->radius, a->temperature);
  vl_calibration_sweep s, cs = {0};
  vl_calibration_fit f = {0};
  char fingerprint[VL_DB_FINGERPRINT_MAX] = "", check_fp[VL_DB_FINGERPRINT_MAX];
  double check_rms = NAN;
  if ((st = measured_sweep(db, a->measured, &q, &s, fingerprint, &err)) != VL_OK)
    return fail(st, &err);
  st = vl_calibration_fit_law(&s, kind, &f, &err);
  if (st == VL_OK && a->check) {
    vl_query cq =
        calibration_query(a, isfinite(a->check_load) ? a->check_load : a->load,
                          isfinite(a->check_radius) ? a->check_radius : a->radius,
                          isfinite(a->check_temperature) ? a->check_temperature : a->temperature);
    st = measured_sweep(db, a->check, &cq, &cs, check_fp, &err);
    if (st == VL_OK) check_rms = vl_calibration_misfit(&cs, &f.law);
  }
  if (st == VL_OK && a->out && (st = write_fit_csv(a->out, &s, &f, &err)) != VL_OK)
    vl_error_prefix(&err, "--out");
  if (st == VL_OK && a->plot && (st = plot_fit(a->plot, &s, &f, &err)) != VL_OK)
    vl_error_prefix(&err, "--plot");
  if (st != VL_OK) {
    rc = fail(st, &err);
  } else {
    if (a->json)
      fit_json(&s, &f, a, check_rms);
    else
      print_fit(a, &s, &f, check_rms);
    rc = a->save ? save_fit(db, a, &s, &f, fingerprint, quiet)
                 : (f.fits ? 0 : vl_status_exit_code(VL_EINPUT));
  }
  vl_calibration_fit_free(&f);
  vl_calibration_sweep_free(&s);
  vl_calibration_sweep_free(&cs);
  return rc;
}
