/* Continuation in speed with step control (sweep.h). */
#include "viscolube/sweep.h"

#include "contact_internal.h"
#include "sweep_internal.h"

#include <math.h>
#include <string.h>
#include <time.h>

void vl_sweep_options_defaults(vl_sweep_options *opt) { opt->max_subdivisions = 6; }

/* Reaches speed `to` from the current (converged at `from`) state through
 * intermediate speeds when the direct step fails. depth counts halvings. */
static vl_status reach(vl_contact *c, double from, double to, int depth, int max_depth,
                       vl_point *pt, vl_sweep_stats *st, vl_error *err) {
  vl_status s = vl_contact_solve(c, to, pt, err);
  st->newton_iterations += pt->iterations;
  if (s != VL_ENOCONV || depth >= max_depth || !(from > 0.0)) return s;
  double mid = sqrt(from * to); /* halve the step in log speed */
  vl_point tmp;
  st->substeps++;
  s = reach(c, from, mid, depth + 1, max_depth, &tmp, st, err);
  if (s != VL_OK) return s;
  return reach(c, mid, to, depth + 1, max_depth, pt, st, err);
}

/* Continuation from the state converged at `from` to `to` (either way)
 * with step control: steps of RAMP_FIRST_DECADES, doubled (up to one
 * decade) after a step that took at most RAMP_EASY_ITERATIONS Newton
 * iterations; a failed step is halved as in reach. Only `to` is reported
 * (pt). */
#define RAMP_FIRST_DECADES 0.25
#define RAMP_EASY_ITERATIONS 8
static vl_status ramp(vl_contact *c, double from, double to, int max_depth, vl_point *pt,
                      vl_sweep_stats *st, vl_error *err) {
  double v = from, h = RAMP_FIRST_DECADES, dir = to > from ? 1.0 : -1.0;
  for (;;) {
    double next = v * pow(10.0, dir * h);
    if (dir * (next - to) >= -1e-12 * to) return reach(c, v, to, 0, max_depth, pt, st, err);
    vl_point tmp;
    st->substeps++;
    vl_status s = reach(c, v, next, 0, max_depth, &tmp, st, err);
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
 * fresh starts of vl_contact_solve find both). On failure the contact
 * holds the Hertz guess. */
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
    s = ramp(c, start, v, max_depth, pt, st, err);
    if (s != VL_ENOCONV) return s;
    break; /* a start that does not carry to v will not from farther away either */
  }
  vl_contact_reset(c);
  return s;
}

/* Solves point v from the state converged at last_ok (0: none), by every
 * path in turn (sweep.h). On VL_ENOCONV the contact holds the Hertz guess
 * and pt the failure at v itself. */
vl_status vl_sweep_solve_point(vl_contact *c, double last_ok, double v, int max_depth, vl_point *pt,
                               vl_sweep_stats *st, vl_error *err) {
  /* far enough below to reach the boundary regime from the mixed one; close
   * above, since a fold of the curve (a film lifting off) is narrow */
  static const double below[] = {1.0, 2.0, 4.0, 8.0, 12.0}, above[] = {0.5, 1.0, 2.0};
  vl_status s = reach(c, last_ok, v, 0, max_depth, pt, st, err);
  /* a contact without a converged state (v_state 0) has just made the
   * fresh start: repeating it would fail the same way */
  if (s == VL_ENOCONV && c->v_state > 0.0) {
    /* continuation can lose the branch where the solution changes fast (a
     * stiff rubber through its transition: 7 consecutive dry points failed
     * at Einf/E0 = 1e4 that a start from Hertz solves); the contact then
     * holds the last converged state, which the fresh start gives up */
    vl_contact_reset(c);
    st->fresh_starts++;
    s = vl_contact_solve(c, v, pt, err);
    st->newton_iterations += pt->iterations;
  }
  vl_point other;
  vl_status so = VL_ENOCONV;
  /* from below only without a converged point below: continuation from
   * there has just failed */
  if (s == VL_ENOCONV && !(last_ok > 0.0 && last_ok < v)) {
    st->starts_below++;
    so = reach_from(c, v, -1.0, below, sizeof below / sizeof below[0], max_depth, &other, st, err);
  }
  if (s == VL_ENOCONV && so == VL_ENOCONV) {
    st->starts_above++;
    so = reach_from(c, v, 1.0, above, sizeof above / sizeof above[0], max_depth, &other, st, err);
  }
  if (s != VL_ENOCONV || so == VL_ENOCONV) return s;
  if (so == VL_OK) *pt = other;
  return so;
}

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
      if (ramp(c, r->v[k], r->v[k - 1], max_depth, &pt, r->st, &e) != VL_OK) break;
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
  double last_ok = 0.0;
  size_t pending = 0; /* points pending .. i-1 failed and are not reported yet */
  for (size_t i = 0; i < n; i++) {
    vl_error e;
    vl_status s =
        vl_sweep_solve_point(c, last_ok, v0_m_s[i], opt->max_subdivisions, &out[i], &st, &e);
    out[i].v0_m_s = v0_m_s[i];
    if (s == VL_OK) {
      if (pending < i) recover_below(c, &r, pending, i, opt->max_subdivisions);
      vl_sweep_report_point(&r, i, c);
      pending = i + 1;
      last_ok = v0_m_s[i];
    } else if (s == VL_ENOCONV) {
      last_ok = 0.0; /* the state is the Hertz guess now */
    } else {
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
