/* viscolube: flow and shear-stress factors of the averaged Reynolds equation.
 *
 * docs/MODEL.md sections 5 and 7 and docs/FLOW_FACTORS.md. With u the average
 * separation (the seed's u, the mean of the local film thickness), rubber and
 * fluid moving at +v0, only the rubber rough:
 *
 *   flux         J   = -(u^3 phi_p / (12 eta)) dpf/dx + (v0/2) (u + h_rms phi_s)
 *   wall shear   tau = (phi_f + phi_fs) eta v0 / u - phi_fp (u/2) dpf/dx
 *
 * The factors are a pluggable model chosen by the scene:
 *
 * smooth       phi_p = 1, phi_s = 0, phi_f = 1, phi_fs = 0, phi_fp = 1.
 *
 * patir-cheng  Patir & Cheng (J. Lubr. Technol. 100 (1978) 12; 101 (1979) 220),
 *              isotropic Gaussian roughness (gamma = 1), sigma = h_rms. Their
 *              argument is the nominal separation H = h/sigma, mapped to u by
 *              the rigid Gaussian gap u/sigma = H Phi(H) + phi(H) (standard
 *              normal cdf and pdf), then
 *                phi_p = Phi_x(H) (h/u)^3, phi_s = Phi_s(H), phi_f = Phi_f(H) u/h,
 *                phi_fs = Phi_fs(H) u/h,   phi_fp = Phi_fp(H) h/u.
 *              Outside the published fit ranges the functions are continued so
 *              that every factor is C1 in u on (0, inf) (the Jacobian uses the
 *              derivatives); src/flow_factors.c lists each continuation:
 *              - Phi_x: cubic a H^2 + b H^3 on 0 < H < 0.5, 0 for H <= 0
 *                (flow stops at the percolation H = 0, u/sigma = 0.3989);
 *              - Phi_s: the same kind of cubic on 0 < H < 0.5 (the fit's slope
 *                is infinite at H = 0), a C1 blend of its two branches on
 *                4.5 <= H <= 5.5, 0 for H <= 0;
 *              - Phi_fs: Phi_fs/H is the same kind of cubic on 0 < H < 0.5
 *                (it goes like H^1.31 there, with a non-Lipschitz slope), and
 *                a cubic Hermite tail from H = 7 to 0 at H = 8;
 *              - Phi_fp: cubic on 0 < H < 0.75 (the fit is negative below
 *                H = 0.51), 0 for H <= 0;
 *              - Phi_f/H (the Couette shear per unit film): its limit at
 *                H = 0, joined C1 by a quadratic on -0.5 <= H <= 0.
 *              For u/sigma <= 0.198 (H <= -0.5) all factors are constants or
 *              proportional to u: no pressure or shear flow, phi_fp = 0 and
 *              phi_f = 1.648 u/sigma.
 *
 * Evaluation is allocation free and thread safe; the first patir-cheng call
 * builds a small table for H(u) once (pthread_once). */
#ifndef VISCOLUBE_FLOW_FACTORS_H
#define VISCOLUBE_FLOW_FACTORS_H

#include <stddef.h>

#include "viscolube/roughness.h"
#include "viscolube/status.h"

typedef enum {
  VL_FLOW_FACTORS_SMOOTH = 0,
  VL_FLOW_FACTORS_PATIR_CHENG,
  VL_FLOW_FACTORS_PERSSON_EMT /* Persson's gap distribution + 2-D Bruggeman medium, from a
                               * table built once per surface (docs/FLOW_FACTORS.md) */
} vl_flow_factor_kind;

/* The persson-emt table of one surface and film cut-off (opaque; built and
 * cached by the database, vl_db_flow_table). */
typedef struct vl_emt_table vl_emt_table;

/* The default film cut-off of persson-emt (m): gaps narrower than a few
 * molecular layers are boundary contact, whose shear is sigma_s, and carry
 * no Couette shear (phi_f). */
#define VL_FILM_CUTOFF_DEFAULT_M 1e-9

/* The five factors (dimensionless), or their derivatives d/du (1/m). */
typedef struct {
  double phi_p, phi_s, phi_f, phi_fs, phi_fp;
} vl_flow_factor_values;

/* The combinations the Reynolds solver and the friction integral use; they
 * stay finite as u -> 0 for patir-cheng (for smooth, couette = 1/u):
 *   conductance_m3 = u^3 phi_p            (flux = -conductance/(12 eta) dpf/dx)
 *   shear_flow     = phi_s                (flux += (v0/2) h_rms phi_s)
 *   couette_per_m  = (phi_f + phi_fs)/u   (shear += eta v0 couette_per_m)
 *   poiseuille_m   = phi_fp u             (shear -= (1/2) poiseuille_m dpf/dx)
 * or their derivatives d/du (units divided by m). */
