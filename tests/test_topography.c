/* Topography -> isotropic 2-D PSD (topography.h):
 *   - synthetic periodic self-affine maps, made here by an independent
 *     route (random phases, amplitudes sqrt(C dq^2) of a prescribed 2-D
 *     PSD, inverse FFT): C(q) per bin, the Hurst exponent of a power-law
 *     fit and h_rms come back;
 *   - crops of a larger surface (non-periodic, as instruments measure);
 *   - line scans of an isotropic surface, whose 1-D PSD is computed here by
 *     GSL quadrature of the prescribed 2-D one (C1(q) = \int C(|q|) dq_y),
 *     converted back to 2-D;
 *   - sinusoids: the power at the right q with the right rms;
 *   - every accepted layout of both file kinds gives the same heights, and
 *     every refusal says what is wrong where;
 *   - the real AFM map (../shared/data/real, SurfaceTopography, MIT) when
 *     present: rms about 35 nm, the PSD's h_rms within 5 % of it. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "topography_private.h"
#include "vl_test_util.h"

#include <fftw3.h> /* before complex.h: fftw_complex stays double[2] */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "viscolube/roughness.h"
#include "viscolube/topography.h"

#define PI 3.14159265358979323846

/* ---- a seeded generator (splitmix64) ------------------------------------ */

static double uniform(uint64_t *s) {
  uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return ((double)(z >> 11) + 0.5) / 9007199254740992.0;
}

/* ---- the prescribed spectrum: flat below q_r, self-affine above --------- */

typedef struct {
  double c0, qr, hurst, qcut; /* C = c0 (q >= qr: (q/qr)^-2(1+H)); 0 above qcut */
} spectrum;

static double spectrum_c(const spectrum *s, double q) {
  if (q > s->qcut) return 0.0;
  return q < s->qr ? s->c0 : s->c0 * pow(q / s->qr, -2.0 * (1.0 + s->hurst));
}

static vl_topography new_topography(vl_topography_kind kind, size_t nx, size_t ny, double dx,
                                    double dy) {
  vl_topography t = {0};
  t.source = strdup("synthetic");
  t.kind = kind;
  t.nx = nx;
  t.ny = ny;
  t.dx_m = dx;
  t.dy_m = dy;
  t.h_m = calloc(nx * ny, sizeof *t.h_m);
  assert_non_null(t.source);
  assert_non_null(t.h_m);
  return t;
}

/* A periodic n x n surface of pixel dx: every wavevector k gets amplitude
 * sqrt(C(|q|) dq^2) and a random phase, its mirror -k the conjugate, so
 * that h = \sum_k Z_k e^{i q.x} is real with <h^2> = \sum_k C dq^2. */
static double *synth_surface(size_t n, double dx, const spectrum *s, uint64_t seed) {
  fftw_complex *z = fftw_alloc_complex(n * n);
  double *h = malloc(n * n * sizeof *h), dq = 2.0 * PI / ((double)n * dx);
  assert_non_null(z);
  assert_non_null(h);
  fftw_plan plan = fftw_plan_dft_2d((int)n, (int)n, z, z, FFTW_BACKWARD, FFTW_ESTIMATE);
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) {
      size_t mi = (n - i) % n, mj = (n - j) % n, self = i * n + j, mirror = mi * n + mj;
      double ki = i <= n / 2 ? (double)i : (double)i - (double)n;
      double kj = j <= n / 2 ? (double)j : (double)j - (double)n;
      double q = dq * hypot(ki, kj), a = q > 0.0 ? sqrt(spectrum_c(s, q)) * dq : 0.0;
      double phase = 2.0 * PI * uniform(&seed);
      if (mirror < self) { /* the conjugate of a wavevector already drawn */
        z[self][0] = z[mirror][0];
        z[self][1] = -z[mirror][1];
      } else if (mirror == self) { /* its own mirror: real */
        z[self][0] = phase < PI ? a : -a;
        z[self][1] = 0.0;
      } else {
        z[self][0] = a * cos(phase);
        z[self][1] = a * sin(phase);
      }
    }
  fftw_execute(plan);
  for (size_t k = 0; k < n * n; k++)
    h[k] = z[k][0];
  fftw_destroy_plan(plan);
  fftw_free(z);
  return h;
}

/* Least-squares slope of ln y against ln x over points with x in [a, b]. */
static double loglog_slope(size_t n, const double *x, const double *y, double a, double b) {
  double m = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t k = 0; k < n; k++) {
    if (!(y[k] > 0.0) || x[k] < a || x[k] > b) continue;
    double u = log(x[k]), v = log(y[k]);
    m += 1, sx += u, sy += v, sxx += u * u, sxy += u * v;
  }
  assert_true(m >= 3);
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

/* Hurst exponent of C ~ q^-2(1+H) fitted over [a, b]. */
static double hurst_fit(const vl_topography_spectrum *p, double a, double b) {
  return -0.5 * loglog_slope(p->n, p->q_per_m, p->c_m4, a, b) - 1.0;
}

static void check_tabulated(const vl_topography_spectrum *p) {
  vl_psd psd;
  vl_error err;
  assert_int_equal(vl_psd_init_tabulated(&psd, p->n, p->q_per_m, p->c_m4, &err), VL_OK);
  assert_true(vl_test_rel(vl_psd_hrms(&psd), p->hrms_psd_m) < 1e-12);
  vl_psd_free(&psd);
}

