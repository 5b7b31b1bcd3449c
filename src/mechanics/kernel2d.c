/* viscolube: influence coefficients of the point contact (kernel2d.h).
 *
 * Love's rectangle. With F(X, Y) = X log(Y + R) + Y log(X + R), R = sqrt(X^2 +
 * Y^2), d^2 F/dX dY = 1/R, so the integral over the cell |x'| <= ax,
 * |y'| <= ay seen from (x, y) is the sum of F over the corners
 * (X, Y) = (x -+ ax, y -+ ay) with signs + - - +. Its first moment, the load
 * x'/(2 ax): x' = x - X, and d^2 G/dX dY = X/R for
 * G = (Y R + X^2 log(Y + R))/2, so the moment kernel is (x Kel - [G])/(2 ax).
 * X log(Y + R) with Y < 0 is written X log(X^2/(R - Y)) (no cancellation),
 * and 0 at X = 0.
 *
 * The memory's exponential cell (Kexp): the y' integral is closed,
 *   L(X', y) = \int dy' / sqrt(X'^2 + (y - y')^2) = log((c1 + s1)/(c2 + s2)),
 *   c1,2 = y +- ay, s = sqrt(c^2 + X'^2) (c + s = X'^2/(s - c) when c < 0),
 * log-singular at X' = 0 only when |y| < ay. The x' integral of
 * e^{-u/b} L, u = x' + ax, becomes b \int dv L with v = 1 - e^{-u/b} (the
 * boundary layer of a short memory absorbed in the variable), by 32-point
 * Gauss-Legendre, split at the singular point, its nodes clustered at the
 * singular ends of each piece (exp_piece).
 *
 * The cell-moment coefficients of the filtered load, in cell units
 * (beta = b/hx, z = 1/beta): E0 = \int_0^1 e^{-u/beta} du = (1 - r)/z,
 * m1 = \int_0^1 (u - 1/2) e^{-u/beta} du = beta^2 (1 - r) - beta r - E0/2,
 * which cancel for small z and are taken from their series there:
 *   1 - E0 = sum_{n>=2} (-1)^n z^(n-1)/n!,
 *   m1 = sum_{n>=1} (-z)^n/n! n/(2 (n+1)(n+2)).
 *
 * The far start of the recursive filter (d -> -inf, point-load limit): with
 * t = D + m cells upstream, Kexp ~ E0 hy [1/t + c3/t^3],
 * c3 = -eta^2/2 + (1/2 - (ay/hx)^2)/6 (the offset across, eta = y/hx, and
 * the cell's quadrupole), and sum_{m>=1} r^{m-1} t^-n is its midpoint
 * integral e^{z/2} e^x E_n(x) / (D + 1/2)^(n-1), x = (D + 1/2) z. */
#include "kernel2d.h"
#include "gsl_errors.h"

#include <gsl/gsl_sf_expint.h>
#include <math.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

/* Offsets (cells, both ways along x; across, from 0) whose exponential
 * cell is integrated instead of taken from its two moments: beyond, the
 * moments' error (the cell's second moment, falling like |d|^-3) is below
 * 6e-6 of Kel(0, 0) for every memory length (tests/test_kernel2d.c). */
#define KERNEL2D_NEAR 6

/* Memory lengths (in cells) for which the near cells are integrated: the
 * moments' error is about 0.5 beta Kel(0, 0) for beta << 1 and falls like
 * beta^-2 for beta >> 1 (1.5e-6 Kel(0, 0) at 100); below the lower bound
 * even a strength A of 1e4 leaves it under 1e-9. */
#define KERNEL2D_BETA_EXACT_MIN 1e-13
#define KERNEL2D_BETA_EXACT_MAX 64.0

/* Below this memory length (cells) a term is relaxed: it adds A Kel. */
#define KERNEL2D_BETA_RELAXED 1e-200

/* The upstream extension of the elastic tables, in units of the grid's
 * extent nx + 2 ny hy/hx: where the filter starts from the point-load
 * limit, whose neglected terms (t^-5) are then below 1e-5 of its value. */
#define KERNEL2D_EXT_FACTOR 8.0

/* A filter that has run this many memory lengths has forgotten its start
 * (e^-38 = 3e-17): shorter memories start at 0 that far upstream. */
#define KERNEL2D_FORGET 38.0

#define GL_N 32
static double gl_t[GL_N], gl_w[GL_N]; /* Gauss-Legendre on [0, 1] */
static pthread_once_t gl_once = PTHREAD_ONCE_INIT;

/* The 32-point Gauss-Legendre rule, by Newton's iteration on P_32 from
 * Tricomi's estimates of its roots. */
