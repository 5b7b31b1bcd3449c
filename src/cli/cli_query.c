/* `viscolube friction ...` and `viscolube compare ...`: Stribeck answers for
 * stored compound / surface / fluid triples, built as scenes in code. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "viscolube/csv.h"
#include "viscolube/database.h"
#include "viscolube/output.h"
#include "viscolube/plot.h"
#include "viscolube/scene.h"
#include "viscolube/simulation.h"

#define MAX_COMPOUNDS 8

/* The operating conditions shared by both commands. Defaults are the seed's
 * real-rubber scenes (Figs. 15-18): R = 1 mm, fN = 117 N/m, sigma_s = 1 MPa. */
typedef struct {
  const char *surface, *fluid;
  double load, radius, sigma_s;
  size_t grid;
  const char *flow_factors;
  int json;
  int plot;
  int have_temperature; /* --temperature: compound (WLF) and fluid (its law) at temperature_c */
  double temperature_c;
} conditions;

/* The strict decimal syntax of every numeric option and CSV cell
 * (vl_csv_parse_double): no hex floats, NaN, Inf or trailing units. */
static int parse_number(const char *cmd, const char *opt, const char *v, double *out, int positive) {
  double d = 0.0;
  if (!v || vl_csv_parse_double(v, &d, NULL) != VL_OK || (positive ? d <= 0.0 : d < 0.0)) {
    fprintf(stderr, "viscolube %s: option %s needs a %s number (got '%s')\n", cmd, opt,
            positive ? "positive" : "non-negative", v ? v : "");
    return 0;
  }
  *out = d;
  return 1;
}

/* Common options; returns 1 when argv[*i] was one of them (consuming its
 * value), 0 when not, -1 on a bad value. */
static int common_option(const char *cmd, int argc, char **argv, int *i, conditions *c) {
  const char *o = argv[*i];
  const char *v = *i + 1 < argc ? argv[*i + 1] : NULL;
  double d;
  if (!strcmp(o, "--json")) {
    c->json = 1;
    return 1;
  }
  if (!strcmp(o, "--plot") && !strcmp(cmd, "compare")) {
    c->plot = 1;
    return 1;
  }
  if (!strcmp(o, "--surface") || !strcmp(o, "--fluid") || !strcmp(o, "--flow-factors")) {
    if (!v) {
      fprintf(stderr, "viscolube %s: option %s needs a value\n", cmd, o);
      return -1;
    }
    if (!strcmp(o, "--surface")) c->surface = v;
    else if (!strcmp(o, "--fluid")) c->fluid = v;
    else c->flow_factors = v;
    (*i)++;
    return 1;
  }
  if (!strcmp(o, "--load") || !strcmp(o, "--radius") || !strcmp(o, "--sigma-s") ||
      !strcmp(o, "--grid")) {
    if (!parse_number(cmd, o, v, &d, strcmp(o, "--sigma-s") != 0)) return -1;
    if (!strcmp(o, "--load")) c->load = d;
    else if (!strcmp(o, "--radius")) c->radius = d;
    else if (!strcmp(o, "--sigma-s")) c->sigma_s = d;
    else {
      if (d < 16 || d > VL_GRID_GRADED_MAX || d != floor(d)) {
        fprintf(stderr, "viscolube %s: option --grid needs a whole number in [16, %d]\n", cmd,
                VL_GRID_GRADED_MAX);
        return -1;
      }
      c->grid = (size_t)d;
    }
    (*i)++;
    return 1;
  }
  if (!strcmp(o, "--temperature")) {
    if (!v || vl_csv_parse_double(v, &d, NULL) != VL_OK || d < -273.15) {
      fprintf(stderr, "viscolube %s: option --temperature needs a temperature in C (got '%s')\n",
              cmd, v ? v : "");
      return -1;
    }
    c->have_temperature = 1;
    c->temperature_c = d;
    (*i)++;
    return 1;
  }
  return 0;
}

/* The viscosity the run uses: the stored one, or with --temperature the
 * fluid's law at that temperature (fluid.h; the same call the simulation
 * makes, so both agree exactly). */
