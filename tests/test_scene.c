/* Scene files (scene.h): vl_scene_parse and vl_scene_load on good and bad
 * text. Every error must name the file and the exact line (and the section
 * and key where there is one); every good file, the shipped cases included,
 * must parse to the values written in it, with the defaults README.md
 * documents for the keys left out. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <dirent.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "viscolube/scene.h"

/* A valid scene; the line numbers below are those the tests expect.
 *  1 ; a scene for the tests
 *  2 [scene]
 *  3 title = test scene
 *  4 [materials]
 *  5 compound = model-rubber
 *  6 [contact]
 *  7 radius_m = 0.01
 *  8 load_n_per_m = 1000
 *  9 [sweep]
 * 10 quantity = deborah
 * 11 from = 1e-2
 * 12 to = 1e2
 * 13 points = 7
 * 14 [effects]
 * 15 viscoelastic = on
 * 16 [numerics]
 * 17 grid = 128 */
static const char *const BASE = "; a scene for the tests\n"
                                "[scene]\n"
                                "title = test scene\n"
                                "[materials]\n"
                                "compound = model-rubber\n"
                                "[contact]\n"
                                "radius_m = 0.01\n"
                                "load_n_per_m = 1000\n"
                                "[sweep]\n"
                                "quantity = deborah\n"
                                "from = 1e-2\n"
                                "to = 1e2\n"
                                "points = 7\n"
                                "[effects]\n"
                                "viscoelastic = on\n"
                                "[numerics]\n"
                                "grid = 128\n";

/* base with the first occurrence of `old` replaced by `new` (which may hold
 * newlines, to insert lines). Static storage, four buffers in turn, so that
 * edits nest: edit(edit(BASE, a, b), c, d). */
static const char *edit(const char *base, const char *old, const char *new) {
  static char bufs[4][8192];
  static int next;
  char *buf = bufs[next++ % 4];
  const char *at = strstr(base, old);
  if (!at) fail_msg("'%s' not in the scene", old);
  snprintf(buf, sizeof bufs[0], "%.*s%s%s", (int)(at - base), base, new, at + strlen(old));
  return buf;
}

static vl_scene g_scene; /* large: keep it off the stack */

static void parse_ok(const char *text) {
  vl_error err = {{0}};
  vl_status st = vl_scene_parse(text, "t.ini", &g_scene, &err);
  if (st != VL_OK) fail_msg("unexpected error %d: %s\n--- text:\n%s", st, err.msg, text);
}

/* The parse fails with VL_EINPUT and a message starting "t.ini:LINE: "
 * (LINE = 0: "t.ini: ", no line) that holds both needles. */
static void parse_fails(const char *text, int line, const char *needle1, const char *needle2) {
  vl_error err = {{0}};
  vl_status st = vl_scene_parse(text, "t.ini", &g_scene, &err);
  if (st != VL_EINPUT) fail_msg("status %d (want VL_EINPUT) for:\n%s", st, text);
  char want[64];
  if (line > 0)
    snprintf(want, sizeof want, "t.ini:%d: ", line);
  else
    snprintf(want, sizeof want, "t.ini: ");
  if (strncmp(err.msg, want, strlen(want)))
    fail_msg("message '%s' does not start with '%s' for:\n%s", err.msg, want, text);
  if (needle1 && !strstr(err.msg, needle1)) fail_msg("message '%s' lacks '%s'", err.msg, needle1);
  if (needle2 && !strstr(err.msg, needle2)) fail_msg("message '%s' lacks '%s'", err.msg, needle2);
}

/* ---- good files ---------------------------------------------------------- */

static void test_defaults(void **state) {
  (void)state;
  parse_ok("[materials]\ncompound = model-rubber\n"
           "[contact]\nradius_m = 0.01\nload_n_per_m = 1000\n"
           "[sweep]\nquantity = v0\nfrom = 1e-3\nto = 1\npoints = 4\n");
  /* README: grid 512, domain -1.5..1.5 (symmetric), tolerance 1e-9, schur */
  assert_int_equal(g_scene.grid, 512);
  assert_true(g_scene.domain_min_a0 == -1.5 && g_scene.domain_max_a0 == 1.5);
  assert_true(g_scene.tolerance == 1e-9);
  assert_int_equal(g_scene.linear_solver, VL_LINSOL_SCHUR);
  /* a wet scene gets the wet numerics of the accuracy study, unless it sets them */
  parse_ok("[materials]\ncompound = model-rubber\nsurface = paper-3um\nfluid = water\n"
           "[contact]\nradius_m = 0.01\nload_n_per_m = 1000\n"
           "[sweep]\nquantity = v0\nfrom = 1e-3\nto = 1\npoints = 4\n"
           "[effects]\nroughness = on\nfluid = on\n");
  /* rough and wet: the graded long inlet */
  assert_int_equal(g_scene.grid, VL_WET_ROUGH_GRID);
  assert_true(g_scene.grid_growth == VL_WET_GRID_GROWTH && g_scene.grid_growth > 1.0);
  assert_true(g_scene.domain_min_a0 == VL_WET_ROUGH_DOMAIN_MIN_A0 &&
              g_scene.domain_max_a0 == VL_WET_DOMAIN_MAX_A0 &&
              g_scene.tolerance == VL_WET_TOLERANCE);
  /* smooth and wet: the uniform grid (the graded one needs roughness) */
  parse_ok("[materials]\ncompound = model-rubber\nfluid = water\n"
           "[contact]\nradius_m = 0.01\nload_n_per_m = 1000\n"
           "[sweep]\nquantity = v0\nfrom = 1e-3\nto = 1\npoints = 4\n"
           "[effects]\nfluid = on\n");
  assert_int_equal(g_scene.grid, VL_WET_GRID);
  assert_true(g_scene.grid_growth == 1.0 && g_scene.domain_min_a0 == VL_WET_DOMAIN_MIN_A0);
  /* the dry default grid is uniform */
  parse_ok(BASE);
  assert_true(g_scene.grid_growth == 1.0);
  parse_ok("[materials]\ncompound = model-rubber\nsurface = paper-3um\nfluid = water\n"
           "[contact]\nradius_m = 0.01\nload_n_per_m = 1000\n"
           "[sweep]\nquantity = v0\nfrom = 1e-3\nto = 1\npoints = 4\n"
           "[effects]\nroughness = on\nfluid = on\n[numerics]\ngrid = 128\ntolerance = 1e-8\n");
  assert_true(g_scene.grid == 128 && g_scene.tolerance == 1e-8);
  parse_ok("[materials]\ncompound = model-rubber\n"
           "[contact]\nradius_m = 0.01\nload_n_per_m = 1000\n"
           "[sweep]\nquantity = v0\nfrom = 1e-3\nto = 1\npoints = 4\n");
  /* only the viscoelastic effect is on by default */
  assert_true(g_scene.effects.viscoelastic);
  assert_false(g_scene.effects.roughness || g_scene.effects.fluid || g_scene.effects.solid_shear ||
               g_scene.effects.viscous_flattening || g_scene.effects.temperature);
  assert_int_equal(g_scene.effects.flow_factors, VL_FLOW_FACTORS_SMOOTH);
  assert_int_equal(g_scene.elastic, VL_ELASTIC_RELAXED);
  assert_true(g_scene.sigma_s_pa == 0.0);
  assert_int_equal(g_scene.n_fields_at, 0);
  assert_string_equal(g_scene.title, "");
  assert_string_equal(g_scene.surface, "");
  assert_string_equal(g_scene.fluid, "");
  assert_string_equal(g_scene.path, "t.ini");
  /* the required values as written */
  assert_string_equal(g_scene.compound, "model-rubber");
  assert_true(g_scene.radius_m == 0.01 && g_scene.load_n_per_m == 1000.0);
  assert_int_equal(g_scene.quantity, VL_SWEEP_V0);
  assert_true(g_scene.from == 1e-3 && g_scene.to == 1.0);
  assert_int_equal(g_scene.points, 4);
}

