/* The isotropic 2-D PSD of a measured topography (topography.h, steps 1
 * to 7): detrend, window, FFT, band, log bins and, for line scans, the
 * inverse Abel transform (abel.c) from the profile's spectrum to the
 * surface's. Reading the topography is topography_file.c's. */
#define _POSIX_C_SOURCE 200809L

#include "topography_private.h"
#include "viscolube/topography.h"

#include <fftw3.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "viscolube/roughness.h"

#include "abel.h"

#define PI 3.14159265358979323846
#define TWO_PI 6.283185307179586476925287
/* Detrended rms below this fraction of the raw rms: rounding, not roughness. */
#define FLAT_TOL 1e-9

/* ---- detrending ---------------------------------------------------------- */

/* The least-squares plane h ~ a + bx (j - cx) + by (i - cy) over the grid
 * (a line for ny = 1): with centred indices the three basis functions are
 * orthogonal on the full grid, so each coefficient is a projection. */
typedef struct {
  double a, bx, by, cx, cy;
} plane;

static plane fit_plane(const vl_topography *t) {
  plane p = {0.0, 0.0, 0.0, 0.5 * (double)(t->nx - 1), 0.5 * (double)(t->ny - 1)};
  double s = 0.0, sx = 0.0, sy = 0.0, xx = 0.0, yy = 0.0;
  for (size_t j = 0; j < t->nx; j++)
    xx += ((double)j - p.cx) * ((double)j - p.cx);
  for (size_t i = 0; i < t->ny; i++)
    yy += ((double)i - p.cy) * ((double)i - p.cy);
  for (size_t i = 0; i < t->ny; i++)
    for (size_t j = 0; j < t->nx; j++) {
      double h = t->h_m[i * t->nx + j];
      s += h;
      sx += h * ((double)j - p.cx);
      sy += h * ((double)i - p.cy);
    }
  p.a = s / ((double)t->nx * (double)t->ny);
  p.bx = xx > 0.0 ? sx / (xx * (double)t->ny) : 0.0;
  p.by = yy > 0.0 ? sy / (yy * (double)t->nx) : 0.0;
  return p;
}

/* The scale the flatness test compares with: the rms of the heights about
 * their mean, and at least their magnitude (a constant height map has a
 * zero rms about its mean, and its detrended rms is round-off of the
 * magnitude: 3.7e-26 m was accepted as a surface). */
static double raw_rms(const vl_topography *t) {
  size_t n = t->nx * t->ny;
  double m = 0.0, s = 0.0, big = 0.0;
  for (size_t k = 0; k < n; k++) {
    m += t->h_m[k];
    big = fmax(big, fabs(t->h_m[k]));
  }
  m /= (double)n;
  for (size_t k = 0; k < n; k++)
    s += (t->h_m[k] - m) * (t->h_m[k] - m);
  return fmax(sqrt(s / (double)n), big);
}

static double residual(const vl_topography *t, const plane *p, size_t i, size_t j) {
  return t->h_m[i * t->nx + j] - p->a - p->bx * ((double)j - p->cx) - p->by * ((double)i - p->cy);
}

double vl_topography_hrms(const vl_topography *t) {
  if (!t || !t->h_m || t->nx == 0 || t->ny == 0) return NAN;
  plane p = fit_plane(t);
  double s = 0.0;
  for (size_t i = 0; i < t->ny; i++)
    for (size_t j = 0; j < t->nx; j++) {
      double r = residual(t, &p, i, j);
      s += r * r;
    }
  return sqrt(s / ((double)t->nx * (double)t->ny));
}

/* ---- window, bins -------------------------------------------------------- */

/* Periodic Tukey window into w[0..n): cosine tapers over a fraction taper
 * of the length (half at each end), 1 between; taper 1 is the periodic
 * Hann window, 0 no window. Returns mean(w^2). */
static double make_window(double taper, size_t n, double *w) {
  double s = 0.0;
  for (size_t k = 0; k < n; k++) {
    double u = (double)k / (double)n, edge = fmin(u, 1.0 - u);
    w[k] = edge < 0.5 * taper ? 0.5 * (1.0 - cos(TWO_PI * edge / taper)) : 1.0;
    s += w[k] * w[k];
  }
  return s / (double)n;
}

/* Log bins centred on q_min 10^(j/b): sums of weight, weight*C and
 * weight*ln q per bin. */
