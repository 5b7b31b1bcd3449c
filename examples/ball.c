/* A dry smooth steel ball sliding on a rubber (point_contact.h): the
 * rolling friction of its viscoelastic hysteresis over speed, through the
 * public API only (viscolube.h).
 *
 *   ball [DATABASE]    (default: the program's database, $VISCOLUBE_DB, ...)
 *
 * First one point solved by hand (the Hertz contact at rest), then the
 * curve by vl_point_contact_sweep, which plans each point's cells around
 * its contact and estimates its error; the pressure along the sliding
 * direction at the fastest speed comes from the sweep's callback. Exit
 * status 0 when every point converged. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "viscolube.h"

#define POINTS 5

/* Keeps the pressure along y ~ 0 of the last point (the sweep's callback). */
static void on_point(void *user, size_t i, size_t total, const vl_point *pt,
                     const vl_point_contact *c) {
  (void)pt;
  if (i + 1 != total || !c) return;
  size_t n = vl_point_contact_cells(c);
  double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y), *p = malloc(n * sizeof *p);
  if (x && y && p) {
    vl_fields2d f = {.x_m = x, .y_m = y, .p_c_pa = p};
    vl_point_contact_fields(c, &f);
    printf("pressure along the sliding direction at the last speed (the row nearest y = 0):\n");
    for (size_t k = 0; k < n; k++)
      if (y[k] == y[0] && p[k] > 0.0) printf("  x = %10.4g m  p = %10.4g Pa\n", x[k], p[k]);
  }
  free(x), free(y), free(p);
  *(int *)user = 1;
}

int main(int argc, char **argv) {
  vl_error err = {{0}};
  vl_db *db = NULL;
  if (vl_db_open(argc > 1 ? argv[1] : NULL, &db, &err) != VL_OK) {
    fprintf(stderr, "ball: %s\n", err.msg);
    return 1;
  }
  vl_point_contact_config cfg;
  vl_point_contact_config_defaults(&cfg); /* the dry ball's numerics */
  vl_status st = vl_db_compound_get(db, "model-rubber", &cfg.rubber, &err);
  vl_db_close(db);
  if (st != VL_OK) {
    fprintf(stderr, "ball: %s\n", err.msg);
    return 1;
  }
  cfg.radius_x_m = cfg.radius_y_m = 0.0095; /* a 19 mm ball */
  cfg.load_n = 3.0;
  /* one point by hand: at rest, the relaxed Hertz contact */
  vl_point_contact *c = NULL;
  if (vl_point_contact_create(&cfg, &c, &err) != VL_OK) {
    fprintf(stderr, "ball: %s\n", err.msg);
    return 1;
  }
  vl_point pt;
  st = vl_point_contact_solve(c, 0.0, &pt, &err);
  double ax, by, p0;
  double er0 = vl_prony_e0(&cfg.rubber) / (1.0 - cfg.rubber.nu * cfg.rubber.nu);
  vl_hertz_ellipse(cfg.radius_x_m, cfg.radius_y_m, cfg.load_n, er0, &ax, &by, &p0);
  printf("%s at rest: contact area %.4g m2 (Hertz %.4g), peak %.4g Pa (Hertz %.4g); a0 = %.4g m, "
         "p0 = %.4g Pa\n",
         vl_geometry_name(pt.ball.geometry), pt.ball.contact_area_m2, 3.14159265 * ax * by,
         pt.peak_pressure_pa, p0, vl_point_contact_a0(c), vl_point_contact_p0(c));
  vl_point_contact_free(c);
  if (st != VL_OK) {
    fprintf(stderr, "ball: %s\n", err.msg);
    return 1;
  }
  /* the curve */
  double v[POINTS];
  vl_point pts[POINTS];
  for (size_t i = 0; i < POINTS; i++) /* 1e-3 ... 0.1 m/s: the rise and fall of mu */
    v[i] = 1e-3 * pow(10.0, 0.5 * (double)i);
  vl_sweep_stats stats;
  int shown = 0;
  if (vl_point_contact_sweep(&cfg, NULL, POINTS, v, pts, on_point, &shown, &stats, &err) != VL_OK) {
    fprintf(stderr, "ball: %s\n", err.msg);
    return 1;
  }
  printf("%12s %12s %10s %14s %10s\n", "v0_m_s", "mu", "converged", "area_m2", "err_est");
  for (size_t i = 0; i < POINTS; i++) /* a failed point is flagged, never a silent 0 */
    printf("%12.4g %12.6g %10s %14.4g %9.2g%%\n", v[i], pts[i].mu, pts[i].converged ? "yes" : "NO",
           pts[i].ball.contact_area_m2, 100.0 * pts[i].error_estimate);
  return stats.failed || !shown ? 1 : 0;
}
