/* vl_assumptions_check (src/assumptions.c): each assumption check fires on
 * a point built to violate it and stays silent on one built to respect it;
 * the rms slope agrees with the closed form of docs/VALIDATION.md section 4
 * (independent of the PSD module); the warning column stays well formed
 * (';'-separated, no commas or quotes, never cut, no repeats). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "assumptions_internal.h"
#include "hard_util.h"
#include "persson_internal.h"
#include "rheology_internal.h"
#include "vl_test_scenes.h"
#include "vl_test_util.h"

static void seed_config(vl_contact_config *cfg, const vl_persson *tab, double eta) {
  vl_contact_config_defaults(cfg);
  cfg->rubber = vl_prony_single(HARD_E0, 10.0, HARD_TAU, HARD_NU);
  cfg->radius_m = HARD_RADIUS;
  cfg->load_n_per_m = HARD_LOAD;
  cfg->roughness = tab;
  cfg->eta_pa_s = eta;
  cfg->flow_factors = tab && eta > 0.0 ? VL_FLOW_FACTORS_PATIR_CHENG : VL_FLOW_FACTORS_SMOOTH;
  cfg->grid = 256;
  cfg->x_min_a0 = -3.0, cfg->x_max_a0 = 1.6;
}

/* A converged point of the seed contact that violates nothing: contact
 * width 2 a0 (~110 cells), u_min 0.5 h_rms, no fluid load. */
static vl_point benign_point(double hrms) {
  vl_point pt;
  memset(&pt, 0, sizeof pt);
  pt.v0_m_s = 1e-3;
  pt.converged = true;
  double a0 = sqrt(4.0 * HARD_LOAD * HARD_RADIUS / (M_PI * HARD_E0 / (1.0 - HARD_NU * HARD_NU)));
  pt.contact_width_m = 2.0 * a0;
  pt.u_min_m = 0.5 * hrms;
  pt.u_central_m = 0.7 * hrms;
  return pt;
}

/* rms slope^2 = 2 pi \int q^3 C dq = 2 pi C0 q0^4 [(q1/q0)^(2(1-H)) - 1]/(2(1-H)),
 * C0 = H h^2/(pi q0^2 [1 - (q0/q1)^(2H)]) (docs/VALIDATION.md section 4). */
static double slope_closed_form(double H, double q0, double q1, double h) {
  double c0 = H * h * h / (M_PI * q0 * q0 * (1.0 - pow(q0 / q1, 2.0 * H)));
  return sqrt(2.0 * M_PI * c0 * pow(q0, 4.0) * (pow(q1 / q0, 2.0 * (1.0 - H)) - 1.0) /
              (2.0 * (1.0 - H)));
}

static void test_rms_slope(void **state) {
  (void)state;
  const double hs[] = {1e-7, 3e-6};
  for (int k = 0; k < 2; k++) {
    vl_psd psd;
    vl_persson *tab;
    tab = vl_test_paper_surface(hs[k], &psd);
    double exact = slope_closed_form(0.8, HARD_Q0, 7.8e9, hs[k]);
    /* the table route (8 g) and the PSD route agree with the closed form
     * to rounding (both are exact integrals of a power law) */
    double via_table = sqrt(8.0 * vl_persson_g(tab));
    printf("  h_rms %.1e m: rms slope %.4f (closed form), %.4f (PSD), %.4f (Persson g)\n", hs[k],
           exact, vl_psd_rms_slope(&psd), via_table);
    assert_true(vl_test_rel(vl_psd_rms_slope(&psd), exact) < 1e-10);
    assert_true(vl_test_rel(via_table, exact) < 1e-10);
    vl_contact_config cfg;
    seed_config(&cfg, tab, 0.0);
    vl_point pt = benign_point(hs[k]);
    char w[VL_WARN_MAX] = "";
    unsigned m1 = vl_assumptions_check(&cfg, &psd, &pt, w, sizeof w);
    char w2[VL_WARN_MAX] = "";
    unsigned m2 = vl_assumptions_check(&cfg, NULL, &pt, w2, sizeof w2);
    printf("    warnings: '%s'\n", w);
    /* the paper surface at 3 um has slope ~9.9: far outside small slopes;
     * 0.1 um has 0.33 */
    assert_int_equal((m1 & VL_ASSUME_RMS_SLOPE) != 0, exact > 1.0);
    assert_int_equal((m2 & VL_ASSUME_RMS_SLOPE) != 0, exact > 1.0);
    assert_int_equal(m1 & ~(unsigned)VL_ASSUME_RMS_SLOPE, 0);
    assert_true(exact > 1.0 ? strstr(w, "rms slope") != NULL : w[0] == '\0');
    vl_persson_free(tab);
    vl_psd_free(&psd);
  }
}

