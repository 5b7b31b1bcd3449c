/* `viscolube flattening ...`: the viscous flattening parameter epsilon_f
 * against u/h_rms for stored materials (the seed's Figs. 19-20), from
 * options or from a case file's materials, contact and speeds. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_options.h"

#define MAX_SPEEDS 32
#define MAX_HURST 16
#define MAX_U 4001

static void usage(FILE *out) {
  fputs("usage: viscolube flattening --compound C --surface S --fluid F --speeds V1,V2,...\n"
        "                            [--hurst H1,H2,...] [--load N_PER_M] [--radius M]\n"
        "                            [--response modulus|complex] [--u-range MIN,MAX]\n"
        "                            [--per-decade N] [--out DIR] [--json]\n"
        "       viscolube flattening --case SCENE [any option above to override it]\n"
        "\n"
        "Viscous flattening of the asperities (seed Appendix C, Figs. 19-20): the factor\n"
        "epsilon_f(u) by which the film's pressure reduces the mean-square roughness,\n"
        "h_rms^2 -> epsilon_f h_rms^2, against the average separation u/h_rms (log grid),\n"
        "for each sliding speed (m/s). The rubber responds with its compliance at the\n"
        "asperity frequency wH = pi v0/aH (aH from --load and --radius).\n"
        "  --hurst      recompute the stored self-affine surface with these Hurst exponents\n"
        "               (same q0, q1 and h_rms): one family of curves per H\n"
        "  --response   modulus (default): |1/Er(wH)|; complex: the seed's Eq. 31 with the\n"
        "               loss part J''(wH) too (can give epsilon_f > 1, see flattening.h)\n"
        "  --case       a scene file: compound, surface, first fluid, radius, load and the\n"
        "               sweep's speeds (quantity v0 or v0_eta)\n"
        "Writes DIR/flattening.csv (u_over_hrms, then eps_H<H>_v<V> per curve) and\n"
        "DIR/flattening-summary.csv (one row per curve: wH, |Er(wH)|, tan delta, the\n"
        "separations where epsilon_f = 0.9 and 0.5, the minimum). DIR defaults to\n"
        "out/flattening. Defaults: --load 117 --radius 0.001 (the seed's real-rubber\n"
        "scenes), --u-range 0.001,10, --per-decade 20, the surface's own H.\n",
        out);
}

/* The separation (in h_rms) where epsilon_f first falls to level coming
 * from large u along the grid, refined by bisection in ln u on the exact
 * quadrature; NAN when it stays above. */
static double crossing(const vl_flattening *f, double hrms, size_t n, const double *u,
                       const double *eps, double level) {
  for (size_t i = n - 1; i > 0; i--) {
    if (eps[i] >= level && eps[i - 1] < level) {
      double lo = log(u[i - 1]), hi = log(u[i]);
      for (int it = 0; it < 60; it++) {
        double mid = 0.5 * (lo + hi);
        if (vl_flattening_eps_exact(f, hrms * exp(mid), NULL) < level)
          lo = mid;
        else
          hi = mid;
      }
      return exp(0.5 * (lo + hi));
    }
  }
  return NAN;
}

/* separations (u/h_rms) of the printed table */
static const double table_u[] = {0.003, 0.01, 0.03, 0.1, 1.0};
#define N_TABLE_U (sizeof table_u / sizeof table_u[0])

typedef struct {
  double hurst, v0;
  vl_flattening_state st;
  double u90, u50, eps_min, u_min, eps_max;
  double at[N_TABLE_U]; /* epsilon_f at table_u */
} curve_info;

static void print_opt(FILE *f, double v) {
  if (isfinite(v)) fprintf(f, "%.6g", v);
}

/* What the command was asked for: options first, then a case file's values
 * for those not given. */
