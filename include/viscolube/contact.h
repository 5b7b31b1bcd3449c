/* viscolube: one operating point of a rigid smooth cylinder on a (rough)
 * viscoelastic half-space, solved by KINSOL (Newton, dense Jacobian).
 *
 * Frame and signs (docs/MODEL.md section 1): cylinder frame, rubber moving at +v0
 * along x, inlet at x < 0. Friction components are positive when they resist
 * the motion.
 *
 * Unknowns are dimensionless: x/a0, p/p0, u/(a0^2/R), with a0, p0 the Hertz
 * half-width and peak pressure of the low-speed (relaxed) modulus.
 *   smooth, dry: pressure p_i on the grid + rigid approach h0; the contact
 *                condition p >= 0, u >= 0, p u = 0 by a (slightly smoothed)
 *                Fischer-Burmeister function;
 *   rough, dry:  separation u_i + h0, with pc = |Er(wH)| s(u) from Persson.
 *   rough, wet:  plus the fluid pressure pf_i, scaled by its current
 *                magnitude; the averaged Reynolds equation in conservative
 *                finite-volume form (second-order upwind Couette flux,
 *                centred Poiseuille flux), pf = 0 at both ends of the
 *                domain, and the Reynolds cavitation condition pf >= 0,
 *                dJ/dx >= 0, pf dJ/dx = 0 by Fischer-Burmeister.
 *   smooth, wet: the same Reynolds equation and cavitation condition, but
 *                no contact unknowns (a smooth film stays open at any
 *                v0 > 0: pc = 0): pf_i and the rigid approach only, with a
 *                film that must stay positive (a Newton step that closes it
 *                is shortened). The Reynolds rows are flux imbalances
 *                divided by their sensitivity to pf_i (a pressure
 *                measure, as the complementarity needs, free of any length
 *                scale: stiff solids, whose inlet length sqrt(2 R h) far
 *                exceeds a0, are as well posed as soft ones). A fresh start
 *                (first solve, or a continuation step that failed) solves
 *                on a chain of half-size grids first: cavitation is a free
 *                boundary that one Newton step moves by about one cell.
 *                The coarsest level starts from Martin's rigid solution or,
 *                for soft EHL, from Hertz.
 * The rigid approach h0 (the displacement kernel's free constant) is the
 * load-balance unknown; the separation at the pressure centroid u0 is
 * reported afterwards (docs/MODEL.md section 3: measured to converge better than
 * u0 as the unknown). */
#ifndef VISCOLUBE_CONTACT_H
#define VISCOLUBE_CONTACT_H

#include <stdbool.h>
#include <stddef.h>

#include "viscolube/flattening.h"
#include "viscolube/flow_factors.h"
#include "viscolube/persson.h"
#include "viscolube/results.h"
#include "viscolube/rheology.h"
#include "viscolube/shear_law.h"
#include "viscolube/status.h"

typedef enum {
  VL_LINSOL_LAPACK = 0, /* LAPACK dgetrf/dgetrs on the SUNDIALS dense matrix */
  VL_LINSOL_SUNDIALS,   /* SUNLinSol_Dense (SUNDIALS' own dense LU) */
  VL_LINSOL_SCHUR       /* rough wet contacts: the Reynolds rows (a tridiagonal block in pf)
                         * eliminated first, LAPACK LU of the (N+1)^2 Schur complement, the
                         * residual checked against the full matrix (plain LAPACK when that
                         * fails). On a dry smooth contact: the cells out of contact solved
                         * row by row, LAPACK LU of the cells in contact only (the reduced,
                         * active-set system). Plain LAPACK on every other contact. The
                         * default. */
} vl_linear_solver;

/* Numerics: every default and limit of the grid, the domain and the
 * Newton solve is defined here, in the solver layer that owns them; the
 * scene parser (scene.h), the friction and compare commands and the tests
 * take theirs from these (vl_contact_numerics_defaults). */

