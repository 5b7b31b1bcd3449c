/* viscolube: the files of a study (study.h) in its output folder DIR.
 *
 *   DIR/tasks/NNNNNN.csv  one per task (NNNNNN = task id), written whole
 *                         when the task ends (atomic_file.h): two comment
 *                         lines (the study's fingerprint, the task's
 *                         outcome), then, unless the task stopped on an
 *                         error, its curve: the curve.csv of `run` with the
 *                         factor columns compound, surface, fluid,
 *                         load_n_per_m, radius_m, temperature_c in front.
 *   DIR/results.csv       every task's rows, in task order, one header
 *   DIR/tasks.csv         one row per task: factors, points, converged,
 *                         failed, seconds, status (ok, not_converged,
 *                         error, missing), message
 *
 * A task file is the record that the task is done: a study started again
 * on the same DIR skips the tasks whose file is there, so every task runs
 * once however often the study is interrupted. The functions hold no
 * state: any number of processes may run tasks into one DIR at once. */
#ifndef VISCOLUBE_STUDY_OUTPUT_H
#define VISCOLUBE_STUDY_OUTPUT_H

#include <stdbool.h>
#include <stddef.h>

#include "viscolube/status.h"
#include "viscolube/study.h"

/* Writes task i's file from r (vl_study_solve_task): its outcome, and its
 * curve unless the task stopped on an error. A status other than VL_OK
 * (VL_EIO: the file cannot be written; VL_ENOMEM) means that no file was
 * written. DIR/tasks must exist. */
vl_status vl_study_write_task(const vl_study *s, size_t i, const char *out_dir,
                              const vl_study_result *r, vl_error *err);

/* True when task i's file is there and belongs to s (its fingerprint and
 * id); *o (may be NULL) is then the recorded outcome. */
bool vl_study_task_done(const vl_study *s, size_t i, const char *out_dir, vl_study_outcome *o);

/* Creates DIR/tasks and refuses (VL_EINPUT, naming the file) a folder
 * whose tasks/ holds a task file of another study (another text): its
 * results would be mixed with this one's. VL_EIO when DIR/tasks cannot be
 * created. */
vl_status vl_study_check_dir(const vl_study *s, const char *out_dir, vl_error *err);

/* Writes DIR/results.csv and DIR/tasks.csv from the task files (each
 * atomically), and the outcome of every task into outcomes[0..n_tasks)
 * (state VL_TASK_MISSING where there is no file). */
vl_status vl_study_write_results(const vl_study *s, const char *out_dir, vl_study_outcome *outcomes,
                                 vl_error *err);

#endif
