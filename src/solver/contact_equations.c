/* The discretised equations (docs/MODEL.md sections 3-6 and 9) on the cells of
 * contact_grid.c, in the dimensionless unknowns of contact.h:
 *   the gap u = h0 + x^2/(2R) + w(x), w from the influence matrix (section 3);
 *   the contact pressure pc(u) of Persson's theory, or the hard-contact
 *   complementarity pc >= 0, u >= 0, pc u = 0 by Fischer-Burmeister
 *   (section 4), with viscous flattening's rescaling of the PSD (seed
 *   Appendix C);
 *   the averaged Reynolds equation in conservative finite-volume form with
 *   its flow factors and the cavitation condition by Fischer-Burmeister
 *   (section 5; docs/FLOW_FACTORS.md);
 *   the load balance (section 6);
 * their residual and analytic Jacobian, and the scales of the fluid
 * unknowns and the Reynolds rows (section 9). */
#include "contact_internal.h"

#include <math.h>
#include <string.h>

#include "flattening_internal.h"
#include "flow_factors_internal.h"
#include "lapack_abi.h"

/* Fischer-Burmeister complementarity a >= 0, b >= 0, a b = eps/2 (smoothed),
 * with its partial derivatives. */
static double fb_eps(double a, double b, double eps, double *da, double *db) {
  double r = sqrt(a * a + b * b + eps);
  if (da) *da = 1.0 - a / r;
  if (db) *db = 1.0 - b / r;
  return a + b - r;
}
static double fb(double a, double b, double *da, double *db) {
  return fb_eps(a, b, FB_EPS, da, db);
}

/* The hard contact of a smooth dry cell, P >= 0, U >= 0, P U = 0: min(P, U)
 * (exact; its Newton step is the active-set step: the gap row where U < P,
 * the row P = 0 elsewhere, so the steps converge in a few set changes), or
 * Fischer-Burmeister (smoothed) where min_rows is off. */
static double hard_contact(const vl_contact *c, double p, double u, double *dp, double *du) {
  if (!c->min_rows) return fb(p, u, dp, du);
  bool gap = u < p;
  if (dp) *dp = gap ? 0.0 : 1.0;
  if (du) *du = gap ? 1.0 : 0.0;
  return gap ? u : p;
}

/* Couette film carried across face f (0..n; face f lies between cells f-1
 * and f): returns its value and writes the cells k[q] and the partial
 * derivatives w[q] = d(value)/d(cf[k[q]]); returns the number m of terms
 * in *m. Second-order upwind (the film of the cell the fluid leaves,
 * extrapolated from the cell behind it): a centred film would decouple odd
 * and even cells where the Poiseuille flow vanishes (the EHL contact zone),
 * first-order upwind costs O(dx) in the film (13 % at 128 cells on Martin's
 * rigid cylinder). A smooth film limits the extrapolation (van Albada,
 * first order where the film has an extremum): the plain extrapolation
 * 1.5 cf[C] - 0.5 cf[U] vanishes where the film drops by 3x per cell, and
 * a thin viscoelastic film (whose inlet pressure rises within a few cells)
 * then found a spurious discrete solution with no Couette flux at all and
 * a film of 1e-11 m; the limited face value stays between 0 and the
 * larger neighbour. The outlet face takes the upwind cell; the inflow
 * faces 0 and 1 (far inlet, smooth film) are not limited. */
