/* Validation of the dry smooth point contact (a ball sliding on a
 * viscoelastic half-space, include/viscolube/point_contact.h) against
 * independent solutions:
 *  - Hertz (elastic; the relaxed and glassy limits of a viscoelastic
 *    rubber at low and high speed): contact radius, peak pressure,
 *    approach, and the order at which the error falls with the cells;
 *  - the Fourier-space solution of the same contact (tests/oracles/
 *    ball_fft.c: the displacement 2 p(q)/(|q| Er(q_x v0)) on a padded FFT
 *    grid, its own active-set solve): the rolling friction within 1 %;
 *  - the signs of docs/MODEL.md section 1: mu_Rc > 0 with one maximum over
 *    speed, the pressure centroid on the inlet side (x < 0);
 *  - the grid convergence of mu_Rc (Richardson).
 * Numbers measured here are in docs/POINT_CONTACT.md section 6. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
/* cmocka.h needs the four above first (own block: not re-sorted) */
#include <cmocka.h>

#include "vl_test_util.h"

#include <gsl/gsl_integration.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ball_fft.h"
#include "point_contact_internal.h"
#include "rheology_internal.h"
#include "viscolube/point_contact.h"

/* A 19.05 mm (3/4 inch) steel ball on a soft rubber, 3 N (scales only:
 * every check is in the dimensionless a0, p0 units). */
#define RADIUS 0.009525
#define LOAD 3.0
#define E0 2.0e6
#define NU 0.5
#define TAU 0.01

static vl_point_contact *make(double einf_over_e0, double cells_per_a0, double half) {
  vl_point_contact_config cfg;
  vl_point_contact_config_defaults(&cfg);
  cfg.rubber = einf_over_e0 > 1.0 ? vl_prony_single(E0, einf_over_e0, TAU, NU)
                                  : (vl_prony){.e_inf_pa = E0, .nu = NU};
  cfg.radius_x_m = cfg.radius_y_m = RADIUS;
  cfg.load_n = LOAD;
  cfg.cells_per_a0 = cells_per_a0;
  if (half > 0.0) cfg.x_half_a0 = cfg.y_max_a0 = half;
  vl_point_contact *c = NULL;
  vl_error err;
  if (vl_point_contact_create(&cfg, &c, &err) != VL_OK) fail_msg("create: %s", err.msg);
  return c;
}

/* Solves at the Deborah number De = v0 tau / a0 (0: v0 = 0). */
static void solve_de(vl_point_contact *c, double de, vl_point *pt) {
  vl_error err;
  double v0 = de * vl_point_contact_a0(c) / TAU;
  if (vl_point_contact_solve(c, v0, pt, &err) != VL_OK) fail_msg("solve: %s", err.msg);
  assert_true(pt->converged);
  assert_true(pt->load_error < 1e-9);
}

/* The Hertz checks of one solve against a modulus ratio Er/Er0 (1:
 * relaxed): relative errors of the radius sqrt(area/pi), of the peak
 * pressure and of the approach. */
typedef struct {
  double radius, peak, approach;
} hertz_err;

static hertz_err hertz_errors(const vl_point_contact *c, const vl_point *pt, double ratio) {
  double a0 = vl_point_contact_a0(c), p0 = vl_point_contact_p0(c);
  double a = a0 * cbrt(1.0 / ratio), p = p0 * cbrt(ratio * ratio); /* a ~ Er^-1/3, p ~ Er^2/3 */
  double delta = -N_VGetArrayPointer(c->y)[c->n] * c->uscale;      /* Hertz: a^2/R */
  hertz_err e = {sqrt(pt->ball.contact_area_m2 / M_PI) / a - 1.0, pt->peak_pressure_pa / p - 1.0,
                 delta / (a * a / RADIUS) - 1.0};
  return e;
}

/* Elastic ball: Hertz within 0.5 % at 16 cells per a0 (radius from the
 * contact area, peak pressure, approach), zero rolling friction on the
 * symmetric grid, and the peak pressure's error falling at second order
 * (measured 1.8-2.0 between 8, 12 and 16 cells; asserted >= 1.5). */
