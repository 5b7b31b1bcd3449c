/* Extrapolation made visible (issue 18): the loss peak of a series within
 * a window (vl_prony_loss_peak_in), the warning of a point whose
 * frequencies leave a compound's measured window
 * (vl_assumptions_check_window), and the self-affine law closest to a
 * tabulated spectrum (vl_psd_fit_self_affine), each against closed forms. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <math.h>
#include <string.h>

#include "assumptions_internal.h"
#include "rheology_internal.h"
#include "viscolube/assumptions.h"
#include "viscolube/rheology.h"
#include "viscolube/roughness.h"

/* One Debye term: E = Einf (1 - i w tau) / (1 - i w tau + A) in the
 * creep form, tan delta = A w tau / (1 + A + (w tau)^2), largest at
 * w tau = sqrt(1 + A). */
static void test_loss_peak_in(void **state) {
  (void)state;
  double tau = 1e-3, ratio = 100.0; /* Einf/E0 = 1 + A */
  vl_prony p = vl_prony_single(1e6, ratio, tau, 0.5);
  double w_true = sqrt(ratio) / tau, w, td;
  int edge = 7;
  /* the window holds the peak: found inside, as the global search */
  assert_int_equal(vl_prony_loss_peak_in(&p, 1.0, 1e6, &w, &td, &edge, NULL), VL_OK);
  assert_int_equal(edge, 0);
  assert_true(fabs(w / w_true - 1.0) < 1e-6);
  assert_true(fabs(td - (ratio - 1.0) / (2.0 * sqrt(ratio))) < 1e-9);
  /* a window below the peak: its upper end, where tan delta still rises */
  assert_int_equal(vl_prony_loss_peak_in(&p, 1.0, 100.0, &w, &td, &edge, NULL), VL_OK);
  assert_int_equal(edge, 1);
  assert_true(fabs(w / 100.0 - 1.0) < 1e-3);
  assert_true(fabs(td - vl_prony_tan_delta(&p, 100.0)) < 1e-4 * td);
  /* above it: the lower end */
  assert_int_equal(vl_prony_loss_peak_in(&p, 1e5, 1e7, &w, &td, &edge, NULL), VL_OK);
  assert_int_equal(edge, -1);
  assert_true(fabs(w / 1e5 - 1.0) < 1e-2);
  /* no window, or an elastic material */
  vl_error err;
  assert_int_equal(vl_prony_loss_peak_in(&p, 10.0, 1.0, &w, &td, &edge, &err), VL_EINPUT);
  assert_int_equal(vl_prony_loss_peak_in(&p, 0.0, 1.0, &w, &td, &edge, &err), VL_EINPUT);
  vl_prony el = p;
  el.n_terms = 0;
  assert_int_equal(vl_prony_loss_peak_in(&el, 1.0, 10.0, &w, &td, &edge, &err), VL_EINPUT);
}

/* A point at v0 on a surface q0..q1: asperity frequencies v0 q0..v0 q1,
 * contact frequency v0/a with a half its contact width. */
