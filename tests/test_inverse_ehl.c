/* An imposed static contact pressure (docs/MODEL.md section 14; issue 33):
 * the seal's preload from an FE model, the rubber's shape not given.
 *   - inverse hydrodynamic lubrication (Blok; Mueller and Nau, Fluid
 *     Sealing Technology, 1998): when the rubber's elastic displacements
 *     dwarf the film (a large load parameter), the film hardly changes the
 *     static pressure, the film at the pressure maximum tends to
 *     h* = sqrt(8 eta U / (9 w_max)), w_max the steepest gradient of the
 *     static pressure on the inlet side, and the flux to U h* / 2: measured
 *     against that closed form over three decades of the load parameter,
 *     with the rate of approach fitted;
 *   - a Hertzian static pressure on a smooth elastic rubber gives the film
 *     of the cylinder it comes from at high load (the two differ only by
 *     the gap outside the contact: straight flanks against the parabola);
 *   - the table through a scene: load and scales from it, mirrored strokes,
 *     errors naming the table's line. */
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
#include "rheology_internal.h"
#include "viscolube/contact.h"
#include "vl_test_scenes.h"
#include "vl_test_util.h"

#define NU 0.5
#define E0 3.6e6
#define ETA 0.1
#define HALF_SPAN 2e-3 /* b, m */
#define P_MAX 5e5      /* Pa */
#define TABLE 801

/* The static pressure p_m (1 - (x/b)^2)^2: smooth at the edges, its
 * steepest inlet gradient w_max = (8/(3 sqrt 3)) p_m / b at x = -b/sqrt 3. */
static double *quartic_table(void) {
  double *t = malloc(2 * TABLE * sizeof *t);
  assert_non_null(t);
  for (size_t k = 0; k < TABLE; k++) {
    double x = HALF_SPAN * (-1.0 + 2.0 * (double)k / (TABLE - 1)), s = 1.0 - pow(x / HALF_SPAN, 2);
    t[k] = x, t[TABLE + k] = P_MAX * s * s;
  }
  t[TABLE] = t[2 * TABLE - 1] = 0.0;
  return t;
}

/* The contact of the static pressure t on the elastic rubber, uniform grid
 * of `grid` cells on [x_min, x_max] a0. */
static vl_contact *make_static(const double *t, size_t grid, double x_min, double x_max) {
  vl_contact_config cfg;
  vl_contact_config_defaults(&cfg);
  cfg.rubber = vl_prony_single(E0, 1.0, 0.1, NU);
  cfg.moving = VL_MOVING_COUNTERFACE;
  cfg.eta_pa_s = ETA;
  cfg.static_x_m = t, cfg.static_p_pa = t + TABLE, cfg.static_points = TABLE;
  vl_error err;
  if (vl_contact_static_scales(&cfg, &cfg.load_n_per_m, &cfg.radius_m, &err) != VL_OK)
    fail_msg("scales: %s", err.msg);
  cfg.grid = grid, cfg.x_min_a0 = x_min, cfg.x_max_a0 = x_max;
  cfg.tolerance = 1e-9;
  vl_contact *c = NULL;
  if (vl_contact_create(&cfg, &c, &err) != VL_OK) fail_msg("create: %s", err.msg);
  return c;
}

/* The error of the flux against U h* / 2 at the load parameters lambda
 * (p_m b / Er0 over h*: the rubber's elastic displacement under the static
 * pressure against the film) of the speeds v[0..n) on a grid of `grid`
 * cells, into err[] and lam[]. The flux is that through the face at the
 * fluid pressure's maximum, where it is the Couette flux U h/2 alone: its
 * ratio to U h* / 2 is the film's there to h*. */
static void flux_errors(const double *t, size_t grid, size_t n, const double *v, double *err,
                        double *lam) {
  double w_max = 8.0 / (3.0 * sqrt(3.0)) * P_MAX / HALF_SPAN, er = E0 / (1.0 - NU * NU);
  vl_contact *c = make_static(t, grid, -2.0, 1.6);
  for (size_t k = 0; k < n; k++) {
    vl_point pt;
    vl_error e;
    if (vl_contact_solve(c, v[k], &pt, &e) != VL_OK) fail_msg("%s", e.msg);
    double hs = sqrt(8.0 * ETA * v[k] / (9.0 * w_max));
    lam[k] = P_MAX * HALF_SPAN / er / hs;
    err[k] = fabs(pt.flux_m2_s / (0.5 * v[k] * hs) - 1.0);
    printf("  N %zu, U %g m/s: load parameter %.4g, flux / (U h*/2) - 1 = %+.3e, u_min/h* %.4f\n",
           grid, v[k], lam[k], pt.flux_m2_s / (0.5 * v[k] * hs) - 1.0, pt.u_min_m / hs);
  }
  vl_contact_free(c);
}

