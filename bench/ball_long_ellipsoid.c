/* A long ellipsoid against the line contact (issue 35's check): in the
 * central strip of an ellipsoid elongated across the sliding direction
 * (Ry >> Rx), the contact tends to a cylinder's of radius Rx carrying the
 * strip's load per unit length. Both are solved dry and smooth on the
 * model rubber (one Prony term, Einf/E0 = 10) at the same speeds: the
 * ellipsoid by the point contact (the pressure of its row of cells next to
 * y = 0), the cylinder by the line contact (an independent code: its own
 * closed-form memory kernel), with the strip's load per length
 * \int p(x, 0) dx. Printed: the pressure centroid of the strip and of the
 * cylinder in units of the strip's half-length l, the cylinder's contact
 * half-width in l, and the cells along the strip's contact (2 l / h).
 *
 *   ball_long_ellipsoid [--ratio RY_OVER_RX] [--cells N_ACROSS_A] [--db PATH]
 *
 * (default ratio 30, 10 cells across the ellipse's semi-axis along x). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "viscolube.h"

#include "point_contact_internal.h"

int main(int argc, char **argv) {
  double ratio = 30.0, across = 10.0;
  const char *db_path = NULL;
  for (int i = 1; i < argc; i++) {
    const char *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(argv[i], "--ratio") && v)
      ratio = atof(v), i++;
    else if (!strcmp(argv[i], "--cells") && v)
      across = atof(v), i++;
    else if (!strcmp(argv[i], "--db") && v)
      db_path = v, i++;
    else {
      fprintf(stderr, "usage: ball_long_ellipsoid [--ratio RY_OVER_RX] [--cells N] [--db PATH]\n");
      return 2;
    }
  }
  char tmp[] = "/tmp/ball-ellipsoid-XXXXXX", db_tmp[64] = "";
  if (!db_path) {
    if (!mkdtemp(tmp)) return 6;
    snprintf(db_tmp, sizeof db_tmp, "%s/m.db", tmp);
    db_path = db_tmp;
  }
  vl_error err;
  vl_db *db = NULL;
  vl_prony rubber;
  int rc = 1;
  if (vl_db_open(db_path, &db, &err) != VL_OK ||
      vl_db_compound_get(db, "model-rubber", &rubber, &err) != VL_OK) {
    fprintf(stderr, "ball_long_ellipsoid: %s\n", err.msg);
    goto done;
  }
  double rx = 0.01, ry = ratio * rx, W = 10.0, er0 = vl_prony_e0(&rubber) / 0.75, ax, by;
  vl_hertz_ellipse(rx, ry, W, er0, &ax, &by, NULL);
  vl_point_contact_config pc;
  vl_point_contact_config_defaults(&pc);
  pc.rubber = rubber, pc.radius_x_m = rx, pc.radius_y_m = ry, pc.load_n = W;
  vl_point_contact *probe = NULL;
  if (vl_point_contact_create(&pc, &probe, &err) != VL_OK) goto fail;
  double a0 = vl_point_contact_a0(probe);
  vl_point_contact_free(probe);
  pc.cells_per_a0 = across / (ax / a0);
  pc.x_half_a0 = 1.3 * ax / a0, pc.y_max_a0 = 1.3 * by / a0;
  vl_point_contact *c = NULL;
  if (vl_point_contact_create(&pc, &c, &err) != VL_OK) goto fail;
  printf("Ry/Rx = %g: Hertz ellipse %.4g x %.4g mm (b/a = %.2f), %zu x %zu cells\n", ratio,
         ax * 1e3, by * 1e3, by / ax, c->nx, c->ny);
  printf("%10s %10s %12s %12s %12s %12s\n", "v0_m_s", "De_strip", "xc_strip/l", "xc_line/l",
         "len_line/l", "cells_2l");
  const double de[] = {0.1, 0.3, 1.0, 3.0, 10.0};
  for (size_t k = 0; k < sizeof de / sizeof de[0]; k++) {
    double v0 = de[k] * ax / rubber.tau_s[0];
    vl_point pt;
    if (vl_point_contact_solve(c, v0, &pt, &err) != VL_OK) goto fail;
    /* the strip: the row of cells next to y = 0 */
    double fn = 0.0, fx = 0.0, h = c->h * c->a0;
    for (size_t ix = 0; ix < c->nx; ix++) {
      double p = c->P[ix * c->ny] * c->p0, x = c->X[ix * c->ny] * c->a0;
      fn += p * h, fx += p * x * h;
    }
    vl_contact_config lc;
    vl_contact_config_defaults(&lc);
    lc.rubber = rubber, lc.radius_m = rx, lc.load_n_per_m = fn;
    lc.grid = 1024, lc.x_min_a0 = -1.5, lc.x_max_a0 = 1.5;
    vl_contact *line = NULL;
    vl_point lp;
    if (vl_contact_create(&lc, &line, &err) != VL_OK) goto fail;
    vl_status s = vl_contact_solve(line, v0, &lp, &err);
    vl_contact_free(line);
    if (s != VL_OK) goto fail;
    double l = 0.5 * pt.ball.contact_length_m; /* the strip's half-length */
    printf("%10.4g %10.4g %12.5f %12.5f %12.5f %12.1f\n", v0, v0 * rubber.tau_s[0] / l, fx / fn / l,
           lp.x_centroid_m / l, 0.5 * lp.contact_width_m / l, 2.0 * l / h);
  }
  vl_point_contact_free(c);
  rc = 0;
  goto done;
fail:
  fprintf(stderr, "ball_long_ellipsoid: %s\n", err.msg);
done:
  vl_db_close(db);
  if (db_tmp[0]) {
    unlink(db_tmp);
    rmdir(tmp);
  }
  return rc;
}
