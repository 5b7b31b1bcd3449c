/* The temperature effect (issue 9, docs/MODEL.md sections 2 and 10): the
 * compound's Prony times shifted by its WLF a_T, the fluid's viscosity by
 * its stored Vogel law.
 *
 * Library level: nothing changes at the reference temperature; the dry
 * model's exact identity "compound shifted by a_T at speed v = compound at
 * Tref at speed a_T v"; the shipped laws against independent published
 * viscosities (IAPWS 2008 for water, Segur & Oberstar 1951 for glycerol);
 * the seed's remark on the rolling number (docs/CASES.md fig15) measured on the
 * shipped sbr-unfilled; the stored law (migration from schema 2, adding,
 * refusing bad laws). Command line: scenes with temperature = on and their
 * errors, `friction` and `compare` with --temperature. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "vl_test_util.h"

#include <math.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fluid_internal.h"
#include "rheology_internal.h"
#include "simulation_internal.h"
#include "viscolube/database.h"
#include "viscolube/fluid.h"
#include "viscolube/rheology.h"
#include "viscolube/scene.h"
#include "viscolube/simulation.h"

static char g_db[1200]; /* one database for the library tests, created once */

static int group_setup(void **state) {
  (void)state;
  snprintf(g_db, sizeof g_db, "%s/materials.db", vl_test_tmpdir());
  return 0;
}

static vl_db *open_db(const char *path) {
  vl_db *db = NULL;
  vl_error err = {{0}};
  if (vl_db_open(path, &db, &err) != VL_OK) fail_msg("open %s: %s", path, err.msg);
  return db;
}

/* A scene built in code: compound on a smooth rigid cylinder, dry,
 * viscoelastic, one speed (m/s). R = 1 mm and fN = 117 N/m as the seed's
 * real-rubber figures. */
static void dry_scene(vl_scene *sc, const char *compound, double v0, int temperature_on,
                      double t_c) {
  vl_scene_defaults(sc);
  snprintf(sc->path, sizeof sc->path, "test");
  snprintf(sc->compound, sizeof sc->compound, "%s", compound);
  sc->radius_m = 1e-3;
  sc->load_n_per_m = 117.0;
  sc->quantity = VL_SWEEP_V0;
  sc->from = sc->to = v0;
  sc->points = 1;
  sc->grid = 128;
  sc->effects.temperature = temperature_on;
  sc->effects.temperature_c = temperature_on ? t_c : NAN;
}

/* The seed's wet rough scene of Fig. 15 (sbr-unfilled, paper-0.5um, water,
 * sigma_s 1 MPa, smooth flow factors as cases/fig15.ini) at one v0 eta. */
static void wet_scene(vl_scene *sc, double v0_eta, int temperature_on, double t_c) {
  dry_scene(sc, "sbr-unfilled", v0_eta, temperature_on, t_c);
  snprintf(sc->surface, sizeof sc->surface, "paper-0.5um");
  snprintf(sc->fluid, sizeof sc->fluid, "water");
  snprintf(sc->fluids[0], sizeof sc->fluids[0], "water");
  sc->n_fluids = 1;
  sc->quantity = VL_SWEEP_V0_ETA;
  sc->sigma_s_pa = 1e6;
  sc->effects.roughness = sc->effects.fluid = sc->effects.solid_shear = true;
  sc->grid = 64;
  sc->domain_min_a0 = VL_WET_DOMAIN_MIN_A0;
  sc->domain_max_a0 = VL_WET_DOMAIN_MAX_A0;
}

/* Solves the one point of the scene; fails the test unless it converges.
 * *a_T and *eta (may be NULL) get what the simulation used. */
static vl_point solve(vl_db *db, const vl_scene *sc, double *a_T, double *eta) {
  vl_simulation *sim = NULL;
  vl_error err = {{0}};
  if (vl_simulation_create(sc, db, &sim, &err) != VL_OK) fail_msg("create: %s", err.msg);
  vl_point pt = {0};
  vl_sweep_stats stats;
  if (vl_simulation_run(sim, &pt, NULL, NULL, &stats, &err) != VL_OK || !pt.converged)
    fail_msg("solve at %g: %s", vl_simulation_speeds(sim)[0], err.msg);
  if (a_T) *a_T = vl_simulation_shift_factor(sim);
  if (eta) *eta = vl_simulation_eta(sim);
  vl_simulation_free(sim);
  return pt;
}

/* ---- (a) at the reference temperature nothing changes ------------------ */

