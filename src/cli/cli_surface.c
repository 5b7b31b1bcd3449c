/* `viscolube surface VERB ...`: surface roughness, an isotropic power
 * spectrum C(q), self-affine, tabulated or estimated from measured heights
 * (`add --topography`); what is stored and derived, the spectrum's figure,
 * and `surface flow-factors`, the flow-factor table of a stored surface.
 * As elsewhere, inputs are read and checked before the database is opened,
 * messages are one line on stderr, results go to stdout. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_materials.h"

#define FF_MAX_POINTS 10000
#define FF_X_LO 1e-3
#define FF_X_HI 30.0

/* patir-cheng's flow stops at H = 0, where u/sigma = phi(0) = 1/sqrt(2 pi)
 * (flow_factors.h). */
#define PATIR_CHENG_PERCOLATION 0.3989422804014327

/* ---- help ------------------------------------------------------------- */

static const char surface_help[] =
    "usage: viscolube [--db PATH] surface VERB ...\n"
    "\n"
    "Surface roughness: an isotropic 2-D power spectrum C(q), self-affine or tabulated.\n"
    "\n"
    "verbs:\n"
    "  list [--json]          one line per surface: name, kind, h_rms, rms slope, band\n"
    "  show NAME [--json]     h_rms, rms slope, C0, q0, q1, H or point count\n"
    "  add NAME --self-affine --hurst H --q0 PER_M --q1 PER_M --hrms M\n"
    "  add NAME --psd FILE\n"
    "  add NAME --topography FILE\n"
    "                         register a surface from its parameters, a tabulated\n"
    "                         spectrum or a measured line scan or height map (see\n"
    "                         `surface add --help`)\n"
    "  remove NAME            delete a surface\n"
    "  flow-factors NAME [--model M] [--u-range MIN,MAX] [--points N]\n"
    "                         the flow factors phi_p, phi_s, phi_fp, phi_fs, phi_f and\n"
    "                         A/A0 against u/h_rms (see `surface flow-factors --help`)\n"
    "\n"
    "`viscolube surface VERB --help` describes a verb.\n";

/* `surface show --help` */
static const char surface_show_help[] =
    "usage: viscolube [--db PATH] surface show NAME [--json] [--plot FILE]\n"
    "\n"
    "Prints what is stored about surface NAME and the quantities derived from it.\n"
    "  --json       print one JSON object instead\n"
    "  --plot FILE  also draw C(q) against q (log-log) as FILE's stem .png and .svg;\n"
    "               over a tabulated spectrum the closest self-affine law\n"
    "               C ~ q^(-2(1+H)), fitted from the largest C on, dashed, with its\n"
    "               H (printed with the rms misfit in log10 C)\n";

