/* viscolube: friction of wet rubber contacts, from first principles.
 *
 * A smooth rigid cylinder slides on a randomly rough viscoelastic half-space
 * lubricated by a Newtonian fluid (Scaraggi & Persson's mean-field theory of
 * viscoelastic lubrication). For each sliding speed the library solves, as
 * one nonlinear system (KINSOL, dense Jacobian), the rubber's viscoelastic
 * deformation, Persson's rough-contact law and an averaged Reynolds equation,
 * and reports the friction coefficient and its four parts. docs/MODEL.md
 * gives the equations and the one sign convention; docs/NUMERICS.md the
 * discretisation; docs/FORMATS.md the files.
 *
 * This header is the library's manual: include it and nothing else. It
 * declares what a program calls (src/cli and the Python package call
 * nothing else); the plumbing between the library's layers and its test
 * hooks are private headers of src/ (scripts/api-users.py lists who calls
 * each public function).
 *
 * Conventions
 *   - SI units at every interface; names carry them (radius_m,
 *     load_n_per_m, eta_pa_s, v0_m_s).
 *   - Every fallible call returns a vl_status (VL_OK = 0) and fills a
 *     caller-owned vl_error with a message; the library never prints and
 *     never exits (status.h).
 *   - Whoever creates an object frees it with the matching _free call.
 *
 * A program, in four steps (src/cli does exactly this):
 *
 *   1. Open the material database (database.h). With a NULL path the
 *      default one, created on first use from the materials shipped in the
 *      program:
 *        vl_db *db;  vl_error err;
 *        if (vl_db_open(NULL, &db, &err) != VL_OK) ... err.msg ...
 *      Compounds (Prony series, rheology.h; measured DMA data, dma.h),
 *      surfaces (power spectra, roughness.h) and fluids (fluid.h) are
 *      listed, added and removed there.
 *
 *   2. Describe the contact: a scene (scene.h) names a compound, a surface
 *      and a fluid, the load, the radius, the speeds and the effects to
 *      simulate; read it from an INI file or fill a vl_scene in code
 *      (vl_scene_defaults, then set the fields).
 *        vl_scene sc;  vl_scene_load("cases/fig05.ini", &sc, &err);
 *
 *   3. Make it runnable and solve (simulation.h): the materials are loaded,
 *      the solver (contact.h) configured with only the effects asked for,
 *      and a sweep (sweep.h) carries each solution to the next speed.
 *        vl_simulation *sim;
 *        vl_simulation_create(&sc, db, &sim, &err);
 *        vl_point *pts = calloc(vl_simulation_points(sim), sizeof *pts);
 *        vl_simulation_run(sim, pts, NULL, NULL, &stats, &err);
 *      A contact configured in code (contact.h) is solved point by point
 *      with vl_contact_solve(contact, v0, &pt, &err), or swept with
 *      vl_sweep_run_auto (sweep.h); examples/point.c and examples/stribeck.c
 *      do each in fifty lines. A ball (point_contact.h) is solved point by
 *      point the same way (examples/ball.c). The
 *      command line's friction query, robustly (continuation when a
 *      direct solve fails), with its defaults: vl_query_friction (query.h).
 *
 *   4. Read the results (results.h): each vl_point holds mu and its parts
 *      mu_Rc, mu_Rf, mu_Sc, mu_Sf, the film, the regime, and whether the
 *      solve converged (iterations, residual): a failed point is flagged,
 *      never silently zero. vl_contact_fields gives the pressure and film
 *      profiles. output.h writes curves as CSV or JSON, plot.h draws them;
 *      atomic_file.h writes any file to a temporary name and renames it
 *      when complete.
 */
#ifndef VISCOLUBE_H
#define VISCOLUBE_H

/* base: statuses and messages, JSON text, atomic files */
#include "viscolube/atomic_file.h"
#include "viscolube/edit_distance.h"
#include "viscolube/json.h"
#include "viscolube/status.h"

/* materials: rubber rheology, surface roughness, fluids */
#include "viscolube/fluid.h"
#include "viscolube/rheology.h"
#include "viscolube/roughness.h"
#include "viscolube/shear_law.h"

/* mechanics: Persson's contact law, flow factors, viscous flattening */
#include "viscolube/flattening.h"
#include "viscolube/flow_factors.h"
#include "viscolube/persson.h"

/* import: measured data (CSV, DMA), Prony fits, topography to PSD */
#include "viscolube/csv.h"
#include "viscolube/dma.h"
#include "viscolube/prony_fit.h"
#include "viscolube/topography.h"

/* solver: one operating point (a cylinder; a ball), sweeps, results,
 * model-validity checks */
#include "viscolube/assumptions.h"
#include "viscolube/contact.h"
#include "viscolube/point_contact.h"
#include "viscolube/results.h"
#include "viscolube/sweep.h"

/* database, scenes and simulations */
#include "viscolube/calibrate.h"
#include "viscolube/database.h"
#include "viscolube/query.h"
#include "viscolube/scene.h"
#include "viscolube/simulation.h"
#include "viscolube/study.h"

/* writers */
#include "viscolube/manifest.h"
#include "viscolube/output.h"
#include "viscolube/plot.h"
#include "viscolube/study_output.h"

#endif
