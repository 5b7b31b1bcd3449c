/* Flow and shear-stress factors (docs/FLOW_FACTORS.md, docs/MODEL.md sections 5 and 7).
 *
 * patir-cheng works in the nominal separation H = h/sigma. The hot path
 * (called for every grid node in every residual and Jacobian) is:
 *   g = u/sigma  ->  H(g) from a quintic Hermite table (no special function)
 *                ->  the factors of H and their H-derivatives (closed forms)
 *                ->  the factors of u (chain rule with dH/du = 1/(sigma Phi(H))).
 *
 * Continuations beyond the published fits (all chosen so that each factor is
 * C1 in H, hence in u, since dH/du = 1/(sigma Phi(H)) is smooth and positive):
 *
 * Phi_x   1 - 0.90 exp(-0.56 H) for H >= 0.5; a H^2 + b H^3 on (0, 0.5) with a, b
 *         computed here from the fit's value and slope at 0.5 (a = 3.075706,
 *         b = -3.593054; the quoted 3.0758, -3.5934 leave a slope jump of
 *         1.7e-4); 0 for H <= 0.
 * Phi_s   1.899 H^0.98 exp(-0.92 H + 0.05 H^2) (branch A, H <= 5) and
 *         1.126 exp(-0.25 H) (branch B, H > 5) do not meet C1 at H = 5 (value
 *         jump 3.1e-5, slope jump -8.4e-3), so the two are blended with a C1
 *         smoothstep over [4.5, 5.5]. Branch A's slope diverges like H^-0.02 at
 *         H = 0, which no C1 continuation by 0 allows: on (0, 0.5) it is
 *         replaced by the same kind of cubic as Phi_x. 0 for H <= 0.
 * Phi_f   exact Patir-Cheng closed forms, z = H/3 (checked symbolically: the
 *         z <= 1 polynomial is \int_{-z}^{1} of the quotient of (1-t^2)^3 by
 *         (z+t), the z > 1 one the same over [-1, 1]; both branches give 7/6
 *         and slope -1.6 in z at z = 1, so nothing to fix). For z >= 2 the
 *         series Phi_f = sum_j 105 z^-2j / ((2j+1)(2j+3)(2j+5)(2j+7)) replaces
 *         the closed form, which cancels like z^6 (its rounding noise, 1e-13
 *         at z = 3, is what a finite-difference Jacobian would see). The library stores
 *         Psi_f = Phi_f/H, finite at H = 0 (Psi_0 = (35/96)(ln 300 - 11/12)).
 *         Its slope there is 7/18, so the constant limit for H < 0 would break
 *         C1: on [-0.5, 0] Psi_f = Psi_0 + (7/18)(H + H^2), constant
 *         Psi_0 - 7/72 below.
 * Phi_fs  11.1 H^2.31 exp(-2.38 H + 0.11 H^2), fitted on 0.5 < H < 7. The
 *         solver needs Phi_fs/H ~ H^1.31, whose slope ~H^0.31 is continuous at
 *         0 but not Lipschitz; below 0.5 Phi_fs/H is the cubic a H^2 + b H^3
 *         (value and slope matched at 0.5), 0 for H <= 0. At H = 7 the fit
 *         drops by 0.0127 to 0: replaced by a monotone cubic Hermite tail to 0
 *         (value and slope) at H = 8.
 * Phi_fp  1 - 1.40 exp(-0.66 H) is negative for H < ln(1.4)/0.66 = 0.510; a
 *         cubic joined at 0.5 would dip to -0.05, so it is joined at 0.75 (the
 *         cubic a H^2 + b H^3 stays >= 0 and monotone for a join at H >= 0.738).
 *         0 for H <= 0.
 */
#include "viscolube/flow_factors.h"
#include "flow_factors_internal.h"

#include "flow_factors_emt.h"

#include <math.h>
#include <pthread.h>
#include <string.h>

/* ---------------------------------------------------------------------------
 * The Gaussian gap g(H) = u/sigma = H Phi(H) + phi(H) and its inverse. */

#define INV_SQRT2 0.70710678118654752440
#define INV_SQRT_2PI 0.39894228040143267794

static double norm_cdf(double x) { return 0.5 * erfc(-x * INV_SQRT2); }
static double norm_pdf(double x) { return INV_SQRT_2PI * exp(-0.5 * x * x); }
static double gap_of_H(double H) { return norm_pdf(H) + H * norm_cdf(H); }