/* `surface add --help` */
static const char surface_add_help[] =
    "usage: viscolube [--db PATH] surface add NAME --self-affine --hurst H --q0 PER_M\n"
    "                 --q1 PER_M --hrms M [--description TEXT]\n"
    "       viscolube [--db PATH] surface add NAME --psd FILE [--psd-kind 1d|2d]\n"
    "                 [--description TEXT]\n"
    "       viscolube [--db PATH] surface add NAME --topography FILE [--description TEXT]\n"
    "\n"
    "Registers an isotropic roughness power spectrum C(q) (m^4), with\n"
    "h_rms^2 = 2 pi \\int q C(q) dq.\n"
    "\n"
    "  --self-affine   C(q) = C0 (q/q0)^(-2(1+H)) for q0 <= q <= q1; C0 follows\n"
    "                  from h_rms. Needs all of:\n"
    "    --hurst H     Hurst exponent, 0 < H <= 1 (fractal dimension 3 - H)\n"
    "    --q0 PER_M    low wavevector cut-off, 1/m (> 0)\n"
    "    --q1 PER_M    high wavevector cut-off, 1/m (> q0)\n"
    "    --hrms M      rms roughness, m (> 0)\n"
    "  --psd FILE      tabulated spectrum: CSV with the header line 'q_per_m,C_m4',\n"
    "                  q > 0 strictly increasing, C > 0, at least 2 rows; an optional\n"
    "                  units row '1/m,m^4' may follow the header. Interpolated as a\n"
    "                  power law between points, zero outside. Units may be given in\n"
    "                  the header instead ('q [1/um],C [m^4]'); see docs/FORMATS.md.\n"
    "  --psd-kind 1d|2d  2d (default): the isotropic C(q), m^4; 1d: a profile's\n"
    "                  C1(q), m^3, converted to C(q) (inverse Abel transform).\n"
    "                  What the reading did is printed on stderr as 'note: ' lines.\n"
    "  --topography FILE  measured heights (docs/FORMATS.md), the spectrum estimated\n"
    "                  from them (detrended, Tukey window, FFT, log bins; a line scan's\n"
    "                  1-D spectrum turned 2-D by the inverse Abel transform):\n"
    "                    line scan: a header naming the units, then position,height\n"
    "                      rows ('x [um],z [nm]'; tab, ';', blank or ',' separated)\n"
    "                    height map: '# Width: 10 um', '# Height: 10 um' and\n"
    "                      '# Value units: m' lines, then one row of heights per line\n"
    "                      (Gwyddion and SurfaceTopography 'matrix' exports)\n"
    "                  Reports the measured rms, the PSD's h_rms and their ratio and\n"
    "                  stores how the spectrum was made as the description (after\n"
    "                  --description when given).\n"
    "  --description TEXT  free text; note the source of the data here\n";

/* `surface flow-factors --help` */
static const char surface_flow_factors_help[] =
    "usage: viscolube [--db PATH] surface flow-factors NAME [--model MODEL]\n"
    "                 [--u-range MIN,MAX] [--points N] [--film-cutoff M] [--out FILE]\n"
    "                 [--json] [--plot]\n"
    "\n"
    "The flow and shear-stress factors of the averaged Reynolds equation for surface\n"
    "NAME (docs/FLOW_FACTORS.md) against the average separation u/h_rms, with the\n"
    "contact area A/A0 of Persson's contact law at that separation. Columns:\n"
    "  u_over_hrms, contact_fraction, phi_p, phi_s, phi_fp, phi_fs, phi_f\n"
    "  --model MODEL   persson-emt (default; its table is cached in the database),\n"
    "                  patir-cheng or smooth\n"
    "  --u-range MIN,MAX  u/h_rms range, log spaced (default 0.001,30)\n"
    "  --points N      rows, 2 to 10000 (default 100)\n"
    "  --film-cutoff M persson-emt's film cut-off in (0, 1e-6] m (default 1e-9): gaps\n"
    "                  narrower carry no Couette shear (phi_f)\n"
    "  --out FILE      also write the table as CSV (a '#' line naming the surface,\n"
    "                  model, h_rms and cut-off, then the columns; exact numbers)\n"
    "  --json          print one JSON object (surface, model, hrms_m, film_cutoff_m,\n"
    "                  percolation_u_over_hrms, rows) instead of the table\n"
    "  --plot          draw the factors against u/h_rms as FILE's stem .png and .svg\n"
    "                  (without --out: flow-factors-NAME.png and .svg here)\n"
    "The header gives the percolation point, where the pressure flow stops.\n";

/* ---- show and list --------------------------------------------------------- */