static void test_hertz_elastic(void **state) {
  (void)state;
  const double r[] = {8, 12, 16};
  hertz_err e[3];
  for (size_t k = 0; k < 3; k++) {
    vl_point_contact *c = make(1.0, r[k], 0.0);
    vl_point pt;
    solve_de(c, 0.0, &pt);
    e[k] = hertz_errors(c, &pt, 1.0);
    printf("Hertz r %2.0f: radius %+.2e peak %+.2e approach %+.2e mu_Rc %.1e (%zu cells in "
           "contact, %ld iterations)\n",
           r[k], e[k].radius, e[k].peak, e[k].approach, pt.mu_Rc, pt.ball.cells_in_contact,
           pt.iterations);
    assert_true(fabs(pt.mu_Rc) < 1e-12);
    assert_true(pt.x_centroid_m == 0.0 || fabs(pt.x_centroid_m) < 1e-12 * vl_point_contact_a0(c));
    vl_point_contact_free(c);
  }
  assert_true(fabs(e[2].radius) < 5e-3);
  assert_true(fabs(e[2].peak) < 5e-3);
  assert_true(fabs(e[2].approach) < 5e-3);
  double order = log(fabs(e[0].peak / e[2].peak)) / log(2.0);
  printf("peak pressure error: observed order %.2f (8 -> 16 cells per a0)\n", order);
  assert_true(order >= 1.5);
}

/* A viscoelastic rubber (Einf/E0 = 10) at De = 1e-7 is the relaxed Hertz
 * contact, at De = 1e7 the glassy one (radius 0.464 a0: checked on a
 * domain of 0.6 a0 at 32 cells per a0, 15 cells per glassy radius);
 * within 0.5 %. */
static void test_viscoelastic_limits(void **state) {
  (void)state;
  vl_point pt;
  vl_point_contact *c = make(10.0, 16, 0.0);
  solve_de(c, 1e-7, &pt);
  hertz_err lo = hertz_errors(c, &pt, 1.0);
  vl_point_contact_free(c);
  c = make(10.0, 32, 0.6);
  solve_de(c, 1e7, &pt);
  hertz_err hi = hertz_errors(c, &pt, 10.0);
  vl_point_contact_free(c);
  printf("relaxed limit: radius %+.2e peak %+.2e; glassy: radius %+.2e peak %+.2e\n", lo.radius,
         lo.peak, hi.radius, hi.peak);
  assert_true(fabs(lo.radius) < 5e-3 && fabs(lo.peak) < 5e-3);
  assert_true(fabs(hi.radius) < 5e-3 && fabs(hi.peak) < 5e-3);
}

/* mu_Rc over speed (De = 0.01 ... 100, continued from point to point):
 * positive, one maximum, the centroid on the inlet side. */
static void test_rolling_over_speed(void **state) {
  (void)state;
  const double de[] = {0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0};
  size_t n = sizeof de / sizeof de[0];
  double mu[9];
  vl_point_contact *c = make(10.0, 12, 0.0);
  for (size_t k = 0; k < n; k++) {
    vl_point pt;
    solve_de(c, de[k], &pt);
    mu[k] = pt.mu_Rc * RADIUS / vl_point_contact_a0(c);
    printf("De %6.2f: mu_Rc R/a0 %.5f centroid %+.4f a0, %ld iterations\n", de[k], mu[k],
           pt.x_centroid_m / vl_point_contact_a0(c), pt.iterations);
    assert_true(mu[k] > 0.0);
    assert_true(pt.x_centroid_m < 0.0);
  }
  int turns = 0;
  for (size_t k = 1; k + 1 < n; k++)
    turns += (mu[k] - mu[k - 1] > 0.0) != (mu[k + 1] - mu[k] > 0.0);
  assert_int_equal(turns, 1);
  vl_point_contact_free(c);
}

