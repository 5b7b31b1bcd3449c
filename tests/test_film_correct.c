/* The film pressure of a rough film's Newton step (contact_film.c,
 * docs/NUMERICS.md section 7): the step keeps Newton's gap and rigid
 * approach and takes the fluid pressure that balances the flow at that gap.
 *
 * On fig05's contact (model rubber on the paper surface, h_rms 0.5 um, eta
 * 1e-4 Pa s, the wet rough defaults), at the speed where the film stops
 * carrying load (5.8e-3 m/s), a sweep's next step of 1.5x starts from a
 * state whose plain Newton step lands on a residual of about 4e3 (the flow
 * factors switch the flow on where the contact opens); checked:
 *  - the corrected step changes no gap or approach unknown (exactly), and
 *    its Reynolds rows are satisfied to 1e-3 of the tolerance (the inner
 *    solve's target);
 *  - it lands on a residual at least 100x smaller than the plain step's
 *    (measured: 2.4 against 4.1e3);
 *  - it agrees with the plain step to second order: for speed steps of 1 %
 *    and 0.1 % the pf difference relative to the pf step falls with the
 *    step (first order in the step, i.e. second order in absolute terms),
 *    by at least 5x per decade (measured 9.7x);
 *  - where the fluid carries more than half the load it is not applied.
 * The curve itself is unchanged by the correction to 5e-7 (relative mu, the
 * validation tests' references hold as before); this test checks the
 * mechanism. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "contact_test.h"
#include "numerics_plan.h"
#include "viscolube/contact.h"
#include "vl_test_scenes.h"
#include "vl_test_util.h"

#include <math.h>

#define ETA 1e-4
#define HRMS 5e-7

typedef struct {
  vl_psd psd;
  vl_persson *tab;
  vl_contact *c;
} fixture;

/* fig05's contact, swept 2.6e-3 -> 3.8e-3 -> 5.8e-3 m/s (each point from the
 * one before, as a sweep does) */
static const double SPEEDS[] = {2.56e-3, 3.84e-3, 5.77e-3};
#define N_SPEEDS (sizeof SPEEDS / sizeof *SPEEDS)

static int setup(void **state) {
  static fixture f;
  f.tab = vl_test_paper_surface(HRMS, &f.psd);
  vl_contact_config cfg;
  vl_test_fig05_config(&cfg, f.tab, ETA, VL_WET_ROUGH_GRID, VL_WET_ROUGH_DOMAIN_MIN_A0);
  cfg.grid_growth = VL_WET_GRID_GROWTH;
  cfg.tolerance = VL_WET_TOLERANCE;
  vl_error err;
  if (vl_contact_create(&cfg, &f.c, &err) != VL_OK) fail_msg("%s", err.msg);
  for (size_t k = 0; k < N_SPEEDS; k++) {
    vl_point p;
    if (vl_contact_solve(f.c, SPEEDS[k], &p, &err) != VL_OK) fail_msg("%s", err.msg);
  }
  *state = &f;
  return 0;
}

static int teardown(void **state) {
  fixture *f = *state;
  vl_contact_free(f->c);
  vl_persson_free(f->tab);
  vl_psd_free(&f->psd);
  return 0;
}

static void test_corrected_step(void **state) {
  fixture *f = *state;
  vl_contact_film_check_result r;
  assert_true(vl_contact_film_check(f->c, 1.5 * SPEEDS[N_SPEEDS - 1], &r));
  print_message("1.5x step: residual after the plain step %.3g, after the corrected %.3g; "
                "Reynolds rows %.2e\n",
                r.plain_norm, r.corr_norm, r.reynolds_max);
  assert_true(r.applied);
  assert_true(r.gap_change == 0.0);
  assert_true(r.reynolds_max <= 1e-3 * VL_WET_TOLERANCE);
  assert_true(r.corr_norm * 100.0 < r.plain_norm);
}

static void test_second_order(void **state) {
  fixture *f = *state;
  double rel[2];
  for (int k = 0; k < 2; k++) {
    vl_contact_film_check_result r;
    double d = k ? 1e-3 : 1e-2;
    assert_true(vl_contact_film_check(f->c, (1.0 + d) * SPEEDS[N_SPEEDS - 1], &r));
    assert_true(r.applied && r.pf_step > 0.0);
    rel[k] = r.pf_diff / r.pf_step;
    print_message("speed step %g: pf step %.3g, corrected - plain %.3g (%.3g of it)\n", d,
                  r.pf_step, r.pf_diff, rel[k]);
  }
  assert_true(rel[1] * 5.0 < rel[0]);
}

/* fig05's contact at 100x the viscosity carries most of its load on the
 * film at 1 m/s (swept up to it from 1e-3 m/s) */
static void test_not_in_thick_film(void **state) {
  fixture *f = *state;
  vl_contact_config cfg;
  vl_test_fig05_config(&cfg, f->tab, 100.0 * ETA, VL_WET_ROUGH_GRID, VL_WET_ROUGH_DOMAIN_MIN_A0);
  cfg.grid_growth = VL_WET_GRID_GROWTH;
  cfg.tolerance = VL_WET_TOLERANCE;
  vl_contact *c;
  vl_error err;
  if (vl_contact_create(&cfg, &c, &err) != VL_OK) fail_msg("%s", err.msg);
  vl_point p;
  for (double v = 1e-3; v < 1.01; v *= 1.5)
    if (vl_contact_solve(c, v, &p, &err) != VL_OK) fail_msg("%s", err.msg);
  print_message("eta %g Pa s, %g m/s: fluid load fraction %.3f\n", 100.0 * ETA, p.v0_m_s,
                p.fluid_load_fraction);
  assert_true(p.fluid_load_fraction > 0.5);
  vl_contact_film_check_result r;
  assert_true(vl_contact_film_check(c, 1.5 * p.v0_m_s, &r));
  assert_false(r.applied);
  assert_true(r.pf_diff == 0.0 && r.gap_change == 0.0);
  vl_contact_free(c);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_corrected_step),
      cmocka_unit_test(test_second_order),
      cmocka_unit_test(test_not_in_thick_film),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
