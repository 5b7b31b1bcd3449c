/* Validation of the smooth wet (hydrodynamic / EHL) solver, docs/VALIDATION.md
 * section 5 and docs/MODEL.md sections 1 and 7:
 *   - a rigid cylinder against Martin's film (published constant) and
 *     against the closed form of the same problem with the finite inlet of
 *     the computational domain (derived here, independently of the solver);
 *   - the soft (isoviscous-elastic) exponents of the minimum film;
 *   - invariants of every solution: a constant mass flux, load balance,
 *     pf >= 0, u > 0, the EHL constriction on the outlet side;
 *   - the energy balance of smooth surfaces.
 * Sizes are chosen so that the whole file runs in a few seconds. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "contact_private.h"
#include "contact_test.h"
#include "flow_factors_emt.h"
#include "flow_factors_internal.h"
#include "rheology_internal.h"
#include "sweep_internal.h"
#include "viscolube/contact.h"
#include "viscolube/sweep.h"
#include "vl_test_scenes.h"
#include "vl_test_util.h"

#define RADIUS 0.01
#define NU 0.5

/* An elastic smooth wet contact (Einf = E0: no Prony memory). */
static vl_contact *make_wet(double e0, double load, double eta, size_t grid, double x_min_a0,
                            double x_max_a0) {
  vl_contact_config cfg;
  vl_contact_config_defaults(&cfg);
  cfg.rubber = vl_prony_single(e0, 1.0, 0.1, NU);
  cfg.radius_m = RADIUS;
  cfg.load_n_per_m = load;
  cfg.eta_pa_s = eta;
  cfg.grid = grid;
  cfg.x_min_a0 = x_min_a0;
  cfg.x_max_a0 = x_max_a0;
  vl_contact *c = NULL;
  vl_error err;
  if (vl_contact_create(&cfg, &c, &err) != VL_OK) fail_msg("create: %s", err.msg);
  return c;
}

/* Relaxed Hertz half-width, the unit of the domain (docs/MODEL.md section 9). */
static double hertz_a0(double e0, double load) {
  return sqrt(4.0 * load * RADIUS * (1.0 - NU * NU) / (M_PI * e0));
}

static double inlet_length(double e0, double load, double eta, double v0) {
  vl_contact_config cfg;
  vl_contact_config_defaults(&cfg);
  cfg.rubber = vl_prony_single(e0, 1.0, 0.1, NU);
  cfg.radius_m = RADIUS;
  cfg.load_n_per_m = load;
  cfg.eta_pa_s = eta;
  return vl_contact_inlet_length_m(&cfg, v0);
}

static vl_point solve_one(vl_contact *c, double v0) {
  vl_point pt;
  vl_error err;
  if (vl_contact_solve(c, v0, &pt, &err) != VL_OK) fail_msg("solve at %g m/s: %s", v0, err.msg);
  return pt;
}

/* Least-squares slope of ln y against ln x. */
static double log_slope(size_t n, const double *x, const double *y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < n; i++) {
    double a = log(x[i]), b = log(y[i]);
    sx += a, sy += b, sxx += a * a, sxy += a * b;
  }
  return ((double)n * sxy - sx * sy) / ((double)n * sxx - sx * sx);
}

/* ---- Rigid cylinder: Martin ---------------------------------------------
 * Gap h0 (1 + X^2), X = x/b, b = sqrt(2 R h0); Reynolds with p = 0 at the
 * inlet X_in and p = dp/dX = 0 at the rupture Xc:
 *   p = (6 eta v0 b/h0^2) P(X),  P = (I2(X) - I2(X_in)) - Hc (I3(X) - I3(X_in)),
 *   I2 = \int dX/H^2 = (X/H + atan X)/2,
 *   I3 = \int dX/H^3 = X/(4 H^2) + 3 X/(8 H) + 3 atan(X)/8,  Hc = 1 + Xc^2,
 * Xc the root of P(Xc) = 0, and the load (integration by parts)
 *   fN = (12 eta v0 R/h0) [1/(4 Hc) - 1/(2 H_in) + Hc/(4 H_in^2)].
 * X_in -> -inf gives Xc = 0.4751 and Martin's h0 = 4.895 eta (v0/2) R/fN. */
static double rigid_i2(double X) { return 0.5 * (X / (1.0 + X * X) + atan(X)); }
static double rigid_i3(double X) {
  double H = 1.0 + X * X;
  return X / (4.0 * H * H) + 3.0 * X / (8.0 * H) + 0.375 * atan(X);
}

