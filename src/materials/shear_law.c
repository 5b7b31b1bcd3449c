/* The shear stress in the real contact area as a law of the sliding speed
 * (shear_law.h): constant, Eyring's thermally activated shear, and the
 * dewetting switch of the seed's Eq. 6. */
#include "viscolube/shear_law.h"
#include "shear_law_private.h"

#include <math.h>
#include <string.h>

static const char *const law_names[] = {"constant", "eyring", "dewetting"};
static const size_t law_n_params[] = {1, 3, 3};
static const char *const param_names[][VL_SHEAR_LAW_MAX_PARAMS] = {
    {"sigma_s_pa", "?", "?"},
    {"sigma_0_pa", "sigma_e_pa", "v_e_m_s"},
    {"sigma_dry_pa", "sigma_wet_pa", "v_d_m_s"},
};

static int kind_ok(vl_shear_law_kind kind) {
  return kind >= VL_SHEAR_CONSTANT && kind <= VL_SHEAR_DEWETTING;
}

vl_shear_law vl_shear_law_constant(double sigma_s_pa) {
  vl_shear_law law = {VL_SHEAR_CONSTANT, {sigma_s_pa, 0.0, 0.0}, NAN, NAN};
  return law;
}

const char *vl_shear_law_name(vl_shear_law_kind kind) {
  return kind_ok(kind) ? law_names[kind] : "?";
}

vl_status vl_shear_law_parse(const char *s, vl_shear_law_kind *kind, vl_error *err) {
  for (int k = VL_SHEAR_CONSTANT; k <= VL_SHEAR_DEWETTING; k++)
    if (s && !strcmp(s, law_names[k])) {
      *kind = (vl_shear_law_kind)k;
      return VL_OK;
    }
  vl_error_set(err, "unknown shear-stress law '%s' (known: constant, eyring, dewetting)",
               s ? s : "");
  return VL_EINPUT;
}

size_t vl_shear_law_n_params(vl_shear_law_kind kind) {
  return kind_ok(kind) ? law_n_params[kind] : 0;
}

const char *vl_shear_law_param_name(vl_shear_law_kind kind, size_t i) {
  return kind_ok(kind) && i < law_n_params[kind] ? param_names[kind][i] : "?";
}

vl_status vl_shear_law_validate(const vl_shear_law *law, vl_error *err) {
  if (!kind_ok(law->kind)) {
    vl_error_set(err, "unknown shear-stress law (kind %d)", (int)law->kind);
    return VL_EINPUT;
  }
  size_t n = law_n_params[law->kind];
  for (size_t i = 0; i < n; i++) {
    const char *name = param_names[law->kind][i];
    int speed = law->kind != VL_SHEAR_CONSTANT && i == 2;
    double v = law->p[i];
    if (!isfinite(v) || (speed ? !(v > 0.0) : !(v >= 0.0))) {
      vl_error_set(err, "%s law: %s must be a finite number %s (got %g)", law_names[law->kind],
                   name, speed ? "> 0 (a speed in m/s)" : ">= 0 (Pa)", v);
      return VL_EINPUT;
    }
  }
  if (!isnan(law->tref_c) && !(isfinite(law->tref_c) && law->tref_c > -273.15)) {
    vl_error_set(err, "%s law: reference temperature must be above -273.15 C (got %g)",
                 law_names[law->kind], law->tref_c);
    return VL_EINPUT;
  }
  if (!isnan(law->eta_ref_pa_s) && !(isfinite(law->eta_ref_pa_s) && law->eta_ref_pa_s >= 0.0)) {
    vl_error_set(err, "%s law: reference viscosity must be >= 0 Pa s (got %g)",
                 law_names[law->kind], law->eta_ref_pa_s);
    return VL_EINPUT;
  }
  return VL_OK;
}

double vl_shear_law_eval(const vl_shear_law *law, double v_m_s,
                         double grad[VL_SHEAR_LAW_MAX_PARAMS]) {
  double v = fabs(v_m_s);
  const double *p = law->p;
  double g[VL_SHEAR_LAW_MAX_PARAMS] = {0.0, 0.0, 0.0}, sigma = 0.0;
  switch (law->kind) {
  case VL_SHEAR_CONSTANT:
    sigma = p[0];
    g[0] = 1.0;
    break;
  case VL_SHEAR_EYRING: {
    double x = v / p[2];
    sigma = p[0] + p[1] * asinh(x);
    g[0] = 1.0;
    g[1] = asinh(x);
    g[2] = -p[1] * x / (p[2] * sqrt(1.0 + x * x)); /* d asinh(v/ve)/d ve */
    break;
  }
  case VL_SHEAR_DEWETTING: {
    /* s = 1/(1 + (V_d/v)^n), written so that v = 0 and huge ratios are safe */
    double r = v > 0.0 ? pow(p[2] / v, VL_DEWETTING_SWITCH_N) : INFINITY;
    double s = 1.0 / (1.0 + r);
    sigma = p[0] + (p[1] - p[0]) * s;
    g[0] = 1.0 - s;
    g[1] = s;
    /* ds/dV_d = -s^2 n r / V_d */
    g[2] = isfinite(r) ? -(p[1] - p[0]) * s * s * VL_DEWETTING_SWITCH_N * r / p[2] : 0.0;
    break;
  }
  }
  if (grad) memcpy(grad, g, sizeof g);
  return sigma;
}

vl_status vl_shear_law_at(const vl_shear_law *law, double t_c, double eta_pa_s, vl_shear_law *out,
                          vl_error *err) {
  if (!isnan(t_c) && !(isfinite(t_c) && t_c > -273.15)) {
    vl_error_set(err, "shear-stress law at %g C: below absolute zero", t_c);
    return VL_EINPUT;
  }
  if (!isnan(eta_pa_s) && !(isfinite(eta_pa_s) && eta_pa_s >= 0.0)) {
    vl_error_set(err, "shear-stress law in a fluid of viscosity %g Pa s: needs >= 0", eta_pa_s);
    return VL_EINPUT;
  }
  vl_shear_law l = *law;
  if (l.kind == VL_SHEAR_EYRING && !isnan(t_c) && !isnan(l.tref_c)) {
    l.p[1] *= (t_c + 273.15) / (l.tref_c + 273.15); /* sigma_e = k_B T / V_a */
    l.tref_c = t_c;
  }
  if (l.kind == VL_SHEAR_DEWETTING && eta_pa_s > 0.0 && l.eta_ref_pa_s > 0.0) {
    l.p[2] *= l.eta_ref_pa_s / eta_pa_s; /* Eq. 6: V_d ~ 1/eta */
    l.eta_ref_pa_s = eta_pa_s;
  }
  *out = l;
  return VL_OK;
}

double vl_dewetting_speed(double k, double spreading_pressure_n_m, double eta_pa_s, double e_pa,
                          double gap_m) {
  return k * spreading_pressure_n_m * spreading_pressure_n_m / (eta_pa_s * e_pa * gap_m);
}
