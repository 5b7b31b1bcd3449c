/* Accuracy-vs-cost benchmark of the contact solver (issue 7).
 *
 *   bench_accuracy [--out DIR] [--only SECTIONS] [--quick] [--db PATH]
 *                  [--cases DIR] [--ref-grid N] [--ref-inlet X] [--accuracy F]
 *
 * SECTIONS (comma-separated; default all): hunter, fig05, fig10, rubber,
 * linsol, defaults, targets.
 *   hunter   smooth dry rolling (model rubber, Einf/E0 = 10) against Hunter's
 *            exact solution (tests/oracles/hunter.c): grid 64 ... 2048, relative
 *            error of mu at De = v0 tau/a0 = 0.1, 1.3, 10 and time per point of a
 *            6-point continuation ramp in De.
 *   fig05    the scene of cases/fig05.ini (model rubber on paper-3um, eta
 *            1e-4 Pa s, Patir-Cheng, sigma_s 1 MPa), 25 points v0 eta =
 *            1e-12 ... 1 Pa m: grid x inlet length x tolerance, and the Persson
 *            table size, against a reference at the finest settings we can
 *            afford (printed). Errors are the largest over the sweep:
 *            |mu - mu_ref|/mu_ref; each component |c - c_ref|/mu_ref (components
 *            can vanish, so they are measured in units of the total);
 *            |u_min - u_min_ref|/u_min_ref. The same runs give the cost per
 *            call of residual, Jacobian, LU set-up and solve and their exponent
 *            in N.
 *   fig10    the same for cases/fig10.ini (eta 1 Pa s).
 *   rubber   cases/fig15.ini: the shipped sbr-unfilled (a fit to measured-style
 *            DMA data) on paper-0.5um in water, smooth flow factors, 23 points
 *            v0 eta = 1e-12 ... 0.1 Pa m. The compound's raw points are read
 *            from the database and refitted with 0.5, 1, 1.5, 2 Prony terms per
 *            decade of the measured window (vl_prony_fit, the stored fit's
 *            weights); grid x inlet x tolerance at 2 per decade, and the
 *            Prony density, against a reference at 2 per decade on the finest
 *            grid.
 *            Settings of the three scenes: N 64 ... 1024 (768 and 1024 at
 *            inlets >= 16 a0 only, for time) x inlet 3, 5, 8, 16, 24, 32 a0 at
 *            tolerance 1e-9, plus 1e-3 and 1e-6 at N 256, 512 and inlets 24,
 *            32; references N 1536, inlet 32 a0 (the inlet limits them: mu
 *            converges like 1/X in the inlet length, and the section prints
 *            the reference's own truncation estimated from that law).
 *   linsol   LAPACK dgetrf/dgetrs, the Schur-complement solver and
 *            SUNLinSol_Dense on a 7-point part of the fig05 sweep.
 *   defaults per scene the cheapest setting with mu within 1 % of the
 *            reference at every point, then the cheapest (grid, inlet) at
 *            tolerance 1e-9 that meets 1 % in all scenes, at that the loosest
 *            tolerance and then the fewest Prony terms per decade that still
 *            do (runs what is missing). Printed as a table for the README.
 *   targets  the speed targets: a 61-point fig05 curve (cases/fig05.ini)
 *            at N 512 and at the recommended defaults; the Newton step against
 *            one dgetrf of the same size.
 * Materials come from a temporary database created from the embedded
 * materials (the same seeding as a new default database), or from --db PATH.
 * Times are wall-clock, the median of repeats (each repeat resets the solver
 * to the Hertz guess and runs the whole sweep). Run with OPENBLAS_NUM_THREADS=1
 * for one-core figures (scripts/bench.sh does). Writes accuracy.csv,
 * cost_vs_n.csv, prony_fits.csv, defaults.csv, reference-<scene>.csv and
 * pareto-<scene>.svg into DIR (default bench-out). The full run takes about
 * 8 minutes on a 2-core Xeon; results and the selection rule: bench/README.md. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "hunter.h"
#include "viscolube/contact.h"
#include "viscolube/database.h"
#include "viscolube/prony_fit.h"
#include "viscolube/roughness.h"
#include "viscolube/scene.h"
#include "viscolube/sweep.h"

#ifndef VL_CASES_DIR
#define VL_CASES_DIR "cases"
#endif

extern void dgetrf_(const int *m, const int *n, double *a, const int *lda, int *ipiv, int *info);

/* ---------------------------------------------------------------- utils */

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static void die(const char *what, const vl_error *err) {
  fprintf(stderr, "bench_accuracy: %s: %s\n", what, err ? err->msg : "failed");
  exit(1);
}

static void machine(FILE *out) {
  char model[256] = "?", line[512];
  FILE *f = fopen("/proc/cpuinfo", "r");
  if (f) {
    while (fgets(line, sizeof line, f))
      if (strncmp(line, "model name", 10) == 0) {
        char *p = strchr(line, ':');
        if (p) snprintf(model, sizeof model, "%s", p + 2);
        model[strcspn(model, "\n")] = 0;
        break;
      }
    fclose(f);
  }
  double load[3] = {0, 0, 0};
  f = fopen("/proc/loadavg", "r");
  if (f) {
    if (fscanf(f, "%lf %lf %lf", &load[0], &load[1], &load[2]) != 3) load[0] = NAN;
    fclose(f);
  }
  const char *ob = getenv("OPENBLAS_NUM_THREADS");
  fprintf(out,
          "# machine: %s, %ld online cores, load average %.2f %.2f %.2f, "
          "OPENBLAS_NUM_THREADS=%s\n",
          model, sysconf(_SC_NPROCESSORS_ONLN), load[0], load[1], load[2], ob ? ob : "(unset)");
}

/* DIR/NAME opened for writing with the machine line and the CSV header
 * (NULL, with a message, when it cannot be created). */
static FILE *open_csv(const char *dir, const char *name, const char *header) {
  char path[1200];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  if (!f) {
    fprintf(stderr, "cannot write %s\n", path);
    return NULL;
  }
  machine(f);
  fputs(header, f);
  return f;
}

/* ---------------------------------------------------------------- results */

typedef enum {
  KIND_OTHER = 0, /* hunter, linsol, targets */
  KIND_REF,       /* a scene's reference */
  KIND_STUDY,     /* grid x inlet x tolerance at the scene's own compound */
  KIND_TABLE,     /* Persson table size */
  KIND_PRONY      /* rubber: another Prony density */
} row_kind;

typedef struct {
  char scene[16], setting[48], linsol[12];
  row_kind kind;
  size_t grid, unknowns, n_table, points, failed, compared;
  double inlet_a0, tolerance;
  double per_decade; /* Prony terms per decade of the rubber's refit (0: as stored) */
  size_t prony_terms;
  long iterations;
  double err_mu, err_rc, err_rf, err_sc, err_sf, err_umin;
  double worst_v0_eta; /* where err_mu occurs (Pa m) */
  double t_point_ms, t_curve_s;
  double t_last_s; /* the last repeat's time, which `timing` splits */
  int repeats;
  vl_contact_timing timing; /* of the last repeat */
} row;

enum { MAX_ROWS = 256 };
static row rows[MAX_ROWS];
static size_t nrows;

static void print_header(void) {
  printf("%-7s %-28s %-8s %5s %7s %4s %6s %9s %9s %9s %9s %9s %9s %9s %9s %9s\n", "scene",
         "setting", "linsol", "N", "tol", "fail", "iters", "err_mu", "at_v0eta", "err_Rc", "err_Rf",
         "err_Sc", "err_Sf", "err_umin", "ms/point", "s/curve");
}

static void print_row(const row *r) {
  printf("%-7s %-28s %-8s %5zu %7.0e %4zu %6ld %9.2e %9.1e %9.2e %9.2e %9.2e %9.2e %9.2e %9.2f "
         "%9.3f\n",
         r->scene, r->setting, r->linsol, r->grid, r->tolerance, r->failed, r->iterations,
         r->err_mu, r->worst_v0_eta, r->err_rc, r->err_rf, r->err_sc, r->err_sf, r->err_umin,
         r->t_point_ms, r->t_curve_s);
  fflush(stdout);
}

static row *new_row(void) {
  if (nrows == MAX_ROWS) {
    fprintf(stderr, "too many rows\n");
    exit(1);
  }
  row *r = &rows[nrows++];
  memset(r, 0, sizeof *r);
  r->err_mu = r->err_rc = r->err_rf = r->err_sc = r->err_sf = r->err_umin = NAN;
  r->worst_v0_eta = NAN;
  return r;
}

static const char *kind_name(row_kind k) {
  return k == KIND_REF     ? "reference"
         : k == KIND_STUDY ? "study"
         : k == KIND_TABLE ? "persson-table"
         : k == KIND_PRONY ? "prony"
                           : "other";
}

static int write_rows_csv(const char *dir) {
  FILE *f = open_csv(dir, "accuracy.csv",
                     "scene,kind,setting,linear_solver,grid,unknowns,inlet_a0,tolerance,n_table,"
                     "prony_per_decade,prony_terms,points,failed,newton_iterations,err_mu,"
                     "worst_v0_eta_pa_m,err_mu_Rc,err_mu_Rf,err_mu_Sc,err_mu_Sf,err_u_min,"
                     "ms_per_point,s_per_curve,repeats\n");
  if (!f) return -1;
  for (size_t i = 0; i < nrows; i++) {
    const row *r = &rows[i];
    fprintf(f,
            "%s,%s,%s,%s,%zu,%zu,%g,%g,%zu,%g,%zu,%zu,%zu,%ld,%.6e,%.3e,%.6e,%.6e,%.6e,%.6e,%.6e,"
            "%.4f,%.5f,%d\n",
            r->scene, kind_name(r->kind), r->setting, r->linsol, r->grid, r->unknowns, r->inlet_a0,
            r->tolerance, r->n_table, r->per_decade, r->prony_terms, r->points, r->failed,
            r->iterations, r->err_mu, r->worst_v0_eta, r->err_rc, r->err_rf, r->err_sc, r->err_sf,
            r->err_umin, r->t_point_ms, r->t_curve_s, r->repeats);
  }
  return fclose(f);
}

/* ---------------------------------------------------------------- Pareto SVG */

/* Log-log scatter of error against time; the non-dominated points (sorted
 * by time, each with a smaller error than every cheaper one) are joined and
 * drawn blue; `chosen` (may be SIZE_MAX) gets a green ring, `rec` (the
 * recommended defaults, may be SIZE_MAX) a purple square. */
