/* The creep-form Prony fit (prony_fit.h): data made from known Prony series
 * (evaluated here by the closed form of docs/MODEL.md section 2, not by
 * rheology.c), refitted; grid construction; refusals. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "prony_fit_internal.h"
#include "viscolube/prony_fit.h"

/* E' and E'' of the creep form in the DMA convention:
 * J = (1/Einf)(1 + sum A_i/(1 + i w tau_i)) = J' - i J'', E = 1/J. */
static void closed_form(double einf, size_t n, const double *A, const double *tau, double w,
                        double *e1, double *e2) {
  double j1 = 1.0, j2 = 0.0;
  for (size_t i = 0; i < n; i++) {
    double wt = w * tau[i], d = 1.0 / (1.0 + wt * wt);
    j1 += A[i] * d;
    j2 += A[i] * wt * d;
  }
  j1 /= einf, j2 /= einf;
  double m2 = j1 * j1 + j2 * j2;
  *e1 = j1 / m2;
  *e2 = j2 / m2;
}

/* Largest relative deviation of the fitted series from the closed form on
 * the data frequencies (E' and E'' separately). */
static void max_rel(const vl_prony *p, double einf, size_t nt, const double *A, const double *tau,
                    size_t n, const double *w, double *d1, double *d2) {
  *d1 = *d2 = 0.0;
  for (size_t k = 0; k < n; k++) {
    double e1, e2;
    closed_form(einf, nt, A, tau, w[k], &e1, &e2);
    double complex e = vl_prony_modulus(p, w[k]);
    *d1 = fmax(*d1, fabs(creal(e) / e1 - 1.0));
    *d2 = fmax(*d2, fabs(cimag(e) / e2 - 1.0));
  }
}

/* A smooth (log-normal) retardation spectrum of 41 terms at 5 per decade,
 * offset by 0.1 decade from any grid the fit can use, data 10 per decade
 * over 10 decades (1e-3 to 1e7 rad/s) reaching both plateaus. With the
 * default 2 terms per decade the fit must reproduce E' and E'' within 1 %
 * everywhere in the window (the accuracy the compound database promises;
 * measured: 0.27 % and 0.46 %), Einf and E0 within 0.1 %. One term per
 * decade is not enough (it leaves ~5 % ripple in E''): the reason for the
 * default. */
static void test_smooth_spectrum(void **state) {
  (void)state;
  enum { NT = 41, NW = 81 };
  double A[NT], tau[NT], w[NW], e1[NW], e2[NW], suma = 0.0;
  const double einf = 2e9;
  for (int i = 0; i < NT; i++) {
    double lt = -5.9 + 0.2 * i;
    tau[i] = pow(10.0, lt);
    A[i] = 7.5 * exp(-pow((lt + 2.0) / 1.8, 2.0));
    suma += A[i];
  }
  for (int k = 0; k < NW; k++) {
    w[k] = pow(10.0, -3.0 + 0.125 * k);
    closed_form(einf, NT, A, tau, w[k], &e1[k], &e2[k]);
  }
  vl_prony p;
  vl_prony_fit_report rep;
  vl_error err;
  assert_int_equal(vl_prony_fit(NW, w, e1, e2, 0.0, VL_PRONY_WEIGHTS_RELATIVE, 0.5, &p, &rep, &err),
                   VL_OK);
  double d1, d2;
  max_rel(&p, einf, NT, A, tau, NW, w, &d1, &d2);
  if (!(d1 < 0.01 && d2 < 0.01)) fail_msg("max rel error E' %.3g, E'' %.3g", d1, d2);
  /* the report is the same measure */
  assert_true(fabs(rep.max_rel_storage - d1) < 1e-12 && fabs(rep.max_rel_loss - d2) < 1e-12);
  assert_true(rep.rms_rel_storage <= rep.max_rel_storage && rep.rms_rel_loss <= rep.max_rel_loss);
  assert_true(vl_test_rel(p.e_inf_pa, einf) < 1e-3);
  assert_true(vl_test_rel(vl_prony_e0(&p), einf / (1.0 + suma)) < 1e-3);
  assert_true(p.nu == 0.5);
  assert_int_equal(rep.n_grid, 21); /* 10 decades x 2 + 1 */
  assert_true(rep.n_terms <= rep.n_grid && rep.n_terms == p.n_terms);
  assert_true(rep.terms_per_decade == VL_PRONY_FIT_DEFAULT_PER_DECADE);
  for (size_t i = 1; i < p.n_terms; i++)
    assert_true(p.tau_s[i] > p.tau_s[i - 1] && p.A[i] > 0.0);
  fprintf(stderr, "smooth spectrum, 2/decade: max rel error E' %.3g, E'' %.3g\n", d1, d2);

  /* both weightings meet 1 % in rms (modulus weights: looser E'' tails) */
  assert_int_equal(vl_prony_fit(NW, w, e1, e2, 0.0, VL_PRONY_WEIGHTS_MODULUS, 0.5, &p, &rep, &err),
                   VL_OK);
  assert_true(rep.rms_rel_storage < 0.01 && rep.rms_rel_loss < 0.01);
  assert_true(rep.weights == VL_PRONY_WEIGHTS_MODULUS);

  assert_int_equal(vl_prony_fit(NW, w, e1, e2, 1.0, VL_PRONY_WEIGHTS_RELATIVE, 0.5, &p, &rep, &err),
                   VL_OK);
  max_rel(&p, einf, NT, A, tau, NW, w, &d1, &d2);
  assert_true(d2 > 0.01); /* one per decade: the ripple shows */
}

