/* Viscous flattening coupled into the contact solver ([effects]
 * viscous_flattening = on; seed Appendix C, src/contact.c flat_scale):
 * the PSD seen by the contact and the flow factors becomes epsilon_f(u) C(q)
 * at each node. Checked here:
 *   - the derivation the coupling rests on, u_eps(p) = sqrt(eps) u(p/sqrt(eps))
 *     and A_eps(p) = A(p/sqrt(eps)), against Persson's theory evaluated
 *     directly for the scaled PSD (an independent quadrature of Eq. 8);
 *   - at a converged state where epsilon_f drops to ~0.65, the contact
 *     pressure and area of every kind of node equal Persson's for the PSD
 *     scaled by that node's epsilon_f (a separately built table);
 *   - the analytic Jacobian (chain rule through epsilon_f(u)) against finite
 *     differences, per block of rows;
 *   - epsilon_f = 1 (thick film): identical to the contact without the effect;
 *   - the evaluator follows the contact's speed and viscosity; inputs the
 *     effect cannot take are refused;
 *   - a scene with viscous_flattening = on through `viscolube run`. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "contact_private.h"
#include "vl_test_scenes.h"
#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact_test.h"
#include "flattening_internal.h"
#include "persson_internal.h"
#include "sweep_internal.h"
#include "viscolube/contact.h"
#include "viscolube/flattening.h"
#include "viscolube/persson.h"
#include "viscolube/sweep.h"

/* The paper surface's spectrum (seed: H = 0.8, q0 = 2e5, q1 = 7.8e9 1/m). */
#define HURST 0.8
#define Q0 2e5
#define Q1 7.8e9

static vl_psd paper(double hrms_m) {
  vl_psd psd;
  vl_error err;
  if (vl_psd_init_self_affine(&psd, HURST, Q0, Q1, hrms_m, &err) != VL_OK) fail_msg("%s", err.msg);
  return psd;
}

static vl_persson *table_of(const vl_psd *psd) {
  vl_persson *t = NULL;
  vl_error err;
  if (vl_persson_build(psd, 0, &t, &err) != VL_OK) fail_msg("%s", err.msg);
  return t;
}

/* ---- the scaling identity, from Persson's Eq. 8 itself -------------------
 * C -> eps C gives w(q) -> w/sqrt(eps), so
 *   u_eps(p) = (sqrt(pi)/2) \int q^2 eps C (w/sqrt(eps)) E1((w p/(sqrt(eps) E))^2) dq
 *            = sqrt(eps) u(p/sqrt(eps)),
 * and G -> eps G in A/A0 = erf(p/(2 sqrt(G))). A self-affine PSD scales as
 * h_rms^2 (C0 ~ h_rms^2), so h_rms -> sqrt(eps) h_rms is exactly C -> eps C.
 * vl_persson_separation_exact integrates Eq. 8 for each surface on its own
 * (no table): both sides agree to the quadrature's rounding, measured
 * <= 2e-15; bound 1e-12. Area and g: rounding (1e-14). The tables of the
 * two surfaces (what the solver interpolates), s(u) = sqrt(eps) s1(u/sqrt(eps)):
 * within their interpolation error, 5e-8 each (test_persson), bound 2e-7;
 * measured 1.6e-14, as each table places its nodes relative to its h_rms
 * and so interpolates the same function scaled. */
