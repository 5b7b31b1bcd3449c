/* The rubber's undeformed profile f(x) (docs/MODEL.md section 13), private
 * to the solver: the cylinder's parabola x^2/(2 R), a table (x_m, z_m) or a
 * parametric lip, evaluated in metres wherever the solver needs it (the
 * contact's gap at its nodes, the automatic numerics' lengths), and the dry
 * elastic contact it makes under a load, from the closed-form conditions of
 * a two-dimensional punch. */
#ifndef VISCOLUBE_PROFILE_H
#define VISCOLUBE_PROFILE_H

#include <stddef.h>

#include "viscolube/contact.h"
#include "viscolube/status.h"

typedef enum { VL_PROFILE_PARABOLA = 0, VL_PROFILE_TABLE, VL_PROFILE_LIP } vl_profile_kind;

typedef struct {
  vl_profile_kind kind;
  double radius_m; /* the parabola's radius, or the lip's tip radius */
  /* lip: the flanks' slopes on the inlet side (x < 0) and the outlet side
   * (x > 0), after the mirror of an instroke */
  double slope_in, slope_out;
  /* table: sorted, shifted so that the interpolant's minimum (the tip)
   * sits at x = 0, z = 0; d the slopes of the Hermite interpolant at the
   * points; one block of 3 m values (owned) */
  size_t m;
  double *x, *z, *d;
} vl_profile;

/* The profile of cfg (its table, its lip, else the parabola of radius_m),
 * mirrored (f(-x)) when cfg->profile_mirror. VL_ENOMEM; the configuration
 * is assumed checked (vl_contact_config_check). Free with vl_profile_free. */
vl_status vl_profile_init(vl_profile *p, const vl_contact_config *cfg, vl_error *err);
void vl_profile_free(vl_profile *p);

/* f(x) (m) above the counter-surface, x in m from the tip, and its slope
 * f'(x) in *slope. The lip: x^2/(2 r) on [-r s_in, r s_out], straight
 * flanks of slopes -s_in and s_out beyond (value and slope continuous at
 * the tangent points); a table: cubic Hermite inside, straight beyond its
 * ends. */
double vl_profile_height(const vl_profile *p, double x_m, double *slope);

/* The dry, smooth contact the profile makes on an elastic half-space of
 * plane-strain modulus er_pa (Pa) under load_n_per_m: the strip [c - a,
 * c + a] where, for a convex profile, the pressure is bounded at both ends
 * (the two-dimensional punch with free edges; Johnson, Contact Mechanics,
 * 1985, chapter 2):
 *   \int f'(c + a t) / sqrt(1 - t^2) dt = 0,
 *   fN = (er a / 2) \int t f'(c + a t) / sqrt(1 - t^2) dt,   t in [-1, 1]
 * (the cylinder: c = 0, a the Hertz half-width). Gauss-Chebyshev
 * quadrature and bisections. *centre_m = c, *half_width_m = a; VL_EINPUT
 * when no width carries the load (a profile that is not convex). */
vl_status vl_profile_dry_contact(const vl_profile *p, double load_n_per_m, double er_pa,
                                 double *centre_m, double *half_width_m, vl_error *err);

/* The distance upstream of the tip (x < 0) at which the profile has risen
 * by h (m) above the tip: sqrt(2 R h) for the cylinder (the rigid film's
 * inlet length), shorter on a steep flank. */
double vl_profile_rise_length(const vl_profile *p, double h_m);

/* An imposed static contact pressure (vl_contact_config.static_x_m; docs/
 * MODEL.md section 14): the table sorted (mirrored when cfg->profile_mirror)
 * and shifted so that the middle of its span sits at x = 0. */
typedef struct {
  size_t m;
  double *x, *p;                     /* one block of 2 m values (owned) */
  double load_n_per_m, half_width_m; /* its integral (trapezoids) and half its span */
} vl_static_pressure;

/* VL_EINPUT naming the point when the table is not one (fewer than 3 points,
 * a value not finite, an x twice, p < 0, p not zero at both ends, no p >
 * 0); VL_ENOMEM. Free with vl_static_pressure_free. */
vl_status vl_static_pressure_init(vl_static_pressure *t, const vl_contact_config *cfg,
                                  vl_error *err);
void vl_static_pressure_free(vl_static_pressure *t);
/* p_s(x) (Pa), linear between the points, 0 beyond. */
double vl_static_pressure_at(const vl_static_pressure *t, double x_m);

#endif
