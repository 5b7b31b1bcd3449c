/* A ball in a scene, end to end (docs/POINT_CONTACT.md section 7): the
 * [contact] keys of each geometry and the combinations refused naming the
 * key (file and line), what a point contact does not take yet, and `run`:
 * the curve with the point contact's columns (contact area, extents, the
 * minimum film's position), the 2-D fields, the JSON and the figures
 * (the Stribeck curve and the maps with the Hertz circle). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "viscolube.h"

/* A dry ball scene on the model rubber; contact and extra are [contact]
 * lines and more sections appended. */
static const char *ball_scene(const char *name, const char *contact, const char *extra) {
  char text[2048];
  snprintf(text, sizeof text,
           "[scene]\ntitle = ball test\n[materials]\ncompound = model-rubber\n"
           "[contact]\n%s\nsigma_s_pa = 0\n"
           "[sweep]\nquantity = deborah\nfrom = 0.1\nto = 10\npoints = 3\nfields_at = 1\n"
           "[numerics]\ntarget_error = 0.05\n" /* no refinement: for the time */
           "[effects]\nviscoelastic = on\nsolid_shear = off\n%s",
           contact, extra);
  return vl_test_scratch(name, text);
}

#define BALL "geometry = ball\nradius_m = 0.0095\nload_n = 3"

static void load_ok(const char *path, vl_scene *sc) {
  vl_error err;
  if (vl_scene_load(path, sc, &err) != VL_OK) fail_msg("%s", err.msg);
}

/* Each geometry's keys: a ball's radius across is its radius; an
 * ellipsoid's radii are Rx (along the sliding) and Ry. */
static void test_geometry_keys(void **state) {
  (void)state;
  vl_scene sc;
  load_ok(ball_scene("b.ini", BALL, ""), &sc);
  assert_int_equal(sc.geometry, VL_GEOMETRY_BALL);
  assert_true(sc.radius_m == 0.0095 && sc.radius_y_m == 0.0095 && sc.load_n == 3.0);
  assert_true(sc.auto_numerics);
  load_ok(ball_scene("e.ini", "geometry = ellipsoid\nradii_m = 0.01, 0.04\nload_n = 5", ""), &sc);
  assert_int_equal(sc.geometry, VL_GEOMETRY_ELLIPSOID);
  assert_true(sc.radius_m == 0.01 && sc.radius_y_m == 0.04 && sc.load_n == 5.0);
  load_ok(ball_scene("c.ini", "radius_m = 0.01\nload_n_per_m = 1000", ""), &sc);
  assert_int_equal(sc.geometry, VL_GEOMETRY_CYLINDER);
}

/* The message of a scene that must fail, with the needles in it. */
static void expect_refused(const char *contact, const char *extra, const char *n1, const char *n2) {
  vl_scene sc;
  vl_error err = {{0}};
  const char *path = ball_scene("bad.ini", contact, extra);
  assert_int_equal(vl_scene_load(path, &sc, &err), VL_EINPUT);
  if (!strstr(err.msg, n1) || (n2 && !strstr(err.msg, n2)))
    fail_msg("expected '%s' and '%s' in: %s", n1, n2 ? n2 : "", err.msg);
}

/* A wrong combination names the key, its line and what the geometry takes
 * instead; a missing key names the key. */
static void test_wrong_combinations(void **state) {
  (void)state;
  expect_refused("geometry = ball\nradius_m = 0.01\nload_n_per_m = 100", "",
                 "bad.ini:8: [contact] load_n_per_m", "takes load_n");
  expect_refused("radius_m = 0.01\nload_n = 3", "", "[contact] load_n", "takes load_n_per_m");
  expect_refused("geometry = ellipsoid\nradius_m = 0.01\nload_n = 3", "", "[contact] radius_m",
                 "takes radii_m = Rx, Ry");
  expect_refused("geometry = ball\nradii_m = 0.01, 0.02\nload_n = 3", "", "[contact] radii_m",
                 "takes radius_m");
  expect_refused("geometry = ball\nradius_m = 0.01", "", "missing required key [contact] load_n",
                 NULL);
  expect_refused("geometry = ellipsoid\nload_n = 3", "", "missing required key [contact] radii_m",
                 NULL);
  expect_refused("geometry = sphere\nradius_m = 0.01\nload_n = 3", "", "[contact] geometry",
                 "expected cylinder, ball or ellipsoid");
  expect_refused("geometry = ellipsoid\nradii_m = 0.01\nload_n = 3", "", "[contact] radii_m",
                 "two positive radii");
}

