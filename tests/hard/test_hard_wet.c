/* Hard-case matrix, wet contacts (issue 8): Stribeck sweeps over v0 =
 * 1e-12 ... 100 m/s with eta = 1e-5 ... 100 Pa s, rough (Persson contact,
 * Patir-Cheng or smooth flow factors) and smooth (soft EHL), combined with
 * the rubber (elastic to Einf/E0 = 1e4, 1 to 60 Prony terms over up to 20
 * decades), the surface (h_rms 1 nm ... 50 um, H 0.3 ... 1, q1/q0 10 ...
 * 1e6, tabulated with scatter), loads 1e-3 ... 1e2 times the seed's 1 kN/m,
 * radii 0.1 mm ... 1 m, grids 32 ... 128 and inlets from 2 to 30 a0, and graded
 * inlets of 16 ... 200 a0 (test_rough_graded). A
 * Latin hypercube (fixed seed) plus a two-level fraction of the extremes
 * per kind; every point is checked by hard_util.h. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "hard_util.h"
#include "vl_test_util.h"

/* Step control: a failed step is split down to 1/16 decade (the library's
 * default goes to 1/64; at up to 100 Newton iterations a solve, the extra
 * levels cost minutes on the corners that fail anyway). */
#define SUBDIV 4
/* Stated minimum convergence rates (points whose a priori film is >= 1 nm;
 * below 1 nm the continuum model has no meaning and 50 % is asked). The
 * rough families are far from 100 %: the wet rough solver fails at many
 * speeds (above ~0.1 m/s on the fig05 scene) for h_rms below ~0.3 um (a
 * known solver problem, see the h_rms scan and the summary's list of
 * corners); raise these minimums when it is fixed. */
static hard_family fam_rough_lhs = {
    .name = "wet rough, LHS", .min_rate = 0.7, .min_rate_subnm = 0.5, .max_subdivisions = SUBDIV};
static hard_family fam_rough_ext = {.name = "wet rough, extremes",
                                    .min_rate = 0.7,
                                    .min_rate_subnm = 0.5,
                                    .max_subdivisions = SUBDIV};
static hard_family fam_scan_fine = {.name = "wet rough, h_rms < 1 um",
                                    .min_rate = 0.5,
                                    .min_rate_subnm = 0.5,
                                    .max_subdivisions = SUBDIV};
static hard_family fam_scan_rough = {.name = "wet rough, h_rms >= 1 um",
                                     .min_rate = 1.0,
                                     .min_rate_subnm = 0.5,
                                     .max_subdivisions = SUBDIV};
/* Graded inlets: measured 85.6 % (308/360). With the earlier cap of 100
 * Newton iterations it was 81.1 %. On the 16 corners whose uniform grid is
 * affordable (<= 1300 cells), the uniform grids then converged 194/240 and
 * the graded ones 183/240; the uniform runs took 868 s for those 16
 * corners, the graded family 14 s for all 24. The difference was one
 * fine-surface corner (h_rms 5 nm, 8.5 cells per a0), whose film lifts off
 * (u_min x35) in one step: 92 Newton iterations on the uniform grid,
 * 110-128 on graded ones. Under the cap of 200
 * (VL_NEWTON_MAX_ITERATIONS) it converges on both, and its graded points
 * agree with the uniform ones (u_min to 5e-5, mu to 2e-4). */
static hard_family fam_rough_graded = {.name = "wet rough, graded inlet",
                                       .min_rate = 0.7,
                                       .min_rate_subnm = 0.5,
                                       .max_subdivisions = SUBDIV};
static hard_family fam_smooth_lhs = {
    .name = "wet smooth, LHS", .min_rate = 0.85, .min_rate_subnm = 0.5, .max_subdivisions = SUBDIV};
static hard_family fam_smooth_ext = {.name = "wet smooth, extremes",
                                     .min_rate = 0.85,
                                     .min_rate_subnm = 0.5,
                                     .max_subdivisions = SUBDIV};

