/* A Stribeck sweep on one contact's cells (sweep_internal.h): the points
 * in order, each reached from the last converged one by the paths of
 * contact_solve.c, and the failed ones retried from above (path 5). */
#include "viscolube/sweep.h"

#include "contact_internal.h"
#include "sweep_internal.h"

#include <math.h>
#include <string.h>
#include <time.h>

void vl_sweep_options_defaults(vl_sweep_options *opt) { opt->max_subdivisions = 6; }

void vl_sweep_report_point(const vl_sweep_report *r, size_t i, const vl_contact *c) {
  r->out[i].v0_m_s = r->v[i];
  if (r->out[i].converged)
    r->st->converged++;
  else
    r->st->failed++;
  if (r->cb) r->cb(r->user, i, r->n, &r->out[i], c);
}

/* Points lo .. hi-1 failed on the way up and hi has converged (the contact
 * holds it): each failed point is retried by continuation down from its
 * neighbour above (ramp), nearest first, until one fails (the points below
 * it would have to be reached through it). A thin smooth film that no start
 * near its own speed finds is reached this way from a thicker one (the
 * hard-case matrix: films at 1e-12-1e-7 m/s on coarse grids). Every point
 * lo .. hi-1 is reported here, in decreasing speed; the contact then has
 * hi's state back. */
static void recover_below(vl_contact *c, const vl_sweep_report *r, size_t lo, size_t hi,
                          int max_depth) {
  vl_contact_mark mark = {0};
  size_t k = hi;
  if (vl_contact_mark_take(c, &mark)) {
    for (; k > lo; k--) {
      vl_point pt;
      vl_error e;
      if (vl_contact_ramp(c, r->v[k - 1], max_depth, &pt, r->st, &e) != VL_OK) break;
      r->out[k - 1] = pt;
      r->st->recovered_below++;
      vl_sweep_report_point(r, k - 1, c);
    }
    vl_contact_mark_return(c, &mark);
  }
  vl_contact_mark_free(&mark);
  while (k-- > lo)
    vl_sweep_report_point(r, k, c);
}

vl_status vl_sweep_run(vl_contact *c, size_t n, const double *v0_m_s, const vl_sweep_options *opt,
                       vl_point *out, vl_sweep_callback cb, void *user, vl_sweep_stats *stats,
                       vl_error *err) {
  vl_sweep_options defaults;
  if (!opt) {
    vl_sweep_options_defaults(&defaults);
    opt = &defaults;
  }
  vl_sweep_stats st;
  memset(&st, 0, sizeof st);
  for (size_t i = 0; i < n; i++) {
    if (!(v0_m_s[i] > 0.0 && isfinite(v0_m_s[i]))) {
      vl_error_set(err, "sweep speed %zu must be positive and finite (got %g m/s)", i + 1,
                   v0_m_s[i]);
      return VL_EINPUT;
    }
  }
  struct timespec t0, t1;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  vl_sweep_report r = {v0_m_s, n, out, cb, user, &st};
  size_t pending = 0; /* points pending .. i-1 failed and are not reported yet */
  for (size_t i = 0; i < n; i++) {
    vl_error e;
    vl_status s = vl_contact_reach(c, v0_m_s[i], opt->max_subdivisions, &out[i], &st, &e);
    out[i].v0_m_s = v0_m_s[i];
    if (s == VL_OK) {
      if (pending < i) recover_below(c, &r, pending, i, opt->max_subdivisions);
      vl_sweep_report_point(&r, i, c);
      pending = i + 1;
    } else if (s != VL_ENOCONV) {          /* (a failed point leaves the Hertz guess) */
      for (size_t k = pending; k < i; k++) /* the failed points before the error */
        vl_sweep_report_point(&r, k, c);
      if (err) *err = e;
      return s;
    }
  }
  for (size_t i = pending; i < n; i++) /* failed with nothing converged above */
    vl_sweep_report_point(&r, i, c);
  clock_gettime(CLOCK_MONOTONIC, &t1);
  st.seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
  if (stats) *stats = st;
  return VL_OK;
}
