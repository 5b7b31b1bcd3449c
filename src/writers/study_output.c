/* The files of a study (study_output.h), written from the tasks that
 * src/study/study_run.c solved: nothing here runs a solver. */
#include "viscolube/study_output.h"
#include "study_output_private.h"
#include "study_private.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "output_internal.h"
#include "viscolube/atomic_file.h"
#include "viscolube/output.h"

#define PATH_SIZE 4400

/* The factor columns of a study's tasks: the rigid body's load and radii
 * by its geometry (vl_geometry: all tasks alike). */
static const char *factor_columns(int geometry) {
  switch (geometry) {
  case VL_GEOMETRY_BALL: return "compound,surface,fluid,load_n,radius_m,temperature_c";
  case VL_GEOMETRY_ELLIPSOID:
    return "compound,surface,fluid,load_n,radius_x_m,radius_y_m,temperature_c";
  default: return "compound,surface,fluid,load_n_per_m,radius_m,temperature_c";
  }
}

/* The load and radius cells of task t (each followed by a comma). */
static void print_body(FILE *f, const vl_study_task *t) {
  if (t->geometry == VL_GEOMETRY_CYLINDER)
    fprintf(f, "%.15g,%.15g,", t->load_n_per_m, t->radius_m);
  else if (t->geometry == VL_GEOMETRY_BALL)
    fprintf(f, "%.15g,%.15g,", t->load_n, t->radius_m);
  else
    fprintf(f, "%.15g,%.15g,%.15g,", t->load_n, t->radius_m, t->radius_y_m);
}

void vl_study_task_path(const char *out_dir, size_t id, char *buf, size_t size) {
  snprintf(buf, size, "%s/tasks/%06zu.csv", out_dir, id);
}

/* The factor cells of a task (no trailing comma); temperature_c empty when
 * the materials are at their reference temperatures. */
static void print_factors(FILE *f, const vl_study_task *t, const vl_scene *scene) {
  fprintf(f, "%s,%s,%s,", t->compound, t->surface, t->fluid);
  print_body(f, t);
  if (scene->effects.temperature) fprintf(f, "%.15g", scene->effects.temperature_c);
}