/* Below H_LO the factors do not depend on H (see the header comment), so the
 * hot path never needs H there; above G_HI, g(H) - H < 1.4e-20 and H = g. */
#define H_LO (-0.5)
#define G_HI 9.0
#define TABLE_N 512

static struct {
  double g_lo, s_lo, ds, inv_ds; /* table uniform in s = sqrt(g), g in [g_lo, G_HI] */
  double c[TABLE_N][6]; /* H on interval i: sum_k c[i][k] t^k, t = (s - s_i)/ds in [0, 1] */
  double ax, bx;        /* Phi_x cubic on (0, 0.5) */
  double as, bs;        /* Phi_s cubic on (0, 0.5) */
  double afp, bfp;      /* Phi_fp cubic on (0, 0.75) */
  double afs, bfs;      /* Phi_fs/H cubic on (0, 0.5) */
  double fs7, dfs7;     /* Phi_fs value and slope at H = 7 (tail start) */
  double psi0;          /* Psi_f = Phi_f/H at H = 0 */
} T;

static pthread_once_t table_once = PTHREAD_ONCE_INIT;

/* Cubic a H^2 + b H^3 with value and slope 0 at H = 0 and value v, slope m at
 * H = h1: the regularisation below the fit ranges. */
static void cubic_join(double h1, double v, double m, double *a, double *b) {
  *a = (3.0 * v - m * h1) / (h1 * h1);
  *b = (m * h1 - 2.0 * v) / (h1 * h1 * h1);
}

/* H(g) is tabulated as a quintic Hermite interpolant in s = sqrt(g) (which
 * puts the nodes closer where H(g) bends most, at small g) of the exact H,
 * dH/ds = 2 s/Phi(H) and d2H/ds2 = 2/Phi - 4 g phi/Phi^3 at the nodes: C2
 * across nodes, within ~1e-14 of the root (checked by the tests), and the hot
 * path needs no erfc. */
static void table_build(void) {
  T.g_lo = gap_of_H(H_LO);
  T.s_lo = sqrt(T.g_lo);
  T.ds = (sqrt(G_HI) - T.s_lo) / TABLE_N;
  T.inv_ds = 1.0 / T.ds;
  double H = H_LO, y0 = 0.0, d0 = 0.0, c0 = 0.0;
  for (int i = 0; i <= TABLE_N; i++) {
    double s = T.s_lo + i * T.ds, g = i == 0 ? T.g_lo : s * s;
    /* g is convex increasing in H: Newton from the previous node (left of
     * the root) first overshoots right, then converges monotonically */
    for (int it = 0; it < 60 && i > 0; it++) {
      double step = (gap_of_H(H) - g) / norm_cdf(H);
      H -= step;
      if (fabs(step) <= 1e-16 * (1.0 + fabs(H))) break;
    }
    double cdf = norm_cdf(H), pdf = norm_pdf(H);
    double y1 = H, d1 = T.ds * 2.0 * s / cdf;
    double c1 = T.ds * T.ds * (2.0 / cdf - 4.0 * g * pdf / (cdf * cdf * cdf));
    if (i > 0) {
      double *c = T.c[i - 1];
      c[0] = y0, c[1] = d0, c[2] = 0.5 * c0;
      double r0 = y1 - (c[0] + c[1] + c[2]), r1 = d1 - (c[1] + 2.0 * c[2]), r2 = c1 - 2.0 * c[2];
      c[3] = 10.0 * r0 - 4.0 * r1 + 0.5 * r2;
      c[4] = -15.0 * r0 + 7.0 * r1 - r2;
      c[5] = 6.0 * r0 - 3.0 * r1 + 0.5 * r2;
    }
    y0 = y1, d0 = d1, c0 = c1;
  }

  double e = exp(-0.56 * 0.5);
  cubic_join(0.5, 1.0 - 0.90 * e, 0.90 * 0.56 * e, &T.ax, &T.bx);
  double A = 1.899 * exp(0.98 * log(0.5) - 0.92 * 0.5 + 0.05 * 0.25);
  cubic_join(0.5, A, A * (0.98 / 0.5 - 0.92 + 0.10 * 0.5), &T.as, &T.bs);
  e = exp(-0.66 * 0.75);
  cubic_join(0.75, 1.0 - 1.40 * e, 1.40 * 0.66 * e, &T.afp, &T.bfp);
  double P = 11.1 * exp(1.31 * log(0.5) - 2.38 * 0.5 + 0.11 * 0.25); /* Phi_fs(0.5)/0.5 */
  cubic_join(0.5, P, P * (1.31 / 0.5 - 2.38 + 0.22 * 0.5), &T.afs, &T.bfs);
  T.fs7 = 11.1 * exp(2.31 * log(7.0) - 2.38 * 7.0 + 0.11 * 49.0);
  T.dfs7 = T.fs7 * (2.31 / 7.0 - 2.38 + 0.22 * 7.0);
  T.psi0 = (35.0 / 96.0) * (log(300.0) - 55.0 / 60.0);
}

