/* Tests of the test oracles themselves (tests/oracles): Hunter's exact
 * viscoelastic rolling solution and Persson's linear-order formula.
 *
 * The decisive check is test_hunter_gap_consistency: the oracle's pressure is
 * put back into the displacement integral of docs/MODEL.md §3 (memory term
 * included) by direct adaptive quadrature, and the gap must be flat inside
 * the contact and open outside. Nothing here calls the vl_ library.
 *
 * Units: x in a0, p in p0, gap in a0^2/R (a0, p0: Hertz with Er0). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "vl_test_util.h"

#include "hunter.h"
#include "persson_linear.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_sf_expint.h>
#include <math.h>
#include <stdio.h>
#include <time.h>

/* ---------------------------------------------------------------- helpers */

/* Memory kernel k(y) = \int_0^inf e^{-s} log|y - De s| ds in closed form:
 * y < 0: log|y| + e^z E1(z); y > 0: log y - e^{-z} Ei(z), z = |y|/De
 * (from \int_0^inf e^{-s} log(1 + s/z) ds = e^z E1(z) and the principal
 * value \int_0^inf e^{-s} log|1 - s/z| ds = -e^{-z} Ei(z));
 * k(0) = log De - gamma. Checked against brute force in test_memory_kernel. */
static double memory_kernel(double y, double De) {
  if (y == 0.0) return log(De) - M_EULER;
  const double z = fabs(y) / De;
  if (y < 0.0) return log(-y) + gsl_sf_expint_E1_scaled(z);
  return log(y) - gsl_sf_expint_Ei_scaled(z);
}

typedef struct {
  double y, De;
} kern_params;

static double kern_brute_integrand(double s, void *p) {
  const kern_params *kp = p;
  return exp(-s) * log(fabs(kp->y - kp->De * s));
}

/* The same kernel by adaptive quadrature (log singularity at s = y/De). */
static double memory_kernel_brute(double y, double De) {
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(2000);
  kern_params kp = {y, De};
  gsl_function f = {kern_brute_integrand, &kp};
  double r = 0.0, e = 0.0, total = 0.0;
  const double sstar = y / De;
  if (sstar > 0.0 && sstar < 60.0) {
    assert_int_equal(gsl_integration_qags(&f, 0.0, sstar, 1e-14, 1e-12, 2000, ws, &r, &e), 0);
    total += r;
    assert_int_equal(gsl_integration_qags(&f, sstar, sstar + 1.0, 1e-14, 1e-12, 2000, ws, &r, &e),
                     0);
    total += r;
    assert_int_equal(gsl_integration_qagiu(&f, sstar + 1.0, 1e-14, 1e-12, 2000, ws, &r, &e), 0);
    total += r;
  } else {
    /* Singular point beyond s = 60 (weight e^-60) or absent. */
    assert_int_equal(gsl_integration_qagiu(&f, 0.0, 1e-14, 1e-12, 2000, ws, &r, &e), 0);
    total = r;
  }
  gsl_integration_workspace_free(ws);
  return total;
}

typedef struct {
  const vl_oracle_hunter_profile *pr;
  double c, h; /* contact centre and half width */
  double x;    /* field point */
  double A, De;
  int moment; /* 0: pressure, 1: pressure * x, 2: displacement kernel */
} disp_params;

/* Integrand in theta, x' = c - h cos(theta) (theta = 0 at the inlet edge);
 * the sqrt edge behaviour of p becomes smooth in theta. */
static double disp_integrand(double theta, void *params) {
  const disp_params *dp = params;
  const double xs = dp->c - dp->h * cos(theta);
  const double jac = dp->h * sin(theta);
  const double p = vl_oracle_hunter_profile_pressure(dp->pr, xs);
  if (dp->moment == 0) return p * jac;
  if (dp->moment == 1) return p * xs * jac;
  const double y = dp->x - xs;
  if (y == 0.0) return 0.0; /* integrable log point, measure zero */
  return p * jac * (log(fabs(y)) + dp->A * memory_kernel(y, dp->De));
}

/* \int over the contact of the selected integrand; splits at the field
 * point (log singularity) when it lies inside. */
