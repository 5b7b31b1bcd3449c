/* viscolube: what the two sweeps (sweep.c, sweep_auto.c) share. */
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

#endif
