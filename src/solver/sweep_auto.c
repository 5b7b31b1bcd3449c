/* The automatic sweep (numerics.h): numerics per run of points, an error
 * estimate on every point, refinement until it meets the target. */
#include "contact_private.h"
#include "numerics_plan.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "contact_internal.h"
#include "sweep_internal.h"

/* A smooth film re-planned when the film expected at the next speed is
 * this many times thicker or thinner than the one the layout was made for
 * (the edge zones scale as h^(2/3): 1.3x). */
#define REPLAN_FILM_RATIO 1.5
/* The film's growth with speed used to predict the next one (soft EHL
 * h ~ (eta v0)^0.6-0.7, a rigid film ~ eta v0). */
#define FILM_SPEED_EXPONENT 0.7

#define AUTO_SPARES 3

typedef struct {
  vl_contact_config base;
  bool layout; /* smooth film: planned cells */
  vl_contact *c;
  vl_plan plan;
  double plan_film;             /* the film the layout was planned for (m) */
  double resolution;            /* vl_plan_input.resolution, or the grid's divisor */
  double inlet_scale;           /* vl_plan_input.inlet_scale, or the inlet's factor */
  double c_resolution, c_inlet; /* the numerics c was built with */
  /* Contacts of uniform or graded cells (which do not depend on the speed)
   * that were set aside, to be used again by a later point with the same
   * numerics: a refined point goes back to the standard cells at the next
   * point, and the next refined one to the refined cells (made anew each
   * time, fig15 built 38 contacts for its 12 refined points instead of 10:
   * their allocation and the first touch of their matrices took 0.31 s to
   * 0.28 s). */
  struct {
    vl_contact *c;
    double resolution, inlet;
  } spare[AUTO_SPARES];
} auto_state;

/* The spare contact for a's present numerics, taken out (NULL: none). */
static vl_contact *spare_take(auto_state *a) {
  for (int k = 0; k < AUTO_SPARES; k++)
    if (a->spare[k].c && a->spare[k].resolution == a->resolution &&
        a->spare[k].inlet == a->inlet_scale) {
      vl_contact *c = a->spare[k].c;
      a->spare[k].c = NULL;
      vl_contact_set_max_iterations(c, a->base.max_iterations); /* refine may have capped it */
      return c;
    }
  return NULL;
}

/* Sets c (built with the given numerics) aside, in place of the oldest
 * spare; a planned layout's contact is freed (its cells fit one film). */
static void spare_put(auto_state *a, vl_contact *c, double resolution, double inlet) {
  if (!c) return;
  if (a->layout) {
    vl_contact_free(c);
    return;
  }
  vl_contact_free(a->spare[0].c);
  for (int k = 0; k + 1 < AUTO_SPARES; k++)
    a->spare[k] = a->spare[k + 1];
  a->spare[AUTO_SPARES - 1].c = c;
  a->spare[AUTO_SPARES - 1].resolution = resolution;
  a->spare[AUTO_SPARES - 1].inlet = inlet;
}

static void free_state(auto_state *a) {
  vl_contact_free(a->c);
  a->c = NULL;
  for (int k = 0; k < AUTO_SPARES; k++)
    vl_contact_free(a->spare[k].c), a->spare[k].c = NULL;
  vl_plan_free(&a->plan);
}

/* A new contact for speed v (prev: the last converged point, or NULL),
 * started from a's converged state where it has one (*continued, unless
 * NULL), and
 * its layout (plan->spans NULL when not planned). Only a's spares change
 * (one may be taken). */
