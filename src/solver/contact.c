/* One operating point of the contact (dry or wet): KINSOL Newton on dimensionless
 * unknowns (contact.h). */
#include "viscolube/contact.h"
#include "viscolube/persson.h"

#include <float.h>
#include <kinsol/kinsol.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "linsol_lapack.h"
#include "linsol_schur.h"
#include "kernel.h"

/* Smoothing of the Fischer-Burmeister function: p u = FB_EPS at the contact
 * edge instead of 0, far below the tolerance, but the function stays
 * differentiable where both p and u vanish. */
#define FB_EPS 1e-18
/* The same for the cavitation of a smooth film, where it must be far
 * smaller: FB(pf, R) = 0 means pf R = eps/2, and the far inlet of a stiff
 * contact has pf ~ 1e-7 (of its peak) with R = (flux imbalance)/(its
 * sensitivity to pf), a sensitivity of ~1e11 there: 1e-18 left the inlet
 * flux off by 1 %. */
#define FB_EPS_FILM 1e-200

/* Smallest grid of the coarse levels used to start smooth wet solves. */
#define VL_COARSE_MIN 96

struct vl_contact {
  vl_contact_config cfg;
  bool rough, wet;
  size_t n;        /* grid nodes */
  size_t nc;       /* contact unknowns (n; 0 for a smooth wet contact) */
  size_t nf;       /* fluid unknowns (n when wet, else 0) */
  size_t nunk;     /* unknowns: nc contact + nf fluid + rigid approach */
  size_t of, ih;   /* offsets of the fluid unknowns and of the rigid approach */
  double er_ref;   /* reduced modulus defining a0 (relaxed, or the elastic one) */
  double er_inf;   /* reduced glassy modulus (kernel prefactor) */
  double a0, p0, uscale, dxi, kfac; /* dxi: width of the uniform cells */
  double hrms;     /* rms roughness (m), 0 when smooth */
  double *xi;      /* node positions x/a0 (cell centres) */
  double *wc;      /* cell widths /a0 */
  double *hf;      /* n + 1 face distances /a0: node to node, half a cell at both ends */
  /* graded grid (vl_contact_config.grid_growth): cell i is uniform cells
   * first[i] .. first[i] + span[i] - 1 of an nv-cell uniform grid (span odd,
   * so its node is uniform node first[i] + span[i]/2); psum: prefix sums of
   * the uniform Toeplitz coefficients. All NULL on a uniform grid (nv = n). */
  size_t nv, *first, *span;
  double *psum;
  double *A, *beta;/* Prony strengths and v0 tau_k / a0 */
  vl_toeplitz kern;
  double *M;       /* dense influence matrix, row-major: U_i += M[i n + j] P_j */
  double v0;       /* speed the kernel is built for (NAN: not yet) */
  bool kernel_ready;
  double e_abs, a_h, omega_h, sfac; /* asperity state; P = sfac * s(u) */
  /* fluid scales of the current solve: pf = kappa p0 Pf; flux in units of
   * v0 us/2 (lambda: its Poiseuille coefficient); rough Reynolds rows per
   * Couette flux v0 u_ref/2 (rscale = 1/u_ref), see reynolds_weights */
  double kappa, lambda, rscale, u_ref;
  double *rw;         /* weight of Reynolds row i (frozen during a solve) */
  double v_state;     /* speed at which y was last converged (0: initial guess) */
  double q_rolling;   /* rolling number (wet, rough, viscoelastic), else 0 */
  double *P, *dPdU;   /* contact pressure (p0) and dP/dU on the grid */
  double *F;          /* fluid pressure (p0) */
  double *U;          /* separation (a0^2/R) */
  double *g, *dg, *cf, *dcf; /* conductance u^3 phi_p and Couette film u + h phi_s, /us^3, /us */
  double *Jf;         /* face fluxes, n + 1 */
  double *D;          /* rough: elasticity residual U - G */
  double *sf, *dsf;   /* viscous flattening: sqrt(epsilon_f(u)) per node and its d/du (1/m);
                       * NULL when off */
  double *theta;      /* film fraction (report only) */
  vl_contact *coarse; /* smooth wet: half-size grid for fresh starts (NULL when small) */
  bool no_fallback;   /* inside the viscosity-continuation fallback of a fresh start */
  vl_contact *dry;    /* smooth wet viscoelastic, coarsest level: the dry contact on the same
                       * grid, whose solution starts the wet one (NULL otherwise) */
  vl_contact_timing timing; /* cost counters (vl_contact_timing_get) */
  SUNContext ctx;
  N_Vector y, y_saved, y_outer, ones, fwork;
  SUNMatrix J;
  SUNLinearSolver LS;
  SUNLinearSolver schur; /* the inner solver of LS when VL_LINSOL_SCHUR applies (not owned) */
  void *kmem;
};

const char *vl_regime_name(int regime) {
  switch (regime) {
  case VL_REGIME_DRY: return "dry";
  case VL_REGIME_BOUNDARY: return "boundary";
  case VL_REGIME_MIXED: return "mixed";
  case VL_REGIME_HYDRODYNAMIC: return "hydrodynamic";
  }
  return "?";
}

void vl_contact_config_defaults(vl_contact_config *cfg) {
  memset(cfg, 0, sizeof *cfg);
  cfg->grid_growth = 1.0;
  cfg->grid = 512;
  cfg->x_min_a0 = -1.6;
  cfg->x_max_a0 = 1.4;
  cfg->tolerance = 1e-9;
  cfg->max_iterations = VL_NEWTON_MAX_ITERATIONS;
  cfg->linear_solver = VL_LINSOL_SCHUR;
}

/* Fischer-Burmeister complementarity a >= 0, b >= 0, a b = eps/2 (smoothed),
 * with its partial derivatives. */
static double fb_eps(double a, double b, double eps, double *da, double *db) {
  double r = sqrt(a * a + b * b + eps);
  if (da) *da = 1.0 - a / r;
  if (db) *db = 1.0 - b / r;
  return a + b - r;
}
static double fb(double a, double b, double *da, double *db) { return fb_eps(a, b, FB_EPS, da, db); }

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
 * theory (MODEL.md section 4, seed Eq. 8) that is an exact rescaling:
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
  if (!c->cfg.flattening) return 1.0;
  double de, e = vl_flattening_eps(c->cfg.flattening, u_m, &de);
  if (!(e > 0.0)) return 0.0; /* u <= 0: every wavelength flattened */
  double s = sqrt(e);
  *ds_du = 0.5 * de / s;
  return s;
}

/* Everything the residual needs from the unknowns y: contact pressure P (and
 * dP/dU), fluid pressure F, separation U, flow quantities and face fluxes. */
static void eval_state(vl_contact *c, const double *y) {
  size_t n = c->n;
  double h0 = y[c->ih];
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
  for (size_t i = 0; i < n; i++) c->F[i] = c->wet ? c->kappa * y[c->of + i] : 0.0;
  /* elastic/viscoelastic gap: h0 + xi^2/2 + sum_j M_ij (P_j + F_j); for a
   * rough surface it is stored in D (the residual compares it with U) */
  double *G = c->rough ? c->D : c->U;
  for (size_t i = 0; i < n; i++) {
    const double *row = c->M + i * n;
    double acc = 0.0;
    for (size_t j = 0; j < n; j++) acc += row[j] * (c->P[j] + c->F[j]);
    G[i] = h0 + 0.5 * c->xi[i] * c->xi[i] + acc;
  }
  if (c->rough) {
    for (size_t i = 0; i < n; i++) {
      c->U[i] = y[i];
      c->D[i] = y[i] - c->D[i]; /* elasticity residual U - G */
    }
  }
  if (!c->wet) return;
  /* flow: conductance g = u^3 phi_p and Couette film c = u + h phi_s, with a
   * conductance floor so that a fully contacted (or closed) cell still fixes
   * its pressure (a leak far below any physical flow) */
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
      vl_flow_factors_eval(c->cfg.flow_factors, u, h, &v, &d);
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
    vl_flow_factors_eval(c->cfg.flow_factors, u, c->hrms, &v, &d);
    double u3 = u * u * u;
    c->g[i] = u3 * v.phi_p / (us * us * us) + floor_g;
    c->dg[i] = on * (3.0 * u * u * v.phi_p + u3 * d.phi_p) / (us * us);
    c->cf[i] = (u + c->hrms * v.phi_s) / us;
    c->dcf[i] = on * (1.0 + c->hrms * d.phi_s);
  }
  /* face fluxes J/(v0 us/2): -lambda g dPf/dxi + Couette film at the face
   * (couette_face); pf = 0 beyond both ends of the domain (half-cell
   * distance) */
  const double *pf = y + c->of, *hf = c->hf;
  double L = c->lambda;
  for (size_t f = 0; f <= n; f++) {
    size_t k[3];
    double w[3];
    int m;
    double jc = couette_face(c, f, k, w, &m), dl, dr;
    double jp = f == 0   ? -L * c->g[0] * pf[0] / hf[0]
                : f == n ? L * c->g[n - 1] * pf[n - 1] / hf[n]
                         : -L * face_g(c, f, &dl, &dr) * (pf[f] - pf[f - 1]) / hf[f];
    c->Jf[f] = jp + jc;
  }
}

static double load_sum(const vl_contact *c) {
  double s = 0.0;
  for (size_t i = 0; i < c->n; i++) s += (c->P[i] + c->F[i]) * c->wc[i];
  return s / (0.5 * M_PI);
}

/* Reynolds row i before complementarity: rw_i (J_{i+1/2} - J_{i-1/2}), see
 * reynolds_weights. */
