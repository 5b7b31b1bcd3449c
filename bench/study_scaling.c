/* What a large study costs (issue 21): runs every task of a study file in
 * this process, one at a time on one core (as each worker of `viscolube
 * study` does), measures the distribution of the per-task cost, and
 * projects the wall time of an N-curve study on R ranks of `mpirun`: rank
 * 0 hands out the tasks one at a time, R - 1 ranks compute. The projection
 * replays that dynamic schedule on N costs drawn from the measured ones
 * (with replacement, fixed seed), so it includes the load imbalance that
 * costs differing tenfold leave at the end of the study. A task's cost
 * is its CPU time, so that other programs on the machine do not count.
 *
 *   study_scaling [--db PATH] [--curves N] [--ranks R] [STUDY]
 *
 * Defaults: a temporary database created from the embedded materials, N =
 * 3000, R = 64, STUDY = studies/example.ini. Prints the figures; the
 * task files go to a temporary folder, removed at the end. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "viscolube.h"

/* The cost of a task is its CPU time: on a shared machine the wall time
 * also counts the other programs' turns. */
static double cpu_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double quantile(const double *sorted, size_t n, double q) {
  double pos = q * (double)(n - 1);
  size_t i = (size_t)pos;
  return i + 1 < n ? sorted[i] + (pos - (double)i) * (sorted[i + 1] - sorted[i]) : sorted[n - 1];
}

/* xorshift64*: a fixed, portable stream for the resampling. */
static uint64_t next_random(uint64_t *s) {
  *s ^= *s >> 12, *s ^= *s << 25, *s ^= *s >> 27;
  return *s * 2685821657736338717ull;
}

/* The dynamic schedule: each task, in order, to the worker free first.
 * Returns the makespan (s). */
static double schedule(const double *cost, size_t n, size_t workers) {
  double *free_at = calloc(workers, sizeof *free_at), end = 0;
  for (size_t i = 0; i < n; i++) {
    size_t w = 0;
    for (size_t k = 1; k < workers; k++)
      if (free_at[k] < free_at[w]) w = k;
    free_at[w] += cost[i];
    if (free_at[w] > end) end = free_at[w];
  }
  free(free_at);
  return end;
}

static void project(const double *measured, size_t m, size_t curves, size_t ranks) {
  double *cost = malloc(curves * sizeof *cost), total = 0;
  uint64_t seed = 0x9e3779b97f4a7c15ull;
  for (size_t i = 0; i < curves; i++) {
    cost[i] = measured[next_random(&seed) % m];
    total += cost[i];
  }
  size_t workers = ranks > 1 ? ranks - 1 : 1;
  double span = schedule(cost, curves, workers);
  printf("projection: %zu curves on %zu ranks (%zu computing, rank 0 hands out tasks)\n", curves,
         ranks, workers);
  printf("  serial time            %10.1f s (%.1f min)\n", total, total / 60);
  printf("  perfect balance        %10.1f s (total / %zu)\n", total / (double)workers, workers);
  printf("  dynamic schedule       %10.1f s (%.1f min), efficiency %.1f %% of the %zu ranks\n",
         span, span / 60, 100 * total / (span * (double)ranks), ranks);
  printf("  imbalance at the end   %10.1f s (makespan - perfect balance)\n",
         span - total / (double)workers);
  free(cost);
}

int main(int argc, char **argv) {
  const char *db_path = NULL, *study_path = VL_STUDIES_DIR "/example.ini";
  size_t curves = 3000, ranks = 64;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--db") && i + 1 < argc)
      db_path = argv[++i];
    else if (!strcmp(argv[i], "--curves") && i + 1 < argc)
      curves = strtoul(argv[++i], NULL, 10);
    else if (!strcmp(argv[i], "--ranks") && i + 1 < argc)
      ranks = strtoul(argv[++i], NULL, 10);
    else if (argv[i][0] != '-')
      study_path = argv[i];
    else {
      fprintf(stderr, "usage: study_scaling [--db PATH] [--curves N] [--ranks R] [STUDY]\n");
      return 2;
    }
  }
  char tmp[] = "/tmp/study-scaling-XXXXXX", db_tmp[64];
  if (!mkdtemp(tmp)) return 6;
  snprintf(db_tmp, sizeof db_tmp, "%s/m.db", tmp);
  vl_error err = {{0}};
  vl_study *s = NULL;
  vl_db *db = NULL;
  int rc = 1;
  if (vl_study_load(study_path, &s, &err) != VL_OK ||
      vl_db_open(db_path ? db_path : db_tmp, &db, &err) != VL_OK ||
      vl_study_prepare(s, db, &err) != VL_OK || vl_study_check_dir(s, tmp, &err) != VL_OK) {
    fprintf(stderr, "study_scaling: %s\n", err.msg);
    goto done;
  }
  size_t n = vl_study_n_tasks(s);
  double *sec = calloc(n, sizeof *sec), sum = 0, wall = 0;
  for (size_t i = 0; i < n; i++) {
    vl_study_result *r = NULL;
    double c0 = cpu_s();
    vl_status st = vl_study_solve_task(s, i, db, &r, &err);
    if (st == VL_OK) st = vl_study_write_task(s, i, tmp, r, &err);
    if (st != VL_OK) {
      fprintf(stderr, "study_scaling: %s\n", err.msg);
      vl_study_result_free(r);
      free(sec);
      goto done;
    }
    sec[i] = cpu_s() - c0;
    sum += sec[i];
    wall += r->outcome.seconds;
    vl_study_result_free(r);
    fprintf(stderr, "\r  task %zu/%zu  %.2f s   ", i + 1, n, sec[i]);
  }
  fputc('\n', stderr);
  qsort(sec, n, sizeof *sec, cmp_double);
  printf("study %s: %zu tasks on one core, %.1f s of CPU (%.3g tasks/s), %.1f s of wall time\n",
         study_path, n, sum, (double)n / sum, wall);
  printf("per task (CPU s): min %.3f  median %.3f  p90 %.3f  max %.3f  mean %.3f  max/min %.1f\n",
         sec[0], quantile(sec, n, 0.5), quantile(sec, n, 0.9), sec[n - 1], sum / (double)n,
         sec[n - 1] / fmax(sec[0], 1e-9));
  project(sec, n, curves, ranks);
  free(sec);
  rc = 0;
done:
  vl_db_close(db);
  vl_study_free(s);
  char cmd[200];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
  if (system(cmd) != 0) rc = rc ? rc : 6;
  return rc;
}
