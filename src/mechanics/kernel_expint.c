/* viscolube: g(z) = -e^{-z} Ei(z) by piecewise polynomial interpolation
 * (kernel_expint.h).
 *
 * g is analytic except for the logarithmic branch point at z = 0. Each octave
 * 2^(e-1) <= |z| < 2^e, e = 0 .. TAB_OCTAVES-1, is cut into TAB_SUB equal
 * pieces; the closest piece to the branch point, [2^(e-1), (1 + 1/TAB_SUB)
 * 2^(e-1)], has its half-width 1/(2 TAB_SUB + 1) = 1/33 of its centre's
 * distance to z = 0, so the Chebyshev series of g on it converges like rho^-k,
 * rho = 33 + sqrt(33^2 - 1) = 66 (Bernstein ellipse through the singularity):
 * TAB_DEG = 10 coefficients leave 66^-10 ~ 1e-18 of |g|, far under GSL's own
 * rounding, which interpolation at the Chebyshev nodes passes on (a factor
 * ~2). The series is turned into powers of the local variable u in [-1, 1]
 * (its coefficients fall like (2/rho)^k, so nothing cancels) and summed by
 * Estrin's scheme: 4 dependent steps instead of 9. The piece is found from the
 * exponent and mantissa of |z| (frexp), exactly. */
#include "kernel_expint.h"
#include "gsl_errors.h"

#include <math.h>
#include <pthread.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_expint.h>

#define TAB_OCTAVES 7 /* 1/2 <= |z| < 64 */
#define TAB_SUB 16
#define TAB_DEG 10 /* Estrin's sum below is written for 10 */
#define TAB_PIECES (TAB_OCTAVES * TAB_SUB)

/* coef[sign][piece][k] of u^k, sign 0 for z > 0 and 1 for z < 0 */
static double coef[2][TAB_PIECES][TAB_DEG];
static pthread_once_t table_once = PTHREAD_ONCE_INIT;

double vl_expint_g_gsl(double z) {
  gsl_sf_result r;
  int st;
  vl_gsl_errors_off();
  if (z < 0.0) {
    st = gsl_sf_expint_E1_scaled_e(-z, &r);
    return st == GSL_SUCCESS ? r.val : NAN;
  }
  st = gsl_sf_expint_Ei_scaled_e(z, &r);
  return st == GSL_SUCCESS ? -r.val : NAN;
}

/* The piece [lo, lo + w] of |z|: g's interpolant at the Chebyshev nodes, as
 * powers of u = 2 (|z| - lo)/w - 1. The transform and the change of basis run
 * in long double: in double, their rounding (about TAB_DEG ulps of g, spread
 * over all coefficients) would be the largest error of the table. */
static void fit_piece(double *c, double sign, double lo, double w) {
  long double f[TAB_DEG], cheb[TAB_DEG], acc[TAB_DEG];
  const long double pi = 3.141592653589793238462643383279503L;
  for (int j = 0; j < TAB_DEG; j++) {
    double u = (double)cosl(pi * (j + 0.5L) / TAB_DEG);
    f[j] = vl_expint_g_gsl(sign * (lo + 0.5 * w * (u + 1.0)));
  }
  for (int k = 0; k < TAB_DEG; k++) {
    long double s = 0.0L;
    for (int j = 0; j < TAB_DEG; j++)
      s += f[j] * cosl(pi * k * (j + 0.5L) / TAB_DEG);
    cheb[k] = (k == 0 ? 1.0L : 2.0L) * s / TAB_DEG;
  }
  /* T_k's powers by T_{k+1} = 2u T_k - T_{k-1}, accumulated into acc */
  long double tm[TAB_DEG] = {1.0L}, t[TAB_DEG] = {0.0L, 1.0L}, tn[TAB_DEG];
  for (int j = 0; j < TAB_DEG; j++)
    acc[j] = cheb[0] * tm[j] + cheb[1] * t[j];
  for (int k = 2; k < TAB_DEG; k++) {
    for (int j = 0; j < TAB_DEG; j++)
      tn[j] = (j > 0 ? 2.0L * t[j - 1] : 0.0L) - tm[j];
    for (int j = 0; j < TAB_DEG; j++) {
      tm[j] = t[j], t[j] = tn[j];
      acc[j] += cheb[k] * t[j];
    }
  }
  for (int j = 0; j < TAB_DEG; j++)
    c[j] = (double)acc[j];
}

static void table_build(void) {
  for (int s = 0; s < 2; s++)
    for (int e = 0; e < TAB_OCTAVES; e++) {
      double base = ldexp(0.5, e), w = base / TAB_SUB;
      for (int p = 0; p < TAB_SUB; p++)
        fit_piece(coef[s][e * TAB_SUB + p], s ? -1.0 : 1.0, base + p * w, w);
    }
}

/* sum c_k u^k, k < 10, by Estrin's scheme. */
static double power_sum(const double *c, double u) {
  double u2 = u * u, u4 = u2 * u2;
  double p01 = c[0] + c[1] * u, p23 = c[2] + c[3] * u, p45 = c[4] + c[5] * u;
  double p67 = c[6] + c[7] * u, p89 = c[8] + c[9] * u;
  return (p01 + p23 * u2) + (p45 + p67 * u2) * u4 + p89 * (u4 * u4);
}

double vl_expint_g(double z) {
  double az = fabs(z);
  if (!(az >= 0.5 && az < ldexp(0.5, TAB_OCTAVES))) return vl_expint_g_gsl(z); /* and NaN */
  int e;
  double m = frexp(az, &e); /* |z| = m 2^e, 1/2 <= m < 1, 0 <= e < TAB_OCTAVES */
  pthread_once(&table_once, table_build);
  double t = (m - 0.5) * (2.0 * TAB_SUB); /* exact: 0 <= t < TAB_SUB */
  int p = (int)t;
  return power_sum(coef[z < 0.0][e * TAB_SUB + p], 2.0 * (t - p) - 1.0);
}
