/* Validation of the dry contact solver against exact solutions:
 * Hertz (elastic limits), Hunter's viscoelastic rolling solution and
 * Persson's linear-order formula (docs/VALIDATION.md sections 1-3), plus the
 * seed's fig03 statements for rough surfaces. Oracles live in tests/oracles
 * and share no code with the solver. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "contact_test.h"
#include "hunter.h"
#include "persson_internal.h"
#include "persson_linear.h"
#include "rheology_internal.h"
#include "sweep_internal.h"
#include "viscolube/contact.h"
#include "viscolube/persson.h"
#include "viscolube/sweep.h"
#include "vl_test_util.h"

/* The seed's model rubber and cylinder (docs/CASES.md fig03). */
#define E0 3.6e6
#define TAU 0.1
#define NU 0.5
#define RADIUS 0.01
#define LOAD 1000.0

static vl_contact *make_contact(double ratio, size_t grid, const vl_persson *rough) {
  vl_contact_config cfg;
  vl_contact_config_defaults(&cfg);
  cfg.rubber = vl_prony_single(E0, ratio, TAU, NU);
  cfg.radius_m = RADIUS;
  cfg.load_n_per_m = LOAD;
  cfg.grid = grid;
  cfg.roughness = rough;
  cfg.x_min_a0 = -1.5, cfg.x_max_a0 = 1.5;
  if (rough) cfg.x_min_a0 = -1.8, cfg.x_max_a0 = 1.8;
  vl_contact *c = NULL;
  vl_error err;
  if (vl_contact_create(&cfg, &c, &err) != VL_OK) fail_msg("create: %s", err.msg);
  return c;
}

/* Sweeps Deborah numbers de[0..n-1] (increasing) by continuation. */
static void sweep_deborah(vl_contact *c, size_t n, const double *de, vl_point *pts) {
  double *v = malloc(n * sizeof *v);
  for (size_t i = 0; i < n; i++)
    v[i] = de[i] * vl_contact_a0(c) / TAU;
  vl_error err;
  vl_sweep_stats st;
  assert_int_equal(vl_sweep_run(c, n, v, NULL, pts, NULL, NULL, &st, &err), VL_OK);
  free(v);
}

static double deborah_of(const vl_contact *c, double v0) { return v0 * TAU / vl_contact_a0(c); }

/* Effective half-width 2 sqrt(<(x - xc)^2>) of the pressure (exact for Hertz:
 * \int p x^2 / \int p = a^2/4), from the fields; cells carry their own
 * variance delta^2/12. */
static void pressure_moments(const vl_contact *c, double *half_width, double *pmax) {
  size_t n = vl_contact_grid(c);
  double *buf = calloc(5 * n, sizeof *buf);
  vl_fields f = {n, buf, buf + n, buf + 2 * n, buf + 3 * n, buf + 4 * n, NULL, NULL};
  vl_contact_fields(c, &f);
  double s0 = 0, s1 = 0, s2 = 0, pm = 0, dx = f.x_m[1] - f.x_m[0];
  for (size_t i = 0; i < n; i++) {
    double p = f.p_c_pa[i] + f.p_f_pa[i], x = f.x_m[i];
    s0 += p, s1 += p * x, s2 += p * (x * x + dx * dx / 12.0);
    pm = fmax(pm, p);
  }
  double xc = s1 / s0;
  *half_width = 2.0 * sqrt(s2 / s0 - xc * xc) / vl_contact_a0(c);
  *pmax = pm / vl_contact_p0(c);
  free(buf);
}

/* docs/VALIDATION.md 1: Hertz with E0 at v0 tau/a0 = 1e-4, with Einf at 1e4.
 * Tolerance 0.5 % (the issue's) at the default grid. */
static void test_elastic_limits(void **state) {
  (void)state;
  vl_contact *c = make_contact(10.0, 512, NULL);
  double de[] = {1e-4};
  vl_point pt;
  sweep_deborah(c, 1, de, &pt);
  assert_true(pt.converged);
  double a, pm;
  pressure_moments(c, &a, &pm);
  printf("  De = 1e-4: half-width %.6f a0 (Hertz E0: 1), p_max %.6f p0 (1)\n", a, pm);
  assert_true(fabs(a - 1.0) < 5e-3);
  assert_true(fabs(pm - 1.0) < 5e-3);
  /* low-speed slope mu R/a0 -> (A/(1+A)) De (docs/VALIDATION.md 2); the next
   * order is ~0.55 De relative, far below the 1 % allowed here */
  assert_true(vl_test_rel(pt.mu_Rc * RADIUS / vl_contact_a0(c), 0.9 * 1e-4) < 1e-2);

  double ramp[] = {1e-2, 1e-1, 1, 10, 100, 1e3, 1e4};
  vl_point pts[7];
  sweep_deborah(c, 7, ramp, pts);
  assert_true(pts[6].converged);
  pressure_moments(c, &a, &pm);
  double ah = 1.0 / sqrt(10.0), ph = sqrt(10.0);
  printf("  De = 1e4: half-width %.6f a0 (Hertz Einf: %.6f), p_max %.6f p0 (%.6f)\n", a, ah, pm,
         ph);
  assert_true(fabs(a / ah - 1.0) < 5e-3);
  assert_true(fabs(pm / ph - 1.0) < 5e-3);
  vl_contact_free(c);
}