/* Inverse hydrodynamics on the quartic static pressure, U from 1e-2 to
 * 1e-5 m/s (load parameter 137 to 4335). Measured: the flux error falls
 * 4.0e-2, 5.7e-3, 1.16e-3, 3.4e-4; over the three largest parameters a
 * log-log fit gives error ~ lambda^-1.22 (4.9 and 3.4 times per half
 * decade): the film's change of the pressure, whose share falls like
 * 1/lambda, shifts the inlet gradient that sets the film. Asserted: the
 * fitted rate steeper than lambda^-0.9 (at least the first order the
 * perturbation argument gives, with a margin for the 1.07-1.38 spread of
 * the local rates), the error falling at each step, and below 6e-4 at
 * lambda = 4335 (measured 3.4e-4; the grid moves it by 1e-5: N 400
 * against 800, asserted within 5e-5). */
static void test_inverse_hydrodynamics(void **state) {
  (void)state;
  double *t = quartic_table();
  const double v[4] = {1e-2, 1e-3, 1e-4, 1e-5};
  double err[4], lam[4], err_fine, lam_fine;
  flux_errors(t, 400, 4, v, err, lam);
  flux_errors(t, 800, 1, v + 3, &err_fine, &lam_fine);
  /* least squares of log err on log lambda over the three largest */
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int k = 1; k < 4; k++) {
    double x = log(lam[k]), y = log(err[k]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  double rate = (3.0 * sxy - sx * sy) / (3.0 * sxx - sx * sx);
  printf("  fitted: error ~ lambda^%.3f; at lambda %.4g: %.3e (N 400), %.3e (N 800)\n", rate,
         lam[3], err[3], err_fine);
  assert_true(rate < -0.9);
  for (int k = 2; k < 4; k++)
    assert_true(err[k] < err[k - 1]);
  assert_true(err[3] < 6e-4);
  assert_true(fabs(err_fine - err[3]) < 5e-5);
  free(t);
}

/* The relaxed Hertz pressure of a cylinder (R 1 cm, 1000 N/m) as a table
 * of n points. */
static double *hertz_table(size_t n, double *a0) {
  double er = E0 / (1.0 - NU * NU), R = 0.01, fN = 1000.0;
  double a = sqrt(4.0 * fN * R / (M_PI * er)), p0 = 2.0 * fN / (M_PI * a);
  double *t = malloc(2 * n * sizeof *t);
  assert_non_null(t);
  for (size_t k = 0; k < n; k++) {
    double x = a * (-1.0 + 2.0 * (double)k / (double)(n - 1));
    t[k] = x, t[n + k] = k == 0 || k + 1 == n ? 0.0 : p0 * sqrt(1.0 - x * x / (a * a));
  }
  *a0 = a;
  return t;
}

/* The Hertz pressure of the cylinder imposed as a static pressure, on the
 * same uniform grid (920 cells on [-3, 1.6] a0) as the elastic solve of the
 * cylinder, smooth elastic rubber, moving counter-surface, U from 1 to
 * 1e-3 m/s. Inside the dry contact both rubbers have the same shape; they
 * differ outside it, where the imposed one continues straight and the
 * cylinder curves: a difference that matters less as the film's inlet
 * zone (of width ~ a (h/delta)^(2/3)) shrinks towards the edge, so it falls
 * slowly with speed. Measured (flux, u_min): +6.5 %, +5.3 % at 1 m/s;
 * +3.1, +2.6 % at 0.1; +1.9, +2.0 % at 0.01; +1.7, +1.2 % at 1e-3 (1840
 * cells: +1.3, +1.5 %: the rest is the grid's, the sampled Hertz
 * pressure's square-root edges against the cylinder's discrete contact).
 * Asserted: the flux's difference falls with every decade of speed, and
 * both are within 2.5 % at 1e-3 m/s. */
static void test_hertz_static(void **state) {
  (void)state;
  size_t n = 2001;
  double a0;
  double *t = hertz_table(n, &a0);
  vl_contact_config cfg;
  vl_contact_config_defaults(&cfg);
  cfg.rubber = vl_prony_single(E0, 1.0, 0.1, NU);
  cfg.moving = VL_MOVING_COUNTERFACE;
  cfg.eta_pa_s = ETA;
  cfg.grid = 920, cfg.x_min_a0 = -3.0, cfg.x_max_a0 = 1.6;
  cfg.radius_m = 0.01, cfg.load_n_per_m = 1000.0;
  vl_contact *cyl = NULL, *st = NULL;
  vl_error err;
  assert_int_equal(vl_contact_create(&cfg, &cyl, &err), VL_OK);
  cfg.static_x_m = t, cfg.static_p_pa = t + n, cfg.static_points = n;
  assert_int_equal(vl_contact_static_scales(&cfg, &cfg.load_n_per_m, &cfg.radius_m, &err), VL_OK);
  if (vl_contact_create(&cfg, &st, &err) != VL_OK) fail_msg("%s", err.msg);
  const double v[4] = {1.0, 1e-1, 1e-2, 1e-3};
  double prev = INFINITY;
  for (int k = 0; k < 4; k++) {
    vl_point pc, ps;
    assert_int_equal(vl_contact_solve(cyl, v[k], &pc, &err), VL_OK);
    assert_int_equal(vl_contact_solve(st, v[k], &ps, &err), VL_OK);
    double dq = ps.flux_m2_s / pc.flux_m2_s - 1.0, du = ps.u_min_m / pc.u_min_m - 1.0;
    printf("  U %g m/s: u_min %.5g / %.5g m (%+.2e), flux %.5g / %.5g (%+.2e), mu %.5g / %.5g\n",
           v[k], pc.u_min_m, ps.u_min_m, du, pc.flux_m2_s, ps.flux_m2_s, dq, pc.mu, ps.mu);
    if (k > 0) assert_true(fabs(dq) < prev);
    prev = fabs(dq);
    if (k == 3) assert_true(fabs(dq) < 0.025 && fabs(du) < 0.025);
  }
  vl_contact_free(cyl);
  vl_contact_free(st);
  free(t);
}

/* The static pressure through a scene and `viscolube seal`: the quartic
 * in p.csv (rows in any order, comments), the load and scales from it, no
 * sealed pressure. Symmetric, so both strokes are the same film: asserted
 * 1e-12 on friction, film and flux (the same solve mirrored). The load
 * the friction force counts is the table's integral: F = mu fN with fN
 * = 1066.7 N/m (16/15 p_m b; trapezoids of 801 points, 1e-5). Bad tables
 * are refused naming the table's line; keys that the pressure replaces
 * naming the scene's. */
static const char *pressure_scene(const char *table, const char *extra) {
  static char buf[1024];
  snprintf(buf, sizeof buf,
           "[materials]\ncompound = model-rubber\nfluid = model-1e-1\n"
           "[contact]\npressure_profile_file = %s\nmoving = counterface\n%s"
           "[sweep]\nquantity = v0\nfrom = 1e-3\nto = 1e-2\npoints = 2\n"
           "[effects]\nviscoelastic = off\nfluid = on\n"
           "[numerics]\ngrid = 200\ndomain_a0 = -2, 1.6\ntarget_error = 0.5\n",
           table, extra);
  return buf;
}

static void test_pressure_scene(void **state) {
  (void)state;
  double *t = quartic_table();
  vl_test_text tx = {0};
  vl_test_text_add(&tx, "# the quartic static pressure\nx_m,p_pa\n");
  for (size_t k = TABLE; k-- > 0;)
    vl_test_text_add(&tx, "%.17g, %.17g\n", t[k], t[TABLE + k]);
  vl_test_scratch("p.csv", tx.s);
  free(tx.s);
  free(t);
  const char *scene = vl_test_scratch("p.ini", pressure_scene("p.csv", ""));
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "seal %s --out %s/p --json --quiet", scene, vl_test_dir);
  if (rc != 0) fail_msg("seal exited %d: %s", rc, err);
  const char *keys[3] = {"friction_n_per_m", "u_min_m", "flux_m2_s"};
  for (size_t i = 0; i < 2; i++)
    for (int k = 0; k < 3; k++) {
      double a = vl_test_json_number(out, keys[k], 2 * i),
             b = vl_test_json_number(out, keys[k], 2 * i + 1);
      printf("  point %zu %s: out %.12g, in %.12g\n", i, keys[k], a, b);
      assert_true(a > 0.0 && fabs(b / a - 1.0) < 1e-12);
    }
  double mu = vl_test_json_number(out, "mu", 0),
         f = vl_test_json_number(out, "friction_n_per_m", 0);
  printf("  F / mu = %.8g N/m (16/15 p_m b = %.8g)\n", f / mu, 16.0 / 15.0 * P_MAX * HALF_SPAN);
  assert_true(fabs(f / mu / (16.0 / 15.0 * P_MAX * HALF_SPAN) - 1.0) < 1e-5);
  free(out), free(err);
  static const struct {
    const char *table, *extra, *message;
  } bad[] = {
      {"x_m,p_pa\n-1e-3, 0\n0, -5\n1e-3, 0\n", "", "neg.csv:3: a contact pressure must be >= 0"},
      {"x_m,p_pa\n-1e-3, 0\n0, 5\n1e-3, 2\n", "", "end.csv:4: the pressure must fall to 0"},
      {"x_m,p_pa\n-1e-3, 0\n0, 5\n1e-3, 0\n", "radius_m = 0.01\n",
       "[contact] radius_m: not with pressure_profile_file"},
  };
  const char *names[3] = {"neg.csv", "end.csv", "ok.csv"};
  for (int k = 0; k < 3; k++) {
    vl_test_scratch(names[k], bad[k].table);
    scene = vl_test_scratch("bad.ini", pressure_scene(names[k], bad[k].extra));
    rc = vl_test_run(&out, &err, "seal %s --out %s/bad", scene, vl_test_dir);
    printf("  exit %d: %s", rc, err);
    assert_int_equal(rc, 2);
    assert_non_null(strstr(err, bad[k].message));
    free(out), free(err);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_inverse_hydrodynamics),
      cmocka_unit_test(test_hertz_static),
      cmocka_unit_test_setup(test_pressure_scene, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
