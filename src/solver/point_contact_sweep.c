/* A curve of the point contact (point_contact.h): the Hertz ellipse,
 * cells and domain planned for each point from its own contact size, the
 * point's error estimate (the same point on cells twice as wide) and its
 * refinement to the target (docs/POINT_CONTACT.md section 5).
 *
 * A viscoelastic ball's contact shrinks with speed from the relaxed Hertz
 * radius a0 towards the glassy one, a0 (E0/Einf)^(1/3) (0.1 a0 for a
 * filled rubber with Einf/E0 = 1000): cells of a0/20 would leave two cells
 * across it. So each point gets its own cells: the contact radius is
 * estimated as Hertz's with the modulus at the frequency v0/a of the
 * contact it predicts (a fixed point), the domain is that ellipse with a
 * margin and the cells VL_BALL_CELLS_PER_A0 across its shorter semi-axis.
 * Each point is solved from the Hertz guess on its own cells (points are
 * independent: a curve can be run in any order); one that does not
 * converge is reached by continuation from the previous point's speed on
 * the same cells. */
#include "point_contact_internal.h"

#include <complex.h>
#include <gsl/gsl_sf_ellint.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gsl_errors.h"
#include "rheology_internal.h"

/* The domain around the estimated contact (its semi-axes times this):
 * room for a viscoelastic contact's shift to the inlet; a contact that
 * still reaches the edge gets a domain BALL_EDGE_GROWTH times larger. */
#define BALL_AUTO_MARGIN 1.3
#define BALL_EDGE_GROWTH 1.5
#define BALL_EDGE_RETRIES 3

/* The automatic cells stop here (the dense LU of the cells in contact
 * grows as their cube): a refinement beyond is not made. */
#define BALL_AUTO_MAX_CELLS 4000

/* A refinement multiplies the cells per a0 by this (twice the cells). */
#define BALL_REFINE_FACTOR M_SQRT2

/* An estimate a refinement did not lower below this fraction of the
 * coarser one stops the refinement (as the line contact's sweep). */
#define BALL_REFINE_MIN_GAIN 0.7

vl_status vl_hertz_ellipse(double radius_x_m, double radius_y_m, double load_n, double er_pa,
                           double *ax_m, double *by_m, double *p0_pa) {
  if (!(radius_x_m > 0 && radius_y_m > 0 && load_n > 0 && er_pa > 0)) return VL_EINPUT;
  vl_gsl_errors_off();
  double A = 0.5 / radius_x_m, B = 0.5 / radius_y_m, lo = fmin(A, B), ratio = fmax(A, B) / lo;
  double major, minor;
  if (ratio - 1.0 < 1e-12) {
    major = minor = cbrt(0.75 * load_n / (2.0 * A * er_pa));
  } else {
    /* B/A = ((1/(1 - e^2)) E(e) - K(e)) / (K(e) - E(e)), increasing in e */
    double e0 = 0.0, e1 = 1.0 - 1e-15;
    for (int it = 0; it < 200 && e1 - e0 > 1e-15; it++) {
      double e = 0.5 * (e0 + e1);
      double K = gsl_sf_ellint_Kcomp(e, GSL_PREC_DOUBLE),
             E = gsl_sf_ellint_Ecomp(e, GSL_PREC_DOUBLE);
      double g = (E / (1.0 - e * e) - K) / (K - E);
      if (g < ratio)
        e0 = e;
      else
        e1 = e;
    }
    double e = 0.5 * (e0 + e1), K = gsl_sf_ellint_Kcomp(e, GSL_PREC_DOUBLE);
    double E = gsl_sf_ellint_Ecomp(e, GSL_PREC_DOUBLE);
    /* the smaller curvature A_min = p0 b (K - E)/(Er e^2 a^2), p0 = 3W/(2 pi a b) */
    major = cbrt(3.0 * load_n * (K - E) / (2.0 * M_PI * er_pa * e * e * lo));
    minor = major * sqrt(1.0 - e * e);
  }
  /* the major axis lies along the smaller curvature (the larger radius) */
  *ax_m = A <= B ? major : minor;
  *by_m = A <= B ? minor : major;
  if (p0_pa) *p0_pa = 1.5 * load_n / (M_PI * major * minor);
  return VL_OK;
}