static double couette_face(const vl_contact *c, size_t f, size_t k[3], double w[3], int *m) {
  size_t n = c->n;
  const double *cf = c->cf;
  if (f == n) {
    k[0] = n - 1, w[0] = 1.0, *m = 1;
    return cf[n - 1];
  }
  if (f <= 1) { /* inflow face extrapolated from cells 0, 1; face 1 interpolated */
    double t = c->wc[0] / (c->wc[0] + c->wc[1]); /* 1/2 on a uniform grid */
    k[0] = 0, k[1] = 1, w[0] = f ? 1.0 - t : 1.0 + t, w[1] = f ? t : -t, *m = 2;
    return w[0] * cf[0] + w[1] * cf[1];
  }
  if (c->rough) {
    /* linear extrapolation from the nodes of cells f-2, f-1 to the face,
     * half a cell beyond f-1 (1.5 cf[f-1] - 0.5 cf[f-2] when uniform) */
    double t = c->wc[f - 1] / (c->wc[f - 1] + c->wc[f - 2]);
    k[0] = f - 1, k[1] = f - 2, w[0] = 1.0 + t, w[1] = -t, *m = 2;
    return w[0] * cf[f - 1] + w[1] * cf[f - 2];
  }
  /* cells U = f-2, C = f-1, D = f; face = cf[C] + b psi(a/b)/2 with
   * a = cf[D] - cf[C], b = cf[C] - cf[U], psi(r) = (r^2 + r)/(r^2 + 1) for
   * r > 0, 0 otherwise: b psi(a/b) = a b (a + b)/(a^2 + b^2) */
  double a = cf[f] - cf[f - 1], b = cf[f - 1] - cf[f - 2];
  k[0] = f - 1, k[1] = f - 2, k[2] = f, *m = 3;
  if (!(a * b > 0.0)) {
    w[0] = 1.0, w[1] = 0.0, w[2] = 0.0;
    return cf[f - 1];
  }
  double s = a * a + b * b, inc = 0.5 * a * b * (a + b) / s;
  double da = 0.5 * b * b * (2.0 * a * b - a * a + b * b) / (s * s);
  double db = 0.5 * a * a * (2.0 * a * b - b * b + a * a) / (s * s);
  w[0] = 1.0 - da + db, w[1] = -db, w[2] = da;
  return cf[f - 1] + inc;
}

/* Poiseuille conductance of interior face f (between cells f-1 and f) and
 * its derivatives with respect to g[f-1] and g[f]. A smooth film uses the
 * harmonic mean (the two half-cells in series, as \int dx/u^3 does): with
 * the arithmetic mean, a face next to a nearly closed cell kept the open
 * cell's conductance, and a thin film's under-resolved inlet balanced the
 * whole Couette inflow by backflow through that face, closing the contact
 * to 1e-11 m (a spurious discrete solution). Rough films keep the
 * arithmetic mean (their flow factors keep the film open). */
static double face_g(const vl_contact *c, size_t f, double *dl, double *dr) {
  double gl = c->g[f - 1], gr = c->g[f];
  if (c->rough) {
    *dl = 0.5, *dr = 0.5;
    return 0.5 * (gl + gr);
  }
  double s = gl + gr;
  *dl = 2.0 * gr * gr / (s * s), *dr = 2.0 * gl * gl / (s * s);
  return 2.0 * gl * gr / s;
}

/* Viscous flattening (seed Appendix C) replaces the surface's PSD C(q) by
 * eps C(q), eps = epsilon_f(u, v0) at the node's separation u. In Persson's
 * theory (docs/MODEL.md section 4, seed Eq. 8) that is an exact rescaling:
 *   w(q) = (pi \int^q q'^3 eps C dq')^(-1/2) = eps^(-1/2) w(q), so
 *   u_eps(p) = (sqrt(pi)/2) \int dq q^2 (eps C)(eps^(-1/2) w) E1((eps^(-1/2) w p/|Er|)^2)
 *            = sqrt(eps) u(p/sqrt(eps)),
 * i.e. with s = sqrt(eps) the pressure at separation u is
 *   p_eps(u) = s p(u/s),
 * and G = (pi/4)|Er|^2 \int q^3 C dq scales as eps, so
 *   A_eps/A0 (p) = erf(p/(2 sqrt(eps G))) = A/A0 (p/s) = A/A0 (p(u/s)):
 * the area of the unflattened surface at separation u/s. The flow factors
 * see h_rms^2 -> eps h_rms^2, i.e. h_rms -> s h_rms. eps depends on u only
 * (at a fixed speed), so the chain rule through ds/du adds to the diagonal
 * d/du terms of pc and of the node's flow quantities: no new coupling (the
 * Reynolds rows' pf block stays tridiagonal). Off: s = 1, ds/du = 0. */
