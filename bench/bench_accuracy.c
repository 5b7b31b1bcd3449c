/* Accuracy-vs-cost benchmark of the contact solver (issue 7).
 *
 *   bench_accuracy [--out DIR] [--only hunter,fig05,linsol,targets] [--quick]
 *
 * Sections:
 *   hunter  smooth dry rolling (model rubber, Einf/E0 = 10) against Hunter's
 *           exact solution (tests/oracles/hunter.c): grid 64 ... 2048, relative
 *           error of mu at De = v0 tau/a0 = 0.1, 1.3, 10 and time per point of a
 *           6-point continuation ramp in De.
 *   fig05   the fig05 wet scene (model rubber, paper surface h_rms 3 um built
 *           here, eta 1e-4 Pa s, Patir-Cheng, sigma_s 1 MPa), 25-point sweep
 *           v0 eta = 1e-12 ... 1 Pa m: grid x inlet length x tolerance, and the
 *           Persson table resolution, each against a reference computed at the
 *           finest settings we can afford (printed). Errors are the largest over
 *           the sweep: |mu - mu_ref|/mu_ref; each component |c - c_ref|/mu_ref
 *           (components can vanish, so they are measured in units of the total);
 *           |u_min - u_min_ref|/u_min_ref. The same runs give the cost per call
 *           of residual, Jacobian, LU set-up and solve, and their exponent in N.
 *   linsol  LAPACK dgetrf/dgetrs against SUNLinSol_Dense on a 7-point part of
 *           the fig05 sweep at N = 256, 512.
 *   targets the targets: a 61-point fig05 curve at the default settings
 *           (N 512, domain [-3, 1.6] a0, tolerance 1e-9) and the Newton step
 *           against one dgetrf of the same size.
 * Times are wall-clock, the median of repeats (each repeat resets the solver
 * to the Hertz guess and runs the whole sweep). Run with OPENBLAS_NUM_THREADS=1
 * for one-core figures (scripts/bench.sh does). Writes CSV files and
 * pareto-*.svg into DIR (default bench-out). */
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
#include "viscolube/roughness.h"
#include "viscolube/sweep.h"

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
  fprintf(out, "# machine: %s, %ld online cores, load average %.2f %.2f %.2f, "
               "OPENBLAS_NUM_THREADS=%s\n",
          model, sysconf(_SC_NPROCESSORS_ONLN), load[0], load[1], load[2], ob ? ob : "(unset)");
}

/* ---------------------------------------------------------------- results */

typedef struct {
  char scene[16], setting[48], linsol[12];
  size_t grid, unknowns, n_table, points, failed;
  double inlet_a0, tolerance;
  long iterations;
  double err_mu, err_rc, err_rf, err_sc, err_sf, err_umin;
  double t_point_ms, t_curve_s;
  int repeats;
  vl_contact_timing timing; /* of the last repeat */
} row;

enum { MAX_ROWS = 128 };
static row rows[MAX_ROWS];
static size_t nrows;

static void print_header(void) {
  printf("%-7s %-26s %-8s %5s %7s %4s %7s %6s %9s %9s %9s %9s %9s %9s %9s %9s\n", "scene",
         "setting", "linsol", "N", "tol", "fail", "iters", "table", "err_mu", "err_Rc", "err_Rf",
         "err_Sc", "err_Sf", "err_umin", "ms/point", "s/curve");
}