typedef struct {
  double q_min, q_max, per_decade;
  size_t n;
  double *w, *wc, *wlnq;
  double band_power;   /* \sum C dq^d over the kept wavevectors */
  double window_power; /* mean(w^2) */
} bins;

static int bins_init(bins *b, double q_min, double q_max, double per_decade) {
  b->q_min = q_min;
  b->q_max = q_max;
  b->per_decade = per_decade;
  b->n = (size_t)floor(per_decade * log10(q_max / q_min) + 0.5) + 1;
  b->w = calloc(b->n, sizeof *b->w);
  b->wc = calloc(b->n, sizeof *b->wc);
  b->wlnq = calloc(b->n, sizeof *b->wlnq);
  b->band_power = 0.0;
  return b->w && b->wc && b->wlnq;
}

static void bins_free(bins *b) {
  free(b->w);
  free(b->wc);
  free(b->wlnq);
}

/* Adds C at |q| with weight (the number of lattice points it stands for)
 * to the bin means, and power (C times the lattice cells it stands for) to
 * the band power, if q is in the band. The band's edges get a relative
 * slack of 1e-9 (rounding of 2 pi k/L). */
static void bins_add(bins *b, double q, double c, double weight, double power) {
  if (q < b->q_min * (1.0 - 1e-9) || q > b->q_max * (1.0 + 1e-9)) return;
  double x = floor(b->per_decade * log10(q / b->q_min) + 0.5);
  size_t j = x <= 0.0 ? 0 : (size_t)x;
  if (j >= b->n) j = b->n - 1;
  b->w[j] += weight;
  b->wc[j] += weight * c;
  b->wlnq[j] += weight * log(q);
  b->band_power += power;
}

/* The non-empty bins as points (q, C, count); returns how many. A bin of
 * zero power (a spectral line elsewhere, no window) has no point: the
 * tabulated PSD is positive. */
static size_t bins_points(const bins *b, double *q, double *c, size_t *count) {
  size_t m = 0;
  for (size_t j = 0; j < b->n; j++) {
    if (!(b->w[j] > 0.0 && b->wc[j] > 0.0)) continue;
    q[m] = exp(b->wlnq[j] / b->w[j]);
    c[m] = b->wc[j] / b->w[j];
    count[m] = (size_t)llround(b->w[j]);
    m++;
  }
  return m;
}

/* ---- spectra ----------------------------------------------------------- */

/* The detrended, windowed heights of t into in[] (row-major); returns
 * mean(w^2) of the (separable) window, or -1 without memory. Without a
 * window (periodic data) only the mean is removed: a plane would turn the
 * periodic heights into a sawtooth whose jump leaks power ~ q^-2. */
static double windowed(const vl_topography *t, double taper, double *in) {
  double *wx = malloc(t->nx * sizeof *wx), *wy = malloc(t->ny * sizeof *wy);
  double w2 = -1.0;
  if (!wx || !wy) goto cleanup;
  w2 = make_window(taper, t->nx, wx);
  if (t->ny > 1)
    w2 *= make_window(taper, t->ny, wy);
  else
    wy[0] = 1.0;
  plane p = fit_plane(t);
  if (taper == 0.0) p.bx = p.by = 0.0;
  for (size_t i = 0; i < t->ny; i++)
    for (size_t j = 0; j < t->nx; j++)
      in[i * t->nx + j] = wy[i] * wx[j] * residual(t, &p, i, j);

cleanup:
  free(wx);
  free(wy);
  return w2;
}

/* Map: 2-D FFT, every wavevector of the half plane FFTW returns (weight 2
 * where its mirror -q is not stored), C from step 3 of topography.h. */
