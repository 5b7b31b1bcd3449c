/* `viscolube friction ...` and `viscolube compare ...`: Stribeck answers for
 * stored compound / surface / fluid triples, built as scenes in code. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_options.h"

#define MAX_COMPOUNDS 8

/* The operating conditions shared by both commands: a query of the library
 * (query.h, whose defaults are the seed's real-rubber scenes) and how the
 * answer is shown. */
typedef struct {
  vl_query q;               /* surface, fluid, load, radius, sigma_s, grid, film
                             * cut-off, temperature; flow_factors from the text below */
  const char *flow_factors; /* --flow-factors as given (NULL: the default) */
  int geometry;             /* --geometry: the index of vl_geometry (cylinder, ball, ellipsoid) */
  double radii[2];          /* --radii RX,RY (an ellipsoid's) */
  size_t n_radii;
  /* which of the rigid body's options were given (geometry_options) */
  int load_given, load_n_given, radius_given, grid_given, cutoff_given;
  int json;
  int plot;
  int quiet; /* --quiet (or the global one): no warnings, no progress */
} conditions;

/* The rules of the numeric options (messages: option, text as typed). */
static const vl_cli_number_rule positive = {
    .lo = 0.0, .lo_open = 1, .hi = INFINITY, .bad = "option %s needs a positive number (got '%s')"};
static const vl_cli_number_rule non_negative = {
    .lo = 0.0, .hi = INFINITY, .bad = "option %s needs a non-negative number (got '%s')"};
static const vl_cli_number_rule temperature = {
    .lo = -273.15, .hi = INFINITY, .bad = "option %s needs a temperature in C (got '%s')"};

/* The options both commands take, into opts (room for N_COMMON); the
 * numbers that need a second look go to grid and the given counts. */
#define N_COMMON 16
#define UNKNOWN_OR_INCOMPLETE "unknown or incomplete option '%s' (see --help)"

typedef struct {
  vl_cli_number_rule grid, film_cutoff, target; /* with their limits in the messages */
  char grid_range[96], cutoff_range[96];
  double grid_value;
} common_rules;

static size_t common_options(conditions *c, common_rules *r, vl_cli_option *opts) {
  r->grid = positive;
  r->grid.range_lo = VL_GRID_MIN;
  r->grid.hi = VL_GRID_GRADED_MAX;
  r->grid.whole = 1;
  snprintf(r->grid_range, sizeof r->grid_range, "option %%s needs a whole number in [%d, %d]",
           VL_GRID_MIN, VL_GRID_GRADED_MAX);
  r->grid.range = r->grid_range;
  r->film_cutoff = positive;
  r->film_cutoff.hi = VL_FILM_CUTOFF_MAX_M;
  snprintf(r->cutoff_range, sizeof r->cutoff_range,
           "option %%s needs a length in (0, %g] m (got '%%s')", VL_FILM_CUTOFF_MAX_M);
  r->film_cutoff.range = r->cutoff_range;
  r->target = positive;
  r->target.range_lo = 1e-6, r->target.hi = 0.5;
  r->target.range = "option %s needs a relative error in [1e-6, 0.5] (got '%s')";
  const char *value = "option %s needs a value";
  static const char *const geometries[] = {"cylinder", "ball", "ellipsoid", NULL};
  vl_cli_option common[N_COMMON] = {
      {.name = "--help", .alias = "-h", .kind = VL_CLI_HELP},
      {.name = "--json", .kind = VL_CLI_FLAG, .dest = &c->json},
      {.name = "--quiet", .alias = "-q", .kind = VL_CLI_FLAG, .dest = &c->quiet},
      {.name = "--surface", .kind = VL_CLI_TEXT, .dest = &c->q.surface, .missing = value},
      {.name = "--fluid", .kind = VL_CLI_TEXT, .dest = &c->q.fluid, .missing = value},
      {.name = "--flow-factors", .kind = VL_CLI_TEXT, .dest = &c->flow_factors, .missing = value},
      {.name = "--load", .kind = VL_CLI_NUMBER, .dest = &c->q.load_n_per_m, .rule = &positive},
      {.name = "--radius", .kind = VL_CLI_NUMBER, .dest = &c->q.radius_m, .rule = &positive},
      {.name = "--geometry",
       .kind = VL_CLI_CHOICE,
       .dest = &c->geometry,
       .choices = geometries,
       .choice_bad = "option %s needs cylinder, ball or ellipsoid (got '%s')"},
      {.name = "--load-n", .kind = VL_CLI_NUMBER, .dest = &c->q.load_n, .rule = &positive},
      {.name = "--radii",
       .kind = VL_CLI_LIST,
       .dest = c->radii,
       .max_values = 2,
       .n_values = &c->n_radii},
      {.name = "--sigma-s", .kind = VL_CLI_NUMBER, .dest = &c->q.sigma_s_pa, .rule = &non_negative},
      {.name = "--grid", .kind = VL_CLI_NUMBER, .dest = &r->grid_value, .rule = &r->grid},
      {.name = "--film-cutoff",
       .kind = VL_CLI_NUMBER,
       .dest = &c->q.film_cutoff_m,
       .rule = &r->film_cutoff},
      {.name = "--temperature",
       .kind = VL_CLI_NUMBER,
       .dest = &c->q.temperature_c,
       .rule = &temperature},
      {.name = "--target-error",
       .kind = VL_CLI_NUMBER,
       .dest = &c->q.target_error,
       .rule = &r->target},
  };
  memcpy(opts, common, sizeof common);
  return N_COMMON;
}

/* After the parse: the common options that are more than a value. */
static void common_given(vl_cli_parser *p, conditions *c, const common_rules *r) {
  if (vl_cli_find(p, "--grid")->given) c->q.grid = (size_t)r->grid_value;
  if (vl_cli_find(p, "--temperature")->given) c->q.at_temperature = true;
  if (vl_cli_find(p, "--sigma-s")->given) c->q.sigma_s_given = true; /* over a stored pair */
  c->load_given = vl_cli_find(p, "--load")->given;
  c->load_n_given = vl_cli_find(p, "--load-n")->given;
  c->radius_given = vl_cli_find(p, "--radius")->given;
  c->grid_given = vl_cli_find(p, "--grid")->given;
  c->cutoff_given = vl_cli_find(p, "--film-cutoff")->given;
}

/* Parses argv by p (its table: the common options and the command's);
 * -1 to go on, else the exit status (0 after the usage on --help). */
static int parse_command(vl_cli_parser *p, int argc, char **argv, conditions *c,
                         const common_rules *r, void (*usage)(FILE *)) {
  p->flags = 0;
  p->unknown = UNKNOWN_OR_INCOMPLETE;
  p->usage = usage;
  int rc = vl_cli_parse(p, argc, argv, 1);
  if (rc >= 0) return rc;
  common_given(p, c, r);
  return -1;
}

/* The viscosity the run uses (vl_query_fluid_eta), the message naming the
 * option. */
static vl_status fluid_eta(vl_db *db, const conditions *c, double *eta, vl_error *err) {
  vl_status st = vl_query_fluid_eta(db, &c->q, eta, err);
  /* the message names the fluid and the temperature: the option, once */
  if (st == VL_EINPUT) vl_error_prefix(err, "--temperature");
  return st;
}

/* With --temperature: VL_OK if compound can be taken there, checked before
 * anything is computed so the message names the option. Without: VL_OK. */
static vl_status compound_at(vl_db *db, const conditions *c, const char *compound, vl_error *err) {
  vl_status st = vl_query_check_compound(db, &c->q, compound, err);
  if (st == VL_EINPUT) vl_error_prefix(err, "--temperature");
  return st;
}

