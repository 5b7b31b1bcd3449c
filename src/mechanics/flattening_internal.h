/* viscolube (private): viscous flattening below its public part
 * (viscolube/flattening.h: the evaluator, its speed, its state and the
 * exact epsilon_f). Here: what the solver uses (a change of viscosity, the
 * tabulated epsilon_f) and the steps tests check (the angular average, the
 * one-shot epsilon_f). */
#ifndef VISCOLUBE_FLATTENING_INTERNAL_H
#define VISCOLUBE_FLATTENING_INTERNAL_H

#include "viscolube/flattening.h"
#include "viscolube/roughness.h"
#include "viscolube/status.h"

/* Changes the fluid viscosity (finite, >= 0) and rebuilds the table at the
 * current speed, as vl_flattening_set_speed (for continuation in
 * viscosity). VL_EINPUT otherwise, leaving the evaluator as it was. */
vl_status vl_flattening_set_viscosity(vl_flattening *f, double eta_pa_s, vl_error *err);

/* epsilon_f at separation u (m) at the current speed, and d epsilon_f / du
 * (1/m) in *deps_du when not NULL. Fast path: cubic Hermite interpolation
 * in ln(u/h_rms) of the table, with the exact node slopes, so the value is
 * C1 in u and *deps_du is the exact derivative of the value returned (what
 * a Newton Jacobian needs); outside the table the exact quadrature. As
 * u -> 0+ every wavelength is flattened and epsilon_f = (u^3/(12 eta v0 j_eff))
 * \int q^3 C / \int q C (1 + O(u^6)), so u <= 0 (or u^3 underflowing)
 * returns 0 with derivative 0, continuously. At v0 = 0 (or eta = 0): 1 and 0.
 * Thread-safe for concurrent readers; no allocation. */
double vl_flattening_eps(const vl_flattening *f, double u_m, double *deps_du);

/* The angular average (1/2pi) \int_0^{2pi} dtheta / lambda with
 * lambda = (1 + delta t cos)^2 + (t cos)^2, t >= 0 (t = J'_r s), delta =
 * tan delta >= 0, in closed form:
 *   A = Re[ 1/sqrt(t^2 - z^2) ],  z = (i - delta)/(1 + delta^2)  (principal root),
 *   dA/dt = -t Re[ (t^2 - z^2)^(-3/2) ];
 * delta = 0 gives 1/sqrt(1 + t^2). Small t: A = 1 - (1 - 3 delta^2) t^2/2 + O(t^4);
 * large t: A = 1/t + O(1/t^3) for any delta. *dA_dt when not NULL. Any
 * t >= 0, delta >= 0 finite (t = inf gives 0). */
double vl_flattening_angular(double t, double tan_delta, double *dA_dt);

/* One-shot epsilon_f(u, v0) for cfg (its table fields ignored) and psd,
 * with d epsilon_f / du in *deps_du (may be NULL). Builds no table: for a
 * few values; a solver should create one vl_flattening and use
 * vl_flattening_eps. NAN on bad input (with err set) or allocation failure. */
double vl_flattening_epsilon(const vl_flattening_config *cfg, const vl_psd *psd, double v0_m_s,
                             double u_m, double *deps_du, vl_error *err);

#endif
