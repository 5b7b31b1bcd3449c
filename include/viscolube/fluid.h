/* viscolube: a Newtonian lubricant's viscosity at a temperature.
 *
 * A fluid is stored with its low-shear viscosity eta_ref at a reference
 * temperature Tref (database.h) and, optionally, a viscosity-temperature
 * law. The one law so far is Vogel's (Vogel-Fulcher-Tammann),
 *   log10 eta(T) = A + B / (T - C),          T, C in kelvin, B > 0,
 * stored as B and C only: A is fixed by the stored reference point, so that
 *   log10 eta(T) = log10 eta_ref + B [1/(T - C) - 1/(Tref - C)]
 * and eta(Tref) = eta_ref exactly (a scene at the fluid's reference
 * temperature is the same scene with or without the temperature effect).
 * Andrade's law, ln eta = a + b/T, is the case C = 0 (B = b / ln 10).
 *
 * A law is trusted only over the temperatures of the data it was fitted to
 * [tmin_c, tmax_c] (water at 1 atm: 0-100 C, liquid); outside, and at or
 * below C (where the law diverges), it is refused, not extrapolated.
 * Temperatures in degrees Celsius, viscosities in Pa s. */
#ifndef VISCOLUBE_FLUID_H
#define VISCOLUBE_FLUID_H

#include "viscolube/status.h"

typedef enum {
  VL_VISCOSITY_LAW_NONE = 0, /* known at the reference temperature only */
  VL_VISCOSITY_LAW_VOGEL     /* log10 eta = A + B/(T - C) */
} vl_viscosity_law_kind;

typedef struct {
  vl_viscosity_law_kind kind;
  double vogel_b_k;      /* B > 0, kelvin (decades of eta times K) */
  double vogel_c_k;      /* C, kelvin: the divergence temperature */
  double tmin_c, tmax_c; /* range of validity, Celsius (tmin < tmax) */
} vl_viscosity_law;

/* "none" or "vogel" (the name stored in the database). */
const char *vl_viscosity_law_name(vl_viscosity_law_kind kind);

/* Viscosity (Pa s) at t_c of a fluid with viscosity eta_ref_pa_s at
 * tref_c and the given law (NULL = NONE). At t_c == tref_c returns
 * eta_ref_pa_s exactly, whatever the law. Errors (VL_EINPUT, *eta_pa_s
 * untouched, the message does not name the fluid: the caller prefixes it):
 * no law and t_c != tref_c; t_c outside [tmin_c, tmax_c]; an invalid law
 * (VOGEL needs finite B > 0, C >= 0 K, tmin < tmax, tmin + 273.15 > C and
 * tref_c inside [tmin, tmax]) or eta_ref not positive and finite. */
vl_status vl_fluid_viscosity(const vl_viscosity_law *law, double eta_ref_pa_s, double tref_c,
                             double t_c, double *eta_pa_s, vl_error *err);

#endif