/* The query of these conditions for compound, --flow-factors parsed. */
static vl_query query_for(const conditions *c, const char *compound) {
  vl_query q = c->q;
  q.compound = compound;
  if (c->flow_factors) vl_flow_factors_parse(c->flow_factors, &q.flow_factors, NULL);
  return q;
}

/* The flow-factor model of these conditions (the user's, else the default)
 * and its film cut-off (persson-emt; else 0), as the scenes get them; NULL
 * (cut-off 0) for a point contact without a rough film (no surface or no
 * fluid: no flow factors). */
static const char *model_of(const conditions *c, double *film_cutoff_m) {
  vl_query q = query_for(c, NULL);
  *film_cutoff_m = 0.0;
  if (c->geometry != VL_GEOMETRY_CYLINDER && !(q.surface && q.fluid)) return NULL;
  return vl_query_flow_factors(&q, film_cutoff_m);
}

/* The wet rough scene of compound at the given conditions (vl_query_scene);
 * 0 after the message naming the option when they do not go together. */
static int make_scene(const char *cmd, const conditions *c, const char *compound, vl_scene *sc) {
  vl_error err;
  vl_flow_factor_kind k;
  if (c->flow_factors && vl_flow_factors_parse(c->flow_factors, &k, &err) != VL_OK) {
    fprintf(stderr, "viscolube %s: --flow-factors: %s\n", cmd, err.msg);
    return 0;
  }
  vl_query q = query_for(c, compound);
  if (q.film_cutoff_m > 0.0 && q.flow_factors != VL_FLOW_FACTORS_PERSSON_EMT) {
    fprintf(stderr, "viscolube %s: --film-cutoff applies to --flow-factors persson-emt only\n",
            cmd);
    return 0;
  }
  if (vl_query_scene(&q, NULL, sc, &err) != VL_OK) {
    fprintf(stderr, "viscolube %s: %s\n", cmd, err.msg);
    return 0;
  }
  return 1;
}

/* 1 if name (given by option opt) is a valid material name, else 0 after
 * the message: a name becomes a folder name (compare's DIR/<compound>). */
static int valid_name(const char *cmd, const char *opt, const char *name) {
  vl_error err;
  if (vl_db_check_name(name, &err) == VL_OK) return 1;
  fprintf(stderr, "viscolube %s: %s: %s\n", cmd, opt, err.msg);
  return 0;
}

static int need(const char *cmd, const char *what, const void *value) {
  if (value) return 1;
  fprintf(stderr, "viscolube %s: missing %s (see viscolube %s --help)\n", cmd, what, cmd);
  return 0;
}

/* Why the rigid body's options do not go together (the rules of a scene's
 * [contact] keys, FORMATS.md, in options), into buf; NULL when they do. */
static const char *geometry_trouble(const conditions *c, char *buf, size_t size) {
  int g = c->geometry;
  const char *name = vl_geometry_name(g);
  if (g == VL_GEOMETRY_CYLINDER && c->load_n_given)
    return "--load-n (a total load, N) is a ball's or an ellipsoid's (--geometry): a cylinder "
           "takes --load N_PER_M";
  if (g != VL_GEOMETRY_ELLIPSOID && c->n_radii)
    snprintf(buf, size, "--radii is an ellipsoid's: a %s takes --radius M", name);
  else if (g == VL_GEOMETRY_CYLINDER)
    return NULL;
  else if (c->load_given)
    snprintf(buf, size,
             "--load (N per metre of a cylinder's length) is not a %s's: it takes --load-n N, "
             "its total load",
             name);
  else if (!c->load_n_given)
    snprintf(buf, size, "missing --load-n N (the %s's total load)", name);
  else if (g == VL_GEOMETRY_BALL && !c->radius_given)
    return "missing --radius M (the ball's radius)";
  else if (g == VL_GEOMETRY_ELLIPSOID && c->radius_given)
    return "--radius is not an ellipsoid's: it takes --radii RX,RY (along the sliding direction "
           "and across it)";
  else if (g == VL_GEOMETRY_ELLIPSOID && c->n_radii != 2)
    return "--geometry ellipsoid needs --radii RX,RY (two radii, m: along the sliding direction "
           "and across it)";
  else if (c->grid_given)
    snprintf(buf, size,
             "--grid sets a line contact's cells: a %s's are planned per point "
             "(docs/POINT_CONTACT.md)",
             name);
  else if (!c->q.surface && (c->flow_factors || c->cutoff_given))
    snprintf(buf, size, "%s applies to a rough contact (--surface) only",
             c->flow_factors ? "--flow-factors" : "--film-cutoff");
  else
    return NULL;
  return buf;
}

/* The rigid body's options into the query: 1 when they go together, else
 * 0 after the message naming the option. */
static int geometry_options(const char *cmd, conditions *c) {
  char buf[256];
  const char *bad = geometry_trouble(c, buf, sizeof buf);
  if (bad) {
    fprintf(stderr, "viscolube %s: %s\n", cmd, bad);
    return 0;
  }
  c->q.geometry = c->geometry;
  if (c->geometry == VL_GEOMETRY_ELLIPSOID)
    c->q.radius_m = c->radii[0], c->q.radius_y_m = c->radii[1];
  return 1;
}

/* The material options of both commands: a cylinder needs --surface and
 * --fluid, a ball or an ellipsoid may go without (smooth, dry). 1 when
 * they are fine, else 0 after the message. */
static int material_options(const char *cmd, const conditions *c) {
  bool line = c->geometry == VL_GEOMETRY_CYLINDER;
  if (line && (!need(cmd, "--surface", c->q.surface) || !need(cmd, "--fluid", c->q.fluid)))
    return 0;
  return (!c->q.surface || valid_name(cmd, "--surface", c->q.surface)) &&
         (!c->q.fluid || valid_name(cmd, "--fluid", c->q.fluid));
}

static void friction_usage(FILE *out) {
  fputs("usage: viscolube friction --compound C --surface S --fluid F --speed V_M_S\n"
        "                          [--load N_PER_M] [--radius M] [--sigma-s PA]\n"
        "                          [--flow-factors persson-emt|patir-cheng|smooth]\n"
        "                          [--film-cutoff M] [--grid N] [--temperature C]\n"
        "                          [--target-error E] [--json] [--quiet]\n"
        "       viscolube friction --geometry ball|ellipsoid --compound C [--surface S]\n"
        "                          [--fluid F] --speed V_M_S --load-n N\n"
        "                          (--radius M | --radii RX,RY) [--sigma-s PA] ...\n"
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
        "--sigma-s 1e6, --flow-factors persson-emt (Persson's gap distribution and an\n"
        "effective medium, consistent with the contact law: docs/FLOW_FACTORS.md) with\n"
        "--film-cutoff 1e-9 (gaps below it carry no Couette shear), domain [-96, 1.6] a0 with\n"
        "--grid 2928 (the uniform cells: a0/30) merged upstream of -2 a0 into cells\n"
        "growing by 5 % (about 200 cells), tolerance 1e-6 (docs/NUMERICS.md).\n"
        "The point's model-validity warnings follow on stderr, one a line (with --json\n"
        "only in the JSON; --quiet leaves them out).\n"
        "--target-error E: the relative error of mu the point should meet (default\n"
        "0.01); the numerics are refined towards it, and a point still above it (or\n"
        "without an error estimate) is marked.\n"
        "--geometry ball (--radius M, --load-n N: the total load) or ellipsoid (--radii\n"
        "RX,RY along and across the sliding direction, --load-n N): the point contact of\n"
        "`run` (docs/POINT_CONTACT.md), the scene of the same [contact] keys solved on its\n"
        "own cells (no --grid, no --load); --surface and --fluid are optional (smooth, dry;\n"
        "a rough or lubricated ellipsoid is refused as in a scene). The answer\n"
        "adds the film's minimum and its position, the contact area and extents, and the\n"
        "peak pressure, as run's curve.csv.\n"
        "Exit status: 0 converged, 7 did not converge (iterations and residual on\n"
        "stderr), 8 converged but above its error target or without an estimate,\n"
        "2 bad option or name, 3 unknown material, 5 database error.\n",
        out);
}