/* C(q) of several synthetic measurements averaged point by point. Points
 * are matched by log bin (every measurement of one size has the same bins,
 * but a line scan may drop a point); step 7's point is left out. */
#define MAX_BINS 128
typedef struct {
  double q[MAX_BINS], sum[MAX_BINS];
  size_t seen[MAX_BINS];
} average;

static void average_points(average *a, size_t n, const double *q, const double *c,
                           const size_t *count, double q_min) {
  for (size_t k = 0; k < n; k++) {
    if (count && count[k] == 0) continue;
    long b = lround(10.0 * log10(q[k] / q_min));
    assert_true(b >= 0 && b < MAX_BINS);
    a->q[b] = q[k];
    a->sum[b] += c[k];
    a->seen[b]++;
  }
}

static void average_add(average *a, const vl_topography_spectrum *p) {
  average_points(a, p->n, p->q_per_m, p->c_m4, p->count, p->q_min_per_m);
}

/* Against the prescribed spectrum (C, or C1 when ws is given) over
 * q >= qa: the worst relative error and the mean |ln ratio| of the
 * averaged C; and the Hurst exponent fitted to the averaged C over
 * [fa, fb]. */
static double c1_of(const spectrum *s, double q, gsl_integration_workspace *ws);
static void average_check(const average *a, const spectrum *s, gsl_integration_workspace *ws,
                          double qa, double fa, double fb, double *worst, double *mean_log,
                          double *h_fit) {
  double w = 0.0, sum = 0.0, x[MAX_BINS], y[MAX_BINS];
  size_t m = 0, n = 0;
  for (size_t b = 0; b < MAX_BINS; b++) {
    if (!a->seen[b]) continue;
    x[n] = a->q[b];
    y[n] = a->sum[b] / (double)a->seen[b];
    if (x[n] >= qa) {
      double r = y[n] / (ws ? c1_of(s, x[n], ws) : spectrum_c(s, x[n]));
      if (getenv("VL_TOPO_VERBOSE")) fprintf(stderr, "    q %.4g C/C_prescribed %.3f\n", x[n], r);
      w = fmax(w, fabs(r - 1.0));
      sum += fabs(log(r));
      m++;
    }
    n++;
  }
  assert_true(m >= 5);
  *worst = w;
  *mean_log = sum / (double)m;
  *h_fit = -0.5 * loglog_slope(n, x, y, fa, fb) - (ws ? 0.5 : 1.0); /* C1 ~ q^-(1+2H) */
}

/* ---- synthetic maps -------------------------------------------------------- */

/* Periodic 256 x 256 maps (four seeds), roll-off at 8 x 2 pi/L, H = hurst,
 * with the default window and with Hann: C(q) per bin averaged over the
 * seeds, the Hurst exponent, and each map's h_rms. */
static void self_affine_map(double hurst, int check_rms) {
  const size_t n = 256, seeds = 4;
  const double dx = 10e-9, ql = 2.0 * PI / ((double)n * dx);
  spectrum s = {1e-30, 8.0 * ql, hurst, PI / dx};
  for (int w = 0; w < 2; w++) {
    vl_topography_psd_options o = vl_topography_psd_options_default();
    if (w) o.taper = 1.0;
    average a = {{0}, {0}, {0}};
    double worst_rms = 0.0, q_max = 0.0, ratio_sum = 0.0;
    for (size_t r = 0; r < seeds; r++) {
      vl_topography t = new_topography(VL_TOPOGRAPHY_MAP, n, n, dx, dx);
      double *h = synth_surface(n, dx, &s, 2024 + r);
      memcpy(t.h_m, h, n * n * sizeof *h);
      free(h);
      vl_topography_spectrum p;
      vl_error err;
      assert_int_equal(vl_topography_psd(&t, &o, &p, &err), VL_OK);
      check_tabulated(&p);
      assert_true(p.extended && p.count[0] == 0 && p.q_per_m[0] < p.q_min_per_m);
      average_add(&a, &p);
      double ratio = p.hrms_psd_m / p.hrms_topography_m;
      worst_rms = fmax(worst_rms, fabs(ratio - 1.0));
      ratio_sum += ratio;
      q_max = p.q_max_per_m;
      vl_topography_spectrum_free(&p);
      vl_topography_free(&t);
    }
    double worst, mean_log, h_fit;
    average_check(&a, &s, NULL, 4.0 * ql, 2.0 * s.qr, q_max, &worst, &mean_log, &h_fit);
    fprintf(stderr,
            "periodic maps H %.2f taper %.2f: C(q >= 4 x 2pi/L) worst %.1f %%, mean |ln| %.3f; "
            "H fit %.3f; PSD/topography rms mean %.3f, worst %.1f %%\n",
            hurst, o.taper, 100 * worst, mean_log, h_fit, ratio_sum / (double)seeds,
            100 * worst_rms);
    assert_true(worst < 0.25);
    assert_true(mean_log < 0.08);
    assert_true(fabs(h_fit - hurst) < 0.05);
    if (check_rms && !w) assert_true(worst_rms < 0.05); /* Hann: see test_real_afm */
  }
}

static void test_map_self_affine(void **state) {
  (void)state;
  self_affine_map(0.8, 1);
  /* H = 0.4 puts more power above the short cut (4 pixels): the rms is
   * reported, not required */
  self_affine_map(0.4, 0);
}