static vl_status build(auto_state *a, double v, const vl_point *prev, vl_contact **out,
                       vl_plan *plan, double *plan_film, bool *continued, vl_error *err) {
  vl_status st;
  bool spare = false;
  memset(plan, 0, sizeof *plan);
  *out = NULL;
  if (a->layout) {
    vl_plan_input in = {0.0, 0.0, a->resolution, a->inlet_scale};
    if (prev) in.film_m = prev->u_min_m * pow(v / prev->v0_m_s, FILM_SPEED_EXPONENT);
    st = vl_plan_wet(&a->base, v, &in, plan, err);
    if (st != VL_OK) return st;
    st = vl_contact_create(&plan->cfg, out, err);
    if (st != VL_OK) {
      vl_plan_free(plan);
      return st;
    }
    *plan_film = in.film_m > 0.0 ? in.film_m : vl_contact_film_estimate(&a->base, v);
  } else if ((*out = spare_take(a))) {
    spare = true;
  } else {
    vl_contact_config cfg = a->base;
    cfg.grid = (size_t)round((double)cfg.grid / a->resolution);
    /* a pressure at the domain's ends: both ends moved out (the asperity
     * contact of a very rough surface reaches past 1.6 a0 downstream) */
    cfg.x_min_a0 *= a->inlet_scale;
    cfg.x_max_a0 *= sqrt(a->inlet_scale);
    st = vl_contact_create(&cfg, out, err);
    if (st != VL_OK) return st;
  }
  /* continued from the old contact's converged state where it has one
   * (the same branch, without a fresh start), else a fresh start (a spare
   * contact forgets the state it had) */
  bool cont = a->c && vl_contact_start_from(*out, a->c);
  if (continued) *continued = cont;
  if (!cont && spare) { /* as vl_contact_create leaves a contact */
    vl_contact_set_speed(*out, 0.0);
    vl_contact_reset(*out);
  }
  return VL_OK;
}

/* Makes c (with its layout) a's contact; the old one is set aside as a
 * spare (spare_put). */
static void install(auto_state *a, vl_contact *c, vl_plan *plan, double plan_film) {
  spare_put(a, a->c, a->c_resolution, a->c_inlet);
  a->c = c;
  a->c_resolution = a->resolution, a->c_inlet = a->inlet_scale;
  if (plan->spans) {
    vl_plan_free(&a->plan);
    a->plan = *plan;
    a->plan_film = plan_film;
  }
}

static vl_status rebuild(auto_state *a, double v, const vl_point *prev, vl_error *err) {
  vl_contact *c;
  vl_plan plan;
  double film = 0.0;
  vl_status st = build(a, v, prev, &c, &plan, &film, NULL, err);
  if (st == VL_OK) install(a, c, &plan, film);
  return st;
}

/* Whether another refinement stays within the cost bound: a planned layout
 * that was not capped, or a grid whose doubled cells stay within
 * VL_AUTO_MAX_CELLS. */
static bool can_refine(const auto_state *a) {
  if (a->layout) return !a->plan.capped;
  return 2 * vl_contact_grid(a->c) <= VL_AUTO_MAX_CELLS;
}

/* Whether a smooth film's layout no longer fits the film expected at v. */
static bool needs_plan(const auto_state *a, double v, const vl_point *prev) {
  if (!a->c) return true;
  if (!a->layout || !prev) return false;
  double h = prev->u_min_m * pow(v / prev->v0_m_s, FILM_SPEED_EXPONENT);
  double r = h / a->plan_film;
  return r > REPLAN_FILM_RATIO || r < 1.0 / REPLAN_FILM_RATIO;
}

static void append_warning(vl_point *pt, const char *w) {
  size_t len = strlen(pt->warnings);
  snprintf(pt->warnings + len, sizeof pt->warnings - len, "%s%s", len ? ";" : "", w);
}

/* Solves v again with the given resolution and inlet scale, from the point
 * pt converged on a's contact. VL_OK: the new contact is a's and pt its
 * point. VL_ENOCONV: the new cells did not converge, and a (contact,
 * resolution, domain) and pt are as they were: a refinement improves a
 * converged point, it is never the reason the point fails. Continued from
 * pt's state, the refined Newton gets REFINE_MAX_ITERATIONS (fig05 on a 30
 * nm surface at 0.16-0.63 m/s: the 560-cell contact took 20 s to minutes
 * over every path of vl_sweep_solve_point, to a film its estimate put
 * 100-275 % off); from a fresh start (a longer domain) every path. */
