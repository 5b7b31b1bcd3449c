/* viscolube: surface-displacement influence coefficients (kernel.h).
 *
 * Closed form (derived for the convention of docs/MODEL.md section 1; the paper's
 * Appendix A uses x + v0 t, i.e. the mirror image, and has typos).
 *
 * Everything is written in units of the cell width delta: x = d/delta,
 * beta = b/delta, a+- = x +- 1/2, z+- = a+-/beta. Because
 * log|delta u| = log(delta) + log|u|,
 *   Ke(d)     = delta [ log(delta) + k(x) ],
 *   Kve(d, b) = delta [ log(delta) + kve(x, beta) ].
 *
 * Elastic cell:  k(x) = F(a+) - F(a-),  F(y) = y log|y| - y  (F(0) = 0), i.e.
 *   k(x) = x log|a+/a-| + (1/2) log|x^2 - 1/4| - 1.
 *
 * Memory term. With L(a, beta) = \int_0^inf e^{-s} log|a - beta s| ds,
 *   L(a, beta) = log(beta) + m(a/beta),   m(z) = log|z| - e^{-z} Ei(z),
 * (for z < 0, -e^{-z} Ei(z) = e^{|z|} E1(|z|); for z > 0 the principal value
 * gives -e^{-z} Ei(z)), m is continuous with m(0) = -gamma. Integrating by
 * parts, \int_0^inf e^{-s} F(a - beta s) ds = F(a) - beta L(a, beta), so
 *   kve(x, beta) = k(x) - beta [ m(z+) - m(z-) ]                          (I)
 *                = log(beta) + (1/w) \int_{z-}^{z+} m(z) dz,  w = 1/beta.   (II)
 * With g(z) = -e^{-z} Ei(z) (so m = log|z| + g), for |x| > 1/2
 *   m(z+) - m(z-) = log|a+/a-| + g(z+) - g(z-),  log|a+/a-| = 2 atanh(1/(2x)).
 *
 * Limits: beta -> 0: kve = k(x) - beta log|a+/a-| + O(beta^2).
 * beta -> inf:
 *   kve = log(beta) - gamma - (x/beta)(log(beta) - gamma + 3/2)
 *         + [a+^2 log|a+| - a-^2 log|a-|] / (2 beta) + O(x^2 log(beta)/beta^2),
 * so Kve(d, b) - delta (log b - gamma) -> 0 like (|d| + delta)/b * log(b/delta).
 *
 * Numerical branches (each accurate to a few ulps of max(|kve|, 1)):
 *  - beta <= VL_KERNEL_BETA_SWITCH: form (I). Its rounding error is about
 *    eps * beta * |g|, small while beta is O(1).
 *  - beta > switch, |x| < VL_KERNEL_X_SWITCH: form (II) with the convergent
 *    series m(z) = log|z| (1 - e^{-z}) - gamma e^{-z} - Q(z), where
 *    Q(z) = e^{-z} sum_{n>=1} z^n/(n n!) = sum c_n z^n,
 *    (n+1) c_{n+1} = -c_n + (-1)^n/(n+1)!, c_0 = 0, integrated term by term
 *    (|z| <= ~1 here). Cell averages of z^n log|z| are formed without the
 *    difference of nearly equal antiderivatives.
 *  - beta > switch, |x| >= switch: form (II) as a midpoint (Taylor) series,
 *    kve = sum_k L^(2k)(x) / (4^k (2k+1)!), with the derivatives
 *    L^(n)(x) = beta^{-n} (-1)^n [ g(z) + sum_{j=1}^{n-1} (j-1)!/z^j ], z = x/beta,
 *    computed by T_1 = g(z)/beta, T_{n+1} = (T_n + (n-1)!/x^n)/beta. The series
 *    converges like (2|x|)^{-2k} (the only singularity of L is at a = 0). */
#include "kernel.h"
#include "gsl_errors.h"
#include "kernel_expint.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#define EULER_GAMMA 0.57721566490153286060651209008240243

/* Below this b/delta the memory correction (~beta log) is under 1e-190 of
 * Ke, and (x +- 1/2)/beta could overflow: treat the term as relaxed. */
#define BETA_NEGLIGIBLE 1e-200