static void gl_build(void) {
  for (int i = 0; i < GL_N; i++) {
    double x = cos(M_PI * (i + 0.75) / (GL_N + 0.5)), dp = 1.0;
    for (int it = 0; it < 100; it++) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= GL_N; k++) {
        double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1, p1 = p2;
      }
      dp = GL_N * (x * p1 - p0) / (x * x - 1.0);
      double dx = p1 / dp;
      x -= dx;
      if (fabs(dx) < 1e-16) break;
    }
    gl_t[i] = 0.5 * (1.0 - x);
    gl_w[i] = 1.0 / ((1.0 - x * x) * dp * dp); /* half of 2/((1-x^2) P'^2) */
  }
}

/* X log(Y + R), R = |(X, Y)|, without cancellation; 0 at X = 0. */
static double xlog(double X, double Y) {
  if (X == 0.0) return 0.0;
  double R = hypot(X, Y);
  return Y >= 0.0 ? X * log(Y + R) : X * (2.0 * log(fabs(X)) - log(R - Y));
}

static double love_f(double X, double Y) { return xlog(X, Y) + xlog(Y, X); }

static double love_g(double X, double Y) { return 0.5 * (Y * hypot(X, Y) + X * xlog(X, Y)); }

double vl_kernel2d_rect(double x, double y, double ax, double ay) {
  return love_f(x + ax, y + ay) - love_f(x - ax, y + ay) - love_f(x + ax, y - ay) +
         love_f(x - ax, y - ay);
}

double vl_kernel2d_rect_moment(double x, double y, double ax, double ay) {
  double g = love_g(x + ax, y + ay) - love_g(x - ax, y + ay) - love_g(x + ax, y - ay) +
             love_g(x - ax, y - ay);
  return (x * vl_kernel2d_rect(x, y, ax, ay) - g) / (2.0 * ax);
}

/* log(c + sqrt(c^2 + X^2)) without cancellation (c < 0: X^2/(s - c)). */
static double log_cs(double c, double X) {
  double s = hypot(c, X);
  return c >= 0.0 ? log(c + s) : 2.0 * log(fabs(X)) - log(s - c);
}

/* L(X', y): the strip |y'| <= ay at the distance X' along x. */
static double strip(double Xp, double y, double ay) {
  return log_cs(y + ay, Xp) - log_cs(y - ay, Xp);
}

/* b \int_{v0}^{v1} L(X'(v), y) dv, X' = x + ax - u(v), u = -b log(1 - v),
 * by Gauss-Legendre in t with v = v0 + (v1 - v0) t^p (end = -1) or
 * v1 - (v1 - v0) t^p (end = +1), which clusters the nodes at that end: the
 * log singularity of L where X' = 0 (p = 5), or that of u(v) at v -> 1
 * when b is short against the cell (p = 3), then costs no accuracy. */
static double exp_piece(double x, double y, double ax, double ay, double b, double v0, double v1,
                        int end, int p) {
  double len = v1 - v0, s = 0.0;
  for (int i = 0; i < GL_N; i++) {
    double t = gl_t[i], tp = 1.0;
    for (int k = 1; k < p; k++)
      tp *= t;
    double jac = len * p * tp, dv = len * tp * t;
    double v = end < 0 ? v0 + dv : v1 - dv;
    double u = -b * log1p(-v);
    if (u > 2.0 * ax) u = 2.0 * ax; /* rounding of v near 1 - r */
    double Xp = x + ax - u;
    if (Xp != 0.0) s += gl_w[i] * jac * strip(Xp, y, ay); /* the singular point: weight 0 */
  }
  return b * s;
}

double vl_kernel2d_rect_exp(double x, double y, double ax, double ay, double b) {
  pthread_once(&gl_once, gl_build);
  double vmax = -expm1(-2.0 * ax / b), us = x + ax;
  bool short_b = 2.0 * ax > 4.0 * b; /* u(v) steep near vmax */
  if (!(fabs(y) < ay && us > 0.0 && us < 2.0 * ax))
    return exp_piece(x, y, ax, ay, b, 0.0, vmax, short_b ? +1 : -1, short_b ? 3 : 1);
  double vs = -expm1(-us / b), s = exp_piece(x, y, ax, ay, b, 0.0, vs, +1, 5);
  if (!short_b) return s + exp_piece(x, y, ax, ay, b, vs, vmax, -1, 5);
  double vm = 0.5 * (vs + vmax);
  return s + exp_piece(x, y, ax, ay, b, vs, vm, -1, 5) +
         exp_piece(x, y, ax, ay, b, vm, vmax, +1, 3);
}

/* The moments of the load e^{-u/beta} over a cell (u in cells from its
 * upstream edge): 1 - E0 and m1 (see the top of the file). */
