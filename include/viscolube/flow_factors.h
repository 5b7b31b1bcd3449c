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

/* The five factors at average separation u_m for rms roughness hrms_m, and
 * their derivatives d/du in *d when d != NULL (v must not be NULL).
 * patir-cheng: u_m <= 0 gives the limit u -> 0+ (and its right derivative);
 * hrms_m <= 0 gives the smooth factors (the limit sigma -> 0); a NaN input
 * gives NaN outputs. Every output is finite for finite inputs. persson-emt
 * needs its table (vl_emt_table_eval): here it gives NaN. */
void vl_flow_factors_eval(vl_flow_factor_kind kind, double u_m, double hrms_m,
                          vl_flow_factor_values *v, vl_flow_factor_values *d);

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

/* Table sizes vl_db_flow_table accepts (0 asks for the default). */
#define VL_EMT_DEFAULT_N_POINTS 100
#define VL_EMT_MIN_N_POINTS 80
#define VL_EMT_MAX_N_POINTS 120

/* The table's top, x = u/h_rms; above it the Tripp forms take over. */
#define VL_EMT_X_MAX 30.0

void vl_emt_table_free(vl_emt_table *table);

/* The five factors at average separation u_m (m) and, when d != NULL,
 * their derivatives d/du (1/m), from one C1 interpolant (v must not be
 * NULL). Inside the table: monotone cubic Hermite in ln x; above it the
 * Tripp forms; below it the continuations of flow_factors_emt.c. u_m <= 0
 * gives the limit u -> 0+ (and its right derivative); NaN gives NaN. Every
 * output is finite for finite u_m. */
void vl_emt_table_eval(const vl_emt_table *table, double u_m, vl_flow_factor_values *v,
                       vl_flow_factor_values *d);

/* h_rms (m) and the percolation point x of the table. */
double vl_emt_table_hrms(const vl_emt_table *table);
double vl_emt_table_percolation(const vl_emt_table *table);

#endif
