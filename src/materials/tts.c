/* Time-temperature superposition: pairwise shifts and the WLF fit (tts.h). */
#include "tts.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bracket.h"

#define COARSE_STEP 0.05 /* decades: the global scan */
#define SCAN_STEP 0.005  /* decades: the fine scan around the coarse minimum */
#define MIN_OVERLAP_FRAC 0.25
#define MIN_OVERLAP_POINTS 3
#define GOLDEN 0.6180339887498949
/* The shift found with E' and E'' together stands when E' alone superposes
 * there within this factor of its own best mismatch (plus a floor in log10
 * for data without noise): E'' then tells the same story and adds the
 * information E' lacks on its plateaus. Worse means E'' does not superpose
 * (secondary relaxations below the glass transition), and E' decides. */
#define CONSISTENT_RATIO 1.5
#define CONSISTENT_FLOOR 1e-3
#define WLF_C2_MAX 1e5 /* K: beyond this WLF is a straight line in T */
#define WLF_SCAN 400

/* A curve with distinct, increasing x (repeats averaged). */
typedef struct {
  size_t n;
  double *x, *y1, *y2;
} curve;

static void curve_free(curve *c) {
  free(c->x);
  free(c->y1);
  free(c->y2);
  memset(c, 0, sizeof *c);
}

static vl_status curve_make(const vl_tts_isotherm *iso, curve *c) {
  memset(c, 0, sizeof *c);
  c->x = malloc(iso->n * sizeof *c->x);
  c->y1 = malloc(iso->n * sizeof *c->y1);
  c->y2 = malloc(iso->n * sizeof *c->y2);
  if (!c->x || !c->y1 || !c->y2) {
    curve_free(c);
    return VL_ENOMEM;
  }
  for (size_t k = 0; k < iso->n;) {
    size_t j = k;
    double s1 = 0.0, s2 = 0.0;
    while (j < iso->n && iso->log10_omega[j] == iso->log10_omega[k]) {
      s1 += iso->log10_storage[j];
      s2 += iso->log10_loss[j];
      j++;
    }
    c->x[c->n] = iso->log10_omega[k];
    c->y1[c->n] = s1 / (double)(j - k);
    c->y2[c->n] = s2 / (double)(j - k);
    c->n++;
    k = j;
  }
  return VL_OK;
}

/* Slope of column y of c at point k: the three-point (parabola) derivative,
 * one-sided at the ends; the chord with only two points. */
static double curve_slope(const curve *c, const double *y, size_t k) {
  if (c->n < 3) return (y[1] - y[0]) / (c->x[1] - c->x[0]);
  size_t m = k == 0 ? 1 : k == c->n - 1 ? c->n - 2 : k;
  double h0 = c->x[m] - c->x[m - 1], h1 = c->x[m + 1] - c->x[m];
  double s0 = (y[m] - y[m - 1]) / h0, s1 = (y[m + 1] - y[m]) / h1;
  if (k == m) return (h1 * s0 + h0 * s1) / (h0 + h1);
  if (k < m) return s0 - h0 * (s1 - s0) / (h0 + h1);
  return s1 + h1 * (s1 - s0) / (h0 + h1);
}

/* Value of c at x (x within [x0, x_{n-1}]): a cubic Hermite interpolant
 * with three-point slopes. Not piecewise-linear: a chord between points
 * 1/3 decade apart misses a curved log E by up to ~0.01 decade, and that
 * error vanishes only where the two curves' points coincide, so the
 * mismatch had spurious minima at shifts of whole point spacings (on
 * pyvisco's isotherms three neighbouring pairs locked at 5/3 decades). */
static void curve_at(const curve *c, double x, double *y1, double *y2) {
  size_t lo = vl_bracket(c->x, c->n, x), hi = lo + 1;
  double h = c->x[hi] - c->x[lo], t = (x - c->x[lo]) / h;
  if (t < 0.0) t = 0.0;
  if (t > 1.0) t = 1.0;
  double t2 = t * t, t3 = t2 * t;
  double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
  *y1 = h00 * c->y1[lo] + h01 * c->y1[hi] +
        h * (h10 * curve_slope(c, c->y1, lo) + h11 * curve_slope(c, c->y1, hi));
  *y2 = h00 * c->y2[lo] + h01 * c->y2[hi] +
        h * (h10 * curve_slope(c, c->y2, lo) + h11 * curve_slope(c, c->y2, hi));
}

/* Mean squared log mismatches of b shifted by d against a over their
 * overlap: *s1 of log E', *s2 of log E''; *count gets the data points of
 * the two curves within the overlap. Returns 0 when the overlap is too
 * small to judge. The mean is over the overlap interval (MISMATCH_SAMPLES
 * midpoints of the two interpolants), not over the data points in it: a
 * point-set mean jumps whenever a point enters or leaves the overlap, and
 * those jumps made spurious minima at shifts of whole point spacings
 * (with the interpolation error, which also vanishes there). */
