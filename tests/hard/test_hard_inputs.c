/* Hard-case matrix, inputs (issue 8): malformed combinations give a clean
 * VL_EINPUT with a message (never a crash, a NaN or a half-made object);
 * domains too short, or missing the contact altogether, warn or fail
 * cleanly; scales at the edge of double precision either are refused or
 * give finite answers. Library calls only (the command line and its
 * parsers are covered by test_hostile_input.c and the fuzz targets). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "contact_private.h"
#include "hard_util.h"
#include "persson_internal.h"
#include "rheology_internal.h"
#include "vl_test_scenes.h"
#include "vl_test_util.h"

static hard_family fam_domain = {
    .name = "short domains", .min_rate = 0.0, .min_rate_subnm = 0.0, .edge_numerics = true};
static hard_family fam_scales = {
    .name = "extreme scales", .min_rate = 0.0, .min_rate_subnm = 0.0, .edge_numerics = true};
static hard_family fam_enum = {
    .name = "garbage enumerations", .min_rate = 0.0, .min_rate_subnm = 0.0};
static hard_family fam_grids = {.name = "grids 8-127 (edges)", .min_rate = 1.0};

static vl_psd g_psd;
static vl_persson *g_tab;

static int setup(void **state) {
  (void)state;
  g_tab = vl_test_paper_surface(3e-6, &g_psd);
  return 0;
}
static int teardown(void **state) {
  (void)state;
  vl_persson_free(g_tab);
  vl_psd_free(&g_psd);
  return 0;
}

/* The seed's scene (fig05 geometry, model rubber), dry smooth, grid 64 on
 * [-1.6, 1.4] a0. */
static void seed_config(vl_contact_config *cfg) {
  vl_contact_config_defaults(cfg);
  cfg->rubber = vl_prony_single(HARD_E0, 10.0, HARD_TAU, HARD_NU);
  cfg->radius_m = HARD_RADIUS;
  cfg->load_n_per_m = HARD_LOAD;
  cfg->grid = 64;
  cfg->x_min_a0 = -1.6, cfg->x_max_a0 = 1.4;
}

/* One refused configuration: VL_EINPUT, a message naming `needle`, no
 * object. */
static void expect_refused(const vl_contact_config *cfg, const char *what, const char *needle) {
  vl_contact *c = (vl_contact *)&g_psd; /* must be reset to NULL */
  vl_error err;
  memset(&err, 0, sizeof err);
  vl_status st = vl_contact_create(cfg, &c, &err);
  if (st != VL_EINPUT) {
    vl_contact_free(st == VL_OK ? c : NULL);
    fail_msg("%s: expected VL_EINPUT, got %d (%s)", what, st, err.msg);
  }
  if (c != NULL) fail_msg("%s: refused but *out not NULL", what);
  if (!err.msg[0] || (needle && !strstr(err.msg, needle)))
    fail_msg("%s: message '%s' does not name '%s'", what, err.msg, needle ? needle : "");
  printf("  %-34s -> %s\n", what, err.msg);
}

typedef struct {
  const char *what, *needle;
  void (*mutate)(vl_contact_config *);
} mutation;

#define M(name, needle, body)                                                                      \
  static void mut_##name(vl_contact_config *c) { body; }