/* 16 crops 256 x 256 of a periodic 1024 x 1024 surface: non-periodic
 * measurements, as instruments make them. Roll-off at 64 pixels (the
 * crops see it). C(q) averaged over the crops, and each crop's rms. */
static void test_map_crops(void **state) {
  (void)state;
  const size_t big = 1024, n = 256;
  const double dx = 10e-9, ql = 2.0 * PI / ((double)n * dx);
  spectrum s = {1e-30, 4.0 * ql, 0.8, PI / dx};
  double *h = synth_surface(big, dx, &s, 77), worst_rms = 0.0, ratio_sum = 0.0, q_max = 0.0;
  average a = {{0}, {0}, {0}};
  size_t crops = 0;
  for (size_t oi = 0; oi < big; oi += n)
    for (size_t oj = 0; oj < big; oj += n) {
      vl_topography t = new_topography(VL_TOPOGRAPHY_MAP, n, n, dx, dx);
      for (size_t i = 0; i < n; i++)
        memcpy(t.h_m + i * n, h + (oi + i) * big + oj, n * sizeof *h);
      vl_topography_spectrum p;
      vl_error err;
      assert_int_equal(vl_topography_psd(&t, NULL, &p, &err), VL_OK);
      average_add(&a, &p);
      double ratio = p.hrms_psd_m / p.hrms_topography_m;
      worst_rms = fmax(worst_rms, fabs(ratio - 1.0));
      ratio_sum += ratio;
      q_max = p.q_max_per_m;
      crops++;
      vl_topography_spectrum_free(&p);
      vl_topography_free(&t);
    }
  free(h);
  double worst, mean_log, h_fit;
  average_check(&a, &s, NULL, 4.0 * ql, 2.0 * s.qr, q_max, &worst, &mean_log, &h_fit);
  fprintf(stderr,
          "crops: %zu, C(q >= 4 x 2pi/L) worst %.1f %%, mean |ln| %.3f; H fit %.3f; "
          "PSD/topography rms mean %.3f, worst %.1f %%\n",
          crops, 100 * worst, mean_log, h_fit, ratio_sum / (double)crops, 100 * worst_rms);
  assert_true(worst < 0.25);
  assert_true(mean_log < 0.08);
  assert_true(fabs(h_fit - s.hurst) < 0.05);
  assert_true(fabs(ratio_sum / (double)crops - 1.0) < 0.05);
  assert_true(worst_rms < 0.10);
}

/* ---- synthetic line scans ------------------------------------------------- */

typedef struct {
  double x, hurst; /* q_x / q_r */
} projection;

static double projection_integrand(double u, void *par) {
  const projection *p = par;
  return pow(p->x * p->x + u * u, -(1.0 + p->hurst));
}

/* C1(q) = \int dq_y C(sqrt(q^2 + q_y^2)) of the prescribed spectrum (no
 * upper cut), by GSL: the flat disc in closed form, the power law by
 * adaptive quadrature to infinity. */
static double c1_of(const spectrum *s, double q, gsl_integration_workspace *ws) {
  double x = q / s->qr, u0 = x < 1.0 ? sqrt(1.0 - x * x) : 0.0, val, abserr;
  projection par = {x, s->hurst};
  gsl_function f = {projection_integrand, &par};
  int rc = gsl_integration_qagiu(&f, u0, 0.0, 1e-10, 1000, ws, &val, &abserr);
  assert_int_equal(rc, GSL_SUCCESS);
  return 2.0 * s->c0 * s->qr * (u0 + val);
}

/* The amplitudes 2 sqrt(C1(q_k) dq) of the frequencies q_k = 2 pi k / L,
 * k = 0 .. n/2 (none at 0 and at Nyquist). */
static double *line_amplitudes(size_t n, double dx, const spectrum *s) {
  double *a = malloc((n / 2 + 1) * sizeof *a), dq = 2.0 * PI / ((double)n * dx);
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
  assert_non_null(a);
  for (size_t k = 0; k <= n / 2; k++)
    a[k] = (k == 0 || 2 * k == n) ? 0.0 : 2.0 * sqrt(c1_of(s, dq * (double)k, ws) * dq);
  gsl_integration_workspace_free(ws);
  return a;
}

/* A periodic line of n points, the amplitudes a[k] with random phases:
 * h = \sum_k a_k cos(q_k x + phi_k), <h^2> = 2 \sum_k C1 dq. */
static vl_topography synth_line(size_t n, double dx, const double *a, uint64_t seed) {
  vl_topography t = new_topography(VL_TOPOGRAPHY_LINE, n, 1, dx, 0.0);
  fftw_complex *z = fftw_alloc_complex(n / 2 + 1);
  fftw_plan plan = fftw_plan_dft_c2r_1d((int)n, z, t.h_m, FFTW_ESTIMATE);
  for (size_t k = 0; k <= n / 2; k++) {
    double phase = 2.0 * PI * uniform(&seed);
    z[k][0] = 0.5 * a[k] * cos(phase); /* c2r: h_n = 2 Re \sum_k z_k e^{2 pi i k n/N} */
    z[k][1] = 0.5 * a[k] * sin(phase);
  }
  fftw_execute(plan);
  fftw_destroy_plan(plan);
  fftw_free(z);
  return t;
}