static void test_reference_temperature(void **state) {
  (void)state;
  vl_db *db = open_db(g_db);
  vl_db_compound c;
  vl_error err = {{0}};
  assert_int_equal(vl_db_compound_info(db, "sbr-unfilled", &c, &err), VL_OK);
  /* a dry viscoelastic point near the loss peak (v0 / a0 ~ the peak
   * frequency): off and on at tref give the same numbers, bit for bit */
  vl_scene off, on;
  dry_scene(&off, "sbr-unfilled", 1e-4, 0, NAN);
  dry_scene(&on, "sbr-unfilled", 1e-4, 1, c.tref_c);
  double a_T = 0.0;
  vl_point p0 = solve(db, &off, NULL, NULL), p1 = solve(db, &on, &a_T, NULL);
  printf("  dry at tref: mu_Rc %.10g (off) %.10g (on), a_T %g\n", p0.mu_Rc, p1.mu_Rc, a_T);
  assert_true(a_T == 1.0);
  assert_true(p0.mu_Rc > 0.01); /* a point where the rubber matters */
  assert_true(p1.mu_Rc == p0.mu_Rc && p1.mu == p0.mu && p1.u_min_m == p0.u_min_m);

  /* a wet scene: the compound and the viscosity the solver gets are the
   * stored ones, bit for bit (water's tref is 20 C, as the compound's) */
  vl_scene w0, w1;
  wet_scene(&w0, 1e-8, 0, NAN);
  wet_scene(&w1, 1e-8, 1, 20.0);
  vl_simulation *s0 = NULL, *s1 = NULL;
  assert_int_equal(vl_simulation_create(&w0, db, &s0, &err), VL_OK);
  assert_int_equal(vl_simulation_create(&w1, db, &s1, &err), VL_OK);
  assert_true(vl_simulation_eta(s0) == vl_simulation_eta(s1));
  assert_true(vl_simulation_eta(s1) == 1.0e-3);
  assert_memory_equal(vl_simulation_rubber(s0), vl_simulation_rubber(s1), sizeof(vl_prony));
  assert_true(vl_simulation_speeds(s0)[0] == vl_simulation_speeds(s1)[0]);
  assert_true(isnan(vl_simulation_temperature_c(s0)) && vl_simulation_temperature_c(s1) == 20.0);
  vl_simulation_free(s0);
  vl_simulation_free(s1);

  /* a compound without WLF constants is fine at its own tref */
  vl_scene m;
  dry_scene(&m, "model-rubber", 1e-3, 1, 20.0);
  vl_simulation *sm = NULL;
  assert_int_equal(vl_simulation_create(&m, db, &sm, &err), VL_OK);
  vl_simulation_free(sm);
  vl_db_close(db);
}

/* ---- (b) the exact identity of the dry model ---------------------------- */

/* Dry, the model sees the rubber only through w tau_i with w ~ v0 / length
 * (the kernel of section 3, Persson's |Er(wH)| with wH = pi v0 / a_H), and
 * the lengths a0, a_H depend on moduli that a horizontal shift leaves
 * alone: multiplying every tau_i by a_T is the same as multiplying v0 by
 * a_T. Both sides are solved on the same grid from the same (Hertz) start
 * to a scaled residual of 1e-9; they differ only by the rounding of the
 * products v0 tau_i, so they must agree far below what the residual allows
 * (|d mu| ~ 1e-9 relative); 1e-7 relative leaves a margin of 100. */
static void test_shift_equals_speed(void **state) {
  (void)state;
  vl_db *db = open_db(g_db);
  const struct { double t_c, v0; } cases[] = {{30.0, 1e-3}, {10.0, 1e-6}, {45.0, 3e-2}};
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    vl_scene hot, ref;
    dry_scene(&hot, "sbr-unfilled", cases[k].v0, 1, cases[k].t_c);
    double a_T = 0.0;
    vl_point ph = solve(db, &hot, &a_T, NULL);
    dry_scene(&ref, "sbr-unfilled", cases[k].v0 * a_T, 0, NAN);
    vl_point pr = solve(db, &ref, NULL, NULL);
    double rel = fabs(ph.mu_Rc - pr.mu_Rc) / fabs(pr.mu_Rc);
    printf("  %g C, v0 %g m/s (a_T %.4g): mu_Rc %.10g; at tref, v0 a_T: %.10g (rel %.2g)\n",
           cases[k].t_c, cases[k].v0, a_T, ph.mu_Rc, pr.mu_Rc, rel);
    assert_true(pr.mu_Rc > 1e-3);
    assert_true(rel < 1e-7);
    /* u_min of this smooth dry contact is 0 up to round-off (the gap inside
     * the contact: ~1e-20 m or exactly 0 as the active set ends): compared
     * with a floor of 1e-12 of the gap scale a0^2/R (~1e-4 m here) */
    double floor_m = 1e-12 * 1e-4;
    assert_true(fabs(ph.u_min_m - pr.u_min_m) <= 1e-7 * fabs(pr.u_min_m) + floor_m);
  }
  /* the direction (tts.h): warmer = shorter times, a_T < 1 */
  vl_db_compound c;
  vl_error err;
  assert_int_equal(vl_db_compound_info(db, "sbr-unfilled", &c, &err), VL_OK);
  vl_prony p;
  double a_hot, a_cold;
  assert_int_equal(vl_compound_at_temperature(&c, c.tref_c + 10, &p, &a_hot, &err), VL_OK);
  assert_true(a_hot < 1.0 && p.tau_s[0] == c.prony.tau_s[0] * a_hot);
  assert_true(p.e_inf_pa == c.prony.e_inf_pa && p.A[3] == c.prony.A[3]);
  assert_int_equal(vl_compound_at_temperature(&c, c.tref_c - 10, &p, &a_cold, &err), VL_OK);
  assert_true(a_cold > 1.0);
  /* WLF by hand: log10 a_T = -C1 dT / (C2 + dT) */
  double want = -c.wlf_c1 * 10.0 / (c.wlf_c2_k + 10.0);
  assert_true(fabs(log10(a_hot) - want) < 1e-12);
  vl_db_close(db);
}