/* What a point contact does not take yet (an ellipsoid: dry and smooth;
 * a ball: no viscous flattening), each naming its key. */
static void test_not_yet(void **state) {
  (void)state;
  expect_refused("geometry = ellipsoid\nradii_m = 0.01, 0.04\nload_n = 5",
                 "fluid = on\n[materials]\nfluid = water\n", "[effects] fluid",
                 "a lubricated ellipsoid is not available yet");
  expect_refused("geometry = ellipsoid\nradii_m = 0.01, 0.04\nload_n = 5",
                 "roughness = on\n[materials]\nsurface = paper-3um\n", "[effects] roughness",
                 "a rough ellipsoid is not available yet");
  expect_refused(BALL,
                 "roughness = on\nfluid = on\nviscous_flattening = on\n[materials]\n"
                 "surface = paper-3um\nfluid = water\n",
                 "[effects] viscous_flattening", "the line contact's only");
  expect_refused(BALL, "[numerics]\ngrid = 256\n", "[numerics] grid", "planned per point");
  expect_refused(BALL, "[numerics]\ndomain_a0 = -2, 2\n", "[numerics] domain_a0", NULL);
  expect_refused(BALL "\nmoving = counterface", "", "[contact] moving", NULL);
  expect_refused(BALL, "[sweep]\ndirection = both\n", "[sweep] direction", "runs upward");
  expect_refused(BALL "\npressure_profile_file = p.csv", "", "[contact] pressure_profile_file",
                 "cylinder only");
}

static char *read_in(const char *dir, const char *name) {
  char path[4400];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  return vl_test_read_file(path);
}

static int exists(const char *dir, const char *name) {
  char path[4400];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  struct stat sb;
  return stat(path, &sb) == 0;
}

/* Lines of text (its rows). */
static size_t lines(const char *text) {
  size_t n = 0;
  for (const char *c = text; c && *c; c++)
    n += *c == '\n';
  return n;
}

/* `run` of a ball: the curve's point-contact columns with the contact area
 * of a viscoelastic ball at De = 0.1 ... 10 (below the relaxed Hertz area
 * pi a0^2 and falling with speed), the 2-D fields of the cells in contact,
 * the JSON and the figures. */
static void test_run_ball(void **state) {
  (void)state;
  const char *scene = ball_scene("run.ini", BALL, "");
  char dir[1200], *out = NULL, *err = NULL;
  snprintf(dir, sizeof dir, "%s/o", vl_test_dir);
  int rc = vl_test_run(&out, &err, "--quiet run %s --out %s --plot", scene, dir);
  if (rc != 0 && rc != 8) fail_msg("run: exit %d: %s", rc, err);
  assert_non_null(strstr(out, "ball, 3 points"));
  assert_non_null(strstr(out, "area_m2"));
  char *curve = read_in(dir, "curve.csv");
  assert_non_null(curve);
  assert_non_null(strstr(curve, ",geometry,contact_area_m2,contact_length_m,contact_breadth_m,"
                                "x_min_film_m,y_min_film_m,y_peak_m,cells_in_contact,"
                                "cells_per_a0\n"));
  assert_int_equal(lines(curve), 4);
  /* the area column of each row: after the warnings and the geometry */
  double a0 = 0.0, area[3];
  char *row = strchr(curve, '\n') + 1;
  for (int i = 0; i < 3; i++) {
    const char *g = strstr(row, ",ball,");
    assert_non_null(g);
    area[i] = strtod(g + 6, NULL);
    row = strchr(row, '\n') + 1;
  }
  /* a0 of 3 N on a 9.5 mm ball of the model rubber (E0 3.6 MPa, nu 0.5) */
  a0 = cbrt(3.0 * 3.0 * 0.0095 / (4.0 * 3.6e6 / 0.75));
  for (int i = 0; i < 3; i++) {
    assert_true(area[i] > 0.0 && area[i] < M_PI * a0 * a0);
    if (i) assert_true(area[i] < area[i - 1]);
  }
  char *fields = read_in(dir, "fields/001.csv");
  assert_non_null(fields);
  assert_true(!strncmp(fields, "x_m,y_m,x_over_a0,y_over_a0,p_c_pa,u_m\n", 38));
  assert_true(lines(fields) > 500);
  const char *figures[] = {"stribeck.png", "map-pc-1.svg", "map-u-1.png"};
  for (size_t k = 0; k < 3; k++)
    assert_true(exists(dir, figures[k]));
  free(fields), free(curve), free(out), free(err);
  out = err = NULL;
  rc = vl_test_run(&out, &err, "--quiet run %s --out %s --json", scene, dir);
  if (rc != 0 && rc != 8) fail_msg("run --json: exit %d: %s", rc, err);
  assert_true(vl_test_json_valid(out));
  assert_non_null(strstr(out, "\"geometry\": \"ball\""));
  assert_true(fabs(vl_test_json_number(out, "contact_area_m2", 2) / area[2] - 1.0) < 1e-9);
  free(out), free(err);
}