static void exp_moments(double z, double *one_minus_e0, double *m1) {
  if (z < 0.5) {
    double term = 1.0, a = 0.0, m = 0.0; /* term = (-z)^n / n! */
    for (int n = 1; n < 40; n++) {
      term *= -z / n;
      a -= term / (n + 1);
      m += term * n / (2.0 * (n + 1) * (n + 2));
      if (fabs(term) < 1e-20) break;
    }
    *one_minus_e0 = a, *m1 = m;
    return;
  }
  double beta = 1.0 / z, r = exp(-z), omr = -expm1(-z), e0 = omr * beta;
  *one_minus_e0 = 1.0 - e0;
  *m1 = beta * beta * omr - beta * r - 0.5 * e0;
}

vl_status vl_kernel2d_init(vl_kernel2d *k, size_t nx, size_t ny, double hx, double hy,
                           vl_error *err) {
  memset(k, 0, sizeof *k);
  if (nx < 1 || ny < 1 || !(hx > 0.0) || !(hy > 0.0) || !isfinite(hx) || !isfinite(hy)) {
    vl_error_set(err, "point-contact kernel: need cells (%zu x %zu) and positive sizes", nx, ny);
    return VL_EINPUT;
  }
  vl_gsl_errors_off();
  pthread_once(&gl_once, gl_build);
  k->nx = nx, k->ny = ny, k->ne = 2 * ny, k->hx = hx, k->hy = hy;
  k->ext = (size_t)ceil(KERNEL2D_EXT_FACTOR * ((double)nx + (double)k->ne * hy / hx));
  k->nd = k->ext + 2 * nx - 1;
  size_t nc = 2 * nx - 1, nnear = 2 * KERNEL2D_NEAR + 1;
  k->kel = malloc(k->nd * k->ne * sizeof *k->kel);
  k->mom = malloc(k->nd * k->ne * sizeof *k->mom);
  k->coef = malloc(nc * k->ne * sizeof *k->coef);
  k->work = malloc((nnear * (KERNEL2D_NEAR + 1) + nc + nnear) * sizeof *k->work);
  if (!k->kel || !k->mom || !k->coef || !k->work) {
    vl_kernel2d_free(k);
    vl_error_set(err, "out of memory for a %zu x %zu point-contact kernel", nx, ny);
    return VL_ENOMEM;
  }
  double ax = 0.5 * hx, ay = 0.5 * hy;
  long dlo = -(long)(nx - 1) - (long)k->ext;
  for (size_t e = 0; e < k->ne; e++) {
    double y = (double)e * hy;
    for (size_t i = 0; i < k->nd; i++) {
      double x = (double)(dlo + (long)i) * hx;
      k->kel[e * k->nd + i] = vl_kernel2d_rect(x, y, ax, ay);
      k->mom[e * k->nd + i] = vl_kernel2d_rect_moment(x, y, ax, ay);
    }
    memcpy(k->coef + e * nc, k->kel + e * k->nd + k->ext, nc * sizeof *k->coef);
  }
  return VL_OK;
}

void vl_kernel2d_free(vl_kernel2d *k) {
  if (!k) return;
  free(k->kel), free(k->mom), free(k->coef), free(k->work);
  k->kel = k->mom = k->coef = k->work = NULL;
}

/* One Prony term's memory kernel F, times A, added to coef. */
typedef struct {
  double z, r, omr, e0, c0, s; /* 1/beta, e^-z, 1 - r, E0, 1 - E0, 12 m1 */
  size_t run;                  /* cells upstream of the grid the filter starts */
  bool near;                   /* the near cells integrated (delta holds them) */
} term_filter;

/* The far start of the filter at offset D cells upstream (top of file). */
static double filter_start(const vl_kernel2d *k, const term_filter *tf, size_t e, double D) {
  double x = (D + 0.5) * tf->z, eta = (double)e * k->hy / k->hx, q = 0.5 * k->hy / k->hx;
  double c3 = -0.5 * eta * eta + (0.5 - q * q) / 6.0;
  double e1 = gsl_sf_expint_E1_scaled(x), e3 = gsl_sf_expint_En_scaled(3, x);
  double v = tf->omr * tf->e0 * k->hy * exp(0.5 * tf->z) * (e1 + c3 * e3 / ((D + 0.5) * (D + 0.5)));
  return isfinite(v) ? v : 0.0;
}

/* delta(d', e) = Kexp by quadrature - its two moments, for the near cells
 * (|d'| <= NEAR, e <= NEAR), into delta[(d' + NEAR) * (NEAR + 1) + e]. */
