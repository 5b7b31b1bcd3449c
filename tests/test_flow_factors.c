/* Flow and shear-stress factors (docs/FLOW_FACTORS.md): the smooth model, the
 * Patir-Cheng factors at known points against the published formulas and
 * against quadrature of Patir-Cheng's defining integral for Phi_f, the
 * Gaussian-gap mapping u(H) round trip against an independent evaluation,
 * continuity and C1 (analytic derivatives vs central differences) on a dense
 * log grid and at every join, the limits u -> 0 and u -> inf, and the solver
 * combinations. The oracles below are written from the formulas in
 * docs/FLOW_FACTORS.md, not from the library. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "flow_factors_internal.h"
#include "viscolube/flow_factors.h"
#include "vl_test_util.h"

#define PC VL_FLOW_FACTORS_PATIR_CHENG
#define SIG 1.5e-6 /* h_rms (m) used throughout */

/* ---------------------------------------------------------------- oracles */

/* u/sigma = H Phi(H) + phi(H), in long double. */
static long double gap_ld(long double H) {
  return expl(-0.5L * H * H) / sqrtl(2.0L * 3.14159265358979323846264338327950288L) +
         H * 0.5L * erfcl(-H / sqrtl(2.0L));
}
static double gap(double H) { return (double)gap_ld(H); }
static double cdf(double H) { return (double)(0.5L * erfcl(-(long double)H / sqrtl(2.0L))); }

static const double gl_x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                               0.9061798459386640};
static const double gl_w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                               0.4786286704993665, 0.2369268850561891};

/* \int_a^b f by 5-point Gauss-Legendre on n panels. */
static double gauss(double (*f)(double, double), double z, double a, double b, int n) {
  double s = 0.0, h = (b - a) / n;
  for (int p = 0; p < n; p++) {
    double c = a + (p + 0.5) * h;
    for (int k = 0; k < 5; k++)
      s += gl_w[k] * f(c + 0.5 * h * gl_x[k], z);
  }
  return 0.5 * h * s;
}
/* ln(u/sigma) for H <= -8 by quadrature, independent of erfc: with x = -H,
 * g = phi(H) \int_0^inf s e^{-x s - s^2/2} ds = phi(H)/x^2 \int_0^inf y e^{-y}
 * e^{-y^2/(2x^2)} dy (composite Gauss-Legendre on [0, 60], e^-60 negligible). */
static double laplace_kernel(double y, double x) { return y * exp(-y - y * y / (2.0 * x * x)); }
static double log_gap_quad(double H) {
  double x = -H;
  return -0.5 * x * x - 0.5 * log(2.0 * M_PI) - 2.0 * log(x) +
         log(gauss(laplace_kernel, x, 0.0, 60.0, 600));
}

static double poly_dist(double t) { return (1 - t * t) * (1 - t * t) * (1 - t * t); }
static double pc_kernel(double t, double z) { return poly_dist(t) / (z + t); }
static double pc_quotient(double t, double z) { return (poly_dist(t) - poly_dist(-z)) / (z + t); }

/* Phi_f from Patir-Cheng's definition: the mean of h/h_T over the
 * polynomial height density (35/32)(1-t^2)^3 on |t| < 1 (heights in units of
 * 3 sigma), with z = H/3. For z > 1 the integral over [-1, 1]; for z <= 1
 * the gap is cut at h_T = sigma/100 (epsilon* = 1/300), giving the log term,
 * and the polynomial part \int_{-z}^{1} of the quotient (degree 5 in t: GL
 * is exact). */
static double phi_f_oracle(double H) {
  double z = H / 3.0;
  if (z > 1.0) return (35.0 / 32.0) * z * gauss(pc_kernel, z, -1.0, 1.0, 2000);
  double w = 1 - z * z;
  return (35.0 / 32.0) * z *
         (w * w * w * log(300.0 * (1.0 + z)) + gauss(pc_quotient, z, -z, 1.0, 4));
}

/* The published fits (docs/FLOW_FACTORS.md table). */
static double phi_x_fit(double H) { return 1.0 - 0.90 * exp(-0.56 * H); }
static double phi_s_low(double H) { return 1.899 * pow(H, 0.98) * exp(-0.92 * H + 0.05 * H * H); }
static double phi_s_high(double H) { return 1.126 * exp(-0.25 * H); }
static double phi_fs_fit(double H) { return 11.1 * pow(H, 2.31) * exp(-2.38 * H + 0.11 * H * H); }
static double phi_fp_fit(double H) { return 1.0 - 1.40 * exp(-0.66 * H); }

