/* The seed's statements for its wet scenes (docs/CASES.md fig05, fig10) as
 * automated checks on computed Stribeck curves and fields. The seed's flow
 * factors are not published; these curves use Patir-Cheng, so we check
 * shapes and orders of magnitude, not the paper's exact numbers. Where the
 * code disagrees with the paper, the check states the difference. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sweep_internal.h"
#include "viscolube/contact.h"
#include "viscolube/persson.h"
#include "viscolube/scene.h"
#include "viscolube/sweep.h"
#include "vl_test_scenes.h"
#include "vl_test_util.h"

#define HRMS 3e-6
enum { N = 49 }; /* 4 points per decade, v0 eta = 1e-12 ... 1 Pa m */

typedef struct {
  double v0eta[N];
  vl_point pt[N];
  double pc_max[N], x_pc_max[N], pf_max[N], x_pf_max[N]; /* p0 and a0 units */
  double eta, a0, p0;
} curve;

static void on_point(void *user, size_t i, size_t total, const vl_point *pt, const vl_contact *c) {
  (void)total, (void)pt;
  curve *cv = user;
  size_t n = vl_contact_grid(c);
  double *b = calloc(7 * n, sizeof *b);
  vl_fields f = {n, b, b + n, b + 2 * n, b + 3 * n, b + 4 * n, b + 5 * n, NULL};
  vl_contact_fields(c, &f);
  size_t ic = 0, jf = 0;
  for (size_t k = 0; k < n; k++) {
    if (f.p_c_pa[k] > f.p_c_pa[ic]) ic = k;
    if (f.p_f_pa[k] > f.p_f_pa[jf]) jf = k;
    assert_true(f.p_f_pa[k] >= -1e-9 * cv->p0 && f.p_c_pa[k] >= 0.0 && f.u_m[k] > 0.0);
    assert_true(isfinite(f.p_f_pa[k]) && isfinite(f.film_fraction[k]));
  }
  cv->pc_max[i] = f.p_c_pa[ic] / cv->p0;
  cv->x_pc_max[i] = f.x_m[ic] / cv->a0;
  cv->pf_max[i] = f.p_f_pa[jf] / cv->p0;
  cv->x_pf_max[i] = f.x_m[jf] / cv->a0;
  free(b);
}

/* The contact of the fig05/fig10/fig12 scenes (vl_test_fig05_config) at
 * the shipped numerics of rough wet scenes (include/viscolube/scene.h: a0/30
 * cells near the contact, a 96 a0 inlet graded by 1.05): the statements are
 * checked on the curves users get. */
static void shipped_config(vl_contact_config *cfg, const vl_persson *tab, double eta) {
  vl_test_fig05_config(cfg, tab, eta, VL_WET_ROUGH_GRID, VL_WET_ROUGH_DOMAIN_MIN_A0);
  cfg->grid_growth = VL_WET_GRID_GROWTH;
}

/* The fig05/fig10 scene (model rubber, paper surface 3 um, sigma_s 1 MPa). */
static void stribeck(double eta, curve *cv) {
  vl_psd psd;
  vl_persson *tab;
  vl_error err;
  tab = vl_test_paper_surface(HRMS, &psd);
  vl_contact_config cfg;
  shipped_config(&cfg, tab, eta);
  vl_contact *c;
  assert_int_equal(vl_contact_create(&cfg, &c, &err), VL_OK);
  cv->eta = eta;
  cv->a0 = vl_contact_a0(c);
  cv->p0 = vl_contact_p0(c);
  double v[N];
  for (int i = 0; i < N; i++) {
    cv->v0eta[i] = pow(10.0, -12.0 + 12.0 * i / (N - 1));
    v[i] = cv->v0eta[i] / eta;
  }
  vl_sweep_stats st;
  assert_int_equal(vl_sweep_run(c, N, v, NULL, cv->pt, on_point, cv, &st, &err), VL_OK);
  printf("  eta %g: %zu converged, %zu failed, %ld Newton iterations, %.2f s\n", eta, st.converged,
         st.failed, st.newton_iterations, st.seconds);
  for (int i = 0; i < N; i++) {
    const vl_point *p = &cv->pt[i];
    assert_true(p->converged);
    assert_true(isfinite(p->mu) && p->load_error < 1e-8);
    assert_true(fabs(p->mu - (p->mu_Rc + p->mu_Rf + p->mu_Sc + p->mu_Sf)) < 1e-12);
    if (i % 4 == 0)
      printf("  v0eta %8.2g mu %.4f Rc %+.4f Rf %.4f Sc %.4f Sf %.4f load(fluid) %.3f "
             "umin/h %.3f pc_max %.2f@%+.2f pf_max %.3g@%+.2f\n",
             cv->v0eta[i], p->mu, p->mu_Rc, p->mu_Rf, p->mu_Sc, p->mu_Sf, p->fluid_load_fraction,
             p->u_min_m / HRMS, cv->pc_max[i], cv->x_pc_max[i], cv->pf_max[i], cv->x_pf_max[i]);
  }
  vl_contact_free(c);
  vl_persson_free(tab);
  vl_psd_free(&psd);
}