/* Minimum film of the rigid cylinder fed from x_in (m, < 0): fixed point in
 * h0 (b depends on h0), bisection for Xc. */
static double martin_finite_inlet(double eta, double v0, double load, double x_in) {
  double h0 = 2.447 * eta * v0 * RADIUS / load;
  for (int it = 0; it < 100; it++) {
    double Xi = x_in / sqrt(2.0 * RADIUS * h0), a2 = rigid_i2(Xi), a3 = rigid_i3(Xi);
    double lo = 0.0, hi = 10.0;
    for (int k = 0; k < 200; k++) {
      double m = 0.5 * (lo + hi);
      if ((rigid_i2(m) - a2) - (1.0 + m * m) * (rigid_i3(m) - a3) > 0.0)
        lo = m;
      else
        hi = m;
    }
    double Hc = 1.0 + lo * lo, Hi = 1.0 + Xi * Xi;
    h0 = 12.0 * eta * v0 * RADIUS * (0.25 / Hc - 0.5 / Hi + 0.25 * Hc / (Hi * Hi)) / load;
  }
  return h0;
}

/* docs/VALIDATION.md 5: a nearly rigid cylinder (E0 = 1e13 Pa: the elastic
 * deformation is ~1e-4 of the film) against Martin's h_min = 4.894 eta
 * (v0/2) R/fN, within 1 % at 512 cells (measured -0.54 %). The domain
 * follows the hydrodynamic length, not a0 (here a0 = 1 um, the inlet length
 * sqrt(2 R h) = 0.22 mm): the inlet end at 30 inlet lengths, the outlet at
 * ~2, a node on x = 0 so that the minimum over the nodes is the film on the
 * axis. The closed form for that finite inlet separates the truncation
 * (-0.25 %) from the discretisation error (-0.29 % at 512 cells), which
 * must fall as dx^2: error ratio 256 -> 512 above 2.5 (4 for second order,
 * 2 for the first-order upwind scheme this replaced; measured 3.5), and the
 * Richardson extrapolation of 256 and 512 within 1e-3 of the closed form
 * (measured 5e-4). */
static void test_martin_rigid_cylinder(void **state) {
  (void)state;
  const double e0 = 1e13, load = 1000.0, eta = 0.1, v0 = 1.0;
  const double h_martin = 4.894 * eta * (0.5 * v0) * RADIUS / load;
  double a0 = hertz_a0(e0, load), lh = inlet_length(e0, load, eta, v0);
  double h_finite = martin_finite_inlet(eta, v0, load, -30.0 * lh);
  size_t grids[] = {128, 256, 512};
  double err_finite[3];
  printf("  inlet length %.4g m = %.1f a0; finite-inlet closed form / Martin - 1 = %+.4f\n", lh,
         lh / a0, h_finite / h_martin - 1.0);
  printf("  %6s %14s %14s %6s\n", "grid", "h/Martin-1", "h/finite-1", "iter");
  for (int k = 0; k < 3; k++) {
    size_t n = grids[k];
    /* node k0 on x = 0: x_min = -(k0 + 1/2) dx */
    size_t k0 = (size_t)(0.9375 * (double)n);
    double dx = 30.0 * lh / ((double)k0 + 0.5);
    double x_min = -30.0 * lh / a0, x_max = x_min + (double)n * dx / a0;
    vl_contact *c = make_wet(e0, load, eta, n, x_min, x_max);
    assert_true(fabs(vl_contact_a0(c) / a0 - 1.0) < 1e-12);
    vl_point pt = solve_one(c, v0);
    err_finite[k] = pt.u_min_m / h_finite - 1.0;
    printf("  %6zu %+14.6f %+14.6f %6ld\n", n, pt.u_min_m / h_martin - 1.0, err_finite[k],
           pt.iterations);
    /* a rigid symmetric gap: the film is thinnest on the axis */
    assert_true(fabs(pt.x_min_film_m) < 0.5 * dx);
    if (k == 2) assert_true(fabs(pt.u_min_m / h_martin - 1.0) < 1e-2);
    vl_contact_free(c);
  }
  double ratio = err_finite[1] / err_finite[2];
  double richardson = err_finite[2] + (err_finite[2] - err_finite[1]) / 3.0;
  printf("  discretisation error ratio 256->512: %.2f (second order: 4); Richardson "
         "extrapolation vs closed form: %+.2e\n",
         ratio, richardson);
  assert_true(ratio > 2.5);
  assert_true(fabs(richardson) < 1e-3);
}