static void print_row(const row *r) {
  printf("%-7s %-26s %-8s %5zu %7.0e %4zu %7ld %6zu %9.2e %9.2e %9.2e %9.2e %9.2e %9.2e %9.2f "
         "%9.3f\n",
         r->scene, r->setting, r->linsol, r->grid, r->tolerance, r->failed, r->iterations,
         r->n_table, r->err_mu, r->err_rc, r->err_rf, r->err_sc, r->err_sf, r->err_umin,
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
  r->err_rc = r->err_rf = r->err_sc = r->err_sf = r->err_umin = NAN;
  return r;
}

static int write_rows_csv(const char *dir) {
  char path[1024];
  snprintf(path, sizeof path, "%s/accuracy.csv", dir);
  FILE *f = fopen(path, "w");
  if (!f) return -1;
  machine(f);
  fprintf(f, "scene,setting,linear_solver,grid,unknowns,inlet_a0,tolerance,n_table,points,failed,"
             "newton_iterations,err_mu,err_mu_Rc,err_mu_Rf,err_mu_Sc,err_mu_Sf,err_u_min,"
             "ms_per_point,s_per_curve,repeats\n");
  for (size_t i = 0; i < nrows; i++) {
    const row *r = &rows[i];
    fprintf(f, "%s,%s,%s,%zu,%zu,%g,%g,%zu,%zu,%zu,%ld,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.4f,%.5f,%d\n",
            r->scene, r->setting, r->linsol, r->grid, r->unknowns, r->inlet_a0, r->tolerance,
            r->n_table, r->points, r->failed, r->iterations, r->err_mu, r->err_rc, r->err_rf,
            r->err_sc, r->err_sf, r->err_umin, r->t_point_ms, r->t_curve_s, r->repeats);
  }
  return fclose(f);
}

/* ---------------------------------------------------------------- Pareto SVG */

/* Log-log scatter of error against time, the non-dominated points joined. */
static int pareto_svg(const char *path, const char *title, const char *xlabel, size_t n,
                      const double *t, const double *e, const char *const *label) {
  FILE *f = fopen(path, "w");
  if (!f) return -1;
  const double W = 900, H = 640, L = 90, R = 280, T = 50, B = 70;
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
  for (size_t i = 0; i < n; i++) {
    if (!(t[i] > 0 && e[i] > 0)) continue;
    xmin = fmin(xmin, log10(t[i])), xmax = fmax(xmax, log10(t[i]));
    ymin = fmin(ymin, log10(e[i])), ymax = fmax(ymax, log10(e[i]));
  }
  xmin = floor(xmin), xmax = ceil(xmax), ymin = floor(ymin), ymax = ceil(ymax);
  if (xmax <= xmin) xmax = xmin + 1;
  if (ymax <= ymin) ymax = ymin + 1;
#define PX(v) (L + (log10(v) - xmin) / (xmax - xmin) * (W - L - R))
#define PY(v) (H - B - (log10(v) - ymin) / (ymax - ymin) * (H - T - B))
  fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" "
             "font-family=\"sans-serif\" font-size=\"13\">\n<rect width=\"100%%\" height=\"100%%\" "
             "fill=\"white\"/>\n<text x=\"%g\" y=\"28\" font-size=\"16\">%s</text>\n",
          W, H, L, title);
  for (double d = xmin; d <= xmax + 1e-9; d += 1) {
    double x = L + (d - xmin) / (xmax - xmin) * (W - L - R);
    fprintf(f, "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"#ddd\"/>"
               "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">1e%g</text>\n",
            x, T, x, H - B, x, H - B + 20, d);
  }
  for (double d = ymin; d <= ymax + 1e-9; d += 1) {
    double y = H - B - (d - ymin) / (ymax - ymin) * (H - T - B);
    fprintf(f, "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"#ddd\"/>"
               "<text x=\"%g\" y=\"%g\" text-anchor=\"end\">1e%g</text>\n",
            L, y, W - R, y, L - 6, y + 4, d);
  }
  if (ymin <= -2 && ymax >= -2)
    fprintf(f, "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"#c00\" "
               "stroke-dasharray=\"6,4\"/><text x=\"%g\" y=\"%g\" fill=\"#c00\">1 %%</text>\n",
            L, PY(1e-2), W - R, PY(1e-2), W - R + 4, PY(1e-2) + 4);
  fprintf(f, "<rect x=\"%g\" y=\"%g\" width=\"%g\" height=\"%g\" fill=\"none\" stroke=\"black\"/>\n",
          L, T, W - L - R, H - T - B);
  fprintf(f, "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">%s</text>\n", (L + W - R) / 2,
          H - 20, xlabel);
  fprintf(f, "<text transform=\"translate(24,%g) rotate(-90)\" text-anchor=\"middle\">largest "
             "relative error of mu over the sweep</text>\n",
          (T + H - B) / 2);
  /* Pareto front: sorted by time, keep each point with a smaller error than
   * every cheaper one */
  size_t *ord = malloc(n * sizeof *ord);
  for (size_t i = 0; i < n; i++) ord[i] = i;
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
    fprintf(f, "%g,%g ", PX(t[i]), PY(e[i]));
  }
  fprintf(f, "\"/>\n");
  for (size_t i = 0; i < n; i++) {
    if (!(t[i] > 0 && e[i] > 0)) continue;
    fprintf(f, "<circle cx=\"%g\" cy=\"%g\" r=\"4.5\" fill=\"#ff7f0e\" stroke=\"black\" "
               "stroke-width=\"0.6\"><title>%s</title></circle>\n",
            PX(t[i]), PY(e[i]), label[i]);
    fprintf(f, "<text x=\"%g\" y=\"%g\" font-size=\"9\" fill=\"#444\">%s</text>\n", PX(t[i]) + 6,
            PY(e[i]) - 4, label[i]);
  }
  fprintf(f, "<text x=\"%g\" y=\"%g\">blue line: Pareto front</text>\n", W - R + 10, T + 14);
  fprintf(f, "<text x=\"%g\" y=\"%g\">labels: N / inlet / tol</text>\n", W - R + 10, T + 32);
  fprintf(f, "</svg>\n");