/* Against the Fourier-space solution of the same contact on the same
 * cells (12 per a0): mu_Rc within 1 %. The two discretisations differ
 * (cell averages against point values of the pressure, a free surface
 * against a periodic one whose period is 40 memory lengths along x and 16
 * grid lengths across): measured -0.24, -0.04 and -0.09 %; with a period
 * of 4 grid lengths across the images moved the reference by 0.6 %. */
static void test_fourier_reference(void **state) {
  (void)state;
  const double de[] = {0.1, 1.0, 3.0};
  double A = 9.0;
  vl_point_contact *c = make(10.0, 12, 0.0);
  for (size_t k = 0; k < 3; k++) {
    vl_point pt;
    solve_de(c, de[k], &pt);
    double mu = pt.mu_Rc * RADIUS / vl_point_contact_a0(c);
    vl_oracle_ball_problem pb = {.nx = c->nx,
                                 .ny = c->ny,
                                 .h = c->h,
                                 .gx = 1.0,
                                 .gy = 1.0,
                                 .n_terms = 1,
                                 .A = &A,
                                 .de = &de[k],
                                 .pad_y = 16.0};
    pb.pad_x = fmax(4.0, 40.0 * de[k] / ((double)c->nx * c->h));
    vl_oracle_ball_solution ref;
    assert_int_equal(vl_oracle_ball_fft_solve(&pb, &ref), 0);
    printf("De %.1f: mu_Rc R/a0 %.5f, Fourier %.5f (%+.2f %%)\n", de[k], mu, ref.mu_R_over_a0,
           100.0 * (mu / ref.mu_R_over_a0 - 1.0));
    assert_true(fabs(mu / ref.mu_R_over_a0 - 1.0) < 0.01);
  }
  vl_point_contact_free(c);
}

/* mu_Rc at De = 1 on 8, 12, 16 and 24 cells per a0 against 32 (measured
 * -0.27, -0.16, +0.003, +0.011 %): within 0.5 % from 12 cells on. The
 * contact's edge crosses the cells differently on each grid, so the
 * difference does not fall at a steady order (at another speed, 10 cells
 * were 0.36 % off and 12 0.05 %): Richardson's extrapolation would
 * amplify that scatter, and the finest grid is the reference. */
static void test_grid_convergence(void **state) {
  (void)state;
  const double r[] = {8, 12, 16, 24, 32};
  double mu[5];
  for (size_t k = 0; k < 5; k++) {
    vl_point_contact *c = make(10.0, r[k], 1.1);
    vl_point pt;
    solve_de(c, 1.0, &pt);
    mu[k] = pt.mu_Rc;
    vl_point_contact_free(c);
  }
  for (size_t k = 0; k < 4; k++) {
    printf("De 1, %2.0f cells per a0: mu_Rc %.6f, %+.3f %% from 32\n", r[k], mu[k],
           100.0 * (mu[k] / mu[4] - 1.0));
    if (k >= 1) assert_true(fabs(mu[k] / mu[4] - 1.0) < 5e-3);
  }
}

/* At low speed the memory shifts the relaxed Hertz contact upstream by
 * s = A b/(1 + A), b = v0 tau (to first order in b/a0: the gap equation
 * Jr0 W - Jinf A b W' = -h0 - f is solved by the relaxed Hertz pressure
 * moved by s), so mu_Rc R/a0 -> (A/(1 + A)) De = 0.9 De for Einf/E0 = 10.
 * The cells resolve this limit slowly: the memory samples the displacement
 * of the piecewise-constant pressure within b of each node, and at the
 * contact's edge that pressure jumps to zero. Measured at De = 1e-3:
 * -14.9, -9.0, -7.1, -6.5, -5.3 % at 8, 12, 16, 20, 24 cells per a0 (order
 * about 0.6). Asserted: the error falls with the cells and is below 8 %
 * at 20 (docs/POINT_CONTACT.md section 6 discusses it). */