static double flat_scale(const vl_contact *c, double u_m, double *ds_du) {
  *ds_du = 0.0;
  if (!c->flattening) return 1.0;
  double de, e = vl_flattening_eps(c->flattening, u_m, &de);
  if (!(e > 0.0)) return 0.0; /* u <= 0: every wavelength flattened */
  double s = sqrt(e);
  *ds_du = 0.5 * de / s;
  return s;
}

/* Contact pressure P (p0) and dP/dU on the grid: Persson's pc(u) on a rough
 * surface (flattened or not), the unknowns themselves on a smooth dry one,
 * none in a smooth film. */
static void eval_contact_pressure(vl_contact *c, const double *y) {
  size_t n = c->n;
  if (c->rough && c->sf) {
    /* flattened: P = sfac s p(u/s) (flat_scale), dP/du = sfac (s' p + p' (1 - u s'/s));
     * s -> 0 (u -> 0+) sends u/s -> inf and P -> 0 smoothly */
    for (size_t i = 0; i < n; i++) {
      double u = y[i] * c->uscale, ds, s = flat_scale(c, u, &ds);
      double v = s > 0.0 ? u / s : INFINITY;
      c->sf[i] = s, c->dsf[i] = ds;
      if (isfinite(v)) {
        double dp, p = vl_persson_pressure(c->cfg.roughness, v, &dp);
        c->P[i] = c->sfac * s * p;
        c->dPdU[i] = c->sfac * (ds * p + dp * (1.0 - u * ds / s)) * c->uscale;
      } else {
        c->P[i] = 0.0, c->dPdU[i] = 0.0;
      }
    }
  } else if (c->rough) {
    for (size_t i = 0; i < n; i++) {
      double dsdu;
      double s = vl_persson_pressure(c->cfg.roughness, y[i] * c->uscale, &dsdu);
      c->P[i] = c->sfac * s;
      c->dPdU[i] = c->sfac * dsdu * c->uscale;
    }
  } else if (c->nc) {
    memcpy(c->P, y, n * sizeof *c->P);
  } else {
    memset(c->P, 0, n * sizeof *c->P); /* smooth wet: the film carries all */
  }
}

/* Fluid pressure F (p0) and the gap: the separation U (smooth), or the
 * elasticity residual D = U - G (rough, where U is the unknown). */
static void eval_gap(vl_contact *c, const double *y) {
  size_t n = c->n;
  double h0 = y[c->ih];
  for (size_t i = 0; i < n; i++)
    c->F[i] = c->wet ? c->kappa * y[c->of + i] : 0.0;
  /* elastic/viscoelastic gap: h0 + xi^2/2 + sum_j M_ij (P_j + F_j); for a
   * rough surface it is stored in D (the residual compares it with U) */
  double *G = c->rough ? c->D : c->U;
  for (size_t j = 0; j < n; j++)
    c->q[j] = c->P[j] + c->F[j];
  if (c->pamb) /* a sealed side: the pressure above its ambient deforms the rubber */
    for (size_t j = 0; j < n; j++)
      c->q[j] -= c->pamb[j];
  /* M is row-major: the column-major n x n matrix M^T, transposed (BLAS:
   * a plain loop is bound by the latency of its one running sum, about
   * 4x slower at n = 400, where it was a third of a dry point's time) */
  int ni = (int)n, one = 1;
  double w1 = 1.0, w0 = 0.0;
  dgemv_("T", &ni, &ni, &w1, c->M, &ni, c->q, &one, &w0, G, &one, 1);
  for (size_t i = 0; i < n; i++)
    G[i] += h0 + (c->fprof ? c->fprof[i] : 0.5 * c->xi[i] * c->xi[i]);
  if (c->rough) {
    for (size_t i = 0; i < n; i++) {
      c->U[i] = y[i];
      c->D[i] = y[i] - c->D[i]; /* elasticity residual U - G */
    }
  }
}

/* Flow quantities per node: conductance g = u^3 phi_p and Couette film
 * c = u + h phi_s, with a conductance floor so that a fully contacted (or
 * closed) cell still fixes its pressure (a leak far below any physical
 * flow). */