static void test_every_key(void **state) {
  (void)state;
  parse_ok("[scene]\ntitle = wet, rough: the lot\n"
           "[materials]\ncompound = c1\nsurface = s1\nfluid = f1\n"
           "[contact]\nradius_m = 2.5e-2\nload_n_per_m = 350.5\nsigma_s_pa = 1e6\n"
           "[sweep]\nquantity = v0_eta\nfrom = 1e-6\nto = 1e-2\npoints = 41\n"
           "fields_at = 1e-5, 3e-4,1e-2\n"
           "[effects]\nviscoelastic = on\nroughness = on\nfluid = on\nsolid_shear = on\n"
           "flow_factors = patir-cheng\nviscous_flattening = off\ntemperature = off\n"
           "[numerics]\ngrid = 300\ngrid_growth = 1.25\ndomain_a0 = -3, 1.25\ntolerance = 1e-7\n"
           "linear_solver = sundials\npersson_table = 256\n");
  assert_string_equal(g_scene.title, "wet, rough: the lot");
  assert_string_equal(g_scene.compound, "c1");
  assert_string_equal(g_scene.surface, "s1");
  assert_string_equal(g_scene.fluid, "f1");
  assert_true(g_scene.radius_m == 2.5e-2 && g_scene.load_n_per_m == 350.5);
  assert_true(g_scene.sigma_s_pa == 1e6);
  assert_int_equal(g_scene.quantity, VL_SWEEP_V0_ETA);
  assert_true(g_scene.from == 1e-6 && g_scene.to == 1e-2);
  assert_int_equal(g_scene.points, 41);
  assert_int_equal(g_scene.n_fields_at, 3);
  assert_true(g_scene.fields_at[0] == 1e-5 && g_scene.fields_at[1] == 3e-4 &&
              g_scene.fields_at[2] == 1e-2);
  assert_true(g_scene.effects.viscoelastic && g_scene.effects.roughness && g_scene.effects.fluid &&
              g_scene.effects.solid_shear);
  assert_int_equal(g_scene.effects.flow_factors, VL_FLOW_FACTORS_PATIR_CHENG);
  assert_int_equal(g_scene.grid, 300);
  assert_true(g_scene.grid_growth == 1.25);
  assert_true(g_scene.domain_min_a0 == -3.0 && g_scene.domain_max_a0 == 1.25);
  assert_true(g_scene.tolerance == 1e-7);
  assert_int_equal(g_scene.linear_solver, VL_LINSOL_SUNDIALS);
  assert_int_equal(g_scene.persson_table, 256);
  assert_string_equal(vl_sweep_quantity_name(g_scene.quantity), "v0_eta");
}

/* Comments (; and # at the start, ; after a value), blank lines, blanks
 * around '=', indentation, tabs, CRLF line ends. */
static void test_comments_and_whitespace(void **state) {
  (void)state;
  parse_ok("# hash comment\n"
           "; semicolon comment\n"
           "\n"
           "   \t\n"
           "[materials]   \n"
           "  ; indented comment\n"
           "compound=model-rubber\n"
           "\n"
           "[contact]\r\n"
           "  radius_m   =   0.01   ; inline comment\r\n"
           "\tload_n_per_m\t=\t1000\r\n"
           "[sweep]\n"
           "    quantity = deborah\n"
           "    from = 1e-2\n"
           "    to = 1e2 ; up to here\n"
           "    points = 7\n"
           "[effects]\n"
           "viscoelastic = yes\n"
           "roughness = false\n"
           "# trailing comment without a newline");
  assert_string_equal(g_scene.compound, "model-rubber");
  /* an indented key is a key, not the continuation of the value above */
  assert_true(g_scene.radius_m == 0.01);
  assert_true(g_scene.load_n_per_m == 1000.0);
  assert_int_equal(g_scene.quantity, VL_SWEEP_DEBORAH);
  assert_true(g_scene.to == 1e2);
  assert_int_equal(g_scene.points, 7);
  assert_true(g_scene.effects.viscoelastic);
  assert_false(g_scene.effects.roughness);
}

