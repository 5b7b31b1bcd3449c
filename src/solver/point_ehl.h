/* viscolube: a lubricated smooth ball, isoviscous, on an elastic or
 * viscoelastic half-space (soft EHL;
 * docs/POINT_CONTACT.md section 9). Private to the library: the point
 * contact calls it for a ball with a fluid (point_contact_wet.c), the tests
 * and the benchmark directly.
 *
 * A rigid ball of radius R at rest on a viscoelastic half-space (the
 * steady-sliding Prony memory of docs/POINT_CONTACT.md section 3; Hertz's
 * scales from the relaxed reduced modulus Er0 = E0/(1 - nu^2)) whose
 * surface moves at +v0 along x (the inlet
 * at x < 0, docs/MODEL.md section 1), under the load W, fully flooded with
 * a Newtonian fluid of viscosity eta. On the half plane y >= 0 (symmetry):
 *   div(u^3/(12 eta) grad p) = (v0/2) du/dx,   p = 0 on the outer boundary,
 *   dp/dy = 0 on y = 0, Reynolds cavitation (p >= 0, the flow's residual
 *   >= 0, their product 0), u = h0 + (x^2 + y^2)/(2R) + w[p], \int p = W.
 * Finite volumes on a tensor-product grid graded towards the contact's rim,
 * the dense influence matrix of Love's rectangles (each cell and its
 * mirror image) filtered along x by each Prony term's memory, KINSOL with the dense Jacobian
 * (LAPACK's LU) on the pressures and h0. */
#ifndef VISCOLUBE_POINT_EHL_H
#define VISCOLUBE_POINT_EHL_H

#include <stddef.h>

#include "viscolube/flow_factors.h"
#include "viscolube/persson.h"
#include "viscolube/rheology.h"
#include "viscolube/status.h"

typedef struct {
  double radius_m, load_n; /* ball radius, total load */
  vl_prony rubber;         /* n_terms 0: elastic with E = e_inf_pa */
  double eta_pa_s;         /* viscosity (0: dry, with roughness only) */
  /* A rough surface (NULL: smooth): in every cell Persson's contact
   * pressure at the mean separation u (the asperity modulus |Er| at the
   * contact's frequency), the averaged Reynolds equation with the flow
   * factors of the surface; the unknowns are then the total pressure
   * (docs/POINT_CONTACT.md section 10) */
  const vl_persson *roughness;
  vl_flow_factor_kind flow_factors;
  const vl_emt_table *flow_table;
  double sigma_s_pa; /* shear stress on the real contact area (rough) */
  double v0_m_s;     /* sliding speed (entrainment v0/2) */
  /* the domain in units of the Hertz radius a: x in [x_in, x_out], y in [0, y_max];
   * the zones of finest cells are placed in units of `unit` Hertz radii (1;
   * less for a viscoelastic rubber's contact shrunk by its speed) */
  double unit;
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
  long iterations;         /* Newton steps (all attempts) */
  long continuation_steps; /* steps down in speed from a thicker film */
  int from_start;          /* converged from the given start */
  size_t nx, ny;           /* cells */
  double a_m, p0_pa;       /* Hertz radius and peak pressure (dry, same load) */
  double h_c_m;            /* film at the centre (x = y = 0) */
  double h_min_m;          /* minimum film */
  double x_min_m, y_min_m; /* where it is */
  double h_min_axis_m;     /* minimum film on the centre line y = 0 */
  double h0_m;             /* the rigid approach unknown */
  double load_error;       /* (\int p dA - W)/W */
  double residual;         /* max norm of the scaled residual at the end */
  double mu_Rf, mu_Sf_couette, mu_Sf_poiseuille, mu_Sf;
  double mu_Rc, mu_Sc; /* the asperities' (rough; 0 when smooth) */
  double real_area_m2; /* the real contact area, both halves (rough) */
  /* the nominal contact's extents (rough): along x and across (both
   * halves), where the asperities' pressure exceeds 1 % of its peak */
  double contact_length_m, contact_breadth_m;
  double fluid_load_fraction;          /* \int p_f / W (1 when smooth) */
  double e_abs_pa;                     /* the asperity modulus |Er(v0/a)| (rough) */
  double x_centroid_m;                 /* pressure centroid */
  double h_centroid_m;                 /* film there (on y = 0) */
  double p_max_pa, x_pmax_m, y_pmax_m; /* the largest pressure and where */
  double dissipation_w;                /* viscous dissipation in the film (both halves) */
  double hysteresis_w; /* the power the pressure puts into the rubber, v0 \int p dw/dx */
  double t_influence_s, t_solve_s;
} vl_point_ehl_result;