static void surface_json(vl_json *w, const vl_db_surface *s) {
  int tab = s->kind == VL_PSD_TABULATED;
  vl_json_object_begin(w, VL_JSON_INLINE);
  vl_json_key_string(w, "name", s->name);
  vl_json_key_string(w, "kind", tab ? "tabulated" : "self-affine");
  vl_json_key_string(w, "description", s->description);
  vl_json_key_number(w, "hrms_m", s->hrms_m);
  vl_json_key_number(w, "rms_slope", s->rms_slope);
  vl_json_key_number(w, "c0_m4", tab ? NAN : s->c0_m4);
  vl_json_key_number(w, "q0_per_m", s->q0_per_m);
  vl_json_key_number(w, "q1_per_m", s->q1_per_m);
  vl_json_key_number(w, "hurst", tab ? NAN : s->hurst);
  vl_json_key_integer(w, "n_points", (long long)s->n_points);
  vl_cli_key_text_or_null(w, "source_file", s->source_file);
  vl_json_key_string(w, "created_at", s->created_at);
  vl_json_end(w);
}

static void surface_text(FILE *out, const vl_db_surface *s) {
  int tab = s->kind == VL_PSD_TABULATED;
  fprintf(out, "surface %s (%s)\n", s->name, tab ? "tabulated" : "self-affine");
  if (s->description[0]) fprintf(out, "  description   %s\n", s->description);
  fprintf(out, "  h_rms         %.6g m\n", s->hrms_m);
  fprintf(out, "  rms slope     %.6g\n", s->rms_slope);
  if (!tab) {
    fprintf(out, "  C0            %.6g m^4\n", s->c0_m4);
    fprintf(out, "  H             %.6g (fractal dimension %.6g)\n", s->hurst, 3.0 - s->hurst);
  }
  fprintf(out, "  q0            %.6g 1/m\n", s->q0_per_m);
  fprintf(out, "  q1            %.6g 1/m\n", s->q1_per_m);
  if (tab) fprintf(out, "  points        %zu\n", s->n_points);
  if (s->source_file[0]) fprintf(out, "  source file   %s\n", s->source_file);
  fprintf(out, "  created       %s\n", s->created_at);
}

static void surface_line(FILE *out, const vl_db_surface *s) {
  int tab = s->kind == VL_PSD_TABULATED;
  fprintf(out, "%-20s %-11s h_rms %-10.4g m  rms slope %-9.4g q0 %-9.4g q1 %-9.4g 1/m  ", s->name,
          tab ? "tabulated" : "self-affine", s->hrms_m, s->rms_slope, s->q0_per_m, s->q1_per_m);
  if (tab)
    fprintf(out, "%zu points\n", s->n_points);
  else
    fprintf(out, "H %.4g\n", s->hurst);
}

/* The spectrum of a self-affine surface on a log grid over its band. */
enum { PSD_GRID = 200 };
static void psd_grid(const vl_psd *p, double hurst, double c_q0, double *q, double *c) {
  for (size_t i = 0; i < PSD_GRID; i++) {
    q[i] = p->q0 * pow(p->q1 / p->q0, (double)i / (PSD_GRID - 1));
    c[i] = c_q0 * pow(q[i] / p->q0, -2.0 * (1.0 + hurst));
  }
}

/* `surface show NAME --plot FILE`: C(q) of the surface, with the closest
 * self-affine law over a tabulated one. Returns -1 or the exit code. */
static int plot_surface(const vl_cli_context *cx, vl_db *db, const char *name, const char *file,
                        int quiet) {
  vl_error err;
  vl_psd p;
  memset(&p, 0, sizeof p);
  char stem[4200], label[128], fit_label[128];
  vl_cli_file_stem(stem, sizeof stem, file);
  double gq[PSD_GRID], gc[PSD_GRID], h = NAN, c_q0 = NAN, rms = NAN;
  vl_status st = vl_db_surface_get(db, name, &p, &err);
  if (st == VL_OK) st = vl_psd_fit_self_affine(&p, &h, &c_q0, &rms, &err);
  if (st == VL_OK) {
    int tab = p.kind == VL_PSD_TABULATED;
    psd_grid(&p, h, c_q0, gq, gc);
    snprintf(label, sizeof label, tab ? "%s (tabulated)" : "%s (self-affine H = %.3g)", name, h);
    snprintf(fit_label, sizeof fit_label, "self-affine fit H = %.3g", h);
    vl_plot_psd_data d = {tab ? p.n : PSD_GRID,
                          tab ? p.q : gq,
                          tab ? p.C : gc,
                          label,
                          tab ? PSD_GRID : 0,
                          gq,
                          gc,
                          fit_label};
    vl_plot_options opt;
    vl_plot_options_defaults(&opt);
    st = vl_plot_psd(stem, &d, &opt, NULL, &err);
    if (st == VL_OK && !quiet) {
      printf("wrote %s.png and %s.svg", stem, stem);
      if (tab) printf(" (self-affine fit: H %.4g, rms %.3g in log10 C)", h, rms);
      printf("\n");
    }
  }
  vl_psd_free(&p);
  return st == VL_OK ? -1 : vl_cli_fail(cx, st, err.msg);
}