static void eval_flow(vl_contact *c) {
  size_t n = c->n;
  double us = c->uscale, floor_g = 1e-12 * pow(fmax(c->hrms / us, 1e-3 * c->u_ref), 3.0);
  for (size_t i = 0; i < n; i++) {
    /* a Newton iterate may cross u < 0 (interpenetration): no flow there,
     * rather than a negative conductance */
    double on = (c->rough || c->U[i] > 0.0) ? 1.0 : 0.0; /* rough: pc(u) and the
                                                          * factors extend to u <= 0 smoothly */
    double u = (c->rough ? c->U[i] : fmax(c->U[i], 0.0)) * us;
    vl_flow_factor_values v, d;
    if (c->sf) {
      /* flattened: h = s h_rms. The factors are functions of u/h only (u
       * clamped at 0 as vl_flow_factors_eval does), so d/dh = -(u/h) d/du and
       * the total d/du is the partial one times k = 1 - u s'/s */
      double h = c->hrms * c->sf[i], dh = c->hrms * c->dsf[i];
      vl_flow_factors_eval_table(c->cfg.flow_factors, c->cfg.flow_table, u, h, &v, &d);
      if (!(h > 0.0)) {
        /* u <= 0: fully flattened, a closed smooth film (the limit u -> 0+,
         * where u/h -> inf); no negative conductance */
        double up = fmax(u, 0.0);
        c->g[i] = up * up * up / (us * us * us) + floor_g;
        c->dg[i] = 3.0 * up * up / (us * us);
        c->cf[i] = u / us;
        c->dcf[i] = 1.0;
        continue;
      }
      double k = 1.0 - fmax(u, 0.0) * c->dsf[i] / c->sf[i], u3 = u * u * u;
      c->g[i] = u3 * v.phi_p / (us * us * us) + floor_g;
      c->dg[i] = (3.0 * u * u * v.phi_p + u3 * k * d.phi_p) / (us * us);
      c->cf[i] = (u + h * v.phi_s) / us;
      c->dcf[i] = 1.0 + dh * v.phi_s + h * k * d.phi_s;
      continue;
    }
    vl_flow_factors_eval_table(c->cfg.flow_factors, c->cfg.flow_table, u, c->hrms, &v, &d);
    double u3 = u * u * u;
    c->g[i] = u3 * v.phi_p / (us * us * us) + floor_g;
    c->dg[i] = on * (3.0 * u * u * v.phi_p + u3 * d.phi_p) / (us * us);
    c->cf[i] = (u + c->hrms * v.phi_s) / us;
    c->dcf[i] = on * (1.0 + c->hrms * d.phi_s);
  }
}

double vl_contact_face_poiseuille(const vl_contact *c, size_t f) {
  size_t n = c->n;
  double dl, dr;
  double g = f == 0 ? c->g[0] : f == n ? c->g[n - 1] : face_g(c, f, &dl, &dr);
  return c->lambda * g / c->hf[f];
}

/* Face fluxes J/(v0 us/2): -lambda g dPf/dxi + Couette film at the face
 * (couette_face); pf = 0 beyond both ends of the domain (half-cell
 * distance). */
void vl_contact_eval_fluxes(vl_contact *c, const double *y) {
  size_t n = c->n;
  const double *pf = y + c->of, *hf = c->hf;
  double L = c->lambda, pin, pout;
  vl_contact_end_pressures(c, &pin, &pout);
  for (size_t f = 0; f <= n; f++) {
    size_t k[3];
    double w[3];
    int m;
    double jc = couette_face(c, f, k, w, &m), dl, dr;
    double jp = f == 0   ? -L * c->g[0] * (pf[0] - pin) / hf[0]
                : f == n ? L * c->g[n - 1] * (pf[n - 1] - pout) / hf[n]
                         : -L * face_g(c, f, &dl, &dr) * (pf[f] - pf[f - 1]) / hf[f];
    c->Jf[f] = jp + jc;
  }
}

void vl_contact_eval_state(vl_contact *c, const double *y) {
  eval_contact_pressure(c, y);
  eval_gap(c, y);
  if (c->state_y) { /* smooth dry: the state is that of y and this kernel */
    memcpy(c->state_y, y, c->nunk * sizeof *c->state_y);
    c->state_kernel = c->kernel_builds;
  }
  if (!c->wet) return;
  eval_flow(c);
  vl_contact_eval_fluxes(c, y);
}