static double reynolds_residual(const vl_contact *c, size_t i) {
  return c->rw[i] * (c->Jf[i + 1] - c->Jf[i]);
}

/* Weights of the Reynolds rows for the next solve, from the current state
 * (needs eval_state). The complementarity FB(pf_i, R_i) compares a pressure
 * with a flux imbalance; it identifies the cavitated cells only if both are
 * measured alike. Rough: R is the imbalance per unit length in units of the
 * Couette flux at the reference film. Smooth: R is the imbalance divided by
 * its sensitivity to pf_i (Poiseuille conductance of both faces plus the
 * elastic change of the Couette film), i.e. the pressure change that would
 * balance the cell alone. With the rough scaling, where the film is thick
 * (the inlet of a soft EHL contact) a tiny relative flux error is a huge R
 * next to a tiny pf, and Newton took the inlet for cavitated. Frozen during
 * a solve, so the rows stay smooth; the solution does not depend on it. */
static void reynolds_weights(vl_contact *c) {
  size_t n = c->n;
  if (c->rough) {
    /* per unit of the larger of the reference Couette flux and the cell's
     * own: a thick inlet film (10^4 u_min five a0 upstream of a soft
     * contact) carries fluxes whose rounding alone left rows above the
     * tolerance, and Newton stalled there */
    for (size_t i = 0; i < n; i++) c->rw[i] = 1.0 / (c->wc[i] * fmax(1.0 / c->rscale, fabs(c->cf[i])));
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

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A SUNLinearSolver that forwards to an inner one and times its set-up
 * (factorisation) and solves: the cost split of vl_contact_timing. */
typedef struct {
  SUNLinearSolver inner;
  vl_contact_timing *timing;
} timed_ls;

static SUNLinearSolver_Type timed_gettype(SUNLinearSolver S) {
  return SUNLinSolGetType(((timed_ls *)S->content)->inner);
}
static SUNLinearSolver_ID timed_getid(SUNLinearSolver S) {
  return SUNLinSolGetID(((timed_ls *)S->content)->inner);
}
static int timed_initialize(SUNLinearSolver S) {
  return SUNLinSolInitialize(((timed_ls *)S->content)->inner);
}
static int timed_setup(SUNLinearSolver S, SUNMatrix A) {
  timed_ls *t = S->content;
  double t0 = now_s();
  int r = SUNLinSolSetup(t->inner, A);
  t->timing->t_setup_s += now_s() - t0;
  t->timing->setups++;
  return r;
}
static int timed_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, realtype tol) {
  timed_ls *t = S->content;
  double t0 = now_s();
  int r = SUNLinSolSolve(t->inner, A, x, b, tol);
  t->timing->t_solve_s += now_s() - t0;
  t->timing->solves++;
  return r;
}
static sunindextype timed_lastflag(SUNLinearSolver S) {
  return SUNLinSolLastFlag(((timed_ls *)S->content)->inner);
}
static int timed_space(SUNLinearSolver S, long *lenrw, long *leniw) {
  return SUNLinSolSpace(((timed_ls *)S->content)->inner, lenrw, leniw);
}
static int timed_free(SUNLinearSolver S) {
  if (!S) return SUNLS_SUCCESS;
  if (S->content) {
    SUNLinSolFree(((timed_ls *)S->content)->inner);
    free(S->content);
    S->content = NULL;
  }
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

/* Wraps inner (owned from here on, freed with the wrapper, also on failure). */
static SUNLinearSolver timed_ls_create(SUNLinearSolver inner, vl_contact_timing *timing,
                                       SUNContext ctx) {
  if (!inner) return NULL;
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  timed_ls *t = S ? malloc(sizeof *t) : NULL;
  if (!t) {
    if (S) SUNLinSolFreeEmpty(S);
    SUNLinSolFree(inner);
    return NULL;
  }
  t->inner = inner, t->timing = timing;
  S->content = t;
  S->ops->gettype = timed_gettype;
  S->ops->getid = timed_getid;
  S->ops->initialize = timed_initialize;
  S->ops->setup = timed_setup;
  S->ops->solve = timed_solve;
  S->ops->lastflag = timed_lastflag;
  S->ops->space = timed_space;
  S->ops->free = timed_free;
  return S;
}

static int residual_impl(N_Vector yv, N_Vector fv, vl_contact *c);

static int residual_fn(N_Vector yv, N_Vector fv, void *user) {
  vl_contact *c = user;
  double t0 = now_s();
  int r = residual_impl(yv, fv, c);
  c->timing.t_residual_s += now_s() - t0;
  c->timing.residuals++;
  return r;
}

static int residual_impl(N_Vector yv, N_Vector fv, vl_contact *c) {
  const double *y = N_VGetArrayPointer(yv);
  double *f = N_VGetArrayPointer(fv);
  size_t nc = c->nc, nf = c->nf, of = c->of;
  eval_state(c, y);
  for (size_t i = 0; i < nc; i++)
    f[i] = c->rough ? c->D[i] : fb(c->P[i], c->U[i], NULL, NULL);
  double eps = c->rough ? FB_EPS : FB_EPS_FILM;
  for (size_t i = 0; i < nf; i++) f[of + i] = fb_eps(y[of + i], reynolds_residual(c, i), eps, NULL, NULL);
  f[c->ih] = load_sum(c) - 1.0;
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
  for (size_t j = 0; j < c->nc; j++) Jd[j * ld + row] += w * mrow[j];
  double wk = w * c->kappa, *col = Jd + c->of * ld + row;
  for (size_t j = 0; j < c->nf; j++) col[j * ld] += wk * mrow[j];
  Jd[c->ih * ld + row] += w;
}

static void jacobian_impl(N_Vector yv, SUNMatrix J, vl_contact *c);

static int jacobian_fn(N_Vector yv, N_Vector fv, SUNMatrix J, void *user, N_Vector t1,
                       N_Vector t2) {
  (void)fv, (void)t1, (void)t2;
  vl_contact *c = user;
  double t0 = now_s();
  jacobian_impl(yv, J, c);
  c->timing.t_jacobian_s += now_s() - t0;
  c->timing.jacobians++;
  return 0;
}

static void jacobian_impl(N_Vector yv, SUNMatrix J, vl_contact *c) {
  const double *y = N_VGetArrayPointer(yv);
  size_t n = c->n, nc = c->nc, nf = c->nf, of = c->of, ld = c->nunk, ih = c->ih;
  double *Jd = SUNDenseMatrix_Data(J);
  eval_state(c, y);
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
          for (size_t i = 0; i < n; i++) col[i] = -dp * c->M[i * n + cell];
        } else {
          const double *t = c->kern.coef + (n - 1 - cell);
          double w = c->kfac * dp;
          for (size_t i = 0; i < n; i++) col[i] = w * t[i];
        }
        if (j < n) col[j] += 1.0;
      } else {
        for (size_t i = 0; i < n; i++) col[i] = -1.0;
      }
      memset(col + n, 0, (ld - n) * sizeof *col);
    }
  } else {
    memset(Jd, 0, ld * ld * sizeof *Jd);
    for (size_t i = 0; i < nc; i++) { /* smooth contact: complementarity rows */
      double dfdp, dfdu;
      fb(c->P[i], c->U[i], &dfdp, &dfdu);
      add_dU(c, Jd, ld, i, i, dfdu);
      Jd[i * ld + i] += dfdp;
    }
  }
  /* Reynolds rows: the fluxes of faces i (left) and i+1 (right) depend on
   * pf of cells i-1..i+1 and on u of cells i-2..i+1 */
  const double *pf = y + of, *hf = c->hf;
  double L = c->lambda;
  for (size_t i = 0; i < nf; i++) {
    size_t row = of + i;
    double da, db;
    fb_eps(pf[i], reynolds_residual(c, i), c->rough ? FB_EPS : FB_EPS_FILM, &da, &db);
    Jd[row * ld + row] += da;
    double s = db * c->rw[i]; /* d(row)/d(J_{i+1}) = s, d(row)/d(J_i) = -s */
    if (s == 0.0) continue;
    /* d/d(pf) of cells i-1..i+1, d/du of cells i-2..i+1 */
    double dpf[3] = {0.0, 0.0, 0.0}, du[4] = {0.0, 0.0, 0.0, 0.0};
    for (int side = 0; side < 2; side++) {
      size_t f = i + (size_t)side;
      double sg = side ? s : -s;
      if (f == 0) {
        dpf[1] += sg * (-L * c->g[0] / hf[0]);
        du[2] += sg * (-L * c->dg[0] * pf[0] / hf[0]);
      } else if (f == n) {
        dpf[1] += sg * (L * c->g[n - 1] / hf[n]);
        du[2] += sg * (L * c->dg[n - 1] * pf[n - 1] / hf[n]);
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
      for (int q = 0; q < m; q++) du[k[q] + 2 - i] += sg * cw[q] * c->dcf[k[q]];
    }
    for (int q = 0; q < 3; q++)
      if (dpf[q] != 0.0) Jd[(of + i + (size_t)q - 1) * ld + row] += dpf[q];
    for (int q = 0; q < 4; q++)
      if (du[q] != 0.0) add_dU(c, Jd, ld, row, i + (size_t)q - 2, du[q]);
  }
  /* load balance */
  for (size_t j = 0; j < nc; j++)
    Jd[j * ld + ih] = c->wc[j] / (0.5 * M_PI) * (c->rough ? c->dPdU[j] : 1.0);
  for (size_t j = 0; j < nf; j++) Jd[(of + j) * ld + ih] = c->wc[j] / (0.5 * M_PI) * c->kappa;
}