/* g(z) = -e^{-z} Ei(z) for z != 0 (log-singular at 0): kernel_expint.h. */
static double g_fn(double z) { return vl_expint_g(z); }

/* log|a+/a-| for |x| > 1/2. For large |x|, 2 atanh(1/(2x)) avoids the
 * cancellation of two close logs; near the cell edge atanh(u -> 1) would
 * amplify the rounding of 1/(2x), while |x| - 1/2 is exact there (Sterbenz). */
static double dlog_fn(double x) {
  double ax = fabs(x);
  if (ax < 2.0) return copysign(log(ax + 0.5) - log(ax - 0.5), x);
  return 2.0 * atanh(0.5 / x);
}

/* k(x) = Ke/delta - log(delta): integral of log|x - y| over |y| < 1/2. */
static double cell_log(double x) {
  double ax = fabs(x);
  if (ax >= 2.0) {
    /* k = log|x| - sum_{n>=1} u^{2n} / (2n (2n+1)), u = 1/(2x): avoids the
     * cancellation of x log|a+/a-| against 1 when x is large. */
    double u2 = 0.25 / (x * x), p = u2, s = 0.0;
    for (int n = 1; n < 40; n++) {
      double t = p / (double)(2 * n * (2 * n + 1));
      s += t;
      if (t < 1e-18 * s) break;
      p *= u2;
    }
    return log(ax) - s;
  }
  if (ax > 0.5) return x * dlog_fn(x) + 0.5 * (log(ax - 0.5) + log(ax + 0.5)) - 1.0;
  double ap = x + 0.5, am = x - 0.5;
  double fp = ap > 0.0 ? ap * log(ap) - ap : 0.0;
  double fm = am < 0.0 ? am * log(-am) - am : 0.0;
  return fp - fm;
}

/* Coefficients of m(z) = log|z| A(z) + B(z): A = 1 - e^{-z} = sum alpha_n z^n,
 * B = -gamma e^{-z} - Q(z) = sum b_n z^n. Advances (n -> n+1) in place. */
typedef struct {
  int n;
  double inv_fact; /* 1/n! */
  double c;        /* c_n of Q */
} m_coef;

static double m_alpha(const m_coef *mc) {
  return mc->n == 0 ? 0.0 : ((mc->n & 1) ? mc->inv_fact : -mc->inv_fact);
}
static double m_b(const m_coef *mc) {
  double e = (mc->n & 1) ? -mc->inv_fact : mc->inv_fact; /* (-1)^n / n! */
  return -EULER_GAMMA * e - mc->c;
}
static void m_next(m_coef *mc) {
  /* (n+1) c_{n+1} = -c_n + (-1)^n/(n+1)! */
  double np1 = (double)(mc->n + 1);
  double sgn_if = ((mc->n & 1) ? -1.0 : 1.0) * mc->inv_fact / np1;
  mc->c = (-mc->c + sgn_if) / np1;
  mc->inv_fact /= np1;
  mc->n++;
}

/* m(z) by its power series; accurate for |z| <~ 1. m(0) = -gamma. */
static double m_series(double z) {
  if (z == 0.0) return -EULER_GAMMA;
  /* A(z) = -expm1(-z) is exact; only B needs the series. */
  m_coef mc = {0, 1.0, 0.0};
  double zn = 1.0, sb = 0.0;
  int small = 0;
  for (int n = 0; n < 60; n++) {
    double tb = m_b(&mc) * zn;
    sb += tb;
    /* two small terms in a row: a single one can vanish by accident */
    small = fabs(tb) < 1e-18 * fabs(sb) ? small + 1 : 0;
    if (small == 2) break;
    zn *= z;
    m_next(&mc);
  }
  return log(fabs(z)) * -expm1(-z) + sb;
}

/* m(z) = log|z| + g(z), switching to the series near 0 (log cancellation). */
static double m_fn(double z) {
  if (fabs(z) < 0.5) return m_series(z);
  return log(fabs(z)) + g_fn(z);
}

