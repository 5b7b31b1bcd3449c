/* The film pressure that balances the flow of a given gap: nonlinear
 * elimination of the fluid pressure from the Newton step of a rough film
 * (contact_internal.h, vl_contact_film_correct).
 *
 * Why: in the mixed regime of a soft compound the flow factors switch the
 * flow on and off within a fraction of h_rms (persson-emt's percolation,
 * Patir-Cheng's u = 0.4 h_rms), and the conductance g = u^3 phi_p changes
 * by orders of magnitude across the cells where the contact opens. A
 * Newton step that moves the gap there (the whole contact shifts with every
 * new speed of a sweep) predicts the flow linearly and lands on a flux
 * imbalance 100x the one it started from: on fig15 (sbr-unfilled,
 * persson-emt) the full step took the elasticity and load rows down 7x and
 * raised the Reynolds row of the cell where the film closes from 1e-7 to
 * 30. The line search then cut every step to about a tenth, and the points
 * between 6e-7 and 7e-5 m/s took 20-35 iterations each.
 *
 * For a fixed gap the Reynolds rows are the complementarity of an M-matrix
 * problem in pf alone (the fluxes are affine in pf, the Poiseuille block
 * tridiagonal), which a semismooth Newton with a tridiagonal solve settles
 * in a few O(n) iterations. The corrected step keeps Newton's gap and rigid
 * approach and takes the pf that balances the flow there: the full step
 * lands with the Reynolds rows satisfied. It replaces Newton's step only
 * when (vl_contact_film_correct) the solve continues from a converged film,
 * the fluid carries at most half the load, and the full corrected step
 * lands on a residual both below the plain full step's and acceptable to
 * KINSOL's sufficient-decrease test as it is; the line search then takes it
 * whole. Near the solution the two steps agree to second order, so the
 * convergence stays quadratic. */
#include "contact_internal.h"

#include <math.h>

/* Iterations of the inner Newton; the elimination is skipped (the plain
 * Newton step kept) when it has not converged by then. */
#define FILM_MAX_ITERATIONS 30

/* Largest share of the load carried by the fluid at which the step is
 * corrected (see vl_contact_film_correct). */
#define FILM_MAX_FLUID_SHARE 0.5

/* KINSOL's sufficient decrease (alpha, on ||F||^2/2, with the slope
 * -||F||^2 of a Newton direction) that the full corrected step must meet. */
#define FILM_ARMIJO 1e-4

/* The inner solve's target, relative to the outer tolerance: far enough
 * below it that the outer convergence does not see the inner residual. */
#define FILM_TOLERANCE_FRACTION 1e-3

/* The Reynolds rows of the state in c at the fluid unknowns pf into f;
 * returns their max norm (INFINITY when one is not finite). */
static double film_rows(vl_contact *c, const double *y, double *f) {
  double mx = 0.0;
  vl_contact_eval_fluxes(c, y);
  for (size_t i = 0; i < c->nf; i++) {
    f[i] = vl_contact_reynolds_row(c, y, i, NULL, NULL);
    mx = isfinite(f[i]) ? fmax(mx, fabs(f[i])) : INFINITY;
  }
  return mx;
}

/* One semismooth Newton step on the Reynolds rows at a fixed gap: the
 * tridiagonal system (lo, di, up) d = -f solved by the Thomas algorithm
 * (diagonally dominant wherever a row depends on the flux at all: the
 * Fischer-Burmeister derivatives are >= 0 and the Poiseuille block is an
 * M-matrix). Adds d to pf; false on a zero pivot. */