static void ensure_table(void) { pthread_once(&table_once, table_build); }

/* H(g) and dH/dg for g in [g_lo, inf) (table built). */
static double H_of_gap(double g, double *dH_dg) {
  if (g >= G_HI) {
    *dH_dg = 1.0;
    return g;
  }
  double sg = sqrt(g), x = (sg - T.s_lo) * T.inv_ds;
  int i = (int)x;
  if (i < 0) i = 0;
  if (i > TABLE_N - 1) i = TABLE_N - 1;
  double t = x - i;
  const double *c = T.c[i];
  /* dH/dg = (dH/dt) (dt/ds) (ds/dg), ds/dg = 1/(2 s) */
  *dH_dg = (c[1] + t * (2.0 * c[2] + t * (3.0 * c[3] + t * (4.0 * c[4] + t * 5.0 * c[5])))) *
           T.inv_ds / (2.0 * sg);
  return c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))));
}

/* ln g(H) for H <= H_LO without underflow: with x = -H, g = phi(x)(1 - x R(x))
 * where R is Mills' ratio, 1 - x R = (1/t1)/t0 from R's continued fraction
 * R = 1/t0, t0 = x + 1/t1, t1 = x + 2/t2, ... (no cancellation). Also returns
 * d ln g/dH = Phi(H)/g(H). */
static double log_gap_low(double H, double *dlng) {
  double x = -H;
  if (x < 6.0) {
    double g = gap_of_H(H);
    *dlng = norm_cdf(H) / g;
    return log(g);
  }
  double t = x;
  for (int k = 80; k >= 2; k--)
    t = x + k / t; /* t = t1 */
  double t0 = x + 1.0 / t;
  double one_minus_xR = (1.0 / t) / t0;
  *dlng = (1.0 / t0) / one_minus_xR; /* Phi/g = R/(1 - x R) */
  return -0.5 * x * x + log(INV_SQRT_2PI) + log(one_minus_xR);
}

double vl_flow_factors_nominal_gap(double u_m, double hrms_m, double *dh_du) {
  double dummy;
  if (!dh_du) dh_du = &dummy;
  if (isnan(u_m) || isnan(hrms_m) || !(hrms_m > 0.0)) {
    *dh_du = NAN;
    return NAN;
  }
  if (!(u_m > 0.0)) {
    *dh_du = INFINITY;
    return -INFINITY;
  }
  ensure_table();
  double g = u_m / hrms_m, dH;
  if (g >= T.g_lo) {
    double H = H_of_gap(g, &dH);
    *dh_du = dH;
    return H * hrms_m;
  }
  /* ln g(H) is concave increasing (g is log-concave): Newton from the left
   * of the root converges monotonically. Start from ln g ~ -x^2/2 + ln phi0,
   * which lies left of the root because 1 - x R(x) < 1. */
  double lng = log(g), H = -sqrt(fmax(0.0, -2.0 * (lng - log(INV_SQRT_2PI)))), d = 1.0;
  if (H > H_LO) H = H_LO;
  for (int it = 0; it < 100; it++) {
    double step = (log_gap_low(H, &d) - lng) / d;
    H -= step;
    if (fabs(step) <= 4e-16 * fabs(H)) break;
  }
  log_gap_low(H, &d);
  *dh_du = 1.0 / (d * g); /* dH/dg = 1/Phi = 1/(g d ln g/dH) */
  return H * hrms_m;
}