#define MISMATCH_SAMPLES 48
static int mismatch_parts(const curve *a, const curve *b, double d, double *s1, double *s2,
                          size_t *count) {
  *s1 = *s2 = 0.0;
  *count = 0;
  double lo = fmax(a->x[0], b->x[0] + d), hi = fmin(a->x[a->n - 1], b->x[b->n - 1] + d);
  double wa = a->x[a->n - 1] - a->x[0], wb = b->x[b->n - 1] - b->x[0];
  if (!(hi - lo >= MIN_OVERLAP_FRAC * fmin(wa, wb)) || !(hi > lo)) return 0;
  for (size_t j = 0; j < b->n; j++)
    *count += b->x[j] + d >= lo && b->x[j] + d <= hi;
  for (size_t i = 0; i < a->n; i++)
    *count += a->x[i] >= lo && a->x[i] <= hi;
  for (int k = 0; k < MISMATCH_SAMPLES; k++) {
    double x = lo + (hi - lo) * (k + 0.5) / MISMATCH_SAMPLES, a1, a2, b1, b2;
    curve_at(a, x, &a1, &a2);
    curve_at(b, x - d, &b1, &b2);
    *s1 += (a1 - b1) * (a1 - b1) / MISMATCH_SAMPLES;
    *s2 += (a2 - b2) * (a2 - b2) / MISMATCH_SAMPLES;
  }
  return *count >= MIN_OVERLAP_POINTS;
}

/* Mean squared mismatch of log E' plus wl times that of log E'', or
 * INFINITY when the overlap is too small to judge. */
static double mismatch(const curve *a, const curve *b, double d, double wl) {
  double s1, s2;
  size_t n;
  if (!mismatch_parts(a, b, d, &s1, &s2, &n)) return INFINITY;
  return (s1 + wl * s2) / (1.0 + wl);
}

/* The best shifts of cb onto ca for nw loss weights wl[] at once (one
 * coarse scan serves all; see vl_tts_pair_shift); ta, tb name the
 * isotherms in messages. */
static vl_status shift_curves(const curve *ca, const curve *cb, size_t nw, const double *wl,
                              double ta, double tb, double *shift, double *rms, vl_error *err) {
  if (ca->n < 2 || cb->n < 2) {
    vl_error_set(err, "the isotherm at %.4g C has fewer than 2 distinct frequencies",
                 ca->n < 2 ? ta : tb);
    return VL_EINPUT;
  }
  double d_lo = ca->x[0] - cb->x[cb->n - 1], d_hi = ca->x[ca->n - 1] - cb->x[0];
  double best[2] = {NAN, NAN}, best_f[2] = {INFINITY, INFINITY};
  /* coarse scan of the whole range */
  size_t steps = (size_t)ceil((d_hi - d_lo) / COARSE_STEP);
  for (size_t k = 0; k <= steps; k++) {
    double d = d_lo + (d_hi - d_lo) * (double)k / (double)(steps ? steps : 1), s1, s2;
    size_t n;
    if (!mismatch_parts(ca, cb, d, &s1, &s2, &n)) continue;
    for (size_t w = 0; w < nw; w++) {
      double f = (s1 + wl[w] * s2) / (1.0 + wl[w]);
      if (f < best_f[w]) best_f[w] = f, best[w] = d;
    }
  }
  if (!isfinite(best_f[0])) {
    vl_error_set(err,
                 "the isotherms at %.4g C and %.4g C cannot be superposed: their frequency "
                 "windows cannot overlap by a quarter of the narrower one",
                 ta, tb);
    return VL_EINPUT;
  }
  for (size_t w = 0; w < nw; w++) {
    /* a fine scan around the coarse minimum, then golden section */
    double centre = best[w];
    int half = (int)ceil(COARSE_STEP / SCAN_STEP);
    for (int k = -half; k <= half; k++) {
      double d = centre + k * SCAN_STEP;
      if (d < d_lo || d > d_hi) continue;
      double f = mismatch(ca, cb, d, wl[w]);
      if (f < best_f[w]) best_f[w] = f, best[w] = d;
    }
    double lo = best[w] - SCAN_STEP, hi = best[w] + SCAN_STEP;
    double c = hi - GOLDEN * (hi - lo), d = lo + GOLDEN * (hi - lo);
    double fc = mismatch(ca, cb, c, wl[w]), fd = mismatch(ca, cb, d, wl[w]);
    for (int it = 0; it < 30; it++) {
      if (fc < fd) {
        hi = d, d = c, fd = fc;
        c = hi - GOLDEN * (hi - lo);
        fc = mismatch(ca, cb, c, wl[w]);
      } else {
        lo = c, c = d, fc = fd;
        d = lo + GOLDEN * (hi - lo);
        fd = mismatch(ca, cb, d, wl[w]);
      }
    }
    double mid = 0.5 * (lo + hi), fm = mismatch(ca, cb, mid, wl[w]);
    if (fm < best_f[w]) best_f[w] = fm, best[w] = mid;
    shift[w] = best[w];
    if (rms) rms[w] = sqrt(best_f[w]);
  }
  return VL_OK;
}

