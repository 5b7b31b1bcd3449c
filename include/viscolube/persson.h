/* viscolube: Persson's contact mechanics of a randomly rough surface
 * (docs/MODEL.md section 4): the average separation u(s) and the real contact
 * area A/A0 as functions of s = pc/|Er|, tabulated once per surface.
 *
 * Persson (docs/MODEL.md section 4): with s = pc/|Er| (dimensionless),
 *   A/A0 = erf( s / (2 sqrt(g)) ),   g = (pi/4) \int q^3 C dq,
 *   u(s) = (sqrt(pi)/2) \int dq q^2 C(q) w(q) E1( (w(q) s)^2 ),
 *   w(q) = ( pi \int_{q0}^{q} q'^3 C dq' )^(-1/2).
 * u(s) is monotone decreasing; the table stores it once per surface and its
 * inverse s(u) is a monotone C1 interpolant with its derivative. */
#ifndef VISCOLUBE_PERSSON_H
#define VISCOLUBE_PERSSON_H

#include "viscolube/roughness.h"
#include "viscolube/status.h"

/* Persson's u(s) table for one surface; opaque. */
typedef struct vl_persson vl_persson;

/* Table sizes vl_db_persson_table accepts (0 asks for the default). */
#define VL_PERSSON_DEFAULT_N_TABLE 256
#define VL_PERSSON_MIN_N_TABLE 64
#define VL_PERSSON_MAX_N_TABLE 1000000

void vl_persson_free(vl_persson *table);

/* s(u) = pc/|Er| for a separation u (m), any real u (u <= 0 gives a large but
 * finite s, continuing C1), and ds/du (1/m) when dsdu != NULL. */
double vl_persson_pressure(const vl_persson *table, double u_m, double *dsdu);
/* A/A0 for s = pc/|Er|, and d(A/A0)/ds when dads != NULL. */
double vl_persson_area_ratio(const vl_persson *table, double s, double *dads);

#endif
