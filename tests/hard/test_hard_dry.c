/* Hard-case matrix, dry contacts (issue 8): smooth and rough surfaces,
 * elastic to Einf/E0 = 1e4, Prony series of 1 to 60 terms over up to 20
 * decades, loads 1e-3 ... 1e2 times the seed's 1 kN/m, radii 0.1 mm ... 1 m,
 * speeds 1e-12 ... 100 m/s, grids 32 ... 2048. A Latin hypercube (fixed
 * seed) over the continuous parameters plus a two-level fractional
 * factorial of the extremes; every point is checked by hard_util.h. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "hard_util.h"
#include "vl_test_util.h"

/* Stated minimum convergence rates. Dry contacts converge almost
 * everywhere; the known failures (listed in the summary) are rubbers with
 * Einf/E0 >= ~5e3 in their transition (v0 tau/a0 ~ 0.5-5), where
 * continuation in speed fails although a fresh start converges. */
static hard_family fam_smooth_lhs = {.name = "dry smooth, LHS", .min_rate = 0.95};
static hard_family fam_smooth_ext = {.name = "dry smooth, extremes", .min_rate = 0.95};
static hard_family fam_rough_lhs = {.name = "dry rough, LHS", .min_rate = 0.95};
static hard_family fam_rough_ext = {.name = "dry rough, extremes", .min_rate = 0.95};
static hard_family fam_big = {.name = "dry, grids 512-2048", .min_rate = 1.0};

static const size_t grids[] = {32, 48, 64, 96, 128};

static void base_config(vl_contact_config *cfg, const vl_prony *r, double load, double radius,
                        const vl_persson *tab, size_t grid) {
  vl_contact_config_defaults(cfg);
  cfg->rubber = *r;
  cfg->radius_m = radius;
  cfg->load_n_per_m = load;
  cfg->roughness = tab;
  cfg->grid = grid;
  /* a rough contact spreads beyond the Hertz width (the validation tests'
   * domains) */
  cfg->x_min_a0 = tab ? -1.8 : -1.5;
  cfg->x_max_a0 = tab ? 1.8 : 1.5;
}

/* Latin hypercube over (Einf/E0, terms, decades, tau_c, load, radius,
 * grid, ragged spectrum): 32 corners, 15 speeds each (one a decade). */
static void test_smooth_lhs(void **state) {
  (void)state;
  enum { N = 32, D = 8 };
  double u[N * D], v[32];
  hard_lhs(N, D, 0x5eed0001, u);
  uint64_t rng = 42;
  size_t nv = hard_speeds(1e-12, 100.0, 1.0, v, 32);
  for (size_t i = 0; i < N; i++) {
    const double *p = u + i * D;
    hard_solid so = hard_decode_solid(p, grids);
    double ratio = so.ratio, dec = so.decades, tau_c = so.tau_c, load = so.load;
    double radius = so.radius;
    size_t nt = so.terms, grid = so.grid;
    vl_prony r = hard_rubber(ratio, nt, dec, tau_c, p[7] < 0.5, &rng);
    vl_contact_config cfg;
    base_config(&cfg, &r, load, radius, NULL, grid);
    char label[400];
    int k = hard_rubber_label(label, sizeof label, ratio, nt, dec, tau_c);
    snprintf(label + k, sizeof label - (size_t)k, ", R %.3g m, fN %.3g N/m, grid %zu", radius, load,
             grid);
    hard_run_corner(&fam_smooth_lhs, label, &cfg, NULL, nv, v, NULL);
  }
  hard_assert_rate(&fam_smooth_lhs);
}

/* The extremes combined: Einf/E0 in {1, 1e4} x Prony {1 term, 60 terms
 * over 20 decades} x load {1e-3, 1e2} x 1 kN/m x radius {0.1 mm, 1 m}:
 * the full 2^4 factorial, grid 64. */
static void test_smooth_extremes(void **state) {
  (void)state;
  double v[32];
  size_t nv = hard_speeds(1e-12, 100.0, 1.0, v, 32);
  uint64_t rng = 7;
  for (int m = 0; m < 16; m++) {
    double ratio = (m & 1) ? 1e4 : 1.0;
    size_t nt = (m & 2) ? 60 : 1;
    double dec = (m & 2) ? 20.0 : 0.0;
    double load = HARD_LOAD * ((m & 4) ? 1e2 : 1e-3);
    double radius = (m & 8) ? 1.0 : 1e-4;
    vl_prony r = hard_rubber(ratio, nt, dec, HARD_TAU, 0, &rng);
    vl_contact_config cfg;
    base_config(&cfg, &r, load, radius, NULL, 64);
    char label[400];
    int k = hard_rubber_label(label, sizeof label, ratio, nt, dec, HARD_TAU);
    snprintf(label + k, sizeof label - (size_t)k, ", R %.3g m, fN %.3g N/m, grid 64", radius, load);
    hard_run_corner(&fam_smooth_ext, label, &cfg, NULL, nv, v, NULL);
  }
  hard_assert_rate(&fam_smooth_ext);
}

/* One rough corner: builds the surface and its Persson table. */
static void rough_corner(hard_family *fam, double ratio, size_t nt, double dec, double tau_c,
                         double load, double radius, size_t grid, double hurst, double q1_over_q0,
                         double hrms, double noise, uint64_t *rng, size_t nv, const double *v) {
  vl_psd psd;
  size_t n_tab;
  vl_persson *tab = hard_rough_surface(&psd, hurst, q1_over_q0, hrms, noise, rng, &n_tab);
  vl_prony r = hard_rubber(ratio, nt, dec, tau_c, 1, rng);
  vl_contact_config cfg;
  base_config(&cfg, &r, load, radius, tab, grid);
  char label[400];
  int k = hard_rubber_label(label, sizeof label, ratio, nt, dec, tau_c);
  snprintf(label + k, sizeof label - (size_t)k,
           ", R %.3g m, fN %.3g N/m, grid %zu, h_rms %.3g m, H %.2f, q1/q0 %.3g, %s", radius, load,
           grid, hrms, hurst, q1_over_q0, noise < 0.0 ? "self-affine" : "tabulated");
  if (noise >= 0.0)
    snprintf(label + strlen(label), sizeof label - strlen(label), " (%zu points, noise %.2f)",
             n_tab, noise);
  hard_run_corner(fam, label, &cfg, &psd, nv, v, NULL);
  vl_persson_free(tab);
  vl_psd_free(&psd);
}