/* Branch (I): kve - k = -beta [m(z+) - m(z-)]. */
static double kve_minus_k_small(double x, double beta) {
  double zp = (x + 0.5) / beta, zm = (x - 0.5) / beta;
  double dm;
  /* log|a+/a-| + g(z+) - g(z-) keeps the large-|x| accuracy, but when a cell
   * edge is near (|z| < 1/2) log|z| and g(z) nearly cancel: use m's series. */
  if (fabs(x) > 0.5 && fmin(fabs(zp), fabs(zm)) >= 0.5)
    dm = dlog_fn(x) + (g_fn(zp) - g_fn(zm));
  else
    dm = m_fn(zp) - m_fn(zm);
  return -beta * dm;
}

/* Branch (II), |x| small: log(beta) + cell average of m over [z-, z+] by the
 * term-by-term integrated power series. */
static double kve_series(double x, double beta) {
  double q = (x + 0.5) / beta, p = (x - 0.5) / beta;
  int same_sign = fabs(x) > 0.5;
  double lq = q != 0.0 ? log(fabs(q)) : 0.0, lp = p != 0.0 ? log(fabs(p)) : 0.0;
  /* (log|q| - log|p|)/(q - p) = beta log|a+/a-| (stable for close p, q). */
  double lr = same_sign ? beta * dlog_fn(x) : 0.0;
  m_coef mc = {0, 1.0, 0.0};
  double s = 1.0;          /* S_n = (q^{n+1} - p^{n+1})/(q - p) = sum_j q^j p^{n-j} */
  double pn = 1.0;         /* p^n */
  double qn1 = q, pn1 = p; /* q^{n+1}, p^{n+1} */
  double sum = 0.0;
  int small = 0;
  for (int n = 0; n < 80; n++) {
    double np1 = (double)(n + 1);
    double avg_z = s / np1;
    double avg_zl;
    if (same_sign)
      avg_zl = (lq * s + pn1 * lr) / np1 - s / (np1 * np1);
    else
      avg_zl = beta * (qn1 * (lq - 1.0 / np1) - pn1 * (lp - 1.0 / np1)) / np1;
    double t = m_alpha(&mc) * avg_zl + m_b(&mc) * avg_z;
    sum += t;
    /* On a cell symmetric about z = 0 every odd term vanishes: require two
     * small terms in a row. */
    small = fabs(t) < 1e-18 * fabs(sum) ? small + 1 : 0;
    if (small == 2) break;
    m_next(&mc);
    pn *= p;
    s = q * s + pn;
    qn1 *= q;
    pn1 *= p;
  }
  return log(beta) + sum;
}

/* Branch (II), |x| large: midpoint Taylor series of the cell average of L.
 * The recurrences multiply by 1/beta and 1/x: a division in the chain of
 * t would set the pace of the loop, the most frequent in a refill. */
static double kve_far(double x, double beta) {
  double z = x / beta, ib = 1.0 / beta, ix = 1.0 / x;
  double gz = g_fn(z);
  double sum = fabs(z) < 0.5 ? log(beta) + m_series(z) : log(fabs(x)) + gz;
  double t = gz * ib; /* T_1 = L'(x) */
  double r = ix;      /* (n-1)!/x^n at n = 1 */
  double c = 1.0;     /* 1/(4^k (2k+1)!) */
  for (int n = 1; n < 40; n++) {
    t = (t + r) * ib; /* T_{n+1} = L^{(n+1)}(x) (-1)^{n+1} */
    r *= (double)n * ix;
    if ((n + 1) % 2 == 0) {
      int kk = (n + 1) / 2;
      c /= 4.0 * (double)(2 * kk) * (double)(2 * kk + 1);
      double term = c * t;
      sum += term;
      if (fabs(term) < 1e-18 * fabs(sum)) break;
    }
  }
  return sum;
}

/* kve(x, beta) for beta > VL_KERNEL_BETA_SWITCH. */
static double kve_large(double x, double beta) {
  if (fabs(x) < VL_KERNEL_X_SWITCH) return kve_series(x, beta);
  return kve_far(x, beta);
}

double vl_kernel_elastic(double d, double delta) {
  if (!(delta > 0.0)) return NAN;
  return delta * (log(delta) + cell_log(d / delta));
}