typedef struct {
  const char *compound, *surface, *fluid, *case_path, *out_dir;
  double speeds[MAX_SPEEDS], hursts[MAX_HURST], load, radius;
  double u_lo, u_hi, per_decade;
  size_t n_speeds, n_hurst;
  int json, have_load, have_radius;
  int case_needs_eta; /* the case's speeds are v0 eta: divide by the fluid's eta */
  vl_flattening_response response;
  const char *response_text; /* --response as given */
  double u_range[2];         /* --u-range as given */
  size_t n_u_range;
  vl_scene scene; /* --case: the names above may point into it */
} flat_args;

/* The computed curves: n_hurst * n_speeds of them (Hurst exponent major),
 * curve c's epsilon_f at u[i] is eps[c * n_u + i]. */
typedef struct {
  vl_psd psd0; /* the stored surface */
  int have_psd;
  double eta; /* Pa s */
  size_t n_u, n_curves;
  double *u, *eps;
  curve_info *info;
} flat_curves;

/* The checks of --hurst, --u-range and --response as soon as they are
 * given: -1, else the exit status after the message. */
static int check_hurst(const char *cmd, void *ctx) {
  flat_args *a = ctx;
  for (size_t k = 0; k < a->n_hurst; k++)
    if (a->hursts[k] > 1.0) {
      fprintf(stderr, "viscolube %s: --hurst values must lie in (0, 1] (got %g)\n", cmd,
              a->hursts[k]);
      return 2;
    }
  return -1;
}

static int check_u_range(const char *cmd, void *ctx) {
  flat_args *a = ctx;
  if (a->n_u_range != 2 || !(a->u_range[1] > a->u_range[0])) {
    fprintf(stderr, "viscolube %s: --u-range needs MIN,MAX with 0 < MIN < MAX\n", cmd);
    return 2;
  }
  a->u_lo = a->u_range[0], a->u_hi = a->u_range[1];
  return -1;
}

static int check_response(const char *cmd, void *ctx) {
  flat_args *a = ctx;
  vl_error e;
  if (vl_flattening_response_parse(a->response_text, &a->response, &e) != VL_OK) {
    fprintf(stderr, "viscolube %s: --response: %s\n", cmd, e.msg);
    return 2;
  }
  return -1;
}

/* The options: -1 to go on, else the exit code (0 after --help). */
static int flat_parse(int argc, char **argv, flat_args *a) {
  static const vl_cli_number_rule positive = {.lo = 0.0,
                                              .lo_open = 1,
                                              .hi = 1000,
                                              .bad = "option %s needs a positive number (got '%s')",
                                              .range = "%s needs a whole number in [1, 1000]",
                                              .whole = 1};
  vl_cli_number_rule length = positive;
  length.hi = INFINITY, length.whole = 0, length.range = NULL;
  vl_cli_option opts[] = {
      {.name = "--help", .alias = "-h", .kind = VL_CLI_HELP},
      {.name = "--json", .kind = VL_CLI_FLAG, .dest = &a->json},
      {.name = "--compound", .kind = VL_CLI_TEXT, .dest = &a->compound},
      {.name = "--surface", .kind = VL_CLI_TEXT, .dest = &a->surface},
      {.name = "--fluid", .kind = VL_CLI_TEXT, .dest = &a->fluid},
      {.name = "--case", .kind = VL_CLI_TEXT, .dest = &a->case_path},
      {.name = "--out", .kind = VL_CLI_TEXT, .dest = &a->out_dir},
      {.name = "--speeds",
       .kind = VL_CLI_LIST,
       .dest = a->speeds,
       .max_values = MAX_SPEEDS,
       .n_values = &a->n_speeds},
      {.name = "--hurst",
       .kind = VL_CLI_LIST,
       .dest = a->hursts,
       .max_values = MAX_HURST,
       .n_values = &a->n_hurst,
       .check = check_hurst,
       .ctx = a},
      {.name = "--u-range",
       .kind = VL_CLI_LIST,
       .dest = a->u_range,
       .max_values = 2,
       .n_values = &a->n_u_range,
       .check = check_u_range,
       .ctx = a},
      {.name = "--load", .kind = VL_CLI_NUMBER, .dest = &a->load, .rule = &length},
      {.name = "--radius", .kind = VL_CLI_NUMBER, .dest = &a->radius, .rule = &length},
      {.name = "--per-decade", .kind = VL_CLI_NUMBER, .dest = &a->per_decade, .rule = &positive},
      {.name = "--response",
       .kind = VL_CLI_TEXT,
       .dest = &a->response_text,
       .check = check_response,
       .ctx = a},
  };
  vl_cli_parser p = {.cmd = "flattening",
                     .opts = opts,
                     .n_opts = sizeof opts / sizeof opts[0],
                     .unknown = "unknown or incomplete option '%s' (see --help)",
                     .missing = "unknown or incomplete option '%s' (see --help)",
                     .usage = usage};
  int rc = vl_cli_parse(&p, argc, argv, 1);
  a->have_load = vl_cli_find(&p, "--load")->given > 0;
  a->have_radius = vl_cli_find(&p, "--radius")->given > 0;
  return rc;
}

