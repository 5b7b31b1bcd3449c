/* The inverse Abel transform (abel.h): a profile's 1-D roughness spectrum
 * to the isotropic surface's 2-D one, step 6 of topography.h. Its own file
 * because two readers need it: the PSD of a line scan (topography_psd.c)
 * and a tabulated 1-D spectrum (psd_file.c). It calls no other file of the
 * layer. */
#include "abel.h"

#include <math.h>
#include <stdlib.h>

#define PI 3.14159265358979323846
/* Inverse Abel quadrature: panels at most this wide in t (q = Q cosh t),
 * and every piece (the tail too) integrated until cosh(t)^-(s+1) has
 * fallen by e^-TAIL_DECAY. */
#define ABEL_PANEL 0.25
#define TAIL_DECAY 40.0
/* The tail slope of C1 is fitted over the last half decade of bins. */
#define TAIL_FIT_DECADES 0.5

/* 8-point Gauss-Legendre on [-1, 1]. */
static const double gl_x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                               0.9602898564975363};
static const double gl_w[4] = {0.3626837833783620, 0.3137066053114875, 0.2223810344533745,
                               0.1012285362903763};

/* \int_{ta}^{tb} (cosh t)^-(s+1) dt (s >= 0) by Gauss-Legendre panels,
 * ended where the integrand has fallen by e^-TAIL_DECAY from ta, as the
 * tail is: beyond that it adds nothing, and a band of q spanning more
 * than the range of double (a 1-D q of 5.6e-299 1/m next to 1e14, found by
 * the fuzzer) made tb infinite and the panel count undefined. */
static double cosh_power_integral(double s, double ta, double tb) {
  tb = fmin(tb, ta + TAIL_DECAY / (s + 1.0));
  if (!(tb > ta)) return 0.0; /* also ta infinite */
  size_t panels = (size_t)ceil((tb - ta) / ABEL_PANEL);
  double h = (tb - ta) / (double)panels, sum = 0.0;
  for (size_t p = 0; p < panels; p++) {
    double mid = ta + ((double)p + 0.5) * h;
    for (int k = 0; k < 4; k++)
      for (int sign = -1; sign <= 1; sign += 2)
        sum += gl_w[k] * pow(cosh(mid + sign * 0.5 * h * gl_x[k]), -(s + 1.0));
  }
  return 0.5 * h * sum;
}

/* C(Q) at Q = q[j] from C1 given at q[0..n) as a power law between points
 * and C1 = c[n-1] (q/q[n-1])^-tail beyond. On a piece C1 = c_k (q/q_k)^-s,
 * -C1'(q) = s C1 / q, and with q = Q cosh t
 *   C(Q) = (1/pi) \sum_k s_k c_k (Q/q_k)^-s_k / Q \int (cosh t)^-(s_k+1) dt. */
static double inverse_abel(const double *q, const double *c, size_t n, double tail, size_t j) {
  double big_q = q[j], sum = 0.0;
  for (size_t k = j; k < n; k++) {
    double s = k + 1 < n ? -log(c[k + 1] / c[k]) / log(q[k + 1] / q[k]) : tail;
    double ta = acosh(q[k] / big_q);
    double tb = k + 1 < n ? acosh(q[k + 1] / big_q) : ta + TAIL_DECAY / (s + 1.0);
    if (s == 0.0) continue;
    sum += s * c[k] * pow(big_q / q[k], -s) / big_q * cosh_power_integral(s, ta, tb);
  }
  return sum / PI;
}

/* -dlnC1/dlnq from a least-squares fit over the last TAIL_FIT_DECADES of
 * points (at least the last two); clamped at 0 (a rising tail would put
 * infinite power above the band). */
static double tail_slope(const double *q, const double *c, size_t n) {
  size_t first = n - 2;
  while (first > 0 && log10(q[n - 1] / q[first - 1]) <= TAIL_FIT_DECADES)
    first--;
  double m = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (size_t k = first; k < n; k++) {
    double x = log(q[k]), y = log(c[k]);
    m += 1.0, sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  double slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  return fmax(0.0, -slope);
}

/* The non-increasing sequence closest to c[0..n) in least squares with
 * weights w (pool adjacent violators: a pool takes the weighted mean of its
 * points, i.e. merges their bins). The profile of an isotropic surface
 * whose C(q) does not increase has a non-increasing C1, and then the
 * inverse Abel transform is >= 0 everywhere; the pools are where one
 * profile's noise says otherwise. Returns 0 without memory. */
static int non_increasing(const double *c, const size_t *w, size_t n, double *out) {
  double *sum = malloc(n * sizeof *sum), *weight = malloc(n * sizeof *weight);
  size_t *len = malloc(n * sizeof *len), top = 0;
  int ok = sum && weight && len;
  for (size_t k = 0; ok && k < n; k++) {
    sum[top] = c[k] * (double)w[k];
    weight[top] = (double)w[k];
    len[top] = 1;
    top++;
    while (top > 1 && sum[top - 2] / weight[top - 2] < sum[top - 1] / weight[top - 1]) {
      sum[top - 2] += sum[top - 1];
      weight[top - 2] += weight[top - 1];
      len[top - 2] += len[top - 1];
      top--;
    }
  }
  for (size_t b = 0, k = 0; ok && b < top; b++)
    for (size_t i = 0; i < len[b]; i++)
      out[k++] = sum[b] / weight[b];
  free(sum);
  free(weight);
  free(len);
  return ok;
}

vl_status vl_abel_profile_to_surface(size_t n, const double *q, const double *c1,
                                     const size_t *weight, double *c2, double *tail_out) {
  vl_status st = VL_OK;
  double *mono = malloc(n * sizeof *mono);
  size_t *ones = weight ? NULL : malloc(n * sizeof *ones);
  if (!mono || (!weight && !ones)) {
    st = VL_ENOMEM;
    goto cleanup;
  }
  for (size_t k = 0; ones && k < n; k++)
    ones[k] = 1;
  if (!non_increasing(c1, weight ? weight : ones, n, mono)) {
    st = VL_ENOMEM;
    goto cleanup;
  }
  double tail = tail_slope(q, mono, n);
  for (size_t j = 0; j < n; j++)
    c2[j] = inverse_abel(q, mono, n, tail, j);
  if (tail_out) *tail_out = tail;

cleanup:
  free(mono);
  free(ones);
  return st;
}
