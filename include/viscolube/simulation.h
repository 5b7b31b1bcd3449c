/* viscolube: a scene made runnable: materials loaded from the database, the
 * contact solver configured with only the effects asked for, and the list
 * of sweep speeds. */
#ifndef VISCOLUBE_SIMULATION_H
#define VISCOLUBE_SIMULATION_H

#include <stdbool.h>
#include <stddef.h>

#include "viscolube/contact.h"
#include "viscolube/database.h"
#include "viscolube/scene.h"
#include "viscolube/status.h"
#include "viscolube/sweep.h"

typedef struct vl_simulation vl_simulation;

/* Loads the scene's materials from db and creates the solver. */
vl_status vl_simulation_create(const vl_scene *scene, vl_db *db, vl_simulation **out,
                               vl_error *err);
void vl_simulation_free(vl_simulation *sim);

/* Sweep speeds (m/s, increasing): the scene's log-spaced points merged with
 * its fields_at values. */
size_t vl_simulation_points(const vl_simulation *sim);
const double *vl_simulation_speeds(const vl_simulation *sim);
/* True when fields are to be written at point i. */
bool vl_simulation_wants_fields(const vl_simulation *sim, size_t i);

vl_contact *vl_simulation_contact(vl_simulation *sim);
const vl_scene *vl_simulation_scene(const vl_simulation *sim);
double vl_simulation_eta(const vl_simulation *sim);      /* Pa s, 0 if no fluid named */
double vl_simulation_tau(const vl_simulation *sim);      /* s, one-term compounds, else 0 */
const vl_prony *vl_simulation_rubber(const vl_simulation *sim);
const vl_psd *vl_simulation_psd(const vl_simulation *sim); /* NULL when smooth */

/* Runs the sweep (continuation in speed). */
vl_status vl_simulation_run(vl_simulation *sim, vl_point *out, vl_sweep_callback cb, void *user,
                            vl_sweep_stats *stats, vl_error *err);

#endif