/* ---- Soft EHL ------------------------------------------------------------
 * Rubber E0 = 3.6 MPa (elastic), R = 1 cm, eta = 0.1 Pa s. In Hamrock's
 * variables g_E = fN/sqrt(eta um E' R), um = v0/2, E' = 2 Er, the film is
 * 10 to 200 times thinner than the Hertz deformation a0^2/R here. */
#define SOFT_E0 3.6e6

static double soft_g(double load, double eta, double v0) {
  double er = SOFT_E0 / (1.0 - NU * NU);
  return load / sqrt(eta * 0.5 * v0 * 2.0 * er * RADIUS);
}

/* Hamrock's prefactor C in h_min fN/(eta um R) = C g_E^0.8. */
static double hamrock_c(double h, double load, double eta, double v0) {
  return h * load / (eta * 0.5 * v0 * RADIUS) / pow(soft_g(load, eta, v0), 0.8);
}

/* Exponents of h_min against eta v0 (fixed load, two decades of speed, by
 * continuation from high speed down) and against fN (fixed speed), and the
 * prefactor C, reported, not asserted (the definitions of E', um and the
 * load vary between sources). The soft limit has h ~ (eta v0)^0.6
 * fN^-0.2; at g_E = 10..200 C still falls slowly (the local power of g_E
 * is 0.75 at g_E = 10, 0.79 at 100), so the fits give 0.612 and -0.214:
 * the 0.03 allowed (the issue's) covers that approach, grid convergence of
 * the fits is below 0.005 (measured with 1024 cells). Same eta v0 with
 * eta and v0 swapped by a factor 10 must give the same film: the problem
 * depends on the product only (up to rounding: 1e-8). */
static void test_soft_ehl_exponents(void **state) {
  (void)state;
  const double eta = 0.1, load = 1000.0;
  enum { NV = 5 };
  double v[NV], h[2][NV], cpre[2][NV];
  size_t grids[2] = {256, 512};
  for (int i = 0; i < NV; i++)
    v[i] = 2.07 * pow(10.0, -0.5 * i); /* g_E 10 .. 100 */
  for (int k = 0; k < 2; k++) {
    vl_contact *c = make_wet(SOFT_E0, load, eta, grids[k], -3.0, 1.5);
    vl_point pts[NV];
    vl_sweep_stats st;
    vl_error err;
    assert_int_equal(vl_sweep_run(c, NV, v, NULL, pts, NULL, NULL, &st, &err), VL_OK);
    assert_int_equal((int)st.failed, 0);
    for (int i = 0; i < NV; i++) {
      assert_true(pts[i].converged);
      h[k][i] = pts[i].u_min_m;
      cpre[k][i] = hamrock_c(h[k][i], load, eta, v[i]);
    }
    printf("  grid %zu: speed sweep %.2f s, %ld Newton iterations, %zu sub-steps\n", grids[k],
           st.seconds, st.newton_iterations, st.substeps);
    vl_contact_free(c);
  }
  printf("  %8s %7s %12s %9s %9s %11s\n", "v0", "g_E", "h_min (m)", "C (256)", "C (512)",
         "local power");
  for (int i = 0; i < NV; i++) {
    char pw[32] = "";
    if (i > 0)
      snprintf(pw, sizeof pw, "%.3f",
               0.8 + log(cpre[1][i] / cpre[1][i - 1]) /
                         log(soft_g(load, eta, v[i]) / soft_g(load, eta, v[i - 1])));
    printf("  %8.4g %7.1f %12.5e %9.4f %9.4f %11s\n", v[i], soft_g(load, eta, v[i]), h[1][i],
           cpre[0][i], cpre[1][i], pw);
  }
  double s_speed = log_slope(NV, v, h[1]);
  printf("  h_min ~ (eta v0)^%.4f at 512 cells (%.4f at 256)\n", s_speed, log_slope(NV, v, h[0]));
  assert_true(fabs(s_speed - 0.6) < 0.03);

  /* eta and v0 enter as a product */
  vl_contact *c = make_wet(SOFT_E0, load, 10.0 * eta, 512, -3.0, 1.5);
  vl_point pt = solve_one(c, 0.1 * v[2]);
  printf("  eta x10, v0 /10: h_min relative change %.2e\n", pt.u_min_m / h[1][2] - 1.0);
  assert_true(fabs(pt.u_min_m / h[1][2] - 1.0) < 1e-8);
  vl_contact_free(c);

  /* load series at fixed speed, g_E 20 .. 200; the domain follows each
   * load's inlet length (8 of them ahead of the Hertz edge: inlet
   * truncation < 0.1 %), 512 cells */
  enum { NF = 3 };
  const double v0 = 0.0575;
  double f[NF] = {333.3, 1054.0, 3333.0}, hf[NF];
  printf("  %8s %7s %12s %9s %6s\n", "fN", "g_E", "h_min (m)", "C", "iter");
  for (int i = 0; i < NF; i++) {
    double a0 = hertz_a0(SOFT_E0, f[i]), lh = inlet_length(SOFT_E0, f[i], eta, v0);
    c = make_wet(SOFT_E0, f[i], eta, 512, -(1.0 + 8.0 * lh / a0), 1.3);
    pt = solve_one(c, v0);
    hf[i] = pt.u_min_m;
    printf("  %8.1f %7.1f %12.5e %9.4f %6ld\n", f[i], soft_g(f[i], eta, v0), hf[i],
           hamrock_c(hf[i], f[i], eta, v0), pt.iterations);
    vl_contact_free(c);
  }
  double s_load = log_slope(NF, f, hf);
  printf("  h_min ~ fN^%.4f\n", s_load);
  assert_true(fabs(s_load + 0.2) < 0.03);
}