double vl_contact_load_sum(const vl_contact *c) {
  double s = 0.0;
  for (size_t i = 0; i < c->n; i++)
    s += (c->P[i] + c->F[i]) * c->wc[i];
  if (c->pamb)
    for (size_t i = 0; i < c->n; i++)
      s -= c->pamb[i] * c->wc[i];
  return s / (0.5 * M_PI);
}

void vl_contact_end_pressures(const vl_contact *c, double *pin, double *pout) {
  double unit = c->kappa * c->p0;
  *pin = c->cfg.p_inlet_pa > 0.0 ? c->cfg.p_inlet_pa / unit : 0.0;
  *pout = c->cfg.p_outlet_pa > 0.0 ? c->cfg.p_outlet_pa / unit : 0.0;
}

/* Reynolds row i before complementarity: rw_i (J_{i+1/2} - J_{i-1/2}), see
 * vl_contact_reynolds_weights. */
double vl_contact_reynolds_residual(const vl_contact *c, size_t i) {
  return c->rw[i] * (c->Jf[i + 1] - c->Jf[i]);
}

/* Weights of the Reynolds rows for the next solve, from the current state
 * (needs vl_contact_eval_state). The complementarity FB(pf_i, R_i) compares a pressure
 * with a flux imbalance; it identifies the cavitated cells only if both are
 * measured alike. Rough: R is the imbalance per unit length in units of the
 * Couette flux at the reference film. Smooth: R is the imbalance divided by
 * its sensitivity to pf_i (Poiseuille conductance of both faces plus the
 * elastic change of the Couette film), i.e. the pressure change that would
 * balance the cell alone. With the rough scaling, where the film is thick
 * (the inlet of a soft EHL contact) a tiny relative flux error is a huge R
 * next to a tiny pf, and Newton took the inlet for cavitated. Frozen during
 * a solve, so the rows stay smooth; the solution does not depend on it. */
void vl_contact_reynolds_weights(vl_contact *c) {
  size_t n = c->n;
  if (c->rough) {
    /* per unit of the larger of the reference Couette flux and the cell's
     * own: a thick inlet film (10^4 u_min five a0 upstream of a soft
     * contact) carries fluxes whose rounding alone left rows above the
     * tolerance, and Newton stalled there */
    for (size_t i = 0; i < n; i++)
      c->rw[i] = 1.0 / (c->wc[i] * fmax(1.0 / c->rscale, fabs(c->cf[i])));
    return;
  }
  double L = c->lambda;
  for (size_t i = 0; i < n; i++) {
    double d1, d2;
    double gl = i > 0 ? face_g(c, i, &d1, &d2) : c->g[0];
    double gr = i + 1 < n ? face_g(c, i + 1, &d1, &d2) : c->g[n - 1];
    double poiseuille = L * (gl / c->hf[i] + gr / c->hf[i + 1]), elastic = 0.0;
    for (int side = 0; side < 2; side++) {
      size_t k[3];
      double w[3];
      int m;
      couette_face(c, i + (size_t)side, k, w, &m);
      for (int q = 0; q < m; q++)
        elastic += (side ? 1.0 : -1.0) * w[q] * c->dcf[k[q]] * c->M[k[q] * n + i] * c->kappa;
    }
    double d = poiseuille + fabs(elastic);
    c->rw[i] = d > 0.0 ? 1.0 / d : 1.0;
  }
}

double vl_contact_reynolds_row(const vl_contact *c, const double *y, size_t i, double *da,
                               double *db) {
  return fb_eps(y[c->of + i], vl_contact_reynolds_residual(c, i), c->rough ? FB_EPS : FB_EPS_FILM,
                da, db);
}