/* docs/VALIDATION.md 2: mu_Rc against Hunter's exact solution, within 1 % over
 * v0 tau/a0 in [1e-2, 1e2] at the default grid (512). */
static void test_hunter_default_grid(void **state) {
  (void)state;
  vl_contact *c = make_contact(10.0, 512, NULL);
  enum { N = 17 };
  double de[N];
  vl_point pts[N];
  for (int i = 0; i < N; i++)
    de[i] = pow(10.0, -2.0 + 4.0 * i / (N - 1));
  sweep_deborah(c, N, de, pts);
  double worst = 0.0;
  printf("  %10s %12s %12s %10s\n", "De", "mu R/a0", "Hunter", "rel.err");
  for (int i = 0; i < N; i++) {
    assert_true(pts[i].converged);
    vl_oracle_hunter_solution h;
    assert_int_equal(vl_oracle_hunter_solve(de[i], 10.0, &h), 0);
    double mu = pts[i].mu_Rc * RADIUS / vl_contact_a0(c);
    double e = vl_test_rel(mu, h.mu_R_over_a0);
    printf("  %10.4g %12.6g %12.6g %10.2e\n", de[i], mu, h.mu_R_over_a0, e);
    worst = fmax(worst, e);
    /* sign convention: the contact sits on the inlet side (x < 0) */
    assert_true(pts[i].x_centroid_m < 0.0);
    assert_true(pts[i].mu_Rc > 0.0);
  }
  printf("  worst relative error at grid 512: %.3e\n", worst);
  assert_true(worst < 1e-2);
  vl_contact_free(c);
}

/* Error vs grid at three Deborah numbers around the peak; the finest grid
 * must be within 0.1 % of Hunter (the fine-grid target). */
static void test_hunter_grid_convergence(void **state) {
  (void)state;
  double de[] = {0.1, 1.3, 10.0};
  size_t grids[] = {128, 256, 512, 1024, 2048};
  double href[3];
  for (int k = 0; k < 3; k++) {
    vl_oracle_hunter_solution h;
    assert_int_equal(vl_oracle_hunter_solve(de[k], 10.0, &h), 0);
    href[k] = h.mu_R_over_a0;
  }
  printf("  %6s %12s %12s %12s\n", "grid", "err De=0.1", "err De=1.3", "err De=10");
  double finest[3] = {0};
  for (size_t g = 0; g < sizeof grids / sizeof grids[0]; g++) {
    vl_contact *c = make_contact(10.0, grids[g], NULL);
    double ramp[] = {1e-2, 0.1, 0.4, 1.3, 4.0, 10.0};
    vl_point pts[6];
    sweep_deborah(c, 6, ramp, pts);
    double e[3] = {vl_test_rel(pts[1].mu_Rc * RADIUS / vl_contact_a0(c), href[0]),
                   vl_test_rel(pts[3].mu_Rc * RADIUS / vl_contact_a0(c), href[1]),
                   vl_test_rel(pts[5].mu_Rc * RADIUS / vl_contact_a0(c), href[2])};
    printf("  %6zu %12.3e %12.3e %12.3e\n", grids[g], e[0], e[1], e[2]);
    for (int k = 0; k < 3; k++)
      finest[k] = e[k];
    vl_contact_free(c);
  }
  for (int k = 0; k < 3; k++)
    assert_true(finest[k] < 1e-3);
}

/* docs/VALIDATION.md 3: Persson's linear-order formula is exact to first order
 * in A = Einf/E0 - 1. Its departure from the exact (Hunter) answer is itself
 * first order in A, about A/3 at the peak (the oracle's self-test measures
 * 1.63 % for Einf/E0 = 1.05 and 0.33 % for 1.01): the "within 1 % at
 * 1.05" cannot hold for a correct solver. We assert what is true: within 1 %
 * at Einf/E0 = 1.01, within 2 % at 1.05, and at 1.05 within 0.5 % of Hunter. */