/* Both isotherms as curves (on failure nothing is left allocated). */
static vl_status curve_pair(const vl_tts_isotherm *a, const vl_tts_isotherm *b, curve *ca,
                            curve *cb, vl_error *err) {
  memset(cb, 0, sizeof *cb);
  vl_status st;
  if ((st = curve_make(a, ca)) != VL_OK || (st = curve_make(b, cb)) != VL_OK) {
    curve_free(ca);
    vl_error_set(err, "out of memory shifting isotherms");
  }
  return st;
}

vl_status vl_tts_pair_shift(const vl_tts_isotherm *a, const vl_tts_isotherm *b, double loss_weight,
                            double *shift, double *rms, vl_error *err) {
  curve ca, cb;
  vl_status st = curve_pair(a, b, &ca, &cb, err);
  if (st != VL_OK) return st;
  double r;
  st = shift_curves(&ca, &cb, 1, &loss_weight, a->temperature_c, b->temperature_c, shift, &r, err);
  if (st == VL_OK && rms) *rms = r;
  curve_free(&ca);
  curve_free(&cb);
  return st;
}

/* Scatter of log E' along a curve: the rms residual (n - 3 degrees of
 * freedom) of a least-squares quadratic in log w; 0 when there are too few
 * points to tell. A curve that is not quadratic over its window reads as a
 * little noisier than it is, which only makes E'' more welcome. */
static double scatter(const curve *c, int q) {
  const double *yq = q ? c->y2 : c->y1;
  size_t n = c->n;
  if (n < 5) return 0.0;
  double xm = 0.0;
  for (size_t k = 0; k < n; k++)
    xm += c->x[k] / (double)n;
  double s[5] = {0}, r[3] = {0};
  for (size_t k = 0; k < n; k++) {
    double t = c->x[k] - xm, p = 1.0, y = yq[k];
    for (int j = 0; j < 5; j++, p *= t)
      s[j] += p;
    r[0] += y, r[1] += y * t, r[2] += y * t * t;
  }
  double m[3][4] = {{s[0], s[1], s[2], r[0]}, {s[1], s[2], s[3], r[1]}, {s[2], s[3], s[4], r[2]}};
  for (int i = 0; i < 3; i++) { /* Gauss-Jordan with partial pivoting */
    int piv = i;
    for (int j = i + 1; j < 3; j++)
      if (fabs(m[j][i]) > fabs(m[piv][i])) piv = j;
    for (int k = 0; k < 4; k++) {
      double tmp = m[i][k];
      m[i][k] = m[piv][k];
      m[piv][k] = tmp;
    }
    if (m[i][i] == 0.0) return 0.0;
    for (int j = 0; j < 3; j++) {
      if (j == i) continue;
      double f = m[j][i] / m[i][i];
      for (int k = i; k < 4; k++)
        m[j][k] -= f * m[i][k];
    }
  }
  double c0 = m[0][3] / m[0][0], c1 = m[1][3] / m[1][1], c2 = m[2][3] / m[2][2], ss = 0.0;
  for (size_t k = 0; k < n; k++) {
    double t = c->x[k] - xm, e = yq[k] - (c0 + c1 * t + c2 * t * t);
    ss += e * e;
  }
  return sqrt(ss / (double)(n - 3));
}

/* ---- bridging a thin overlap ----------------------------------------------
 *
 * When the best shift found from the overlap sits at the smallest overlap
 * allowed (MIN_OVERLAP_FRAC of the narrower window), the constraint, not
 * the data, decided it: the true shift lies further out, where the two
 * curves share too little frequency range to be compared point by point.
 * Cold isotherms near the glass transition are shifted by most of a
 * measured window per step, and there log E' is flat, so this is where a
 * cold isotherm used to land 0.6 decades off. The curves are then joined
 * by their trends: the points of each within BRIDGE_SPAN of the junction
 * (the end of a facing the other curve, and that end of b) are fitted
 * together, b shifted by d, by one polynomial of degree BRIDGE_DEGREE in
 * log w per quantity (log E', log E''); d minimises the residual. Both
 * point sets are fixed whatever d, so no d is favoured by comparing more
 * or fewer points. The shifts scanned run from the overlap constraint out
 * to a gap of BRIDGE_MAX_GAP between the windows. A cubic, because the
 * junction spans up to 4 decades: on noise-free Havriliak-Negami isotherms
 * 10 K apart across the glass transition the bridged shifts come within
 * 0.001 decade of the truth (a quadratic: 0.014), at 1 % noise within
 * 0.03. */
#define BRIDGE_SPAN 1.5
#define BRIDGE_DEGREE 3
#define BRIDGE_MAX_GAP 1.0
#define BRIDGE_MIN_POINTS 3 /* of each curve */
/* The joint fit may cost this many times the separate fits' residual
 * variance per extra parameter (F statistic; measured: up to 1.7 on
 * Havriliak-Negami isotherms at 1 % noise, 485 on pyvisco's glassy ones). */
#define BRIDGE_MAX_F 10.0
/* Scatter assumed at least (log10, 0.5 %), so that exact data, whose own
 * fits leave nothing, are not refused for the cubic's small misfit. */