/* --case: the scene supplies what the options did not. -1 to go on, else
 * the exit code after the message. */
static int flat_from_case(flat_args *a) {
  vl_error err = {{0}};
  vl_scene *sc = &a->scene;
  vl_status st = vl_scene_load(a->case_path, sc, &err);
  if (st != VL_OK) {
    fprintf(stderr, "viscolube flattening: %s\n", err.msg);
    return vl_status_exit_code(st);
  }
  if (!a->compound) a->compound = sc->compound;
  if (!a->surface && sc->surface[0]) a->surface = sc->surface;
  if (!a->fluid && sc->fluid[0]) a->fluid = sc->fluid;
  if (!a->have_load) a->load = sc->load_n_per_m;
  if (!a->have_radius) a->radius = sc->radius_m;
  if (a->n_speeds > 0) return -1;
  if (sc->quantity == VL_SWEEP_DEBORAH) {
    fprintf(stderr, "viscolube flattening: %s: the sweep is in v0 tau/a0; give --speeds\n",
            a->case_path);
    return 2;
  }
  if (sc->points > MAX_SPEEDS) {
    fprintf(stderr,
            "viscolube flattening: %s: at most %d speeds (the sweep has %zu points); "
            "give --speeds\n",
            a->case_path, MAX_SPEEDS, sc->points);
    return 2;
  }
  a->n_speeds = sc->points;
  for (size_t k = 0; k < a->n_speeds; k++) {
    double t = a->n_speeds > 1 ? (double)k / (double)(a->n_speeds - 1) : 0.0;
    a->speeds[k] = sc->from * pow(sc->to / sc->from, t); /* as the sweep spaces them */
  }
  a->case_needs_eta = sc->quantity == VL_SWEEP_V0_ETA;
  return -1;
}

/* The materials from the database into cfg and fc (psd0, eta), and the
 * Hurst exponents to compute (the surface's own when none was given). */
static vl_status flat_load(vl_db *db, flat_args *a, vl_flattening_config *cfg, flat_curves *fc,
                           vl_error *err) {
  vl_status st = vl_db_compound_get(db, a->compound, &cfg->rubber, err);
  if (st == VL_OK) {
    st = vl_db_surface_get(db, a->surface, &fc->psd0, err);
    fc->have_psd = st == VL_OK;
  }
  if (st == VL_OK) st = vl_db_fluid_get(db, a->fluid, &fc->eta, err);
  if (st == VL_OK && a->n_hurst > 0 && fc->psd0.kind != VL_PSD_SELF_AFFINE) {
    vl_error_set(err, "--hurst applies to self-affine surfaces only ('%s' is tabulated)",
                 a->surface);
    st = VL_EINPUT;
  }
  if (st != VL_OK) return st;
  if (a->case_needs_eta)
    for (size_t k = 0; k < a->n_speeds; k++)
      a->speeds[k] /= fc->eta; /* v0 eta -> v0 */
  if (a->n_hurst == 0) {
    a->hursts[0] = fc->psd0.kind == VL_PSD_SELF_AFFINE ? fc->psd0.hurst : NAN;
    a->n_hurst = 1;
  }
  cfg->load_n_per_m = a->load;
  cfg->radius_m = a->radius;
  cfg->eta_pa_s = fc->eta;
  cfg->response = a->response;
  return VL_OK;
}

