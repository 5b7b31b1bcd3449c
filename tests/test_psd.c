/* Roughness power spectra (roughness.h, src/psd.c) against closed forms
 * (docs/VALIDATION.md §4) and GSL quadrature of independently coded PSDs. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "vl_test_util.h"

#include <math.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_math.h>

#include "roughness_internal.h"
#include "viscolube/roughness.h"

static gsl_integration_workspace *g_ws;

/* Our own PSD: self-affine closed form with C0 of docs/VALIDATION.md §4, or a
 * power law between tabulated points (linear search, log-log). */
typedef struct {
  int tab;
  double H, q0, q1, c0;
  size_t n;
  const double *q, *C;
  int k; /* moment order */
} ref_psd;

static double ref_c0(double H, double q0, double q1, double hrms) {
  return H * hrms * hrms / (M_PI * q0 * q0 * (1.0 - pow(q0 / q1, 2.0 * H)));
}

static double ref_C(const ref_psd *p, double q) {
  if (!p->tab) return (q < p->q0 || q > p->q1) ? 0.0 : p->c0 * pow(q / p->q0, -2.0 * (1.0 + p->H));
  if (q < p->q[0] || q > p->q[p->n - 1]) return 0.0;
  size_t k = 0;
  while (k + 2 < p->n && p->q[k + 1] <= q)
    k++;
  double a = log(p->C[k + 1] / p->C[k]) / log(p->q[k + 1] / p->q[k]);
  return p->C[k] * pow(q / p->q[k], a);
}

static double moment_integrand(double t, void *v) { /* q^k C(q) dq = q^(k+1) C dt */
  const ref_psd *p = v;
  double q = exp(t);
  return pow(q, (double)(p->k + 1)) * ref_C(p, q);
}

/* \int_{qa}^{qb} q^k C dq by GSL in t = ln q, split at the band edges and
 * knots (where the integrand is not smooth). */
static double ref_moment(ref_psd *p, int k, double qa, double qb) {
  double edges[80];
  size_t ne = 0;
  edges[ne++] = qa;
  if (p->tab) {
    for (size_t j = 0; j < p->n; j++)
      if (p->q[j] > qa && p->q[j] < qb) edges[ne++] = p->q[j];
  } else {
    if (p->q0 > qa && p->q0 < qb) edges[ne++] = p->q0;
    if (p->q1 > qa && p->q1 < qb) edges[ne++] = p->q1;
  }
  edges[ne++] = qb;
  p->k = k;
  gsl_function fn = {moment_integrand, p};
  double sum = 0.0;
  for (size_t j = 0; j + 1 < ne; j++) {
    double r, e;
    int st = gsl_integration_qag(&fn, log(edges[j]), log(edges[j + 1]), 0.0, 1e-13, 1000,
                                 GSL_INTEG_GAUSS21, g_ws, &r, &e);
    assert_true(st == GSL_SUCCESS || st == GSL_EROUND);
    sum += r;
  }
  return sum;
}

static int setup(void **state) {
  (void)state;
  gsl_set_error_handler_off();
  g_ws = gsl_integration_workspace_alloc(1000);
  return 0;
}

static int teardown(void **state) {
  (void)state;
  gsl_integration_workspace_free(g_ws);
  return 0;
}

/* C0 = H h^2 / (pi q0^2 [1 - (q0/q1)^(2H)]) (docs/VALIDATION.md §4); the library
 * uses an expm1 form, so agreement is to rounding (1e-12 allows the pow
 * form's cancellation when q0/q1 -> 1). */
static void test_c0_formula(void **state) {
  (void)state;
  const double H[] = {1e-3, 0.3, 0.8, 1.0};
  for (int i = 0; i < 4; i++) {
    vl_psd psd;
    vl_error err;
    assert_int_equal(vl_psd_init_self_affine(&psd, H[i], 2e5, 7.8e9, 3e-6, &err), VL_OK);
    assert_true(vl_test_rel(psd.c0, ref_c0(H[i], 2e5, 7.8e9, 3e-6)) < 1e-12);
    assert_int_equal(psd.kind, VL_PSD_SELF_AFFINE);
    vl_psd_free(&psd);
  }
}

/* vl_psd_moment (exact power-law integrals) against GSL quadrature of our
 * own C(q), k = 0..3, for intervals inside, across and outside the band;
 * quadrature tolerance 1e-13, asserted 1e-10. Includes H = 1, where
 * q^3 C ~ 1/q (the log case of the power integral). */
static void check_moments(vl_psd *psd, ref_psd *ref, const double (*iv)[2], size_t niv) {
  for (int k = 0; k <= 3; k++) {
    for (size_t j = 0; j < niv; j++) {
      double got = vl_psd_moment(psd, k, iv[j][0], iv[j][1]);
      double qa = fmax(iv[j][0], psd->q0), qb = fmin(iv[j][1], psd->q1);
      double want = qb > qa ? ref_moment(ref, k, qa, qb) : 0.0;
      if (want == 0.0)
        assert_true(got == 0.0);
      else
        assert_true(vl_test_rel(got, want) < 1e-10);
    }
  }
}