static void test_scaling_identity(void **state) {
  (void)state;
  const double h = 3e-6, eps[] = {0.8, 0.5, 0.2, 0.02};
  vl_psd p1 = paper(h);
  vl_persson *t1 = table_of(&p1);
  double g1 = vl_persson_g(t1);
  double worst_exact = 0.0, worst_area = 0.0, worst_table = 0.0;
  for (size_t k = 0; k < sizeof eps / sizeof *eps; k++) {
    double s = sqrt(eps[k]);
    vl_psd pe = paper(h * s);
    vl_persson *te = table_of(&pe);
    assert_true(vl_test_rel(vl_persson_g(te), eps[k] * g1) < 1e-14);
    /* dimensionless pressures p/|Er| spanning u from ~10 h_rms to ~0.01 h_rms */
    for (int j = 0; j <= 12; j++) {
      double pr = pow(10.0, -9.0 + 8.0 * j / 12.0);
      double ue = vl_persson_separation_exact(te, pr);
      double u1 = s * vl_persson_separation_exact(t1, pr / s);
      worst_exact = fmax(worst_exact, vl_test_rel(ue, u1));
      worst_area = fmax(worst_area, vl_test_rel(vl_persson_area_ratio(te, pr, NULL),
                                                vl_persson_area_ratio(t1, pr / s, NULL)));
    }
    for (int j = 0; j <= 40; j++) {
      double u = h * s * pow(10.0, -2.0 + 3.0 * j / 40.0); /* 0.01 .. 10 of its h_rms */
      worst_table = fmax(worst_table, vl_test_rel(vl_persson_pressure(te, u, NULL),
                                                  s * vl_persson_pressure(t1, u / s, NULL)));
    }
    vl_persson_free(te);
    vl_psd_free(&pe);
  }
  print_message("u_eps(p) vs sqrt(eps) u(p/sqrt(eps)): exact %.2e, area %.2e, tables %.2e\n",
                worst_exact, worst_area, worst_table);
  assert_true(worst_exact < 1e-12);
  assert_true(worst_area < 1e-14);
  assert_true(worst_table < 2e-7);
  vl_persson_free(t1);
  vl_psd_free(&p1);
}

/* ---- a contact whose film flattens the roughness noticeably --------------
 * The model rubber (E0 3.6 MPa, Einf/E0 10, tau 0.1 s) in the real-rubber
 * contact (R 1 mm, fN 117 N/m) on the paper spectrum with h_rms 0.3 um,
 * eta 1 Pa s, Patir-Cheng factors: at v0 = 5.6e-4 m/s the mixed film is
 * u_min ~ 0.64 h_rms thick and epsilon_f(u_min) ~ 0.65 (a thick film or a
 * stiff compound leaves epsilon_f = 1 to rounding: fig05, fig19/20).
 * Continuation from 1e-6 m/s, where epsilon_f ~ 1 (a fresh Hertz start at
 * the target speed separates less than the flattened asperities can carry
 * and does not converge). */
#define A_HRMS 3e-7
#define A_ETA 1.0
#define A_GRID 128
static const double A_SPEEDS[] = {1e-6, 1e-5, 1e-4, 3e-4, 5.6e-4};
#define A_N (sizeof A_SPEEDS / sizeof *A_SPEEDS)

typedef struct {
  vl_psd psd;
  vl_persson *table;
  vl_flattening_config flat; /* the settings the contact builds its evaluator from */
  vl_contact *c;
  vl_point pt[8];
} fixture;

static void fixture_config(vl_contact_config *cfg, const vl_persson *table, double eta,
                           double radius_m, double load_n_per_m, size_t grid) {
  vl_test_fig05_config(cfg, table, eta, grid, -3.0);
  cfg->radius_m = radius_m;
  cfg->load_n_per_m = load_n_per_m;
}

/* The flattening settings of a contact (its rubber, load, radius and fluid). */
static vl_flattening_config flattening_for(const vl_contact_config *cfg) {
  vl_flattening_config fc;
  vl_flattening_config_defaults(&fc);
  fc.rubber = cfg->rubber;
  fc.load_n_per_m = cfg->load_n_per_m;
  fc.radius_m = cfg->radius_m;
  fc.eta_pa_s = cfg->eta_pa_s;
  return fc;
}

/* An evaluator of those settings, built apart from any contact. */
static vl_flattening *evaluator_for(const vl_contact_config *cfg, const vl_psd *psd) {
  vl_flattening_config fc = flattening_for(cfg);
  vl_flattening *f = NULL;
  vl_error err;
  if (vl_flattening_create(&fc, psd, &f, &err) != VL_OK) fail_msg("%s", err.msg);
  return f;
}

