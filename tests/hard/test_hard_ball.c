/* Hard-case matrix, point contacts (issue 35): the dry smooth ball and
 * ellipsoid, and the lubricated smooth ball (soft EHL), through the public
 * API (vl_point_contact_sweep on the corner's own cells, each point with
 * its error estimate; docs/POINT_CONTACT.md sections 5 and 9).
 *
 *   dry:  elastic or Einf/E0 up to 1e4 with 1-12 Prony terms over up to
 *         12 decades, radii 0.5 mm ... 5 cm (an ellipsoid: Ry/Rx 0.1 ...
 *         10), loads 0.01 ... 100 N, a shear stress in the contact or none,
 *         speeds 1e-9 ... 1e3 m/s;
 *   wet:  a ball in a fluid of 1e-3 ... 1 Pa s, elastic or viscoelastic,
 *         the same radii and loads, speeds from where Hamrock and Dowson's
 *         minimum film is 10 nm up to 10 m/s.
 *
 * A Latin hypercube (fixed seed) per family, as tests/hard/test_hard_dry.c
 * and test_hard_wet.c do for the line contact. Every point is checked
 * (ball_check_point, ball_check_fields): converged, or reported failed
 * with converged = false and zeros (never NaN); every value finite; the
 * load balance; the friction's parts adding up and their signs; the error
 * estimate finite, or its absence said; the fields finite and the
 * complementarity's signs. Counts and the stated minimum convergence rates
 * are printed at the end.
 *
 * Cost: 37 s CPU for the 280 points (dry balls 2 s, ellipsoids 4 s,
 * lubricated balls 33 s): coarse cells (BALL_DRY_CELLS, BALL_WET_CELLS),
 * no refinement. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "hard_util.h"
#include "vl_test_scenes.h"
#include "vl_test_util.h"

#include <complex.h>
#include <float.h>

#include "viscolube/point_contact.h"

/* The corners' cells: 10 across the relaxed contact's (shorter)
 * semi-axis (325 cells on a ball), the lubricated ball's rim cells
 * a0/12.5 (0.08 a0: about 300 cells). A viscoelastic contact shrinks with
 * speed, down to (E0/Einf)^(1/3) of the relaxed one: on these cells it
 * may span a single cell ("fewer than 8 cells across the contact"), a
 * corner of its own. The automatic numerics (20 cells across the planned
 * contact, up to 4000 cells) cost 10-100 s per corner of 5 speeds at
 * Einf/E0 >= 1e3 (measured: docs/POINT_CONTACT.md section 5). A
 * lubricated ball's cells follow its contact's size at each speed
 * (ball_wet_plan). */
#define BALL_DRY_CELLS 10.0
#define BALL_WET_CELLS 12.5

/* ------------------------------------------------------------ a family */

typedef struct {
  const char *name;
  double min_rate;      /* stated minimum share of converged points */
  double min_real_rate; /* the same of the realistic points (ball_realistic) */
  size_t corners, points, converged, failed, flagged;
  size_t met, above_target, no_estimate; /* converged points by their estimate */
  size_t real_points, real_converged;    /* realistic points (ball_realistic) */
  double worst_load_error, worst_residual, worst_neg_pressure, worst_jump, seconds;
  size_t violations;
  char fails[HARD_MAX_FAILS][400];
  size_t n_fails;
} ball_family;

typedef struct {
  char label[400];
  vl_point_contact_config cfg;
  ball_family *fam;
} ball_ctx;

