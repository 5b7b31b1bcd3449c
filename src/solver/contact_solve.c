/* The solve of one operating point, every way of reaching it in one place:
 *
 *   1. the ladder of attempts at one speed (vl_contact_solve): an ordered
 *      table of rungs, each a condition on the contact and its state, a
 *      start (contact_start.c guesses; the helper contacts some of them
 *      need are solved here) and a Newton variant (contact_newton.c), tried
 *      in order until one converges;
 *   2. the paths that reach a speed from the contact's converged state
 *      (vl_contact_reach: continuation with step halving, a fresh start,
 *      starts below and above), used by the sweeps.
 *
 * The speed of the converged state is c->v_state (0: none, the state is a
 * guess); the speed the equations are set for is c->v0 (the kernel, the
 * asperity state). A failed solve leaves both, the unknowns and the fluid
 * scales as they were. */
#include "contact_internal.h"
#include "contact_private.h"

#include <float.h>
#include <kinsol/kinsol.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "blas_threads.h"

/* ---- helper contacts: solved here, their solutions start c ---------- */

/* The dry contact of a rough film on the same grid, created when first
 * needed (most sweeps never need it): the configuration without the fluid
 * (and so without viscous flattening, which needs one). NULL when it cannot
 * be made (out of memory): the start is then skipped. */
static vl_contact *dry_helper(vl_contact *c) {
  if (!c->dry) {
    vl_contact_config dry = c->cfg;
    dry.eta_pa_s = 0.0;
    dry.flattening = NULL;
    dry.flattening_psd = NULL;
    if (vl_contact_create(&dry, &c->dry, NULL) != VL_OK) c->dry = NULL;
  }
  return c->dry;
}

/* Cells of the smooth film that starts a rough one (film_helper): the wet
 * default's resolution (VL_WET_GRID on the default inlet), at most the
 * rough contact's own uniform cells. */
#define FILM_START_GRID VL_WET_GRID

/* The smooth film of a rough contact on a uniform grid over the same
 * domain, created when first needed: the configuration without roughness
 * (its flow factors, Couette roughness and asperity contact), viscous
 * flattening or graded cells. NULL when it cannot be made. */
static vl_contact *film_helper(vl_contact *c) {
  if (!c->coarse) {
    vl_contact_config film = c->cfg;
    film.roughness = NULL;
    film.flow_factors = VL_FLOW_FACTORS_SMOOTH;
    film.flow_table = NULL;
    film.flattening = NULL;
    film.flattening_psd = NULL;
    film.sigma_s_pa = 0.0;
    film.shear_law = NULL;
    film.grid_growth = 1.0;
    if (film.grid > FILM_START_GRID) film.grid = FILM_START_GRID;
    if (vl_contact_create(&film, &c->coarse, NULL) != VL_OK) c->coarse = NULL;
  }
  return c->coarse;
}

/* ---- the ladder at one speed ---------------------------------------- */

/* One solve at speed v0: what the contact is and where its state stands
 * (fixed when the solve begins), the state to go back to, and the
 * iterations spent and the last Newton's outcome. */
typedef struct {
  double v0;
  bool viscosity; /* the rung of continuation in viscosity is allowed */
  bool dry, smooth_wet, rough_wet;
  bool continued;          /* c held a converged state (c->v_state > 0) */
  bool companion;          /* a smooth dry contact whose error-estimate companion holds the
                            * estimate of c's converged state (companion_ready) */
  vl_contact_scales saved; /* with the unknowns in c->y_saved */
  long nni;
  int flag;
  double fnorm;
} attempt;

static vl_status solve_at(vl_contact *c, double v0_m_s, bool viscosity, vl_point *pt,
                          vl_error *err);
static vl_status continue_in_viscosity(vl_contact *c, double v0_m_s, double eta_pa_s,
                                       double max_ratio, bool viscosity, vl_point *pt,
                                       vl_error *err);

/* When a rung applies. */
static bool rough_continued(const attempt *a) { return a->rough_wet && a->continued; }
static bool rough_fresh(const attempt *a) { return a->rough_wet && !a->continued; }
static bool smooth_fresh(const attempt *a) { return a->smooth_wet && !a->continued; }
static bool smooth_continued(const attempt *a) { return a->smooth_wet && a->continued; }
static bool dry_or_smooth_continued(const attempt *a) { return a->dry || smooth_continued(a); }
static bool dry_companion(const attempt *a) { return a->companion; }
static bool smooth_thickened(const attempt *a) { return a->smooth_wet && a->viscosity; }