static vl_flow_factor_values eval_at(double u, vl_flow_factor_values *d) {
  vl_flow_factor_values v;
  vl_flow_factors_eval(PC, u, SIG, &v, d);
  return v;
}

/* Every place where the implementation switches formula, in H: the Couette
 * join (-0.5), percolation (0), the cubic joins (0.5, 0.75), z = 1 (3), the
 * Phi_s blend (4.5, 5, 5.5), the Phi_f series (6), the Phi_fs tail (7, 8)
 * and the end of the H(u) table (9). */
static const double joins_H[] = {-0.5, 0.0, 0.5, 0.75, 3.0, 4.5, 5.0, 5.5, 6.0, 7.0, 8.0, 9.0};
#define N_JOINS (sizeof joins_H / sizeof joins_H[0])

/* ------------------------------------------------------------------ tests */

typedef struct {
  double u[64];
  vl_flow_factor_values v[64], d[64];
} thread_job;

static void *thread_eval(void *arg) {
  thread_job *job = arg;
  for (int i = 0; i < 64; i++)
    vl_flow_factors_eval(PC, job->u[i], SIG, &job->v[i], &job->d[i]);
  return NULL;
}

/* First use from several threads at once (the lazily built H(u) table) gives
 * the same results as later single-threaded calls. Must run first. */
static void test_first_use_concurrent(void **state) {
  (void)state;
  thread_job jobs[4];
  pthread_t th[4];
  for (int k = 0; k < 4; k++) {
    for (int i = 0; i < 64; i++)
      jobs[k].u[i] = SIG * pow(10.0, -1.0 + 2.0 * (i + 64 * k) / 256.0);
    assert_int_equal(pthread_create(&th[k], NULL, thread_eval, &jobs[k]), 0);
  }
  for (int k = 0; k < 4; k++)
    assert_int_equal(pthread_join(th[k], NULL), 0);
  for (int k = 0; k < 4; k++) {
    for (int i = 0; i < 64; i++) {
      vl_flow_factor_values v, d;
      vl_flow_factors_eval(PC, jobs[k].u[i], SIG, &v, &d);
      assert_memory_equal(&v, &jobs[k].v[i], sizeof v);
      assert_memory_equal(&d, &jobs[k].d[i], sizeof d);
    }
  }
}

static void test_smooth_is_exactly_smooth(void **state) {
  (void)state;
  const double us[] = {1e-12, 1e-6, 3e-3, 1.0};
  for (size_t i = 0; i < 4; i++) {
    vl_flow_factor_values v, d;
    vl_flow_factors_eval(VL_FLOW_FACTORS_SMOOTH, us[i], SIG, &v, &d);
    assert_true(v.phi_p == 1.0 && v.phi_s == 0.0 && v.phi_f == 1.0 && v.phi_fs == 0.0 &&
                v.phi_fp == 1.0);
    assert_true(d.phi_p == 0.0 && d.phi_s == 0.0 && d.phi_f == 0.0 && d.phi_fs == 0.0 &&
                d.phi_fp == 0.0);
    /* patir-cheng without roughness is the smooth model */
    vl_flow_factors_eval(PC, us[i], 0.0, &v, &d);
    assert_true(v.phi_p == 1.0 && v.phi_s == 0.0 && v.phi_f == 1.0 && v.phi_fs == 0.0 &&
                v.phi_fp == 1.0 && d.phi_p == 0.0 && d.phi_f == 0.0);
    vl_flow_terms t, dt;
    vl_flow_factors_terms(VL_FLOW_FACTORS_SMOOTH, us[i], SIG, &t, &dt);
    double u = us[i];
    assert_true(vl_test_rel(t.conductance_m3, u * u * u) < 1e-15);
    assert_true(t.shear_flow == 0.0 && dt.shear_flow == 0.0);
    assert_true(vl_test_rel(t.couette_per_m, 1.0 / u) < 1e-15);
    assert_true(t.poiseuille_m == u && dt.poiseuille_m == 1.0);
    assert_true(vl_test_rel(dt.conductance_m3, 3 * u * u) < 1e-15);
    assert_true(vl_test_rel(dt.couette_per_m, -1.0 / (u * u)) < 1e-15);
  }
}