/* Terms exactly on the grid the fit uses (window 1e-3..1e7 rad/s, 2 per
 * decade: tau = 10^(-7 + k/2)): the data are in the model space, so the
 * fit must give back the generating series, A_i to 1e-6 relative and no
 * other term above 1e-6 of the largest (a check of the whole linear
 * algebra, NNLS included). */
static void test_on_grid_recovery(void **state) {
  (void)state;
  enum { NW = 81 };
  const double tau[4] = {1e-6, pow(10.0, -3.5), 1e-1, pow(10.0, 1.5)};
  const double A[4] = {40.0, 120.0, 15.0, 3.0};
  double w[NW], e1[NW], e2[NW];
  for (int k = 0; k < NW; k++) {
    w[k] = pow(10.0, -3.0 + 0.125 * k);
    closed_form(1e9, 4, A, tau, w[k], &e1[k], &e2[k]);
  }
  vl_prony p;
  vl_prony_fit_report rep;
  vl_error err;
  assert_int_equal(
      vl_prony_fit(NW, w, e1, e2, 2.0, VL_PRONY_WEIGHTS_RELATIVE, 0.49, &p, &rep, &err), VL_OK);
  assert_true(vl_test_rel(p.e_inf_pa, 1e9) < 1e-8);
  double amax = 0.0;
  for (size_t i = 0; i < p.n_terms; i++)
    amax = fmax(amax, p.A[i]);
  size_t found = 0;
  for (size_t i = 0; i < p.n_terms; i++) {
    int matched = 0;
    for (int j = 0; j < 4; j++) {
      if (vl_test_rel(p.tau_s[i], tau[j]) < 1e-12) {
        matched = 1;
        found++;
        if (vl_test_rel(p.A[i], A[j]) > 1e-6)
          fail_msg("A at tau %g: %.12g, want %g", tau[j], p.A[i], A[j]);
      }
    }
    if (!matched && p.A[i] > 1e-6 * amax)
      fail_msg("spurious term A %g at tau %g", p.A[i], p.tau_s[i]);
  }
  assert_int_equal(found, 4);
  assert_true(rep.max_rel_storage < 1e-8 && rep.max_rel_loss < 1e-8);
  assert_true(p.nu == 0.49);
}

/* The paper's model rubber (one term, A = 9, tau = 0.1 s) from 4 decades
 * of data around its loss peak (tau on the grid): exact recovery. */