static int pareto_svg(const char *path, const char *title, const char *xlabel, size_t n,
                      const double *t, const double *e, const char *const *label, size_t chosen,
                      const char *chosen_note, size_t rec) {
  FILE *f = fopen(path, "w");
  if (!f) return -1;
  const double W = 960, H = 660, L = 90, R = 300, T = 50, B = 70;
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
  for (size_t i = 0; i < n; i++) {
    if (!(t[i] > 0 && e[i] > 0)) continue;
    xmin = fmin(xmin, log10(t[i])), xmax = fmax(xmax, log10(t[i]));
    ymin = fmin(ymin, log10(e[i])), ymax = fmax(ymax, log10(e[i]));
  }
  if (!(xmax >= xmin)) xmin = -1, xmax = 1, ymin = -3, ymax = 0;
  xmin = floor(xmin), xmax = ceil(xmax), ymin = floor(fmin(ymin, -2.0)), ymax = ceil(ymax);
  if (xmax <= xmin) xmax = xmin + 1;
  if (ymax <= ymin) ymax = ymin + 1;
#define PX(v) (L + (log10(v) - xmin) / (xmax - xmin) * (W - L - R))
#define PY(v) (H - B - (log10(v) - ymin) / (ymax - ymin) * (H - T - B))
  fprintf(f,
          "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" "
          "font-family=\"sans-serif\" font-size=\"13\">\n<rect width=\"100%%\" height=\"100%%\" "
          "fill=\"white\"/>\n<text x=\"%g\" y=\"28\" font-size=\"16\">%s</text>\n",
          W, H, L, title);
  for (double d = xmin; d <= xmax + 1e-9; d += 1) {
    double x = L + (d - xmin) / (xmax - xmin) * (W - L - R);
    fprintf(f,
            "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"#ddd\"/>"
            "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">1e%g</text>\n",
            x, T, x, H - B, x, H - B + 20, d);
  }
  for (double d = ymin; d <= ymax + 1e-9; d += 1) {
    double y = H - B - (d - ymin) / (ymax - ymin) * (H - T - B);
    fprintf(f,
            "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"#ddd\"/>"
            "<text x=\"%g\" y=\"%g\" text-anchor=\"end\">1e%g</text>\n",
            L, y, W - R, y, L - 6, y + 4, d);
  }
  if (ymin <= -2 && ymax >= -2)
    fprintf(f,
            "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"#c00\" "
            "stroke-dasharray=\"6,4\"/><text x=\"%g\" y=\"%g\" fill=\"#c00\">1 %%</text>\n",
            L, PY(1e-2), W - R, PY(1e-2), W - R + 4, PY(1e-2) + 4);
  fprintf(f,
          "<rect x=\"%g\" y=\"%g\" width=\"%g\" height=\"%g\" fill=\"none\" stroke=\"black\"/>\n",
          L, T, W - L - R, H - T - B);
  fprintf(f, "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">%s</text>\n", (L + W - R) / 2, H - 20,
          xlabel);
  fprintf(f,
          "<text transform=\"translate(24,%g) rotate(-90)\" text-anchor=\"middle\">largest "
          "relative error of mu over the sweep</text>\n",
          (T + H - B) / 2);
  size_t *ord = malloc((n ? n : 1) * sizeof *ord);
  char *front = calloc(n ? n : 1, 1);
  for (size_t i = 0; i < n; i++)
    ord[i] = i;
  for (size_t i = 1; i < n; i++)
    for (size_t j = i; j > 0 && t[ord[j]] < t[ord[j - 1]]; j--) {
      size_t s = ord[j];
      ord[j] = ord[j - 1], ord[j - 1] = s;
    }
  fprintf(f, "<polyline fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"2.5\" points=\"");
  double best = INFINITY;
  for (size_t k = 0; k < n; k++) {
    size_t i = ord[k];
    if (!(t[i] > 0 && e[i] > 0) || e[i] >= best) continue;
    best = e[i];
    front[i] = 1;
    fprintf(f, "%g,%g ", PX(t[i]), PY(e[i]));
  }
  fprintf(f, "\"/>\n");
  for (size_t i = 0; i < n; i++) {
    if (!(t[i] > 0 && e[i] > 0)) continue;
    fprintf(f,
            "<circle cx=\"%g\" cy=\"%g\" r=\"4.5\" fill=\"%s\" stroke=\"black\" "
            "stroke-width=\"0.6\"><title>%s</title></circle>\n",
            PX(t[i]), PY(e[i]), front[i] ? "#1f77b4" : "#ff7f0e", label[i]);
    fprintf(f, "<text x=\"%g\" y=\"%g\" font-size=\"9\" fill=\"#444\">%s</text>\n", PX(t[i]) + 6,
            PY(e[i]) - 4, label[i]);
  }
  if (chosen < n && t[chosen] > 0 && e[chosen] > 0)
    fprintf(f,
            "<circle cx=\"%g\" cy=\"%g\" r=\"10\" fill=\"none\" stroke=\"#2ca02c\" "
            "stroke-width=\"2.5\"/>\n",
            PX(t[chosen]), PY(e[chosen]));
  if (rec < n && t[rec] > 0 && e[rec] > 0)
    fprintf(f,
            "<rect x=\"%g\" y=\"%g\" width=\"18\" height=\"18\" fill=\"none\" "
            "stroke=\"#9467bd\" stroke-width=\"2.5\"/>\n",
            PX(t[rec]) - 9, PY(e[rec]) - 9);
  double ly = T + 14;
  fprintf(f, "<text x=\"%g\" y=\"%g\">blue line and dots: Pareto front</text>\n", W - R + 10, ly);
  fprintf(f, "<text x=\"%g\" y=\"%g\">orange: dominated settings</text>\n", W - R + 10, ly += 18);
  fprintf(f,
          "<text x=\"%g\" y=\"%g\">labels: N / inlet (a0) / tol [/ table | /p terms per "
          "decade]</text>\n",
          W - R + 10, ly += 18);
  if (chosen_note)
    fprintf(f, "<text x=\"%g\" y=\"%g\" fill=\"#2ca02c\">green ring: %s</text>\n", W - R + 10,
            ly += 18, chosen_note);
  if (rec < n)
    fprintf(f,
            "<text x=\"%g\" y=\"%g\" fill=\"#9467bd\">purple square: the recommended "
            "defaults</text>\n",
            W - R + 10, ly += 18);
  fprintf(f, "<text x=\"%g\" y=\"%g\">failed points: not drawn</text>\n", W - R + 10, ly += 18);
  fprintf(f, "</svg>\n");
#undef PX
#undef PY
  free(ord);
  free(front);
  return fclose(f);
}

/* ---------------------------------------------------------------- dgetrf */

/* Median seconds of one dgetrf of an n x n well-conditioned matrix. */
static double dgetrf_seconds(int n, int repeats) {
  size_t nn = (size_t)n * (size_t)n;
  double *a0 = malloc(nn * sizeof *a0), *a = malloc(nn * sizeof *a);
  int *piv = malloc((size_t)n * sizeof *piv);
  double t[16];
  unsigned s = 12345u;
  for (size_t i = 0; i < nn; i++) {
    s = s * 1103515245u + 12345u;
    a0[i] = (double)(s >> 8) / 16777216.0 - 0.5;
  }
  for (int i = 0; i < n; i++)
    a0[(size_t)i * (size_t)n + (size_t)i] += n;
  if (repeats > 16) repeats = 16;
  for (int r = 0; r < repeats; r++) {
    memcpy(a, a0, nn * sizeof *a);
    int info;
    double t0 = now_s();
    dgetrf_(&n, &n, a, &n, piv, &info);
    t[r] = now_s() - t0;
  }
  free(a0), free(a), free(piv);
  return median(t, repeats);
}

/* ---------------------------------------------------------------- Hunter */

#define E0 3.6e6
#define TAU 0.1
#define RADIUS 0.01
#define LOAD 1000.0

static void bench_hunter(bool quick) {
  double de[] = {1e-2, 0.1, 0.4, 1.3, 4.0, 10.0};
  const int nde = 6, check[3] = {1, 3, 5};
  double href[3];
  for (int k = 0; k < 3; k++) {
    vl_oracle_hunter_solution h;
    if (vl_oracle_hunter_solve(de[check[k]], 10.0, &h) != 0) {
      fprintf(stderr, "Hunter oracle failed\n");
      exit(1);
    }
    href[k] = h.mu_R_over_a0;
  }
  printf("\n## hunter: smooth dry, Einf/E0 = 10, domain [-1.5, 1.5] a0, tolerance 1e-9,\n"
         "## 6-point ramp De = 0.01 ... 10; err_mu = worst of De = 0.1, 1.3, 10; "
         "err_Rc/Rf/Sc columns = error at De = 0.1, 1.3, 10\n");
  print_header();
  size_t grids[] = {64, 128, 256, 512, 1024, 2048};
  size_t ng = quick ? 4 : 6;
  for (int ls = 0; ls < 2; ls++)
    for (size_t g = 0; g < ng; g++) {
      size_t N = grids[g];
      if (ls == 1 && N != 256) continue; /* SUNDIALS: one comparison size (linsol has more) */
      vl_contact_config cfg;
      vl_contact_config_defaults(&cfg);
      cfg.rubber = vl_prony_single(E0, 10.0, TAU, 0.5);
      cfg.radius_m = RADIUS, cfg.load_n_per_m = LOAD, cfg.grid = N;
      cfg.x_min_a0 = -1.5, cfg.x_max_a0 = 1.5;
      cfg.linear_solver = ls ? VL_LINSOL_SUNDIALS : VL_LINSOL_LAPACK;
      vl_contact *c;
      vl_error err;
      if (vl_contact_create(&cfg, &c, &err) != VL_OK) die("create", &err);
      double v[6];
      for (int i = 0; i < nde; i++)
        v[i] = de[i] * vl_contact_a0(c) / TAU;
      vl_point pts[6];
      int reps = N <= 256 ? 3 : N <= 512 ? 2 : 1;
      if (ls) reps = 1;
      double tt[8];
      vl_sweep_stats st = {0};
      row *r = new_row();
      for (int k = 0; k < reps; k++) {
        vl_contact_reset(c);
        vl_contact_timing_reset(c);
        double t0 = now_s();
        vl_sweep_run(c, (size_t)nde, v, NULL, pts, NULL, NULL, &st, &err);
        tt[k] = now_s() - t0;
      }
      vl_contact_timing_get(c, &r->timing);
      snprintf(r->scene, sizeof r->scene, "hunter");
      snprintf(r->setting, sizeof r->setting, "N%zu", N);
      snprintf(r->linsol, sizeof r->linsol, "%s", ls ? "sundials" : "lapack");
      r->grid = N, r->unknowns = N + 1, r->inlet_a0 = 1.5, r->tolerance = cfg.tolerance;
      r->points = (size_t)nde, r->failed = st.failed, r->iterations = st.newton_iterations;
      r->repeats = reps;
      r->t_curve_s = median(tt, reps);
      r->t_point_ms = 1e3 * r->t_curve_s / nde;
      double e[3];
      for (int k = 0; k < 3; k++) {
        const vl_point *p = &pts[check[k]];
        e[k] = p->converged ? fabs(p->mu_Rc * RADIUS / vl_contact_a0(c) - href[k]) / href[k] : NAN;
      }
      r->err_mu = fmax(e[0], fmax(e[1], e[2]));
      r->err_rc = e[0], r->err_rf = e[1], r->err_sc = e[2];
      r->worst_v0_eta = NAN;
      print_row(r);
      vl_contact_free(c);
    }
}

