/* The rubber's undeformed profile (profile.h; docs/MODEL.md section 13):
 * the parabola, a table interpolated by cubic Hermite, a parametric lip,
 * and the dry contact each makes. */
#include "profile.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bracket.h"

/* Sorts the points (x, z) by x (insertion: tables are small). */
static void sort_points(double *x, double *z, size_t m) {
  for (size_t i = 1; i < m; i++) {
    double xi = x[i], zi = z[i];
    size_t j = i;
    for (; j > 0 && x[j - 1] > xi; j--)
      x[j] = x[j - 1], z[j] = z[j - 1];
    x[j] = xi, z[j] = zi;
  }
}

/* Slope at point i of the parabola through points i-1, i, i+1 (at the ends
 * through the three end points): exact for a quadratic, so the Hermite
 * interpolant reproduces a parabola. */
static double three_point_slope(const double *x, const double *z, size_t m, size_t i) {
  size_t a = i == 0 ? 0 : i + 1 == m ? m - 3 : i - 1;
  double x0 = x[a], x1 = x[a + 1], x2 = x[a + 2], t = x[i];
  return z[a] * (2.0 * t - x1 - x2) / ((x0 - x1) * (x0 - x2)) +
         z[a + 1] * (2.0 * t - x0 - x2) / ((x1 - x0) * (x1 - x2)) +
         z[a + 2] * (2.0 * t - x0 - x1) / ((x2 - x0) * (x2 - x1));
}

/* f and f' at t of the table (sorted, slopes d): cubic Hermite inside,
 * straight beyond the ends. */
static double table_at(const double *x, const double *z, const double *d, size_t m, double t,
                       double *slope) {
  if (t <= x[0]) return *slope = d[0], z[0] + d[0] * (t - x[0]);
  if (t >= x[m - 1]) return *slope = d[m - 1], z[m - 1] + d[m - 1] * (t - x[m - 1]);
  size_t lo = vl_bracket(x, m, t), hi = lo + 1;
  double h = x[hi] - x[lo], s = (t - x[lo]) / h, s2 = s * s, s3 = s2 * s;
  double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  *slope = (6 * s2 - 6 * s) / h * z[lo] + (3 * s2 - 4 * s + 1) * d[lo] +
           (-6 * s2 + 6 * s) / h * z[hi] + (3 * s2 - 2 * s) * d[hi];
  return h00 * z[lo] + h10 * h * d[lo] + h01 * z[hi] + h11 * h * d[hi];
}

/* The table of cfg, sorted, its slopes, and shifted so that the tip (the
 * interpolant's minimum next to the lowest point, where its slope changes
 * sign: bisection) sits at x = 0, z = 0; a table need not hold the tip. */
static vl_status table_init(vl_profile *p, const vl_contact_config *cfg, vl_error *err) {
  size_t m = cfg->profile_points;
  double *w = calloc(3 * m, sizeof *w);
  if (!w) {
    vl_error_set(err, "out of memory for a profile of %zu points", m);
    return VL_ENOMEM;
  }
  double *x = w, *z = w + m, *d = w + 2 * m;
  size_t imin = 0;
  for (size_t k = 0; k < m; k++) {
    x[k] = cfg->profile_mirror ? -cfg->profile_x_m[k] : cfg->profile_x_m[k];
    z[k] = cfg->profile_z_m[k];
  }
  sort_points(x, z, m);
  for (size_t k = 0; k < m; k++)
    if (z[k] < z[imin]) imin = k;
  for (size_t k = 0; k < m; k++)
    d[k] = three_point_slope(x, z, m, k);
  double lo = x[imin > 0 ? imin - 1 : 0], hi = x[imin + 1 < m ? imin + 1 : m - 1], sl;
  table_at(x, z, d, m, lo, &sl);
  bool falls = sl < 0.0;
  table_at(x, z, d, m, hi, &sl);
  if (falls && sl > 0.0) {
    for (int it = 0; it < 200 && hi - lo > 0.0; it++) {
      double mid = 0.5 * (lo + hi);
      if (mid == lo || mid == hi) break;
      table_at(x, z, d, m, mid, &sl);
      if (sl < 0.0)
        lo = mid;
      else
        hi = mid;
    }
  } else {
    lo = x[imin];
  }
  double x0 = lo, z0 = table_at(x, z, d, m, lo, &sl);
  for (size_t k = 0; k < m; k++)
    x[k] -= x0, z[k] -= z0; /* the slopes do not change */
  p->kind = VL_PROFILE_TABLE;
  p->m = m, p->x = x, p->z = z, p->d = d;
  return VL_OK;
}