int vl_contact_residual(vl_contact *c, const double *y, double *f) {
  size_t nc = c->nc, nf = c->nf, of = c->of;
  vl_contact_eval_state(c, y);
  for (size_t i = 0; i < nc; i++)
    f[i] = c->rough ? c->D[i] : hard_contact(c, c->P[i], c->U[i], NULL, NULL);
  if (c->warm_set) /* the rows of the set {P > 0}: the first step solves that set exactly */
    for (size_t i = 0; i < nc; i++)
      f[i] = c->P[i] > 0.0 ? c->U[i] : c->P[i];
  for (size_t i = 0; i < nf; i++)
    f[of + i] = vl_contact_reynolds_row(c, y, i, NULL, NULL);
  f[c->ih] = vl_contact_load_sum(c) - 1.0;
  for (size_t i = 0; i < c->nunk; i++)
    if (!isfinite(f[i])) return 1; /* recoverable: KINSOL shortens the step */
  /* a smooth wet film must stay open: a step that closes it is refused
   * (recoverable: KINSOL halves the step; U is affine in y, so every shorter
   * step of the line search stays open too) */
  if (c->wet && !c->rough)
    for (size_t i = 0; i < c->n; i++)
      if (!(c->U[i] > 0.0)) return 1;
  return 0;
}

/* Adds w * d(U_k)/d(y_j) for all j to column-major row `row` of J: U depends
 * on y through the gap (smooth) or is the unknown itself (rough). */
static void add_dU(vl_contact *c, double *Jd, size_t ld, size_t row, size_t k, double w) {
  size_t n = c->n;
  if (w == 0.0) return;
  if (c->rough) {
    Jd[k * ld + row] += w;
    return;
  }
  const double *mrow = c->M + k * n;
  for (size_t j = 0; j < c->nc; j++)
    Jd[j * ld + row] += w * mrow[j];
  double wk = w * c->kappa, *col = Jd + c->of * ld + row;
  for (size_t j = 0; j < c->nf; j++)
    col[j * ld] += wk * mrow[j];
  Jd[c->ih * ld + row] += w;
}

/* d/dP and d/dU of every smooth dry cell's complementarity row. The first
 * Jacobian of an active-set solve (warm_set) takes the set {P > 0} of the
 * state, the previous solution's (as vl_contact_residual's rows then do). */
static void hard_contact_derivatives(vl_contact *c, double *dp, double *du) {
  for (size_t i = 0; i < c->n; i++)
    hard_contact(c, c->P[i], c->U[i], &dp[i], &du[i]);
  if (c->warm_set)
    for (size_t i = 0; i < c->n; i++)
      dp[i] = c->P[i] > 0.0 ? 0.0 : 1.0, du[i] = 1.0 - dp[i];
  c->warm_set = false;
}

/* The rows of the contact unknowns: elasticity (rough) or complementarity
 * (smooth dry); a smooth wet contact has none, but this zeroes the matrix. */
static void jacobian_contact_rows(vl_contact *c, double *Jd) {
  size_t n = c->n, nc = c->nc, of = c->of, ld = c->nunk, ih = c->ih;
  if (c->rough) {
    /* elasticity rows U_i - G_i, written column by column (the matrix is
     * column-major) and every entry once, so no zeroing pass:
     * d/dy_j = delta_ij - M_ij dP_j/dy_j. On a uniform grid column j of M
     * is -kfac times the Toeplitz coefficients from n-1-j on; a graded
     * grid has no such structure (and is small): read down the row-major M */
    for (size_t j = 0; j < ld; j++) {
      double *col = Jd + j * ld;
      if (j < ih) {
        size_t cell = j < n ? j : j - of;
        double dp = j < n ? c->dPdU[j] : c->kappa;
        if (c->span) {
          for (size_t i = 0; i < n; i++)
            col[i] = -dp * c->M[i * n + cell];
        } else {
          const double *t = c->kern.coef + (n - 1 - cell);
          double w = c->kfac * dp;
          for (size_t i = 0; i < n; i++)
            col[i] = w * t[i];
        }
        if (j < n) col[j] += 1.0;
      } else {
        for (size_t i = 0; i < n; i++)
          col[i] = -1.0;
      }
      memset(col + n, 0, (ld - n) * sizeof *col);
    }
  } else if (nc && !c->span) {
    /* smooth dry contact on a uniform grid: the complementarity rows
     * d FB/du_i dU_i/dy_j + d FB/dp_i delta_ij, written column by column
     * and every entry once (the matrix is column-major); column j of M is
     * -kfac times the Toeplitz coefficients from n-1-j on (as
     * graded_influence builds M, so the same values as the rows of M
     * the general branch below adds, at a fifth of its time) */
    double *dp = c->fb_work, *du = c->fb_work + n, mk = -c->kfac;
    hard_contact_derivatives(c, dp, du);
    size_t lo = 0, hi = n; /* rows lo..hi-1 written in full */
    if (c->gap_rows_only) {
      while (lo < n && du[lo] == 0.0)
        lo++;
      while (hi > lo && du[hi - 1] == 0.0)
        hi--;
    }
    for (size_t j = 0; j < n; j++) {
      double *col = Jd + j * ld;
      const double *t = c->kern.coef + (n - 1 - j);
      for (size_t i = lo; i < hi; i++) /* + 0.0: a zero du gives +0, as the zeroed matrix */
        col[i] = du[i] * (mk * t[i]) + 0.0;
      col[j] = (j >= lo && j < hi ? col[j] : 0.0) + dp[j];
      col[ih] = 0.0; /* the load row: vl_contact_jacobian */
    }
    double *col = Jd + ih * ld; /* d/d(h0) */
    for (size_t i = 0; i < n; i++)
      col[i] = du[i];
    col[ih] = 0.0;
  } else {
    memset(Jd, 0, ld * ld * sizeof *Jd);
    double *dp = c->fb_work, *du = c->fb_work + n;
    if (nc) hard_contact_derivatives(c, dp, du);
    for (size_t i = 0; i < nc; i++) { /* smooth contact: complementarity rows */
      add_dU(c, Jd, ld, i, i, du[i]);
      Jd[i * ld + i] += dp[i];
    }
  }
}

