/* Stored pairs in use (issue 34): a query without sigma_s takes the pair's
 * law, which changes mu_Sc as the law states and nothing else; a given
 * sigma_s, or no pair, is today's answer to the last digit. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "viscolube/query.h"

static vl_db *open_fresh(void) {
  static char path[4200];
  snprintf(path, sizeof path, "%s/pairs.db", vl_test_tmpdir());
  unlink(path);
  vl_db *db = NULL;
  vl_error err;
  if (vl_db_open(path, &db, &err) != VL_OK) fail_msg("%s", err.msg);
  return db;
}

static void add_pair(vl_db *db, vl_shear_law law) {
  vl_db_pair p;
  memset(&p, 0, sizeof p);
  snprintf(p.compound, sizeof p.compound, "sbr-unfilled");
  snprintf(p.surface, sizeof p.surface, "paper-0.5um");
  snprintf(p.fluid, sizeof p.fluid, "water");
  p.law = law;
  for (int k = 0; k < 3; k++)
    p.ci95[k] = NAN;
  snprintf(p.source, sizeof p.source, "typed");
  vl_error err;
  if (vl_db_pair_add(db, &p, &err) != VL_OK) fail_msg("%s", err.msg);
}

static vl_query_result solve(vl_db *db, double v, bool given, double sigma) {
  vl_query q;
  vl_query_defaults(&q);
  q.compound = "sbr-unfilled", q.surface = "paper-0.5um", q.fluid = "water";
  q.sigma_s_given = given;
  if (given) q.sigma_s_pa = sigma;
  vl_query_result r;
  vl_error err;
  if (vl_query_friction(db, &q, v, &r, &err) != VL_OK) fail_msg("%s", err.msg);
  assert_true(r.point.converged);
  return r;
}

/* Everything but mu_Sc and mu is the same to the last digit. */
static void same_contact(const vl_point *a, const vl_point *b) {
  assert_true(a->mu_Rc == b->mu_Rc && a->mu_Rf == b->mu_Rf && a->mu_Sf == b->mu_Sf);
  assert_true(a->u_min_m == b->u_min_m && a->fluid_load_fraction == b->fluid_load_fraction);
}

static void test_pair_changes_mu_sc_only(void **state) {
  (void)state;
  vl_db *db = open_fresh();
  const double speeds[2] = {1e-5, 1e-2};
  for (int k = 0; k < 2; k++) {
    double v = speeds[k];
    vl_query_result none = solve(db, v, false, 0.0);
    assert_false(none.has_pair);
    assert_true(none.sigma_s_pa == VL_QUERY_SIGMA_S_PA);
    vl_query_result given = solve(db, v, true, VL_QUERY_SIGMA_S_PA);
    assert_true(given.point.mu == none.point.mu); /* today's numbers */
    (void)given;
  }
  vl_shear_law eyring = {VL_SHEAR_EYRING, {2e5, 3e5, 1e-4}, NAN, NAN};
  add_pair(db, eyring);
  for (int k = 0; k < 2; k++) {
    double v = speeds[k];
    vl_query_result base = solve(db, v, true, VL_QUERY_SIGMA_S_PA);
    assert_false(base.has_pair); /* --sigma-s wins over the pair */
    vl_query_result r = solve(db, v, false, 0.0);
    assert_true(r.has_pair);
    assert_non_null(strstr(r.shear_law_text, "eyring: sigma_0_pa = 200000"));
    assert_non_null(strstr(r.shear_law_text, "pair sbr-unfilled / paper-0.5um / water, typed"));
    double sigma = 2e5 + 3e5 * asinh(v / 1e-4);
    assert_true(r.sigma_s_pa == sigma);
    same_contact(&r.point, &base.point);
    /* mu_Sc scales with sigma_s: the area integral is the same */
    double want = base.point.mu_Sc * sigma / VL_QUERY_SIGMA_S_PA;
    if (!(fabs(r.point.mu_Sc - want) <= 1e-12 * want))
      fail_msg("v %g: mu_Sc %.15g, want %.15g", v, r.point.mu_Sc, want);
    printf("v = %g m/s: sigma_s %g Pa, mu %.6g -> %.6g\n", v, sigma, base.point.mu, r.point.mu);
  }
  vl_db_close(db);
}

/* At another temperature the stored law is shifted as shear_law.h states:
 * Eyring's sigma_e with the absolute temperature, the dewetting speed as
 * 1/eta of the fluid there. */
static void test_pair_at_temperature(void **state) {
  (void)state;
  vl_db *db = open_fresh();
  add_pair(db, (vl_shear_law){VL_SHEAR_EYRING, {2e5, 3e5, 1e-4}, 20.0, NAN});
  vl_query q;
  vl_query_defaults(&q);
  q.compound = "sbr-unfilled", q.surface = "paper-0.5um", q.fluid = "water";
  q.at_temperature = true, q.temperature_c = 50.0;
  vl_query_result r;
  vl_error err;
  if (vl_query_friction(db, &q, 1e-3, &r, &err) != VL_OK) fail_msg("%s", err.msg);
  assert_true(r.has_pair && r.point.converged);
  double se = 3e5 * (50.0 + 273.15) / (20.0 + 273.15);
  assert_true(fabs(r.shear_law.p[1] / se - 1.0) < 1e-14);
  assert_true(r.shear_law.p[0] == 2e5 && r.shear_law.p[2] == 1e-4);
  assert_true(fabs(r.sigma_s_pa / (2e5 + se * asinh(10.0)) - 1.0) < 1e-14);
  vl_error e2;
  assert_int_equal(vl_db_pair_remove(db, "sbr-unfilled", "paper-0.5um", "water", &e2), VL_OK);
  add_pair(db, (vl_shear_law){VL_SHEAR_DEWETTING, {2e6, 3e5, 1e-4}, NAN, 1e-3});
  if (vl_query_friction(db, &q, 1e-3, &r, &err) != VL_OK) fail_msg("%s", err.msg);
  assert_true(r.has_pair);
  /* water at 50 C is thinner than at 20 C: V_d grows by eta(20)/eta(50) */
  assert_true(fabs(r.shear_law.p[2] / (1e-4 * 1e-3 / r.eta_pa_s) - 1.0) < 1e-14);
  assert_true(r.eta_pa_s < 0.6e-3 && r.shear_law.p[2] > 1.6e-4);
  vl_db_close(db);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_pair_changes_mu_sc_only),
      cmocka_unit_test(test_pair_at_temperature),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
