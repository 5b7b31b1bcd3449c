/* The shear-stress laws (shear_law.h), each against its formula written out
 * independently here, their parameter gradients against central
 * differences, their temperature and viscosity shifts, the seed's Eq. 6,
 * and the refusal of bad parameters. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include <math.h>
#include <string.h>

#include "shear_law_private.h"
#include "viscolube/shear_law.h"

static void close_rel(double got, double want, double tol) {
  if (!(fabs(got - want) <= tol * fabs(want) + 1e-300))
    fail_msg("got %.17g, want %.17g (rel. tol %g)", got, want, tol);
}

static void test_constant(void **state) {
  (void)state;
  vl_shear_law l = vl_shear_law_constant(1e6);
  double g[3];
  for (double v = 1e-9; v < 1e3; v *= 10.0)
    assert_true(vl_shear_law_eval(&l, v, g) == 1e6 && g[0] == 1.0);
  assert_true(vl_shear_law_eval(&l, -0.3, NULL) == 1e6);
  assert_int_equal(vl_shear_law_n_params(VL_SHEAR_CONSTANT), 1);
  assert_string_equal(vl_shear_law_param_name(VL_SHEAR_CONSTANT, 0), "sigma_s_pa");
}

static void test_eyring_formula(void **state) {
  (void)state;
  vl_shear_law l = {VL_SHEAR_EYRING, {2e5, 1.5e5, 1e-4}, 20.0, NAN};
  for (double v = 1e-8; v < 10.0; v *= 3.7) {
    /* asinh(x) = ln(x + sqrt(x^2 + 1)) */
    double x = v / 1e-4, want = 2e5 + 1.5e5 * log(x + sqrt(x * x + 1.0));
    close_rel(vl_shear_law_eval(&l, v, NULL), want, 1e-12);
    close_rel(vl_shear_law_eval(&l, -v, NULL), want, 1e-12);
  }
  /* at v = 0: sigma_0; far above v_e: linear in ln v, slope sigma_e */
  assert_true(vl_shear_law_eval(&l, 0.0, NULL) == 2e5);
  double s1 = vl_shear_law_eval(&l, 1.0, NULL), s2 = vl_shear_law_eval(&l, 10.0, NULL);
  close_rel(s2 - s1, 1.5e5 * log(10.0), 1e-8);
}

static void test_dewetting_formula(void **state) {
  (void)state;
  vl_shear_law l = {VL_SHEAR_DEWETTING, {3e6, 4e5, 1e-3}, NAN, 1e-3};
  double n = 2.0 * log(9.0) / (0.5 * log(10.0));
  close_rel(VL_DEWETTING_SWITCH_N, n, 1e-10);
  for (double v = 1e-7; v < 1.0; v *= 2.3) {
    double s = 1.0 / (1.0 + pow(1e-3 / v, n));
    close_rel(vl_shear_law_eval(&l, v, NULL), 3e6 + (4e5 - 3e6) * s, 1e-12);
  }
  /* dry at rest, half way at V_d, 10 % / 90 % of the way a quarter decade off */
  assert_true(vl_shear_law_eval(&l, 0.0, NULL) == 3e6);
  close_rel(vl_shear_law_eval(&l, 1e-3, NULL), 0.5 * (3e6 + 4e5), 1e-12);
  close_rel(vl_shear_law_eval(&l, 1e-3 * pow(10.0, -0.25), NULL), 3e6 - 0.1 * 2.6e6, 1e-9);
  close_rel(vl_shear_law_eval(&l, 1e-3 * pow(10.0, 0.25), NULL), 3e6 - 0.9 * 2.6e6, 1e-9);
  close_rel(vl_shear_law_eval(&l, 1e3, NULL), 4e5, 1e-12);
}

/* Each gradient component against a central difference. */
static void test_gradients(void **state) {
  (void)state;
  vl_shear_law laws[] = {{VL_SHEAR_EYRING, {2e5, 1.5e5, 1e-4}, NAN, NAN},
                         {VL_SHEAR_DEWETTING, {3e6, 4e5, 1e-3}, NAN, NAN}};
  for (size_t k = 0; k < 2; k++)
    for (double v = 1e-6; v < 1.0; v *= 4.1) {
      double g[3];
      double sigma = vl_shear_law_eval(&laws[k], v, g);
      for (size_t i = 0; i < 3; i++) {
        vl_shear_law a = laws[k], b = laws[k];
        double h = 1e-6 * a.p[i];
        a.p[i] += h, b.p[i] -= h;
        double fd = (vl_shear_law_eval(&a, v, NULL) - vl_shear_law_eval(&b, v, NULL)) / (2 * h);
        /* the difference resolves changes above the rounding of sigma */
        if (!(fabs(g[i] - fd) * h <= 1e-9 * sigma + 1e-6 * fabs(fd) * h))
          fail_msg("law %zu param %zu v %g: grad %.10g, difference %.10g", k, i, v, g[i], fd);
      }
    }
}

