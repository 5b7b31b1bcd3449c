/* Continuation in speed with step control (sweep.h). */
#include "viscolube/sweep.h"

#include "contact_internal.h"

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
static vl_status solve_point(vl_contact *c, double last_ok, double v, int max_depth, vl_point *pt,
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
  double last_ok = 0.0;
  for (size_t i = 0; i < n; i++) {
    vl_error e;
    vl_status s = solve_point(c, last_ok, v0_m_s[i], opt->max_subdivisions, &out[i], &st, &e);
    if (s == VL_OK) {
      st.converged++;
      last_ok = v0_m_s[i];
    } else if (s == VL_ENOCONV) {
      st.failed++;
      last_ok = 0.0; /* the state is the Hertz guess now */
    } else {
      if (err) *err = e;
      return s;
    }
    out[i].v0_m_s = v0_m_s[i];
    if (cb) cb(user, i, n, &out[i], c);
  }
  clock_gettime(CLOCK_MONOTONIC, &t1);
  st.seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
  if (stats) *stats = st;
  return VL_OK;
}