/* ---- (c) the shipped viscosity laws against published data -------------- */

static double eta_at(vl_db *db, const char *fluid, double t_c) {
  vl_db_fluid f;
  vl_error err = {{0}};
  double eta = NAN;
  assert_int_equal(vl_db_fluid_info(db, fluid, &f, &err), VL_OK);
  if (vl_fluid_viscosity(&f.law, f.viscosity_pa_s, f.tref_c, t_c, &eta, &err) != VL_OK)
    fail_msg("%s at %g C: %s", fluid, t_c, err.msg);
  return eta;
}

static void test_fluid_laws(void **state) {
  (void)state;
  vl_db *db = open_db(g_db);
  /* Water, IAPWS 2008 (Huber et al., J. Phys. Chem. Ref. Data 38 (2009)
   * 101) at 0.1 MPa. The stored law is the classic Vogel fit (B 247.8 K,
   * C 140 K, quoted as ~1 % over 0-100 C) anchored at the seed's rounded
   * 1.0e-3 Pa s at 20 C, itself 0.16 % below IAPWS: 1.5 % allows both. */
  const double water[][2] = {{20, 1.0016e-3}, {25, 0.8900e-3}, {40, 0.6527e-3}, {80, 0.3544e-3}};
  for (size_t k = 0; k < 4; k++) {
    double eta = eta_at(db, "water", water[k][0]);
    printf("  water %4g C: %.5g mPa s (IAPWS %.5g, %+.2f %%)\n", water[k][0], eta * 1e3,
           water[k][1] * 1e3, 100 * (eta - water[k][1]) / water[k][1]);
    assert_true(vl_test_rel(eta, water[k][1]) < 0.015);
  }
  /* Glycerol (100 %), Segur & Oberstar, Ind. Eng. Chem. 43 (1951) 2117,
   * 0-100 C. The law's B, C are a least-squares fit to this very table
   * (materials/0003_fluid_viscosity_law.sql), so this checks what is
   * stored and how it is evaluated, not the fit's independence: over the
   * table the fit's rms error is 2.2 % and its largest 4.8 % (50 C, a
   * point off its neighbours' trend); we require 5 % everywhere and 2.5 %
   * rms. */
  const double gly[][2] = {{0, 12.07},   {10, 3.90},   {20, 1.412},  {30, 0.612},
                           {40, 0.284},  {50, 0.142},  {60, 0.0813}, {70, 0.0506},
                           {80, 0.0319}, {90, 0.0213}, {100, 0.0148}};
  double ss = 0.0, worst = 0.0;
  for (size_t k = 0; k < 11; k++) {
    double r = vl_test_rel(eta_at(db, "glycerol", gly[k][0]), gly[k][1]);
    ss += r * r;
    if (r > worst) worst = r;
    assert_true(r < 0.05);
  }
  printf("  glycerol vs Segur & Oberstar: rms %.2f %%, max %.2f %%\n", 100 * sqrt(ss / 11),
         100 * worst);
  assert_true(sqrt(ss / 11) < 0.025);
  /* and against N.-S. Cheng's correlation (Ind. Eng. Chem. Res. 47 (2008)
   * 3285), mu = 12100 exp((-1233 + T) T / (9900 + 70 T)) mPa s, T in C,
   * an independent fit to several data sets: within 3 % over 0-100 C */
  for (double t = 0.0; t <= 100.0; t += 5.0) {
    double cheng = 12.1 * exp((-1233.0 + t) * t / (9900.0 + 70.0 * t));
    assert_true(vl_test_rel(eta_at(db, "glycerol", t), cheng) < 0.03);
  }
  /* at the reference temperature: the stored viscosity, exactly */
  assert_true(eta_at(db, "water", 20.0) == 1.0e-3);
  assert_true(eta_at(db, "glycerol", 20.0) == 1.41);
  /* warmer liquids flow more easily */
  assert_true(eta_at(db, "water", 30.0) < eta_at(db, "water", 20.0));

  /* refusals: no law, outside the law's range, below its divergence */
  vl_db_fluid f;
  vl_error err = {{0}};
  double eta = -1.0;
  assert_int_equal(vl_db_fluid_info(db, "model-1e-3", &f, &err), VL_OK);
  assert_int_equal(f.law.kind, VL_VISCOSITY_LAW_NONE);
  assert_int_equal(vl_fluid_viscosity(&f.law, f.viscosity_pa_s, f.tref_c, 30, &eta, &err),
                   VL_EINPUT);
  assert_non_null(strstr(err.msg, "no viscosity-temperature law"));
  assert_true(eta == -1.0);
  assert_int_equal(vl_db_fluid_info(db, "water", &f, &err), VL_OK);
  assert_int_equal(vl_fluid_viscosity(&f.law, f.viscosity_pa_s, f.tref_c, 120, &eta, &err),
                   VL_EINPUT);
  assert_non_null(strstr(err.msg, "outside the range [0, 100]"));
  vl_viscosity_law bad = {VL_VISCOSITY_LAW_VOGEL, 247.8, 280.0, 0.0, 100.0};
  assert_int_equal(vl_viscosity_law_validate(&bad, 20.0, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "divergence"));
  vl_db_close(db);
}