static vl_status fluid_eta(vl_db *db, const conditions *c, double *eta, vl_error *err) {
  if (!c->have_temperature) return vl_db_fluid_get(db, c->fluid, eta, err);
  vl_db_fluid f;
  vl_status st = vl_db_fluid_info(db, c->fluid, &f, err);
  if (st == VL_OK) st = vl_fluid_viscosity(&f.law, f.viscosity_pa_s, f.tref_c, c->temperature_c,
                                           eta, err);
  if (st == VL_EINPUT)
    vl_error_prefix(err, "--temperature %g: fluid '%s'", c->temperature_c, c->fluid);
  return st;
}

/* With --temperature: VL_OK if compound can be taken there (WLF constants,
 * above the WLF singularity), checked before anything is computed so the
 * message names the option. Without: VL_OK. */
static vl_status compound_at(vl_db *db, const conditions *c, const char *compound, vl_error *err) {
  if (!c->have_temperature) return VL_OK;
  vl_db_compound info;
  vl_prony shifted;
  double a_T;
  vl_status st = vl_db_compound_info(db, compound, &info, err);
  if (st == VL_OK) st = vl_compound_at_temperature(&info, c->temperature_c, &shifted, &a_T, err);
  if (st == VL_EINPUT) vl_error_prefix(err, "--temperature %g", c->temperature_c);
  return st;
}

/* A wet rough scene for compound at the given conditions. */
static int make_scene(const char *cmd, const conditions *c, const char *compound, vl_scene *sc) {
  vl_scene_defaults(sc);
  snprintf(sc->path, sizeof sc->path, "%s", cmd);
  snprintf(sc->compound, sizeof sc->compound, "%s", compound);
  snprintf(sc->surface, sizeof sc->surface, "%s", c->surface);
  snprintf(sc->fluid, sizeof sc->fluid, "%s", c->fluid);
  snprintf(sc->fluids[0], sizeof sc->fluids[0], "%s", c->fluid);
  sc->n_fluids = 1;
  sc->radius_m = c->radius;
  sc->load_n_per_m = c->load;
  sc->sigma_s_pa = c->sigma_s;
  sc->effects.roughness = true;
  sc->effects.fluid = true;
  sc->effects.solid_shear = c->sigma_s > 0.0;
  sc->effects.flow_factors = VL_FLOW_FACTORS_SMOOTH;
  if (c->flow_factors) {
    vl_error err;
    if (vl_flow_factors_parse(c->flow_factors, &sc->effects.flow_factors, &err) != VL_OK) {
      fprintf(stderr, "viscolube %s: --flow-factors: %s\n", cmd, err.msg);
      return 0;
    }
  }
  vl_scene_default_numerics(sc);
  if (c->grid) sc->grid = c->grid; /* 0: the default */
  sc->quantity = VL_SWEEP_V0_ETA;
  if (c->have_temperature) {
    sc->effects.temperature = true;
    sc->effects.temperature_c = c->temperature_c;
  }
  return 1;
}

static int need(const char *cmd, const char *what, const void *value) {
  if (value) return 1;
  fprintf(stderr, "viscolube %s: missing %s (see viscolube %s --help)\n", cmd, what, cmd);
  return 0;
}

static void friction_usage(FILE *out) {
  fputs("usage: viscolube friction --compound C --surface S --fluid F --speed V_M_S\n"
        "                          [--load N_PER_M] [--radius M] [--sigma-s PA]\n"
        "                          [--flow-factors smooth|patir-cheng] [--grid N]\n"
        "                          [--temperature C] [--json]\n"
        "\n"
        "Friction of one operating point: a smooth rigid cylinder (radius, load per unit\n"
        "length) sliding at V on the stored compound with the stored rough surface in the\n"
        "stored fluid. Prints mu and its four components (mu_Rc, mu_Rf, mu_Sc, mu_Sf),\n"
        "the minimum separation, the share of the load carried by solid contact and the\n"
        "regime. The point is reached by continuation in speed from the boundary regime\n"
        "(v0 eta = 1e-12 Pa m) when a direct solve does not converge.\n"
        "--temperature C takes the compound to C by its WLF constants (every Prony time\n"
        "times a_T) and the fluid's viscosity to C by its stored law (`viscolube fluid\n"
        "show`); without it both are at their reference temperatures. A compound without\n"
        "WLF constants or a fluid without a law (other than at its reference\n"
        "temperature) is refused. The output states the temperature, a_T and viscosity.\n"
        "Defaults (the seed's real-rubber scenes): --load 117, --radius 0.001,\n"
        "--sigma-s 1e6, --flow-factors smooth (Patir-Cheng fails below\n"
        "u ~ 0.3 h_rms: README, Known limitations), domain [-96, 1.6] a0 with\n"
        "--grid 2928 (the uniform cells: a0/30) merged upstream of -2 a0 into cells\n"
        "growing by 5 % (about 200 cells), tolerance 1e-6 (README: Accuracy and cost).\n",
        out);
}