static void test_switch_words(void **state) {
  (void)state;
  const char *on[] = {"on", "true", "yes", "1"}, *off[] = {"off", "false", "no", "0"};
  for (int i = 0; i < 4; i++) {
    char line[64];
    snprintf(line, sizeof line, "[effects]\nviscoelastic = %s\n", on[i]);
    parse_ok(edit(BASE, "[effects]\nviscoelastic = on\n", line));
    assert_true(g_scene.effects.viscoelastic);
    /* off: with a v0 sweep, as deborah needs viscoelastic = on */
    snprintf(line, sizeof line, "[effects]\nviscoelastic = %s\n", off[i]);
    char text[4096];
    snprintf(text, sizeof text, "%s", edit(BASE, "quantity = deborah", "quantity = v0"));
    parse_ok(edit(text, "[effects]\nviscoelastic = on\n", line));
    assert_false(g_scene.effects.viscoelastic);
  }
}

static void test_elastic_modulus(void **state) {
  (void)state;
  char text[4096];
  snprintf(text, sizeof text, "%s",
           edit(edit(BASE, "quantity = deborah", "quantity = v0"), "viscoelastic = on",
                "viscoelastic = off"));
  parse_ok(text);
  assert_int_equal(g_scene.elastic, VL_ELASTIC_RELAXED);
  parse_ok(
      edit(text, "compound = model-rubber", "compound = model-rubber\nelastic_modulus = glassy"));
  assert_int_equal(g_scene.elastic, VL_ELASTIC_GLASSY);
  parse_ok(
      edit(text, "compound = model-rubber", "compound = model-rubber\nelastic_modulus = 2.5e7"));
  assert_int_equal(g_scene.elastic, VL_ELASTIC_GIVEN);
  assert_true(g_scene.elastic_modulus_pa == 2.5e7);
  parse_ok(
      edit(text, "compound = model-rubber", "compound = model-rubber\nelastic_modulus = relaxed"));
  assert_int_equal(g_scene.elastic, VL_ELASTIC_RELAXED);
  parse_fails(
      edit(text, "compound = model-rubber", "compound = model-rubber\nelastic_modulus = soft"), 6,
      "[materials] elastic_modulus", "'soft'");
  parse_fails(
      edit(text, "compound = model-rubber", "compound = model-rubber\nelastic_modulus = -1e6"), 6,
      "[materials] elastic_modulus", "'-1e6'");
  /* a modulus for a viscoelastic rubber would be silently ignored: refused */
  parse_fails(
      edit(BASE, "compound = model-rubber", "compound = model-rubber\nelastic_modulus = glassy"), 6,
      "[materials] elastic_modulus", "viscoelastic = off");
}

/* sigma_s_pa is the solid_shear effect's parameter: without the effect the
 * scene carries no shear stress (only the effects on are simulated). */
static void test_sigma_without_solid_shear(void **state) {
  (void)state;
  parse_ok(edit(BASE, "load_n_per_m = 1000", "load_n_per_m = 1000\nsigma_s_pa = 2e6"));
  assert_false(g_scene.effects.solid_shear);
  assert_true(g_scene.sigma_s_pa == 0.0);
  parse_ok(edit(edit(BASE, "load_n_per_m = 1000", "load_n_per_m = 1000\nsigma_s_pa = 2e6"),
                "viscoelastic = on", "viscoelastic = on\nsolid_shear = on"));
  assert_true(g_scene.effects.solid_shear && g_scene.sigma_s_pa == 2e6);
}

/* [contact] moving: rubber (the default, the paper's) or counterface (a seal:
 * the rubber at rest, docs/MODEL.md section 11); a bad word and a deborah
 * sweep (the memory a rubber at rest has not) are refused at their lines. */
static void test_moving(void **state) {
  (void)state;
  parse_ok(BASE);
  assert_int_equal(g_scene.moving, VL_MOVING_RUBBER);
  const char *v0 = edit(BASE, "quantity = deborah", "quantity = v0");
  parse_ok(edit(v0, "load_n_per_m = 1000", "load_n_per_m = 1000\nmoving = counterface"));
  assert_int_equal(g_scene.moving, VL_MOVING_COUNTERFACE);
  parse_ok(edit(v0, "load_n_per_m = 1000", "load_n_per_m = 1000\nmoving = rubber"));
  assert_int_equal(g_scene.moving, VL_MOVING_RUBBER);
  parse_fails(edit(v0, "load_n_per_m = 1000", "load_n_per_m = 1000\nmoving = rod"), 9,
              "[contact] moving", "expected rubber or counterface, got 'rod'");
  parse_fails(edit(BASE, "load_n_per_m = 1000", "load_n_per_m = 1000\nmoving = counterface"), 11,
              "[sweep] quantity", "moving = rubber (line 9");
  parse_fails(edit(v0, "radius_m = 0.01", "radius_m = 0.01\nmovng = rubber"), 8, "movng",
              "did you mean 'moving'?");
}

/* [contact] sealed_pressure_pa and [seal] (docs/MODEL.md section 12): a
 * seal's strokes need a fluid and a moving counter-surface; the rod's
 * diameter and the stroke length go together. Errors name their lines. */