static void fixture_solve(fixture *fx, bool flattening) {
  fx->psd = paper(A_HRMS);
  fx->table = table_of(&fx->psd);
  vl_contact_config cfg;
  fixture_config(&cfg, fx->table, A_ETA, 1e-3, 117.0, A_GRID);
  fx->flat = flattening_for(&cfg);
  if (flattening) cfg.flattening = &fx->flat, cfg.flattening_psd = &fx->psd;
  vl_error err;
  if (vl_contact_create(&cfg, &fx->c, &err) != VL_OK) fail_msg("%s", err.msg);
  vl_sweep_stats st;
  assert_int_equal(vl_sweep_run(fx->c, A_N, A_SPEEDS, NULL, fx->pt, NULL, NULL, &st, &err), VL_OK);
  for (size_t i = 0; i < A_N; i++) {
    if (!fx->pt[i].converged) fail_msg("v0 %g did not converge", A_SPEEDS[i]);
    assert_true(fx->pt[i].load_error < 1e-8);
  }
}

static void fixture_free(fixture *fx) {
  vl_contact_free(fx->c);
  vl_persson_free(fx->table);
  vl_psd_free(&fx->psd);
}

/* The analytic Jacobian against central differences, per block of rows,
 * each relative to its own largest entry (the Reynolds rows set the global
 * scale and would hide the elasticity rows, where the chain rule through
 * epsilon_f acts most). Measured at epsilon_f(u_min) = 0.645: contact rows
 * 2.0e-7, Reynolds 2.6e-7, load 3.3e-7 (without the effect at its own
 * state: 1.3e-7, 2.3e-7, 8e-8: the finite differences' own error, from
 * the C1 interpolants of the Persson table and the flow factors and the
 * smoothed complementarity). Bound 1e-6, as the other Jacobian checks.
 * Dropping a chain-rule term shows: without d eps/du in dpc/du the
 * contact rows' error is 0.55 (load 1.2); without it in the flow factors'
 * or the Couette film's derivative the Reynolds rows' 1e-4. */
static void test_jacobian(void **state) {
  (void)state;
  fixture fx;
  fixture_solve(&fx, true);
  const vl_point *p = &fx.pt[A_N - 1];
  print_message("v0 %g m/s: u_min %.3f h_rms, eps_f_min %.4f, fluid load %.3f\n", p->v0_m_s,
                p->u_min_m / A_HRMS, p->eps_f_min, p->fluid_load_fraction);
  assert_true(p->eps_f_min > 0.3 && p->eps_f_min < 0.8); /* the effect is at work */
  /* epsilon_f depends on u only: the Reynolds rows' pf block stays
   * tridiagonal and the default Schur-complement solver never fell back to
   * the full LU (its solutions are checked against the full matrix) */
  vl_contact_timing tm;
  vl_contact_timing_get(fx.c, &tm);
  assert_true(tm.setups > 0);
  assert_int_equal(tm.linsol_fallbacks, 0);
  double rel[3];
  double e = vl_contact_jacobian_check_blocks(fx.c, p->v0_m_s, rel);
  print_message("Jacobian with flattening: contact rows %.2e, Reynolds rows %.2e, load %.2e\n",
                rel[0], rel[1], rel[2]);
  assert_true(e >= 0.0 && e < 1e-6);
  /* the global measure of the other tests, for comparison */
  double g = vl_contact_jacobian_check(fx.c, p->v0_m_s);
  print_message("global max |J_fd - J|/max |J| = %.2e\n", g);
  assert_true(g >= 0.0 && g < 1e-6);
  fixture_free(&fx);
}

/* The converged flattened state against Persson's theory of the scaled
 * PSD, node by node: for nodes with the smallest epsilon_f (u_min) and
 * epsilon_f near 0.7, 0.8, 0.9 and 0.99, eps_i = epsilon_f(u_i) from the
 * evaluator, a table built for h_rms sqrt(eps_i) (C -> eps_i C), and
 *   pc_i = |Er(wH)| s_eps_i(u_i),  A/A0_i = erf-law of that table at pc_i.
 * Tolerance 3e-7: the two tables' interpolation error (5e-8 each,
 * test_persson) amplified by d ln s/d ln u (~3 here); measured <= 2e-15
 * (see test_scaling_identity). Also eps_f_min is epsilon_f at u_min
 * (epsilon_f increases with u). */