static vl_status map_spectrum(const vl_topography *t, double taper, bins *b) {
  vl_status st = VL_ENOMEM;
  size_t nx = t->nx, ny = t->ny, hx = nx / 2 + 1;
  double *in = fftw_alloc_real(nx * ny);
  fftw_complex *out = fftw_alloc_complex(ny * hx);
  fftw_plan plan = NULL;
  if (!in || !out) goto cleanup;
  plan = fftw_plan_dft_r2c_2d((int)ny, (int)nx, in, out, FFTW_ESTIMATE);
  if (!plan) goto cleanup;
  double w2 = windowed(t, taper, in);
  if (w2 < 0.0) goto cleanup;
  b->window_power = w2;
  fftw_execute(plan);
  double lx = (double)nx * t->dx_m, ly = (double)ny * t->dy_m;
  double dqx = TWO_PI / lx, dqy = TWO_PI / ly;
  double scale = (t->dx_m * t->dy_m) * (t->dx_m * t->dy_m) / (TWO_PI * TWO_PI * lx * ly) / w2;
  for (size_t i = 0; i < ny; i++) {
    double ky = i <= ny / 2 ? (double)i : (double)i - (double)ny;
    for (size_t j = 0; j < hx; j++) {
      double qx = dqx * (double)j, qy = dqy * ky;
      double q = hypot(qx, qy);
      if (q == 0.0) continue;
      double re = out[i * hx + j][0], im = out[i * hx + j][1];
      double weight = (j == 0 || 2 * j == nx) ? 1.0 : 2.0;
      double c = (re * re + im * im) * scale;
      bins_add(b, q, c, weight, weight * c * dqx * dqy);
    }
  }
  st = VL_OK;

cleanup:
  if (plan) fftw_destroy_plan(plan);
  fftw_free(in);
  fftw_free(out);
  return st;
}

/* Line: 1-D FFT, C1 of step 3 at q_k = 2 pi k / L for k >= 1; the band
 * power counts +-q (weight 2, 1 for the Nyquist frequency), the bin means
 * are over k > 0 alone (C1 is even). */
static vl_status line_spectrum(const vl_topography *t, double taper, bins *b) {
  vl_status st = VL_ENOMEM;
  size_t n = t->nx, h = n / 2 + 1;
  double *in = fftw_alloc_real(n);
  fftw_complex *out = fftw_alloc_complex(h);
  fftw_plan plan = NULL;
  if (!in || !out) goto cleanup;
  plan = fftw_plan_dft_r2c_1d((int)n, in, out, FFTW_ESTIMATE);
  if (!plan) goto cleanup;
  double w2 = windowed(t, taper, in);
  if (w2 < 0.0) goto cleanup;
  b->window_power = w2;
  fftw_execute(plan);
  double l = (double)n * t->dx_m, dq = TWO_PI / l;
  double scale = t->dx_m * t->dx_m / (TWO_PI * l) / w2;
  for (size_t k = 1; k < h; k++) {
    double re = out[k][0], im = out[k][1], c1 = (re * re + im * im) * scale;
    bins_add(b, dq * (double)k, c1, 1.0, (2 * k == n ? 1.0 : 2.0) * c1 * dq);
  }
  st = VL_OK;

cleanup:
  if (plan) fftw_destroy_plan(plan);
  fftw_free(in);
  fftw_free(out);
  return st;
}

/* ---- the PSD ------------------------------------------------------------- */

vl_topography_psd_options vl_topography_psd_options_default(void) {
  vl_topography_psd_options o = {VL_TOPOGRAPHY_TAPER, 10.0, 1.0, 0.5, 1};
  return o;
}

void vl_topography_spectrum_free(vl_topography_spectrum *p) {
  if (!p) return;
  free(p->q_per_m);
  free(p->c_m4);
  free(p->count);
  free(p->q1_per_m);
  free(p->c1_m3);
  memset(p, 0, sizeof *p);
}

