/* viscolube (private): the flow factors below their public part
 * (viscolube/flow_factors.h: the models, their names and the five factors
 * of smooth and patir-cheng). Here: any model with its table (for the
 * solver), the solver's combinations of the factors and patir-cheng's
 * nominal gap (for tests). The persson-emt table's own private functions
 * are in flow_factors_emt.h. */
#ifndef VISCOLUBE_FLOW_FACTORS_INTERNAL_H
#define VISCOLUBE_FLOW_FACTORS_INTERNAL_H

#include "viscolube/flow_factors.h"

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

#endif