static bool film_step(vl_contact *c, double *y, const double *f, double *work) {
  size_t n = c->nf;
  double *up = work, *rhs = work + n;
  double *pf = y + c->of;
  double prev_up = 0.0, prev_rhs = 0.0;
  for (size_t i = 0; i < n; i++) {
    double da, db;
    vl_contact_reynolds_row(c, y, i, &da, &db);
    double s = db * c->rw[i];
    double kl = vl_contact_face_poiseuille(c, i), kr = vl_contact_face_poiseuille(c, i + 1);
    double lo = i > 0 ? -s * kl : 0.0, di = da + s * (kl + kr);
    double u = i + 1 < n ? -s * kr : 0.0;
    double piv = di - lo * prev_up;
    if (!(fabs(piv) > 0.0) || !isfinite(piv)) return false;
    up[i] = u / piv;
    rhs[i] = (-f[i] - lo * prev_rhs) / piv;
    prev_up = up[i], prev_rhs = rhs[i];
  }
  for (size_t i = n - 1; i-- > 0;)
    rhs[i] -= up[i] * rhs[i + 1];
  for (size_t i = 0; i < n; i++)
    pf[i] += rhs[i];
  return true;
}

/* The 2-norm of the residual at y (what KINSOL's line search measures), or
 * INFINITY where y is not admissible; f: nunk values of work. */
static double residual_norm(vl_contact *c, const double *y, double *f) {
  if (vl_contact_residual(c, y, f) != 0) return INFINITY;
  double s = 0.0;
  for (size_t i = 0; i < c->nunk; i++)
    s += f[i] * f[i];
  return sqrt(s);
}

/* The share of the load the fluid carries at y (evaluates the state there). */
static double fluid_share(vl_contact *c, const double *y) {
  vl_contact_eval_state(c, y);
  double f = 0.0, t = 0.0;
  for (size_t i = 0; i < c->n; i++) {
    double amb = c->pamb ? c->pamb[i] : 0.0; /* a sealed side's ambient carries nothing */
    f += (c->F[i] - amb) * c->wc[i];
    t += (c->P[i] + c->F[i] - amb) * c->wc[i];
  }
  return t > 0.0 ? f / t : 1.0;
}

bool vl_contact_film_correct(vl_contact *c, const double *y, double fnorm, double *step) {
  if (!c->film_correct || !c->film_work) return false;
  /* the elimination assumes the solid sets the gap and the film follows:
   * where the fluid carries most of the load (EHL), pf at a fixed gap is
   * the ill-conditioned inverse problem (on a thick flattened film the
   * balanced pf put a converging Newton's 4e-8 residual back to 0.1) */
  if (fluid_share(c, y) > FILM_MAX_FLUID_SHARE) return false;
  size_t N = c->nunk, n = c->nf;
  double *yt = c->film_work, *fr = yt + N, *f = fr + N, *work = f + n;
  for (size_t i = 0; i < N; i++)
    yt[i] = y[i] + step[i];
  /* the full plain step's residual, then (the flow quantities of its gap
   * evaluated by that) only pf changes below */
  double plain = residual_norm(c, yt, fr);
  double tol = FILM_TOLERANCE_FRACTION * c->cfg.tolerance;
  bool balanced = false;
  for (int it = 0; it < FILM_MAX_ITERATIONS && !balanced; it++) {
    double mx = film_rows(c, yt, f);
    if (!isfinite(mx)) return false;
    balanced = mx <= tol;
    if (!balanced && !film_step(c, yt, f, work)) return false;
  }
  /* the corrected step is not a Newton direction: a line search along it
   * (pf moved by a fraction of the balance, the gap by the same fraction of
   * Newton's) can find no decrease at all (fig05 at 1e-2 Pa s, 0.011 m/s:
   * 1.19 against 0.18 at the full step, and the solve failed). It is taken
   * only where its full step is acceptable as it is, and better than the
   * plain one; otherwise the line search gets Newton's direction */
  if (!balanced) return false;
  double corr = residual_norm(c, yt, fr);
  if (!(corr < plain) || !(corr * corr <= (1.0 - 2.0 * FILM_ARMIJO) * fnorm * fnorm)) return false;
  for (size_t i = 0; i < n; i++)
    step[c->of + i] = yt[c->of + i] - y[c->of + i];
  return true;
}
