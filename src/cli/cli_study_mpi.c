/* `mpirun -n N viscolube study ...`: rank 0 hands out the tasks one at a
 * time as ranks ask for them (the tasks differ in cost tenfold, so a fixed
 * split would leave ranks idle) and writes the summary files; ranks 1..N-1
 * run tasks, each writing its task file (DIR is on a file system every
 * rank sees) and reporting to rank 0. Point-to-point messages only:
 *   rank r -> 0  TAG_RESULT  a vl_cli_study_record (task -1: "ready")
 *   0 -> rank r  TAG_TASK    a task id, or -1: no more work
 * Built only when CMake finds MPI (VL_HAVE_MPI). */
#include <stdio.h>
#include <string.h>

#include "cli_study.h"

#ifndef VL_HAVE_MPI

int vl_cli_study_mpi(vl_cli_study_run *cs) {
  (void)cs;
  fputs("viscolube study: started by mpirun, but this build has no MPI (install libopenmpi-dev "
        "and configure again); without mpirun, use --jobs N\n",
        stderr);
  return 2;
}

#else

#include <mpi.h>
#include <stdbool.h>
#include <time.h>

enum { TAG_RESULT = 1, TAG_TASK = 2 };

/* Rank 0's wait for a message: probing with short sleeps, not MPI's busy
 * wait, which would take a core from the workers on a small machine. */
static void wait_for_message(MPI_Status *status) {
  for (int flag = 0;;) {
    MPI_Iprobe(MPI_ANY_SOURCE, TAG_RESULT, MPI_COMM_WORLD, &flag, status);
    if (flag) return;
    nanosleep(&(struct timespec){0, 2000000}, NULL);
  }
}

/* Rank 0: answers every request with the next task, then with -1 once
 * each rank has asked after the last one. */
static void coordinate(vl_cli_study_run *cs, int ranks) {
  size_t next = 0;
  int stopped = 0;
  while (stopped < ranks - 1) {
    MPI_Status status;
    vl_cli_study_record rec;
    wait_for_message(&status);
    MPI_Recv(&rec, (int)sizeof rec, MPI_BYTE, status.MPI_SOURCE, TAG_RESULT, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    int src = status.MPI_SOURCE;
    bool cannot = rec.task < 0 && rec.message[0]; /* a rank that could not start */
    if (rec.task >= 0) vl_cli_study_report(cs, &rec);
    if (cannot)
      fprintf(stderr, "viscolube study: rank %d cannot run tasks: %s\n", src, rec.message);
    long task = !cannot && next < cs->n_pending ? (long)cs->pending[next++] : -1;
    MPI_Send(&task, 1, MPI_LONG, src, TAG_TASK, MPI_COMM_WORLD);
    if (task < 0) stopped++;
  }
}

/* Ranks 1..N-1: the study and a read-only database of their own, then
 * tasks until rank 0 says stop. */
static void compute(vl_cli_study_run *cs) {
  vl_error err = {{0}};
  vl_db *db = NULL;
  vl_cli_study_record rec = {.task = -1};
  vl_status st = vl_study_load(cs->study_path, &cs->study, &err);
  if (st == VL_OK) st = vl_db_open_readonly(cs->g->db_path, &db, &err);
  if (st != VL_OK) snprintf(rec.message, sizeof rec.message, "%.500s", err.msg);
  for (size_t here = 1;; here++) {
    long task;
    MPI_Send(&rec, (int)sizeof rec, MPI_BYTE, 0, TAG_RESULT, MPI_COMM_WORLD);
    MPI_Recv(&task, 1, MPI_LONG, 0, TAG_TASK, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (task < 0) break;
    vl_cli_study_run_one(cs, db, (size_t)task, &rec);
    vl_cli_study_kill_hook(here);
  }
  vl_db_close(db);
}

int vl_cli_study_mpi(vl_cli_study_run *cs) {
  int rank = 0, ranks = 1, rc = 0;
  MPI_Init(NULL, NULL);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  cs->mode = "mpi";
  cs->processes = ranks - 1;
  /* rank 0 prepares the database (a new file, the tables) and DIR; the
   * others open the database only once it is ready */
  int ok = 1;
  vl_error err = {{0}};
  vl_status st = VL_OK;
  if (rank == 0) ok = (st = vl_cli_study_setup(cs, &err)) == VL_OK;
  MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (rank == 0 && !ok) {
    fprintf(stderr, "viscolube study: %s\n", err.msg[0] ? err.msg : vl_status_name(st));
    rc = vl_status_exit_code(st);
  } else if (rank == 0) {
    coordinate(cs, ranks);
    rc = vl_cli_study_finish(cs, 0);
  } else if (ok) {
    compute(cs);
  }
  MPI_Finalize();
  return rc;
}

#endif