/* The options of `friction`: -1 to go on, else the exit code (0 after
 * --help). */
static int friction_args(int argc, char **argv, conditions *c, const char **compound,
                         double *speed) {
  common_rules r;
  vl_cli_option opts[N_COMMON + 2];
  size_t n = common_options(c, &r, opts);
  opts[n++] = (vl_cli_option){.name = "--compound",
                              .kind = VL_CLI_TEXT,
                              .dest = compound,
                              .missing = UNKNOWN_OR_INCOMPLETE};
  opts[n++] =
      (vl_cli_option){.name = "--speed", .kind = VL_CLI_NUMBER, .dest = speed, .rule = &positive};
  vl_cli_parser p = {.cmd = "friction", .opts = opts, .n_opts = n};
  int rc = parse_command(&p, argc, argv, c, &r, friction_usage);
  if (rc >= 0) return rc;
  int have_speed = vl_cli_find(&p, "--speed")->given > 0;
  if (!need("friction", "--compound", *compound) || !material_options("friction", c) ||
      !need("friction", "--speed", have_speed ? "" : NULL))
    return 2;
  if (!valid_name("friction", "--compound", *compound) || !geometry_options("friction", c))
    return 2;
  return -1;
}

/* The point as JSON; with --temperature the temperature, shift and
 * viscosity come first in the same object. */
static void friction_json(const conditions *c, const vl_query_result *r) {
  vl_curve_meta meta = {r->eta_pa_s,      0.0,
                        r->a0_m,          r->flow_factors,
                        r->film_cutoff_m, r->has_pair ? r->shear_law_text : NULL};
  vl_json w;
  vl_json_init(&w, stdout, 10);
  vl_json_object_begin(&w, VL_JSON_INLINE);
  if (c->q.at_temperature) {
    vl_json_key_number(&w, "temperature_c", c->q.temperature_c);
    vl_json_key_number(&w, "a_T", r->shift_factor);
    vl_json_key_number(&w, "eta_pa_s", r->eta_pa_s);
  }
  vl_point_json_members(&w, &r->point, &meta);
  vl_json_end(&w);
  fputc('\n', stdout);
}

/* What the regime label means, where it is printed (results.h: the load
 * share and the film ratio together; the share alone when smooth). */
static void regime_meaning(char *buf, size_t size, int regime, bool rough) {
  double lo = 100.0 * VL_REGIME_LOAD_BOUNDARY, hi = 100.0 * VL_REGIME_LOAD_HYDRODYNAMIC;
  if (regime == VL_REGIME_HYDRODYNAMIC)
    snprintf(buf, size,
             rough ? "the fluid carries over %g %% of the load and u_min >= %g h_rms"
                   : "the fluid carries over %g %% of the load",
             hi, VL_REGIME_FILM_FULL);
  else if (regime == VL_REGIME_BOUNDARY)
    snprintf(buf, size,
             rough ? "the fluid carries under %g %% of the load and u_min < %g h_rms"
                   : "the fluid carries under %g %% of the load",
             lo, VL_REGIME_FILM_FULL);
  else if (regime == VL_REGIME_MIXED)
    snprintf(buf, size, "neither boundary nor hydrodynamic%s",
             rough ? ": load share and film ratio disagree or lie between" : "");
  else
    snprintf(buf, size, "no fluid");
}

/* The first line of a point contact's answer: its materials (a smooth
 * ball names no surface, a dry one no fluid), speed and body. */
static void point_heading(const conditions *c, const char *compound, double speed, double eta) {
  const vl_query *q = &c->q;
  printf("%s", compound);
  if (q->surface) printf(" on %s", q->surface);
  if (q->fluid) printf(" in %s", q->fluid);
  printf(" at v0 = %g m/s", speed);
  if (q->fluid) printf(" (v0 eta = %g Pa m)", speed * eta);
  if (q->geometry == VL_GEOMETRY_BALL)
    printf(", ball R = %g m, W = %g N\n", q->radius_m, q->load_n);
  else
    printf(", ellipsoid Rx = %g m, Ry = %g m, W = %g N\n", q->radius_m, q->radius_y_m, q->load_n);
}

/* A point contact's own lines (what run's curve reports for it: the film's
 * minimum and where, the contact's area and extents, the peak pressure). */
static void point_lines(const vl_query_result *r) {
  const vl_point *pt = &r->point;
  const vl_ball_result *b = &pt->ball;
  if (r->eta_pa_s > 0.0)
    printf("  u_min   = %.4g m at x = %.4g m, y = %.4g m; u_central = %.4g m\n", pt->u_min_m,
           pt->x_min_film_m, b->y_min_film_m, pt->u_central_m);
  printf("  contact area = %.4g m2 (length %.4g m, breadth %.4g m); the fluid carries %.1f %% of "
         "the load\n",
         b->contact_area_m2, b->contact_length_m, b->contact_breadth_m,
         100.0 * pt->fluid_load_fraction);
  printf("  peak pressure %.4g Pa at x = %.4g m, y = %.4g m; a0 = %.4g m (relaxed Hertz)\n",
         pt->peak_pressure_pa, pt->x_peak_m, b->y_peak_m, r->a0_m);
  printf("  %ld Newton iteration%s, residual %.2g; cells planned per point (%.3g per a0)\n",
         pt->iterations, vl_cli_plural((size_t)pt->iterations), pt->residual, b->cells_per_a0);
}

static void friction_text(const conditions *c, const char *compound, double speed,
                          const vl_query_result *r) {
  const vl_point *pt = &r->point;
  double eta = r->eta_pa_s, hrms = r->hrms_m;
  bool line = c->q.geometry == VL_GEOMETRY_CYLINDER;
  if (line)
    printf("%s on %s in %s at v0 = %g m/s (v0 eta = %g Pa m), R = %g m, fN = %g N/m\n", compound,
           c->q.surface, c->q.fluid, speed, speed * eta, c->q.radius_m, c->q.load_n_per_m);
  else
    point_heading(c, compound, speed, eta);
  if (r->flow_factors) {
    printf("  flow factors: %s", r->flow_factors);
    if (r->film_cutoff_m > 0.0) printf(" (film cut-off %g m)", r->film_cutoff_m);
    putchar('\n');
  }
  if (r->has_pair) printf("  sigma_s: %s\n", r->shear_law_text);
  if (c->q.at_temperature)
    printf("  at %g C: compound times x a_T = %.4g (WLF), fluid viscosity %.4g Pa s\n",
           c->q.temperature_c, r->shift_factor, eta);
  printf("  mu      = %.5g\n  mu_Rc   = %.5g   (hysteresis under the solid contact)\n"
         "  mu_Rf   = %.5g   (asymmetry of the fluid pressure)\n"
         "  mu_Sc   = %.5g   (shear in the real contact area)\n"
         "  mu_Sf   = %.5g   (fluid shear)\n",
         pt->mu, pt->mu_Rc + 0.0, pt->mu_Rf + 0.0, pt->mu_Sc + 0.0, pt->mu_Sf + 0.0);
  if (!line) point_lines(r);
  char how[96] = "a direct solve";
  if (r->points_solved > 1)
    snprintf(how, sizeof how, "continuation from the boundary regime over %zu points",
             r->points_solved);
  char meaning[128];
  regime_meaning(meaning, sizeof meaning, pt->regime, hrms > 0);
  if (line)
    printf("  u_min   = %.4g m (%.3g h_rms)\n  solid contact carries %.1f %% of the load; "
           "regime: %s (%s)\n  Q = %.3g; %ld Newton iteration%s, residual %.2g (%s)\n",
           pt->u_min_m, hrms > 0 ? pt->u_min_m / hrms : 0.0,
           100.0 * (1.0 - pt->fluid_load_fraction), vl_regime_name(pt->regime), meaning, pt->Q,
           pt->iterations, vl_cli_plural((size_t)pt->iterations), pt->residual, how);
  if (isfinite(pt->error_estimate))
    printf("  error estimate of mu: %.2g %% (against the point on %s)%s\n",
           100.0 * pt->error_estimate, line ? "cells 3x as wide" : "coarser cells",
           pt->accuracy == VL_ACCURACY_ABOVE_TARGET ? ": ABOVE the target, not to be trusted to it"
                                                    : "");
  else
    printf("  error estimate of mu: none (the point on coarser cells did not converge)\n");
}