/* ---- flow-factors: the request --------------------------------------- */

typedef struct {
  vl_flow_factor_kind kind;
  double x_lo, x_hi; /* u/h_rms */
  size_t n;
  double cutoff_m; /* persson-emt only */
} ff_request;

/* `surface flow-factors` options as given (NULL or 0 when absent). */
typedef struct {
  const char *model, *u_range, *points, *film_cutoff, *out;
  int json, plot;
} ff_args;

/* MIN,MAX with 0 < MIN < MAX, both finite. */
static int parse_range(const char *text, double *lo, double *hi) {
  return vl_cli_number_pair(text, lo, hi) && *lo > 0.0 && *hi > *lo;
}

/* Checks the option values into r. Returns -1, else the exit code after
 * the message. */
static int ff_check(const vl_cli_context *cx, const ff_args *a, ff_request *r) {
  vl_error err;
  *r = (ff_request){VL_FLOW_FACTORS_PERSSON_EMT, FF_X_LO, FF_X_HI, 100, VL_FILM_CUTOFF_DEFAULT_M};
  if (a->model && vl_flow_factors_parse(a->model, &r->kind, &err) != VL_OK)
    return vl_cli_failf(cx, VL_EINPUT, "option --model: %s", err.msg);
  if (a->u_range && !parse_range(a->u_range, &r->x_lo, &r->x_hi))
    return vl_cli_failf(
        cx, VL_EINPUT, "option --u-range: expected MIN,MAX (u/h_rms) with 0 < MIN < MAX (got '%s')",
        a->u_range);
  if (a->points) {
    double d;
    if (!vl_cli_number(a->points, &d, NULL) || d != floor(d) || d < 2 || d > FF_MAX_POINTS)
      return vl_cli_failf(cx, VL_EINPUT,
                          "option --points: expected a whole number in [2, %d] (got '%s')",
                          FF_MAX_POINTS, a->points);
    r->n = (size_t)d;
  }
  if (a->film_cutoff) {
    if (r->kind != VL_FLOW_FACTORS_PERSSON_EMT)
      return vl_cli_failf(cx, VL_EINPUT,
                          "option --film-cutoff applies to --model persson-emt only");
    if (!vl_cli_number(a->film_cutoff, &r->cutoff_m, NULL) ||
        !(r->cutoff_m > 0.0 && r->cutoff_m <= VL_FILM_CUTOFF_MAX_M))
      return vl_cli_failf(cx, VL_EINPUT,
                          "option --film-cutoff: expected a length in (0, %g] m (got '%s')",
                          VL_FILM_CUTOFF_MAX_M, a->film_cutoff);
  }
  if (a->out && strlen(a->out) >= 4096) /* PATH_MAX, with room for the figures' names */
    return vl_cli_failf(cx, VL_EINPUT, "option --out: file name longer than 4095 characters");
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
  vl_cli_file_stem(stem, size, out);
}

/* The command line of `surface flow-factors NAME` into a and *name: -1,
 * else the exit status after the message. */
