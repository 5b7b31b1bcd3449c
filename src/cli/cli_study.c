/* `viscolube study STUDY --out DIR [--jobs N]`: many curves, serially, in
 * N worker processes, or under mpirun (cli_study_mpi.c). The library does
 * the work (study.h, study_output.h); this file schedules the tasks. */
#include <errno.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "cli_options.h"
#include "cli_study.h"
#include "vl_version.h"

static void study_usage(FILE *out) {
  fputs("usage: viscolube study STUDY --out DIR [--jobs N] [--quiet]\n"
        "       mpirun -n N viscolube study STUDY --out DIR [--quiet]\n"
        "\n"
        "Runs a study: one Stribeck sweep (as `run` does it) per combination of the\n"
        "[study] section's compounds, surfaces, fluids, loads_n_per_m, radii_m and\n"
        "temperatures_c (or per row of its cases), the file's other sections being the\n"
        "scene defaults of every curve (docs/STUDY.md). Writes\n"
        "  DIR/tasks/NNNNNN.csv  each task's curve, written whole when the task ends\n"
        "  DIR/results.csv       every task's rows: compound, surface, fluid, load_n_per_m,\n"
        "                        radius_m, temperature_c, then the columns of curve.csv\n"
        "  DIR/tasks.csv         per task: factors, points, converged, failed, seconds,\n"
        "                        status (ok, not_converged, error, missing), message\n"
        "  DIR/run.json          the manifest: command, study text, materials, program\n"
        "                        version, start and end, counts\n"
        "Restartable: run again with the same --out, the tasks already written are\n"
        "skipped (a DIR holding another study's tasks is refused).\n"
        "--jobs N runs N worker processes (default 1), each with its own read-only\n"
        "connection to the database; tasks are handed out one at a time as workers\n"
        "free up. Under mpirun (a build with MPI), rank 0 hands out the tasks and\n"
        "writes the summary files, the other ranks compute. The Persson and flow-factor\n"
        "tables are built (and stored in the database) before any task starts.\n"
        "Progress (tasks done, elapsed, remaining) on stderr when it is a terminal,\n"
        "unless --quiet.\n"
        "Exit status: 0 every point of every task converged, 7 some points did not,\n"
        "2 bad study file or option (nothing written) or a task stopped on bad input,\n"
        "3 unknown material, 5 database error, 6 file error, 70 tasks missing (a worker\n"
        "died: run the study again with the same --out to finish them).\n",
        out);
}

/* OpenBLAS would start its own threads in every worker: one each keeps the
 * processes from competing for the cores, and the results the same
 * whatever the number of workers. The symbol is there only when OpenBLAS
 * provides LAPACK (weak: NULL otherwise). */
extern void openblas_set_num_threads(int n) __attribute__((weak));
static void one_blas_thread(void) {
  setenv("OPENBLAS_NUM_THREADS", "1", 1);
  if (openblas_set_num_threads) openblas_set_num_threads(1);
}

static int run_serial(vl_cli_study_run *cs) {
  vl_db *db = NULL;
  vl_error err = {{0}};
  if (vl_db_open_readonly(cs->db_path, &db, &err) != VL_OK) {
    fprintf(stderr, "viscolube study: %s\n", err.msg);
    return vl_status_exit_code(VL_EDB);
  }
  for (size_t k = 0; k < cs->n_pending; k++) {
    vl_cli_study_record r;
    vl_cli_study_run_one(cs, db, cs->pending[k], &r);
    vl_cli_study_report(cs, &r);
    vl_cli_study_kill_hook(k + 1);
  }
  vl_db_close(db);
  return 0;
}

/* One forked worker: its own read-only connection, tasks claimed from the
 * shared counter until none is left, a record per task into fd. */
static void worker(vl_cli_study_run *cs, atomic_size_t *next, int fd) {
  vl_db *db = NULL;
  vl_error err = {{0}};
  int code = 0;
  if (vl_db_open_readonly(cs->db_path, &db, &err) != VL_OK) {
    fprintf(stderr, "viscolube study: worker %d: %s\n", (int)getpid(), err.msg);
    _exit(vl_status_exit_code(VL_EDB));
  }
  for (size_t here = 1;; here++) {
    size_t k = atomic_fetch_add(next, 1);
    if (k >= cs->n_pending) break;
    vl_cli_study_record r;
    vl_cli_study_run_one(cs, db, cs->pending[k], &r);
    if (write(fd, &r, sizeof r) != (ssize_t)sizeof r) code = vl_status_exit_code(VL_EIO);
    vl_cli_study_kill_hook(here);
  }
  vl_db_close(db);
  _exit(code);
}

/* --jobs N: N forked workers take tasks as they free up (a counter in
 * shared memory), each reporting through one pipe the parent reads. */