static double contact_integral(disp_params *dp, gsl_integration_workspace *ws) {
  gsl_function f = {disp_integrand, dp};
  double r = 0.0, e = 0.0, total = 0.0;
  const double tx = (dp->c - dp->x) / dp->h; /* cos(theta_x) */
  if (dp->moment == 2 && tx > -1.0 && tx < 1.0) {
    const double thx = acos(tx);
    int st = gsl_integration_qags(&f, 0.0, thx, 1e-13, 1e-12, 4000, ws, &r, &e);
    assert_true(st == GSL_SUCCESS || st == GSL_EROUND);
    total += r;
    st = gsl_integration_qags(&f, thx, M_PI, 1e-13, 1e-12, 4000, ws, &r, &e);
    assert_true(st == GSL_SUCCESS || st == GSL_EROUND);
    total += r;
  } else {
    int st = gsl_integration_qags(&f, 0.0, M_PI, 1e-13, 1e-12, 4000, ws, &r, &e);
    assert_true(st == GSL_SUCCESS || st == GSL_EROUND);
    total = r;
  }
  return total;
}

/* Gap minus h0, v(x) = x^2/2 + w(x), with (docs/MODEL.md §3 in a0, p0, a0^2/R;
 * 2 p0 R/(pi Er_inf a0) = 1/(pi (1+A)))
 * w(x) = -(1/(pi (1+A))) \int p(x') [log|x-x'| + A k(x-x')] dx'. */
static double gap_v(disp_params *dp, gsl_integration_workspace *ws, double x) {
  dp->x = x;
  dp->moment = 2;
  const double I = contact_integral(dp, ws);
  return 0.5 * x * x - I / (M_PI * (1.0 + dp->A));
}

static double elapsed(clock_t t0) { return (double)(clock() - t0) / CLOCKS_PER_SEC; }

/* ------------------------------------------------------------------ tests */

/* Closed form of the memory kernel against brute-force quadrature. */
static void test_memory_kernel(void **state) {
  (void)state;
  const double ys[] = {-3.0, -0.2, -1e-3, 1e-3, 0.05, 0.7, 2.5};
  const double des[] = {0.01, 0.3, 1.3, 10.0};
  double worst = 0.0;
  for (size_t i = 0; i < sizeof ys / sizeof *ys; i++)
    for (size_t j = 0; j < sizeof des / sizeof *des; j++) {
      double a = memory_kernel(ys[i], des[j]), b = memory_kernel_brute(ys[i], des[j]);
      worst = fmax(worst, fabs(a - b));
    }
  printf("  memory kernel closed form vs quadrature: max abs diff %.2e\n", worst);
  assert_true(worst < 1e-10); /* quadrature tolerance 1e-12 rel, 1e-14 abs */
}

/* Persson's integral by quadrature against its closed form
 * 1/2 - I1(1/De) K1(1/De) (GR 6.535). The closed form cancels for De >> 1
 * (relative error ~ 4 eps De^2/log De), hence the looser bound there. */
static void test_persson_quadrature_vs_closed(void **state) {
  (void)state;
  double worst = 0.0;
  for (int k = -4; k <= 2; k++) {
    double de = pow(10.0, k);
    worst = fmax(worst, vl_test_rel(vl_oracle_persson_linear_mu(de, 10.0),
                                    vl_oracle_persson_linear_mu_closed(de, 10.0)));
  }
  printf("  Persson quadrature vs closed form, De 1e-4..1e2: max rel %.2e\n", worst);
  assert_true(worst < 1e-12);
  double big = vl_test_rel(vl_oracle_persson_linear_mu(1e4, 10.0),
                           vl_oracle_persson_linear_mu_closed(1e4, 10.0));
  printf("  at De = 1e4: rel %.2e (closed form cancellation)\n", big);
  assert_true(big < 1e-7);
  /* Low-speed slope: the closed form expands as A De/(1+A) (1 - De + ...). */
  for (int k = -4; k <= -3; k++) {
    double de = pow(10.0, k);
    double r = vl_oracle_persson_linear_mu(de, 10.0) / (0.9 * de);
    assert_true(fabs(r - (1.0 - de)) < 2.0 * de * de);
  }
  assert_true(isnan(vl_oracle_persson_linear_mu(-1.0, 10.0)));
  assert_true(isnan(vl_oracle_persson_linear_mu(1.0, 0.5)));
}

