/* Automatic numerics (issue 17): the true error of the automatic layout
 * against converged references, next to its error estimate and its cost.
 *
 *   auto_numerics [--only soft,rigid] [--quick]
 *   auto_numerics --levels ETA_V0 R1 R2 ...   (soft EHL: the planned layout at
 *                                              resolutions R1, R2, ...)
 *
 *   soft   soft EHL: elastic E0 3.6 MPa (nu 0.5), R 1 cm, fN 1 kN/m, eta
 *          0.01 Pa s, smooth; eta v0 = 1e-6 ... 0.1 Pa m (g_E from about
 *          4600 down to 14). Reference: the planned layout with every width
 *          divided by 4 and by 8, Richardson-extrapolated (second order; the
 *          difference between the two levels is printed as its uncertainty).
 *   rigid  a nearly rigid cylinder (E0 1e13 Pa) under the same load, eta
 *          0.1 Pa s, v0 = 1 m/s against Martin's h = 4.894 eta (v0/2) R/fN.
 * Each automatic point is a one-point automatic sweep (vl_sweep_run_auto:
 * plan, solve, estimate, refine) from a fresh start; the time is its wall
 * clock. Run with OPENBLAS_NUM_THREADS=1. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "viscolube.h"

#include "numerics_plan.h" /* the planner, private to the solver */

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static vl_contact_config elastic_film(double e0, double eta) {
  vl_contact_config cfg;
  vl_contact_config_defaults(&cfg);
  vl_contact_numerics_defaults(false, true, &cfg);
  cfg.rubber.n_terms = 0;
  cfg.rubber.e_inf_pa = e0;
  cfg.rubber.nu = 0.5;
  cfg.radius_m = 0.01;
  cfg.load_n_per_m = 1000.0;
  cfg.eta_pa_s = eta;
  return cfg;
}

/* One fresh solve on the planned layout at resolution r. */
static int solve_planned(const vl_contact_config *base, double v0, double r, vl_point *pt,
                         size_t *cells) {
  vl_plan_input in = {0.0, 0.0, r, 1.0, 1.0, 0.0, false, 0};
  vl_plan plan;
  vl_error err;
  if (vl_plan_wet(base, v0, &in, &plan, &err) != VL_OK) {
    fprintf(stderr, "plan: %s\n", err.msg);
    return -1;
  }
  vl_contact *c = NULL;
  int rc = -1;
  if (vl_contact_create(&plan.cfg, &c, &err) == VL_OK) {
    rc = vl_contact_solve(c, v0, pt, &err) == VL_OK ? 0 : -1;
    *cells = vl_contact_grid(c);
  } else {
    fprintf(stderr, "create: %s\n", err.msg);
  }
  vl_contact_free(c);
  vl_plan_free(&plan);
  return rc;
}

static int auto_point(const vl_contact_config *base, double v0, vl_point *pt, double *secs) {
  vl_error err;
  double t0 = now_s();
  vl_status st = vl_sweep_run_auto(base, NULL, 1, &v0, pt, NULL, NULL, NULL, &err);
  *secs = now_s() - t0;
  return st == VL_OK && pt->converged ? 0 : -1;
}

static void soft(int quick) {
  vl_contact_config base = elastic_film(3.6e6, 0.01);
  printf("soft EHL (E0 3.6 MPa, R 1 cm, fN 1 kN/m, eta 0.01 Pa s)\n");
  printf("%9s %7s | %11s %9s %9s | %11s %10s %10s %9s %8s\n", "eta_v0", "g_E", "h_ref_m", "ref_unc",
         "mu_unc", "h_auto_m", "h_err", "mu_err", "estimate", "time_s");
  double er = 3.6e6 / 0.75;
  for (int k = 0; k <= 10; k += quick ? 5 : 1) {
    double ev = pow(10.0, -6.0 + 0.5 * k), v0 = ev / base.eta_pa_s;
    double gE = base.load_n_per_m / sqrt(ev * 0.5 * 2.0 * er * base.radius_m);
    vl_point p4, p8, pa;
    size_t c4, c8;
    if (solve_planned(&base, v0, 0.25, &p4, &c4) || solve_planned(&base, v0, 0.125, &p8, &c8)) {
      printf("%9.3g reference failed\n", ev);
      continue;
    }
    double href = p8.u_min_m + (p8.u_min_m - p4.u_min_m) / 3.0;
    double muref = p8.mu + (p8.mu - p4.mu) / 3.0;
    double secs;
    if (auto_point(&base, v0, &pa, &secs)) {
      printf("%9.3g automatic point failed\n", ev);
      continue;
    }
    printf("%9.3g %7.0f | %11.5g %9.2e %9.2e | %11.5g %+10.2e %+10.2e %9.2e %8.2f\n", ev, gE, href,
           fabs(p8.u_min_m - href) / href, fabs(p8.mu - muref) / muref, pa.u_min_m,
           pa.u_min_m / href - 1.0, pa.mu / muref - 1.0, pa.error_estimate, secs);
    fflush(stdout);
  }
}

static void rigid(void) {
  vl_contact_config base = elastic_film(1e13, 0.1);
  double v0 = 1.0;
  double h = 4.894 * base.eta_pa_s * 0.5 * v0 * base.radius_m / base.load_n_per_m;
  vl_point pa;
  double secs;
  printf("rigid cylinder (E0 1e13 Pa, eta 0.1 Pa s, v0 1 m/s): Martin h = %.5g m\n", h);
  if (auto_point(&base, v0, &pa, &secs)) {
    printf("  automatic point failed\n");
    return;
  }
  printf("  automatic: h = %.5g m (%+.3f %%), mu = %.5g, estimate %.2e, %.2f s\n", pa.u_min_m,
         100.0 * (pa.u_min_m / h - 1.0), pa.mu, pa.error_estimate, secs);
}

/* The soft film at eta v0 on layouts of resolutions r[0..n-1]. */
static void levels(double ev, int n, char **r) {
  vl_contact_config base = elastic_film(3.6e6, 0.01);
  double v0 = ev / base.eta_pa_s;
  for (int i = 0; i < n; i++) {
    vl_point p;
    size_t cells = 0;
    double t0 = now_s();
    int rc = solve_planned(&base, v0, atof(r[i]), &p, &cells);
    printf("r %-7s cells %5zu %s h %.6e m mu %.6e x_min %+.4e m iterations %ld %.2f s\n", r[i],
           cells, rc ? "FAILED" : "ok", p.u_min_m, p.mu, p.x_min_film_m, p.iterations,
           now_s() - t0);
    fflush(stdout);
  }
}

int main(int argc, char **argv) {
  const char *only = "soft,rigid";
  int quick = 0;
  if (argc > 3 && !strcmp(argv[1], "--levels")) {
    levels(atof(argv[2]), argc - 3, argv + 3);
    return 0;
  }
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--only") && i + 1 < argc)
      only = argv[++i];
    else if (!strcmp(argv[i], "--quick"))
      quick = 1;
    else {
      fprintf(stderr, "usage: auto_numerics [--only soft,rigid] [--quick]\n");
      return 2;
    }
  }
  if (strstr(only, "rigid")) rigid();
  if (strstr(only, "soft")) soft(quick);
  return 0;
}