M(grid0, "grid", c->grid = 0)
M(grid1, "grid", c->grid = 1)
M(grid7, "grid", c->grid = 7)
M(grid_huge, "grid", c->grid = (size_t)1 << 40)
M(load_neg, "load", c->load_n_per_m = -1000.0)
M(load_zero, "load", c->load_n_per_m = 0.0)
M(load_nan, "load", c->load_n_per_m = NAN)
M(load_inf, "load", c->load_n_per_m = INFINITY)
M(radius_nan, "radius", c->radius_m = NAN)
M(radius_neg, "radius", c->radius_m = -0.01)
M(radius_zero, "radius", c->radius_m = 0.0)
M(radius_inf, "radius", c->radius_m = INFINITY)
M(sigma_neg, "sigma_s", c->sigma_s_pa = -1.0)
M(sigma_nan, "sigma_s", c->sigma_s_pa = NAN)
M(eta_neg, "viscosity", c->eta_pa_s = -1e-3)
M(eta_nan, "viscosity", c->eta_pa_s = NAN)
M(eta_inf, "viscosity", c->eta_pa_s = INFINITY)
M(dom_reversed, "domain", (c->x_min_a0 = 1.0, c->x_max_a0 = -1.0))
M(dom_empty, "domain", (c->x_min_a0 = 0.5, c->x_max_a0 = 0.5))
M(dom_nan, "domain", c->x_min_a0 = NAN)
M(dom_nan_end, "domain", c->x_max_a0 = NAN)
M(dom_inf, NULL, c->x_min_a0 = -INFINITY)
M(tol_zero, "tolerance", c->tolerance = 0.0)
M(tol_one, "tolerance", c->tolerance = 1.0)
M(tol_nan, "tolerance", c->tolerance = NAN)
M(einf_zero, "Einf", c->rubber.e_inf_pa = 0.0)
M(einf_nan, "Einf", c->rubber.e_inf_pa = NAN)
M(nu_big, "nu", c->rubber.nu = 0.7)
M(nu_neg, "nu", c->rubber.nu = -0.1)
M(a_neg, "A", c->rubber.A[0] = -1.0)
M(a_nan, "A", c->rubber.A[0] = NAN)
M(tau_zero, "tau", c->rubber.tau_s[0] = 0.0)
M(tau_inf, "tau", c->rubber.tau_s[0] = INFINITY)
M(terms_many, "terms", c->rubber.n_terms = VL_PRONY_MAX_TERMS + 1)
#undef M