#define REFINE_MAX_ITERATIONS 50
static vl_status refine(auto_state *a, double v, double resolution, double inlet_scale,
                        vl_point *pt, vl_sweep_stats *st, vl_error *err) {
  double old_resolution = a->resolution, old_inlet = a->inlet_scale;
  a->resolution = resolution, a->inlet_scale = inlet_scale;
  vl_contact *c;
  vl_plan plan;
  double film = 0.0;
  bool continued;
  vl_status s = build(a, v, pt, &c, &plan, &film, &continued, err);
  if (s != VL_OK) return s; /* nothing built */
  vl_point np;
  if (continued) {
    vl_contact_set_max_iterations(c, c->cfg.max_iterations < REFINE_MAX_ITERATIONS
                                         ? c->cfg.max_iterations
                                         : REFINE_MAX_ITERATIONS);
    s = vl_contact_solve(c, v, &np, err);
    st->newton_iterations += np.iterations;
  } else {
    s = vl_contact_reach(c, v, 6, &np, st, err);
  }
  if (s == VL_OK) {
    install(a, c, &plan, film);
    *pt = np;
    return VL_OK;
  }
  spare_put(a, c, a->resolution, a->inlet_scale);
  vl_plan_free(&plan);
  a->resolution = old_resolution, a->inlet_scale = old_inlet;
  return s;
}

/* An estimate that a refinement did not lower below this fraction of the
 * coarser one is not converging with the cells (a first-order method's
 * falls to 1/2 per halving): the cells do not resolve the contact, and
 * further refinement only costs (fig05 on a 30 nm surface at 1e-7-1e-5
 * m/s: 15 %, 15 %, 26 % at 208, 330, 560 cells). */
#define REFINE_MIN_GAIN 0.7

/* One point: solved, estimated, refined while above the target and the
 * refinements still lower the estimate. */
static vl_status auto_point(auto_state *a, const vl_auto_options *o, double v, const vl_point *prev,
                            vl_point *pt, vl_sweep_stats *st, vl_error *err) {
  vl_status s = VL_OK;
  /* every point starts from the standard cells: a refinement costs about
   * 8x per Newton step on dense matrices, and only the points that need it
   * should pay (kept refined, a hard stretch of a real rubber's curve took
   * 47 s for 12 points, 2.9 s at the standard cells) */
  bool coarsen = a->resolution < 1.0;
  if (coarsen) a->resolution = 1.0;
  if ((coarsen || needs_plan(a, v, prev)) && (s = rebuild(a, v, prev, err)) != VL_OK) return s;
  s = vl_contact_reach(a->c, v, 6, pt, st, err);
  if (s != VL_OK) return s;
  vl_contact_estimate_error(a->c, pt);
  const char *stop = NULL;
  for (int k = 0; k < o->max_refinements && !stop; k++) {
    bool edge = !o->keep_numerics && a->inlet_scale < 8.0 && strstr(pt->warnings, "domain edge");
    bool coarse = pt->error_estimate > o->target_error && can_refine(a);
    if (!edge && !coarse) break;
    double old_estimate = pt->error_estimate;
    s = refine(a, v, coarse ? 0.5 * a->resolution : a->resolution,
               edge ? 2.0 * a->inlet_scale : a->inlet_scale, pt, st, err);
    if (s == VL_ENOCONV) {
      stop = "refinement did not converge (coarser cells kept)";
      break;
    }
    if (s != VL_OK) return s;
    vl_contact_estimate_error(a->c, pt);
    if (coarse && !edge && !(pt->error_estimate < REFINE_MIN_GAIN * old_estimate))
      stop = "estimate not falling with refinement";
  }
  pt->accuracy = !(pt->error_estimate == pt->error_estimate) ? VL_ACCURACY_NO_ESTIMATE
                 : pt->error_estimate > o->target_error      ? VL_ACCURACY_ABOVE_TARGET
                                                             : VL_ACCURACY_MET;
  if (pt->accuracy == VL_ACCURACY_NO_ESTIMATE)
    append_warning(pt, "no error estimate (the coarser solve failed)");
  if (pt->error_estimate > o->target_error) {
    char w[120];
    snprintf(w, sizeof w, "error estimate %.2g %% above the target %.2g %%",
             100.0 * pt->error_estimate, 100.0 * o->target_error);
    append_warning(pt, w);
    if (stop) append_warning(pt, stop);
  }
  return VL_OK;
}