static void test_moments_self_affine(void **state) {
  (void)state;
  const double iv[][2] = {{2e5, 7.8e9}, {1e3, 1e12}, {3e6, 4e6}, {2e5, 2.001e5},
                          {1e9, 1e11},  {1e2, 1e4},  {5e9, 5e9}, {4e7, 1e6}};
  const double H[] = {0.05, 0.3, 0.8, 1.0};
  for (int i = 0; i < 4; i++) {
    vl_psd psd;
    vl_error err;
    assert_int_equal(vl_psd_init_self_affine(&psd, H[i], 2e5, 7.8e9, 3e-6, &err), VL_OK);
    ref_psd ref = {0, H[i], 2e5, 7.8e9, ref_c0(H[i], 2e5, 7.8e9, 3e-6), 0, NULL, NULL, 0};
    check_moments(&psd, &ref, iv, sizeof iv / sizeof iv[0]);
    vl_psd_free(&psd);
  }
}

/* A measured-like spectrum: a plateau then a roll-off, irregular knots. */
static const double TQ[] = {1e3, 2.5e3, 1e4, 3e4, 1.2e5, 1e6, 4e6, 3e7, 1e8, 2e9};
static const double TC[] = {1e-20, 1.2e-20, 9e-21, 5e-21, 1e-21, 3e-24, 2e-26, 1e-29, 4e-32, 1e-36};

static void test_moments_tabulated(void **state) {
  (void)state;
  vl_psd psd;
  vl_error err;
  size_t n = sizeof TQ / sizeof TQ[0];
  assert_int_equal(vl_psd_init_tabulated(&psd, n, TQ, TC, &err), VL_OK);
  assert_int_equal(psd.kind, VL_PSD_TABULATED);
  assert_true(psd.q0 == TQ[0] && psd.q1 == TQ[n - 1]);
  ref_psd ref = {1, 0.0, 0.0, 0.0, 0.0, n, TQ, TC, 0};
  const double iv[][2] = {{1e3, 2e9}, {1e2, 1e10},  {1.5e3, 2e3}, {2e3, 5e5},
                          {3e4, 3e4}, {9e7, 1.1e8}, {1e1, 1e2}};
  check_moments(&psd, &ref, iv, sizeof iv / sizeof iv[0]);
  /* values: knots exactly, power law between, zero outside */
  for (size_t k = 0; k < n; k++)
    assert_true(vl_test_rel(vl_psd_value(&psd, TQ[k]), TC[k]) < 1e-14);
  assert_true(vl_test_rel(vl_psd_value(&psd, 5e5), ref_C(&ref, 5e5)) < 1e-13);
  assert_true(vl_psd_value(&psd, 999.0) == 0.0 && vl_psd_value(&psd, 2.1e9) == 0.0);
  /* h_rms derived at init: sqrt(2 pi \int q C dq) */
  assert_true(vl_test_rel(psd.hrms_m, sqrt(2.0 * M_PI * ref_moment(&ref, 1, 1e3, 2e9))) < 1e-10);
  vl_psd_free(&psd);
  vl_psd_free(&psd); /* idempotent */
}

/* h_rms round trip: init from h, then 2 pi \int q C dq gives h back
 * (rounding only: 1e-13). */
static void test_hrms_round_trip(void **state) {
  (void)state;
  const double H[] = {1e-3, 0.3, 0.8, 1.0};
  const double h[] = {1e-9, 3e-6, 1e-3};
  for (int i = 0; i < 4; i++) {
    for (int j = 0; j < 3; j++) {
      vl_psd psd;
      vl_error err;
      assert_int_equal(vl_psd_init_self_affine(&psd, H[i], 2e5, 7.8e9, h[j], &err), VL_OK);
      assert_true(vl_test_rel(vl_psd_hrms(&psd), h[j]) < 1e-13);
      assert_true(vl_test_rel(psd.hrms_m, h[j]) < 1e-15);
      vl_psd_free(&psd);
    }
  }
}

/* A tabulated PSD sampled from a self-affine one on a log grid is the same
 * function (a power law is linear in log-log), so every moment, h_rms and
 * the rms slope agree to rounding (1e-12). */
static void test_sampled_self_affine(void **state) {
  (void)state;
  vl_psd sa, tab;
  vl_error err;
  double q[17], C[17];
  assert_int_equal(vl_psd_init_self_affine(&sa, 0.7, 1e4, 1e9, 2e-6, &err), VL_OK);
  for (int k = 0; k < 17; k++) {
    q[k] = 1e4 * pow(1e5, k / 16.0);
    C[k] = vl_psd_value(&sa, q[k]);
  }
  q[0] = 1e4;
  q[16] = 1e9;
  C[0] = sa.c0;
  C[16] = vl_psd_value(&sa, 1e9);
  assert_int_equal(vl_psd_init_tabulated(&tab, 17, q, C, &err), VL_OK);
  for (int k = 0; k <= 3; k++) {
    assert_true(vl_test_rel(vl_psd_moment(&tab, k, 1e4, 1e9), vl_psd_moment(&sa, k, 1e4, 1e9)) <
                1e-12);
    assert_true(vl_test_rel(vl_psd_moment(&tab, k, 3.3e5, 7e7), vl_psd_moment(&sa, k, 3.3e5, 7e7)) <
                1e-12);
  }
  assert_true(vl_test_rel(tab.hrms_m, 2e-6) < 1e-12);
  assert_true(vl_test_rel(vl_psd_rms_slope(&tab), vl_psd_rms_slope(&sa)) < 1e-12);
  vl_psd_free(&sa);
  vl_psd_free(&tab);
}

