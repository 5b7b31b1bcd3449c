/* viscolube: a Stribeck sweep by continuation in speed. */
#ifndef VISCOLUBE_SWEEP_H
#define VISCOLUBE_SWEEP_H

#include <stddef.h>

#include "viscolube/contact.h"
#include "viscolube/status.h"

/* Called after each requested speed; the contact holds that point's solution
 * when pt->converged (so vl_contact_fields may be called). */
typedef void (*vl_sweep_callback)(void *user, size_t index, size_t total, const vl_point *pt,
                                  const vl_contact *contact);

typedef struct {
  int max_subdivisions;  /* a failed step is split in 2, 4, ... up to 2^this */
} vl_sweep_options;

typedef struct {
  size_t converged, failed;
  long newton_iterations;  /* all solves, including sub-steps */
  size_t substeps;         /* extra solves inserted by step control */
  size_t fresh_starts;     /* points retried from the Hertz guess after continuation failed */
  double seconds;
} vl_sweep_stats;

void vl_sweep_options_defaults(vl_sweep_options *opt);

/* Solves at v0[0..n-1] in order (increasing speed recommended), each from the
 * previous converged solution. A failed step is retried through
 * geometrically spaced intermediate speeds (step halving in log v0), then
 * once from the Hertz guess (vl_contact_reset); a point that still fails is
 * reported with converged = false and the sweep goes on from the Hertz
 * guess. out[n] is filled.
 * Returns VL_OK even when some points failed (see stats); errors only for
 * bad input. */
vl_status vl_sweep_run(vl_contact *c, size_t n, const double *v0_m_s, const vl_sweep_options *opt,
                       vl_point *out, vl_sweep_callback cb, void *user, vl_sweep_stats *stats,
                       vl_error *err);

#endif