/* ---------------------------------------------------------------- scenes */

/* Materials: a database created from the embedded materials in a fresh
 * temporary directory (what a new default database holds), unless --db. */
static vl_db *g_db;
static char g_tmpdir[256], g_dbpath[1200];
static const char *g_cases = VL_CASES_DIR;

static void db_open(const char *path) {
  vl_error err;
  if (path) {
    snprintf(g_dbpath, sizeof g_dbpath, "%s", path);
  } else {
    const char *tmp = getenv("TMPDIR");
    snprintf(g_tmpdir, sizeof g_tmpdir, "%s/vl-bench-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(g_tmpdir)) {
      fprintf(stderr, "bench_accuracy: cannot create a temporary directory: %s\n", strerror(errno));
      exit(1);
    }
    snprintf(g_dbpath, sizeof g_dbpath, "%s/materials.db", g_tmpdir);
  }
  if (vl_db_open(g_dbpath, &g_db, &err) != VL_OK) die(g_dbpath, &err);
  printf("# materials: %s%s\n", g_dbpath,
         path ? ""
              : " (temporary, created from the embedded materials like a new default database)");
}

static void db_close(void) {
  vl_db_close(g_db);
  g_db = NULL;
  if (g_tmpdir[0]) {
    const char *suffix[] = {"", "-journal", "-wal", "-shm"};
    char p[1300];
    for (int i = 0; i < 4; i++) {
      snprintf(p, sizeof p, "%s%s", g_dbpath, suffix[i]);
      unlink(p);
    }
    rmdir(g_tmpdir);
    g_tmpdir[0] = 0;
  }
}

enum { MAX_TABLES = 6 };

typedef struct {
  char name[16];   /* fig05, fig10, rubber */
  char file[1100]; /* the case file */
  vl_scene sc;
  vl_prony rubber; /* the compound as stored */
  vl_psd psd;
  double eta_pa_s;
  size_t npts; /* points of the benchmark sweep, log-spaced over [from, to] of the case */
  size_t tab_n[MAX_TABLES];
  vl_persson *tab[MAX_TABLES];
  bool loaded;
  vl_point ref[64]; /* the reference solution (npts points) */
  bool have_ref;
  size_t ref_row;
} scene_ctx;

static scene_ctx g_fig05 = {.name = "fig05"}, g_fig10 = {.name = "fig10"},
                 g_rubber = {.name = "rubber"};

/* Loads cases/<file>: every physical parameter of the benchmark comes from
 * the case file and the database, so the benchmark follows the cases. */
static scene_ctx *scene_load(scene_ctx *s, const char *file, size_t npts) {
  if (s->loaded) return s;
  vl_error err;
  snprintf(s->file, sizeof s->file, "%s/%s", g_cases, file);
  if (vl_scene_load(s->file, &s->sc, &err) != VL_OK) die(s->file, &err);
  const vl_scene *sc = &s->sc;
  if (!sc->effects.viscoelastic || !sc->effects.roughness || !sc->effects.fluid ||
      sc->effects.viscous_flattening || sc->effects.temperature ||
      sc->quantity != VL_SWEEP_V0_ETA) {
    fprintf(stderr,
            "bench_accuracy: %s: expected a wet rough viscoelastic v0_eta sweep without "
            "flattening or temperature\n",
            s->file);
    exit(1);
  }
  if (vl_db_compound_get(g_db, sc->compound, &s->rubber, &err) != VL_OK) die(sc->compound, &err);
  if (vl_db_surface_get(g_db, sc->surface, &s->psd, &err) != VL_OK) die(sc->surface, &err);
  if (vl_db_fluid_get(g_db, sc->fluid, &s->eta_pa_s, &err) != VL_OK) die(sc->fluid, &err);
  s->npts = npts;
  s->loaded = true;
  return s;
}

static void scene_describe(const scene_ctx *s) {
  const vl_scene *sc = &s->sc;
  printf("## %s: %s (%s): %s (%zu Prony terms, E0 %.3g Pa) on %s (h_rms %.3g m), %s (eta %.3g "
         "Pa s),\n##   R %g m, fN %g N/m, sigma_s %g Pa, flow factors %s; %zu points v0 eta = "
         "%g ... %g Pa m (the case: %zu points, N %zu, domain [%g, %g] a0, tol %g)\n",
         s->name, s->file, sc->title, sc->compound, s->rubber.n_terms, vl_prony_e0(&s->rubber),
         sc->surface, s->psd.hrms_m, sc->fluid, s->eta_pa_s, sc->radius_m, sc->load_n_per_m,
         sc->effects.solid_shear ? sc->sigma_s_pa : 0.0,
         vl_flow_factors_name(sc->effects.flow_factors), s->npts, sc->from, sc->to, sc->points,
         sc->grid, sc->domain_min_a0, sc->domain_max_a0, sc->tolerance);
}

static vl_persson *table_for(scene_ctx *s, size_t n_table) {
  for (int i = 0; i < MAX_TABLES; i++)
    if (s->tab[i] && s->tab_n[i] == n_table) return s->tab[i];
  for (int i = 0; i < MAX_TABLES; i++)
    if (!s->tab[i]) {
      vl_error err;
      if (vl_persson_build(&s->psd, n_table, &s->tab[i], &err) != VL_OK) die("persson", &err);
      s->tab_n[i] = n_table;
      return s->tab[i];
    }
  fprintf(stderr, "too many Persson tables\n");
  exit(1);
}

static void scene_free(scene_ctx *s) {
  if (!s->loaded) return;
  for (int i = 0; i < MAX_TABLES; i++)
    vl_persson_free(s->tab[i]);
  vl_psd_free(&s->psd);
  s->loaded = false;
}

/* v0 eta of point i of n over the case's range (log-spaced). */
static double sweep_v0_eta(const scene_ctx *s, size_t n, size_t i) {
  double a = log10(s->sc.from), b = log10(s->sc.to);
  return pow(10.0, a + (b - a) * (double)i / (double)(n - 1));
}

typedef struct {
  size_t grid, n_table;
  double inlet_a0, tol;
  vl_linear_solver ls;
  size_t npts;         /* 0: the scene's */
  size_t first, count; /* sub-range of the sweep that is run (count 0: all) */
  int repeats;
  const vl_prony *rubber; /* NULL: the compound as stored */
  double per_decade;      /* the refit's density (0: as stored) */
} setting;

static const char *linsol_name(vl_linear_solver ls) {
  return ls == VL_LINSOL_SUNDIALS ? "sundials" : ls == VL_LINSOL_SCHUR ? "schur" : "lapack";
}

/* Runs a sweep of scene s at setting q, q->repeats times; fills out[count]
 * (of the last repeat) and a row (errors left to the caller). */
static row *run_setting(scene_ctx *s, const setting *q, vl_point *out, const char *label,
                        row_kind kind) {
  const vl_scene *sc = &s->sc;
  vl_contact_config cfg;
  vl_contact_config_defaults(&cfg);
  cfg.rubber = q->rubber ? *q->rubber : s->rubber;
  cfg.radius_m = sc->radius_m, cfg.load_n_per_m = sc->load_n_per_m;
  cfg.sigma_s_pa = sc->effects.solid_shear ? sc->sigma_s_pa : 0.0;
  cfg.roughness = table_for(s, q->n_table);
  cfg.eta_pa_s = s->eta_pa_s;
  cfg.flow_factors = sc->effects.flow_factors;
  cfg.grid = q->grid, cfg.x_min_a0 = -q->inlet_a0, cfg.x_max_a0 = sc->domain_max_a0;
  cfg.tolerance = q->tol, cfg.linear_solver = q->ls;
  vl_contact *c;
  vl_error err;
  if (vl_contact_create(&cfg, &c, &err) != VL_OK) die("create", &err);
  size_t np = q->npts ? q->npts : s->npts, count = q->count ? q->count : np;
  double *v = malloc(np * sizeof *v);
  for (size_t i = 0; i < np; i++)
    v[i] = sweep_v0_eta(s, np, i) / cfg.eta_pa_s;
  double tt[8];
  int reps = q->repeats < 1 ? 1 : q->repeats < 8 ? q->repeats : 8;
  vl_sweep_stats st = {0};
  row *r = new_row();
  for (int k = 0; k < reps; k++) {
    vl_contact_reset(c);
    vl_contact_timing_reset(c);
    double t0 = now_s();
    vl_sweep_run(c, count, v + q->first, NULL, out, NULL, NULL, &st, &err);
    tt[k] = now_s() - t0;
  }
  vl_contact_timing_get(c, &r->timing);
  snprintf(r->scene, sizeof r->scene, "%s", s->name);
  snprintf(r->setting, sizeof r->setting, "%s", label);
  snprintf(r->linsol, sizeof r->linsol, "%s", linsol_name(q->ls));
  r->kind = kind;
  r->grid = q->grid, r->unknowns = 2 * q->grid + 1, r->inlet_a0 = q->inlet_a0;
  r->tolerance = q->tol, r->n_table = q->n_table, r->points = count;
  r->per_decade = q->per_decade, r->prony_terms = cfg.rubber.n_terms;
  r->failed = st.failed, r->iterations = st.newton_iterations, r->repeats = reps;
  r->t_last_s = tt[reps - 1];
  r->t_curve_s = median(tt, reps);
  r->t_point_ms = 1e3 * r->t_curve_s / (double)count;
  free(v);
  vl_contact_free(c);
  return r;
}

