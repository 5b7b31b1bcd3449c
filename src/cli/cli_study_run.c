/* `viscolube study`: the steps every driver shares (cli_study.h): setting
 * up the run, solving and writing one task, reporting it, and at the end
 * results.csv, tasks.csv, run.json and the summary. The serial and forked
 * drivers (cli_study.c) and the MPI one (cli_study_mpi.c) call these; this
 * file calls neither. */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "cli_study.h"
#include "vl_version.h"

void vl_cli_study_progress(vl_cli_study_run *cs) {
  cs->done_now++;
  if (!cs->tty || cs->quiet) return;
  double el = vl_cli_now_s() - cs->t0;
  size_t left = cs->n_pending - cs->done_now;
  fprintf(stderr, "\r  tasks %zu/%zu  elapsed %.0f s  remaining ~%.0f s   ",
          cs->n_skipped + cs->done_now, cs->n_tasks, el, el / (double)cs->done_now * (double)left);
  if (!left) fputc('\n', stderr);
  fflush(stderr);
}

/* The test hook of a killed study (tests/test_study.c): with
 * VL_TEST_STUDY_KILL_AFTER=K the process kills itself after its K-th task,
 * as a scheduler's time limit would. */
void vl_cli_study_kill_hook(size_t tasks_done_here) {
  const char *k = getenv("VL_TEST_STUDY_KILL_AFTER");
  if (k && *k && tasks_done_here >= (size_t)strtoul(k, NULL, 10)) raise(SIGKILL);
}

/* Loads the study, fills the database's caches, checks DIR and lists the
 * tasks still to run. */
vl_status vl_cli_study_setup(vl_cli_study_run *cs, vl_error *err) {
  cs->started = time(NULL);
  cs->t0 = vl_cli_now_s();
  vl_status st = vl_study_load(cs->study_path, &cs->study, err);
  if (st != VL_OK) return st;
  vl_db *db = NULL;
  /* the database first (a command that cannot open it leaves no folder),
   * then --out, still before anything is computed */
  if ((st = vl_db_open(cs->g->db_path, &db, err)) != VL_OK) return st;
  snprintf(cs->db_path, sizeof cs->db_path, "%s", vl_db_path(db));
  st = vl_study_prepare(cs->study, db, err);
  vl_db_close(db);
  if (st != VL_OK) return st;
  if ((st = vl_cli_check_out_dir("--out", cs->out_dir, err)) != VL_OK) return st;
  if ((st = vl_study_check_dir(cs->study, cs->out_dir, err)) != VL_OK) return st;
  cs->n_tasks = vl_study_n_tasks(cs->study);
  if (!(cs->pending = calloc(cs->n_tasks, sizeof *cs->pending))) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  for (size_t i = 0; i < cs->n_tasks; i++)
    if (!vl_study_task_done(cs->study, i, cs->out_dir, NULL)) cs->pending[cs->n_pending++] = i;
  cs->n_skipped = cs->n_tasks - cs->n_pending;
  cs->t0 = vl_cli_now_s(); /* the tasks' clock */
  return VL_OK;
}

/* A worker's report of one task, through a pipe (one write, atomic: less
 * than PIPE_BUF) or an MPI message. */
void vl_cli_study_report(vl_cli_study_run *cs, const vl_cli_study_record *r) {
  if (r->io_status != VL_OK) cs->io_failed = 1;
  if (r->io_status != VL_OK)
    fprintf(stderr, "%sviscolube study: task %ld not written: %s\n",
            cs->tty && !cs->quiet ? "\n" : "", r->task, r->message);
  vl_cli_study_progress(cs);
}

/* Runs task i in this process with db; the record of it in *r. */
void vl_cli_study_run_one(vl_cli_study_run *cs, vl_db *db, size_t i, vl_cli_study_record *r) {
  vl_study_result *res = NULL;
  vl_error err = {{0}};
  memset(r, 0, sizeof *r);
  r->task = (long)i;
  r->io_status = vl_study_solve_task(cs->study, i, db, &res, &err);
  if (r->io_status == VL_OK)
    r->io_status = vl_study_write_task(cs->study, i, cs->out_dir, res, &err);
  vl_study_result_free(res);
  if (r->io_status != VL_OK) snprintf(r->message, sizeof r->message, "%.500s", err.msg);
}