/* `run` of a lubricated smooth ball (soft EHL, docs/POINT_CONTACT.md
 * section 9) in glycerol at 0.3 and 1 m/s: the fluid carries the load (no
 * contact pressure, area 0, fluid share 1), the film opens with speed, the
 * friction is the fluid's (mu_Rc = mu_Sc = 0), the fields carry p_f on
 * graded cells and the maps show p_f and u. */
static void test_run_wet_ball(void **state) {
  (void)state;
  const char *scene = vl_test_scratch(
      "wet.ini", "[scene]\ntitle = wet ball test\n[materials]\ncompound = model-rubber\n"
                 "fluid = glycerol\n[contact]\n" BALL "\n"
                 "[sweep]\nquantity = v0\nfrom = 0.3\nto = 1\npoints = 2\nfields_at = 1\n"
                 "[numerics]\ntarget_error = 0.5\n" /* no refinement: for the time */
                 "[effects]\nviscoelastic = on\nfluid = on\nsolid_shear = off\n");
  char dir[1200], *out = NULL, *err = NULL;
  snprintf(dir, sizeof dir, "%s/w", vl_test_dir);
  int rc = vl_test_run(&out, &err, "--quiet run %s --out %s --plot --json", scene, dir);
  if (rc != 0) fail_msg("run: exit %d: %s", rc, err);
  assert_true(vl_test_json_valid(out));
  double film[2];
  for (int i = 0; i < 2; i++) {
    assert_true(vl_test_json_number(out, "mu_Rc", i) == 0.0);
    assert_true(vl_test_json_number(out, "mu_Sc", i) == 0.0);
    assert_true(vl_test_json_number(out, "contact_area_m2", i) == 0.0);
    assert_true(vl_test_json_number(out, "fluid_load_fraction", i) == 1.0);
    assert_true(vl_test_json_number(out, "mu_Rf", i) > 0.0);
    assert_true(vl_test_json_number(out, "mu_Sf", i) > 0.0);
    film[i] = vl_test_json_number(out, "u_min_m", i);
    assert_true(film[i] > 0.0);
  }
  assert_true(film[1] > film[0]);
  char *fields = read_in(dir, "fields/001.csv");
  assert_non_null(fields);
  assert_true(!strncmp(fields, "x_m,y_m,x_over_a0,y_over_a0,p_c_pa,u_m,p_f_pa\n", 45));
  const char *figures[] = {"stribeck.png", "map-pf-1.svg", "map-u-1.png"};
  for (size_t k = 0; k < 3; k++)
    assert_true(exists(dir, figures[k]));
  assert_false(exists(dir, "map-pc-1.svg"));
  free(fields), free(out), free(err);
}

/* `run` of a rough lubricated ball: the four friction terms, the fluid's
 * share between 0 and 1, the real contact area, the fields of both
 * pressures and their maps. */
