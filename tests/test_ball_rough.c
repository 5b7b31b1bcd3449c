/* Validation of the rough ball (src/solver/point_ehl.h with a roughness;
 * docs/POINT_CONTACT.md section 10):
 *  - dry, elastic: against an independent axisymmetric solution of the
 *    same equations (tests/oracles/ball_axisym.c: rings, the elliptic
 *    Boussinesq kernel by adaptive quadrature, Newton), with the same
 *    contact law (Persson's u(p) of one surface): the separation at the
 *    centre, the peak pressure and the real contact area;
 *  - lubricated, where the film stands thousands of h_rms apart: the
 *    smooth ball's solution (the flow factors tend to 1, the asperities
 *    carry nothing);
 *  - a short Stribeck curve through the public API: every point converged
 *    with its estimate, the load balanced, the fluid's share rising and
 *    the asperities' friction falling with speed.
 * Figures measured here are in docs/POINT_CONTACT.md section 10. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
/* cmocka.h needs the four above first (own block: not re-sorted) */
#include <cmocka.h>

#include "vl_test_scenes.h"
#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "ball_axisym.h"
#include "persson_internal.h"
#include "point_ehl.h"
#include "viscolube/point_contact.h"
#include "viscolube/roughness.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* A 19.05 mm (3/4 inch) ball on an elastic rubber (2 MPa) under 3 N. */
static void base_config(vl_point_ehl_config *c, const vl_persson *tab) {
  vl_point_ehl_config_defaults(c);
  c->radius_m = 0.009525, c->load_n = 3.0, c->rubber.e_inf_pa = 2e6, c->rubber.nu = 0.5;
  c->roughness = tab;
  c->flow_factors = VL_FLOW_FACTORS_PATIR_CHENG;
  c->sigma_s_pa = 1e6;
  c->v0_m_s = 0.01;
}

static void set_cells(vl_point_ehl_config *c, double h) {
  c->h_fine = h, c->h_coarse = 7.5 * h, c->growth = 25.0 * h;
}

typedef struct {
  const vl_persson *tab;
  double er;
} law_ctx;

static double persson_law(void *user, double u, double *dpdu) {
  law_ctx *l = user;
  double ds, s = vl_persson_pressure(l->tab, u, &ds);
  if (dpdu) *dpdu = l->er * ds;
  return l->er * s;
}

/* The dry rough elastic ball on two grids against the axisymmetric
 * oracle on 240 rings over 1.6 a (the 2-D domain's shortest reach). */
