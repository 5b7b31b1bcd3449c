/* Roughness power spectra: self-affine and tabulated (roughness.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bracket.h"
#include "roughness_internal.h"
#include "viscolube/roughness.h"

#ifndef M_PI /* strict C17 <math.h> does not define it */
#define M_PI 3.14159265358979323846
#endif

/* \int_a^b q^p dq for 0 < a <= b, stable when p ~ -1 (expm1 form). */
static double power_integral(double p, double a, double b) {
  double l = log(b / a);
  double x = (p + 1.0) * l;
  double ratio = fabs(x) < 1e-300 ? 1.0 : expm1(x) / x;
  return pow(a, p + 1.0) * l * ratio;
}

vl_status vl_psd_init_self_affine(vl_psd *psd, double hurst, double q0, double q1, double hrms_m,
                                  vl_error *err) {
  memset(psd, 0, sizeof *psd);
  if (!(isfinite(hurst) && hurst > 0.0 && hurst <= 1.0)) {
    vl_error_set(err, "hurst: H must lie in (0, 1] (got %g)", hurst);
    return VL_EINPUT;
  }
  if (!(isfinite(q0) && q0 > 0.0)) {
    vl_error_set(err, "q0: must be a positive wavevector in 1/m (got %g)", q0);
    return VL_EINPUT;
  }
  if (!(isfinite(q1) && q1 > q0)) {
    vl_error_set(err, "q1: must be finite and larger than q0 = %g (got %g)", q0, q1);
    return VL_EINPUT;
  }
  if (!(isfinite(hrms_m) && hrms_m > 0.0)) {
    vl_error_set(err, "hrms: must be a positive length in m (got %g)", hrms_m);
    return VL_EINPUT;
  }
  psd->kind = VL_PSD_SELF_AFFINE;
  psd->hurst = hurst;
  psd->q0 = q0;
  psd->q1 = q1;
  psd->hrms_m = hrms_m;
  /* h_rms^2 = 2 pi \int q C dq = pi C0 q0^2 [1 - (q0/q1)^(2H)] / H */
  psd->c0 = hurst * hrms_m * hrms_m / (M_PI * q0 * q0 * -expm1(2.0 * hurst * log(q0 / q1)));
  return VL_OK;
}

vl_status vl_psd_init_tabulated(vl_psd *psd, size_t n, const double *q, const double *C,
                                vl_error *err) {
  memset(psd, 0, sizeof *psd);
  if (n < 2) {
    vl_error_set(err, "a tabulated PSD needs at least 2 points (got %zu)", n);
    return VL_EINPUT;
  }
  for (size_t k = 0; k < n; k++) {
    if (!(isfinite(q[k]) && q[k] > 0.0)) {
      vl_error_set(err, "point %zu: q must be positive and finite (got %g)", k + 1, q[k]);
      return VL_EINPUT;
    }
    if (!(isfinite(C[k]) && C[k] > 0.0)) {
      vl_error_set(err, "point %zu: C must be positive and finite (got %g)", k + 1, C[k]);
      return VL_EINPUT;
    }
    if (k > 0 && !(q[k] > q[k - 1])) {
      vl_error_set(err, "point %zu: q must be strictly increasing (%g after %g)", k + 1, q[k],
                   q[k - 1]);
      return VL_EINPUT;
    }
  }
  psd->q = malloc(n * sizeof *psd->q);
  psd->C = malloc(n * sizeof *psd->C);
  if (!psd->q || !psd->C) {
    free(psd->q);
    free(psd->C);
    psd->q = psd->C = NULL;
    vl_error_set(err, "out of memory for a %zu-point PSD", n);
    return VL_ENOMEM;
  }
  memcpy(psd->q, q, n * sizeof *q);
  memcpy(psd->C, C, n * sizeof *C);
  psd->kind = VL_PSD_TABULATED;
  psd->n = n;
  psd->q0 = q[0];
  psd->q1 = q[n - 1];
  psd->hrms_m = vl_psd_hrms(psd);
  return VL_OK;
}