#define BRIDGE_NOISE_FLOOR 0.002

/* Least-squares polynomial of degree BRIDGE_DEGREE through (x[k], y[k]):
 * the residual sum of squares (0 when there are too few points). */
static double poly_sse(size_t n, const double *x, const double *y) {
  enum { P = BRIDGE_DEGREE + 1 };
  if (n <= P) return 0.0;
  double xm = 0.0, xs = 0.0;
  for (size_t k = 0; k < n; k++)
    xm += x[k] / (double)n;
  for (size_t k = 0; k < n; k++)
    xs = fmax(xs, fabs(x[k] - xm));
  if (!(xs > 0.0)) xs = 1.0;
  double m[P][P + 1];
  memset(m, 0, sizeof m);
  for (size_t k = 0; k < n; k++) {
    double t = (x[k] - xm) / xs, pw[P];
    pw[0] = 1.0;
    for (int j = 1; j < P; j++)
      pw[j] = pw[j - 1] * t;
    for (int i = 0; i < P; i++) {
      for (int j = 0; j < P; j++)
        m[i][j] += pw[i] * pw[j];
      m[i][P] += pw[i] * y[k];
    }
  }
  for (int i = 0; i < P; i++) { /* Gauss-Jordan with partial pivoting */
    int piv = i;
    for (int j = i + 1; j < P; j++)
      if (fabs(m[j][i]) > fabs(m[piv][i])) piv = j;
    for (int k = 0; k <= P; k++) {
      double tmp = m[i][k];
      m[i][k] = m[piv][k];
      m[piv][k] = tmp;
    }
    if (m[i][i] == 0.0) return 0.0;
    for (int j = 0; j < P; j++) {
      if (j == i) continue;
      double f = m[j][i] / m[i][i];
      for (int k = i; k <= P; k++)
        m[j][k] -= f * m[i][k];
    }
  }
  double sse = 0.0;
  for (size_t k = 0; k < n; k++) {
    double t = (x[k] - xm) / xs, p = 1.0, fit = 0.0;
    for (int j = 0; j < P; j++, p *= t)
      fit += m[j][P] / m[j][j] * p;
    sse += (y[k] - fit) * (y[k] - fit);
  }
  return sse;
}

/* The points of a and b near their junction for shifts of sign `side`
 * (b's window sits above a's when side > 0): indices [a_lo, a_hi) of a and
 * [b_lo, b_hi) of b. Returns 0 when either has too few. */
typedef struct {
  size_t a_lo, a_hi, b_lo, b_hi;
  size_t n;      /* points in all */
  double *x, *y; /* scratch of n values */
} bridge;

static int bridge_init(const curve *a, const curve *b, int side, bridge *br) {
  memset(br, 0, sizeof *br);
  if (side < 0) { /* b below a: a's bottom, b's top */
    br->a_lo = 0;
    while (br->a_hi < a->n && a->x[br->a_hi] <= a->x[0] + BRIDGE_SPAN)
      br->a_hi++;
    br->b_hi = b->n;
    br->b_lo = b->n;
    while (br->b_lo > 0 && b->x[br->b_lo - 1] >= b->x[b->n - 1] - BRIDGE_SPAN)
      br->b_lo--;
  } else { /* b above a: a's top, b's bottom */
    br->a_hi = a->n;
    br->a_lo = a->n;
    while (br->a_lo > 0 && a->x[br->a_lo - 1] >= a->x[a->n - 1] - BRIDGE_SPAN)
      br->a_lo--;
    br->b_lo = 0;
    while (br->b_hi < b->n && b->x[br->b_hi] <= b->x[0] + BRIDGE_SPAN)
      br->b_hi++;
  }
  if (br->a_hi - br->a_lo < BRIDGE_MIN_POINTS || br->b_hi - br->b_lo < BRIDGE_MIN_POINTS) return 0;
  br->n = br->a_hi - br->a_lo + br->b_hi - br->b_lo;
  br->x = malloc(br->n * sizeof *br->x);
  br->y = malloc(br->n * sizeof *br->y);
  return br->x && br->y ? 1 : -1;
}

static void bridge_free(bridge *br) {
  free(br->x);
  free(br->y);
  br->x = br->y = NULL;
}

/* Residual sums of squares of the joint fits at shift d: *s1 of log E',
 * *s2 of log E''. */
static void bridge_sse(const curve *a, const curve *b, const bridge *br, double d, double *s1,
                       double *s2) {
  for (int q = 0; q < 2; q++) {
    size_t k = 0;
    for (size_t i = br->a_lo; i < br->a_hi; i++, k++)
      br->x[k] = a->x[i], br->y[k] = q ? a->y2[i] : a->y1[i];
    for (size_t j = br->b_lo; j < br->b_hi; j++, k++)
      br->x[k] = b->x[j] + d, br->y[k] = q ? b->y2[j] : b->y1[j];
    *(q ? s2 : s1) = poly_sse(br->n, br->x, br->y);
  }
}