static void dry_rough_matches_axisymmetric(void **state) {
  (void)state;
  vl_psd psd;
  vl_persson *tab = vl_test_paper_surface(1e-6, &psd);
  vl_point_ehl_config c;
  base_config(&c, tab);
  c.eta_pa_s = 0.0;
  double er = 2e6 / (1.0 - 0.25), a = cbrt(0.75 * c.load_n * c.radius_m / er);
  law_ctx law = {tab, er};
  size_t nr = getenv("RINGS") ? (size_t)atoi(getenv("RINGS")) : 240;
  vl_oracle_axisym_problem pb = {c.radius_m, c.load_n, er, 1.6 * a, nr, persson_law, &law};
  vl_oracle_axisym_solution ref;
  double *pr = malloc(nr * sizeof *pr), *rr = malloc(nr * sizeof *rr);
  assert_int_equal(vl_oracle_axisym_solve(&pb, &ref, pr, rr), 0);
  double area_ref = 0.0, h = 1.6 * a / (double)nr;
  for (size_t i = 0; i < nr; i++)
    area_ref +=
        vl_persson_area_ratio(tab, pr[i] / er, NULL) * M_PI * h * h * (2.0 * (double)i + 1.0);
  print_message("oracle: u0 %.6g m, h0 %.6g m, p_max %.6g Pa, area %.6g m2 (%d Newton)\n", ref.u0_m,
                ref.h0_m, ref.p_max_pa, area_ref, ref.iterations);
  /* measured (docs/POINT_CONTACT.md section 10): the approach -0.136 %,
   * -0.031 %, the centre row's pressure 6.9 %, 1.9 % of the peak (both
   * falling at second order), the centre's separation -0.27 %, +0.49 % (a
   * film of 5e-4 of the approach: its error is 2.5e-7 of the approach) */
  const double hs[2] = {0.08, 0.04};
  double err_h0[2], err_p[2];
  for (int g = 0; g < 2; g++) {
    set_cells(&c, hs[g]);
    vl_point_ehl_result r;
    vl_point_ehl_map m;
    vl_error err;
    assert_int_equal(vl_point_ehl_solve(&c, NULL, &r, &m, &err), VL_OK);
    /* the pressure along the centre row against the oracle's at the same
     * radius (linear between its rings), relative to its peak */
    double worst = 0.0;
    for (size_t i = 0; i < m.nx; i++) {
      double x = m.x_m[i * m.ny], y = m.y_m[0], rad = hypot(x, y);
      size_t k = (size_t)fmin((double)nr - 2.0, fmax(0.0, floor(rad / h - 0.5)));
      double t = (rad - rr[k]) / h, pref = (1.0 - t) * pr[k] + t * pr[k + 1];
      if (rad < 1.5 * a) worst = fmax(worst, fabs(m.pc_pa[i * m.ny] - pref) / ref.p_max_pa);
    }
    err_h0[g] = fabs(r.h0_m / ref.h0_m - 1.0), err_p[g] = worst;
    print_message(
        "cells %.3g a (%zu x %zu): u0 %.6g (%+.3f %%), h0 %.6g (%+.4f %%), axis p %.3f %%, "
        "area %+.4f %%, load %.1e, mu_Rc %.2e, %ld Newton, %.2f s\n",
        hs[g], r.nx, r.ny, r.h_c_m, 100.0 * (r.h_c_m / ref.u0_m - 1.0), r.h0_m,
        100.0 * (r.h0_m / ref.h0_m - 1.0), 100.0 * worst, 100.0 * (r.real_area_m2 / area_ref - 1.0),
        r.load_error, r.mu_Rc, r.iterations, r.t_influence_s + r.t_solve_s);
    assert_true(fabs(r.load_error) < 1e-9);
    /* the real area is linear in the load at these pressures (erf's
     * linear range): a check of the sums, not of the mechanics */
    assert_true(fabs(r.real_area_m2 / area_ref - 1.0) < 1e-4);
    assert_true(fabs(r.h_c_m / ref.u0_m - 1.0) < 0.01);
    vl_point_ehl_map_free(&m);
  }
  assert_true(err_h0[1] < 1e-3 && err_p[1] < 0.03);
  /* second order: halving the cells divides both by 3 or more */
  assert_true(err_h0[1] < err_h0[0] / 3.0 && err_p[1] < err_p[0] / 3.0);
  free(pr), free(rr);
  vl_persson_free(tab);
}

/* A film thousands of h_rms thick (h_rms 5 nm, 1 m/s: about 10 um): the
 * rough solution is the smooth one (the flow factors tend to 1 as
 * (h_rms/u)^2, the asperities carry nothing), on the same cells. */