/* The starts. Each sets c's unknowns for the rung's Newton; false: no
 * start (the rung is skipped). */
static bool start_as_is(vl_contact *c, attempt *a) {
  (void)c, (void)a;
  return true;
}

/* The state the solve began with (c->y_saved), whatever an earlier rung's
 * start left in y: the dry contact's companion start (a smooth film's
 * first attempt has none before it and keeps y as it is). */
static bool start_as_it_was(vl_contact *c, attempt *a) {
  if (a->dry) N_VScale(1.0, c->y_saved, c->y);
  return true;
}

static bool start_predicted(vl_contact *c, attempt *a) {
  vl_contact_predict_state(c, a->v0);
  return true;
}

/* The predictor scales pf with the speed, as a film of fixed shape does;
 * fluid trapped between the asperities of a fine surface does not follow:
 * there (fig05 on paper-0.1um, 0.025-0.16 m/s) Newton from the scaled state
 * failed steps of 1/64 of 0.2 decade, from the state as it was it took
 * 30-50 iterations per 0.04 decade. */
static bool start_unpredicted(vl_contact *c, attempt *a) {
  N_VScale(1.0, c->y_saved, c->y);
  vl_contact_scales_put(c, &a->saved);
  return true;
}

/* A smooth film without a usable previous state: the converged solution
 * of the coarse level (itself started the same way), interpolated, or on
 * the coarsest level the analytic guess, with the dry contact's pressure
 * on a viscoelastic solid. Cavitation is a free boundary that a semismooth
 * Newton step moves by about one cell (cells beyond it are held at pf = 0
 * by the linearised complementarity), so a start whose film rupture is n
 * cells off costs n iterations; each level halves that distance in its own
 * cells. The coarse level's iterations count; the dry contact's do not (it
 * is part of the guess, as before this room existed). */
static bool start_smooth_film(vl_contact *c, attempt *a) {
  vl_contact *cc = c->coarse;
  if (cc) {
    vl_point cp;
    cc->v_state = 0.0; /* a fresh start there too */
    vl_status st = solve_at(cc, a->v0, true, &cp, NULL);
    a->nni += cp.iterations;
    if (st == VL_OK) {
      vl_contact_guess_from_coarse(c, cc);
      return true;
    }
  }
  const vl_contact *dry = NULL;
  if (c->dry && !vl_contact_film_rigid(c, a->v0)) {
    vl_point dp;
    vl_contact_reset(c->dry);
    if (solve_at(c->dry, a->v0, true, &dp, NULL) == VL_OK) dry = c->dry;
  }
  vl_contact_guess_smooth_film(c, a->v0, dry);
  return true;
}

/* Whether c (a smooth dry contact of the active-set Newton, continued)
 * can start from its companion: the contact on cells three times as wide
 * that estimates each point's error (contact_estimate.c), holding the
 * estimate of c's converged state, i.e. on its branch at the same speed. */
static bool companion_ready(const vl_contact *c) {
  const vl_contact *e = c->estimator;
  return c->min_rows && c->v_state > 0.0 && e && e->v_state == c->v_state;
}

/* Why the companion: the active-set Newton changes the contact set where
 * its linearised gap changes sign, and between two speeds of a transition
 * the edges move by tens of cells, which took it 6-8 steps of the full
 * system (fig03-smooth at N 400, 13 speeds). The companion moves its edges
 * in its own cells, at a ninth of the cost per step, and its contact set,
 * interpolated, puts c's edges within about one of its cells: c then takes
 * ~2 steps. The companion's iterations count, as a coarse level's do. Its
 * solution is not the estimate: that is solved again from c's converged
 * point. */
static bool start_companion(vl_contact *c, attempt *a) {
  vl_contact *e = c->estimator;
  vl_point ep;
  vl_status st = solve_at(e, a->v0, true, &ep, NULL);
  a->nni += ep.iterations;
  if (st != VL_OK) return false;
  /* e's solve began from its state at c's converged speed (y_saved) */
  vl_contact_guess_from_companion(c, e, N_VGetArrayPointer(e->y_saved));
  return true;
}

