/* A seal's parametric lip (docs/MODEL.md section 13; issue 33): the tip's
 * parabola x^2/(2 r) between the tangent points x = -r tan(alpha) and
 * r tan(beta), straight flanks of slopes tan(alpha) (oil side, the inlet of
 * an outstroke) and tan(beta) (air side) beyond.
 *   - the shape: value and slope continuous at the tangent points, where
 *     they lie, the flanks' slopes, the mirror of an instroke;
 *   - its dry contact (the 2-D punch's conditions, profile.c) against
 *     closed forms (Hertz; the asymmetric wedge) and against the solver's
 *     own dry contact of the lip;
 *   - through scenes and `viscolube seal`: a symmetric lip mirrors its
 *     strokes, a lip's instroke is the outstroke of the lip turned round,
 *     and a rod seal's lip (steep oil side, shallow air side) carries back
 *     more than it lets out, as inverse hydrodynamics predicts from its dry
 *     pressure's inlet gradients: tight; turned round, it leaks;
 *   - the scene's errors for keys that do not go together;
 *   - the automatic numerics of a lip's film against a fine reference. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact_private.h"
#include "profile.h"
#include "rheology_internal.h"
#include "viscolube/contact.h"
#include "viscolube/scene.h"
#include "vl_test_scenes.h"
#include "vl_test_util.h"

#define NU 0.5
#define E0 3.6e6
#define ER (E0 / (1.0 - NU * NU))
#define DEG (M_PI / 180.0)

static vl_contact_config lip_config(double r, double oil_deg, double air_deg, bool mirror) {
  vl_contact_config cfg;
  vl_contact_config_defaults(&cfg);
  cfg.rubber = vl_prony_single(E0, 1.0, 0.1, NU);
  cfg.moving = VL_MOVING_COUNTERFACE;
  cfg.radius_m = r, cfg.load_n_per_m = 1000.0;
  cfg.lip_tip_radius_m = r;
  cfg.lip_oil_angle_rad = oil_deg * DEG, cfg.lip_air_angle_rad = air_deg * DEG;
  cfg.profile_mirror = mirror;
  return cfg;
}

/* ---- the shape ------------------------------------------------------------
 * Value and slope on both sides of each tangent point (e = 1e-9 r either
 * side) agree to the order of that step: the values differ by 2 e f' and
 * no more (asserted 1e-6 e: no step), the slopes by e/r at most (asserted
 * 1e-8: continuous; the curvature jumps from 1/r to 0, the join is C1 and
 * not C2). The slope is x/r inside and the flank's
 * beyond, the tangent points are where x/r meets the flanks, and the
 * mirror swaps the sides (f(-x), bit for bit). */
static void test_lip_shape(void **state) {
  (void)state;
  double r = 2e-4, ta = tan(40 * DEG), tb = tan(15 * DEG);
  vl_contact_config cfg = lip_config(r, 40, 15, false), mir = lip_config(r, 40, 15, true);
  vl_profile p, m;
  assert_int_equal(vl_profile_init(&p, &cfg, NULL), VL_OK);
  assert_int_equal(vl_profile_init(&m, &mir, NULL), VL_OK);
  const double xt[2] = {-r * ta, r * tb}, flank[2] = {-ta, tb};
  for (int k = 0; k < 2; k++) {
    double e = 1e-9 * r, s1, s2, s0;
    double f1 = vl_profile_height(&p, xt[k] - e, &s1), f2 = vl_profile_height(&p, xt[k] + e, &s2);
    double f0 = vl_profile_height(&p, xt[k], &s0);
    printf("  tangent point %+.6e m: f %.12e m, values apart by %.3e m beyond 2 e f', slopes "
           "%.12f / %.12f\n",
           xt[k], f0, fabs(f2 - f1 - 2.0 * e * s0), s1, s2);
    assert_true(fabs(f0 - 0.5 * xt[k] * xt[k] / r) < 1e-15 * r);
    assert_true(fabs(f2 - f1 - 2.0 * e * s0) < 1e-6 * e); /* no step: the slope's change alone */
    assert_true(fabs(s2 - s1) < 1e-8);
    assert_true(fabs(s0 - flank[k]) < 1e-12);
    /* inside: the parabola; beyond: the flank */
    double sin_, sout;
    vl_profile_height(&p, 0.5 * xt[k], &sin_);
    vl_profile_height(&p, 3.0 * xt[k], &sout);
    assert_true(fabs(sin_ - 0.5 * xt[k] / r) < 1e-12 && sout == flank[k]);
  }
  for (int i = -20; i <= 20; i++) {
    double x = 1e-4 * i, s, sm;
    assert_true(vl_profile_height(&p, x, &s) == vl_profile_height(&m, -x, &sm) && s == -sm);
  }
  vl_profile_free(&p);
  vl_profile_free(&m);
}