void vl_psd_free(vl_psd *psd) {
  if (!psd) return;
  free(psd->q);
  free(psd->C);
  psd->q = psd->C = NULL;
  psd->n = 0;
}

/* Index k of the segment [q_k, q_{k+1}] holding q (tabulated). */
static size_t segment(const vl_psd *psd, double q) { return vl_bracket(psd->q, psd->n, q); }

static double segment_slope(const vl_psd *psd, size_t k) {
  return log(psd->C[k + 1] / psd->C[k]) / log(psd->q[k + 1] / psd->q[k]);
}

double vl_psd_value(const vl_psd *psd, double q) {
  if (q < psd->q0 || q > psd->q1) return 0.0;
  if (psd->kind == VL_PSD_SELF_AFFINE) return psd->c0 * pow(q / psd->q0, -2.0 * (1.0 + psd->hurst));
  size_t k = segment(psd, q);
  return psd->C[k] * pow(q / psd->q[k], segment_slope(psd, k));
}

double vl_psd_moment(const vl_psd *psd, int k, double qa, double qb) {
  qa = fmax(qa, psd->q0);
  qb = fmin(qb, psd->q1);
  if (!(qb > qa)) return 0.0;
  if (psd->kind == VL_PSD_SELF_AFFINE) {
    double e = -2.0 * (1.0 + psd->hurst);
    /* C0 q0^{-e} \int q^{k+e} dq, written to avoid overflow of q0^{-e}. */
    return psd->c0 * pow(qa / psd->q0, e) * pow(qa, (double)k) *
           power_integral((double)k + e, 1.0, qb / qa) * qa;
  }
  double sum = 0.0;
  for (size_t s = segment(psd, qa); s + 1 < psd->n && psd->q[s] < qb; s++) {
    double a = fmax(qa, psd->q[s]), b = fmin(qb, psd->q[s + 1]);
    if (!(b > a)) continue;
    double alpha = segment_slope(psd, s);
    double ca = psd->C[s] * pow(a / psd->q[s], alpha); /* C at a */
    sum += ca * pow(a, (double)k) * a * power_integral((double)k + alpha, 1.0, b / a);
  }
  return sum;
}

double vl_psd_hrms(const vl_psd *psd) {
  return sqrt(2.0 * M_PI * vl_psd_moment(psd, 1, psd->q0, psd->q1));
}

double vl_psd_rms_slope(const vl_psd *psd) {
  return sqrt(2.0 * M_PI * vl_psd_moment(psd, 3, psd->q0, psd->q1));
}

vl_status vl_psd_fit_self_affine(const vl_psd *psd, double *hurst, double *c_q0, double *rms_log10,
                                 vl_error *err) {
  if (psd->kind == VL_PSD_SELF_AFFINE) {
    *hurst = psd->hurst;
    if (c_q0) *c_q0 = psd->c0;
    if (rms_log10) *rms_log10 = 0.0;
    return VL_OK;
  }
  /* from the largest C on: a roll-off below it is not self-affine */
  size_t first = 0;
  for (size_t i = 1; i < psd->n; i++)
    if (psd->C[i] > psd->C[first]) first = i;
  if (psd->n - first < 2) first = 0;
  if (psd->n < 2) {
    vl_error_set(err, "a self-affine fit needs at least 2 points");
    return VL_EINPUT;
  }
  /* x = log10(q/q0), y = log10 C: y = b + m x */
  double n = (double)(psd->n - first), sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (size_t i = first; i < psd->n; i++) {
    double x = log10(psd->q[i] / psd->q0), y = log10(psd->C[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  double m = (n * sxy - sx * sy) / (n * sxx - sx * sx), b = (sy - m * sx) / n, ss = 0.0;
  for (size_t i = first; i < psd->n; i++) {
    double r = log10(psd->C[i]) - b - m * log10(psd->q[i] / psd->q0);
    ss += r * r;
  }
  *hurst = -0.5 * m - 1.0;
  if (c_q0) *c_q0 = pow(10.0, b);
  if (rms_log10) *rms_log10 = sqrt(ss / n);
  return VL_OK;
}