static void test_temperature_and_viscosity(void **state) {
  (void)state;
  vl_error err;
  vl_shear_law e = {VL_SHEAR_EYRING, {2e5, 1.5e5, 1e-4}, 20.0, NAN}, out;
  assert_int_equal(vl_shear_law_at(&e, 60.0, NAN, &out, &err), VL_OK);
  /* sigma_e = k_B T / V_a with V_a fixed */
  double va = VL_BOLTZMANN_J_K * 293.15 / 1.5e5;
  close_rel(out.p[1], VL_BOLTZMANN_J_K * 333.15 / va, 1e-12);
  assert_true(out.p[0] == 2e5 && out.p[2] == 1e-4 && out.tref_c == 60.0);
  /* no temperature: as stored */
  assert_int_equal(vl_shear_law_at(&e, NAN, NAN, &out, &err), VL_OK);
  assert_true(out.kind == e.kind && out.p[0] == e.p[0] && out.p[1] == e.p[1] &&
              out.p[2] == e.p[2] && out.tref_c == e.tref_c);
  vl_shear_law d = {VL_SHEAR_DEWETTING, {3e6, 4e5, 1e-3}, NAN, 1e-3};
  assert_int_equal(vl_shear_law_at(&d, 40.0, 0.5e-3, &out, &err), VL_OK);
  close_rel(out.p[2], 2e-3, 1e-15); /* half the viscosity: twice V_d */
  vl_shear_law c = vl_shear_law_constant(7e5);
  assert_int_equal(vl_shear_law_at(&c, 80.0, 1.0, &out, &err), VL_OK);
  assert_true(out.p[0] == 7e5);
  assert_int_equal(vl_shear_law_at(&c, -300.0, NAN, &out, &err), VL_EINPUT);
}

static void test_eq6(void **state) {
  (void)state;
  /* k 1, S = -20 mN/m, water 1e-3 Pa s, E 10 MPa, e 1 nm: 4e-4 / 1e-5 = 40 m/s;
   * a glycerol-like 1 Pa s and e = 10 nm: 4 mm/s */
  close_rel(vl_dewetting_speed(1.0, -0.02, 1e-3, 1e7, 1e-9), 40.0, 1e-14);
  close_rel(vl_dewetting_speed(1.0, -0.02, 1.0, 1e7, 1e-8), 4e-3, 1e-14);
}

static void test_names_and_validation(void **state) {
  (void)state;
  vl_error err;
  vl_shear_law_kind k;
  assert_int_equal(vl_shear_law_parse("eyring", &k, &err), VL_OK);
  assert_int_equal(k, VL_SHEAR_EYRING);
  assert_int_equal(vl_shear_law_parse("eyrin", &k, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "dewetting"));
  assert_string_equal(vl_shear_law_name(VL_SHEAR_DEWETTING), "dewetting");
  assert_string_equal(vl_shear_law_param_name(VL_SHEAR_EYRING, 2), "v_e_m_s");
  vl_shear_law bad[] = {{VL_SHEAR_CONSTANT, {-1.0, 0, 0}, NAN, NAN},
                        {VL_SHEAR_CONSTANT, {NAN, 0, 0}, NAN, NAN},
                        {VL_SHEAR_EYRING, {1e5, 1e5, 0.0}, NAN, NAN},
                        {VL_SHEAR_EYRING, {1e5, -1.0, 1e-3}, NAN, NAN},
                        {VL_SHEAR_DEWETTING, {1e5, 1e5, INFINITY}, NAN, NAN},
                        {VL_SHEAR_CONSTANT, {1e6, 0, 0}, -400.0, NAN},
                        {VL_SHEAR_CONSTANT, {1e6, 0, 0}, NAN, -1.0},
                        {(vl_shear_law_kind)7, {1e6, 0, 0}, NAN, NAN}};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
    assert_int_equal(vl_shear_law_validate(&bad[i], &err), VL_EINPUT);
  vl_shear_law good = {VL_SHEAR_EYRING, {0.0, 0.0, 1e-3}, 20.0, 1e-3};
  assert_int_equal(vl_shear_law_validate(&good, &err), VL_OK);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_constant),
      cmocka_unit_test(test_eyring_formula),
      cmocka_unit_test(test_dewetting_formula),
      cmocka_unit_test(test_gradients),
      cmocka_unit_test(test_temperature_and_viscosity),
      cmocka_unit_test(test_eq6),
      cmocka_unit_test(test_names_and_validation),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
