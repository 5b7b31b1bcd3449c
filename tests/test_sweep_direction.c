/* [sweep] direction (scene.h vl_sweep_direction): a sweep run from the top
 * visits its speeds downward and, where the curve has one state, finds the
 * upward sweep's points; direction = both runs both and sets every point's
 * downward result (vl_down_result) without reporting two states there.
 * The contact: the seed's sbr-unfilled on paper-0.5um in water (cases/
 * fig15.ini's materials) on 64 fixed cells, 5 speeds through the mixed
 * regime. Tolerance: 1e-4 relative in mu, the two sweeps reach each point
 * from different neighbours, each converged to the wet Newton tolerance
 * (1e-6 scaled residual); a difference of the branch would be percents. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "simulation_internal.h"
#include "viscolube/database.h"
#include "viscolube/scene.h"
#include "viscolube/simulation.h"
#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>

#define N 5

static vl_db *g_db;

static int setup(void **state) {
  (void)state;
  char path[1200];
  snprintf(path, sizeof path, "%s/materials.db", vl_test_tmpdir());
  vl_error err = {{0}};
  if (vl_db_open(path, &g_db, &err) != VL_OK) fail_msg("open %s: %s", path, err.msg);
  return 0;
}

static int teardown(void **state) {
  (void)state;
  vl_db_close(g_db);
  return 0;
}

static void scene(vl_scene *sc, vl_sweep_direction d) {
  vl_scene_defaults(sc);
  snprintf(sc->path, sizeof sc->path, "test");
  snprintf(sc->compound, sizeof sc->compound, "sbr-unfilled");
  snprintf(sc->surface, sizeof sc->surface, "paper-0.5um");
  snprintf(sc->fluid, sizeof sc->fluid, "water");
  snprintf(sc->fluids[0], sizeof sc->fluids[0], "water");
  sc->n_fluids = 1;
  sc->radius_m = 1e-3;
  sc->load_n_per_m = 117.0;
  sc->sigma_s_pa = 1e6;
  sc->effects.roughness = sc->effects.fluid = sc->effects.solid_shear = true;
  sc->quantity = VL_SWEEP_V0_ETA;
  sc->from = 1e-6, sc->to = 1e-2, sc->points = N;
  sc->direction = d;
  sc->grid = 64;
  sc->domain_min_a0 = VL_WET_DOMAIN_MIN_A0;
  sc->domain_max_a0 = VL_WET_DOMAIN_MAX_A0;
  sc->auto_numerics = false;
}

/* Runs the scene; its speeds in *v (the order visited), its points in pt. */
static void run(vl_sweep_direction d, double *v, vl_point *pt) {
  vl_scene sc;
  scene(&sc, d);
  vl_simulation *sim = NULL;
  vl_error err = {{0}};
  if (vl_simulation_create(&sc, g_db, &sim, &err) != VL_OK) fail_msg("create: %s", err.msg);
  assert_int_equal(vl_simulation_points(sim), N);
  vl_sweep_stats st;
  if (vl_simulation_run(sim, pt, NULL, NULL, &st, &err) != VL_OK) fail_msg("run: %s", err.msg);
  for (size_t i = 0; i < N; i++) {
    v[i] = vl_simulation_speeds(sim)[i];
    if (!pt[i].converged) fail_msg("%g m/s did not converge", v[i]);
  }
  vl_simulation_free(sim);
}

static void test_down_and_both(void **state) {
  (void)state;
  double vu[N], vd[N], vb[N];
  vl_point up[N], down[N], both[N];
  run(VL_DIRECTION_UP, vu, up);
  run(VL_DIRECTION_DOWN, vd, down);
  run(VL_DIRECTION_BOTH, vb, both);
  for (size_t i = 0; i < N; i++) {
    const vl_point *d = &down[N - 1 - i]; /* the same speed */
    print_message("%.4g m/s: mu up %.8g, down %.8g, both's downward %.8g\n", vu[i], up[i].mu, d->mu,
                  both[i].down.mu);
    if (i > 0) assert_true(vd[i] < vd[i - 1] && vu[i] > vu[i - 1]); /* the order visited */
    assert_true(vd[N - 1 - i] == vu[i] && vb[i] == vu[i]);
    assert_false(up[i].down.swept);
    assert_true(fabs(d->mu - up[i].mu) <= 1e-4 * up[i].mu);
    assert_true(both[i].mu == up[i].mu); /* both's rows are the upward sweep */
    assert_true(both[i].down.swept && both[i].down.converged);
    assert_true(fabs(both[i].down.mu - up[i].mu) <= 1e-4 * up[i].mu);
    assert_false(both[i].down.two_states);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {cmocka_unit_test(test_down_and_both)};
  return cmocka_run_group_tests(tests, setup, teardown);
}