/* The residual sum of squares of each curve's points near the junction
 * fitted on their own (log E', plus wl times log E''). */
static double bridge_separate(const curve *a, const curve *b, const bridge *br, double wl) {
  double sse = 0.0;
  size_t na = br->a_hi - br->a_lo, nb = br->b_hi - br->b_lo;
  for (int q = 0; q < 2; q++) {
    double w = q ? wl : 1.0;
    if (w == 0.0) continue;
    for (size_t i = 0; i < na; i++)
      br->x[i] = a->x[br->a_lo + i], br->y[i] = q ? a->y2[br->a_lo + i] : a->y1[br->a_lo + i];
    sse += w * poly_sse(na, br->x, br->y);
    for (size_t j = 0; j < nb; j++)
      br->x[j] = b->x[br->b_lo + j], br->y[j] = q ? b->y2[br->b_lo + j] : b->y1[br->b_lo + j];
    sse += w * poly_sse(nb, br->x, br->y);
  }
  return sse;
}

/* The bridged shift of b onto a for loss weight wl, scanned over
 * [d_from, d_to] (0.005 decade, then golden section); *f gets the
 * objective at it. */
static double bridge_shift(const curve *a, const curve *b, const bridge *br, double wl,
                           double d_from, double d_to, double *f) {
  double best = d_from, best_f = INFINITY, s1, s2;
  size_t steps = (size_t)ceil(fabs(d_to - d_from) / SCAN_STEP);
  for (size_t k = 0; k <= steps; k++) {
    double d = d_from + (d_to - d_from) * (double)k / (double)(steps ? steps : 1);
    bridge_sse(a, b, br, d, &s1, &s2);
    double v = s1 + wl * s2;
    if (v < best_f) best_f = v, best = d;
  }
  double lo = best - SCAN_STEP, hi = best + SCAN_STEP;
  for (int it = 0; it < 30; it++) {
    double c = hi - GOLDEN * (hi - lo), e = lo + GOLDEN * (hi - lo), fc, fe;
    bridge_sse(a, b, br, c, &s1, &s2);
    fc = s1 + wl * s2;
    bridge_sse(a, b, br, e, &s1, &s2);
    fe = s1 + wl * s2;
    if (fc < fe)
      hi = e;
    else
      lo = c;
  }
  double mid = 0.5 * (lo + hi);
  bridge_sse(a, b, br, mid, &s1, &s2);
  if (s1 + wl * s2 < best_f) best_f = s1 + wl * s2, best = mid;
  *f = best_f;
  return best;
}

/* Overlap (decades) of a and b shifted by d; negative for a gap. */
static double overlap_at(const curve *a, const curve *b, double d) {
  return fmin(a->x[a->n - 1], b->x[b->n - 1] + d) - fmax(a->x[0], b->x[0] + d);
}

/* The pair shift across a thin overlap or a gap (see above), by the
 * policy of pair_auto: E' and E'' together unless E' alone fits markedly
 * better. *info is left as it is when the curves have too few points near
 * their ends (bridged stays 0), or when they do not join into one smooth
 * curve (no_join set). */
static vl_status pair_bridge(const curve *a, const curve *b, double d_edge, double loss_w,
                             vl_tts_pair_info *info) {
  bridge br;
  int side = d_edge > 0.0 ? 1 : -1;
  int ok = bridge_init(a, b, side, &br);
  if (ok < 0) {
    bridge_free(&br);
    return VL_ENOMEM;
  }
  if (ok == 0) return VL_OK;
  /* from the overlap constraint out to the largest gap */
  double d_far = d_edge + side * (overlap_at(a, b, d_edge) + BRIDGE_MAX_GAP);
  double f[2], ds[2];
  const double wl[2] = {0.0, loss_w};
  for (int w = 0; w < 2; w++)
    ds[w] = bridge_shift(a, b, &br, wl[w], d_edge, d_far, &f[w]);
  double s1, s2, dof = (double)br.n - (BRIDGE_DEGREE + 1);
  bridge_sse(a, b, &br, ds[1], &s1, &s2);
  double r1_own = sqrt(f[0] / dof), r1_at_d2 = sqrt(s1 / dof);
  int both = r1_at_d2 <= CONSISTENT_RATIO * r1_own + CONSISTENT_FLOOR;
  /* one smooth curve through both? the joint fit against each curve's own
   * (BRIDGE_DEGREE + 1 parameters more): an F statistic near 1 when they
   * join, hundreds when they do not (glassy isotherms whose E'' does not
   * superpose): then the bridge would only pick a noise minimum */
  double f_sep = bridge_separate(a, b, &br, wl[both]);
  double extra = BRIDGE_DEGREE + 1.0, dof_sep = (double)br.n - 2.0 * extra;
  double var = dof_sep > 0.0 ? f_sep / dof_sep : 0.0;
  var = fmax(var, (1.0 + wl[both]) * BRIDGE_NOISE_FLOOR * BRIDGE_NOISE_FLOOR);
  if ((f[both] - f_sep) / extra > BRIDGE_MAX_F * var) {
    info->no_join = 1;
    bridge_free(&br);
    return VL_OK;
  }
  info->shift = ds[both];
  info->rms = sqrt(f[both] / ((1.0 + wl[both]) * dof));
  info->loss_used = both;
  info->loss_weight = both ? loss_w : 0.0;
  info->bridged = 1;
  info->at_limit = fabs(info->shift - d_far) < 2.0 * SCAN_STEP;
  bridge_free(&br);
  return VL_OK;
}

