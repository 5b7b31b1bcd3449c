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

/* The strokes of a seal (a scene's [seal] stroke; docs/MODEL.md section 12):
 * outstroke, the rod moving from the oil side to the air side (the sealed
 * pressure at the film's inlet); instroke, from air to oil (the profile
 * mirrored, the sealed pressure at the outlet). */
typedef enum { VL_STROKE_NONE = 0, VL_STROKE_OUT, VL_STROKE_IN, VL_STROKE_BOTH } vl_stroke;

/* A seal's results at one speed, beside the point's own (which are those of
 * the outstroke for VL_STROKE_BOTH, else of its one stroke). */
typedef struct {
  int stroke;              /* vl_stroke; VL_STROKE_NONE: not a seal scene (no seal columns) */
  double friction_n_per_m; /* mu fN of the point's stroke */
  /* VL_STROKE_BOTH: the instroke at the same speed (flux along its own
   * motion, air to oil) */
  bool in_converged;
  double in_mu, in_mu_Sc, in_mu_Sf, in_u_min_m, in_flux_m2_s, in_friction_n_per_m;
  double in_u_central_m;
  /* the instroke's error estimates (of mu and of the flux, as the point's
   * error_estimate and flux_error_estimate) and its vl_accuracy */
  double in_error_estimate, in_flux_error_estimate;
  int in_accuracy;
  long in_iterations; /* the instroke's Newton iterations and final residual */
  double in_residual;
  char in_warnings[VL_WARN_MAX]; /* the instroke's, as vl_point.warnings */
  /* VL_STROKE_BOTH with a rod diameter D and a stroke length L: the fluid
   * carried out per cycle pi D L q_out/v and back pi D L q_in/v (m^3), and
   * whether the seal is tight (back >= out: 1, else 0); NAN and -1 when not
   * known (no D and L, or a stroke did not converge) */
  double volume_out_m3, volume_back_m3;
  int tight;
} vl_seal_result;

/* A scene swept both ways ([sweep] direction = both): the downward sweep's
 * point at the same speed, beside the point's own (the upward sweep's). */
typedef struct {
  bool swept; /* the downward sweep was run (else the rest is unset) */
  bool converged;
  double mu, error_estimate, u_min_m, fluid_load_fraction;
  /* the two sweeps found different states here: their mu differ by more
   * than the target and both estimates together (a fold of the curve: the
   * sweep up follows one branch, the sweep down the other) */
  bool two_states;
} vl_down_result;
/* The rigid body's shape (a scene's [contact] geometry): the paper's
 * infinitely long cylinder (contact.h, per unit length), or a ball or an
 * ellipsoid, a point contact (point_contact.h, total load). */
typedef enum { VL_GEOMETRY_CYLINDER = 0, VL_GEOMETRY_BALL, VL_GEOMETRY_ELLIPSOID } vl_geometry;

/* "cylinder", "ball", "ellipsoid"; "?" for anything else. */
const char *vl_geometry_name(int geometry);

/* A point contact's own results, beside the point's (whose mu, pressures,
 * centroid and films are those of the whole contact, both halves). */
typedef struct {
  int geometry;               /* vl_geometry; VL_GEOMETRY_CYLINDER (0): a line contact (no
                               * point-contact columns) */
  double contact_area_m2;     /* where the solids touch */
  double contact_length_m;    /* its extent along x (sliding), near y = 0 */
  double contact_breadth_m;   /* its widest extent along y */
  double y_min_film_m;        /* where u is smallest, across (>= 0; x: vl_point.x_min_film_m) */
  double y_peak_m;            /* where the pressure peaks, across (>= 0) */
  size_t cells_in_contact;    /* cells of the solved half y >= 0 in contact */
  double cells_per_a0;        /* the point's resolution (automatic numerics: planned per point) */
  double x_half_a0, y_max_a0; /* its domain [-x_half, x_half] x [0, y_max], in a0 */
} vl_ball_result;

/* Result of one operating point, SI units. */
typedef struct {
  double v0_m_s;
  bool converged;
  long iterations; /* Newton iterations of this call (smooth wet: including a
                    * failed continuation attempt and coarse-grid starts) */
  double residual; /* final scaled residual norm (max norm) */
  double mu, mu_Rc, mu_Rf, mu_Sc, mu_Sf;
  /* true when the rolling terms do not apply (a moving counter-surface,
   * contact.h VL_MOVING_COUNTERFACE: the rubber at rest has no macroscopic
   * hysteresis, and the flat counter-surface no slope for a pressure to push
   * on): mu_Rc and mu_Rf then hold 0, and writers show them as not
   * applicable (empty CSV cells, JSON null), not as computed zeros */
  bool rolling_na;
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
  /* fluid flux per unit length (m^2/s) through the film along +x (the
   * direction of the moving surface), through the face at the fluid
   * pressure's maximum (constant along the full film, docs/MODEL.md
   * section 12); 0 when dry */
  double flux_m2_s;
  int regime;       /* vl_regime */
  double eps_f_min; /* smallest epsilon_f(u) over the grid (viscous flattening);
                     * 1 when the effect is off */
  /* relative error of mu estimated from a coarser solve (sweep.h; the
   * point on cells three times as wide); NAN when none was made or it failed */
  double error_estimate;
  /* the same estimate of flux_m2_s (0.5 |q - q_coarse| / |q|), for a seal's
   * leakage; NAN as error_estimate, and when dry */
  double flux_error_estimate;
  int accuracy;               /* vl_accuracy: the estimate against the point's target */
  char warnings[VL_WARN_MAX]; /* ';'-separated, empty when none */
  vl_seal_result seal;        /* stroke VL_STROKE_NONE unless a seal scene */
  vl_down_result down;        /* swept false unless [sweep] direction = both */
  vl_ball_result ball;        /* geometry VL_GEOMETRY_CYLINDER unless a point contact */
} vl_point;

/* How a converged point's error estimate compares with its target (the
 * sweep's target_error). A point above its target, or without an estimate,
 * is not known to be accurate: every output marks it (the console, the
 * CSV and JSON column `accuracy`, the figures, the exit status of the
 * program, a study's counts, Python's `reliable`), as it marks a point that
 * did not converge, but distinguishably. */
typedef enum {
  VL_ACCURACY_UNCHECKED = 0, /* not compared: the point did not converge, or no target */
  VL_ACCURACY_MET,           /* the estimate is within the target */
  VL_ACCURACY_ABOVE_TARGET,  /* the estimate is above the target */
  VL_ACCURACY_NO_ESTIMATE    /* no estimate could be made (its coarser solve failed) */
} vl_accuracy;

/* "", "met", "above_target", "no_estimate"; "?" for anything else. */
const char *vl_accuracy_name(int accuracy);

/* True when pt converged but is above its error target or has no estimate. */
bool vl_point_unreliable(const vl_point *pt);

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