static void test_seal_keys(void **state) {
  (void)state;
  /* copies: edit() reuses four buffers */
  static char v0[2048], wet[2048], seal[2048], text[4096];
  snprintf(v0, sizeof v0, "%s", edit(BASE, "quantity = deborah", "quantity = v0"));
  snprintf(wet, sizeof wet, "%s",
           edit(edit(v0, "compound = model-rubber", "compound = model-rubber\nfluid = f"),
                "viscoelastic = on", "viscoelastic = on\nfluid = on"));
  snprintf(seal, sizeof seal, "%s",
           edit(wet, "load_n_per_m = 1000",
                "load_n_per_m = 1000\nmoving = counterface\nsealed_pressure_pa = 1e5"));
  snprintf(text, sizeof text,
           "%s[seal]\nstroke = both\nrod_diameter_m = 0.02\n"
           "stroke_length_m = 0.1\n",
           seal);
  parse_ok(text);
  assert_int_equal(g_scene.stroke, VL_STROKE_BOTH);
  assert_true(g_scene.sealed_pressure_pa == 1e5 && g_scene.rod_diameter_m == 0.02 &&
              g_scene.stroke_length_m == 0.1);
  snprintf(text, sizeof text, "%s[seal]\nstroke = sideways\n", seal);
  parse_fails(text, 23, "[seal] stroke", "expected out, in or both");
  snprintf(text, sizeof text, "%s[seal]\nstroke = in\nrod_diameter_m = 0.02\n", seal);
  parse_fails(text, 24, "[seal] rod_diameter_m", "both rod_diameter_m and stroke_length_m");
  snprintf(text, sizeof text, "%s[seal]\nstroke_length_m = 0.1\n", seal);
  parse_fails(text, 23, "[seal] stroke_length_m", "needs [seal] stroke");
  snprintf(text, sizeof text, "%s[seal]\nstroke = out\n", wet);
  parse_fails(text, 21, "[seal] stroke", "moving = counterface");
  parse_fails(edit(v0, "load_n_per_m = 1000", "load_n_per_m = 1000\nsealed_pressure_pa = 1"), 9,
              "[contact] sealed_pressure_pa", "fluid = on");
  parse_fails(edit(wet, "load_n_per_m = 1000", "load_n_per_m = 1000\nsealed_pressure_pa = -1"), 10,
              "[contact] sealed_pressure_pa", ">= 0");
  parse_ok(wet);
  assert_int_equal(g_scene.stroke, VL_STROKE_NONE);
}

/* fields_at at the ends of [from, to] and a single sweep point. */
static void test_sweep_edges(void **state) {
  (void)state;
  parse_ok(edit(BASE, "points = 7", "points = 7\nfields_at = 1e-2, 1e2"));
  assert_int_equal(g_scene.n_fields_at, 2);
  char list[512] = "points = 7\nfields_at = 1";
  for (int i = 1; i < VL_FIELDS_AT_MAX; i++)
    strcat(list, ",1");
  parse_ok(edit(BASE, "points = 7", list)); /* 32 values: the maximum */
  assert_int_equal(g_scene.n_fields_at, VL_FIELDS_AT_MAX);
  parse_ok(edit(BASE, "points = 7", "points = 1"));
  assert_int_equal(g_scene.points, 1);
}

/* [sweep] direction: up by default, down, both; a bad word, a single
 * point, and both ways with both strokes refused, naming the line. */
static void test_sweep_direction(void **state) {
  (void)state;
  parse_ok(BASE);
  assert_int_equal(g_scene.direction, VL_DIRECTION_UP);
  parse_ok(edit(BASE, "points = 7", "points = 7\ndirection = down"));
  assert_int_equal(g_scene.direction, VL_DIRECTION_DOWN);
  parse_ok(edit(BASE, "points = 7", "points = 7\ndirection = both"));
  assert_int_equal(g_scene.direction, VL_DIRECTION_BOTH);
  parse_fails(edit(BASE, "points = 7", "points = 7\ndirection = sideways"), 14, "[sweep] direction",
              "expected up, down or both, got 'sideways'");
  parse_fails(edit(BASE, "points = 7", "points = 1\ndirection = down"), 14, "[sweep] direction",
              "points >= 2");
}

/* Every shipped case parses, to the values its text holds. */
static void test_shipped_cases(void **state) {
  (void)state;
  const char *dir = vl_test_source_path("cases");
  char dirpath[4096];
  snprintf(dirpath, sizeof dirpath, "%s", dir);
  DIR *d = opendir(dirpath);
  if (!d) fail_msg("cannot open %s", dirpath);
  int n = 0;
  for (struct dirent *e; (e = readdir(d));) {
    size_t len = strlen(e->d_name);
    if (len < 5 || strcmp(e->d_name + len - 4, ".ini")) continue;
    char path[8192];
    snprintf(path, sizeof path, "%s/%s", dirpath, e->d_name);
    vl_error err = {{0}};
    vl_status st = vl_scene_load(path, &g_scene, &err);
    if (st != VL_OK) fail_msg("%s: %s", e->d_name, err.msg);
    assert_string_equal(g_scene.path, path);
    /* a cylinder's load per length, a ball's (cases/ball-*.ini) total load */
    assert_true(g_scene.compound[0] && g_scene.radius_m > 0 &&
                (g_scene.geometry == VL_GEOMETRY_CYLINDER ? g_scene.load_n_per_m : g_scene.load_n) >
                    0);
    assert_true(g_scene.points >= 1 && g_scene.to > g_scene.from);
    /* the grid, the domain and tolerance as written in the file */
    char *text = vl_test_read_file(path);
    char want[128];
    snprintf(want, sizeof want, "\ngrid = %zu\n", g_scene.grid);
    /* automatic numerics exactly when the file sets no grid or domain */
    bool manual = strstr(text, "\ngrid =") || strstr(text, "\ndomain_a0 =");
    assert_true(g_scene.auto_numerics == !manual);
    if (manual) assert_non_null(strstr(text, want));
    snprintf(want, sizeof want, "\npoints = %zu\n", g_scene.points);
    assert_non_null(strstr(text, want));
    const char *dom = strstr(text, "\ndomain_a0 = ");
    if (dom) { /* as written (automatic numerics start from the effects' defaults) */
      double d0, d1;
      assert_int_equal(sscanf(dom, " domain_a0 = %lf , %lf", &d0, &d1), 2);
      assert_true(g_scene.domain_min_a0 == d0 && g_scene.domain_max_a0 == d1);
    }
    assert_true(g_scene.effects.roughness == (strstr(text, "\nroughness = on") != NULL));
    free(text);
    n++;
  }
  closedir(d);
  assert_true(n >= 6);
  /* one in detail: the smooth Hunter case */
  vl_error err = {{0}};
  assert_int_equal(vl_scene_load(vl_test_source_path("cases/fig03-smooth.ini"), &g_scene, &err),
                   VL_OK);
  assert_string_equal(g_scene.compound, "model-rubber");
  assert_true(g_scene.radius_m == 0.01 && g_scene.load_n_per_m == 1000);
  assert_int_equal(g_scene.quantity, VL_SWEEP_DEBORAH);
  assert_true(g_scene.from == 1e-3 && g_scene.to == 1e3);
  assert_int_equal(g_scene.points, 61);
  assert_int_equal(g_scene.n_fields_at, 3);
  assert_true(g_scene.fields_at[0] == 0.01 && g_scene.fields_at[1] == 1.3 &&
              g_scene.fields_at[2] == 100);
  assert_true(g_scene.effects.viscoelastic && !g_scene.effects.roughness && !g_scene.effects.fluid);
  assert_true(g_scene.domain_min_a0 == -1.5 && g_scene.domain_max_a0 == 1.5);
}