static void test_scaled_psd(void **state) {
  (void)state;
  fixture fx;
  fixture_solve(&fx, true);
  const vl_point *p = &fx.pt[A_N - 1];
  size_t n = vl_contact_grid(fx.c);
  double *b = calloc(6 * n, sizeof *b);
  assert_non_null(b);
  vl_fields f = {n, b, b + n, b + 2 * n, b + 3 * n, b + 4 * n, b + 5 * n, NULL};
  vl_contact_fields(fx.c, &f);
  double eps_umin = vl_flattening_eps(vl_contact_flattening(fx.c), p->u_min_m, NULL);
  print_message("eps_f_min %.12f, epsilon_f(u_min) %.12f\n", p->eps_f_min, eps_umin);
  assert_true(fabs(p->eps_f_min - eps_umin) < 1e-12);
  const double targets[] = {0.0, 0.7, 0.8, 0.9, 0.99};
  double worst_p = 0.0, worst_a = 0.0;
  for (size_t k = 0; k < sizeof targets / sizeof *targets; k++) {
    /* the loaded node (pc above 1 % of the peak) whose eps is nearest the target */
    double pmax = 0.0;
    for (size_t i = 0; i < n; i++)
      pmax = fmax(pmax, f.p_c_pa[i]);
    size_t best = SIZE_MAX;
    double best_d = INFINITY;
    for (size_t i = 0; i < n; i++) {
      if (f.p_c_pa[i] < 0.01 * pmax) continue;
      double d = fabs(vl_flattening_eps(vl_contact_flattening(fx.c), f.u_m[i], NULL) - targets[k]);
      if (d < best_d) best_d = d, best = i;
    }
    assert_true(best != SIZE_MAX);
    double u = f.u_m[best], eps = vl_flattening_eps(vl_contact_flattening(fx.c), u, NULL);
    vl_psd ps = paper(A_HRMS * sqrt(eps));
    vl_persson *ts = table_of(&ps);
    double pc = p->E_wH_pa * vl_persson_pressure(ts, u, NULL);
    double area = vl_persson_area_ratio(ts, f.p_c_pa[best] / p->E_wH_pa, NULL);
    print_message("  node %3zu: u %.4f h_rms, eps %.4f: pc %.6e vs scaled-PSD %.6e (%.1e), "
                  "A/A0 %.6f vs %.6f (%.1e)\n",
                  best, u / A_HRMS, eps, f.p_c_pa[best], pc, vl_test_rel(f.p_c_pa[best], pc),
                  f.area_ratio[best], area, vl_test_rel(f.area_ratio[best], area));
    worst_p = fmax(worst_p, vl_test_rel(f.p_c_pa[best], pc));
    worst_a = fmax(worst_a, vl_test_rel(f.area_ratio[best], area));
    vl_persson_free(ts);
    vl_psd_free(&ps);
  }
  assert_true(worst_p < 3e-7);
  assert_true(worst_a < 3e-7);
  free(b);
  fixture_free(&fx);
}

/* The same contact without the effect: flattening lowers the asperity
 * pressure at a given separation (s p(u/s) < p(u): s < 1, u/s > u and p
 * decreases), so the mixed film is thinner and the fluid carries more: a
 * check of direction, not of size. */
static void test_direction(void **state) {
  (void)state;
  fixture on, off;
  fixture_solve(&on, true);
  fixture_solve(&off, false);
  const vl_point *a = &on.pt[A_N - 1], *b = &off.pt[A_N - 1];
  print_message("on: u_min %.4f h_rms, fluid %.3f, mu %.5f; off: %.4f h_rms, %.3f, %.5f\n",
                a->u_min_m / A_HRMS, a->fluid_load_fraction, a->mu, b->u_min_m / A_HRMS,
                b->fluid_load_fraction, b->mu);
  assert_true(b->eps_f_min == 1.0);
  assert_true(a->u_min_m < b->u_min_m);
  assert_true(a->fluid_load_fraction > b->fluid_load_fraction);
  fixture_free(&on);
  fixture_free(&off);
}