/* The fields of a solve (SI units; row-major in x: cell k = i ny + j,
 * y >= 0 only). */
typedef struct {
  size_t nx, ny;
  double *x_m, *y_m, *p_pa, *u_m; /* one allocation, at x_m; p_pa the fluid's */
  double *pc_pa;                  /* the asperities' (0 when smooth) */
  double h0_m;                    /* the rigid approach */
  double v0_m_s;                  /* the speed it was solved at */
} vl_point_ehl_map;
void vl_point_ehl_map_free(vl_point_ehl_map *map);

/* The defaults: unit 1, domain [-3, 1.6] x [0, 1.8] a, h_fine 0.02, h_coarse 0.2,
 * growth 1, tolerance 1e-9, 60 iterations (the physical inputs zero). */
void vl_point_ehl_config_defaults(vl_point_ehl_config *cfg);

/* Solves one point from `start` when not NULL (the same contact's
 * solution on other cells: a refinement's or a coarser estimate's start),
 * else (or when that fails) from the dry Hertz pressure lifted to Hamrock and
 * Dowson's central film, else from thicker films (a faster entrainment)
 * continued down to v0. On return res holds the figures and, when map is
 * not NULL, map the fields (the caller frees them with
 * vl_point_ehl_map_free). VL_EINPUT naming the field, VL_ENOMEM,
 * VL_ENOCONV (res and map filled, converged = 0). */
vl_status vl_point_ehl_solve(const vl_point_ehl_config *cfg, const vl_point_ehl_map *start,
                             vl_point_ehl_result *res, vl_point_ehl_map *map, vl_error *err);

/* Cells of cfg's grid (0 on allocation failure; cfg not checked). */
size_t vl_point_ehl_cells(const vl_point_ehl_config *cfg);

/* Hamrock and Dowson's isoviscous-elastic fits for a ball (k = 1):
 * E' = 2E/(1 - nu^2) (E the relaxed modulus E0 of a viscoelastic rubber), U = eta (v0/2)/(E' R), W'
 * = W/(E' R^2), h_min/R = 7.43 U^0.65 W'^-0.21 (1 - 0.85 e^{-0.31}), h_c/R = 7.32 U^0.64 W'^-0.22
 * (1 - 0.72 e^{-0.28}). */
void vl_point_ehl_hamrock_dowson(const vl_point_ehl_config *cfg, double *h_min_m, double *h_c_m);

/* Test hook: the influence matrix (units of a^2/R per p0) of the grid cfg
 * gives at the speed cfg->v0_m_s, malloc'd row-major n x n (target cell
 * k = i ny + j, i along x), with the cells' centres (units of a) in *xc
 * and *yc (malloc'd), their numbers in *nx, *ny; NULL on failure. */
double *vl_point_ehl_influence(const vl_point_ehl_config *cfg, size_t *nx, size_t *ny, double **xc,
                               double **yc);

/* Test hook: the largest difference between the analytic Jacobian and
 * forward differences (relative to max(1, |entry|)) at the Hertz pressure
 * lifted to the central film `lift` (units of a^2/R; nowhere below half of
 * it); NAN where the film closes at a step. */
double vl_point_ehl_jacobian_check(const vl_point_ehl_config *cfg, double lift);

#endif