/* Low-speed slope mu R/a0 -> (A/(1+A)) De. The next order is a relative
 * correction linear in De: -De in the small-loss limit (Persson's closed
 * form above), and in Hunter's solution of magnitude between De/2 and De for
 * any A. So |ratio - 1| <= 1.05 De, and the error must drop tenfold from
 * De = 1e-3 to 1e-4 (first order, not a floor). */
static void test_hunter_low_speed_slope(void **state) {
  (void)state;
  const double ratios[] = {1.05, 10.0, 100.0};
  for (size_t i = 0; i < 3; i++) {
    const double A = ratios[i] - 1.0;
    double err[2];
    for (int k = 0; k < 2; k++) {
      const double de = k == 0 ? 1e-4 : 1e-3;
      vl_oracle_hunter_solution s;
      assert_int_equal(vl_oracle_hunter_solve(de, ratios[i], &s), 0);
      assert_true(s.converged);
      err[k] = s.mu_R_over_a0 / (A / (1.0 + A) * de) - 1.0;
      printf("  Einf/E0 %6.2f De %6.0e: mu R/a0 = %.10e, relative deviation from slope %+.3e (%.3f "
             "De)\n",
             ratios[i], de, s.mu_R_over_a0, err[k], err[k] / de);
      assert_true(err[k] < 0.0);
      assert_true(fabs(err[k]) <= 1.05 * de);
    }
    const double order = err[1] / err[0];
    assert_true(order > 8.0 && order < 12.0);
  }
}

/* Elastic limits (docs/VALIDATION.md §1): De -> 0 gives Hertz with E0 (half width
 * 1, centred, p_max = 1); De -> inf gives Hertz with Einf (half width
 * sqrt(E0/Einf), p_max sqrt(Einf/E0)), mu -> 0. Tolerances: O(De) at low
 * speed (centre shift and width change are first order in De); at high speed
 * the glassy limit is approached like log(De)/De: Persson's linear form
 * gives mu R/a0 ~ (A/(1+A)) (log(2 De) - gamma + 1/4)/(2 De), and Hunter's
 * departure from Hertz-Einf is bounded by a few times that. */
static void test_hunter_elastic_limits(void **state) {
  (void)state;
  const double ratios[] = {1.05, 10.0, 100.0};
  for (size_t i = 0; i < 3; i++) {
    const double r = ratios[i], A = r - 1.0;
    vl_oracle_hunter_solution s;
    const double lo = 1e-4;
    assert_int_equal(vl_oracle_hunter_solve(lo, r, &s), 0);
    printf("  Einf/E0 %6.2f De 1e-4: half width %.8f centre %+.3e p_max %.8f\n", r,
           s.half_width_over_a0, s.centre_over_a0, s.p_max_over_p0);
    assert_true(fabs(s.half_width_over_a0 - 1.0) < lo);
    assert_true(fabs(s.centre_over_a0) < lo);
    assert_true(fabs(s.p_max_over_p0 - 1.0) < lo);
    /* Profile against Hertz-E0 in the interior (the sqrt edges amplify a
     * centre shift d to ~sqrt(d) there). */
    for (int k = -8; k <= 8; k++) {
      const double x = 0.1 * k;
      assert_true(fabs(vl_oracle_hunter_pressure(&s, x) - vl_oracle_hertz_pressure(1.0, x)) <
                  10 * lo);
    }

    const double hi = 1e4;
    assert_int_equal(vl_oracle_hunter_solve(hi, r, &s), 0);
    const double scale = A / (1.0 + A) * (log(2.0 * hi) - M_EULER + 0.25) / (2.0 * hi);
    printf("  Einf/E0 %6.2f De 1e4: half width %.8f (glassy %.8f) centre %+.3e mu R/a0 %.3e "
           "(log(De)/De scale %.3e)\n",
           r, s.half_width_over_a0, 1.0 / sqrt(r), s.centre_over_a0, s.mu_R_over_a0, scale);
    assert_true(fabs(s.half_width_over_a0 * sqrt(r) - 1.0) < 2.0 * scale);
    assert_true(fabs(s.centre_over_a0) < 2.0 * scale);
    assert_true(s.mu_R_over_a0 > 0.0 && s.mu_R_over_a0 < 2.0 * scale);
    assert_true(fabs(s.p_max_over_p0 / sqrt(r) - 1.0) < 2.0 * scale);
  }
}