/* rms slope: <|grad h|^2> = \int d^2q q^2 C = 2 pi \int q^3 C dq; closed
 * form for self-affine with docs/VALIDATION.md §4's \int q^3 C =
 * C0 q0^4 [(q1/q0)^(2(1-H)) - 1] / (2(1-H)) (log for H = 1); 1e-12. */
static void test_rms_slope(void **state) {
  (void)state;
  const double H[] = {0.3, 0.8, 1.0};
  for (int i = 0; i < 3; i++) {
    vl_psd psd;
    vl_error err;
    double q0 = 2e5, q1 = 7.8e9, c0 = ref_c0(H[i], q0, q1, 3e-6);
    assert_int_equal(vl_psd_init_self_affine(&psd, H[i], q0, q1, 3e-6, &err), VL_OK);
    double m3 = H[i] == 1.0 ? c0 * pow(q0, 4.0) * log(q1 / q0)
                            : c0 * pow(q0, 4.0) * (pow(q1 / q0, 2.0 * (1.0 - H[i])) - 1.0) /
                                  (2.0 * (1.0 - H[i]));
    assert_true(vl_test_rel(vl_psd_rms_slope(&psd), sqrt(2.0 * M_PI * m3)) < 1e-12);
    vl_psd_free(&psd);
  }
  vl_psd tab;
  vl_error err;
  size_t n = sizeof TQ / sizeof TQ[0];
  assert_int_equal(vl_psd_init_tabulated(&tab, n, TQ, TC, &err), VL_OK);
  ref_psd ref = {1, 0.0, 0.0, 0.0, 0.0, n, TQ, TC, 0};
  assert_true(vl_test_rel(vl_psd_rms_slope(&tab),
                          sqrt(2.0 * M_PI * ref_moment(&ref, 3, TQ[0], TQ[n - 1]))) < 1e-10);
  vl_psd_free(&tab);
}

/* Every invalid input is rejected with VL_EINPUT and a message. */
static void expect_sa_error(double H, double q0, double q1, double h) {
  vl_psd psd;
  vl_error err;
  err.msg[0] = '\0';
  assert_int_equal(vl_psd_init_self_affine(&psd, H, q0, q1, h, &err), VL_EINPUT);
  assert_true(strlen(err.msg) > 0);
}

static void expect_tab_error(size_t n, const double *q, const double *C) {
  vl_psd psd;
  vl_error err;
  err.msg[0] = '\0';
  assert_int_equal(vl_psd_init_tabulated(&psd, n, q, C, &err), VL_EINPUT);
  assert_true(strlen(err.msg) > 0);
  vl_psd_free(&psd); /* safe after a failed init */
}

static void test_invalid_inputs(void **state) {
  (void)state;
  expect_sa_error(0.0, 2e5, 7.8e9, 3e-6);
  expect_sa_error(1.01, 2e5, 7.8e9, 3e-6);
  expect_sa_error(NAN, 2e5, 7.8e9, 3e-6);
  expect_sa_error(0.8, 0.0, 7.8e9, 3e-6);
  expect_sa_error(0.8, 2e5, 2e5, 3e-6);
  expect_sa_error(0.8, 2e5, INFINITY, 3e-6);
  expect_sa_error(0.8, 2e5, 7.8e9, 0.0);
  expect_sa_error(0.8, 2e5, 7.8e9, NAN);
  const double q[] = {1.0, 2.0, 2.0}, C[] = {1.0, 1.0, 1.0};
  const double qok[] = {1.0, 2.0, 3.0}, Cbad[] = {1.0, 0.0, 1.0}, Cnan[] = {1.0, NAN, 1.0};
  const double qneg[] = {-1.0, 2.0, 3.0};
  expect_tab_error(1, qok, C);
  expect_tab_error(3, q, C);
  expect_tab_error(3, qok, Cbad);
  expect_tab_error(3, qok, Cnan);
  expect_tab_error(3, qneg, C);
  vl_psd_free(NULL);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_c0_formula),          cmocka_unit_test(test_moments_self_affine),
      cmocka_unit_test(test_moments_tabulated),   cmocka_unit_test(test_hrms_round_trip),
      cmocka_unit_test(test_sampled_self_affine), cmocka_unit_test(test_rms_slope),
      cmocka_unit_test(test_invalid_inputs),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
