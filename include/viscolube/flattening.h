/* viscolube: viscous flattening of the asperities (seed Appendix C,
 * Eqs. 23-31, Figs. 19-20; docs/MODEL.md section 10).
 *
 * The thin film's first-order pressure p1 = K^f h (Eq. 25) deforms the rough
 * rubber by u_z = K^c p1 (Eq. 23), so each Fourier component of the
 * separation is h(q) = h_r(q) / (1 - K^c K^f) and the mean-square roughness
 * the flow and the contact see is reduced to (Eq. 30)
 *
 *   epsilon_f(u) = \int d^2q C(q) / lambda(q, u)  /  \int d^2q C(q),
 *   lambda       = |1 - K^c K^f|^2 = (1 + J''_r s cos(theta))^2 + (J'_r s cos(theta))^2,
 *   s(q, u)      = 12 eta v0 / (u^3 q^2)                              [Pa],
 *
 * with the rubber's reduced compliance 1/Er(wH) = J'_r - i J''_r taken at
 * the asperity frequency wH = pi v0 / aH, aH^2 = 4 fN R / (pi |Er(wH)|)
 * (docs/MODEL.md section 4), theta the angle between q and the sliding direction,
 * grad pf ~ 0, and only the rubber rough (C_2 = 0, v_2 = 0, v_R = v_1).
 * In the seed's variables (zeta = q/q0, F_s = 6 eta v0/(q0^2 h_rms^3 Er_inf),
 * k_re + i k_im = Er_inf / Er(wH)): J'_r s = 2 k_re F_s / ((u/h_rms)^3 zeta^2),
 * J''_r s = 2 k_im F_s / (...).
 *
 * Corrections to the seed's text (derived from its Eqs. 23-27, see
 * src/flattening.c): (i) the quadratic term of Eq. 29/31 carries the same
 * factor 2 as the linear one, i.e. lambda = (1 + 2 k_im F X)^2 + (2 k_re F X)^2
 * with X = cos(theta)/((u/h_rms)^3 zeta^2); the printed Eq. 31 drops it in the
 * second term (the factor 2 is 12/6: the Couette velocity of the film
 * relative to the roughness is v0/2, the half-space kernel is 2/(Er q));
 * (ii) "1 + K^c G = 1/(1 - i K^c K^f)" has a stray i (K^f already holds it);
 * (iii) [.]^2 in Eq. 28 is a squared modulus. The seed's "lambda >= 1" holds
 * only for an elastic (or relaxed) response: with the phase of J(wH) the
 * cross term can give lambda < 1 for some angles, and epsilon_f exceeds 1
 * slightly at large u when tan delta(wH) > 1/sqrt(3). VL_FLATTENING_MODULUS
 * drops the phase (lambda = 1 + (|J_r| s cos)^2, epsilon_f in (0, 1]).
 *
 * The angular average has a closed form (src/mechanics/flattening.c); the
 * q integral is Gauss-Legendre in ln q. epsilon_f depends on u only through
 * t = J'_r s, i.e. through u^-3, so at one speed it is a one-dimensional
 * function of u/h_rms, tabulated per speed for the solver's residual and
 * Jacobian. All inputs SI, epsilon_f dimensionless. The library never
 * prints. */
#ifndef VISCOLUBE_FLATTENING_H
#define VISCOLUBE_FLATTENING_H

#include <stddef.h>

#include "viscolube/rheology.h"
#include "viscolube/roughness.h"
#include "viscolube/status.h"

/* How the rubber responds to the film's pressure on its asperities.
 * MODULUS is the default: the seed states lambda >= 1 and 0 <= epsilon_f <= 1,
 * which only it satisfies. The pressure pattern is steady relative to the
 * rubber's roughness, so the phase lag of J(wH) (wH is the rate at which
 * an asperity is loaded and unloaded crossing the contact, not the
 * frequency of the pattern) does not belong in the spatial quadrature
 * between pressure and height that the cross term of Eq. 31 mixes it into;
 * with it (COMPLEX, the seed as printed) epsilon_f exceeds 1 by up to
 * 0.6 % (sbr-unfilled, 1 mm/s, R = 1 mm, fN = 117 N/m, H = 0.8) or 23 %
 * (model rubber, same contact) where tan delta(wH) > 1/sqrt(3). */
typedef enum {
  VL_FLATTENING_MODULUS = 0, /* |J_r(wH)| = 1/|Er(wH)| as an elastic compliance */
  VL_FLATTENING_COMPLEX      /* the seed's Eq. 31: J'_r and J''_r at wH, phase included */
} vl_flattening_response;