/* Largest errors over the points where both converged (see the header). */
static void set_errors(row *r, const scene_ctx *s, const vl_point *p, const vl_point *ref,
                       size_t n) {
  double e[6] = {0, 0, 0, 0, 0, 0};
  size_t m = 0, worst = SIZE_MAX;
  for (size_t i = 0; i < n; i++) {
    if (!p[i].converged || !ref[i].converged) continue;
    m++;
    double mu = fabs(ref[i].mu), d = fabs(p[i].mu - ref[i].mu) / mu;
    if (worst == SIZE_MAX || d > e[0]) e[0] = d, worst = i;
    e[1] = fmax(e[1], fabs(p[i].mu_Rc - ref[i].mu_Rc) / mu);
    e[2] = fmax(e[2], fabs(p[i].mu_Rf - ref[i].mu_Rf) / mu);
    e[3] = fmax(e[3], fabs(p[i].mu_Sc - ref[i].mu_Sc) / mu);
    e[4] = fmax(e[4], fabs(p[i].mu_Sf - ref[i].mu_Sf) / mu);
    e[5] = fmax(e[5], fabs(p[i].u_min_m - ref[i].u_min_m) / ref[i].u_min_m);
  }
  r->compared = m;
  if (m == 0) return; /* errors stay NaN */
  r->err_mu = e[0], r->err_rc = e[1], r->err_rf = e[2], r->err_sc = e[3], r->err_sf = e[4];
  r->err_umin = e[5];
  r->worst_v0_eta = sweep_v0_eta(s, s->npts, worst);
}

static void write_reference_csv(const char *dir, const scene_ctx *s, const row *r) {
  char path[1200];
  snprintf(path, sizeof path, "%s/reference-%s.csv", dir, s->name);
  FILE *f = fopen(path, "w");
  if (!f) {
    fprintf(stderr, "cannot write %s\n", path);
    return;
  }
  fprintf(f,
          "# reference of %s: %s, N %zu, domain [-%g, %g] a0, tol %g, Persson table %zu, "
          "%zu Prony terms\n",
          s->name, s->file, r->grid, r->inlet_a0, s->sc.domain_max_a0, r->tolerance, r->n_table,
          r->prony_terms);
  fprintf(f, "v0_eta_pa_m,converged,mu,mu_Rc,mu_Rf,mu_Sc,mu_Sf,u_min_m,fluid_load_fraction\n");
  for (size_t i = 0; i < s->npts; i++) {
    const vl_point *p = &s->ref[i];
    fprintf(f, "%.6e,%d,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e,%.6f\n", sweep_v0_eta(s, s->npts, i),
            p->converged ? 1 : 0, p->mu, p->mu_Rc, p->mu_Rf, p->mu_Sc, p->mu_Sf, p->u_min_m,
            p->fluid_load_fraction);
  }
  fclose(f);
}

static void setting_label(char *buf, size_t size, size_t N, double inlet, double tol) {
  snprintf(buf, size, "N%zu/in%g/tol%.0e", N, inlet, tol);
}

/* ---------------------------------------------------------------- studies */

/* Points of each row's (last) sweep, for the defaults and the extrapolation. */
static vl_point *row_pts[MAX_ROWS];

static void keep_points(const row *r, const vl_point *p) {
  size_t i = (size_t)(r - rows);
  free(row_pts[i]);
  row_pts[i] = malloc(r->points * sizeof *p);
  memcpy(row_pts[i], p, r->points * sizeof *p);
}

typedef struct {
  size_t ref_grid, ref_table;
  double ref_inlet, ref_tol;
  size_t grids[8], ngrids;
  double inlets[8];
  size_t ninlets;
  size_t big_grid; /* grids >= this run only at inlets >= big_inlet_min (cost) */
  double big_inlet_min;
  double tols[4]; /* extra tolerances besides 1e-9 ... */
  size_t ntols;
  size_t tol_grids[4], ntol_grids; /* ... at these grids ... */
  double tol_inlets[4];
  size_t ntol_inlets;     /* ... and these inlets */
  double extrap_inlet[2]; /* the 1/X estimate of the reference's inlet truncation */
} plan;

static size_t ref_grid_opt;
static double ref_inlet_opt;
static const size_t DEFAULT_TABLE = 256;
#define COST_INLET 16.0 /* the inlet of the cost-vs-N runs: present at every grid */

static int reps_for(size_t N, bool quick) {
  if (quick) return 1;
  return N <= 128 ? 3 : N <= 256 ? 2 : 1; /* median of 3 where a curve is cheap */
}

static plan plan_for(const scene_ctx *s, bool quick) {
  bool rubber = strcmp(s->name, "rubber") == 0;
  plan p;
  memset(&p, 0, sizeof p);
  if (quick) {
    p = (plan){.ref_grid = 512,
               .ref_table = 1024,
               .ref_inlet = 16,
               .ref_tol = 1e-9,
               .grids = {64, 128, 256},
               .ngrids = 3,
               .inlets = {5, 16},
               .ninlets = 2,
               .big_grid = 100000,
               .tols = {1e-6},
               .ntols = 1,
               .tol_grids = {128},
               .ntol_grids = 1,
               .tol_inlets = {16},
               .ntol_inlets = 1,
               .extrap_inlet = {5, 16}};
    if (rubber) p.ref_grid = 256, p.grids[2] = 0, p.ngrids = 2;
  } else {
    /* Reference: the finest grid we can afford with the longest inlet. The
     * inlet, not the grid, limits the top of the wet sweeps: mu converges
     * like 1/X in the inlet length X (the film's pressure and shear tails),
     * so the largest studied inlet is the reference's. */
    p = (plan){.ref_grid = 1536,
               .ref_table = 2048,
               .ref_inlet = 32,
               .ref_tol = 1e-9,
               .grids = {64, 128, 256, 512, 768, 1024},
               .ngrids = 6,
               .inlets = {3, 5, 8, 16, 24, 32},
               .ninlets = 6,
               .big_grid = 768,
               .big_inlet_min = 16,
               .tols = {1e-3, 1e-6},
               .ntols = 2,
               .tol_grids = {256, 512},
               .ntol_grids = 2,
               .tol_inlets = {24, 32},
               .ntol_inlets = 2,
               .extrap_inlet = {16, 32}};
    (void)rubber; /* the rubber needs N 1024 too: its contact is the narrowest */
  }
  if (ref_grid_opt) p.ref_grid = ref_grid_opt;
  if (ref_inlet_opt > 0) p.ref_inlet = ref_inlet_opt;
  return p;
}

/* Runs the reference of s (once) and prints it. */
static void run_reference(scene_ctx *s, const plan *p, const vl_prony *rubber, double per_decade,
                          const char *dir) {
  setting q = {p->ref_grid, p->ref_table, p->ref_inlet, p->ref_tol, VL_LINSOL_SCHUR, 0, 0, 0,
               1,           rubber,       per_decade};
  char name[48];
  snprintf(name, sizeof name, "reference N%zu/in%g", p->ref_grid, p->ref_inlet);
  row *r = run_setting(s, &q, s->ref, name, KIND_REF);
  set_errors(r, s, s->ref, s->ref, s->npts);
  r->worst_v0_eta = NAN;
  s->have_ref = true;
  s->ref_row = (size_t)(r - rows);
  keep_points(r, s->ref);
  print_header();
  print_row(r);
  if (r->failed)
    printf("# WARNING: the reference failed at %zu of %zu points; errors skip them\n", r->failed,
           s->npts);
  write_reference_csv(dir, s, r);
}

/* Grid x inlet x tolerance of s against its reference. */
static void run_study(scene_ctx *s, const plan *p, const vl_prony *rubber, double per_decade) {
  vl_point pts[64];
  for (size_t g = 0; g < p->ngrids; g++)
    for (size_t il = 0; il < p->ninlets; il++) {
      size_t N = p->grids[g];
      double X = p->inlets[il];
      if (N >= p->big_grid && X < p->big_inlet_min) continue;
      double tl[5] = {1e-9};
      size_t nt = 1;
      for (size_t a = 0; a < p->ntol_grids; a++)
        for (size_t b = 0; b < p->ntol_inlets; b++)
          if (p->tol_grids[a] == N && p->tol_inlets[b] == X)
            for (size_t k = 0; k < p->ntols; k++)
              tl[nt++] = p->tols[k];
      for (size_t k = 0; k < nt; k++) {
        setting q = {N, DEFAULT_TABLE,      X,      tl[k],     VL_LINSOL_SCHUR, 0, 0,
                     0, reps_for(N, false), rubber, per_decade};
        char name[48];
        setting_label(name, sizeof name, N, X, tl[k]);
        row *r = run_setting(s, &q, pts, name, KIND_STUDY);
        set_errors(r, s, pts, s->ref, s->npts);
        keep_points(r, pts);
        print_row(r);
      }
    }
}

static const row *find_row(const char *scene, row_kind kind, size_t N, double X, double tol,
                           double per_decade, size_t n_table) {
  for (size_t i = 0; i < nrows; i++) {
    const row *r = &rows[i];
    if (strcmp(r->scene, scene) == 0 && r->kind == kind && r->grid == N && r->inlet_a0 == X &&
        r->tolerance == tol && r->per_decade == per_decade && r->n_table == n_table)
      return r;
  }
  return NULL;
}

/* The reference's own inlet truncation, from mu(X) = mu_inf - c/X through
 * the two study runs at inlets X1 < X2 on the finest studied grid:
 * mu_inf - mu(Xr) = (mu(X2) - mu(X1)) (1/Xr) / (1/X1 - 1/X2). */
