/* viscolube: random surface roughness and Persson's contact mechanics.
 *
 * PSD: isotropic, C(q) in m^4, either self-affine
 *   C(q) = C0 (q/q0)^(-2(1+H)) for q0 <= q <= q1, 0 elsewhere,
 * with h_rms^2 = 2 pi \int q C(q) dq, or tabulated (q_k, C_k) points
 * interpolated as a power law between points (linear in log-log), zero
 * outside [q_first, q_last].
 *
 * Persson (MODEL.md section 4): with s = pc/|Er| (dimensionless),
 *   A/A0 = erf( s / (2 sqrt(g)) ),   g = (pi/4) \int q^3 C dq,
 *   u(s) = (sqrt(pi)/2) \int dq q^2 C(q) w(q) E1( (w(q) s)^2 ),
 *   w(q) = ( pi \int_{q0}^{q} q'^3 C dq' )^(-1/2).
 * u(s) is monotone decreasing; the table stores it once per surface and its
 * inverse s(u) is a monotone C1 interpolant with its derivative. */
#ifndef VISCOLUBE_ROUGHNESS_H
#define VISCOLUBE_ROUGHNESS_H

#include <stddef.h>

#include "viscolube/status.h"

typedef enum { VL_PSD_SELF_AFFINE = 0, VL_PSD_TABULATED = 1 } vl_psd_kind;

typedef struct {
  vl_psd_kind kind;
  double hurst;      /* self-affine only, 0 < H <= 1 */
  double q0, q1;     /* 1/m: the band (tabulated: first and last q) */
  double c0;         /* m^4, self-affine prefactor derived from h_rms */
  double hrms_m;     /* rms height */
  size_t n;          /* tabulated points (0 for self-affine) */
  double *q;         /* owned, n values, strictly increasing */
  double *C;         /* owned, n values, > 0 */
} vl_psd;

/* Self-affine PSD from H, q0, q1, h_rms; validates (0 < H <= 1, 0 < q0 < q1,
 * h_rms > 0, all finite) and derives C0. */
vl_status vl_psd_init_self_affine(vl_psd *psd, double hurst, double q0, double q1,
                                  double hrms_m, vl_error *err);

/* Tabulated PSD, copying the arrays; validates (n >= 2, q strictly increasing
 * and > 0, C > 0, finite) and derives h_rms. */
vl_status vl_psd_init_tabulated(vl_psd *psd, size_t n, const double *q, const double *C,
                                vl_error *err);

void vl_psd_free(vl_psd *psd);

double vl_psd_value(const vl_psd *psd, double q);
/* \int_{qa}^{qb} q^k C(q) dq, exact for both kinds (clipped to the band). */
double vl_psd_moment(const vl_psd *psd, int k, double qa, double qb);
double vl_psd_hrms(const vl_psd *psd);      /* sqrt(2 pi \int q C dq) */
double vl_psd_rms_slope(const vl_psd *psd); /* sqrt(<|grad h|^2>) = sqrt(2 pi \int q^3 C dq) */

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