/* ---------------------------------------------------------------------------
 * The Patir-Cheng functions of H and their derivatives d/dH. */

typedef struct {
  double x, s, psf, psfs, fp; /* Phi_x, Phi_s, Phi_f/H, Phi_fs/H, Phi_fp */
} pc_h;

/* Phi_f/H for z = H/3 > 0 and its derivative d/dH. */
static double psi_f(double H, double *d) {
  double z = H / 3.0;
  if (z <= 1.0) {
    double w = 1.0 - z * z, w2 = w * w, L = log(300.0 * (1.0 + z));
    double P =
        -55.0 + z * (132.0 + z * (345.0 + z * (-160.0 + z * (-405.0 + z * (60.0 + 147.0 * z)))));
    double dP = 132.0 + z * (690.0 + z * (-480.0 + z * (-1620.0 + z * (300.0 + 882.0 * z))));
    *d = (35.0 / 96.0) * (-6.0 * z * w2 * L + w2 * w / (1.0 + z) + dP / 60.0) / 3.0;
    return (35.0 / 96.0) * (w2 * w * L + P / 60.0);
  }
  if (z < 2.0) {
    double w = 1.0 - z * z, w2 = w * w, z2 = z * z, L = log((z + 1.0) / (z - 1.0));
    *d = (35.0 / 96.0) *
         (-6.0 * z * w2 * L + 2.0 * w2 + (66.0 + z2 * (150.0 * z2 - 240.0)) / 15.0) / 3.0;
    return (35.0 / 96.0) * (w2 * w * L + z * (66.0 + z2 * (30.0 * z2 - 80.0)) / 15.0);
  }
  /* Phi_f = sum_j c_j w^j, w = 1/z^2 <= 1/4: 22 terms reach 1e-17 */
  static const double c[22] = {
#define C(j) 105.0 / ((2 * (j) + 1.0) * (2 * (j) + 3.0) * (2 * (j) + 5.0) * (2 * (j) + 7.0))
      C(0),  C(1),  C(2),  C(3),  C(4),  C(5),  C(6),  C(7),  C(8),  C(9), C(10), C(11),
      C(12), C(13), C(14), C(15), C(16), C(17), C(18), C(19), C(20), C(21)
#undef C
  };
  double w = 1.0 / (z * z), f = 0.0, jf = 0.0;
  for (int j = 21; j >= 1; j--) {
    f = f * w + c[j];
    jf = jf * w + j * c[j];
  }
  f = f * w + c[0]; /* Phi_f */
  jf *= w;          /* sum_j j c_j w^j */
  /* dPhi_f/dH = (1/3) dPhi_f/dz = (1/3)(-2/z) sum_j j c_j w^j */
  double dphif = -2.0 * jf / (3.0 * z);
  double psi = f / H;
  *d = (dphif - psi) / H;
  return psi;
}