/* The influence matrix M from the uniform grid's Toeplitz coefficients: on a
 * uniform grid they are M itself; a graded grid's cell is a run of uniform
 * cells whose node is a uniform node, so its coefficient is the sum of the
 * run's, taken from prefix sums (O(n^2) whatever the cell sizes; a direct
 * evaluation would cost n^2 exponential integrals per Prony term and speed).
 * Single cells take the coefficient itself, so the uniform part of a graded
 * grid has exactly the uniform grid's coefficients. */
static void graded_influence(vl_contact *c) {
  size_t n = c->n;
  if (!c->span) {
    for (size_t i = 0; i < n; i++)
      for (size_t j = 0; j < n; j++) c->M[i * n + j] = -c->kfac * vl_toeplitz_at(&c->kern, i, j);
    return;
  }
  size_t nv = c->nv;
  const double *coef = c->kern.coef;
  double *S = c->psum;
  S[0] = 0.0;
  for (size_t k = 0; k + 1 < 2 * nv; k++) S[k + 1] = S[k] + coef[k];
  for (size_t i = 0; i < n; i++) {
    size_t ci = c->first[i] + c->span[i] / 2;
    for (size_t j = 0; j < n; j++) {
      /* offsets ci - l of the run l = a .. a + m - 1 are coefficients
       * lo .. hi (offset d is coefficient d + nv - 1) */
      size_t a = c->first[j], m = c->span[j];
      size_t hi = ci + nv - 1 - a, lo = ci + nv - a - m;
      c->M[i * n + j] = -c->kfac * (m == 1 ? coef[hi] : S[hi + 1] - S[lo]);
    }
  }
}

/* Cells of the grid (vl_contact_config.grid_growth): nv uniform cells on
 * [x_min, x_max]; upstream of -VL_GRADE_START_A0 they are merged, from the
 * contact outwards, into runs of odd length growing by `growth` (never
 * shrinking), the last run taking the rest, between one and two of the
 * previous runs (one uniform cell more when the rest is even: the domain
 * then starts one uniform cell earlier). Writes span[] left to right (room
 * for nv + 1 cells) and the uniform cells covered in *nv_out. Returns the
 * number of cells. */
static size_t grid_layout(size_t nv, double x_min, double x_max, double growth, size_t *span,
                          size_t *nv_out) {
  double dx = (x_max - x_min) / (double)nv, start = -VL_GRADE_START_A0;
  size_t ig = 0;
  if (growth > 1.0 && x_min < start) ig = (size_t)fmin(floor((start - x_min) / dx), (double)nv);
  size_t cells = 0, rem = ig, prev = 1, covered = 0;
  double t = 1.0;
  /* the merged runs, from the contact outwards (reversed below) */
  while (rem > 0) {
    t *= growth;
    size_t m = 2 * (size_t)round((t - 1.0) / 2.0) + 1;
    if (m < prev) m = prev;
    if (rem < 2 * m) m = rem % 2 ? rem : rem + 1; /* the last run: m .. 2m */
    span[cells++] = m;
    covered += m;
    rem -= m < rem ? m : rem;
    prev = m;
  }
  for (size_t i = 0; i < cells / 2; i++) {
    size_t tmp = span[i];
    span[i] = span[cells - 1 - i], span[cells - 1 - i] = tmp;
  }
  for (size_t i = cells; i < cells + nv - ig; i++) span[i] = 1;
  *nv_out = covered + (nv - ig);
  return cells + nv - ig;
}

/* Rebuilds the influence matrix for speed v0 (viscoelastic kernels only). */
static void contact_set_speed(vl_contact *c, double v0) {
  if (c->v0 == v0) return;
  c->v0 = v0;
  vl_asperity_state(&c->cfg.rubber, c->cfg.load_n_per_m, c->cfg.radius_m, v0, &c->e_abs, &c->a_h,
                    &c->omega_h);
  c->sfac = c->e_abs / c->p0;
  /* v0 was validated (finite): set_speed cannot fail */
  if (c->cfg.flattening) vl_flattening_set_speed(c->cfg.flattening, v0, NULL);
  size_t nt = c->cfg.rubber.n_terms;
  if (nt == 0 && c->kernel_ready) return; /* elastic: one kernel for all speeds */
  double t0 = now_s();
  c->kernel_ready = true;
  for (size_t k = 0; k < nt; k++) c->beta[k] = v0 * c->cfg.rubber.tau_s[k] / c->a0;
  vl_toeplitz_refill(&c->kern, c->A, c->beta, nt);
  graded_influence(c);
  c->timing.t_kernel_s += now_s() - t0;
  c->timing.kernels++;
}

/* Hertz gap outside a contact of half-width 1 (units a0^2/R, x in a0). */
static double hertz_gap(double xi) {
  double ax = fabs(xi);
  if (ax <= 1.0) return 0.0;
  double r = sqrt(ax * ax - 1.0);
  return 0.5 * (ax * r - log(ax + r));
}

void vl_contact_reset(vl_contact *c) {
  size_t n = c->n;
  double *y = N_VGetArrayPointer(c->y);
  contact_set_speed(c, c->v0 == c->v0 ? c->v0 : 0.0);
  for (size_t i = 0; i < n; i++) {
    double x = c->xi[i];
    double p = fabs(x) < 1.0 ? sqrt(1.0 - x * x) : 0.0;
    if (!c->rough) {
      y[i] = p; /* contact pressure, or fluid pressure when smooth wet (kappa = 1) */
    } else {
      /* Separation of the rough contact under the Hertz pressure, plus the
       * Hertz gap outside. */
      double s = p * c->p0 / c->e_abs;
      double u = vl_persson_separation(c->cfg.roughness, s > 0.0 ? s : 1e-12);
      y[i] = u / c->uscale + hertz_gap(x);
    }
  }
  if (c->nc) for (size_t i = 0; i < c->nf; i++) y[c->of + i] = 0.0;
  c->kappa = 1.0;
  c->v_state = 0.0;
  /* h0 that best satisfies the gap equation inside the contact */
  y[c->ih] = 0.0;
  eval_state(c, y);
  double sum = 0.0;
  size_t cnt = 0;
  for (size_t i = 0; i < n; i++) {
    if (fabs(c->xi[i]) < 1.0) {
      sum += c->rough ? c->D[i] : -c->U[i];
      cnt++;
    }
  }
  y[c->ih] = cnt ? sum / (double)cnt : 0.0;
}

static int skip_zero(SUNMatrix A) {
  (void)A;
  return SUNMAT_SUCCESS;
}

/* The library never prints: KINSOL's messages are dropped, its return flags
 * reported in vl_error instead. */
static void silent_error_handler(int code, const char *module, const char *function, char *msg,
                                 void *user) {
  (void)code, (void)module, (void)function, (void)msg, (void)user;
}