/* A fluid added with a law reads back with it; bad laws are refused before
 * the file is touched; a law broken in the file is refused on reading. */
static void test_fluid_add_law(void **state) {
  (void)state;
  char path[1200];
  snprintf(path, sizeof path, "%s/add.db", vl_test_tmpdir());
  vl_db *db = open_db(path);
  vl_error err = {{0}};
  vl_db_fluid f;
  memset(&f, 0, sizeof f);
  snprintf(f.name, sizeof f.name, "oil");
  f.viscosity_pa_s = 0.1;
  f.tref_c = 40.0;
  f.law = (vl_viscosity_law){VL_VISCOSITY_LAW_VOGEL, 700.0, 150.0, 0.0, 120.0};
  assert_int_equal(vl_db_fluid_add(db, &f, &err), VL_OK);
  vl_db_fluid g;
  assert_int_equal(vl_db_fluid_info(db, "oil", &g, &err), VL_OK);
  assert_memory_equal(&g.law, &f.law, sizeof f.law);
  /* Vogel by hand: log10 eta(T)/eta(40 C) = B [1/(T - C) - 1/(313.15 - C)] */
  double eta = 0.0;
  assert_int_equal(vl_fluid_viscosity(&g.law, g.viscosity_pa_s, g.tref_c, 100.0, &eta, &err),
                   VL_OK);
  double want = 0.1 * pow(10.0, 700.0 / (373.15 - 150.0) - 700.0 / (313.15 - 150.0));
  assert_true(vl_test_rel(eta, want) < 1e-13);

  vl_test_snapshot snap = vl_test_take(path);
  snprintf(f.name, sizeof f.name, "oil2");
  f.law.vogel_b_k = -1.0; /* viscosity rising with temperature */
  assert_int_equal(vl_db_fluid_add(db, &f, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "Vogel B"));
  f.law.vogel_b_k = 700.0;
  f.law.tmin_c = 50.0; /* the anchor outside the law's data */
  assert_int_equal(vl_db_fluid_add(db, &f, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "outside the range"));
  vl_db_close(db);
  assert_true(vl_test_same_db(path, &snap));
  free(snap.bytes);

  /* half a law in the file (the schema cannot check across columns) */
  sqlite3 *h = NULL;
  assert_int_equal(sqlite3_open(path, &h), SQLITE_OK);
  assert_int_equal(
      sqlite3_exec(h, "UPDATE fluid SET law_tmax_c = NULL WHERE name = 'oil'", NULL, NULL, NULL),
      SQLITE_OK);
  sqlite3_close(h);
  db = open_db(path);
  assert_int_equal(vl_db_fluid_info(db, "oil", &g, &err), VL_EDB);
  assert_non_null(strstr(err.msg, "invalid viscosity law"));
  vl_db_close(db);
}

/* A database of schema version 2 (made from the .sql files themselves) is
 * migrated by 0003: its shipped water and glycerol get the same laws as a
 * new database's, its other fluids none. */
static void test_migrate_from_schema_2(void **state) {
  (void)state;
  char path[1200];
  snprintf(path, sizeof path, "%s/v2.db", vl_test_tmpdir());
  const char *files[] = {"materials/0001_schema.sql", "materials/0002_measured.sql",
                         "materials/seed_shipped.sql"};
  sqlite3 *h = NULL;
  assert_int_equal(sqlite3_open(path, &h), SQLITE_OK);
  for (size_t k = 0; k < 3; k++) {
    char *sql = vl_test_read_file(vl_test_source_path(files[k]));
    assert_non_null(sql);
    char *msg = NULL;
    if (sqlite3_exec(h, sql, NULL, NULL, &msg) != SQLITE_OK) fail_msg("%s: %s", files[k], msg);
    free(sql);
  }
  assert_int_equal(sqlite3_exec(h, "PRAGMA user_version = 2", NULL, NULL, NULL), SQLITE_OK);
  sqlite3_close(h);
  vl_db *old = open_db(path), *fresh = open_db(g_db);
  const char *names[] = {"water", "glycerol", "model-1e-3"};
  for (size_t k = 0; k < 3; k++) {
    vl_db_fluid a, b;
    vl_error err;
    assert_int_equal(vl_db_fluid_info(old, names[k], &a, &err), VL_OK);
    assert_int_equal(vl_db_fluid_info(fresh, names[k], &b, &err), VL_OK);
    assert_memory_equal(&a.law, &b.law, sizeof a.law);
    assert_int_equal(a.law.kind, k < 2 ? VL_VISCOSITY_LAW_VOGEL : VL_VISCOSITY_LAW_NONE);
  }
  vl_db_close(old);
  vl_db_close(fresh);
}

/* ---- (d) the seed's remark on the rolling number (docs/CASES.md fig15) ------- */

/* Q = v_GT / v_ML (docs/MODEL.md section 8) with v_GT = w~ 2 a0 and
 * v_ML = 10 h_rms^2 Er0 / (R eta). Warming shortens every time by a_T, so
 * the loss peak w~ moves up by 1/a_T; a0 and Er0 (relaxed modulus) do not
 * move; the water thins, raising v_ML by eta_ref / eta(T). Hence
 *   Q(T) = Q(Tref) eta(T) / (eta_ref a_T(T)):
 * warmer = larger Q (the seed: "a temperature increase ... could result in
 * a rolling number ~ 1"). The seed quotes ~5 K per decade of frequency and
 * Q_unfilled = 3e-4 at its reference, and says about ten degrees (at fixed
 * viscosity) bring Q near 1. Measured here on sbr-unfilled: its WLF
 * constants give 5.7 K per decade at 20 C but fewer decades per kelvin
 * further up (WLF flattens), and Q ~ 1 needs 3.5 decades. */
