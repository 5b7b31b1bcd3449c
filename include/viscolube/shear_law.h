/* viscolube: the shear stress in the real contact area, sigma_s, as a law
 * of the sliding speed (docs/MODEL.md section 7, ../BOUNDARY design): what a
 * stored (compound, surface, fluid) pair adds to its three materials.
 *
 *   constant    sigma_s = sigma_s_pa (today's scene key; 1 MPa the seed's)
 *   eyring      sigma_s = sigma_0 + sigma_e asinh(v / v_e),
 *               sigma_e = k_B T / V_a: a wetting fluid's ordered layers in
 *               the junctions shear by thermal activation
 *   dewetting   sigma_s = sigma_dry + (sigma_wet - sigma_dry) s(v / V_d),
 *               s(x) = 1 / (1 + x^-n): dry below the dewetting speed V_d,
 *               wet above; n = VL_DEWETTING_SWITCH_N makes s go from 0.1 to
 *               0.9 over half a decade of speed centred on V_d
 *
 * The dewetting speed is the seed's Eq. 6 read as V_d = k S^2 / (eta E e)
 * (the "2em" in its text is a typesetting space, not a factor): k of order
 * one, S the (negative) spreading pressure, eta the fluid's bulk viscosity,
 * E the rubber's modulus, e the smallest local gap; it has the units of a
 * speed. S, E and e are seldom known, so a pair stores V_d itself together
 * with the viscosity eta_ref_pa_s it holds for; Eq. 6 moves it as 1/eta.
 *
 * The line contact slides at v0 everywhere, so the local sliding speed of
 * the law is v0 at every node. All quantities SI, temperatures in C. */
#ifndef VISCOLUBE_SHEAR_LAW_H
#define VISCOLUBE_SHEAR_LAW_H

#include <stddef.h>

#include "viscolube/status.h"

typedef enum {
  VL_SHEAR_CONSTANT = 0, /* p[0] sigma_s_pa */
  VL_SHEAR_EYRING,       /* p[0] sigma_0_pa, p[1] sigma_e_pa, p[2] v_e_m_s */
  VL_SHEAR_DEWETTING     /* p[0] sigma_dry_pa, p[1] sigma_wet_pa, p[2] v_d_m_s */
} vl_shear_law_kind;

#define VL_SHEAR_LAW_MAX_PARAMS 3
/* s(x) = 1/(1 + x^-n) runs from 0.1 to 0.9 between x = 10^-0.25 and
 * 10^0.25: n = 2 ln 9 / (0.5 ln 10). */
#define VL_DEWETTING_SWITCH_N 3.8169700377572995
/* Boltzmann's constant (J/K), exact since 2019. */
#define VL_BOLTZMANN_J_K 1.380649e-23

/* A law with its parameters at the conditions they hold for. */
typedef struct {
  vl_shear_law_kind kind;
  double p[VL_SHEAR_LAW_MAX_PARAMS]; /* in the order of the kind's comment */
  /* Where the parameters hold: the temperature (eyring's sigma_e is
   * k_B T / V_a there; NAN: at every temperature, no shift) and the fluid's
   * viscosity (dewetting's V_d; NAN or 0: no shift). */
  double tref_c;
  double eta_ref_pa_s;
} vl_shear_law;

/* "constant", "eyring", "dewetting" (static); "?" for anything else. */
const char *vl_shear_law_name(vl_shear_law_kind kind);

/* The kind named s (as vl_shear_law_name). VL_EINPUT listing the names. */
vl_status vl_shear_law_parse(const char *s, vl_shear_law_kind *kind, vl_error *err);

/* Parameters of a kind (1 or 3) and the name of parameter i, with its unit
 * in the name ("sigma_0_pa"; static, "?" out of range). */
size_t vl_shear_law_n_params(vl_shear_law_kind kind);
const char *vl_shear_law_param_name(vl_shear_law_kind kind, size_t i);

/* sigma_s (Pa) at sliding speed |v_m_s| at the law's own conditions (at
 * v = 0: eyring sigma_0, dewetting sigma_dry). grad (may be NULL) gets
 * d sigma / d p[i] for the kind's parameters. */
double vl_shear_law_eval(const vl_shear_law *law, double v_m_s,
                         double grad[VL_SHEAR_LAW_MAX_PARAMS]);

#endif