vl_status vl_profile_init(vl_profile *p, const vl_contact_config *cfg, vl_error *err) {
  memset(p, 0, sizeof *p);
  p->radius_m = cfg->radius_m;
  if (cfg->profile_x_m) return table_init(p, cfg, err);
  if (cfg->lip_tip_radius_m > 0.0) {
    double oil = tan(cfg->lip_oil_angle_rad), air = tan(cfg->lip_air_angle_rad);
    p->kind = VL_PROFILE_LIP;
    p->radius_m = cfg->lip_tip_radius_m;
    /* the oil side is the inlet of an outstroke; an instroke sees it mirrored */
    p->slope_in = cfg->profile_mirror ? air : oil;
    p->slope_out = cfg->profile_mirror ? oil : air;
  }
  return VL_OK;
}

void vl_profile_free(vl_profile *p) {
  free(p->x);
  memset(p, 0, sizeof *p);
}

/* The lip: the tip's parabola between the tangent points x = -r s_in and
 * x = r s_out, where its slope x/r meets the flanks' -s_in and s_out. */
static double lip_at(const vl_profile *p, double x, double *slope) {
  double r = p->radius_m, xl = -r * p->slope_in, xr = r * p->slope_out;
  if (x < xl) return *slope = -p->slope_in, 0.5 * xl * xl / r - p->slope_in * (x - xl);
  if (x > xr) return *slope = p->slope_out, 0.5 * xr * xr / r + p->slope_out * (x - xr);
  return *slope = x / r, 0.5 * x * x / r;
}

double vl_profile_height(const vl_profile *p, double x_m, double *slope) {
  switch (p->kind) {
  case VL_PROFILE_TABLE: return table_at(p->x, p->z, p->d, p->m, x_m, slope);
  case VL_PROFILE_LIP: return lip_at(p, x_m, slope);
  case VL_PROFILE_PARABOLA: break;
  }
  *slope = x_m / p->radius_m;
  return 0.5 * x_m * x_m / p->radius_m;
}

/* Gauss-Chebyshev nodes of the punch integrals: the lip's slope jumps in its
 * second derivative at the tangent points, so the rule converges like
 * 1/N^2 there; 4096 nodes put the width within 1e-6 of 65536 nodes'. */
#define CHEB_NODES 4096

typedef struct {
  const vl_profile *p;
  double t[CHEB_NODES]; /* cos((k + 1/2) pi / N) */
} punch;

/* \int f'(c + a t) t^k / sqrt(1 - t^2) dt over [-1, 1], k = 0 and 1, as
 * \int_0^pi f'(c + a cos th) cos^k th dth by the midpoint rule. */
static void punch_integrals(const punch *q, double c, double a, double *i0, double *i1) {
  double s0 = 0.0, s1 = 0.0;
  for (int k = 0; k < CHEB_NODES; k++) {
    double sl;
    vl_profile_height(q->p, c + a * q->t[k], &sl);
    s0 += sl, s1 += sl * q->t[k];
  }
  *i0 = s0 * M_PI / CHEB_NODES, *i1 = s1 * M_PI / CHEB_NODES;
}

/* The centre c of the strip of half-width a whose ends the pressure leaves
 * smoothly: \int f'/sqrt(1 - t^2) = 0, increasing in c for a convex
 * profile (negative for c = -a, where the whole strip lies left of the tip,
 * positive for c = a); bisection. */