/* Latin hypercube over (Einf/E0, terms, decades, tau_c, load, radius,
 * grid, h_rms, H, q1/q0, tabulated noise): 32 corners; half the surfaces
 * tabulated with log-normal scatter of 0 ... 1 (factor e) per point. */
static void test_rough_lhs(void **state) {
  (void)state;
  enum { N = 32, D = 11 };
  double u[N * D], v[32];
  hard_lhs(N, D, 0x5eed0002, u);
  uint64_t rng = 43;
  size_t nv = hard_speeds(1e-12, 100.0, 1.0, v, 32);
  for (size_t i = 0; i < N; i++) {
    const double *p = u + i * D;
    hard_solid so = hard_decode_solid(p, grids);
    hard_rough su = hard_decode_rough(p);
    rough_corner(&fam_rough_lhs, so.ratio, so.terms, so.decades, so.tau_c, so.load, so.radius,
                 so.grid, su.hurst, su.q1_over_q0, su.hrms, su.noise, &rng, nv, v);
  }
  hard_assert_rate(&fam_rough_lhs);
}

/* The extremes: h_rms {1 nm, 50 um} x H {0.3, 1} x q1/q0 {10, 1e6} x load
 * {1e-3, 1e2} x radius {0.1 mm, 1 m}, with Einf/E0 = 1e4 (60 terms, 20
 * decades) where the number of high levels is odd and the elastic solid
 * where it is even: the 2^(6-1) half fraction (resolution VI), grid 48. */
static void test_rough_extremes(void **state) {
  (void)state;
  double v[32];
  size_t nv = hard_speeds(1e-12, 100.0, 1.0, v, 32);
  uint64_t rng = 8;
  for (int m = 0; m < 32; m++) {
    int odd = __builtin_popcount((unsigned)m) & 1;
    rough_corner(&fam_rough_ext, odd ? 1e4 : 1.0, odd ? 60 : 0, 20.0, HARD_TAU,
                 HARD_LOAD * ((m & 8) ? 1e2 : 1e-3), (m & 16) ? 1.0 : 1e-4, 48, (m & 4) ? 0.3 : 1.0,
                 (m & 2) ? 1e6 : 10.0, (m & 1) ? 5e-5 : 1e-9, -1.0, &rng, nv, v);
  }
  hard_assert_rate(&fam_rough_ext);
}

/* Large grids (the dense Newton matrix is (N+1)^2, (2N+1)^2 rough: a
 * 2048-node solve costs seconds): the seed's smooth contact at 2048 near
 * the relaxed limit (v0 tau/a0 = 0.01), a 60-term rubber over 20 decades
 * at 1024 at two speeds, the paper surface (h_rms 3 um) at 512. */
static void test_big_grids(void **state) {
  (void)state;
  uint64_t rng = 9;
  double a0 = sqrt(4.0 * HARD_LOAD * HARD_RADIUS / (M_PI * HARD_E0 / (1.0 - HARD_NU * HARD_NU)));
  double v1[] = {1e-2 * a0 / HARD_TAU};
  vl_prony r = hard_rubber(10.0, 1, 0.0, HARD_TAU, 0, &rng);
  vl_contact_config cfg;
  base_config(&cfg, &r, HARD_LOAD, HARD_RADIUS, NULL, 2048);
  hard_run_corner(&fam_big,
                  "seed smooth (Einf/E0 10, 1 term at tau 0.1 s, R 0.01 m, fN 1e3 N/m), "
                  "grid 2048",
                  &cfg, NULL, 1, v1, NULL);
  double v2[] = {0.1 * a0 / HARD_TAU, 10.0 * a0 / HARD_TAU};
  r = hard_rubber(1e3, 60, 20.0, HARD_TAU, 1, &rng);
  base_config(&cfg, &r, HARD_LOAD, HARD_RADIUS, NULL, 1024);
  hard_run_corner(&fam_big,
                  "smooth, Einf/E0 1e3, 60 terms over 20 decades at tau 0.1 s, R 0.01 m, "
                  "fN 1e3 N/m, grid 1024",
                  &cfg, NULL, 2, v2, NULL);
  double v3[] = {1e-2 * a0 / HARD_TAU, 1.0 * a0 / HARD_TAU, 100.0 * a0 / HARD_TAU};
  rough_corner(&fam_big, 10.0, 1, 0.0, HARD_TAU, HARD_LOAD, HARD_RADIUS, 512, 0.8, 7.8e9 / HARD_Q0,
               3e-6, -1.0, &rng, 3, v3);
  hard_assert_rate(&fam_big);
}

static void test_summary(void **state) {
  (void)state;
  hard_family *f[] = {&fam_smooth_lhs, &fam_smooth_ext, &fam_rough_lhs, &fam_rough_ext, &fam_big};
  hard_print_summary("dry", f, 5);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_smooth_lhs), cmocka_unit_test(test_smooth_extremes),
      cmocka_unit_test(test_rough_lhs),  cmocka_unit_test(test_rough_extremes),
      cmocka_unit_test(test_big_grids),  cmocka_unit_test(test_summary),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