/* The numerics of point v0: the contact's size s (in units of its relaxed
 * Hertz ellipse) estimated from Hertz with |Er(v0/a)|, then cells and
 * domain around it. */
static void plan_point(const vl_point_contact_config *base, double v0, double scale,
                       vl_point_contact_config *cfg) {
  *cfg = *base;
  double red = vl_prony_reduced_factor(&base->rubber), er0 = vl_prony_e0(&base->rubber) * red;
  double ax, by, re = sqrt(base->radius_x_m * base->radius_y_m);
  vl_hertz_ellipse(base->radius_x_m, base->radius_y_m, base->load_n, er0, &ax, &by, NULL);
  double a0 = cbrt(0.75 * base->load_n * re / er0), s = 1.0, aeq = sqrt(ax * by);
  for (int it = 0; it < 30 && v0 > 0.0 && base->rubber.n_terms > 0; it++) {
    double er = cabs(vl_prony_modulus(&base->rubber, v0 / (s * aeq))) * red;
    s = cbrt(er0 / er);
  }
  double lx = s * ax / a0, ly = s * by / a0; /* the semi-axes, in a0 */
  cfg->x_half_a0 = BALL_AUTO_MARGIN * scale * lx;
  cfg->y_max_a0 = BALL_AUTO_MARGIN * scale * ly;
  cfg->cells_per_a0 = VL_BALL_CELLS_PER_A0 / fmin(lx, ly);
}

/* Cells of cfg (as point_contact.c counts them). */
static size_t cells_of(const vl_point_contact_config *cfg) {
  if (vl_point_contact_is_graded(cfg)) return vl_point_contact_wet_cells(cfg);
  double r = cfg->cells_per_a0;
  return (2 * (size_t)ceil(cfg->x_half_a0 * r - 0.5) + 1) *
         (size_t)fmax(1.0, ceil(cfg->y_max_a0 * r - 1e-9));
}

/* Solves point v0 on cfg's cells into *pt: from Hertz, else by
 * continuation from v_prev (> 0: the speed below it on the curve) on the
 * same cells, in up to 16 steps of log v0. *c gets the contact (the
 * caller frees it), also when the point failed. */
static vl_status solve_on(const vl_point_contact_config *cfg, double v0, double v_prev,
                          const vl_point_contact *from, vl_point_contact **c, vl_point *pt,
                          vl_sweep_stats *st, vl_error *err) {
  vl_status s = vl_point_contact_create(cfg, c, err);
  if (s != VL_OK) return s;
  if ((*c)->graded) vl_point_contact_wet_start_from(*c, from);
  s = vl_point_contact_solve(*c, v0, pt, err);
  st->newton_iterations += pt->iterations;
  /* (a lubricated ball continues in speed within its own solve) */
  if (s != VL_ENOCONV || !(v_prev > 0.0 && v_prev < v0) || vl_point_contact_is_graded(cfg))
    return s;
  st->substeps++;
  vl_point_contact_reset(*c);
  long nni = pt->iterations;
  for (int k = 0; k <= 16; k++) {
    double v = v_prev * pow(v0 / v_prev, k / 16.0);
    s = vl_point_contact_solve(*c, k == 16 ? v0 : v, pt, err);
    nni += pt->iterations;
    if (s != VL_OK) break;
  }
  st->newton_iterations += nni - pt->iterations;
  pt->iterations = nni;
  return s;
}