/* ---- weighing E' against E'' ---------------------------------------------
 *
 * Each quantity alone gives an estimate of the pair's shift; how well it
 * superposes there (its rms mismatch at its own best shift: noise, and
 * whatever does not shift with temperature) and how steep it is there fix
 * that estimate's standard error, se^2 = s^2 / (n <slope^2>) (least
 * squares in one parameter; <slope^2> from the isotherms' trends). Real
 * glassy isotherms show why both matter: on pyvisco's data E'' below the
 * glass transition barely moves with temperature (a secondary relaxation,
 * and a tan delta rising to 0.044 at 100 Hz at every temperature, an
 * instrument artefact) and superposes 10 to 30 times worse than E' (rms
 * 0.02 to 0.06 against 0.001 to 0.004 decade); E' alone gives pyvisco's own
 * shifts (E' alone) within 0.06 decade from 2.5 C up and 0.3 in the glass,
 * E'' pulled glassy steps to ~0.1 decade where pyvisco has 0.9 to 2.3
 * (tests/test_tts_pyvisco.c). So:
 *   - the two estimates must agree within SHIFT_AGREE standard errors
 *     (plus SHIFT_AGREE_FLOOR for the interpolants' own error on exact
 *     data), else E'' does not follow the superposition E' does and E'
 *     decides alone;
 *   - when they agree the shift minimises the mismatches weighted by the
 *     inverse of their variances, s1^2 / s1_own^2 + s2^2 / s2_own^2
 *     (loss weight s1_own^2 / s2_own^2, each at least SHIFT_NOISE_FLOOR):
 *     equal noise gives equal weights (synthetic data at equal relative
 *     noise: as before), E'' that superposes worse weighs less;
 *   - "misfit" is the rms mismatch at the own shift but at least the
 *     scatter of the quantity about a quadratic in log w (two isotherms in
 *     quadrature): on a flat noisy curve the own shift is a noise minimum
 *     whose mismatch understates the noise (a chain of synthetic rubbery
 *     isotherms at 1 % noise otherwise put one step 1.7 decades off). */
#define SHIFT_AGREE 3.0
#define SHIFT_AGREE_FLOOR 0.02  /* decades */
#define SHIFT_NOISE_FLOOR 0.002 /* log10 (0.5 %) */
/* An own shift held by the overlap constraint is a bound without a
 * standard error; a free E' rules it out only when its trend changes by
 * more than SHIFT_RULE times its misfit between its own shift and that
 * bound (measured: at most 1.0 on synthetic glassy isotherms at 1 % noise,
 * where the bound is the truth's side and bridging must decide; 4.3 to
 * 7.4 on pyvisco's 32 to 47 C pairs, whose E'' sits at the bound). */
#define SHIFT_RULE 2.0
#define LOSS_ONLY 1e6 /* a loss weight that leaves E' out in effect */

/* Least-squares slope of log E' (q = 0) or log E'' (q = 1) against
 * log w over the whole of c: the trend, not the local derivative, whose
 * wiggles on noisy data (a noise minimum of a flat E') would claim
 * information that is not there. */
static double trend_slope(const curve *c, int q) {
  double xm = 0.0, ym = 0.0, sxy = 0.0, sxx = 0.0;
  const double *y = q ? c->y2 : c->y1;
  for (size_t k = 0; k < c->n; k++)
    xm += c->x[k] / (double)c->n, ym += y[k] / (double)c->n;
  for (size_t k = 0; k < c->n; k++)
    sxy += (c->x[k] - xm) * (y[k] - ym), sxx += (c->x[k] - xm) * (c->x[k] - xm);
  return sxx > 0.0 ? sxy / sxx : 0.0;
}

/* Standard error of the shift d found on quantity q alone, whose rms
 * mismatch there is r: r over the trends' rms slope and the square root
 * of the points compared (INFINITY for flat curves: no information). */
static double shift_se(const curve *a, const curve *b, int q, double d, double r) {
  double s1, s2, sa = trend_slope(a, q), sb = trend_slope(b, q);
  size_t n;
  double slope2 = 0.5 * (sa * sa + sb * sb);
  if (!mismatch_parts(a, b, d, &s1, &s2, &n) || !(slope2 > 0.0)) return INFINITY;
  return fmax(r, SHIFT_NOISE_FLOOR) / sqrt((double)n * slope2);
}