static double neg_mu_hunter(double lnde, void *p) {
  vl_oracle_hunter_solution s;
  if (vl_oracle_hunter_solve(exp(lnde), *(const double *)p, &s) != 0) return NAN;
  return -s.mu_R_over_a0;
}

static double neg_mu_persson(double lnde, void *p) {
  return -vl_oracle_persson_linear_mu(exp(lnde), *(const double *)p);
}

/* Maximum over De by Brent on log De; returns the location, value in *mu. */
static double find_peak(double (*f)(double, void *), double ratio, double guess, double *mu) {
  gsl_function F = {f, &ratio};
  gsl_min_fminimizer *m = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
  assert_non_null(m);
  assert_int_equal(gsl_min_fminimizer_set(m, &F, log(guess), log(0.2), log(20.0)), 0);
  for (int it = 0; it < 100; it++) {
    assert_int_equal(gsl_min_fminimizer_iterate(m), 0);
    if (gsl_min_test_interval(gsl_min_fminimizer_x_lower(m), gsl_min_fminimizer_x_upper(m), 1e-7,
                              0.0) == GSL_SUCCESS)
      break;
  }
  double x = exp(gsl_min_fminimizer_x_minimum(m));
  *mu = -gsl_min_fminimizer_f_minimum(m);
  gsl_min_fminimizer_free(m);
  return x;
}

/* docs/VALIDATION.md §2-3: for Einf/E0 = 10 the maximum of mu R/a0 lies near
 * De ~ 1.3 (tau the retardation time; 0.13 would mean the relaxation time
 * was used), with the contact strongly shifted toward the inlet, and
 * Persson's linear form (a = a0) underestimates the peak. */
static void test_hunter_peak(void **state) {
  (void)state;
  gsl_set_error_handler_off();
  double mu_h = 0.0, mu_p = 0.0;
  const double de_h = find_peak(neg_mu_hunter, 10.0, 1.3, &mu_h);
  const double de_p = find_peak(neg_mu_persson, 10.0, 1.0, &mu_p);
  printf("  Einf/E0 = 10: Hunter peak mu R/a0 = %.8f at De = %.6f\n", mu_h, de_h);
  printf("                Persson-linear peak mu R/a0 = %.8f at De = %.6f\n", mu_p, de_p);
  assert_true(de_h > 1.0 && de_h < 1.7);
  assert_true(mu_p < mu_h);
  vl_oracle_hunter_solution s;
  assert_int_equal(vl_oracle_hunter_solve(de_h, 10.0, &s), 0);
  printf("  at the peak: c1 %.6f c2 %.6f centre %.6f half width %.6f p_max %.6f at x %.6f\n",
         s.c1_over_a0, s.c2_over_a0, s.centre_over_a0, s.half_width_over_a0, s.p_max_over_p0,
         s.x_pmax_over_a0);
  assert_true(s.centre_over_a0 < -0.5 * s.half_width_over_a0);

  printf("  Einf/E0 = 10 table:\n  %8s %14s %14s %12s %12s %10s\n", "De", "Hunter", "Persson-lin",
         "centre", "half width", "t/solve");
  const double des[] = {0.01, 0.1, 1.0, 10.0, 100.0};
  for (size_t i = 0; i < 5; i++) {
    clock_t t0 = clock();
    assert_int_equal(vl_oracle_hunter_solve(des[i], 10.0, &s), 0);
    double t = elapsed(t0);
    printf("  %8.3g %14.10f %14.10f %12.6f %12.6f %9.1es\n", des[i], s.mu_R_over_a0,
           vl_oracle_persson_linear_mu(des[i], 10.0), s.centre_over_a0, s.half_width_over_a0, t);
  }
}

/* Small loss: Hunter and Persson-linear are both exact to first order in A,
 * so their relative difference is O(A): bounded by A over De in [1e-2, 1e2],
 * and it must shrink about in proportion to A (Einf/E0 1.05 -> 1.01). */