/* Why the dry contact: Hertz is the relaxed solid's contact, and a rough
 * film on a stiffening (viscoelastic) solid at speed is far from it. On
 * fig05 with paper-0.1um (h_rms 0.1 um), Newton from Hertz fails at every
 * v0 from 0.016 to 0.16 m/s (the loss peak: the real contact shrinks and
 * u_min drops to 0.002 h_rms), and continuation in speed needs 100-150
 * iterations for steps of 0.5 %; the dry contact converges from Hertz in
 * 11-32 iterations there, and the film from it in 6-11. In the boundary and
 * mixed regimes the film barely changes the contact (mu of the wet and dry
 * points agree to 5 digits at 0.01 m/s); in the hydrodynamic regime the
 * film lifts the solid off and the start fails (fig05 above ~10 m/s): the
 * sweep then continues from a lower speed (vl_contact_reach). */
static bool start_dry(vl_contact *c, attempt *a) {
  vl_contact *d = dry_helper(c);
  if (!d) return false;
  vl_point dp;
  vl_contact_reset(d);
  vl_status st = solve_at(d, a->v0, true, &dp, NULL);
  a->nni += dp.iterations;
  if (st != VL_OK) return false;
  vl_contact_guess_from_dry(c, d);
  return true;
}

/* Why the smooth film: in the hydrodynamic regime the film has lifted the
 * solid off the asperities (u >> h_rms: the flow factors are 1, the
 * asperity pressure vanishes), so the rough solution is the smooth one,
 * which its own fresh starts find (coarse grids, Martin's rigid film).
 * Neither Hertz nor the dry contact (a closed film) is near it. On fig05
 * with a self-affine surface of h_rms 30 nm, the rough film from this start
 * converged at 15.8 to 400 m/s where continuation from the mixed regime
 * failed: there u_min jumps from 8e-11 m to 1.6e-7 m (a fold of the
 * Stribeck curve: the mixed and the lifted branches coexist near 10-16
 * m/s). The smooth film is solved without its continuation in viscosity:
 * the films that need it are thin, where the rough film is not the smooth
 * one anyway, and on a fine grid it cost a hard-case corner that failed at
 * 1e-12 m/s 100 s. */
static bool start_film(vl_contact *c, attempt *a) {
  vl_contact *s = film_helper(c);
  if (!s) return false;
  vl_point sp;
  s->v_state = 0.0; /* its own fresh start */
  vl_status st = solve_at(s, a->v0, false, &sp, NULL);
  a->nni += sp.iterations;
  if (st != VL_OK) return false;
  vl_contact_guess_from_film(c, s);
  return true;
}

/* A thin smooth film that a fresh start misses: starts afresh at a
 * viscosity 10, 100, ... times larger (thicker film, wider inlet and outlet
 * zones) and comes down by continuation in viscosity, neither solve
 * climbing this rung again. Returns whether that converged at the
 * contact's viscosity (then a->flag = 0 and a->fnorm is the residual); the
 * viscosity is the contact's again either way. */
static bool newton_thickened(vl_contact *c, attempt *a) {
  bool ok = false;
  double eta = c->cfg.eta_pa_s, v_state = c->v_state;
  N_VScale(1.0, c->y_saved, c->y_outer); /* the inner solves reuse y_saved */
  for (int k = 1; k <= 6 && !ok; k++) {
    vl_point tp;
    vl_contact_set_viscosity(c, eta * pow(10.0, k), NULL);
    c->v_state = 0.0;
    vl_status st = solve_at(c, a->v0, false, &tp, NULL);
    a->nni += tp.iterations;
    if (st != VL_OK) continue;
    ok = continue_in_viscosity(c, a->v0, eta, 10.0, false, &tp, NULL) == VL_OK;
    a->nni += tp.iterations;
    if (ok) {
      a->fnorm = tp.residual;
      a->flag = 0;
    }
    break;
  }
  vl_contact_set_viscosity(c, eta, NULL);
  N_VScale(1.0, c->y_outer, c->y_saved);
  if (!ok) c->v_state = v_state;
  return ok;
}

/* The Newton of a rung: a variant of contact_newton.c, or the continuation
 * in viscosity (VL_NEWTON_KINDS). */
#define NEWTON_THICKENED VL_NEWTON_KINDS

