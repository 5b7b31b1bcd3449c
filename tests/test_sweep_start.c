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

#include "numerics_plan.h"
#include "sweep_internal.h"
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

/* A thin smooth film (soft EHL, no roughness): a stiff one-term rubber
 * (Einf/E0 2930, tau 22 ms), R 0.84 mm, 700 N/m, eta 1.99 Pa s, 48 cells on
 * [-2.36, 1.6] a0 (a corner of the hard-case matrix), one speed a decade from
 * 1e-12 to 100 m/s. Every start near 1e-12-1e-9 m/s fails on these cells
 * (minimum films of 1.7e-11-5.3e-10 m); the sweep reaches them by continuation down
 * from the first point that converges above them (sweep.h, path 5). */
static void thin_film_config(vl_contact_config *cfg) {
  vl_contact_config_defaults(cfg);
  cfg->rubber.e_inf_pa = 3.6e6 * 2930.0;
  cfg->rubber.nu = 0.5;
  cfg->rubber.n_terms = 1;
  cfg->rubber.tau_s[0] = 0.0223;
  cfg->rubber.A[0] = 2929.0;
  cfg->radius_m = 0.00084;
  cfg->load_n_per_m = 700.0;
  cfg->eta_pa_s = 1.99;
  cfg->flow_factors = VL_FLOW_FACTORS_SMOOTH;
  cfg->grid = 48;
  cfg->x_min_a0 = -2.36;
  cfg->x_max_a0 = 1.6;
}

typedef struct {
  int calls[16];
  int converged_without_contact;
} report_log;

static void log_report(void *user, size_t i, size_t total, const vl_point *pt,
                       const vl_contact *c) {
  report_log *l = user;
  (void)total;
  l->calls[i]++;
  if (pt->converged && !c) l->converged_without_contact++;
}

/* Whether the sweep through v converged everywhere (the contact of cfg). */
static size_t sweep_failures(const vl_contact_config *cfg, size_t n, const double *v, vl_point *pt,
                             vl_sweep_stats *st, report_log *log) {
  vl_contact *c = NULL;
  vl_error err;
  assert_int_equal(vl_contact_create(cfg, &c, &err), VL_OK);
  assert_int_equal(vl_sweep_run(c, n, v, NULL, pt, log ? log_report : NULL, log, st, &err), VL_OK);
  vl_contact_free(c);
  size_t failed = 0;
  for (size_t i = 0; i < n; i++)
    failed += !pt[i].converged;
  return failed;
}

static void test_thin_film_from_above(void **state) {
  (void)state;
  enum { N = 15, LOW = 4 };
  double v[N];
  for (int i = 0; i < N; i++)
    v[i] = 1e-12 * pow(10.0, i);
  vl_contact_config cfg;
  thin_film_config(&cfg);
  vl_point pt[N], low[LOW];
  vl_sweep_stats st, st_low;
  /* the four lowest speeds on their own: nothing converged above them */
  size_t low_failed = sweep_failures(&cfg, LOW, v, low, &st_low, NULL);
  report_log log = {{0}, 0};
  assert_int_equal(sweep_failures(&cfg, N, v, pt, &st, &log), 0);
  print_message("thin smooth film: alone, %zu of the %d lowest speeds fail; in the sweep to 100 "
                "m/s every point converges, %zu of them from above; u_min %.3g m at %g m/s, "
                "%.3g m at %g m/s\n",
                low_failed, LOW, st.recovered_below, pt[0].u_min_m, v[0], pt[LOW].u_min_m, v[LOW]);
  assert_true(low_failed > 0);
  assert_true(st.recovered_below >= low_failed);
  for (int i = 0; i < N; i++) {
    assert_int_equal(log.calls[i], 1); /* each point reported once */
    assert_true(pt[i].load_error < 1e-8);
    assert_true(pt[i].residual <= cfg.tolerance);
    /* the film thickens with speed at every step (soft EHL) */
    if (i > 0 && !(pt[i].u_min_m > pt[i - 1].u_min_m))
      fail_msg("u_min %.4g m at %g m/s, %.4g m at %g m/s", pt[i - 1].u_min_m, v[i - 1],
               pt[i].u_min_m, v[i]);
  }
  assert_int_equal(log.converged_without_contact, 0);
  /* the automatic sweep on the same cells (keep_numerics) recovers them the
   * same way, through its own copy of the contact: the same solutions */
  vl_point pa[N];
  vl_sweep_stats sa;
  vl_auto_options o = {0.0, -1, true};
  vl_error err;
  assert_int_equal(vl_sweep_run_auto(&cfg, &o, N, v, pa, NULL, NULL, &sa, &err), VL_OK);
  assert_int_equal(sa.converged, N);
  assert_true(sa.recovered_below >= low_failed);
  for (int i = 0; i < N; i++)
    if (fabs(pa[i].u_min_m - pt[i].u_min_m) > UMIN_TOL * pt[i].u_min_m)
      fail_msg("%g m/s: u_min %.6g m (automatic sweep), %.6g m (sweep)", v[i], pa[i].u_min_m,
               pt[i].u_min_m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_start_mid_curve),
      cmocka_unit_test(test_start_above_fold),
      cmocka_unit_test(test_thin_film_from_above),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
