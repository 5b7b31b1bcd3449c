/* viscolube: does an operating point lie inside the model's assumptions?
 *
 * The model (docs/MODEL.md; the seed paper, Scaraggi & Persson) rests on
 * assumptions the solver does not enforce: it converges just as well
 * outside them, and its numbers are then only as good as the assumption.
 * A simulation (simulation.h) tests every operating point against each
 * assumption and appends a short warning per violated one to the point's
 * warnings (vl_point.warnings, results.h). Thresholds are stated with
 * each check below; they mark where an assumption is clearly stretched,
 * not a sharp validity limit.
 *
 *   VL_ASSUME_RMS_SLOPE       rms slope sqrt(2 pi \int q^3 C dq) > 1: Persson's
 *                             contact mechanics and the linear elasticity of
 *                             the half-space assume small surface slopes.
 *   VL_ASSUME_HOMOGENISATION  a_H < 5 lambda0, lambda0 = 2 pi/q0: the
 *                             mean-field description averages the roughness
 *                             over the contact, which needs the contact width
 *                             2 a_H to hold ~10 of the longest wavelengths
 *                             (seed: "a large separation of length scales").
 *   VL_ASSUME_PERSSON_TABLE   u_min < 1e-3 h_rms on a rough surface: below
 *                             the Persson table (roughness.h), where pc(u)
 *                             is a linear wall that keeps Newton finite, not
 *                             the theory.
 *   VL_ASSUME_PRONY_WINDOW    a fitted Prony series (>= 2 terms) probed at
 *                             wH = pi v0/a_H outside [0.1/tau_max, 10/tau_min]:
 *                             the series represents the measured window
 *                             (prony_fit.h puts the tau_i on it) and beyond
 *                             it only repeats a plateau. One term is the
 *                             model rubber: a complete material law.
 *   VL_ASSUME_GRID            the pressure zone (contact_width_m) spans
 *                             fewer than 8 grid cells: the discrete
 *                             solution does not resolve the contact.
 *   VL_ASSUME_HALF_SPACE      half the contact width > 0.2 R: the parabolic
 *                             gap x^2/(2R) (2 % off the circle at 0.3 R) and
 *                             small strains (~a/R) no longer hold.
 *   VL_ASSUME_CONTINUUM_FILM  wet, u_min < 1 nm: a Newtonian continuum film
 *                             is not expected at nanometre separations (the
 *                             seed says so itself).
 *   VL_ASSUME_THIN_FILM       wet, u_central > 0.1 x half the contact
 *                             width: the Reynolds equation needs a film
 *                             thin compared with its lateral extent.
 *   VL_ASSUME_INERTIA         wet, reduced Reynolds number
 *                             rho v0 u^2/(eta L) > 1 with rho = 1000 kg/m^3
 *                             (water; oils 800-1000), u = u_central, L =
 *                             half the contact width: the seed neglects the
 *                             fluid's inertia.
 *   VL_ASSUME_FLOW_FACTORS    wet rough, the fluid carrying > 5 % of the load
 *                             and u_min below the range of the flow-factor
 *                             model: smooth factors with u_min < 3 h_rms
 *                             (roughness then changes the flow), or
 *                             Patir-Cheng with u_min < 0.7 h_rms (h/sigma <
 *                             0.5: their fits end there and flow_factors.h
 *                             continues them).
 *
 *   VL_ASSUME_MEASURED_WINDOW a compound fitted to measured data probed more
 *                             than a decade outside the frequencies its
 *                             master curve covers: the modulus there is
 *                             the Prony series' extrapolation, not a
 *                             measurement.
 *
 * A point that did not converge (all zeros, flow quantities unknown) is
 * checked only on what the configuration and speed decide: rms slope,
 * homogenisation and the Prony window. */
#ifndef VISCOLUBE_ASSUMPTIONS_H
#define VISCOLUBE_ASSUMPTIONS_H

typedef enum {
  VL_ASSUME_RMS_SLOPE = 1u << 0,
  VL_ASSUME_HOMOGENISATION = 1u << 1,
  VL_ASSUME_PERSSON_TABLE = 1u << 2,
  VL_ASSUME_PRONY_WINDOW = 1u << 3,
  VL_ASSUME_GRID = 1u << 4,
  VL_ASSUME_HALF_SPACE = 1u << 5,
  VL_ASSUME_CONTINUUM_FILM = 1u << 6,
  VL_ASSUME_THIN_FILM = 1u << 7,
  VL_ASSUME_INERTIA = 1u << 8,
  VL_ASSUME_FLOW_FACTORS = 1u << 9,
  VL_ASSUME_MEASURED_WINDOW = 1u << 10
} vl_assumption;

#endif