static void test_run_rough_ball(void **state) {
  (void)state;
  const char *scene = vl_test_scratch(
      "rough.ini", "[scene]\ntitle = rough ball test\n[materials]\ncompound = model-rubber\n"
                   "surface = paper-1um\nfluid = glycerol\n[contact]\n" BALL "\nsigma_s_pa = 1e6\n"
                   "[sweep]\nquantity = v0\nfrom = 1e-3\nto = 1e-2\npoints = 2\nfields_at = 1e-2\n"
                   "[numerics]\ntarget_error = 0.5\n" /* no refinement: for the time */
                   "[effects]\nviscoelastic = on\nroughness = on\nfluid = on\n"
                   "solid_shear = on\nflow_factors = patir-cheng\n");
  char dir[1200], *out = NULL, *err = NULL;
  snprintf(dir, sizeof dir, "%s/r", vl_test_dir);
  int rc = vl_test_run(&out, &err, "--quiet run %s --out %s --plot --json", scene, dir);
  if (rc != 0) fail_msg("run: exit %d: %s", rc, err);
  assert_true(vl_test_json_valid(out));
  for (int i = 0; i < 2; i++) {
    double parts = 0.0;
    const char *terms[4] = {"mu_Rc", "mu_Rf", "mu_Sc", "mu_Sf"};
    for (int t = 0; t < 4; t++)
      parts += vl_test_json_number(out, terms[t], i);
    assert_true(fabs(vl_test_json_number(out, "mu", i) - parts) < 1e-9);
    assert_true(vl_test_json_number(out, "mu_Sc", i) > 0.0);
    assert_true(vl_test_json_number(out, "contact_area_m2", i) > 0.0);
    double share = vl_test_json_number(out, "fluid_load_fraction", i);
    assert_true(share > 0.0 && share < 1.0);
    assert_true(vl_test_json_number(out, "u_min_over_h_rms", i) > 0.0);
  }
  char *fields = read_in(dir, "fields/001.csv");
  assert_non_null(fields);
  assert_true(!strncmp(fields, "x_m,y_m,x_over_a0,y_over_a0,p_c_pa,u_m,p_f_pa\n", 45));
  const char *figures[] = {"stribeck.png", "map-pc-1.svg", "map-pf-1.svg", "map-u-1.png"};
  for (size_t k = 0; k < 4; k++)
    assert_true(exists(dir, figures[k]));
  free(fields), free(out), free(err);
}

/* The JSON numbers of one point that say what a ball's point is: each
 * must be the same in both answers (same scene, same solver path). */
static void same_point(const char *a, size_t ia, const char *b, size_t ib) {
  static const char *const keys[] = {
      "mu",           "mu_Rc",        "mu_Rf",           "mu_Sc",    "mu_Sf",          "u_min_m",
      "x_min_film_m", "y_min_film_m", "contact_area_m2", "y_peak_m", "error_estimate", NULL};
  for (size_t k = 0; keys[k]; k++) {
    double x = vl_test_json_number(a, keys[k], ia), y = vl_test_json_number(b, keys[k], ib);
    if (!(x == y || (isnan(x) && isnan(y))))
      fail_msg("%s: %.17g (friction) != %.17g (run)", keys[k], x, y);
  }
}

/* `friction --geometry ball` answers what `run` answers for the scene of
 * the same keys at that speed (from = to = v0): the same numbers, dry
 * (model rubber, sigma_s 1 MPa: mu_Sc = sigma_s A/W) and lubricated
 * (glycerol, soft EHL), with the ball's columns in the JSON. */
