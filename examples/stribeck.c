/* A Stribeck curve of a soft elastohydrodynamic film, configured in code
 * and run by the library's sweep (viscolube.h, sweep.h): automatic numerics,
 * an error estimate on every point, through the public API only.
 *
 *   stribeck [DATABASE]    (default: the program's database)
 *
 * A smooth cylinder (R 10 mm, 1000 N/m) on the shipped model rubber in the
 * model fluid of 0.1 Pa s, from 1e-3 to 1 m/s: the film grows with speed
 * (soft EHL, h ~ (eta v0)^0.6-0.7); the friction also carries the rubber's
 * hysteresis, largest near v0 tau ~ a0 (tau = 0.1 s, a0 ~ 1.6 mm). Exit
 * status 0 when every point converged within its error target. */
#include <math.h>
#include <stdio.h>

#include "viscolube.h"

static void on_point(void *user, size_t i, size_t n, const vl_point *pt, const vl_contact *c) {
  (void)c, (void)n;
  int *bad = user;
  if (!pt->converged || !(pt->error_estimate <= 0.01)) (*bad)++;
  printf("%3zu %12.4g %12.6g %12.4g %10.2g %s\n", i, pt->v0_m_s, pt->mu, pt->u_min_m,
         pt->error_estimate, pt->converged ? "yes" : "NO");
}

int main(int argc, char **argv) {
  vl_error err = {{0}};
  vl_db *db = NULL;
  if (vl_db_open(argc > 1 ? argv[1] : NULL, &db, &err) != VL_OK) {
    fprintf(stderr, "stribeck: %s\n", err.msg);
    return 1;
  }
  vl_contact_config cfg;
  vl_contact_config_defaults(&cfg);
  vl_status st = vl_db_compound_get(db, "model-rubber", &cfg.rubber, &err);
  if (st == VL_OK) st = vl_db_fluid_get(db, "model-1e-1", &cfg.eta_pa_s, &err);
  vl_db_close(db);
  if (st != VL_OK) {
    fprintf(stderr, "stribeck: %s\n", err.msg);
    return 1;
  }
  cfg.radius_m = 0.01;
  cfg.load_n_per_m = 1000;
  vl_contact_numerics_defaults(false, true, &cfg); /* smooth and wet: the sweep plans its cells */
  enum { N = 7 };
  double v0[N];
  for (int i = 0; i < N; i++) /* 1e-3 ... 1 m/s in half decades */
    v0[i] = 1e-3 * pow(10.0, 0.5 * i);
  vl_point pts[N];
  vl_sweep_stats stats;
  int bad = 0;
  printf("%3s %12s %12s %12s %10s %s\n", "i", "v0_m_s", "mu", "u_min_m", "error_est", "conv");
  st = vl_sweep_run_auto(&cfg, NULL, N, v0, pts, on_point, &bad, &stats, &err);
  if (st != VL_OK) {
    fprintf(stderr, "stribeck: %s\n", err.msg);
    return 1;
  }
  printf("%zu converged, %zu failed, %ld Newton iterations\n", stats.converged, stats.failed,
         stats.newton_iterations);
  return bad ? 2 : 0;
}
