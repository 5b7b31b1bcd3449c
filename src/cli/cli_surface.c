/* The surface verbs beyond list/show/add/remove: `surface flow-factors`
 * (the flow-factor table of a stored surface) and `surface add NAME
 * --topography FILE` (a surface from measured heights). cli_materials.c
 * parses their command lines; this file checks the values, computes and
 * prints. As elsewhere, inputs are read and checked before the database is
 * opened, messages are one line on stderr, results go to stdout. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

#define FF_MAX_POINTS 10000
#define FF_X_LO 1e-3
#define FF_X_HI 30.0

/* patir-cheng's flow stops at H = 0, where u/sigma = phi(0) = 1/sqrt(2 pi)
 * (flow_factors.h). */
#define PATIR_CHENG_PERCOLATION 0.3989422804014327

static int failf(const char *verb, vl_status st, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* One message "viscolube surface VERB: ..." on stderr; the exit code. */
static int failf(const char *verb, vl_status st, const char *fmt, ...) {
  char buf[VL_ERROR_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  fprintf(stderr, "viscolube surface %s: %s\n", verb, buf);
  return vl_status_exit_code(st);
}

/* ---- flow-factors: the request --------------------------------------- */

typedef struct {
  vl_flow_factor_kind kind;
  double x_lo, x_hi; /* u/h_rms */
  size_t n;
  double cutoff_m; /* persson-emt only */
} ff_request;

/* MIN,MAX with 0 < MIN < MAX, both finite. */
static int parse_range(const char *text, double *lo, double *hi) {
  const char *comma = strchr(text, ',');
  char a[64];
  size_t len = comma ? (size_t)(comma - text) : 0;
  if (!comma || len >= sizeof a) return 0;
  memcpy(a, text, len);
  a[len] = '\0';
  return vl_csv_parse_double(a, lo, NULL) == VL_OK &&
         vl_csv_parse_double(comma + 1, hi, NULL) == VL_OK && *lo > 0.0 && *hi > *lo;
}

/* Checks the option values into r. Returns -1, else the exit code after
 * the message. */
static int ff_check(const vl_cli_flow_factor_args *a, ff_request *r) {
  const char *verb = "flow-factors";
  vl_error err;
  *r = (ff_request){VL_FLOW_FACTORS_PERSSON_EMT, FF_X_LO, FF_X_HI, 100, VL_FILM_CUTOFF_DEFAULT_M};
  if (a->model && vl_flow_factors_parse(a->model, &r->kind, &err) != VL_OK)
    return failf(verb, VL_EINPUT, "option --model: %s", err.msg);
  if (a->u_range && !parse_range(a->u_range, &r->x_lo, &r->x_hi))
    return failf(verb, VL_EINPUT,
                 "option --u-range: expected MIN,MAX (u/h_rms) with 0 < MIN < MAX (got '%s')",
                 a->u_range);
  if (a->points) {
    double d;
    if (vl_csv_parse_double(a->points, &d, NULL) != VL_OK || d != floor(d) || d < 2 ||
        d > FF_MAX_POINTS)
      return failf(verb, VL_EINPUT,
                   "option --points: expected a whole number in [2, %d] (got '%s')", FF_MAX_POINTS,
                   a->points);
    r->n = (size_t)d;
  }
  if (a->film_cutoff) {
    if (r->kind != VL_FLOW_FACTORS_PERSSON_EMT)
      return failf(verb, VL_EINPUT, "option --film-cutoff applies to --model persson-emt only");
    if (vl_csv_parse_double(a->film_cutoff, &r->cutoff_m, NULL) != VL_OK ||
        !(r->cutoff_m > 0.0 && r->cutoff_m <= VL_FILM_CUTOFF_MAX_M))
      return failf(verb, VL_EINPUT,
                   "option --film-cutoff: expected a length in (0, %g] m (got '%s')",
                   VL_FILM_CUTOFF_MAX_M, a->film_cutoff);
  }
  if (a->out && strlen(a->out) >= 4096) /* PATH_MAX, with room for the figures' names */
    return failf(verb, VL_EINPUT, "option --out: file name longer than 4095 characters");
  return -1;
}

/* ---- flow-factors: the table ----------------------------------------- */

enum { C_X, C_AREA, C_P, C_S, C_FP, C_FS, C_F, N_COLS };

static const char *const col_name[N_COLS] = {"u_over_hrms", "contact_fraction", "phi_p", "phi_s",
                                             "phi_fp",      "phi_fs",           "phi_f"};

typedef struct {
  size_t n;
  double *col[N_COLS]; /* col[k][i]: column k of row i (one allocation, col[0]) */
  double hrms_m;
  double x_perc;  /* NAN: the model has none */
  int from_cache; /* persson-emt: the table was read from the database */
} ff_table;

/* The rows of r for the surface whose spectrum is psd: Persson's table for
 * A/A0 and, for persson-emt, the factor table, both through the database's
 * caches. */
static vl_status ff_compute(vl_db *db, const char *name, const vl_psd *psd, const ff_request *r,
                            ff_table *t, vl_error *err) {
  vl_persson *pt = NULL;
  vl_emt_table *et = NULL;
  bool cached = false;
  vl_status st = vl_db_persson_table(db, name, psd, 0, &pt, NULL, err);
  if (st == VL_OK && r->kind == VL_FLOW_FACTORS_PERSSON_EMT)
    st = vl_db_flow_table(db, name, psd, r->cutoff_m, 0, &et, &cached, err);
  if (st == VL_OK && !(t->col[0] = malloc(N_COLS * r->n * sizeof(double)))) {
    vl_error_set(err, "out of memory");
    st = VL_ENOMEM;
  }
  if (st != VL_OK) goto cleanup;
  t->n = r->n;
  for (size_t k = 1; k < N_COLS; k++)
    t->col[k] = t->col[0] + k * r->n;
  t->from_cache = cached;
  t->hrms_m = et ? vl_emt_table_hrms(et) : vl_psd_hrms(psd);
  t->x_perc = et                                       ? vl_emt_table_percolation(et)
              : r->kind == VL_FLOW_FACTORS_PATIR_CHENG ? PATIR_CHENG_PERCOLATION
                                                       : NAN;
  for (size_t i = 0; i < r->n; i++) {
    /* log spaced, both ends exact */
    double x =
        i + 1 == r->n ? r->x_hi : r->x_lo * pow(r->x_hi / r->x_lo, (double)i / (double)(r->n - 1));
    double u = x * t->hrms_m;
    vl_flow_factor_values v;
    if (et)
      vl_emt_table_eval(et, u, &v, NULL);
    else
      vl_flow_factors_eval(r->kind, u, t->hrms_m, &v, NULL);
    t->col[C_X][i] = x;
    t->col[C_AREA][i] = vl_persson_area_ratio(pt, vl_persson_pressure(pt, u, NULL), NULL);
    t->col[C_P][i] = v.phi_p;
    t->col[C_S][i] = v.phi_s;
    t->col[C_FP][i] = v.phi_fp;
    t->col[C_FS][i] = v.phi_fs;
    t->col[C_F][i] = v.phi_f;
  }
cleanup:
  vl_emt_table_free(et);
  vl_persson_free(pt);
  return st;
}

/* A number that reads back to the same double, with the JSON writer's
 * exact rule (json.h, digits 0): 15 significant digits, 17 when 15 do not
 * suffice, so the CSV and --json agree bit for bit. */
static void put_exact(FILE *f, double v) {
  char buf[40];
  snprintf(buf, sizeof buf, "%.15g", v);
  if (strtod(buf, NULL) != v) snprintf(buf, sizeof buf, "%.17g", v);
  fputs(buf, f);
}

static vl_status ff_write_csv(const char *path, const char *name, const ff_request *r,
                              const ff_table *t, vl_error *err) {
  vl_atomic_file af;
  if (vl_atomic_file_open(&af, path, err) != VL_OK) return VL_EIO;
  FILE *f = af.f;
  fprintf(f, "# flow factors of surface %s, model %s, h_rms %.10g m, film_cutoff_m ", name,
          vl_flow_factors_name(r->kind), t->hrms_m);
  if (r->kind == VL_FLOW_FACTORS_PERSSON_EMT)
    fprintf(f, "%.10g", r->cutoff_m);
  else
    fputs("none", f);
  if (isfinite(t->x_perc)) fprintf(f, ", percolation_u_over_hrms %.10g", t->x_perc);
  fputc('\n', f);
  for (size_t k = 0; k < N_COLS; k++)
    fprintf(f, "%s%s", k ? "," : "", col_name[k]);
  fputc('\n', f);
  for (size_t i = 0; i < t->n; i++) {
    for (size_t k = 0; k < N_COLS; k++) {
      if (k) fputc(',', f);
      put_exact(f, t->col[k][i]);
    }
    fputc('\n', f);
  }
  return vl_atomic_file_commit(&af, err);
}

static vl_status ff_plot(const char *stem, const char *name, const ff_request *r, const ff_table *t,
                         vl_error *err) {
  char title[160];
  snprintf(title, sizeof title, "Flow factors: %s (%s)", name, vl_flow_factors_name(r->kind));
  vl_plot_options opt;
  vl_plot_options_defaults(&opt);
  opt.title = title;
  vl_plot_flow_factor_data d = {t->n,        t->col[C_X],    t->col[C_P],
                                t->col[C_S], t->col[C_FP],   t->col[C_FS],
                                t->col[C_F], t->col[C_AREA], t->x_perc};
  return vl_plot_flow_factors(stem, &d, &opt, NULL, err);
}

static void ff_print_json(const char *name, const ff_request *r, const ff_table *t) {
  vl_json w;
  vl_json_init(&w, stdout, 0); /* exact: the numbers of the CSV */
  vl_json_object_begin(&w, VL_JSON_INLINE);
  vl_json_key_string(&w, "surface", name);
  vl_json_key_string(&w, "model", vl_flow_factors_name(r->kind));
  vl_json_key_number(&w, "hrms_m", t->hrms_m);
  vl_json_key_number(&w, "film_cutoff_m",
                     r->kind == VL_FLOW_FACTORS_PERSSON_EMT ? r->cutoff_m : NAN);
  vl_json_key_number(&w, "percolation_u_over_hrms", t->x_perc);
  vl_json_key(&w, "rows");
  vl_json_array_begin(&w, VL_JSON_STACKED);
  for (size_t i = 0; i < t->n; i++) {
    vl_json_object_begin(&w, VL_JSON_INLINE);
    for (size_t k = 0; k < N_COLS; k++)
      vl_json_key_number(&w, col_name[k], t->col[k][i]);
    vl_json_end(&w);
  }
  vl_json_end(&w);
  vl_json_end(&w);
  fputc('\n', stdout);
}

static void ff_print_text(const char *name, const ff_request *r, const ff_table *t) {
  printf("flow factors of surface %s, model %s: h_rms %.6g m", name, vl_flow_factors_name(r->kind),
         t->hrms_m);
  if (r->kind == VL_FLOW_FACTORS_PERSSON_EMT)
    printf(", film cut-off %.6g m, percolation at u/h_rms = %.6g (table %s)\n", r->cutoff_m,
           t->x_perc, t->from_cache ? "from the database cache" : "built");
  else if (isfinite(t->x_perc))
    printf(", percolation at u/h_rms = %.6g\n", t->x_perc);
  else
    printf("\n");
  printf("%12s %16s", col_name[0], col_name[1]);
  for (size_t k = 2; k < N_COLS; k++)
    printf(" %12s", col_name[k]);
  printf("\n");
  for (size_t i = 0; i < t->n; i++) {
    printf("%12.6g %16.6g", t->col[C_X][i], t->col[C_AREA][i]);
    for (size_t k = 2; k < N_COLS; k++)
      printf(" %12.6g", t->col[k][i]);
    printf("\n");
  }
}

/* The figure's stem: --out FILE without its extension, else
 * flow-factors-NAME in the current directory. */
static void plot_stem(char *stem, size_t size, const char *out, const char *name) {
  if (!out) {
    snprintf(stem, size, "flow-factors-%s", name);
    return;
  }
  snprintf(stem, size, "%s", out);
  char *slash = strrchr(stem, '/'), *base = slash ? slash + 1 : stem, *dot = strrchr(base, '.');
  if (dot && dot > base) *dot = '\0'; /* "dir/.hidden" keeps its name */
}

int vl_cli_surface_flow_factors(const vl_cli_globals *g, const char *name,
                                const vl_cli_flow_factor_args *a) {
  ff_request r;
  int rc = ff_check(a, &r);
  if (rc >= 0) return rc;
  vl_error err = {{0}};
  vl_db *db = NULL;
  vl_psd psd;
  memset(&psd, 0, sizeof psd);
  int have_psd = 0;
  ff_table t = {0};
  char stem[VL_ATOMIC_PATH_MAX];
  plot_stem(stem, sizeof stem, a->out, name);
  vl_status st = vl_db_open(g->db_path, &db, &err);
  if (st == VL_OK) have_psd = (st = vl_db_surface_get(db, name, &psd, &err)) == VL_OK;
  if (st == VL_OK) st = ff_compute(db, name, &psd, &r, &t, &err);
  /* the files first: a failure to write them prints no table */
  if (st == VL_OK && a->out) st = ff_write_csv(a->out, name, &r, &t, &err);
  if (st == VL_OK && a->plot) st = ff_plot(stem, name, &r, &t, &err);
  if (st != VL_OK) {
    rc = failf("flow-factors", st, "%s", err.msg[0] ? err.msg : vl_status_name(st));
    goto cleanup;
  }
  if (a->json) {
    ff_print_json(name, &r, &t);
  } else {
    ff_print_text(name, &r, &t);
    if (a->out) printf("wrote %s\n", a->out);
    if (a->plot) printf("wrote %s.png and %s.svg\n", stem, stem);
  }
  rc = 0;
cleanup:
  free(t.col[0]);
  if (have_psd) vl_psd_free(&psd);
  vl_db_close(db);
  return rc;
}

/* ---- add --topography ------------------------------------------------- */

/* The stored description: the provenance, after --description when given
 * (which is kept whole), cut with "..." to fit the database's texts. */
static void topo_description(char *buf, size_t size, const char *user, const char *provenance) {
  char all[2 * VL_DB_TEXT_MAX + 1024];
  snprintf(all, sizeof all, "%s%s%s", user ? user : "", user ? "; " : "", provenance);
  size_t keep = user ? strlen(user) : 0;
  if (strlen(all) < size) {
    snprintf(buf, size, "%s", all);
  } else if (keep + 6 < size) {
    snprintf(buf, size, "%.*s...", (int)(size - 4), all);
  } else {
    snprintf(buf, size, "%s", user); /* no room left for the provenance */
  }
}

/* What was measured and what the spectrum keeps of it. */
static void topo_report(const vl_topography *t, const vl_topography_spectrum *sp, const vl_psd *psd,
                        const char *description) {
  if (t->kind == VL_TOPOGRAPHY_MAP)
    printf("  measured      height map, %zu x %zu px over %.4g x %.4g m (pixel %.4g x %.4g m%s)\n",
           t->nx, t->ny, (double)t->nx * t->dx_m, (double)t->ny * t->dy_m, t->dx_m, t->dy_m,
           t->square_assumed ? ", square assumed: no '# Height:' line" : "");
  else
    printf("  measured      line scan, %zu points over %.4g m (dx %.4g m)\n", t->nx,
           (double)t->nx * t->dx_m, t->dx_m);
  double ratio = vl_psd_hrms(psd) / sp->hrms_topography_m;
  printf("  rms height    %.6g m (%s removed)\n", sp->hrms_topography_m,
         t->kind == VL_TOPOGRAPHY_MAP ? "plane" : "line");
  printf("  h_rms         %.6g m of the tabulated PSD: %.4f x the rms height\n", vl_psd_hrms(psd),
         ratio);
  printf("  band          q %.4g ... %.4g 1/m kept (rms %.6g m)\n", sp->q_min_per_m,
         sp->q_max_per_m, sp->hrms_band_m);
  printf("  PSD points    %zu, q %.4g ... %.4g 1/m\n", sp->n, sp->q_per_m[0],
         sp->q_per_m[sp->n - 1]);
  printf("  rms slope     %.6g\n", vl_psd_rms_slope(psd));
  if (ratio < 0.9)
    printf("  note          the spectrum keeps %.0f %% of the measured rms (power outside the "
           "band, or a window that weighs smoother parts)\n",
           100.0 * ratio);
  printf("  description   %s\n", description);
}

int vl_cli_surface_add_topography(const vl_cli_globals *g, const char *name, const char *path,
                                  const char *description) {
  const char *verb = "add";
  if (strlen(path) >= VL_DB_TEXT_MAX)
    return failf(verb, VL_EINPUT, "option --topography: file name longer than %d characters",
                 VL_DB_TEXT_MAX - 1);
  if (description && strlen(description) >= VL_DB_TEXT_MAX)
    return failf(verb, VL_EINPUT, "option --description: longer than %d characters",
                 VL_DB_TEXT_MAX - 1);
  vl_error err = {{0}};
  vl_topography t = {0};
  vl_topography_spectrum sp = {0};
  vl_psd psd;
  memset(&psd, 0, sizeof psd);
  vl_db *db = NULL;
  char desc[VL_DB_TEXT_MAX];
  int rc;
  vl_status st = vl_topography_read_file(path, &t, &err);
  if (st == VL_OK) st = vl_topography_psd(&t, NULL, &sp, &err);
  if (st == VL_OK) st = vl_psd_init_tabulated(&psd, sp.n, sp.q_per_m, sp.c_m4, &err);
  if (st == VL_OK) {
    topo_description(desc, sizeof desc, description, sp.provenance);
    st = vl_db_open(g->db_path, &db, &err);
  }
  if (st == VL_OK) st = vl_db_surface_add(db, name, &psd, desc, path, &err);
  if (st != VL_OK) {
    rc = failf(verb, st, "%s", err.msg[0] ? err.msg : vl_status_name(st));
    goto cleanup;
  }
  printf("added surface '%s' to %s: tabulated, %zu points, from the %s %s\n", name, vl_db_path(db),
         sp.n, vl_topography_kind_name(t.kind), path);
  topo_report(&t, &sp, &psd, desc);
  rc = 0;
cleanup:
  vl_db_close(db);
  vl_psd_free(&psd);
  vl_topography_spectrum_free(&sp);
  vl_topography_free(&t);
  return rc;
}
