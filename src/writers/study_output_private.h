/* The private part of viscolube/study_output.h: the path of a task's file, for the
 * writers. */
#ifndef VISCOLUBE_STUDY_OUTPUT_PRIVATE_H
#define VISCOLUBE_STUDY_OUTPUT_PRIVATE_H

#include "viscolube/study_output.h"

/* DIR/tasks/NNNNNN.csv of task id into buf. */
void vl_study_task_path(const char *out_dir, size_t id, char *buf, size_t size);

#endif