static int run_jobs(vl_cli_study_run *cs) {
  atomic_size_t *next =
      mmap(NULL, sizeof *next, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  int fds[2];
  if (next == MAP_FAILED || pipe(fds) != 0) {
    fprintf(stderr, "viscolube study: cannot start workers: %s\n", strerror(errno));
    return vl_status_exit_code(VL_EINTERNAL);
  }
  atomic_init(next, 0);
  fflush(NULL); /* nothing buffered is written twice */
  int started = 0;
  for (int w = 0; w < cs->jobs; w++) {
    pid_t pid = fork();
    if (pid == 0) {
      close(fds[0]);
      worker(cs, next, fds[1]);
    }
    if (pid > 0)
      started++;
    else
      fprintf(stderr, "viscolube study: cannot start worker %d: %s\n", w, strerror(errno));
  }
  close(fds[1]);
  vl_cli_study_record r;
  while (started && read(fds[0], &r, sizeof r) == (ssize_t)sizeof r)
    vl_cli_study_report(cs, &r);
  close(fds[0]);
  int rc = 0, status;
  for (pid_t pid; (pid = wait(&status)) > 0;)
    if (WIFSIGNALED(status)) {
      fprintf(stderr, "viscolube study: worker %d was killed by signal %d\n", (int)pid,
              WTERMSIG(status));
      rc = vl_status_exit_code(VL_EINTERNAL);
    }
  munmap(next, sizeof *next);
  return rc;
}

bool vl_cli_study_launched_by_mpi(void) {
  static const char *const size_vars[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE",
                                          "MPI_LOCALNRANKS"};
  for (size_t k = 0; k < sizeof size_vars / sizeof size_vars[0]; k++) {
    const char *v = getenv(size_vars[k]);
    if (v && atoi(v) > 1) return true;
  }
  return false;
}

/* Reads the options; -1 to go on, else the exit status (0 after --help). */
static int study_options(vl_cli_study_run *cs, int argc, char **argv) {
  static const vl_cli_number_rule jobs_rule = {
      .lo = 1, .hi = 1024, .whole = 1, .bad = "%s: expected a whole number in [1, 1024], got '%s'"};
  double jobs = cs->jobs;
  vl_cli_option opts[] = {
      {.name = "--help", .alias = "-h", .kind = VL_CLI_HELP},
      {.name = "--quiet", .alias = "-q", .kind = VL_CLI_FLAG, .dest = &cs->quiet},
      {.name = "--out", .kind = VL_CLI_TEXT, .metavar = "DIR", .dest = &cs->out_dir},
      {.name = "--jobs", .kind = VL_CLI_NUMBER, .metavar = "N", .dest = &jobs, .rule = &jobs_rule},
  };
  vl_cli_parser p =
      vl_cli_file_command("study", opts, sizeof opts / sizeof opts[0], &cs->study_path,
                          "one study at a time (got '%s' and '%s')", study_usage);
  int rc = vl_cli_parse(&p, argc, argv, 1);
  if (rc >= 0) return rc;
  cs->jobs = (int)jobs;
  if (!cs->study_path || !cs->out_dir) {
    fprintf(stderr, "viscolube study: %s\n",
            !cs->study_path ? "which study? (STUDY file)" : "--out DIR is required");
    return 2;
  }
  return -1;
}

int vl_cli_study(const vl_cli_globals *g, int argc, char **argv) {
  vl_cli_study_run cs = {.g = g,
                         .argc = argc,
                         .argv = argv,
                         .jobs = 1,
                         .quiet = g->quiet,
                         .tty = isatty(STDERR_FILENO),
                         .mode = "serial",
                         .processes = 1};
  int rc = study_options(&cs, argc, argv);
  if (rc >= 0) return rc;
  one_blas_thread(); /* before any worker (fork, MPI rank) computes */
  if (vl_cli_study_launched_by_mpi()) {
    if (cs.jobs > 1) {
      fputs("viscolube study: --jobs and mpirun: use one or the other\n", stderr);
      return 2;
    }
    rc = vl_cli_study_mpi(&cs);
    vl_cli_study_free(&cs);
    return rc;
  }
  vl_error err = {{0}};
  vl_status st = vl_cli_study_setup(&cs, &err);
  if (st != VL_OK) {
    fprintf(stderr, "viscolube study: %s\n", err.msg[0] ? err.msg : vl_status_name(st));
    vl_cli_study_free(&cs);
    return vl_status_exit_code(st);
  }
  if (cs.jobs > 1 && cs.n_pending > 1) {
    cs.mode = "jobs";
    cs.processes = cs.jobs < (int)cs.n_pending ? cs.jobs : (int)cs.n_pending;
    cs.jobs = cs.processes;
    rc = run_jobs(&cs);
  } else {
    rc = run_serial(&cs);
  }
  rc = vl_cli_study_finish(&cs, rc);
  vl_cli_study_free(&cs);
  return rc;
}