/* ---- epsilon_f = 1: nothing changes -----------------------------------------
 * The fig05 contact (R 1 cm, fN 1 kN/m, h_rms 3 um, eta 1e-4 Pa s) in the
 * boundary regime, u ~ 1.2 h_rms, v0 eta <= 1e-6 Pa m: 1 - epsilon_f ~ t^2/2
 * with t = 12 eta v0 |J| / (u^3 q0^2) < 1e-8, so epsilon_f = 1 to rounding,
 * and every reported quantity and field must equal the contact's without
 * the effect to 1e-12 (the same Newton path; only rounding in
 * sqrt(epsilon_f) could differ). At v0 eta = 1e-4 Pa m, 1 - epsilon_f =
 * 5e-13 already moves the results by 6e-13. */
static void test_thick_film_identical(void **state) {
  (void)state;
  vl_psd psd = paper(3e-6);
  vl_persson *tab = table_of(&psd);
  const double v[] = {1e-4, 1e-3, 1e-2}; /* v0 eta = 1e-8 .. 1e-6 Pa m */
  vl_point pt[2][3];
  double *fld[2];
  size_t n = 128;
  vl_flattening_config flat;
  for (int on = 0; on < 2; on++) {
    vl_contact_config cfg;
    fixture_config(&cfg, tab, 1e-4, 0.01, 1000.0, n);
    cfg.x_min_a0 = -5.0;
    flat = flattening_for(&cfg);
    if (on) cfg.flattening = &flat, cfg.flattening_psd = &psd;
    vl_contact *c;
    vl_error err;
    assert_int_equal(vl_contact_create(&cfg, &c, &err), VL_OK);
    assert_int_equal(vl_sweep_run(c, 3, v, NULL, pt[on], NULL, NULL, NULL, &err), VL_OK);
    fld[on] = calloc(6 * n, sizeof *fld[on]);
    assert_non_null(fld[on]);
    double *b = fld[on];
    vl_fields f = {n, b, b + n, b + 2 * n, b + 3 * n, b + 4 * n, b + 5 * n, NULL};
    vl_contact_fields(c, &f);
    vl_contact_free(c);
  }
  double worst = 0.0;
  for (int i = 0; i < 3; i++) {
    const vl_point *a = &pt[1][i], *b = &pt[0][i];
    assert_true(a->converged && b->converged);
    assert_true(a->eps_f_min > 1.0 - 1e-12 && b->eps_f_min == 1.0);
    assert_int_equal(a->iterations, b->iterations);
    const double pa[] = {a->mu,
                         a->mu_Rc,
                         a->mu_Rf,
                         a->mu_Sc,
                         a->mu_Sf,
                         a->u_min_m,
                         a->u_central_m,
                         a->x_centroid_m,
                         a->contact_width_m,
                         a->fluid_load_fraction,
                         a->peak_pressure_pa};
    const double pb[] = {b->mu,
                         b->mu_Rc,
                         b->mu_Rf,
                         b->mu_Sc,
                         b->mu_Sf,
                         b->u_min_m,
                         b->u_central_m,
                         b->x_centroid_m,
                         b->contact_width_m,
                         b->fluid_load_fraction,
                         b->peak_pressure_pa};
    for (size_t k = 0; k < sizeof pa / sizeof *pa; k++)
      worst = fmax(worst, fabs(pa[k] - pb[k]) / fmax(fabs(pb[k]), 1e-300));
  }
  /* fields of the last point: pressures relative to the peak, u to u_min */
  double pk = 0.0, worst_f = 0.0;
  for (size_t i = 0; i < n; i++)
    pk = fmax(pk, fld[0][2 * n + i] + fld[0][n + i]);
  for (size_t i = 0; i < n; i++) {
    worst_f = fmax(worst_f, fabs(fld[1][n + i] - fld[0][n + i]) / pk);          /* p_f */
    worst_f = fmax(worst_f, fabs(fld[1][2 * n + i] - fld[0][2 * n + i]) / pk);  /* p_c */
    worst_f = fmax(worst_f, vl_test_rel(fld[1][3 * n + i], fld[0][3 * n + i])); /* u */
    worst_f = fmax(worst_f, fabs(fld[1][4 * n + i] - fld[0][4 * n + i]));       /* A/A0 */
  }
  print_message("eps_f_min %.17g; on vs off: points %.2e, fields %.2e\n", pt[1][2].eps_f_min, worst,
                worst_f);
  assert_true(worst < 1e-12 && worst_f < 1e-12);
  free(fld[0]);
  free(fld[1]);
  vl_persson_free(tab);
  vl_psd_free(&psd);
}

