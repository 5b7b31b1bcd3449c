/* Accuracy-vs-cost benchmark of the contact solver (issue 7).
 *
 *   bench_accuracy [--out DIR] [--only SECTIONS] [--quick] [--db PATH]
 *                  [--cases DIR] [--ref-grid R] [--ref-inlet X] [--ref-growth G]
 *                  [--accuracy F]
 *
 * SECTIONS (comma-separated; default all): hunter, fig05, fig10, rubber,
 * linsol, defaults, targets.
 *   hunter   smooth dry rolling (model rubber, Einf/E0 = 10) against Hunter's
 *            exact solution (tests/oracles/hunter.c): grid 64 ... 2048, relative
 *            error of mu at De = v0 tau/a0 = 0.1, 1.3, 10 and time per point of a
 *            6-point continuation ramp in De.
 *   fig05    the scene of cases/fig05.ini (model rubber on paper-3um, eta
 *            1e-4 Pa s, Patir-Cheng, sigma_s 1 MPa), 25 points v0 eta =
 *            1e-12 ... 1 Pa m, against a reference at the finest settings we
 *            can afford (printed). A setting is the resolution r (uniform
 *            cells per a0: grid = round((X + x_max) r) on the domain
 *            [-X, x_max] a0), the inlet length X, the growth g of the graded
 *            inlet (vl_contact_config.grid_growth; 1: uniform grid), the
 *            tolerance and the Persson table size. Errors are the largest over
 *            the sweep: |mu - mu_ref|/mu_ref; each component |c - c_ref|/mu_ref
 *            (components can vanish, so they are measured in units of the
 *            total); |u_min - u_min_ref|/u_min_ref. fig05 also runs uniform
 *            grids N 64 ... 1024 at inlet 16 a0 for the cost per call of
 *            residual, Jacobian, LU set-up and solve and their exponent in N.
 *   fig10    the same for cases/fig10.ini (eta 1 Pa s).
 *   rubber   cases/fig15.ini: the shipped sbr-unfilled (a fit to measured-style
 *            DMA data) on paper-0.5um in water, smooth flow factors, 23 points
 *            v0 eta = 1e-12 ... 0.1 Pa m. The compound's raw points are read
 *            from the database and refitted with 0.5, 1, 1.5, 2 Prony terms per
 *            decade of the measured window (vl_prony_fit, the stored fit's
 *            weights); the study at 2 per decade, and the Prony density at the
 *            shipped setting, against a reference at 2 per decade.
 *            Settings of the three scenes: graded r 10, 15, 20, 30, 45 x inlet
 *            24, 48, 96, 192 a0 x growth 1.05, 1.1, 1.2, plus growth 1.02 at
 *            r 30, at tolerance 1e-9; tolerances 1e-3, 1e-6 at r 30 / 96 a0 /
 *            1.05; uniform r 10, 20, 30 x inlet 8, 16, 24 a0. References:
 *            graded, r 60, inlet 192 a0, growth 1.02, tolerance 1e-9, Persson
 *            table 2048 (mu converges like 1/X in the inlet length; a run at
 *            inlet 96 a0 at the reference's resolution gives the reference's
 *            own truncation from that law, printed).
 *   linsol   LAPACK dgetrf/dgetrs, the Schur-complement solver and
 *            SUNLinSol_Dense on a 7-point part of the fig05 sweep (uniform).
 *   defaults per scene the cheapest setting with mu within 1 % of the
 *            reference at every point, then the cheapest (r, inlet, growth) at
 *            tolerance 1e-9 that meets 1 % in all scenes, at that the loosest
 *            tolerance and then the fewest Prony terms per decade that still
 *            do (runs what is missing); and the shipped defaults of wet rough
 *            scenes (include/viscolube/scene.h) against the bound. Printed as
 *            tables for the README.
 *   targets  the speed targets: a 61-point fig05 curve (cases/fig05.ini)
 *            at the shipped defaults, uniform N 512 and the old uniform
 *            default N 768 on [-24, 1.6] a0; the Newton step against one
 *            dgetrf of the same size (2 cells + 1); the heap the contact holds.
 * Materials come from a temporary database created from the embedded
 * materials (the same seeding as a new default database), or from --db PATH.
 * Times are wall-clock, the median of repeats (each repeat resets the solver
 * to the Hertz guess and runs the whole sweep; 3 repeats when a curve takes
 * under 0.7 s, 2 under 2.5 s, else 1). Run with OPENBLAS_NUM_THREADS=1 for
 * one-core figures (scripts/bench.sh does). Writes accuracy.csv,
 * cost_vs_n.csv, prony_fits.csv, defaults.csv, reference-<scene>.csv and
 * pareto-<scene>.svg into DIR (default bench-out). The full run takes about
 * 6 minutes on a 2-core Xeon; results and the selection rule: bench/README.md. */
#include <errno.h>
#include <malloc.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "contact_private.h"
#include "contact_test.h"
#include "hunter.h"
#include "persson_internal.h"
#include "prony_fit_internal.h"
#include "rheology_internal.h"
#include "sweep_internal.h"
#include "viscolube/contact.h"
#include "viscolube/database.h"
#include "viscolube/persson.h"
#include "viscolube/prony_fit.h"
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
  KIND_REF_INLET, /* the reference at a shorter inlet (its own 1/X truncation) */
  KIND_STUDY,     /* resolution x inlet x growth x tolerance, the scene's own compound */
  KIND_COST,      /* fig05: uniform N 64 ... 1024 at inlet 16 (cost per call vs N) */
  KIND_TABLE,     /* Persson table size */
  KIND_PRONY      /* rubber: another Prony density */
} row_kind;

typedef struct {
  char scene[16], setting[64], linsol[12];
  row_kind kind;
  size_t grid;     /* uniform cells on the domain (vl_contact_config.grid) */
  size_t cells;    /* the solver's cells (vl_contact_grid: fewer when graded) */
  size_t unknowns; /* 2 cells + 1 (wet), cells + 1 (dry) */
  size_t n_table, points, failed, compared;
  double res; /* uniform cells per a0 near the contact */
  double inlet_a0, growth, tolerance;
  double per_decade; /* Prony terms per decade of the rubber's refit (0: as stored) */
  size_t prony_terms;
  long iterations;
  double err_mu, err_rc, err_rf, err_sc, err_sf, err_umin;
  double worst_v0_eta; /* where err_mu occurs (Pa m) */
  double t_point_ms, t_curve_s;
  double t_last_s; /* the last repeat's time, which `timing` splits */
  int repeats;
  size_t heap_bytes;        /* heap the contact holds after its sweep (mallinfo2) */
  vl_contact_timing timing; /* of the last repeat */
} row;

enum { MAX_ROWS = 512 };
static row rows[MAX_ROWS];
static size_t nrows;

static void print_header(void) {
  printf("%-7s %-31s %-6s %5s %5s %7s %4s %6s %9s %9s %9s %9s %9s %9s %9s %9s %9s\n", "scene",
         "setting", "linsol", "N", "cells", "tol", "fail", "iters", "err_mu", "at_v0eta", "err_Rc",
         "err_Rf", "err_Sc", "err_Sf", "err_umin", "ms/point", "s/curve");
}