/* a_H against lambda0 = 2 pi/q0: the seed cylinder (a0 = 1.63 mm, 52
 * lambda0) passes; a 0.1 mm cylinder under 10 N/m (a0 = 16 um = 0.5
 * lambda0, and a_H = a0/sqrt(10) at 1 mm/s, glassy) is flagged, also when
 * the point did not converge. */
static void test_homogenisation(void **state) {
  (void)state;
  vl_psd psd;
  vl_persson *tab;
  tab = vl_test_paper_surface(1e-7, &psd);
  vl_contact_config cfg;
  seed_config(&cfg, tab, 0.0);
  vl_point pt = benign_point(1e-7);
  char w[VL_WARN_MAX] = "";
  assert_int_equal(vl_assumptions_check(&cfg, &psd, &pt, w, sizeof w), 0);
  cfg.radius_m = 1e-4, cfg.load_n_per_m = 10.0;
  pt.contact_width_m = 2.0 * 1.63e-5;
  pt.converged = false;
  unsigned m = vl_assumptions_check(&cfg, &psd, &pt, w, sizeof w);
  printf("  small cylinder: '%s'\n", w);
  assert_true(m & VL_ASSUME_HOMOGENISATION);
  assert_true(strstr(w, "a_H") != NULL);
  /* without the PSD (no q0) the check is skipped */
  w[0] = '\0';
  assert_false(vl_assumptions_check(&cfg, NULL, &pt, w, sizeof w) & VL_ASSUME_HOMOGENISATION);
  vl_persson_free(tab);
  vl_psd_free(&psd);
}