vl_status vl_contact_create(const vl_contact_config *cfg, vl_contact **out, vl_error *err) {
  *out = NULL;
  vl_status st = vl_prony_validate(&cfg->rubber, err);
  if (st != VL_OK) return st;
  if (!(cfg->radius_m > 0.0 && isfinite(cfg->radius_m))) {
    vl_error_set(err, "radius_m must be positive (got %g)", cfg->radius_m);
    return VL_EINPUT;
  }
  if (!(cfg->load_n_per_m > 0.0 && isfinite(cfg->load_n_per_m))) {
    vl_error_set(err, "load_n_per_m must be positive (got %g)", cfg->load_n_per_m);
    return VL_EINPUT;
  }
  if (!(cfg->sigma_s_pa >= 0.0 && isfinite(cfg->sigma_s_pa))) {
    vl_error_set(err, "sigma_s_pa must be >= 0 (got %g)", cfg->sigma_s_pa);
    return VL_EINPUT;
  }
  if (cfg->grid_growth != cfg->grid_growth || cfg->grid_growth > 2.0) {
    vl_error_set(err, "grid_growth must be <= 2 (1 or less: uniform grid; got %g)",
                 cfg->grid_growth);
    return VL_EINPUT;
  }
  size_t max_grid = cfg->grid_growth > 1.0 ? VL_CONTACT_MAX_GRID_GRADED : VL_CONTACT_MAX_CELLS;
  if (cfg->grid < 8 || cfg->grid > max_grid) {
    vl_error_set(err, "grid must lie in [8, %zu] (got %zu)", max_grid, cfg->grid);
    return VL_EINPUT;
  }
  if (cfg->grid_growth > 1.0 && !cfg->roughness) {
    /* the smooth film's limited upwinding and its coarse-grid starts are
     * written for a uniform grid */
    vl_error_set(err, "grid_growth %g: a graded grid needs a rough surface (smooth contacts use "
                      "a uniform grid; set grid_growth = 1)",
                 cfg->grid_growth);
    return VL_EINPUT;
  }
  if (!(cfg->x_max_a0 > cfg->x_min_a0)) {
    vl_error_set(err, "domain_a0: the end must exceed the start (got %g, %g)", cfg->x_min_a0,
                 cfg->x_max_a0);
    return VL_EINPUT;
  }
  if (!(cfg->x_min_a0 < 0.0 && cfg->x_max_a0 > 0.0)) {
    /* the contact forms around the cylinder's axis, x = 0 */
    vl_error_set(err, "domain_a0 must contain the axis x = 0 (got %g, %g)", cfg->x_min_a0,
                 cfg->x_max_a0);
    return VL_EINPUT;
  }
  if ((unsigned)cfg->linear_solver > VL_LINSOL_SCHUR ||
      (unsigned)cfg->flow_factors > VL_FLOW_FACTORS_PATIR_CHENG) {
    vl_error_set(err, "unknown %s (%d)",
                 (unsigned)cfg->linear_solver > VL_LINSOL_SCHUR ? "linear solver" : "flow factors",
                 (unsigned)cfg->linear_solver > VL_LINSOL_SCHUR ? (int)cfg->linear_solver
                                                                : (int)cfg->flow_factors);
    return VL_EINPUT;
  }
  {
    /* the scales of the dimensionless unknowns must exist in double precision
     * (R = fN = 1e200 gave a0^2/R = inf and a NaN point reported converged) */
    double er = vl_prony_e0(&cfg->rubber) * vl_prony_reduced_factor(&cfg->rubber);
    double a0 = sqrt(4.0 * cfg->load_n_per_m * cfg->radius_m / (M_PI * er));
    double p0 = 2.0 * cfg->load_n_per_m / (M_PI * a0), us = a0 * a0 / cfg->radius_m;
    if (!(isfinite(a0) && a0 > 0.0 && isfinite(p0) && p0 > 0.0 && isfinite(us) && us > 0.0 &&
          isfinite(a0 * cfg->x_min_a0) && isfinite(a0 * cfg->x_max_a0))) {
      vl_error_set(err,
                   "the contact's scales overflow: Hertz half-width %g m, peak pressure %g Pa, "
                   "a0^2/R %g m (radius %g m, load %g N/m, reduced modulus %g Pa)",
                   a0, p0, us, cfg->radius_m, cfg->load_n_per_m, er);
      return VL_EINPUT;
    }
  }
  if (!(cfg->tolerance > 0.0 && cfg->tolerance < 1.0)) {
    vl_error_set(err, "tolerance must lie in (0, 1) (got %g)", cfg->tolerance);
    return VL_EINPUT;
  }
  if (!(cfg->eta_pa_s >= 0.0 && isfinite(cfg->eta_pa_s))) {
    vl_error_set(err, "viscosity must be >= 0 (got %g Pa s)", cfg->eta_pa_s);
    return VL_EINPUT;
  }
  if (cfg->flattening) {
    /* epsilon_f modulates the roughness by the film's pressure: nothing to
     * flatten on a smooth surface, no film in a dry contact */
    if (!cfg->roughness || !(cfg->eta_pa_s > 0.0)) {
      vl_error_set(err, "viscous flattening needs %s",
                   !cfg->roughness ? "a rough surface (roughness = NULL: smooth contact)"
                                   : "a fluid (eta > 0: the contact is dry)");
      return VL_EINPUT;
    }
    vl_flattening_state fs;
    vl_flattening_state_get(cfg->flattening, &fs);
    double h_table = vl_persson_hrms(cfg->roughness);
    if (!(fabs(fs.hrms_m - h_table) <= 1e-9 * h_table)) {
      vl_error_set(err,
                   "viscous flattening was built for a surface of h_rms %g m, the roughness "
                   "table has %g m: both must come from the same PSD",
                   fs.hrms_m, h_table);
      return VL_EINPUT;
    }
    /* the contact's viscosity is the one that counts */
    st = vl_flattening_set_viscosity(cfg->flattening, cfg->eta_pa_s, err);
    if (st != VL_OK) return st;
  }
  vl_contact *c = calloc(1, sizeof *c);
  if (!c) goto nomem;
  c->cfg = *cfg;
  if (c->cfg.max_iterations <= 0) c->cfg.max_iterations = VL_NEWTON_MAX_ITERATIONS;
  c->rough = cfg->roughness != NULL;
  c->wet = cfg->eta_pa_s > 0.0;
  /* flow factors only make sense for a rough surface */
  if (!c->rough) c->cfg.flow_factors = VL_FLOW_FACTORS_SMOOTH;
  c->hrms = c->rough ? vl_persson_hrms(cfg->roughness) : 0.0;
  c->span = malloc((cfg->grid + 1) * sizeof *c->span);
  if (!c->span) goto nomem;
  c->n = grid_layout(cfg->grid, cfg->x_min_a0, cfg->x_max_a0, cfg->grid_growth, c->span, &c->nv);
  if (c->n == cfg->grid && c->nv == cfg->grid) { /* nothing merged: the uniform grid */
    free(c->span);
    c->span = NULL;
  }
  if (c->n > VL_CONTACT_MAX_CELLS) {
    vl_error_set(err, "grid %zu with growth %g gives %zu cells (at most %d: the matrices are dense)",
                 cfg->grid, cfg->grid_growth, c->n, VL_CONTACT_MAX_CELLS);
    st = VL_EINPUT;
    goto fail;
  }
  c->nf = c->wet ? c->n : 0;
  /* A smooth wet contact keeps a positive film (Reynolds' equation carries
   * any load at any v0 > 0): no contact unknowns, pressure-only system. */
  c->nc = c->wet && !c->rough ? 0 : c->n;
  c->of = c->nc;
  c->ih = c->nc + c->nf;
  c->nunk = c->nc + c->nf + 1;
  double red = vl_prony_reduced_factor(&cfg->rubber);
  c->er_ref = vl_prony_e0(&cfg->rubber) * red;
  c->er_inf = cfg->rubber.e_inf_pa * red;
  c->a0 = sqrt(4.0 * cfg->load_n_per_m * cfg->radius_m / (M_PI * c->er_ref));
  c->p0 = 2.0 * cfg->load_n_per_m / (M_PI * c->a0);
  c->uscale = c->a0 * c->a0 / cfg->radius_m;
  c->dxi = (cfg->x_max_a0 - cfg->x_min_a0) / (double)cfg->grid;
  /* w/(a0^2/R) = -(Er_ref/(pi Er_inf)) sum_j P_j Khat_ij, Khat in units of a0. */
  c->kfac = c->er_ref / (M_PI * c->er_inf);
  c->v0 = NAN;
  size_t n = c->n, nt = cfg->rubber.n_terms;
  c->xi = malloc(n * sizeof *c->xi);
  c->wc = malloc(n * sizeof *c->wc);
  c->hf = malloc((n + 1) * sizeof *c->hf);
  if (!c->xi || !c->wc || !c->hf) goto nomem;
  if (c->span) {
    c->first = malloc(n * sizeof *c->first);
    c->psum = malloc(2 * c->nv * sizeof *c->psum);
    if (!c->first || !c->psum) goto nomem;
  }
  c->A = malloc((nt ? nt : 1) * sizeof *c->A);
  c->beta = calloc(nt ? nt : 1, sizeof *c->beta);
  c->M = calloc(n * n, sizeof *c->M);
  c->P = calloc(n, sizeof *c->P);
  c->U = calloc(n, sizeof *c->U);
  c->dPdU = calloc(n, sizeof *c->dPdU);
  c->F = calloc(n, sizeof *c->F);
  c->D = calloc(n, sizeof *c->D);
  c->theta = calloc(n, sizeof *c->theta);
  c->g = calloc(4 * n, sizeof *c->g);
  c->Jf = calloc(n + 1, sizeof *c->Jf);
  c->rw = calloc(n, sizeof *c->rw);
  if (!c->xi || !c->A || !c->beta || !c->M || !c->P || !c->U || !c->dPdU || !c->F || !c->D || !c->theta ||
      !c->g || !c->Jf || !c->rw)
    goto nomem;
  if (cfg->flattening) {
    c->sf = malloc(2 * n * sizeof *c->sf);
    if (!c->sf) goto nomem;
    c->dsf = c->sf + n;
    for (size_t i = 0; i < n; i++) c->sf[i] = 1.0, c->dsf[i] = 0.0;
  }
  c->dg = c->g + n;
  c->cf = c->g + 2 * n;
  c->dcf = c->g + 3 * n;
  c->u_ref = 1.0;
  c->kappa = 1.0;
  if (c->wet && c->rough && nt > 0) {
    /* Q = v_GT / v_ML: v_GT = (loss-peak frequency) x (relaxed Hertz width
     * 2 a0), v_ML = 10 h_rms^2 Er0 / (R eta) (MODEL.md section 8) */
    double wpk = 0.0;
    if (vl_prony_loss_peak(&cfg->rubber, &wpk, NULL, NULL) == VL_OK) {
      double v_ml = 10.0 * c->hrms * c->hrms * c->er_ref / (cfg->radius_m * cfg->eta_pa_s);
      c->q_rolling = wpk * 2.0 * c->a0 / v_ml;
    }
  }
  if (c->span) {
    /* the uniform grid extends the covered cells to the left of the domain's
     * end when the last run came out one cell longer (grid_layout) */
    double x0 = cfg->x_max_a0 - (double)c->nv * c->dxi;
    size_t pos = 0;
    for (size_t i = 0; i < n; i++) {
      c->first[i] = pos;
      c->wc[i] = (double)c->span[i] * c->dxi;
      c->xi[i] = x0 + ((double)(pos + c->span[i] / 2) + 0.5) * c->dxi;
      pos += c->span[i];
    }
  } else {
    for (size_t i = 0; i < n; i++) {
      c->xi[i] = cfg->x_min_a0 + ((double)i + 0.5) * c->dxi;
      c->wc[i] = c->dxi;
    }
  }
  c->hf[0] = 0.5 * c->wc[0], c->hf[n] = 0.5 * c->wc[n - 1];
  for (size_t f = 1; f < n; f++) c->hf[f] = c->xi[f] - c->xi[f - 1];
  for (size_t k = 0; k < nt; k++) c->A[k] = cfg->rubber.A[k];
  st = vl_toeplitz_build(&c->kern, c->nv, c->dxi, c->A, c->beta, nt, err);
  if (st != VL_OK) goto fail;

  if (SUNContext_Create(NULL, &c->ctx) != 0) goto nomem;
  c->y = N_VNew_Serial((sunindextype)c->nunk, c->ctx);
  c->y_saved = N_VNew_Serial((sunindextype)c->nunk, c->ctx);
  c->y_outer = N_VNew_Serial((sunindextype)c->nunk, c->ctx);
  c->ones = N_VNew_Serial((sunindextype)c->nunk, c->ctx);
  c->fwork = N_VNew_Serial((sunindextype)c->nunk, c->ctx);
  c->J = SUNDenseMatrix((sunindextype)c->nunk, (sunindextype)c->nunk, c->ctx);
  if (!c->y || !c->y_saved || !c->y_outer || !c->ones || !c->fwork || !c->J) goto nomem;
  N_VConst(1.0, c->ones);
  /* KINSOL zeroes the matrix before every Jacobian call, element by
   * element (a fifth of a rough wet solve's time at N = 512); jacobian_impl
   * writes every entry itself (rough) or zeroes by memset */
  c->J->ops->zero = skip_zero;
  SUNLinearSolver inner;
  if (cfg->linear_solver == VL_LINSOL_SUNDIALS) {
    inner = SUNLinSol_Dense(c->y, c->J, c->ctx);
  } else if (cfg->linear_solver == VL_LINSOL_SCHUR && c->rough && c->wet) {
    inner = c->schur = vl_linsol_schur_create((long)n, (long)c->of, (long)c->ih, c->ctx);
  } else {
    inner = vl_linsol_lapack_create((long)c->nunk, c->ctx);
  }
  c->LS = timed_ls_create(inner, &c->timing, c->ctx);
  if (!c->LS) goto nomem;
  c->kmem = KINCreate(c->ctx);
  if (!c->kmem) goto nomem;
  if (KINInit(c->kmem, residual_fn, c->y) != KIN_SUCCESS ||
      KINSetUserData(c->kmem, c) != KIN_SUCCESS ||
      KINSetLinearSolver(c->kmem, c->LS, c->J) != KIN_SUCCESS ||
      KINSetJacFn(c->kmem, jacobian_fn) != KIN_SUCCESS ||
      KINSetFuncNormTol(c->kmem, cfg->tolerance) != KIN_SUCCESS ||
      KINSetScaledStepTol(c->kmem, 1e-14) != KIN_SUCCESS ||
      KINSetMaxSetupCalls(c->kmem, 1) != KIN_SUCCESS ||
      KINSetNumMaxIters(c->kmem, c->cfg.max_iterations) != KIN_SUCCESS ||
      KINSetPrintLevel(c->kmem, 0) != KIN_SUCCESS) {
    vl_error_set(err, "KINSOL set-up failed");
    st = VL_EINTERNAL;
    goto fail;
  }
  KINSetErrHandlerFn(c->kmem, silent_error_handler, NULL);
  if (c->nc == 0 && n >= 2 * VL_COARSE_MIN) {
    vl_contact_config coarse = c->cfg;
    coarse.grid = n / 2;
    st = vl_contact_create(&coarse, &c->coarse, err);
    if (st != VL_OK) goto fail;
  } else if (c->nc == 0 && nt > 0) {
    /* the coarsest level of a viscoelastic film starts from the dry contact
     * (wet_smooth_guess) */
    vl_contact_config dry = c->cfg;
    dry.eta_pa_s = 0.0;
    st = vl_contact_create(&dry, &c->dry, err);
    if (st != VL_OK) goto fail;
  }
  contact_set_speed(c, 0.0);
  vl_contact_reset(c);
  *out = c;
  return VL_OK;
nomem:
  vl_error_set(err, "out of memory for a %zu-node contact solver", cfg->grid);
  st = VL_ENOMEM;
fail:
  vl_contact_free(c);
  return st;
}