/* Newton iterations a solve may take. A film lifting off from mixed to full
 * lubrication within one step of a sweep (u_min x35 on a 5 nm surface) took
 * 92 iterations on a uniform grid and 110-128 on graded ones; at 100 such a
 * point failed, and the sweep after it. Raising the cap from 100 to 200
 * turned 25 of the hard-case matrix's failed wet rough points (16 of them
 * on graded grids) into converged ones (tests/hard); points that converge
 * within 100 iterations are unchanged. */
#define VL_NEWTON_MAX_ITERATIONS 200

/* Smallest grid: vl_contact_create takes 8 cells (the least its stencils
 * are tested at: tests/hard probes that edge); a scene and the command line
 * ask for at least 16, so that the dry domain's contact (2 a0 of 3) spans
 * the 8 cells VL_ASSUME_GRID wants in the pressure zone. */
#define VL_CONTACT_MIN_GRID 8
#define VL_GRID_MIN 16

/* Largest solver grid: the dense matrices grow as the square of the cells
 * (56 bytes per cell squared: 15 GB at the limit). A graded grid may start
 * from far more uniform cells, since they are merged. A scene's uniform
 * grid stops at VL_GRID_UNIFORM_MAX (3.7 GB of matrices); larger ones take
 * a graded inlet (grid_growth > 1). */
#define VL_CONTACT_MAX_CELLS 16384
#define VL_CONTACT_MAX_GRID_GRADED 262144
#define VL_GRID_UNIFORM_MAX 8192
#define VL_GRID_GRADED_MAX VL_CONTACT_MAX_GRID_GRADED

/* Largest growth ratio of a graded grid (vl_contact_config.grid_growth; 1 or
 * less: uniform). */
#define VL_GRID_GROWTH_MAX 2.0

/* Largest uniform grid under an explicit cell layout
 * (vl_contact_config.cell_spans): its Toeplitz coefficients and their
 * prefix sums take 32 bytes per cell (64 MB at the limit), and a
 * viscoelastic kernel is refilled at every speed at about 2e7 coefficients
 * per second and Prony term. */
#define VL_CONTACT_MAX_GRID_LAYOUT 2097152

/* Where a graded grid (vl_contact_config.grid_growth) starts to coarsen: the
 * relaxed Hertz contact ends at x = -a0, and rough or viscoelastic pressure
 * tails reach a little beyond. */
#define VL_GRADE_START_A0 2.0

/* Numerics of a dry contact: symmetric about the axis, so that an elastic
 * contact has exactly zero rolling friction on the grid and small
 * viscoelastic shifts are resolved. */
#define VL_DRY_GRID 512
#define VL_DRY_DOMAIN_MIN_A0 -1.5
#define VL_DRY_DOMAIN_MAX_A0 1.5
#define VL_DRY_TOLERANCE 1e-9

/* Numerics of wet contacts, from the accuracy study (bench/, README
 * "Accuracy and cost"): the cheapest setting with mu within 1 % of a
 * reference at N 1536 / inlet 32 a0 over the fig05, fig10 and real-rubber
 * sweeps. A lubricated contact needs room for the inlet meniscus and the
 * film build-up upstream of the contact (docs/MODEL.md section 5). The inlet must
 * hold the film's inlet zone at the top of the Stribeck curve (fig05 at
 * v0 eta = 1 Pa m: 6.1 % / 1.5 % short with 5 / 12 a0 against 20 a0); the
 * grid then resolves the contact (N 512: fig10 1.9 %); the tolerance does
 * not move mu between 1e-3 and 1e-9, 1e-6 keeps a margin on the load
 * balance. */
#define VL_WET_DOMAIN_MIN_A0 -24.0
#define VL_WET_DOMAIN_MAX_A0 1.6
#define VL_WET_GRID 768
#define VL_WET_TOLERANCE 1e-6
/* Rough wet contacts take a graded inlet (vl_contact_config.grid_growth):
 * uniform cells of a0/30 near the contact (as grid 768 on [-24, 1.6] a0
 * gives), merged into cells growing by 5 % upstream of -2 a0, on an inlet of
 * 96 a0; about 200 cells in all. From the study with graded grids (bench/,
 * docs/NUMERICS.md, the accuracy study): against a reference with a0/60 cells, a
 * 192 a0 inlet and growth 1.02, mu is within 0.75 % on fig05, fig10 and the
 * real rubber, where the uniform 768 / 24 a0 grid was 1.2-1.6 % off (its
 * inlet too short: mu converges like 1/X in the inlet length). */