static void near_cells(const vl_kernel2d *k, const term_filter *tf, double b, double *delta) {
  double ax = 0.5 * k->hx, ay = 0.5 * k->hy;
  size_t ne = k->ne < KERNEL2D_NEAR + 1 ? k->ne : KERNEL2D_NEAR + 1;
  for (long dp = -KERNEL2D_NEAR; dp <= KERNEL2D_NEAR; dp++)
    for (size_t e = 0; e < KERNEL2D_NEAR + 1; e++) {
      double *dl = delta + (size_t)(dp + KERNEL2D_NEAR) * (KERNEL2D_NEAR + 1) + e;
      *dl = 0.0;
      if (e >= ne) continue;
      size_t i = e * k->nd + (size_t)(dp + (long)(k->nx - 1) + (long)k->ext);
      double mom = tf->e0 * k->kel[i] + tf->s * k->mom[i];
      *dl = vl_kernel2d_rect_exp((double)dp * k->hx, (double)e * k->hy, ax, ay, b) - mom;
    }
}

/* coef += A F over the grid's offsets, for one term (the filter along d,
 * one row e at a time). rp[m] = (1 - r) r^(m-1), m >= 1. */
static void add_term(vl_kernel2d *k, const term_filter *tf, double A, const double *delta,
                     const double *rp) {
  size_t nc = 2 * k->nx - 1;
  long n1 = (long)k->nx - 1, start = -n1 - (long)tf->run;
  for (size_t e = 0; e < k->ne; e++) {
    /* kel[d], mom[d] for d = start .. n1 */
    const double *kel = k->kel + e * k->nd + k->ext + n1, *mom = k->mom + e * k->nd + k->ext + n1;
    double *coef = k->coef + e * nc + n1, S = 0.0;
    if (tf->run == k->ext) S = filter_start(k, tf, e, (double)(n1 + (long)k->ext));
    bool near = tf->near && e <= KERNEL2D_NEAR;
    for (long d = start; d <= n1; d++) {
      double kd = kel[d], md = mom[d];
      if (d >= -n1) {
        double v = tf->c0 * kd - tf->s * md + S;
        if (near) {
          const double *dl = delta + e;
          if (d >= -KERNEL2D_NEAR && d <= KERNEL2D_NEAR)
            v -= dl[(size_t)(d + KERNEL2D_NEAR) * (KERNEL2D_NEAR + 1)];
          for (long dp = -KERNEL2D_NEAR; dp <= KERNEL2D_NEAR && dp < d; dp++)
            v += rp[d - dp] * dl[(size_t)(dp + KERNEL2D_NEAR) * (KERNEL2D_NEAR + 1)];
        }
        coef[d] += A * v;
      }
      S = tf->r * S + tf->omr * (tf->e0 * kd + tf->s * md);
    }
  }
}

void vl_kernel2d_fill(vl_kernel2d *k, const double *A, const double *b, size_t n_terms) {
  size_t nc = 2 * k->nx - 1, nnear = 2 * KERNEL2D_NEAR + 1;
  for (size_t e = 0; e < k->ne; e++)
    memcpy(k->coef + e * nc, k->kel + e * k->nd + k->ext, nc * sizeof *k->coef);
  double *delta = k->work, *rp = k->work + nnear * (KERNEL2D_NEAR + 1);
  size_t nrp = nc + nnear; /* m = d - d' <= nx - 1 + NEAR */
  for (size_t t = 0; t < n_terms; t++) {
    double beta = b[t] / k->hx;
    if (A[t] == 0.0 || isinf(beta)) continue; /* glassy: no memory term */
    if (!(beta > KERNEL2D_BETA_RELAXED)) {    /* relaxed: A Kel */
      for (size_t e = 0; e < k->ne; e++)
        for (size_t i = 0; i < nc; i++)
          k->coef[e * nc + i] += A[t] * k->kel[e * k->nd + k->ext + i];
      continue;
    }
    term_filter tf = {.z = 1.0 / beta};
    tf.r = exp(-tf.z), tf.omr = -expm1(-tf.z);
    double m1;
    exp_moments(tf.z, &tf.c0, &m1);
    tf.e0 = 1.0 - tf.c0, tf.s = 12.0 * m1;
    double run = ceil(KERNEL2D_FORGET * beta) + 1.0;
    tf.run = run >= (double)k->ext ? k->ext : (size_t)run;
    tf.near = beta > KERNEL2D_BETA_EXACT_MIN && beta < KERNEL2D_BETA_EXACT_MAX;
    if (tf.near) {
      near_cells(k, &tf, b[t], delta);
      double p = tf.omr;
      rp[0] = 0.0;
      for (size_t m = 1; m < nrp; m++, p *= tf.r)
        rp[m] = p;
    }
    add_term(k, &tf, A[t], delta, rp);
  }
}
