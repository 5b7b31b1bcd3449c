/* viscolube: a lubricated smooth ball, isoviscous and elastic (soft EHL;
 * docs/POINT_CONTACT.md section 9). Private to the library: the tests and
 * the benchmark call it; the users' view (scenes) does not yet.
 *
 * A rigid ball of radius R at rest on an elastic half-space (reduced
 * modulus Er = E/(1 - nu^2)) whose surface moves at +v0 along x (the inlet
 * at x < 0, docs/MODEL.md section 1), under the load W, fully flooded with
 * a Newtonian fluid of viscosity eta. On the half plane y >= 0 (symmetry):
 *   div(u^3/(12 eta) grad p) = (v0/2) du/dx,   p = 0 on the outer boundary,
 *   dp/dy = 0 on y = 0, Reynolds cavitation (p >= 0, the flow's residual
 *   >= 0, their product 0), u = h0 + (x^2 + y^2)/(2R) + w[p], \int p = W.
 * Finite volumes on a tensor-product grid graded towards the contact's rim,
 * the dense influence matrix of Love's rectangles (each cell and its
 * mirror image), KINSOL with the dense Jacobian (LAPACK's LU) on the
 * pressures and h0. */
#ifndef VISCOLUBE_POINT_EHL_H
#define VISCOLUBE_POINT_EHL_H

#include <stddef.h>

#include "viscolube/status.h"

typedef struct {
  double radius_m, load_n; /* ball radius, total load */
  double e_pa, nu;         /* the rubber's Young's modulus and Poisson ratio */
  double eta_pa_s;         /* viscosity */
  double v0_m_s;           /* sliding speed (entrainment v0/2) */
  /* the domain in units of the Hertz radius a: x in [x_in, x_out], y in [0, y_max] */
  double x_in, x_out, y_max;
  /* cell size (units of a) where the grid is finest (the rim zones) and
   * where it is coarsest; the size grows linearly at rate `growth` per unit
   * of distance from the rim zones. Halving fine, coarse and growth halves
   * every cell (a nested refinement for Richardson) */
  double h_fine, h_coarse, growth;
  double tolerance; /* max norm of the scaled residual */
  int max_iterations;
} vl_point_ehl_config;

typedef struct {
  int converged;
  long iterations;       /* Newton steps (all attempts) */
  long continuation_steps; /* steps down in speed from a thicker film */
  size_t nx, ny;         /* cells */
  double a_m, p0_pa;     /* Hertz radius and peak pressure (dry, same load) */
  double h_c_m;          /* film at the centre (x = y = 0) */
  double h_min_m;        /* minimum film */
  double x_min_m, y_min_m; /* where it is */
  double h_min_axis_m;   /* minimum film on the centre line y = 0 */
  double h0_m;           /* the rigid approach unknown */
  double load_error;     /* (\int p dA - W)/W */
  double residual;       /* max norm of the scaled residual at the end */
  double mu_Rf, mu_Sf_couette, mu_Sf_poiseuille, mu_Sf;
  double x_centroid_m;   /* pressure centroid */
  double t_influence_s, t_solve_s;
} vl_point_ehl_result;

/* The defaults: domain [-3, 1.6] x [0, 1.8] a, h_fine 0.02, h_coarse 0.2,
 * growth 1, tolerance 1e-9, 60 iterations (the physical inputs zero). */
void vl_point_ehl_config_defaults(vl_point_ehl_config *cfg);

/* Solves one point from the dry Hertz pressure (or from guess_p, the
 * pressure in p0 on the same cells, when not NULL, with the rigid approach
 * *guess_h0 in units of a^2/R). On return res holds the figures; when p_out
 * is not NULL it receives a malloc'd copy of the pressures (p0) and
 * *h0_out the approach (a^2/R), for continuation. VL_EINPUT naming the
 * field, VL_ENOMEM, VL_ENOCONV (res filled, converged = 0). */
vl_status vl_point_ehl_solve(const vl_point_ehl_config *cfg, const double *guess_p,
                             const double *guess_h0, vl_point_ehl_result *res, double **p_out,
                             double *h0_out, vl_error *err);

/* Hamrock and Dowson's isoviscous-elastic fits for a ball (k = 1):
 * E' = 2E/(1 - nu^2), U = eta (v0/2)/(E' R), W' = W/(E' R^2),
 * h_min/R = 7.43 U^0.65 W'^-0.21 (1 - 0.85 e^{-0.31}),
 * h_c/R = 7.32 U^0.64 W'^-0.22 (1 - 0.72 e^{-0.28}). */
void vl_point_ehl_hamrock_dowson(const vl_point_ehl_config *cfg, double *h_min_m, double *h_c_m);

/* Test hook: the largest difference between the analytic Jacobian and
 * forward differences (relative to max(1, |entry|)) at the Hertz pressure
 * lifted to the central film `lift` (units of a^2/R). */
double vl_point_ehl_jacobian_check(const vl_point_ehl_config *cfg, double lift);

#endif
