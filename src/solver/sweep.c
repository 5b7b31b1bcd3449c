/* Continuation in speed with step control (sweep.h). */
#include "viscolube/sweep.h"

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
      vl_error_set(err, "sweep speed %zu must be positive and finite (got %g m/s)", i + 1, v0_m_s[i]);
      return VL_EINPUT;
    }
  }
  struct timespec t0, t1;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  double last_ok = 0.0;
  for (size_t i = 0; i < n; i++) {
    vl_error e;
    vl_status s = reach(c, last_ok, v0_m_s[i], 0, opt->max_subdivisions, &out[i], &st, &e);
    if (s == VL_ENOCONV) {
      /* continuation can lose the branch where the solution changes fast (a
       * stiff rubber through its transition: 7 consecutive dry points failed
       * at Einf/E0 = 1e4 that a start from Hertz solves); the contact then
       * holds the last converged state, which the fresh start gives up */
      vl_contact_reset(c);
      st.fresh_starts++;
      s = vl_contact_solve(c, v0_m_s[i], &out[i], &e);
      st.newton_iterations += out[i].iterations;
      if (s == VL_ENOCONV) last_ok = 0.0; /* the state is the Hertz guess now */
    }
    if (s == VL_OK) {
      st.converged++;
      last_ok = v0_m_s[i];
    } else if (s == VL_ENOCONV) {
      st.failed++;
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