static void test_names_and_parse(void **state) {
  (void)state;
  vl_flow_factor_kind k = VL_FLOW_FACTORS_SMOOTH;
  vl_error err;
  assert_int_equal(vl_flow_factors_parse("patir-cheng", &k, &err), VL_OK);
  assert_int_equal(k, PC);
  assert_int_equal(vl_flow_factors_parse("smooth", &k, &err), VL_OK);
  assert_int_equal(k, VL_FLOW_FACTORS_SMOOTH);
  assert_string_equal(vl_flow_factors_name(PC), "patir-cheng");
  assert_string_equal(vl_flow_factors_name(VL_FLOW_FACTORS_SMOOTH), "smooth");
  assert_int_equal(vl_flow_factors_parse("Patir-Cheng", &k, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "Patir-Cheng"));
  assert_non_null(strstr(err.msg, "patir-cheng"));
  assert_int_equal(vl_flow_factors_parse(NULL, &k, NULL), VL_EINPUT);
  assert_int_equal(k, VL_FLOW_FACTORS_SMOOTH); /* untouched on failure */
}

/* H -> u (oracle) -> h(u) (library) returns H, and dh/du = 1/Phi(H), over
 * u/sigma from 1e-300 to 60. Tolerance: u is rounded to double (relative
 * 1e-16), which moves H by 1e-16 g/Phi(H) <= 1e-16 (1 + |H|); the library's
 * table is quoted at ~1e-14, so 5e-14 (1 + |H|). */
static void test_mapping_round_trip(void **state) {
  (void)state;
  double worst = 0.0, worst_d = 0.0;
  for (double H = -36.0; H <= 60.0; H += 0.01953125) {
    double u = H >= -8.0 ? SIG * gap(H) : SIG * exp(log_gap_quad(H));
    double dh;
    double h = vl_flow_factors_nominal_gap(u, SIG, &dh);
    double e = fabs(h / SIG - H) / (1.0 + fabs(H));
    if (e > worst) worst = e;
    if (H >= -8.0) { /* the oracle's Phi underflows below */
      double ed = fabs(dh * cdf(H) - 1.0);
      if (ed > worst_d) worst_d = ed;
    }
  }
  print_message("mapping round trip: max |H err|/(1+|H|) = %.2e, max rel dh/du err = %.2e\n", worst,
                worst_d);
  assert_true(worst < 5e-14);
  assert_true(worst_d < 1e-10);
  /* the mapping's anchor: u/sigma = 1/sqrt(2 pi) at H = 0 */
  assert_true(fabs(vl_flow_factors_nominal_gap(SIG / sqrt(2.0 * M_PI), SIG, NULL)) < 1e-14 * SIG);
  /* percolation: below it, no pressure flow */
  vl_flow_factor_values v = eval_at(0.999999 * SIG / sqrt(2.0 * M_PI), NULL);
  assert_true(v.phi_p == 0.0);
  v = eval_at(1.000001 * SIG / sqrt(2.0 * M_PI), NULL);
  assert_true(v.phi_p > 0.0);
}

/* The factors inside the published fit ranges equal the formulas of
 * docs/FLOW_FACTORS.md (and Phi_f its defining integral), mapped with h/u = H/g
 * where g = u/sigma comes from the oracle. The only error sources are the
 * mapping (~1e-14 in H, times d ln Phi/d ln H <= ~10) and quadrature
 * (< 1e-14): tolerance 1e-12 relative. */
