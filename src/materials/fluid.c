/* Viscosity-temperature laws of lubricants (fluid.h). */
#include "viscolube/fluid.h"
#include "fluid_internal.h"

#include <math.h>
#include <string.h>

#define KELVIN 273.15

const char *vl_viscosity_law_name(vl_viscosity_law_kind kind) {
  switch (kind) {
  case VL_VISCOSITY_LAW_NONE: return "none";
  case VL_VISCOSITY_LAW_VOGEL: return "vogel";
  }
  return "?";
}

vl_status vl_viscosity_law_parse(const char *name, vl_viscosity_law_kind *kind, vl_error *err) {
  if (name && !strcmp(name, "vogel")) {
    *kind = VL_VISCOSITY_LAW_VOGEL;
    return VL_OK;
  }
  vl_error_set(err, "unknown viscosity-temperature law '%s' (known: vogel)", name ? name : "");
  return VL_EINPUT;
}

vl_status vl_viscosity_law_validate(const vl_viscosity_law *law, double tref_c, vl_error *err) {
  if (!law || law->kind == VL_VISCOSITY_LAW_NONE) return VL_OK;
  if (law->kind != VL_VISCOSITY_LAW_VOGEL) {
    vl_error_set(err, "unknown viscosity-temperature law (kind %d)", (int)law->kind);
    return VL_EINPUT;
  }
  /* B > 0: viscosity falls as the liquid warms, the only physical case */
  if (!(isfinite(law->vogel_b_k) && law->vogel_b_k > 0.0)) {
    vl_error_set(err, "Vogel B must be a positive number of kelvin (got %g)", law->vogel_b_k);
    return VL_EINPUT;
  }
  if (!(isfinite(law->vogel_c_k) && law->vogel_c_k >= 0.0)) {
    vl_error_set(err, "Vogel C must be a temperature >= 0 K (got %g)", law->vogel_c_k);
    return VL_EINPUT;
  }
  if (!(isfinite(law->tmin_c) && isfinite(law->tmax_c) && law->tmin_c < law->tmax_c)) {
    vl_error_set(err, "the range of the viscosity law needs finite tmin < tmax (got %g, %g C)",
                 law->tmin_c, law->tmax_c);
    return VL_EINPUT;
  }
  if (!(law->tmin_c + KELVIN > law->vogel_c_k)) {
    vl_error_set(err,
                 "the range of the viscosity law starts at %g C, at or below its divergence "
                 "temperature C = %g K (%g C)",
                 law->tmin_c, law->vogel_c_k, law->vogel_c_k - KELVIN);
    return VL_EINPUT;
  }
  if (!(tref_c >= law->tmin_c && tref_c <= law->tmax_c)) {
    vl_error_set(err,
                 "the reference temperature %g C lies outside the range [%g, %g] C of the "
                 "viscosity law",
                 tref_c, law->tmin_c, law->tmax_c);
    return VL_EINPUT;
  }
  return VL_OK;
}

vl_status vl_fluid_viscosity(const vl_viscosity_law *law, double eta_ref_pa_s, double tref_c,
                             double t_c, double *eta_pa_s, vl_error *err) {
  if (!(isfinite(eta_ref_pa_s) && eta_ref_pa_s > 0.0) || !isfinite(tref_c)) {
    vl_error_set(err, "invalid reference viscosity %g Pa s at %g C", eta_ref_pa_s, tref_c);
    return VL_EINPUT;
  }
  if (!isfinite(t_c) || t_c < -KELVIN) {
    vl_error_set(err, "invalid temperature %g C", t_c);
    return VL_EINPUT;
  }
  /* the reference point is data, not a law's estimate of it */
  if (t_c == tref_c) {
    *eta_pa_s = eta_ref_pa_s;
    return VL_OK;
  }
  if (!law || law->kind == VL_VISCOSITY_LAW_NONE) {
    vl_error_set(err,
                 "no viscosity-temperature law is stored: the viscosity is known at %g C only "
                 "(asked for %g C)",
                 tref_c, t_c);
    return VL_EINPUT;
  }
  vl_status s = vl_viscosity_law_validate(law, tref_c, err);
  if (s != VL_OK) return s;
  if (t_c < law->tmin_c || t_c > law->tmax_c) {
    vl_error_set(err,
                 "%g C lies outside the range [%g, %g] C of its %s viscosity law "
                 "(not extrapolated)",
                 t_c, law->tmin_c, law->tmax_c, vl_viscosity_law_name(law->kind));
    return VL_EINPUT;
  }
  double b = law->vogel_b_k, c = law->vogel_c_k;
  double decades = b / (t_c + KELVIN - c) - b / (tref_c + KELVIN - c);
  *eta_pa_s = eta_ref_pa_s * pow(10.0, decades);
  return VL_OK;
}