/* The conditions of both commands before any option: the library's
 * defaults, the global --quiet. */
static conditions conditions_default(const vl_cli_globals *g) {
  conditions c = {.quiet = g->quiet};
  vl_query_defaults(&c.q);
  return c;
}

int vl_cli_friction(const vl_cli_globals *g, int argc, char **argv) {
  conditions c = conditions_default(g);
  const char *compound = NULL;
  double speed = 0.0;
  int rc = friction_args(argc, argv, &c, &compound, &speed);
  if (rc >= 0) return rc;
  vl_scene sc; /* checks the options go together before the database is opened */
  if (!make_scene("friction", &c, compound, &sc)) return 2;
  vl_query q = query_for(&c, compound);
  vl_error err = {{0}};
  vl_db *db = NULL;
  double eta = 0.0;
  vl_query_result r;
  vl_status st = vl_db_open(g->db_path, &db, &err);
  if (st == VL_OK) st = compound_at(db, &c, compound, &err);
  if (st == VL_OK) st = fluid_eta(db, &c, &eta, &err);
  if (st == VL_OK) st = vl_query_friction(db, &q, speed, &r, &err);
  rc = 0;
  if (st != VL_OK) {
    fprintf(stderr, "viscolube friction: %s\n", err.msg[0] ? err.msg : vl_status_name(st));
    rc = vl_status_exit_code(st);
    goto done;
  }
  if (c.json)
    friction_json(&c, &r);
  else if (r.point.converged)
    friction_text(&c, compound, speed, &r);
  fflush(stdout);
  if (!c.json && !c.quiet) vl_cli_print_warnings(stderr, NULL, 1, &r.point);
  if (!r.point.converged) {
    fprintf(stderr,
            "viscolube friction: the solve did not converge at v0 = %g m/s "
            "(%ld iteration%s, residual %.3g)\n",
            speed, r.point.iterations, vl_cli_plural((size_t)r.point.iterations), r.point.residual);
    rc = vl_status_exit_code(VL_ENOCONV);
  } else if (vl_cli_print_unreliable(stderr, "friction", NULL, 1, &r.point)) {
    rc = VL_CLI_EXIT_UNRELIABLE;
  }
done:
  vl_db_close(db);
  return rc;
}

static void compare_usage(FILE *out) {
  fputs("usage: viscolube compare --compounds A,B[,...] --surface S --fluid F\n"
        "                         [--from V0ETA --to V0ETA | --from-speed M_S --to-speed M_S]\n"
        "                         [--points N] [--out DIR]\n"
        "                         [--axis speed|v0eta] [--load N_PER_M] [--radius M]\n"
        "                         [--sigma-s PA] [--flow-factors persson-emt|patir-cheng|smooth]\n"
        "                         [--film-cutoff M] [--grid N] [--json] [--plot]\n"
        "                         [--temperature C] [--target-error E] [--quiet]\n"
        "                         [--geometry ball|ellipsoid --load-n N --radius M|--radii RX,RY]\n"
        "\n"
        "Stribeck curves of several compounds on one surface in one fluid, side by side:\n"
        "mu and u_min/h_rms per compound. The sweep runs over v0*eta from --from to --to\n"
        "(Pa m, whatever the axis: in water, 1e-12 .. 0.1 Pa m is 1 nm/s .. 100 m/s);\n"
        "given either way round, it runs upward, from the boundary regime.\n"
        "--from-speed/--to-speed give the range in m/s instead (the fluid's viscosity\n"
        "then does not matter, at --temperature or not).\n"
        "--axis: the first column of the table and of compare.csv, the JSON's axis and the\n"
        "figures' x axis: speed (v0_m_s, m/s; the default) or v0eta (v0_eta_pa_m, Pa m).\n"
        "Writes DIR/compare.csv (one row per speed; the axis, then mu, mu_Rc, mu_Rf, mu_Sc,\n"
        "mu_Sf, u_min_over_hrms, converged per compound), DIR/<compound>/curve.csv (every\n"
        "column, both v0_m_s and v0_eta_pa_m) and, last, DIR/run.json: the command, the\n"
        "options, the materials with their database fingerprints, the numerics, the\n"
        "program version, start and end times, the points converged and the files written.\n"
        "Files of an earlier run listed in its run.json and not rewritten are removed; other\n"
        "files in DIR are left alone, named in a warning. Every file is written whole (a\n"
        "temporary renamed into place) before the table is printed. DIR defaults to\n"
        "out/compare.\n"
        "With --plot also DIR/compare-mu.{png,svg} and DIR/compare-umin.{png,svg}: the\n"
        "compounds' curves on one axis, titled with the compounds and the conditions.\n"
        "--temperature C: every compound and the fluid at C, as for `viscolube friction`\n"
        "(v0*eta then uses the fluid's viscosity at C); compare.csv gets the columns\n"
        "temperature_c and eta_pa_s, the JSON the keys of the same names.\n"
        "DIR and DIR/<compound> are checked (created, writable, not a file) before\n"
        "anything is computed.\n"
        "After the table, on stderr: one line per kind of model-validity warning and\n"
        "compound with the points it applies to (with --json only in the JSON), and the\n"
        "points that did not converge (speed, iterations, residual), then those above their\n"
        "error target (--target-error, default 0.01) or without an estimate, marked '!' in\n"
        "the table, `accuracy` in curve.csv and hollow squares in the figures. --quiet\n"
        "leaves out the warnings and the progress lines.\n"
        "Exit status: 0 every point converged, 7 some did not (written with converged = 0),\n"
        "8 all converged but some are above their error target or have no estimate,\n"
        "2 bad option or name, 3 unknown material, 5 database error, 6 file error (a file\n"
        "that did not fit is named; the others are kept) or standard output lost.\n"
        "--geometry ball or ellipsoid (as for `viscolube friction`): a point contact's\n"
        "curves; the range must be given (--from-speed/--to-speed, or --from/--to with a\n"
        "fluid); compare.csv then has per compound u_min_m, x_min_film_m, y_min_film_m and\n"
        "contact_area_m2 (u_min_over_hrms only with a surface), the table u_min_m and\n"
        "area_m2, curve.csv the columns of run's.\n"
        "Defaults: --from 1e-12 --to 0.1 --points 45 --axis speed, and those of\n"
        "`viscolube friction`.\n",
        out);
}