#define VL_WET_ROUGH_DOMAIN_MIN_A0 -96.0
#define VL_WET_ROUGH_GRID 2928 /* 97.6 a0 / (a0/30) */
#define VL_WET_GRID_GROWTH 1.05

/* Which body moves through the contact (docs/MODEL.md section 11). Both are
 * solved in the frame of the contact, the fluid entering from x < 0. */
typedef enum {
  /* The paper's: the rubber (and the fluid it drags) moves at +v0 under the
   * rigid curved body; its macroscopic deformation carries the Prony memory
   * (rolling friction mu_Rc, mu_Rf); friction is the force on the rigid body.
   * The default: zero in a zeroed configuration. */
  VL_MOVING_RUBBER = 0,
  /* Seals, wipers: the rubber part (its profile f(x)) is at rest and a flat
   * rigid rough counter-surface slides under it at +v0. The macroscopic
   * deformation is static: elastic with the relaxed modulus (no memory, no
   * Prony kernel); the asperity state is as with VL_MOVING_RUBBER (the
   * counter-surface's asperities sweep the rubber at v0: |Er(wH)|); the
   * Couette flux is the counter-surface's; the friction is the tangential
   * force on the flat counter-surface, mu = mu_Sc + mu_Sf, and the rolling
   * terms do not apply (vl_point.rolling_na). */
  VL_MOVING_COUNTERFACE
} vl_moving;

/* Largest slope of a tabulated profile in the pressure zone before a point
 * warns (the half-space model of docs/MODEL.md section 3 wants small
 * slopes), in radians. */
#define VL_PROFILE_SLOPE_MAX 0.3