static int index_of(const curve *cv, double v0eta) {
  int best = 0;
  for (int i = 0; i < N; i++)
    if (fabs(log10(cv->v0eta[i] / v0eta)) < fabs(log10(cv->v0eta[best] / v0eta))) best = i;
  return best;
}

static int argmax(const curve *cv, double (*f)(const vl_point *)) {
  int best = 0;
  for (int i = 0; i < N; i++)
    if (f(&cv->pt[i]) > f(&cv->pt[best])) best = i;
  return best;
}
static double get_Rc(const vl_point *p) { return p->mu_Rc; }
static double get_Rf(const vl_point *p) { return p->mu_Rf; }

/* First v0 eta where the fluid carries half the load (log interpolation). */
static double ml_transition(const curve *cv) {
  for (int i = 1; i < N; i++) {
    double a = cv->pt[i - 1].fluid_load_fraction, b = cv->pt[i].fluid_load_fraction;
    if (a < 0.5 && b >= 0.5) {
      double t = (0.5 - a) / (b - a);
      return pow(10.0, log10(cv->v0eta[i - 1]) + t * log10(cv->v0eta[i] / cv->v0eta[i - 1]));
    }
  }
  return NAN;
}

static void test_fig05(void **state) {
  (void)state;
  curve *cv = calloc(1, sizeof *cv);
  stribeck(1e-4, cv);
  int irc = argmax(cv, get_Rc), irf = argmax(cv, get_Rf);
  printf("  mu_Rc max %.4f at v0eta %.2g; mu_Rf max %.4f at %.2g; ML transition at %.3g Pa m\n",
         cv->pt[irc].mu_Rc, cv->v0eta[irc], cv->pt[irf].mu_Rf, cv->v0eta[irf], ml_transition(cv));
  /* friction rises as the speed falls below v0 eta ~ 1e-4 Pa m, in the
   * boundary regime (fluid load < 5 %), driven by mu_Rc and mu_Sc */
  int i4 = index_of(cv, 1e-4), i5 = index_of(cv, 1e-5), i3 = index_of(cv, 1e-3);
  assert_true(cv->pt[i5].mu > cv->pt[i4].mu && cv->pt[i4].mu > cv->pt[i3].mu);
  assert_true(cv->pt[i5].fluid_load_fraction < 0.05 && cv->pt[i4].fluid_load_fraction < 0.05);
  assert_true(cv->pt[i5].mu_Rc + cv->pt[i5].mu_Sc > 0.95 * cv->pt[i5].mu);
  /* the mu_Rf maximum lies at least two decades above the mu_Rc maximum, at
   * the same order of magnitude (with Patir-Cheng factors mu_Rf keeps rising:
   * its maximum is the end of the sweep, as docs/CASES.md anticipates) */
  assert_true(cv->v0eta[irf] >= 100.0 * cv->v0eta[irc]);
  double r = cv->pt[irf].mu_Rf / cv->pt[irc].mu_Rc;
  printf("  max mu_Rf / max mu_Rc = %.2f\n", r);
  assert_true(r > 0.1 && r < 10.0);
  /* mu_Rf comparable to mu_Sf where the fluid takes over: within 3x at the
   * mixed-lubrication transition (half the load on the fluid), and of the
   * same order (within 10x) along the whole fluid-carried branch above it.
   * With Patir-Cheng factors mu_Rf keeps rising with speed (docs/CASES.md), so
   * the ratio grows along that branch: at the shipped numerics (96 a0
   * inlet) it is 3.4 at the end of the sweep, 1 Pa m. Session 1 checked
   * the end of the sweep within 3x, on a 3 a0 inlet where it was 1.9: the
   * longer inlet thickens the film, so mu_Sf falls. */
  int ih = index_of(cv, ml_transition(cv));
  double rs = cv->pt[ih].mu_Rf / cv->pt[ih].mu_Sf;
  printf("  mu_Rf / mu_Sf at the ML transition (v0 eta %.2g Pa m): %.2f, at the end of the sweep: "
         "%.2f\n",
         cv->v0eta[ih], rs, cv->pt[N - 1].mu_Rf / cv->pt[N - 1].mu_Sf);
  assert_true(rs > 0.3 && rs < 3.0);
  for (int i = ih; i < N; i++) {
    double q = cv->pt[i].mu_Rf / cv->pt[i].mu_Sf;
    assert_true(q > 0.1 && q < 10.0);
  }
  /* u_min/h_rms vs v0 eta is not monotonic, with two plateaus in the
   * boundary regime (rubbery, then glassy) */
  int nonmono = 0;
  for (int i = 1; i < N; i++)
    if (cv->pt[i].u_min_m < cv->pt[i - 1].u_min_m * (1.0 - 1e-4)) nonmono = 1;
  assert_true(nonmono);
  double lo1 = cv->pt[index_of(cv, 1e-11)].u_min_m, lo2 = cv->pt[index_of(cv, 1e-9)].u_min_m;
  double hi1 = cv->pt[index_of(cv, 1e-5)].u_min_m, hi2 = cv->pt[index_of(cv, 1e-3)].u_min_m;
  printf("  plateaus of u_min/h_rms: %.3f..%.3f (rubbery), %.3f..%.3f (glassy)\n", lo1 / HRMS,
         lo2 / HRMS, hi1 / HRMS, hi2 / HRMS);
  assert_true(vl_test_rel(lo2, lo1) < 0.01 && vl_test_rel(hi2, hi1) < 0.01);
  assert_true(hi1 / lo1 > 1.5);
  /* Figs. 6-8: an inlet pressure spike in the glassy transition that moves
   * toward the outlet with speed and vanishes in mixed lubrication */
  int is = index_of(cv, 1e-6), im = index_of(cv, 1e-4), iml = index_of(cv, 0.3);
  assert_true(cv->x_pc_max[is] < -0.5 && cv->pc_max[is] > 1.3);
  assert_true(cv->x_pc_max[im] > cv->x_pc_max[is]);
  assert_true(cv->pc_max[iml] < 0.25 * cv->pc_max[im]);
  free(cv);
}