/* What `compare` was asked for. */
typedef struct {
  conditions c;
  char list[MAX_COMPOUNDS * 128]; /* --compounds, cut by names[] */
  char *names[MAX_COMPOUNDS];
  size_t nc;
  double from, to, points;
  double from_speed, to_speed; /* --from-speed/--to-speed (m/s); NAN: the range is in v0 eta */
  int from_given;              /* --from or --to given */
  const char *out_dir;
  int axis_v0eta; /* --axis v0eta; else speed (one fluid: the speed reads directly) */
} compare_args;

/* The curves of the compounds, side by side: compound k's point i is
 * pts[k * n + i]. */
typedef struct {
  size_t n;
  vl_point *pts;
  double *hrms; /* of each compound's surface (1 when smooth) */
  double eta;   /* Pa s, the fluid's (at --temperature) */
  size_t failed;
  size_t unreliable; /* converged, but above their error target or without an estimate */
} compare_curves;

/* The options of `compare`: -1 to go on, else the exit code (0 after
 * --help). */
static int compare_parse(int argc, char **argv, compare_args *a) {
  static const char *const axes[] = {"speed", "v0eta", NULL};
  common_rules r;
  const char *compounds = NULL;
  enum { N_COMPARE = 9 }; /* the options below: room for each */
  vl_cli_option opts[N_COMMON + N_COMPARE];
  size_t n = common_options(&a->c, &r, opts);
  opts[n++] = (vl_cli_option){.name = "--plot", .kind = VL_CLI_FLAG, .dest = &a->c.plot};
  opts[n++] = (vl_cli_option){.name = "--compounds",
                              .kind = VL_CLI_TEXT,
                              .dest = &compounds,
                              .missing = UNKNOWN_OR_INCOMPLETE};
  opts[n++] = (vl_cli_option){
      .name = "--out", .kind = VL_CLI_TEXT, .dest = &a->out_dir, .missing = UNKNOWN_OR_INCOMPLETE};
  opts[n++] = (vl_cli_option){.name = "--axis",
                              .kind = VL_CLI_CHOICE,
                              .dest = &a->axis_v0eta,
                              .choices = axes,
                              .choice_bad = "option %s needs speed or v0eta (got '%s')"};
  opts[n++] =
      (vl_cli_option){.name = "--from", .kind = VL_CLI_NUMBER, .dest = &a->from, .rule = &positive};
  opts[n++] =
      (vl_cli_option){.name = "--to", .kind = VL_CLI_NUMBER, .dest = &a->to, .rule = &positive};
  opts[n++] = (vl_cli_option){
      .name = "--from-speed", .kind = VL_CLI_NUMBER, .dest = &a->from_speed, .rule = &positive};
  opts[n++] = (vl_cli_option){
      .name = "--to-speed", .kind = VL_CLI_NUMBER, .dest = &a->to_speed, .rule = &positive};
  opts[n++] = (vl_cli_option){
      .name = "--points", .kind = VL_CLI_NUMBER, .dest = &a->points, .rule = &positive};
  if (n > sizeof opts / sizeof *opts) abort(); /* N_COMPARE is short: a bug */
  vl_cli_parser p = {.cmd = "compare", .opts = opts, .n_opts = n};
  int rc = parse_command(&p, argc, argv, &a->c, &r, compare_usage);
  if (rc < 0 && compounds) snprintf(a->list, sizeof a->list, "%s", compounds);
  a->from_given = vl_cli_find(&p, "--from")->given || vl_cli_find(&p, "--to")->given;
  return rc;
}