static void inlet_extrapolation(const scene_ctx *s, const plan *p, double per_decade) {
  const row *a = NULL, *b = NULL;
  for (size_t g = p->ngrids; g-- > 0 && !(a && b);) {
    a = find_row(s->name, KIND_STUDY, p->grids[g], p->extrap_inlet[0], 1e-9, per_decade,
                 DEFAULT_TABLE);
    b = find_row(s->name, KIND_STUDY, p->grids[g], p->extrap_inlet[1], 1e-9, per_decade,
                 DEFAULT_TABLE);
  }
  if (!a || !b) return;
  const vl_point *pa = row_pts[a - rows], *pb = row_pts[b - rows];
  double x1 = p->extrap_inlet[0], x2 = p->extrap_inlet[1], xr = p->ref_inlet, worst = 0;
  size_t wi = 0;
  for (size_t i = 0; i < s->npts; i++) {
    if (!pa[i].converged || !pb[i].converged || !s->ref[i].converged) continue;
    double d = (pb[i].mu - pa[i].mu) * (1.0 / xr) / (1.0 / x1 - 1.0 / x2) / fabs(s->ref[i].mu);
    if (fabs(d) > fabs(worst)) worst = d, wi = i;
  }
  printf("# inlet truncation of the reference itself, estimated from mu(X) = mu_inf - c/X through "
         "the N%zu runs at inlets %g and %g: mu_inf/mu_ref - 1 = %+.2f %% at worst "
         "(v0 eta = %.2g Pa m)\n",
         a->grid, x1, x2, 100 * worst, sweep_v0_eta(s, s->npts, wi));
}

static void cost_vs_n(const char *dir) {
  printf("\n## cost per call vs N (fig05 runs, inlet %g, tol 1e-9, Schur solver: LU of the "
         "(N+1)^2 complement; unknowns 2N+1)\n",
         COST_INLET);
  printf("%6s %8s %12s %12s %12s %12s %12s %14s %12s %8s\n", "N", "unknowns", "residual_ms",
         "jacobian_ms", "LU_setup_ms", "solve_ms", "kernel_ms", "newton_step_ms", "dgetrf_ms",
         "step/LU");
  FILE *f = open_csv(dir, "cost_vs_n.csv",
                     "grid,unknowns,residual_ms,jacobian_ms,lu_setup_ms,solve_ms,kernel_ms,"
                     "newton_step_ms,dgetrf_of_2n1_ms,step_over_dgetrf\n");
  double xs[8], yr[8], yj[8], ys[8], yv[8], xlo = INFINITY, xhi = 0;
  size_t nx = 0;
  for (size_t i = 0; i < nrows; i++) {
    const row *r = &rows[i];
    if (strcmp(r->scene, "fig05") != 0 || r->kind != KIND_STUDY || r->inlet_a0 != COST_INLET ||
        r->tolerance != 1e-9 || r->n_table != DEFAULT_TABLE)
      continue;
    const vl_contact_timing *tm = &r->timing;
    double res = 1e3 * tm->t_residual_s / (double)tm->residuals;
    double jac = 1e3 * tm->t_jacobian_s / (double)tm->jacobians;
    double lu = 1e3 * tm->t_setup_s / (double)tm->setups;
    double sol = 1e3 * tm->t_solve_s / (double)tm->solves;
    double ker = tm->kernels ? 1e3 * tm->t_kernel_s / (double)tm->kernels : 0.0;
    double step = 1e3 * tm->t_newton_s / (double)(r->iterations > 0 ? r->iterations : 1);
    double lap = 1e3 * dgetrf_seconds((int)r->unknowns, r->grid >= 1024 ? 3 : 7);
    printf("%6zu %8zu %12.4f %12.3f %12.3f %12.4f %12.3f %14.3f %12.3f %8.2f\n", r->grid,
           r->unknowns, res, jac, lu, sol, ker, step, lap, step / lap);
    if (f)
      fprintf(f, "%zu,%zu,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.4f\n", r->grid, r->unknowns, res,
              jac, lu, sol, ker, step, lap, step / lap);
    if (r->grid >= 128 && nx < 8) {
      xs[nx] = (double)r->grid, yr[nx] = res, yj[nx] = jac, ys[nx] = lu, yv[nx] = sol;
      xlo = fmin(xlo, xs[nx]), xhi = fmax(xhi, xs[nx]);
      nx++;
    }
  }
  if (f) fclose(f);
  if (nx >= 2) {
    /* least-squares slopes of log cost against log N */
    double sl[4];
    double *ys4[4] = {yr, yj, ys, yv};
    for (int k = 0; k < 4; k++) {
      double a = 0, b = 0, c = 0, d = 0;
      for (size_t i = 0; i < nx; i++) {
        double lx = log(xs[i]), ly = log(ys4[k][i]);
        a += lx, b += ly, c += lx * lx, d += lx * ly;
      }
      double m = (double)nx;
      sl[k] = (m * d - a * b) / (m * c - a * a);
    }
    printf("# exponents (least squares, N = %g ... %g): residual %.2f, Jacobian %.2f, "
           "LU set-up %.2f, solve %.2f\n",
           xlo, xhi, sl[0], sl[1], sl[2], sl[3]);
  }
}

/* The Pareto plot of one scene's settings (all kinds but the reference). */
static void scene_pareto(const char *dir, const scene_ctx *s, size_t chosen_row, const char *note,
                         size_t rec_row) {
  size_t n = 0, chosen = SIZE_MAX, rec = SIZE_MAX;
  double t[MAX_ROWS], e[MAX_ROWS];
  const char *lab[MAX_ROWS];
  for (size_t i = 0; i < nrows; i++) {
    const row *r = &rows[i];
    if (strcmp(r->scene, s->name) != 0 || r->kind == KIND_REF || r->kind == KIND_OTHER) continue;
    if (i == chosen_row) chosen = n;
    if (i == rec_row) rec = n;
    t[n] = r->t_curve_s, e[n] = r->failed ? NAN : r->err_mu, lab[n] = r->setting;
    n++;
  }
  if (n == 0) return;
  const row *ref = &rows[s->ref_row];
  char path[1200], title[300], xl[120];
  snprintf(path, sizeof path, "%s/pareto-%s.svg", dir, s->name);
  snprintf(title, sizeof title,
           "%s (%zu-point sweep): error of mu vs time per curve; reference N %zu, inlet %g a0",
           s->name, s->npts, ref->grid, ref->inlet_a0);
  snprintf(xl, sizeof xl, "time per %zu-point curve (s), one core", s->npts);
  if (pareto_svg(path, title, xl, n, t, e, lab, chosen, note, rec) != 0)
    fprintf(stderr, "cannot write %s\n", path);
}

/* Model-rubber scenes fig05 and fig10. */
static void bench_model_scene(scene_ctx *s, const char *dir, bool quick) {
  plan p = plan_for(s, quick);
  printf("\n");
  scene_describe(s);
  printf("## reference: N = %zu, inlet %g a0 (domain [-%g, %g] a0), tolerance %g, Persson table "
         "%zu entries; settings: Persson table %zu; repeats: 3 (N <= 128), 2 (N 256), 1\n",
         p.ref_grid, p.ref_inlet, p.ref_inlet, s->sc.domain_max_a0, p.ref_tol, p.ref_table,
         DEFAULT_TABLE);
  run_reference(s, &p, NULL, 0.0, dir);
  run_study(s, &p, NULL, 0.0);
  if (strcmp(s->name, "fig05") == 0) {
    /* Persson table resolution at N 256, inlet 16 */
    size_t tabs[] = {64, 128, 1024};
    vl_point pts[64];
    for (int k = 0; k < (quick ? 1 : 3); k++) {
      setting q = {256, tabs[k], 16.0, 1e-9, VL_LINSOL_SCHUR, 0, 0, 0, quick ? 1 : 2, NULL, 0};
      char name[48];
      snprintf(name, sizeof name, "N256/in16/tol1e-09/table%zu", tabs[k]);
      row *r = run_setting(s, &q, pts, name, KIND_TABLE);
      set_errors(r, s, pts, s->ref, s->npts);
      keep_points(r, pts);
      print_row(r);
    }
  }
  inlet_extrapolation(s, &p, 0.0);
  scene_pareto(dir, s, SIZE_MAX, NULL, SIZE_MAX);
}

/* ---------------------------------------------------------------- rubber */

#define REF_PER_DECADE 2.0
static const double PER_DECADE[] = {0.5, 1.0, 1.5, 2.0};
enum { NFITS = 4 };

typedef struct {
  double per_decade;
  vl_prony prony;
  vl_prony_fit_report rep;
} prony_refit;

static prony_refit g_fits[NFITS];
static bool g_have_fits;
static double g_prony_only[NFITS]; /* error of mu from the density alone (0: not measured) */

static const vl_prony *fit_for(double per_decade) {
  for (int i = 0; i < NFITS; i++)
    if (g_fits[i].per_decade == per_decade) return &g_fits[i].prony;
  return NULL;
}

/* Refits the compound's measured master curve (the raw points stored with
 * it, at their reduced frequencies) with each density of PER_DECADE. */