double vl_kernel_viscoelastic(double d, double delta, double b) {
  if (!(delta > 0.0) || !(b >= 0.0)) return NAN;
  double x = d / delta, beta = b / delta;
  if (beta < BETA_NEGLIGIBLE) return vl_kernel_elastic(d, delta);
  vl_gsl_errors_off();
  double kve;
  if (beta <= VL_KERNEL_BETA_SWITCH)
    kve = cell_log(x) + kve_minus_k_small(x, beta);
  else
    kve = kve_large(x, beta);
  return delta * (log(delta) + kve);
}

/* ---------- The Toeplitz coefficients of a Prony series ----------
 *
 * Per offset x, the terms fall in three groups by their memory length beta
 * against the cell's distance from the load (amin = min|a+-|, amax =
 * max|a+-|):
 *  - relaxed, beta <= amin / RELAXED_Z: g's asymptotic series,
 *    kve - k = -beta log|a+/a-| + sum_j j! beta^(j+2) (a+^-(j+1) - a-^-(j+1));
 *  - frozen, beta >= FROZEN_Z amax (|z+-| <= 1/FROZEN_Z): form (II) with
 *    m's power series, kve = log beta + sum_n beta^-n [alpha_n (Lg_n -
 *    log(beta) P_n) + b_n P_n], P_n and Lg_n the cell averages of y^n and
 *    y^n log|y|;
 *  - the window between: evaluated term by term as vl_kernel_viscoelastic.
 * In the first two, x and the terms separate: each group is a few sums over
 * its terms (recomputed when a term changes group, at most twice a term),
 * and a short series per offset. A 28-term rubber then costs a handful of
 * exponential integrals per offset instead of 28 (the window spans
 * RELAXED_Z FROZEN_Z in beta: about two decades). Truncation: the relaxed
 * series' first omitted term is RELAXED_J!/RELAXED_Z^(RELAXED_J+1) = 4e-18
 * of beta; the frozen series' is (1/2)^FROZEN_N / FROZEN_N! = 4e-25. */
#define RELAXED_Z 64.0
#define RELAXED_J 16
#define FROZEN_Z 2.0
#define FROZEN_N 20

enum term_group { TERM_RELAXED, TERM_WINDOW, TERM_FROZEN };

/* The group of a term of memory beta at offset |x| = ax. */
static enum term_group group_of(double beta, double ax) {
  double amin = ax >= 1.0 ? ax - 0.5 : 0.5, amax = ax + 0.5;
  if (RELAXED_Z * beta <= amin) return TERM_RELAXED;
  if (beta >= FROZEN_Z * amax) return TERM_FROZEN;
  return TERM_WINDOW;
}

/* The sums of the relaxed and frozen groups at one offset. */
typedef struct {
  size_t n_relaxed, n_frozen;
  double t;                                     /* sum A beta (relaxed) */
  double s[RELAXED_J];                          /* j! sum A beta^(j+2) (relaxed) */
  double a_f, c_f;                              /* sum A, sum A (log beta - gamma) (frozen) */
  double u[FROZEN_N + 1];                       /* sum A beta^-n (frozen) */
  double v[FROZEN_N + 1];                       /* sum A beta^-n log beta (frozen) */
  double alpha[FROZEN_N + 1], bc[FROZEN_N + 1]; /* m's coefficients */
  double inv[FROZEN_N + 1];                     /* 1/(n+1) */
  double fa[FROZEN_N + 1], fb[FROZEN_N + 1];    /* alpha u, bc u - alpha v */
} term_sums;

static bool term_active(double A, double beta) { return A != 0.0 && beta >= BETA_NEGLIGIBLE; }

