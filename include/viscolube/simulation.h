/* viscolube: a scene made runnable: materials loaded from the database, the
 * contact solver configured with only the effects asked for, and the list
 * of sweep speeds. */
#ifndef VISCOLUBE_SIMULATION_H
#define VISCOLUBE_SIMULATION_H

#include <stdbool.h>
#include <stddef.h>

#include "viscolube/contact.h"
#include "viscolube/database.h"
#include "viscolube/point_contact.h"
#include "viscolube/scene.h"
#include "viscolube/status.h"
#include "viscolube/sweep.h"

typedef struct vl_simulation vl_simulation;

/* Loads the scene's materials from db and creates the solver. With
 * [effects] temperature = on the compound is taken at temperature_c by
 * its WLF shift of every retardation time (docs/MODEL.md section 2; when
 * viscoelastic: elastic moduli do not shift) and, when the fluid effect is
 * on, the fluid's viscosity by its law (fluid.h, vl_fluid_viscosity);
 * either failing is VL_EINPUT naming the scene, the temperature and the
 * material. */
vl_status vl_simulation_create(const vl_scene *scene, vl_db *db, vl_simulation **out,
                               vl_error *err);
void vl_simulation_free(vl_simulation *sim);

/* Number of sweep speeds: the scene's log-spaced points merged with its
 * fields_at values. */
size_t vl_simulation_points(const vl_simulation *sim);
/* True when fields are to be written at point i. */
bool vl_simulation_wants_fields(const vl_simulation *sim, size_t i);

/* The line contact's solver; NULL for a point contact ([contact] geometry =
 * ball or ellipsoid), whose points are each solved on their own cells
 * (vl_simulation_run_point_contact). */
vl_contact *vl_simulation_contact(vl_simulation *sim);
/* The Hertz scales of the relaxed modulus (docs/MODEL.md section 9 for a
 * cylinder, point_contact.h for a ball): a0 (m) and p0 (Pa). */
double vl_simulation_a0(const vl_simulation *sim);
double vl_simulation_p0(const vl_simulation *sim);
/* A point contact's Hertz ellipse with the relaxed modulus (semi-axes along
 * x and y, m); VL_EINPUT for a cylinder. */
vl_status vl_simulation_hertz_ellipse(const vl_simulation *sim, double *ax_m, double *by_m);
double vl_simulation_eta(const vl_simulation *sim); /* Pa s, 0 if no fluid named; with
                                                     * [effects] temperature and fluid on:
                                                     * at the scene's temperature */
double vl_simulation_tau(const vl_simulation *sim); /* s, one-term compounds, else 0 (and 0
                                                     * with [contact] moving = counterface:
                                                     * no memory) */
/* [effects] temperature = on: the scene's temperature_c (C) and the WLF
 * shift factor a_T its compound's times were multiplied by (1 in an
 * elastic scene). Off: NAN and 1 (every material at its reference
 * temperature). */
double vl_simulation_temperature_c(const vl_simulation *sim);
double vl_simulation_shift_factor(const vl_simulation *sim);
const vl_psd *vl_simulation_psd(const vl_simulation *sim); /* NULL when smooth */

/* "LAW: p = v, ... (pair C / S / F, SOURCE ...)": where sigma_s came from,
 * for CSV headers, JSON and manifests; NULL without a pair (the scene's
 * constant). Owned by sim. */
const char *vl_simulation_shear_law_text(const vl_simulation *sim);

/* The flow-factor model of the scene's rough film (vl_flow_factors_name)
 * and, for persson-emt, its film cut-off in *film_cutoff_m (else 0); NULL
 * (and 0) when the scene has no rough wet contact. film_cutoff_m may be
 * NULL. */
const char *vl_simulation_flow_factors(const vl_simulation *sim, double *film_cutoff_m);

/* Runs the sweep (vl_sweep_run_auto: continuation in speed, upwards from the
 * first speed, which may lie anywhere on the curve; a point continuation
 * misses is retried by fresh starts at, below and above its speed); every
 * point's warnings gain the model-assumption checks of assumptions.h before
 * cb sees it. A one-point scene (from = to) is a robust single solve: the
 * query `friction` needs nothing else. */
vl_status vl_simulation_run(vl_simulation *sim, vl_point *out, vl_sweep_callback cb, void *user,
                            vl_sweep_stats *stats, vl_error *err);
/* The same for a point contact (vl_point_contact_sweep: automatic numerics
 * per point, estimates, refinement), cb seeing each point's contact (its
 * 2-D fields); vl_simulation_run also runs a point contact's scene, its
 * callback then without a contact. VL_EINPUT for a cylinder. */
vl_status vl_simulation_run_point_contact(vl_simulation *sim, vl_point *out,
                                          vl_point_contact_callback cb, void *user,
                                          vl_sweep_stats *stats, vl_error *err);

/* The statistics of the last run's instroke ([seal] stroke = both: its
 * sweep at the same speeds, whose results are in each point's seal
 * result; the run's own statistics are the outstroke's); zero otherwise. */
const vl_sweep_stats *vl_simulation_instroke_stats(const vl_simulation *sim);

#endif
