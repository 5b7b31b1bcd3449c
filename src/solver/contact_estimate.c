/* The error estimate of a point (numerics.h): the same point on cells
 * three times as wide. */
#include "contact_private.h"
#include "numerics_plan.h"

#include <math.h>
#include <stdlib.h>

#include "contact_internal.h"

#define MU_FLOOR 1e-9

/* The companion contact of c on cells three times as wide, created on first
 * use (NULL when it cannot be made: too few cells). */
static vl_contact *estimator(vl_contact *c) {
  if (c->estimator || c->n < 3 * VL_CONTACT_MIN_GRID) return c->estimator;
  vl_contact_config cfg = c->cfg;
  size_t *spans = NULL;
  cfg.cell_spans = NULL;
  if (c->cfg.cell_spans && c->span) {
    spans = malloc(c->n * sizeof *spans);
    if (!spans) return NULL;
    cfg.n_cells = vl_contact_merge_cells(c->span, c->n, spans);
    cfg.cell_spans = spans;
  } else if (c->span) {
    /* a graded inlet: also half as long, since mu converges like 1/X in the
     * inlet length X (docs/NUMERICS.md section 10): the change then holds
     * the truncation error of the inlet as well */
    double dx = (c->cfg.x_max_a0 - c->cfg.x_min_a0) / (double)c->cfg.grid;
    cfg.x_min_a0 = 0.5 * c->cfg.x_min_a0;
    cfg.grid = (size_t)round((cfg.x_max_a0 - cfg.x_min_a0) / (3.0 * dx));
  } else {
    cfg.grid = c->cfg.grid / 3;
  }
  if (vl_contact_create(&cfg, &c->estimator, NULL) != VL_OK) c->estimator = NULL;
  free(spans);
  return c->estimator;
}

void vl_contact_estimate_error(vl_contact *c, vl_point *pt) {
  pt->error_estimate = pt->flux_error_estimate = NAN;
  if (!pt->converged) return;
  vl_contact *e = estimator(c);
  if (!e) return;
  if (e->wet && e->cfg.eta_pa_s != c->cfg.eta_pa_s)
    vl_contact_set_viscosity(e, c->cfg.eta_pa_s, NULL);
  vl_point ep;
  /* from the point itself: on its branch (the coarse contact's own previous
   * state may lie decades of speed away, across a transition) */
  vl_contact_start_from(e, c);
  if (vl_contact_solve(e, pt->v0_m_s, &ep, NULL) != VL_OK) {
    vl_contact_reset(e); /* continuation lost: a fresh start */
    if (vl_contact_solve(e, pt->v0_m_s, &ep, NULL) != VL_OK) return;
  }
  /* relative to mu, but a friction below MU_FLOOR is zero for every
   * purpose (an elastic contact's mu is round-off: 1e-17) */
  double scale = fmax(fabs(pt->mu), MU_FLOOR);
  pt->error_estimate = 0.5 * fabs(pt->mu - ep.mu) / scale;
  /* the domain's outlet end: the film's shear beyond it */
  pt->error_estimate += vl_contact_outlet_tail(c, pt);
  /* the leakage the same way (a seal's flux, docs/MODEL.md section 12) */
  if (c->wet && pt->flux_m2_s != 0.0)
    pt->flux_error_estimate = 0.5 * fabs(pt->flux_m2_s - ep.flux_m2_s) / fabs(pt->flux_m2_s);
}
