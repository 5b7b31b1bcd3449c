/* A dry smooth steel ball sliding on a rubber (point_contact.h): the
 * rolling friction of its viscoelastic hysteresis over speed, through the
 * public API only (viscolube.h).
 *
 *   ball [DATABASE]    (default: the program's database, $VISCOLUBE_DB, ...)
 *
 * Each speed is solved from the previous solution (continuation). Prints
 * the curve with the contact area, then the pressure along the sliding
 * direction at the fastest speed. Exit status 0 when every point
 * converged. */
#include <stdio.h>
#include <stdlib.h>

#include "viscolube.h"

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
  vl_point_contact *c = NULL;
  if (vl_point_contact_create(&cfg, &c, &err) != VL_OK) {
    fprintf(stderr, "ball: %s\n", err.msg);
    return 1;
  }
  printf("Hertz (relaxed): a0 = %.4g m, p0 = %.4g Pa\n", vl_point_contact_a0(c),
         vl_point_contact_p0(c));
  printf("%12s %12s %10s %14s\n", "v0_m_s", "mu", "converged", "area_m2");
  int failed = 0;
  for (double v0 = 1e-5; v0 <= 1.01e-1; v0 *= 10.0) {
    vl_point pt;
    vl_ball_result ball;
    st = vl_point_contact_solve(c, v0, &pt, &ball, &err);
    if (st != VL_OK && st != VL_ENOCONV) {
      fprintf(stderr, "ball: %s\n", err.msg);
      failed++;
      break;
    }
    failed += !pt.converged; /* a failed point is flagged, never a silent 0 */
    printf("%12.4g %12.6g %10s %14.4g\n", v0, pt.mu, pt.converged ? "yes" : "NO",
           ball.contact_area_m2);
  }
  size_t n = vl_point_contact_cells(c);
  double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y), *p = malloc(n * sizeof *p);
  if (x && y && p) {
    vl_fields2d f = {.x_m = x, .y_m = y, .p_c_pa = p};
    vl_point_contact_fields(c, &f);
    printf("pressure along the sliding direction (the row nearest y = 0):\n");
    for (size_t k = 0; k < n; k++)
      if (y[k] == y[0] && p[k] > 0.0) printf("  x = %10.4g m  p = %10.4g Pa\n", x[k], p[k]);
  }
  free(x), free(y), free(p);
  vl_point_contact_free(c);
  return failed ? 1 : 0;
}