/* Reynolds row i: the fluxes of faces i (left) and i+1 (right) depend on
 * pf of cells i-1..i+1 and on u of cells i-2..i+1. */
static void jacobian_reynolds_row(vl_contact *c, const double *y, double *Jd, size_t i) {
  size_t n = c->n, of = c->of, ld = c->nunk;
  const double *pf = y + of, *hf = c->hf;
  double L = c->lambda, pin, pout;
  vl_contact_end_pressures(c, &pin, &pout);
  size_t row = of + i;
  double da, db;
  vl_contact_reynolds_row(c, y, i, &da, &db);
  Jd[row * ld + row] += da;
  double s = db * c->rw[i]; /* d(row)/d(J_{i+1}) = s, d(row)/d(J_i) = -s */
  if (s == 0.0) return;
  /* d/d(pf) of cells i-1..i+1, d/du of cells i-2..i+1 */
  double dpf[3] = {0.0, 0.0, 0.0}, du[4] = {0.0, 0.0, 0.0, 0.0};
  for (int side = 0; side < 2; side++) {
    size_t f = i + (size_t)side;
    double sg = side ? s : -s;
    if (f == 0) {
      dpf[1] += sg * (-L * c->g[0] / hf[0]);
      du[2] += sg * (-L * c->dg[0] * (pf[0] - pin) / hf[0]);
    } else if (f == n) {
      dpf[1] += sg * (L * c->g[n - 1] / hf[n]);
      du[2] += sg * (L * c->dg[n - 1] * (pf[n - 1] - pout) / hf[n]);
    } else {
      double dl, dr, gf = face_g(c, f, &dl, &dr), dp = (pf[f] - pf[f - 1]) / hf[f];
      /* cells f-1 and f are i-1, i (left face) or i, i+1 (right face) */
      dpf[side] += sg * (L * gf / hf[f]);
      dpf[side + 1] += sg * (-L * gf / hf[f]);
      du[side + 1] += sg * (-L * dl * c->dg[f - 1] * dp);
      du[side + 2] += sg * (-L * dr * c->dg[f] * dp);
    }
    size_t k[3];
    double cw[3];
    int m;
    couette_face(c, f, k, cw, &m);
    for (int q = 0; q < m; q++)
      du[k[q] + 2 - i] += sg * cw[q] * c->dcf[k[q]];
  }
  for (int q = 0; q < 3; q++)
    if (dpf[q] != 0.0) Jd[(of + i + (size_t)q - 1) * ld + row] += dpf[q];
  for (int q = 0; q < 4; q++)
    if (du[q] != 0.0) add_dU(c, Jd, ld, row, i + (size_t)q - 2, du[q]);
}