/* Profiles of an isotropic surface (roll-off at 16 x 2 pi/L, H = 0.7),
 * converted to 2-D. One profile is one sample: C1 of a bin of few
 * frequencies scatters, and the inverse Abel transform (a derivative)
 * amplifies that, so C(q) is averaged over 16 profiles; each profile's rms
 * and Hurst exponent are checked on their own. */
static void test_line_to_2d(void **state) {
  (void)state;
  const size_t n = 32768, lines = 16;
  const double dx = 10e-9, ql = 2.0 * PI / ((double)n * dx);
  spectrum s = {1e-24, 16.0 * ql, 0.7, INFINITY};
  double *amp = line_amplitudes(n, dx, &s), worst_rms = 0.0, worst_h = 0.0, q_max = 0.0;
  average a = {{0}, {0}, {0}}, a1 = {{0}, {0}, {0}};
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
  for (size_t r = 0; r < lines; r++) {
    vl_topography t = synth_line(n, dx, amp, 1000 + r);
    vl_topography_spectrum p;
    vl_error err;
    assert_int_equal(vl_topography_psd(&t, NULL, &p, &err), VL_OK);
    check_tabulated(&p);
    assert_true(p.n1 > 0 && p.q1_per_m && p.c1_m3);
    average_add(&a, &p);
    average_points(&a1, p.n1, p.q1_per_m, p.c1_m3, NULL, p.q_min_per_m);
    double ratio = p.hrms_psd_m / p.hrms_topography_m;
    double h = hurst_fit(&p, 2.0 * s.qr, p.q_max_per_m);
    worst_rms = fmax(worst_rms, fabs(ratio - 1.0));
    worst_h = fmax(worst_h, fabs(h - s.hurst));
    q_max = p.q_max_per_m;
    if (r < 2 || getenv("VL_TOPO_VERBOSE"))
      fprintf(stderr,
              "line %zu: %zu points (%zu dropped), C1 tail slope %.3f, H fit %.3f, "
              "PSD/topography rms %.3f\n",
              r, p.n, p.n_dropped, p.tail_slope, h, ratio);
    vl_topography_spectrum_free(&p);
    vl_topography_free(&t);
  }
  double worst1, mean1, h1, worst, mean_log, h_fit, worst_hi, mean_hi, h_hi;
  average_check(&a1, &s, ws, 4.0 * ql, 2.0 * s.qr, q_max, &worst1, &mean1, &h1);
  average_check(&a, &s, NULL, 4.0 * ql, 2.0 * s.qr, q_max, &worst, &mean_log, &h_fit);
  average_check(&a, &s, NULL, 100.0 * ql, 2.0 * s.qr, q_max, &worst_hi, &mean_hi, &h_hi);
  gsl_integration_workspace_free(ws);
  free(amp);
  fprintf(stderr,
          "lines: %zu averaged; C1(q >= 4 x 2pi/L) worst %.1f %%, mean |ln| %.3f, H fit %.3f; "
          "2-D C: q >= 4 x 2pi/L worst %.1f %%, mean |ln| %.3f, q >= 100 x 2pi/L worst %.1f %%; "
          "H fit %.3f (each line within %.3f); PSD/topography rms worst %.1f %%\n",
          lines, 100 * worst1, mean1, h1, 100 * worst, mean_log, 100 * worst_hi, h_fit, worst_h,
          100 * worst_rms);
  assert_true(worst1 < 0.25);
  assert_true(mean1 < 0.08);
  assert_true(fabs(h1 - s.hurst) < 0.05);
  assert_true(worst < 0.25);
  assert_true(mean_log < 0.08);
  assert_true(worst_hi < 0.10);
  assert_true(fabs(h_fit - s.hurst) < 0.05);
  assert_true(worst_h < 0.05);
  assert_true(worst_rms < 0.10);
}

/* The inverse Abel transform alone: a periodic line (no window: every
 * frequency's power exact) whose band sees a pure power law C1 = A
 * q^-(1+2H) must give C = C1/q Gamma(H+1)/(sqrt(pi) Gamma(H+1/2)), the
 * prescribed C. The shortcut C1/(pi q) is exact only for H = 0. */
static void test_abel_power_law(void **state) {
  (void)state;
  const double hurst = 0.9;
  const size_t n = 4096;
  const double dx = 1e-6, ql = 2.0 * PI / ((double)n * dx);
  spectrum s = {1e-20, ql, hurst, INFINITY}; /* flat below q_L only */
  double *amp = line_amplitudes(n, dx, &s);
  vl_topography t = synth_line(n, dx, amp, 5);
  vl_topography_psd_options o = vl_topography_psd_options_default();
  o.taper = 0.0;
  vl_topography_spectrum p;
  vl_error err;
  assert_int_equal(vl_topography_psd(&t, &o, &p, &err), VL_OK);
  double worst = 0.0;
  for (size_t k = 0; k < p.n; k++)
    if (p.count[k] > 0) worst = fmax(worst, fabs(p.c_m4[k] / spectrum_c(&s, p.q_per_m[k]) - 1.0));
  double f = tgamma(hurst + 1.0) / (sqrt(PI) * tgamma(hurst + 0.5));
  fprintf(stderr,
          "power law H %.1f, exact periodogram: C worst %.1f %% over %zu points "
          "(C1/(pi q) would be off by %.0f %%)\n",
          hurst, 100 * worst, p.n, 100 * (1.0 / (f * PI) - 1.0));
  assert_int_equal(p.n_dropped, 0);
  assert_true(worst < 0.05);
  vl_topography_spectrum_free(&p);
  vl_topography_free(&t);
  free(amp);
}