/* Cuts --compounds into names and checks that everything needed was given. */
static int compare_check(compare_args *a) {
  char *save = NULL;
  for (char *t = strtok_r(a->list, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
    if (a->nc == MAX_COMPOUNDS) {
      fprintf(stderr, "viscolube compare: at most %d compounds\n", MAX_COMPOUNDS);
      return 2;
    }
    a->names[a->nc++] = t;
  }
  if (!need("compare", "--compounds", a->nc ? "" : NULL) || !material_options("compare", &a->c))
    return 2;
  for (size_t k = 0; k < a->nc; k++)
    if (!valid_name("compare", "--compounds", a->names[k])) return 2;
  if (!geometry_options("compare", &a->c)) return 2;
  bool speeds = !isnan(a->from_speed) || !isnan(a->to_speed);
  if (speeds && (isnan(a->from_speed) || isnan(a->to_speed))) {
    fprintf(stderr, "viscolube compare: --from-speed and --to-speed go together\n");
    return 2;
  }
  if (speeds && a->from_given) {
    fprintf(stderr, "viscolube compare: give the range in m/s (--from-speed, --to-speed) or in "
                    "v0 eta (--from, --to), not both\n");
    return 2;
  }
  if (!a->c.q.fluid && (a->from_given || a->axis_v0eta)) {
    fprintf(stderr,
            "viscolube compare: %s: a dry contact (no --fluid) has no v0 eta: give the "
            "range in m/s (--from-speed, --to-speed) on the speed axis\n",
            a->from_given ? "--from/--to" : "--axis v0eta");
    return 2;
  }
  if (a->c.geometry != VL_GEOMETRY_CYLINDER && !speeds && !a->from_given) {
    fprintf(stderr,
            "viscolube compare: --geometry %s needs its range: --from-speed and --to-speed (m/s), "
            "or --from and --to (v0 eta, Pa m); the default 1e-12 .. 0.1 Pa m is a line "
            "contact's (a point contact's point costs seconds)\n",
            vl_geometry_name(a->c.geometry));
    return 2;
  }
  if (speeds) a->from = a->from_speed, a->to = a->to_speed; /* in m/s from here on */
  if (a->to < a->from) { /* the same speeds, swept upward (the scene's rule) */
    double high = a->from;
    a->from = a->to, a->to = high;
  }
  if (!(a->to > a->from) || a->points != floor(a->points) || a->points < 2 || a->points > 10000) {
    fprintf(stderr, "viscolube compare: need --from and --to apart and a whole --points in [2, "
                    "10000]\n");
    return 2;
  }
  return -1;
}

/* Before anything is computed or written: every compound exists and, with
 * --temperature, can be taken there (WLF constants, fluid law); the output
 * folders exist and can be written in. */
static vl_status compare_prepare(vl_db *db, const compare_args *a, compare_curves *cv,
                                 vl_error *err) {
  vl_status st = VL_OK;
  for (size_t k = 0; st == VL_OK && k < a->nc; k++) {
    vl_prony probe;
    st = vl_db_compound_get(db, a->names[k], &probe, err);
  }
  for (size_t k = 0; st == VL_OK && k < a->nc; k++)
    st = compound_at(db, &a->c, a->names[k], err);
  if (st == VL_OK && a->c.q.at_temperature) st = fluid_eta(db, &a->c, &cv->eta, err);
  if (st == VL_OK) st = vl_cli_check_out_dir("--out", a->out_dir, err);
  for (size_t k = 0; st == VL_OK && k < a->nc; k++) {
    char dir[4200];
    snprintf(dir, sizeof dir, "%s/%s", a->out_dir, a->names[k]);
    st = vl_cli_check_out_dir("--out", dir, err);
  }
  return st;
}

/* The numerics of compound's sweep into the manifest: a line contact's
 * cells, or (a point contact: planned per point) the words `run` records. */
static void compare_numerics(vl_manifest *man, const char *compound, const vl_scene *sc,
                             vl_simulation *sim) {
  if (sc->geometry == VL_GEOMETRY_CYLINDER) {
    const vl_contact *contact = vl_simulation_contact(sim);
    vl_contact_numerics_used nu;
    vl_contact_numerics_of(contact, &nu);
    vl_manifest_add_numerics(man, compound, &nu, vl_contact_a0(contact), vl_contact_p0(contact));
    return;
  }
  char key[160], numerics[200];
  snprintf(key, sizeof key, "numerics_%s", compound);
  snprintf(numerics, sizeof numerics,
           "point contact: cells planned per point (%d across the contact's shorter semi-axis), "
           "target error %g, tolerance %g, a0 %.6g m, p0 %.6g Pa",
           VL_BALL_CELLS_PER_A0, sc->target_error, sc->tolerance, vl_simulation_a0(sim),
           vl_simulation_p0(sim));
  vl_manifest_add_option(man, key, numerics);
}

/* Runs compound k's sweep into cv and writes DIR/<compound>/curve.csv.
 * Returns 2 after the message when the scene cannot be made, else -1 with
 * *st the status. */
static int compare_one(vl_db *db, const compare_args *a, size_t k, compare_curves *cv,
                       vl_manifest *man, vl_status *st, vl_error *err) {
  vl_scene sc;
  if (!make_scene("compare", &a->c, a->names[k], &sc)) return 2;
  sc.from = a->from, sc.to = a->to, sc.points = cv->n;
  if (!isnan(a->from_speed)) sc.quantity = VL_SWEEP_V0; /* the range in m/s */
  vl_simulation *sim = NULL;
  *st = vl_simulation_create(&sc, db, &sim, err);
  if (*st != VL_OK) return -1;
  cv->eta = vl_simulation_eta(sim);
  const vl_psd *psd = vl_simulation_psd(sim);
  cv->hrms[k] = psd ? psd->hrms_m : 1.0;
  compare_numerics(man, a->names[k], &sc, sim);
  vl_sweep_stats stats;
  if (!a->c.json && !a->c.quiet) fprintf(stderr, "compare: %s ...\n", a->names[k]);
  vl_point *pts = cv->pts + k * cv->n;
  *st = vl_simulation_run(sim, pts, NULL, NULL, &stats, err);
  cv->failed += stats.failed;
  if (*st == VL_OK) vl_manifest_add_counts(man, stats.converged, stats.failed);
  const char *law = vl_simulation_shear_law_text(sim);
  if (*st == VL_OK && law) { /* a stored pair's law gave sigma_s: say which */
    char key[128];
    snprintf(key, sizeof key, "sigma_s_%s", a->names[k]);
    vl_manifest_add_text(man, key, law);
    if (!a->c.json && !a->c.quiet) fprintf(stderr, "compare: %s: sigma_s: %s\n", a->names[k], law);
  }
  char dir[4200], path[4300];
  snprintf(dir, sizeof dir, "%s/%s", a->out_dir, a->names[k]);
  if (*st == VL_OK && vl_cli_make_dirs(dir) != 0) {
    vl_error_set(err, "%s: cannot create: %s", dir, strerror(errno));
    *st = VL_EIO;
  }
  if (*st == VL_OK) {
    vl_curve_meta meta = {cv->eta, vl_simulation_tau(sim),           vl_simulation_a0(sim), NULL,
                          0.0,     vl_simulation_shear_law_text(sim)};
    meta.flow_factors = vl_simulation_flow_factors(sim, &meta.film_cutoff_m);
    snprintf(path, sizeof path, "%s/curve.csv", dir);
    /* a file that does not fit is noted and the others still written */
    vl_error werr = {{0}};
    vl_cli_manifest_file(man, path, vl_write_curve_csv(path, cv->n, pts, &meta, &werr), &werr);
  }
  vl_simulation_free(sim);
  return -1;
}

/* The axis of the table, compare.csv, the JSON and the figures: v0 (m/s)
 * or v0*eta (Pa m), with the name of its column. */
static double axis_value(const compare_args *a, const compare_curves *cv, size_t i) {
  return a->axis_v0eta ? cv->pts[i].v0_m_s * cv->eta : cv->pts[i].v0_m_s;
}
static const char *axis_column(const compare_args *a) {
  return a->axis_v0eta ? "v0_eta_pa_m" : "v0_m_s";
}

/* DIR/compare.csv: one row per speed, the compounds side by side. */
static vl_status write_compare_csv(const char *path, const compare_args *a,
                                   const compare_curves *cv, vl_error *err) {
  vl_atomic_file af;
  if (vl_atomic_file_open(&af, path, err) != VL_OK) return VL_EIO;
  FILE *f = af.f;
  double cut;
  const char *model = model_of(&a->c, &cut);
  if (model) { /* as curve.csv: no line without flow factors */
    fprintf(f, "# flow_factors = %s", model);
    if (cut > 0.0) fprintf(f, ", film_cutoff_m = %.6g", cut);
    fputc('\n', f);
  }
  fputs(axis_column(a), f);
  bool point = a->c.geometry != VL_GEOMETRY_CYLINDER, rough = a->c.q.surface != NULL;
  for (size_t k = 0; k < a->nc; k++) {
    const char *m = a->names[k];
    fprintf(f, ",mu_%s,mu_Rc_%s,mu_Rf_%s,mu_Sc_%s,mu_Sf_%s", m, m, m, m, m);
    if (rough) fprintf(f, ",u_min_over_hrms_%s", m);
    if (point) /* what run's curve.csv says of a point contact's film and contact */
      fprintf(f, ",u_min_m_%s,x_min_film_m_%s,y_min_film_m_%s,contact_area_m2_%s", m, m, m, m);
    fprintf(f, ",converged_%s", m);
  }
  /* with --temperature the rows say at which temperature and viscosity
   * (appended: the columns of a reference-temperature run are unchanged) */
  if (a->c.q.at_temperature) fputs(",temperature_c,eta_pa_s", f);
  fputc('\n', f);
  for (size_t i = 0; i < cv->n; i++) {
    fprintf(f, "%.10g", axis_value(a, cv, i));
    for (size_t k = 0; k < a->nc; k++) {
      const vl_point *p = &cv->pts[k * cv->n + i];
      if (!p->converged) {
        fputs(",,,,,", f);
        if (rough) fputc(',', f);
        if (point) fputs(",,,,", f);
        fputs(",0", f);
        continue;
      }
      fprintf(f, ",%.10g,%.10g,%.10g,%.10g,%.10g", p->mu, p->mu_Rc + 0.0, p->mu_Rf + 0.0,
              p->mu_Sc + 0.0, p->mu_Sf + 0.0);
      if (rough) fprintf(f, ",%.10g", p->u_min_m / cv->hrms[k]);
      if (point)
        fprintf(f, ",%.10g,%.10g,%.10g,%.10g", p->u_min_m, p->x_min_film_m + 0.0,
                p->ball.y_min_film_m + 0.0, p->ball.contact_area_m2 + 0.0);
      fputs(",1", f);
    }
    if (a->c.q.at_temperature) fprintf(f, ",%.10g,%.10g", a->c.q.temperature_c, cv->eta);
    fputc('\n', f);
  }
  return vl_atomic_file_commit(&af, err);
}

/* The table: mu and u_min/h_rms of each compound at every v0*eta. */
static void compare_table(const compare_args *a, const compare_curves *cv) {
  double cut;
  const char *model = model_of(&a->c, &cut);
  if (model) printf("flow factors: %s", model);
  if (cut > 0.0) printf(" (film cut-off %g m)", cut);
  if (model) putchar('\n');
  if (a->c.q.at_temperature)
    printf("at %g C: fluid viscosity %.4g Pa s, compounds shifted by WLF\n", a->c.q.temperature_c,
           cv->eta);
  if (cv->n && !(cv->eta > 0.0)) /* dry: no v0 eta */
    printf("speeds: %.4g .. %.4g m/s (dry)\n", cv->pts[0].v0_m_s, cv->pts[cv->n - 1].v0_m_s);
  else if (cv->n) /* the range in both units, whichever was given */
    printf("speeds: %.4g .. %.4g m/s (v0 eta %.4g .. %.4g Pa m at eta %.4g Pa s)\n",
           cv->pts[0].v0_m_s, cv->pts[cv->n - 1].v0_m_s, cv->pts[0].v0_m_s * cv->eta,
           cv->pts[cv->n - 1].v0_m_s * cv->eta, cv->eta);
  /* a point contact: its film in metres (smooth) and its contact area */
  bool point = a->c.geometry != VL_GEOMETRY_CYLINDER, rough = a->c.q.surface != NULL;
  printf("%12s", axis_column(a));
  for (size_t k = 0; k < a->nc; k++) {
    printf(" %14.14s %14s", a->names[k], rough ? "u_min/h_rms" : "u_min_m");
    if (point) printf(" %14s", "area_m2");
  }
  printf("\n");
  for (size_t i = 0; i < cv->n; i++) {
    printf("%12.4g", axis_value(a, cv, i));
    for (size_t k = 0; k < a->nc; k++) {
      const vl_point *p = &cv->pts[k * cv->n + i];
      if (p->converged) /* '!': not known to its error target */
        printf(" %13.5g%c %14.4g", p->mu, vl_point_unreliable(p) ? '!' : ' ',
               p->u_min_m / (rough ? cv->hrms[k] : 1.0));
      else
        printf(" %14s %14s", "-", "-");
      if (point && p->converged)
        printf(" %14.4g", p->ball.contact_area_m2);
      else if (point)
        printf(" %14s", "-");
    }
    printf("\n");
  }
}

/* One object: [temperature_c, eta_pa_s,] the axis (v0_m_s or v0_eta_pa_m),
 * and each compound's curve under its name. */
static void compare_json(const compare_args *a, const compare_curves *cv) {
  vl_json w;
  vl_json_init(&w, stdout, 10);
  vl_json_object_begin(&w, VL_JSON_INLINE);
  if (a->c.q.at_temperature) {
    vl_json_key_number(&w, "temperature_c", a->c.q.temperature_c);
    vl_json_key_number(&w, "eta_pa_s", cv->eta);
  }
  vl_json_key(&w, axis_column(a));
  vl_json_array_begin(&w, VL_JSON_INLINE);
  for (size_t i = 0; i < cv->n; i++)
    vl_json_number_digits(&w, axis_value(a, cv, i), 6);
  vl_json_end(&w);
  for (size_t k = 0; k < a->nc; k++) {
    vl_curve_meta meta = {cv->eta, 0.0, 0.0, NULL, 0.0, NULL};
    meta.flow_factors = model_of(&a->c, &meta.film_cutoff_m);
    vl_json_key(&w, a->names[k]);
    vl_curve_json(&w, cv->n, cv->pts + k * cv->n, &meta);
  }
  vl_json_end(&w);
  fputc('\n', stdout);
}

/* A point contact's subtitle: its materials (those given), body and load. */
static int point_subtitle(const compare_args *a, const char *eta, const char *radius, char *buf,
                          size_t size) {
  const vl_query *q = &a->c.q;
  char load[48], ry[48], materials[600] = "";
  vl_plot_format_value(load, sizeof load, q->load_n);
  vl_plot_format_value(ry, sizeof ry, q->radius_y_m * 1e3);
  int m = 0;
  if (q->surface) m = snprintf(materials, sizeof materials, "on %s · ", q->surface);
  if (q->fluid && m >= 0 && (size_t)m < sizeof materials)
    snprintf(materials + m, sizeof materials - (size_t)m, "in %s (η = %s Pa s) · ", q->fluid, eta);
  if (q->geometry == VL_GEOMETRY_BALL)
    return snprintf(buf, size, "%sball R = %s mm · W = %s N", materials, radius, load);
  return snprintf(buf, size, "%sellipsoid Rx = %s mm, Ry = %s mm · W = %s N", materials, radius, ry,
                  load);
}

/* The conditions of the figures' subtitle: surface, fluid, load, radius,
 * flow-factor model (and temperature). */
static void compare_subtitle(const compare_args *a, const compare_curves *cv, char *buf,
                             size_t size) {
  char eta[48], load[48], radius[48], cut_text[64] = "";
  vl_plot_format_value(eta, sizeof eta, cv->eta);
  vl_plot_format_value(radius, sizeof radius, a->c.q.radius_m * 1e3);
  double cut;
  const char *model = model_of(&a->c, &cut);
  if (cut > 0.0) snprintf(cut_text, sizeof cut_text, " (cut-off %g nm)", cut * 1e9);
  int n;
  if (a->c.geometry != VL_GEOMETRY_CYLINDER) {
    n = point_subtitle(a, eta, radius, buf, size);
  } else {
    vl_plot_format_value(load, sizeof load, a->c.q.load_n_per_m);
    n = snprintf(buf, size, "on %s in %s (η = %s Pa s) · fN = %s N/m · R = %s mm · %s%s",
                 a->c.q.surface, a->c.q.fluid, eta, load, radius, model, cut_text);
  }
  if (a->c.q.at_temperature && n >= 0 && (size_t)n < size)
    snprintf(buf + n, size - (size_t)n, " · %g °C", a->c.q.temperature_c);
}

/* --plot: DIR/compare-mu and DIR/compare-umin, each recorded in man
 * (written, or not written with the reason). VL_OK unless PLplot failed
 * otherwise than on a file. */
static vl_status compare_plots(const compare_args *a, const compare_curves *cv, vl_manifest *man,
                               vl_error *err) {
  vl_plot_curve curves[MAX_COMPOUNDS];
  for (size_t k = 0; k < a->nc; k++)
    curves[k] = (vl_plot_curve){
        a->names[k], cv->n, cv->pts + k * cv->n, {cv->eta, 0.0, 0.0, NULL, 0.0, NULL}, cv->hrms[k]};
  char names[MAX_COMPOUNDS * 80], title[MAX_COMPOUNDS * 80 + 64], subtitle[1024];
  int len = 0;
  names[0] = '\0';
  for (size_t k = 0; k < a->nc && len >= 0 && (size_t)len < sizeof names; k++)
    len += snprintf(names + len, sizeof names - (size_t)len, "%s%s", k ? " vs " : "", a->names[k]);
  compare_subtitle(a, cv, subtitle, sizeof subtitle);
  vl_plot_options opt;
  vl_plot_options_defaults(&opt);
  opt.mark_half_load = true;
  opt.title = title;
  opt.subtitle = subtitle;
  vl_sweep_quantity x = a->axis_v0eta ? VL_SWEEP_V0_ETA : VL_SWEEP_V0;
  static const struct {
    const char *name, *kind;
    vl_plot_y y;
  } figs[] = {{"compare-mu", "Friction coefficient", VL_PLOT_Y_MU},
              {"compare-umin", "Minimum separation", VL_PLOT_Y_U_MIN}};
  for (size_t k = 0; k < 2; k++) {
    char stem[4300];
    snprintf(stem, sizeof stem, "%s/%s", a->out_dir, figs[k].name);
    /* what it shows, then of what: "Friction coefficient — sbr-unfilled vs sbr-filled" */
    snprintf(title, sizeof title, "%s — %s", figs[k].kind, names);
    vl_status st = vl_plot_compare(stem, a->nc, curves, x, figs[k].y, &opt, NULL, err);
    vl_cli_manifest_figure(man, stem, st, err);
    if (st != VL_OK && st != VL_EIO) return st;
  }
  return VL_OK;
}

/* The run's record: the options (defaults resolved) and the materials. */
static void compare_manifest(vl_manifest *m, vl_db *db, const compare_args *a) {
  char v[64], list[sizeof a->list + MAX_COMPOUNDS] = "";
  for (size_t k = 0; k < a->nc; k++) {
    snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k ? "," : "", a->names[k]);
    vl_cli_manifest_material(m, db, "compound", a->names[k]);
  }
  if (a->c.q.surface) vl_cli_manifest_material(m, db, "surface", a->c.q.surface);
  if (a->c.q.fluid) vl_cli_manifest_material(m, db, "fluid", a->c.q.fluid);
  vl_manifest_add_option(m, "compounds", list);
  if (a->c.q.surface) vl_manifest_add_option(m, "surface", a->c.q.surface);
  if (a->c.q.fluid) vl_manifest_add_option(m, "fluid", a->c.q.fluid);
  bool point = a->c.geometry != VL_GEOMETRY_CYLINDER;
  if (point) vl_manifest_add_option(m, "geometry", vl_geometry_name(a->c.geometry));
  const struct {
    const char *key;
    double value;
  } nums[] = {{isnan(a->from_speed) ? "from_v0_eta_pa_m" : "from_v0_m_s", a->from},
              {isnan(a->from_speed) ? "to_v0_eta_pa_m" : "to_v0_m_s", a->to},
              {"points", a->points},
              {point ? "load_n" : "load_n_per_m", point ? a->c.q.load_n : a->c.q.load_n_per_m},
              {"radius_m", a->c.q.radius_m},
              {"sigma_s_pa", a->c.q.sigma_s_pa},
              {"radius_y_m", a->c.q.radius_y_m}};
  size_t n_nums = sizeof nums / sizeof nums[0] - (a->c.geometry != VL_GEOMETRY_ELLIPSOID);
  for (size_t k = 0; k < n_nums; k++) {
    snprintf(v, sizeof v, "%.10g", nums[k].value);
    vl_manifest_add_option(m, nums[k].key, v);
  }
  double cut;
  const char *model = model_of(&a->c, &cut);
  if (model) vl_manifest_add_option(m, "flow_factors", model);
  if (cut > 0.0) snprintf(v, sizeof v, "%.6g", cut), vl_manifest_add_option(m, "film_cutoff_m", v);
  if (a->c.q.grid) snprintf(v, sizeof v, "%zu", a->c.q.grid), vl_manifest_add_option(m, "grid", v);
  if (a->c.q.at_temperature)
    snprintf(v, sizeof v, "%.10g", a->c.q.temperature_c),
        vl_manifest_add_option(m, "temperature_c", v);
  vl_manifest_add_option(m, "axis", a->axis_v0eta ? "v0eta" : "speed");
}