static void sums_regroup(term_sums *g, const double *A, const double *beta, size_t n_terms,
                         double ax) {
  memset(g->s, 0, sizeof g->s);
  memset(g->u, 0, sizeof g->u);
  memset(g->v, 0, sizeof g->v);
  g->t = g->a_f = g->c_f = 0.0;
  g->n_relaxed = g->n_frozen = 0;
  for (size_t k = 0; k < n_terms; k++) {
    if (!term_active(A[k], beta[k])) continue;
    enum term_group grp = group_of(beta[k], ax);
    if (grp == TERM_RELAXED) {
      g->n_relaxed++;
      g->t += A[k] * beta[k];
      double p = A[k] * beta[k] * beta[k], fact = 1.0;
      for (int j = 0; j < RELAXED_J; j++) {
        g->s[j] += fact * p;
        p *= beta[k];
        fact *= (double)(j + 1);
      }
    } else if (grp == TERM_FROZEN) {
      g->n_frozen++;
      double lb = log(beta[k]), p = A[k];
      g->a_f += A[k];
      g->c_f += A[k] * (lb - EULER_GAMMA);
      for (int n = 1; n <= FROZEN_N; n++) {
        p /= beta[k];
        g->u[n] += p;
        g->v[n] += p * lb;
      }
    }
  }
  for (int n = 0; n <= FROZEN_N; n++) {
    g->fa[n] = g->alpha[n] * g->u[n];
    g->fb[n] = g->bc[n] * g->u[n] - g->alpha[n] * g->v[n];
  }
}

/* The window's terms at |x| = ax (their indices into win, returned count)
 * and the sizes of the other two groups, in one pass: the groups only grow
 * (relaxed) or shrink (frozen) with |x|, so the sizes say when the sums of
 * g must be redone. */
static size_t classify(const double *A, const double *beta, size_t n_terms, double ax, size_t *win,
                       size_t *n_relaxed, size_t *n_frozen) {
  size_t nw = 0;
  *n_relaxed = *n_frozen = 0;
  for (size_t k = 0; k < n_terms; k++) {
    if (!term_active(A[k], beta[k])) continue;
    enum term_group grp = group_of(beta[k], ax);
    if (grp == TERM_RELAXED)
      ++*n_relaxed;
    else if (grp == TERM_FROZEN)
      ++*n_frozen;
    else
      win[nw++] = k;
  }
  return nw;
}

/* sum over the relaxed terms of A (kve - k) at x. */
static double relaxed_part(const term_sums *g, double x) {
  if (g->n_relaxed == 0) return 0.0;
  double ip = 1.0 / (x + 0.5), im = 1.0 / (x - 0.5), pp = ip, pm = im;
  double sum = x != 0.0 ? -g->t * dlog_fn(x) : 0.0;
  for (int j = 0; j < RELAXED_J; j++) {
    sum += g->s[j] * (pp - pm);
    pp *= ip;
    pm *= im;
  }
  return sum;
}

/* sum over the frozen terms of A (kve - log beta + gamma) at x: the n >= 1
 * terms of m's series, cell-averaged (P_n = s_n/(n+1), s_n = sum_j a+^j
 * a-^(n-j), free of the cancellation of a+^(n+1) - a-^(n+1)). In terms of
 * Lg_n (the average of y^n log|y|): sum_n fa_n Lg_n + fb_n P_n. */
static double frozen_part(const term_sums *g, double x) {
  if (g->n_frozen == 0) return 0.0;
  double ap = x + 0.5, am = x - 0.5;
  double lp = log(fabs(ap)), lm = log(fabs(am));
  double s = 1.0, amn = 1.0, ap1 = ap, am1 = am, sum = 0.0;
  if (fabs(x) > 0.5) { /* both edges on one side of 0: log|a+/a-| */
    double dl = dlog_fn(x);
    for (int n = 1; n <= FROZEN_N; n++) {
      amn *= am;
      s = ap * s + amn;
      am1 *= am;
      double r = g->inv[n], pn = s * r;
      sum += g->fa[n] * ((lp * s + am1 * dl) * r - pn * r) + g->fb[n] * pn;
    }
    return sum;
  }
  for (int n = 1; n <= FROZEN_N; n++) {
    amn *= am;
    s = ap * s + amn;
    ap1 *= ap;
    am1 *= am;
    double r = g->inv[n];
    sum += g->fa[n] * (ap1 * (lp - r) - am1 * (lm - r)) * r + g->fb[n] * s * r;
  }
  return sum;
}

/* kve(x, beta) - k(x) of one term, as vl_kernel_viscoelastic evaluates it. */
static double kve_minus_k(double x, double beta) {
  if (beta <= VL_KERNEL_BETA_SWITCH) return kve_minus_k_small(x, beta);
  return kve_large(x, beta) - cell_log(x);
}

/* coef / delta at offset x: (1 + sum A)(log delta + k) + sum A (kve - k),
 * the window's nw terms listed in win. */