static void ball_violation(ball_family *f, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static void ball_violation(ball_family *f, const char *fmt, ...) {
  if (f->violations++ < 40) {
    va_list ap;
    va_start(ap, fmt);
    printf("  VIOLATION (%s): ", f->name);
    vprintf(fmt, ap);
    printf("\n");
    va_end(ap);
  }
}

static void ball_finite(const ball_ctx *x, double v, const char *what, double v0) {
  if (!isfinite(v))
    ball_violation(x->fam, "%s = %g not finite at v0 = %g m/s in %s", what, v, v0, x->label);
}

/* The relaxed Hertz scales of cfg: a0 = (3 W Re/(4 Er0))^(1/3) (m). */
static double ball_a0(const vl_point_contact_config *cfg) {
  double er0 = vl_prony_e0(&cfg->rubber) * vl_prony_reduced_factor(&cfg->rubber);
  return cbrt(0.75 * cfg->load_n * sqrt(cfg->radius_x_m * cfg->radius_y_m) / er0);
}

/* Hamrock and Dowson's minimum film of a ball (isoviscous-elastic, k = 1;
 * docs/POINT_CONTACT.md section 9): h = R 7.43 U^0.65 W^-0.21 (1 - 0.85
 * e^-0.31), U = eta (v0/2)/(E' R), W = load/(E' R^2), E' = 2 E0/(1 - nu^2)
 * (the relaxed modulus: a stiffer rubber at speed makes the film thinner
 * by (E/E0)^0.44). The a priori film of a lubricated corner. */
static double ball_film_hd(const vl_point_contact_config *cfg, double v0) {
  double ep = 2.0 * vl_prony_e0(&cfg->rubber) * vl_prony_reduced_factor(&cfg->rubber);
  double R = cfg->radius_x_m, U = cfg->eta_pa_s * 0.5 * v0 / (ep * R),
         W = cfg->load_n / (ep * R * R);
  return R * 7.43 * pow(U, 0.65) * pow(W, -0.21) * (1.0 - 0.85 * exp(-0.31));
}

/* A realistic operating point (README, "Hard cases", as the line
 * contact's hard_realistic): speed 1e-9 ... 10 m/s, a relaxed contact
 * a0 <= 0.2 R (the half-space of the model), and lubricated: a film of at
 * least 10 nm (the continuum film; Hamrock and Dowson's estimate). */
static bool ball_realistic(const vl_point_contact_config *cfg, double v0) {
  if (v0 < 1e-9 || v0 > 10.0) return false;
  if (ball_a0(cfg) > 0.2 * fmin(cfg->radius_x_m, cfg->radius_y_m)) return false;
  return !(cfg->eta_pa_s > 0.0) || ball_film_hd(cfg, v0) >= 1e-8;
}

/* The fields of a converged point (the solved half y >= 0):
 * - finite, on the domain;
 * - dry: p_c >= -1e-8 p_ref (the rows min(P, U) = 0, or Fischer-Burmeister
 *   FB(P, U), solved to the max-norm tolerance 1e-9 in units of p0: |FB|
 *   <= tol implies P >= -tol; p_ref = max(p0, peak)), u >= 0 (reported as
 *   max(u, 0)), p_f = 0;
 * - lubricated: p_f >= -1e-8 p_ref (Reynolds' cavitation by
 *   Fischer-Burmeister, the same bound), p_c = 0 and u > 0 (smooth solids
 *   apart: the film stays open). */
static void ball_check_fields(ball_ctx *x, const vl_point_contact *c, const vl_point *pt) {
  size_t n = vl_point_contact_cells(c);
  double *b = malloc(5 * n * sizeof *b);
  assert_non_null(b);
  vl_fields2d f = {b, b + n, b + 2 * n, b + 3 * n, b + 4 * n};
  vl_point_contact_fields(c, &f);
  double pref = fmax(vl_point_contact_p0(c), pt->peak_pressure_pa), v0 = pt->v0_m_s;
  bool wet = x->cfg.eta_pa_s > 0.0, rough = x->cfg.roughness != NULL;
  size_t bad = 0;
  for (size_t i = 0; i < n; i++) {
    if (!(isfinite(f.x_m[i]) && isfinite(f.y_m[i]) && isfinite(f.p_c_pa[i]) && isfinite(f.u_m[i]) &&
          isfinite(f.p_f_pa[i]) && f.y_m[i] >= 0.0)) {
      bad++;
      continue;
    }
    double lowest = wet ? f.p_f_pa[i] : f.p_c_pa[i];
    if (rough) lowest = fmin(lowest, f.p_c_pa[i]); /* both pressures (rough) */
    double neg = -lowest / pref;
    x->fam->worst_neg_pressure = fmax(x->fam->worst_neg_pressure, neg);
    bool full = strstr(pt->warnings, "below the Persson table") != NULL; /* u <= 0 said */
    if (neg > HARD_PNEG || (f.u_m[i] < 0.0 && !full)) bad++;
    if (rough ? (!wet && f.p_f_pa[i] != 0.0)
        : wet ? (f.p_c_pa[i] != 0.0 || !(f.u_m[i] > 0.0))
              : f.p_f_pa[i] != 0.0)
      bad++;
  }
  if (bad)
    ball_violation(x->fam, "%zu cells with a non-finite or out-of-sign field at v0 = %g m/s in %s",
                   bad, v0, x->label);
  free(b);
}

static void ball_on_point(void *user, size_t i, size_t total, const vl_point *pt,
                          const vl_point_contact *c) {
  (void)i, (void)total;
  if (pt->converged) {
    if (!c)
      ball_violation(((ball_ctx *)user)->fam, "no contact for a converged point at v0 = %g",
                     pt->v0_m_s);
    else
      ball_check_fields(user, c, pt);
  }
}

/* A failed point: an explicit flag (converged = false), zeros, a finite
 * residual (or DBL_MAX when KINSOL's was not), no estimate. */
static void ball_check_failed(ball_ctx *x, const vl_point *pt) {
  if (!(pt->mu == 0.0 && pt->mu_Rc == 0.0 && pt->mu_Rf == 0.0 && pt->mu_Sc == 0.0 &&
        pt->mu_Sf == 0.0 && pt->iterations >= 0 && pt->residual >= 0.0 &&
        pt->accuracy == VL_ACCURACY_UNCHECKED && pt->ball.contact_area_m2 == 0.0))
    ball_violation(x->fam, "failed point not cleanly flagged at v0 = %g in %s", pt->v0_m_s,
                   x->label);
}

/* The error estimate and the accuracy it gives against the target: a
 * finite estimate >= 0, met or above the target with the warning saying
 * so; or none (NAN), said by accuracy and warning. */
static void ball_check_estimate(ball_ctx *x, const vl_point *pt, double target) {
  ball_family *f = x->fam;
  double e = pt->error_estimate;
  bool warned_above = strstr(pt->warnings, "above the target") != NULL;
  bool ok;
  if (isnan(e)) {
    f->no_estimate++;
    ok = pt->accuracy == VL_ACCURACY_NO_ESTIMATE && strstr(pt->warnings, "no error estimate");
  } else if (e > target) {
    f->above_target++;
    ok = e < INFINITY && pt->accuracy == VL_ACCURACY_ABOVE_TARGET && warned_above;
  } else {
    f->met++;
    ok = e >= 0.0 && pt->accuracy == VL_ACCURACY_MET && !warned_above;
  }
  if (!ok)
    ball_violation(f, "estimate %g, accuracy %d, warnings '%s' disagree at v0 = %g in %s", e,
                   pt->accuracy, pt->warnings, pt->v0_m_s, x->label);
}

/* A converged point. Bounds:
 * - residual within the tolerance; the load row (part of the residual)
 *   within 1e-8 (10x for the sum's rounding);
 * - mu = mu_Rc + mu_Rf + mu_Sc + mu_Sf, mu_Sf = Couette + Poiseuille
 *   (1e-12);
 * - dry: no fluid terms; mu_Sc = sigma_s A/W (A the contact area); a
 *   contact of at least one cell, inside the domain (4 x_half y_max a0^2);
 *   mu_Rc = -x_c/Rx is the rubber's hysteresis: 0 for an elastic one (the
 *   grid is symmetric about x = 0: |x_c| < 1e-9 a0), else >= -h/Rx (the
 *   centroid within a cell h of the inlet side);
 * - lubricated: no contact terms, the fluid carries the load, the film
 *   open (u_min > 0, u_min <= the film at the centroid), the Couette shear
 *   resisting the motion (> 0);
 * - rough: the fluid's share in [0, 1] (0 when dry), mu_Sc = sigma_s A/W
 *   (A the real contact area), the mean separation positive unless the
 *   point warns that it lies below Persson's table (full contact), the
 *   Couette shear resisting the motion when lubricated. */
static void ball_check_converged(ball_ctx *x, const vl_point *pt) {
  ball_family *f = x->fam;
  const vl_point_contact_config *cfg = &x->cfg;
  double v0 = pt->v0_m_s, W = cfg->load_n;
  f->worst_load_error = fmax(f->worst_load_error, pt->load_error);
  f->worst_residual = fmax(f->worst_residual, pt->residual);
  if (!(pt->load_error <= HARD_LOAD_TOL) || !(pt->residual <= VL_BALL_TOLERANCE))
    ball_violation(f, "load error %g, residual %g at v0 = %g in %s", pt->load_error, pt->residual,
                   v0, x->label);
  double sum = pt->mu_Rc + pt->mu_Rf + pt->mu_Sc + pt->mu_Sf;
  if (!(fabs(pt->mu - sum) <= 1e-12 * (1.0 + fabs(pt->mu))) ||
      !(fabs(pt->mu_Sf - pt->mu_Sf_couette - pt->mu_Sf_poiseuille) <=
        1e-12 * (1.0 + fabs(pt->mu_Sf))))
    ball_violation(f, "friction parts do not add up at v0 = %g in %s", v0, x->label);
  int geometry = cfg->radius_x_m == cfg->radius_y_m ? VL_GEOMETRY_BALL : VL_GEOMETRY_ELLIPSOID;
  if (pt->ball.geometry != geometry)
    ball_violation(f, "geometry %d at v0 = %g in %s", pt->ball.geometry, v0, x->label);
  double a0 = ball_a0(cfg);
  if (cfg->roughness) {
    bool wet = cfg->eta_pa_s > 0.0;
    double share = pt->fluid_load_fraction, area = pt->ball.contact_area_m2;
    if (!(share >= 0.0 && share <= 1.0 + 1e-9) || (!wet && share != 0.0) || !(area >= 0.0) ||
        !(fabs(pt->mu_Sc - cfg->sigma_s_pa * area / W) <= 1e-12 * (1.0 + pt->mu_Sc)) ||
        (wet && !(pt->mu_Sf_couette > 0.0)) ||
        !(pt->u_min_over_h_rms > 0.0 || strstr(pt->warnings, "below the Persson table")))
      ball_violation(f,
                     "rough point out of range (load share %g, area %g m^2, mu_Sc %g, Couette "
                     "%g, u_min/h_rms %g) at v0 = %g in %s",
                     share, area, pt->mu_Sc, pt->mu_Sf_couette, pt->u_min_over_h_rms, v0, x->label);
    return;
  }
  if (cfg->eta_pa_s > 0.0) {
    if (pt->mu_Rc != 0.0 || pt->mu_Sc != 0.0 || pt->fluid_load_fraction != 1.0 ||
        !(pt->u_min_m > 0.0) || !(pt->u_min_m <= pt->u_central_m * (1.0 + 1e-12)) ||
        !(pt->mu_Sf_couette > 0.0) || pt->regime != VL_REGIME_HYDRODYNAMIC)
      ball_violation(f,
                     "lubricated point out of range (mu_Rc %g mu_Sc %g load share %g u_min %g "
                     "u_c %g Couette %g) at v0 = %g in %s",
                     pt->mu_Rc, pt->mu_Sc, pt->fluid_load_fraction, pt->u_min_m, pt->u_central_m,
                     pt->mu_Sf_couette, v0, x->label);
    return;
  }
  const vl_ball_result *b = &pt->ball;
  double h = a0 / b->cells_per_a0;
  double domain = 4.0 * b->x_half_a0 * b->y_max_a0 * a0 * a0;
  if (pt->mu_Rf != 0.0 || pt->mu_Sf != 0.0 || pt->fluid_load_fraction != 0.0 ||
      pt->regime != VL_REGIME_DRY || b->cells_in_contact < 1 || !(b->contact_area_m2 > 0.0) ||
      b->contact_area_m2 > domain * (1.0 + 1e-12) || !(pt->peak_pressure_pa > 0.0) ||
      !(fabs(pt->mu_Sc - cfg->sigma_s_pa * b->contact_area_m2 / W) <= 1e-12 * (1.0 + pt->mu_Sc)))
    ball_violation(f,
                   "dry point out of range (mu_Rf %g mu_Sf %g area %g of %g m^2, %zu cells, "
                   "peak %g, mu_Sc %g) at v0 = %g in %s",
                   pt->mu_Rf, pt->mu_Sf, b->contact_area_m2, domain, b->cells_in_contact,
                   pt->peak_pressure_pa, pt->mu_Sc, v0, x->label);
  bool elastic = cfg->rubber.n_terms == 0;
  if (elastic ? !(fabs(pt->x_centroid_m) < 1e-9 * a0) : pt->mu_Rc < -h / cfg->radius_x_m)
    ball_violation(f, "dry mu_Rc = %g (centroid %g m, cell %g m) at v0 = %g in %s", pt->mu_Rc,
                   pt->x_centroid_m, h, v0, x->label);
}

/* One point: finite values, then failed or converged. */
static void ball_check_point(ball_ctx *x, vl_point *pt, double target) {
  double v0 = pt->v0_m_s;
  const vl_ball_result *b = &pt->ball;
  const double vals[] = {pt->mu,
                         pt->mu_Rc,
                         pt->mu_Rf,
                         pt->mu_Sc,
                         pt->mu_Sf,
                         pt->mu_Sf_couette,
                         pt->mu_Sf_poiseuille,
                         pt->u_min_m,
                         pt->u_central_m,
                         pt->x_centroid_m,
                         pt->contact_width_m,
                         pt->fluid_load_fraction,
                         pt->load_error,
                         pt->E_wH_pa,
                         pt->a_H_m,
                         pt->peak_pressure_pa,
                         pt->x_peak_m,
                         pt->x_min_film_m,
                         pt->residual,
                         pt->eps_f_min,
                         b->contact_area_m2,
                         b->contact_length_m,
                         b->contact_breadth_m,
                         b->y_min_film_m,
                         b->y_peak_m,
                         b->cells_per_a0,
                         b->x_half_a0,
                         b->y_max_a0};
  for (size_t k = 0; k < sizeof vals / sizeof vals[0]; k++) {
    char what[32];
    snprintf(what, sizeof what, "value %zu", k);
    ball_finite(x, vals[k], what, v0);
  }
  size_t len = strnlen(pt->warnings, VL_WARN_MAX);
  if (len >= VL_WARN_MAX || strpbrk(pt->warnings, ",\"\n"))
    ball_violation(x->fam, "warnings not terminated or with a comma or quote in %s", x->label);
  if (!pt->converged) {
    ball_check_failed(x, pt);
    return;
  }
  if (pt->warnings[0]) x->fam->flagged++;
  ball_check_converged(x, pt);
  ball_check_estimate(x, pt, target);
}

/* Neighbouring speeds (as the line contact's hard_run_corner): no part of
 * the model grows or decays faster than v0^2 (the compliance of a strong
 * Prony term in its transition), so |log10(mu_b/mu_a)| <= 2 |log10(v_b/
 * v_a)| + log10 2, mu floored at 1e-4. */
static void ball_check_jumps(ball_ctx *x, size_t n, const double *v, const vl_point *pt) {
  size_t last = n;
  for (size_t i = 0; i < n; i++) {
    if (!pt[i].converged) continue;
    if (last < n) {
      double j =
          fabs(log10((fabs(pt[i].mu) + HARD_MU_FLOOR) / (fabs(pt[last].mu) + HARD_MU_FLOOR)));
      double bound = HARD_JUMP_SLOPE * fabs(log10(v[i] / v[last])) + HARD_JUMP_SLACK;
      x->fam->worst_jump = fmax(x->fam->worst_jump, j / bound);
      if (j > bound)
        ball_violation(x->fam, "mu jumps from %g to %g between v0 = %g and %g m/s in %s",
                       pt[last].mu, pt[i].mu, v[last], v[i], x->label);
    }
    last = i;
  }
}

/* A lubricated ball's point on its own cells: the unit of its zones the
 * contact's size at v0 (Hertz with |Er(v0/a)|, the fixed point the
 * automatic numerics plan with, docs/POINT_CONTACT.md section 5), rim
 * cells of 1/BALL_WET_CELLS of it. (The relaxed unit for every speed left
 * a glassy contact, 9x smaller, on a grid for the relaxed one: mu jumped
 * 50x between 2.4 and 10 m/s.) */
static void ball_wet_plan(const vl_point_contact_config *base, double v0,
                          vl_point_contact_config *cfg) {
  *cfg = *base;
  double red = vl_prony_reduced_factor(&base->rubber), er0 = vl_prony_e0(&base->rubber) * red;
  double a0 = ball_a0(base), s = 1.0;
  for (int it = 0; it < 30 && base->rubber.n_terms > 0; it++)
    s = cbrt(er0 / (cabs(vl_prony_modulus(&base->rubber, v0 / (s * a0))) * red));
  cfg->y_max_a0 = cfg->x_half_a0 = VL_BALL_DOMAIN_A0 * s;
  cfg->cells_per_a0 = BALL_WET_CELLS / s;
}

/* Runs one corner: the sweep over v[0..n-1] on cfg's own cells
 * (keep_numerics: every point still gets its estimate on cells twice as
 * wide; a lubricated ball point by point on cells planned for it), every
 * point checked. */
static void ball_run_corner(ball_family *fam, const char *label, const vl_point_contact_config *cfg,
                            size_t n, const double *v) {
  ball_ctx x;
  memset(&x, 0, sizeof x);
  snprintf(x.label, sizeof x.label, "%s", label);
  x.cfg = *cfg;
  x.fam = fam;
  vl_auto_options opt = {VL_TARGET_ERROR_DEFAULT, 0, true};
  vl_point *pt = calloc(n, sizeof *pt);
  assert_non_null(pt);
  vl_sweep_stats ss = {0}, one;
  vl_error err;
  struct timespec t0, t1;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  vl_status st = VL_OK;
  if (cfg->eta_pa_s > 0.0 || cfg->roughness) {
    for (size_t i = 0; i < n && st == VL_OK; i++) {
      ball_wet_plan(cfg, v[i], &x.cfg);
      st = vl_point_contact_sweep(&x.cfg, &opt, 1, v + i, pt + i, ball_on_point, &x, &one, &err);
      ss.converged += one.converged, ss.failed += one.failed;
      ss.newton_iterations += one.newton_iterations;
    }
    x.cfg = *cfg;
  } else {
    st = vl_point_contact_sweep(cfg, &opt, n, v, pt, ball_on_point, &x, &ss, &err);
  }
  clock_gettime(CLOCK_MONOTONIC, &t1);
  double secs = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
  fam->seconds += secs;
  if (st != VL_OK) fail_msg("sweep returned %d (%s) for %s", st, err.msg, label);
  assert_int_equal(ss.converged + ss.failed, n);
  if (getenv("VL_HARD_VERBOSE"))
    printf("  corner %3zu: %zu/%zu converged, %ld Newton iterations, %.2f s | %s\n", fam->corners,
           ss.converged, n, ss.newton_iterations, secs, label);
  fam->corners++;
  size_t nfail = 0;
  for (size_t i = 0; i < n; i++) {
    assert_true(pt[i].v0_m_s == v[i]); /* every requested speed is reported */
    ball_check_point(&x, &pt[i], opt.target_error);
    fam->points++;
    if (pt[i].converged)
      fam->converged++;
    else
      fam->failed++, nfail++;
    if (ball_realistic(cfg, v[i])) {
      fam->real_points++;
      if (pt[i].converged) fam->real_converged++;
    }
  }
  ball_check_jumps(&x, n, v, pt);
  if (nfail && fam->n_fails < HARD_MAX_FAILS) {
    char *s = fam->fails[fam->n_fails++];
    int k = snprintf(s, sizeof fam->fails[0], "%zu/%zu failed at v0 =", nfail, n);
    for (size_t i = 0; i < n && k > 0 && (size_t)k < sizeof fam->fails[0] - 12; i++)
      if (!pt[i].converged) k += snprintf(s + k, sizeof fam->fails[0] - (size_t)k, " %.1e", v[i]);
    if (k > 0 && (size_t)k < sizeof fam->fails[0])
      snprintf(s + k, sizeof fam->fails[0] - (size_t)k, " | %s", label);
  }
  free(pt);
}

static double ball_rate(const ball_family *f) {
  return f->points ? (double)f->converged / (double)f->points : 1.0;
}

static void ball_print_family(const ball_family *f) {
  printf("  %-24s corners %3zu  points %4zu  converged %4zu  flagged %4zu  failed %3zu  (%.1f s)\n",
         f->name, f->corners, f->points, f->converged, f->flagged, f->failed, f->seconds);
  printf("  %-24s converged: %.1f %% (stated minimum %.0f %%); realistic points: %zu of %zu "
         "converged (minimum %.0f %%)\n",
         "", 100.0 * ball_rate(f), 100.0 * f->min_rate, f->real_converged, f->real_points,
         100.0 * f->min_real_rate);
  printf("  %-24s estimates: %zu within the 1 %% target, %zu above, %zu none; worst load error "
         "%.1e, residual %.1e, pressure < 0: %.1e p_ref, jump %.2f of its bound\n",
         "", f->met, f->above_target, f->no_estimate, f->worst_load_error, f->worst_residual,
         f->worst_neg_pressure, f->worst_jump);
  for (size_t i = 0; i < f->n_fails; i++)
    printf("    FAILED %s\n", f->fails[i]);
}

/* No invariant violated, and the stated minimum rates (of all points and
 * of the realistic ones: 1 where every realistic point must converge,
 * issue 19's rule for the line contact). */
static void ball_assert_rate(const ball_family *f) {
  if (f->violations)
    fail_msg("%s: %zu invariant violations (printed above)", f->name, f->violations);
  if (ball_rate(f) < f->min_rate)
    fail_msg("%s: %.1f %% of points converged, below the stated %.0f %%", f->name,
             100.0 * ball_rate(f), 100.0 * f->min_rate);
  double real = f->real_points ? (double)f->real_converged / (double)f->real_points : 1.0;
  if (real < f->min_real_rate)
    fail_msg("%s: %zu of %zu realistic points converged, below the stated %.0f %%", f->name,
             f->real_converged, f->real_points, 100.0 * f->min_real_rate);
}

/* ------------------------------------------------------------ corners */

/* The solid of a corner from four coordinates in [0, 1): elastic below
 * 0.25, else Einf/E0 log-uniform in 10 ... 1e4 with 1-12 terms over 0-12
 * decades centred on tau_c in 1e-6 ... 1e2 s (the strengths ragged, as
 * hard_rubber's). */
static vl_prony ball_rubber(const double *p, uint64_t *rng, double *ratio, size_t *terms,
                            double *decades, double *tau_c) {
  *ratio = p[0] < 0.25 ? 1.0 : hard_log_between(10.0, 1e4, (p[0] - 0.25) / 0.75);
  *terms = p[0] < 0.25 ? 0 : (size_t)lround(hard_log_between(1.0, 12.0, p[1]));
  *decades = *terms > 1 ? 12.0 * p[2] : 0.0;
  *tau_c = hard_log_between(1e-6, 1e2, p[3]);
  return hard_rubber(*ratio, *terms, *decades, *tau_c, 1, rng);
}

/* A corner's contact on `across` cells across the shorter semi-axis of
 * its relaxed Hertz ellipse, on a domain of 1.25 times its semi-axes (a
 * ball: the library's default domain). */
static void ball_base(vl_point_contact_config *cfg, const vl_prony *r, double rx, double ry,
                      double load, double across) {
  vl_point_contact_config_defaults(cfg);
  cfg->rubber = *r;
  cfg->radius_x_m = rx, cfg->radius_y_m = ry, cfg->load_n = load;
  double er0 = vl_prony_e0(r) * vl_prony_reduced_factor(r), ax, by, a0 = ball_a0(cfg);
  assert_int_equal(vl_hertz_ellipse(rx, ry, load, er0, &ax, &by, NULL), VL_OK);
  cfg->x_half_a0 = VL_BALL_DOMAIN_A0 * ax / a0, cfg->y_max_a0 = VL_BALL_DOMAIN_A0 * by / a0;
  cfg->cells_per_a0 = across * a0 / fmin(ax, by);
}

static int ball_label(char *s, size_t cap, double ratio, size_t nt, double dec, double tau_c,
                      double rx, double ry, double load) {
  int k = hard_rubber_label(s, cap, ratio, nt, dec, tau_c);
  return k + snprintf(s + k, cap - (size_t)k, ", Rx %.3g m, Ry %.3g m, W %.3g N", rx, ry, load);
}

/* Speeds: n log-spaced from lo to hi, the whole ladder moved by a fraction
 * `shift` of one step (each corner meets other speeds; the ends stay). */
static size_t ball_speeds(double lo, double hi, size_t n, double shift, double *v) {
  double step = log10(hi / lo) / (double)(n - 1);
  for (size_t i = 0; i < n; i++) {
    double e = (double)i * step + (i > 0 && i + 1 < n ? (shift - 0.5) * step : 0.0);
    v[i] = lo * pow(10.0, e);
  }
  return n;
}

/* Stated minimum convergence rates, measured (docs/POINT_CONTACT.md
 * section 5, "Corners"): dry, every point (120 of 120 balls, 64 of 64
 * ellipsoids); lubricated, 93 of 96 points (96.9 %), 39 of 42 realistic
 * ones: the three failures are listed in the summary (at 10 m/s, films
 * thicker than the elastic approach on light loads in viscous fluids, and
 * 0.01 m/s on a 4 cm ball under 0.04 N with Einf/E0 = 5100); raise these
 * when they are fixed. */
static ball_family fam_dry_ball = {.name = "dry ball, LHS", .min_rate = 1.0, .min_real_rate = 1.0};
static ball_family fam_dry_ellipsoid = {
    .name = "dry ellipsoid, LHS", .min_rate = 1.0, .min_real_rate = 1.0};
static ball_family fam_wet_ball = {
    .name = "lubricated ball, LHS", .min_rate = 0.95, .min_real_rate = 0.9};
/* Rough balls, dry and lubricated (docs/POINT_CONTACT.md section 10):
 * measured 14 of 16 points (21 of 24 at 3 speeds a corner); the failures
 * one corner, a 0.8 mm ball under 0.066 N on a surface of h_rms 3.9 um
 * (the roughness as large as the elastic approach: the contact spreads
 * beyond its planned domain). */
static ball_family fam_rough_ball = {
    .name = "rough ball, LHS", .min_rate = 0.85, .min_real_rate = 0.8};

/* A corner's solid (p[0..3]), radius Rx (p[4]; Ry = ry_over_rx Rx) and
 * load (p[5]) on `cells` across its relaxed contact into cfg, and its label
 * (its length returned). */
static int ball_corner(const double *p, uint64_t *rng, double ry_over_rx, double cells,
                       vl_point_contact_config *cfg, char *label, size_t cap) {
  double ratio, dec, tau_c;
  size_t nt;
  vl_prony r = ball_rubber(p, rng, &ratio, &nt, &dec, &tau_c);
  double rx = hard_log_between(5e-4, 5e-2, p[4]), W = hard_log_between(0.01, 100.0, p[5]);
  ball_base(cfg, &r, rx, rx * ry_over_rx, W, cells);
  return ball_label(label, cap, ratio, nt, dec, tau_c, rx, rx * ry_over_rx, W);
}

/* A dry family: Latin hypercube (seed, rng) over (solid x 4, radius, load,
 * sigma_s on or off, speed shift and, an ellipsoid, Ry/Rx log-uniform in
 * 0.1 ... 10: an ellipse elongated across the sliding or along it), n
 * corners of nv speeds from 1e-9 to 1e3 m/s. */
static void dry_family(ball_family *fam, size_t n, size_t nv, uint64_t seed, uint64_t rng,
                       bool ellipsoid) {
  size_t d = ellipsoid ? 9 : 8;
  double *u = malloc(n * d * sizeof *u), v[8];
  assert_non_null(u);
  assert_true(nv <= 8);
  hard_lhs(n, d, seed, u);
  for (size_t i = 0; i < n; i++) {
    const double *p = u + i * d;
    double ry = ellipsoid ? hard_log_between(0.1, 10.0, p[8]) : 1.0;
    vl_point_contact_config cfg;
    char label[400];
    int k = ball_corner(p, &rng, ry, BALL_DRY_CELLS, &cfg, label, sizeof label);
    cfg.sigma_s_pa = p[6] < 0.5 ? 0.0 : 1e5;
    snprintf(label + k, sizeof label - (size_t)k, ", sigma_s %g Pa", cfg.sigma_s_pa);
    ball_run_corner(fam, label, &cfg, ball_speeds(1e-9, 1e3, nv, p[7], v), v);
  }
  free(u);
  ball_assert_rate(fam);
}

/* Dry balls: 24 corners of 5 speeds. */
static void test_dry_ball(void **state) {
  (void)state;
  dry_family(&fam_dry_ball, 24, 5, 0x5eedba11, 35, false);
}

/* Dry ellipsoids: 16 corners of 4 speeds (an ellipsoid's point costs up to
 * 10x a ball's). */
static void test_dry_ellipsoid(void **state) {
  (void)state;
  dry_family(&fam_dry_ellipsoid, 16, 4, 0x5eede111, 36, true);
}

/* Lubricated balls: Latin hypercube over (solid x 4, radius, load,
 * viscosity, speed shift), 3 speeds from Hamrock and Dowson's 10 nm film
 * to 10 m/s (a corner whose 10 nm film needs more than 1 m/s starts at
 * 0.1 m/s below 10 m/s: its films are thinner, below the continuum). */
static void test_wet_ball(void **state) {
  (void)state;
  enum { N = 24, D = 8, NV = 4 };
  double u[N * D], v[NV];
  hard_lhs(N, D, 0x5eedf11e, u);
  uint64_t rng = 37;
  for (size_t i = 0; i < N; i++) {
    const double *p = u + i * D;
    vl_point_contact_config cfg;
    char label[400];
    int k = ball_corner(p, &rng, 1.0, BALL_WET_CELLS, &cfg, label, sizeof label);
    cfg.eta_pa_s = hard_log_between(1e-3, 1.0, p[6]);
    /* h ~ v0^0.65: the speed of a 10 nm film */
    double lo = pow(1e-8 / ball_film_hd(&cfg, 1.0), 1.0 / 0.65);
    lo = fmin(lo, 1.0);
    snprintf(label + k, sizeof label - (size_t)k, ", eta %.3g Pa s, 10 nm film at %.3g m/s",
             cfg.eta_pa_s, lo);
    ball_run_corner(&fam_wet_ball, label, &cfg, ball_speeds(lo, 10.0, NV, p[7], v), v);
  }
  ball_assert_rate(&fam_wet_ball);
}

/* Rough balls: Latin hypercube over (solid x 4, radius, load, viscosity
 * or dry, h_rms, speed shift), N corners at 1e-4 and 1 m/s (3 speeds a
 * corner cost 45 s of the CI's time) on a self-affine surface (H 0.8, q0 2e5, q1 7.8e9 1/m) of
 * h_rms 10 nm
 * ... 5 um, Patir and Cheng's flow factors, sigma_s 1 MPa. */
static void test_rough_ball(void **state) {
  (void)state;
  enum { N = 8, D = 9, NV = 2 };
  double u[N * D], v[NV];
  hard_lhs(N, D, 0x5eed4011, u);
  uint64_t rng = 38;
  for (size_t i = 0; i < N; i++) {
    const double *p = u + i * D;
    vl_point_contact_config cfg;
    char label[400];
    int k = ball_corner(p, &rng, 1.0, BALL_WET_CELLS, &cfg, label, sizeof label);
    double hrms = hard_log_between(1e-8, 5e-6, p[7]);
    vl_psd psd;
    vl_persson *tab = vl_test_paper_surface(hrms, &psd);
    cfg.eta_pa_s = p[6] < 0.2 ? 0.0 : hard_log_between(1e-3, 1.0, (p[6] - 0.2) / 0.8);
    cfg.roughness = tab, cfg.flow_factors = VL_FLOW_FACTORS_PATIR_CHENG, cfg.sigma_s_pa = 1e6;
    snprintf(label + k, sizeof label - (size_t)k, ", h_rms %.3g m, eta %.3g Pa s", hrms,
             cfg.eta_pa_s);
    ball_run_corner(&fam_rough_ball, label, &cfg, ball_speeds(1e-4, 1.0, NV, p[8], v), v);
    vl_persson_free(tab);
    vl_psd_free(&psd);
  }
  ball_assert_rate(&fam_rough_ball);
}

static void test_summary(void **state) {
  (void)state;
  ball_family *f[] = {&fam_dry_ball, &fam_dry_ellipsoid, &fam_wet_ball, &fam_rough_ball};
  printf("\n== hard-case matrix: point contacts ==\n");
  size_t points = 0, converged = 0;
  double secs = 0.0;
  for (size_t i = 0; i < sizeof f / sizeof f[0]; i++) {
    ball_print_family(f[i]);
    points += f[i]->points, converged += f[i]->converged, secs += f[i]->seconds;
  }
  printf("  TOTAL: points %zu, converged %zu; %.1f s in sweeps\n", points, converged, secs);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_dry_ball), cmocka_unit_test(test_dry_ellipsoid),
      cmocka_unit_test(test_wet_ball), cmocka_unit_test(test_rough_ball),
      cmocka_unit_test(test_summary),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