static const size_t grids[] = {32, 40, 48, 56, 64};

static void wet_config(vl_contact_config *cfg, const vl_prony *r, double load, double radius,
                       const vl_persson *tab, double eta, vl_flow_factor_kind ff, size_t grid,
                       double x_min_a0, double growth) {
  vl_contact_config_defaults(cfg);
  cfg->rubber = *r;
  cfg->radius_m = radius;
  cfg->load_n_per_m = load;
  cfg->roughness = tab;
  cfg->sigma_s_pa = tab ? 1e6 : 0.0; /* the seed's wet scenes */
  cfg->eta_pa_s = eta;
  cfg->flow_factors = ff;
  cfg->grid = grid;
  cfg->x_min_a0 = x_min_a0;
  cfg->x_max_a0 = 1.6;
  cfg->grid_growth = growth;
}

static void rough_corner(hard_family *fam, double ratio, size_t nt, double dec, double tau_c,
                         double load, double radius, size_t grid, double hurst, double q1_over_q0,
                         double hrms, double noise, double eta, vl_flow_factor_kind ff,
                         double x_min_a0, double growth, uint64_t *rng, size_t nv,
                         const double *v) {
  vl_psd psd;
  size_t n_tab;
  vl_persson *tab = hard_rough_surface(&psd, hurst, q1_over_q0, hrms, noise, rng, &n_tab);
  vl_prony r = hard_rubber(ratio, nt, dec, tau_c, 1, rng);
  vl_contact_config cfg;
  wet_config(&cfg, &r, load, radius, tab, eta, ff, grid, x_min_a0, growth);
  char label[400];
  int k = snprintf(label, sizeof label, "eta %.3g Pa s, ", eta);
  k += hard_rubber_label(label + k, sizeof label - (size_t)k, ratio, nt, dec, tau_c);
  k += snprintf(label + k, sizeof label - (size_t)k,
                ", R %.3g m, fN %.3g N/m, grid %zu (growth %.3g), domain [%.3g, 1.6] a0, h_rms "
                "%.3g m, H %.2f, q1/q0 %.3g, %s",
                radius, load, grid, growth, x_min_a0, hrms, hurst, q1_over_q0,
                vl_flow_factors_name(ff));
  if (noise >= 0.0)
    snprintf(label + k, sizeof label - (size_t)k, ", tabulated (%zu points, noise %.2f)", n_tab,
             noise);
  hard_run_corner(fam, label, &cfg, &psd, nv, v, NULL);
  vl_persson_free(tab);
  vl_psd_free(&psd);
}

static void smooth_corner(hard_family *fam, double ratio, size_t nt, double dec, double tau_c,
                          double load, double radius, size_t grid, double eta, double x_min_a0,
                          uint64_t *rng, size_t nv, const double *v) {
  vl_prony r = hard_rubber(ratio, nt, dec, tau_c, 1, rng);
  vl_contact_config cfg;
  wet_config(&cfg, &r, load, radius, NULL, eta, VL_FLOW_FACTORS_SMOOTH, grid, x_min_a0, 1.0);
  char label[400];
  int k = snprintf(label, sizeof label, "smooth, eta %.3g Pa s, ", eta);
  k += hard_rubber_label(label + k, sizeof label - (size_t)k, ratio, nt, dec, tau_c);
  snprintf(label + k, sizeof label - (size_t)k,
           ", R %.3g m, fN %.3g N/m, grid %zu, domain [%.3g, 1.6] a0", radius, load, grid,
           x_min_a0);
  hard_run_corner(fam, label, &cfg, NULL, nv, v, NULL);
}

/* The rough corner of Latin-hypercube point p: the solid from p[0..6],
 * the surface from p[7..10], eta from p[11], the flow factors from p[12]
 * (a quarter smooth); the grid, domain and growth as given. */