/* The u/h_rms grid, per_decade points a decade, both ends included, and
 * room for the curves. */
static vl_status flat_grid(const flat_args *a, flat_curves *fc, vl_error *err) {
  size_t n_u = (size_t)ceil(log10(a->u_hi / a->u_lo) * a->per_decade - 1e-9) + 1;
  if (n_u < 2) n_u = 2;
  if (n_u > MAX_U) {
    vl_error_set(err, "--u-range and --per-decade ask for %zu separations (at most %d)", n_u,
                 MAX_U);
    return VL_EINPUT;
  }
  fc->n_u = n_u;
  fc->n_curves = a->n_hurst * a->n_speeds;
  fc->u = malloc(n_u * sizeof *fc->u);
  fc->eps = malloc(n_u * fc->n_curves * sizeof *fc->eps);
  fc->info = calloc(fc->n_curves, sizeof *fc->info);
  if (!fc->u || !fc->eps || !fc->info) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  for (size_t i = 0; i < n_u; i++)
    fc->u[i] =
        i + 1 == n_u ? a->u_hi : a->u_lo * pow(a->u_hi / a->u_lo, (double)i / (double)(n_u - 1));
  return VL_OK;
}

/* Curve ci (epsilon_f into e) of flattening f at speed v0. */
static vl_status flat_curve(vl_flattening *f, double hrms_m, double hurst, double v0,
                            const flat_curves *fc, curve_info *ci, double *e, vl_error *err) {
  vl_status st = vl_flattening_set_speed(f, v0, err);
  if (st != VL_OK) return st;
  ci->hurst = hurst, ci->v0 = v0;
  vl_flattening_state_get(f, &ci->st);
  ci->eps_min = INFINITY, ci->eps_max = -INFINITY;
  for (size_t i = 0; i < fc->n_u; i++) {
    e[i] = vl_flattening_eps_exact(f, fc->u[i] * hrms_m, NULL);
    if (e[i] < ci->eps_min) ci->eps_min = e[i], ci->u_min = fc->u[i];
    if (e[i] > ci->eps_max) ci->eps_max = e[i];
  }
  for (size_t j = 0; j < N_TABLE_U; j++)
    ci->at[j] = vl_flattening_eps_exact(f, table_u[j] * hrms_m, NULL);
  ci->u90 = crossing(f, hrms_m, fc->n_u, fc->u, e, 0.9);
  ci->u50 = crossing(f, hrms_m, fc->n_u, fc->u, e, 0.5);
  return VL_OK;
}

/* Every curve: per Hurst exponent (the stored surface recomputed with it
 * when it differs), per speed. */
static vl_status flat_compute(const flat_args *a, const vl_flattening_config *cfg, flat_curves *fc,
                              vl_error *err) {
  vl_status st = VL_OK;
  const vl_psd *psd0 = &fc->psd0;
  for (size_t h = 0; h < a->n_hurst && st == VL_OK; h++) {
    vl_psd variant = {0};
    const vl_psd *psd = psd0;
    if (psd0->kind == VL_PSD_SELF_AFFINE && a->hursts[h] != psd0->hurst) {
      st = vl_psd_init_self_affine(&variant, a->hursts[h], psd0->q0, psd0->q1, psd0->hrms_m, err);
      psd = &variant;
    }
    vl_flattening *f = NULL;
    if (st == VL_OK) st = vl_flattening_create(cfg, psd, &f, err);
    for (size_t k = 0; k < a->n_speeds && st == VL_OK; k++) {
      size_t c = h * a->n_speeds + k;
      st = flat_curve(f, psd->hrms_m, a->hursts[h], a->speeds[k], fc, &fc->info[c],
                      fc->eps + c * fc->n_u, err);
    }
    vl_flattening_free(f);
    if (psd == &variant) vl_psd_free(&variant);
  }
  return st;
}