/* The contact drives its evaluator: the speed of each solve, and the
 * viscosity of vl_contact_set_viscosity (u_onset ~ eta^(1/3): 8x eta
 * doubles it) and of the configuration at create. */
static void test_follows_speed_and_viscosity(void **state) {
  (void)state;
  vl_psd psd = paper(A_HRMS);
  vl_persson *tab = table_of(&psd);
  vl_contact_config cfg;
  fixture_config(&cfg, tab, A_ETA, 1e-3, 117.0, A_GRID);
  /* the settings and the reference ref are for A_ETA; the contact's 2 A_ETA
   * replaces it at create */
  vl_flattening_config fc = flattening_for(&cfg);
  vl_flattening *ref = evaluator_for(&cfg, &psd);
  cfg.eta_pa_s = 2.0 * A_ETA;
  cfg.flattening = &fc;
  cfg.flattening_psd = &psd;
  vl_contact *c;
  vl_error err;
  assert_int_equal(vl_contact_create(&cfg, &c, &err), VL_OK);
  vl_point pt;
  assert_int_equal(vl_contact_solve(c, 1e-6, &pt, &err), VL_OK);
  vl_flattening_state s1, s0;
  vl_flattening_state_get(vl_contact_flattening(c), &s1);
  vl_flattening_set_speed(ref, 1e-6, NULL);
  vl_flattening_state_get(ref, &s0);
  assert_true(s1.v0_m_s == 1e-6);
  assert_true(vl_test_rel(s1.u_onset_m, cbrt(2.0) * s0.u_onset_m) < 1e-12);
  assert_int_equal(vl_contact_set_viscosity(c, 16.0 * A_ETA, &err), VL_OK);
  vl_flattening_state_get(vl_contact_flattening(c), &s1);
  assert_true(vl_test_rel(s1.u_onset_m, 2.0 * cbrt(2.0) * s0.u_onset_m) < 1e-12);
  vl_contact_free(c);
  vl_flattening_free(ref);
  vl_persson_free(tab);
  vl_psd_free(&psd);
}

/* Flattening needs a rough surface, a fluid, and the same surface as the
 * roughness table: each refused with a message saying which. */
static void test_refusals(void **state) {
  (void)state;
  vl_psd psd = paper(A_HRMS), other = paper(2.0 * A_HRMS);
  vl_persson *tab = table_of(&psd), *tab2 = table_of(&other);
  vl_contact_config cfg;
  fixture_config(&cfg, tab, A_ETA, 1e-3, 117.0, 64);
  vl_flattening_config flat = flattening_for(&cfg);
  vl_contact *c = NULL;
  vl_error err;
  struct {
    const vl_persson *table;
    double eta;
    const char *needle;
  } bad[] = {{NULL, A_ETA, "rough surface"}, {tab, 0.0, "fluid"}, {tab2, A_ETA, "h_rms"}};
  for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
    cfg.roughness = bad[k].table;
    cfg.eta_pa_s = bad[k].eta;
    cfg.flattening = &flat;
    cfg.flattening_psd = &psd;
    err.msg[0] = '\0';
    assert_int_equal(vl_contact_create(&cfg, &c, &err), VL_EINPUT);
    assert_null(c);
    if (!strstr(err.msg, bad[k].needle) || !strstr(err.msg, "flattening"))
      fail_msg("case %zu: '%s' lacks '%s'", k, err.msg, bad[k].needle);
  }
  vl_persson_free(tab);
  vl_persson_free(tab2);
  vl_psd_free(&psd);
  vl_psd_free(&other);
}

/* ---- the scene effect through the command line ----------------------------
 * cases/fig05.ini with viscous_flattening = on, grid 128, one point a decade
 * and fields at one more speed: runs, every row converged, eps_f_min present in
 * (0, 1] (the modulus response keeps epsilon_f <= 1). */