/* ---- Invariants ----------------------------------------------------------
 * Fields of a converged solution: the face fluxes (as discretised) are one
 * constant along the pressurised film, to 1e-8 relative (the rows are
 * converged to 1e-9 of the pressure scale; measured 2e-11); in the
 * cavitated zone the film fraction carries the same flux; the load balance
 * holds to the solver tolerance; pf >= 0 (up to the tolerance), u > 0
 * everywhere. Soft case: the constriction (minimum film) sits on the outlet
 * side, x > 0, downstream of the pressure peak (docs/MODEL.md section 1). */
static void check_invariants(vl_contact *c, const vl_point *pt, double v0, bool soft) {
  size_t n = vl_contact_grid(c);
  double *buf = calloc(7 * n + 1, sizeof *buf);
  assert_non_null(buf);
  vl_fields f = {n, buf, buf + n, buf + 2 * n, buf + 3 * n, buf + 4 * n, buf + 5 * n, NULL};
  double *J = buf + 6 * n;
  vl_contact_fields(c, &f);
  assert_int_equal(vl_contact_face_fluxes(c, J, n + 1), n + 1);
  assert_true(pt->converged);
  assert_true(pt->load_error < 1e-8);
  assert_true(pt->fluid_load_fraction > 1.0 - 1e-8);
  double pmax = pt->peak_pressure_pa, jmin = INFINITY, jmax = -INFINITY;
  size_t faces = 0, last = 0;
  for (size_t i = 0; i < n; i++) {
    assert_true(f.p_f_pa[i] >= -1e-9 * pmax);
    assert_true(f.u_m[i] > 0.0);
    if (f.p_f_pa[i] > 1e-6 * pmax) last = i;
  }
  for (size_t k = 1; k < n; k++)
    if (f.p_f_pa[k - 1] > 1e-6 * pmax && f.p_f_pa[k] > 1e-6 * pmax) {
      jmin = fmin(jmin, J[k]);
      jmax = fmax(jmax, J[k]);
      faces++;
    }
  double spread = (jmax - jmin) / jmax, cav = 0.0;
  /* downstream of the rupture: theta v0 u/2 = J */
  for (size_t i = last + 2; i < n; i++)
    cav = fmax(cav, fabs(f.film_fraction[i] * 0.5 * v0 * f.u_m[i] / jmax - 1.0));
  printf("  %zu pressurised faces: flux spread %.2e; cavitated zone theta v0 u/2 vs J: %.2e; "
         "minimum film at x = %+.4f a0, peak at %+.4f a0\n",
         faces, spread, cav, pt->x_min_film_m / vl_contact_a0(c), pt->x_peak_m / vl_contact_a0(c));
  assert_true(faces > n / 4);
  assert_true(spread < 1e-8);
  assert_true(cav < 1e-6);
  if (soft) {
    assert_true(pt->x_min_film_m > 0.0);
    assert_true(pt->x_min_film_m > pt->x_peak_m);
  }
  free(buf);
}