static double wlf_q(const vl_db_compound *c, double q_ref, double t_c, int fluid_follows,
                    vl_db *db) {
  double log10_a = vl_wlf_log10_shift(c->wlf_c1, c->wlf_c2_k, t_c, c->tref_c);
  double ratio = fluid_follows ? eta_at(db, "water", t_c) / 1.0e-3 : 1.0;
  return q_ref * ratio / pow(10.0, log10_a);
}

/* Temperature (C) at which wlf_q reaches 1, by bisection over [tref, 100]. */
static double t_q1(const vl_db_compound *c, double q_ref, int fluid_follows, vl_db *db) {
  double lo = c->tref_c, hi = 100.0;
  assert_true(wlf_q(c, q_ref, hi, fluid_follows, db) > 1.0);
  for (int i = 0; i < 60; i++) {
    double mid = 0.5 * (lo + hi);
    if (wlf_q(c, q_ref, mid, fluid_follows, db) < 1.0)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

static void test_rolling_number(void **state) {
  (void)state;
  vl_db *db = open_db(g_db);
  vl_db_compound c;
  vl_error err;
  assert_int_equal(vl_db_compound_info(db, "sbr-unfilled", &c, &err), VL_OK);
  /* Q from the solver (boundary regime, v0 eta = 1e-10 Pa m, a cheap
   * converged point; Q is a property of the scene, not of the speed) */
  vl_scene sc;
  wet_scene(&sc, 1e-10, 0, NAN);
  double q_ref = solve(db, &sc, NULL, NULL).Q;
  /* the shipped compound was made to have the seed's Q_unfilled = 3e-4 */
  assert_true(q_ref > 1.5e-4 && q_ref < 6e-4);

  /* the solver's Q at temperature follows the closed form above: both
   * shifts reach it. Tolerance: the loss peak is located by golden section
   * (rheology.h), ~1e-6 relative; 1e-4 is ample. */
  const double temps[] = {30.0, 40.0};
  double q[2];
  for (size_t k = 0; k < 2; k++) {
    wet_scene(&sc, 1e-10, 1, temps[k]);
    double a_T, eta;
    q[k] = solve(db, &sc, &a_T, &eta).Q;
    double want = q_ref * (eta / 1.0e-3) / a_T;
    printf("  Q at %g C: %.4g (a_T %.4g, eta %.4g Pa s; closed form %.4g)\n", temps[k], q[k], a_T,
           eta, want);
    assert_true(vl_test_rel(q[k], want) < 1e-4);
  }
  /* warming raises Q, by more than a decade per 10 K here */
  assert_true(q[0] > 10.0 * q_ref && q[1] > 10.0 * q[0]);

  /* kelvin per decade of a_T at tref: C2 / C1 (seed: ~5 K) */
  double k_per_decade = c.wlf_c2_k / c.wlf_c1;
  double q10_fixed = wlf_q(&c, q_ref, c.tref_c + 10.0, 0, db);
  double t1_fixed = t_q1(&c, q_ref, 0, db), t1_water = t_q1(&c, q_ref, 1, db);
  printf("  Q(20 C) = %.3g; %.2f K per decade at 20 C; +10 K at fixed viscosity: Q = %.3g; "
         "Q = 1 at %.1f C (fixed viscosity, +%.1f K), %.1f C (water following its law)\n",
         q_ref, k_per_decade, q10_fixed, t1_fixed, t1_fixed - c.tref_c, t1_water);
  assert_true(k_per_decade > 4.0 && k_per_decade < 8.0);
  /* The seed's "about ten degrees" to Q ~ 1 does not hold for this
   * compound (nor for the seed's own 5 K per decade, which gives Q ~ 3e-2
   * at +10 K): +10 K gives Q ~ 1e-2, and Q = 1 needs a rise of some
   * 20-35 K. What we assert is the physically stated bound: Q ~ 1 is
   * reached by warming alone within the liquid range of water and the
   * compound's WLF range, a few tens of kelvin above tref. */
  assert_true(q10_fixed > 3e-3 && q10_fixed < 0.1);
  assert_true(t1_fixed - c.tref_c > 10.0 && t1_fixed - c.tref_c < 40.0);
  assert_true(t1_water > t1_fixed && t1_water < 80.0); /* thinner water lowers Q */
  /* and the solver agrees at that temperature */
  wet_scene(&sc, 1e-10, 1, t1_water);
  double q1 = solve(db, &sc, NULL, NULL).Q;
  printf("  solver at %.2f C: Q = %.4f\n", t1_water, q1);
  assert_true(fabs(q1 - 1.0) < 1e-3);
  vl_db_close(db);
}

/* ---- errors of the library --------------------------------------------- */

static void test_library_errors(void **state) {
  (void)state;
  vl_db *db = open_db(g_db);
  vl_error err = {{0}};
  vl_simulation *sim = NULL;
  vl_scene sc;
  /* no WLF constants: the message names the compound and the reason */
  dry_scene(&sc, "model-rubber", 1e-3, 1, 30.0);
  assert_int_equal(vl_simulation_create(&sc, db, &sim, &err), VL_EINPUT);
  assert_null(sim);
  assert_non_null(strstr(err.msg, "model-rubber"));
  assert_non_null(strstr(err.msg, "no WLF constants"));
  assert_non_null(strstr(err.msg, "[effects] temperature"));
  /* at or below Tref - C2 (about -51.6 C here): WLF is singular */
  dry_scene(&sc, "sbr-unfilled", 1e-3, 1, -60.0);
  assert_int_equal(vl_simulation_create(&sc, db, &sim, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "WLF singularity"));
  /* a wet scene whose fluid has no law */
  wet_scene(&sc, 1e-8, 1, 30.0);
  snprintf(sc.fluid, sizeof sc.fluid, "model-1e-3");
  assert_int_equal(vl_simulation_create(&sc, db, &sim, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "fluid 'model-1e-3'"));
  /* an elastic scene uses E0, which does not shift: no WLF needed */
  dry_scene(&sc, "model-rubber", 1e-3, 1, 30.0);
  sc.effects.viscoelastic = false;
  assert_int_equal(vl_simulation_create(&sc, db, &sim, &err), VL_OK);
  assert_true(vl_simulation_shift_factor(sim) == 1.0);
  vl_simulation_free(sim);
  /* the same fluid in a dry scene is not simulated: no law needed */
  wet_scene(&sc, 1e-8, 1, 30.0);
  snprintf(sc.fluid, sizeof sc.fluid, "model-1e-3");
  sc.effects.fluid = sc.effects.roughness = sc.effects.solid_shear = false;
  sc.quantity = VL_SWEEP_V0;
  assert_int_equal(vl_simulation_create(&sc, db, &sim, &err), VL_OK);
  vl_simulation_free(sim);
  vl_db_close(db);
}

/* ---- the command line -------------------------------------------------- */

static const char *const SCENE = "[materials]\n"             /* 1 */
                                 "compound = sbr-unfilled\n" /* 2 */
                                 "surface = paper-0.5um\n"   /* 3 */
                                 "fluid = water\n"           /* 4 */
                                 "[contact]\n"               /* 5 */
                                 "radius_m = 0.001\n"        /* 6 */
                                 "load_n_per_m = 117\n"      /* 7 */
                                 "sigma_s_pa = 1e6\n"        /* 8 */
                                 "[sweep]\n"                 /* 9 */
                                 "quantity = v0_eta\n"       /* 10 */
                                 "from = 1e-10\n"            /* 11 */
                                 "to = 1e-9\n"               /* 12 */
                                 "points = 2\n"              /* 13 */
                                 "[effects]\n"               /* 14 */
                                 "roughness = on\n"          /* 15 */
                                 "fluid = on\n"              /* 16 */
                                 "solid_shear = on\n"        /* 17 */
                                 "%s"                        /* 18...: the temperature lines */
                                 "[numerics]\n"
                                 "grid = 64\n"
                                 /* coarse cells, for speed: not the accuracy test */
                                 "target_error = 0.5\n";

/* Writes the scene with the given temperature lines to dir/name. */
static const char *scene_file(const char *name, const char *temperature_lines,
                              const char *compound) {
  char text[2048], body[2048];
  snprintf(body, sizeof body, SCENE, temperature_lines);
  const char *at = strstr(body, "sbr-unfilled");
  snprintf(text, sizeof text, "%.*s%s%s", (int)(at - body), body, compound,
           at + strlen("sbr-unfilled"));
  return vl_test_scratch(name, text);
}

static double json_number(const char *json, const char *key) {
  char pat[128];
  snprintf(pat, sizeof pat, "\"%s\": ", key);
  const char *p = strstr(json, pat);
  return p ? strtod(p + strlen(pat), NULL) : NAN;
}

static void test_cli_scene(void **state) {
  (void)state;
  char *out = NULL, *err = NULL;
  /* a scene at 30 C runs and matches `friction --temperature 30` */
  const char *ok = scene_file("t30.ini", "temperature = on\ntemperature_c = 30\n", "sbr-unfilled");
  int rc = vl_test_run(&out, &err, "run %s --out %s/t30 --json", ok, vl_test_dir);
  if (rc != 0) fail_msg("exit %d: %s", rc, err);
  assert_true(vl_test_json_valid(out));
  /* the second point (v0 eta = 1e-9 Pa m): after the first one's key */
  const char *second = strstr(out, "\"v0_eta_pa_m\": ");
  second = second ? strstr(second + 1, "\"v0_eta_pa_m\": ") : NULL;
  assert_non_null(second);
  assert_true(vl_test_rel(strtod(second + strlen("\"v0_eta_pa_m\": "), NULL), 1e-9) < 1e-12);
  double mu_run = json_number(second, "mu");
  free(out);
  free(err);
  /* the table form states the temperature, a_T and the viscosity used */
  rc = vl_test_run(&out, &err, "run %s --out %s/t30t", ok, vl_test_dir);
  if (rc != 0) fail_msg("exit %d: %s", rc, err);
  assert_non_null(strstr(out, "at 30 C: compound times x a_T = "));
  assert_non_null(strstr(out, "fluid viscosity 0.0007958 Pa s"));
  free(out);
  free(err);
  /* the same point from `friction`: v0 = 1e-9 Pa m / eta(30 C) */
  double eta30 = 1.0e-3 * pow(10.0, 247.8 / (303.15 - 140.0) - 247.8 / (293.15 - 140.0));
  rc = vl_test_run(&out, &err,
                   "friction --compound sbr-unfilled --surface paper-0.5um --fluid water "
                   "--speed %.17g --flow-factors smooth --grid 64 --temperature 30 --json "
                   "--target-error 0.5",
                   1e-9 / eta30);
  if (rc != 0) fail_msg("exit %d: %s", rc, err);
  assert_true(vl_test_json_valid(out));
  double mu_fr = json_number(out, "mu"), t = json_number(out, "temperature_c"),
         eta = json_number(out, "eta_pa_s"), a_T = json_number(out, "a_T");
  printf("  run at 30 C: mu %.8g; friction --temperature 30: mu %.8g (eta %.6g, a_T %.4g)\n",
         mu_run, mu_fr, eta, a_T);
  assert_true(t == 30.0);
  assert_true(vl_test_rel(eta, eta30) < 1e-9);
  assert_true(a_T > 0.01 && a_T < 0.1); /* 10 K warmer: ~1.5 decades faster */
  assert_true(vl_test_rel(mu_fr, mu_run) < 1e-6);
  free(out);
  free(err);

  /* errors: file:line: [section] key, nothing written */
  const char *typo =
      scene_file("typo.ini", "temprature = on\ntemperature_c = 30\n", "sbr-unfilled");
  vl_test_expect_fail(2, ":18: [effects] temprature", "did you mean 'temperature'",
                      "run %s --out %s/x", typo, vl_test_dir);
  const char *missing = scene_file("missing.ini", "temperature = on\n", "sbr-unfilled");
  vl_test_expect_fail(2, ":18: [effects] temperature", "temperature_c", "run %s --out %s/x",
                      missing, vl_test_dir);
  const char *nowlf =
      scene_file("nowlf.ini", "temperature = on\ntemperature_c = 30\n", "model-rubber");
  vl_test_expect_fail(2, "model-rubber", "no WLF constants", "run %s --out %s/x", nowlf,
                      vl_test_dir);
}

static void test_cli_query(void **state) {
  (void)state;
  assert_int_equal(vl_test_run(NULL, NULL, "fluid list"), 0); /* the database, to compare with */
  /* friction: a compound without WLF, a fluid without a law, a bad value */
  vl_test_expect_fail(2, "--temperature 30", "'model-rubber' has no WLF constants",
                      "friction --compound model-rubber --surface paper-0.5um --fluid water "
                      "--speed 0.01 --temperature 30");
  vl_test_expect_fail(2, "fluid 'model-1e-3'", "no viscosity-temperature law",
                      "friction --compound sbr-unfilled --surface paper-0.5um --fluid model-1e-3 "
                      "--speed 0.01 --temperature 30");
  vl_test_expect_fail(2, "--temperature", "abc",
                      "friction --compound sbr-unfilled --surface paper-0.5um --fluid water "
                      "--speed 0.01 --temperature abc");
  vl_test_expect_fail(2, "'model-rubber' has no WLF constants", NULL,
                      "compare --compounds sbr-unfilled,model-rubber --surface paper-0.5um "
                      "--fluid water --temperature 30 --out %s/c0",
                      vl_test_dir);

  /* compare at 40 C: the CSV and the JSON state temperature and viscosity */
  char *out = NULL, *err = NULL;
  int rc =
      vl_test_run(&out, &err,
                  "compare --compounds sbr-unfilled,sbr-filled --surface paper-0.5um "
                  "--fluid water --from 1e-10 --to 1e-9 --points 2 --grid 64 "
                  "--flow-factors smooth --temperature 40 --json --out %s/c40 --target-error 0.5",
                  vl_test_dir);
  if (rc != 0) fail_msg("exit %d: %s", rc, err);
  assert_true(vl_test_json_valid(out));
  double eta40 = 1.0e-3 * pow(10.0, 247.8 / (313.15 - 140.0) - 247.8 / (293.15 - 140.0));
  assert_true(json_number(out, "temperature_c") == 40.0);
  assert_true(vl_test_rel(json_number(out, "eta_pa_s"), eta40) < 1e-9);
  free(out);
  free(err);
  char path[1400];
  snprintf(path, sizeof path, "%s/c40/compare.csv", vl_test_dir);
  char *csv = vl_test_read_file(path);
  assert_non_null(csv);
  assert_non_null(strstr(csv, ",converged_sbr-filled,temperature_c,eta_pa_s\n"));
  /* after the model line and the header, each row ends with 40 and the
   * viscosity */
  assert_true(!strncmp(csv, "# flow_factors = smooth\n", 24));
  char *row = strchr(strchr(csv, '\n') + 1, '\n') + 1, *end = strchr(row, '\n');
  *end = '\0';
  char *last = strrchr(row, ',');
  assert_true(vl_test_rel(strtod(last + 1, NULL), eta40) < 1e-9);
  *last = '\0';
  assert_true(strtod(strrchr(row, ',') + 1, NULL) == 40.0);
  free(csv);
}

/* A compound used outside its measured isotherms (issue 32): every point
 * of `friction` (console, JSON) warns with the measured range, for a
 * synthetic compound measured at 20..60 C and for the real EPDM export
 * (../shared/data/real; that part skipped when absent); nothing inside the
 * range, nothing for a compound entered as a Prony series with WLF
 * constants (no measured range to compare with). */
static void test_cli_measured_range(void **state) {
  (void)state;
  vl_test_text t = {0};
  vl_test_text_add(&t, "f,E_stor,E_loss,T\nHz,Pa,Pa,C\n");
  for (int j = 0; j < 9; j++) {
    double tc = 20.0 + 5.0 * j, at = pow(10.0, -8.86 * (tc - 20.0) / (101.6 + tc - 20.0));
    for (int k = 0; k <= 12; k++) {
      double f = pow(10.0, -1.0 + 0.25 * k), w = 6.283185307179586 * f * at * 1e-3;
      /* a one-term Zener solid, E0 2 MPa, Einf 200 MPa, tau 1 ms at 20 C */
      double e0 = 2e6, einf = 2e8, d = 1.0 + w * w;
      vl_test_text_add(&t, "%.17g,%.17g,%.17g,%.17g\n", f, e0 + (einf - e0) * w * w / d,
                       (einf - e0) * w / d, tc);
    }
  }
  const char *csv = vl_test_scratch("syn20_60.csv", t.s);
  free(t.s);
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "compound add syn --measured %s", csv);
  if (rc != 0) fail_msg("compound add exit %d: %s", rc, err);
  free(out);
  free(err);
  const char *q = "friction --compound %s --surface paper-0.5um --fluid water --speed 0.01 "
                  "--grid 64 --target-error 0.5 --temperature %g %s";
  rc = vl_test_run(&out, &err, q, "syn", 80.0, "--json");
  if (rc != 0) fail_msg("friction exit %d: %s", rc, err);
  assert_non_null(strstr(out, "temperature 80 C above the measured isotherms (20 to 60 C): the "
                              "WLF shift is extrapolated 20 K beyond them"));
  free(out);
  free(err);
  rc = vl_test_run(&out, &err, q, "syn", 10.0, "");
  if (rc != 0) fail_msg("friction exit %d: %s", rc, err);
  assert_non_null(
      strstr(err, "warning: temperature 10 C below the measured isotherms (20 to 60 C)"));
  free(out);
  free(err);
  rc = vl_test_run(&out, &err, q, "syn", 40.0, "--json");
  if (rc != 0) fail_msg("friction exit %d: %s", rc, err);
  assert_null(strstr(out, "measured isotherms"));
  free(out);
  free(err);
  /* a Prony series with WLF constants: no measured range, no warning */
  const char *terms = vl_test_scratch("zener.csv", "A,tau_s\n1,s\n99,1e-3\n");
  rc = vl_test_run(&out, &err,
                   "compound add zener --prony %s --e-inf 2e8 --nu 0.5 --tref 20 --wlf-c1 8.86 "
                   "--wlf-c2 101.6",
                   terms);
  if (rc != 0) fail_msg("compound add exit %d: %s", rc, err);
  free(out);
  free(err);
  rc = vl_test_run(&out, &err, q, "zener", 80.0, "--json");
  if (rc != 0) fail_msg("friction exit %d: %s", rc, err);
  assert_null(strstr(out, "measured isotherms"));
  free(out);
  free(err);
  /* the real EPDM (-10 .. 53 C) at 80 C */
  char path[4400];
  snprintf(path, sizeof path, "%s/../shared/data/real/marcusni96_epdm_70_tf_015p.csv",
           vl_test_source_path("."));
  if (access(path, R_OK) != 0)
    snprintf(path, sizeof path, "%s/../../shared/data/real/marcusni96_epdm_70_tf_015p.csv",
             vl_test_source_path("."));
  if (access(path, R_OK) != 0) {
    fprintf(stderr,
            "SKIPPED (EPDM part): no ../shared/data/real/marcusni96_epdm_70_tf_015p.csv "
            "beside %s\n",
            vl_test_source_path("."));
    return;
  }
  rc = vl_test_run(&out, &err, "compound add epdm --measured %s", path);
  if (rc != 0) fail_msg("compound add exit %d: %s", rc, err);
  free(out);
  free(err);
  rc = vl_test_run(&out, &err, q, "epdm", 80.0, "--json");
  if (rc != 0) fail_msg("friction exit %d: %s", rc, err);
  assert_non_null(strstr(out, "temperature 80 C above the measured isotherms (-9.999 to 52.97 C)"));
  free(out);
  free(err);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_reference_temperature),
      cmocka_unit_test(test_shift_equals_speed),
      cmocka_unit_test(test_fluid_laws),
      cmocka_unit_test(test_fluid_add_law),
      cmocka_unit_test(test_migrate_from_schema_2),
      cmocka_unit_test(test_rolling_number),
      cmocka_unit_test(test_library_errors),
      cmocka_unit_test_setup(test_cli_scene, vl_test_setup_db),
      cmocka_unit_test_setup(test_cli_query, vl_test_setup_db),
      cmocka_unit_test_setup(test_cli_measured_range, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, group_setup, NULL);
}