/* Parses "complex" / "modulus" (VL_EINPUT naming the choices otherwise). */
vl_status vl_flattening_response_parse(const char *text, vl_flattening_response *out,
                                       vl_error *err);
const char *vl_flattening_response_name(vl_flattening_response response);

typedef struct {
  vl_prony rubber;     /* copied; n_terms = 0: elastic with Er = Einf/(1-nu^2) */
  double load_n_per_m; /* fN and R: only through aH and so wH */
  double radius_m;
  double eta_pa_s; /* fluid viscosity, >= 0 (0: no flattening) */
  vl_flattening_response response;
  /* per-speed table in x = ln(u/h_rms): nodes per decade (0: 64) over
   * [u_min, u_max] h_rms (0, 0: 1e-3, 1e2); outside it the exact quadrature */
  size_t table_per_decade;
  double table_u_min_hrms, table_u_max_hrms;
} vl_flattening_config;

/* Fills cfg: rubber zeroed (caller sets it), fN = 117 N/m, R = 1 mm (the
 * seed's real-rubber scenes), eta = 0, VL_FLATTENING_MODULUS, table
 * defaults (64 nodes a decade over 1e-3..1e2 h_rms). */
void vl_flattening_config_defaults(vl_flattening_config *cfg);

typedef struct vl_flattening vl_flattening;

/* Creates the evaluator for one rubber, fluid and surface: validates cfg
 * (vl_prony_validate, fN > 0, R > 0, eta >= 0, table range 0 < min < max,
 * per decade <= 1000) and psd (read here only: the caller may free it
 * afterwards), builds the
 * q quadrature (Gauss-Legendre, 8 nodes per panel of at most a quarter
 * decade in q, panels split at tabulated PSD points) and sets speed 0
 * (epsilon_f = 1). VL_EINPUT, VL_ENOMEM; *out NULL on failure. */
vl_status vl_flattening_create(const vl_flattening_config *cfg, const vl_psd *psd,
                               vl_flattening **out, vl_error *err);
void vl_flattening_free(vl_flattening *f); /* NULL is a no-op */

/* Sets the sliding speed (m/s; the sign is irrelevant, epsilon_f is even in
 * v0): computes wH, |Er(wH)|, J_r(wH) and rebuilds the table: 321 exact
 * evaluations with the defaults, 1-2 ms (modulus) or 2-5 ms (complex) on
 * the paper surface; no allocation. The table then matches the exact
 * quadrature within 1e-7 (modulus) / 3e-6 (complex, tan delta 1.4) in
 * epsilon_f and 1e-5 / 3e-4 in d epsilon_f / d ln u (4th and 3rd order in
 * the node spacing; measured in test_flattening). VL_EINPUT for a
 * non-finite v0, and then the previous speed stays set. */
vl_status vl_flattening_set_speed(vl_flattening *f, double v0_m_s, vl_error *err);

/* epsilon_f at separation u (m) at the current speed by the quadrature
 * itself (152 closed-form angular averages on the paper surface: 1-5 us
 * modulus, 8-17 us complex; the solver's table path ~0.1 us), and
 * d epsilon_f / du (1/m, analytic) in *deps_du when not NULL. Absolute
 * difference from adaptive quadrature below 1e-13 (test_flattening). As
 * u -> 0+ every wavelength is flattened, so u <= 0 (or u^3 underflowing)
 * returns 0 with derivative 0, continuously. At v0 = 0 (or eta = 0): 1 and 0.
 * Thread-safe for concurrent readers; no allocation. */
double vl_flattening_eps_exact(const vl_flattening *f, double u_m, double *deps_du);

/* What the current speed fixed. */
typedef struct {
  double v0_m_s;        /* as set (>= 0) */
  double omega_h_rad_s; /* wH = pi v0 / aH */
  double e_abs_pa;      /* |Er(wH)| (reduced) */
  double a_h_m;         /* aH */
  double j_eff_per_pa;  /* the compliance multiplying s: J'_r (complex) or |J_r| (modulus) */
  double tan_delta;     /* J''/J' at wH used in lambda (0 for VL_FLATTENING_MODULUS) */
  double hrms_m;        /* of the surface */
  /* the u at which the longest wavelength (q0) has t = j_eff s(q0, u) = 1:
   * flattening sets in near it, u_c = (12 eta v0 j_eff / q0^2)^(1/3) */
  double u_onset_m;
} vl_flattening_state;
void vl_flattening_state_get(const vl_flattening *f, vl_flattening_state *out);

#endif