/* vl_contact_create refuses each malformed combination. */
static void test_create_refuses(void **state) {
  (void)state;
#define E(name, needle)                                                                            \
  { #name, needle, mut_##name }
  const mutation ms[] = {
      E(grid0, "grid"),        E(grid1, "grid"),         E(grid7, "grid"),
      E(grid_huge, "grid"),    E(load_neg, "load"),      E(load_zero, "load"),
      E(load_nan, "load"),     E(load_inf, "load"),      E(radius_nan, "radius"),
      E(radius_neg, "radius"), E(radius_zero, "radius"), E(radius_inf, "radius"),
      E(sigma_neg, "sigma_s"), E(sigma_nan, "sigma_s"),  E(eta_neg, "viscosity"),
      E(eta_nan, "viscosity"), E(eta_inf, "viscosity"),  E(dom_reversed, "domain"),
      E(dom_empty, "domain"),  E(dom_nan, "domain"),     E(dom_nan_end, "domain"),
      E(dom_inf, NULL),        E(tol_zero, "tolerance"), E(tol_one, "tolerance"),
      E(tol_nan, "tolerance"), E(einf_zero, "Einf"),     E(einf_nan, "Einf"),
      E(nu_big, "nu"),         E(nu_neg, "nu"),          E(a_neg, "A"),
      E(a_nan, "A"),           E(tau_zero, "tau"),       E(tau_inf, "tau"),
      E(terms_many, "terms"),
  };
#undef E
  for (size_t i = 0; i < sizeof ms / sizeof ms[0]; i++) {
    /* dry smooth, dry rough and wet rough variants of each */
    for (int v = 0; v < 3; v++) {
      vl_contact_config cfg;
      seed_config(&cfg);
      if (v >= 1) cfg.roughness = g_tab;
      if (v == 2) cfg.eta_pa_s = 1e-3, cfg.flow_factors = VL_FLOW_FACTORS_PATIR_CHENG;
      ms[i].mutate(&cfg);
      char what[64];
      snprintf(what, sizeof what, "%s (%s)", ms[i].what,
               v == 0   ? "dry smooth"
               : v == 1 ? "dry rough"
                        : "wet rough");
      expect_refused(&cfg, what, ms[i].needle);
    }
  }
}

/* Speeds: NaN, negative and infinite speeds are refused by a solve (and 0
 * by a wet one), a sweep refuses a list holding one, and the contact stays
 * usable afterwards (a valid solve converges). Viscosity changes likewise. */
static void test_solve_refuses(void **state) {
  (void)state;
  for (int wet = 0; wet < 2; wet++) {
    vl_contact_config cfg;
    seed_config(&cfg);
    if (wet)
      cfg.roughness = g_tab, cfg.eta_pa_s = 1e-3, cfg.flow_factors = VL_FLOW_FACTORS_PATIR_CHENG;
    vl_contact *c;
    vl_error err;
    assert_int_equal(vl_contact_create(&cfg, &c, &err), VL_OK);
    const double bad[] = {NAN, -1e-3, INFINITY, -INFINITY, 0.0};
    for (size_t i = 0; i < 5; i++) {
      if (!wet && bad[i] == 0.0) continue; /* a dry contact at rest is valid */
      vl_point pt;
      err.msg[0] = '\0';
      assert_int_equal(vl_contact_solve(c, bad[i], &pt, &err), VL_EINPUT);
      assert_true(err.msg[0] != '\0' && strstr(err.msg, "speed"));
      assert_false(pt.converged);
      assert_true(pt.mu == 0.0);
      double list[3] = {1e-6, bad[i], 1e-3};
      vl_point pts[3];
      assert_int_equal(vl_sweep_run(c, 3, list, NULL, pts, NULL, NULL, NULL, &err), VL_EINPUT);
      assert_true(strstr(err.msg, "sweep speed 2") != NULL);
    }
    if (wet) {
      assert_int_equal(vl_contact_set_viscosity(c, NAN, &err), VL_EINPUT);
      assert_int_equal(vl_contact_set_viscosity(c, -1.0, &err), VL_EINPUT);
      assert_int_equal(vl_contact_set_viscosity(c, 0.0, &err), VL_EINPUT);
      vl_point pt;
      assert_int_equal(vl_contact_solve_viscosity(c, 1e-3, 1e-2, 1.0, &pt, &err), VL_EINPUT);
      assert_true(vl_contact_viscosity(c) == 1e-3);
    } else {
      assert_int_equal(vl_contact_set_viscosity(c, 1e-3, &err), VL_EINPUT);
      assert_true(strstr(err.msg, "dry") != NULL);
    }
    vl_point pt;
    assert_int_equal(vl_contact_solve(c, 1e-3, &pt, &err), VL_OK);
    assert_true(pt.converged && isfinite(pt.mu));
    vl_contact_free(c);
  }
  vl_contact_free(NULL); /* allowed, like free(NULL) */
}

/* Surfaces: the PSD and Persson builders refuse malformed spectra. */
static void test_surface_refuses(void **state) {
  (void)state;
  vl_psd psd;
  vl_error err;
  const double sa[][4] = {{0.0, 2e5, 7.8e9, 3e-6},    {1.5, 2e5, 7.8e9, 3e-6},
                          {NAN, 2e5, 7.8e9, 3e-6},    {0.8, 0.0, 7.8e9, 3e-6},
                          {0.8, 2e5, 1e5, 3e-6},      {0.8, 2e5, 2e5, 3e-6},
                          {0.8, 2e5, INFINITY, 3e-6}, {0.8, 2e5, 7.8e9, 0.0},
                          {0.8, 2e5, 7.8e9, NAN},     {0.8, -2e5, 7.8e9, 3e-6}};
  for (size_t i = 0; i < sizeof sa / sizeof sa[0]; i++) {
    err.msg[0] = '\0';
    assert_int_equal(vl_psd_init_self_affine(&psd, sa[i][0], sa[i][1], sa[i][2], sa[i][3], &err),
                     VL_EINPUT);
    assert_true(err.msg[0] != '\0');
    vl_psd_free(&psd); /* safe after a refusal */
  }
  const double q_dec[] = {1e5, 1e4, 1e6}, q_ok[] = {1e5, 1e6, 1e7}, q_dup[] = {1e5, 1e5, 1e6};
  const double c_ok[] = {1e-20, 1e-24, 1e-28}, c_zero[] = {1e-20, 0.0, 1e-28},
               c_nan[] = {1e-20, NAN, 1e-28}, c_neg[] = {1e-20, -1e-24, 1e-28};
  assert_int_equal(vl_psd_init_tabulated(&psd, 3, q_dec, c_ok, &err), VL_EINPUT);
  assert_int_equal(vl_psd_init_tabulated(&psd, 3, q_dup, c_ok, &err), VL_EINPUT);
  assert_int_equal(vl_psd_init_tabulated(&psd, 3, q_ok, c_zero, &err), VL_EINPUT);
  assert_int_equal(vl_psd_init_tabulated(&psd, 3, q_ok, c_nan, &err), VL_EINPUT);
  assert_int_equal(vl_psd_init_tabulated(&psd, 3, q_ok, c_neg, &err), VL_EINPUT);
  assert_int_equal(vl_psd_init_tabulated(&psd, 1, q_ok, c_ok, &err), VL_EINPUT);
  assert_int_equal(vl_psd_init_tabulated(&psd, 0, q_ok, c_ok, &err), VL_EINPUT);
  assert_true(err.msg[0] != '\0');
  /* a valid PSD, a table size below the minimum */
  assert_int_equal(vl_psd_init_tabulated(&psd, 3, q_ok, c_ok, &err), VL_OK);
  vl_persson *tab = (vl_persson *)&psd;
  assert_int_equal(vl_persson_build(&psd, 10, &tab, &err), VL_EINPUT);
  assert_true(strstr(err.msg, "n_table") != NULL);
  vl_psd_free(&psd);
}

/* Domains too short for the contact, and domains that miss it: each point
 * converges with the solver's domain warning in its column, or is flagged
 * not converged; everything finite (hard_util.h checks). Dry smooth, dry
 * rough (3 um), wet smooth (soft EHL) and wet rough (fig05), grid 48. */
static void test_short_domains(void **state) {
  (void)state;
  const double doms[][2] = {{-0.6, 0.6}, {-0.3, 0.3}, {-0.05, 0.05},
                            {0.0, 1e-6}, {2.0, 5.0},  {-1e6, 1e6}};
  double v[] = {1e-9, 1e-6, 1e-3, 1.0};
  for (int kind = 0; kind < 4; kind++) {
    for (size_t d = 0; d < sizeof doms / sizeof doms[0]; d++) {
      vl_contact_config cfg;
      seed_config(&cfg);
      cfg.grid = 48;
      if (kind & 1)
        cfg.roughness = g_tab, cfg.sigma_s_pa = 1e6, cfg.flow_factors = VL_FLOW_FACTORS_PATIR_CHENG;
      if (kind & 2) cfg.eta_pa_s = 1e-4;
      cfg.x_min_a0 = doms[d][0], cfg.x_max_a0 = doms[d][1];
      char label[200];
      snprintf(label, sizeof label, "%s %s, seed scene, domain [%g, %g] a0",
               kind & 2 ? "wet" : "dry", kind & 1 ? "rough 3 um" : "smooth", doms[d][0],
               doms[d][1]);
      if (doms[d][0] >= 0.0) { /* the contact forms around x = 0: such domains are refused */
        expect_refused(&cfg, label, "axis");
        continue;
      }
      vl_point pts[4];
      hard_run_corner(&fam_domain, label, &cfg, kind & 1 ? &g_psd : NULL, 4, v, pts);
      /* where the Hertz half-width at |Er(wH)| (the contact shrinks as the
       * rubber turns glassy) exceeds the domain's half-length by 10 %, the
       * pressure must reach an edge, and the point must say so */
      double a0 =
          sqrt(4.0 * HARD_LOAD * HARD_RADIUS / (M_PI * HARD_E0 / (1.0 - HARD_NU * HARD_NU)));
      for (int i = 0; i < 4; i++) {
        double e_h, a_h;
        vl_asperity_state(&cfg.rubber, HARD_LOAD, HARD_RADIUS, v[i], &e_h, &a_h, NULL);
        if (!pts[i].converged || doms[d][0] >= 0.0 ||
            a_h < 1.1 * a0 * fmax(-doms[d][0], doms[d][1]))
          continue;
        if (!strstr(pts[i].warnings, "domain"))
          fail_msg("no domain warning at v0 = %g in %s: '%s'", v[i], label, pts[i].warnings);
      }
    }
  }
  hard_assert_rate(&fam_domain);
}

/* Scales at the edge of double precision with otherwise valid inputs: the
 * solver either refuses them (VL_EINPUT at create) or every point is
 * finite and checked like any other (converged or flagged). */
static void test_extreme_scales(void **state) {
  (void)state;
  struct {
    const char *label;
    double radius, load, einf, A, tau;
  } cs[] = {
      {"R 1e200 m, fN 1e200 N/m", 1e200, 1e200, 3.6e7, 9.0, 0.1},
      {"R 1e-300 m, fN 1e-300 N/m", 1e-300, 1e-300, 3.6e7, 9.0, 0.1},
      {"R 1e-30 m, fN 1e30 N/m", 1e-30, 1e30, 3.6e7, 9.0, 0.1},
      {"Einf 1e-300 Pa", HARD_RADIUS, HARD_LOAD, 1e-300, 9.0, 0.1},
      {"Einf 1e300 Pa", HARD_RADIUS, HARD_LOAD, 1e300, 9.0, 0.1},
      {"A 1e300 (E0 ~ 1e-293 Pa)", HARD_RADIUS, HARD_LOAD, 3.6e7, 1e300, 0.1},
      {"tau 1e300 s", HARD_RADIUS, HARD_LOAD, 3.6e7, 9.0, 1e300},
      {"tau 1e-300 s", HARD_RADIUS, HARD_LOAD, 3.6e7, 9.0, 1e-300},
  };
  double v[] = {1e-12, 1e-3, 100.0};
  for (size_t i = 0; i < sizeof cs / sizeof cs[0]; i++) {
    for (int wet = 0; wet < 2; wet++) {
      vl_contact_config cfg;
      seed_config(&cfg);
      cfg.grid = 32;
      cfg.radius_m = cs[i].radius, cfg.load_n_per_m = cs[i].load;
      cfg.rubber.e_inf_pa = cs[i].einf, cfg.rubber.A[0] = cs[i].A, cfg.rubber.tau_s[0] = cs[i].tau;
      if (wet) cfg.eta_pa_s = 1e-3;
      char label[200];
      snprintf(label, sizeof label, "%s, %s", cs[i].label,
               wet ? "wet smooth eta 1e-3" : "dry smooth");
      vl_contact *c;
      vl_error err;
      vl_status st = vl_contact_create(&cfg, &c, &err);
      if (st == VL_EINPUT) {
        printf("  refused: %s: %s\n", label, err.msg);
        continue;
      }
      assert_int_equal(st, VL_OK);
      vl_contact_free(c);
      hard_run_corner(&fam_scales, label, &cfg, NULL, 3, v, NULL);
    }
  }
  hard_assert_rate(&fam_scales);
}

/* Out-of-range enumerations are refused, naming the option. */
static void test_enum_garbage(void **state) {
  (void)state;
  double v[] = {1e-6, 1e-3};
  for (int k = 0; k < 2; k++) {
    vl_contact_config cfg;
    seed_config(&cfg);
    cfg.grid = 32;
    if (k == 0)
      cfg.linear_solver = (vl_linear_solver)7;
    else
      cfg.roughness = g_tab, cfg.eta_pa_s = 1e-4, cfg.flow_factors = (vl_flow_factor_kind)99;
    expect_refused(&cfg, k == 0 ? "linear_solver = 7" : "flow_factors = 99",
                   k == 0 ? "linear solver" : "flow factors");
  }
  (void)v;
  hard_assert_rate(&fam_enum);
}

/* Grid edges: the smallest grid the solver accepts (8), odd sizes, and
 * 2048 for a dry smooth point at the seed's loss peak. */
static void test_grid_edges(void **state) {
  (void)state;
  const size_t gs[] = {8, 9, 33, 127};
  double v[] = {1e-6, 1e-3, 1e-1};
  for (size_t i = 0; i < 4; i++) {
    for (int rough = 0; rough < 2; rough++) {
      vl_contact_config cfg;
      seed_config(&cfg);
      cfg.grid = gs[i];
      if (rough) cfg.roughness = g_tab, cfg.x_min_a0 = -1.8, cfg.x_max_a0 = 1.8;
      char label[100];
      snprintf(label, sizeof label, "seed %s, grid %zu", rough ? "rough 3 um" : "smooth", gs[i]);
      hard_run_corner(&fam_grids, label, &cfg, rough ? &g_psd : NULL, 3, v, NULL);
    }
  }
  hard_assert_rate(&fam_grids);
}

static void test_summary(void **state) {
  (void)state;
  hard_family *f[] = {&fam_domain, &fam_scales, &fam_enum, &fam_grids};
  hard_print_summary("inputs", f, 4);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_create_refuses),  cmocka_unit_test(test_solve_refuses),
      cmocka_unit_test(test_surface_refuses), cmocka_unit_test(test_short_domains),
      cmocka_unit_test(test_extreme_scales),  cmocka_unit_test(test_enum_garbage),
      cmocka_unit_test(test_grid_edges),      cmocka_unit_test(test_summary),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