/* ---- sinusoids ------------------------------------------------------------- */

static void test_sinusoid_map(void **state) {
  (void)state;
  const size_t n = 128;
  const double dx = 20e-9, l = (double)n * dx, amp = 5e-9, q0 = 2.0 * PI * 10.0 / l;
  vl_topography t = new_topography(VL_TOPOGRAPHY_MAP, n, n, dx, dx);
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      t.h_m[i * n + j] = amp * cos(q0 * (double)j * dx + 0.3);
  const double tapers[3] = {VL_TOPOGRAPHY_TAPER, 1.0, 0.0};
  for (int w = 0; w < 3; w++) {
    vl_topography_psd_options o = vl_topography_psd_options_default();
    o.taper = tapers[w];
    vl_topography_spectrum p;
    vl_error err;
    assert_int_equal(vl_topography_psd(&t, &o, &p, &err), VL_OK);
    size_t best = 0;
    for (size_t k = 1; k < p.n; k++)
      if (p.c_m4[k] > p.c_m4[best]) best = k;
    fprintf(stderr,
            "sinusoid map taper %.1f: peak at q/q0 %.3f, band rms / (a/sqrt 2) %.4f, "
            "topography %.4f\n",
            o.taper, p.q_per_m[best] / q0, p.hrms_band_m / (amp / sqrt(2.0)),
            p.hrms_topography_m / (amp / sqrt(2.0)));
    assert_true(fabs(log10(p.q_per_m[best] / q0)) < 0.5 / o.bins_per_decade);
    assert_true(vl_test_rel(p.hrms_band_m, amp / sqrt(2.0)) < 0.02);
    assert_true(vl_test_rel(p.hrms_topography_m, amp / sqrt(2.0)) < 0.01);
    vl_topography_spectrum_free(&p);
  }
  vl_topography_free(&t);
}

static void test_sinusoid_line(void **state) {
  (void)state;
  const size_t n = 1024;
  const double dx = 1e-6, l = (double)n * dx, amp = 2e-7, q0 = 2.0 * PI * 37.0 / l;
  vl_topography t = new_topography(VL_TOPOGRAPHY_LINE, n, 1, dx, 0.0);
  for (size_t j = 0; j < n; j++)
    t.h_m[j] = amp * sin(q0 * (double)j * dx);
  vl_topography_spectrum p;
  vl_error err;
  assert_int_equal(vl_topography_psd(&t, NULL, &p, &err), VL_OK);
  size_t best = 0;
  for (size_t k = 1; k < p.n1; k++)
    if (p.c1_m3[k] > p.c1_m3[best]) best = k;
  fprintf(stderr, "sinusoid line: C1 peak at q/q0 %.3f, band rms / (a/sqrt 2) %.4f\n",
          p.q1_per_m[best] / q0, p.hrms_band_m / (amp / sqrt(2.0)));
  assert_true(fabs(log10(p.q1_per_m[best] / q0)) < 0.05);
  assert_true(vl_test_rel(p.hrms_band_m, amp / sqrt(2.0)) < 0.02);
  vl_topography_spectrum_free(&p);
  vl_topography_free(&t);
}

/* ---- file layouts ---------------------------------------------------------- */

/* the growing text of vl_test_util */
typedef vl_test_text text;
#define add vl_test_text_add

/* A number with 17 digits, '.' replaced by ',' when comma is set. */
static void add_number(text *t, double v, int comma) {
  char buf[64];
  snprintf(buf, sizeof buf, "%.17g", v);
  if (comma)
    for (char *c = buf; *c; c++)
      if (*c == '.') *c = ',';
  add(t, "%s", buf);
}

#define LINE_N 40
#define LINE_DX 0.1e-6

static double line_height(size_t i) {
  return 1e-9 * (3.0 * sin(0.7 * (double)i) + 0.25 * (double)(i % 5));
}

typedef struct {
  const char *preamble; /* before the header ('#' lines, BOM), may be "" */
  const char *header;
  const char *sep; /* between the two fields */
  double xu, zu;   /* m per file unit */
  int comma;       /* decimal comma */
  const char *nl;
} line_layout;

static char *line_text(const line_layout *lay) {
  text t = {0};
  add(&t, "%s%s%s", lay->preamble, lay->header, lay->nl);
  for (size_t i = 0; i < LINE_N; i++) {
    if (i == 7) add(&t, "# a comment inside%s%s", lay->nl, lay->nl);
    add_number(&t, (double)i * LINE_DX / lay->xu, lay->comma);
    add(&t, "%s", lay->sep);
    add_number(&t, line_height(i) / lay->zu, lay->comma);
    add(&t, "%s", lay->nl);
  }
  return t.s;
}