static void lhs_rough_corner(hard_family *fam, const double *p, size_t grid, double x_min_a0,
                             double growth, uint64_t *rng, size_t nv, const double *v) {
  hard_solid so = hard_decode_solid(p, grids);
  hard_rough su = hard_decode_rough(p);
  rough_corner(fam, so.ratio, so.terms, so.decades, so.tau_c, so.load, so.radius, grid, su.hurst,
               su.q1_over_q0, su.hrms, su.noise, hard_log_between(1e-5, 100.0, p[11]),
               p[12] < 0.25 ? VL_FLOW_FACTORS_SMOOTH : VL_FLOW_FACTORS_PATIR_CHENG, x_min_a0,
               growth, rng, nv, v);
}

/* Latin hypercube over 14 parameters: 32 corners of 15 speeds (one a
 * decade); a quarter of them with smooth flow factors on a rough surface. */
static void test_rough_lhs(void **state) {
  (void)state;
  enum { N = 32, D = 14 };
  double u[N * D], v[32];
  hard_lhs(N, D, 0x5eed0003, u);
  uint64_t rng = 44;
  size_t nv = hard_speeds(1e-12, 100.0, 1.0, v, 32);
  for (size_t i = 0; i < N; i++) {
    const double *p = u + i * D;
    lhs_rough_corner(&fam_rough_lhs, p, hard_decode_solid(p, grids).grid,
                     -hard_log_between(2.0, 30.0, p[13]), 1.0, &rng, nv, v);
  }
  hard_assert_rate(&fam_rough_lhs);
}

/* Extremes: eta {1e-5, 100} x h_rms {1 nm, 50 um} x load {1e-3, 1e2} x
 * radius {0.1 mm, 1 m}, with the rubber (elastic, or Einf/E0 = 1e4 over 60
 * terms and 20 decades) set by the parity of the other four: the 2^(5-1)
 * half fraction (resolution V). Paper-like surface (H 0.8, q1/q0 1e3),
 * Patir-Cheng, grid 48, inlet 3 a0. */
static void test_rough_extremes(void **state) {
  (void)state;
  double v[32];
  size_t nv = hard_speeds(1e-12, 100.0, 1.0, v, 32);
  uint64_t rng = 10;
  for (int m = 0; m < 16; m++) {
    int odd = __builtin_popcount((unsigned)m) & 1;
    rough_corner(&fam_rough_ext, odd ? 1e4 : 1.0, odd ? 60 : 0, 20.0, HARD_TAU,
                 HARD_LOAD * ((m & 4) ? 1e2 : 1e-3), (m & 8) ? 1.0 : 1e-4, 48, 0.8, 1e3,
                 (m & 2) ? 5e-5 : 1e-9, -1.0, (m & 1) ? 100.0 : 1e-5, VL_FLOW_FACTORS_PATIR_CHENG,
                 -3.0, 1.0, &rng, nv, v);
  }
  hard_assert_rate(&fam_rough_ext);
}

/* One at a time: the fig05 scene (model rubber, R 1 cm, fN 1 kN/m, paper
 * surface, sigma_s 1 MPa, eta 1e-4 Pa s, Patir-Cheng, grid 48, inlet 3 a0)
 * with h_rms from 1 nm to 50 um, two values a decade: pins the surface
 * roughness at which the wet rough solver stops converging. */
static void test_hrms_scan(void **state) {
  (void)state;
  double v[32];
  size_t nv = hard_speeds(1e-12, 100.0, 1.0, v, 32);
  uint64_t rng = 12;
  for (int k = 0; k <= 10; k++) {
    double hrms = fmin(1e-9 * pow(10.0, 0.5 * k), 5e-5);
    rough_corner(hrms < 1e-6 ? &fam_scan_fine : &fam_scan_rough, 10.0, 1, 0.0, HARD_TAU, HARD_LOAD,
                 HARD_RADIUS, 48, 0.8, 7.8e9 / HARD_Q0, hrms, -1.0, 1e-4,
                 VL_FLOW_FACTORS_PATIR_CHENG, -3.0, 1.0, &rng, nv, v);
  }
  hard_assert_rate(&fam_scan_rough);
  hard_assert_rate(&fam_scan_fine);
}