static const struct rung {
  const char *what;
  bool (*applies)(const attempt *a);
  bool (*start)(vl_contact *c, attempt *a);
  int newton; /* vl_newton_kind, or NEWTON_THICKENED */
} LADDER[] = {
    /* the first attempt: exactly one of these four applies, the dry
     * contact's companion start before the state as it was when it can */
    {"rough film, continued from the predicted state", rough_continued, start_predicted,
     VL_NEWTON_CONTINUED},
    {"rough film from the Hertz guess (vl_contact_reset)", rough_fresh, start_as_is,
     VL_NEWTON_FROM_HERTZ},
    {"smooth film, fresh start", smooth_fresh, start_smooth_film, VL_NEWTON_PLAIN},
    {"dry contact from its companion at this speed (cells three times as wide)", dry_companion,
     start_companion, VL_NEWTON_PLAIN},
    {"dry contact or smooth film from the state as it was", dry_or_smooth_continued,
     start_as_it_was, VL_NEWTON_PLAIN},
    /* then, while the point has not converged, in this order */
    {"rough film, continued from the state as it was", rough_continued, start_unpredicted,
     VL_NEWTON_FILM},
    {"smooth film, fresh start after a failed continuation", smooth_continued, start_smooth_film,
     VL_NEWTON_PLAIN},
    {"smooth film from a thicker one (continuation in viscosity)", smooth_thickened, NULL,
     NEWTON_THICKENED},
    {"rough film from the dry contact at this speed", rough_fresh, start_dry, VL_NEWTON_PLAIN},
    {"rough film from the smooth film at this speed", rough_fresh, start_film, VL_NEWTON_PLAIN},
};

/* Tries the rungs that apply, in order, until one converges. */
static bool climb(vl_contact *c, attempt *a) {
  bool ok = false;
  for (size_t k = 0; k < sizeof LADDER / sizeof LADDER[0] && !ok; k++) {
    const struct rung *r = &LADDER[k];
    if (!r->applies(a) || (r->start && !r->start(c, a))) continue;
    ok = r->newton == NEWTON_THICKENED
             ? newton_thickened(c, a)
             : vl_contact_newton(c, (vl_newton_kind)r->newton, a->v0, &a->nni, &a->flag, &a->fnorm);
  }
  return ok;
}

/* A solve that failed: says why in err, goes back to the last converged
 * state, its speed and scales, and reports the point as not converged
 * (never NaN). */
static vl_status solve_failed(vl_contact *c, const attempt *a, vl_point *pt, vl_error *err) {
  bool closed =
      a->smooth_wet && (a->flag == KIN_REPTD_SYSFUNC_ERR || a->flag == KIN_FIRST_SYSFUNC_ERR);
  char *flag_name = KINGetReturnFlagName(a->flag); /* malloc'd by SUNDIALS */
  vl_error_set(err,
               "no convergence at v0 = %g m/s: KINSOL flag %d (%s), %ld iterations, "
               "residual %.3g%s",
               a->v0, a->flag, flag_name ? flag_name : "?", a->nni, a->fnorm,
               closed ? " (Newton steps kept closing the film: the grid is probably too coarse "
                        "for the inlet and outlet zones of this soft EHL film; refine it or "
                        "narrow the domain)"
                      : "");
  free(flag_name);
  vl_contact_restore(c, c->y_saved, &a->saved);
  memset(pt, 0, sizeof *pt);
  pt->error_estimate = pt->flux_error_estimate = NAN;
  pt->v0_m_s = a->v0;
  pt->converged = false;
  pt->iterations = a->nni;
  pt->residual = isfinite(a->fnorm) ? a->fnorm : DBL_MAX;
  pt->regime = c->wet ? VL_REGIME_BOUNDARY : VL_REGIME_DRY;
  pt->u_min_over_h_rms = NAN;
  return VL_ENOCONV;
}

/* The solve of point v0_m_s on c; viscosity: whether the ladder may
 * continue in viscosity (not inside that continuation, nor for the smooth
 * film that starts a rough one). */
