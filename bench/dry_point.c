/* The dry smooth point (issue 30): viscolube's cost per point on Hunter's
 * problem (cases/fig03-smooth.ini at N 400), and the discrete problem it
 * solves, for bench/dry_active_set.py to solve independently.
 *
 *   dry_point [--case FILE] [--grid N] [--points K] [--repeats R] [--db PATH]
 *             [--dump DIR]
 *
 * The scene's sweep becomes K points (default 13, fields_at dropped) on a
 * uniform grid of N cells (default 400). Each repeat times one
 * vl_simulation_run over the K speeds, what `viscolube run` does between
 * reading the database and writing the files: it creates the contact, and
 * per speed builds the influence matrix, solves (KINSOL), reports, solves
 * again on cells three times as wide for the error estimate and checks the
 * model's assumptions. Prints the median of R repeats per point, after one
 * untimed warm-up run, and the cost split of the last run.
 *
 * --dump DIR writes, from the warm-up run, what defines each point's
 * discrete problem and viscolube's solution of it (raw little-endian
 * float64): DIR/grid.txt (n, the mu_Rc factor, K), DIR/xi.bin and
 * DIR/wc.bin (node positions and cell widths /a0), and per point k
 * DIR/M<k>.bin (the n x n influence matrix, row-major: gap_i = h0 +
 * xi_i^2/2 + sum_j M_ij P_j), DIR/P<k>.bin (the contact pressure /p0) and a
 * line "k v0_m_s h0 mu_Rc iterations" of DIR/points.txt.
 *
 * Without --db the database is a fresh temporary one made from the embedded
 * materials. Run with OPENBLAS_NUM_THREADS=1 (the solver pins one thread
 * anyway). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "viscolube.h"

#include "contact_internal.h"

typedef struct {
  const char *dump;         /* NULL: no dump */
  vl_contact_timing main;   /* the last point's counters: the N contact */
  vl_contact_timing coarse; /* and its error-estimate contact */
  int failed;
} run_state;

static double cpu_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static int write_bin(const char *dir, const char *name, size_t k, const double *v, size_t n) {
  char path[4096];
  if (k == (size_t)-1)
    snprintf(path, sizeof path, "%s/%s.bin", dir, name);
  else
    snprintf(path, sizeof path, "%s/%s%zu.bin", dir, name, k);
  FILE *f = fopen(path, "wb");
  if (!f) return -1;
  size_t w = fwrite(v, sizeof *v, n, f);
  return fclose(f) == 0 && w == n ? 0 : -1;
}

/* Writes point k's matrix, pressure and summary line (dump mode). */
static int dump_point(const char *dir, size_t k, const vl_point *pt, const vl_contact *c) {
  size_t n = c->n;
  const double *y = N_VGetArrayPointer(c->y);
  char path[4096];
  if (k == 0) {
    snprintf(path, sizeof path, "%s/grid.txt", dir);
    FILE *f = fopen(path, "w");
    if (!f) return -1;
    /* mu_Rc = -(p0 a0^2/(fN R)) sum P xi wc = -(2 a0/(pi R)) sum P xi wc */
    fprintf(f, "%zu %.17g\n", n, 2.0 * c->a0 / (M_PI * c->cfg.radius_m));
    if (fclose(f) != 0) return -1;
    if (write_bin(dir, "xi", (size_t)-1, c->xi, n) || write_bin(dir, "wc", (size_t)-1, c->wc, n))
      return -1;
  }
  if (write_bin(dir, "M", k, c->M, n * n) || write_bin(dir, "P", k, c->P, n)) return -1;
  snprintf(path, sizeof path, "%s/points.txt", dir);
  FILE *f = fopen(path, k == 0 ? "w" : "a");
  if (!f) return -1;
  fprintf(f, "%zu %.17g %.17g %.17g %ld\n", k, pt->v0_m_s, y[c->ih], pt->mu_Rc, pt->iterations);
  return fclose(f);
}

static void on_point(void *user, size_t k, size_t total, const vl_point *pt, const vl_contact *c) {
  run_state *r = user;
  if (!pt->converged || !c) {
    r->failed++;
    return;
  }
  if (k + 1 == total) {
    r->main = c->timing;
    if (c->estimator) r->coarse = c->estimator->timing;
  }
  if (r->dump && dump_point(r->dump, k, pt, c) != 0) {
    fprintf(stderr, "dry_point: cannot write into %s\n", r->dump);
    r->failed++;
  }
}