static double offset_total(const term_sums *g, const double *A, const double *beta,
                           const size_t *win, size_t nw, double sum_a, double ld, double x) {
  double k = cell_log(x), w = 0.0;
  for (size_t j = 0; j < nw; j++)
    w += A[win[j]] * kve_minus_k(x, beta[win[j]]);
  return (1.0 + sum_a) * ld + (1.0 + sum_a - g->a_f) * k + g->c_f + frozen_part(g, x) +
         relaxed_part(g, x) + w;
}

/* ---------- Far offsets by interpolation ----------
 *
 * Each term's coefficient is an analytic function of the offset x except at
 * the cell edges x = +-1/2 (L(a) is singular only at a = 0), and so is their
 * sum. From offset INTERP_FROM on, each octave [2^k, 2^(k+1)) is cut into
 * INTERP_PIECES pieces; on a piece [x0, x0 (1 + 1/4)] the distance from the
 * centre to the nearest singularity is at least 9 half-widths (less 4/x0), so
 * the Chebyshev interpolant at INTERP_NODES nodes converges like
 * (9 + sqrt(80))^-16 = 1e-20: what is left is the rounding of the node values
 * (a few ulps, times the interpolant's Lebesgue constant, about 3). A graded
 * grid's merged cells need every uniform offset out to the far end of the
 * domain (their coefficients are run sums): 2928 offsets cost 2 x 256 direct
 * evaluations and 16 per piece instead of one each. */
#define INTERP_FROM 256
#define INTERP_PIECES 4
#define INTERP_NODES 16

/* What every offset's evaluation shares. */
typedef struct {
  const double *A;
  const double *beta; /* b / delta */
  size_t n_terms;
  double sum_a, ld;
  term_sums g;
  size_t win[VL_KERNEL_MAX_TERMS];
} refill_state;

/* coef/delta at +ax and -ax (ax >= 0, any real). The groups of the terms are
 * set by their counts alone (relaxed: the smallest beta, frozen: the largest),
 * so the offsets may come in any order. */
static void total_pair(refill_state *r, double ax, double *plus, double *minus) {
  size_t nr, nf, nw = classify(r->A, r->beta, r->n_terms, ax, r->win, &nr, &nf);
  if (nr != r->g.n_relaxed || nf != r->g.n_frozen)
    sums_regroup(&r->g, r->A, r->beta, r->n_terms, ax);
  *plus = offset_total(&r->g, r->A, r->beta, r->win, nw, r->sum_a, r->ld, ax);
  *minus = ax > 0.0 ? offset_total(&r->g, r->A, r->beta, r->win, nw, r->sum_a, r->ld, -ax) : *plus;
}

/* Chebyshev coefficients from values at the nodes cos(pi (j + 1/2)/N), summed in
 * long double (in double, the transform's rounding would be the largest error). */
static void chebyshev_fit(const double *f, const double (*cosines)[INTERP_NODES], double *c) {
  for (int k = 0; k < INTERP_NODES; k++) {
    long double s = 0.0L;
    for (int j = 0; j < INTERP_NODES; j++)
      s += (long double)f[j] * cosines[k][j];
    c[k] = (double)((k == 0 ? 1.0L : 2.0L) * s / INTERP_NODES);
  }
}

static double chebyshev_eval(const double *c, double u) {
  double b1 = 0.0, b2 = 0.0, u2 = 2.0 * u;
  for (int k = INTERP_NODES - 1; k >= 1; k--) {
    double b0 = c[k] + u2 * b1 - b2;
    b2 = b1, b1 = b0;
  }
  return c[0] + u * b1 - b2;
}

/* Offsets lo .. hi - 1 (and their negatives) from one interpolant on [lo, hi]. */
static void interpolate_piece(refill_state *r, vl_toeplitz *t, size_t lo, size_t hi,
                              const double (*cosines)[INTERP_NODES]) {
  double mid = 0.5 * (double)(lo + hi), half = 0.5 * (double)(hi - lo);
  double fp[INTERP_NODES], fm[INTERP_NODES], cp[INTERP_NODES], cm[INTERP_NODES];
  for (int j = 0; j < INTERP_NODES; j++)
    total_pair(r, mid + half * cosines[1][j], &fp[j], &fm[j]);
  chebyshev_fit(fp, cosines, cp);
  chebyshev_fit(fm, cosines, cm);
  size_t n = t->n;
  for (size_t i = lo; i < hi; i++) {
    double u = ((double)i - mid) / half;
    t->coef[n - 1 + i] = t->delta * chebyshev_eval(cp, u);
    t->coef[n - 1 - i] = t->delta * chebyshev_eval(cm, u);
  }
}