typedef struct {
  double conductance_m3, shear_flow, couette_per_m, poiseuille_m;
} vl_flow_terms;

/* The five factors at average separation u_m for rms roughness hrms_m, and
 * their derivatives d/du in *d when d != NULL (v must not be NULL).
 * patir-cheng: u_m <= 0 gives the limit u -> 0+ (and its right derivative);
 * hrms_m <= 0 gives the smooth factors (the limit sigma -> 0); a NaN input
 * gives NaN outputs. Every output is finite for finite inputs. persson-emt
 * needs its table (vl_flow_factors_eval_table): here it gives NaN. */
void vl_flow_factors_eval(vl_flow_factor_kind kind, double u_m, double hrms_m,
                          vl_flow_factor_values *v, vl_flow_factor_values *d);

/* The factors of any model: smooth and patir-cheng as vl_flow_factors_eval
 * (table unused); persson-emt from table (built for the surface's h_rms
 * h0) at x = u/hrms_m, so that a locally rescaled roughness (viscous
 * flattening: hrms_m = s h0) keeps the model's scale invariance. persson-emt
 * without a table, or hrms_m <= 0, gives NaN. */
void vl_flow_factors_eval_table(vl_flow_factor_kind kind, const vl_emt_table *table, double u_m,
                                double hrms_m, vl_flow_factor_values *v, vl_flow_factor_values *d);

/* The solver's combinations (vl_flow_terms) and, when d != NULL, their
 * derivatives d/du. Same conventions as vl_flow_factors_eval; for the smooth
 * model (or hrms_m <= 0) u_m must be > 0 (the smooth Couette shear 1/u has
 * no limit at u = 0). */
void vl_flow_factors_terms(vl_flow_factor_kind kind, double u_m, double hrms_m, vl_flow_terms *t,
                           vl_flow_terms *d);

/* patir-cheng's mapping: the nominal separation h (m) of the mean planes for
 * average separation u_m > 0 and hrms_m > 0, i.e. the root of
 * u = h Phi(h/sigma) + sigma phi(h/sigma); dh/du in *dh_du when non-NULL.
 * Works for every u in (0, inf) (h -> -inf as u -> 0, h -> u for u >> sigma);
 * error below 1e-14 sigma (1 + |h|/sigma). u_m <= 0 returns -INFINITY (dh_du =
 * +INFINITY); NaN or hrms_m <= 0 returns NaN. */
double vl_flow_factors_nominal_gap(double u_m, double hrms_m, double *dh_du);

/* "smooth", "patir-cheng" or "persson-emt" (the scene's spelling);
 * "unknown" otherwise. */
const char *vl_flow_factors_name(vl_flow_factor_kind kind);

/* Parses a scene's model name (exact, as above). VL_EINPUT with the valid
 * names in err for anything else (or NULL). */
vl_status vl_flow_factors_parse(const char *name, vl_flow_factor_kind *kind, vl_error *err);

/* ---- persson-emt: the table of one surface ------------------------------
 * The factors depend on the PSD only (and, phi_f only, on the film
 * cut-off), never on modulus, speed or load: they are tabulated once per
 * surface in x = u/h_rms (src/mechanics/flow_factors_emt.c gives the model
 * step by step). A built table is immutable; evaluation is allocation free
 * and thread safe. */

/* Table sizes vl_emt_table_build accepts (0 asks for the default). */
#define VL_EMT_DEFAULT_N_POINTS 100
#define VL_EMT_MIN_N_POINTS 80
#define VL_EMT_MAX_N_POINTS 120

/* The table's top, x = u/h_rms; above it the Tripp forms take over. */
#define VL_EMT_X_MAX 30.0

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
void vl_emt_table_free(vl_emt_table *table);

/* The five factors at average separation u_m (m) and, when d != NULL,
 * their derivatives d/du (1/m), from one C1 interpolant (v must not be
 * NULL). Inside the table: monotone cubic Hermite in ln x; above it the
 * Tripp forms; below it the continuations of flow_factors_emt.c. u_m <= 0
 * gives the limit u -> 0+ (and its right derivative); NaN gives NaN. Every
 * output is finite for finite u_m. */
void vl_emt_table_eval(const vl_emt_table *table, double u_m, vl_flow_factor_values *v,
                       vl_flow_factor_values *d);

/* Number of nodes; node k < size: its x, its factors (v, may be NULL) and
 * its A/A0 (area, may be NULL). Returns x. */
size_t vl_emt_table_size(const vl_emt_table *table);
double vl_emt_table_node(const vl_emt_table *table, size_t k, vl_flow_factor_values *v,
                         double *area);

/* h_rms (m), the film cut-off (m) and the percolation point x of the table. */
double vl_emt_table_hrms(const vl_emt_table *table);
double vl_emt_table_film_cutoff(const vl_emt_table *table);
double vl_emt_table_percolation(const vl_emt_table *table);

#endif