static void test_invariants(void **state) {
  (void)state;
  vl_contact *c = make_wet(SOFT_E0, 1000.0, 0.1, 256, -3.0, 1.5);
  vl_point pt = solve_one(c, 0.23); /* g_E = 30 */
  check_invariants(c, &pt, 0.23, true);
  vl_contact_free(c);

  double e0 = 1e13, a0 = hertz_a0(e0, 1000.0), lh = inlet_length(e0, 1000.0, 0.1, 1.0);
  c = make_wet(e0, 1000.0, 0.1, 256, -30.0 * lh / a0, 2.0 * lh / a0);
  pt = solve_one(c, 1.0);
  check_invariants(c, &pt, 1.0, false);
  vl_contact_free(c);

  /* the analytic Jacobian of the smooth wet system against central finite
   * differences at a converged state (FD steps straddle the complementarity
   * kink at the rupture: 1e-5 relative; measured 5e-7) */
  c = make_wet(SOFT_E0, 1000.0, 0.1, 64, -3.0, 1.5);
  pt = solve_one(c, 0.23);
  double e = vl_contact_jacobian_check(c, 0.23);
  printf("  smooth wet Jacobian: max |J_fd - J|/max|J| = %.2e\n", e);
  assert_true(e >= 0.0 && e < 1e-5);
  vl_contact_free(c);
}

/* ---- Energy balance (docs/MODEL.md section 7) ---------------------------------
 * Smooth surfaces, elastic solid (no hysteresis): the power of the friction
 * force equals the viscous dissipation of the film,
 *   (mu_Rf + mu_Sf) fN v0 = \int [ theta eta v0^2/u + u^3/(12 eta) (dpf/dx)^2 ] dx,
 * theta the film fraction (1 in the full film; the cavitated zone carries
 * theta-weighted Couette shear on both sides). The dissipation here is a
 * face quadrature of the fields (Poiseuille part on the faces, pf = 0
 * half a cell beyond both ends), the friction the solver's node quadrature:
 * they differ by the discretisation only, O(dx^2). Measured (harmonic
 * face conductance, as the solver's): soft 4.1e-5 at 256 cells, 1.15e-5 at
 * 512 (ratio 3.6); rigid 2e-7. Asserted: 5e-4 at 256 and a drop by more
 * than 3 to 512 (second order: 4; first order would give 2). The wrong
 * Poiseuille sign in mu_Sf misses by tens of percent. */
static double energy_mismatch(vl_contact *c, const vl_point *pt, double v0, double eta,
                              double load) {
  size_t n = vl_contact_grid(c);
  double *buf = calloc(6 * n, sizeof *buf);
  assert_non_null(buf);
  vl_fields f = {n, buf, buf + n, buf + 2 * n, buf + 3 * n, buf + 4 * n, buf + 5 * n, NULL};
  vl_contact_fields(c, &f);
  double dx = f.x_m[1] - f.x_m[0], couette = 0.0, poiseuille = 0.0;
  for (size_t i = 0; i < n; i++)
    couette += f.film_fraction[i] * eta * v0 * v0 / f.u_m[i] * dx;
  for (size_t k = 0; k <= n; k++) {
    double pl = k > 0 ? f.p_f_pa[k - 1] : 0.0, pr = k < n ? f.p_f_pa[k] : 0.0;
    double ul = f.u_m[k > 0 ? k - 1 : 0], ur = f.u_m[k < n ? k : n - 1];
    double h = (k == 0 || k == n) ? 0.5 * dx : dx, g = (pr - pl) / h;
    /* harmonic mean of u^3: the two half-cells in series, as the solver's
     * face conductance (the arithmetic mean differs by O(dx^2)) */
    double gl = ul * ul * ul, gr = ur * ur * ur, u3 = 2.0 * gl * gr / (gl + gr);
    poiseuille += u3 / (12.0 * eta) * g * g * h;
  }
  free(buf);
  double power = (pt->mu_Rf + pt->mu_Sf) * load * v0;
  printf("  grid %4zu: friction power %.6e W/m, dissipation %.6e (Couette %.4e, Poiseuille "
         "%.4e): relative mismatch %.2e\n",
         n, power, couette + poiseuille, couette, poiseuille, power / (couette + poiseuille) - 1.0);
  return fabs(power / (couette + poiseuille) - 1.0);
}