typedef struct {
  vl_prony rubber;  /* n_terms = 0: elastic with E = e_inf_pa */
  vl_moving moving; /* VL_MOVING_RUBBER (0) or VL_MOVING_COUNTERFACE */
  double radius_m;
  double load_n_per_m;
  double sigma_s_pa; /* shear stress in the real contact area; 0 = off */
  /* sigma_s as a law of the sliding speed v0 (shear_law.h, at the
   * contact's temperature and viscosity), used instead of sigma_s_pa when
   * not NULL; not owned, must outlive the contact. sigma_s does not enter
   * the solution, only mu_Sc = sigma_s(v0) (1/fN) int A/A0 dx. */
  const vl_shear_law *shear_law;
  const vl_persson *roughness;      /* NULL = smooth (hard contact); not owned */
  double eta_pa_s;                  /* fluid viscosity; 0 = dry (no fluid unknowns at all) */
  vl_flow_factor_kind flow_factors; /* with roughness; smooth surfaces use smooth */
  /* persson-emt: the factor table of the surface of roughness (same h_rms;
   * not owned, must outlive the contact); NULL for the other models */
  const vl_emt_table *flow_table;
  size_t grid; /* cells of the uniform grid on the domain (the resolution) */
  /* Graded inlet (rough contacts only; <= 1: uniform grid): upstream of
   * x = -VL_GRADE_START_A0 a0 the uniform cells are merged into cells that
   * grow by this ratio towards the inlet end (an odd number of uniform cells
   * each, so that every node sits on a node of the uniform grid and the
   * influence coefficients stay exact sums of the uniform ones). The contact
   * keeps the uniform resolution; the long inlet a lubricated contact needs
   * costs tens of cells instead of hundreds. The last cell may end up to
   * one uniform cell beyond x_min_a0. */
  double grid_growth;
  /* Where the graded inlet starts, x = -grade_start_a0 a0 (0: the default
   * VL_GRADE_START_A0; a lip's or a table's contact may reach further
   * upstream, vl_contact_numerics_follow_profile). */
  double grade_start_a0;
  /* An explicit cell layout (NULL: the uniform or graded grid above): cell
   * k is cell_spans[k] consecutive cells of the uniform grid of `grid` cells
   * on the domain, odd (so that its node is a uniform node and its influence
   * coefficients exact sums of the uniform ones), summing to `grid`; n_cells
   * of them, at most VL_CONTACT_MAX_CELLS, on any contact. Copied by
   * vl_contact_create. The automatic sweep (sweep.h) lays cells out
   * this way: fine where the solution changes fast (the edges of the
   * contact, a film's outlet constriction), coarse elsewhere. */
  const size_t *cell_spans;
  size_t n_cells;
  double x_min_a0, x_max_a0; /* domain in units of a0 (the relaxed Hertz half-width, however
                              * stiff the solid): smooth wet contacts need an inlet of tens
                              * of vl_contact_inlet_length_m beyond the contact */
  double tolerance;          /* scaled residual norm for convergence */
  int max_iterations;        /* Newton iterations per solve (0 = VL_NEWTON_MAX_ITERATIONS) */
  vl_linear_solver linear_solver;
  /* Viscous flattening of the asperities (seed Appendix C; NULL = off).
   * The PSD both the contact and the flow factors see becomes
   * epsilon_f(u, v0) C(q) at each node, u the local separation:
   * pc(u) -> s pc(u/s), A/A0 at pc -> A/A0 at pc/s, h_rms -> s h_rms in the
   * flow factors and the Couette film, s = sqrt(epsilon_f) (the solver
   * derives the scaling), with the chain rule through epsilon_f(u) in the
   * Jacobian. Needs roughness and a fluid (eta > 0), and flattening_psd, the
   * PSD the roughness table was built from (same h_rms): vl_contact_create
   * refuses it otherwise. Both are read only during vl_contact_create: the
   * contact builds and owns its own evaluator (whose speed and viscosity it
   * sets as it solves), so nothing outside it changes under it. */
  const vl_flattening_config *flattening;
  const vl_psd *flattening_psd;
  /* Fluid pressure at the inlet end (x_min) and at the outlet end (x_max) of
   * the domain (Pa, >= 0, wet contacts only; 0 and 0: the paper's flooded
   * contact). A seal's sealed pressure on its oil side (docs/MODEL.md
   * section 12): the rubber's surface on that side of the tip x = 0 is
   * bathed in it, so the deformation and the load balance count the fluid
   * pressure above it there (the ambient: p_inlet_pa for x < 0, p_outlet_pa
   * for x > 0), and fN is the lip's force above that ambient. */
  double p_inlet_pa, p_outlet_pa;
  /* The rubber's profile f(x) (docs/MODEL.md section 13; NULL: the
   * cylinder's parabola x^2/(2 R)): profile_points >= 3 points (x_m, z_m),
   * any order, distinct x, the height above the counter-surface of the
   * undeformed rubber. Shifted so that its lowest point sits at x = 0, z = 0
   * (the tip), interpolated by cubic Hermite with three-point slopes (exact
   * for a parabola), continued straight beyond its ends. profile_mirror:
   * f(-x) (an instroke). radius_m still sets the scales (a0, the domain):
   * give the tip radius. Copied by vl_contact_create. */
  const double *profile_x_m, *profile_z_m;
  size_t profile_points;
  bool profile_mirror;
  /* A parametric lip instead (docs/MODEL.md section 13; lip_tip_radius_m 0:
   * none; not with a table): the tip's parabola f = x^2/(2 r), r the tip
   * radius, between the tangent points x = -r tan(oil) and r tan(air), and
   * straight flanks beyond: of slope tan(lip_oil_angle_rad) on the oil side
   * x < 0 (the inlet of an outstroke), tan(lip_air_angle_rad) on the air
   * side, value and slope continuous at the joins; both angles in
   * (0, pi/2). profile_mirror swaps the sides (an instroke). radius_m
   * still sets the scales: the study layer gives it the radius of the
   * cylinder whose dry contact is as wide as the lip's. */
  double lip_tip_radius_m, lip_oil_angle_rad, lip_air_angle_rad;
  /* An imposed static contact pressure instead of a profile (docs/MODEL.md
   * section 14; NULL: none): static_points >= 3 points (x_m, p_pa), any
   * order, distinct x, p >= 0, zero at the lowest and the highest x
   * (the contact's edges), linear between. The rubber's shape is not
   * given: it is the one on which the dry smooth contact has this
   * pressure (f = -w[p_s] over the span where p_s > 0, w the elastic
   * displacement with the relaxed modulus, continued straight beyond
   * with the slope at each edge); the film's change of the pressure
   * deforms the rubber elastically around that state. The table is
   * shifted so that the middle of its span sits at x = 0; profile_mirror
   * mirrors it. Moving counter-surface only, no table or lip; load_n_per_m
   * must be the table's integral and radius_m sets the scales
   * (vl_contact_static_scales, private, gives both). Copied by
   * vl_contact_create. */
  const double *static_x_m, *static_p_pa;
  size_t static_points;
} vl_contact_config;