/* ---- bad text: file:line, section, key ----------------------------------- */

static void test_unknown_section_and_key(void **state) {
  (void)state;
  /* the header line itself, even for a section left empty */
  parse_fails(edit(BASE, "[numerics]", "[numeric]"), 16, "unknown section [numeric]",
              "did you mean [numerics]");
  parse_fails(edit(BASE, "grid = 128\n", "grid = 128\n[extras]\n"), 18, "unknown section [extras]",
              NULL);
  parse_fails(edit(BASE, "[effects]", "[Effects]"), 14, "[Effects]", NULL);
  parse_fails(edit(BASE, "; a scene for the tests", "compound = x"), 1, "before any [section]",
              "'compound'");
  /* typos of a key */
  parse_fails(edit(BASE, "radius_m = 0.01", "radius = 0.01"), 7, "[contact] radius: unknown key",
              "did you mean 'radius_m'");
  parse_fails(edit(BASE, "radius_m = 0.01", "raduis_m = 0.01"), 7,
              "[contact] raduis_m: unknown key", "did you mean 'radius_m'");
  parse_fails(edit(BASE, "radius_m = 0.01", "radius_mm = 0.01"), 7, "[contact] radius_mm", NULL);
  parse_fails(edit(BASE, "viscoelastic = on", "roughnes = on"), 15, "[effects] roughnes",
              "did you mean 'roughness'");
  parse_fails(edit(BASE, "viscoelastic = on", "frobnicate = on"), 15,
              "[effects] frobnicate: unknown key", NULL);
  /* a known key in the wrong section */
  parse_fails(edit(BASE, "points = 7", "points = 7\ngrid = 64"), 14, "[sweep] grid: unknown key",
              "belongs in [numerics]");
  /* keys are case-sensitive */
  parse_fails(edit(BASE, "grid = 128", "Grid = 128"), 17, "[numerics] Grid", NULL);
  /* the same key twice: the second line, naming the first */
  parse_fails(edit(BASE, "load_n_per_m = 1000", "load_n_per_m = 1000\nradius_m = 0.02"), 9,
              "[contact] radius_m", "first on line 7");
  /* also through a second [contact] section */
  parse_fails(edit(BASE, "grid = 128", "grid = 128\n[contact]\nload_n_per_m = 5"), 19,
              "[contact] load_n_per_m", "first on line 8");
}

static void test_bad_numbers(void **state) {
  (void)state;
  const char *bad[] = {"1cm", "nan", "NaN",   "inf",       "-inf", "infinity", "-0.01", "0",
                       "-0",  "",    "1e999", "0.01 0.02", "0,01", "abc",      "1e-400"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
    char line[64], quoted[64];
    snprintf(line, sizeof line, "radius_m = %s", bad[i]);
    snprintf(quoted, sizeof quoted, "'%s'", bad[i]);
    parse_fails(edit(BASE, "radius_m = 0.01", line), 7, "[contact] radius_m", quoted);
  }
  parse_fails(edit(BASE, "load_n_per_m = 1000", "load_n_per_m = 0"), 8, "[contact] load_n_per_m",
              "positive");
  parse_fails(edit(BASE, "load_n_per_m = 1000", "load_n_per_m = 1 kN"), 8, "[contact] load_n_per_m",
              NULL);
  parse_fails(edit(BASE, "load_n_per_m = 1000", "load_n_per_m = 1000\nsigma_s_pa = -1"), 9,
              "[contact] sigma_s_pa", ">= 0");
  parse_fails(edit(BASE, "load_n_per_m = 1000", "load_n_per_m = 1000\nsigma_s_pa = nan"), 9,
              "[contact] sigma_s_pa", NULL);
  parse_fails(edit(BASE, "from = 1e-2", "from = -1e-2"), 11, "[sweep] from", "positive");
  parse_fails(edit(BASE, "from = 1e-2", "from = 0"), 11, "[sweep] from", NULL);
  parse_fails(edit(BASE, "to = 1e2", "to = inf"), 12, "[sweep] to", NULL);
  const char *bad_points[] = {"7.5",   "0",      "-3", "1e3",
                              "seven", "100001", "",   "99999999999999999999"};
  for (size_t i = 0; i < sizeof bad_points / sizeof *bad_points; i++) {
    char line[64];
    snprintf(line, sizeof line, "points = %s", bad_points[i]);
    parse_fails(edit(BASE, "points = 7", line), 13, "[sweep] points", "whole number");
  }
  parse_fails(edit(BASE, "quantity = deborah", "quantity = speed"), 10, "[sweep] quantity",
              "'speed'");
  parse_fails(edit(BASE, "grid = 128", "grid = 8"), 17, "[numerics] grid", "[16, 262144]");
  parse_fails(edit(BASE, "grid = 128", "grid = 300000"), 17, "[numerics] grid", NULL);
  /* a uniform grid above 8192 cells: refused at the grid's line, with the way out */
  parse_fails(edit(BASE, "grid = 128", "grid = 10000"), 17, "[numerics] grid", "grid_growth");
  /* grid_growth: a ratio in [1, 2], and only for rough contacts */
  parse_fails(edit(BASE, "grid = 128", "grid = 128\ngrid_growth = 0.9"), 18,
              "[numerics] grid_growth", "[1, 2]");
  parse_fails(edit(BASE, "grid = 128", "grid = 128\ngrid_growth = 3"), 18, "[numerics] grid_growth",
              "'3'");
  parse_fails(edit(BASE, "grid = 128", "grid = 128\ngrid_growth = 1.05"), 18,
              "[numerics] grid_growth", "roughness = on");
  parse_fails(edit(BASE, "grid = 128", "grid = 128.5"), 17, "[numerics] grid", NULL);
  parse_fails(edit(BASE, "grid = 128", "grid = 128\ntolerance = 0"), 18, "[numerics] tolerance",
              "(0, 1)");
  parse_fails(edit(BASE, "grid = 128", "grid = 128\ntolerance = 1"), 18, "[numerics] tolerance",
              NULL);
  parse_fails(edit(BASE, "grid = 128", "grid = 128\ntolerance = nan"), 18, "[numerics] tolerance",
              NULL);
  parse_fails(edit(BASE, "grid = 128", "grid = 128\nlinear_solver = umfpack"), 18,
              "[numerics] linear_solver", "'umfpack'");
  parse_fails(edit(BASE, "grid = 128", "grid = 128\npersson_table = 10"), 18,
              "[numerics] persson_table", NULL);
  parse_fails(edit(BASE, "viscoelastic = on", "temperature_c = -300"), 15,
              "[effects] temperature_c", NULL);
  parse_fails(edit(BASE, "compound = model-rubber", "compound ="), 5, "[materials] compound",
              "bad name");
}