/* Graded inlets (vl_contact_config.grid_growth, the default of rough wet
 * scenes): a Latin hypercube as test_rough_lhs with long inlets (16 ...
 * 200 a0), growth 1.02 ... 1.3 and 8 ... 24 uniform cells per a0 near the
 * contact (grid = (inlet + 1.6) x that: up to ~4900 uniform cells, merged
 * into a few hundred): 24 corners of 15 speeds. */
static void test_rough_graded(void **state) {
  (void)state;
  enum { N = 24, D = 16 };
  double u[N * D], v[32];
  hard_lhs(N, D, 0x5eed0007, u);
  uint64_t rng = 46;
  size_t nv = hard_speeds(1e-12, 100.0, 1.0, v, 32);
  for (size_t i = 0; i < N; i++) {
    const double *p = u + i * D;
    double inlet = hard_log_between(16.0, 200.0, p[13]);
    double growth = 1.02 + 0.28 * p[14], per_a0 = 8.0 + 16.0 * p[15];
    size_t grid = (size_t)lround((inlet + 1.6) * per_a0);
    lhs_rough_corner(&fam_rough_graded, p, grid, -inlet, growth, &rng, nv, v);
  }
  hard_assert_rate(&fam_rough_graded);
}

/* Smooth (soft EHL) Latin hypercube over 9 parameters: 24 corners. */
static void test_smooth_lhs(void **state) {
  (void)state;
  enum { N = 24, D = 9 };
  double u[N * D], v[32];
  hard_lhs(N, D, 0x5eed0004, u);
  uint64_t rng = 45;
  size_t nv = hard_speeds(1e-12, 100.0, 1.0, v, 32);
  for (size_t i = 0; i < N; i++) {
    const double *p = u + i * D;
    hard_solid so = hard_decode_solid(p, grids);
    smooth_corner(&fam_smooth_lhs, so.ratio, so.terms, so.decades, so.tau_c, so.load, so.radius,
                  so.grid, hard_log_between(1e-5, 100.0, p[7]), -hard_log_between(2.0, 30.0, p[8]),
                  &rng, nv, v);
  }
  hard_assert_rate(&fam_smooth_lhs);
}

/* Smooth extremes: eta {1e-5, 100} x load {1e-3, 1e2} x radius {0.1 mm,
 * 1 m} x rubber {elastic, Einf/E0 1e4 over 60 terms and 20 decades}: the
 * full 2^4 factorial, grid 64, inlet 3 a0. */
static void test_smooth_extremes(void **state) {
  (void)state;
  double v[32];
  size_t nv = hard_speeds(1e-12, 100.0, 1.0, v, 32);
  uint64_t rng = 11;
  for (int m = 0; m < 16; m++) {
    smooth_corner(&fam_smooth_ext, (m & 8) ? 1e4 : 1.0, (m & 8) ? 60 : 0, 20.0, HARD_TAU,
                  HARD_LOAD * ((m & 2) ? 1e2 : 1e-3), (m & 4) ? 1.0 : 1e-4, 64,
                  (m & 1) ? 100.0 : 1e-5, -3.0, &rng, nv, v);
  }
  hard_assert_rate(&fam_smooth_ext);
}

static void test_summary(void **state) {
  (void)state;
  hard_family *f[] = {&fam_rough_lhs,  &fam_rough_ext,  &fam_rough_graded, &fam_scan_fine,
                      &fam_scan_rough, &fam_smooth_lhs, &fam_smooth_ext};
  hard_print_summary("wet", f, 7);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_rough_lhs),    cmocka_unit_test(test_rough_extremes),
      cmocka_unit_test(test_rough_graded), cmocka_unit_test(test_hrms_scan),
      cmocka_unit_test(test_smooth_lhs),   cmocka_unit_test(test_smooth_extremes),
      cmocka_unit_test(test_summary),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
