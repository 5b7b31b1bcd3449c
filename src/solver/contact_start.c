/* Initial guesses of the Newton solve. Each only guesses: it sets the
 * unknowns (and the fluid scales) of a contact, from closed forms or from a
 * helper contact that contact_solve.c has already solved, and solves
 * nothing itself. The relaxed Hertz contact (docs/MODEL.md section 9: the
 * scales a0, p0), with Persson's separation under it on a rough surface
 * (section 4); for a smooth film the rigid cylinder's Reynolds pressure
 * (Martin, section 5), the dry contact of a viscoelastic solid, or the
 * solution of a half-size grid; for a rough film the dry contact or the
 * smooth film at the same speed; a state interpolated from the same
 * contact on other cells; and the predictor of a continuation step in
 * speed. */
#include "bracket.h"
#include "contact_internal.h"
#include "contact_private.h"
#include "persson_internal.h"

#include <math.h>

/* Linear interpolation at x of the node values f[0..m-1] at the increasing
 * positions xs (any cells: uniform, graded or laid out); the end values
 * beyond the ends. */
static double interpolate(const double *f, const double *xs, size_t m, double x) {
  if (x <= xs[0]) return f[0];
  if (x >= xs[m - 1]) return f[m - 1];
  size_t lo = vl_bracket(xs, m, x), hi = lo + 1; /* xs[lo] <= x < xs[hi] */
  double w = (x - xs[lo]) / (xs[hi] - xs[lo]);
  return (1.0 - w) * f[lo] + w * f[hi];
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
  vl_contact_set_speed(c, c->v0 == c->v0 ? c->v0 : 0.0);
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
  if (c->nc)
    for (size_t i = 0; i < c->nf; i++)
      y[c->of + i] = 0.0;
  c->kappa = 1.0;
  c->v_state = 0.0;
  /* h0 that best satisfies the gap equation inside the contact */
  y[c->ih] = 0.0;
  vl_contact_eval_state(c, y);
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
    if (G(mid) > 0.0)
      lo = mid;
    else
      hi = mid;
  }
#undef G
  return 0.5 * (lo + hi);
}

bool vl_contact_film_rigid(const vl_contact *c, double v0) {
  const vl_contact_config *cfg = &c->cfg;
  double um = 0.5 * v0, eta = cfg->eta_pa_s, R = cfg->radius_m, fN = cfg->load_n_per_m;
  return vl_contact_film_estimate(cfg, v0) <= 4.894 * eta * um * R / fN * (1.0 + 1e-12);
}

/* A fresh smooth wet solve starts from a film with a pressure that carries
 * the load (a start without pressure leaves the load independent of the
 * rigid approach: singular Jacobian). The film is vl_contact_film_estimate; the
 * pressure is the rigid cylinder's (Martin) where that film exceeds the
 * soft estimate, else the dry contact's (dry: a viscoelastic solid is
 * stiffer and its pressure asymmetric at v0 tau ~ a0, where Hertz would
 * leave the gap far from flat) or the relaxed Hertz pressure (the soft EHL
 * pressure is nearly Hertzian); the rigid approach puts the minimum film at
 * the estimate. Newton then corrects the shape. */