static void test_bad_switches_and_lists(void **state) {
  (void)state;
  parse_fails(edit(BASE, "viscoelastic = on", "viscoelastic = on\nroughness = maybe"), 16,
              "[effects] roughness", "'maybe'");
  parse_fails(edit(BASE, "viscoelastic = on", "viscoelastic = ON"), 15, "[effects] viscoelastic",
              "on or off");
  parse_fails(edit(BASE, "viscoelastic = on", "viscoelastic ="), 15, "[effects] viscoelastic",
              NULL);
  parse_fails(edit(BASE, "viscoelastic = on", "flow_factors = patir_cheng"), 15,
              "[effects] flow_factors", "'patir_cheng'");
  /* domain_a0: two numbers, start < 0 < end */
  const char *bad_domain[] = {"1",          "1.5, -1.5", "-1.5, -1.5", "-1.5", "-1.5, 1.5, 2",
                              "-1.5,",      ",1.5",      "-1.5,,1.5",  "a, b", "0.2, 1.5",
                              "-1.5, -0.2", "nan, 1",    "-1.5 1.5",   ""};
  for (size_t i = 0; i < sizeof bad_domain / sizeof *bad_domain; i++) {
    char line[64];
    snprintf(line, sizeof line, "grid = 128\ndomain_a0 = %s", bad_domain[i]);
    parse_fails(edit(BASE, "grid = 128", line), 18, "[numerics] domain_a0", "start < 0 < end");
  }
  /* fields_at: 1 to 32 positive numbers */
  const char *bad_fields[] = {"", "1,,2", "1,", ",1", "0.5; 1", "one", "0", "-1", "1, nan"};
  for (size_t i = 0; i < sizeof bad_fields / sizeof *bad_fields; i++) {
    char line[64];
    snprintf(line, sizeof line, "points = 7\nfields_at = %s", bad_fields[i]);
    parse_fails(edit(BASE, "points = 7", line), 14, "[sweep] fields_at", NULL);
  }
  char list[512] = "points = 7\nfields_at = 1";
  for (int i = 0; i < VL_FIELDS_AT_MAX; i++)
    strcat(list, ",1");
  parse_fails(edit(BASE, "points = 7", list), 14, "[sweep] fields_at", "1 to 32");
  /* outside [from, to] = [1e-2, 1e2]: the line of fields_at, the value named */
  parse_fails(edit(BASE, "points = 7", "points = 7\nfields_at = 0.5, 1000"), 14,
              "[sweep] fields_at", "1000");
  parse_fails(edit(BASE, "points = 7", "points = 7\nfields_at = 0.001"), 14, "[sweep] fields_at",
              "outside [from, to]");
  /* a sweep needs two different ends */
  parse_fails(edit(BASE, "to = 1e2", "to = 1e-2"), 12, "[sweep] to", "must differ from from");
  /* given high to low, the same speeds swept upward (from the boundary
   * regime); fields_at is checked against the range either way */
  parse_ok(edit(BASE, "to = 1e2", "to = 1e-3"));
  assert_true(g_scene.from == 1e-3 && g_scene.to == 1e-2);
  parse_ok(edit(edit(BASE, "from = 1e-2", "from = 1e2"), "to = 1e2", "to = 1e-2"));
  assert_true(g_scene.from == 1e-2 && g_scene.to == 1e2);
  parse_fails(edit(edit(edit(BASE, "from = 1e-2", "from = 1e2"), "to = 1e2", "to = 1e-2"),
                   "points = 7", "points = 7\nfields_at = 1000"),
              14, "[sweep] fields_at", "1000");
}

/* A line that is neither a section, a key = value nor a comment. */
static void test_syntax_errors(void **state) {
  (void)state;
  parse_fails(edit(BASE, "radius_m = 0.01", "radius_m 0.01"), 7, "syntax error", NULL);
  parse_fails(edit(BASE, "[contact]", "[contact"), 6, "syntax error", NULL);
  parse_fails(edit(BASE, "grid = 128", "grid = 128\n  loose words"), 18, "syntax error", NULL);
  /* the first error wins: a syntax error before a bad key ... */
  parse_fails(edit(edit(BASE, "radius_m = 0.01", "radius_m 0.01"), "grid = 128", "grod = 128"), 7,
              "syntax error", NULL);
  /* ... and a bad key before a syntax error */
  parse_fails(edit(edit(BASE, "radius_m = 0.01", "raduis_m = 0.01"), "grid = 128", "grid 128"), 7,
              "raduis_m", NULL);
  /* a line too long for the INI reader is an error at its line, not cut
   * into pieces; a long comment is fine and shifts no line number */
  char text[4096], line[600];
  memset(line, 'x', 400);
  line[400] = '\0';
  snprintf(text, sizeof text, "[scene]\ntitle = %s\n", line);
  strcat(text, BASE);
  parse_fails(text, 2, "too long", NULL);
  snprintf(text, sizeof text, "; %s\n# %s\n%s", line, line, edit(BASE, "grid = 128", "grod = 1"));
  parse_fails(text, 19, "[numerics] grod", NULL);
}