static void test_line_layouts(void **state) {
  (void)state;
  const line_layout lays[] = {
      {"", "x [um], z [nm]", ",", 1e-6, 1e-9, 0, "\n"},
      {"", "position (m);height (m)", ";", 1.0, 1.0, 1, "\n"},
      {"", "x_m,z_m", ",", 1.0, 1.0, 0, "\n"},
      {"# profilometer export\n# Height: n/a (a comment, not a map header)\n",
       "x [\xC2\xB5m]\tz [nm]", "\t", 1e-6, 1e-9, 0, "\r\n"},
      {"\xEF\xBB\xBF", "position (mm) height (um)", "  ", 1e-3, 1e-6, 1, "\r\n"},
      {"", "x [micrometers], height [Nanometre]", ", ", 1e-6, 1e-9, 0, "\n"},
      {"", "x (\xCE\xBCm); z (MM)", " ; ", 1e-6, 1e-3, 0, "\r"},
      {"", "Position_microns\tHeight_nm", "\t", 1e-6, 1e-9, 1, "\n"},
  };
  for (size_t k = 0; k < sizeof lays / sizeof lays[0]; k++) {
    char *s = line_text(&lays[k]);
    vl_topography t;
    vl_error err;
    vl_status st = vl_topography_read_text(s, strlen(s), "scan.txt", &t, &err);
    if (st != VL_OK) fail_msg("layout %zu ('%s'): %s", k, lays[k].header, err.msg);
    assert_int_equal(t.kind, VL_TOPOGRAPHY_LINE);
    assert_int_equal(t.nx, LINE_N);
    assert_int_equal(t.ny, 1);
    assert_true(vl_test_rel(t.dx_m, LINE_DX) < 1e-12);
    for (size_t i = 0; i < LINE_N; i++)
      assert_true(fabs(t.h_m[i] - line_height(i)) <= 1e-12 * 4e-9);
    vl_topography_free(&t);
    free(s);
  }
}

/* A 16 x 20 map (rows x columns) of known heights. */
#define MAP_ROWS 16
#define MAP_COLS 20

static double map_height(size_t i, size_t j) {
  return 1e-8 * (1.5 + cos(0.9 * (double)i) * sin(0.4 * (double)j)) + 2e-10 * (double)(i + j);
}

typedef struct {
  const char *header; /* '#' lines, each ending in \n */
  const char *sep;
  double zu;
  int comma;
  int three_digit_exp; /* 1.8823e-008 as some exporters write */
} map_layout;

static char *map_text(const map_layout *lay) {
  text t = {0};
  add(&t, "%s", lay->header);
  for (size_t i = 0; i < MAP_ROWS; i++) {
    for (size_t j = 0; j < MAP_COLS; j++) {
      if (j) add(&t, "%s", lay->sep);
      if (lay->three_digit_exp) {
        char buf[64], out[64];
        snprintf(buf, sizeof buf, "%.16e", map_height(i, j) / lay->zu);
        char *e = strchr(buf, 'e');
        assert_non_null(e);
        snprintf(out, sizeof out, "%.*se%c0%s", (int)(e - buf), buf, e[1], e + 2);
        add(&t, "%s", out);
      } else {
        add_number(&t, map_height(i, j) / lay->zu, lay->comma);
      }
    }
    add(&t, "%s\n", i % 3 == 0 ? lay->sep[0] == ',' ? "," : "\t" : "");
  }
  return t.s;
}

static void test_map_layouts(void **state) {
  (void)state;
  const map_layout lays[] = {
      {"# Channel: ZSensor\n# Width: 2.00 \xC2\xB5m\n# Height: 1.60 \xC2\xB5m\n# Value units: m\n",
       "\t", 1.0, 0, 1},
      {"# width = 2000 nm\n# HEIGHT: 1,6 um\n# value units: nm\n# Scan rate: 1 Hz\n", ",", 1e-9, 0,
       0},
      {"#Width:2um\n#Height:0.0016mm\n#Value Units: um\n", ";", 1e-6, 1, 0},
      {"# Width: 2e-6 m\n# Height: 1.6e-6 m\n# Value units: \xCE\xBCm\n", " ", 1e-6, 1, 0},
      {"# Width: 2 micrometers\n# Height: 1.6 microns\n# Value_units: Meter\n", "  ", 1.0, 0, 0},
  };
  for (size_t k = 0; k < sizeof lays / sizeof lays[0]; k++) {
    char *s = map_text(&lays[k]);
    vl_topography t;
    vl_error err;
    vl_status st = vl_topography_read_text(s, strlen(s), "map.txt", &t, &err);
    if (st != VL_OK) fail_msg("map layout %zu: %s", k, err.msg);
    assert_int_equal(t.kind, VL_TOPOGRAPHY_MAP);
    assert_int_equal(t.nx, MAP_COLS);
    assert_int_equal(t.ny, MAP_ROWS);
    assert_false(t.square_assumed);
    assert_true(vl_test_rel(t.dx_m, 2e-6 / MAP_COLS) < 1e-12);
    assert_true(vl_test_rel(t.dy_m, 1.6e-6 / MAP_ROWS) < 1e-12);
    for (size_t i = 0; i < MAP_ROWS; i++)
      for (size_t j = 0; j < MAP_COLS; j++)
        assert_true(vl_test_rel(t.h_m[i * MAP_COLS + j], map_height(i, j)) < 1e-12);
    vl_topography_free(&t);
    free(s);
  }
  /* no '# Height:': square pixels, said so */
  map_layout sq = {"# Width: 2 um\n# Value units: m\n", "\t", 1.0, 0, 0};
  char *s = map_text(&sq);
  vl_topography t;
  vl_error err;
  assert_int_equal(vl_topography_read_text(s, strlen(s), "map.txt", &t, &err), VL_OK);
  assert_true(t.square_assumed);
  assert_true(vl_test_rel(t.dy_m, t.dx_m) < 1e-15);
  vl_topography_free(&t);
  free(s);
}