static void print_split(const char *name, const vl_contact_timing *t, size_t points) {
  double k = 1e3 / (double)points;
  printf("  %-8s per point: newton %.3f ms (jacobian %.3f, LU set-up %.3f, solves %.3f, "
         "residuals %.3f), kernel %.3f ms; %.1f Newton steps, %.1f residuals\n",
         name, t->t_newton_s * k, t->t_jacobian_s * k, t->t_setup_s * k, t->t_solve_s * k,
         t->t_residual_s * k, t->t_kernel_s * k, (double)t->jacobians / (double)points,
         (double)t->residuals / (double)points);
}

int main(int argc, char **argv) {
  const char *case_path = VL_CASES_DIR "/fig03-smooth.ini", *db_path = NULL, *dump = NULL;
  size_t grid = 400, points = 13;
  int repeats = 9;
  for (int i = 1; i < argc; i++) {
    const char *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(argv[i], "--case") && v)
      case_path = v, i++;
    else if (!strcmp(argv[i], "--grid") && v)
      grid = (size_t)atol(v), i++;
    else if (!strcmp(argv[i], "--points") && v)
      points = (size_t)atol(v), i++;
    else if (!strcmp(argv[i], "--repeats") && v)
      repeats = atoi(v), i++;
    else if (!strcmp(argv[i], "--db") && v)
      db_path = v, i++;
    else if (!strcmp(argv[i], "--dump") && v)
      dump = v, i++;
    else {
      fprintf(stderr, "usage: dry_point [--case FILE] [--grid N] [--points K] [--repeats R] "
                      "[--db PATH] [--dump DIR]\n");
      return 2;
    }
  }
  if (repeats < 1 || points < 1) return 2;
  char tmp[] = "/tmp/dry-point-XXXXXX", db_tmp[64] = "";
  if (!db_path) {
    if (!mkdtemp(tmp)) return 6;
    snprintf(db_tmp, sizeof db_tmp, "%s/m.db", tmp);
    db_path = db_tmp;
  }
  vl_error err = {{0}};
  vl_scene sc;
  vl_db *db = NULL;
  vl_simulation *sim = NULL;
  vl_point *pts = NULL;
  double *sec = calloc(2 * (size_t)repeats, sizeof *sec), *cpu = sec ? sec + repeats : NULL;
  int rc = 1;
  if (vl_scene_load(case_path, &sc, &err) != VL_OK || vl_db_open(db_path, &db, &err) != VL_OK)
    goto done;
  sc.grid = grid, sc.points = points, sc.n_fields_at = 0;
  if (vl_simulation_create(&sc, db, &sim, &err) != VL_OK) goto done;
  pts = calloc(points, sizeof *pts);
  if (!pts || !sec) goto done;
  for (int r = -1; r < repeats; r++) { /* r = -1: the warm-up (and the dump) */
    run_state st = {r < 0 ? dump : NULL, {0}, {0}, 0};
    double t0 = vl_contact_now_s(), c0 = cpu_s();
    vl_status s = vl_simulation_run(sim, pts, on_point, &st, NULL, &err);
    double t = vl_contact_now_s() - t0, tc = cpu_s() - c0;
    if (s != VL_OK || st.failed) {
      if (s == VL_OK) vl_error_set(&err, "%d points failed", st.failed);
      goto done;
    }
    if (r >= 0) sec[r] = t, cpu[r] = tc;
    if (r == repeats - 1) {
      printf("# %s, N %zu, %zu speeds, repeats %d\n", case_path, grid, points, repeats);
      print_split("N", &st.main, points);
      print_split("estimate", &st.coarse, points);
    }
  }
  qsort(sec, (size_t)repeats, sizeof *sec, cmp_double);
  qsort(cpu, (size_t)repeats, sizeof *cpu, cmp_double);
  printf("viscolube_ms_per_point %.4f (median of %d; min %.4f, max %.4f; CPU time %.4f)\n",
         1e3 * sec[repeats / 2] / (double)points, repeats, 1e3 * sec[0] / (double)points,
         1e3 * sec[repeats - 1] / (double)points, 1e3 * cpu[repeats / 2] / (double)points);
  rc = 0;
done:
  if (rc) fprintf(stderr, "dry_point: %s\n", err.msg);
  free(pts);
  free(sec);
  vl_simulation_free(sim);
  vl_db_close(db);
  if (db_tmp[0]) {
    unlink(db_tmp);
    rmdir(tmp);
  }
  return rc;
}