#undef PX
#undef PY
  free(ord);
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
  for (int i = 0; i < n; i++) a0[(size_t)i * (size_t)n + (size_t)i] += n;
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
      if (ls == 1 && (N < 256 || N > 512)) continue; /* SUNDIALS: the comparison sizes */
      vl_contact_config cfg;
      vl_contact_config_defaults(&cfg);
      cfg.rubber = vl_prony_single(E0, 10.0, TAU, 0.5);
      cfg.radius_m = RADIUS, cfg.load_n_per_m = LOAD, cfg.grid = N;
      cfg.x_min_a0 = -1.5, cfg.x_max_a0 = 1.5;
      cfg.linear_solver = ls ? VL_LINSOL_SUNDIALS : VL_LINSOL_LAPACK;
      vl_contact *c;
      vl_error err;
      if (vl_contact_create(&cfg, &c, &err) != VL_OK) {
        fprintf(stderr, "create: %s\n", err.msg);
        exit(1);
      }
      double v[6];
      for (int i = 0; i < nde; i++) v[i] = de[i] * vl_contact_a0(c) / TAU;
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
      print_row(r);
      vl_contact_free(c);
    }
}

/* ---------------------------------------------------------------- fig05 */

enum { NP = 25 };

typedef struct {
  size_t grid, n_table;
  double inlet_a0, tol;
  vl_linear_solver ls;
  size_t npts; /* points of the sweep (log-spaced v0 eta 1e-12 ... 1) */
  size_t first, count; /* sub-range of the sweep that is run */
  int repeats;
} fig05_setting;

static vl_persson *table_for(size_t n_table) {
  static size_t sizes[8];
  static vl_persson *tabs[8];
  for (int i = 0; i < 8; i++)
    if (tabs[i] && sizes[i] == n_table) return tabs[i];
  vl_psd psd;
  vl_error err;
  if (vl_psd_init_self_affine(&psd, 0.8, 2e5, 7.8e9, 3e-6, &err) != VL_OK) exit(1);
  for (int i = 0; i < 8; i++)
    if (!tabs[i]) {
      double t0 = now_s();
      if (vl_persson_build(&psd, n_table, &tabs[i], &err) != VL_OK) {
        fprintf(stderr, "persson: %s\n", err.msg);
        exit(1);
      }
      printf("# Persson table of %zu entries built in %.3f s (once per surface; not in the times)\n",
             n_table, now_s() - t0);
      sizes[i] = n_table;
      vl_psd_free(&psd);
      return tabs[i];
    }
  exit(1);
}

