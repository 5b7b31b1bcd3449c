/* viscolube: the sweep on one contact's cells (sweep.c; the automatic
 * sweep of viscolube/sweep.h runs its points on contacts whose cells it
 * chooses per point), and what the two sweeps share. */
#ifndef VISCOLUBE_SWEEP_INTERNAL_H
#define VISCOLUBE_SWEEP_INTERNAL_H

#include "viscolube/sweep.h"

/* Where a sweep reports its points, and counts them. */
typedef struct {
  const double *v; /* the requested speeds */
  size_t n;
  vl_point *out;
  vl_sweep_callback cb;
  void *user;
  vl_sweep_stats *st;
} vl_sweep_report;

/* Point i is final: its speed set, counted (converged or failed) and passed
 * to the callback with the contact that holds it. */
void vl_sweep_report_point(const vl_sweep_report *r, size_t i, const vl_contact *c);

typedef struct {
  int max_subdivisions; /* a failed step is split in 2, 4, ... up to 2^this */
} vl_sweep_options;

void vl_sweep_options_defaults(vl_sweep_options *opt);

/* Solves at v0[0..n-1] in order, each from the previous converged
 * solution. Increasing speed is the direction continuation is easiest in:
 * from the boundary regime, where any start converges, up through the
 * mixed regime, where the film lifts the solid off gradually (a fresh start
 * in the hydrodynamic regime misses the lifted film). Every point is tried
 * by these paths in turn:
 *   1. continuation: a failed step is retried through geometrically spaced
 *      intermediate speeds (step halving in log v0, up to
 *      2^max_subdivisions sub-steps);
 *   2. a fresh start at v0 (vl_contact_reset; vl_contact_solve then starts
 *      a rough film that Hertz does not from the dry contact at v0);
 *   3. without a converged point below v0 (the first point, or after a
 *      failed one): a fresh start 1, 2, 4, 8 or 12 decades below v0, the
 *      first that converges, continued up to v0 with step control (steps
 *      of a quarter decade, doubled up to a decade after easy steps,
 *      halved as in 1);
 *   4. a fresh start 0.5, 1 or 2 decades above v0, continued down to v0
 *      the same way: past a fold of the curve (a film that lifts off the
 *      asperities within a step: the mixed branch ends) the lifted branch
 *      is found from above;
 *   5. when a later point converges: continuation down from it to the
 *      failed points below, nearest first, until one fails (a thin film
 *      that no start near its own speed finds is reached from a thicker
 *      one). The sweep then goes on from the later point.
 * So the first point need not lie in the boundary regime. Only the
 * requested speeds are reported (cb, out), each once; a run of failed
 * points is reported after path 5 was tried for it, in decreasing speed,
 * just before the converged point above it (or at the end). A point that
 * still fails is reported with converged = false and the sweep goes on
 * from the Hertz guess. out[n] is filled.
 * Returns VL_OK even when some points failed (see stats); errors only for
 * bad input. */
vl_status vl_sweep_run(vl_contact *c, size_t n, const double *v0_m_s, const vl_sweep_options *opt,
                       vl_point *out, vl_sweep_callback cb, void *user, vl_sweep_stats *stats,
                       vl_error *err);

/* Test aid: while on, every refinement of the automatic sweep is taken as
 * not converged (its finer cells discarded), the path a refinement takes
 * when its Newton fails; tests/test_auto_refine.c checks that the coarser
 * point is kept and warned. Not thread-safe; the program never sets it. */
void vl_sweep_auto_fail_refinements(bool on);

#endif