static char *replace(const char *text, const char *old, const char *new) {
  const char *at = strstr(text, old);
  if (!at) fail_msg("'%s' not in the case file", old);
  size_t n = strlen(text) - strlen(old) + strlen(new) + 1;
  char *out = malloc(n);
  assert_non_null(out);
  snprintf(out, n, "%.*s%s%s", (int)(at - text), text, new, at + strlen(old));
  return out;
}

/* The next comma- or newline-terminated cell of *p (modified in place);
 * NULL at the end of the line. */
static char *next_cell(char **p) {
  if (!*p) return NULL;
  char *cell = *p, *end = cell + strcspn(cell, ",\n");
  *p = *end == ',' ? end + 1 : NULL;
  *end = '\0';
  return cell;
}

static void test_cli_scene(void **state) {
  (void)state;
  char *text = vl_test_read_file(vl_test_source_path("cases/fig05.ini"));
  assert_non_null(text);
  const char *edits[][2] = {
      {"viscous_flattening = off", "viscous_flattening = on"},
      {"[numerics]\n", "[numerics]\ngrid = 488\ngrid_growth = 1.05\ndomain_a0 = -96, 1.6\n"},
      {"points = 61", "points = 13"},
      {"fields_at = 1e-7, 1e-6, 3e-6, 1e-5, 1e-3, 1e-1, 1", "fields_at = 3e-3"}};
  for (size_t k = 0; k < sizeof edits / sizeof *edits; k++) {
    char *t = replace(text, edits[k][0], edits[k][1]);
    free(text);
    text = t;
  }
  const char *scene = vl_test_scratch("fig05-flat.ini", text);
  free(text);
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "run %s --out %s/out", scene, vl_test_dir);
  /* 488 cells (for the test's time) leave points above the 1 % target:
   * every point converges, and the run says so with exit status 8 */
  if (rc != 0 && rc != 8) fail_msg("run exited %d: %s", rc, err);
  free(out), free(err);
  char path[1400];
  snprintf(path, sizeof path, "%s/out/curve.csv", vl_test_dir);
  char *csv = vl_test_read_file(path);
  assert_non_null(csv);
  /* a rough wet curve states its flow-factor model first (fig05's) */
  const char *model = "# flow_factors = patir-cheng\n";
  assert_memory_equal(csv, model, strlen(model));
  /* header: the column indices of converged and eps_f_min */
  int col_conv = -1, col_eps = -1, ncol = 0;
  char *line = csv + strlen(model), *next = strchr(line, '\n');
  assert_non_null(next);
  *next++ = '\0';
  for (char *p = line, *tok; (tok = next_cell(&p)); ncol++) {
    if (!strcmp(tok, "converged")) col_conv = ncol;
    if (!strcmp(tok, "eps_f_min")) col_eps = ncol;
  }
  assert_true(col_conv >= 0 && col_eps >= 0);
  int rows = 0;
  double lo = INFINITY;
  while ((line = next) && *line) {
    next = strchr(line, '\n');
    if (next) *next++ = '\0';
    int col = 0;
    for (char *p = line, *tok; (tok = next_cell(&p)); col++) {
      if (col == col_conv) assert_string_equal(tok, "1");
      if (col == col_eps) {
        char *end;
        double e = strtod(tok, &end);
        if (end == tok || !(e > 0.0 && e <= 1.0)) fail_msg("row %d: eps_f_min '%s'", rows, tok);
        lo = fmin(lo, e);
      }
    }
    assert_int_equal(col, ncol);
    rows++;
  }
  print_message("%d rows, smallest eps_f_min %.10g\n", rows, lo);
  assert_int_equal(rows, 14); /* 13 points and the fields speed */
  free(csv);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_scaling_identity),
      cmocka_unit_test(test_jacobian),
      cmocka_unit_test(test_scaled_psd),
      cmocka_unit_test(test_direction),
      cmocka_unit_test(test_thick_film_identical),
      cmocka_unit_test(test_follows_speed_and_viscosity),
      cmocka_unit_test(test_refusals),
      cmocka_unit_test_setup(test_cli_scene, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