static void test_window_check(void **state) {
  (void)state;
  vl_contact_config cfg;
  vl_contact_config_defaults(&cfg);
  cfg.rubber = vl_prony_single(1e6, 100.0, 1e-3, 0.5);
  cfg.load_n_per_m = 100.0;
  cfg.radius_m = 1e-3;
  vl_psd psd;
  assert_int_equal(vl_psd_init_self_affine(&psd, 0.8, 1e4, 1e6, 1e-6, NULL), VL_OK);
  vl_point pt;
  memset(&pt, 0, sizeof pt);
  pt.v0_m_s = 1e-2;
  pt.converged = true;
  pt.contact_width_m = 2e-4; /* v0/a = 100 rad/s */
  /* v0 q: 100..1e4 rad/s; inside 10..1e5 */
  char w[VL_WARN_MAX] = "";
  assert_int_equal(vl_assumptions_check_window(&cfg, &psd, &pt, 10.0, 1e5, w, sizeof w), 0u);
  assert_string_equal(w, "");
  /* a window 1..1e2: v0 q1 = 1e4 is 100 x above it; v0/a = 100 inside */
  assert_int_equal(vl_assumptions_check_window(&cfg, &psd, &pt, 1.0, 1e2, w, sizeof w),
                   VL_ASSUME_MEASURED_WINDOW);
  assert_string_equal(w, "asperity frequency v0 q1 1e+04 rad/s over a decade above the measured "
                         "window (top 1e+02 rad/s)");
  /* within a decade is not warned: 1..1.001e3 */
  w[0] = '\0';
  assert_int_equal(vl_assumptions_check_window(&cfg, &psd, &pt, 1.0, 1.001e3, w, sizeof w), 0u);
  /* a window 1e4..1e6: v0/a = 100 is 100 x below it, v0 q0 as much
   * (the contact after the asperities) */
  assert_int_equal(vl_assumptions_check_window(&cfg, &psd, &pt, 1e4, 1e6, w, sizeof w),
                   VL_ASSUME_MEASURED_WINDOW);
  assert_non_null(strstr(w, "asperity frequency v0 q0 1e+02 rad/s over a decade below the "
                            "measured window (bottom 1e+04 rad/s)"));
  assert_non_null(strstr(w, ";contact frequency v0/a 1e+02 rad/s over a decade below"));
  assert_null(strchr(w, ',')); /* CSV-safe */
  /* smooth: only the contact frequency; no window (a Prony series), no
   * sliding: nothing */
  w[0] = '\0';
  assert_int_equal(vl_assumptions_check_window(&cfg, NULL, &pt, 1e4, 1e6, w, sizeof w),
                   VL_ASSUME_MEASURED_WINDOW);
  assert_null(strstr(w, "asperity"));
  w[0] = '\0';
  assert_int_equal(vl_assumptions_check_window(&cfg, &psd, &pt, NAN, NAN, w, sizeof w), 0u);
  pt.v0_m_s = 0.0;
  assert_int_equal(vl_assumptions_check_window(&cfg, &psd, &pt, 1e4, 1e6, w, sizeof w), 0u);
  assert_string_equal(w, "");
  assert_string_equal(vl_assumption_name(VL_ASSUME_MEASURED_WINDOW), "measured window");
  vl_psd_free(&psd);
}

/* A tabulated self-affine spectrum gives back its H and C(q0); a roll-off
 * below the largest C is left out; a self-affine PSD reports itself. */
static void test_fit_self_affine(void **state) {
  (void)state;
  enum { N = 31 };
  double q[N], c[N], h = 0.7, c0 = 3e-26;
  for (int i = 0; i < N; i++) {
    q[i] = 1e5 * pow(10.0, 0.1 * i);
    c[i] = c0 * pow(q[i] / 1e5, -2.0 * (1.0 + h));
  }
  vl_psd p;
  assert_int_equal(vl_psd_init_tabulated(&p, N, q, c, NULL), VL_OK);
  double hf, cf, rms;
  assert_int_equal(vl_psd_fit_self_affine(&p, &hf, &cf, &rms, NULL), VL_OK);
  assert_true(fabs(hf - h) < 1e-9 && fabs(cf / c0 - 1.0) < 1e-9 && rms < 1e-9);
  vl_psd_free(&p);
  /* a flat roll-off over the first 5 points: ignored */
  for (int i = 0; i < 5; i++)
    c[i] = c[5] * (0.5 + 0.1 * i);
  assert_int_equal(vl_psd_init_tabulated(&p, N, q, c, NULL), VL_OK);
  assert_int_equal(vl_psd_fit_self_affine(&p, &hf, NULL, &rms, NULL), VL_OK);
  assert_true(fabs(hf - h) < 1e-9 && rms < 1e-9);
  vl_psd_free(&p);
  assert_int_equal(vl_psd_init_self_affine(&p, 0.45, 1e4, 1e8, 1e-6, NULL), VL_OK);
  assert_int_equal(vl_psd_fit_self_affine(&p, &hf, &cf, &rms, NULL), VL_OK);
  assert_true(hf == 0.45 && cf == p.c0 && rms == 0.0);
  vl_psd_free(&p);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_loss_peak_in),
      cmocka_unit_test(test_window_check),
      cmocka_unit_test(test_fit_self_affine),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
