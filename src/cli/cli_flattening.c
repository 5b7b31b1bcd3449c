/* `viscolube flattening ...`: the viscous flattening parameter epsilon_f
 * against u/h_rms for stored materials (the seed's Figs. 19-20), from
 * options or from a case file's materials, contact and speeds. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "viscolube/csv.h"
#include "viscolube/database.h"
#include "viscolube/flattening.h"
#include "viscolube/scene.h"

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

/* Comma-separated positive numbers (strict syntax); 0 and a message on
 * failure. */
static int parse_list(const char *opt, const char *text, double *vals, size_t max, size_t *n) {
  char buf[2048];
  if (!text || strlen(text) >= sizeof buf) {
    fprintf(stderr, "viscolube flattening: option %s needs a comma-separated list\n", opt);
    return 0;
  }
  snprintf(buf, sizeof buf, "%s", text);
  *n = 0;
  char *save = NULL;
  for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
    double d = 0.0;
    if (*n == max) {
      fprintf(stderr, "viscolube flattening: option %s takes at most %zu values\n", opt, max);
      return 0;
    }
    if (vl_csv_parse_double(t, &d, NULL) != VL_OK || !(d > 0.0)) {
      fprintf(stderr, "viscolube flattening: option %s needs positive numbers (got '%s')\n", opt,
              t);
      return 0;
    }
    vals[(*n)++] = d;
  }
  if (*n == 0) {
    fprintf(stderr, "viscolube flattening: option %s needs at least one value\n", opt);
    return 0;
  }
  return 1;
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
        if (vl_flattening_eps_exact(f, hrms * exp(mid), NULL) < level) lo = mid;
        else hi = mid;
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

static void json_num(double v) {
  if (isfinite(v)) printf("%.10g", v);
  else printf("null");
}

/* Writes text produced by the caller into path through path.tmp. */
static FILE *open_tmp(const char *path, char *tmp, size_t size, vl_error *err) {
  snprintf(tmp, size, "%s.tmp", path);
  FILE *f = fopen(tmp, "w");
  if (!f) vl_error_set(err, "%s: cannot write: %s", path, strerror(errno));
  return f;
}

static vl_status close_tmp(FILE *f, const char *tmp, const char *path, vl_error *err) {
  int bad = ferror(f);
  if (fclose(f) != 0) bad = 1;
  if (bad || rename(tmp, path) != 0) {
    vl_error_set(err, "%s: cannot write: %s", path, strerror(errno ? errno : EIO));
    remove(tmp);
    return VL_EIO;
  }
  return VL_OK;
}