static void test_energy_balance(void **state) {
  (void)state;
  double e[2];
  size_t grids[2] = {256, 512};
  for (int k = 0; k < 2; k++) {
    vl_contact *c = make_wet(SOFT_E0, 1000.0, 0.1, grids[k], -3.0, 1.5);
    vl_point pt = solve_one(c, 0.23);
    assert_true(fabs(pt.mu_Rc) < 1e-12 && pt.mu_Sc == 0.0); /* no solid contact */
    e[k] = energy_mismatch(c, &pt, 0.23, 0.1, 1000.0);
    vl_contact_free(c);
  }
  assert_true(e[0] < 5e-4);
  assert_true(e[1] < e[0] / 3.0); /* O(dx^2): 4 asymptotically, first order 2 */

  double e0 = 1e13, a0 = hertz_a0(e0, 1000.0), lh = inlet_length(e0, 1000.0, 0.1, 1.0);
  vl_contact *c = make_wet(e0, 1000.0, 0.1, 256, -30.0 * lh / a0, 2.0 * lh / a0);
  vl_point pt = solve_one(c, 1.0);
  assert_true(energy_mismatch(c, &pt, 1.0, 0.1, 1000.0) < 5e-4);
  vl_contact_free(c);
}

/* ---- Energy balance of a rough film with persson-emt factors -------------
 * docs/FLOW_FACTORS.md: with phi_s from the reciprocity identity
 * phi_s = x (1 - phi_fp), the balance holds for rough films too, the local
 * dissipation being
 *   theta (phi_f + phi_fs) eta v0^2/u + (u^3 phi_p/(12 eta)) (dpf/dx)^2.
 * Elastic solid (no hysteresis), sigma_s = 0 (no dissipation in the real
 * contact area): the power of the friction force, (mu_Rc + mu_Rf + mu_Sf)
 * fN v0, equals the film's dissipation. The seed's paper surface (h_rms
 * 3 um) under the fig05 contact, uniform cells on [-3, 1.6] a0, at speeds
 * where the film carries 40-100 % of the load and solid contact remains.
 * The Poiseuille part is a face quadrature with the solver's face
 * conductance (the mean of the nodes' u^3 phi_p); the difference is the
 * discretisation's, O(dx^2): measured 0.8-2.9e-5 at 256 cells and
 * 1.5-5.3e-6 at 512 (ratio 4.4-5.4) over v0 eta = 1e-8 ... 1 Pa m (fluid
 * load 0 ... 100 %); asserted 1e-4 at 256 and a fall by more than 3. */
static double rough_energy_mismatch(vl_contact *c, const vl_point *pt, const vl_emt_table *tab,
                                    double hrms, double v0, double eta, double load) {
  size_t n = vl_contact_grid(c);
  double *buf = calloc(6 * n, sizeof *buf);
  assert_non_null(buf);
  vl_fields f = {n, buf, buf + n, buf + 2 * n, buf + 3 * n, buf + 4 * n, buf + 5 * n, NULL};
  vl_contact_fields(c, &f);
  double dx = f.x_m[1] - f.x_m[0], couette = 0.0, poiseuille = 0.0;
  double *g = calloc(n, sizeof *g);
  assert_non_null(g);
  for (size_t i = 0; i < n; i++) {
    vl_flow_factor_values v;
    vl_flow_factors_eval_table(VL_FLOW_FACTORS_PERSSON_EMT, tab, f.u_m[i], hrms, &v, NULL);
    couette += f.film_fraction[i] * (v.phi_f + v.phi_fs) * eta * v0 * v0 / f.u_m[i] * dx;
    g[i] = f.u_m[i] * f.u_m[i] * f.u_m[i] * v.phi_p;
  }
  for (size_t k = 0; k <= n; k++) {
    double pl = k > 0 ? f.p_f_pa[k - 1] : 0.0, pr = k < n ? f.p_f_pa[k] : 0.0;
    double h = (k == 0 || k == n) ? 0.5 * dx : dx, grad = (pr - pl) / h;
    double gf = 0.5 * (g[k > 0 ? k - 1 : 0] + g[k < n ? k : n - 1]);
    poiseuille += gf / (12.0 * eta) * grad * grad * h;
  }
  free(g);
  free(buf);
  double power = (pt->mu_Rc + pt->mu_Rf + pt->mu_Sf) * load * v0;
  printf("  rough grid %4zu, v0 %g: friction power %.6e W/m, dissipation %.6e (Couette %.4e, "
         "Poiseuille %.4e), fluid load %.2f: relative mismatch %.2e\n",
         n, v0, power, couette + poiseuille, couette, poiseuille, pt->fluid_load_fraction,
         power / (couette + poiseuille) - 1.0);
  return fabs(power / (couette + poiseuille) - 1.0);
}

