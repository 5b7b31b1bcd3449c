/* Persson's linear-order rolling friction for a standard linear solid.
 * See persson_linear.h for the nondimensional form. GSL + libm only. */
#include "persson_linear.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_bessel.h>
#include <math.h>

#define PL_LIMIT 1000
#define PL_HEAD_CYCLES 64 /* head integral on [0, 64 pi]; tail beyond */

typedef struct {
  double De;
  int part; /* tail: 0 smooth part, 1 coefficient of sin 2s, 2 of cos 2s */
} pl_params;

static double head_integrand(double s, void *params) {
  const pl_params *pp = params;
  if (s <= 0.0) return 0.0;
  const double j = gsl_sf_bessel_J1(s);
  return j * j / (s * (1.0 + pp->De * pp->De * s * s));
}

/* Hankel expansion (mu = 4 nu^2 = 4):
 * J1(s) = sqrt(2/(pi s)) [P cos w - Q sin w], w = s - 3 pi/4,
 * P = 1 + 15/(128 s^2) - 14175/(98304 s^4), Q = 3/(8 s) - 105/(1024 s^3).
 * With cos 2w = -sin 2s and sin 2w = cos 2s:
 * J1^2 = (2/(pi s)) [(P^2+Q^2)/2 - ((P^2-Q^2)/2) sin 2s - P Q cos 2s].
 * At s >= 64 pi the neglected terms are O(s^-5) relative to J1^2. */
static double tail_integrand(double s, void *params) {
  const pl_params *pp = params;
  const double is2 = 1.0 / (s * s);
  const double P = 1.0 + is2 * (15.0 / 128.0 - is2 * 14175.0 / 98304.0);
  const double Q = (3.0 / 8.0 - is2 * 105.0 / 1024.0) / s;
  const double pref = 2.0 / (M_PI * s) / (s * (1.0 + pp->De * pp->De * s * s));
  switch (pp->part) {
  case 0: return pref * 0.5 * (P * P + Q * Q);
  case 1: return -pref * 0.5 * (P * P - Q * Q);
  default: return -pref * P * Q;
  }
}

/* \int_0^inf J1^2/(s (1 + De^2 s^2)) ds, or NAN. */
static double persson_integral(double De) {
  gsl_set_error_handler_off();
  double total = NAN;
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(PL_LIMIT);
  gsl_integration_workspace *cw = gsl_integration_workspace_alloc(PL_LIMIT);
  gsl_integration_qawo_table *ts = gsl_integration_qawo_table_alloc(2.0, 1.0, GSL_INTEG_SINE, 30);
  gsl_integration_qawo_table *tc = gsl_integration_qawo_table_alloc(2.0, 1.0, GSL_INTEG_COSINE, 30);
  if (!ws || !cw || !ts || !tc) goto cleanup;

  pl_params pp = {De, 0};
  gsl_function fh = {head_integrand, &pp};
  double head = 0.0;
  /* One period of J1^2 per panel; the Lorentzian knee at s = 1/De falls in a
   * panel the adaptive rule resolves (it bisects toward it). */
  for (int k = 0; k < 2 * PL_HEAD_CYCLES; k++) {
    double r = 0.0, e = 0.0;
    int st = gsl_integration_qag(&fh, 0.5 * M_PI * k, 0.5 * M_PI * (k + 1), 0.0, 1e-13, PL_LIMIT,
                                 GSL_INTEG_GAUSS21, ws, &r, &e);
    if (st != GSL_SUCCESS && st != GSL_EROUND) goto cleanup;
    head += r;
  }
  const double S = PL_HEAD_CYCLES * M_PI;
  /* Tail tolerance relative to the head (the tail is < 1/(pi S) of it). */
  const double eps = 1e-14 * fabs(head);
  gsl_function ft = {tail_integrand, &pp};
  double t0 = 0.0, t1 = 0.0, t2 = 0.0, e = 0.0;
  pp.part = 0;
  int st = gsl_integration_qagiu(&ft, S, eps, 1e-12, PL_LIMIT, ws, &t0, &e);
  if (st != GSL_SUCCESS && st != GSL_EROUND) goto cleanup;
  pp.part = 1;
  st = gsl_integration_qawf(&ft, S, eps, PL_LIMIT, ws, cw, ts, &t1, &e);
  if (st != GSL_SUCCESS && st != GSL_EROUND) goto cleanup;
  pp.part = 2;
  st = gsl_integration_qawf(&ft, S, eps, PL_LIMIT, ws, cw, tc, &t2, &e);
  if (st != GSL_SUCCESS && st != GSL_EROUND) goto cleanup;
  total = head + t0 + t1 + t2;

cleanup:
  if (tc) gsl_integration_qawo_table_free(tc);
  if (ts) gsl_integration_qawo_table_free(ts);
  if (cw) gsl_integration_workspace_free(cw);
  if (ws) gsl_integration_workspace_free(ws);
  return total;
}

double vl_oracle_persson_linear_mu(double deborah, double einf_over_e0) {
  if (!(deborah > 0.0 && isfinite(deborah) && einf_over_e0 >= 1.0 && isfinite(einf_over_e0)))
    return NAN;
  const double A = einf_over_e0 - 1.0;
  return 2.0 * A / (1.0 + A) * deborah * persson_integral(deborah);
}

double vl_oracle_persson_linear_mu_closed(double deborah, double einf_over_e0) {
  if (!(deborah > 0.0 && isfinite(deborah) && einf_over_e0 >= 1.0 && isfinite(einf_over_e0)))
    return NAN;
  gsl_set_error_handler_off();
  const double A = einf_over_e0 - 1.0;
  const double z = 1.0 / deborah;
  gsl_sf_result i1, k1;
  /* Scaled forms: e^{-z} I1 * e^{z} K1 = I1 K1 without overflow. */
  if (gsl_sf_bessel_I1_scaled_e(z, &i1) != GSL_SUCCESS) return NAN;
  if (gsl_sf_bessel_K1_scaled_e(z, &k1) != GSL_SUCCESS) return NAN;
  return 2.0 * A / (1.0 + A) * deborah * (0.5 - i1.val * k1.val);
}
