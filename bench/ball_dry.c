/* The dry smooth viscoelastic ball point (issue 35): its cost at given
 * cells, and where the time goes.
 *
 *   ball_dry [--compound NAME] [--cells R] [--half L] [--speed V] [--repeats N] [--db PATH]
 *
 * A ball of 19.05 mm under 3 N on the compound (default model-rubber, one
 * Prony term; sbr-unfilled has 28) at sliding speed V (default: the speed
 * of largest rolling friction of model-rubber, 0.03 m/s), on square cells
 * of a0/R (default VL_BALL_CELLS_PER_A0) on [-L, L] x [0, L] a0. Each
 * repeat times a fresh point: the solver created, the point solved from
 * the Hertz guess, freed; then a continued point (the same contact at
 * 1.25 V from the solution at V). Prints the medians of N repeats (default
 * 5, after one untimed warm-up) and the cost split of the last fresh point.
 * Without --db the database is a fresh temporary one made from the
 * embedded materials. Run with OPENBLAS_NUM_THREADS=1 (the solver pins one
 * thread anyway). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "viscolube.h"

#include "point_contact_internal.h"

static double cpu_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

typedef struct {
  double fresh_s, create_s, continued_s, mu;
  long iterations, iterations_continued;
  size_t cells, in_contact;
  vl_point_contact_timing timing;
} one_run;

static int run_once(const vl_point_contact_config *cfg, double v0, one_run *r) {
  vl_error err;
  vl_point pt;
  double t0 = cpu_s();
  vl_point_contact *c = NULL;
  if (vl_point_contact_create(cfg, &c, &err) != VL_OK) {
    fprintf(stderr, "ball_dry: %s\n", err.msg);
    return 1;
  }
  r->create_s = cpu_s() - t0;
  vl_status st = vl_point_contact_solve(c, v0, &pt, &err);
  r->fresh_s = cpu_s() - t0;
  r->timing = c->timing;
  r->mu = pt.mu, r->iterations = pt.iterations;
  r->cells = c->n, r->in_contact = pt.ball.cells_in_contact;
  if (st == VL_OK) {
    t0 = cpu_s();
    st = vl_point_contact_solve(c, 1.25 * v0, &pt, &err);
    r->continued_s = cpu_s() - t0;
    r->iterations_continued = pt.iterations;
  }
  vl_point_contact_free(c);
  if (st != VL_OK) fprintf(stderr, "ball_dry: %s\n", err.msg);
  return st != VL_OK;
}

int main(int argc, char **argv) {
  const char *compound = "model-rubber", *db_path = NULL;
  double cells = VL_BALL_CELLS_PER_A0, half = VL_BALL_DOMAIN_A0, v0 = 0.03;
  int repeats = 5;
  for (int i = 1; i < argc; i++) {
    const char *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(argv[i], "--compound") && v)
      compound = v, i++;
    else if (!strcmp(argv[i], "--cells") && v)
      cells = atof(v), i++;
    else if (!strcmp(argv[i], "--half") && v)
      half = atof(v), i++;
    else if (!strcmp(argv[i], "--speed") && v)
      v0 = atof(v), i++;
    else if (!strcmp(argv[i], "--repeats") && v)
      repeats = atoi(v), i++;
    else if (!strcmp(argv[i], "--db") && v)
      db_path = v, i++;
    else {
      fprintf(stderr, "usage: ball_dry [--compound NAME] [--cells R] [--half L] [--speed V] "
                      "[--repeats N] [--db PATH]\n");
      return 2;
    }
  }
  if (repeats < 1 || repeats > 1000) repeats = 5;
  char tmp[] = "/tmp/ball-dry-XXXXXX", db_tmp[64] = "";
  if (!db_path) {
    if (!mkdtemp(tmp)) return 6;
    snprintf(db_tmp, sizeof db_tmp, "%s/m.db", tmp);
    db_path = db_tmp;
  }
  vl_error err;
  vl_db *db = NULL;
  vl_point_contact_config cfg;
  vl_point_contact_config_defaults(&cfg);
  int rc = 1;
  if (vl_db_open(db_path, &db, &err) != VL_OK ||
      vl_db_compound_get(db, compound, &cfg.rubber, &err) != VL_OK) {
    fprintf(stderr, "ball_dry: %s\n", err.msg);
    goto done;
  }
  cfg.radius_x_m = cfg.radius_y_m = 0.009525;
  cfg.load_n = 3.0;
  cfg.cells_per_a0 = cells;
  cfg.x_half_a0 = cfg.y_max_a0 = half;
  one_run r;
  double *fresh = malloc((size_t)repeats * sizeof *fresh);
  double *cont = malloc((size_t)repeats * sizeof *cont);
  if (!fresh || !cont || run_once(&cfg, v0, &r)) goto free_runs; /* warm-up */
  for (int k = 0; k < repeats; k++) {
    if (run_once(&cfg, v0, &r)) goto free_runs;
    fresh[k] = r.fresh_s, cont[k] = r.continued_s;
  }
  qsort(fresh, (size_t)repeats, sizeof *fresh, cmp_double);
  qsort(cont, (size_t)repeats, sizeof *cont, cmp_double);
  const vl_point_contact_timing *t = &r.timing;
  double other = r.fresh_s - r.create_s - t->t_kernel_s - t->t_residual_s - t->t_jacobian_s;
  printf("ball_dry: %s (%zu Prony terms), %g cells per a0 on [-%g, %g] x [0, %g] a0: %zu "
         "cells, %zu in contact\n",
         compound, cfg.rubber.n_terms, cells, half, half, half, r.cells, r.in_contact);
  printf("  v0 %g m/s: mu %.6g, %ld Newton iterations fresh, %ld continued (1.25 v0)\n", v0, r.mu,
         r.iterations, r.iterations_continued);
  printf("  fresh point (create + solve from Hertz): median %.3f s of %d (min %.3f, max %.3f)\n",
         fresh[repeats / 2], repeats, fresh[0], fresh[repeats - 1]);
  printf("  continued point:                        median %.3f s\n", cont[repeats / 2]);
  printf("  split of a fresh point: create (elastic tables, allocation) %.3f s, kernel %.3f s "
         "(%ld), residual %.3f s (%ld), Jacobian %.3f s (%ld), LU and the rest %.3f s\n",
         r.create_s, t->t_kernel_s, t->kernels, t->t_residual_s, t->residuals, t->t_jacobian_s,
         t->jacobians, other);
  rc = 0;
free_runs:
  free(fresh), free(cont);
done:
  vl_db_close(db);
  if (db_tmp[0]) {
    unlink(db_tmp);
    rmdir(tmp);
  }
  return rc;
}
