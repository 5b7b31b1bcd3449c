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

/* Table sizes vl_persson_build accepts (0 asks for the default). */
#define VL_PERSSON_DEFAULT_N_TABLE 256
#define VL_PERSSON_MIN_N_TABLE 64
#define VL_PERSSON_MAX_N_TABLE 1000000

/* Builds the table of u(s) on n_table log-spaced s (n_table >= 64; 0 picks a
 * default) spanning from u ~ 50 h_rms down to u ~ 1e-3 h_rms, with a C1
 * monotone interpolant of ln s as a function of u and exact asymptotic
 * continuation outside. Returns VL_ENOMEM / VL_EINPUT. */
vl_status vl_persson_build(const vl_psd *psd, size_t n_table, vl_persson **out, vl_error *err);
void vl_persson_free(vl_persson *table);

/* Version of the serialised table (vl_persson_serialize). It names both the
 * byte layout and the build algorithm: a stored table is only as good as the
 * code that built it, so it MUST be bumped whenever vl_persson_build's
 * result can change (persson.c: node placement, quadrature rule, range,
 * constants; psd.c: the moments and h_rms it uses) as well as when the
 * layout changes. Stored tables of another version are then rebuilt. */
#define VL_PERSSON_FORMAT 1

/* Serialises a built table into a malloc'd blob (*blob, *len; the caller
 * free()s it): a portable little-endian record of the table (format
 * VL_PERSSON_FORMAT), a fingerprint of the PSD it was built from, and a
 * checksum. VL_ENOMEM. */
vl_status vl_persson_serialize(const vl_persson *table, void **blob, size_t *len, vl_error *err);

/* Rebuilds a table from a blob of vl_persson_serialize for the PSD psd (the
 * table keeps a private copy of it for vl_persson_separation_exact). The
 * result answers every query bit for bit like the table that was
 * serialised. The blob is untrusted (it may be truncated or hand-edited):
 * its length, magic, format, checksum, node count, the PSD fingerprint
 * (kind, parameters, points), h_rms and g recomputed from psd, and every
 * value (finite, nodes strictly monotone, the node abscissae consistent
 * with their separations) are checked. On success *out is owned by the
 * caller (vl_persson_free); on failure *out is NULL and the status is
 * VL_EINPUT (a blob that is not a valid table of this format: corrupt,
 * stale or of another PSD) or VL_ENOMEM. */
vl_status vl_persson_deserialize(const vl_psd *psd, const void *blob, size_t len, vl_persson **out,
                                 vl_error *err);

/* Number of nodes of the table. */
size_t vl_persson_size(const vl_persson *table);

/* u(s) in metres by direct quadrature (the defining integral; slow). */
double vl_persson_separation_exact(const vl_persson *table, double s);
/* u(s) in metres from the table. */
double vl_persson_separation(const vl_persson *table, double s);
/* s(u) = pc/|Er| for a separation u (m), any real u (u <= 0 gives a large but
 * finite s, continuing C1), and ds/du (1/m) when dsdu != NULL. */
double vl_persson_pressure(const vl_persson *table, double u_m, double *dsdu);
/* A/A0 for s = pc/|Er|, and d(A/A0)/ds when dads != NULL. */
double vl_persson_area_ratio(const vl_persson *table, double s, double *dads);
/* g = (pi/4) \int q^3 C dq (so G = g |Er|^2), and u* = sqrt(pi) \int q^2 C w dq:
 * the decay length of s(u) ~ exp(-u/u*) at large u. */
double vl_persson_g(const vl_persson *table);
double vl_persson_ustar(const vl_persson *table);
double vl_persson_hrms(const vl_persson *table);

#endif
