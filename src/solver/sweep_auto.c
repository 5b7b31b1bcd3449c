/* The automatic sweep (numerics.h): numerics per run of points, an error
 * estimate on every point, refinement until it meets the target. */
#include "contact_private.h"
#include "numerics_plan.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
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
/* A rough film's (the wiper on glass, 1 mm/s ... 0.8 m/s: u_min ~ v0^0.30
 * to v0^0.35) */
#define ROUGH_FILM_SPEED_EXPONENT 0.35

#define AUTO_SPARES 3

typedef struct {
  vl_contact_config base;
  bool layout; /* smooth film: planned cells */
  vl_contact *c;
  vl_plan plan;
  double plan_film;    /* the film the layout was planned for (m) */
  double resolution;   /* vl_plan_input.resolution, or the grid's divisor */
  double inlet_scale;  /* vl_plan_input.inlet_scale, or the inlet's factor */
  double outlet_scale; /* vl_plan_input.outlet_scale, or the outlet's factor */
  double standard;     /* the resolution every point starts from (1) */
  bool reference;      /* a reference run: the domain's ends refined, not the cells */
  size_t max_cells;    /* most cells of a layout or refinement (VL_AUTO_MAX_CELLS) */
  bool unplanned;      /* this rough point keeps the standard cells, refined by halving: its
                        * planned cells did not converge, or its asperities hold it apart */
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
  if (a->outlet_scale != 1.0) return NULL; /* spares have the standard outlet */
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
  if (c->cfg.cell_spans || a->outlet_scale != 1.0) {
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

/* A rough contact whose smallest separation is below this fraction of the
 * floor of the planned films (vl_plan_rough_film_floor) is held apart by
 * its asperities (boundary lubrication: the fluid that carries load sits in
 * the roughness' valleys, which the flow factors average), not by a film
 * with edge zones, where the smooth film expected at its speed is below the
 * floor too: planned cells do not resolve anything there. fig05 on a 30 nm
 * surface at 1e-6 ... 6e-4 m/s (u_min 2e-12 ... 1e-11 m, the fluid carrying
 * 45-52 %, a smooth film of 0.06 h_rms at most) spent 5-6 s per point on
 * planned cells that did not converge. Where the smooth film is thicker than
 * the floor, such a separation is a collapsed film (below): the soft gel
 * lens of bench/rough/ (12 nm expected on 10 nm glass at 0.1 mm/s) gave mu
 * 40.7 at u_min 8e-12 m on the standard cells, 31.6 on cells half as wide,
 * and its estimate said 7.7 %. */
#define BOUNDARY_SEPARATION_SHARE 0.1

/* Whether pt's film has collapsed: no separation (u_min 0: a state below
 * Persson's contact law), or a separation far below the floor where a
 * smooth film would stand above it. Without roughness: u_min 0. */
static bool collapsed_separation(const auto_state *a, const vl_point *pt) {
  if (!(pt->u_min_m > 0.0)) return true;
  double floor = vl_plan_rough_film_floor(&a->base);
  return pt->u_min_m < BOUNDARY_SEPARATION_SHARE * floor &&
         vl_contact_film_estimate(&a->base, pt->v0_m_s) >= floor;
}

static bool held_by_asperities(const auto_state *a, const vl_point *pt) {
  double floor = vl_plan_rough_film_floor(&a->base);
  return pt->u_min_m > 0.0 && pt->u_min_m < BOUNDARY_SEPARATION_SHARE * floor &&
         !collapsed_separation(a, pt);
}

/* The film the layout at v is planned for: the last point's u_min carried
 * to v, or the estimate of a smooth film (0: the planner's own); the
 * planner floors a rough film at a fraction of h_rms. A rough film whose
 * last point collapsed (u_min 0) gets the smooth film's estimate too, not
 * the floor: the syringe plunger of bench/rough/ after its collapsed 0.1
 * mm/s point planned 3 points for a film of 1 nm where the film is 70-340
 * nm, and each failed every path of vl_contact_reach on them (20-48 s). */
static double expected_film(const auto_state *a, double v, const vl_point *prev) {
  double h = 0.0;
  double e = a->base.roughness ? ROUGH_FILM_SPEED_EXPONENT : FILM_SPEED_EXPONENT;
  if (prev && !collapsed_separation(a, prev)) h = prev->u_min_m * pow(v / prev->v0_m_s, e);
  if (a->base.roughness) {
    if (!(h > 0.0)) h = vl_contact_film_estimate(&a->base, v);
    h = fmax(h, vl_plan_rough_film_floor(&a->base));
  }
  return h;
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
  if (a->layout && !(a->unplanned && a->base.roughness)) {
    vl_plan_input in = {0.0,
                        0.0,
                        a->resolution,
                        a->inlet_scale,
                        a->outlet_scale,
                        prev ? prev->fluid_load_fraction : 0.0,
                        a->plan.spans != NULL,
                        a->max_cells};
    in.film_m = expected_film(a, v, prev);
    st = vl_plan_wet(&a->base, v, &in, plan, err);
    if (st != VL_OK) return st;
    *plan_film = in.film_m > 0.0 ? in.film_m : vl_contact_film_estimate(&a->base, v);
    if (plan->standard) vl_plan_free(plan); /* a rough film the graded cells resolve */
  }
  if (plan->spans) {
    st = vl_contact_create(&plan->cfg, out, err);
    if (st != VL_OK) {
      vl_plan_free(plan);
      return st;
    }
  } else if ((*out = spare_take(a))) {
    spare = true;
  } else {
    vl_contact_config cfg = a->base;
    cfg.grid = (size_t)round((double)cfg.grid / a->resolution);
    /* a pressure at the domain's ends: both ends moved out (the asperity
     * contact of a very rough surface reaches past 1.6 a0 downstream) */
    double len = cfg.x_max_a0 - cfg.x_min_a0;
    cfg.x_min_a0 *= a->inlet_scale;
    cfg.x_max_a0 *= sqrt(a->inlet_scale);
    if (a->outlet_scale != 1.0) { /* the same cells, more of them */
      cfg.x_max_a0 *= a->outlet_scale;
      cfg.grid = (size_t)round((double)cfg.grid * (cfg.x_max_a0 - cfg.x_min_a0) / len);
    }
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
  vl_plan_free(&a->plan); /* a->plan.spans: a->c is planned */
  if (plan->spans) a->plan = *plan;
  a->plan_film = plan_film;
}

static vl_status rebuild(auto_state *a, double v, const vl_point *prev, bool keep, vl_error *err) {
  /* a rough film on the standard cells that the standard cells still
   * resolve keeps its contact (and its state as it is) */
  if (keep && a->c && a->base.roughness && !a->plan.spans && a->c_resolution == a->standard &&
      a->c_inlet == 1.0 && a->outlet_scale == 1.0) {
    vl_plan p;
    vl_plan_input in = {expected_film(a, v, prev),
                        0.0,
                        a->standard,
                        1.0,
                        1.0,
                        prev ? prev->fluid_load_fraction : 0.0,
                        false,
                        a->max_cells};
    if (vl_plan_wet(&a->base, v, &in, &p, NULL) == VL_OK) {
      bool standard = p.standard;
      vl_plan_free(&p);
      if (standard) {
        a->plan_film = in.film_m;
        return VL_OK;
      }
    }
  }
  vl_contact *c;
  vl_plan plan;
  double film = 0.0;
  vl_status st = build(a, v, prev, &c, &plan, &film, NULL, err);
  if (st == VL_OK) install(a, c, &plan, film);
  return st;
}

/* Whether another refinement stays within the cost bound: a planned layout
 * that was not capped, or a grid whose doubled cells stay within
 * a->max_cells. */
static bool can_refine(const auto_state *a) {
  if (a->plan.spans) return !a->plan.capped;
  return 2 * vl_contact_grid(a->c) <= a->max_cells;
}

/* Whether a smooth film's layout no longer fits the film expected at v. */
static bool needs_plan(const auto_state *a, double v, const vl_point *prev) {
  if (!a->c) return true;
  if (!a->layout || !prev) return false;
  double h = expected_film(a, v, prev);
  if (a->base.roughness && !a->plan.spans) /* the standard cells: until the film carries load */
    return prev->fluid_load_fraction >= VL_PLAN_ROUGH_FLUID_SHARE && a->resolution == a->standard &&
           !held_by_asperities(a, prev);
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
static bool fail_refinements; /* vl_sweep_auto_fail_refinements */

void vl_sweep_auto_fail_refinements(bool on) { fail_refinements = on; }

static vl_status refine(auto_state *a, double v, double resolution, double inlet_scale,
                        double outlet_scale, vl_point *pt, vl_sweep_stats *st, vl_error *err) {
  double old_resolution = a->resolution, old_inlet = a->inlet_scale, old_outlet = a->outlet_scale;
  a->resolution = resolution, a->inlet_scale = inlet_scale, a->outlet_scale = outlet_scale;
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
  if (fail_refinements && s == VL_OK) s = VL_ENOCONV;
  if (s == VL_OK) {
    install(a, c, &plan, film);
    *pt = np;
    return VL_OK;
  }
  spare_put(a, c, a->resolution, a->inlet_scale);
  vl_plan_free(&plan);
  a->resolution = old_resolution, a->inlet_scale = old_inlet, a->outlet_scale = old_outlet;
  return s;
}

/* An estimate that a refinement did not lower below this fraction of the
 * coarser one is not converging with the cells (a first-order method's
 * falls to 1/2 per halving): the cells do not resolve the contact, and
 * further refinement only costs (fig05 on a 30 nm surface at 1e-7-1e-5
 * m/s: 15 %, 15 %, 26 % at 208, 330, 560 cells). */
#define REFINE_MIN_GAIN 0.7

/* A rough film whose shear beyond the outlet end (vl_contact_outlet_tail)
 * exceeds this share of the target gets its outlet moved OUTLET_STEP times
 * farther out. */
#define OUTLET_TAIL_SHARE 0.25
#define OUTLET_STEP 4.0

/* A fresh start of a's contact at v (the Hertz guess and the ladder's
 * starts without a state): pt and *s become its point when it converges to
 * a lifted film (u_min > 0) or when *s was a failure; else the contact
 * goes back to pt's state. */
static void lifted_start(auto_state *a, double v, vl_point *pt, vl_status *s, vl_sweep_stats *st) {
  vl_contact_mark m;
  memset(&m, 0, sizeof m);
  bool had = *s == VL_OK && vl_contact_mark_take(a->c, &m);
  vl_contact_reset(a->c);
  vl_point np;
  vl_error e;
  st->fresh_starts++;
  vl_status ns = vl_contact_solve(a->c, v, &np, &e);
  st->newton_iterations += np.iterations;
  if (ns == VL_OK && (!collapsed_separation(a, &np) || *s != VL_OK)) {
    *pt = np, *s = VL_OK;
  } else if (had) {
    vl_contact_mark_return(a->c, &m);
  }
  vl_contact_mark_free(&m);
}

/* A rough point pt solved on the standard cells solved again on its
 * planned cells (when the plan wants them): a collapsed point (u_min 0)
 * from a fresh start, else continued from pt with REFINE_MAX_ITERATIONS and
 * then a fresh start; as a refinement, a failure keeps the standard point
 * (with the warning "planned cells did not converge (standard cells
 * kept)"), since every path of the sweep on hundreds of cells costs
 * minutes (fig05 on a 30 nm surface near its lift-off). Returns whether a
 * fresh start was made. */
static bool replan(auto_state *a, double v, vl_point *pt, vl_sweep_stats *st) {
  vl_contact *c;
  vl_plan plan;
  double film = 0.0;
  bool continued, fresh = false;
  vl_error e;
  if (build(a, v, pt, &c, &plan, &film, &continued, &e) != VL_OK) return false;
  if (!plan.spans) { /* the standard cells resolve it after all */
    spare_put(a, c, a->resolution, a->inlet_scale);
    return false;
  }
  vl_point np;
  vl_status s = VL_ENOCONV;
  if (continued && !collapsed_separation(a, pt)) {
    vl_contact_set_max_iterations(c, c->cfg.max_iterations < REFINE_MAX_ITERATIONS
                                         ? c->cfg.max_iterations
                                         : REFINE_MAX_ITERATIONS);
    s = vl_contact_solve(c, v, &np, &e);
    st->newton_iterations += np.iterations;
    vl_contact_set_max_iterations(c, a->base.max_iterations);
  }
  if (s != VL_OK) {
    fresh = true;
    vl_contact_reset(c);
    st->fresh_starts++;
    s = vl_contact_solve(c, v, &np, &e);
    st->newton_iterations += np.iterations;
  }
  if (s == VL_OK && !(!collapsed_separation(a, pt) && collapsed_separation(a, &np))) {
    install(a, c, &plan, film);
    *pt = np;
    return fresh;
  }
  vl_contact_free(c);
  vl_plan_free(&plan);
  append_warning(pt, "planned cells did not converge (standard cells kept)");
  a->unplanned = true; /* its refinements double the standard cells */
  return fresh;
}

/* A rough film that has collapsed (u_min 0: a separation below Persson's
 * contact law) while the fluid carries load is a state of cells too coarse
 * for its edge zones, not the film: the wiper at 1 mm/s gives mu 0.48 on
 * the standard cells, 0.092 on its planned ones, where no start at that
 * speed finds the film (fresh starts, 2 decades above) but continuation
 * from a lifted neighbour does. Such a point is reported as failed to the
 * sweep's loop, which comes back to it from the next converged point
 * (path 5 of sweep.h); it keeps the collapsed state, without an estimate,
 * when that fails too. */
static bool collapsed_film(const auto_state *a, const vl_point *pt) {
  return a->layout && a->base.roughness && !a->reference && collapsed_separation(a, pt) &&
         pt->fluid_load_fraction >= 0.01;
}

/* Levels of one point's cells (each halving the widths of the last) kept
 * for the estimate of richardson. */
#define VL_AUTO_MAX_REFINEMENTS_CAP 8

/* The estimate of a refined point pt from the sequence of its levels (mu
 * at widths 1, 1/2, ...: *n of them before pt): with two levels the change
 * |mu - mu_coarser| (the error of a first-order method; the companion's
 * estimate sits on the coarser cells' branch when those collapse: the
 * wiper at 1 mm/s, 185 %), with three or more the observed order p (kept
 * within 1 ... 3) and twice Richardson's |mu - mu_coarser| / (2^p - 1).
 * The wiper's levels (529, 868, 1478 cells at 1 mm/s: 0.0982, 0.0930,
 * 0.0921) converge at order 2.6; the companion's estimate, first order on
 * cells 3x wider, overestimated their error by 4-8x. The outlet's tail
 * (vl_contact_outlet_tail) stays in the estimate. */
static void richardson(vl_contact *c, vl_point *pt, double *mu, int *n) {
  if (*n >= VL_AUTO_MAX_REFINEMENTS_CAP || *n < 1) return;
  mu[(*n)++] = pt->mu;
  double scale = fmax(fabs(pt->mu), 1e-9);
  double d1 = fabs(mu[*n - 1] - mu[*n - 2]), est = d1 / scale;
  if (*n >= 3) {
    double d0 = fabs(mu[*n - 2] - mu[*n - 3]);
    double p = d1 > 0.0 && d0 > 0.0 ? log2(d0 / d1) : 1.0;
    p = fmin(fmax(p, 1.0), 3.0);
    est = fmin(est, 2.0 * d1 / (pow(2.0, p) - 1.0) / scale);
  }
  pt->error_estimate = est + vl_contact_outlet_tail(c, pt);
}

/* The point's accuracy against the target, and the warning that says
 * when it is not met. */
static void set_accuracy(vl_point *pt, double target) {
  pt->accuracy = !(pt->error_estimate == pt->error_estimate) ? VL_ACCURACY_NO_ESTIMATE
                 : pt->error_estimate > target               ? VL_ACCURACY_ABOVE_TARGET
                                                             : VL_ACCURACY_MET;
  if (pt->accuracy == VL_ACCURACY_NO_ESTIMATE) {
    append_warning(pt, "no error estimate (the coarser solve failed)");
  } else if (pt->accuracy == VL_ACCURACY_ABOVE_TARGET) {
    char w[120];
    snprintf(w, sizeof w, "error estimate %.2g %% above the target %.2g %%",
             100.0 * pt->error_estimate, 100.0 * target);
    append_warning(pt, w);
  }
}

/* The estimate of pt, converged at v on a's contact, and its refinement
 * while above the target and the refinements still lower the estimate
 * (with the domain's ends moved out where they are too close); pt's
 * accuracy set. VL_OK unless a refinement hit an error other than
 * non-convergence (a failed refinement keeps pt, with a warning). */
static vl_status estimate_and_refine(auto_state *a, const vl_auto_options *o, double v,
                                     vl_point *pt, vl_sweep_stats *st, vl_error *err) {
  vl_status s;
  vl_contact_estimate_error(a->c, pt);
  const char *stop = NULL;
  char failed[160] = "";
  double mu_level[1 + VL_AUTO_MAX_REFINEMENTS_CAP];
  int levels = 1;
  mu_level[0] = pt->mu;
  for (int k = 0; k < o->max_refinements && !stop; k++) {
    bool edge = !o->keep_numerics && a->inlet_scale < 8.0 && strstr(pt->warnings, "domain edge");
    /* the film still shears at the outlet end: the outlet moved out */
    bool outlet = !o->keep_numerics && a->outlet_scale < 16.0 &&
                  vl_contact_outlet_tail(a->c, pt) > OUTLET_TAIL_SHARE * o->target_error;
    bool coarse = !a->reference && pt->error_estimate > o->target_error && can_refine(a);
    if (!edge && !coarse && !outlet) break;
    double old_estimate = pt->error_estimate;
    s = refine(a, v, coarse ? 0.5 * a->resolution : a->resolution,
               edge ? 2.0 * a->inlet_scale : a->inlet_scale,
               outlet ? OUTLET_STEP * a->outlet_scale : a->outlet_scale, pt, st, err);
    if (s == VL_ENOCONV) {
      snprintf(failed, sizeof failed,
               "refinement did not converge; estimate %.2g %% of the coarser cells",
               100.0 * pt->error_estimate);
      stop = failed;
      break;
    }
    if (s != VL_OK) return s;
    vl_contact_estimate_error(a->c, pt);
    if (a->base.roughness && coarse && !edge && !outlet)
      richardson(a->c, pt, mu_level, &levels);
    else
      mu_level[0] = pt->mu, levels = 1; /* another domain: a new sequence */
    if (coarse && !edge && !outlet && !(pt->error_estimate < REFINE_MIN_GAIN * old_estimate))
      stop = "estimate not falling with refinement";
  }
  set_accuracy(pt, o->target_error);
  if (pt->accuracy == VL_ACCURACY_ABOVE_TARGET) {
    if (stop) append_warning(pt, stop);
  } else if (stop == failed) {
    append_warning(pt, stop); /* never silently: the finer cells were wanted */
  }
  return VL_OK;
}

/* One point: solved, estimated and refined (estimate_and_refine). */
static vl_status auto_point(auto_state *a, const vl_auto_options *o, double v, const vl_point *prev,
                            vl_point *pt, vl_sweep_stats *st, vl_error *err) {
  vl_status s = VL_OK;
  /* every point starts from the standard cells: a refinement costs about
   * 8x per Newton step on dense matrices, and only the points that need it
   * should pay (kept refined, a hard stretch of a real rubber's curve took
   * 47 s for 12 points, 2.9 s at the standard cells) */
  a->unplanned = false;
  bool coarsen = a->resolution < a->standard || a->outlet_scale != 1.0;
  if (coarsen) a->resolution = a->standard, a->outlet_scale = 1.0;
  if ((coarsen || needs_plan(a, v, prev)) && (s = rebuild(a, v, prev, !coarsen, err)) != VL_OK)
    return s;
  s = vl_contact_reach(a->c, v, 6, pt, st, err);
  /* a rough film on the standard cells that turns out to carry load with
   * edge zones below those cells: solved again on its planned cells */
  bool fresh = false;
  if (s == VL_OK && a->base.roughness && !a->plan.spans && held_by_asperities(a, pt))
    a->unplanned = true;
  else if (s == VL_OK && a->layout && a->base.roughness && !a->plan.spans &&
           pt->fluid_load_fraction >= VL_PLAN_ROUGH_FLUID_SHARE)
    fresh = replan(a, v, pt, st);
  /* a collapsed rough film (U <= 0 somewhere: outside Persson's contact law,
   * a solution of coarse cells) while the fluid carries load: a fresh start
   * on the same cells, which finds the lifted film where there is one */
  if (s == VL_OK && !fresh && a->base.roughness && a->plan.spans && collapsed_separation(a, pt) &&
      pt->fluid_load_fraction >= 0.01)
    lifted_start(a, v, pt, &s, st);
  if (s != VL_OK) return s;
  if (collapsed_film(a, pt)) {
    pt->error_estimate = NAN;
    pt->accuracy = VL_ACCURACY_NO_ESTIMATE;
    append_warning(pt, "collapsed film (u_min 0, or far below the film expected, while the fluid "
                       "carries load): a state of cells too coarse, kept only if no film is "
                       "reached from a neighbour");
    return VL_ENOCONV;
  }
  return estimate_and_refine(a, o, v, pt, st, err);
}

/* A collapsed film at v (collapsed_film) reached from a's lifted state
 * above by continuation on a's own cells (no re-planning, which would start
 * from the standard cells that collapse, and Newton capped at
 * REFINE_MAX_ITERATIONS: the wiper at 1 mm/s takes 17 iterations from 3.8
 * mm/s; a wiper-like contact of tests/test_rough_films.c, whose lifted
 * neighbour is itself 110 % off, spent 120 s in a deep descent that failed);
 * the point, estimated and refined, when it lands on a lifted film. */
#define LIFT_MAX_DEPTH 2 /* at most 4 sub-steps: on refined cells each costs seconds */
static bool lift_from_above(auto_state *a, const vl_auto_options *o, double v, vl_point *pt,
                            vl_sweep_stats *st) {
  vl_error e;
  vl_contact_set_max_iterations(a->c, REFINE_MAX_ITERATIONS);
  vl_status s = vl_contact_ramp(a->c, v, LIFT_MAX_DEPTH, pt, st, &e);
  vl_contact_set_max_iterations(a->c, a->base.max_iterations);
  if (s != VL_OK || collapsed_separation(a, pt)) return false;
  return estimate_and_refine(a, o, v, pt, st, &e) == VL_OK;
}

/* Points lo .. hi-1 failed and hi has converged on a's contact: each failed
 * point is solved again by continuation down from its neighbour above,
 * nearest first, until one fails (path 5 of vl_sweep_run, sweep.h): first
 * on the neighbour's cells (lift_from_above), then, for a point that did
 * not converge, as a point of its own (auto_point: the standard cells, on
 * which the syringe's 0.4 mm/s point collapsed below its lifted neighbour),
 * each with its estimate and refinement. The descent runs on a copy of a's
 * contact, so a goes on from hi unchanged. Every point lo .. hi-1 is
 * reported here, in decreasing speed. */
static void auto_recover_below(const auto_state *a, const vl_auto_options *o,
                               const vl_sweep_report *r, size_t lo, size_t hi) {
  auto_state down = {.base = a->base,
                     .layout = a->layout,
                     .plan_film = a->plan_film,
                     .resolution = a->resolution,
                     .standard = a->standard,
                     .reference = a->reference,
                     .max_cells = a->max_cells,
                     .inlet_scale = a->inlet_scale,
                     .outlet_scale = a->outlet_scale,
                     .c_resolution = a->c_resolution,
                     .c_inlet = a->c_inlet};
  size_t k = hi;
  if (vl_contact_create(&a->c->cfg, &down.c, NULL) == VL_OK &&
      vl_contact_start_from(down.c, a->c)) {
    vl_contact_set_max_iterations(down.c, a->base.max_iterations); /* a->c may be capped */
    for (; k > lo; k--) {
      vl_point pt;
      vl_error e;
      if (!lift_from_above(&down, o, r->v[k - 1], &pt, r->st) &&
          (r->out[k - 1].converged ||
           auto_point(&down, o, r->v[k - 1], &r->out[k], &pt, r->st, &e) != VL_OK))
        break;
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
  auto_state a = {.base = *base, .standard = 1.0, .inlet_scale = 1.0, .outlet_scale = 1.0};
  /* reference runs (bench/rough_estimate.sh): every width times this, no
   * refinement */
  const char *ref = getenv("VISCOLUBE_AUTO_RESOLUTION");
  if (ref && atof(ref) > 0.0 && atof(ref) <= 1.0) a.standard = atof(ref), a.reference = true;
  a.resolution = a.standard;
  /* and the most cells a layout or refinement takes (reference runs: more
   * than the automatic sweep's finest level reaches) */
  a.max_cells = VL_AUTO_MAX_CELLS;
  const char *cap = getenv("VISCOLUBE_AUTO_MAX_CELLS");
  if (cap && atol(cap) >= VL_AUTO_MAX_CELLS) a.max_cells = (size_t)atol(cap);
  /* and the most refinements per point (reference runs: up to the cap) */
  const char *nref = getenv("VISCOLUBE_AUTO_MAX_REFINEMENTS");
  if (nref && !o.keep_numerics && atoi(nref) >= 0)
    o.max_refinements =
        atoi(nref) < VL_AUTO_MAX_REFINEMENTS_CAP ? atoi(nref) : VL_AUTO_MAX_REFINEMENTS_CAP;
  a.layout = !o.keep_numerics && base->eta_pa_s > 0.0;
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
      prev = out[i].converged ? &out[i] : NULL; /* a collapsed film: its cells' state */
      /* not continued from: the next point starts afresh, and from below
       * (the gel lens at 0.4 mm/s spent 9 s continuing from its collapsed
       * neighbour, at 6.3 mm/s the start from below found the film) */
      if (prev) vl_contact_reset(a.c);
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