/* The error estimate of pt: the point again on cells twice as wide on the
 * same domain; each term's change over the error of the finer solve at
 * the slowest order measured for it (docs/POINT_CONTACT.md section 6), so
 * that no point's error is understated:
 *   (|d mu_Rc| / (sqrt 2 - 1) + |d mu_Sc|) / |mu|,
 * the rolling term's error falling like the square root of the cell size
 * (its low-speed flank, De << 1, converges like h^0.6 towards its exact
 * limit), the contact area's (mu_Sc) at first order or better. NAN when the
 * coarse solve fails. */
static double estimate(const vl_point_contact_config *cfg, double v0, vl_sweep_stats *st,
                       const vl_point *pt, const vl_point_contact *fine) {
  vl_point_contact_config coarse = *cfg;
  coarse.cells_per_a0 = cfg->cells_per_a0 / 2.0;
  if (coarse.cells_per_a0 < VL_BALL_MIN_CELLS_PER_A0) return NAN;
  vl_point_contact *c = NULL;
  vl_point cp;
  vl_error e;
  vl_status s = solve_on(&coarse, v0, 0.0, fine, &c, &cp, st, &e);
  vl_point_contact_free(c);
  if (s != VL_OK) return NAN;
  double d = fabs(pt->mu_Rc - cp.mu_Rc) / (M_SQRT2 - 1.0) + fabs(pt->mu_Sc - cp.mu_Sc);
  if (cfg->roughness) /* rough: the change itself (order 1), the rolling terms together */
    d = fabs(pt->mu_Rc + pt->mu_Rf - cp.mu_Rc - cp.mu_Rf) + fabs(pt->mu_Sc - cp.mu_Sc) +
        fabs(pt->mu_Sf - cp.mu_Sf);
  else if (cfg->eta_pa_s > 0.0) /* lubricated: the change itself (order 1, see above) */
    d = fabs(pt->mu_Rf - cp.mu_Rf) + fabs(pt->mu_Sf - cp.mu_Sf);
  return d / fmax(fabs(pt->mu), 1e-9);
}

static void append_warning(vl_point *pt, const char *w) {
  size_t len = strlen(pt->warnings);
  snprintf(pt->warnings + len, sizeof pt->warnings - len, "%s%s", len ? ";" : "", w);
}

/* One point of the curve, its contact in *c (the caller frees it). */
typedef struct {
  const vl_point_contact_config *base;
  const vl_auto_options *opt;
  double v_prev;
  /* the previous converged point's contact: a graded contact's first start
   * (the curve continued; its own paths when that fails) */
  const vl_point_contact *prev;
  vl_sweep_stats *st;
} point_job;

static vl_status solve_planned(const point_job *j, double v0, double scale, double refine,
                               const vl_point_contact *from, vl_point_contact **c, vl_point *pt,
                               vl_point_contact_config *cfg, vl_error *err) {
  if (j->opt->keep_numerics)
    *cfg = *j->base;
  else
    plan_point(j->base, v0, scale, cfg);
  cfg->cells_per_a0 *= refine;
  while (cells_of(cfg) > BALL_AUTO_MAX_CELLS && !j->opt->keep_numerics)
    cfg->cells_per_a0 /= 1.05; /* the bound: fewer cells, said by the estimate */
  return solve_on(cfg, v0, j->v_prev, from, c, pt, j->st, err);
}