/* DIR/flattening.csv: u_over_hrms, then epsilon_f of every curve. */
static vl_status write_curves_csv(const char *path, const flat_curves *fc, vl_error *err) {
  vl_atomic_file af;
  if (vl_atomic_file_open(&af, path, err) != VL_OK) return VL_EIO;
  FILE *f = af.f;
  fputs("u_over_hrms", f);
  for (size_t c = 0; c < fc->n_curves; c++) {
    const curve_info *ci = &fc->info[c];
    if (isnan(ci->hurst))
      fprintf(f, ",eps_v%g", ci->v0); /* tabulated surface */
    else
      fprintf(f, ",eps_H%g_v%g", ci->hurst, ci->v0);
  }
  fputc('\n', f);
  for (size_t i = 0; i < fc->n_u; i++) {
    fprintf(f, "%.8g", fc->u[i]);
    for (size_t c = 0; c < fc->n_curves; c++)
      fprintf(f, ",%.10g", fc->eps[c * fc->n_u + i]);
    fputc('\n', f);
  }
  return vl_atomic_file_commit(&af, err);
}

/* DIR/flattening-summary.csv: one row per curve. */
static vl_status write_summary_csv(const char *path, const flat_curves *fc, vl_error *err) {
  vl_atomic_file af;
  if (vl_atomic_file_open(&af, path, err) != VL_OK) return VL_EIO;
  FILE *f = af.f;
  fputs("hurst,v0_m_s,omega_h_rad_s,e_abs_wh_pa,a_h_m,tan_delta_wh,u_onset_over_hrms,"
        "u90_over_hrms,u50_over_hrms,eps_min,u_at_eps_min_over_hrms,eps_max\n",
        f);
  for (size_t c = 0; c < fc->n_curves; c++) {
    const curve_info *ci = &fc->info[c];
    print_opt(f, ci->hurst);
    fprintf(f, ",%g,%.8g,%.8g,%.8g,%.8g,%.8g,", ci->v0, ci->st.omega_h_rad_s, ci->st.e_abs_pa,
            ci->st.a_h_m, ci->st.tan_delta, ci->st.u_onset_m / ci->st.hrms_m);
    print_opt(f, ci->u90);
    fputc(',', f);
    print_opt(f, ci->u50);
    fprintf(f, ",%.8g,%.8g,%.8g\n", ci->eps_min, ci->u_min, ci->eps_max);
  }
  return vl_atomic_file_commit(&af, err);
}

/* One object: the conditions, the u/h_rms grid and every curve. */
static void print_json(const flat_args *a, const flat_curves *fc) {
  vl_json w;
  vl_json_init(&w, stdout, 10);
  vl_json_object_begin(&w, VL_JSON_INLINE);
  vl_json_key_string(&w, "compound", a->compound);
  vl_json_key_string(&w, "surface", a->surface);
  vl_json_key_string(&w, "fluid", a->fluid);
  vl_json_key_number(&w, "eta_pa_s", fc->eta);
  vl_json_key_number(&w, "load_n_per_m", a->load);
  vl_json_key_number(&w, "radius_m", a->radius);
  vl_json_key_string(&w, "response", vl_flattening_response_name(a->response));
  vl_json_key_number(&w, "hrms_m", fc->psd0.hrms_m);
  vl_json_key(&w, "u_over_hrms");
  vl_json_array_begin(&w, VL_JSON_INLINE);
  for (size_t i = 0; i < fc->n_u; i++)
    vl_json_number_digits(&w, fc->u[i], 8);
  vl_json_end(&w);
  vl_json_key(&w, "curves");
  vl_json_array_begin(&w, VL_JSON_INLINE);
  for (size_t c = 0; c < fc->n_curves; c++) {
    const curve_info *ci = &fc->info[c];
    vl_json_object_begin(&w, VL_JSON_INLINE);
    vl_json_key_number(&w, "hurst", ci->hurst);
    vl_json_key_number(&w, "v0_m_s", ci->v0);
    vl_json_key_number(&w, "omega_h_rad_s", ci->st.omega_h_rad_s);
    vl_json_key_number(&w, "e_abs_wh_pa", ci->st.e_abs_pa);
    vl_json_key_number(&w, "a_h_m", ci->st.a_h_m);
    vl_json_key_number(&w, "tan_delta_wh", ci->st.tan_delta);
    vl_json_key_number(&w, "u_onset_over_hrms", ci->st.u_onset_m / ci->st.hrms_m);
    vl_json_key_number(&w, "u90_over_hrms", ci->u90);
    vl_json_key_number(&w, "u50_over_hrms", ci->u50);
    vl_json_key_number(&w, "eps_min", ci->eps_min);
    vl_json_key(&w, "epsilon_f");
    vl_json_array_begin(&w, VL_JSON_INLINE);
    for (size_t i = 0; i < fc->n_u; i++)
      vl_json_number(&w, fc->eps[c * fc->n_u + i]);
    vl_json_end(&w);
    vl_json_end(&w);
  }
  vl_json_end(&w);
  vl_json_end(&w);
  fputc('\n', stdout);
}