/* ---- the dry contact -------------------------------------------------------
 * The punch conditions give (1) the cylinder's Hertz half-width with c = 0
 * (asserted 1e-6: the Chebyshev rule is exact for a polynomial slope), and
 * (2) for a lip whose tip radius is small against the contact, the wedge
 * of slopes ta, tb: t0 = cos(theta0) = -c/a, theta0 = pi ta/(ta + tb), and
 * fN = (Er a/2)(ta + tb) sin(theta0) (both from the conditions with a
 * piecewise-constant slope); the tip's rounding changes them by about
 * r tan/a (1e-3 here; asserted 5e-3). (3) The solver's own dry contact of
 * a lip (elastic, 1536 cells over the domain vl_contact_numerics_follow_
 * profile lays out): where its pressure is positive agrees with the strip
 * to the cells' width (asserted 1.5 cells at each edge). */
static void test_lip_dry_contact(void **state) {
  (void)state;
  double c, a, R;
  vl_contact_config cyl = lip_config(0.01, 10, 3, false);
  cyl.lip_tip_radius_m = cyl.lip_oil_angle_rad = cyl.lip_air_angle_rad = 0.0;
  assert_int_equal(vl_contact_profile_contact(&cyl, &c, &a, &R, NULL), VL_OK);
  double a0 = sqrt(4.0 * 1000.0 * 0.01 / (M_PI * ER));
  printf("  cylinder: c = %.3e m, a = %.10e m (Hertz %.10e), R = %.10g m\n", c, a, a0, R);
  assert_true(fabs(c) < 1e-9 * a0 && fabs(a / a0 - 1.0) < 1e-6 && fabs(R / 0.01 - 1.0) < 2e-6);

  vl_contact_config w = lip_config(1e-6, 12, 4, false);
  assert_int_equal(vl_contact_profile_contact(&w, &c, &a, NULL, NULL), VL_OK);
  double ta = tan(12 * DEG), tb = tan(4 * DEG), th = M_PI * ta / (ta + tb);
  double aw = 2.0 * 1000.0 / (ER * (ta + tb) * sin(th)), cw = -aw * cos(th);
  printf("  near-wedge: c = %.6e m (wedge %.6e), a = %.6e m (wedge %.6e)\n", c, cw, a, aw);
  assert_true(fabs(a / aw - 1.0) < 5e-3 && fabs(c - cw) < 5e-3 * aw);

  vl_contact_config d = lip_config(5e-3, 10, 3, false);
  assert_int_equal(vl_contact_profile_contact(&d, &c, &a, &d.radius_m, NULL), VL_OK);
  d.grid = 1536;
  assert_int_equal(vl_contact_numerics_follow_profile(&d, NULL), VL_OK);
  vl_contact *s = NULL;
  vl_error err;
  if (vl_contact_create(&d, &s, &err) != VL_OK) fail_msg("%s", err.msg);
  vl_point pt;
  assert_int_equal(vl_contact_solve(s, 0.0, &pt, &err), VL_OK);
  size_t n = vl_contact_grid(s);
  double *b = calloc(6 * n, sizeof *b);
  vl_fields f = {n, b, b + n, b + 2 * n, b + 3 * n, b + 4 * n, b + 5 * n, NULL};
  vl_contact_fields(s, &f);
  double lo = INFINITY, hi = -INFINITY, dx = (d.x_max_a0 - d.x_min_a0) * a / (double)d.grid;
  for (size_t i = 0; i < n; i++)
    if (f.p_c_pa[i] > 0.0) lo = fmin(lo, f.x_m[i]), hi = fmax(hi, f.x_m[i]);
  printf("  lip r 5 mm, 10/3 deg: strip [%.5e, %.5e] m, solver's contact nodes [%.5e, %.5e] m "
         "(cells %.2e m)\n",
         c - a, c + a, lo, hi, dx);
  assert_true(fabs(lo - (c - a)) < 1.5 * dx && fabs(hi - (c + a)) < 1.5 * dx);
  free(b);
  vl_contact_free(s);
}