typedef struct {
  const vl_emt_table *flow;
  double hrms, eta, load, *e;
} rough_energy_ctx;

/* At each point of the sweep (the contact holds its solution). */
static void rough_energy_at(void *user, size_t i, size_t total, const vl_point *pt,
                            const vl_contact *c) {
  (void)total;
  rough_energy_ctx *x = user;
  if (!pt->converged) fail_msg("point %zu (v0 %g) did not converge", i, pt->v0_m_s);
  x->e[i] =
      rough_energy_mismatch((vl_contact *)c, pt, x->flow, x->hrms, pt->v0_m_s, x->eta, x->load);
}

static void test_energy_balance_rough_emt(void **state) {
  (void)state;
  const double hrms = 3e-6, eta = 1e-4;
  vl_psd psd;
  vl_persson *tab = vl_test_paper_surface(hrms, &psd);
  vl_emt_table *flow = NULL;
  vl_error err;
  if (vl_emt_table_build(&psd, VL_FILM_CUTOFF_DEFAULT_M, 0, &flow, &err) != VL_OK)
    fail_msg("%s", err.msg);
  /* v0 eta 1e-8 .. 1 Pa m: from the boundary regime, where the sweep can
   * start, through mixed lubrication to a full film */
  const double speeds[] = {1e-4, 1e-3, 1e-2, 1e-1, 1e0, 1e1, 1e2, 1e3, 1e4};
  const size_t ns = sizeof speeds / sizeof *speeds;
  double e[2][9];
  size_t grids[2] = {256, 512};
  for (int k = 0; k < 2; k++) {
    vl_contact_config cfg;
    vl_test_fig05_config(&cfg, tab, eta, grids[k], -3.0);
    cfg.rubber.e_inf_pa = vl_prony_e0(&cfg.rubber); /* elastic, the relaxed modulus */
    cfg.rubber.n_terms = 0;
    cfg.sigma_s_pa = 0.0;
    cfg.flow_factors = VL_FLOW_FACTORS_PERSSON_EMT;
    cfg.flow_table = flow;
    vl_contact *c = NULL;
    if (vl_contact_create(&cfg, &c, &err) != VL_OK) fail_msg("%s", err.msg);
    vl_point pts[9];
    rough_energy_ctx ctx = {flow, hrms, eta, cfg.load_n_per_m, e[k]};
    assert_int_equal(vl_sweep_run(c, ns, speeds, NULL, pts, rough_energy_at, &ctx, NULL, &err),
                     VL_OK);
    for (size_t i = 0; i < ns; i++)
      assert_true(pts[i].converged && pts[i].mu_Sc == 0.0);
    if (k == 0) {
      /* the analytic Jacobian with the table's derivatives against central
       * differences, per block of rows, at the full film of the last point.
       * Measured 2.5e-7, 8.1e-7, 2.2e-6; patir-cheng's closed-form
       * derivatives give 2.5e-7, 8.1e-7, 2.4e-6 on the same contact, so the
       * load row's level is the differences' own error, not the table's */
      double rel[3], j = vl_contact_jacobian_check_blocks(c, speeds[ns - 1], rel);
      printf("  persson-emt Jacobian: contact rows %.2e, Reynolds rows %.2e, load %.2e\n", rel[0],
             rel[1], rel[2]);
      assert_true(j >= 0.0 && rel[0] < 1e-6 && rel[1] < 2e-6 && rel[2] < 1e-5);
    }
    vl_contact_free(c);
  }
  for (size_t i = 0; i < ns; i++) {
    assert_true(e[0][i] < 1e-4);
    assert_true(e[1][i] < e[0][i] / 3.0);
  }
  vl_emt_table_free(flow);
  vl_persson_free(tab);
  vl_psd_free(&psd);
}

