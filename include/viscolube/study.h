/* viscolube: a study, many Stribeck curves from one file.
 *
 * A study file is a scene file (scene.h) whose [materials] and the
 * operating conditions that vary are replaced by a [study] section:
 *
 *   [study]
 *   title = ...                      (optional)
 *   compounds = a, b                 (required without cases)
 *   surfaces = s1, s2                (optional: smooth contacts without)
 *   fluids = water                   (optional: dry contacts without)
 *   loads_n_per_m = 117, 234         (required without cases; a cylinder's)
 *   loads_n = 1, 3                   (instead: total loads, N, of a ball or an
 *                                     ellipsoid, [contact] geometry)
 *   radii_m = 0.001                  (required without cases; a cylinder's or a
 *                                     ball's radii; an ellipsoid's radii are
 *                                     [contact] radii_m = Rx, Ry, and it takes
 *                                     no [study] radii_m)
 *   temperatures_c = 20, 40          (optional: [effects] temperature = on
 *                                     at each; without, the materials are
 *                                     taken at their reference temperatures)
 *   cases = COMPOUND SURFACE FLUID LOAD RADIUS [TEMPERATURE]
 *           ...                      (instead of the lists: one task per row,
 *                                     a row per indented line; '-' for no
 *                                     surface or fluid; a ball's LOAD in N, an
 *                                     ellipsoid's row without RADIUS)
 *
 * The other sections ([contact] sigma_s_pa, [sweep], [effects], [numerics])
 * are the defaults of every curve, with the keys and checks of a scene.
 * The lists span the full grid, compounds outermost, temperatures
 * innermost: each combination is one task, a Stribeck sweep as `run` does
 * it. Errors name "file:line: [section] key: why". */
#ifndef VISCOLUBE_STUDY_H
#define VISCOLUBE_STUDY_H

#include <stddef.h>
#include <stdint.h>

#include "viscolube/database.h"
#include "viscolube/results.h"
#include "viscolube/scene.h"
#include "viscolube/status.h"

/* Most tasks a study may hold (a list or case table larger than this is a
 * mistake, not a study). */
#define VL_STUDY_TASKS_MAX 100000

/* One task: one curve's factors. */
typedef struct {
  size_t id; /* 0-based position in the study */
  char compound[VL_NAME_MAX];
  char surface[VL_NAME_MAX]; /* "" = smooth */
  char fluid[VL_NAME_MAX];   /* "" = dry */
  int geometry;              /* vl_geometry: the study's [contact] geometry (all tasks alike) */
  double load_n_per_m;       /* a cylinder's (0 for a point contact) */
  double load_n;             /* a ball's or an ellipsoid's total load, N (0 for a cylinder) */
  double radius_m;           /* a cylinder's or a ball's; an ellipsoid's Rx ([contact] radii_m) */
  double radius_y_m;         /* an ellipsoid's Ry (a ball: radius_m; a cylinder: 0) */
  double temperature_c;      /* NAN: materials at their reference temperatures */
  int line;                  /* the row of cases (0 for a grid) */
} vl_study_task;

typedef struct vl_study vl_study;

/* Parses the study file at path (vl_study_parse). On success the caller
 * owns *out (vl_study_free); on failure *out is NULL. VL_EIO when the file
 * cannot be read. */
vl_status vl_study_load(const char *path, vl_study **out, vl_error *err);

void vl_study_free(vl_study *s);

const char *vl_study_text(const vl_study *s); /* the file as read */
/* 64-bit FNV-1a of the text: task files carry it, so that a folder holding
 * the results of another study is recognised. */
uint64_t vl_study_fingerprint(const vl_study *s);

size_t vl_study_n_tasks(const vl_study *s);

/* The distinct material names of the study (kind 0 compounds, 1
 * surfaces, 2 fluids), in order of first use: n names in *names (owned by
 * s). */
const char *const *vl_study_materials(const vl_study *s, int kind, size_t *n);

/* Gets db ready for the tasks, before any starts: every material is
 * looked up (an unknown one is VL_ENOTFOUND naming the [study] line), and
 * the Persson and flow-factor tables of every (compound, surface, fluid)
 * in the study are built and stored in the database's caches, so that
 * workers that open it read-only (vl_db_open_readonly) find them there. */
vl_status vl_study_prepare(const vl_study *s, vl_db *db, vl_error *err);

/* ---- solving a task (the writers, study_output.h, record it) ---------- */

typedef enum {
  VL_TASK_MISSING = 0,   /* no file: not run (yet) */
  VL_TASK_OK,            /* every point converged */
  VL_TASK_NOT_CONVERGED, /* written, some points with converged = 0 */
  VL_TASK_ABOVE_TARGET,  /* written, every point converged, some not known to their error
                          * target (vl_point_unreliable) */
  VL_TASK_ERROR          /* stopped on an error: no curve, the message says why */
} vl_task_state;

typedef struct {
  vl_task_state state;
  size_t points, converged, failed;
  size_t above_target; /* converged points not known to their error target */
  double seconds;      /* wall time of the task */
  vl_status error;     /* VL_TASK_ERROR: the status */
  char message[VL_ERROR_MAX];
} vl_study_outcome;

const char *vl_task_state_name(vl_task_state s);

/* A task solved: its outcome and, unless it stopped on an error, its curve
 * with what labels it (vl_curve_meta of output.h). */
typedef struct {
  vl_study_outcome outcome;
  vl_scene scene;   /* the task's scene (vl_study_scene) */
  size_t n;         /* points[0..n): the sweep, as vl_simulation_run */
  vl_point *points; /* owned by the result */
  double eta_pa_s, tau_s, a0_m;
  const char *flow_factors; /* vl_simulation_flow_factors: a static name or NULL */
  double film_cutoff_m;
  /* vl_simulation_shear_law_text: the stored pair's law that gave sigma_s
   * ("": the scene's constant) */
  char shear_law[VL_DB_TEXT_MAX + 512];
} vl_study_result;

/* Solves task i of s on db (a sweep, as vl_simulation_run) into *out
 * (caller frees, vl_study_result_free). The task's own failure (a material
 * it cannot load, a solver error) is its outcome: the call still returns
 * VL_OK. VL_ENOMEM otherwise, with *out NULL. */
vl_status vl_study_solve_task(const vl_study *s, size_t i, vl_db *db, vl_study_result **out,
                              vl_error *err);
void vl_study_result_free(vl_study_result *r);

#endif