void vl_contact_free(vl_contact *c) {
  if (!c) return;
  vl_contact_free(c->coarse);
  vl_contact_free(c->dry);
  if (c->kmem) KINFree(&c->kmem);
  if (c->LS) SUNLinSolFree(c->LS);
  if (c->J) SUNMatDestroy(c->J);
  if (c->ones) N_VDestroy(c->ones);
  if (c->fwork) N_VDestroy(c->fwork);
  if (c->y_saved) N_VDestroy(c->y_saved);
  if (c->y_outer) N_VDestroy(c->y_outer);
  if (c->y) N_VDestroy(c->y);
  if (c->ctx) SUNContext_Free(&c->ctx);
  vl_toeplitz_free(&c->kern);
  free(c->xi);
  free(c->wc);
  free(c->hf);
  free(c->first);
  free(c->span);
  free(c->psum);
  free(c->A);
  free(c->beta);
  free(c->M);
  free(c->P);
  free(c->U);
  free(c->dPdU);
  free(c->F);
  free(c->D);
  free(c->theta);
  free(c->g);
  free(c->Jf);
  free(c->rw);
  free(c->sf);
  free(c);
}

/* Minimum film (m) of a smooth wet contact at v0, estimated as the larger of
 * Martin's rigid film 4.894 eta um R/fN and the isoviscous-elastic (soft
 * EHL) one 2.32 (eta um R/fN) g^0.8, g = fN/sqrt(eta um E' R), um = v0/2,
 * E' = 2 Er (relaxed). */
static double film_estimate_cfg(const vl_contact_config *cfg, double v0) {
  double er = vl_prony_e0(&cfg->rubber) * vl_prony_reduced_factor(&cfg->rubber);
  double um = 0.5 * v0, eta = cfg->eta_pa_s, R = cfg->radius_m, fN = cfg->load_n_per_m;
  double ge = fN / sqrt(eta * um * 2.0 * er * R);
  return fmax(2.32 * pow(ge, 0.8), 4.894) * eta * um * R / fN;
}
static double film_estimate(const vl_contact *c, double v0) { return film_estimate_cfg(&c->cfg, v0); }

double vl_contact_inlet_length_m(const vl_contact_config *cfg, double v0_m_s) {
  return sqrt(2.0 * cfg->radius_m * film_estimate_cfg(cfg, v0_m_s));
}

static void add_warning(vl_point *pt, const char *w) {
  size_t len = strlen(pt->warnings);
  snprintf(pt->warnings + len, sizeof pt->warnings - len, "%s%s", len ? ";" : "", w);
}

/* Film fraction theta per node (1 in the full film): downstream of film
 * rupture the flux stays that of the last full-film face while the
 * full-film Couette flux grows, so the gap is only partly filled (mass
 * conservation). Needs eval_state. */
static void film_fraction(const vl_contact *c, const double *y, double *theta) {
  size_t n = c->n;
  double jcur = c->Jf[0];
  for (size_t i = 0; i < n; i++) {
    bool cavitated = c->wet && y[c->of + i] <= 1e-12 && reynolds_residual(c, i) > c->cfg.tolerance;
    if (!cavitated) {
      theta[i] = 1.0;
      jcur = c->Jf[i + 1];
    } else {
      theta[i] = c->cf[i] > 0.0 ? fmin(1.0, fmax(jcur, 0.0) / c->cf[i]) : 1.0;
    }
  }
}

/* Real contact area ratio of node i (needs eval_state). Rough: Persson's
 * A/A0 at pc/|Er|; flattened (flat_scale) at pc/(|Er| s), the unflattened
 * surface's area at separation u/s (0 where s = 0: no contact pressure). */
static double area_at(const vl_contact *c, size_t i) {
  if (!c->rough) return c->P[i] > 1e-9 ? 1.0 : 0.0;
  double s = c->sf ? c->sf[i] : 1.0;
  return s > 0.0 ? vl_persson_area_ratio(c->cfg.roughness, c->P[i] / (c->sfac * s), NULL) : 0.0;
}