static void test_fig10(void **state) {
  (void)state;
  curve *cv = calloc(1, sizeof *cv);
  stribeck(1.0, cv);
  int irc = argmax(cv, get_Rc);
  double ml = ml_transition(cv);
  printf("  mu_Rc max %.4f at v0eta %.2g; ML transition at %.3g Pa m\n", cv->pt[irc].mu_Rc,
         cv->v0eta[irc], ml);
  /* viscoelastic and mixed-lubrication transitions coupled: within a decade */
  assert_true(fabs(log10(cv->v0eta[irc] / ml)) < 1.0);
  /* a second, apparent hydrodynamic regime: friction rises by more than half
   * over a speed range where the fluid carries under 15 % of the load, then
   * falls to a minimum before the true hydrodynamic rise */
  int imax = 0;
  for (int i = 0; i < N; i++)
    if (cv->pt[i].fluid_load_fraction < 0.15 && cv->pt[i].mu > cv->pt[imax].mu) imax = i;
  assert_true(cv->pt[imax].mu > 1.5 * cv->pt[0].mu);
  int imin = imax;
  for (int i = imax; i < N; i++)
    if (cv->pt[i].mu < cv->pt[imin].mu) imin = i;
  assert_true(imin > imax && imin < N - 1);
  assert_true(cv->pt[N - 1].mu > cv->pt[imin].mu);
  printf("  apparent hydrodynamic branch up to v0eta %.2g (mu %.4f), minimum at %.2g (mu %.4f)\n",
         cv->v0eta[imax], cv->pt[imax].mu, cv->v0eta[imin], cv->pt[imin].mu);
  /* mu_Rc and mu_Rf of the same order in the transitions */
  int it = index_of(cv, ml);
  double r = cv->pt[it].mu_Rf / cv->pt[it].mu_Rc;
  printf("  at the ML transition: mu_Rf/mu_Rc = %.2f, mu_Rf/mu_Sf = %.2f (seed: ~10; "
         "depends on the flow-factor model)\n",
         r, cv->pt[it].mu_Rf / cv->pt[it].mu_Sf);
  assert_true(r > 0.1 && r < 10.0);
  /* Fig. 11: an inlet spike on both pressure fields in the coupled transition */
  int ic = irc;
  printf("  inlet spikes at v0 eta %.2g Pa m: pc peak at x = %.2f a0, pf peak at %.2f a0\n",
         cv->v0eta[ic], cv->x_pc_max[ic], cv->x_pf_max[ic]);
  assert_true(cv->x_pc_max[ic] < -0.3 && cv->x_pf_max[ic] < -0.3);
  free(cv);
}

