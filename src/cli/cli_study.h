/* `viscolube study`: what the serial, forked (cli_study.c) and MPI
 * (cli_study_mpi.c) drivers share. */
#ifndef VL_CLI_STUDY_H
#define VL_CLI_STUDY_H

#include <stdbool.h>
#include <stddef.h>
#include <time.h>

#include "cli.h"

typedef struct {
  const vl_cli_globals *g;
  const char *study_path, *out_dir;
  int argc; /* the command as given, for run.json */
  char **argv;
  int jobs; /* --jobs (1: serial) */
  int quiet, tty;
  const char *mode; /* serial | jobs | mpi */
  int processes;    /* workers (jobs) or ranks (mpi) */
  vl_study *study;
  char db_path[4096];
  size_t n_tasks;
  size_t *pending; /* ids of the tasks without a file at the start */
  size_t n_pending, n_skipped;
  size_t done_now; /* tasks reported in this run */
  int io_failed;   /* a task file could not be written */
  time_t started;
  double t0; /* vl_cli_now_s() when the tasks started */
} vl_cli_study_run;

/* What a worker reports of one task (the outcome itself is in its file). */
typedef struct {
  long task;     /* id; -1: a worker that could not start */
  int io_status; /* vl_status of writing the file */
  char message[512];
} vl_cli_study_record;

vl_status vl_cli_study_setup(vl_cli_study_run *cs, vl_error *err);
void vl_cli_study_run_one(vl_cli_study_run *cs, vl_db *db, size_t i, vl_cli_study_record *r);
void vl_cli_study_report(vl_cli_study_run *cs, const vl_cli_study_record *r);
void vl_cli_study_progress(vl_cli_study_run *cs);
void vl_cli_study_kill_hook(size_t tasks_done_here);
/* results.csv, tasks.csv, run.json and the summary; the exit status. */
int vl_cli_study_finish(vl_cli_study_run *cs, int rc);
void vl_cli_study_free(vl_cli_study_run *cs);

/* True when the program was started by an MPI launcher with more than one
 * process (Open MPI, MPICH/Hydra, PMI, Slurm's srun with PMIx). */
bool vl_cli_study_launched_by_mpi(void);
/* The study under MPI (cli_study_mpi.c); without MPI in the build an error
 * saying so. Returns the exit status. */
int vl_cli_study_mpi(vl_cli_study_run *cs);

#endif