static void test_model_rubber(void **state) {
  (void)state;
  enum { NW = 41 };
  double w[NW], e1[NW], e2[NW];
  const double A = 9.0, tau = 0.1;
  for (int k = 0; k < NW; k++) {
    w[k] = pow(10.0, -1.0 + 0.1 * k);
    closed_form(36e6, 1, &A, &tau, w[k], &e1[k], &e2[k]);
  }
  vl_prony p;
  vl_error err;
  assert_int_equal(vl_prony_fit(NW, w, e1, e2, 1.0, VL_PRONY_WEIGHTS_RELATIVE, 0.5, &p, NULL, &err),
                   VL_OK);
  double amax = 0.0, a_at = 0.0;
  for (size_t i = 0; i < p.n_terms; i++) {
    amax = fmax(amax, p.A[i]);
    if (vl_test_rel(p.tau_s[i], tau) < 1e-12) a_at = p.A[i];
  }
  assert_true(vl_test_rel(a_at, A) < 1e-8 && amax == a_at);
  assert_true(vl_test_rel(vl_prony_e0(&p), 3.6e6) < 1e-8);
}

static void test_grid(void **state) {
  (void)state;
  double tau[32];
  assert_int_equal(vl_prony_fit_grid(1e-3, 1e7, 2.0, tau, 32), 21);
  assert_true(vl_test_rel(tau[0], 1e-7) < 1e-14 && vl_test_rel(tau[20], 1e3) < 1e-14);
  assert_int_equal(vl_prony_fit_grid(1.0, 10.0, 1.0, NULL, 0), 2);
  assert_int_equal(vl_prony_fit_grid(1.0, 1e3, 0.5, NULL, 0), 3); /* 1.5 steps -> 2 */
  assert_int_equal(vl_prony_fit_grid(1.0, 2e3, 2.0, NULL, 0), 8); /* 6.6 steps -> 7 */
  assert_int_equal(vl_prony_fit_grid(1.0, 1.0, 2.0, NULL, 0), 0);
  assert_int_equal(vl_prony_fit_grid(-1.0, 10.0, 2.0, NULL, 0), 0);
}

static void test_refusals(void **state) {
  (void)state;
  double w[20], e1[20], e2[20];
  for (int k = 0; k < 20; k++) {
    w[k] = pow(10.0, 0.04 * k); /* 0.76 decade */
    e1[k] = 1e6 * (1.0 + 0.1 * k);
    e2[k] = 1e5;
  }
  vl_prony p;
  vl_error err;
  vl_prony_weights rel = VL_PRONY_WEIGHTS_RELATIVE;
  assert_int_equal(vl_prony_fit(20, w, e1, e2, 0.0, rel, 0.5, &p, NULL, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "one decade"));
  for (int k = 0; k < 20; k++)
    w[k] = pow(10.0, 0.5 * k); /* 9.5 decades, 20 points: 20 < 20 + 1 unknowns at 2/decade */
  assert_int_equal(vl_prony_fit(20, w, e1, e2, 2.0, rel, 0.5, &p, NULL, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "points cannot determine"));
  e2[3] = -1.0;
  assert_int_equal(vl_prony_fit(20, w, e1, e2, 1.0, rel, 0.5, &p, NULL, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "point 4"));
  e2[3] = 0.0;
  assert_int_equal(vl_prony_fit(20, w, e1, e2, 1.0, rel, 0.5, &p, NULL, &err), VL_EINPUT);
  e2[3] = 1e5;
  assert_int_equal(vl_prony_fit(20, w, e1, e2, 9.0, rel, 0.5, &p, NULL, &err), VL_EINPUT);
  assert_int_equal(vl_prony_fit(20, w, e1, e2, -1.0, rel, 0.5, &p, NULL, &err), VL_EINPUT);
  assert_int_equal(vl_prony_fit(20, w, e1, e2, 1.0, (vl_prony_weights)7, 0.5, &p, NULL, &err),
                   VL_EINPUT);
  assert_int_equal(vl_prony_fit(20, w, e1, e2, 1.0, rel, 0.6, &p, NULL, &err), VL_EINPUT);
  assert_int_equal(vl_prony_fit(1, w, e1, e2, 1.0, rel, 0.5, &p, NULL, &err), VL_EINPUT);
  /* 200 decades at 8 per decade: more than VL_PRONY_MAX_TERMS */
  w[19] = 1e200;
  assert_int_equal(vl_prony_fit(20, w, e1, e2, 8.0, rel, 0.5, &p, NULL, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "fewer terms per decade"));
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_smooth_spectrum), cmocka_unit_test(test_on_grid_recovery),
      cmocka_unit_test(test_model_rubber),    cmocka_unit_test(test_grid),
      cmocka_unit_test(test_refusals),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