/* Each check on a point made to violate it, and on its benign twin. */
static void test_each_check(void **state) {
  (void)state;
  vl_psd psd;
  vl_persson *tab;
  const double h = 1e-7;
  tab = vl_test_paper_surface(h, &psd);
  vl_contact_config dry, wet;
  seed_config(&dry, tab, 0.0);
  seed_config(&wet, tab, 1e-3);
  double a0 = sqrt(4.0 * HARD_LOAD * HARD_RADIUS / (M_PI * HARD_E0 / (1.0 - HARD_NU * HARD_NU)));
  double dx = 4.6 * a0 / 256.0;
  struct {
    const char *what;
    unsigned bit;
    const vl_contact_config *cfg;
    double u_min, u_c, width, fluid, v0;
  } cs[] = {
      /* Persson table: u_min below 1e-3 h_rms */
      {"Persson table", VL_ASSUME_PERSSON_TABLE, &dry, 1e-4 * h, 0.5 * h, 2 * a0, 0, 1e-3},
      {"Persson table (benign)", 0, &dry, 1e-2 * h, 0.5 * h, 2 * a0, 0, 1e-3},
      /* grid: 5 cells */
      {"grid", VL_ASSUME_GRID, &dry, 0.5 * h, 0.5 * h, 5 * dx, 0, 1e-3},
      {"grid (benign)", 0, &dry, 0.5 * h, 0.5 * h, 9 * dx, 0, 1e-3},
      /* half-space: half-width 0.25 R */
      {"half-space", VL_ASSUME_HALF_SPACE, &dry, 0.5 * h, 0.5 * h, 0.5 * HARD_RADIUS, 0, 1e-3},
      /* continuum film: 0.5 nm (wet only) */
      {"continuum film", VL_ASSUME_CONTINUUM_FILM, &wet, 5e-10, 0.5 * h, 2 * a0, 0, 1e-3},
      {"continuum film (dry)", VL_ASSUME_PERSSON_TABLE, &dry, 5e-11, 0.5 * h, 2 * a0, 0, 1e-3},
      /* thin film: u_central 0.2 of the half-width */
      {"thin film", VL_ASSUME_THIN_FILM, &wet, 0.8 * h, 0.2 * a0, 2 * a0, 1.0, 1e-3},
      /* inertia: 1000 * 10 * (3e-5)^2 / (1e-3 * a0) = 5.5 */
      {"inertia", VL_ASSUME_INERTIA, &wet, 3e-5, 3e-5, 2 * a0, 1.0, 10.0},
      {"inertia (benign)", 0, &wet, 3e-5, 3e-5, 2 * a0, 1.0, 1.0},
      /* Patir-Cheng below h/sigma = 0.5 with the fluid carrying load */
      {"flow factors", VL_ASSUME_FLOW_FACTORS, &wet, 0.5 * h, 0.5 * h, 2 * a0, 0.5, 1e-3},
      {"flow factors (boundary)", 0, &wet, 0.5 * h, 0.5 * h, 2 * a0, 0.01, 1e-3},
      {"flow factors (benign)", 0, &wet, 0.8 * h, 0.8 * h, 2 * a0, 0.5, 1e-3},
  };
  for (size_t i = 0; i < sizeof cs / sizeof cs[0]; i++) {
    vl_point pt;
    memset(&pt, 0, sizeof pt);
    pt.converged = true;
    pt.v0_m_s = cs[i].v0;
    pt.u_min_m = cs[i].u_min, pt.u_central_m = cs[i].u_c;
    pt.contact_width_m = cs[i].width, pt.fluid_load_fraction = cs[i].fluid;
    char w[VL_WARN_MAX] = "";
    unsigned m = vl_assumptions_check(cs[i].cfg, &psd, &pt, w, sizeof w);
    printf("  %-26s mask %#5x '%s'\n", cs[i].what, m, w);
    if (m != cs[i].bit) fail_msg("%s: mask %#x, expected %#x", cs[i].what, m, cs[i].bit);
    assert_int_equal(w[0] != '\0', m != 0);
    assert_null(strpbrk(w, ",\""));
  }
  /* smooth flow factors on a rough surface: already at u_min < 3 h_rms */
  wet.flow_factors = VL_FLOW_FACTORS_SMOOTH;
  vl_point pt = benign_point(h);
  pt.u_min_m = 2.0 * h, pt.u_central_m = 2.0 * h, pt.fluid_load_fraction = 0.5;
  char w[VL_WARN_MAX] = "";
  assert_int_equal(vl_assumptions_check(&wet, &psd, &pt, w, sizeof w), VL_ASSUME_FLOW_FACTORS);
  assert_non_null(strstr(w, "smooth flow factors"));
  vl_persson_free(tab);
  vl_psd_free(&psd);
}

/* The Prony window: a two-term series with tau 1e-3 and 0.1 s covers wH
 * in [1, 1e4] rad/s; the seed contact at v0 = 1e-8 m/s (wH ~ 2e-5 rad/s)
 * and at 100 m/s (~2e5) lies outside, at 1e-3 m/s (~2) inside. One term
 * (the model rubber) is never flagged. */
static void test_prony_window(void **state) {
  (void)state;
  vl_contact_config cfg;
  seed_config(&cfg, NULL, 0.0);
  cfg.rubber.n_terms = 2;
  cfg.rubber.A[0] = 4.5, cfg.rubber.tau_s[0] = 1e-3;
  cfg.rubber.A[1] = 4.5, cfg.rubber.tau_s[1] = 0.1;
  const double v[] = {1e-8, 1e-3, 100.0};
  const int flagged[] = {1, 0, 1};
  for (int i = 0; i < 3; i++) {
    vl_point pt = benign_point(0.0);
    pt.v0_m_s = v[i];
    char w[VL_WARN_MAX] = "";
    unsigned m = vl_assumptions_check(&cfg, NULL, &pt, w, sizeof w);
    double wh;
    vl_asperity_state(&cfg.rubber, cfg.load_n_per_m, cfg.radius_m, v[i], NULL, NULL, &wh);
    printf("  v0 %g m/s, wH %.3g rad/s: '%s'\n", v[i], wh, w);
    assert_int_equal((m & VL_ASSUME_PRONY_WINDOW) != 0, flagged[i]);
  }
  cfg.rubber = vl_prony_single(HARD_E0, 10.0, HARD_TAU, HARD_NU);
  vl_point pt = benign_point(0.0);
  pt.v0_m_s = 100.0;
  char w[VL_WARN_MAX] = "";
  assert_int_equal(vl_assumptions_check(&cfg, NULL, &pt, w, sizeof w), 0);
}