/* The loss weight for the pair (above), or 0 when E'' and E' disagree. */
static vl_status loss_weight(const curve *ca, const curve *cb, double ta, double tb, double *wl,
                             vl_error *err) {
  const double w[2] = {0.0, LOSS_ONLY};
  double d[2], r[2], sd[2], se[2];
  vl_status st = shift_curves(ca, cb, 2, w, ta, tb, d, r, err);
  if (st != VL_OK) return st;
  for (int q = 0; q < 2; q++) { /* misfit at its own shift, at least its scatter */
    sd[q] = fmax(fmax(r[q], hypot(scatter(ca, q), scatter(cb, q))), SHIFT_NOISE_FLOOR);
    se[q] = shift_se(ca, cb, q, d[q], sd[q]);
  }
  double wa = ca->x[ca->n - 1] - ca->x[0], wb = cb->x[cb->n - 1] - cb->x[0];
  double min_ov = MIN_OVERLAP_FRAC * fmin(wa, wb) + 2.0 * SCAN_STEP;
  int edge1 = overlap_at(ca, cb, d[0]) <= min_ov, edge2 = overlap_at(ca, cb, d[1]) <= min_ov;
  if (edge1 || edge2) {
    /* a shift held by the overlap constraint is a bound, with no standard
     * error and a misfit that says nothing of how well that quantity
     * superposes: unless E' alone is free and rules the bound out, the
     * weights stay equal and bridging decides (pair_bridge) */
    double sa = trend_slope(ca, 0), sb = trend_slope(cb, 0);
    double change = fabs(d[0] - d[1]) * sqrt(0.5 * (sa * sa + sb * sb)) / sd[0];
    int e_rules = !edge1 && fabs(d[0] - d[1]) > SHIFT_AGREE * se[0] + SHIFT_AGREE_FLOOR &&
                  change > SHIFT_RULE;
    *wl = e_rules ? 0.0 : 1.0;
  } else {
    double tol = SHIFT_AGREE * hypot(se[0], se[1]) + SHIFT_AGREE_FLOOR;
    *wl = fabs(d[0] - d[1]) <= tol ? (sd[0] * sd[0]) / (sd[1] * sd[1]) : 0.0;
  }
  return VL_OK;
}

/* The shift of one neighbouring pair by the policy of vl_tts_chain: the
 * shift of log E' and log E'' together, d2 (weighted as above), unless
 * the two quantities' own shifts disagree, or E' alone mismatches at d2
 * markedly more than at its own best shift d1 and more than its scatter
 * explains (then E'' is not telling the story E' tells, and d1 stands).
 * The scatter term keeps a noise-fitted minimum of a flat E' (few points in
 * a small overlap) from looking better than it is. A shift held at the
 * smallest overlap allowed is found again by bridging (above). */
static vl_status pair_auto(const vl_tts_isotherm *a, const vl_tts_isotherm *b,
                           vl_tts_pair_info *info, vl_error *err) {
  curve ca, cb;
  vl_status st = curve_pair(a, b, &ca, &cb, err);
  if (st != VL_OK) return st;
  double wl[2] = {0.0, 1.0}, ds[2], rs[2];
  memset(info, 0, sizeof *info);
  st = loss_weight(&ca, &cb, a->temperature_c, b->temperature_c, &wl[1], err);
  if (st == VL_OK && wl[1] > 0.0)
    st = shift_curves(&ca, &cb, 2, wl, a->temperature_c, b->temperature_c, ds, rs, err);
  else if (st == VL_OK) /* E' alone */
    st = shift_curves(&ca, &cb, 1, wl, a->temperature_c, b->temperature_c, ds, rs, err),
    ds[1] = ds[0], rs[1] = rs[0];
  if (st == VL_OK) {
    /* the mismatch E' would show from its scatter alone, had it no trend */
    double noise = hypot(scatter(&ca, 0), scatter(&cb, 0));
    double r1_at_d2 = sqrt(mismatch(&ca, &cb, ds[1], 0.0));
    int both = wl[1] > 0.0 && r1_at_d2 <= CONSISTENT_RATIO * fmax(rs[0], noise) + CONSISTENT_FLOOR;
    info->shift = ds[both];
    info->rms = rs[both];
    info->loss_used = both;
    info->loss_weight = both ? wl[1] : 0.0;
    double wa = ca.x[ca.n - 1] - ca.x[0], wb = cb.x[cb.n - 1] - cb.x[0];
    double min_ov = MIN_OVERLAP_FRAC * fmin(wa, wb);
    /* the joint shift held at the constraint: E' alone cannot be trusted to
     * overrule it there (its own best shift may be a noise minimum of a flat
     * curve), so the pair is bridged whichever shift was taken */
    int edge2 = overlap_at(&ca, &cb, ds[1]) <= min_ov + 2.0 * SCAN_STEP && ds[1] != 0.0;
    int edge = overlap_at(&ca, &cb, info->shift) <= min_ov + 2.0 * SCAN_STEP && info->shift != 0.0;
    if (edge2 || edge) {
      st = pair_bridge(&ca, &cb, edge2 ? ds[1] : info->shift, wl[1] > 0.0 ? wl[1] : 1.0, info);
      if (st != VL_OK) vl_error_set(err, "out of memory shifting isotherms");
    }
    info->overlap_decades = overlap_at(&ca, &cb, info->shift);
  }
  curve_free(&ca);
  curve_free(&cb);
  return st;
}