/* Fills the derived quantities of pt from the current state. */
static void contact_report(vl_contact *c, vl_point *pt) {
  size_t n = c->n;
  const double *y = N_VGetArrayPointer(c->y);
  eval_state(c, y);
  const vl_contact_config *cfg = &c->cfg;
  double fN = cfg->load_n_per_m, R = cfg->radius_m;
  double sum_pcx = 0.0, sum_pfx = 0.0, sum_pf = 0.0, sum_area = 0.0;
  double pmax = 0.0, pfmax = 0.0, umin = INFINITY, couette = 0.0, poiseuille = 0.0;
  size_t imax = 0, iumin = 0;
  double *theta = c->theta;
  if (c->wet) film_fraction(c, y, theta);
  pt->eps_f_min = c->sf ? INFINITY : 1.0;
  if (c->sf)
    for (size_t i = 0; i < n; i++) pt->eps_f_min = fmin(pt->eps_f_min, c->sf[i] * c->sf[i]);
  for (size_t i = 0; i < n; i++) {
    double pc = c->P[i] * c->p0, pf = c->F[i] * c->p0, x = c->xi[i] * c->a0;
    double dx = c->wc[i] * c->a0;
    sum_pcx += pc * x * dx;
    sum_pfx += pf * x * dx;
    sum_pf += pf * dx;
    double area = area_at(c, i);
    sum_area += area * dx;
    if (pc + pf > pmax) pmax = pc + pf, imax = i;
    pfmax = fmax(pfmax, pf);
    if (c->U[i] < umin) umin = c->U[i], iumin = i;
    if (c->wet) {
      double u = fmax(c->U[i], 0.0) * c->uscale;
      vl_flow_factor_values v;
      /* flattened: the factors of h_rms s (as in eval_state) */
      vl_flow_factors_eval(cfg->flow_factors, u, c->sf ? c->hrms * c->sf[i] : c->hrms, &v, NULL);
      /* node gradient: mean of the two face gradients (pf = 0 beyond the ends) */
      double left = (c->F[i] - (i > 0 ? c->F[i - 1] : 0.0)) / (c->hf[i] * c->a0);
      double right = ((i + 1 < n ? c->F[i + 1] : 0.0) - c->F[i]) / (c->hf[i + 1] * c->a0);
      double dpdx = 0.5 * (left + right) * c->p0;
      /* a smooth hard contact (u = 0) carries no fluid shear: sigma_s acts there */
      if (!(!c->rough && area > 0.0) && u > 0.0)
        couette += theta[i] * (v.phi_f + v.phi_fs) * cfg->eta_pa_s * c->v0 / u * dx;
      poiseuille += -v.phi_fp * 0.5 * u * dpdx * dx;
    }
  }
  pt->x_centroid_m = (sum_pcx + sum_pfx) / fN;
  pt->mu_Rc = -sum_pcx / (fN * R);
  pt->mu_Rf = -sum_pfx / (fN * R);
  pt->mu_Sc = cfg->sigma_s_pa * sum_area / fN;
  pt->mu_Sf_couette = couette / fN;
  pt->mu_Sf_poiseuille = poiseuille / fN;
  pt->mu_Sf = pt->mu_Sf_couette + pt->mu_Sf_poiseuille;
  pt->mu = pt->mu_Rc + pt->mu_Rf + pt->mu_Sc + pt->mu_Sf;
  pt->u_min_m = fmax(umin, 0.0) * c->uscale;
  pt->x_min_film_m = c->xi[iumin] * c->a0;
  /* separation at the pressure centroid (linear interpolation on nodes) */
  double xc = pt->x_centroid_m / c->a0;
  size_t k = 0;
  while (k + 2 < n && c->xi[k + 1] <= xc) k++;
  double w = fmin(fmax((xc - c->xi[k]) / c->hf[k + 1], 0.0), 1.0);
  pt->u_central_m = fmax((1 - w) * c->U[k] + w * c->U[k + 1], 0.0) * c->uscale;
  /* contact extent where the total pressure >= 1% of its peak, interpolated */
  double thr = 0.01 * pmax / c->p0;
#define PTOT(j) (c->P[j] + c->F[j])
  size_t lo = imax, hi = imax;
  while (lo > 0 && PTOT(lo - 1) >= thr) lo--;
  while (hi + 1 < n && PTOT(hi + 1) >= thr) hi++;
  double xl = c->xi[lo], xr = c->xi[hi];
  if (lo > 0) xl -= c->hf[lo] * (PTOT(lo) - thr) / (PTOT(lo) - PTOT(lo - 1));
  if (hi + 1 < n) xr += c->hf[hi + 1] * (PTOT(hi) - thr) / (PTOT(hi) - PTOT(hi + 1));
  pt->contact_width_m = pmax > 0 ? (xr - xl) * c->a0 : 0.0;
  pt->fluid_load_fraction = sum_pf / fN;
  pt->load_error = fabs(load_sum(c) - 1.0);
  pt->E_wH_pa = c->e_abs;
  pt->a_H_m = c->a_h;
  pt->Q = c->q_rolling;
  pt->peak_pressure_pa = pmax;
  pt->x_peak_m = c->xi[imax] * c->a0;
  pt->regime = !c->wet                          ? VL_REGIME_DRY
               : pt->fluid_load_fraction < 0.05 ? VL_REGIME_BOUNDARY
               : pt->fluid_load_fraction > 0.95 ? VL_REGIME_HYDRODYNAMIC
                                                : VL_REGIME_MIXED;
  if (pmax > 0 && (PTOT(0) > 1e-3 * pmax / c->p0 || PTOT(n - 1) > 1e-3 * pmax / c->p0))
    add_warning(pt, "pressure reaches the domain edge (domain too short)");
  /* a smooth film is fed from far upstream: with the inlet end less than 5
   * inlet lengths sqrt(2 R u_min) ahead of the pressure zone (where the
   * pressure reaches 1 % of its peak) the film is short by about a percent
   * or more (rigid cylinder, closed form: 2 %; soft EHL, measured: 0.1 to
   * 0.4 %, 1.2 % at 2.5 lengths) */
  if (c->wet && !c->rough && pmax > 0 &&
      (xl - c->xi[0] + c->hf[0]) * c->a0 < 5.0 * sqrt(2.0 * cfg->radius_m * pt->u_min_m))
    add_warning(pt, "inlet shorter than 5 inlet lengths sqrt(2 R u_min) ahead of the pressure "
                    "(fully flooded film underestimated)");
#undef PTOT
  (void)pfmax;
}

/* Scales of the fluid unknowns for a solve at v0, from the current state,
 * then the Reynolds row weights. Rough: pf by its expected magnitude
 * (extrapolated linearly in speed from the last converged state: pf ~ eta v0
 * in the boundary regime), Reynolds rows by the Couette flux at the current
 * minimum film. Smooth: the film carries the whole load at any speed, so pf
 * keeps the magnitude of the current state (fN over the pressurised length,
 * which is the larger of a0 and the inlet length sqrt(2 R u): the speed
 * does not enter); rows as in reynolds_weights, free of any length scale,
 * which keeps stiff solids (inlet length >> a0) as well conditioned as soft
 * ones. Rescales y accordingly. */
static void fluid_scales(vl_contact *c, double v0) {
  if (!c->wet) return;
  size_t n = c->n;
  double *y = N_VGetArrayPointer(c->y);
  eval_state(c, y);
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
    c->u_ref = umin > 0.0 ? umin : film_estimate(c, v0) / us;
    kappa = fmax_p0 > 0.0 ? fmax_p0 : 1.0 / fmax(1.0, sqrt(2.0 * c->u_ref));
  } else {
    /* the film cannot be thinner than a rigid cylinder's (Martin) nor, on a
     * rough surface, than a fraction of the roughness */
    double h_martin = 2.447 * eta * v0 * c->cfg.radius_m / c->cfg.load_n_per_m;
    c->u_ref = fmax(umin, fmax(1e-3 * c->hrms, h_martin) / us);
    if (fmax_p0 > 0.0 && c->v_state > 0.0) {
      kappa = fmax_p0; /* the predictor (predict_state) has scaled pf to v0 */
    } else {
      /* hydrodynamic estimate 6 eta v0 a0 / u^2, at most p0 */
      double u = c->u_ref * us;
      kappa = 6.0 * eta * v0 * c->a0 / (u * u) / c->p0;
    }
    kappa = fmin(fmax(kappa, 1e-300), 10.0);
    c->rscale = 1.0 / c->u_ref;
  }
  for (size_t i = 0; i < c->nf; i++) y[c->of + i] *= c->kappa / kappa;
  c->kappa = kappa;
  c->lambda = us * us * c->p0 * kappa / (6.0 * eta * v0 * c->a0);
  eval_state(c, y);
  reynolds_weights(c);
}


/* Rigid-cylinder Reynolds pressure (Swift-Stieber outlet) for the gap
 * h0 (1 + X^2), X = x/b, b = sqrt(2 R h0), fed from X_in: dp/dX is
 * proportional to (H - Hc)/H^3, integrated in closed form with
 * I2 = \int dX/H^2 and I3 = \int dX/H^3; the outlet Xc solves p(Xc) = 0.
 * Returns the unnormalised shape at X (0 beyond Xc). */
static double rigid_i2(double X) { return 0.5 * (X / (1.0 + X * X) + atan(X)); }
static double rigid_i3(double X) {
  double H = 1.0 + X * X;
  return X / (4.0 * H * H) + 3.0 * X / (8.0 * H) + 0.375 * atan(X);
}
static double rigid_outlet(double X_in, double X_max) {
  double lo = 0.0, hi = X_max;
  double a2 = rigid_i2(X_in), a3 = rigid_i3(X_in);
#define G(X) ((rigid_i2(X) - a2) - (1.0 + (X) * (X)) * (rigid_i3(X) - a3))
  if (!(G(hi) < 0.0)) return X_max;
  for (int it = 0; it < 100; it++) {
    double mid = 0.5 * (lo + hi);
    if (G(mid) > 0.0) lo = mid; else hi = mid;
  }
#undef G
  return 0.5 * (lo + hi);
}

/* A fresh smooth wet solve starts from a film with a pressure that carries
 * the load (a start without pressure leaves the load independent of the
 * rigid approach: singular Jacobian). The film is film_estimate(); the
 * pressure is the rigid cylinder's (Martin) where that film exceeds the
 * soft estimate, else the relaxed Hertz pressure (the soft EHL pressure is
 * nearly Hertzian); the rigid approach puts the minimum film at the
 * estimate. Newton then corrects the shape. */
