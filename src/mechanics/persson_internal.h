/* viscolube (private): Persson's u(s) table below its public part
 * (viscolube/persson.h: the type, freeing, s(u) and A/A0, which the
 * program reads from a table of vl_db_persson_table). Here: building the
 * table, its serialisation (for the database cache, src/db/db_persson.c),
 * and the queries the solver and the tests use. */
#ifndef VISCOLUBE_PERSSON_INTERNAL_H
#define VISCOLUBE_PERSSON_INTERNAL_H

#include <stddef.h>

#include "viscolube/persson.h"
#include "viscolube/roughness.h"
#include "viscolube/status.h"

/* Builds the table of u(s) on n_table log-spaced s (n_table >= 64; 0 picks a
 * default) spanning from u ~ 50 h_rms down to u ~ 1e-3 h_rms, with a C1
 * monotone interpolant of ln s as a function of u and exact asymptotic
 * continuation outside. Returns VL_ENOMEM / VL_EINPUT. */
vl_status vl_persson_build(const vl_psd *psd, size_t n_table, vl_persson **out, vl_error *err);

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
/* g = (pi/4) \int q^3 C dq (so G = g |Er|^2), and u* = sqrt(pi) \int q^2 C w dq:
 * the decay length of s(u) ~ exp(-u/u*) at large u. */
double vl_persson_g(const vl_persson *table);
double vl_persson_ustar(const vl_persson *table);
double vl_persson_hrms(const vl_persson *table);

#endif
