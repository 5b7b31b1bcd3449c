/* viscolube: one operating point of a rigid smooth ball (or ellipsoid)
 * sliding on a viscoelastic half-space, dry, or a ball lubricated by a
 * Newtonian fluid (eta_pa_s > 0: soft EHL, docs/POINT_CONTACT.md section
 * 9): the point contact (docs/POINT_CONTACT.md).
 *
 * Frame and signs as the line contact's (docs/MODEL.md section 1): the
 * ball at rest, the rubber moving at +v0 along x, the inlet at x < 0;
 * friction positive when it resists the motion. The undeformed gap is
 * f = x^2/(2 Rx) + y^2/(2 Ry); the load W in newtons. Sliding along x
 * keeps the contact symmetric in y: the solver works on y >= 0 (the
 * mirror image enters the influence coefficients).
 *
 * Unknowns are dimensionless: lengths in a0, pressures in p0, the gap in
 * a0^2/Re, with Re = sqrt(Rx Ry) and the Hertz scales of the relaxed
 * reduced modulus Er0 = E0/(1 - nu^2):
 *   a0 = (3 W Re / (4 Er0))^(1/3),   p0 = 3 W / (2 pi a0^2)
 * (a ball's Hertz radius and peak pressure). On square cells of a0/r
 * (r = cells_per_a0) the pressure is piecewise constant, the gap
 * u = h0 + f + w collocated at the cell centres, w from Love's rectangle
 * and the steady-sliding Prony memory (docs/POINT_CONTACT.md section 3),
 * the hard contact min(p, u) = 0 per cell and the load balance for the
 * rigid approach h0: the line contact's active-set Newton (KINSOL with
 * full steps, the dense Jacobian reduced to the cells in contact), with
 * Fischer-Burmeister and a line search where full steps do not converge. */
#ifndef VISCOLUBE_POINT_CONTACT_H
#define VISCOLUBE_POINT_CONTACT_H

#include <stddef.h>

#include "viscolube/flow_factors.h"
#include "viscolube/persson.h"
#include "viscolube/results.h"
#include "viscolube/rheology.h"
#include "viscolube/status.h"
#include "viscolube/sweep.h"

/* Numerics of a dry ball (measured in docs/POINT_CONTACT.md section 5):
 * square cells of a0/VL_BALL_CELLS_PER_A0 on [-L, L] x [0, L] a0,
 * L = VL_BALL_DOMAIN_A0 (the relaxed Hertz circle, the largest contact of
 * a viscoelastic ball, with a margin). The x domain is symmetric about the
 * axis with a node on it, so that an elastic ball has exactly zero rolling
 * friction on the grid. */
#define VL_BALL_CELLS_PER_A0 20
#define VL_BALL_DOMAIN_A0 1.25
#define VL_BALL_TOLERANCE 1e-9

/* Fewest cells per a0 (the Hertz circle then spans 8 cells across) and the
 * most cells in all: the dense matrices take about 28 bytes per cell
 * squared (1.1 GB at the limit). */
#define VL_BALL_MIN_CELLS_PER_A0 4
#define VL_BALL_MAX_CELLS 6144

typedef struct {
  vl_prony rubber;   /* n_terms = 0: elastic with E = e_inf_pa */
  double radius_x_m; /* radius of curvature along the sliding direction */
  double radius_y_m; /* across it (a ball: radius_y_m = radius_x_m) */
  double load_n;     /* normal load W */
  double eta_pa_s;   /* the fluid's viscosity; 0: dry. A lubricated ball (not an
                      * ellipsoid) is solved on its own graded cells: cells_per_a0
                      * sets their finest size 1/cells_per_a0 a0 and y_max_a0 their
                      * zones and domain (units of y_max_a0/VL_BALL_DOMAIN_A0 a0;
                      * docs/POINT_CONTACT.md section 9); x_half_a0 is not used */
  /* A rough surface (NULL: smooth): Persson's contact pressure in every
   * cell at its mean separation, the averaged Reynolds equation with the
   * flow factors (docs/POINT_CONTACT.md section 10); dry when eta_pa_s is
   * 0. A ball only, solved on the lubricated ball's graded cells. Not owned. */
  const vl_persson *roughness;
  vl_flow_factor_kind flow_factors; /* with roughness and a fluid */
  const vl_emt_table *flow_table;   /* persson-emt: the surface's table */
  double sigma_s_pa;   /* shear stress on the contact area (rough: the real area); 0 = off */
  double cells_per_a0; /* resolution r: square cells of a0/r */
  double x_half_a0;    /* domain [-x_half, x_half] along x, in a0 */
  double y_max_a0;     /* domain [0, y_max] across, in a0 */
  double tolerance;    /* max norm of the dimensionless residual */
  int max_iterations;  /* Newton iterations per solve (0: VL_NEWTON_MAX_ITERATIONS) */
} vl_point_contact_config;