static void test_missing_required_keys(void **state) {
  (void)state;
  struct {
    const char *line, *what;
  } req[] = {{"compound = model-rubber\n", "[materials] compound"},
             {"radius_m = 0.01\n", "[contact] radius_m"},
             {"load_n_per_m = 1000\n", "[contact] load_n_per_m"},
             {"quantity = deborah\n", "[sweep] quantity"},
             {"from = 1e-2\n", "[sweep] from"},
             {"to = 1e2\n", "[sweep] to"},
             {"points = 7\n", "[sweep] points"}};
  for (size_t i = 0; i < sizeof req / sizeof *req; i++)
    parse_fails(edit(BASE, req[i].line, ""), 0, "missing required key", req[i].what);
  parse_fails("", 0, "missing required key", "[materials] compound");
  parse_fails("; only a comment\n", 0, "missing required key", NULL);
}

/* Effects that need something else: the
 * error names the line of the key that asks for too much. */
static void test_inconsistent_effects(void **state) {
  (void)state;
  const char *fx = "viscoelastic = on";
  parse_fails(edit(BASE, fx, "viscoelastic = on\nroughness = on"), 16, "[effects] roughness",
              "[materials] surface");
  parse_fails(edit(BASE, fx, "viscoelastic = on\nfluid = on"), 16, "[effects] fluid",
              "[materials] fluid");
  /* a fluid named but the effect off: v0_eta has no fluid to sweep */
  parse_fails(edit(edit(BASE, "quantity = deborah", "quantity = v0_eta"), "compound = model-rubber",
                   "compound = model-rubber\nfluid = water"),
              11, "[sweep] quantity", "fluid = on");
  parse_fails(edit(BASE, fx, "viscoelastic = off"), 10, "[sweep] quantity",
              "viscoelastic = on (line 15 sets it off)");
  /* solid shear without the key: the stored pair's law, else the seed's 1 MPa
   * (issue 34; refused before) */
  parse_ok(edit(BASE, fx, "viscoelastic = on\nsolid_shear = on"));
  assert_true(g_scene.sigma_s_pa == VL_SCENE_SIGMA_S_PA && !g_scene.sigma_s_given);
  parse_fails(edit(edit(BASE, fx, "viscoelastic = on\nsolid_shear = on"), "load_n_per_m = 1000",
                   "load_n_per_m = 1000\nsigma_s_pa = 0"),
              17, "[effects] solid_shear", "sigma_s_pa > 0");
  parse_fails(edit(BASE, fx, "viscoelastic = on\nflow_factors = patir-cheng"), 16,
              "[effects] flow_factors", "roughness = on");
  /* viscous flattening modulates the roughness by the film: needs both */
  parse_fails(edit(BASE, fx, "viscoelastic = on\nviscous_flattening = on"), 16,
              "[effects] viscous_flattening", "roughness = on");
  parse_fails(edit(edit(BASE, fx, "viscoelastic = on\nroughness = on\nviscous_flattening = on"),
                   "compound = model-rubber", "compound = model-rubber\nsurface = s1"),
              18, "[effects] viscous_flattening", "fluid = on");
  parse_ok(
      edit(edit(BASE, fx, "viscoelastic = on\nroughness = on\nfluid = on\nviscous_flattening = on"),
           "compound = model-rubber", "compound = model-rubber\nsurface = s1\nfluid = f1"));
  assert_true(g_scene.effects.viscous_flattening && g_scene.effects.roughness &&
              g_scene.effects.fluid);
  /* temperature = on needs the temperature; temperature_c alone is refused */
  parse_fails(edit(BASE, fx, "viscoelastic = on\ntemperature = on"), 16, "[effects] temperature",
              "needs [effects] temperature_c");
  parse_fails(edit(BASE, fx, "viscoelastic = on\ntemperature_c = 40"), 16,
              "[effects] temperature_c", "temperature = on only");
  parse_ok(edit(BASE, fx, "viscoelastic = on\ntemperature = on\ntemperature_c = 40"));
  assert_true(g_scene.effects.temperature && g_scene.effects.temperature_c == 40.0);
  /* flow factors with roughness are fine */
  parse_ok(edit(edit(BASE, fx, "viscoelastic = on\nroughness = on\nflow_factors = patir-cheng"),
                "compound = model-rubber", "compound = model-rubber\nsurface = paper-3um"));
  assert_int_equal(g_scene.effects.flow_factors, VL_FLOW_FACTORS_PATIR_CHENG);
  /* a rough wet scene that names no model gets persson-emt with a 1 nm
   * film cut-off; a rough dry one keeps smooth (it has no film) */
  static char rough[2048]; /* edit()'s buffers are reused: keep a copy */
  snprintf(rough, sizeof rough, "%s",
           edit(BASE, "compound = model-rubber",
                "compound = model-rubber\nsurface = paper-3um\nfluid = water"));
  parse_ok(edit(rough, fx, "viscoelastic = on\nroughness = on\nfluid = on"));
  assert_int_equal(g_scene.effects.flow_factors, VL_FLOW_FACTORS_PERSSON_EMT);
  assert_true(g_scene.effects.film_cutoff_m == 1e-9);
  parse_ok(edit(rough, fx, "viscoelastic = on\nroughness = on"));
  assert_int_equal(g_scene.effects.flow_factors, VL_FLOW_FACTORS_SMOOTH);
  parse_ok(edit(rough, fx,
                "roughness = on\nfluid = on\nflow_factors = persson-emt\n"
                "film_cutoff_m = 3e-10"));
  assert_true(g_scene.effects.film_cutoff_m == 3e-10);
  /* the cut-off: persson-emt only, a length in (0, 1e-6] m */
  parse_fails(edit(rough, fx,
                   "roughness = on\nfluid = on\nflow_factors = patir-cheng\n"
                   "film_cutoff_m = 1e-9"),
              20, "[effects] film_cutoff_m", "persson-emt only");
  parse_fails(edit(rough, fx, "roughness = on\nfluid = on\nfilm_cutoff_m = 0"), 19,
              "[effects] film_cutoff_m", "(0, 1e-6]");
  parse_fails(edit(rough, fx, "roughness = on\nfluid = on\nfilm_cutoff_m = 2e-6"), 19,
              "[effects] film_cutoff_m", "'2e-6'");
}