static void wet_smooth_guess(vl_contact *c, double v0) {
  size_t n = c->n;
  double *y = N_VGetArrayPointer(c->y);
  const vl_contact_config *cfg = &c->cfg;
  double um = 0.5 * v0, eta = cfg->eta_pa_s, R = cfg->radius_m, fN = cfg->load_n_per_m;
  double h = film_estimate(c, v0);
  bool rigid = h <= 4.894 * eta * um * R / fN * (1.0 + 1e-12);
  double b = sqrt(2.0 * R * h) / c->a0; /* in a0 */
  double X_in = c->xi[0] / b - 0.5 * c->dxi / b, X_max = c->xi[n - 1] / b + 0.5 * c->dxi / b;
  double Xc = rigid ? rigid_outlet(X_in, X_max) : 0.0, Hc = 1.0 + Xc * Xc;
  double a2 = rigid_i2(X_in), a3 = rigid_i3(X_in), sum = 0.0;
  /* a viscoelastic solid: the dry contact at this speed (same grid), the
   * limit of a thin film; Hertz would leave the gap far from flat (the
   * solid is stiffer and the pressure asymmetric at v0 tau ~ a0) */
  bool dry = false;
  if (!rigid && c->dry) {
    vl_point dp;
    vl_contact_reset(c->dry);
    dry = vl_contact_solve(c->dry, v0, &dp, NULL) == VL_OK;
  }
  for (size_t i = 0; i < n; i++) {
    double x = c->xi[i], p;
    if (dry) {
      p = fmax(c->dry->P[i], 0.0);
    } else if (rigid) {
      double X = x / b;
      p = X < Xc ? fmax((rigid_i2(X) - a2) - Hc * (rigid_i3(X) - a3), 0.0) : 0.0;
    } else {
      p = fabs(x) < 1.0 ? sqrt(1.0 - x * x) : 0.0;
    }
    c->F[i] = p;
    sum += p;
  }
  double scale = sum > 0.0 ? (0.5 * M_PI) / (sum * c->dxi) : 0.0, fmx = 0.0;
  for (size_t i = 0; i < n; i++) fmx = fmax(fmx, c->F[i] *= scale);
  c->kappa = fmx > 0.0 ? fmx : 1.0;
  for (size_t i = 0; i < n; i++) y[c->of + i] = c->F[i] / c->kappa;
  y[c->ih] = 0.0;
  eval_state(c, y);
  double umin = INFINITY;
  for (size_t i = 0; i < n; i++) umin = fmin(umin, c->U[i]);
  y[c->ih] = h / c->uscale - umin;
}

/* Starts a smooth wet solve without a usable previous state: the converged
 * solution of the coarse level (itself started the same way), interpolated,
 * or on the coarsest level the analytic guess. Cavitation is a free
 * boundary that a semismooth Newton step moves by about one cell (cells
 * beyond it are held at pf = 0 by the linearised complementarity), so a
 * start whose film rupture is n cells off costs n iterations; each level
 * halves that distance in its own cells. Adds the Newton iterations spent
 * to *nni. */
static void smooth_wet_start(vl_contact *c, double v0, long *nni) {
  vl_contact *cc = c->coarse;
  if (cc) {
    vl_point cp;
    cc->v_state = 0.0; /* a fresh start there too */
    vl_status st = vl_contact_solve(cc, v0, &cp, NULL);
    *nni += cp.iterations;
    if (st == VL_OK) {
      /* pressure (p0) linear between the coarse nodes, 0 on the domain ends;
       * rigid approach such that the minimum films agree */
      size_t n = c->n, m = cc->n;
      double *y = N_VGetArrayPointer(c->y), fmx = 0.0, umin_c = INFINITY, umin = INFINITY;
      eval_state(cc, N_VGetArrayPointer(cc->y));
      for (size_t k = 0; k < m; k++) umin_c = fmin(umin_c, cc->U[k]);
      for (size_t i = 0; i < n; i++) {
        double t = (c->xi[i] - cc->xi[0]) / cc->dxi, f;
        if (t <= 0.0) {
          f = cc->F[0] * fmax(0.0, 1.0 + 2.0 * t);
        } else if (t >= (double)(m - 1)) {
          f = cc->F[m - 1] * fmax(0.0, 1.0 - 2.0 * (t - (double)(m - 1)));
        } else {
          size_t k = (size_t)t;
          double w = t - (double)k;
          f = (1.0 - w) * cc->F[k] + w * cc->F[k + 1];
        }
        c->F[i] = f;
        fmx = fmax(fmx, f);
      }
      c->kappa = fmx > 0.0 ? fmx : 1.0;
      for (size_t i = 0; i < n; i++) y[c->of + i] = c->F[i] / c->kappa;
      y[c->ih] = 0.0;
      eval_state(c, y);
      for (size_t i = 0; i < n; i++) umin = fmin(umin, c->U[i]);
      y[c->ih] = umin_c - umin;
      return;
    }
  }
  wet_smooth_guess(c, v0);
}

/* Predictor of a continuation step to speed v0 from the converged state at
 * v_state (rough films; a smooth film has its own fresh starts). At a fixed
 * film the hydrodynamic pressure grows like v0 (the Reynolds equation is
 * linear in pf and eta v0), so pf starts scaled by v0/v_state: in boundary
 * lubrication, where the film does not change, that is the solution. fig05
 * at N = 512: 946 Newton iterations for 62 points down to 515 (13 per
 * boundary point down to 1-3). A secant in log v0 on the separation and pf
 * (from the state before) was tried and cost more (544-735 iterations): the
 * cavitation boundary, not the predictor, limits the steps near the
 * transition. */
static void predict_state(vl_contact *c, double v0) {
  if (!c->rough || !(c->v_state > 0.0)) return;
  double *y = N_VGetArrayPointer(c->y), grow = v0 / c->v_state;
  for (size_t i = 0; i < c->nf; i++) y[c->of + i] *= grow;
}

/* Newton (KINSOL) from the current y at speed v0; scales set here. Adds
 * the iterations to *nni; returns whether our own residual check passed
 * (KINSOL also returns success when the step, not the residual, became
 * small). */
static bool newton(vl_contact *c, double v0, long *nni, int *flag, double *fnorm) {
  fluid_scales(c, v0);
  double t0 = now_s();
  *flag = KINSol(c->kmem, c->y, KIN_LINESEARCH, c->ones, c->ones);
  c->timing.t_newton_s += now_s() - t0;
  c->timing.newtons++;
  long it = 0;
  KINGetNumNonlinSolvIters(c->kmem, &it);
  *nni += it;
  *fnorm = INFINITY;
  if (residual_fn(c->y, c->fwork, c) == 0) *fnorm = N_VMaxNorm(c->fwork);
  return *flag >= 0 && *fnorm <= c->cfg.tolerance;
}

vl_status vl_contact_solve(vl_contact *c, double v0_m_s, vl_point *pt, vl_error *err) {
  memset(pt, 0, sizeof *pt);
  pt->v0_m_s = v0_m_s;
  if (!(v0_m_s >= 0.0 && isfinite(v0_m_s)) || (c->wet && !(v0_m_s > 0.0))) {
    vl_error_set(err, "speed must be finite and %s 0 (got %g m/s)", c->wet ? ">" : ">=", v0_m_s);
    return VL_EINPUT;
  }
  N_VScale(1.0, c->y, c->y_saved);
  double saved_kappa = c->kappa, saved_lambda = c->lambda, saved_rscale = c->rscale,
         saved_uref = c->u_ref, saved_v = c->v0;
  contact_set_speed(c, v0_m_s);
  bool smooth_wet = c->wet && !c->rough, fresh = smooth_wet && c->v_state == 0.0;
  long nni = 0;
  int flag;
  double fnorm;
  if (fresh) smooth_wet_start(c, v0_m_s, &nni);
  predict_state(c, v0_m_s);
  bool ok = newton(c, v0_m_s, &nni, &flag, &fnorm);
  if (!ok && smooth_wet && !fresh) {
    /* continuation from the previous speed failed: start afresh */
    smooth_wet_start(c, v0_m_s, &nni);
    ok = newton(c, v0_m_s, &nni, &flag, &fnorm);
  }
  if (!ok && smooth_wet && !c->no_fallback) {
    /* a thin film that a fresh start misses: start afresh at a viscosity
     * 10, 100, ... times larger (thicker film, wider inlet and outlet
     * zones) and come down by continuation in viscosity */
    double eta = c->cfg.eta_pa_s, v_state = c->v_state;
    N_VScale(1.0, c->y_saved, c->y_outer); /* the inner solves reuse y_saved */
    c->no_fallback = true;
    for (int k = 1; k <= 6 && !ok; k++) {
      vl_point tp;
      vl_contact_set_viscosity(c, eta * pow(10.0, k), NULL);
      c->v_state = 0.0;
      if (vl_contact_solve(c, v0_m_s, &tp, NULL) != VL_OK) {
        nni += tp.iterations;
        continue;
      }
      nni += tp.iterations;
      ok = vl_contact_solve_viscosity(c, v0_m_s, eta, 10.0, &tp, NULL) == VL_OK;
      nni += tp.iterations;
      if (ok) {
        fnorm = tp.residual;
        flag = 0;
      }
      break;
    }
    c->no_fallback = false;
    vl_contact_set_viscosity(c, eta, NULL);
    N_VScale(1.0, c->y_outer, c->y_saved);
    if (!ok) c->v_state = v_state;
  }
  pt->iterations = nni;
  pt->residual = fnorm;
  pt->converged = ok;
  if (!ok) {
    bool closed = smooth_wet && (flag == KIN_REPTD_SYSFUNC_ERR || flag == KIN_FIRST_SYSFUNC_ERR);
    char *flag_name = KINGetReturnFlagName(flag); /* malloc'd by SUNDIALS */
    vl_error_set(err, "no convergence at v0 = %g m/s: KINSOL flag %d (%s), %ld iterations, "
                      "residual %.3g%s",
                 v0_m_s, flag, flag_name ? flag_name : "?", nni, fnorm,
                 closed ? " (Newton steps kept closing the film: the grid is probably too coarse "
                          "for the inlet and outlet zones of this soft EHL film; refine it or "
                          "narrow the domain)"
                        : "");
    free(flag_name);
    /* back to the last converged state, its speed and scales */
    N_VScale(1.0, c->y_saved, c->y);
    if (saved_v == saved_v) contact_set_speed(c, saved_v);
    c->kappa = saved_kappa, c->lambda = saved_lambda, c->rscale = saved_rscale;
    c->u_ref = saved_uref;
    if (c->wet) {
      eval_state(c, N_VGetArrayPointer(c->y));
      reynolds_weights(c);
    }
    memset(pt, 0, sizeof *pt);
    pt->v0_m_s = v0_m_s;
    pt->converged = false;
    pt->iterations = nni;
    pt->residual = isfinite(fnorm) ? fnorm : DBL_MAX;
    pt->regime = c->wet ? VL_REGIME_BOUNDARY : VL_REGIME_DRY;
    return VL_ENOCONV;
  }
  c->v_state = v0_m_s;
  contact_report(c, pt);
  return VL_OK;
}