/* ---- refusals ---------------------------------------------------------- */

static void refused_n(const char *s, size_t len, const char *expect) {
  vl_topography t;
  vl_error err = {{0}};
  vl_status st = vl_topography_read_text(s, len, "bad.txt", &t, &err);
  if (st != VL_EINPUT || !strstr(err.msg, expect))
    fail_msg("expected VL_EINPUT with '%s', got %d: '%s'", expect, (int)st, err.msg);
  assert_null(t.h_m);
  assert_null(t.source);
  fprintf(stderr, "  refused: %s\n", err.msg);
}

static void refused(const char *s, const char *expect) { refused_n(s, strlen(s), expect); }

/* A text built from a line layout with one row replaced. */
static char *line_with(const char *header, size_t n, size_t bad_row, const char *bad) {
  text t = {0};
  add(&t, "%s\n", header);
  for (size_t i = 0; i < n; i++) {
    if (i == bad_row)
      add(&t, "%s\n", bad);
    else
      add(&t, "%.3f,%.3f\n", 0.1 * (double)i, line_height(i) * 1e9);
  }
  return t.s;
}

static void test_refusals(void **state) {
  (void)state;
  char *s;
  /* line scans */
  s = line_with("x [um], z [nm]", 30, 5, "0.53,1.0");
  refused(s, "bad.txt:7: position 0.53 is 0.30 spacings off the uniform grid");
  free(s);
  s = line_with("x [um], z [nm]", 30, 5, "0.3,1.0");
  refused(s, "bad.txt:7: position 0.3 does not increase");
  free(s);
  s = line_with("x [um], z [nm]", 10, 99, "");
  refused(s, "a line scan needs at least 16 points (got 10");
  free(s);
  s = line_with("x [furlong], z [nm]", 30, 99, "");
  refused(s, "bad.txt:1: field 1: unknown length unit 'furlong' for the position");
  free(s);
  s = line_with("x [um], z [V]", 30, 99, "");
  refused(s, "bad.txt:1: field 2: unknown length unit 'V' for the height");
  free(s);
  s = line_with("x, z", 30, 99, "");
  refused(s, "bad.txt:1: field 1: the position column 'x' names no unit");
  free(s);
  s = line_with("x [um], z [nm], i [nm]", 30, 99, "");
  refused(s, "a line scan has two columns, position and height, but its header has 3");
  free(s);
  s = line_with("x [um], z [nm]", 30, 3, "0.3,nan");
  refused(s, "bad.txt:5: field 2: NaN and infinity are not allowed");
  free(s);
  s = line_with("x [um], z [nm]", 30, 3, "0.3,1.2.3");
  refused(s, "bad.txt:5: field 2: not a number (got '1.2.3')");
  free(s);
  s = line_with("x [um], z [nm]", 30, 3, "0.3,1.0,7");
  refused(s, "bad.txt:5: a line scan row has two fields");
  free(s);
  refused("x [um];z [nm]\n0,0;1,5\n0,1;2.5\n", "bad.txt:3: field 2: a '.' in a file that uses "
                                               "decimal commas");
  /* empty and headerless */
  refused("", "bad.txt: empty");
  refused("# only a comment\n\n   \n", "bad.txt: empty");
  refused("0.0 1.0\n0.1 2.0\n", "bad.txt:1: a height map needs the header lines '# Width");
  refused_n("x [um], z [nm]\n0,\0\n", 19, "NUL byte");
  /* maps */
  refused("# Width: 1 um\n1 2 3\n", "a height map needs the header lines");
  refused("# Width: wide\n# Value units: m\n1 2 3\n", "bad.txt:1: 'Width:' must be a positive "
                                                      "length");
  refused("# Width: 1 furlong\n", "bad.txt:1: 'Width:': unknown length unit 'furlong'");
  refused("# Width: 1 um\n# Value units: V\n",
          "bad.txt:2: 'Value units:': unknown length unit 'V'");
  text t = {0};
  add(&t, "# Width: 1 um\n# Value units: m\n");
  for (int i = 0; i < 20; i++) {
    for (int j = 0; j < (i == 9 ? 15 : 16); j++)
      add(&t, "%s1e-9", j ? "\t" : "");
    add(&t, "\n");
  }
  refused(t.s, "bad.txt:12: row has 15 values, the first row has 16: a height map's rows must "
               "have equal length");
  free(t.s);
  t = (text){0};
  add(&t, "# Width: 1 um\n# Value units: m\n");
  for (int i = 0; i < 8; i++)
    add(&t, "1 2 3 4 5 6 7 8\n");
  refused(t.s, "a height map needs at least 16 rows and 16 columns (got 8 x 8)");
  free(t.s);
  /* files */
  vl_topography topo;
  vl_error err;
  assert_int_equal(vl_topography_read_file("/nonexistent/scan.txt", &topo, &err), VL_EIO);
  assert_non_null(strstr(err.msg, "/nonexistent/scan.txt: cannot open"));
}