/* docs/CASES.md fig12/13: five viscosities 1e-4 ... 1 Pa s. The Stribeck curves
 * do not collapse on a master curve in v0 eta; the mixed-lubrication
 * transition sits near the same v0 eta for all; the rolling friction
 * mu_Rc + mu_Rf vs v0 tau/a0 overlaps at low speed and grows without bound
 * at high speed. Coarser (grid 128, 2 points a decade) to keep it cheap: the
 * statements are about decades, not digits. */
static void test_fig12(void **state) {
  (void)state;
  enum { M = 25, K = 5 };
  static double mu[K][M], rolling[K][M], fl[K][M], de[K][M], v0eta[M];
  double ml[K];
  vl_psd psd;
  vl_persson *tab;
  vl_error err;
  tab = vl_test_paper_surface(HRMS, &psd);
  for (int k = 0; k < K; k++) {
    double eta = pow(10.0, -4.0 + k);
    vl_contact_config cfg;
    shipped_config(&cfg, tab, eta);
    vl_contact *c;
    assert_int_equal(vl_contact_create(&cfg, &c, &err), VL_OK);
    double v[M];
    vl_point pt[M];
    for (int i = 0; i < M; i++) {
      v0eta[i] = pow(10.0, -12.0 + 12.0 * i / (M - 1));
      v[i] = v0eta[i] / eta;
    }
    assert_int_equal(vl_sweep_run(c, M, v, NULL, pt, NULL, NULL, NULL, &err), VL_OK);
    ml[k] = NAN;
    for (int i = 0; i < M; i++) {
      assert_true(pt[i].converged);
      mu[k][i] = pt[i].mu;
      rolling[k][i] = pt[i].mu_Rc + pt[i].mu_Rf;
      fl[k][i] = pt[i].fluid_load_fraction;
      de[k][i] = v[i] * 0.1 / vl_contact_a0(c);
      if (i > 0 && isnan(ml[k]) && fl[k][i - 1] < 0.5 && fl[k][i] >= 0.5)
        ml[k] = v0eta[i - 1] *
                pow(v0eta[i] / v0eta[i - 1], (0.5 - fl[k][i - 1]) / (fl[k][i] - fl[k][i - 1]));
    }
    printf("  eta %6.0e: ML transition at v0 eta = %.3g Pa m, mu range %.4f..%.4f\n", eta, ml[k],
           mu[k][0], mu[k][M - 1]);
    vl_contact_free(c);
  }
  vl_persson_free(tab);
  vl_psd_free(&psd);
  /* no master curve: at some v0 eta the curves differ by more than 2x */
  double spread = 0.0;
  for (int i = 0; i < M; i++) {
    double lo = INFINITY, hi = 0.0;
    for (int k = 0; k < K; k++)
      lo = fmin(lo, mu[k][i]), hi = fmax(hi, mu[k][i]);
    spread = fmax(spread, hi / lo);
  }
  printf("  largest ratio between curves at equal v0 eta: %.2f\n", spread);
  assert_true(spread > 2.0);
  /* the ML transitions lie within one decade of each other */
  double lo = INFINITY, hi = 0.0;
  for (int k = 0; k < K; k++) {
    assert_false(isnan(ml[k]));
    lo = fmin(lo, ml[k]), hi = fmax(hi, ml[k]);
  }
  assert_true(log10(hi / lo) < 1.0);
  /* Fig. 13: at low speed (De < 1e-2, dry-like) the rolling friction of all
   * viscosities agrees within 5 % at equal De; at the highest speed it grows
   * with viscosity (the fluid's unbounded rolling dissipation) */
  for (int k = 1; k < K; k++) {
    for (int i = 0; i < M; i++) {
      if (de[k][i] > 1e-2 || de[k][i] < 1e-4) continue;
      /* the same De on the eta = 1e-4 curve, log-interpolated */
      for (int j = 1; j < M; j++) {
        if (de[0][j - 1] <= de[k][i] && de[k][i] <= de[0][j]) {
          double t = log(de[k][i] / de[0][j - 1]) / log(de[0][j] / de[0][j - 1]);
          double ref = rolling[0][j - 1] + t * (rolling[0][j] - rolling[0][j - 1]);
          assert_true(vl_test_rel(rolling[k][i], ref) < 0.05);
        }
      }
    }
  }
  printf("  rolling friction at the end of the sweep (v0 eta = 1 Pa m): ");
  for (int k = 0; k < K; k++)
    printf("%.4f ", rolling[k][M - 1]);
  printf("\n");
}