vl_status vl_tts_chain_info(size_t n, const vl_tts_isotherm *iso, size_t ref, double *log10_a_t,
                            vl_tts_pair_info *info, vl_error *err) {
  if (n == 0 || ref >= n) {
    vl_error_set(err, "no isotherms to shift");
    return VL_EINPUT;
  }
  log10_a_t[ref] = 0.0;
  vl_tts_pair_info one;
  for (size_t k = ref; k + 1 < n; k++) {
    vl_status st = pair_auto(&iso[k], &iso[k + 1], &one, err);
    if (st != VL_OK) return st;
    log10_a_t[k + 1] = log10_a_t[k] + one.shift;
    if (info) info[k] = one;
  }
  for (size_t k = ref; k > 0; k--) {
    vl_status st = pair_auto(&iso[k - 1], &iso[k], &one, err);
    if (st != VL_OK) return st;
    log10_a_t[k - 1] = log10_a_t[k] - one.shift;
    if (info) info[k - 1] = one;
  }
  return VL_OK;
}

vl_status vl_tts_chain(size_t n, const vl_tts_isotherm *iso, size_t ref, double *log10_a_t,
                       double *pair_rms, vl_error *err) {
  vl_tts_pair_info *info = n > 1 ? malloc((n - 1) * sizeof *info) : NULL;
  if (n > 1 && !info) {
    vl_error_set(err, "out of memory shifting isotherms");
    return VL_ENOMEM;
  }
  vl_status st = vl_tts_chain_info(n, iso, ref, log10_a_t, info, err);
  for (size_t k = 0; st == VL_OK && pair_rms && k + 1 < n; k++)
    pair_rms[k] = info[k].rms;
  free(info);
  return st;
}

/* For fixed C2: the least-squares C1 and the sum of squared residuals. */
static double wlf_sse(size_t n, const double *u, const double *y, double c2, double *c1) {
  double sgy = 0.0, sgg = 0.0;
  for (size_t k = 0; k < n; k++) {
    double g = -u[k] / (c2 + u[k]);
    sgy += g * y[k];
    sgg += g * g;
  }
  double a = sgg > 0.0 ? sgy / sgg : 0.0, s = 0.0;
  for (size_t k = 0; k < n; k++) {
    double r = y[k] + a * u[k] / (c2 + u[k]);
    s += r * r;
  }
  *c1 = a;
  return s;
}

vl_status vl_wlf_fit(size_t n, const double *t_c, const double *log10_a_t, double tref_c,
                     double *c1, double *c2_k, double *rms, vl_error *err) {
  if (n < 3) {
    vl_error_set(err, "a WLF fit needs shifts at 3 or more temperatures (got %zu)", n);
    return VL_EINPUT;
  }
  double *u = malloc(n * sizeof *u);
  if (!u) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  double umin = INFINITY;
  for (size_t k = 0; k < n; k++) {
    if (!isfinite(t_c[k]) || !isfinite(log10_a_t[k])) {
      free(u);
      vl_error_set(err, "WLF fit: shift %zu is not finite", k + 1);
      return VL_EINPUT;
    }
    u[k] = t_c[k] - tref_c;
    umin = fmin(umin, u[k]);
  }
  /* C2 + (T - Tref) > 0 at every point: the WLF domain. */
  double c2_lo = fmax(0.0, -umin) + 0.01;
  double l_lo = log(c2_lo), l_hi = log(WLF_C2_MAX), best_l = l_lo, best_s = INFINITY, a;
  for (int k = 0; k <= WLF_SCAN; k++) {
    double l = l_lo + (l_hi - l_lo) * k / WLF_SCAN;
    double s = wlf_sse(n, u, log10_a_t, exp(l), &a);
    if (s < best_s) best_s = s, best_l = l;
  }
  double step = (l_hi - l_lo) / WLF_SCAN;
  double lo = fmax(l_lo, best_l - step), hi = fmin(l_hi, best_l + step);
  for (int it = 0; it < 80; it++) {
    double c = hi - GOLDEN * (hi - lo), d = lo + GOLDEN * (hi - lo);
    if (wlf_sse(n, u, log10_a_t, exp(c), &a) < wlf_sse(n, u, log10_a_t, exp(d), &a))
      hi = d;
    else
      lo = c;
  }
  double l = 0.5 * (lo + hi);
  double s = wlf_sse(n, u, log10_a_t, exp(l), &a);
  if (s > best_s) s = wlf_sse(n, u, log10_a_t, exp(l = best_l), &a);
  free(u);
  if (!(a > 0.0)) {
    vl_error_set(err,
                 "the shifts do not decrease with temperature (best WLF C1 = %.3g <= 0): "
                 "the isotherms do not follow time-temperature superposition",
                 a);
    return VL_EINPUT;
  }
  *c1 = a;
  *c2_k = exp(l);
  if (rms) *rms = sqrt(s / (double)n);
  return VL_OK;
}