/* ---- files --------------------------------------------------------------- */

static void test_files(void **state) {
  (void)state;
  const char *dir = vl_test_tmpdir();
  char path[4200];
  vl_error err = {{0}};
  /* a missing file: VL_EIO naming the path */
  snprintf(path, sizeof path, "%s/absent.ini", dir);
  assert_int_equal(vl_scene_load(path, &g_scene, &err), VL_EIO);
  assert_non_null(strstr(err.msg, path));
  assert_non_null(strstr(err.msg, "cannot open"));
  /* a directory */
  err.msg[0] = '\0';
  assert_int_equal(vl_scene_load(dir, &g_scene, &err), VL_EIO);
  assert_non_null(strstr(err.msg, dir));
  /* a good file; the message path of a bad one */
  snprintf(path, sizeof path, "%s/good.ini", dir);
  vl_test_write_file(path, BASE);
  assert_int_equal(vl_scene_load(path, &g_scene, &err), VL_OK);
  assert_int_equal(g_scene.grid, 128);
  vl_test_write_file(path, edit(BASE, "grid = 128", "grid = x"));
  assert_int_equal(vl_scene_load(path, &g_scene, &err), VL_EINPUT);
  char want[4300];
  snprintf(want, sizeof want, "%s:17: [numerics] grid", path);
  if (strncmp(err.msg, want, strlen(want)))
    fail_msg("'%s' does not start with '%s'", err.msg, want);
  /* a NUL byte on line 5 */
  snprintf(path, sizeof path, "%s/nul.ini", dir);
  FILE *f = fopen(path, "wb");
  assert_non_null(f);
  const char *at = strstr(BASE, "compound");
  fwrite(BASE, 1, (size_t)(at - BASE) + 3, f);
  fputc('\0', f);
  fputs(at + 3, f);
  fclose(f);
  assert_int_equal(vl_scene_load(path, &g_scene, &err), VL_EINPUT);
  snprintf(want, sizeof want, "%s:5: ", path);
  if (strncmp(err.msg, want, strlen(want)))
    fail_msg("'%s' does not start with '%s'", err.msg, want);
  assert_non_null(strstr(err.msg, "NUL"));
  /* a file larger than the first read buffer (16 KiB) */
  size_t big = 40000;
  char *text = malloc(big + strlen(BASE) + 1);
  assert_non_null(text);
  size_t k = 0;
  while (k + 40 < big)
    k += (size_t)sprintf(text + k, "; %036zu\n", k);
  strcpy(text + k, edit(BASE, "grid = 128", "grid = 256"));
  snprintf(path, sizeof path, "%s/big.ini", dir);
  vl_test_write_file(path, text);
  free(text);
  assert_int_equal(vl_scene_load(path, &g_scene, &err), VL_OK);
  assert_int_equal(g_scene.grid, 256);
}

/* ---- robustness: mutated scenes ------------------------------------------ */

/* Thousands of random edits of a valid scene: the parser returns VL_OK or
 * VL_EINPUT, never crashes (ASan/UBSan builds check memory), and every
 * error names t.ini and, when it gives a line, one that exists. */
static void test_mutations(void **state) {
  (void)state;
  const char alphabet[] = "[]=;#,\n \t-.0123456789eainfx_";
  unsigned long x = 88172645463325252UL;
  char text[4096];
  for (int iter = 0; iter < 3000; iter++) {
    snprintf(text, sizeof text, "%s", BASE);
    int edits = 1 + iter % 4;
    for (int e = 0; e < edits; e++) {
      x ^= x << 13, x ^= x >> 7, x ^= x << 17;
      size_t len = strlen(text), pos = (size_t)(x % len);
      char c = alphabet[(x >> 20) % (sizeof alphabet - 1)];
      switch ((x >> 40) % 3) {
      case 0: text[pos] = c; break;                                  /* replace */
      case 1: memmove(text + pos, text + pos + 1, len - pos); break; /* delete */
      default:                                                       /* insert */
        if (len + 2 < sizeof text) {
          memmove(text + pos + 1, text + pos, len - pos + 1);
          text[pos] = c;
        }
      }
    }
    int lines = 1;
    for (const char *p = text; *p; p++)
      lines += *p == '\n';
    vl_error err = {{0}};
    vl_status st = vl_scene_parse(text, "t.ini", &g_scene, &err);
    if (st == VL_OK) continue;
    if (st != VL_EINPUT) fail_msg("status %d for:\n%s", st, text);
    if (strncmp(err.msg, "t.ini:", 6)) fail_msg("message '%s' lacks the file", err.msg);
    if (err.msg[6] >= '0' && err.msg[6] <= '9') {
      int line = atoi(err.msg + 6);
      if (line < 1 || line > lines)
        fail_msg("line %d of %d in '%s' for:\n%s", line, lines, err.msg, text);
    }
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_defaults),
      cmocka_unit_test(test_every_key),
      cmocka_unit_test(test_comments_and_whitespace),
      cmocka_unit_test(test_switch_words),
      cmocka_unit_test(test_elastic_modulus),
      cmocka_unit_test(test_sigma_without_solid_shear),
      cmocka_unit_test(test_sweep_edges),
      cmocka_unit_test(test_sweep_direction),
      cmocka_unit_test(test_moving),
      cmocka_unit_test(test_seal_keys),
      cmocka_unit_test(test_shipped_cases),
      cmocka_unit_test(test_unknown_section_and_key),
      cmocka_unit_test(test_bad_numbers),
      cmocka_unit_test(test_bad_switches_and_lists),
      cmocka_unit_test(test_syntax_errors),
      cmocka_unit_test(test_missing_required_keys),
      cmocka_unit_test(test_inconsistent_effects),
      cmocka_unit_test(test_files),
      cmocka_unit_test(test_mutations),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