static void rubber_fits(const scene_ctx *s, const char *dir) {
  vl_error err;
  const char *name = s->sc.compound;
  vl_db_compound *info = malloc(sizeof *info);
  vl_db_compound_fit fi;
  if (vl_db_compound_info(g_db, name, info, &err) != VL_OK) die(name, &err);
  if (vl_db_compound_fit_info(g_db, name, &fi, &err) != VL_OK) die(name, &err);
  if (!fi.has_fit) {
    fprintf(stderr, "bench_accuracy: compound '%s' has no measured data to refit\n", name);
    exit(1);
  }
  vl_db_measured_point *pt;
  size_t n;
  if (vl_db_compound_points(g_db, name, &pt, &n, &err) != VL_OK) die(name, &err);
  double *w = malloc(n * sizeof *w), *e1 = malloc(n * sizeof *e1), *e2 = malloc(n * sizeof *e2);
  for (size_t i = 0; i < n; i++)
    w[i] = pt[i].reduced_omega_rad_s, e1[i] = pt[i].storage_pa, e2[i] = pt[i].loss_pa;
  vl_prony_weights wt =
      strcmp(fi.weights, "modulus") == 0 ? VL_PRONY_WEIGHTS_MODULUS : VL_PRONY_WEIGHTS_RELATIVE;
  printf("## %s: %zu measured points (%zu isotherms, %s), master curve at %g C over "
         "%.3g ... %.3g rad/s (%.1f decades); stored: %g terms per decade, %zu terms, "
         "E' rms %.2f %%, E'' rms %.2f %%\n",
         name, n, fi.n_isotherms, fi.input_kind, info->tref_c, fi.omega_min_rad_s,
         fi.omega_max_rad_s, log10(fi.omega_max_rad_s / fi.omega_min_rad_s), fi.terms_per_decade,
         info->prony.n_terms, 100 * fi.rms_rel_storage, 100 * fi.rms_rel_loss);
  printf("## Prony refits of the raw points (vl_prony_fit, %s weights, nu %g):\n",
         vl_prony_weights_name(wt), info->prony.nu);
  printf("%10s %6s %6s %11s %11s %10s %10s %10s %10s\n", "per_decade", "grid", "terms", "Einf_Pa",
         "E0_Pa", "E'_rms_%", "E'_max_%", "E''_rms_%", "E''_max_%");
  FILE *f = open_csv(dir, "prony_fits.csv",
                     "compound,per_decade,grid,terms,e_inf_pa,e0_pa,storage_rms_rel,"
                     "storage_max_rel,loss_rms_rel,loss_max_rel\n");
  for (int k = 0; k < NFITS; k++) {
    prony_refit *p = &g_fits[k];
    p->per_decade = PER_DECADE[k];
    if (vl_prony_fit(n, w, e1, e2, p->per_decade, wt, info->prony.nu, &p->prony, &p->rep, &err) !=
        VL_OK)
      die("vl_prony_fit", &err);
    const vl_prony_fit_report *r = &p->rep;
    printf("%10g %6zu %6zu %11.4g %11.4g %10.2f %10.2f %10.2f %10.2f\n", p->per_decade, r->n_grid,
           r->n_terms, p->prony.e_inf_pa, vl_prony_e0(&p->prony), 100 * r->rms_rel_storage,
           100 * r->max_rel_storage, 100 * r->rms_rel_loss, 100 * r->max_rel_loss);
    if (f)
      fprintf(f, "%s,%g,%zu,%zu,%.9e,%.9e,%.6e,%.6e,%.6e,%.6e\n", name, p->per_decade, r->n_grid,
              r->n_terms, p->prony.e_inf_pa, vl_prony_e0(&p->prony), r->rms_rel_storage,
              r->max_rel_storage, r->rms_rel_loss, r->max_rel_loss);
  }
  if (f) fclose(f);
  /* the refit at the stored density must be the stored series */
  const vl_prony *same = fit_for(fi.terms_per_decade);
  if (same) {
    double d = fabs(same->e_inf_pa / info->prony.e_inf_pa - 1);
    if (same->n_terms == info->prony.n_terms)
      for (size_t i = 0; i < same->n_terms; i++)
        d = fmax(d, fmax(fabs(same->tau_s[i] / info->prony.tau_s[i] - 1),
                         fabs(same->A[i] - info->prony.A[i]) / fmax(info->prony.A[i], 1e-300)));
    else
      d = INFINITY;
    printf("# the refit at %g per decade %s the stored series (largest relative difference of "
           "Einf, tau_i, A_i: %.1e)\n",
           fi.terms_per_decade, d < 1e-6 ? "reproduces" : "DIFFERS FROM", d);
  }
  g_have_fits = true;
  free(w), free(e1), free(e2), free(pt), free(info);
  vl_db_compound_fit_free(&fi);
}

/* The row of scene s at (N, X, tol) and Prony density d (0: the scene's
 * compound as stored; rubber: 2 per decade is the study's density), run
 * now if it is not there yet. */
static const row *ensure_row(scene_ctx *s, size_t N, double X, double tol, double d) {
  row_kind kind = d == 0.0 || d == REF_PER_DECADE ? KIND_STUDY : KIND_PRONY;
  const row *old = find_row(s->name, kind, N, X, tol, d, DEFAULT_TABLE);
  if (old) return old;
  vl_point pts[64];
  setting q = {N,
               DEFAULT_TABLE,
               X,
               tol,
               VL_LINSOL_SCHUR,
               0,
               0,
               0,
               reps_for(N, false),
               d > 0 ? fit_for(d) : NULL,
               d};
  char name[48];
  setting_label(name, sizeof name, N, X, tol);
  if (kind == KIND_PRONY) snprintf(name + strlen(name), sizeof name - strlen(name), "/p%g", d);
  row *r = run_setting(s, &q, pts, name, kind);
  set_errors(r, s, pts, s->ref, s->npts);
  keep_points(r, pts);
  print_row(r);
  return r;
}

static const row *run_prony(scene_ctx *s, size_t N, double X, double tol, double d) {
  return ensure_row(s, N, X, tol, d);
}

/* The error of mu that the Prony density alone makes: row a against the
 * 2-per-decade row b of the same grid, inlet and tolerance. */
static double prony_only_error(const row *a, const row *b) {
  const vl_point *pa = row_pts[a - rows], *pb = row_pts[b - rows];
  double e = 0;
  for (size_t i = 0; i < a->points; i++)
    if (pa[i].converged && pb[i].converged) e = fmax(e, fabs(pa[i].mu - pb[i].mu) / fabs(pb[i].mu));
  return e;
}

static void bench_rubber(scene_ctx *s, const char *dir, bool quick) {
  plan p = plan_for(s, quick);
  printf("\n");
  scene_describe(s);
  rubber_fits(s, dir);
  printf("## reference: %g Prony terms per decade, N = %zu, inlet %g a0 (domain [-%g, %g] a0), "
         "tolerance %g, Persson table %zu entries\n",
         REF_PER_DECADE, p.ref_grid, p.ref_inlet, p.ref_inlet, s->sc.domain_max_a0, p.ref_tol,
         p.ref_table);
  run_reference(s, &p, fit_for(REF_PER_DECADE), REF_PER_DECADE, dir);
  run_study(s, &p, fit_for(REF_PER_DECADE), REF_PER_DECADE);
  /* Prony density on a fine grid (the defaults section adds it at the
   * recommended setting) */
  size_t N = quick ? 128 : 512;
  double X = quick ? 16 : 24;
  for (int k = 0; k < NFITS; k++)
    run_prony(s, N, X, 1e-9, PER_DECADE[k]);
  const row *b = run_prony(s, N, X, 1e-9, REF_PER_DECADE);
  printf("# error of mu from the Prony density alone (against %g per decade at N%zu/in%g):",
         REF_PER_DECADE, N, X);
  for (int k = 0; k < NFITS - 1; k++) {
    g_prony_only[k] = prony_only_error(run_prony(s, N, X, 1e-9, PER_DECADE[k]), b);
    printf(" %g/decade %.2e;", PER_DECADE[k], g_prony_only[k]);
  }
  printf("\n");
  inlet_extrapolation(s, &p, REF_PER_DECADE);
  scene_pareto(dir, s, SIZE_MAX, NULL, SIZE_MAX);
}

/* ---------------------------------------------------------------- linsol */

static void bench_linsol(scene_ctx *s, bool quick) {
  printf("\n## linear solvers: fig05, inlet %g, tolerance 1e-9, 7 points v0 eta = 1e-8 ... 1e-5 "
         "(N 512: 3 points, 1e-8 ... 1e-7) of the 25-point sweep\n"
         "#   schur: Reynolds block eliminated, LAPACK LU of the (N+1)^2 complement (default)\n"
         "#   lapack: LAPACK LU of the full (2N+1)^2 Jacobian; sundials: SUNLinSol_Dense\n",
         COST_INLET);
  print_header();
  vl_point pts[64];
  size_t grids[] = {256, 512};
  const vl_linear_solver kinds[] = {VL_LINSOL_SCHUR, VL_LINSOL_LAPACK, VL_LINSOL_SUNDIALS};
  for (int g = 0; g < (quick ? 1 : 2); g++) {
    double t[3] = {0, 0, 0};
    for (int ls = 0; ls < 3; ls++) {
      if (g == 1 && ls == 2) continue; /* SUNDIALS at N 512: ~1.5 s per LU */
      setting q = {grids[g], DEFAULT_TABLE,       COST_INLET,      1e-9, kinds[ls], 25,
                   8,        (size_t)(g ? 3 : 7), ls == 2 ? 1 : 3, NULL, 0};
      char name[48];
      snprintf(name, sizeof name, "N%zu/in%g/tol1e-09/%dpt", grids[g], COST_INLET, g ? 3 : 7);
      row *r = run_setting(s, &q, pts, name, KIND_OTHER);
      snprintf(r->scene, sizeof r->scene, "linsol");
      print_row(r);
      double lu = 1e3 * r->timing.t_setup_s / (double)r->timing.setups;
      printf("#   %s: set-up (LU) %.2f ms per call, solve %.3f ms per call, %ld fallbacks\n",
             r->linsol, lu, 1e3 * r->timing.t_solve_s / (double)r->timing.solves,
             r->timing.linsol_fallbacks);
      t[ls] = r->t_point_ms;
    }
    printf("# N = %zu: time per point lapack / schur = %.1f", grids[g], t[1] / t[0]);
    if (t[2] > 0) printf(", sundials / lapack = %.1f", t[2] / t[1]);
    printf("\n");
  }
}

/* ---------------------------------------------------------------- defaults */

/* The recommendation; the fallback (used when the defaults section does not
 * run, e.g. --only targets) is the result of the last full run, see
 * bench/README.md. */
typedef struct {
  bool found; /* from this run */
  size_t grid;
  double inlet_a0, tol, per_decade;
} recommendation;
static recommendation g_rec = {false, 768, 24.0, 1e-3, 1.5};

static double g_accuracy = 1e-2; /* --accuracy */
#define TIME_NOISE 0.10          /* settings closer in cost than this count as equally cheap */

static bool meets(const row *r) {
  return r && r->failed == 0 && r->compared > 0 && r->err_mu <= g_accuracy;
}

/* Is candidate a (cost ca) preferable to b (cost cb)? Cheaper wins; within
 * the timing noise the tighter tolerance, then the smaller error, wins. */
static bool preferable(double ca, double ta, double ea, double cb, double tb, double eb) {
  if (ca < cb * (1 - TIME_NOISE)) return true;
  if (cb < ca * (1 - TIME_NOISE)) return false;
  if (ta != tb) return ta < tb;
  return ea < eb;
}

static const scene_ctx *g_scenes[3] = {&g_fig05, &g_fig10, &g_rubber};

static double scene_per_decade(const scene_ctx *s) {
  return strcmp(s->name, "rubber") == 0 ? REF_PER_DECADE : 0.0;
}

static const row *study_row(const scene_ctx *s, size_t N, double X, double tol) {
  return find_row(s->name, KIND_STUDY, N, X, tol, scene_per_decade(s), DEFAULT_TABLE);
}

/* One knob's row r against base; the time ratio is taken against the base
 * setting at r's tolerance where that was run (grid and inlet were studied
 * at 1e-9 only). */