/* ---- Viscoelastic smooth film: the dry limit (issue 5) ------------------
 * The model rubber (E0 3.6 MPa, Einf/E0 = 10, tau 0.1 s), no roughness, at
 * v0 tau/a0 = 0.1, 1, 10. As eta -> 0 the film vanishes and the fluid
 * pressure becomes the dry contact pressure, so the rolling friction
 * mu_R = mu_Rc + mu_Rf (mu_Rc = 0: a smooth film has no solid contact)
 * must tend to the dry solver's mu_Rc (itself validated against Hunter's
 * exact solution in test_validation_dry). That is the comparison: the
 * viscous shear mu_Sf = eta v0 \int dx/u / fN + Poiseuille part vanishes
 * too, but only as the film allows (h ~ (eta v0)^0.6 for a soft film, so
 * mu_Sf ~ (eta v0)^0.4: still 1 % of mu at eta = 1e-3, measured), so the
 * total mu approaches the dry value much more slowly and is reported, not
 * asserted. Same grid and domain for both solvers, so the discretisation
 * is common. Path: a fresh solve at eta = 1e-2 Pa s, then continuation in
 * viscosity to 1e-3, 1e-4, 1e-5. Asserted: |mu_R/mu_dry - 1| falls with
 * eta at every step and is below 1e-3 (the 0.1 %) at 1e-5 Pa s
 * (measured 2.0e-5, 1.8e-5, 4.9e-4 at v0 tau/a0 = 0.1, 1, 10; the error
 * falls as about eta^0.35-0.6 between 1e-3 and 1e-5). Sign convention (docs/MODEL.md section 1)
 * at eta = 1e-2: the constriction (minimum film) on the outlet side and
 * mu_Rf > 0. */
static void test_viscoelastic_dry_limit(void **state) {
  (void)state;
  const double de[3] = {0.1, 1.0, 10.0}, tau = 0.1;
  for (int k = 0; k < 3; k++) {
    vl_contact_config cfg;
    vl_contact_config_defaults(&cfg);
    cfg.rubber = vl_prony_single(SOFT_E0, 10.0, tau, NU);
    cfg.radius_m = RADIUS;
    cfg.load_n_per_m = 1000.0;
    cfg.grid = 256;
    cfg.x_min_a0 = -2.5, cfg.x_max_a0 = 1.5;
    vl_contact *dry = NULL, *wet = NULL;
    vl_error err;
    assert_int_equal(vl_contact_create(&cfg, &dry, &err), VL_OK);
    double v0 = de[k] * vl_contact_a0(dry) / tau;
    vl_point pd = solve_one(dry, v0);
    cfg.eta_pa_s = 1e-2;
    assert_int_equal(vl_contact_create(&cfg, &wet, &err), VL_OK);
    vl_point pw = solve_one(wet, v0);
    printf("  v0 tau/a0 = %g: dry mu_Rc = %.6f; eta 1e-2: minimum film %.3g m at x = %+.3f a0, "
           "mu_Rf = %.6f (%ld iterations, fresh)\n",
           de[k], pd.mu_Rc, pw.u_min_m, pw.x_min_film_m / vl_contact_a0(wet), pw.mu_Rf,
           pw.iterations);
    assert_true(pw.x_min_film_m > 0.0);
    assert_true(pw.mu_Rf > 0.0);
    double prev = fabs(pw.mu_Rc + pw.mu_Rf - pd.mu_Rc) / pd.mu_Rc;
    printf("    %8s %12s %12s %10s %5s\n", "eta", "mu_R/dry-1", "mu/dry-1", "mu_Sf", "iter");
    printf("    %8.0e %+12.3e %+12.3e %10.3e %5ld\n", 1e-2, prev, pw.mu / pd.mu_Rc - 1.0, pw.mu_Sf,
           pw.iterations);
    for (double eta = 1e-3; eta > 0.5e-5; eta *= 0.1) {
      if (vl_contact_solve_viscosity(wet, v0, eta, 10.0, &pw, &err) != VL_OK)
        fail_msg("eta %g: %s", eta, err.msg);
      double e = fabs(pw.mu_Rc + pw.mu_Rf - pd.mu_Rc) / pd.mu_Rc;
      printf("    %8.0e %+12.3e %+12.3e %10.3e %5ld\n", eta, (pw.mu_Rc + pw.mu_Rf) / pd.mu_Rc - 1.0,
             pw.mu / pd.mu_Rc - 1.0, pw.mu_Sf, pw.iterations);
      assert_true(e < prev);
      if (eta < 2e-5) assert_true(e < 1e-3);
      prev = e;
    }
    vl_contact_free(dry);
    vl_contact_free(wet);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_martin_rigid_cylinder), cmocka_unit_test(test_invariants),
      cmocka_unit_test(test_energy_balance),        cmocka_unit_test(test_energy_balance_rough_emt),
      cmocka_unit_test(test_soft_ehl_exponents),    cmocka_unit_test(test_viscoelastic_dry_limit),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