/* The table: one row per curve with epsilon_f at the table's separations. */
static void print_text(const flat_args *a, const flat_curves *fc) {
  printf("viscous flattening: %s on %s in %s (eta %g Pa s), R = %g m, fN = %g N/m, "
         "response %s\n",
         a->compound, a->surface, a->fluid, fc->eta, a->radius, a->load,
         vl_flattening_response_name(a->response));
  printf("%5s %9s %10s %10s %7s %9s %9s %9s", "H", "v0 m/s", "wH rad/s", "|Er(wH)| Pa", "tan d",
         "u90/h", "u50/h", "eps_min");
  for (size_t j = 0; j < N_TABLE_U; j++) {
    char label[32];
    snprintf(label, sizeof label, "eps(%g)", table_u[j]);
    printf(" %10s", label);
  }
  printf("\n");
  for (size_t c = 0; c < fc->n_curves; c++) {
    const curve_info *ci = &fc->info[c];
    printf("%5.2f %9.3g %10.3g %10.3g %7.3f %9.3g %9.3g %9.4f", ci->hurst, ci->v0,
           ci->st.omega_h_rad_s, ci->st.e_abs_pa, ci->st.tan_delta, ci->u90, ci->u50, ci->eps_min);
    for (size_t j = 0; j < N_TABLE_U; j++)
      printf(" %10.4f", ci->at[j]);
    printf("\n");
  }
  printf("(u90, u50: u/h_rms where epsilon_f = 0.9, 0.5, nan: not reached in [%g, %g]; "
         "eps(x): epsilon_f at u/h_rms = x)\n"
         "wrote %s/flattening.csv and %s/flattening-summary.csv\n",
         a->u_lo, a->u_hi, a->out_dir, a->out_dir);
}

/* The record of DIR/run.json: the options (resolved) and the materials. */
static void flat_manifest(vl_manifest *m, vl_db *db, const flat_args *a) {
  char v[64];
  vl_cli_manifest_material(m, db, "compound", a->compound);
  vl_cli_manifest_material(m, db, "surface", a->surface);
  vl_cli_manifest_material(m, db, "fluid", a->fluid);
  if (a->case_path) vl_manifest_add_option(m, "case", a->case_path);
  vl_manifest_add_option(m, "compound", a->compound);
  vl_manifest_add_option(m, "surface", a->surface);
  vl_manifest_add_option(m, "fluid", a->fluid);
  char list[MAX_SPEEDS * 24] = "";
  for (size_t k = 0; k < a->n_speeds; k++)
    snprintf(list + strlen(list), sizeof list - strlen(list), "%s%.10g", k ? "," : "",
             a->speeds[k]);
  vl_manifest_add_option(m, "speeds_m_s", list);
  list[0] = '\0';
  for (size_t k = 0; k < a->n_hurst; k++)
    snprintf(list + strlen(list), sizeof list - strlen(list), "%s%.10g", k ? "," : "",
             a->hursts[k]);
  if (a->n_hurst) vl_manifest_add_option(m, "hurst", list);
  const struct {
    const char *key;
    double value;
  } nums[] = {{"load_n_per_m", a->load},
              {"radius_m", a->radius},
              {"u_min_over_hrms", a->u_lo},
              {"u_max_over_hrms", a->u_hi},
              {"per_decade", a->per_decade}};
  for (size_t k = 0; k < sizeof nums / sizeof nums[0]; k++) {
    snprintf(v, sizeof v, "%.10g", nums[k].value);
    vl_manifest_add_option(m, nums[k].key, v);
  }
  vl_manifest_add_option(m, "response", vl_flattening_response_name(a->response));
}

