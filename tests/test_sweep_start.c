/* Sweeps that start anywhere (sweep.h): a sweep whose first speed is not in
 * the boundary regime converges at every point and finds the same
 * solutions as a sweep from the boundary regime through the same speeds.
 *
 * The scenes are fig05's contact (model rubber, R 1 cm, fN 1 kN/m, eta
 * 1e-4 Pa s, Patir-Cheng, the wet rough defaults: a0/30 cells graded by
 * 5 % on a 96 a0 inlet, tolerance 1e-6) on fine paper surfaces, where
 * starting is hard:
 *   h_rms 0.1 um: from 0.016 to 0.16 m/s the rubber passes its loss peak
 *     and Newton from Hertz fails (the real contact is far from the
 *     relaxed one), as it does in the hydrodynamic regime (the film has
 *     lifted the solid off: Hertz and the dry contact are closed films);
 *   h_rms 30 nm: the film lifts off between 10 and 16 m/s within a fold of
 *     the curve (u_min jumps from 8e-11 to 1.6e-7 m): the mixed branch ends
 *     there and the sweep from below finds the lifted branch from above.
 * Before the robust starts (dry contact, smooth film, fresh starts below
 * and above a point) the mid-curve sweeps failed at their first point and
 * the sweeps from the boundary regime lost every point from 0.025 m/s
 * (0.1 um) or 0.016 m/s (30 nm) on.
 *
 * Agreement: both sweeps meet the scaled residual tolerance 1e-6 at every
 * point, and Newton converges quadratically, so their residuals are far
 * below it (1e-7 ... 1e-12): the solutions agree far better than the
 * tolerance suggests. mu is asserted within 1e-6 relative (measured: equal
 * to all 10 printed digits, 1e-11 relative at most), u_min within 1e-4. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "viscolube/sweep.h"
#include "vl_test_scenes.h"
#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>

#define ETA 1e-4
#define MU_TOL 1e-6
#define UMIN_TOL 1e-4

/* fig05's contact on the paper surface of rms roughness hrms_m, with the
 * wet rough defaults (the numerics of cases/fig05.ini). */
static vl_contact *fig05_contact(double hrms_m, vl_psd *psd, vl_persson **tab) {
  *tab = vl_test_paper_surface(hrms_m, psd);
  vl_contact_config cfg;
  vl_test_fig05_config(&cfg, *tab, ETA, VL_WET_ROUGH_GRID, VL_WET_ROUGH_DOMAIN_MIN_A0);
  cfg.grid_growth = VL_WET_GRID_GROWTH;
  cfg.tolerance = VL_WET_TOLERANCE;
  vl_contact *c = NULL;
  vl_error err;
  if (vl_contact_create(&cfg, &c, &err) != VL_OK) fail_msg("contact: %s", err.msg);
  return c;
}

/* Sweeps v[0..n-1] on a new contact; fails the test unless every point
 * converges. */
static void sweep_all(double hrms_m, size_t n, const double *v, vl_point *pt, vl_sweep_stats *st) {
  vl_psd psd;
  vl_persson *tab;
  vl_contact *c = fig05_contact(hrms_m, &psd, &tab);
  vl_error err;
  assert_int_equal(vl_sweep_run(c, n, v, NULL, pt, NULL, NULL, st, &err), VL_OK);
  for (size_t i = 0; i < n; i++)
    if (!pt[i].converged)
      fail_msg("h_rms %g m: the sweep from %g m/s did not converge at %g m/s (%ld iterations, "
               "residual %.3g)",
               hrms_m, v[0], v[i], pt[i].iterations, pt[i].residual);
  vl_contact_free(c);
  vl_persson_free(tab);
  vl_psd_free(&psd);
}

/* The mid-curve sweep v[first..n-1] against the same points of the
 * reference (ref[first..n-1], from v[0]). */
static void agree(double hrms_m, size_t first, size_t n, const double *v, const vl_point *ref) {
  vl_point pt[32];
  vl_sweep_stats st;
  assert_true(n - first <= 32);
  sweep_all(hrms_m, n - first, v + first, pt, &st);
  double dmu = 0.0, du = 0.0;
  for (size_t i = first; i < n; i++) {
    const vl_point *a = &pt[i - first], *b = &ref[i];
    dmu = fmax(dmu, fabs(a->mu - b->mu) / b->mu);
    du = fmax(du, fabs(a->u_min_m - b->u_min_m) / b->u_min_m);
    if (fabs(a->mu - b->mu) > MU_TOL * b->mu ||
        fabs(a->u_min_m - b->u_min_m) > UMIN_TOL * b->u_min_m)
      fail_msg("h_rms %g m, %g m/s: from %g m/s mu %.10g u_min %.6g m, from %g m/s mu %.10g "
               "u_min %.6g m",
               hrms_m, v[i], v[first], a->mu, a->u_min_m, v[0], b->mu, b->u_min_m);
  }
  print_message("h_rms %g m, start %g m/s: %zu points, %zu starts below, %zu above, %ld Newton "
                "iterations, %.1f s; mu within %.1e, u_min within %.1e of the sweep from %g m/s\n",
                hrms_m, v[first], n - first, st.starts_below, st.starts_above, st.newton_iterations,
                st.seconds, dmu, du, v[0]);
}

/* h_rms 0.1 um, two points a decade from 1e-8 m/s (1e-12 Pa m, boundary)
 * to 1000 m/s; mid-curve sweeps from 0.0316 m/s (the loss peak) and from
 * 100 m/s (hydrodynamic). */
static void test_start_mid_curve(void **state) {
  (void)state;
  enum { N = 23 };
  double v[N];
  for (int i = 0; i < N; i++)
    v[i] = 1e-8 * pow(10.0, 0.5 * i);
  vl_point ref[N];
  vl_sweep_stats st;
  sweep_all(1e-7, N, v, ref, &st);
  print_message("h_rms 1e-07 m from %g m/s: %zu points, %ld Newton iterations, %.1f s\n", v[0],
                (size_t)N, st.newton_iterations, st.seconds);
  agree(1e-7, 13, 18, v, ref); /* 0.0316 ... 1 m/s */
  agree(1e-7, 20, N, v, ref);  /* 100 ... 1000 m/s */
}

/* h_rms 30 nm, two points a decade from 1e-8 to 10 m/s, then 15.8 m/s
 * (just above the fold), 31.6 and 100 m/s; mid-curve sweep from 15.8 m/s. */
static void test_start_above_fold(void **state) {
  (void)state;
  enum { N = 22 };
  double v[N];
  for (int i = 0; i < 19; i++)
    v[i] = 1e-8 * pow(10.0, 0.5 * i);
  v[19] = 15.8;
  v[20] = 31.6;
  v[21] = 100.0;
  vl_point ref[N];
  vl_sweep_stats st;
  sweep_all(3e-8, N, v, ref, &st);
  print_message("h_rms 3e-08 m from %g m/s: %zu points, %ld Newton iterations, %.1f s; u_min "
                "%.3g m at 10 m/s, %.3g m at 15.8 m/s\n",
                v[0], (size_t)N, st.newton_iterations, st.seconds, ref[18].u_min_m,
                ref[19].u_min_m);
  /* the film has lifted off between 10 and 15.8 m/s (the fold) */
  assert_true(ref[18].u_min_m < 3e-8 && ref[19].u_min_m > 3e-8);
  agree(3e-8, 19, N, v, ref);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_start_mid_curve),
      cmocka_unit_test(test_start_above_fold),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