int vl_cli_friction(const vl_cli_globals *g, int argc, char **argv) {
  conditions c = {NULL, NULL, 117.0, 1e-3, 1e6, 0, NULL, 0, 0, 0, NAN};
  const char *compound = NULL;
  double speed = 0.0;
  int have_speed = 0;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      friction_usage(stdout);
      return 0;
    }
    int r = common_option("friction", argc, argv, &i, &c);
    if (r < 0) return 2;
    if (r) continue;
    if (!strcmp(argv[i], "--compound") && i + 1 < argc) {
      compound = argv[++i];
    } else if (!strcmp(argv[i], "--speed")) {
      if (!parse_number("friction", "--speed", i + 1 < argc ? argv[i + 1] : NULL, &speed, 1))
        return 2;
      have_speed = 1;
      i++;
    } else {
      fprintf(stderr, "viscolube friction: unknown or incomplete option '%s' (see --help)\n",
              argv[i]);
      return 2;
    }
  }
  if (!need("friction", "--compound", compound) || !need("friction", "--surface", c.surface) ||
      !need("friction", "--fluid", c.fluid) || !need("friction", "--speed", have_speed ? "" : NULL))
    return 2;
  vl_scene sc;
  if (!make_scene("friction", &c, compound, &sc)) return 2;
  vl_error err = {{0}};
  vl_db *db = NULL;
  vl_simulation *sim = NULL;
  vl_status st = vl_db_open(g->db_path, &db, &err);
  double eta = 0.0;
  if (st == VL_OK) st = compound_at(db, &c, compound, &err);
  if (st == VL_OK) st = fluid_eta(db, &c, &eta, &err);
  vl_point pt = {0};
  vl_sweep_stats stats = {0};
  /* first a direct solve from the Hertz guess; if it fails, continuation
   * from the boundary regime (v0 eta = 1e-12 Pa m), 4 points a decade */
  for (int attempt = 0; st == VL_OK && attempt < 2; attempt++) {
    sc.to = speed * eta;
    sc.from = attempt == 0 ? sc.to : fmin(1e-12, 0.1 * sc.to);
    sc.points = attempt == 0 ? 1 : (size_t)ceil(4.0 * log10(sc.to / sc.from)) + 1;
    vl_simulation_free(sim);
    sim = NULL;
    st = vl_simulation_create(&sc, db, &sim, &err);
    if (st != VL_OK) break;
    size_t n = vl_simulation_points(sim);
    vl_point *pts = calloc(n, sizeof *pts);
    if (!pts) {
      st = VL_ENOMEM;
      vl_error_set(&err, "out of memory");
      break;
    }
    vl_sweep_stats one;
    st = vl_simulation_run(sim, pts, NULL, NULL, &one, &err);
    stats.converged += one.converged;
    stats.failed += one.failed;
    pt = pts[n - 1];
    free(pts);
    if (pt.converged) break;
  }
  int rc = 0;
  if (st != VL_OK) {
    fprintf(stderr, "viscolube friction: %s\n", err.msg[0] ? err.msg : vl_status_name(st));
    rc = vl_status_exit_code(st);
  } else {
    const vl_psd *psd = vl_simulation_psd(sim);
    double hrms = psd ? psd->hrms_m : 0.0;
    vl_curve_meta meta = {eta, 0.0, vl_contact_a0(vl_simulation_contact(sim))};
    if (c.json && c.have_temperature) {
      /* the point's object with the temperature, shift and viscosity first */
      char *obj = NULL;
      size_t len = 0;
      FILE *m = open_memstream(&obj, &len);
      if (m) {
        vl_print_point_json(m, &pt, &meta);
        fclose(m);
      }
      if (!m || !obj) {
        fprintf(stderr, "viscolube friction: out of memory\n");
        rc = vl_status_exit_code(VL_ENOMEM);
      } else {
        printf("{\"temperature_c\": %.10g, \"a_T\": %.10g, \"eta_pa_s\": %.10g, %s\n",
               c.temperature_c, vl_simulation_shift_factor(sim), eta, obj + 1);
      }
      free(obj);
    } else if (c.json) {
      vl_print_point_json(stdout, &pt, &meta);
      fputc('\n', stdout);
    } else if (pt.converged) {
      printf("%s on %s in %s at v0 = %g m/s (v0 eta = %g Pa m), R = %g m, fN = %g N/m\n",
             compound, c.surface, c.fluid, speed, speed * eta, c.radius, c.load);
      if (c.have_temperature)
        printf("  at %g C: compound times x a_T = %.4g (WLF), fluid viscosity %.4g Pa s\n",
               c.temperature_c, vl_simulation_shift_factor(sim), eta);
      printf("  mu      = %.5g\n  mu_Rc   = %.5g   (hysteresis under the solid contact)\n"
             "  mu_Rf   = %.5g   (asymmetry of the fluid pressure)\n"
             "  mu_Sc   = %.5g   (shear in the real contact area)\n"
             "  mu_Sf   = %.5g   (fluid shear)\n",
             pt.mu, pt.mu_Rc + 0.0, pt.mu_Rf + 0.0, pt.mu_Sc + 0.0, pt.mu_Sf + 0.0);
      printf("  u_min   = %.4g m (%.3g h_rms)\n  solid contact carries %.1f %% of the load; "
             "regime: %s\n  Q = %.3g; %ld Newton iterations, residual %.2g (%zu continuation "
             "points)\n",
             pt.u_min_m, hrms > 0 ? pt.u_min_m / hrms : 0.0, 100.0 * (1.0 - pt.fluid_load_fraction),
             vl_regime_name(pt.regime), pt.Q, pt.iterations, pt.residual, stats.converged + stats.failed);
    }
    if (!pt.converged) {
      fprintf(stderr, "viscolube friction: the solve did not converge at v0 = %g m/s "
                      "(%ld iterations, residual %.3g)\n", speed, pt.iterations, pt.residual);
      rc = vl_status_exit_code(VL_ENOCONV);
    }
  }
  vl_simulation_free(sim);
  vl_db_close(db);
  return rc;
}