/* DIR/flattening.csv and DIR/flattening-summary.csv, then DIR/run.json.
 * Returns the exit code (0 when all were written). */
static int write_files(const vl_cli_globals *g, vl_db *db, const flat_args *a,
                       const flat_curves *fc) {
  int rc = 0;
  vl_manifest *m = vl_cli_manifest_begin(g, "flattening", a->out_dir, &rc);
  if (!m) return rc;
  flat_manifest(m, db, a);
  char path[4300];
  vl_error err = {{0}};
  snprintf(path, sizeof path, "%s/flattening.csv", a->out_dir);
  vl_cli_manifest_file(m, path, write_curves_csv(path, fc, &err), &err);
  snprintf(path, sizeof path, "%s/flattening-summary.csv", a->out_dir);
  vl_cli_manifest_file(m, path, write_summary_csv(path, fc, &err), &err);
  return vl_cli_manifest_finish(m, "flattening", g->quiet, 0);
}

int vl_cli_flattening(const vl_cli_globals *g, int argc, char **argv) {
  flat_args a = {.out_dir = "out/flattening",
                 .load = 117.0,
                 .radius = 1e-3,
                 .u_lo = 1e-3,
                 .u_hi = 10.0,
                 .per_decade = 20.0,
                 .response = VL_FLATTENING_MODULUS};
  int rc = flat_parse(argc, argv, &a);
  if (rc < 0 && a.case_path) rc = flat_from_case(&a);
  if (rc >= 0) return rc;
  if (!a.compound || !a.surface || !a.fluid || a.n_speeds == 0) {
    fprintf(stderr, "viscolube flattening: missing %s (see viscolube flattening --help)\n",
            !a.compound  ? "--compound"
            : !a.surface ? "--surface"
            : !a.fluid   ? "--fluid"
                         : "--speeds");
    return 2;
  }
  vl_error err = {{0}};
  vl_db *db = NULL;
  flat_curves fc = {0};
  vl_flattening_config cfg;
  vl_flattening_config_defaults(&cfg);
  rc = 0;
  vl_status st = vl_db_open(g->db_path, &db, &err);
  /* --out before anything is computed */
  if (st == VL_OK) st = vl_cli_check_out_dir("--out", a.out_dir, &err);
  if (st == VL_OK) st = flat_load(db, &a, &cfg, &fc, &err);
  if (st == VL_OK) st = flat_grid(&a, &fc, &err);
  if (st == VL_OK) st = flat_compute(&a, &cfg, &fc, &err);
  if (st == VL_OK) rc = write_files(g, db, &a, &fc);
  if (st == VL_OK) {
    if (a.json)
      print_json(&a, &fc);
    else
      print_text(&a, &fc);
  } else {
    fprintf(stderr, "viscolube flattening: %s\n", err.msg[0] ? err.msg : vl_status_name(st));
    rc = vl_status_exit_code(st);
  }
  free(fc.u);
  free(fc.eps);
  free(fc.info);
  if (fc.have_psd) vl_psd_free(&fc.psd0);
  vl_db_close(db);
  return rc;
}