static void test_small_loss_agreement(void **state) {
  (void)state;
  const double ratios[] = {1.05, 1.01};
  double worst[2] = {0.0, 0.0}, at[2] = {0.0, 0.0};
  for (int k = 0; k < 2; k++) {
    for (int i = 0; i <= 40; i++) {
      const double de = pow(10.0, -2.0 + 0.1 * i);
      vl_oracle_hunter_solution s;
      assert_int_equal(vl_oracle_hunter_solve(de, ratios[k], &s), 0);
      const double e = vl_test_rel(s.mu_R_over_a0, vl_oracle_persson_linear_mu(de, ratios[k]));
      if (e > worst[k]) {
        worst[k] = e;
        at[k] = de;
      }
    }
    printf("  Einf/E0 = %.2f: max |Hunter/Persson - 1| over De 1e-2..1e2 = %.3e (at De = %.3g)\n",
           ratios[k], worst[k], at[k]);
    assert_true(worst[k] < ratios[k] - 1.0);
  }
  const double scaling = worst[0] / worst[1];
  printf("  ratio of the two differences %.2f (A ratio 5)\n", scaling);
  assert_true(scaling > 4.0 && scaling < 6.0);
}

/* The real proof: put the oracle's pressure into the displacement integral
 * (memory term included) by direct quadrature. Checks (a) load, (b) mu from
 * \int p x, (c) gap flat on the contact and (d) open outside, (e) p >= 0.
 * Tolerances come from the quadrature (1e-12 relative requested on O(1)
 * integrals): 1e-11 for the integrals of p, 1e-10 a0^2/R for the gap
 * spread (both measured ~1e-14). */
static void check_consistency(double de, double ratio) {
  vl_oracle_hunter_solution s;
  clock_t t0 = clock();
  assert_int_equal(vl_oracle_hunter_solve(de, ratio, &s), 0);
  const double tsolve = elapsed(t0);
  vl_oracle_hunter_profile *pr = vl_oracle_hunter_profile_new(&s);
  assert_non_null(pr);
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(4000);
  disp_params dp = {pr, s.centre_over_a0, s.half_width_over_a0, 0.0, ratio - 1.0, de, 0};
  const double c1 = s.c1_over_a0, c2 = s.c2_over_a0, h = s.half_width_over_a0;

  dp.moment = 0;
  const double load = contact_integral(&dp, ws); /* must be fN/(p0 a0) = pi/2 */
  dp.moment = 1;
  const double mu = -(2.0 / M_PI) * contact_integral(&dp, ws);
  const double e_load = fabs(load / M_PI_2 - 1.0), e_mu = fabs(mu - s.mu_R_over_a0);

  /* Inside: t from -0.9999 to 0.9999 (clustered near the edges). */
  double vmin = INFINITY, vmax = -INFINITY, vsum = 0.0;
  const int nin = 25;
  for (int i = 0; i < nin; i++) {
    const double t = -0.9999 * cos(M_PI * i / (nin - 1));
    const double v = gap_v(&dp, ws, s.centre_over_a0 + h * t);
    vmin = fmin(vmin, v);
    vmax = fmax(vmax, v);
    vsum += v;
  }
  const double vc = vsum / nin; /* = -h0 */
  /* Outside: the gap must open, like d^{3/2} near the edges. */
  double open_min = INFINITY;
  const double ds[] = {1e-3, 1e-2, 0.1, 0.5, 1.0};
  for (size_t i = 0; i < sizeof ds / sizeof *ds; i++) {
    const double gin = gap_v(&dp, ws, c1 - ds[i] * h) - vc;
    const double gout = gap_v(&dp, ws, c2 + ds[i] * h) - vc;
    open_min = fmin(open_min, fmin(gin, gout) / pow(ds[i], 1.5));
    assert_true(gin > 0.0 && gout > 0.0);
  }
  double pmin = INFINITY;
  for (int i = 1; i < 2000; i++)
    pmin = fmin(
        pmin, vl_oracle_hunter_profile_pressure(pr, s.centre_over_a0 - h * cos(M_PI * i / 2000.0)));

  printf("  De %5.3g Einf/E0 %5.1f: mu R/a0 %.8f, load err %.1e, mu err %.1e, gap spread in "
         "contact %.1e a0^2/R,"
         " min gap/d^1.5 outside %.3f, min p %.1e, solve %.1e s\n",
         de, ratio, s.mu_R_over_a0, e_load, e_mu, vmax - vmin, open_min, pmin, tsolve);
  assert_true(e_load < 1e-11);
  assert_true(e_mu < 1e-11);
  assert_true(vmax - vmin < 1e-10);
  assert_true(pmin > -1e-12);
  /* Sign convention (docs/MODEL.md §1): contact on the inlet side, mu > 0. */
  assert_true(s.centre_over_a0 < 0.0 && s.mu_R_over_a0 > 0.0 && s.x_pmax_over_a0 < 0.0);
  gsl_integration_workspace_free(ws);
  vl_oracle_hunter_profile_free(pr);
}