static void test_friction_ball_equals_run(void **state) {
  (void)state;
  static const struct {
    const char *options, *materials, *contact, *effects;
    double speed;
  } c[2] = {
      {"", "", "sigma_s_pa = 1e6\n", "solid_shear = on\n", 0.01},
      {"--fluid glycerol --sigma-s 0", "fluid = glycerol\n", "", "fluid = on\nsolid_shear = off\n",
       0.3},
  };
  for (int k = 0; k < 2; k++) {
    char text[1024], *out = NULL, *err = NULL, *run = NULL;
    snprintf(text, sizeof text,
             "[materials]\ncompound = model-rubber\n%s[contact]\n" BALL "\n%s"
             "[sweep]\nquantity = v0\nfrom = %g\nto = %g\npoints = 1\n"
             "[numerics]\ntarget_error = 0.5\n[effects]\n%s",
             c[k].materials, c[k].contact, c[k].speed, c[k].speed, c[k].effects);
    const char *scene = vl_test_scratch("same.ini", text);
    int rc = vl_test_run(&out, &err,
                         "--quiet friction --compound model-rubber --geometry ball --radius 0.0095 "
                         "--load-n 3 --speed %g --target-error 0.5 %s --json",
                         c[k].speed, c[k].options);
    if (rc != 0) fail_msg("friction: exit %d: %s", rc, err);
    assert_non_null(strstr(out, "\"geometry\": \"ball\""));
    free(err);
    err = NULL;
    rc = vl_test_run(&run, &err, "--quiet run %s --out %s/same --json", scene, vl_test_dir);
    if (rc != 0) fail_msg("run: exit %d: %s", rc, err);
    same_point(out, 0, run, 0);
    double area = vl_test_json_number(out, "contact_area_m2", 0);
    if (k == 0) /* dry: the shear in the contact area */
      assert_true(fabs(vl_test_json_number(out, "mu_Sc", 0) - 1e6 * area / 3.0) < 1e-12);
    else /* lubricated and smooth: no contact, a film */
      assert_true(area == 0.0 && vl_test_json_number(out, "u_min_m", 0) > 0.0);
    free(out), free(err), free(run);
  }
}

/* A command that must fail with status 2 and the needle on stderr. */
static void expect_cli_refusal(const char *args, const char *needle) {
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "%s", args);
  if (rc != 2 || !strstr(err, needle))
    fail_msg("%s: exit %d, expected 2 and '%s' in: %s", args, rc, needle, err);
  free(out), free(err);
}

/* The geometry options that do not go together are refused naming the
 * option; an ellipsoid with a surface (roughness) gets the scene's refusal
 * of what it does not take yet, not a crash; compare's point contact
 * needs its range. */
static void test_query_refusals(void **state) {
  (void)state;
  const char *f = "friction --compound model-rubber --speed 0.01 ";
  char a[1400];
  static const struct {
    const char *options, *needle;
  } r[] = {
      {"--geometry ball --radius 0.01 --load 100", "viscolube friction: --load (N per metre"},
      {"--geometry ball --radius 0.01", "missing --load-n N (the ball's total load)"},
      {"--geometry ball --load-n 3", "missing --radius M (the ball's radius)"},
      {"--geometry ball --radius 0.01 --load-n 3 --radii 0.01,0.02", "--radii is an ellipsoid's"},
      {"--geometry ellipsoid --radius 0.01 --load-n 3", "--radius is not an ellipsoid's"},
      {"--geometry ellipsoid --radii 0.01 --load-n 3", "needs --radii RX,RY"},
      {"--geometry ball --radius 0.01 --load-n 3 --grid 256", "--grid sets a line contact's cells"},
      {"--geometry ball --radius 0.01 --load-n 3 --flow-factors smooth",
       "--flow-factors applies to a rough contact (--surface) only"},
      {"--geometry sphere", "option --geometry needs cylinder, ball or ellipsoid"},
      {"--surface paper-0.5um --fluid water --load-n 3", "--load-n (a total load, N) is a ball's"},
      {"--geometry ellipsoid --radii 0.01,0.04 --load-n 3 --surface paper-0.5um",
       "surface 'paper-0.5um': [effects] roughness: not with [contact] geometry = ellipsoid: a "
       "rough ellipsoid is not available yet"},
      {"--geometry ellipsoid --radii 0.01,0.02 --load-n 3 --fluid water",
       "fluid 'water': [effects] fluid: not with [contact] geometry = ellipsoid"},
  };
  for (size_t k = 0; k < sizeof r / sizeof r[0]; k++) {
    snprintf(a, sizeof a, "--quiet %s%s", f, r[k].options);
    expect_cli_refusal(a, r[k].needle);
  }
  snprintf(a, sizeof a,
           "compare --compounds model-rubber --geometry ball --radius 0.01 --load-n 3 --out %s/c",
           vl_test_dir);
  expect_cli_refusal(a, "--geometry ball needs its range");
  snprintf(a, sizeof a,
           "compare --compounds model-rubber --geometry ball --radius 0.01 --load-n 3 --from 1e-6 "
           "--to 1e-3 --out %s/c",
           vl_test_dir);
  expect_cli_refusal(a, "a dry contact (no --fluid) has no v0 eta");
}