static vl_status solve_at(vl_contact *c, double v0_m_s, bool viscosity, vl_point *pt,
                          vl_error *err) {
  memset(pt, 0, sizeof *pt);
  pt->error_estimate = pt->flux_error_estimate = NAN;
  pt->v0_m_s = v0_m_s;
  if (!(v0_m_s >= 0.0 && isfinite(v0_m_s)) || (c->wet && !(v0_m_s > 0.0))) {
    vl_error_set(err, "speed must be finite and %s 0 (got %g m/s)", c->wet ? ">" : ">=", v0_m_s);
    return VL_EINPUT;
  }
  N_VScale(1.0, c->y, c->y_saved);
  attempt a = {.v0 = v0_m_s, .viscosity = viscosity, .saved = vl_contact_scales_get(c)};
  vl_contact_set_speed(c, v0_m_s);
  a.dry = !c->wet;
  a.smooth_wet = c->wet && !c->rough;
  a.rough_wet = c->wet && c->rough;
  a.continued = c->v_state > 0.0;
  a.companion = a.dry && companion_ready(c);
  if (!climb(c, &a)) return solve_failed(c, &a, pt, err);
  pt->iterations = a.nni;
  pt->residual = a.fnorm;
  pt->converged = true;
  c->v_state = v0_m_s;
  vl_contact_report(c, pt);
  return VL_OK;
}

vl_status vl_contact_solve(vl_contact *c, double v0_m_s, vl_point *pt, vl_error *err) {
  int threads = vl_blas_pin_one_thread(); /* the same rounding at any OPENBLAS_NUM_THREADS */
  vl_status s = solve_at(c, v0_m_s, true, pt, err);
  vl_blas_restore_threads(threads);
  return s;
}

/* Log-spaced steps from the current viscosity to the target; a failed step
 * is halved (in log eta) up to 6 times, each from the last converged state. */
static vl_status continue_in_viscosity(vl_contact *c, double v0_m_s, double eta_pa_s,
                                       double max_ratio, bool viscosity, vl_point *pt,
                                       vl_error *err) {
  double eta = c->cfg.eta_pa_s, lstep = log(max_ratio);
  long nni = 0;
  vl_status st = VL_OK;
  int halvings = 0;
  for (;;) {
    double gap = log(eta_pa_s / eta);
    double step = fabs(gap) <= lstep ? gap : copysign(lstep, gap);
    double eta_next = fabs(gap) <= lstep ? eta_pa_s : eta * exp(step);
    vl_contact_set_viscosity(c, eta_next, NULL);
    st = solve_at(c, v0_m_s, viscosity, pt, err);
    nni += pt->iterations;
    if (st == VL_OK) {
      eta = eta_next;
      if (eta == eta_pa_s) break;
      continue;
    }
    vl_contact_set_viscosity(c, eta, NULL); /* back to the converged state's */
    if (st != VL_ENOCONV || ++halvings > 6) break;
    lstep *= 0.5;
  }
  pt->iterations = nni;
  return st;
}

vl_status vl_contact_solve_viscosity(vl_contact *c, double v0_m_s, double eta_pa_s,
                                     double max_ratio, vl_point *pt, vl_error *err) {
  memset(pt, 0, sizeof *pt);
  pt->error_estimate = pt->flux_error_estimate = NAN;
  pt->v0_m_s = v0_m_s;
  if (!c->wet || !(eta_pa_s > 0.0 && isfinite(eta_pa_s)) || !(max_ratio > 1.0)) {
    vl_error_set(err,
                 "viscosity continuation needs a wet contact, eta > 0 and max_ratio > 1 "
                 "(got eta %g Pa s, max_ratio %g)",
                 eta_pa_s, max_ratio);
    return VL_EINPUT;
  }
  int threads = vl_blas_pin_one_thread();
  vl_status s = continue_in_viscosity(c, v0_m_s, eta_pa_s, max_ratio, true, pt, err);
  vl_blas_restore_threads(threads);
  return s;
}

/* ---- the paths to a speed from the converged state ------------------ */

/* Reaches speed `to` from c's state (converged at c->v_state) through
 * intermediate speeds when the direct step fails. depth counts halvings. */
static vl_status reach(vl_contact *c, double to, int depth, int max_depth, vl_point *pt,
                       vl_sweep_stats *st, vl_error *err) {
  double from = c->v_state;
  vl_status s = vl_contact_solve(c, to, pt, err);
  st->newton_iterations += pt->iterations;
  if (s != VL_ENOCONV || depth >= max_depth || !(from > 0.0)) return s;
  double mid = sqrt(from * to); /* halve the step in log speed */
  vl_point tmp;
  st->substeps++;
  s = reach(c, mid, depth + 1, max_depth, &tmp, st, err);
  if (s != VL_OK) return s;
  return reach(c, to, depth + 1, max_depth, pt, st, err);
}