static void compare_usage(FILE *out) {
  fputs("usage: viscolube compare --compounds A,B[,...] --surface S --fluid F\n"
        "                         [--from V0ETA] [--to V0ETA] [--points N] [--out DIR]\n"
        "                         [--load N_PER_M] [--radius M] [--sigma-s PA]\n"
        "                         [--flow-factors smooth|patir-cheng] [--grid N] [--json]\n"
        "                         [--plot] [--temperature C]\n"
        "\n"
        "Stribeck curves (mu vs v0*eta, Pa m) of several compounds on one surface in one\n"
        "fluid, side by side: mu and u_min/h_rms per compound. Writes DIR/compare.csv\n"
        "(one row per v0*eta; mu, mu_Rc, mu_Rf, mu_Sc, mu_Sf, u_min_over_hrms, converged\n"
        "per compound) and DIR/<compound>/curve.csv. DIR defaults to out/compare.\n"
        "With --plot also DIR/compare-mu.{png,svg} and DIR/compare-umin.{png,svg}: the\n"
        "compounds' curves on one axis.\n"
        "--temperature C: every compound and the fluid at C, as for `viscolube friction`\n"
        "(v0*eta then uses the fluid's viscosity at C); compare.csv gets the columns\n"
        "temperature_c and eta_pa_s, the JSON the keys of the same names.\n"
        "Defaults: --from 1e-12 --to 0.1 --points 45, and those of `viscolube friction`.\n",
        out);
}