/* A lip scene, smooth elastic rubber, 1000 N/m, oil 0.1 Pa s, both strokes
 * on a 20 mm rod with a 0.1 m stroke, at `speeds`. */
static const char *lip_scene(double r, double oil, double air, const char *speeds,
                             const char *extra) {
  static char buf[1024];
  snprintf(buf, sizeof buf,
           "[materials]\ncompound = model-rubber\nfluid = model-1e-1\n"
           "[contact]\nprofile = lip\nlip_tip_radius_m = %g\nlip_oil_angle_deg = %g\n"
           "lip_air_angle_deg = %g\nload_n_per_m = 1000\nmoving = counterface\n%s"
           "[sweep]\nquantity = v0\n%s"
           "[effects]\nviscoelastic = off\nfluid = on\n"
           "[seal]\nstroke = both\nrod_diameter_m = 0.02\nstroke_length_m = 0.1\n",
           r, oil, air, extra, speeds);
  return buf;
}

/* `viscolube seal --json` on the scene text; the JSON (caller frees). */
static char *seal_json(const char *name, const char *text) {
  const char *scene = vl_test_scratch(name, text);
  char *out = NULL, *err = NULL;
  int rc =
      vl_test_run(&out, &err, "seal %s --out %s/%s.out --json --quiet", scene, vl_test_dir, name);
  if (rc != 0) fail_msg("seal %s exited %d: %s", name, rc, err);
  free(err);
  return out;
}

/* ---- strokes ------------------------------------------------------------
 * (1) A symmetric lip (8 deg both sides, r 5 mm, at 1e-2 m/s) without
 * sealed pressure:
 * the two strokes are one film mirrored (asserted 1e-12 on the friction,
 * the film and the flux; the same solve). (2) The lip 10/3 deg: its
 * instroke is the outstroke of the lip 3/10 deg and the other way round
 * (asserted 1e-12). (3) The rod seal's rule: the lip 10/3 deg (steep oil
 * side) lets out less on the outstroke than it carries back: tight; turned
 * round (3/10) it leaks. Measured q_in/q_out 1.65 at 1e-3 m/s, 1.60 at
 * 1e-2 (asserted > 1.2). Inverse hydrodynamics gives no number here: the
 * curvature jumps at the tangent points (inside the contact) make the dry
 * pressure's gradient log-singular there (docs/MODEL.md section 13), and
 * its steepest inlet gradient is not defined; the film regularises it. At
 * 1e-4 m/s the fresh start of such a lip fails (the symmetric one: 2264
 * iterations over every path, a minute); 1e-3 m/s is the test's lowest. */