static void test_low_speed_limit(void **state) {
  (void)state;
  const double r[] = {12, 20};
  double err[2];
  for (size_t k = 0; k < 2; k++) {
    vl_point_contact *c = make(10.0, r[k], 1.1);
    vl_point pt;
    solve_de(c, 1e-3, &pt);
    err[k] = pt.mu_Rc * RADIUS / vl_point_contact_a0(c) / (0.9 * 1e-3) - 1.0;
    printf("De 1e-3, %2.0f cells per a0: mu_Rc R/a0 / (0.9 De) - 1 = %+.2f %%\n", r[k],
           100.0 * err[k]);
    vl_point_contact_free(c);
  }
  assert_true(err[0] < 0.0 && err[1] < 0.0);
  assert_true(fabs(err[1]) < fabs(err[0]));
  assert_true(fabs(err[1]) < 0.08);
}

/* ---- the Hertz ellipse, computed here apart from the library: the complete
 * elliptic integrals by quadrature, the eccentricity by bisection ---- */

static double ellint_integrand(double t, void *p) {
  double k = *(const double *)p, s = sin(t);
  return sqrt(1.0 - k * k * s * s);
}
static double ellint_k_integrand(double t, void *p) { return 1.0 / ellint_integrand(t, p); }

/* K(k), E(k) by adaptive quadrature over [0, pi/2]. */
static void ellint_quad(double k, double *K, double *E) {
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(200);
  gsl_function fk = {ellint_k_integrand, &k}, fe = {ellint_integrand, &k};
  double err;
  gsl_integration_qags(&fk, 0.0, M_PI / 2, 0.0, 1e-13, 200, ws, K, &err);
  gsl_integration_qags(&fe, 0.0, M_PI / 2, 0.0, 1e-13, 200, ws, E, &err);
  gsl_integration_workspace_free(ws);
}

/* Semi-axes (m) along x and y and the peak pressure of Hertz's ellipse for
 * the gap x^2/(2 Rx) + y^2/(2 Ry) (Johnson, Contact Mechanics, 4.2): with
 * A = 1/(2 Rx) < B = 1/(2 Ry) the major axis a lies along x, e^2 = 1 - b^2/a^2,
 * B/A = ((a/b)^2 E - K)/(K - E), A = 3 W (K - E)/(2 pi Er e^2 a^3). */
static void hertz_ellipse_ref(double rx, double ry, double W, double er, double *ax, double *by,
                              double *p0) {
  double A = 0.5 / fmax(rx, ry), ratio = fmax(rx, ry) / fmin(rx, ry), lo = 1e-6, hi = 1.0 - 1e-12;
  double K, E;
  for (int it = 0; it < 100; it++) {
    double e = 0.5 * (lo + hi);
    ellint_quad(e, &K, &E);
    if ((E / (1.0 - e * e) - K) / (K - E) < ratio)
      lo = e;
    else
      hi = e;
  }
  double e = 0.5 * (lo + hi);
  ellint_quad(e, &K, &E);
  double a = cbrt(3.0 * W * (K - E) / (2.0 * M_PI * er * e * e * A)), b = a * sqrt(1.0 - e * e);
  *ax = rx >= ry ? a : b, *by = rx >= ry ? b : a;
  *p0 = 1.5 * W / (M_PI * a * b);
}

/* An elastic ellipsoid (Ry = 4 Rx: the contact twice as long across as
 * along x) against Hertz's ellipse: semi-axes from the contact's extents
 * within 1 % (their p^2 extrapolation at the edge, biased by about h^2/a),
 * area and peak pressure within 0.5 %, on 16 cells across the shorter
 * semi-axis; the library's own vl_hertz_ellipse to 1e-9. */