static void test_psd_refusals(void **state) {
  (void)state;
  vl_topography t = new_topography(VL_TOPOGRAPHY_LINE, 64, 1, 1e-6, 0.0);
  for (size_t j = 0; j < 64; j++)
    t.h_m[j] = 1e-9 * (double)j; /* a line: nothing left after detrending */
  vl_topography_spectrum p;
  vl_error err;
  assert_int_equal(vl_topography_psd(&t, NULL, &p, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "no roughness left"));
  assert_null(p.q_per_m);
  /* constant heights: their rms about the mean is 0 and the detrended rms
   * round-off of the height (it was accepted as a 3.7e-26 m surface) */
  for (size_t j = 0; j < 64; j++)
    t.h_m[j] = 3.3e-6;
  assert_int_equal(vl_topography_psd(&t, NULL, &p, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "no roughness left"));
  for (size_t j = 0; j < 64; j++)
    t.h_m[j] = 1e-9 * sin(0.3 * (double)j * (double)j);
  struct {
    double taper, bins, long_cut, short_cut;
    const char *expect;
  } bad[] = {{2.0, 10, 1, 0.5, "taper must be in [0, 1]"},
             {0.2, 0, 1, 0.5, "bins per decade"},
             {0.2, 10, 0.5, 0.5, "long-wavelength cut"},
             {0.2, 10, 1, 0.0, "short-wavelength cut"},
             {0.2, 10, 20, 0.5, "the band is empty"}};
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    vl_topography_psd_options o = vl_topography_psd_options_default();
    o.taper = bad[k].taper;
    o.bins_per_decade = bad[k].bins;
    o.long_cut = bad[k].long_cut;
    o.short_cut = bad[k].short_cut;
    assert_int_equal(vl_topography_psd(&t, &o, &p, &err), VL_EINPUT);
    if (!strstr(err.msg, bad[k].expect)) fail_msg("'%s' not in '%s'", bad[k].expect, err.msg);
  }
  vl_topography_psd_options o = vl_topography_psd_options_default();
  assert_int_equal(vl_topography_psd(&t, &o, &p, &err), VL_OK);
  assert_non_null(strstr(p.provenance, "line scan 64 points"));
  assert_non_null(strstr(p.provenance, "Tukey window"));
  vl_topography_spectrum_free(&p);
  vl_topography_free(&t);
}

/* ---- the real AFM map ------------------------------------------------------ */

static void test_real_afm(void **state) {
  (void)state;
  const char *rel = "../shared/data/real/surfacetopography_matrix-3_afm.txt";
  const char *path = vl_test_source_path(rel), *dir = getenv("VL_REAL_DATA");
  char own[4096];
  if (dir) { /* a worktree elsewhere can point at the folder */
    snprintf(own, sizeof own, "%s/surfacetopography_matrix-3_afm.txt", dir);
    path = own;
  }
  if (access(path, R_OK) != 0) path = rel;
  if (access(path, R_OK) != 0) {
    fprintf(stderr, "skipped: the real AFM map is absent (looked for $VL_SOURCE_DIR/%s)\n", rel);
    skip();
  }
  vl_topography t;
  vl_error err;
  if (vl_topography_read_file(path, &t, &err) != VL_OK) fail_msg("%s", err.msg);
  assert_int_equal(t.kind, VL_TOPOGRAPHY_MAP);
  assert_int_equal(t.nx, 256);
  assert_int_equal(t.ny, 256);
  assert_true(vl_test_rel(t.dx_m, 10e-6 / 256) < 1e-12);
  assert_true(vl_test_rel(t.dy_m, 10e-6 / 256) < 1e-12);
  double rms = vl_topography_hrms(&t);
  assert_true(rms > 34e-9 && rms < 36.5e-9);
  for (int w = 0; w < 2; w++) {
    vl_topography_psd_options o = vl_topography_psd_options_default();
    if (w) o.taper = 1.0;
    vl_topography_spectrum p;
    assert_int_equal(vl_topography_psd(&t, &o, &p, &err), VL_OK);
    check_tabulated(&p);
    double h_fit = hurst_fit(&p, 10.0 * p.q_min_per_m, p.q_max_per_m);
    double ratio = p.hrms_psd_m / rms;
    fprintf(stderr,
            "AFM map taper %.2f: rms %.2f nm; %zu points q = %.3g ... %.3g 1/m; H fit "
            "(q > 10 x 2pi/L) %.2f; band/rms %.3f, PSD/rms %.3f\n  %s\n",
            o.taper, 1e9 * rms, p.n, p.q_per_m[0], p.q_per_m[p.n - 1], h_fit, p.hrms_band_m / rms,
            ratio, p.provenance);
    /* the default window only: Hann weighs the centre of this map, which is
     * smoother than its edges (see topography.h) */
    if (!w) assert_true(fabs(ratio - 1.0) < 0.05);
    vl_topography_spectrum_free(&p);
  }
  vl_topography_free(&t);
}

int main(void) {
  gsl_set_error_handler_off(); /* c1_of checks every status */
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_map_self_affine), cmocka_unit_test(test_map_crops),
      cmocka_unit_test(test_line_to_2d),      cmocka_unit_test(test_abel_power_law),
      cmocka_unit_test(test_sinusoid_map),    cmocka_unit_test(test_sinusoid_line),
      cmocka_unit_test(test_line_layouts),    cmocka_unit_test(test_map_layouts),
      cmocka_unit_test(test_refusals),        cmocka_unit_test(test_psd_refusals),
      cmocka_unit_test(test_real_afm),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