static void test_lip_strokes(void **state) {
  (void)state;
  const char *speeds = "from = 1e-3\nto = 1e-2\npoints = 2\n";
  char *sym =
      seal_json("sym.ini", lip_scene(5e-3, 8, 8, "from = 1e-2\nto = 1e-2\npoints = 1\n", ""));
  const char *keys[3] = {"friction_n_per_m", "u_min_m", "flux_m2_s"};
  for (size_t i = 0; i < 1; i++)
    for (int k = 0; k < 3; k++) {
      double o = vl_test_json_number(sym, keys[k], 2 * i),
             n = vl_test_json_number(sym, keys[k], 2 * i + 1);
      assert_true(o > 0.0 && fabs(n / o - 1.0) < 1e-12);
    }
  free(sym);
  char *lip = seal_json("lip.ini", lip_scene(5e-3, 10, 3, speeds, ""));
  char *turned = seal_json("turned.ini", lip_scene(5e-3, 3, 10, speeds, ""));
  for (size_t i = 0; i < 2; i++) {
    for (int k = 0; k < 3; k++) {
      double a = vl_test_json_number(lip, keys[k], 2 * i + 1),
             b = vl_test_json_number(turned, keys[k], 2 * i);
      assert_true(fabs(b / a - 1.0) < 1e-12);
    }
    double qo = vl_test_json_number(lip, "flux_m2_s", 2 * i),
           qi = vl_test_json_number(lip, "flux_m2_s", 2 * i + 1);
    double vo = vl_test_json_number(lip, "volume_out_m3", i),
           vb = vl_test_json_number(lip, "volume_back_m3", i);
    printf("  lip 10/3 deg at %g m/s: flux out %.5g, back %.5g m^2/s: ratio %.4f; per cycle "
           "%.4g out, %.4g back m^3\n",
           vl_test_json_number(lip, "v0_m_s", i), qo, qi, qi / qo, vo, vb);
    assert_true(vb > vo && qi > 1.2 * qo);
  }
  assert_null(strstr(lip, "\"tight\": false"));
  assert_null(strstr(turned, "\"tight\": true"));
  free(lip);
  free(turned);
}

/* ---- the scene's keys ------------------------------------------------------
 * A lip's keys go together: all three with profile = lip, none without;
 * radius_m and a table are refused beside a lip; an angle outside (0, 90)
 * degrees is refused at its line. Each message names the file, the line
 * and the key. */