/* Points lo .. hi-1 failed and hi has converged on a's contact: each failed
 * point is solved again by continuation down from its neighbour above,
 * nearest first, until one fails (path 5 of vl_sweep_run, sweep.h), with its
 * own cells, estimate and refinement. The descent runs on a copy of a's
 * contact, so a goes on from hi unchanged. Every point lo .. hi-1 is
 * reported here, in decreasing speed. */
static void auto_recover_below(const auto_state *a, const vl_auto_options *o,
                               const vl_sweep_report *r, size_t lo, size_t hi) {
  auto_state down = {.base = a->base,
                     .layout = a->layout,
                     .plan_film = a->plan_film,
                     .resolution = a->resolution,
                     .inlet_scale = a->inlet_scale,
                     .c_resolution = a->c_resolution,
                     .c_inlet = a->c_inlet};
  size_t k = hi;
  if (vl_contact_create(&a->c->cfg, &down.c, NULL) == VL_OK &&
      vl_contact_start_from(down.c, a->c)) {
    vl_contact_set_max_iterations(down.c, a->base.max_iterations); /* a->c may be capped */
    for (; k > lo; k--) {
      vl_point pt;
      vl_error e;
      if (auto_point(&down, o, r->v[k - 1], &r->out[k], &pt, r->st, &e) != VL_OK) break;
      r->out[k - 1] = pt;
      r->st->recovered_below++;
      vl_sweep_report_point(r, k - 1, down.c);
    }
  }
  free_state(&down);
  while (k-- > lo)
    vl_sweep_report_point(r, k, NULL);
}

vl_status vl_sweep_run_auto(const vl_contact_config *base, const vl_auto_options *opt, size_t n,
                            const double *v0_m_s, vl_point *out, vl_sweep_callback cb, void *user,
                            vl_sweep_stats *stats, vl_error *err) {
  vl_auto_options o = {VL_TARGET_ERROR_DEFAULT, VL_AUTO_MAX_REFINEMENTS, false};
  if (opt && opt->target_error > 0.0) o.target_error = opt->target_error;
  if (opt && opt->max_refinements >= 0) o.max_refinements = opt->max_refinements;
  if (opt && opt->keep_numerics) o.keep_numerics = true, o.max_refinements = 0;
  for (size_t i = 0; i < n; i++) {
    if (!(v0_m_s[i] > 0.0 && isfinite(v0_m_s[i]))) {
      vl_error_set(err, "sweep speed %zu must be positive and finite (got %g m/s)", i + 1,
                   v0_m_s[i]);
      return VL_EINPUT;
    }
  }
  auto_state a = {.base = *base, .resolution = 1.0, .inlet_scale = 1.0};
  a.layout = !o.keep_numerics && base->eta_pa_s > 0.0 && !base->roughness;
  vl_sweep_stats st;
  memset(&st, 0, sizeof st);
  double t0 = vl_contact_now_s();
  const vl_point *prev = NULL;
  vl_status s = VL_OK;
  vl_sweep_report r = {v0_m_s, n, out, cb, user, &st};
  size_t pending = 0, end = n; /* points pending .. i-1 failed and are not reported yet */
  for (size_t i = 0; i < n; i++) {
    vl_error e;
    s = auto_point(&a, &o, v0_m_s[i], prev, &out[i], &st, &e);
    out[i].v0_m_s = v0_m_s[i];
    if (s == VL_ENOCONV) {
      prev = NULL;
      s = VL_OK;
      continue;
    }
    if (s != VL_OK) {
      if (err) *err = e;
      end = i;
      break;
    }
    if (pending < i) auto_recover_below(&a, &o, &r, pending, i);
    vl_sweep_report_point(&r, i, a.c);
    pending = i + 1;
    prev = &out[i];
  }
  for (size_t i = pending; i < end; i++) /* failed with nothing converged above */
    vl_sweep_report_point(&r, i, NULL);
  st.seconds = vl_contact_now_s() - t0;
  if (stats) *stats = st;
  free_state(&a);
  return s;
}