static void print_knob(const scene_ctx *s, const char *knob, const row *r, const row *base) {
  if (!r) return;
  if (r->tolerance != base->tolerance && strcmp(knob, "tolerance") != 0) {
    const row *b = find_row(s->name, KIND_STUDY, base->grid, base->inlet_a0, r->tolerance,
                            base->per_decade, DEFAULT_TABLE);
    if (b) base = b;
  }
  printf("#   %-10s %-28s err_mu %8.2e (%-16s) %8.3f s/curve = x%.2f of %s\n", knob, r->setting,
         r->err_mu,
         r->failed  ? "points failed"
         : meets(r) ? "meets the bound"
                    : "misses the bound",
         r->t_curve_s, r->t_curve_s / base->t_curve_s, base->setting);
}

static const size_t KNOB_GRIDS[] = {64, 128, 256, 512, 768, 1024};
static const double KNOB_INLETS[] = {3, 5, 8, 16, 24, 32};

/* The study row at (N, X, tol), else at (N, X, 1e-9): grid and inlet were
 * studied at the reference tolerance. */
static const row *study_row_or_tight(const scene_ctx *s, size_t N, double X, double tol) {
  const row *r = study_row(s, N, X, tol);
  return r ? r : study_row(s, N, X, 1e-9);
}

/* What each knob buys around the recommended setting of scene s. */
static void knob_table(const scene_ctx *s, const row *base) {
  printf("# %s around %s (err_mu %.2e, %.3f s/curve):\n", s->name, base->setting, base->err_mu,
         base->t_curve_s);
  size_t N = base->grid;
  double X = base->inlet_a0, tol = base->tolerance;
  for (int k = 0; k < 6; k++)
    if (KNOB_GRIDS[k] != N)
      print_knob(s, "grid", study_row_or_tight(s, KNOB_GRIDS[k], X, tol), base);
  for (int k = 0; k < 6; k++)
    if (KNOB_INLETS[k] != X)
      print_knob(s, "inlet", study_row_or_tight(s, N, KNOB_INLETS[k], tol), base);
  double tols[] = {1e-3, 1e-6, 1e-9};
  for (int k = 0; k < 3; k++)
    if (tols[k] != tol) print_knob(s, "tolerance", study_row(s, N, X, tols[k]), base);
  if (strcmp(s->name, "rubber") == 0)
    for (int k = 0; k < NFITS - 1; k++)
      print_knob(s, "prony", find_row(s->name, KIND_PRONY, N, X, tol, PER_DECADE[k], DEFAULT_TABLE),
                 base);
}

/* Sum of the scenes' times per curve at (N, X, tol), running what is
 * missing; NAN unless every scene meets 1 % there. */
static double common_cost(size_t N, double X, double tol, double *worst_err) {
  double cost = 0, err = 0;
  for (int k = 0; k < 3; k++) {
    scene_ctx *s = (scene_ctx *)g_scenes[k];
    if (!s->have_ref) continue;
    const row *o = ensure_row(s, N, X, tol, scene_per_decade(s));
    if (!meets(o)) return NAN;
    cost += o->t_curve_s, err = fmax(err, o->err_mu);
  }
  if (worst_err) *worst_err = err;
  return cost;
}

static void bench_defaults(const char *dir) {
  printf("\n## defaults: the cheapest setting with mu within %g %% of the reference at every point "
         "of the sweep (no failed point);\n## settings within %.0f %% in time count as equally "
         "cheap: then the tighter tolerance, then the smaller error\n",
         100 * g_accuracy, 100 * TIME_NOISE);
  FILE *f = open_csv(dir, "defaults.csv",
                     "what,scene,setting,grid,inlet_a0,tolerance,prony_per_decade,err_mu,"
                     "worst_v0_eta,err_component_max,err_u_min,s_per_curve,ms_per_point\n");
  printf("%-7s %-26s %-28s %9s %9s %9s %9s %9s %9s\n", "scene", "reference",
         "cheapest within bound", "err_mu", "at_v0eta", "err_comp", "err_umin", "s/curve",
         "ms/point");
  size_t best_row[3] = {SIZE_MAX, SIZE_MAX, SIZE_MAX};
  int nscenes = 0;
  for (int k = 0; k < 3; k++) {
    const scene_ctx *s = g_scenes[k];
    if (!s->have_ref) continue;
    nscenes++;
    size_t b = SIZE_MAX;
    for (size_t i = 0; i < nrows; i++) {
      const row *r = &rows[i];
      if (strcmp(r->scene, s->name) != 0 || r->kind == KIND_REF || r->kind == KIND_OTHER ||
          !meets(r))
        continue;
      if (b == SIZE_MAX || preferable(r->t_curve_s, r->tolerance, r->err_mu, rows[b].t_curve_s,
                                      rows[b].tolerance, rows[b].err_mu))
        b = i;
    }
    best_row[k] = b;
    const row *ref = &rows[s->ref_row];
    char refs[64];
    snprintf(refs, sizeof refs, "N%zu/in%g/tol%.0e%s", ref->grid, ref->inlet_a0, ref->tolerance,
             strcmp(s->name, "rubber") == 0 ? "/p2" : "");
    if (b == SIZE_MAX) {
      printf("%-7s %-26s %-28s\n", s->name, refs, "(none)");
      continue;
    }
    const row *r = &rows[b];
    double ec = fmax(fmax(r->err_rc, r->err_rf), fmax(r->err_sc, r->err_sf));
    printf("%-7s %-26s %-28s %9.2e %9.1e %9.2e %9.2e %9.3f %9.2f\n", s->name, refs, r->setting,
           r->err_mu, r->worst_v0_eta, ec, r->err_umin, r->t_curve_s, r->t_point_ms);
    if (f)
      fprintf(f, "scene-cheapest,%s,%s,%zu,%g,%g,%g,%.4e,%.3e,%.4e,%.4e,%.4f,%.3f\n", s->name,
              r->setting, r->grid, r->inlet_a0, r->tolerance, r->per_decade, r->err_mu,
              r->worst_v0_eta, ec, r->err_umin, r->t_curve_s, r->t_point_ms);
  }
  const scene_ctx *first = NULL;
  for (int k = 0; k < 3 && !first; k++)
    if (g_scenes[k]->have_ref) first = g_scenes[k];
  if (!first) {
    if (f) fclose(f);
    return;
  }
  /* 1. grid and inlet: the cheapest (N, X) at the reference tolerance that
   * meets 1 % in every scene (summed time per curve) */
  size_t best = SIZE_MAX;
  double best_cost = 0, best_err = 0;
  for (size_t i = 0; i < nrows; i++) {
    const row *r = &rows[i];
    if (strcmp(r->scene, first->name) != 0 || r->kind != KIND_STUDY || r->tolerance != 1e-9)
      continue;
    double cost = 0, err = 0;
    bool ok = true;
    for (int k = 0; k < 3 && ok; k++) {
      const scene_ctx *s = g_scenes[k];
      if (!s->have_ref) continue;
      const row *o = study_row(s, r->grid, r->inlet_a0, r->tolerance);
      ok = meets(o);
      if (ok) cost += o->t_curve_s, err = fmax(err, o->err_mu);
    }
    if (ok && (best == SIZE_MAX ||
               preferable(cost, r->tolerance, err, best_cost, rows[best].tolerance, best_err)))
      best = i, best_cost = cost, best_err = err;
  }
  if (best == SIZE_MAX) {
    printf("# no studied setting meets %g %% in all %d scenes; the targets use the fallback "
           "N %zu, inlet %g, tol %g\n",
           100 * g_accuracy, nscenes, g_rec.grid, g_rec.inlet_a0, g_rec.tol);
    if (f) fclose(f);
    return;
  }
  const row *rb = &rows[best];
  g_rec.found = true, g_rec.grid = rb->grid, g_rec.inlet_a0 = rb->inlet_a0;
  g_rec.tol = 1e-9, g_rec.per_decade = REF_PER_DECADE;
  printf("# 1. grid and inlet (tolerance 1e-9, summed time of the %d curves): N%zu/in%g, %.3f s, "
         "worst err_mu %.2e\n",
         nscenes, g_rec.grid, g_rec.inlet_a0, best_cost, best_err);
  /* 2. tolerance there: the loosest that still meets 1 % everywhere and
   * saves more than the timing noise */
  printf("# 2. tolerance at N%zu/in%g (run where missing):\n", g_rec.grid, g_rec.inlet_a0);
  print_header();
  double loose[] = {1e-3, 1e-6};
  for (int k = 0; k < 2; k++) {
    double e = 0, c = common_cost(g_rec.grid, g_rec.inlet_a0, loose[k], &e);
    /* what the looser tolerance changes in mu itself, point by point */
    double dmu = 0;
    for (int j = 0; j < 3; j++) {
      const scene_ctx *s = g_scenes[j];
      const row *a = study_row(s, g_rec.grid, g_rec.inlet_a0, loose[k]),
                *b = study_row(s, g_rec.grid, g_rec.inlet_a0, 1e-9);
      if (!s->have_ref || !a || !b) continue;
      const vl_point *pa = row_pts[a - rows], *pb = row_pts[b - rows];
      for (size_t i = 0; i < a->points; i++)
        if (pa[i].converged && pb[i].converged)
          dmu = fmax(dmu, fabs(pa[i].mu - pb[i].mu) / fabs(pb[i].mu));
    }
    printf("#    tol %.0e: %s, summed %.3f s (tol 1e-9: %.3f s); mu differs from tol 1e-9 by "
           "%.1e at most\n",
           loose[k], isnan(c) ? "misses the bound somewhere" : "meets the bound everywhere", c,
           best_cost, dmu);
    if (!isnan(c) && c < (1 - TIME_NOISE) * best_cost) {
      g_rec.tol = loose[k];
      break;
    }
  }
  /* 3. the Prony density: the fewest terms per decade that still meet 1 %
   * there; a density whose error alone (rubber section) exceeds 1 % is not
   * tried */
  if (g_rubber.have_ref && g_have_fits) {
    printf("# 3. Prony terms per decade at N%zu/in%g/tol%.0e:\n", g_rec.grid, g_rec.inlet_a0,
           g_rec.tol);
    print_header();
    for (int k = 0; k < NFITS; k++) {
      if (PER_DECADE[k] != REF_PER_DECADE && g_prony_only[k] > g_accuracy) {
        printf("#    %g per decade: not tried (its error alone is %.1f %%)\n", PER_DECADE[k],
               100 * g_prony_only[k]);
        continue;
      }
      const row *r = ensure_row(&g_rubber, g_rec.grid, g_rec.inlet_a0, g_rec.tol, PER_DECADE[k]);
      if (meets(r)) {
        g_rec.per_decade = PER_DECADE[k];
        break;
      }
    }
  }
  printf("\n## recommended defaults (the cheapest setting meeting %g %% in %s%s%s):\n",
         100 * g_accuracy, "fig05", g_fig10.have_ref ? ", fig10" : "",
         g_rubber.have_ref ? ", rubber" : "");
  printf("##   grid N = %zu, domain [-%g, x_max of the case] a0, tolerance %g, Prony terms per "
         "decade %g\n\n",
         g_rec.grid, g_rec.inlet_a0, g_rec.tol, g_rec.per_decade);
  printf("| scene | reference | recommended setting | err mu | at v0 eta (Pa m) | err components "
         "(of mu) | err u_min | s per curve | ms per point |\n");
  printf("|---|---|---|---|---|---|---|---|---|\n");
  double total = 0;
  size_t rec_row[3] = {SIZE_MAX, SIZE_MAX, SIZE_MAX};
  for (int k = 0; k < 3; k++) {
    scene_ctx *s = (scene_ctx *)g_scenes[k];
    if (!s->have_ref) continue;
    bool rub = strcmp(s->name, "rubber") == 0;
    const row *r =
        ensure_row(s, g_rec.grid, g_rec.inlet_a0, g_rec.tol, rub ? g_rec.per_decade : 0.0);
    rec_row[k] = (size_t)(r - rows);
    const row *ref = &rows[s->ref_row];
    double ec = fmax(fmax(r->err_rc, r->err_rf), fmax(r->err_sc, r->err_sf));
    printf(
        "| %s (%zu points) | N %zu, inlet %g a0, tol %.0e%s | %s%s | %.2e | %.1e | %.2e | %.2e | "
        "%.3f | %.1f |\n",
        s->name, s->npts, ref->grid, ref->inlet_a0, ref->tolerance, rub ? ", 2/decade" : "",
        r->setting, r->failed ? " (FAILED POINTS)" : "", r->err_mu, r->worst_v0_eta, ec,
        r->err_umin, r->t_curve_s, r->t_point_ms);
    total += r->t_curve_s;
    if (f)
      fprintf(f, "recommended,%s,%s,%zu,%g,%g,%g,%.4e,%.3e,%.4e,%.4e,%.4f,%.3f\n", s->name,
              r->setting, r->grid, r->inlet_a0, r->tolerance, r->per_decade, r->err_mu,
              r->worst_v0_eta, ec, r->err_umin, r->t_curve_s, r->t_point_ms);
  }
  printf("\n# total %.2f s for the %d curves at the recommended setting\n", total, nscenes);
  printf("\n## what each knob buys (one knob changed from the recommended setting; error of mu "
         "against the reference, time relative)\n");
  for (int k = 0; k < 3; k++) {
    const scene_ctx *s = g_scenes[k];
    if (!s->have_ref) continue;
    const row *base = study_row(s, g_rec.grid, g_rec.inlet_a0, g_rec.tol);
    if (base) knob_table(s, base);
  }
  if (f) fclose(f);
  /* Pareto plots, the scene's cheapest setting within 1 % ringed */
  for (int k = 0; k < 3; k++)
    if (g_scenes[k]->have_ref)
      scene_pareto(dir, g_scenes[k], best_row[k],
                   best_row[k] == SIZE_MAX ? NULL : "the scene's cheapest within the bound",
                   rec_row[k]);
}

