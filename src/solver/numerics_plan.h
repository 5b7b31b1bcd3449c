/* Automatic numerics (private to the solver; the automatic sweep is
 * vl_sweep_run_auto, viscolube/sweep.h). The domain and the cells of a contact
 * chosen from the physics of the operating point, and the layout refined
 * until an error estimate meets a target.
 *
 * A lubricated line contact has three lengths (docs/NUMERICS.md section 11):
 *   a     the contact half-width (the relaxed Hertz a0 for an elastic solid;
 *         narrower on a stiffer, faster viscoelastic one),
 *   L_h   the hydrodynamic inlet length sqrt(2 R h), h the film: the
 *         pressure of a rigid cylinder spreads over a few L_h, its inlet
 *         feeds from tens of L_h (Martin's film with the inlet at -X L_h is
 *         short by about 2.4/X^2: 0.07 % at 60 L_h),
 *   s     the width of the edge zones of a soft film: outside a Hertzian
 *         contact the gap opens like delta (4 sqrt 2/3) ((x - a)/a)^(3/2),
 *         delta = a^2/R, so it reaches the film h within
 *         s = a (3 h/(4 sqrt 2 delta))^(2/3) of the edge (a/700 for the
 *         soft EHL film at eta v0 = 1e-6 Pa m). The inlet meniscus and the
 *         outlet constriction live there.
 * The layout puts cells of s/32 at both edges of the contact, grows them by
 * at most 10 % a cell to the background width max(a/60, L_h/80) inside the
 * contact, and further upstream to inlet cells of a twentieth of the inlet;
 * the domain runs from a + 60 L_h (at least 2 a0 beyond the contact)
 * upstream to max(a + 0.6 a0, 2 L_h) downstream. Rough films (their film
 * floored at 0.1 h_rms) are planned only where the edge zone is below a
 * quarter of a standard a0/30 cell and the fluid carries load (else
 * vl_plan.standard): edge cells s/8, background a0/120, the validated rough
 * inlet (VL_WET_ROUGH_DOMAIN_MIN_A0) at least (docs/NUMERICS.md section
 * 11, "Rough films"). */
#ifndef VISCOLUBE_NUMERICS_PLAN_H
#define VISCOLUBE_NUMERICS_PLAN_H

#include <stdbool.h>
#include <stddef.h>

#include "viscolube/contact.h"
#include "viscolube/results.h"
#include "viscolube/status.h"
#include "viscolube/sweep.h"

/* Most cells an automatic layout may take (a dense solve of n cells costs
 * n^3/3 flops per Newton step: 1500 cells about 0.1 s). */
#define VL_AUTO_MAX_CELLS 1500

/* A rough film gets planned cells only where the fluid carries at least
 * this share of the load on the standard cells (a film that carries none
 * has no friction to lose in its edge zones: fig15's carries 5e-6 to 2e-4
 * of the load with s down to a0/160, and is within 0.2 % of its reference
 * on the standard cells). The standard cells underestimate that share
 * where they do not resolve the film: sbr-unfilled on glass at 0.01 m/s
 * (bench/rough/glass-sbr.ini) carries 0.5 % on them, 22 % on cells 4x
 * finer, 35 % on 8x, and its mu falls from 0.0280 to 0.0220 (a share of 1 %
 * kept the standard cells, with an estimate of 0.12 %). */
#define VL_PLAN_ROUGH_FLUID_SHARE 1e-3

/* What the planner knows of the point. */
typedef struct {
  double film_m;       /* minimum film estimate (m); 0: vl_contact_film_estimate's */
  double half_width_m; /* contact half-width (m); 0: the relaxed Hertz a0 */
  double resolution;   /* 1 = the standard layout; 0.5 = every width halved, ... */
  double inlet_scale;  /* 1 (or 0) = the standard inlet; 2 = twice as long, ... */
  double outlet_scale; /* 1 (or 0) = the standard outlet; 2 = twice as far, ... */
  double fluid_share;  /* a rough film: the fluid's share of the load expected (the
                        * last point's); below VL_PLAN_ROUGH_FLUID_SHARE the standard cells
                        * are kept */
  bool planned;        /* a rough film on planned cells now (kept planned longer) */
  size_t max_cells;    /* most cells of the layout; 0: VL_AUTO_MAX_CELLS (a reference run
                        * takes more) */
} vl_plan_input;

/* A planned layout: the configuration to give vl_contact_create (a copy of
 * the base with the domain, grid and cell_spans set; cell_spans points
 * into this struct, so keep it alive while the configuration is used). */
typedef struct {
  vl_contact_config cfg;
  size_t *spans;                           /* owned */
  double fine_a0, background_a0, inlet_a0; /* cell widths of the layout (a0) */
  double edge_zone_a0, inlet_length_a0;    /* s and L_h (a0) */
  int standard; /* a rough film whose edge zones the standard graded cells
                 * resolve: the caller may keep those (the layout is still made) */
  int capped;   /* the base grid hit VL_CONTACT_MAX_GRID_LAYOUT or the cells
                 * VL_AUTO_MAX_CELLS: the finest cells are wider than planned */
} vl_plan;

/* Plans the numerics of the wet contact base (materials, geometry, fluid set;
 * its numerics ignored, except the tolerance and solver) at speed v0.
 * VL_EINPUT when base is not wet, VL_ENOMEM. Free with vl_plan_free. */
vl_status vl_plan_wet(const vl_contact_config *base, double v0, const vl_plan_input *in,
                      vl_plan *out, vl_error *err);
void vl_plan_free(vl_plan *p);

/* The least film a rough film's layout is planned for (m): a fraction of
 * h_rms (0 for a smooth surface). */
double vl_plan_rough_film_floor(const vl_contact_config *base);

/* Relative error estimate of mu at a converged point pt of contact c: the
 * point solved again on cells three times as wide (every three cells of c
 * merged; a uniform or graded grid: a third of its cells), started from
 * the point's own solution interpolated onto those cells, and
 * |mu - mu_coarse| / (2 |mu|): the error of a first-order method whose
 * error falls by three (a second-order one's falls by nine: then an
 * overestimate by four). Sets pt->error_estimate (NAN when the coarse
 * solve fails: the caller reports "no estimate"). */
void vl_contact_estimate_error(vl_contact *c, vl_point *pt);

/* The friction of a rough film's shear beyond the outlet end of c's domain,
 * relative to pt->mu (0 for any other contact): the Couette shear of the
 * film leaving the last cell, carried on with its flux theta u and the
 * Hertz gap x^2/2R (the cavitated film still shears there: a lip seal at
 * 10 m/s gained 4.6 % of mu with the outlet moved from 1.6 to 12 a0). */
double vl_contact_outlet_tail(vl_contact *c, const vl_point *pt);

#endif