int vl_cli_compare(const vl_cli_globals *g, int argc, char **argv) {
  conditions c = {NULL, NULL, 117.0, 1e-3, 1e6, 0, NULL, 0, 0, 0, NAN};
  char list[MAX_COMPOUNDS * 128] = "";
  char *names[MAX_COMPOUNDS];
  size_t nc = 0;
  double from = 1e-12, to = 0.1, points = 45;
  const char *out_dir = "out/compare";
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      compare_usage(stdout);
      return 0;
    }
    int r = common_option("compare", argc, argv, &i, &c);
    if (r < 0) return 2;
    if (r) continue;
    const char *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(argv[i], "--compounds") && v) {
      snprintf(list, sizeof list, "%s", v);
      i++;
    } else if (!strcmp(argv[i], "--out") && v) {
      out_dir = v;
      i++;
    } else if (!strcmp(argv[i], "--from") || !strcmp(argv[i], "--to") || !strcmp(argv[i], "--points")) {
      double *dst = !strcmp(argv[i], "--from") ? &from : !strcmp(argv[i], "--to") ? &to : &points;
      if (!parse_number("compare", argv[i], v, dst, 1)) return 2;
      i++;
    } else {
      fprintf(stderr, "viscolube compare: unknown or incomplete option '%s' (see --help)\n",
              argv[i]);
      return 2;
    }
  }
  char *save = NULL;
  for (char *t = strtok_r(list, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
    if (nc == MAX_COMPOUNDS) {
      fprintf(stderr, "viscolube compare: at most %d compounds\n", MAX_COMPOUNDS);
      return 2;
    }
    names[nc++] = t;
  }
  if (!need("compare", "--compounds", nc ? "" : NULL) || !need("compare", "--surface", c.surface) ||
      !need("compare", "--fluid", c.fluid))
    return 2;
  if (!(to > from) || points != floor(points) || points < 2 || points > 10000) {
    fprintf(stderr, "viscolube compare: need --from < --to and a whole --points in [2, 10000]\n");
    return 2;
  }
  vl_error err = {{0}};
  vl_db *db = NULL;
  vl_status st = vl_db_open(g->db_path, &db, &err);
  size_t n = (size_t)points;
  vl_point *pts = calloc(n * nc, sizeof *pts);
  double *hrms = calloc(nc, sizeof *hrms), eta = 0.0;
  int rc = 0;
  size_t failed = 0;
  if (!pts || !hrms) st = VL_ENOMEM, vl_error_set(&err, "out of memory");
  /* every name must exist before anything is computed or written */
  for (size_t k = 0; st == VL_OK && k < nc; k++) {
    vl_prony probe;
    st = vl_db_compound_get(db, names[k], &probe, &err);
  }
  /* and, with --temperature, be usable there (WLF constants, fluid law) */
  for (size_t k = 0; st == VL_OK && k < nc; k++) st = compound_at(db, &c, names[k], &err);
  if (st == VL_OK && c.have_temperature) st = fluid_eta(db, &c, &eta, &err);
  if (st == VL_OK && vl_cli_make_dirs(out_dir) != 0) {
    vl_error_set(&err, "%s: cannot create: %s", out_dir, strerror(errno));
    st = VL_EIO;
  }
  for (size_t k = 0; st == VL_OK && k < nc; k++) {
    vl_scene sc;
    if (!make_scene("compare", &c, names[k], &sc)) {
      rc = 2;
      goto done;
    }
    sc.from = from, sc.to = to, sc.points = n;
    vl_simulation *sim = NULL;
    st = vl_simulation_create(&sc, db, &sim, &err);
    if (st != VL_OK) break;
    eta = vl_simulation_eta(sim);
    const vl_psd *psd = vl_simulation_psd(sim);
    hrms[k] = psd ? psd->hrms_m : 1.0;
    vl_sweep_stats stats;
    if (!c.json) fprintf(stderr, "compare: %s ...\n", names[k]);
    st = vl_simulation_run(sim, pts + k * n, NULL, NULL, &stats, &err);
    failed += stats.failed;
    char dir[4200], path[4300];
    snprintf(dir, sizeof dir, "%s/%s", out_dir, names[k]);
    if (st == VL_OK && vl_cli_make_dirs(dir) != 0) {
      vl_error_set(&err, "%s: cannot create: %s", dir, strerror(errno));
      st = VL_EIO;
    }
    if (st == VL_OK) {
      vl_curve_meta meta = {eta, vl_simulation_tau(sim), vl_contact_a0(vl_simulation_contact(sim))};
      snprintf(path, sizeof path, "%s/curve.csv", dir);
      st = vl_write_curve_csv(path, n, pts + k * n, &meta, &err);
    }
    vl_simulation_free(sim);
  }
  if (st != VL_OK) goto done;
  /* side by side: DIR/compare.csv and the table */
  char path[4300];
  snprintf(path, sizeof path, "%s/compare.csv", out_dir);
  FILE *f = fopen(path, "w");
  if (!f) {
    vl_error_set(&err, "%s: cannot write: %s", path, strerror(errno));
    st = VL_EIO;
    goto done;
  }
  fputs("v0_eta_pa_m", f);
  for (size_t k = 0; k < nc; k++)
    fprintf(f, ",mu_%s,mu_Rc_%s,mu_Rf_%s,mu_Sc_%s,mu_Sf_%s,u_min_over_hrms_%s,converged_%s",
            names[k], names[k], names[k], names[k], names[k], names[k], names[k]);
  /* with --temperature the rows say at which temperature and viscosity
   * (appended: the columns of a reference-temperature run are unchanged) */
  if (c.have_temperature) fputs(",temperature_c,eta_pa_s", f);
  fputc('\n', f);
  if (!c.json) {
    if (c.have_temperature)
      printf("at %g C: fluid viscosity %.4g Pa s, compounds shifted by WLF\n", c.temperature_c,
             eta);
    printf("%12s", "v0_eta_pa_m");
    for (size_t k = 0; k < nc; k++) printf(" %14.14s %14s", names[k], "u_min/h_rms");
    printf("\n");
  } else {
    printf("{");
    if (c.have_temperature)
      printf("\"temperature_c\": %.10g, \"eta_pa_s\": %.10g, ", c.temperature_c, eta);
    printf("\"v0_eta_pa_m\": [");
    for (size_t i = 0; i < n; i++) printf("%s%.6g", i ? ", " : "", pts[i].v0_m_s * eta);
    printf("]");
  }
  for (size_t i = 0; i < n; i++) {
    double x = pts[i].v0_m_s * eta;
    fprintf(f, "%.10g", x);
    if (!c.json) printf("%12.4g", x);
    for (size_t k = 0; k < nc; k++) {
      const vl_point *p = &pts[k * n + i];
      if (p->converged) {
        fprintf(f, ",%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,1", p->mu, p->mu_Rc + 0.0, p->mu_Rf + 0.0,
                p->mu_Sc + 0.0, p->mu_Sf + 0.0, p->u_min_m / hrms[k]);
        if (!c.json) printf(" %14.5g %14.4g", p->mu, p->u_min_m / hrms[k]);
      } else {
        fputs(",,,,,,,0", f);
        if (!c.json) printf(" %14s %14s", "-", "-");
      }
    }
    if (c.have_temperature) fprintf(f, ",%.10g,%.10g", c.temperature_c, eta);
    fputc('\n', f);
    if (!c.json) printf("\n");
  }
  if (c.json) {
    for (size_t k = 0; k < nc; k++) {
      vl_curve_meta meta = {eta, 0.0, 0.0};
      printf(", \"%s\": ", names[k]);
      vl_print_curve_json(stdout, n, pts + k * n, &meta);
    }
    printf("}\n");
  }
  if (fclose(f) != 0) {
    vl_error_set(&err, "%s: write failed", path);
    st = VL_EIO;
    goto done;
  }
  if (c.plot) {
    vl_plot_curve curves[MAX_COMPOUNDS];
    for (size_t k = 0; k < nc; k++)
      curves[k] = (vl_plot_curve){names[k], n, pts + k * n, {eta, 0.0, 0.0}, hrms[k]};
    vl_plot_options opt;
    vl_plot_options_defaults(&opt);
    opt.mark_half_load = true;
    char stem[4300];
    snprintf(stem, sizeof stem, "%s/compare-mu", out_dir);
    st = vl_plot_compare(stem, nc, curves, VL_SWEEP_V0_ETA, VL_PLOT_Y_MU, &opt, NULL, &err);
    if (st == VL_OK) {
      snprintf(stem, sizeof stem, "%s/compare-umin", out_dir);
      st = vl_plot_compare(stem, nc, curves, VL_SWEEP_V0_ETA, VL_PLOT_Y_U_MIN, &opt, NULL, &err);
    }
    if (st != VL_OK) goto done;
  }
  if (!c.json) printf("wrote %s and %s/<compound>/curve.csv%s\n", path, out_dir,
                      c.plot ? " and compare-mu/compare-umin figures" : "");
  if (failed) rc = vl_status_exit_code(VL_ENOCONV);
done:
  if (st != VL_OK) {
    fprintf(stderr, "viscolube compare: %s\n", err.msg[0] ? err.msg : vl_status_name(st));
    rc = vl_status_exit_code(st);
  }
  free(pts);
  free(hrms);
  vl_db_close(db);
  return rc;
}