static void test_hunter_gap_consistency(void **state) {
  (void)state;
  gsl_set_error_handler_off();
  check_consistency(0.1, 10.0);
  check_consistency(1.3, 10.0);
  check_consistency(10.0, 10.0);
  check_consistency(0.3, 100.0);  /* sharp inlet boundary layer */
  check_consistency(0.01, 100.0); /* thin layer, ~1000 Bessel terms */
  check_consistency(1.0, 1.05);
  check_consistency(100.0, 2.0); /* near glassy */
}

/* A control for the consistency check: a wrong memory condition (the exact
 * solution with De perturbed by 1 % in the kernel only) must be caught. */
static void test_consistency_check_detects_error(void **state) {
  (void)state;
  gsl_set_error_handler_off();
  vl_oracle_hunter_solution s;
  assert_int_equal(vl_oracle_hunter_solve(1.3, 10.0, &s), 0);
  vl_oracle_hunter_profile *pr = vl_oracle_hunter_profile_new(&s);
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(4000);
  disp_params dp = {pr, s.centre_over_a0, s.half_width_over_a0, 0.0, 9.0, 1.3 * 1.01, 0};
  double vmin = INFINITY, vmax = -INFINITY;
  for (int i = 0; i < 9; i++) {
    const double v = gap_v(&dp, ws, s.centre_over_a0 + s.half_width_over_a0 * (-0.99 + 0.2475 * i));
    vmin = fmin(vmin, v);
    vmax = fmax(vmax, v);
  }
  printf("  gap spread with a 1%% wrong kernel: %.2e a0^2/R\n", vmax - vmin);
  assert_true(vmax - vmin > 1e-4);
  gsl_integration_workspace_free(ws);
  vl_oracle_hunter_profile_free(pr);
}

/* Sign convention and basic API behaviour. */
static void test_hunter_sign_and_api(void **state) {
  (void)state;
  vl_oracle_hunter_solution s;
  assert_int_equal(vl_oracle_hunter_solve(1.0, 10.0, &s), 0);
  assert_true(s.converged);
  assert_true(s.centre_over_a0 < 0.0); /* contact on the inlet side */
  assert_true(s.x_pmax_over_a0 < 0.0); /* pressure peak at the inlet */
  assert_true(s.mu_R_over_a0 > 0.0);   /* resists the motion */
  assert_true(s.c1_over_a0 < s.c2_over_a0);
  assert_true(vl_oracle_hunter_pressure(&s, s.c1_over_a0 - 0.01) == 0.0);
  assert_true(vl_oracle_hunter_pressure(&s, s.c2_over_a0 + 0.01) == 0.0);
  assert_true(vl_oracle_hunter_pressure(&s, s.centre_over_a0) > 0.0);
  assert_int_equal(vl_oracle_hunter_solve(0.0, 10.0, &s), -1);
  assert_int_equal(vl_oracle_hunter_solve(1.0, 1.0, &s), -1);
  assert_int_equal(vl_oracle_hunter_solve(NAN, 10.0, &s), -1);
  /* Whole advertised range solves. */
  const double ratios[] = {1.01, 2.0, 10.0, 100.0};
  for (size_t i = 0; i < 4; i++)
    for (int k = -4; k <= 4; k++) {
      int rc = vl_oracle_hunter_solve(pow(10.0, k), ratios[i], &s);
      assert_int_equal(rc, 0);
      assert_true(s.mu_R_over_a0 > 0.0 && s.half_width_over_a0 <= 1.0 &&
                  s.half_width_over_a0 >= 1.0 / sqrt(ratios[i]));
    }
}

int main(void) {
  gsl_set_error_handler_off();
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_memory_kernel),
      cmocka_unit_test(test_persson_quadrature_vs_closed),
      cmocka_unit_test(test_hunter_sign_and_api),
      cmocka_unit_test(test_hunter_low_speed_slope),
      cmocka_unit_test(test_hunter_elastic_limits),
      cmocka_unit_test(test_hunter_peak),
      cmocka_unit_test(test_small_loss_agreement),
      cmocka_unit_test(test_hunter_gap_consistency),
      cmocka_unit_test(test_consistency_check_detects_error),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
