/* The private part of viscolube/study.h: parsing a study from text, its path,
 * title, tasks and the scene of a task, for the study and writer layers and
 * the tests. */
#ifndef VISCOLUBE_STUDY_PRIVATE_H
#define VISCOLUBE_STUDY_PRIVATE_H

#include "viscolube/study.h"

/* The same from text (path names it in messages). Every task's scene is
 * parsed and checked here, so a study that loads has no bad task. */
vl_status vl_study_parse(const char *text, const char *path, vl_study **out, vl_error *err);

const char *vl_study_path(const vl_study *s);

const char *vl_study_title(const vl_study *s); /* "" when none */

const vl_study_task *vl_study_task_at(const vl_study *s, size_t i);

/* The scene of task i (titled "TITLE | task I"); VL_EINPUT cannot happen
 * for a study that loaded, but is checked. */
vl_status vl_study_scene(const vl_study *s, size_t i, vl_scene *out, vl_error *err);

#endif
