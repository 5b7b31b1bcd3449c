/* viscolube: a Stribeck sweep, the points solved by continuation in speed
 * with numerics chosen per point (docs/NUMERICS.md sections 8 and 11). */
#ifndef VISCOLUBE_SWEEP_H
#define VISCOLUBE_SWEEP_H

#include <stddef.h>

#include "viscolube/contact.h"
#include "viscolube/status.h"

/* Called once for each requested speed, when its result is final; the
 * contact holds that point's solution when pt->converged (so
 * vl_contact_fields may be called), and may be NULL otherwise. Points come
 * in increasing index, except that a run of failed points comes (in
 * decreasing index) after the retry from the converged point above it. */
typedef void (*vl_sweep_callback)(void *user, size_t index, size_t total, const vl_point *pt,
                                  const vl_contact *contact);

typedef struct {
  size_t converged, failed;
  long newton_iterations; /* all solves, including sub-steps */
  size_t substeps;        /* extra solves inserted by step control */
  size_t fresh_starts;    /* points retried from the Hertz guess after continuation failed */
  size_t starts_below;    /* points retried from a fresh start at a lower speed */
  size_t starts_above;    /* points retried from a fresh start at a higher speed */
  size_t recovered_below; /* failed points reached later from the converged point above */
  double seconds;
} vl_sweep_stats;

/* Default relative error of mu a point should meet (scene key
 * [numerics] target_error). */
#define VL_TARGET_ERROR_DEFAULT 0.01

/* Refinements (every width halved) a point may take to meet its target. */
#define VL_AUTO_MAX_REFINEMENTS 2

/* Options of an automatic sweep. */
typedef struct {
  double target_error; /* relative error of mu to meet (<= 0: VL_TARGET_ERROR_DEFAULT) */
  int max_refinements; /* per point (< 0: VL_AUTO_MAX_REFINEMENTS) */
  bool keep_numerics;  /* base's numerics throughout (a scene's own [numerics]): every
                        * point still gets its estimate, none is refined */
} vl_auto_options;

/* The Stribeck sweep: solves at v0_m_s[0..n-1] (positive, in order) the
 * contact base describes, and reports each point once (out[0..n-1], and cb
 * when not NULL).
 *
 * Each point is reached from the last converged one by these paths in
 * turn (increasing speed is the direction continuation is easiest in: from
 * the boundary regime, where any start converges, up through the mixed
 * regime, where the film lifts the solid off gradually):
 *   1. continuation: a failed step is retried through geometrically spaced
 *      intermediate speeds (step halving in log v0, up to 64 sub-steps);
 *   2. a fresh start at v0 (the Hertz guess; a rough film that Hertz does
 *      not start is started from the dry contact or the smooth film at v0);
 *   3. without a converged point below v0 (the first point, or after a
 *      failed one): a fresh start 1, 2, 4, 8 or 12 decades below v0, the
 *      first that converges, continued up to v0 with step control (steps
 *      of a quarter decade, doubled up to a decade after easy steps,
 *      halved as in 1);
 *   4. a fresh start 0.5, 1 or 2 decades above v0, continued down to v0
 *      the same way: past a fold of the curve (a film that lifts off the
 *      asperities within a step) the lifted branch is found from above;
 *   5. when a later point converges: continuation down from it to the
 *      failed points below, nearest first, until one fails. The sweep then
 *      goes on from the later point.
 * A point that still fails is reported with converged = false (never NaN
 * or zero as if computed) and the sweep goes on.
 *
 * Numerics: a smooth film gets cells planned for its film (docs/NUMERICS.md
 * section 11), re-planned when the film it expects has changed by more
 * than 1.5x since the last plan; so does a rough film whose edge zones are
 * below the standard cells while the fluid carries at least 1 % of the
 * load (its film floored at 0.1 h_rms; a collapsed film, u_min 0, is
 * solved again from a fresh start); any other contact keeps base's
 * numerics. A rough film's estimate holds its shear beyond the outlet, and
 * the outlet is moved out (up to 16x) while that exceeds a quarter of the
 * target; a refined rough point's estimate comes from its levels
 * (Richardson with the observed order).
 * Every converged point gets an error estimate (results.h,
 * error_estimate: the point solved again on cells three times as wide);
 * above the target the numerics are refined (every width halved) and the
 * point solved again from the coarser solution, up to max_refinements
 * times within a bound on the cells (the next point starts from the
 * standard cells again), and a pressure that reaches the domain's ends
 * doubles the inlet (up to 8x) and moves the outlet by sqrt(2). A point
 * still above its target carries the warning "error estimate X % above the
 * target Y %"; one whose refinement did not converge "refinement did not
 * converge; estimate X % of the coarser cells"; one without an estimate
 * "no estimate". opt->keep_numerics keeps base's numerics throughout (every
 * point still gets its estimate). opt may be NULL (the defaults).
 *
 * The callback receives the contact that solved the point. Returns VL_OK
 * even when some points failed (see stats); errors only for bad input or
 * when out of memory. */
vl_status vl_sweep_run_auto(const vl_contact_config *base, const vl_auto_options *opt, size_t n,
                            const double *v0_m_s, vl_point *out, vl_sweep_callback cb, void *user,
                            vl_sweep_stats *stats, vl_error *err);

#endif