/* After the table, on stderr: each compound's warnings and failed points. */
static void compare_report(const compare_args *a, compare_curves *cv) {
  fflush(stdout); /* the lines follow the table in a shared log */
  for (size_t k = 0; k < a->nc; k++) {
    const vl_point *pts = cv->pts + k * cv->n;
    if (!a->c.json && !a->c.quiet) vl_cli_print_warnings(stderr, a->names[k], cv->n, pts);
    char where[4400];
    snprintf(where, sizeof where, "written with converged = 0 in %s/%s/curve.csv", a->out_dir,
             a->names[k]);
    vl_cli_print_failures(stderr, "compare", a->names[k], cv->n, pts, where);
    cv->unreliable += vl_cli_print_unreliable(stderr, "compare", a->names[k], cv->n, pts);
  }
}

/* The sweep of every compound (DIR/<compound>/curve.csv), DIR/compare.csv
 * and the figures, each file recorded in man. *rc: 2 after the message
 * when a compound's scene cannot be made. */
static vl_status compare_files(vl_db *db, const compare_args *a, compare_curves *cv,
                               vl_manifest *man, int *rc, vl_error *err) {
  vl_status st = VL_OK;
  for (size_t k = 0; st == VL_OK && k < a->nc; k++) {
    int r = compare_one(db, a, k, cv, man, &st, err);
    if (r >= 0) {
      *rc = r;
      return VL_OK;
    }
  }
  if (st != VL_OK) return st;
  char path[4300];
  snprintf(path, sizeof path, "%s/compare.csv", a->out_dir);
  vl_error werr = {{0}};
  vl_cli_manifest_file(man, path, write_compare_csv(path, a, cv, &werr), &werr);
  /* every file before the table: a reader of stdout that goes away
   * (`| head`) cannot cut them short */
  return a->c.plot ? compare_plots(a, cv, man, err) : VL_OK;
}