/* ---------------------------------------------------------------- targets */

static void run_target(scene_ctx *s, size_t N, double X, double tol, const char *what) {
  vl_point pts[64];
  /* median of 3 repeats; 1 above N 512 (a curve takes tens of seconds) */
  setting q = {N, DEFAULT_TABLE, X, tol, VL_LINSOL_SCHUR, 61, 0, 0, N <= 512 ? 3 : 1, NULL, 0};
  char name[48];
  snprintf(name, sizeof name, "N%zu/in%g/tol%.0e/61pt", N, X, tol);
  row *r = run_setting(s, &q, pts, name, KIND_OTHER);
  snprintf(r->scene, sizeof r->scene, "target");
  print_row(r);
  printf("# %s: 61-point curve %.2f s (target < 2 s); %.1f ms per point (target < 100 ms at "
         "N 512); %.1f Newton iterations per point; %zu failed\n",
         what, r->t_curve_s, r->t_point_ms, (double)r->iterations / 61.0, r->failed);
  const vl_contact_timing *tm = &r->timing;
  double tl = r->t_last_s; /* the counters are of the last repeat */
  printf("# split of the curve's time (last repeat, %.2f s): residual %.0f %%, Jacobian %.0f %%, "
         "LU %.0f %%, solve %.0f %%, kernel builds %.0f %%, rest %.0f %%\n",
         tl, 100 * tm->t_residual_s / tl, 100 * tm->t_jacobian_s / tl, 100 * tm->t_setup_s / tl,
         100 * tm->t_solve_s / tl, 100 * tm->t_kernel_s / tl,
         100 *
             (tl - tm->t_residual_s - tm->t_jacobian_s - tm->t_setup_s - tm->t_solve_s -
              tm->t_kernel_s) /
             tl);
  double lap = dgetrf_seconds((int)r->unknowns, N >= 1024 ? 3 : 7);
  double step = tm->t_newton_s / (double)r->iterations;
  printf("# Newton step %.2f ms vs one dgetrf(%zu) %.2f ms: ratio %.2f (target <= 2)\n", 1e3 * step,
         r->unknowns, 1e3 * lap, step / lap);
  size_t nu = r->unknowns;
  printf("# memory: dense Jacobian %zu^2 x 8 B = %.1f MB + influence matrix %zu^2 x 8 B = %.1f MB "
         "(O(N^2): about 40 N^2 bytes for the wet rough contact)\n",
         nu, 8e-6 * (double)nu * (double)nu, r->grid, 8e-6 * (double)r->grid * (double)r->grid);
}

static void bench_targets(scene_ctx *s) {
  printf("\n## targets: %s, 61 points as the case; recommended defaults %s: N %zu, domain "
         "[-%g, %g] a0, tol %g\n",
         s->file, g_rec.found ? "of this run" : "of the last full run (bench/README.md)",
         g_rec.grid, g_rec.inlet_a0, s->sc.domain_max_a0, g_rec.tol);
  print_header();
  run_target(s, 512, g_rec.inlet_a0, g_rec.tol, "N 512 (the issue's grid), recommended domain");
  if (g_rec.grid != 512)
    run_target(s, g_rec.grid, g_rec.inlet_a0, g_rec.tol, "recommended defaults");
}

/* ---------------------------------------------------------------- main */

static void section_done(double *ts, const char *name) {
  printf("# section %s: %.0f s\n", name, now_s() - *ts);
  *ts = now_s();
}

static bool section(const char *only, const char *name) {
  size_t n = strlen(name);
  for (const char *p = only; (p = strstr(p, name)) != NULL; p += n)
    if ((p == only || p[-1] == ',') && (p[n] == 0 || p[n] == ',')) return true;
  return false;
}

int main(int argc, char **argv) {
  const char *dir = "bench-out", *only = "hunter,fig05,fig10,rubber,linsol,defaults,targets";
  const char *db = NULL;
  bool quick = false;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
      dir = argv[++i];
    else if (strcmp(argv[i], "--only") == 0 && i + 1 < argc)
      only = argv[++i];
    else if (strcmp(argv[i], "--quick") == 0)
      quick = true;
    else if (strcmp(argv[i], "--db") == 0 && i + 1 < argc)
      db = argv[++i];
    else if (strcmp(argv[i], "--cases") == 0 && i + 1 < argc)
      g_cases = argv[++i];
    else if (strcmp(argv[i], "--ref-grid") == 0 && i + 1 < argc)
      ref_grid_opt = (size_t)strtoul(argv[++i], NULL, 10);
    else if (strcmp(argv[i], "--ref-inlet") == 0 && i + 1 < argc)
      ref_inlet_opt = strtod(argv[++i], NULL);
    else if (strcmp(argv[i], "--accuracy") == 0 && i + 1 < argc)
      g_accuracy = strtod(argv[++i], NULL);
    else {
      fprintf(stderr,
              "usage: %s [--out DIR] [--only SECTIONS] [--quick] [--db PATH] [--cases DIR]\n"
              "          [--ref-grid N] [--ref-inlet X] [--accuracy FRACTION (0.01)]\n"
              "  SECTIONS: comma-separated of hunter,fig05,fig10,rubber,linsol,defaults,targets "
              "(default: all, ~12 min)\n",
              argv[0]);
      return 2;
    }
  }
  if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
    fprintf(stderr, "cannot create %s: %s\n", dir, strerror(errno));
    return 1;
  }
  machine(stdout);
  double t0 = now_s();
  bool need_db = section(only, "fig05") || section(only, "fig10") || section(only, "rubber") ||
                 section(only, "linsol") || section(only, "targets");
  if (need_db) db_open(db);
  double ts = now_s();
  if (section(only, "hunter")) bench_hunter(quick), section_done(&ts, "hunter");
  if (section(only, "fig05")) {
    bench_model_scene(scene_load(&g_fig05, "fig05.ini", 25), dir, quick);
    cost_vs_n(dir);
    section_done(&ts, "fig05");
  }
  if (section(only, "fig10")) {
    bench_model_scene(scene_load(&g_fig10, "fig10.ini", 25), dir, quick);
    section_done(&ts, "fig10");
  }
  if (section(only, "rubber")) {
    bench_rubber(scene_load(&g_rubber, "fig15.ini", 23), dir, quick);
    section_done(&ts, "rubber");
  }
  if (section(only, "linsol"))
    bench_linsol(scene_load(&g_fig05, "fig05.ini", 25), quick), section_done(&ts, "linsol");
  if (section(only, "defaults")) bench_defaults(dir), section_done(&ts, "defaults");
  if (section(only, "targets"))
    bench_targets(scene_load(&g_fig05, "fig05.ini", 25)), section_done(&ts, "targets");
  if (write_rows_csv(dir) != 0) fprintf(stderr, "cannot write %s/accuracy.csv\n", dir);
  for (size_t i = 0; i < nrows; i++)
    free(row_pts[i]);
  scene_free(&g_fig05), scene_free(&g_fig10), scene_free(&g_rubber);
  if (need_db) db_close();
  printf("\n# total %.0f s; CSV and SVG in %s\n", now_s() - t0, dir);
  machine(stdout);
  return 0;
}