/* The curve as `run` writes it, each row behind the task's factors. */
static vl_status print_rows(FILE *f, const vl_study_task *t, const vl_scene *scene, size_t n,
                            const vl_point *pts, const vl_curve_meta *meta, vl_error *err) {
  char *buf = NULL;
  size_t len = 0;
  FILE *mem = open_memstream(&buf, &len);
  if (!mem) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  vl_print_curve_csv(mem, n, pts, meta);
  if (fclose(mem) != 0 || !buf) {
    free(buf);
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  bool header = true;
  for (char *line = buf, *end; *line; line = end + 1) {
    end = strchr(line, '\n');
    if (!end) break; /* the writer ends every line */
    if (line[0] == '#') {
      fprintf(f, "%.*s\n", (int)(end - line), line);
      continue;
    }
    if (header)
      fputs(factor_columns(t->geometry), f);
    else
      print_factors(f, t, scene);
    fprintf(f, ",%.*s\n", (int)(end - line), line);
    header = false;
  }
  free(buf);
  return VL_OK;
}

/* The two comment lines every task file begins with. */
static void print_head(FILE *f, const vl_study *s, size_t i, const vl_study_outcome *o) {
  fprintf(f, "# viscolube study task %zu of %zu, study %016" PRIx64 "\n", i, vl_study_n_tasks(s),
          vl_study_fingerprint(s));
  fprintf(f, "# outcome: %s, points %zu, converged %zu, failed %zu, seconds %.6f",
          vl_task_state_name(o->state), o->points, o->converged, o->failed, o->seconds);
  if (o->above_target) fprintf(f, ", above_target %zu", o->above_target);
  if (o->state == VL_TASK_ERROR) {
    fprintf(f, ", status %d, message ", (int)o->error);
    for (const char *c = o->message; *c; c++) /* one line */
      fputc(*c == '\n' ? ' ' : *c, f);
  }
  fputc('\n', f);
}

vl_status vl_study_write_task(const vl_study *s, size_t i, const char *out_dir,
                              const vl_study_result *r, vl_error *err) {
  char path[PATH_SIZE];
  vl_study_task_path(out_dir, i, path, sizeof path);
  vl_atomic_file af;
  vl_status st = vl_atomic_file_open(&af, path, err);
  if (st != VL_OK) return st;
  print_head(af.f, s, i, &r->outcome);
  if (r->outcome.state != VL_TASK_ERROR) {
    const vl_curve_meta meta = {r->eta_pa_s,      r->tau_s,
                                r->a0_m,          r->flow_factors,
                                r->film_cutoff_m, r->shear_law[0] ? r->shear_law : NULL};
    st = print_rows(af.f, vl_study_task_at(s, i), &r->scene, r->n, r->points, &meta, err);
    if (st != VL_OK) {
      vl_atomic_file_abort(&af);
      return st;
    }
  }
  return vl_atomic_file_commit(&af, err);
}

/* Reads the head of a task file: true when it is task i of s. */
static bool read_head(FILE *f, const vl_study *s, size_t i, vl_study_outcome *o) {
  char line[2 * VL_ERROR_MAX], state[32];
  size_t id, n_tasks;
  uint64_t fp;
  if (!fgets(line, sizeof line, f) ||
      sscanf(line, "# viscolube study task %zu of %zu, study %" SCNx64, &id, &n_tasks, &fp) != 3 ||
      id != i || n_tasks != vl_study_n_tasks(s) || fp != vl_study_fingerprint(s))
    return false;
  vl_study_outcome r = {0};
  int status = 0, used = 0;
  if (!fgets(line, sizeof line, f) ||
      sscanf(line, "# outcome: %31[a-z_], points %zu, converged %zu, failed %zu, seconds %lf%n",
             state, &r.points, &r.converged, &r.failed, &r.seconds, &used) != 5)
    return false;
  for (int k = VL_TASK_OK; k <= VL_TASK_ERROR; k++)
    if (!strcmp(state, vl_task_state_name((vl_task_state)k))) r.state = (vl_task_state)k;
  int more = 0; /* absent from files without such points (and from older versions) */
  if (sscanf(line + used, ", above_target %zu%n", &r.above_target, &more) == 1) used += more;
  if (r.state == VL_TASK_MISSING) return false;
  if (r.state == VL_TASK_ERROR) {
    int at = 0;
    if (sscanf(line + used, ", status %d, message %n", &status, &at) != 1 || !at) return false;
    r.error = (vl_status)status;
    snprintf(r.message, sizeof r.message, "%s", line + used + at);
    r.message[strcspn(r.message, "\n")] = '\0';
  }
  if (o) *o = r;
  return true;
}

bool vl_study_task_done(const vl_study *s, size_t i, const char *out_dir, vl_study_outcome *o) {
  char path[PATH_SIZE];
  vl_study_task_path(out_dir, i, path, sizeof path);
  FILE *f = fopen(path, "r");
  if (!f) return false;
  bool done = read_head(f, s, i, o);
  fclose(f);
  return done;
}

vl_status vl_study_check_dir(const vl_study *s, const char *out_dir, vl_error *err) {
  char path[PATH_SIZE];
  snprintf(path, sizeof path, "%s/tasks", out_dir);
  if (mkdir(path, 0777) != 0 && errno != EEXIST) {
    vl_error_set(err, "%s: cannot create the task folder: %s", path, strerror(errno));
    return VL_EIO;
  }
  /* a file of this study's name space that is not this study's task */
  for (size_t i = 0; i < vl_study_n_tasks(s); i++) {
    vl_study_task_path(out_dir, i, path, sizeof path);
    FILE *f = fopen(path, "r");
    if (!f) continue;
    bool ours = read_head(f, s, i, NULL);
    fclose(f);
    if (!ours) {
      vl_error_set(err,
                   "%s is not a task of %s as it is now (another study, or the file was "
                   "edited since): use a new --out, or remove %s/tasks",
                   path, vl_study_path(s), out_dir);
      return VL_EINPUT;
    }
  }
  return VL_OK;
}

/* Appends the rows of task i's file to out (its header too when *header
 * is false, and the flow-factor line first); the outcome into o. */
static vl_status copy_rows(const vl_study *s, size_t i, const char *out_dir, FILE *out,
                           bool *header, vl_study_outcome *o, vl_error *err) {
  char path[PATH_SIZE];
  vl_study_task_path(out_dir, i, path, sizeof path);
  *o = (vl_study_outcome){0};
  FILE *f = fopen(path, "r");
  if (!f) return VL_OK; /* missing */
  vl_status st = VL_OK;
  if (!read_head(f, s, i, o)) {
    *o = (vl_study_outcome){0};
    goto done;
  }
  char *line = NULL;
  size_t cap = 0;
  bool first = true; /* the file's header line comes first after comments */
  while (getline(&line, &cap, f) > 0) {
    if (line[0] == '#') {
      if (!*header) fputs(line, out);
      continue;
    }
    if (!first || !*header) fputs(line, out);
    if (first) *header = true;
    first = false;
  }
  free(line);
  if (ferror(f)) {
    vl_error_set(err, "%s: cannot read: %s", path, strerror(errno));
    st = VL_EIO;
  }
done:
  fclose(f);
  return st;
}

/* A CSV cell: quoted when it holds a comma, a quote or a line break. */
static void csv_text(FILE *f, const char *text) {
  if (!strpbrk(text, ",\"\n\r")) {
    fputs(text, f);
    return;
  }
  fputc('"', f);
  for (const char *c = text; *c; c++) {
    if (*c == '"') fputc('"', f);
    fputc(*c, f);
  }
  fputc('"', f);
}

static void print_task_row(FILE *f, const vl_study_task *t, const vl_study_outcome *o) {
  fprintf(f, "%zu,%s,%s,%s,", t->id, t->compound, t->surface, t->fluid);
  print_body(f, t);
  if (!isnan(t->temperature_c)) fprintf(f, "%.15g", t->temperature_c);
  fprintf(f, ",%zu,%zu,%zu,%zu,", o->points, o->converged, o->failed, o->above_target);
  if (o->state != VL_TASK_MISSING) fprintf(f, "%.3f", o->seconds);
  fprintf(f, ",%s,", vl_task_state_name(o->state));
  csv_text(f, o->message);
  fputc('\n', f);
}

vl_status vl_study_write_results(const vl_study *s, const char *out_dir, vl_study_outcome *outcomes,
                                 vl_error *err) {
  char path[PATH_SIZE];
  vl_atomic_file res, tab;
  snprintf(path, sizeof path, "%s/results.csv", out_dir);
  if (vl_atomic_file_open(&res, path, err) != VL_OK) return VL_EIO;
  snprintf(path, sizeof path, "%s/tasks.csv", out_dir);
  if (vl_atomic_file_open(&tab, path, err) != VL_OK) {
    vl_atomic_file_abort(&res);
    return VL_EIO;
  }
  const vl_study_task *first = vl_study_task_at(s, 0);
  const char *factors = factor_columns(first ? first->geometry : VL_GEOMETRY_CYLINDER);
  fprintf(tab.f, "task,%s,points,converged,failed,above_target,seconds,status,message\n", factors);
  bool header = false;
  vl_status st = VL_OK;
  for (size_t i = 0; st == VL_OK && i < vl_study_n_tasks(s); i++) {
    st = copy_rows(s, i, out_dir, res.f, &header, &outcomes[i], err);
    print_task_row(tab.f, vl_study_task_at(s, i), &outcomes[i]);
  }
  if (st != VL_OK) {
    vl_atomic_file_abort(&res);
    vl_atomic_file_abort(&tab);
    return st;
  }
  /* no task wrote a curve: the columns all the same */
  if (!header) {
    fputs(factors, res.f);
    for (size_t c = 0; vl_curve_columns[c]; c++)
      fprintf(res.f, ",%s", vl_curve_columns[c]);
    fputc('\n', res.f);
  }
  st = vl_atomic_file_commit(&res, err);
  if (st != VL_OK) {
    vl_atomic_file_abort(&tab);
    return st;
  }
  return vl_atomic_file_commit(&tab, err);
}