/* docs/MODEL.md section 5: the inlet must reach well beyond the contact; friction
 * at high v0 eta depends on it. Measured on the fig05 contact at v0 eta = 0.3
 * and 1 Pa m (mixed and hydrodynamic) for inlets of 2, 3 and 5 a0 at equal
 * cell size: more inlet entrains more fluid (mu grows), with a shrinking
 * increment per a0 of inlet. The printed changes are the price of the
 * default 3 a0 (several per cent at 1 Pa m: an accuracy-study item). */
static void test_domain_length(void **state) {
  (void)state;
  double inlets[] = {-2.0, -3.0, -5.0};
  double mu[3][2];
  vl_psd psd;
  vl_persson *tab;
  vl_error err;
  tab = vl_test_paper_surface(HRMS, &psd);
  for (int k = 0; k < 3; k++) {
    vl_contact_config cfg;
    /* the same cell size for every domain, so only the inlet changes */
    vl_test_fig05_config(&cfg, tab, 1e-4, (size_t)lround((1.6 - inlets[k]) / (4.6 / 256.0)),
                         inlets[k]);
    vl_contact *c;
    assert_int_equal(vl_contact_create(&cfg, &c, &err), VL_OK);
    double v[] = {1e-4 / 1e-4, 1e-3 / 1e-4, 1e-2 / 1e-4, 0.1 / 1e-4, 0.3 / 1e-4, 1.0 / 1e-4};
    vl_point pt[6];
    assert_int_equal(vl_sweep_run(c, 6, v, NULL, pt, NULL, NULL, NULL, &err), VL_OK);
    for (int i = 0; i < 6; i++)
      assert_true(pt[i].converged);
    mu[k][0] = pt[4].mu;
    mu[k][1] = pt[5].mu;
    printf("  inlet %4.1f a0 (grid %zu): mu = %.5f at 0.3 Pa m, %.5f at 1 Pa m\n", -inlets[k],
           cfg.grid, mu[k][0], mu[k][1]);
    vl_contact_free(c);
  }
  for (int j = 0; j < 2; j++) {
    printf("  relative change of mu, inlet 2 -> 3 a0: %.2e, 3 -> 5 a0: %.2e\n",
           mu[1][j] / mu[0][j] - 1, mu[2][j] / mu[1][j] - 1);
    assert_true(mu[2][j] > mu[1][j] && mu[1][j] > mu[0][j]);
    assert_true((mu[2][j] - mu[1][j]) / 2.0 < (mu[1][j] - mu[0][j]) / 1.0);
  }
  vl_persson_free(tab);
  vl_psd_free(&psd);
}

int main(void) {
  const struct CMUnitTest tests[] = {cmocka_unit_test(test_fig05), cmocka_unit_test(test_fig10),
                                     cmocka_unit_test(test_fig12),
                                     cmocka_unit_test(test_domain_length)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
