/* Fuzz target: study files (`viscolube study STUDY`), read by
 * vl_study_load. Properties: a refused study gets VL_EINPUT and a message
 * starting with the file name, without control bytes; an accepted one has
 * 1..VL_STUDY_TASKS_MAX tasks with a compound, positive finite load and
 * radius, and every task's scene loads with exactly the task's factors. */
#include "study_private.h"
#include "vl_fuzz.h"

#include <math.h>
#include <string.h>

#include "viscolube/study.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *path = vl_fuzz_file(data, size);
  static vl_scene sc; /* off the stack */
  vl_error err = {{0}};
  vl_study *s = NULL;
  vl_status st = vl_study_load(path, &s, &err);
  if (st != VL_OK) {
    FUZZ_CHECK(s == NULL, "a study on failure");
    FUZZ_CHECK_REFUSED(st, path, err.msg);
    return 0;
  }
  size_t n = vl_study_n_tasks(s);
  FUZZ_CHECK(n >= 1 && n <= VL_STUDY_TASKS_MAX, "%zu tasks", n);
  for (size_t i = 0; i < n && i < 64; i++) {
    const vl_study_task *t = vl_study_task_at(s, i);
    FUZZ_CHECK(t->id == i, "task %zu has id %zu", i, t->id);
    FUZZ_CHECK(t->compound[0], "task %zu: no compound", i);
    FUZZ_CHECK(isfinite(t->load_n_per_m) && t->load_n_per_m > 0, "task %zu: load %g", i,
               t->load_n_per_m);
    FUZZ_CHECK(isfinite(t->radius_m) && t->radius_m > 0, "task %zu: radius %g", i, t->radius_m);
    st = vl_study_scene(s, i, &sc, &err);
    FUZZ_CHECK(st == VL_OK, "task %zu of a loaded study: %s", i, err.msg);
    FUZZ_CHECK(!strcmp(sc.compound, t->compound) && !strcmp(sc.surface, t->surface) &&
                   !strcmp(sc.fluid, t->fluid),
               "task %zu: materials %s/%s/%s in the scene", i, sc.compound, sc.surface, sc.fluid);
    FUZZ_CHECK(sc.load_n_per_m == t->load_n_per_m && sc.radius_m == t->radius_m,
               "task %zu: load or radius not the task's", i);
    FUZZ_CHECK(isnan(t->temperature_c) ||
                   (sc.effects.temperature && sc.effects.temperature_c == t->temperature_c),
               "task %zu: temperature not the task's", i);
  }
  vl_study_free(s);
  return 0;
}