static void test_hertz_ellipsoid(void **state) {
  (void)state;
  double rx = RADIUS, ry = 4.0 * RADIUS, er = E0 / (1.0 - NU * NU), a, b, p0, la, lb, lp;
  hertz_ellipse_ref(rx, ry, LOAD, er, &a, &b, &p0);
  assert_int_equal(vl_hertz_ellipse(rx, ry, LOAD, er, &la, &lb, &lp), VL_OK);
  assert_true(fabs(la / a - 1) < 1e-9 && fabs(lb / b - 1) < 1e-9 && fabs(lp / p0 - 1) < 1e-9);
  vl_point_contact_config cfg;
  vl_point_contact_config_defaults(&cfg);
  cfg.rubber = (vl_prony){.e_inf_pa = E0, .nu = NU};
  cfg.radius_x_m = rx, cfg.radius_y_m = ry, cfg.load_n = LOAD;
  vl_point_contact *c = NULL;
  vl_error err;
  assert_int_equal(vl_point_contact_create(&cfg, &c, &err), VL_OK);
  double a0 = vl_point_contact_a0(c);
  vl_point_contact_free(c);
  cfg.cells_per_a0 = 16.0 / (fmin(a, b) / a0);
  cfg.x_half_a0 = 1.25 * a / a0, cfg.y_max_a0 = 1.25 * b / a0;
  assert_int_equal(vl_point_contact_create(&cfg, &c, &err), VL_OK);
  vl_point pt;
  assert_int_equal(vl_point_contact_solve(c, 0.0, &pt, &err), VL_OK);
  double ea = pt.ball.contact_length_m / (2 * a) - 1, eb = pt.ball.contact_breadth_m / (2 * b) - 1;
  double ep = pt.peak_pressure_pa / p0 - 1, es = pt.ball.contact_area_m2 / (M_PI * a * b) - 1;
  printf("ellipsoid Ry/Rx = 4 (b/a = %.3f, %zu cells): a %+.2e b %+.2e area %+.2e peak %+.2e\n",
         b / a, vl_point_contact_cells(c), ea, eb, es, ep);
  assert_int_equal(pt.ball.geometry, VL_GEOMETRY_ELLIPSOID);
  assert_true(fabs(ea) < 0.01 && fabs(eb) < 0.01);
  assert_true(fabs(es) < 5e-3 && fabs(ep) < 5e-3);
  vl_point_contact_free(c);
}

/* A bad configuration is refused, naming the field. */
static void test_bad_config(void **state) {
  (void)state;
  vl_point_contact_config cfg;
  vl_point_contact_config_defaults(&cfg);
  cfg.rubber = vl_prony_single(E0, 10.0, TAU, NU);
  cfg.radius_x_m = cfg.radius_y_m = RADIUS;
  cfg.load_n = LOAD;
  vl_point_contact *c = NULL;
  vl_error err;
  struct {
    const char *field;
    double *at, bad;
  } cases[] = {{"radius_x_m", &cfg.radius_x_m, -1.0},
               {"radius_y_m", &cfg.radius_y_m, NAN},
               {"load_n", &cfg.load_n, 0.0},
               {"sigma_s_pa", &cfg.sigma_s_pa, -1.0},
               {"cells_per_a0", &cfg.cells_per_a0, 2.0},
               {"x_half_a0", &cfg.x_half_a0, 0.0},
               {"cells", &cfg.cells_per_a0, 200.0}};
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    double keep = *cases[k].at;
    *cases[k].at = cases[k].bad;
    assert_int_equal(vl_point_contact_create(&cfg, &c, &err), VL_EINPUT);
    assert_null(c);
    assert_non_null(strstr(err.msg, cases[k].field));
    *cases[k].at = keep;
  }
  vl_point pt;
  assert_int_equal(vl_point_contact_create(&cfg, &c, &err), VL_OK);
  assert_int_equal(vl_point_contact_solve(c, -1.0, &pt, &err), VL_EINPUT);
  assert_false(pt.converged);
  vl_point_contact_free(c);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_hertz_elastic),      cmocka_unit_test(test_viscoelastic_limits),
      cmocka_unit_test(test_rolling_over_speed), cmocka_unit_test(test_fourier_reference),
      cmocka_unit_test(test_grid_convergence),   cmocka_unit_test(test_low_speed_limit),
      cmocka_unit_test(test_hertz_ellipsoid),    cmocka_unit_test(test_bad_config),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