/* Every function of H with its derivative (H > -inf; H <= H_LO constant). */
static void pc_of_H(double H, pc_h *v, pc_h *d) {
  *v = (pc_h){0};
  *d = (pc_h){0};
  if (H <= 0.0) {
    /* only the Couette shear survives; quadratic C1 join on [-0.5, 0] */
    if (H > H_LO) {
      v->psf = T.psi0 + (7.0 / 18.0) * (H + H * H);
      d->psf = (7.0 / 18.0) * (1.0 + 2.0 * H);
    } else {
      v->psf = T.psi0 - 7.0 / 72.0;
    }
    return;
  }
  double lnH = H >= 0.5 && H <= 7.0 ? log(H) : 0.0; /* only the power-law fits need it */

  /* pressure flow */
  if (H < 0.5) {
    v->x = H * H * (T.ax + T.bx * H);
    d->x = H * (2.0 * T.ax + 3.0 * T.bx * H);
  } else {
    double e = exp(-0.56 * H);
    v->x = 1.0 - 0.90 * e;
    d->x = 0.90 * 0.56 * e;
  }

  /* shear flow */
  if (H < 0.5) {
    v->s = H * H * (T.as + T.bs * H);
    d->s = H * (2.0 * T.as + 3.0 * T.bs * H);
  } else {
    double A = 0.0, dA = 0.0, B = 0.0, dB = 0.0;
    if (H < 5.5) {
      A = 1.899 * exp(0.98 * lnH - 0.92 * H + 0.05 * H * H);
      dA = A * (0.98 / H - 0.92 + 0.10 * H);
    }
    if (H > 4.5) {
      B = 1.126 * exp(-0.25 * H);
      dB = -0.25 * B;
    }
    if (H <= 4.5) {
      v->s = A, d->s = dA;
    } else if (H >= 5.5) {
      v->s = B, d->s = dB;
    } else {
      double t = H - 4.5, S = t * t * (3.0 - 2.0 * t), dS = 6.0 * t * (1.0 - t);
      v->s = A + S * (B - A);
      d->s = dA + dS * (B - A) + S * (dB - dA);
    }
  }

  /* Couette shear of the mean film (Phi_f) and of the roughness (Phi_fs) */
  v->psf = psi_f(H, &d->psf);
  if (H < 0.5) {
    v->psfs = H * H * (T.afs + T.bfs * H);
    d->psfs = H * (2.0 * T.afs + 3.0 * T.bfs * H);
  } else if (H <= 7.0) {
    double e = exp(1.31 * lnH - 2.38 * H + 0.11 * H * H); /* Phi_fs/H */
    v->psfs = 11.1 * e;
    d->psfs = v->psfs * (1.31 / H - 2.38 + 0.22 * H);
  } else if (H < 8.0) {
    double t = H - 7.0, t2 = t * t, t3 = t2 * t;
    double p = (2.0 * t3 - 3.0 * t2 + 1.0) * T.fs7 + (t3 - 2.0 * t2 + t) * T.dfs7;
    double dp = (6.0 * t2 - 6.0 * t) * T.fs7 + (3.0 * t2 - 4.0 * t + 1.0) * T.dfs7;
    v->psfs = p / H;
    d->psfs = (dp - v->psfs) / H;
  }

  /* Poiseuille shear */
  if (H < 0.75) {
    v->fp = H * H * (T.afp + T.bfp * H);
    d->fp = H * (2.0 * T.afp + 3.0 * T.bfp * H);
  } else {
    double e = exp(-0.66 * H);
    v->fp = 1.0 - 1.40 * e;
    d->fp = 1.40 * 0.66 * e;
  }
}

/* H and dH/dg for the hot path; for g < g_lo H is irrelevant (returns H_LO - 1
 * and dH/dg = 0, which zeroes every chain-rule term). */
static double hot_H(double g, double *dH_dg) {
  if (g < T.g_lo) {
    *dH_dg = 0.0;
    return H_LO - 1.0;
  }
  return H_of_gap(g, dH_dg);
}

static const vl_flow_factor_values smooth_values = {1.0, 0.0, 1.0, 0.0, 1.0};

void vl_flow_factors_eval(vl_flow_factor_kind kind, double u_m, double hrms_m,
                          vl_flow_factor_values *v, vl_flow_factor_values *d) {
  if (d) *d = (vl_flow_factor_values){0};
  if (isnan(u_m) || isnan(hrms_m) || kind == VL_FLOW_FACTORS_PERSSON_EMT) {
    /* persson-emt needs its table: vl_flow_factors_eval_table */
    *v = (vl_flow_factor_values){NAN, NAN, NAN, NAN, NAN};
    if (d) *d = *v;
    return;
  }
  if (kind != VL_FLOW_FACTORS_PATIR_CHENG || !(hrms_m > 0.0)) {
    *v = smooth_values;
    return;
  }
  ensure_table();
  double sig = hrms_m, g = fmax(u_m, 0.0) / sig, Hg;
  double H = hot_H(g, &Hg);
  pc_h f, df;
  pc_of_H(H, &f, &df);
  double r = 0.0, dr = 0.0; /* r = H/g = h/u and dr/dg */
  if (H > 0.0) {
    r = H / g;
    dr = (Hg - r) / g;
  }
  double r2 = r * r;
  v->phi_p = f.x * r2 * r;
  v->phi_s = f.s;
  v->phi_f = f.psf * g;
  v->phi_fs = f.psfs * g;
  v->phi_fp = f.fp * r;
  if (d) {
    /* d/du = (1/sigma) d/dg, dH/dg = Hg */
    d->phi_p = (df.x * Hg * r2 * r + 3.0 * f.x * r2 * dr) / sig;
    d->phi_s = df.s * Hg / sig;
    d->phi_f = (df.psf * Hg * g + f.psf) / sig;
    d->phi_fs = (df.psfs * Hg * g + f.psfs) / sig;
    d->phi_fp = (df.fp * Hg * r + f.fp * dr) / sig;
  }
}