static void print_row(const row *r) {
  printf("%-7s %-31s %-6s %5zu %5zu %7.0e %4zu %6ld %9.2e %9.1e %9.2e %9.2e %9.2e %9.2e %9.2e "
         "%9.2f %9.3f\n",
         r->scene, r->setting, r->linsol, r->grid, r->cells, r->tolerance, r->failed, r->iterations,
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
  r->growth = 1.0;
  return r;
}

static const char *kind_name(row_kind k) {
  return k == KIND_REF         ? "reference"
         : k == KIND_REF_INLET ? "reference-inlet"
         : k == KIND_STUDY     ? "study"
         : k == KIND_COST      ? "cost"
         : k == KIND_TABLE     ? "persson-table"
         : k == KIND_PRONY     ? "prony"
                               : "other";
}

static int write_rows_csv(const char *dir) {
  FILE *f = open_csv(dir, "accuracy.csv",
                     "scene,kind,setting,linear_solver,cells_per_a0,grid,grid_growth,cells,"
                     "unknowns,inlet_a0,tolerance,n_table,prony_per_decade,prony_terms,points,"
                     "failed,newton_iterations,err_mu,worst_v0_eta_pa_m,err_mu_Rc,err_mu_Rf,"
                     "err_mu_Sc,err_mu_Sf,err_u_min,ms_per_point,s_per_curve,repeats,"
                     "heap_bytes\n");
  if (!f) return -1;
  for (size_t i = 0; i < nrows; i++) {
    const row *r = &rows[i];
    fprintf(f,
            "%s,%s,%s,%s,%g,%zu,%g,%zu,%zu,%g,%g,%zu,%g,%zu,%zu,%zu,%ld,%.6e,%.3e,%.6e,%.6e,"
            "%.6e,%.6e,%.6e,%.4f,%.5f,%d,%zu\n",
            r->scene, kind_name(r->kind), r->setting, r->linsol, r->res, r->grid, r->growth,
            r->cells, r->unknowns, r->inlet_a0, r->tolerance, r->n_table, r->per_decade,
            r->prony_terms, r->points, r->failed, r->iterations, r->err_mu, r->worst_v0_eta,
            r->err_rc, r->err_rf, r->err_sc, r->err_sf, r->err_umin, r->t_point_ms, r->t_curve_s,
            r->repeats, r->heap_bytes);
  }
  return fclose(f);
}

/* ---------------------------------------------------------------- Pareto SVG */

/* One point's marks of a Pareto plot. */
typedef struct {
  double t, e;       /* time per curve (s), error of mu */
  const char *label; /* the setting */
  bool graded;       /* graded inlet (circle) or uniform grid (diamond) */
} pareto_point;

/* Log-log scatter of error against time; the non-dominated points (sorted
 * by time, each with a smaller error than every cheaper one) are joined and
 * drawn blue, the others orange; graded settings are circles, uniform ones
 * diamonds. Only the front and the marked points are labelled (every point
 * has its setting as a tooltip). `chosen` (may be SIZE_MAX) gets a green
 * ring, `rec` (the recommended defaults) a purple square, `shipped` (the
 * shipped defaults) a red ring. */
static int pareto_svg(const char *path, const char *title, const char *xlabel, size_t n,
                      const pareto_point *pt, size_t chosen, const char *chosen_note, size_t rec,
                      size_t shipped) {
  FILE *f = fopen(path, "w");
  if (!f) return -1;
  const double W = 1000, H = 700, L = 90, R = 320, T = 50, B = 70;
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
  for (size_t i = 0; i < n; i++) {
    if (!(pt[i].t > 0 && pt[i].e > 0)) continue;
    xmin = fmin(xmin, log10(pt[i].t)), xmax = fmax(xmax, log10(pt[i].t));
    ymin = fmin(ymin, log10(pt[i].e)), ymax = fmax(ymax, log10(pt[i].e));
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
          "fill=\"white\"/>\n<text x=\"%g\" y=\"28\" font-size=\"15\">%s</text>\n",
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
    for (size_t j = i; j > 0 && pt[ord[j]].t < pt[ord[j - 1]].t; j--) {
      size_t s = ord[j];
      ord[j] = ord[j - 1], ord[j - 1] = s;
    }
  fprintf(f, "<polyline fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"2.5\" points=\"");
  double best = INFINITY;
  for (size_t k = 0; k < n; k++) {
    size_t i = ord[k];
    if (!(pt[i].t > 0 && pt[i].e > 0) || pt[i].e >= best) continue;
    best = pt[i].e;
    front[i] = 1;
    fprintf(f, "%g,%g ", PX(pt[i].t), PY(pt[i].e));
  }
  fprintf(f, "\"/>\n");
  for (size_t i = 0; i < n; i++) {
    if (!(pt[i].t > 0 && pt[i].e > 0)) continue;
    double x = PX(pt[i].t), y = PY(pt[i].e);
    const char *fill = front[i] ? "#1f77b4" : "#ff7f0e";
    if (pt[i].graded)
      fprintf(f,
              "<circle cx=\"%g\" cy=\"%g\" r=\"4.5\" fill=\"%s\" stroke=\"black\" "
              "stroke-width=\"0.6\"><title>%s</title></circle>\n",
              x, y, fill, pt[i].label);
    else
      fprintf(f,
              "<polygon points=\"%g,%g %g,%g %g,%g %g,%g\" fill=\"%s\" stroke=\"black\" "
              "stroke-width=\"0.6\"><title>%s</title></polygon>\n",
              x, y - 6, x + 6, y, x, y + 6, x - 6, y, fill, pt[i].label);
    if (front[i] || i == chosen || i == rec || i == shipped)
      fprintf(f, "<text x=\"%g\" y=\"%g\" font-size=\"9\" fill=\"#444\">%s</text>\n", x + 7, y - 4,
              pt[i].label);
  }
  if (chosen < n && pt[chosen].t > 0 && pt[chosen].e > 0)
    fprintf(f,
            "<circle cx=\"%g\" cy=\"%g\" r=\"10\" fill=\"none\" stroke=\"#2ca02c\" "
            "stroke-width=\"2.5\"/>\n",
            PX(pt[chosen].t), PY(pt[chosen].e));
  if (rec < n && pt[rec].t > 0 && pt[rec].e > 0)
    fprintf(f,
            "<rect x=\"%g\" y=\"%g\" width=\"18\" height=\"18\" fill=\"none\" "
            "stroke=\"#9467bd\" stroke-width=\"2.5\"/>\n",
            PX(pt[rec].t) - 9, PY(pt[rec].e) - 9);
  if (shipped < n && pt[shipped].t > 0 && pt[shipped].e > 0)
    fprintf(f,
            "<circle cx=\"%g\" cy=\"%g\" r=\"14\" fill=\"none\" stroke=\"#d62728\" "
            "stroke-width=\"2.5\"/>\n",
            PX(pt[shipped].t), PY(pt[shipped].e));
  double ly = T + 14, lx = W - R + 10;
  fprintf(f, "<text x=\"%g\" y=\"%g\">blue line and marks: Pareto front</text>\n", lx, ly);
  fprintf(f, "<text x=\"%g\" y=\"%g\">orange: dominated settings</text>\n", lx, ly += 18);
  fprintf(f, "<text x=\"%g\" y=\"%g\">circles: graded inlet; diamonds: uniform grid</text>\n", lx,
          ly += 18);
  fprintf(f, "<text x=\"%g\" y=\"%g\">labels: r (cells/a0) or N / inlet (a0) / growth /</text>\n",
          lx, ly += 18);
  fprintf(f, "<text x=\"%g\" y=\"%g\">tol [/ table | /p terms per decade]; hover: all</text>\n", lx,
          ly += 16);
  if (chosen_note)
    fprintf(f, "<text x=\"%g\" y=\"%g\" fill=\"#2ca02c\">green ring: %s</text>\n", lx, ly += 18,
            chosen_note);
  if (rec < n)
    fprintf(f,
            "<text x=\"%g\" y=\"%g\" fill=\"#9467bd\">purple square: the recommended "
            "defaults</text>\n",
            lx, ly += 18);
  if (shipped < n)
    fprintf(f, "<text x=\"%g\" y=\"%g\" fill=\"#d62728\">red ring: the shipped defaults</text>\n",
            lx, ly += 18);
  fprintf(f, "<text x=\"%g\" y=\"%g\">failed points: not drawn</text>\n", lx, ly += 18);
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
      r->grid = N, r->cells = vl_contact_grid(c), r->unknowns = r->cells + 1;
      r->res = (double)N / 3.0, r->inlet_a0 = 1.5, r->tolerance = cfg.tolerance;
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
  size_t grid; /* uniform cells on the domain (vl_contact_config.grid) */
  double res;  /* uniform cells per a0 it was derived from (0: given as N) */
  size_t n_table;
  double inlet_a0, growth, tol;
  vl_linear_solver ls;
  size_t npts;            /* 0: the scene's */
  size_t first, count;    /* sub-range of the sweep that is run (count 0: all) */
  int repeats;            /* 0: by the first repeat's time (3 under 0.7 s, 2 under 2.5 s, else 1) */
  const vl_prony *rubber; /* NULL: the compound as stored */
  double per_decade;      /* the refit's density (0: as stored) */
} setting;

static bool g_quick; /* --quick: one repeat wherever repeats are automatic */

static const char *linsol_name(vl_linear_solver ls) {
  return ls == VL_LINSOL_SUNDIALS ? "sundials" : ls == VL_LINSOL_SCHUR ? "schur" : "lapack";
}

/* Uniform cells on [-X, x_max of the scene] at r cells per a0. */
static size_t grid_for(const scene_ctx *s, double r, double X) {
  return (size_t)lround((X + s->sc.domain_max_a0) * r);
}

/* Heap in use (small blocks and mmapped ones): what a contact holds. */
static size_t heap_in_use(void) {
  struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
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
  cfg.grid_growth = q->growth > 1.0 ? q->growth : 1.0;
  cfg.tolerance = q->tol, cfg.linear_solver = q->ls;
  size_t np = q->npts ? q->npts : s->npts, count = q->count ? q->count : np;
  double *v = malloc(np * sizeof *v);
  for (size_t i = 0; i < np; i++)
    v[i] = sweep_v0_eta(s, np, i) / cfg.eta_pa_s;
  size_t heap0 = heap_in_use();
  vl_contact *c;
  vl_error err;
  if (vl_contact_create(&cfg, &c, &err) != VL_OK) die("create", &err);
  double tt[8];
  int reps = q->repeats > 8 ? 8 : q->repeats;
  vl_sweep_stats st = {0};
  row *r = new_row();
  for (int k = 0; k < (reps < 1 ? 1 : reps); k++) {
    vl_contact_reset(c);
    vl_contact_timing_reset(c);
    double t0 = now_s();
    vl_sweep_run(c, count, v + q->first, NULL, out, NULL, NULL, &st, &err);
    tt[k] = now_s() - t0;
    if (reps < 1) /* automatic: cheap curves get the median of more repeats */
      reps = g_quick ? 1 : tt[0] < 0.7 ? 3 : tt[0] < 2.5 ? 2 : 1;
  }
  size_t heap1 = heap_in_use();
  vl_contact_timing_get(c, &r->timing);
  snprintf(r->scene, sizeof r->scene, "%s", s->name);
  snprintf(r->setting, sizeof r->setting, "%s", label);
  snprintf(r->linsol, sizeof r->linsol, "%s", linsol_name(q->ls));
  r->kind = kind;
  r->grid = q->grid, r->cells = vl_contact_grid(c), r->unknowns = 2 * r->cells + 1;
  r->inlet_a0 = q->inlet_a0, r->growth = cfg.grid_growth;
  r->res = q->res > 0 ? q->res : (double)q->grid / (q->inlet_a0 + sc->domain_max_a0);
  r->tolerance = q->tol, r->n_table = q->n_table, r->points = count;
  r->per_decade = q->per_decade, r->prony_terms = cfg.rubber.n_terms;
  r->failed = st.failed, r->iterations = st.newton_iterations, r->repeats = reps;
  r->heap_bytes = heap1 > heap0 ? heap1 - heap0 : 0;
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
          "# reference of %s: %s, r %g (N %zu, %zu cells), domain [-%g, %g] a0, growth %g, "
          "tol %g, Persson table %zu, %zu Prony terms\n",
          s->name, s->file, r->res, r->grid, r->cells, r->inlet_a0, s->sc.domain_max_a0, r->growth,
          r->tolerance, r->n_table, r->prony_terms);
  fprintf(f, "v0_eta_pa_m,converged,mu,mu_Rc,mu_Rf,mu_Sc,mu_Sf,u_min_m,fluid_load_fraction\n");
  for (size_t i = 0; i < s->npts; i++) {
    const vl_point *p = &s->ref[i];
    fprintf(f, "%.6e,%d,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e,%.6f\n", sweep_v0_eta(s, s->npts, i),
            p->converged ? 1 : 0, p->mu, p->mu_Rc, p->mu_Rf, p->mu_Sc, p->mu_Sf, p->u_min_m,
            p->fluid_load_fraction);
  }
  fclose(f);
}

/* "r30/in96/g1.05/tol1e-09" (N512/... when the setting was given as N). */
static void setting_label(char *buf, size_t size, const setting *q) {
  if (q->res > 0)
    snprintf(buf, size, "r%g/in%g/g%g/tol%.0e", q->res, q->inlet_a0, q->growth, q->tol);
  else
    snprintf(buf, size, "N%zu/in%g/g%g/tol%.0e", q->grid, q->inlet_a0, q->growth, q->tol);
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

/* The shipped numerics of wet rough scenes (include/viscolube/scene.h). */
#define SHIP_INLET (-VL_WET_ROUGH_DOMAIN_MIN_A0)
#define SHIP_RES ((double)VL_WET_ROUGH_GRID / (SHIP_INLET + VL_WET_DOMAIN_MAX_A0))
#define SHIP_GROWTH VL_WET_GRID_GROWTH
#define SHIP_TOL VL_WET_TOLERANCE

typedef struct {
  double ref_res, ref_inlet, ref_growth, ref_tol;
  size_t ref_table;
  /* graded study at tolerance 1e-9: res x inlets x growths ... */
  double res[6];
  size_t nres;
  double inlets[6];
  size_t ninlets;
  double growths[4];
  size_t ngrowths;
  double fine_growth, fine_res; /* ... plus fine_growth at fine_res, every inlet (0: none) */
  /* the shipped setting (full run): the looser tolerances, the Persson
   * table sizes and the Prony densities are studied there */
  double def_res, def_inlet, def_growth;
  double tols[2];
  size_t ntols;
  /* uniform grids (growth 1): u_res x u_inlets */
  double u_res[4];
  size_t nu_res;
  double u_inlets[4];
  size_t nu_inlets;
  size_t cost_grids[6], ncost; /* fig05: uniform N at COST_INLET */
} plan;

static double ref_res_opt, ref_inlet_opt, ref_growth_opt;
static const size_t DEFAULT_TABLE = 256;
#define COST_INLET 16.0 /* the inlet of the cost-vs-N runs */

static plan plan_for(bool quick) {
  plan p;
  if (quick)
    p = (plan){.ref_res = 20,
               .ref_inlet = 48,
               .ref_growth = 1.05,
               .ref_tol = 1e-9,
               .ref_table = 1024,
               .res = {10, 15},
               .nres = 2,
               .inlets = {24, 48},
               .ninlets = 2,
               .growths = {1.1},
               .ngrowths = 1,
               .def_res = 10,
               .def_inlet = 24,
               .def_growth = 1.1,
               .tols = {1e-6},
               .ntols = 1,
               .u_res = {10},
               .nu_res = 1,
               .u_inlets = {8},
               .nu_inlets = 1,
               .cost_grids = {64, 128, 256},
               .ncost = 3};
  else
    /* Reference: graded, twice the finest studied resolution, the longest
     * inlet, growth 1.02. The inlet limits it at the top of the wet sweeps
     * (mu converges like 1/X in the inlet length X: the film's pressure and
     * shear tails), which the graded inlet makes cheap to push out. */
    p = (plan){.ref_res = 60,
               .ref_inlet = 192,
               .ref_growth = 1.02,
               .ref_tol = 1e-9,
               .ref_table = 2048,
               .res = {10, 15, 20, 30, 45},
               .nres = 5,
               .inlets = {24, 48, 96, 192},
               .ninlets = 4,
               .growths = {1.05, 1.1, 1.2},
               .ngrowths = 3,
               .fine_growth = 1.02,
               .fine_res = 30,
               .def_res = SHIP_RES,
               .def_inlet = SHIP_INLET,
               .def_growth = SHIP_GROWTH,
               .tols = {1e-3, 1e-6},
               .ntols = 2,
               /* uniform grids on long inlets are too slow (N 2928 at r 30 / 96 a0) */
               .u_res = {10, 20, 30},
               .nu_res = 3,
               .u_inlets = {8, 16, 24},
               .nu_inlets = 3,
               .cost_grids = {64, 128, 256, 512, 1024},
               .ncost = 5};
  if (ref_res_opt > 0) p.ref_res = ref_res_opt;
  if (ref_inlet_opt > 0) p.ref_inlet = ref_inlet_opt;
  if (ref_growth_opt > 0) p.ref_growth = ref_growth_opt;
  return p;
}

/* Runs q on s as a row of the given kind, compares it with the reference
 * (when there is one), keeps its points and prints it. */
static row *run_row(scene_ctx *s, const setting *q, row_kind kind, const char *suffix) {
  vl_point pts[64];
  char name[64];
  setting_label(name, sizeof name, q);
  if (suffix) snprintf(name + strlen(name), sizeof name - strlen(name), "%s", suffix);
  row *r = run_setting(s, q, pts, name, kind);
  if (s->have_ref) set_errors(r, s, pts, s->ref, s->npts);
  keep_points(r, pts);
  print_row(r);
  return r;
}

/* A setting of s at r cells per a0, inlet X, growth g, tolerance tol. */
static setting at(const scene_ctx *s, double r, double X, double g, double tol,
                  const vl_prony *rubber, double per_decade) {
  return (setting){.grid = grid_for(s, r, X),
                   .res = r,
                   .n_table = DEFAULT_TABLE,
                   .inlet_a0 = X,
                   .growth = g,
                   .tol = tol,
                   .ls = VL_LINSOL_SCHUR,
                   .rubber = rubber,
                   .per_decade = per_decade};
}

static bool same(double a, double b) { return fabs(a - b) <= 1e-9 * fmax(fabs(a), fabs(b)); }

static const row *find_row(const char *scene, row_kind kind, double res, double X, double g,
                           double tol, double per_decade, size_t n_table) {
  for (size_t i = 0; i < nrows; i++) {
    const row *r = &rows[i];
    if (strcmp(r->scene, scene) == 0 && r->kind == kind && same(r->res, res) && r->inlet_a0 == X &&
        r->growth == g && r->tolerance == tol && r->per_decade == per_decade &&
        r->n_table == n_table)
      return r;
  }
  return NULL;
}

/* Runs the reference of s (once) and prints it, then the same at half its
 * inlet for the reference's own 1/X truncation. */
static void run_reference(scene_ctx *s, const plan *p, const vl_prony *rubber, double per_decade,
                          const char *dir) {
  setting q = at(s, p->ref_res, p->ref_inlet, p->ref_growth, p->ref_tol, rubber, per_decade);
  q.n_table = p->ref_table, q.repeats = 1;
  char name[64];
  snprintf(name, sizeof name, "reference r%g/in%g/g%g", p->ref_res, p->ref_inlet, p->ref_growth);
  print_header();
  row *r = run_setting(s, &q, s->ref, name, KIND_REF);
  set_errors(r, s, s->ref, s->ref, s->npts);
  r->worst_v0_eta = NAN;
  s->have_ref = true;
  s->ref_row = (size_t)(r - rows);
  keep_points(r, s->ref);
  print_row(r);
  if (r->failed)
    printf("# WARNING: the reference failed at %zu of %zu points; errors skip them\n", r->failed,
           s->npts);
  write_reference_csv(dir, s, r);
  setting h = q;
  h.inlet_a0 = 0.5 * p->ref_inlet, h.grid = grid_for(s, p->ref_res, h.inlet_a0);
  vl_point pts[64];
  snprintf(name, sizeof name, "ref. at r%g/in%g/g%g", p->ref_res, h.inlet_a0, p->ref_growth);
  row *rh = run_setting(s, &h, pts, name, KIND_REF_INLET);
  set_errors(rh, s, pts, s->ref, s->npts);
  keep_points(rh, pts);
  print_row(rh);
}

/* The reference's own inlet truncation, from mu(X) = mu_inf - c/X through
 * the reference (inlet X2) and the same setting at X1 = X2/2:
 * mu_inf - mu(X2) = (mu(X2) - mu(X1)) (1/X2) / (1/X1 - 1/X2). */
static void inlet_extrapolation(const scene_ctx *s) {
  const row *b = &rows[s->ref_row], *a = NULL;
  for (size_t i = 0; i < nrows && !a; i++)
    if (rows[i].kind == KIND_REF_INLET && strcmp(rows[i].scene, s->name) == 0) a = &rows[i];
  if (!a) return;
  const vl_point *pa = row_pts[a - rows], *pb = s->ref;
  double x1 = a->inlet_a0, x2 = b->inlet_a0, worst = 0, worst_grow = 0;
  size_t wi = 0;
  for (size_t i = 0; i < s->npts; i++) {
    if (!pa[i].converged || !pb[i].converged) continue;
    double d = (pb[i].mu - pa[i].mu) * (1.0 / x2) / (1.0 / x1 - 1.0 / x2) / fabs(pb[i].mu);
    if (fabs(d) > fabs(worst)) worst = d, wi = i;
    worst_grow = fmax(worst_grow, fabs(pb[i].mu - pa[i].mu) / fabs(pb[i].mu));
  }
  printf("# inlet truncation of the reference itself, from mu(X) = mu_inf - c/X through its runs "
         "at inlets %g and %g a0: mu_inf/mu_ref - 1 = %+.2f %% at worst (v0 eta = %.2g Pa m); "
         "|mu(%g) - mu(%g)|/mu at most %.2f %%\n",
         x1, x2, 100 * worst, sweep_v0_eta(s, s->npts, wi), x2, x1, 100 * worst_grow);
}

/* Resolution x inlet x growth x tolerance of s, graded and uniform, against
 * its reference. */
static void run_study(scene_ctx *s, const plan *p, const vl_prony *rubber, double per_decade) {
  for (size_t a = 0; a < p->nres; a++)
    for (size_t b = 0; b < p->ninlets; b++) {
      for (size_t g = 0; g < p->ngrowths; g++) {
        setting q = at(s, p->res[a], p->inlets[b], p->growths[g], 1e-9, rubber, per_decade);
        run_row(s, &q, KIND_STUDY, NULL);
      }
      if (p->fine_growth > 0 && p->res[a] == p->fine_res) {
        setting q = at(s, p->res[a], p->inlets[b], p->fine_growth, 1e-9, rubber, per_decade);
        run_row(s, &q, KIND_STUDY, NULL);
      }
    }
  for (size_t k = 0; k < p->ntols; k++) {
    setting q = at(s, p->def_res, p->def_inlet, p->def_growth, p->tols[k], rubber, per_decade);
    run_row(s, &q, KIND_STUDY, NULL);
  }
  for (size_t a = 0; a < p->nu_res; a++)
    for (size_t b = 0; b < p->nu_inlets; b++) {
      setting q = at(s, p->u_res[a], p->u_inlets[b], 1.0, 1e-9, rubber, per_decade);
      run_row(s, &q, KIND_STUDY, NULL);
    }
}

static void cost_vs_n(const char *dir) {
  printf("\n## cost per call vs N (fig05, uniform grids at inlet %g, tol 1e-9, Schur solver: LU "
         "of the (N+1)^2 complement; unknowns 2N+1)\n",
         COST_INLET);
  printf("%6s %8s %12s %12s %12s %12s %12s %14s %12s %8s\n", "N", "unknowns", "residual_ms",
         "jacobian_ms", "LU_setup_ms", "solve_ms", "kernel_ms", "newton_step_ms", "dgetrf_ms",
         "step/LU");
  FILE *f = open_csv(dir, "cost_vs_n.csv",
                     "grid,unknowns,residual_ms,jacobian_ms,lu_setup_ms,solve_ms,kernel_ms,"
                     "newton_step_ms,dgetrf_of_2n1_ms,step_over_dgetrf\n");
  /* the rows, by N */
  size_t idx[MAX_ROWS], m = 0;
  for (size_t i = 0; i < nrows; i++) {
    const row *r = &rows[i];
    if (strcmp(r->scene, "fig05") != 0 || (r->kind != KIND_STUDY && r->kind != KIND_COST) ||
        r->inlet_a0 != COST_INLET || r->growth != 1.0 || r->tolerance != 1e-9 ||
        r->n_table != DEFAULT_TABLE)
      continue;
    size_t j = m++;
    for (; j > 0 && rows[idx[j - 1]].grid > r->grid; j--)
      idx[j] = idx[j - 1];
    idx[j] = i;
  }
  double xs[16], yr[16], yj[16], ys[16], yv[16], xlo = INFINITY, xhi = 0;
  size_t nx = 0;
  for (size_t k = 0; k < m; k++) {
    const row *r = &rows[idx[k]];
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
    if (r->grid >= 128 && nx < 16) {
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
      double mm = (double)nx;
      sl[k] = (mm * d - a * b) / (mm * c - a * a);
    }
    printf("# exponents (least squares, N = %g ... %g): residual %.2f, Jacobian %.2f, "
           "LU set-up %.2f, solve %.2f\n",
           xlo, xhi, sl[0], sl[1], sl[2], sl[3]);
  }
}

/* The Pareto plot of one scene's settings (all kinds but the references). */
static void scene_pareto(const char *dir, const scene_ctx *s, size_t chosen_row, const char *note,
                         size_t rec_row, size_t shipped_row) {
  size_t n = 0, chosen = SIZE_MAX, rec = SIZE_MAX, shipped = SIZE_MAX;
  static pareto_point pt[MAX_ROWS];
  for (size_t i = 0; i < nrows; i++) {
    const row *r = &rows[i];
    if (strcmp(r->scene, s->name) != 0 || r->kind == KIND_REF || r->kind == KIND_REF_INLET ||
        r->kind == KIND_OTHER)
      continue;
    if (i == chosen_row) chosen = n;
    if (i == rec_row) rec = n;
    if (i == shipped_row) shipped = n;
    pt[n] = (pareto_point){r->t_curve_s, r->failed ? NAN : r->err_mu, r->setting, r->growth > 1};
    n++;
  }
  if (n == 0) return;
  const row *ref = &rows[s->ref_row];
  char path[1200], title[300], xl[120];
  snprintf(path, sizeof path, "%s/pareto-%s.svg", dir, s->name);
  snprintf(title, sizeof title,
           "%s (%zu-point sweep): error of mu vs time per curve; reference r %g, inlet %g a0, "
           "growth %g",
           s->name, s->npts, ref->res, ref->inlet_a0, ref->growth);
  snprintf(xl, sizeof xl, "time per %zu-point curve (s), one core", s->npts);
  if (pareto_svg(path, title, xl, n, pt, chosen, note, rec, shipped) != 0)
    fprintf(stderr, "cannot write %s\n", path);
}

static void describe_plan(const scene_ctx *s, const plan *p) {
  printf("## reference: graded, r %g cells per a0 (N %zu), inlet %g a0 (domain [-%g, %g] a0), "
         "growth %g, tolerance %g, Persson table %zu\n",
         p->ref_res, grid_for(s, p->ref_res, p->ref_inlet), p->ref_inlet, p->ref_inlet,
         s->sc.domain_max_a0, p->ref_growth, p->ref_tol, p->ref_table);
  printf("## settings (Persson table %zu, tol 1e-9): graded r", DEFAULT_TABLE);
  for (size_t k = 0; k < p->nres; k++)
    printf(" %g", p->res[k]);
  printf(" x inlet");
  for (size_t k = 0; k < p->ninlets; k++)
    printf(" %g", p->inlets[k]);
  printf(" x growth");
  for (size_t k = 0; k < p->ngrowths; k++)
    printf(" %g", p->growths[k]);
  if (p->fine_growth > 0) printf(", growth %g at r %g", p->fine_growth, p->fine_res);
  printf("; tol");
  for (size_t k = 0; k < p->ntols; k++)
    printf(" %.0e", p->tols[k]);
  printf(" at r%g/in%g/g%g; uniform r", p->def_res, p->def_inlet, p->def_growth);
  for (size_t k = 0; k < p->nu_res; k++)
    printf(" %g", p->u_res[k]);
  printf(" x inlet");
  for (size_t k = 0; k < p->nu_inlets; k++)
    printf(" %g", p->u_inlets[k]);
  printf("; repeats: 3 when a curve takes < 0.7 s, 2 < 2.5 s, else 1\n");
}

/* Model-rubber scenes fig05 and fig10. */
static void bench_model_scene(scene_ctx *s, const char *dir, bool quick) {
  plan p = plan_for(quick);
  printf("\n");
  scene_describe(s);
  describe_plan(s, &p);
  run_reference(s, &p, NULL, 0.0, dir);
  inlet_extrapolation(s);
  run_study(s, &p, NULL, 0.0);
  if (strcmp(s->name, "fig05") == 0) {
    /* Persson table resolution at the shipped setting */
    size_t tabs[] = {64, 128, 1024};
    for (int k = 0; k < (quick ? 1 : 3); k++) {
      setting q = at(s, p.def_res, p.def_inlet, p.def_growth, 1e-9, NULL, 0.0);
      q.n_table = tabs[k];
      char sfx[24];
      snprintf(sfx, sizeof sfx, "/table%zu", tabs[k]);
      run_row(s, &q, KIND_TABLE, sfx);
    }
    /* uniform grids N 64 ... 1024 at inlet 16: the cost per call vs N */
    for (size_t k = 0; k < p.ncost; k++) {
      setting q = at(s, 0, COST_INLET, 1.0, 1e-9, NULL, 0.0);
      q.grid = p.cost_grids[k], q.res = 0;
      run_row(s, &q, KIND_COST, NULL);
    }
  }
  scene_pareto(dir, s, SIZE_MAX, NULL, SIZE_MAX, SIZE_MAX);
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

/* The row of scene s at (r, X, g, tol) and Prony density d (0: the scene's
 * compound as stored; rubber: 2 per decade is the study's density), run
 * now if it is not there yet. */
static const row *ensure_row(scene_ctx *s, double r, double X, double g, double tol, double d) {
  row_kind kind = d == 0.0 || d == REF_PER_DECADE ? KIND_STUDY : KIND_PRONY;
  const row *old = find_row(s->name, kind, r, X, g, tol, d, DEFAULT_TABLE);
  if (old) return old;
  setting q = at(s, r, X, g, tol, d > 0 ? fit_for(d) : NULL, d);
  char sfx[16] = "";
  if (kind == KIND_PRONY) snprintf(sfx, sizeof sfx, "/p%g", d);
  return run_row(s, &q, kind, sfx);
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
  plan p = plan_for(quick);
  printf("\n");
  scene_describe(s);
  rubber_fits(s, dir);
  printf("## the rubber at %g Prony terms per decade (the stored density)\n", REF_PER_DECADE);
  describe_plan(s, &p);
  run_reference(s, &p, fit_for(REF_PER_DECADE), REF_PER_DECADE, dir);
  inlet_extrapolation(s);
  run_study(s, &p, fit_for(REF_PER_DECADE), REF_PER_DECADE);
  /* Prony density at the shipped setting (tolerance 1e-9) */
  double r = p.def_res, X = p.def_inlet, g = p.def_growth;
  const row *b = ensure_row(s, r, X, g, 1e-9, REF_PER_DECADE);
  for (int k = 0; k < NFITS - 1; k++)
    g_prony_only[k] = prony_only_error(ensure_row(s, r, X, g, 1e-9, PER_DECADE[k]), b);
  printf("# error of mu from the Prony density alone (against %g per decade at r%g/in%g/g%g):",
         REF_PER_DECADE, r, X, g);
  for (int k = 0; k < NFITS - 1; k++)
    printf(" %g/decade %.2e;", PER_DECADE[k], g_prony_only[k]);
  printf("\n");
  scene_pareto(dir, s, SIZE_MAX, NULL, SIZE_MAX, SIZE_MAX);
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
      setting q = {.grid = grids[g],
                   .n_table = DEFAULT_TABLE,
                   .inlet_a0 = COST_INLET,
                   .growth = 1.0,
                   .tol = 1e-9,
                   .ls = kinds[ls],
                   .npts = 25,
                   .first = 8,
                   .count = (size_t)(g ? 3 : 7),
                   .repeats = ls == 2 ? 1 : 3};
      char name[64];
      snprintf(name, sizeof name, "N%zu/in%g/g1/tol1e-09/%dpt", grids[g], COST_INLET, g ? 3 : 7);
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

/* The recommendation of this run (the defaults section). */
typedef struct {
  bool found;
  double res, inlet_a0, growth, tol, per_decade;
} recommendation;
static recommendation g_rec;

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

static const row *study_row(const scene_ctx *s, double r, double X, double g, double tol) {
  return find_row(s->name, KIND_STUDY, r, X, g, tol, scene_per_decade(s), DEFAULT_TABLE);
}

static double comp_err(const row *r) {
  return fmax(fmax(r->err_rc, r->err_rf), fmax(r->err_sc, r->err_sf));
}

/* One knob's row r against base; the time ratio is taken against the base
 * setting at r's tolerance where that was run (resolution, inlet and growth
 * were studied at 1e-9). */
static void print_knob(const scene_ctx *s, const char *knob, const row *r, const row *base) {
  if (!r || r == base) return;
  if (r->tolerance != base->tolerance && strcmp(knob, "tolerance") != 0) {
    const row *b = find_row(s->name, KIND_STUDY, base->res, base->inlet_a0, base->growth,
                            r->tolerance, base->per_decade, DEFAULT_TABLE);
    if (b) base = b;
  }
  printf("#   %-10s %-31s %5zu cells  err_mu %8.2e (%-16s) %8.3f s/curve = x%.2f of %s\n", knob,
         r->setting, r->cells, r->err_mu,
         r->failed  ? "points failed"
         : meets(r) ? "meets the bound"
                    : "misses the bound",
         r->t_curve_s, r->t_curve_s / base->t_curve_s, base->setting);
}

static const double KNOB_RES[] = {10, 15, 20, 30, 45};
static const double KNOB_INLETS[] = {24, 48, 96, 192};
static const double KNOB_GROWTHS[] = {1.02, 1.05, 1.1, 1.2};

/* The study row at (r, X, g, tol), else at tolerance 1e-9 (resolution,
 * inlet and growth were studied at the reference tolerance). */
static const row *study_row_or_tight(const scene_ctx *s, double r, double X, double g, double tol) {
  const row *o = study_row(s, r, X, g, tol);
  return o ? o : study_row(s, r, X, g, 1e-9);
}

/* What each knob buys around the setting `base` of scene s. */
static void knob_table(const scene_ctx *s, const row *base) {
  printf("# %s around %s (%zu cells, err_mu %.2e, %.3f s/curve):\n", s->name, base->setting,
         base->cells, base->err_mu, base->t_curve_s);
  double r = base->res, X = base->inlet_a0, g = base->growth, tol = base->tolerance;
  for (int k = 0; k < 5; k++)
    if (!same(KNOB_RES[k], r))
      print_knob(s, "resolution", study_row_or_tight(s, KNOB_RES[k], X, g, tol), base);
  for (int k = 0; k < 4; k++)
    if (KNOB_INLETS[k] != X)
      print_knob(s, "inlet", study_row_or_tight(s, r, KNOB_INLETS[k], g, tol), base);
  for (int k = 0; k < 4; k++)
    if (KNOB_GROWTHS[k] != g)
      print_knob(s, "growth", study_row_or_tight(s, r, X, KNOB_GROWTHS[k], tol), base);
  double tols[] = {1e-3, 1e-6, 1e-9};
  for (int k = 0; k < 3; k++)
    if (tols[k] != tol) print_knob(s, "tolerance", study_row(s, r, X, g, tols[k]), base);
  /* the old uniform default (N 768 on [-24, 1.6] a0) and its graded twin */
  print_knob(s, "uniform", study_row_or_tight(s, 30, 24, 1.0, tol), base);
  print_knob(s, "graded", study_row_or_tight(s, 30, 24, 1.05, tol), base);
  if (strcmp(s->name, "rubber") == 0)
    for (int k = 0; k < NFITS - 1; k++)
      print_knob(s, "prony",
                 find_row(s->name, KIND_PRONY, r, X, g, tol, PER_DECADE[k], DEFAULT_TABLE), base);
}

/* Sum of the scenes' times per curve at (r, X, g, tol), running what is
 * missing; NAN unless every scene meets the bound there. */
/* The studied rows of setting (r, X, g, tol) in every scene with a
 * reference: their summed curve time and worst err_mu. False when a scene
 * lacks the row, a point failed or (within_bound) a row misses the bound. */
static bool summed_over_scenes(double r, double X, double g, double tol, bool within_bound,
                               double *cost, double *err) {
  *cost = 0, *err = 0;
  for (int k = 0; k < 3; k++) {
    const scene_ctx *s = g_scenes[k];
    if (!s->have_ref) continue;
    const row *o = study_row(s, r, X, g, tol);
    if (within_bound ? !meets(o) : !(o && o->failed == 0 && o->compared > 0)) return false;
    *cost += o->t_curve_s, *err = fmax(*err, o->err_mu);
  }
  return true;
}

/* As summed_over_scenes within the bound, running the rows that are
 * missing (up to the first scene that misses the bound): the summed time,
 * NAN when a scene misses. */
static double common_cost(double r, double X, double g, double tol, double *worst_err) {
  for (int k = 0; k < 3; k++) {
    scene_ctx *s = (scene_ctx *)g_scenes[k];
    if (s->have_ref && !meets(ensure_row(s, r, X, g, tol, scene_per_decade(s)))) return NAN;
  }
  double cost, err;
  summed_over_scenes(r, X, g, tol, true, &cost, &err);
  if (worst_err) *worst_err = err;
  return cost;
}

static void defaults_csv_row(FILE *f, const char *what, const row *r) {
  if (f)
    fprintf(f, "%s,%s,%s,%g,%zu,%g,%zu,%g,%g,%g,%.4e,%.3e,%.4e,%.4e,%.4f,%.3f,%d\n", what, r->scene,
            r->setting, r->res, r->grid, r->growth, r->cells, r->inlet_a0, r->tolerance,
            r->per_decade, r->err_mu, r->worst_v0_eta, comp_err(r), r->err_umin, r->t_curve_s,
            r->t_point_ms, meets(r));
}

/* A table row of the README: scene, reference, setting and its figures. */
static void readme_row(const scene_ctx *s, const row *r) {
  const row *ref = &rows[s->ref_row];
  bool rub = strcmp(s->name, "rubber") == 0;
  printf(
      "| %s (%zu points) | r %g, inlet %g a0, growth %g, tol %.0e%s | %s%s | %zu | %.2e | %.1e | "
      "%.2e | %.2e | %.3f | %.1f |\n",
      s->name, s->npts, ref->res, ref->inlet_a0, ref->growth, ref->tolerance,
      rub ? ", 2/decade" : "", r->setting, r->failed ? " (FAILED POINTS)" : "", r->cells, r->err_mu,
      r->worst_v0_eta, comp_err(r), r->err_umin, r->t_curve_s, r->t_point_ms);
}

static void readme_header(const char *what) {
  printf("| scene | reference | %s | cells | err mu | at v0 eta (Pa m) | err components (of mu) | "
         "err u_min | s per curve | ms per point |\n",
         what);
  printf("|---|---|---|---|---|---|---|---|---|---|\n");
}

static void bench_defaults(const char *dir) {
  printf("\n## defaults: the cheapest setting with mu within %g %% of the reference at every point "
         "of the sweep (no failed point);\n## settings within %.0f %% in time count as equally "
         "cheap: then the tighter tolerance, then the smaller error\n",
         100 * g_accuracy, 100 * TIME_NOISE);
  FILE *f = open_csv(dir, "defaults.csv",
                     "what,scene,setting,cells_per_a0,grid,grid_growth,cells,inlet_a0,tolerance,"
                     "prony_per_decade,err_mu,worst_v0_eta,err_component_max,err_u_min,"
                     "s_per_curve,ms_per_point,meets_bound\n");
  printf("%-7s %-26s %-31s %5s %9s %9s %9s %9s %9s %9s\n", "scene", "reference",
         "cheapest within bound", "cells", "err_mu", "at_v0eta", "err_comp", "err_umin", "s/curve",
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
      if (strcmp(r->scene, s->name) != 0 || r->kind == KIND_REF || r->kind == KIND_REF_INLET ||
          r->kind == KIND_OTHER || !meets(r))
        continue;
      if (b == SIZE_MAX || preferable(r->t_curve_s, r->tolerance, r->err_mu, rows[b].t_curve_s,
                                      rows[b].tolerance, rows[b].err_mu))
        b = i;
    }
    best_row[k] = b;
    const row *ref = &rows[s->ref_row];
    char refs[64];
    snprintf(refs, sizeof refs, "r%g/in%g/g%g/tol%.0e%s", ref->res, ref->inlet_a0, ref->growth,
             ref->tolerance, strcmp(s->name, "rubber") == 0 ? "/p2" : "");
    if (b == SIZE_MAX) {
      printf("%-7s %-26s %-31s\n", s->name, refs, "(none)");
      continue;
    }
    const row *r = &rows[b];
    printf("%-7s %-26s %-31s %5zu %9.2e %9.1e %9.2e %9.2e %9.3f %9.2f\n", s->name, refs, r->setting,
           r->cells, r->err_mu, r->worst_v0_eta, comp_err(r), r->err_umin, r->t_curve_s,
           r->t_point_ms);
    defaults_csv_row(f, "scene-cheapest", r);
  }
  const scene_ctx *first = NULL;
  for (int k = 0; k < 3 && !first; k++)
    if (g_scenes[k]->have_ref) first = g_scenes[k];
  if (!first) {
    if (f) fclose(f);
    return;
  }
  /* 1. resolution, inlet and growth: the cheapest at the reference
   * tolerance that meets the bound in every scene (summed time per curve),
   * graded and uniform settings alike */
  size_t best = SIZE_MAX;
  double best_cost = 0, best_err = 0;
  for (size_t i = 0; i < nrows; i++) {
    const row *r = &rows[i];
    if (strcmp(r->scene, first->name) != 0 || r->kind != KIND_STUDY || r->tolerance != 1e-9)
      continue;
    double cost, err;
    bool ok = summed_over_scenes(r->res, r->inlet_a0, r->growth, r->tolerance, true, &cost, &err);
    if (ok && (best == SIZE_MAX ||
               preferable(cost, r->tolerance, err, best_cost, rows[best].tolerance, best_err)))
      best = i, best_cost = cost, best_err = err;
  }
  /* the cheapest uniform setting, for comparison */
  size_t best_u = SIZE_MAX;
  double best_u_cost = 0, best_u_err = 0;
  for (size_t i = 0; i < nrows; i++) {
    const row *r = &rows[i];
    if (strcmp(r->scene, first->name) != 0 || r->kind != KIND_STUDY || r->tolerance != 1e-9 ||
        r->growth != 1.0)
      continue;
    double cost, err;
    bool ok = summed_over_scenes(r->res, r->inlet_a0, r->growth, r->tolerance, false, &cost, &err);
    if (ok && (best_u == SIZE_MAX || err < best_u_err))
      best_u = i, best_u_cost = cost, best_u_err = err;
  }
  if (best_u != SIZE_MAX)
    printf("# the most accurate uniform setting studied: %s, worst err_mu %.2e (%s), summed "
           "%.3f s\n",
           rows[best_u].setting, best_u_err,
           best_u_err <= g_accuracy ? "meets the bound" : "misses the bound", best_u_cost);
  size_t rec_row[3] = {SIZE_MAX, SIZE_MAX, SIZE_MAX};
  double rec_total = NAN, rec_err = NAN;
  if (best == SIZE_MAX) {
    printf("# no studied setting meets %g %% in all %d scenes\n", 100 * g_accuracy, nscenes);
  } else {
    const row *rb = &rows[best];
    g_rec = (recommendation){true, rb->res, rb->inlet_a0, rb->growth, 1e-9, REF_PER_DECADE};
    printf("# 1. resolution, inlet, growth (tolerance 1e-9, summed time of the %d curves): %s, "
           "%.3f s, worst err_mu %.2e\n",
           nscenes, rb->setting, best_cost, best_err);
    /* 2. tolerance there: the loosest that still meets the bound everywhere
     * and saves more than the timing noise */
    printf("# 2. tolerance at r%g/in%g/g%g (run where missing):\n", g_rec.res, g_rec.inlet_a0,
           g_rec.growth);
    print_header();
    double loose[] = {1e-3, 1e-6};
    for (int k = 0; k < 2; k++) {
      double e = 0, c = common_cost(g_rec.res, g_rec.inlet_a0, g_rec.growth, loose[k], &e);
      /* what the looser tolerance changes in mu itself, point by point */
      double dmu = 0;
      for (int j = 0; j < 3; j++) {
        const scene_ctx *s = g_scenes[j];
        const row *a = study_row(s, g_rec.res, g_rec.inlet_a0, g_rec.growth, loose[k]),
                  *b = study_row(s, g_rec.res, g_rec.inlet_a0, g_rec.growth, 1e-9);
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
    /* 3. the Prony density: the fewest terms per decade that still meet the
     * bound there; a density whose error alone (rubber section) exceeds the
     * bound is not tried */
    if (g_rubber.have_ref && g_have_fits) {
      printf("# 3. Prony terms per decade at r%g/in%g/g%g/tol%.0e:\n", g_rec.res, g_rec.inlet_a0,
             g_rec.growth, g_rec.tol);
      print_header();
      for (int k = 0; k < NFITS; k++) {
        if (PER_DECADE[k] != REF_PER_DECADE && g_prony_only[k] > g_accuracy) {
          printf("#    %g per decade: not tried (its error alone is %.1f %%)\n", PER_DECADE[k],
                 100 * g_prony_only[k]);
          continue;
        }
        const row *r = ensure_row(&g_rubber, g_rec.res, g_rec.inlet_a0, g_rec.growth, g_rec.tol,
                                  PER_DECADE[k]);
        if (meets(r)) {
          g_rec.per_decade = PER_DECADE[k];
          break;
        }
      }
    }
    printf("\n## recommended (the cheapest setting meeting %g %% in %s%s%s): r = %g uniform cells "
           "per a0, inlet %g a0, growth %g, tolerance %g, Prony terms per decade %g\n\n",
           100 * g_accuracy, "fig05", g_fig10.have_ref ? ", fig10" : "",
           g_rubber.have_ref ? ", rubber" : "", g_rec.res, g_rec.inlet_a0, g_rec.growth, g_rec.tol,
           g_rec.per_decade);
    readme_header("recommended setting");
    rec_total = 0, rec_err = 0;
    for (int k = 0; k < 3; k++) {
      scene_ctx *s = (scene_ctx *)g_scenes[k];
      if (!s->have_ref) continue;
      bool rub = strcmp(s->name, "rubber") == 0;
      const row *r = ensure_row(s, g_rec.res, g_rec.inlet_a0, g_rec.growth, g_rec.tol,
                                rub ? g_rec.per_decade : 0.0);
      rec_row[k] = (size_t)(r - rows);
      readme_row(s, r);
      rec_total += r->t_curve_s, rec_err = fmax(rec_err, r->err_mu);
      defaults_csv_row(f, "recommended", r);
    }
    printf("\n# total %.2f s for the %d curves at the recommended setting, worst err_mu %.2e\n",
           rec_total, nscenes, rec_err);
  }
  /* the shipped defaults of wet rough scenes (include/viscolube/scene.h) */
  printf("\n## shipped defaults of wet rough scenes (include/viscolube/scene.h): grid %d on "
         "[%g, %g] a0 (r = %g cells per a0), growth %g, tolerance %g; the stored Prony series\n\n",
         VL_WET_ROUGH_GRID, VL_WET_ROUGH_DOMAIN_MIN_A0, VL_WET_DOMAIN_MAX_A0, SHIP_RES, SHIP_GROWTH,
         SHIP_TOL);
  readme_header("shipped setting");
  size_t ship_row[3] = {SIZE_MAX, SIZE_MAX, SIZE_MAX};
  double ship_total = 0, ship_err = 0;
  bool ship_ok = true;
  for (int k = 0; k < 3; k++) {
    scene_ctx *s = (scene_ctx *)g_scenes[k];
    if (!s->have_ref) continue;
    const row *r = ensure_row(s, SHIP_RES, SHIP_INLET, SHIP_GROWTH, SHIP_TOL, scene_per_decade(s));
    ship_row[k] = (size_t)(r - rows);
    readme_row(s, r);
    ship_total += r->t_curve_s, ship_err = fmax(ship_err, r->err_mu);
    ship_ok = ship_ok && meets(r);
    defaults_csv_row(f, "shipped", r);
  }
  printf("\n# the shipped defaults %s the %g %% bound in %s (worst err_mu %.2e = %.0f %% of the "
         "bound), %.2f s for the %d curves",
         ship_ok ? "meet" : "MISS", 100 * g_accuracy, ship_ok ? "every scene" : "some scene",
         ship_err, 100 * ship_err / g_accuracy, ship_total, nscenes);
  if (!isnan(rec_total))
    printf("; the cheapest within the bound: worst err_mu %.2e (%.0f %% of the bound), %.2f s: "
           "the shipped defaults cost x%.2f of it",
           rec_err, 100 * rec_err / g_accuracy, rec_total, ship_total / rec_total);
  printf("\n");
  printf("\n## what each knob buys (one knob changed from the shipped setting; error of mu against "
         "the reference, time relative)\n");
  for (int k = 0; k < 3; k++)
    if (ship_row[k] != SIZE_MAX) knob_table(g_scenes[k], &rows[ship_row[k]]);
  if (f) fclose(f);
  /* Pareto plots: the scene's cheapest within the bound ringed green, the
   * recommendation squared, the shipped defaults ringed red */
  for (int k = 0; k < 3; k++)
    if (g_scenes[k]->have_ref)
      scene_pareto(dir, g_scenes[k], best_row[k],
                   best_row[k] == SIZE_MAX ? NULL : "the scene's cheapest within the bound",
                   rec_row[k], ship_row[k]);
}

/* ---------------------------------------------------------------- targets */

static void run_target(scene_ctx *s, setting q, int reps, const char *what) {
  vl_point pts[64];
  q.npts = 61, q.repeats = g_quick ? 1 : reps;
  char name[64];
  setting_label(name, sizeof name, &q);
  snprintf(name + strlen(name), sizeof name - strlen(name), "/61pt");
  row *r = run_setting(s, &q, pts, name, KIND_OTHER);
  snprintf(r->scene, sizeof r->scene, "target");
  print_row(r);
  printf("# %s: 61-point curve %.2f s (target: 60 points < 2 s); %.1f ms per point (target "
         "< 100 ms at N 512); %.1f Newton iterations per point; %zu failed; median of %d\n",
         what, r->t_curve_s, r->t_point_ms, (double)r->iterations / 61.0, r->failed, r->repeats);
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
  double lap = dgetrf_seconds((int)r->unknowns, r->unknowns > 2000 ? 3 : 7);
  double step = tm->t_newton_s / (double)r->iterations;
  printf("# Newton step %.2f ms vs one dgetrf of the same size (2*cells+1 = %zu) %.2f ms: ratio "
         "%.2f (target <= 2)\n",
         1e3 * step, r->unknowns, 1e3 * lap, step / lap);
  double n = (double)r->cells;
  printf("# memory: %zu cells; dense Jacobian (2n+1)^2 x 8 B = %.2f MB, Schur complement and "
         "B Bp^-1 2 (n+1) n x 8 B = %.2f MB, influence matrix n^2 x 8 B = %.2f MB: about 56 n^2 "
         "bytes; measured heap held by the contact after the curve %.2f MB = %.0f n^2 bytes\n",
         r->cells, 8e-6 * (double)r->unknowns * (double)r->unknowns, 16e-6 * (n + 1) * n,
         8e-6 * n * n, 1e-6 * (double)r->heap_bytes, (double)r->heap_bytes / (n * n));
}

static void bench_targets(scene_ctx *s) {
  printf("\n## targets: %s, 61 points as the case; the shipped defaults of wet rough scenes: "
         "grid %d on [%g, %g] a0 (r %g), growth %g, tolerance %g\n",
         s->file, VL_WET_ROUGH_GRID, VL_WET_ROUGH_DOMAIN_MIN_A0, VL_WET_DOMAIN_MAX_A0, SHIP_RES,
         SHIP_GROWTH, SHIP_TOL);
  print_header();
  run_target(s, at(s, SHIP_RES, SHIP_INLET, SHIP_GROWTH, SHIP_TOL, NULL, 0.0), 3,
             "shipped defaults");
  setting q = at(s, 0, 24.0, 1.0, SHIP_TOL, NULL, 0.0);
  q.grid = 512;
  run_target(s, q, 3, "uniform N 512 (the issue's grid) on [-24, 1.6] a0");
  q.grid = 768;
  run_target(s, q, 1, "the old uniform default, N 768 on [-24, 1.6] a0");
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
      ref_res_opt = strtod(argv[++i], NULL); /* uniform cells per a0 */
    else if (strcmp(argv[i], "--ref-inlet") == 0 && i + 1 < argc)
      ref_inlet_opt = strtod(argv[++i], NULL);
    else if (strcmp(argv[i], "--ref-growth") == 0 && i + 1 < argc)
      ref_growth_opt = strtod(argv[++i], NULL);
    else if (strcmp(argv[i], "--accuracy") == 0 && i + 1 < argc)
      g_accuracy = strtod(argv[++i], NULL);
    else {
      fprintf(stderr,
              "usage: %s [--out DIR] [--only SECTIONS] [--quick] [--db PATH] [--cases DIR]\n"
              "          [--ref-grid R] [--ref-inlet X] [--ref-growth G] [--accuracy F]\n"
              "  SECTIONS: comma-separated of hunter,fig05,fig10,rubber,linsol,defaults,targets "
              "(default: all, ~6 min)\n"
              "  --ref-grid R: the references' uniform cells per a0 (default 60); --ref-inlet X: "
              "their inlet (192 a0);\n  --ref-growth G: their grid growth (1.02); --accuracy F: "
              "the bound of the defaults (0.01)\n",
              argv[0]);
      return 2;
    }
  }
  if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
    fprintf(stderr, "cannot create %s: %s\n", dir, strerror(errno));
    return 1;
  }
  g_quick = quick;
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