static double punch_centre(const punch *q, double a) {
  double lo = -a, hi = a, i0, i1;
  for (int it = 0; it < 200 && hi - lo > 1e-12 * a; it++) {
    double mid = 0.5 * (lo + hi);
    punch_integrals(q, mid, a, &i0, &i1);
    if (i0 < 0.0)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

/* The load the strip of half-width a carries (its centre set), N/m. */
static double punch_load(const punch *q, double a, double er, double *c) {
  double i0, i1;
  *c = punch_centre(q, a);
  punch_integrals(q, *c, a, &i0, &i1);
  return 0.5 * er * a * i1;
}

vl_status vl_profile_dry_contact(const vl_profile *p, double load_n_per_m, double er_pa,
                                 double *centre_m, double *half_width_m, vl_error *err) {
  punch *q = malloc(sizeof *q);
  if (!q) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  q->p = p;
  for (int k = 0; k < CHEB_NODES; k++)
    q->t[k] = cos(M_PI * (k + 0.5) / CHEB_NODES);
  /* bracket the width from the tip's Hertz half-width, then bisect in log a */
  double a = sqrt(4.0 * load_n_per_m * p->radius_m / (M_PI * er_pa)), c = 0.0;
  double lo = a, hi = a;
  int k = 0;
  for (; k < 200 && punch_load(q, lo, er_pa, &c) > load_n_per_m; k++)
    lo *= 0.5;
  for (; k < 200 && punch_load(q, hi, er_pa, &c) < load_n_per_m; k++)
    hi *= 2.0;
  vl_status st = VL_OK;
  if (k == 200 || !(lo > 0.0 && isfinite(hi))) {
    vl_error_set(err, "the profile's dry contact: no width carries %g N/m (is it convex?)",
                 load_n_per_m);
    st = VL_EINPUT;
    goto done;
  }
  for (int it = 0; it < 200 && hi - lo > 1e-10 * hi; it++) {
    double mid = sqrt(lo * hi);
    if (punch_load(q, mid, er_pa, &c) < load_n_per_m)
      lo = mid;
    else
      hi = mid;
  }
  *half_width_m = sqrt(lo * hi);
  punch_load(q, *half_width_m, er_pa, centre_m);
done:
  free(q);
  return st;
}

double vl_profile_rise_length(const vl_profile *p, double h_m) {
  double sl, lo = 0.0, hi = sqrt(2.0 * p->radius_m * h_m);
  for (int k = 0; k < 200 && vl_profile_height(p, -hi, &sl) < h_m; k++)
    lo = hi, hi *= 2.0;
  for (int it = 0; it < 100 && hi - lo > 1e-12 * hi; it++) {
    double mid = 0.5 * (lo + hi);
    if (vl_profile_height(p, -mid, &sl) < h_m)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

vl_status vl_static_pressure_init(vl_static_pressure *t, const vl_contact_config *cfg,
                                  vl_error *err) {
  memset(t, 0, sizeof *t);
  size_t m = cfg->static_points;
  if (!cfg->static_x_m || !cfg->static_p_pa || m < 3) {
    vl_error_set(err, "a static pressure needs x and p of at least 3 points (got %zu)", m);
    return VL_EINPUT;
  }
  double *w = malloc(2 * m * sizeof *w);
  if (!w) {
    vl_error_set(err, "out of memory for a static pressure of %zu points", m);
    return VL_ENOMEM;
  }
  double *x = w, *p = w + m;
  vl_status st = VL_OK;
  for (size_t k = 0; k < m && st == VL_OK; k++) {
    x[k] = cfg->profile_mirror ? -cfg->static_x_m[k] : cfg->static_x_m[k];
    p[k] = cfg->static_p_pa[k];
    if (!isfinite(x[k]) || !isfinite(p[k]) || p[k] < 0.0) {
      vl_error_set(err, "static pressure point %zu: x = %g m, p = %g Pa (finite, p >= 0)", k + 1,
                   cfg->static_x_m[k], p[k]);
      st = VL_EINPUT;
    }
  }
  if (st == VL_OK) sort_points(x, p, m);
  double pmax = 0.0, load = 0.0;
  for (size_t k = 0; k < m && st == VL_OK; k++) {
    pmax = fmax(pmax, p[k]);
    if (k > 0 && x[k] == x[k - 1]) {
      vl_error_set(err, "static pressure: x = %g m given twice", x[k]);
      st = VL_EINPUT;
    }
    if (k > 0) load += 0.5 * (p[k] + p[k - 1]) * (x[k] - x[k - 1]);
  }
  if (st == VL_OK && (p[0] != 0.0 || p[m - 1] != 0.0 || !(pmax > 0.0))) {
    vl_error_set(err,
                 "static pressure: it must be 0 at both ends of the table (the contact's "
                 "edges) and positive between (got %g Pa at x = %g m, %g Pa at x = %g m)",
                 p[0], x[0], p[m - 1], x[m - 1]);
    st = VL_EINPUT;
  }
  if (st != VL_OK) {
    free(w);
    return st;
  }
  double mid = 0.5 * (x[0] + x[m - 1]);
  for (size_t k = 0; k < m; k++)
    x[k] -= mid;
  *t = (vl_static_pressure){m, x, p, load, 0.5 * (x[m - 1] - x[0])};
  return VL_OK;
}

void vl_static_pressure_free(vl_static_pressure *t) {
  free(t->x);
  memset(t, 0, sizeof *t);
}

double vl_static_pressure_at(const vl_static_pressure *t, double x) {
  if (!(x > t->x[0] && x < t->x[t->m - 1])) return 0.0;
  size_t lo = vl_bracket(t->x, t->m, x), hi = lo + 1;
  double s = (x - t->x[lo]) / (t->x[hi] - t->x[lo]);
  return (1.0 - s) * t->p[lo] + s * t->p[hi];
}