/* Runs a fig05 sweep; fills out[count] and a row (errors left to the caller). */
static row *run_fig05(const fig05_setting *s, vl_point *out, const char *setting) {
  vl_contact_config cfg;
  vl_contact_config_defaults(&cfg);
  cfg.rubber = vl_prony_single(3.6e6, 10.0, 0.1, 0.5);
  cfg.radius_m = 0.01, cfg.load_n_per_m = 1000.0, cfg.sigma_s_pa = 1e6;
  cfg.roughness = table_for(s->n_table);
  cfg.eta_pa_s = 1e-4;
  cfg.flow_factors = VL_FLOW_FACTORS_PATIR_CHENG;
  cfg.grid = s->grid, cfg.x_min_a0 = -s->inlet_a0, cfg.x_max_a0 = 1.6;
  cfg.tolerance = s->tol, cfg.linear_solver = s->ls;
  vl_contact *c;
  vl_error err;
  if (vl_contact_create(&cfg, &c, &err) != VL_OK) {
    fprintf(stderr, "create: %s\n", err.msg);
    exit(1);
  }
  double *v = malloc(s->npts * sizeof *v);
  for (size_t i = 0; i < s->npts; i++)
    v[i] = pow(10.0, -12.0 + 12.0 * (double)i / (double)(s->npts - 1)) / cfg.eta_pa_s;
  double tt[8];
  int reps = s->repeats < 8 ? s->repeats : 8;
  vl_sweep_stats st = {0};
  row *r = new_row();
  for (int k = 0; k < reps; k++) {
    vl_contact_reset(c);
    vl_contact_timing_reset(c);
    double t0 = now_s();
    vl_sweep_run(c, s->count, v + s->first, NULL, out, NULL, NULL, &st, &err);
    tt[k] = now_s() - t0;
  }
  vl_contact_timing_get(c, &r->timing);
  snprintf(r->scene, sizeof r->scene, "fig05");
  snprintf(r->setting, sizeof r->setting, "%s", setting);
  snprintf(r->linsol, sizeof r->linsol, "%s",
           s->ls == VL_LINSOL_SUNDIALS ? "sundials" : s->ls == VL_LINSOL_SCHUR ? "schur" : "lapack");
  r->grid = s->grid, r->unknowns = 2 * s->grid + 1, r->inlet_a0 = s->inlet_a0;
  r->tolerance = s->tol, r->n_table = s->n_table, r->points = s->count;
  r->failed = st.failed, r->iterations = st.newton_iterations, r->repeats = reps;
  r->t_curve_s = median(tt, reps);
  r->t_point_ms = 1e3 * r->t_curve_s / (double)s->count;
  r->err_mu = NAN;
  free(v);
  vl_contact_free(c);
  return r;
}

static void fig05_errors(row *r, const vl_point *p, const vl_point *ref, size_t n) {
  double e[6] = {0, 0, 0, 0, 0, 0};
  for (size_t i = 0; i < n; i++) {
    if (!p[i].converged || !ref[i].converged) continue;
    double m = fabs(ref[i].mu);
    e[0] = fmax(e[0], fabs(p[i].mu - ref[i].mu) / m);
    e[1] = fmax(e[1], fabs(p[i].mu_Rc - ref[i].mu_Rc) / m);
    e[2] = fmax(e[2], fabs(p[i].mu_Rf - ref[i].mu_Rf) / m);
    e[3] = fmax(e[3], fabs(p[i].mu_Sc - ref[i].mu_Sc) / m);
    e[4] = fmax(e[4], fabs(p[i].mu_Sf - ref[i].mu_Sf) / m);
    e[5] = fmax(e[5], fabs(p[i].u_min_m - ref[i].u_min_m) / ref[i].u_min_m);
  }
  r->err_mu = e[0], r->err_rc = e[1], r->err_rf = e[2], r->err_sc = e[3], r->err_sf = e[4];
  r->err_umin = e[5];
}

