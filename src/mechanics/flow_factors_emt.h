/* viscolube (private): the persson-emt flow and shear-stress factors
 * (FLOW_FACTORS.md, model `persson-emt`).
 *
 * Persson's contact mechanics (MODEL.md section 4) fixes, at each average
 * separation u, the real contact area and the whole distribution P(g) of the
 * interfacial gaps; a 2-D Bruggeman effective medium of local conductance
 * g^3 on that distribution gives the five factors. They depend on the PSD
 * (and, phi_f only, on the film cut-off), never on the modulus, speed or
 * load, so they are tabulated once per surface in x = u/h_rms and cached.
 *
 * Inside, lengths are in units of h_rms. The table, its interpolant and its
 * continuations beyond x_min and X_MAX are described in flow_factors_emt.c.
 * A built table is immutable: evaluation is allocation free and thread
 * safe. The queries the program makes of a table (evaluation, h_rms, the
 * percolation point, freeing) are public, in viscolube/flow_factors.h; this
 * header holds building the table and looking at its nodes (for the
 * database and tests), the model's steps (for tests) and the serialisation
 * (for the database cache). */
#ifndef VISCOLUBE_FLOW_FACTORS_EMT_H
#define VISCOLUBE_FLOW_FACTORS_EMT_H

#include <stddef.h>

#include "viscolube/flow_factors.h"
#include "viscolube/roughness.h"
#include "viscolube/status.h"

/* The scene's default film cut-off (m): gaps below it are boundary contact
 * and carry no Couette shear (phi_f). */
#define VL_EMT_DEFAULT_FILM_CUTOFF_M VL_FILM_CUTOFF_DEFAULT_M

/* Version of the serialised table: like VL_PERSSON_FORMAT it names the byte
 * layout AND the build algorithm, so it MUST be bumped whenever
 * vl_emt_table_build's result can change (grids, repairs, bins, the medium,
 * node placement, psd.c's moments) as well as when the layout changes. */
#define VL_EMT_FORMAT 3

/* x = u/h_rms at the percolation of the contact (A/A0 = 1/2), where the
 * pressure flow stops. NaN on an invalid PSD. */
double vl_emt_percolation(const vl_psd *psd);

/* Builds the table for psd and film cut-off film_cutoff_m > 0 (m) at
 * n_points nodes (0: the default; else within [VL_EMT_MIN_N_POINTS,
 * VL_EMT_MAX_N_POINTS]), geometric in x from two decades below the
 * percolation point up to VL_EMT_X_MAX, the node nearest the percolation
 * point moved onto it. On success *out is owned by the caller
 * (vl_emt_table_free); on failure it is NULL and the status is VL_EINPUT or
 * VL_ENOMEM. */
vl_status vl_emt_table_build(const vl_psd *psd, double film_cutoff_m, size_t n_points,
                             vl_emt_table **out, vl_error *err);

/* Number of nodes; node k < size: its x, its factors (v, may be NULL) and
 * its A/A0 (area, may be NULL). Returns x. */
size_t vl_emt_table_size(const vl_emt_table *table);
double vl_emt_table_node(const vl_emt_table *table, size_t k, vl_flow_factor_values *v,
                         double *area);

/* The film cut-off (m) the table was built for. */
double vl_emt_table_film_cutoff(const vl_emt_table *table);

/* The factors at one separation, with what the model knows on the way. */
typedef struct {
  double x; /* u/h_rms */
  double phi_p, phi_s, phi_f, phi_fs, phi_fp;
  double area;    /* A/A0: the contact fraction (the delta at g = 0) */
  double s;       /* pc/|Er| at which Persson's separation is u (NaN for vl_emt_medium) */
  double reflect; /* mean of the binned gaps before the rescale over u (1 for vl_emt_medium) */
} vl_emt_point;

/* The effective medium on a discrete gap distribution: open gaps g[j] > 0
 * with masses m[j] >= 0 (j < n), plus the contact fraction `contact` at
 * g = 0; the masses and the contact should add up to 1. Lengths in units of
 * h_rms (so u = sum m g is also x). g_cut is the film cut-off in the same
 * units. Fills out (s = NaN, reflect = 1). Solves
 *   -contact + sum_j m_j (g_j^3 - c)/(g_j^3 + c) = 0
 * for c >= 0 (c = 0 when the left side is <= 0 at c = 0: percolated), then
 *   w_j = 2c/(g_j^3 + c),  u_w = sum m_j g_j w_j,
 *   phi_p = c/u^3, phi_fp = u_w/u, phi_s = x (1 - phi_fp),
 *   phi_fs = 3u sum_j m_j g_j (g_j - u_w)/(g_j^3 + c),
 *   phi_f = u sum_{g_j > g_cut} m_j/g_j.
 * VL_EINPUT when u is not positive and finite or a value is invalid. */
vl_status vl_emt_medium(size_t n, const double *g, const double *m, double contact, double g_cut,
                        vl_emt_point *out, vl_error *err);

/* The whole model at one x = u/h_rms > 0 (no table, no interpolation): the
 * nominal pressure, the gap distribution of FLOW_FACTORS.md with its two
 * repairs, and the medium. About 1-3 ms. VL_EINPUT / VL_ENOMEM. */
vl_status vl_emt_point_eval(const vl_psd *psd, double film_cutoff_m, double x, vl_emt_point *out,
                            vl_error *err);

/* Serialises a table into a malloc'd blob (*blob, *len; the caller free()s
 * it): portable little-endian, format VL_EMT_FORMAT, the fingerprint of the
 * PSD it was built from, its film cut-off and a checksum. VL_ENOMEM. */
vl_status vl_emt_table_serialize(const vl_emt_table *table, void **blob, size_t *len,
                                 vl_error *err);

/* Rebuilds a table from a blob of vl_emt_table_serialize for this psd and
 * film cut-off; the result answers every query bit for bit like the table
 * that was serialised. The blob is untrusted: its length, magic, format,
 * checksum, node count, the PSD fingerprint, h_rms and the percolation point
 * recomputed from psd (a few ms), the film cut-off, and every value (finite,
 * in range, zero pressure flow exactly up to the percolation point, contact
 * falling with x) are checked; the nodes follow from the percolation
 * point. On failure *out is NULL and the
 * status is VL_EINPUT (corrupt, stale, of another PSD or cut-off) or
 * VL_ENOMEM. */
vl_status vl_emt_table_deserialize(const vl_psd *psd, double film_cutoff_m, const void *blob,
                                   size_t len, vl_emt_table **out, vl_error *err);

#endif