void vl_toeplitz_refill(vl_toeplitz *t, const double *A, const double *b, size_t n_terms) {
  size_t n = t->n;
  double beta[VL_KERNEL_MAX_TERMS];
  refill_state r = {.A = A, .beta = beta, .n_terms = n_terms, .ld = log(t->delta)};
  vl_gsl_errors_off();
  for (size_t k = 0; k < n_terms; k++) {
    r.sum_a += A[k];
    beta[k] = b[k] / t->delta;
  }
  m_coef mc = {0, 1.0, 0.0};
  for (int i = 0; i <= FROZEN_N; i++, m_next(&mc)) {
    r.g.alpha[i] = m_alpha(&mc);
    r.g.bc[i] = m_b(&mc);
    r.g.inv[i] = 1.0 / (double)(i + 1);
  }
  sums_regroup(&r.g, A, beta, n_terms, 0.0);
  size_t direct = n < INTERP_FROM ? n : INTERP_FROM;
  for (size_t i = 0; i < direct; i++) {
    double plus, minus;
    total_pair(&r, (double)i, &plus, &minus);
    t->coef[n - 1 + i] = t->delta * plus;
    t->coef[n - 1 - i] = t->delta * minus;
  }
  if (n <= INTERP_FROM) return;
  double cosines[INTERP_NODES][INTERP_NODES]; /* [k][j] = cos(pi k (j + 1/2)/N) */
  for (int k = 0; k < INTERP_NODES; k++)
    for (int j = 0; j < INTERP_NODES; j++)
      cosines[k][j] = cos(M_PI * k * (j + 0.5) / INTERP_NODES);
  for (size_t lo = INTERP_FROM; lo < n;) {
    size_t octave = lo; /* lo is a power of two times 1 + p/INTERP_PIECES */
    while (octave & (octave - 1))
      octave &= octave - 1;
    size_t hi = lo + octave / INTERP_PIECES;
    if (hi > n) hi = n;
    interpolate_piece(&r, t, lo, hi, (const double(*)[INTERP_NODES])cosines);
    lo = hi;
  }
}

vl_status vl_toeplitz_build(vl_toeplitz *t, size_t n, double delta, const double *A,
                            const double *b, size_t n_terms, vl_error *err) {
  t->coef = NULL;
  t->n = n;
  t->delta = delta;
  if (n == 0) {
    vl_error_set(err, "influence matrix needs at least one node");
    return VL_EINPUT;
  }
  if (!(isfinite(delta) && delta > 0.0)) {
    vl_error_set(err, "grid spacing must be positive and finite (got %g)", delta);
    return VL_EINPUT;
  }
  if (n_terms > VL_KERNEL_MAX_TERMS) {
    vl_error_set(err, "%zu Prony terms: at most %d", n_terms, VL_KERNEL_MAX_TERMS);
    return VL_EINPUT;
  }
  for (size_t k = 0; k < n_terms; k++) {
    if (!isfinite(A[k])) {
      vl_error_set(err, "Prony term %zu: A is not finite", k + 1);
      return VL_EINPUT;
    }
    if (!(isfinite(b[k]) && b[k] >= 0.0)) {
      vl_error_set(err, "Prony term %zu: v0*tau must be finite and >= 0 (got %g)", k + 1, b[k]);
      return VL_EINPUT;
    }
  }
  t->coef = malloc((2 * n - 1) * sizeof *t->coef);
  if (!t->coef) {
    vl_error_set(err, "out of memory for a %zu-node influence matrix", n);
    return VL_ENOMEM;
  }
  vl_toeplitz_refill(t, A, b, n_terms);
  return VL_OK;
}

void vl_toeplitz_free(vl_toeplitz *t) {
  if (!t) return;
  free(t->coef);
  t->coef = NULL;
}