void vl_contact_jacobian(vl_contact *c, const double *y, double *Jd) {
  size_t nc = c->nc, nf = c->nf, of = c->of, ld = c->nunk, ih = c->ih;
  /* KINSOL asks for the Jacobian where it has just evaluated the residual:
   * a smooth dry contact's state is then current (its gap is a product
   * with the n x n influence matrix) */
  if (!c->state_y || c->state_kernel != c->kernel_builds ||
      memcmp(c->state_y, y, ld * sizeof *y) != 0)
    vl_contact_eval_state(c, y);
  jacobian_contact_rows(c, Jd);
  for (size_t i = 0; i < nf; i++)
    jacobian_reynolds_row(c, y, Jd, i);
  /* load balance */
  for (size_t j = 0; j < nc; j++)
    Jd[j * ld + ih] = c->wc[j] / (0.5 * M_PI) * (c->rough ? c->dPdU[j] : 1.0);
  for (size_t j = 0; j < nf; j++)
    Jd[(of + j) * ld + ih] = c->wc[j] / (0.5 * M_PI) * c->kappa;
}

/* Scales of the fluid unknowns for a solve at v0, from the current state,
 * then the Reynolds row weights. Rough: pf by its expected magnitude
 * (extrapolated linearly in speed from the last converged state: pf ~ eta v0
 * in the boundary regime), Reynolds rows by the Couette flux at the current
 * minimum film. Smooth: the film carries the whole load at any speed, so pf
 * keeps the magnitude of the current state (fN over the pressurised length,
 * which is the larger of a0 and the inlet length sqrt(2 R u): the speed
 * does not enter); rows as in vl_contact_reynolds_weights, free of any length scale,
 * which keeps stiff solids (inlet length >> a0) as well conditioned as soft
 * ones. Rescales y accordingly. */
void vl_contact_fluid_scales(vl_contact *c, double v0) {
  if (!c->wet) return;
  size_t n = c->n;
  double *y = N_VGetArrayPointer(c->y);
  vl_contact_eval_state(c, y);
  double umin = INFINITY, fmax_p0 = 0.0;
  for (size_t i = 0; i < n; i++) {
    umin = fmin(umin, c->U[i]);
    fmax_p0 = fmax(fmax_p0, c->F[i]);
  }
  double us = c->uscale, eta = c->cfg.eta_pa_s;
  double kappa;
  if (!c->rough) {
    /* without a pressure yet: fN over the larger of a0 and the inlet
     * length sqrt(2 R u) (= sqrt(2 U) a0 with U in a0^2/R) */
    c->u_ref = umin > 0.0 ? umin : vl_contact_film_estimate(&c->cfg, v0) / us;
    kappa = fmax_p0 > 0.0 ? fmax_p0 : 1.0 / fmax(1.0, sqrt(2.0 * c->u_ref));
  } else {
    /* the film cannot be thinner than a rigid cylinder's (Martin) nor, on a
     * rough surface, than a fraction of the roughness */
    double h_martin = 2.447 * eta * v0 * c->cfg.radius_m / c->cfg.load_n_per_m;
    c->u_ref = fmax(umin, fmax(1e-3 * c->hrms, h_martin) / us);
    if (fmax_p0 > 0.0 && c->v_state > 0.0) {
      kappa = fmax_p0; /* the predictor (vl_contact_predict_state) has scaled pf to v0 */
    } else {
      /* hydrodynamic estimate 6 eta v0 a0 / u^2, at most p0 */
      double u = c->u_ref * us;
      kappa = 6.0 * eta * v0 * c->a0 / (u * u) / c->p0;
    }
    kappa = fmin(fmax(kappa, 1e-300), 10.0);
    c->rscale = 1.0 / c->u_ref;
  }
  for (size_t i = 0; i < c->nf; i++)
    y[c->of + i] *= c->kappa / kappa;
  c->kappa = kappa;
  c->lambda = us * us * c->p0 * kappa / (6.0 * eta * v0 * c->a0);
  vl_contact_eval_state(c, y);
  vl_contact_reynolds_weights(c);
}