/* `compare --geometry ball`: two compounds' dry sweeps; compare.csv and
 * each curve.csv carry the ball's columns (film, its position, contact
 * area), the area of each point that of the curve, and the harder rubber
 * (sbr-filled) touches on a smaller area than the softer at every speed. */
static void test_compare_ball(void **state) {
  (void)state;
  char *out = NULL, *err = NULL, dir[1200];
  snprintf(dir, sizeof dir, "%s/cb", vl_test_dir);
  int rc = vl_test_run(&out, &err,
                       "--quiet compare --compounds sbr-unfilled,sbr-filled --geometry ball "
                       "--radius 0.0095 --load-n 3 --sigma-s 0 --from-speed 0.001 --to-speed 0.1 "
                       "--points 2 --target-error 0.5 --out %s",
                       dir);
  if (rc != 0) fail_msg("compare: exit %d: %s", rc, err);
  assert_non_null(strstr(out, "area_m2"));
  char *csv = read_in(dir, "compare.csv"), *curve = read_in(dir, "sbr-filled/curve.csv");
  assert_non_null(csv), assert_non_null(curve);
  assert_non_null(strstr(csv, "v0_m_s,mu_sbr-unfilled,mu_Rc_sbr-unfilled,mu_Rf_sbr-unfilled,"
                              "mu_Sc_sbr-unfilled,mu_Sf_sbr-unfilled,u_min_m_sbr-unfilled,"
                              "x_min_film_m_sbr-unfilled,y_min_film_m_sbr-unfilled,"
                              "contact_area_m2_sbr-unfilled,converged_sbr-unfilled,"));
  assert_null(strstr(csv, "flow_factors")); /* smooth and dry: none */
  assert_non_null(strstr(curve, ",geometry,contact_area_m2,"));
  assert_int_equal(lines(csv), 3);
  const char *row = strchr(csv, '\n') + 1;
  for (int i = 0; i < 2; i++, row = strchr(row, '\n') + 1) {
    double v[21];
    const char *c = row;
    for (int k = 0; k < 21; k++, c = strchr(c, ',') + 1)
      v[k] = strtod(c, NULL);
    /* 0 speed, 1-10 sbr-unfilled, 11-20 sbr-filled; the area is the 9th */
    assert_true(v[9] > 0.0 && v[19] > 0.0 && v[19] < v[9]);
    assert_true(v[10] == 1.0 && v[20] == 1.0);
    const char *ball = curve;
    for (int k = 0; k <= i; k++)
      ball = strstr(ball + 1, ",ball,");
    assert_true(strtod(ball + 6, NULL) == v[19]);
  }
  free(csv), free(curve), free(out), free(err);
}

/* A study of balls (docs/STUDY.md): loads_n, the ball's radii, two tasks;
 * tasks.csv and results.csv carry load_n and the ball's columns, each
 * task's curve is `run`'s of the same scene (the area at 3 N that of run,
 * to the CSV's 10 digits),
 * and the area grows with the load. The keys of another geometry are
 * refused naming file:line and key. */