/* Continuation from c's converged state to `to` (either way) with step
 * control: steps of RAMP_FIRST_DECADES, doubled (up to one decade) after a
 * step that took at most RAMP_EASY_ITERATIONS Newton iterations; a failed
 * step is halved as in reach. Only `to` is reported (pt). */
#define RAMP_FIRST_DECADES 0.25
#define RAMP_EASY_ITERATIONS 8
vl_status vl_contact_ramp(vl_contact *c, double to, int max_depth, vl_point *pt, vl_sweep_stats *st,
                          vl_error *err) {
  double v = c->v_state, h = RAMP_FIRST_DECADES, dir = to > v ? 1.0 : -1.0;
  for (;;) {
    double next = v * pow(10.0, dir * h);
    if (dir * (next - to) >= -1e-12 * to) return reach(c, to, 0, max_depth, pt, st, err);
    vl_point tmp;
    st->substeps++;
    vl_status s = reach(c, next, 0, max_depth, &tmp, st, err);
    if (s != VL_OK) {
      *pt = tmp;
      return s;
    }
    v = next;
    if (tmp.iterations <= RAMP_EASY_ITERATIONS) h = fmin(2.0 * h, 1.0);
  }
}

/* A fresh start at a speed `decades[k]` decades away from v (below when
 * sign < 0), the first that converges, continued to v (ramp). Below, the
 * contact is closer to the dry one; above, the film has lifted off (the
 * fresh starts of the ladder find both). On failure the contact holds the
 * Hertz guess. */
static vl_status reach_from(vl_contact *c, double v, double sign, const double *decades, size_t nd,
                            int max_depth, vl_point *pt, vl_sweep_stats *st, vl_error *err) {
  vl_status s = VL_ENOCONV;
  for (size_t k = 0; k < nd; k++) {
    double start = v * pow(10.0, sign * decades[k]);
    vl_point tmp;
    vl_contact_reset(c);
    st->substeps++;
    s = vl_contact_solve(c, start, &tmp, err);
    st->newton_iterations += tmp.iterations;
    if (s == VL_ENOCONV) continue;
    if (s != VL_OK) return s;
    s = vl_contact_ramp(c, v, max_depth, pt, st, err);
    if (s != VL_ENOCONV) return s;
    break; /* a start that does not carry to v will not from farther away either */
  }
  vl_contact_reset(c);
  return s;
}

vl_status vl_contact_reach(vl_contact *c, double v, int max_depth, vl_point *pt, vl_sweep_stats *st,
                           vl_error *err) {
  /* far enough below to reach the boundary regime from the mixed one; close
   * above, since a fold of the curve (a film lifting off) is narrow */
  static const double below[] = {1.0, 2.0, 4.0, 8.0, 12.0}, above[] = {0.5, 1.0, 2.0};
  double last_ok = c->v_state;
  /* path 1: continuation */
  vl_status s = reach(c, v, 0, max_depth, pt, st, err);
  /* path 2: a fresh start at v. A contact without a converged state (v_state
   * 0) has just made it: repeating it would fail the same way. Continuation
   * can lose the branch where the solution changes fast (a stiff rubber
   * through its transition: 7 consecutive dry points failed at Einf/E0 =
   * 1e4 that a start from Hertz solves); the contact then holds the last
   * converged state, which the fresh start gives up */
  if (s == VL_ENOCONV && c->v_state > 0.0) {
    vl_contact_reset(c);
    st->fresh_starts++;
    s = vl_contact_solve(c, v, pt, err);
    st->newton_iterations += pt->iterations;
  }
  vl_point other;
  vl_status so = VL_ENOCONV;
  /* path 3: from below, only without a converged point below (continuation
   * from there has just failed) */
  if (s == VL_ENOCONV && !(last_ok > 0.0 && last_ok < v)) {
    st->starts_below++;
    so = reach_from(c, v, -1.0, below, sizeof below / sizeof below[0], max_depth, &other, st, err);
  }
  /* path 4: from above */
  if (s == VL_ENOCONV && so == VL_ENOCONV) {
    st->starts_above++;
    so = reach_from(c, v, 1.0, above, sizeof above / sizeof above[0], max_depth, &other, st, err);
  }
  if (s != VL_ENOCONV || so == VL_ENOCONV) return s;
  if (so == VL_OK) *pt = other;
  return so;
}