static void test_lip_keys(void **state) {
  (void)state;
  static const struct {
    const char *contact, *message;
  } cases[] = {
      {"profile = lip\nlip_tip_radius_m = 1e-4\nlip_oil_angle_deg = 40\nlip_air_angle_deg = 15\n"
       "radius_m = 1e-3\n",
       "s.ini:9: [contact] radius_m: not with profile = lip (line 5)"},
      {"profile = lip\nlip_tip_radius_m = 1e-4\nlip_oil_angle_deg = -40\n",
       "s.ini:7: [contact] lip_oil_angle_deg: expected a flank angle in (0, 90) degrees, got "
       "'-40'"},
      {"profile = lip\nlip_tip_radius_m = 1e-4\nlip_oil_angle_deg = 40\n",
       "s.ini:5: [contact] profile: lip needs [contact] lip_air_angle_deg"},
      {"radius_m = 1e-3\nlip_air_angle_deg = 15\n",
       "s.ini:6: [contact] lip_air_angle_deg: applies to [contact] profile = lip only"},
      {"profile = lip\nlip_tip_radius_m = 1e-4\nlip_oil_angle_deg = 40\nlip_air_angle_deg = 90\n",
       "s.ini:8: [contact] lip_air_angle_deg: expected a flank angle in (0, 90) degrees, got '90'"},
      {"profile = lip\nlip_tip_radius_m = 1e-4\nlip_oil_angle_deg = 40\nlip_air_angle_deg = 15\n"
       "profile_file = lip.csv\n",
       "s.ini:9: [contact] profile_file: not with profile = lip (line 5)"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
    char text[1024];
    snprintf(text, sizeof text,
             "[materials]\ncompound = model-rubber\nfluid = water\n[contact]\n%s"
             "load_n_per_m = 30\nmoving = counterface\n"
             "[sweep]\nquantity = v0\nfrom = 0.01\nto = 1\npoints = 3\n[effects]\nfluid = on\n",
             cases[k].contact);
    vl_scene sc;
    vl_error err = {{0}};
    assert_int_equal(vl_scene_parse(text, "s.ini", &sc, &err), VL_EINPUT);
    printf("  %s\n", err.msg);
    assert_non_null(strstr(err.msg, cases[k].message));
  }
  const char *good = "[materials]\ncompound = model-rubber\n[contact]\nprofile = lip\n"
                     "lip_tip_radius_m = 1e-4\nlip_oil_angle_deg = 40\nlip_air_angle_deg = 15\n"
                     "load_n_per_m = 30\n[sweep]\nquantity = v0\nfrom = 0.01\nto = 1\npoints = 3\n";
  vl_scene sc;
  vl_error err = {{0}};
  assert_int_equal(vl_scene_parse(good, "g.ini", &sc, &err), VL_OK);
  assert_true(sc.lip && sc.lip_tip_radius_m == 1e-4 && sc.lip_oil_angle_deg == 40.0 &&
              sc.lip_air_angle_deg == 15.0);
}

/* ---- the shipped lip (cases/seals/lip.ini, docs/CASES.md "seals") --------
 * A rod seal's lip, r 0.1 mm, 40 deg oil side, 15 deg air side, 30 N/m, on
 * the steel rod in oil, 1e-4 to 1 m/s, `viscolube seal`. Statements: every
 * point of both strokes converges; the flanks are steep for the half-space
 * model and every outstroke point says so (the profile slope warning, 0.31
 * to 0.7 rad measured); boundary-dominated friction when creeping
 * (mu_Sc > 90 % of mu at 1e-4 m/s; the strokes' fluxes there within 1 % of
 * each other: the asperities, not the lip's shape, set the flow); from
 * 0.01 m/s up the film's pumping shows: the instroke carries back more
 * than the outstroke lets out (measured 0.9 % at 0.01 m/s to 39 % at 1 m/s)
 * and the seal is tight. */
static void test_case_lip(void **state) {
  (void)state;
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "seal %s --out %s/lip --json --quiet",
                       vl_test_source_path("cases/seals/lip.ini"), vl_test_dir);
  /* 8: some points above their 1 % target (docs/CASES.md) */
  if (rc != 0 && rc != 8) fail_msg("lip exited %d: %s", rc, err);
  assert_null(strstr(out, "\"converged\": false"));
  size_t n = 9;
  for (size_t i = 0; i < n; i++) {
    double v = vl_test_json_number(out, "v0_m_s", i);
    double qo = vl_test_json_number(out, "flux_m2_s", 2 * i),
           qi = vl_test_json_number(out, "flux_m2_s", 2 * i + 1);
    double fo = vl_test_json_number(out, "friction_n_per_m", 2 * i),
           fi = vl_test_json_number(out, "friction_n_per_m", 2 * i + 1);
    printf("  %.4g m/s: F %.4g / %.4g N/m, q %.4g / %.4g m^2/s (back/out %.4f)\n", v, fo, fi, qo,
           qi, qi / qo);
    if (i == 0) assert_true(fabs(qi / qo - 1.0) < 0.01);
    if (v >= 0.01) assert_true(qi > qo);
  }
  free(out), free(err);
  char path[1300];
  snprintf(path, sizeof path, "%s/lip/curve.csv", vl_test_dir);
  char *csv = vl_test_read_file(path);
  size_t slope = 0;
  for (const char *p = csv; (p = strstr(p, "profile slope")); p++)
    slope++;
  assert_int_equal(slope, n);
  /* creeping: mu = mu_Sc + mu_Sf, mu_Sc the bulk */
  const char *row = strstr(csv, "\n0.0001,");
  assert_non_null(row);
  double mu, sc;
  assert_int_equal(sscanf(row + 1, "%*[^,],%*[^,],,%lf,,,%lf", &mu, &sc), 2);
  printf("  1e-4 m/s: mu %.4g, mu_Sc %.4g\n", mu, sc);
  assert_true(sc > 0.9 * mu);
  free(csv);
  snprintf(path, sizeof path, "%s/lip/seal.json", vl_test_dir);
  char *js = vl_test_read_file(path);
  for (size_t i = 4; i < n; i++) /* 0.01 m/s and up */
    assert_true(vl_test_json_number(js, "volume_back_m3", i) >
                vl_test_json_number(js, "volume_out_m3", i));
  free(js);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_lip_shape),
      cmocka_unit_test(test_lip_dry_contact),
      cmocka_unit_test_setup(test_lip_strokes, vl_test_setup_db),
      cmocka_unit_test(test_lip_keys),
      cmocka_unit_test_setup(test_case_lip, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