/* Sets the numerics of cfg (grid, grid_growth, domain, tolerance,
 * max_iterations, linear_solver) to the defaults of a contact with or
 * without roughness and fluid: dry VL_DRY_GRID on [VL_DRY_DOMAIN_MIN_A0,
 * VL_DRY_DOMAIN_MAX_A0], tolerance VL_DRY_TOLERANCE; wet VL_WET_TOLERANCE and
 * a long inlet, graded on a rough surface (VL_WET_ROUGH_GRID on
 * [VL_WET_ROUGH_DOMAIN_MIN_A0, VL_WET_DOMAIN_MAX_A0], growth
 * VL_WET_GRID_GROWTH) and uniform on a smooth one (VL_WET_GRID on
 * [VL_WET_DOMAIN_MIN_A0, VL_WET_DOMAIN_MAX_A0]); VL_NEWTON_MAX_ITERATIONS,
 * VL_LINSOL_SCHUR. The other fields are left alone. */
void vl_contact_numerics_defaults(bool rough, bool wet, vl_contact_config *cfg);

/* Zeroes cfg and sets the numerics of a dry contact
 * (vl_contact_numerics_defaults); the caller sets the rubber, the geometry
 * and the rest. */
void vl_contact_config_defaults(vl_contact_config *cfg);

/* The result types (vl_point, vl_fields, vl_regime) are in results.h. */

typedef struct vl_contact vl_contact;

/* Allocates the solver (KINSOL, matrices, work) for cfg; no allocation happens
 * inside the Newton loop afterwards. The initial guess is Hertz (relaxed). */
vl_status vl_contact_create(const vl_contact_config *cfg, vl_contact **out, vl_error *err);
void vl_contact_free(vl_contact *c);

/* Solves at sliding speed v0 (m/s) starting from the current state (the
 * previous solution, or Hertz). On return *pt is always filled; pt->converged
 * says whether the solve met the tolerance. When it did not, the internal
 * state is restored to what it was before the call and VL_ENOCONV is
 * returned (err says why); never NaN. */
vl_status vl_contact_solve(vl_contact *c, double v0_m_s, vl_point *pt, vl_error *err);

/* Copies the current fields (n = grid) into f (arrays allocated by caller). */
void vl_contact_fields(const vl_contact *c, vl_fields *f);

/* The test aids (Jacobian checks, face fluxes, influence coefficients,
 * cells, cost counters) are private: src/solver/contact_test.h. */

size_t vl_contact_grid(const vl_contact *c); /* cells (fewer than cfg.grid when graded) */
double vl_contact_a0(const vl_contact *c);   /* m */
double vl_contact_p0(const vl_contact *c);   /* Pa */

/* The numerics a contact solves with, as created (defaults resolved): for
 * the record of a run (a manifest), not to configure another. */
typedef struct {
  size_t grid;               /* cells of the uniform grid on the domain (cfg.grid) */
  size_t cells;              /* solver cells (fewer when graded) */
  double grid_growth;        /* <= 1: uniform */
  double x_min_a0, x_max_a0; /* the domain, in a0 */
  double tolerance;          /* scaled residual norm */
  int max_iterations;        /* Newton iterations per solve */
  const char *linear_solver; /* "lapack", "sundials" or "schur" */
} vl_contact_numerics_used;
void vl_contact_numerics_of(const vl_contact *c, vl_contact_numerics_used *out);

#endif
