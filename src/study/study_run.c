/* Solving one task of a study (study.h): its scene made runnable and swept,
 * the curve and the outcome handed back for the writers (study_output.h)
 * to put in the task's file. Nothing here touches a file, so a task is
 * solved the same whether it is written, benchmarked or thrown away. */
#include "study_private.h"
#include "viscolube/study.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "viscolube/simulation.h"

const char *vl_task_state_name(vl_task_state s) {
  switch (s) {
  case VL_TASK_MISSING: return "missing";
  case VL_TASK_OK: return "ok";
  case VL_TASK_NOT_CONVERGED: return "not_converged";
  case VL_TASK_ABOVE_TARGET: return "above_target";
  case VL_TASK_ERROR: return "error";
  }
  return "?";
}

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The sweep of task i into r (its scene, points and curve labels). The
 * task's own failures land in r->outcome; only VL_ENOMEM is returned, the
 * one failure that is not the task's. */
static vl_status solve(const vl_study *s, size_t i, vl_db *db, vl_study_result *r) {
  vl_study_outcome *o = &r->outcome;
  vl_simulation *sim = NULL;
  vl_error e = {{0}};
  vl_status st = vl_study_scene(s, i, &r->scene, &e);
  if (st == VL_OK) st = vl_simulation_create(&r->scene, db, &sim, &e);
  if (st == VL_OK) {
    r->n = vl_simulation_points(sim);
    if (!(r->points = calloc(r->n, sizeof *r->points))) {
      vl_error_set(&e, "out of memory for %zu points", r->n);
      st = VL_ENOMEM;
    }
  }
  vl_sweep_stats stats = {0};
  if (st == VL_OK) st = vl_simulation_run(sim, r->points, NULL, NULL, &stats, &e);
  if (st == VL_OK) {
    r->eta_pa_s = vl_simulation_eta(sim);
    r->tau_s = vl_simulation_tau(sim);
    r->a0_m = vl_simulation_a0(sim);
    r->flow_factors = vl_simulation_flow_factors(sim, &r->film_cutoff_m);
    const char *law = vl_simulation_shear_law_text(sim);
    snprintf(r->shear_law, sizeof r->shear_law, "%s", law ? law : "");
    o->points = r->n;
    o->converged = stats.converged;
    o->failed = stats.failed;
    for (size_t k = 0; k < r->n; k++)
      o->above_target += vl_point_unreliable(&r->points[k]);
    o->state = stats.failed      ? VL_TASK_NOT_CONVERGED
               : o->above_target ? VL_TASK_ABOVE_TARGET
                                 : VL_TASK_OK;
  } else {
    o->state = VL_TASK_ERROR;
    o->error = st;
    snprintf(o->message, sizeof o->message, "%s", e.msg[0] ? e.msg : vl_status_name(st));
  }
  vl_simulation_free(sim);
  return st == VL_ENOMEM ? st : VL_OK;
}

vl_status vl_study_solve_task(const vl_study *s, size_t i, vl_db *db, vl_study_result **out,
                              vl_error *err) {
  /* calloc: a task that stops early leaves the curve empty (n 0, labels
   * 0, flow_factors NULL), as the writers expect */
  vl_study_result *r = calloc(1, sizeof *r);
  *out = NULL;
  if (!r) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  double t0 = now_s();
  vl_status st = solve(s, i, db, r);
  r->outcome.seconds = now_s() - t0;
  if (st != VL_OK) {
    vl_study_result_free(r);
    vl_error_set(err, "task %zu: out of memory", i);
    return st;
  }
  *out = r;
  return VL_OK;
}

void vl_study_result_free(vl_study_result *r) {
  if (!r) return;
  free(r->points);
  free(r);
}