static int ff_args_parse(const vl_cli_context *cx, int argc, char **argv, ff_args *a,
                         const char **name) {
  vl_cli_option opts[] = {
      {.name = "--model", .kind = VL_CLI_TEXT, .metavar = "MODEL", .dest = &a->model},
      {.name = "--u-range", .kind = VL_CLI_TEXT, .metavar = "MIN,MAX", .dest = &a->u_range},
      {.name = "--points", .kind = VL_CLI_TEXT, .metavar = "N", .dest = &a->points},
      {.name = "--film-cutoff", .kind = VL_CLI_TEXT, .metavar = "M", .dest = &a->film_cutoff},
      {.name = "--out", .kind = VL_CLI_TEXT, .metavar = "FILE", .dest = &a->out},
      {.name = "--json", .kind = VL_CLI_FLAG, .dest = &a->json},
      {.name = "--plot", .kind = VL_CLI_FLAG, .dest = &a->plot},
  };
  return vl_cli_named_args(cx, NULL, argc, argv, opts, sizeof opts / sizeof opts[0], name, NULL);
}

static int surface_flow_factors(const vl_cli_context *cx, const vl_cli_globals *g, int argc,
                                char **argv) {
  ff_args args = {0}, *a = &args;
  const char *name = NULL;
  int rc = ff_args_parse(cx, argc, argv, a, &name);
  if (rc >= 0) return rc;
  ff_request r;
  if ((rc = ff_check(cx, a, &r)) >= 0) return rc;
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
    rc = vl_cli_failf(cx, st, "%s", err.msg[0] ? err.msg : vl_status_name(st));
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

/* `surface add NAME --topography FILE [--description TEXT]` (description
 * may be NULL): the exit status. */
static int surface_add_topography(const vl_cli_context *cx, const vl_cli_globals *g,
                                  const char *name, const char *path, const char *description) {
  if (strlen(path) >= VL_DB_TEXT_MAX)
    return vl_cli_failf(cx, VL_EINPUT, "option --topography: file name longer than %d characters",
                        VL_DB_TEXT_MAX - 1);
  if (description && strlen(description) >= VL_DB_TEXT_MAX)
    return vl_cli_failf(cx, VL_EINPUT, "option --description: longer than %d characters",
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
    rc = vl_cli_failf(cx, st, "%s", err.msg[0] ? err.msg : vl_status_name(st));
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

/* ---- add -------------------------------------------------------------- */

/* What `surface add NAME` was given. */
typedef struct {
  const char *name;
  int self_affine;
  const char *sa[4]; /* --hurst, --q0, --q1, --hrms as given */
  const char *psd, *psd_kind, *topography, *description;
} add_args;

static const char *const sa_names[4] = {"--hurst", "--q0", "--q1", "--hrms"};
static const char *const sa_metavars[4] = {"H", "PER_M", "PER_M", "M"};

static int add_args_parse(const vl_cli_context *cx, int argc, char **argv, add_args *a) {
  vl_cli_option opts[] = {
      {.name = "--self-affine", .kind = VL_CLI_FLAG, .dest = &a->self_affine},
      {.name = "--hurst", .kind = VL_CLI_TEXT, .metavar = "H", .dest = &a->sa[0]},
      {.name = "--q0", .kind = VL_CLI_TEXT, .metavar = "PER_M", .dest = &a->sa[1]},
      {.name = "--q1", .kind = VL_CLI_TEXT, .metavar = "PER_M", .dest = &a->sa[2]},
      {.name = "--hrms", .kind = VL_CLI_TEXT, .metavar = "M", .dest = &a->sa[3]},
      {.name = "--psd", .kind = VL_CLI_TEXT, .metavar = "FILE", .dest = &a->psd},
      {.name = "--description", .kind = VL_CLI_TEXT, .metavar = "TEXT", .dest = &a->description},
      {.name = "--topography", .kind = VL_CLI_TEXT, .metavar = "FILE", .dest = &a->topography},
      {.name = "--psd-kind", .kind = VL_CLI_TEXT, .metavar = "KIND", .dest = &a->psd_kind},
  };
  return vl_cli_named_args(cx, NULL, argc, argv, opts, sizeof opts / sizeof opts[0], &a->name,
                           NULL);
}

/* One of the three forms, with the options that belong to it (and the
 * description short enough): -1, else the exit status after the message. */
static int add_form(const vl_cli_context *cx, const add_args *a, vl_psd_file_kind *kind) {
  int n_forms = (a->self_affine != 0) + (a->psd != NULL) + (a->topography != NULL);
  if (n_forms > 1)
    return vl_cli_fail(cx, VL_EINPUT,
                       "give one of --self-affine, --psd FILE and --topography FILE, not several");
  if (n_forms == 0)
    return vl_cli_fail(cx, VL_EINPUT,
                       "give --self-affine --hurst H --q0 PER_M --q1 PER_M --hrms M, --psd FILE "
                       "or --topography FILE");
  for (size_t k = 0; k < 4; k++) {
    if (!a->self_affine && a->sa[k])
      return vl_cli_failf(cx, VL_EINPUT, "option %s belongs to --self-affine, not to %s",
                          sa_names[k], a->psd ? "--psd" : "--topography");
    if (a->self_affine && !a->sa[k])
      return vl_cli_failf(cx, VL_EINPUT, "--self-affine needs option %s %s", sa_names[k],
                          sa_metavars[k]);
  }
  *kind = VL_PSD_FILE_2D;
  if (a->psd_kind && !a->psd)
    return vl_cli_fail(cx, VL_EINPUT, "option --psd-kind belongs to --psd FILE");
  if (a->psd_kind && vl_psd_file_kind_parse(a->psd_kind, kind) != VL_OK)
    return vl_cli_failf(cx, VL_EINPUT, "option --psd-kind: '%s' is not 1d or 2d", a->psd_kind);
  return vl_cli_check_description(cx, a->description);
}

/* The self-affine spectrum of --hurst, --q0, --q1 and --hrms into psd: -1,
 * else the exit status after the message. */
static int add_self_affine(const vl_cli_context *cx, const add_args *a, vl_psd *psd) {
  double v[4];
  int rc;
  for (size_t k = 0; k < 4; k++)
    if ((rc = vl_cli_number_opt(cx, sa_names[k], a->sa[k], &v[k])) >= 0) return rc;
  if (!(v[0] > 0.0 && v[0] <= 1.0))
    return vl_cli_failf(cx, VL_EINPUT, "option --hurst: H must lie in (0, 1] (got '%s')", a->sa[0]);
  if (!(v[1] > 0.0))
    return vl_cli_failf(cx, VL_EINPUT, "option --q0: the cut-off must be > 0 1/m (got '%s')",
                        a->sa[1]);
  if (!(v[2] > v[1]))
    return vl_cli_failf(cx, VL_EINPUT,
                        "option --q1: must be larger than --q0 (got q0 = %s, q1 = %s)", a->sa[1],
                        a->sa[2]);
  if (!(v[3] > 0.0))
    return vl_cli_failf(cx, VL_EINPUT, "option --hrms: the rms roughness must be > 0 m (got '%s')",
                        a->sa[3]);
  vl_error err;
  vl_status st = vl_psd_init_self_affine(psd, v[0], v[1], v[2], v[3], &err);
  return st == VL_OK ? -1 : vl_cli_fail(cx, st, err.msg);
}

static int surface_add(const vl_cli_context *cx, const vl_cli_globals *g, int argc, char **argv) {
  add_args a = {0};
  vl_psd_file_kind kind;
  int rc = add_args_parse(cx, argc, argv, &a);
  if (rc < 0) rc = add_form(cx, &a, &kind);
  if (rc >= 0) return rc;
  if (a.topography) return surface_add_topography(cx, g, a.name, a.topography, a.description);
  vl_error err;
  vl_psd psd;
  vl_psd_read_report rep;
  memset(&psd, 0, sizeof psd);
  memset(&rep, 0, sizeof rep);
  if (a.self_affine) {
    if ((rc = add_self_affine(cx, &a, &psd)) >= 0) return rc;
  } else if (strlen(a.psd) >= VL_DB_TEXT_MAX) {
    return vl_cli_failf(cx, VL_EINPUT, "option --psd: file name longer than %d characters",
                        VL_DB_TEXT_MAX - 1);
  } else {
    vl_status st = vl_csv_read_psd_file(a.psd, kind, &psd, &rep, &err);
    if (st != VL_OK) return vl_cli_fail(cx, st, err.msg);
  }
  vl_db *db = NULL;
  if ((rc = vl_cli_open_db(cx, g, &db)) < 0) {
    vl_status st = vl_db_surface_add(db, a.name, &psd, a.description, a.psd, &err);
    if (st != VL_OK) {
      rc = vl_cli_fail(cx, st, err.msg);
    } else {
      printf("added surface '%s' to %s: %s, h_rms %.6g m, rms slope %.6g\n", a.name, vl_db_path(db),
             psd.kind == VL_PSD_TABULATED ? "tabulated" : "self-affine", vl_psd_hrms(&psd),
             vl_psd_rms_slope(&psd));
      vl_cli_print_notes(g, rep.notes);
      rc = 0;
    }
  }
  vl_db_close(db);
  vl_psd_free(&psd);
  return rc;
}

/* ---- the noun --------------------------------------------------------- */

static int surface_show(const vl_cli_context *cx, const vl_cli_globals *g, int argc, char **argv) {
  int json = 0;
  const char *plot = NULL, *name = NULL;
  vl_cli_option opts[] = {
      {.name = "--json", .kind = VL_CLI_FLAG, .dest = &json},
      {.name = "--plot", .kind = VL_CLI_TEXT, .metavar = "FILE", .dest = &plot}};
  vl_db *db = NULL;
  int rc = vl_cli_named_args(cx, g, argc, argv, opts, 2, &name, &db);
  if (rc >= 0) return rc;
  vl_error err;
  vl_db_surface s;
  vl_status st = vl_db_surface_info(db, name, &s, &err);
  if (st == VL_OK && json) {
    vl_json w;
    vl_cli_json_start(&w, stdout);
    surface_json(&w, &s);
    fputc('\n', stdout);
  } else if (st == VL_OK) {
    surface_text(stdout, &s);
  }
  if (st == VL_OK && plot) rc = plot_surface(cx, db, name, plot, json);
  if (st != VL_OK) rc = vl_cli_fail(cx, st, err.msg);
  vl_db_close(db);
  return rc >= 0 ? rc : 0;
}

static vl_status surface_list(vl_db *db, vl_json *w, int json, vl_error *err) {
  vl_db_surface *items;
  size_t n = 0;
  vl_status st = vl_db_surface_list(db, &items, &n, err);
  if (st != VL_OK) return st;
  for (size_t i = 0; i < n; i++) {
    if (json)
      surface_json(w, &items[i]);
    else
      surface_line(stdout, &items[i]);
  }
  free(items);
  return VL_OK;
}

static int surface_verb_help(const char *verb, FILE *out) {
  if (!strcmp(verb, "show"))
    fputs(surface_show_help, out);
  else if (!strcmp(verb, "add"))
    fputs(surface_add_help, out);
  else if (!strcmp(verb, "flow-factors"))
    fputs(surface_flow_factors_help, out);
  else
    return 0;
  return 1;
}

/* name, help, verb_help, add, show, flow_factors, list, remove */
const vl_cli_noun vl_cli_surface_noun = {"surface",    surface_help,        surface_verb_help,
                                         surface_add,  surface_show,        surface_flow_factors,
                                         surface_list, vl_db_surface_remove};