static void test_values_at_known_points(void **state) {
  (void)state;
  double worst = 0.0;
#define CHECK(got, want)                                                                           \
  do {                                                                                             \
    double e_ = vl_test_rel((got), (want));                                                        \
    if (e_ > worst) worst = e_;                                                                    \
    if (e_ > 1e-12) fail_msg("H = %g: %s = %.15g, expected %.15g", H, #got, (got), (want));        \
  } while (0)

  /* the brief's example: Phi_x(3) = 1 - 0.9 e^{-1.68} */
  {
    double H = 3.0, g = gap(H);
    vl_flow_factor_values v = eval_at(SIG * g, NULL);
    CHECK(v.phi_p, (1.0 - 0.9 * exp(-1.68)) * pow(H / g, 3));
  }
  const double Hx[] = {0.5, 1.0, 2.0, 4.0, 6.0, 12.0};
  for (size_t i = 0; i < sizeof Hx / sizeof Hx[0]; i++) {
    double H = Hx[i], g = gap(H);
    vl_flow_factor_values v = eval_at(SIG * g, NULL);
    CHECK(v.phi_p, phi_x_fit(H) * pow(H / g, 3));
  }
  const double Hs_low[] = {0.5, 1.0, 2.0, 4.0, 4.5}, Hs_high[] = {5.5, 6.0, 10.0, 40.0};
  for (size_t i = 0; i < 5; i++) {
    double H = Hs_low[i];
    CHECK(eval_at(SIG * gap(H), NULL).phi_s, phi_s_low(H));
  }
  for (size_t i = 0; i < 4; i++) {
    double H = Hs_high[i];
    CHECK(eval_at(SIG * gap(H), NULL).phi_s, phi_s_high(H));
  }
  /* Phi_f on both closed forms, across z = 1, and on the series (z >= 3) */
  const double Hf[] = {0.01, 0.3, 1.5, 2.9, 3.0, 3.3, 4.5, 5.9, 6.0, 6.1, 9.0, 12.0, 30.0, 300.0};
  for (size_t i = 0; i < sizeof Hf / sizeof Hf[0]; i++) {
    double H = Hf[i], g = gap(H);
    CHECK(eval_at(SIG * g, NULL).phi_f, phi_f_oracle(H) * g / H);
  }
  const double Hfs[] = {0.5, 1.0, 3.0, 6.0, 7.0};
  for (size_t i = 0; i < sizeof Hfs / sizeof Hfs[0]; i++) {
    double H = Hfs[i], g = gap(H);
    CHECK(eval_at(SIG * g, NULL).phi_fs, phi_fs_fit(H) * g / H);
  }
  const double Hfp[] = {0.75, 1.0, 2.0, 5.0, 20.0};
  for (size_t i = 0; i < sizeof Hfp / sizeof Hfp[0]; i++) {
    double H = Hfp[i], g = gap(H);
    CHECK(eval_at(SIG * g, NULL).phi_fp, phi_fp_fit(H) * H / g);
  }
#undef CHECK
  print_message("known points: max rel err %.2e\n", worst);
}

/* Central differences with step du = 1e-7 u: truncation (du^2 f''') and
 * rounding (1e-16 f/du) stay below 1e-9 in u df/du for smooth stretches; a
 * central difference straddling a join where f'' jumps by J errs by <= du J/2,
 * i.e. ~1e-6 in u df/du for the joins here (|u^2 f''| <~ 20). A real slope
 * jump s shows up as ~s/2 in u df/du (the quoted Phi_x cubic's would be ~3e-5):
 * tolerance 2e-6 (1 + |f|). */
static double fd_check_factors(double u) {
  vl_flow_factor_values v, d, vp, vm;
  vl_flow_factors_eval(PC, u, SIG, &v, &d);
  double du = 1e-7 * u;
  vl_flow_factors_eval(PC, u + du, SIG, &vp, NULL);
  vl_flow_factors_eval(PC, u - du, SIG, &vm, NULL);
  const double *a = &v.phi_p, *b = &d.phi_p, *p = &vp.phi_p, *m = &vm.phi_p;
  double worst = 0.0;
  for (int j = 0; j < 5; j++) {
    assert_true(isfinite(a[j]) && isfinite(b[j]));
    double e = u * fabs((p[j] - m[j]) / (2.0 * du) - b[j]) / (1.0 + fabs(a[j]));
    if (e > 2e-6)
      fail_msg("u/sigma = %.9g: factor %d derivative %.12g vs FD %.12g", u / SIG, j, b[j],
               (p[j] - m[j]) / (2.0 * du));
    if (e > worst) worst = e;
  }
  return worst;
}

/* The same for the solver combinations, scaled by their natural units. */
static double fd_check_terms(double u) {
  vl_flow_terms t, d, tp, tm;
  vl_flow_factors_terms(PC, u, SIG, &t, &d);
  double du = 1e-7 * u;
  vl_flow_factors_terms(PC, u + du, SIG, &tp, NULL);
  vl_flow_factors_terms(PC, u - du, SIG, &tm, NULL);
  const double *a = &t.conductance_m3, *b = &d.conductance_m3, *p = &tp.conductance_m3,
               *m = &tm.conductance_m3;
  const double scale[4] = {u * u * u, 1.0, 1.0 / SIG + 1.0 / u, u};
  double worst = 0.0;
  for (int j = 0; j < 4; j++) {
    assert_true(isfinite(a[j]) && isfinite(b[j]));
    double e = u * fabs((p[j] - m[j]) / (2.0 * du) - b[j]) / (scale[j] + fabs(a[j]));
    if (e > 2e-6)
      fail_msg("u/sigma = %.9g: term %d derivative %.12g vs FD %.12g", u / SIG, j, b[j],
               (p[j] - m[j]) / (2.0 * du));
    if (e > worst) worst = e;
  }
  return worst;
}

static void test_derivatives_dense_log_grid(void **state) {
  (void)state;
  double worst = 0.0, worst_u = 0.0, worst_t = 0.0, worst_grid = 0.0;
  int n = 40000;
  for (int i = 0; i <= n; i++) {
    double u = SIG * pow(10.0, -3.0 + 6.0 * i / n);
    double e = fd_check_factors(u);
    if (e > worst) worst = e, worst_u = u;
    e = fd_check_terms(u);
    if (e > worst_t) worst_t = e;
  }
  worst_grid = worst;
  /* and straddling every join, at a few offsets */
  for (size_t k = 0; k < N_JOINS; k++) {
    for (int s = -3; s <= 3; s++) {
      double u = SIG * gap(joins_H[k]) * (1.0 + s * 3e-8);
      double e = fd_check_factors(u);
      if (e > worst) worst = e, worst_u = u;
      e = fd_check_terms(u);
      if (e > worst_t) worst_t = e;
    }
  }
  print_message("derivatives vs central FD: max u|d - FD|/(1+|f|) = %.2e on the log grid, "
                "%.2e with the join-straddling points (at u/sigma = %.4g); terms %.2e\n",
                worst_grid, worst, worst_u / SIG, worst_t);
}

/* Continuity and C1 across each join: values and derivatives on either side,
 * 2e-9 u apart, differ by no more than the smooth variation over that gap
 * (|u f'| <~ 10, |u^2 f''| <~ 100, so 1e-7 is ample; a value jump of the
 * quoted Phi_s at H = 5 (3e-5) or slope jump (8e-3) would fail). */
static void test_joins_are_c1(void **state) {
  (void)state;
  double worst_v = 0.0, worst_d = 0.0;
  for (size_t k = 0; k < N_JOINS; k++) {
    double ub = SIG * gap(joins_H[k]), du = 1e-9 * ub;
    vl_flow_factor_values vl, dl, vr, dr;
    vl_flow_factors_eval(PC, ub - du, SIG, &vl, &dl);
    vl_flow_factors_eval(PC, ub + du, SIG, &vr, &dr);
    const double *a = &vl.phi_p, *b = &vr.phi_p, *c = &dl.phi_p, *e = &dr.phi_p;
    for (int j = 0; j < 5; j++) {
      double jv = fabs(a[j] - b[j]), jd = ub * fabs(c[j] - e[j]);
      if (jv > worst_v) worst_v = jv;
      if (jd > worst_d) worst_d = jd;
      if (jv > 1e-7 || jd > 1e-7)
        fail_msg("join H = %g, factor %d: value jump %.3g, slope jump %.3g", joins_H[k], j, jv, jd);
    }
  }
  print_message("joins: max value jump %.2e, max u*slope jump %.2e\n", worst_v, worst_d);
}

/* u -> inf: the smooth factors. Phi_f - 1 = 1/(9 z^2) + O(z^-4) (the series'
 * first term, independently: the second moment of the polynomial density is
 * 1/9), so at u = 1e3 sigma the check is to 1e-3 of that term. */
static void test_limit_large_u(void **state) {
  (void)state;
  vl_flow_factor_values v, d;
  double u = 1e3 * SIG;
  vl_flow_factors_eval(PC, u, SIG, &v, &d);
  double z = 1e3 / 3.0;
  assert_true(fabs(v.phi_p - 1.0) < 1e-15);
  assert_true(v.phi_s >= 0.0 && v.phi_s < 1e-100);
  assert_true(fabs((v.phi_f - 1.0) / (1.0 / (9.0 * z * z)) - 1.0) < 1e-3);
  assert_true(v.phi_fs == 0.0);
  assert_true(fabs(v.phi_fp - 1.0) < 1e-15);
  assert_true(fabs(d.phi_p) * u < 1e-15 && fabs(d.phi_f) * u < 1e-5 && fabs(d.phi_fp) * u < 1e-15);
  const double big[] = {1e6, 1e12, 1e100};
  for (int i = 0; i < 3; i++) {
    vl_flow_factors_eval(PC, big[i] * SIG, SIG, &v, &d);
    double zb = big[i] / 3.0; /* Phi_f - 1 = 1/(9 z^2) + ... as above */
    assert_true(fabs(v.phi_p - 1.0) < 1e-15 && v.phi_s < 1e-100 &&
                fabs(v.phi_f - 1.0) <= 1.001 / (9.0 * zb * zb) + 2e-16 && v.phi_fs == 0.0 &&
                fabs(v.phi_fp - 1.0) < 1e-15);
    assert_true(isfinite(d.phi_p) && isfinite(d.phi_s) && isfinite(d.phi_f) && isfinite(d.phi_fp));
  }
}

/* u -> 0 (and u <= 0, which a Newton trial may produce): finite. No pressure
 * flow, no shear flow, no roughness or Poiseuille shear; the Couette shear
 * per unit film tends to (35/96)(ln 300 - 11/12) - 7/72 (FLOW_FACTORS'
 * H -> 0 limit of Phi_f/H, lowered by the C1 join on [-0.5, 0]). */
static void test_limit_small_u(void **state) {
  (void)state;
  double psi_inf = (35.0 / 96.0) * (log(300.0) - 11.0 / 12.0) - 7.0 / 72.0;
  const double gs[] = {0.19, 1e-3, 1e-30, 1e-300, 0.0, -1.0};
  for (int i = 0; i < 6; i++) {
    double u = gs[i] * SIG;
    vl_flow_factor_values v, d;
    vl_flow_factors_eval(PC, u, SIG, &v, &d);
    assert_true(v.phi_p == 0.0 && v.phi_s == 0.0 && v.phi_fs == 0.0 && v.phi_fp == 0.0);
    assert_true(fabs(v.phi_f - psi_inf * fmax(gs[i], 0.0)) <= 1e-15 * psi_inf);
    assert_true(isfinite(d.phi_p) && isfinite(d.phi_s) && isfinite(d.phi_f) && isfinite(d.phi_fs) &&
                isfinite(d.phi_fp));
    assert_true(fabs(d.phi_f * SIG - psi_inf) < 1e-15);
    vl_flow_terms t, dt;
    vl_flow_factors_terms(PC, u, SIG, &t, &dt);
    assert_true(t.conductance_m3 == 0.0 && t.shear_flow == 0.0 && t.poiseuille_m == 0.0);
    assert_true(fabs(t.couette_per_m * SIG - psi_inf) < 1e-15);
    assert_true(dt.conductance_m3 == 0.0 && dt.couette_per_m == 0.0 && dt.poiseuille_m == 0.0);
  }
  /* the Couette coefficient is continuous into the fit: Phi_f/H at H -> 0+ */
  vl_flow_terms t;
  vl_flow_factors_terms(PC, SIG * gap(1e-9), SIG, &t, NULL);
  assert_true(fabs(t.couette_per_m * SIG - (35.0 / 96.0) * (log(300.0) - 11.0 / 12.0)) < 1e-8);
}

/* The solver combinations are the stated products of the factors, with the
 * product-rule derivatives; physically: the pressure-flow conductance grows
 * with the film, every factor is >= 0. */
static void test_terms_and_physics(void **state) {
  (void)state;
  double prev_g = -1.0;
  for (int i = 0; i <= 6000; i++) {
    double u = SIG * pow(10.0, -3.0 + 6.0 * i / 6000.0);
    vl_flow_factor_values v, d;
    vl_flow_terms t, dt;
    vl_flow_factors_eval(PC, u, SIG, &v, &d);
    vl_flow_factors_terms(PC, u, SIG, &t, &dt);
    double u3 = u * u * u;
    assert_true(fabs(t.conductance_m3 - u3 * v.phi_p) <= 1e-13 * u3 * v.phi_p);
    assert_true(t.shear_flow == v.phi_s && dt.shear_flow == d.phi_s);
    assert_true(vl_test_rel(t.couette_per_m, (v.phi_f + v.phi_fs) / u) < 1e-13);
    assert_true(fabs(t.poiseuille_m - v.phi_fp * u) <= 1e-13 * v.phi_fp * u);
    double dg = 3 * u * u * v.phi_p + u3 * d.phi_p;
    assert_true(fabs(dt.conductance_m3 - dg) <= 1e-12 * (fabs(dg) + u * u * v.phi_p));
    double dc = (d.phi_f + d.phi_fs) / u - (v.phi_f + v.phi_fs) / (u * u);
    assert_true(fabs(dt.couette_per_m - dc) <= 1e-11 * (fabs(t.couette_per_m) / u + fabs(dc)));
    double dp = d.phi_fp * u + v.phi_fp;
    assert_true(fabs(dt.poiseuille_m - dp) <= 1e-12 * (fabs(dp) + v.phi_fp) + 1e-300);
    assert_true(v.phi_p >= 0.0 && v.phi_s >= 0.0 && v.phi_f > 0.0 && v.phi_fs >= 0.0 &&
                v.phi_fp >= 0.0);
    assert_true(t.conductance_m3 >= prev_g && dt.conductance_m3 >= 0.0);
    prev_g = t.conductance_m3;
  }
  /* regularised stretches stay within their neighbours' values */
  for (double H = 0.01; H < 0.75; H += 0.01) {
    vl_flow_factor_values v = eval_at(SIG * gap(H), NULL);
    double g = gap(H);
    if (H < 0.5) {
      assert_true(v.phi_p * pow(g / H, 3) <= phi_x_fit(0.5) + 1e-15); /* Phi_x below its join */
      assert_true(v.phi_s <= phi_s_low(0.5) + 1e-15);
    }
    assert_true(v.phi_fp * g / H <= phi_fp_fit(0.75) + 1e-15);
  }
  for (double H = 4.5; H <= 5.5; H += 0.01) { /* the Phi_s blend lies between its branches */
    double s = eval_at(SIG * gap(H), NULL).phi_s;
    assert_true(s >= fmin(phi_s_low(H), phi_s_high(H)) - 1e-15 &&
                s <= fmax(phi_s_low(H), phi_s_high(H)) + 1e-15);
  }
  double prev = phi_fs_fit(7.0);
  for (double H = 7.0; H <= 8.2; H += 0.01) { /* the Phi_fs tail falls monotonically to 0 */
    double g = gap(H), fs = eval_at(SIG * g, NULL).phi_fs * H / g;
    assert_true(fs >= 0.0 && fs <= prev + 1e-15);
    prev = fs;
  }
}

static void test_nan_propagates(void **state) {
  (void)state;
  vl_flow_factor_values v, d;
  vl_flow_factors_eval(PC, NAN, SIG, &v, &d);
  assert_true(isnan(v.phi_p) && isnan(v.phi_f) && isnan(d.phi_fp));
  vl_flow_factors_eval(PC, SIG, NAN, &v, NULL);
  assert_true(isnan(v.phi_s));
  vl_flow_terms t;
  vl_flow_factors_terms(PC, NAN, SIG, &t, NULL);
  assert_true(isnan(t.conductance_m3) && isnan(t.couette_per_m));
  assert_true(isnan(vl_flow_factors_nominal_gap(NAN, SIG, NULL)));
  double dh;
  assert_true(vl_flow_factors_nominal_gap(0.0, SIG, &dh) == -INFINITY && dh == INFINITY);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_first_use_concurrent),
      cmocka_unit_test(test_smooth_is_exactly_smooth),
      cmocka_unit_test(test_names_and_parse),
      cmocka_unit_test(test_mapping_round_trip),
      cmocka_unit_test(test_values_at_known_points),
      cmocka_unit_test(test_derivatives_dense_log_grid),
      cmocka_unit_test(test_joins_are_c1),
      cmocka_unit_test(test_limit_large_u),
      cmocka_unit_test(test_limit_small_u),
      cmocka_unit_test(test_terms_and_physics),
      cmocka_unit_test(test_nan_propagates),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