void vl_contact_guess_smooth_film(vl_contact *c, double v0, const vl_contact *dry) {
  size_t n = c->n;
  double *y = N_VGetArrayPointer(c->y);
  const vl_contact_config *cfg = &c->cfg;
  double R = cfg->radius_m, h = vl_contact_film_estimate(cfg, v0);
  bool rigid = vl_contact_film_rigid(c, v0);
  double b = sqrt(2.0 * R * h) / c->a0; /* in a0 */
  double X_in = (c->xi[0] - 0.5 * c->wc[0]) / b, X_max = (c->xi[n - 1] + 0.5 * c->wc[n - 1]) / b;
  double Xc = rigid ? rigid_outlet(X_in, X_max) : 0.0, Hc = 1.0 + Xc * Xc;
  double a2 = rigid_i2(X_in), a3 = rigid_i3(X_in), sum = 0.0;
  if (rigid) dry = NULL;
  for (size_t i = 0; i < n; i++) {
    double x = c->xi[i], p;
    if (dry) {
      p = fmax(dry->P[i], 0.0);
    } else if (rigid) {
      double X = x / b;
      p = X < Xc ? fmax((rigid_i2(X) - a2) - Hc * (rigid_i3(X) - a3), 0.0) : 0.0;
    } else {
      p = fabs(x) < 1.0 ? sqrt(1.0 - x * x) : 0.0;
    }
    c->F[i] = p;
    sum += p * c->wc[i];
  }
  double scale = sum > 0.0 ? (0.5 * M_PI) / sum : 0.0, fmx = 0.0;
  for (size_t i = 0; i < n; i++)
    fmx = fmax(fmx, c->F[i] *= scale);
  if (c->pamb) /* the film's pressure above a sealed side's ambient */
    for (size_t i = 0; i < n; i++)
      fmx = fmax(fmx, c->F[i] += c->pamb[i]);
  c->kappa = fmx > 0.0 ? fmx : 1.0;
  for (size_t i = 0; i < n; i++)
    y[c->of + i] = c->F[i] / c->kappa;
  y[c->ih] = 0.0;
  vl_contact_eval_state(c, y);
  double umin = INFINITY;
  for (size_t i = 0; i < n; i++)
    umin = fmin(umin, c->U[i]);
  y[c->ih] = h / c->uscale - umin;
}