void vl_flow_factors_eval_table(vl_flow_factor_kind kind, const vl_emt_table *table, double u_m,
                                double hrms_m, vl_flow_factor_values *v, vl_flow_factor_values *d) {
  if (kind != VL_FLOW_FACTORS_PERSSON_EMT) {
    vl_flow_factors_eval(kind, u_m, hrms_m, v, d);
    return;
  }
  if (!table || !(hrms_m > 0.0)) {
    *v = (vl_flow_factor_values){NAN, NAN, NAN, NAN, NAN};
    if (d) *d = *v;
    return;
  }
  /* the table's factors are functions of x = u/h0; at a local h_rms they
   * are the same functions of u/hrms_m = (u k)/h0, k = h0/hrms_m */
  double k = vl_emt_table_hrms(table) / hrms_m;
  vl_emt_table_eval(table, u_m * k, v, d);
  if (d) {
    d->phi_p *= k, d->phi_s *= k, d->phi_f *= k, d->phi_fs *= k, d->phi_fp *= k;
  }
}

void vl_flow_factors_terms(vl_flow_factor_kind kind, double u_m, double hrms_m, vl_flow_terms *t,
                           vl_flow_terms *d) {
  if (d) *d = (vl_flow_terms){0};
  if (isnan(u_m) || isnan(hrms_m) || kind == VL_FLOW_FACTORS_PERSSON_EMT) {
    *t = (vl_flow_terms){NAN, NAN, NAN, NAN};
    if (d) *d = *t;
    return;
  }
  if (kind != VL_FLOW_FACTORS_PATIR_CHENG || !(hrms_m > 0.0)) {
    double u = u_m;
    *t = (vl_flow_terms){u * u * u, 0.0, 1.0 / u, u};
    if (d) *d = (vl_flow_terms){3.0 * u * u, 0.0, -1.0 / (u * u), 1.0};
    return;
  }
  ensure_table();
  double sig = hrms_m, g = fmax(u_m, 0.0) / sig, Hg;
  double H = hot_H(g, &Hg);
  pc_h f, df;
  pc_of_H(H, &f, &df);
  double Hp = H > 0.0 ? H : 0.0; /* every H-power term carries a factor 0 for H <= 0 */
  double s3 = sig * sig * sig;
  t->conductance_m3 = s3 * Hp * Hp * Hp * f.x;
  t->shear_flow = f.s;
  t->couette_per_m = (f.psf + f.psfs) / sig;
  t->poiseuille_m = sig * Hp * f.fp;
  if (d) {
    d->conductance_m3 = sig * sig * Hp * Hp * (3.0 * f.x + Hp * df.x) * Hg;
    d->shear_flow = df.s * Hg / sig;
    d->couette_per_m = (df.psf + df.psfs) * Hg / (sig * sig);
    d->poiseuille_m = (f.fp + Hp * df.fp) * Hg;
  }
}

const char *vl_flow_factors_name(vl_flow_factor_kind kind) {
  switch (kind) {
  case VL_FLOW_FACTORS_SMOOTH: return "smooth";
  case VL_FLOW_FACTORS_PATIR_CHENG: return "patir-cheng";
  case VL_FLOW_FACTORS_PERSSON_EMT: return "persson-emt";
  }
  return "unknown";
}

vl_status vl_flow_factors_parse(const char *name, vl_flow_factor_kind *kind, vl_error *err) {
  static const vl_flow_factor_kind all[] = {VL_FLOW_FACTORS_SMOOTH, VL_FLOW_FACTORS_PATIR_CHENG,
                                            VL_FLOW_FACTORS_PERSSON_EMT};
  for (size_t i = 0; name && i < sizeof all / sizeof all[0]; i++) {
    if (!strcmp(name, vl_flow_factors_name(all[i]))) {
      *kind = all[i];
      return VL_OK;
    }
  }
  vl_error_set(err, "unknown flow-factor model '%s' (expected smooth, patir-cheng or persson-emt)",
               name ? name : "(null)");
  return VL_EINPUT;
}