static void test_study_ball(void **state) {
  (void)state;
  const char *study = vl_test_scratch(
      "balls.ini", "[study]\ncompounds = model-rubber\nloads_n = 1, 3\nradii_m = 0.0095\n"
                   "[contact]\ngeometry = ball\nsigma_s_pa = 0\n"
                   "[sweep]\nquantity = deborah\nfrom = 0.1\nto = 10\npoints = 3\n"
                   "[numerics]\ntarget_error = 0.05\n[effects]\nsolid_shear = off\n");
  char *out = NULL, *err = NULL, dir[1200];
  snprintf(dir, sizeof dir, "%s/sb", vl_test_dir);
  int rc = vl_test_run(&out, &err, "--quiet study %s --out %s", study, dir);
  if (rc != 0 && rc != 8) fail_msg("study: exit %d: %s", rc, err);
  char *tasks = read_in(dir, "tasks.csv"), *res = read_in(dir, "results.csv");
  assert_non_null(tasks), assert_non_null(res);
  assert_true(!strncmp(tasks, "task,compound,surface,fluid,load_n,radius_m,temperature_c,", 58));
  assert_non_null(strstr(tasks, "\n1,model-rubber,,,3,0.0095,,3,3,0,"));
  assert_true(!strncmp(res, "compound,surface,fluid,load_n,radius_m,temperature_c,v0_m_s,", 60));
  assert_non_null(strstr(res, ",geometry,contact_area_m2,"));
  assert_int_equal(lines(res), 7);
  /* the area of the last point of each task (rows 3 and 6) */
  double area[2];
  const char *row = res;
  for (int i = 0; i < 2; i++) {
    for (int k = 0; k < 3; k++)
      row = strchr(row, '\n') + 1;
    area[i] = strtod(strstr(row, ",ball,") + 6, NULL);
  }
  assert_true(area[1] > area[0]);
  /* task 1 is the scene of test_run_ball's keys with R 9.5 mm, W 3 N */
  free(out), free(err);
  out = err = NULL;
  rc = vl_test_run(&out, &err, "--quiet run %s --out %s/r --json", ball_scene("r.ini", BALL, ""),
                   vl_test_dir);
  if (rc != 0 && rc != 8) fail_msg("run: exit %d: %s", rc, err);
  /* the CSV's 10 digits */
  assert_true(fabs(vl_test_json_number(out, "contact_area_m2", 2) / area[1] - 1.0) < 1e-9);
  free(tasks), free(res), free(out), free(err);
  static const struct {
    const char *text, *needle;
  } bad[] = {
      {"[study]\ncompounds = model-rubber\nloads_n_per_m = 100\nradii_m = 0.01\n"
       "[contact]\ngeometry = ball\n",
       "bad.ini:3: [study] loads_n_per_m: [contact] geometry = ball (line 6) takes loads_n"},
      {"[study]\ncompounds = model-rubber\nloads_n = 3\nradii_m = 0.01\n",
       "bad.ini:3: [study] loads_n: total loads are a ball's or an ellipsoid's"},
      {"[study]\ncompounds = model-rubber\nloads_n = 3\nradii_m = 0.01\n"
       "[contact]\ngeometry = ellipsoid\nradii_m = 0.01, 0.02\n",
       "bad.ini:4: [study] radii_m: not with [contact] geometry = ellipsoid (line 6)"},
      {"[study]\ncases = model-rubber - - 3\n[contact]\ngeometry = ball\n",
       "bad.ini:2: [study] cases: a row is COMPOUND SURFACE FLUID LOAD_N RADIUS_M"},
      {"[study]\ncompounds = model-rubber\nloads_n = 3\nradii_m = 0.01\n"
       "[contact]\ngeometry = ball\nload_n = 3\n",
       "bad.ini:7: [contact] load_n: set by [study] loads_n"},
  };
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    char a[1400];
    snprintf(a, sizeof a, "study %s --out %s/bad", vl_test_scratch("bad.ini", bad[k].text),
             vl_test_dir);
    expect_cli_refusal(a, bad[k].needle);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_geometry_keys, vl_test_setup_db),
      cmocka_unit_test_setup(test_wrong_combinations, vl_test_setup_db),
      cmocka_unit_test_setup(test_not_yet, vl_test_setup_db),
      cmocka_unit_test_setup(test_run_ball, vl_test_setup_db),
      cmocka_unit_test_setup(test_run_wet_ball, vl_test_setup_db),
      cmocka_unit_test_setup(test_run_rough_ball, vl_test_setup_db),
      cmocka_unit_test_setup(test_friction_ball_equals_run, vl_test_setup_db),
      cmocka_unit_test_setup(test_query_refusals, vl_test_setup_db),
      cmocka_unit_test_setup(test_compare_ball, vl_test_setup_db),
      cmocka_unit_test_setup(test_study_ball, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