/* The column: appends after the solver's warnings with ';', never repeats
 * a warning, leaves out (never cuts) one that does not fit, keeps the
 * mask, and handles cap 0 and a NULL buffer. */
static void test_column(void **state) {
  (void)state;
  vl_psd psd;
  vl_persson *tab;
  tab = vl_test_paper_surface(3e-6, &psd);
  vl_contact_config cfg;
  seed_config(&cfg, tab, 1e-3);
  vl_point pt = benign_point(3e-6);
  pt.u_min_m = 1e-10; /* below the table and 1 nm: three warnings with the slope */
  snprintf(pt.warnings, sizeof pt.warnings, "pressure reaches the domain edge (domain too short)");
  unsigned m = vl_assumptions_check(&cfg, &psd, &pt, pt.warnings, sizeof pt.warnings);
  printf("  '%s'\n", pt.warnings);
  assert_true(m == (VL_ASSUME_RMS_SLOPE | VL_ASSUME_PERSSON_TABLE | VL_ASSUME_CONTINUUM_FILM));
  assert_int_equal(strncmp(pt.warnings, "pressure reaches the domain edge (domain too short);", 52),
                   0);
  size_t n1 = strlen(pt.warnings);
  /* again: nothing repeated */
  assert_int_equal(vl_assumptions_check(&cfg, &psd, &pt, pt.warnings, sizeof pt.warnings), m);
  assert_int_equal(strlen(pt.warnings), n1);
  int semis = 0;
  for (const char *s = pt.warnings; *s; s++)
    semis += *s == ';';
  assert_int_equal(semis, 3);
  /* a small buffer: whole warnings or nothing */
  for (size_t cap = 0; cap < 80; cap++) {
    char small[80];
    memset(small, 'x', sizeof small);
    if (cap) small[0] = '\0';
    unsigned mm = vl_assumptions_check(&cfg, &psd, &pt, cap ? small : NULL, cap);
    assert_int_equal(mm, m);
    if (!cap) continue;
    size_t len = strlen(small);
    assert_true(len < cap);
    /* every item is a whole warning of the full column */
    char copy[80];
    memcpy(copy, small, len + 1);
    for (char *tok = strtok(copy, ";"); tok; tok = strtok(NULL, ";"))
      assert_non_null(strstr(pt.warnings, tok));
    if (len) assert_true(small[len - 1] != ';');
  }
  vl_persson_free(tab);
  vl_psd_free(&psd);
}

/* A solved point of the fig03 scene (dry, paper surface 3 um) on a domain
 * too short: solver and assumption warnings fit in the column together. */
static void test_solved_point(void **state) {
  (void)state;
  vl_psd psd;
  vl_persson *tab;
  tab = vl_test_paper_surface(3e-6, &psd);
  vl_contact_config cfg;
  seed_config(&cfg, tab, 0.0);
  cfg.grid = 64;
  cfg.x_min_a0 = -0.5, cfg.x_max_a0 = 0.5; /* too short: the solver warns too */
  vl_contact *c;
  vl_error err;
  assert_int_equal(vl_contact_create(&cfg, &c, &err), VL_OK);
  vl_point pt;
  assert_int_equal(vl_contact_solve(c, 1e-6, &pt, &err), VL_OK);
  unsigned m = vl_assumptions_check(&cfg, &psd, &pt, pt.warnings, sizeof pt.warnings);
  printf("  fig03 at 1e-6 m/s on [-0.5, 0.5] a0: '%s' (%zu chars)\n", pt.warnings,
         strlen(pt.warnings));
  assert_true(m & VL_ASSUME_RMS_SLOPE);
  assert_non_null(strstr(pt.warnings, "domain edge"));
  assert_non_null(strstr(pt.warnings, "rms slope"));
  vl_contact_free(c);
  vl_persson_free(tab);
  vl_psd_free(&psd);
  for (unsigned b = 0; b < HARD_NBITS; b++)
    assert_string_not_equal(vl_assumption_name(1u << b), "unknown");
  assert_string_equal(vl_assumption_name(3), "unknown");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_rms_slope),  cmocka_unit_test(test_homogenisation),
      cmocka_unit_test(test_each_check), cmocka_unit_test(test_prony_window),
      cmocka_unit_test(test_column),     cmocka_unit_test(test_solved_point),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
