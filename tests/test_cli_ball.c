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

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_geometry_keys, vl_test_setup_db),
      cmocka_unit_test_setup(test_wrong_combinations, vl_test_setup_db),
      cmocka_unit_test_setup(test_not_yet, vl_test_setup_db),
      cmocka_unit_test_setup(test_run_ball, vl_test_setup_db),
      cmocka_unit_test_setup(test_run_wet_ball, vl_test_setup_db),
      cmocka_unit_test_setup(test_run_rough_ball, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
