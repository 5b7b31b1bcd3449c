/* viscolube: what a solve produces, as plain data: one operating point
 * (vl_point), the fields on the grid (vl_fields) and the lubrication regime.
 * SI units throughout. The writers (output.h, plot.h) format these and need
 * nothing of the solver that fills them (contact.h). */
#ifndef VISCOLUBE_RESULTS_H
#define VISCOLUBE_RESULTS_H

#include <stdbool.h>
#include <stddef.h>

/* room for the solver's, the model checks' and the temperature warnings
 * together (256 could leave the last one out) */
#define VL_WARN_MAX 512

/* Result of one operating point, SI units. */
typedef struct {
  double v0_m_s;
  bool converged;
  long iterations; /* Newton iterations of this call (smooth wet: including a
                    * failed continuation attempt and coarse-grid starts) */
  double residual; /* final scaled residual norm (max norm) */
  double mu, mu_Rc, mu_Rf, mu_Sc, mu_Sf;
  double u_min_m, u_central_m; /* min separation; separation at the pressure centroid */
  double x_centroid_m;         /* pressure centroid (negative: inlet side) */
  double contact_width_m;      /* extent where pc >= 1% of its maximum */
  double fluid_load_fraction;  /* \int pf / fN */
  double u_min_over_h_rms;     /* film ratio lambda = u_min / h_rms; NAN on smooth surfaces */
  double load_error;           /* |\int p - fN| / fN */
  double E_wH_pa;              /* |Er(wH)| (rough) or Er of the relaxed state */
  double a_H_m;                /* Hertz half-width with |Er(wH)| */
  double Q;                    /* rolling number (wet rough only; else 0) */
  double peak_pressure_pa, x_peak_m;
  double mu_Sf_couette, mu_Sf_poiseuille; /* the two parts of mu_Sf */
  double x_min_film_m; /* where u is smallest (EHL constriction: outlet side, x > 0) */
  int regime;          /* vl_regime */
  double eps_f_min;    /* smallest epsilon_f(u) over the grid (viscous flattening);
                        * 1 when the effect is off */
  /* relative error of mu estimated from a coarser solve (sweep.h; the
   * point on cells three times as wide); NAN when none was made or it failed */
  double error_estimate;
  char warnings[VL_WARN_MAX]; /* ';'-separated, empty when none */
} vl_point;

/* Lubrication regime by the share of the load the fluid carries AND the
 * film ratio lambda = u_min / h_rms (docs/MODEL.md section 9): the two
 * must agree for a pure regime, else the point is mixed.
 *   hydrodynamic  fluid carries > 95 % of the load and lambda >= 3 (the
 *                 surfaces stand three rms heights apart where closest:
 *                 asperities seldom touch, Tallian's full-film ratio)
 *   boundary      fluid carries < 5 % and lambda < 3 (the solids carry the
 *                 load, and stand close enough for their asperities to
 *                 touch: a soft rubber in Persson contact sits at 1 to 2
 *                 h_rms)
 *   mixed         anything else, including a load share and a film that
 *                 disagree (the fluid carrying 99 % through a film of
 *                 0.6 h_rms, or 2 % across 3.8 h_rms)
 * On smooth surfaces (h_rms = 0, lambda undefined) the load share alone
 * decides. Failed points are "boundary" (they carry no solved state). */
typedef enum {
  VL_REGIME_DRY = 0,     /* no fluid */
  VL_REGIME_BOUNDARY,    /* fluid carries < 5 % of the load and lambda < 3 */
  VL_REGIME_MIXED,       /* neither */
  VL_REGIME_HYDRODYNAMIC /* > 95 % and lambda >= 3 */
} vl_regime;
#define VL_REGIME_LOAD_BOUNDARY 0.05     /* fluid load share below: boundary */
#define VL_REGIME_LOAD_HYDRODYNAMIC 0.95 /* above: hydrodynamic */
#define VL_REGIME_FILM_FULL 3.0          /* lambda at or above: hydrodynamic, below: boundary */

/* "dry", "boundary", "mixed", "hydrodynamic"; "?" for anything else. */
const char *vl_regime_name(int regime);

/* Fields on the grid, SI; arrays of length n owned by the caller. */
typedef struct {
  size_t n;
  double *x_m, *p_f_pa, *p_c_pa, *u_m, *area_ratio;
  double *film_fraction; /* theta: 1 in the full film, < 1 where cavitated; may be NULL */
  double *width_m;       /* cell widths (graded grids are not uniform); may be NULL */
} vl_fields;

#endif