static void iso_time(time_t t, char *buf, size_t size) {
  struct tm tm;
  gmtime_r(&t, &tm);
  strftime(buf, size, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

/* Counts of the outcomes: [state] tasks, and the points. */
typedef struct {
  size_t state[VL_TASK_ERROR + 1];
  size_t converged, failed, above_target;
  vl_status first_error;
} study_counts;

static study_counts count(const vl_cli_study_run *cs, const vl_study_outcome *o) {
  study_counts c = {.first_error = VL_OK};
  for (size_t i = 0; i < cs->n_tasks; i++) {
    c.state[o[i].state]++;
    c.converged += o[i].converged;
    c.failed += o[i].failed;
    c.above_target += o[i].above_target;
    if (o[i].state == VL_TASK_ERROR && c.first_error == VL_OK) c.first_error = o[i].error;
  }
  return c;
}

static void json_names(vl_json *w, const char *key, const vl_study *s, int kind) {
  size_t n;
  const char *const *names = vl_study_materials(s, kind, &n);
  vl_json_key(w, key);
  vl_json_array_begin(w, VL_JSON_INLINE);
  for (size_t k = 0; k < n; k++)
    vl_json_string(w, names[k]);
  vl_json_end(w);
}

/* DIR/run.json: what ran, on what, with what, when, and how it went. */
static vl_status write_manifest(const vl_cli_study_run *cs, const study_counts *c, double seconds,
                                vl_error *err) {
  char path[4300], t0[32], t1[32], fp[24];
  snprintf(path, sizeof path, "%s/run.json", cs->out_dir);
  iso_time(cs->started, t0, sizeof t0);
  iso_time(time(NULL), t1, sizeof t1);
  snprintf(fp, sizeof fp, "%016llx", (unsigned long long)vl_study_fingerprint(cs->study));
  vl_atomic_file af;
  if (vl_atomic_file_open(&af, path, err) != VL_OK) return VL_EIO;
  vl_json w;
  vl_json_init(&w, af.f, 0);
  vl_json_object_begin(&w, VL_JSON_BLOCKS);
  vl_json_key(&w, "command");
  vl_json_array_begin(&w, VL_JSON_INLINE);
  vl_json_string(&w, "viscolube");
  for (int i = 0; i < cs->argc; i++)
    vl_json_string(&w, cs->argv[i]);
  vl_json_end(&w);
  vl_json_key_string(&w, "program_version", VL_VERSION);
  vl_json_key_string(&w, "program_source", VL_SOURCE_COMMIT);
  vl_json_key_string(&w, "study", cs->study_path);
  vl_json_key_string(&w, "study_fingerprint", fp);
  vl_json_key_string(&w, "study_text", vl_study_text(cs->study));
  vl_json_key_string(&w, "database", cs->db_path);
  vl_json_key(&w, "materials");
  vl_json_object_begin(&w, VL_JSON_INLINE);
  json_names(&w, "compounds", cs->study, 0);
  json_names(&w, "surfaces", cs->study, 1);
  json_names(&w, "fluids", cs->study, 2);
  vl_json_end(&w);
  vl_json_key_string(&w, "mode", cs->mode);
  vl_json_key_integer(&w, "processes", cs->processes);
  vl_json_key_string(&w, "started", t0);
  vl_json_key_string(&w, "finished", t1);
  vl_json_key_number(&w, "seconds", seconds);
  vl_json_key(&w, "tasks");
  vl_json_object_begin(&w, VL_JSON_INLINE);
  vl_json_key_integer(&w, "total", (long long)cs->n_tasks);
  vl_json_key_integer(&w, "run", (long long)cs->done_now);
  vl_json_key_integer(&w, "skipped", (long long)cs->n_skipped);
  for (int k = VL_TASK_MISSING; k <= VL_TASK_ERROR; k++)
    vl_json_key_integer(&w, vl_task_state_name((vl_task_state)k), (long long)c->state[k]);
  vl_json_end(&w);
  vl_json_key(&w, "points");
  vl_json_object_begin(&w, VL_JSON_INLINE);
  vl_json_key_integer(&w, "converged", (long long)c->converged);
  vl_json_key_integer(&w, "failed", (long long)c->failed);
  vl_json_end(&w);
  vl_json_end(&w);
  fputc('\n', af.f);
  return vl_atomic_file_commit(&af, err);
}

/* The tasks that stopped on an error or are missing, at most ten lines. */
static void print_problems(const vl_cli_study_run *cs, const vl_study_outcome *o) {
  size_t shown = 0;
  for (size_t i = 0; i < cs->n_tasks && shown < 10; i++) {
    if (o[i].state == VL_TASK_ERROR)
      fprintf(stderr, "viscolube study: task %zu: error: %s\n", i, o[i].message), shown++;
    else if (o[i].state == VL_TASK_MISSING)
      fprintf(stderr, "viscolube study: task %zu: missing (not written)\n", i), shown++;
  }
}

int vl_cli_study_finish(vl_cli_study_run *cs, int rc) {
  double seconds = vl_cli_now_s() - cs->t0;
  vl_error err = {{0}};
  vl_study_outcome *o = calloc(cs->n_tasks ? cs->n_tasks : 1, sizeof *o);
  vl_status st = o ? vl_study_write_results(cs->study, cs->out_dir, o, &err) : VL_ENOMEM;
  study_counts c = {0};
  if (st == VL_OK) {
    c = count(cs, o);
    st = write_manifest(cs, &c, seconds, &err);
  }
  if (st != VL_OK) {
    fprintf(stderr, "viscolube study: %s\n", err.msg[0] ? err.msg : vl_status_name(st));
    free(o);
    return vl_status_exit_code(st);
  }
  printf("study %s: %zu tasks (%zu run now, %zu already done), %s with %d process%s\n",
         cs->study_path, cs->n_tasks, cs->done_now, cs->n_skipped, cs->mode, cs->processes,
         cs->processes == 1 ? "" : "es");
  printf("%zu ok, %zu above their error target, %zu not converged, %zu error, %zu missing; "
         "points: %zu converged (%zu above their error target), %zu failed\n",
         c.state[VL_TASK_OK], c.state[VL_TASK_ABOVE_TARGET], c.state[VL_TASK_NOT_CONVERGED],
         c.state[VL_TASK_ERROR], c.state[VL_TASK_MISSING], c.converged, c.above_target, c.failed);
  if (cs->done_now)
    printf("%.2f s for %zu tasks: %.3g tasks/s\n", seconds, cs->done_now,
           (double)cs->done_now / seconds);
  printf("wrote %s/results.csv, tasks.csv, run.json\n", cs->out_dir);
  fflush(stdout);
  print_problems(cs, o);
  free(o);
  if (rc) return rc;
  if (cs->io_failed) return vl_status_exit_code(VL_EIO);
  if (c.state[VL_TASK_MISSING]) return vl_status_exit_code(VL_EINTERNAL);
  if (c.state[VL_TASK_ERROR]) return vl_status_exit_code(c.first_error);
  return vl_cli_points_status(c.failed, c.above_target);
}

void vl_cli_study_free(vl_cli_study_run *cs) {
  free(cs->pending);
  vl_study_free(cs->study);
}