static vl_status check_options(const vl_topography *t, const vl_topography_psd_options *o,
                               vl_error *err) {
  if (!t || !t->h_m || t->nx < VL_TOPOGRAPHY_MIN_POINTS ||
      (t->kind == VL_TOPOGRAPHY_MAP && t->ny < VL_TOPOGRAPHY_MIN_POINTS) || !(t->dx_m > 0.0) ||
      (t->kind == VL_TOPOGRAPHY_MAP && !(t->dy_m > 0.0)) || t->nx > INT_MAX || t->ny > INT_MAX) {
    vl_error_set(err, "%s: not a readable topography (size or pixel)",
                 t && t->source ? t->source : "<topography>");
    return VL_EINPUT;
  }
  if (!(isfinite(o->taper) && o->taper >= 0.0 && o->taper <= 1.0)) {
    vl_error_set(err, "topography PSD: the window taper must be in [0, 1] (1: Hann; got %g)",
                 o->taper);
    return VL_EINPUT;
  }
  if (!(isfinite(o->bins_per_decade) && o->bins_per_decade > 0.0 && o->bins_per_decade <= 100.0)) {
    vl_error_set(err, "topography PSD: bins per decade must be in (0, 100] (got %g)",
                 o->bins_per_decade);
    return VL_EINPUT;
  }
  if (!(isfinite(o->long_cut) && o->long_cut >= 1.0)) {
    vl_error_set(err, "topography PSD: the long-wavelength cut must be >= 1 (x 2 pi/L; got %g)",
                 o->long_cut);
    return VL_EINPUT;
  }
  if (!(isfinite(o->short_cut) && o->short_cut > 0.0 && o->short_cut <= 1.0)) {
    vl_error_set(err,
                 "topography PSD: the short-wavelength cut must be in (0, 1] (x pi/dx; got "
                 "%g)",
                 o->short_cut);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* Line scans: keeps the binned C1 in out and replaces (q, c) by the 2-D
 * points with C > 0 (inverse Abel transform, abel.h, each bin weighted by
 * the wavevectors it holds); *m is updated. */
static vl_status line_to_2d(vl_topography_spectrum *out, double *q, double *c, size_t *count,
                            size_t *m) {
  size_t n = *m;
  vl_status st = VL_ENOMEM;
  double *c2 = malloc(n * sizeof *c2);
  out->q1_per_m = malloc(n * sizeof *out->q1_per_m);
  out->c1_m3 = malloc(n * sizeof *out->c1_m3);
  if (c2 && out->q1_per_m && out->c1_m3)
    st = vl_abel_profile_to_surface(n, q, c, count, c2, &out->tail_slope);
  if (st != VL_OK) {
    free(c2);
    return st;
  }
  memcpy(out->q1_per_m, q, n * sizeof *q);
  memcpy(out->c1_m3, c, n * sizeof *c);
  out->n1 = n;
  size_t kept = 0;
  for (size_t j = 0; j < n; j++) {
    if (!(c2[j] > 0.0 && isfinite(c2[j]))) {
      out->n_dropped++;
      continue;
    }
    q[kept] = q[j];
    c[kept] = c2[j];
    count[kept] = count[j];
    kept++;
  }
  *m = kept;
  free(c2);
  return VL_OK;
}

/* Step 7: the first point's C continued down to the radius q_e of a disc of
 * one lattice cell. The cells of the wavevectors |q| >= 2 pi/L tile the
 * plane outside the cell of q = 0, so the tabulated spectrum, which is
 * zero below its first point, would otherwise drop about half the power of
 * the lowest ring (four wavevectors at 2 pi/L: a large share of h_rms^2
 * when nothing rolls off within the measurement). A line scan of length L
 * is treated as a square L x L. */
static void extend_low(const vl_topography *t, vl_topography_spectrum *out) {
  double lx = (double)t->nx * t->dx_m;
  double ly = t->kind == VL_TOPOGRAPHY_MAP ? (double)t->ny * t->dy_m : lx;
  double qe = sqrt(TWO_PI / lx * TWO_PI / ly / PI);
  if (!(qe < out->q_per_m[0])) return;
  memmove(out->q_per_m + 1, out->q_per_m, out->n * sizeof *out->q_per_m);
  memmove(out->c_m4 + 1, out->c_m4, out->n * sizeof *out->c_m4);
  memmove(out->count + 1, out->count, out->n * sizeof *out->count);
  out->q_per_m[0] = qe;
  out->c_m4[0] = out->c_m4[1];
  out->count[0] = 0;
  out->n++;
  out->extended = 1;
}

static void provenance(const vl_topography *t, const vl_topography_psd_options *o,
                       vl_topography_spectrum *out) {
  char size[160], steps[200];
  char window[64];
  if (o->taper >= 1.0)
    snprintf(window, sizeof window, "Hann window");
  else if (o->taper > 0.0)
    snprintf(window, sizeof window, "Tukey window (taper %.3g)", o->taper);
  else
    snprintf(window, sizeof window, "no window");
  if (t->kind == VL_TOPOGRAPHY_MAP)
    snprintf(size, sizeof size, "height map %zu x %zu px, %.4g x %.4g m (pixel %.4g x %.4g m%s)",
             t->nx, t->ny, (double)t->nx * t->dx_m, (double)t->ny * t->dy_m, t->dx_m, t->dy_m,
             t->square_assumed ? ", square assumed: no '# Height:'" : "");
  else
    snprintf(size, sizeof size, "line scan %zu points over %.4g m (dx %.4g m)", t->nx,
             (double)t->nx * t->dx_m, t->dx_m);
  if (t->kind == VL_TOPOGRAPHY_MAP)
    snprintf(steps, sizeof steps, "plane removed; %s (power / %.4g); 2-D FFT, radial average",
             window, out->window_power);
  else
    snprintf(steps, sizeof steps,
             "line removed; %s (power / %.4g); 1-D FFT, inverse Abel "
             "transform to 2-D (C1 tail slope %.3g; %zu points dropped, C <= 0)",
             window, out->window_power, out->tail_slope, out->n_dropped);
  snprintf(out->provenance, sizeof out->provenance,
           "%s; %s; %.3g log bins per decade over q = %.4g ... %.4g 1/m (%.3g x 2 pi/L ... %.3g x "
           "pi/dx); %zu points; h_rms: topography %.4g m, band %.4g m, tabulated PSD %.4g m",
           size, steps, o->bins_per_decade, out->q_min_per_m, out->q_max_per_m, o->long_cut,
           o->short_cut, out->n, out->hrms_topography_m, out->hrms_band_m, out->hrms_psd_m);
}

vl_status vl_topography_psd(const vl_topography *t, const vl_topography_psd_options *opt,
                            vl_topography_spectrum *out, vl_error *err) {
  vl_topography_psd_options o = opt ? *opt : vl_topography_psd_options_default();
  vl_status st;
  bins b = {0};
  vl_psd tab = {0};
  int map = t && t->kind == VL_TOPOGRAPHY_MAP;
  const char *src = t && t->source ? t->source : "<topography>";

  memset(out, 0, sizeof *out);
  st = check_options(t, &o, err);
  if (st != VL_OK) return st;
  double l = map ? fmin((double)t->nx * t->dx_m, (double)t->ny * t->dy_m) : (double)t->nx * t->dx_m;
  double pixel = map ? fmax(t->dx_m, t->dy_m) : t->dx_m;
  out->q_min_per_m = o.long_cut * TWO_PI / l;
  out->q_max_per_m = o.short_cut * PI / pixel;
  if (!(out->q_max_per_m > out->q_min_per_m)) {
    vl_error_set(err, "%s: the band is empty (q_min %g >= q_max %g 1/m)", src, out->q_min_per_m,
                 out->q_max_per_m);
    return VL_EINPUT;
  }
  st = VL_ENOMEM;
  if (!bins_init(&b, out->q_min_per_m, out->q_max_per_m, o.bins_per_decade)) goto cleanup;
  st = map ? map_spectrum(t, o.taper, &b) : line_spectrum(t, o.taper, &b);
  if (st != VL_OK) goto cleanup;
  st = VL_ENOMEM;
  out->window_power = b.window_power;
  out->q_per_m = malloc((b.n + 1) * sizeof *out->q_per_m); /* + 1: step 7 */
  out->c_m4 = malloc((b.n + 1) * sizeof *out->c_m4);
  out->count = malloc((b.n + 1) * sizeof *out->count);
  if (!out->q_per_m || !out->c_m4 || !out->count) goto cleanup;
  out->n = bins_points(&b, out->q_per_m, out->c_m4, out->count);
  out->hrms_topography_m = vl_topography_hrms(t);
  out->hrms_band_m = sqrt(b.band_power);
  if (!(b.band_power > 0.0) || !(out->hrms_topography_m > FLAT_TOL * raw_rms(t))) {
    vl_error_set(err, "%s: no roughness left after removing the %s: the heights are flat", src,
                 map ? "plane" : "line");
    st = VL_EINPUT;
    goto cleanup;
  }
  if (!map && out->n >= 2) {
    st = line_to_2d(out, out->q_per_m, out->c_m4, out->count, &out->n);
    if (st != VL_OK) goto cleanup;
  }
  if (o.extend_low && o.long_cut == 1.0 && out->n >= 2) extend_low(t, out);
  if (out->n < 2) {
    vl_error_set(err,
                 "%s: only %zu point(s) of the spectrum in the band q = %g ... %g 1/m: too "
                 "short a measurement for a PSD",
                 src, out->n, out->q_min_per_m, out->q_max_per_m);
    st = VL_EINPUT;
    goto cleanup;
  }
  st = vl_psd_init_tabulated(&tab, out->n, out->q_per_m, out->c_m4, err);
  if (st != VL_OK) {
    vl_error_prefix(err, "%s: the estimated PSD", src);
    goto cleanup;
  }
  out->hrms_psd_m = vl_psd_hrms(&tab);
  provenance(t, &o, out);
  st = VL_OK;

cleanup:
  if (st == VL_ENOMEM) vl_error_set(err, "%s: out of memory for the PSD", src);
  bins_free(&b);
  vl_psd_free(&tab);
  if (st != VL_OK) vl_topography_spectrum_free(out);
  return st;
}
