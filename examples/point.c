/* One operating point, then a few more: a dry smooth cylinder sliding on a
 * compound of the material database (the rolling friction of its
 * viscoelastic hysteresis), through the public API only (viscolube.h).
 *
 *   point [DATABASE]    (default: the program's database, $VISCOLUBE_DB, ...)
 *
 * Each speed is solved from the previous solution (continuation), the way a
 * program that drives the solver itself would do it; the command line's
 * `friction` and `compare` do the same through vl_query_*. Exit status 0
 * when every point converged. */
#include <stdio.h>

#include "viscolube.h"

int main(int argc, char **argv) {
  vl_error err = {{0}};
  vl_db *db = NULL;
  if (vl_db_open(argc > 1 ? argv[1] : NULL, &db, &err) != VL_OK) {
    fprintf(stderr, "point: %s\n", err.msg);
    return 1;
  }
  vl_contact_config cfg;
  vl_contact_config_defaults(&cfg); /* a dry contact's numerics */
  vl_status st = vl_db_compound_get(db, "model-rubber", &cfg.rubber, &err);
  vl_db_close(db);
  if (st != VL_OK) {
    fprintf(stderr, "point: %s\n", err.msg);
    return 1;
  }
  cfg.radius_m = 0.01;      /* a 10 mm cylinder */
  cfg.load_n_per_m = 1000;  /* per metre of its length */
  cfg.sigma_s_pa = 0.0;     /* rolling friction only */
  vl_contact *c = NULL;
  if (vl_contact_create(&cfg, &c, &err) != VL_OK) {
    fprintf(stderr, "point: %s\n", err.msg);
    return 1;
  }
  int failed = 0;
  printf("%12s %12s %10s %12s\n", "v0_m_s", "mu", "converged", "half-width_m");
  for (double v0 = 1e-4; v0 <= 1.01; v0 *= 10.0) {
    vl_point pt;
    st = vl_contact_solve(c, v0, &pt, &err);
    if (st != VL_OK && st != VL_ENOCONV) {
      fprintf(stderr, "point: %s\n", err.msg);
      failed++;
      break;
    }
    failed += !pt.converged; /* a failed point is flagged, never a silent 0 */
    printf("%12.4g %12.6g %10s %12.4g\n", v0, pt.mu, pt.converged ? "yes" : "NO",
           pt.contact_width_m / 2.0);
  }
  vl_contact_free(c);
  return failed ? 2 : 0;
}