int vl_cli_flattening(const vl_cli_globals *g, int argc, char **argv) {
  const char *compound = NULL, *surface = NULL, *fluid = NULL, *case_path = NULL;
  const char *out_dir = "out/flattening";
  double speeds[MAX_SPEEDS], hursts[MAX_HURST], load = 117.0, radius = 1e-3;
  double u_lo = 1e-3, u_hi = 10.0, per_decade = 20.0;
  size_t n_speeds = 0, n_hurst = 0;
  int json = 0, have_load = 0, have_radius = 0;
  vl_flattening_response response = VL_FLATTENING_MODULUS;
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(o, "--help") || !strcmp(o, "-h")) {
      usage(stdout);
      return 0;
    }
    if (!strcmp(o, "--json")) {
      json = 1;
      continue;
    }
    if (!v) {
      fprintf(stderr, "viscolube flattening: unknown or incomplete option '%s' (see --help)\n", o);
      return 2;
    }
    i++;
    if (!strcmp(o, "--compound")) compound = v;
    else if (!strcmp(o, "--surface")) surface = v;
    else if (!strcmp(o, "--fluid")) fluid = v;
    else if (!strcmp(o, "--case")) case_path = v;
    else if (!strcmp(o, "--out")) out_dir = v;
    else if (!strcmp(o, "--speeds")) {
      if (!parse_list(o, v, speeds, MAX_SPEEDS, &n_speeds)) return 2;
    } else if (!strcmp(o, "--hurst")) {
      if (!parse_list(o, v, hursts, MAX_HURST, &n_hurst)) return 2;
      for (size_t k = 0; k < n_hurst; k++)
        if (hursts[k] > 1.0) {
          fprintf(stderr, "viscolube flattening: --hurst values must lie in (0, 1] (got %g)\n",
                  hursts[k]);
          return 2;
        }
    } else if (!strcmp(o, "--u-range")) {
      double r[2];
      size_t n = 0;
      if (!parse_list(o, v, r, 2, &n)) return 2;
      if (n != 2 || !(r[1] > r[0])) {
        fprintf(stderr, "viscolube flattening: --u-range needs MIN,MAX with 0 < MIN < MAX\n");
        return 2;
      }
      u_lo = r[0], u_hi = r[1];
    } else if (!strcmp(o, "--load") || !strcmp(o, "--radius") || !strcmp(o, "--per-decade")) {
      double d = 0.0;
      if (vl_csv_parse_double(v, &d, NULL) != VL_OK || !(d > 0.0)) {
        fprintf(stderr, "viscolube flattening: option %s needs a positive number (got '%s')\n", o,
                v);
        return 2;
      }
      if (!strcmp(o, "--load")) load = d, have_load = 1;
      else if (!strcmp(o, "--radius")) radius = d, have_radius = 1;
      else if (d != floor(d) || d > 1000) {
        fprintf(stderr, "viscolube flattening: --per-decade needs a whole number in [1, 1000]\n");
        return 2;
      } else per_decade = d;
    } else if (!strcmp(o, "--response")) {
      vl_error e;
      if (vl_flattening_response_parse(v, &response, &e) != VL_OK) {
        fprintf(stderr, "viscolube flattening: --response: %s\n", e.msg);
        return 2;
      }
    } else {
      fprintf(stderr, "viscolube flattening: unknown or incomplete option '%s' (see --help)\n", o);
      return 2;
    }
  }

  vl_error err = {{0}};
  vl_status st = VL_OK;
  /* a case file supplies what the options did not */
  vl_scene sc;
  int case_needs_eta = 0;
  if (case_path) {
    st = vl_scene_load(case_path, &sc, &err);
    if (st != VL_OK) {
      fprintf(stderr, "viscolube flattening: %s\n", err.msg);
      return vl_status_exit_code(st);
    }
    if (!compound) compound = sc.compound;
    if (!surface && sc.surface[0]) surface = sc.surface;
    if (!fluid && sc.fluid[0]) fluid = sc.fluid;
    if (!have_load) load = sc.load_n_per_m;
    if (!have_radius) radius = sc.radius_m;
    if (n_speeds == 0) {
      if (sc.quantity == VL_SWEEP_DEBORAH) {
        fprintf(stderr, "viscolube flattening: %s: the sweep is in v0 tau/a0; give --speeds\n",
                case_path);
        return 2;
      }
      if (sc.points > MAX_SPEEDS) {
        fprintf(stderr, "viscolube flattening: %s: at most %d speeds (the sweep has %zu points); "
                        "give --speeds\n", case_path, MAX_SPEEDS, sc.points);
        return 2;
      }
      n_speeds = sc.points;
      for (size_t k = 0; k < n_speeds; k++) {
        double t = n_speeds > 1 ? (double)k / (double)(n_speeds - 1) : 0.0;
        speeds[k] = sc.from * pow(sc.to / sc.from, t); /* as the sweep spaces them */
      }
      case_needs_eta = sc.quantity == VL_SWEEP_V0_ETA;
    }
  }
  if (!compound || !surface || !fluid || n_speeds == 0) {
    fprintf(stderr, "viscolube flattening: missing %s (see viscolube flattening --help)\n",
            !compound ? "--compound" : !surface ? "--surface" : !fluid ? "--fluid" : "--speeds");
    return 2;
  }

  vl_db *db = NULL;
  vl_psd psd0 = {0};
  int have_psd = 0;
  double eta = 0.0;
  vl_flattening_config cfg;
  vl_flattening_config_defaults(&cfg);
  size_t n_curves = 0, n_u = 0;
  double *u = NULL, *eps = NULL;
  curve_info *info = NULL;
  int rc = 0;
  st = vl_db_open(g->db_path, &db, &err);
  if (st == VL_OK) st = vl_db_compound_get(db, compound, &cfg.rubber, &err);
  if (st == VL_OK) {
    st = vl_db_surface_get(db, surface, &psd0, &err);
    have_psd = st == VL_OK;
  }
  if (st == VL_OK) st = vl_db_fluid_get(db, fluid, &eta, &err);
  if (st == VL_OK && n_hurst > 0 && psd0.kind != VL_PSD_SELF_AFFINE) {
    vl_error_set(&err, "--hurst applies to self-affine surfaces only ('%s' is tabulated)", surface);
    st = VL_EINPUT;
  }
  if (st == VL_OK && case_needs_eta)
    for (size_t k = 0; k < n_speeds; k++) speeds[k] /= eta; /* v0 eta -> v0 */
  if (st != VL_OK) goto done;
  if (n_hurst == 0) {
    hursts[0] = psd0.kind == VL_PSD_SELF_AFFINE ? psd0.hurst : NAN;
    n_hurst = 1;
  }
  cfg.load_n_per_m = load;
  cfg.radius_m = radius;
  cfg.eta_pa_s = eta;
  cfg.response = response;

  /* the u/h_rms grid: per_decade points a decade, both ends included */
  n_u = (size_t)ceil(log10(u_hi / u_lo) * per_decade - 1e-9) + 1;
  if (n_u < 2) n_u = 2;
  if (n_u > MAX_U) {
    vl_error_set(&err, "--u-range and --per-decade ask for %zu separations (at most %d)", n_u,
                 MAX_U);
    st = VL_EINPUT;
    goto done;
  }
  n_curves = n_hurst * n_speeds;
  u = malloc(n_u * sizeof *u);
  eps = malloc(n_u * n_curves * sizeof *eps);
  info = calloc(n_curves, sizeof *info);
  if (!u || !eps || !info) {
    vl_error_set(&err, "out of memory");
    st = VL_ENOMEM;
    goto done;
  }
  for (size_t i = 0; i < n_u; i++)
    u[i] = i + 1 == n_u ? u_hi : u_lo * pow(u_hi / u_lo, (double)i / (double)(n_u - 1));
  for (size_t h = 0; h < n_hurst && st == VL_OK; h++) {
    vl_psd variant = {0}, *psd = &psd0;
    if (psd0.kind == VL_PSD_SELF_AFFINE && hursts[h] != psd0.hurst) {
      st = vl_psd_init_self_affine(&variant, hursts[h], psd0.q0, psd0.q1, psd0.hrms_m, &err);
      psd = &variant;
    }
    vl_flattening *f = NULL;
    if (st == VL_OK) st = vl_flattening_create(&cfg, psd, &f, &err);
    for (size_t k = 0; k < n_speeds && st == VL_OK; k++) {
      curve_info *ci = &info[h * n_speeds + k];
      double *e = eps + (h * n_speeds + k) * n_u;
      st = vl_flattening_set_speed(f, speeds[k], &err);
      if (st != VL_OK) break;
      ci->hurst = hursts[h], ci->v0 = speeds[k];
      vl_flattening_state_get(f, &ci->st);
      ci->eps_min = INFINITY, ci->eps_max = -INFINITY;
      for (size_t i = 0; i < n_u; i++) {
        e[i] = vl_flattening_eps_exact(f, u[i] * psd->hrms_m, NULL);
        if (e[i] < ci->eps_min) ci->eps_min = e[i], ci->u_min = u[i];
        if (e[i] > ci->eps_max) ci->eps_max = e[i];
      }
      for (size_t j = 0; j < N_TABLE_U; j++)
        ci->at[j] = vl_flattening_eps_exact(f, table_u[j] * psd->hrms_m, NULL);
      ci->u90 = crossing(f, psd->hrms_m, n_u, u, e, 0.9);
      ci->u50 = crossing(f, psd->hrms_m, n_u, u, e, 0.5);
    }
    vl_flattening_free(f);
    if (psd == &variant) vl_psd_free(&variant);
  }
  if (st != VL_OK) goto done;

  /* files */
  if (vl_cli_make_dirs(out_dir) != 0) {
    vl_error_set(&err, "%s: cannot create: %s", out_dir, strerror(errno));
    st = VL_EIO;
    goto done;
  }
  char path[4300], tmp[4400];
  snprintf(path, sizeof path, "%s/flattening.csv", out_dir);
  FILE *f = open_tmp(path, tmp, sizeof tmp, &err);
  if (!f) {
    st = VL_EIO;
    goto done;
  }
  fputs("u_over_hrms", f);
  for (size_t c = 0; c < n_curves; c++) {
    if (isnan(info[c].hurst)) fprintf(f, ",eps_v%g", info[c].v0); /* tabulated surface */
    else fprintf(f, ",eps_H%g_v%g", info[c].hurst, info[c].v0);
  }
  fputc('\n', f);
  for (size_t i = 0; i < n_u; i++) {
    fprintf(f, "%.8g", u[i]);
    for (size_t c = 0; c < n_curves; c++) fprintf(f, ",%.10g", eps[c * n_u + i]);
    fputc('\n', f);
  }
  st = close_tmp(f, tmp, path, &err);
  if (st != VL_OK) goto done;
  snprintf(path, sizeof path, "%s/flattening-summary.csv", out_dir);
  f = open_tmp(path, tmp, sizeof tmp, &err);
  if (!f) {
    st = VL_EIO;
    goto done;
  }
  fputs("hurst,v0_m_s,omega_h_rad_s,e_abs_wh_pa,a_h_m,tan_delta_wh,u_onset_over_hrms,"
        "u90_over_hrms,u50_over_hrms,eps_min,u_at_eps_min_over_hrms,eps_max\n", f);
  for (size_t c = 0; c < n_curves; c++) {
    const curve_info *ci = &info[c];
    print_opt(f, ci->hurst);
    fprintf(f, ",%g,%.8g,%.8g,%.8g,%.8g,%.8g,", ci->v0, ci->st.omega_h_rad_s,
            ci->st.e_abs_pa, ci->st.a_h_m, ci->st.tan_delta, ci->st.u_onset_m / ci->st.hrms_m);
    print_opt(f, ci->u90);
    fputc(',', f);
    print_opt(f, ci->u50);
    fprintf(f, ",%.8g,%.8g,%.8g\n", ci->eps_min, ci->u_min, ci->eps_max);
  }
  st = close_tmp(f, tmp, path, &err);
  if (st != VL_OK) goto done;

  /* stdout */
  if (json) {
    printf("{\"compound\": \"%s\", \"surface\": \"%s\", \"fluid\": \"%s\", \"eta_pa_s\": %.10g, "
           "\"load_n_per_m\": %.10g, \"radius_m\": %.10g, \"response\": \"%s\", \"hrms_m\": %.10g, "
           "\"u_over_hrms\": [",
           compound, surface, fluid, eta, load, radius, vl_flattening_response_name(response),
           psd0.hrms_m);
    for (size_t i = 0; i < n_u; i++) printf("%s%.8g", i ? ", " : "", u[i]);
    printf("], \"curves\": [");
    for (size_t c = 0; c < n_curves; c++) {
      const curve_info *ci = &info[c];
      printf("%s{\"hurst\": ", c ? ", " : "");
      json_num(ci->hurst);
      printf(", \"v0_m_s\": %.10g, \"omega_h_rad_s\": %.10g, \"e_abs_wh_pa\": %.10g, "
             "\"a_h_m\": %.10g, \"tan_delta_wh\": %.10g, \"u_onset_over_hrms\": %.10g, "
             "\"u90_over_hrms\": ",
             ci->v0, ci->st.omega_h_rad_s, ci->st.e_abs_pa, ci->st.a_h_m, ci->st.tan_delta,
             ci->st.u_onset_m / ci->st.hrms_m);
      json_num(ci->u90);
      printf(", \"u50_over_hrms\": ");
      json_num(ci->u50);
      printf(", \"eps_min\": %.10g, \"epsilon_f\": [", ci->eps_min);
      for (size_t i = 0; i < n_u; i++) printf("%s%.10g", i ? ", " : "", eps[c * n_u + i]);
      printf("]}");
    }
    printf("]}\n");
  } else {
    printf("viscous flattening: %s on %s in %s (eta %g Pa s), R = %g m, fN = %g N/m, "
           "response %s\n",
           compound, surface, fluid, eta, radius, load, vl_flattening_response_name(response));
    printf("%5s %9s %10s %10s %7s %9s %9s %9s", "H", "v0 m/s", "wH rad/s", "|Er(wH)| Pa",
           "tan d", "u90/h", "u50/h", "eps_min");
    for (size_t j = 0; j < N_TABLE_U; j++) {
      char label[32];
      snprintf(label, sizeof label, "eps(%g)", table_u[j]);
      printf(" %10s", label);
    }
    printf("\n");
    for (size_t c = 0; c < n_curves; c++) {
      const curve_info *ci = &info[c];
      printf("%5.2f %9.3g %10.3g %10.3g %7.3f %9.3g %9.3g %9.4f", ci->hurst, ci->v0,
             ci->st.omega_h_rad_s, ci->st.e_abs_pa, ci->st.tan_delta, ci->u90, ci->u50,
             ci->eps_min);
      for (size_t j = 0; j < N_TABLE_U; j++) printf(" %10.4f", ci->at[j]);
      printf("\n");
    }
    printf("(u90, u50: u/h_rms where epsilon_f = 0.9, 0.5, nan: not reached in [%g, %g]; "
           "eps(x): epsilon_f at u/h_rms = x)\n"
           "wrote %s/flattening.csv and %s/flattening-summary.csv\n",
           u_lo, u_hi, out_dir, out_dir);
  }

done:
  if (st != VL_OK) {
    fprintf(stderr, "viscolube flattening: %s\n", err.msg[0] ? err.msg : vl_status_name(st));
    rc = vl_status_exit_code(st);
  }
  free(u);
  free(eps);
  free(info);
  if (have_psd) vl_psd_free(&psd0);
  vl_db_close(db);
  return rc;
}