static void persson_linear_case(double ratio, double tol_linear) {
  vl_contact *c = make_contact(ratio, 512, NULL);
  enum { N = 9 };
  double de[N];
  vl_point pts[N];
  for (int i = 0; i < N; i++)
    de[i] = pow(10.0, -2.0 + 4.0 * i / (N - 1));
  sweep_deborah(c, N, de, pts);
  double worst = 0.0, worst_h = 0.0;
  for (int i = 0; i < N; i++) {
    assert_true(pts[i].converged);
    double mu = pts[i].mu_Rc * RADIUS / vl_contact_a0(c);
    double ref = vl_oracle_persson_linear_mu(de[i], ratio);
    vl_oracle_hunter_solution h;
    assert_int_equal(vl_oracle_hunter_solve(de[i], ratio, &h), 0);
    double e = vl_test_rel(mu, ref), eh = vl_test_rel(mu, h.mu_R_over_a0);
    printf("  Einf/E0 %.2f De %8.3g  solver %12.6g  Persson-linear %12.6g (rel %8.2e)  Hunter rel "
           "%8.2e\n",
           ratio, de[i], mu, ref, e, eh);
    worst = fmax(worst, e);
    worst_h = fmax(worst_h, eh);
  }
  assert_true(worst < tol_linear);
  assert_true(worst_h < 5e-3);
  vl_contact_free(c);
}

static void test_persson_linear_small_loss(void **state) {
  (void)state;
  persson_linear_case(1.01, 1e-2);
  persson_linear_case(1.05, 2e-2);
}

/* Invariants of every solution: load balance to the solver tolerance,
 * p >= 0, u >= 0 and u > 0 where p = 0, pressure peak on the inlet side at
 * intermediate speed (docs/MODEL.md section 1). */
static void test_invariants_and_sign(void **state) {
  (void)state;
  vl_contact *c = make_contact(10.0, 256, NULL);
  double de[] = {0.01, 0.1, 1.0, 10.0};
  vl_point pts[4];
  sweep_deborah(c, 4, de, pts);
  size_t n = vl_contact_grid(c);
  double *buf = calloc(5 * n, sizeof *buf);
  vl_fields f = {n, buf, buf + n, buf + 2 * n, buf + 3 * n, buf + 4 * n, NULL, NULL};
  vl_contact_fields(c, &f);
  for (int i = 0; i < 4; i++) {
    assert_true(pts[i].converged);
    assert_true(pts[i].load_error < 1e-8);
    assert_true(pts[i].iterations > 0);
    assert_true(pts[i].residual <= 1e-9);
  }
  double p0 = vl_contact_p0(c), us = vl_contact_a0(c) * vl_contact_a0(c) / RADIUS;
  for (size_t i = 0; i < n; i++) {
    assert_true(f.p_c_pa[i] >= -1e-9 * p0);
    assert_true(f.u_m[i] >= 0.0);
    if (f.p_c_pa[i] <= 0.0) assert_true(f.u_m[i] > 0.0 || fabs(f.u_m[i]) < 1e-9 * us);
  }
  /* De = 10 (last solve): peak and centroid on the inlet side */
  assert_true(pts[2].x_peak_m < 0.0);
  assert_true(pts[2].x_centroid_m < 0.0);
  free(buf);
  vl_contact_free(c);
}

/* The analytic Jacobian against central finite differences, smooth and
 * rough, at a viscoelastic speed (relative 1e-6: FD truncation ~h^2). */
static void test_jacobian(void **state) {
  (void)state;
  vl_contact *c = make_contact(10.0, 64, NULL);
  double de[] = {1.0};
  vl_point pt;
  sweep_deborah(c, 1, de, &pt);
  double e = vl_contact_jacobian_check(c, pt.v0_m_s);
  printf("  smooth Jacobian: max |J_fd - J|/max|J| = %.2e\n", e);
  assert_true(e >= 0.0 && e < 1e-6);
  vl_contact_free(c);

  vl_psd psd;
  vl_persson *tab;
  assert_int_equal(vl_psd_init_self_affine(&psd, 0.8, 2e5, 7.8e9, 3e-6, NULL), VL_OK);
  assert_int_equal(vl_persson_build(&psd, 0, &tab, NULL), VL_OK);
  c = make_contact(10.0, 64, tab);
  sweep_deborah(c, 1, de, &pt);
  assert_true(pt.converged);
  e = vl_contact_jacobian_check(c, pt.v0_m_s);
  printf("  rough Jacobian:  max |J_fd - J|/max|J| = %.2e\n", e);
  assert_true(e >= 0.0 && e < 1e-6);
  vl_contact_free(c);
  vl_persson_free(tab);
  vl_psd_free(&psd);
  (void)deborah_of;
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_jacobian),
      cmocka_unit_test(test_invariants_and_sign),
      cmocka_unit_test(test_elastic_limits),
      cmocka_unit_test(test_hunter_default_grid),
      cmocka_unit_test(test_persson_linear_small_loss),
      cmocka_unit_test(test_hunter_grid_convergence),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