/* Least-squares slope of log y against log x. */
static double loglog_slope(size_t n, const double *x, const double *y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < n; i++) {
    double a = log(x[i]), b = log(y[i]);
    sx += a, sy += b, sxx += a * a, sxy += a * b;
  }
  double m = (double)n;
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

static size_t ref_grid_opt = 512; /* --ref-grid; 768 failed at 15 of 25 points */

static void bench_fig05(const char *dir, bool quick) {
  const size_t ref_grid = ref_grid_opt, ref_table = 2048;
  const double ref_inlet = 5.0, ref_tol = 1e-9; /* 1e-10: no point converges at N 768 */
  printf("\n## fig05: model rubber on paper-3um, eta 1e-4 Pa s, Patir-Cheng, sigma_s 1 MPa,\n"
         "## %d-point sweep v0 eta = 1e-12 ... 1 Pa m, domain [-inlet, 1.6] a0\n"
         "## reference: N = %zu, inlet %g a0, tolerance %g, Persson table %zu entries\n",
         NP, ref_grid, ref_inlet, ref_tol, ref_table);
  vl_point ref[NP], pts[NP];
  fig05_setting s = {ref_grid, ref_table, ref_inlet, ref_tol, VL_LINSOL_SCHUR, NP, 0, NP, 1};
  row *rr = run_fig05(&s, ref, "reference");
  fig05_errors(rr, ref, ref, NP);
  print_header();
  print_row(rr);
  size_t grids[] = {64, 128, 256, 512, 1024};
  double inlets[] = {2.0, 3.0, 5.0}, tols[] = {1e-6, 1e-9};
  size_t ng = quick ? 3 : 4;
  size_t first_fig05 = nrows;
  for (size_t g = 0; g < ng; g++)
    for (int il = 0; il < 3; il++)
      for (int t = 0; t < 2; t++) {
        /* N 512 costs ~1 s per point: inlet 3 only, one repeat */
        if (grids[g] == 512 && il != 1) continue;
        fig05_setting q = {grids[g], 256, inlets[il], tols[t], VL_LINSOL_SCHUR, NP, 0, NP,
                           grids[g] <= 128 ? 3 : grids[g] <= 256 ? 2 : 1};
        if (quick) q.repeats = 1;
        char name[48];
        snprintf(name, sizeof name, "N%zu/in%g/tol%.0e", grids[g], inlets[il], tols[t]);
        row *r = run_fig05(&q, pts, name);
        fig05_errors(r, pts, ref, NP);
        print_row(r);
      }
  /* Persson table resolution at N 256, inlet 3, tolerance 1e-9 */
  size_t tabs[] = {64, 128, 1024};
  for (int k = 0; k < 3; k++) {
    fig05_setting q = {256, tabs[k], 3.0, 1e-9, VL_LINSOL_SCHUR, NP, 0, NP, quick ? 1 : 2};
    char name[48];
    snprintf(name, sizeof name, "N256/in3/tol1e-09/table%zu", tabs[k]);
    row *r = run_fig05(&q, pts, name);
    fig05_errors(r, pts, ref, NP);
    print_row(r);
  }
  size_t last_fig05 = nrows;

  /* Pareto plot of the grid x inlet x tolerance runs */
  size_t n = last_fig05 - first_fig05;
  double *t = malloc(n * sizeof *t), *e = malloc(n * sizeof *e);
  const char **lab = malloc(n * sizeof *lab);
  for (size_t i = 0; i < n; i++) {
    t[i] = rows[first_fig05 + i].t_curve_s, e[i] = rows[first_fig05 + i].err_mu;
    lab[i] = rows[first_fig05 + i].setting;
  }
  char path[1024];
  snprintf(path, sizeof path, "%s/pareto-fig05.svg", dir);
  char title[160];
  snprintf(title, sizeof title, "fig05 (%d-point sweep): error of mu vs time per curve", NP);
  if (pareto_svg(path, title, "time per 25-point curve (s)", n, t, e, lab) != 0)
    fprintf(stderr, "cannot write %s\n", path);
  /* cheapest within 1 % */
  size_t best = SIZE_MAX;
  for (size_t i = first_fig05; i < last_fig05; i++)
    if (rows[i].failed == 0 && rows[i].err_mu <= 1e-2 &&
        (best == SIZE_MAX || rows[i].t_curve_s < rows[best].t_curve_s))
      best = i;
  if (best != SIZE_MAX)
    printf("# cheapest fig05 setting with mu within 1 %% of the reference at every point: %s "
           "(err %.2e, %.3f s per curve, %.1f ms per point)\n",
           rows[best].setting, rows[best].err_mu, rows[best].t_curve_s, rows[best].t_point_ms);
  free(t), free(e), free(lab);

  /* cost per call against N, from the inlet-3, tolerance-1e-9 runs */
  printf("\n## cost per call vs N (fig05 runs, inlet 3, tol 1e-9, LAPACK; unknowns 2N+1)\n");
  printf("%6s %8s %12s %12s %12s %12s %12s %14s %12s %8s\n", "N", "unknowns", "residual_ms",
         "jacobian_ms", "LU_setup_ms", "solve_ms", "kernel_ms", "newton_step_ms", "dgetrf_ms",
         "step/LU");
  snprintf(path, sizeof path, "%s/cost_vs_n.csv", dir);
  FILE *f = fopen(path, "w");
  if (f) {
    machine(f);
    fprintf(f, "grid,unknowns,residual_ms,jacobian_ms,lu_setup_ms,solve_ms,kernel_ms,"
               "newton_step_ms,dgetrf_ms,step_over_dgetrf\n");
  }
  double xs[8], yr[8], yj[8], ys[8], yv[8], xlo = INFINITY, xhi = 0;
  size_t nx = 0;
  for (size_t i = first_fig05 - 1; i < last_fig05; i++) { /* from the reference on */
    const row *r = &rows[i];
    if (i >= first_fig05 && (r->inlet_a0 != 3.0 || r->tolerance != 1e-9 || r->n_table != 256))
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
  if (nx >= 2)
    printf("# exponents (least squares, N = %g ... %g): residual %.2f, Jacobian %.2f, "
           "LU set-up %.2f, solve %.2f\n",
           xlo, xhi, loglog_slope(nx, xs, yr), loglog_slope(nx, xs, yj),
           loglog_slope(nx, xs, ys), loglog_slope(nx, xs, yv));
}

static void bench_linsol(bool quick) {
  printf("\n## linear solvers: fig05, inlet 3, tolerance 1e-9, 7 points "
         "v0 eta = 1e-8 ... 1e-5 (N 512: 3 points, 1e-8 ... 1e-7) of the 25-point sweep\n"
         "#   schur: Reynolds block eliminated, LAPACK LU of the (N+1)^2 complement (default)\n"
         "#   lapack: LAPACK LU of the full (2N+1)^2 Jacobian; sundials: SUNLinSol_Dense\n");
  print_header();
  vl_point pts[NP];
  size_t grids[] = {256, 512};
  const vl_linear_solver kinds[] = {VL_LINSOL_SCHUR, VL_LINSOL_LAPACK, VL_LINSOL_SUNDIALS};
  for (int g = 0; g < (quick ? 1 : 2); g++) {
    double t[3] = {0, 0, 0};
    for (int ls = 0; ls < 3; ls++) {
      if (g == 1 && ls == 2) continue; /* SUNDIALS at N 512: ~1.5 s per LU */
      fig05_setting q = {grids[g], 256, 3.0, 1e-9, kinds[ls], NP, 8, g ? 3 : 7, ls == 2 ? 1 : 3};
      char name[48];
      snprintf(name, sizeof name, "N%zu/in3/tol1e-09/%dpt", grids[g], g ? 3 : 7);
      row *r = run_fig05(&q, pts, name);
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

static void bench_targets(void) {
  printf("\n## targets: fig05 at the default settings (N 512, domain [-3, 1.6] a0, tol 1e-9), "
         "61 points as cases/fig05.ini\n");
  print_header();
  vl_point pts[61];
  fig05_setting q = {512, 256, 3.0, 1e-9, VL_LINSOL_SCHUR, 61, 0, 61, 3};
  row *r = run_fig05(&q, pts, "N512/in3/tol1e-09/61pt");
  snprintf(r->scene, sizeof r->scene, "target");
  print_row(r);
  printf("# 61-point curve: %.2f s (target < 2 s); %.1f ms per point (target < 100 ms); "
         "%.1f Newton iterations per point\n",
         r->t_curve_s, r->t_point_ms, (double)r->iterations / 61.0);
  const vl_contact_timing *tm = &r->timing;
  printf("# split of the curve's time: residual %.0f %%, Jacobian %.0f %%, LU %.0f %%, solve %.0f "
         "%%, kernel builds %.0f %%, rest %.0f %%\n",
         100 * tm->t_residual_s / r->t_curve_s, 100 * tm->t_jacobian_s / r->t_curve_s,
         100 * tm->t_setup_s / r->t_curve_s, 100 * tm->t_solve_s / r->t_curve_s,
         100 * tm->t_kernel_s / r->t_curve_s,
         100 * (r->t_curve_s - tm->t_residual_s - tm->t_jacobian_s - tm->t_setup_s -
                tm->t_solve_s - tm->t_kernel_s) /
             r->t_curve_s);
  double lap = dgetrf_seconds((int)r->unknowns, 7);
  double step = tm->t_newton_s / (double)r->iterations;
  printf("# Newton step %.2f ms vs one dgetrf(%zu) %.2f ms: ratio %.2f (target <= 2)\n",
         1e3 * step, r->unknowns, 1e3 * lap, step / lap);
  size_t nu = r->unknowns;
  printf("# memory: dense Jacobian %zu^2 x 8 B = %.1f MB + influence matrix %zu^2 x 8 B = %.1f MB "
         "(O(N^2): about 40 N^2 bytes for the wet rough contact)\n",
         nu, 8e-6 * (double)nu * (double)nu, r->grid, 8e-6 * (double)r->grid * (double)r->grid);
}

int main(int argc, char **argv) {
  const char *dir = "bench-out", *only = "hunter,fig05,linsol";
  bool quick = false;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) dir = argv[++i];
    else if (strcmp(argv[i], "--only") == 0 && i + 1 < argc) only = argv[++i];
    else if (strcmp(argv[i], "--quick") == 0) quick = true;
    else if (strcmp(argv[i], "--ref-grid") == 0 && i + 1 < argc)
      ref_grid_opt = (size_t)strtoul(argv[++i], NULL, 10);
    else {
      fprintf(stderr, "usage: %s [--out DIR] [--only hunter,fig05,linsol,targets] [--quick] [--ref-grid N]\n"
                      "  default sections: hunter,fig05,linsol (targets: a 61-point curve, ~1 min)\n",
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
  if (strstr(only, "hunter")) bench_hunter(quick);
  if (strstr(only, "fig05")) bench_fig05(dir, quick);
  if (strstr(only, "linsol")) bench_linsol(quick);
  if (strstr(only, "targets")) bench_targets();
  if (write_rows_csv(dir) != 0) fprintf(stderr, "cannot write %s/accuracy.csv\n", dir);
  printf("\n# total %.0f s; CSV and SVG in %s\n", now_s() - t0, dir);
  machine(stdout);
  return 0;
}