static vl_status ball_point(const point_job *j, double v0, vl_point_contact **c, vl_point *pt,
                            vl_error *err) {
  vl_point_contact_config cfg;
  double scale = 1.0, refine = 1.0;
  vl_status s = solve_planned(j, v0, scale, refine, j->prev, c, pt, &cfg, err);
  for (int k = 0; k < BALL_EDGE_RETRIES && s == VL_OK && !j->opt->keep_numerics &&
                  strstr(pt->warnings, "domain edge");
       k++) {
    vl_point_contact_free(*c);
    scale *= BALL_EDGE_GROWTH;
    s = solve_planned(j, v0, scale, refine, j->prev, c, pt, &cfg, err);
  }
  if (s != VL_OK) return s;
  pt->error_estimate = estimate(&cfg, v0, j->st, pt, *c);
  const char *stop = NULL;
  for (int k = 0; k < j->opt->max_refinements && !j->opt->keep_numerics; k++) {
    if (!(pt->error_estimate > j->opt->target_error)) break;
    vl_point_contact_config next = cfg;
    next.cells_per_a0 *= BALL_REFINE_FACTOR;
    if (cells_of(&next) > BALL_AUTO_MAX_CELLS) break;
    vl_point_contact *fine = NULL;
    vl_point fp;
    vl_error e;
    if (solve_planned(j, v0, scale, refine * BALL_REFINE_FACTOR, *c, &fine, &fp, &next, &e) !=
        VL_OK) {
      vl_point_contact_free(fine);
      stop = "refinement did not converge (coarser cells kept)";
      break;
    }
    refine *= BALL_REFINE_FACTOR;
    double old = pt->error_estimate;
    fp.error_estimate = estimate(&next, v0, j->st, &fp, fine);
    vl_point_contact_free(*c);
    *c = fine, *pt = fp, cfg = next;
    if (!(pt->error_estimate < BALL_REFINE_MIN_GAIN * old)) {
      stop = "estimate not falling with refinement";
      break;
    }
  }
  double target = j->opt->target_error;
  pt->accuracy = !(pt->error_estimate == pt->error_estimate) ? VL_ACCURACY_NO_ESTIMATE
                 : pt->error_estimate > target               ? VL_ACCURACY_ABOVE_TARGET
                                                             : VL_ACCURACY_MET;
  if (pt->accuracy == VL_ACCURACY_NO_ESTIMATE)
    append_warning(pt, "no error estimate (the coarser solve failed)");
  if (pt->error_estimate > target) {
    char w[120];
    snprintf(w, sizeof w, "error estimate %.2g %% above the target %.2g %%",
             100.0 * pt->error_estimate, 100.0 * target);
    append_warning(pt, w);
    if (stop) append_warning(pt, stop);
  }
  return VL_OK;
}

vl_status vl_point_contact_sweep(const vl_point_contact_config *base, const vl_auto_options *opt,
                                 size_t n, const double *v0_m_s, vl_point *out,
                                 vl_point_contact_callback cb, void *user, vl_sweep_stats *stats,
                                 vl_error *err) {
  double t0 = vl_point_contact_now_s();
  vl_sweep_stats st = {0};
  vl_auto_options o = {VL_TARGET_ERROR_DEFAULT, VL_AUTO_MAX_REFINEMENTS, false};
  if (opt) o = *opt;
  if (!(o.target_error > 0.0)) o.target_error = VL_TARGET_ERROR_DEFAULT;
  if (o.max_refinements < 0) o.max_refinements = VL_AUTO_MAX_REFINEMENTS;
  vl_point_contact *probe = NULL; /* the base is checked once, up front */
  vl_status s = vl_point_contact_build(base, &probe, err);
  vl_point_contact_release(probe);
  if (s != VL_OK) return s;
  point_job j = {base, &o, 0.0, NULL, &st};
  vl_point_contact *prev = NULL;
  for (size_t i = 0; i < n; i++) {
    vl_point_contact *c = NULL;
    vl_error e;
    s = ball_point(&j, v0_m_s[i], &c, &out[i], &e);
    if (s != VL_OK && s != VL_ENOCONV) {
      vl_point_contact_free(c);
      vl_point_contact_free(prev);
      if (err) *err = e;
      return s;
    }
    if (out[i].converged) {
      st.converged++;
      j.v_prev = v0_m_s[i];
    } else {
      st.failed++;
    }
    if (cb) cb(user, i, n, &out[i], out[i].converged ? c : NULL);
    if (out[i].converged && c->graded) { /* kept as the next point's start */
      vl_point_contact_free(prev);
      prev = c, j.prev = c;
    } else {
      vl_point_contact_free(c);
    }
  }
  vl_point_contact_free(prev);
  st.seconds = vl_point_contact_now_s() - t0;
  if (stats) *stats = st;
  return VL_OK;
}