vl_status vl_contact_set_viscosity(vl_contact *c, double eta_pa_s, vl_error *err) {
  if (!c->wet || !(eta_pa_s > 0.0 && isfinite(eta_pa_s))) {
    vl_error_set(err, "viscosity: a wet contact takes a finite eta > 0 (got %g Pa s%s)", eta_pa_s,
                 c->wet ? "" : ", contact created dry");
    return VL_EINPUT;
  }
  if (c->q_rolling > 0.0) c->q_rolling *= eta_pa_s / c->cfg.eta_pa_s; /* Q ~ eta */
  c->cfg.eta_pa_s = eta_pa_s;
  /* epsilon_f depends on eta v0: its table is rebuilt (eta validated above) */
  if (c->cfg.flattening) vl_flattening_set_viscosity(c->cfg.flattening, eta_pa_s, NULL);
  if (c->coarse) vl_contact_set_viscosity(c->coarse, eta_pa_s, NULL);
  return VL_OK;
}

double vl_contact_viscosity(const vl_contact *c) { return c->cfg.eta_pa_s; }

/* Log-spaced steps from the current viscosity to the target; a failed step
 * is halved (in log eta) up to 6 times, each from the last converged state. */
vl_status vl_contact_solve_viscosity(vl_contact *c, double v0_m_s, double eta_pa_s,
                                     double max_ratio, vl_point *pt, vl_error *err) {
  memset(pt, 0, sizeof *pt);
  pt->v0_m_s = v0_m_s;
  if (!c->wet || !(eta_pa_s > 0.0 && isfinite(eta_pa_s)) || !(max_ratio > 1.0)) {
    vl_error_set(err, "viscosity continuation needs a wet contact, eta > 0 and max_ratio > 1 "
                      "(got eta %g Pa s, max_ratio %g)", eta_pa_s, max_ratio);
    return VL_EINPUT;
  }
  double eta = c->cfg.eta_pa_s, lstep = log(max_ratio);
  long nni = 0;
  vl_status st = VL_OK;
  int halvings = 0;
  for (;;) {
    double gap = log(eta_pa_s / eta);
    double step = fabs(gap) <= lstep ? gap : copysign(lstep, gap);
    double eta_next = fabs(gap) <= lstep ? eta_pa_s : eta * exp(step);
    vl_contact_set_viscosity(c, eta_next, NULL);
    st = vl_contact_solve(c, v0_m_s, pt, err);
    nni += pt->iterations;
    if (st == VL_OK) {
      eta = eta_next;
      if (eta == eta_pa_s) break;
      continue;
    }
    vl_contact_set_viscosity(c, eta, NULL); /* back to the converged state's */
    if (st != VL_ENOCONV || ++halvings > 6) break;
    lstep *= 0.5;
  }
  pt->iterations = nni;
  return st;
}

void vl_contact_fields(const vl_contact *c, vl_fields *f) {
  size_t n = c->n;
  const double *y = N_VGetArrayPointer(c->y);
  vl_contact *mc = (vl_contact *)c; /* work arrays only */
  eval_state(mc, y);
  double *theta = mc->theta;
  if (c->wet) film_fraction(c, y, theta);
  for (size_t i = 0; i < n && i < f->n; i++) {
    f->x_m[i] = c->xi[i] * c->a0;
    f->p_c_pa[i] = c->P[i] * c->p0;
    f->p_f_pa[i] = c->F[i] * c->p0;
    f->u_m[i] = fmax(c->U[i], 0.0) * c->uscale;
    f->area_ratio[i] = area_at(c, i);
    if (f->film_fraction) f->film_fraction[i] = c->wet ? theta[i] : 1.0;
    if (f->width_m) f->width_m[i] = c->wc[i] * c->a0;
  }
}

/* The finite-difference comparison of vl_contact_jacobian_check, per block
 * of rows (contact, Reynolds, load): max |J_fd - J| in worst[b], max |J| in
 * scale[b]. Returns false on allocation failure. */
static bool jacobian_compare(vl_contact *c, double v0_m_s, double worst[3], double scale[3]) {
  contact_set_speed(c, v0_m_s);
  size_t m = c->nunk;
  SUNMatrix J = SUNDenseMatrix((sunindextype)m, (sunindextype)m, c->ctx);
  N_Vector yp = N_VClone(c->y), fp = N_VClone(c->y), fm = N_VClone(c->y);
  if (!J || !yp || !fp || !fm) {
    if (J) SUNMatDestroy(J);
    if (yp) N_VDestroy(yp);
    if (fp) N_VDestroy(fp);
    if (fm) N_VDestroy(fm);
    return false;
  }
  jacobian_fn(c->y, c->fwork, J, c, NULL, NULL);
  double *Jd = SUNDenseMatrix_Data(J);
  for (int b = 0; b < 3; b++) worst[b] = scale[b] = 0.0;
#define BLOCK(i) ((i) < c->nc ? 0 : (i) < c->ih ? 1 : 2)
  for (size_t j = 0; j < m; j++)
    for (size_t i = 0; i < m; i++) scale[BLOCK(i)] = fmax(scale[BLOCK(i)], fabs(Jd[j * m + i]));
  double *y = N_VGetArrayPointer(yp);
  for (size_t j = 0; j < m; j++) {
    N_VScale(1.0, c->y, yp);
    double h = 1e-6 * fmax(fabs(y[j]), 1e-3);
    y[j] += h;
    residual_fn(yp, fp, c);
    y[j] -= 2.0 * h;
    residual_fn(yp, fm, c);
    const double *a = N_VGetArrayPointer(fp), *b = N_VGetArrayPointer(fm);
    for (size_t i = 0; i < m; i++)
      worst[BLOCK(i)] = fmax(worst[BLOCK(i)], fabs((a[i] - b[i]) / (2.0 * h) - Jd[j * m + i]));
  }
#undef BLOCK
  SUNMatDestroy(J);
  N_VDestroy(yp);
  N_VDestroy(fp);
  N_VDestroy(fm);
  return true;
}

double vl_contact_jacobian_check(vl_contact *c, double v0_m_s) {
  double worst[3], scale[3];
  if (!jacobian_compare(c, v0_m_s, worst, scale)) return -1.0;
  return fmax(worst[0], fmax(worst[1], worst[2])) / fmax(scale[0], fmax(scale[1], scale[2]));
}

double vl_contact_jacobian_check_blocks(vl_contact *c, double v0_m_s, double rel[3]) {
  double worst[3], scale[3];
  if (!jacobian_compare(c, v0_m_s, worst, scale)) return -1.0;
  double r = 0.0;
  for (int b = 0; b < 3; b++) {
    rel[b] = scale[b] > 0.0 ? worst[b] / scale[b] : 0.0;
    r = fmax(r, rel[b]);
  }
  return r;
}

size_t vl_contact_face_fluxes(const vl_contact *c, double *flux_m2_s, size_t cap) {
  if (!c->wet) return 0;
  vl_contact *mc = (vl_contact *)c; /* work arrays only */
  eval_state(mc, N_VGetArrayPointer(c->y));
  double unit = 0.5 * c->v0 * c->uscale; /* J is stored in units of v0 us/2 */
  for (size_t f = 0; f <= c->n && f < cap; f++) flux_m2_s[f] = c->Jf[f] * unit;
  return c->n + 1;
}

void vl_contact_timing_get(const vl_contact *c, vl_contact_timing *t) {
  memset(t, 0, sizeof *t);
  for (int k = 0; k < 3; k++) {
    /* c, then its helper contacts (which may own helpers in turn) */
    const vl_contact *h = k == 0 ? c : k == 1 ? c->coarse : c->dry;
    if (!h) continue;
    vl_contact_timing s = h->timing;
    if (k > 0) vl_contact_timing_get(h, &s);
    t->residuals += s.residuals, t->jacobians += s.jacobians, t->setups += s.setups;
    t->solves += s.solves, t->kernels += s.kernels, t->newtons += s.newtons;
    t->t_residual_s += s.t_residual_s, t->t_jacobian_s += s.t_jacobian_s;
    t->t_setup_s += s.t_setup_s, t->t_solve_s += s.t_solve_s;
    t->t_kernel_s += s.t_kernel_s, t->t_newton_s += s.t_newton_s;
    t->linsol_fallbacks += k > 0 ? s.linsol_fallbacks : vl_linsol_schur_fallbacks(h->schur);
  }
}

void vl_contact_timing_reset(vl_contact *c) {
  memset(&c->timing, 0, sizeof c->timing);
  if (c->coarse) vl_contact_timing_reset(c->coarse);
  if (c->dry) vl_contact_timing_reset(c->dry);
}

size_t vl_contact_grid(const vl_contact *c) { return c->n; }
void vl_contact_cell(const vl_contact *c, size_t i, double *x_a0, double *width_a0) {
  *x_a0 = c->xi[i], *width_a0 = c->wc[i];
}
double vl_contact_influence(vl_contact *c, double v0_m_s, size_t i, size_t j) {
  contact_set_speed(c, v0_m_s);
  return c->M[i * c->n + j];
}
double vl_contact_a0(const vl_contact *c) { return c->a0; }
double vl_contact_p0(const vl_contact *c) { return c->p0; }