/* Zeroes cfg and sets its numerics to the defaults above (a ball's domain;
 * an ellipsoid's is stretched along its Hertz ellipse by the caller). */
void vl_point_contact_config_defaults(vl_point_contact_config *cfg);

typedef struct vl_point_contact vl_point_contact;

/* Allocates the solver for cfg; no allocation inside the Newton loop
 * afterwards. The state is the Hertz (relaxed) guess. VL_EINPUT naming the
 * field for a bad configuration, VL_ENOMEM. */
vl_status vl_point_contact_create(const vl_point_contact_config *cfg, vl_point_contact **out,
                                  vl_error *err);
void vl_point_contact_free(vl_point_contact *c);

/* Solves at sliding speed v0 >= 0 (m/s; 0: the relaxed elastic contact)
 * from the current state (the last solution, else Hertz), then from
 * Hertz. On return *pt is filled, with the ball's own quantities (contact
 * area, extents) in pt->ball; pt->converged says whether the solve met the
 * tolerance. When it did not, the state is the one before the call and
 * VL_ENOCONV is returned (err says why); never NaN. */
vl_status vl_point_contact_solve(vl_point_contact *c, double v0_m_s, vl_point *pt, vl_error *err);

/* The fields of the solved half y >= 0, SI, cell by cell (cell
 * k = ix ny + iy: y runs fastest; a lubricated ball's cells are not
 * evenly spaced), arrays of vl_point_contact_cells(c) values owned by the
 * caller (any may be NULL). p_f_pa: the fluid pressure (0 when dry), p_c_pa
 * the contact pressure (0 when lubricated: the smooth solids do not touch). */
typedef struct {
  double *x_m, *y_m, *p_c_pa, *u_m, *p_f_pa;
} vl_fields2d;
void vl_point_contact_fields(const vl_point_contact *c, vl_fields2d *f);

size_t vl_point_contact_cells(const vl_point_contact *c); /* on the solved half */

/* Hertz's contact ellipse of an elastic half-space (reduced modulus er_pa)
 * under a rigid ellipsoid of radii Rx, Ry and load W: the semi-axes along
 * x and y (m) and the peak pressure (Pa; p0_pa may be NULL), from the
 * complete elliptic integrals (Johnson, Contact Mechanics, section 4.2).
 * VL_EINPUT unless every input is positive. */
vl_status vl_hertz_ellipse(double radius_x_m, double radius_y_m, double load_n, double er_pa,
                           double *ax_m, double *by_m, double *p0_pa);

/* Called once per speed of a curve, in order, with the contact that solved
 * the point (its fields: vl_point_contact_fields), NULL when the point did
 * not converge. */
typedef void (*vl_point_contact_callback)(void *user, size_t index, size_t total,
                                          const vl_point *pt, const vl_point_contact *contact);

/* A curve: the points v0_m_s[0..n-1] of the contact base describes, each
 * on its own cells (automatic numerics, docs/POINT_CONTACT.md section 5:
 * the domain around the contact ellipse Hertz predicts with the rubber's
 * modulus at the frequency v0/a, VL_BALL_CELLS_PER_A0 cells across its
 * shorter semi-axis, a larger domain when the contact reaches its edge),
 * solved from the Hertz guess (else by continuation from the previous
 * point's speed on the same cells), with an error estimate (the point on
 * cells twice as wide) and refinement to opt->target_error (every cell
 * size divided by sqrt 2, up to opt->max_refinements times).
 * opt->keep_numerics: base's cells and domain for every point (each still
 * estimated). opt may be NULL (the defaults of sweep.h). Each point is
 * reported in out[i] and through cb (may be NULL). Returns VL_OK even when
 * points failed (stats says how many); an error only for a bad base
 * (VL_EINPUT naming the field) or when out of memory. */
vl_status vl_point_contact_sweep(const vl_point_contact_config *base, const vl_auto_options *opt,
                                 size_t n, const double *v0_m_s, vl_point *out,
                                 vl_point_contact_callback cb, void *user, vl_sweep_stats *stats,
                                 vl_error *err);
double vl_point_contact_a0(const vl_point_contact *c); /* m */
double vl_point_contact_p0(const vl_point_contact *c); /* Pa */

#endif