/* On stdout the table (or JSON) and the files written; then on stderr the
 * warnings and failures. */
static void compare_print(const compare_args *a, compare_curves *cv) {
  if (a->c.json) {
    compare_json(a, cv);
  } else {
    compare_table(a, cv);
    printf("wrote %s/compare.csv and %s/<compound>/curve.csv%s, %s/%s\n", a->out_dir, a->out_dir,
           a->c.plot ? " and compare-mu/compare-umin figures" : "", a->out_dir, VL_MANIFEST_NAME);
  }
  compare_report(a, cv);
}

int vl_cli_compare(const vl_cli_globals *g, int argc, char **argv) {
  compare_args a = {.c = conditions_default(g),
                    .from = VL_QUERY_FROM_PA_M,
                    .to = VL_QUERY_TO_PA_M,
                    .from_speed = NAN,
                    .to_speed = NAN,
                    .points = VL_QUERY_POINTS,
                    .out_dir = "out/compare"};
  int rc = compare_parse(argc, argv, &a);
  if (rc < 0) rc = compare_check(&a);
  if (rc >= 0) return rc;
  vl_error err = {{0}};
  vl_db *db = NULL;
  vl_manifest *man = NULL;
  vl_status st = vl_db_open(g->db_path, &db, &err);
  compare_curves cv = {.n = (size_t)a.points};
  cv.pts = calloc(cv.n * a.nc, sizeof *cv.pts);
  cv.hrms = calloc(a.nc, sizeof *cv.hrms);
  rc = 0;
  if (!cv.pts || !cv.hrms) st = VL_ENOMEM, vl_error_set(&err, "out of memory");
  if (st == VL_OK) st = compare_prepare(db, &a, &cv, &err);
  if (st == VL_OK && !(man = vl_cli_manifest_begin(g, "compare", a.out_dir, &rc))) goto done;
  if (st == VL_OK) {
    compare_manifest(man, db, &a);
    st = compare_files(db, &a, &cv, man, &rc, &err);
  }
  if (st != VL_OK || rc) goto done;
  rc = vl_cli_manifest_finish(man, "compare", a.c.quiet,
                              vl_cli_points_status(cv.failed, cv.unreliable));
  man = NULL;
  compare_print(&a, &cv);
done:
  if (st != VL_OK) {
    fprintf(stderr, "viscolube compare: %s\n", err.msg[0] ? err.msg : vl_status_name(st));
    rc = vl_status_exit_code(st);
  }
  vl_manifest_free(man); /* a failed run leaves no manifest: the folder is incomplete */
  free(cv.pts);
  free(cv.hrms);
  vl_db_close(db);
  return rc;
}