static void thick_film_is_the_smooth_film(void **state) {
  (void)state;
  vl_psd psd;
  vl_persson *tab = vl_test_paper_surface(5e-9, &psd);
  vl_point_ehl_config c;
  base_config(&c, tab);
  c.eta_pa_s = 0.1, c.v0_m_s = 1.0;
  set_cells(&c, 0.08);
  vl_point_ehl_result rough, smooth;
  vl_error err;
  assert_int_equal(vl_point_ehl_solve(&c, NULL, &rough, NULL, &err), VL_OK);
  c.roughness = NULL;
  assert_int_equal(vl_point_ehl_solve(&c, NULL, &smooth, NULL, &err), VL_OK);
  print_message("rough: mu_Rf %.8g mu_Sf %.8g h_min %.6g m, fluid %.9f, mu_Rc %.2e mu_Sc %.2e; "
                "smooth: mu_Rf %.8g mu_Sf %.8g h_min %.6g m\n",
                rough.mu_Rf, rough.mu_Sf, rough.h_min_m, rough.fluid_load_fraction, rough.mu_Rc,
                rough.mu_Sc, smooth.mu_Rf, smooth.mu_Sf, smooth.h_min_m);
  assert_true(fabs(rough.mu_Rf / smooth.mu_Rf - 1.0) < 1e-3);
  assert_true(fabs(rough.mu_Sf / smooth.mu_Sf - 1.0) < 1e-3);
  assert_true(fabs(rough.h_min_m / smooth.h_min_m - 1.0) < 1e-3);
  assert_true(rough.fluid_load_fraction > 1.0 - 1e-6);
  assert_true(fabs(rough.mu_Rc) < 1e-9 && rough.mu_Sc < 1e-9);
  vl_persson_free(tab);
}

/* A short Stribeck curve of the rough lubricated ball through the public
 * API (automatic cells, estimates, each point started from the last). */
static void rough_curve_through_the_api(void **state) {
  (void)state;
  vl_psd psd;
  vl_persson *tab = vl_test_paper_surface(1e-6, &psd);
  vl_point_contact_config c;
  vl_point_contact_config_defaults(&c);
  c.rubber.e_inf_pa = 2e6, c.rubber.nu = 0.5;
  c.radius_x_m = c.radius_y_m = 0.009525, c.load_n = 3.0;
  c.eta_pa_s = 0.1, c.sigma_s_pa = 1e6;
  c.roughness = tab, c.flow_factors = VL_FLOW_FACTORS_PATIR_CHENG;
  c.cells_per_a0 = 12.5; /* finest cells 0.08 a0 (the estimate's 0.16) */
  const double v[4] = {1e-4, 1e-3, 1e-2, 1e-1};
  vl_point pts[4];
  vl_auto_options o = {0.05, 0, true}; /* these cells, no refinement */
  vl_sweep_stats st;
  vl_error err;
  assert_int_equal(vl_point_contact_sweep(&c, &o, 4, v, pts, NULL, NULL, &st, &err), VL_OK);
  for (int i = 0; i < 4; i++) {
    const vl_point *p = &pts[i];
    print_message("v0 %g: mu %.5g (Rc %.3g Rf %.3g Sc %.3g Sf %.3g), fluid %.3f, u_min/h_rms %.3g, "
                  "%s, estimate %.2g %%, %ld Newton, area %.3g m2\n",
                  v[i], p->mu, p->mu_Rc, p->mu_Rf, p->mu_Sc, p->mu_Sf, p->fluid_load_fraction,
                  p->u_min_over_h_rms, vl_regime_name(p->regime), 100.0 * p->error_estimate,
                  p->iterations, p->ball.contact_area_m2);
    assert_true(p->converged);
    assert_true(isfinite(p->error_estimate) && p->error_estimate >= 0.0);
    assert_true(p->load_error < 1e-9);
    assert_true(fabs(p->mu - (p->mu_Rc + p->mu_Rf + p->mu_Sc + p->mu_Sf)) < 1e-12);
    if (i > 0) { /* the film lifts: the fluid takes the load from the asperities */
      assert_true(p->fluid_load_fraction > pts[i - 1].fluid_load_fraction);
      assert_true(p->mu_Sc < pts[i - 1].mu_Sc);
      assert_true(p->u_min_over_h_rms > pts[i - 1].u_min_over_h_rms);
    }
  }
  vl_persson_free(tab);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(dry_rough_matches_axisymmetric),
      cmocka_unit_test(thick_film_is_the_smooth_film),
      cmocka_unit_test(rough_curve_through_the_api),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