void vl_contact_guess_from_coarse(vl_contact *c, vl_contact *cc) {
  /* pressure (p0) linear between the coarse nodes, 0 on the domain ends;
   * rigid approach such that the minimum films agree */
  size_t n = c->n, m = cc->n;
  double *y = N_VGetArrayPointer(c->y), fmx = 0.0, umin_c = INFINITY, umin = INFINITY;
  vl_contact_eval_state(cc, N_VGetArrayPointer(cc->y));
  for (size_t k = 0; k < m; k++)
    umin_c = fmin(umin_c, cc->U[k]);
  for (size_t i = 0; i < n; i++) {
    double x = c->xi[i], f;
    if (x <= cc->xi[0]) {
      f = cc->F[0] * fmax(0.0, 1.0 - (cc->xi[0] - x) / (0.5 * cc->wc[0]));
    } else if (x >= cc->xi[m - 1]) {
      f = cc->F[m - 1] * fmax(0.0, 1.0 - (x - cc->xi[m - 1]) / (0.5 * cc->wc[m - 1]));
    } else {
      f = interpolate(cc->F, cc->xi, m, x);
    }
    c->F[i] = f;
    fmx = fmax(fmx, f);
  }
  c->kappa = fmx > 0.0 ? fmx : 1.0;
  for (size_t i = 0; i < n; i++)
    y[c->of + i] = c->F[i] / c->kappa;
  y[c->ih] = 0.0;
  vl_contact_eval_state(c, y);
  for (size_t i = 0; i < n; i++)
    umin = fmin(umin, c->U[i]);
  y[c->ih] = umin_c - umin;
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
void vl_contact_predict_state(vl_contact *c, double v0) {
  if (!c->rough || !(c->v_state > 0.0)) return;
  double *y = N_VGetArrayPointer(c->y), grow = v0 / c->v_state;
  for (size_t i = 0; i < c->nf; i++)
    y[c->of + i] *= grow;
}

/* Only the set matters: the first step of the active-set Newton solves
 * the set {P > 0} of its start exactly (the equations are linear for a
 * fixed set). Where e's set did not change, c's own set holds its edges to
 * a cell; where it did, e's puts them within about one of e's cells. */
void vl_contact_guess_from_companion(vl_contact *c, const vl_contact *e, const double *e_before) {
  double *y = N_VGetArrayPointer(c->y);
  const double *ye = N_VGetArrayPointer(e->y);
  for (size_t i = 0; i < c->nc; i++) {
    double now = interpolate(ye, e->xi, e->n, c->xi[i]);
    double before = interpolate(e_before, e->xi, e->n, c->xi[i]);
    if ((now > 0.0) != (before > 0.0)) y[i] = now > 0.0 ? now : 0.0;
  }
}

void vl_contact_guess_from_dry(vl_contact *c, const vl_contact *d) {
  /* the same cells and scales (a0, a0^2/R): the separations and the rigid
   * approach carry over; no fluid pressure yet */
  double *y = N_VGetArrayPointer(c->y);
  const double *yd = N_VGetArrayPointer(d->y);
  for (size_t i = 0; i < c->n; i++)
    y[i] = yd[i];
  for (size_t i = 0; i < c->nf; i++)
    y[c->of + i] = 0.0;
  y[c->ih] = yd[d->ih];
  c->kappa = 1.0;
  c->v_state = 0.0; /* no converged wet state: the fluid scales start from estimates */
}

void vl_contact_guess_from_film(vl_contact *c, vl_contact *s) {
  vl_contact_eval_state(s, N_VGetArrayPointer(s->y));
  /* the separation and the fluid pressure (both in the scales a0^2/R, p0
   * that the two contacts share) at the rough contact's nodes */
  double *y = N_VGetArrayPointer(c->y), fmx = 0.0;
  for (size_t i = 0; i < c->n; i++) {
    y[i] = interpolate(s->U, s->xi, s->n, c->xi[i]);
    c->F[i] = interpolate(s->F, s->xi, s->n, c->xi[i]);
    fmx = fmax(fmx, c->F[i]);
  }
  c->kappa = fmx > 0.0 ? fmx : 1.0;
  for (size_t i = 0; i < c->n; i++)
    y[c->of + i] = c->F[i] / c->kappa;
  /* the rigid approach that best satisfies the gap equation inside the
   * relaxed Hertz width, as vl_contact_reset takes it */
  y[c->ih] = 0.0;
  vl_contact_eval_state(c, y);
  double sum = 0.0;
  size_t cnt = 0;
  for (size_t i = 0; i < c->n; i++) {
    if (fabs(c->xi[i]) < 1.0) {
      sum += c->D[i];
      cnt++;
    }
  }
  y[c->ih] = cnt ? sum / (double)cnt : 0.0;
  c->v_state = 0.0;
}

/* How far (a0) a rough contact's domain may reach past the one it is
 * started from: the automatic layouts of rough films (numerics_plan.c) end
 * up to one of their inlet cells past the planned ends, and a state that
 * could not be carried over started the wiper afresh at every new layout
 * (where the fresh start found no film). */
#define START_END_SLACK_A0 0.1

bool vl_contact_start_from(vl_contact *dst, const vl_contact *src) {
  double v0 = src->v_state;
  if (dst->rough != src->rough || dst->wet != src->wet || !(v0 > 0.0)) return false;
  /* separations beyond src's domain are not its end values; planned
   * layouts end within a cell of the planned ends (START_END_SLACK_A0) */
  if (dst->rough && dst->cfg.x_min_a0 < src->cfg.x_min_a0 - START_END_SLACK_A0) return false;
  /* a rough contact whose outlet is moved out (sweep_auto.c): beyond src's
   * end the separation opens like the rigid gap x^2/2 and the film is
   * cavitated (p_f = 0) */
  bool beyond = dst->rough && dst->cfg.x_max_a0 > src->cfg.x_max_a0 + START_END_SLACK_A0;
  const double *ys = N_VGetArrayPointer(src->y);
  double *y = N_VGetArrayPointer(dst->y);
  vl_contact_set_speed(dst, v0);
  double x_end = src->xi[src->n - 1];
  for (size_t i = 0; i < dst->nc; i++) {
    double x = dst->xi[i];
    y[i] = interpolate(ys, src->xi, src->n, x);
    if (beyond && x > x_end) y[i] += 0.5 * (x * x - x_end * x_end);
  }
  for (size_t i = 0; i < dst->nf; i++) {
    double x = dst->xi[i];
    y[dst->of + i] = beyond && x > x_end ? 0.0 : interpolate(ys + src->of, src->xi, src->n, x);
  }
  y[dst->ih] = ys[src->ih];
  dst->kappa = src->kappa, dst->lambda = src->lambda, dst->rscale = src->rscale;
  dst->u_ref = src->u_ref;
  dst->v_state = v0;
  if (dst->wet) {
    vl_contact_eval_state(dst, y);
    vl_contact_reynolds_weights(dst);
  }
  return true;
}
