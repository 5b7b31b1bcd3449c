/* The private part of viscolube/contact.h: continuation in viscosity, the Hertz
 * reset and the inlet-length estimate, which the solver and the tests use; a
 * program solves points with vl_contact_solve and curves with the sweep. */
#ifndef VISCOLUBE_CONTACT_PRIVATE_H
#define VISCOLUBE_CONTACT_PRIVATE_H

#include "viscolube/contact.h"

/* Changes the fluid viscosity of a wet contact (eta > 0; VL_EINPUT for a
 * contact created dry) and keeps the current state: the next
 * vl_contact_solve continues from it (continuation in viscosity). The limit
 * eta -> 0 of a smooth film is the dry contact, reached this way on a
 * fixed grid; a fresh start at small eta would have to find the thin film's
 * inlet and outlet zones from scratch. */
vl_status vl_contact_set_viscosity(vl_contact *c, double eta_pa_s, vl_error *err);

double vl_contact_viscosity(const vl_contact *c); /* Pa s */

/* Continuation in viscosity at speed v0: solves at log-spaced viscosities
 * from the current one to eta_pa_s, steps at most a factor max_ratio (> 1),
 * each from the last converged state; a failed step is halved (in log eta)
 * up to 6 times. On success the contact holds the solution at eta_pa_s and
 * *pt reports it (iterations: the total); on failure the viscosity and
 * state are those of the last converged step, VL_ENOCONV (see err). */
vl_status vl_contact_solve_viscosity(vl_contact *c, double v0_m_s, double eta_pa_s,
                                     double max_ratio, vl_point *pt, vl_error *err);

/* The regime (vl_regime, results.h) of a point of a contact with a fluid
 * (wet) or without, from the fluid's share of the load and the film ratio
 * u_min / h_rms (NAN on smooth surfaces: the load share alone decides). */
int vl_regime_of(int wet, double fluid_load_fraction, double u_min_over_h_rms);

/* Resets the internal state to the Hertz (relaxed) guess. */
void vl_contact_reset(vl_contact *c);

/* Hydrodynamic inlet length sqrt(2 R h) (m) of a smooth wet contact of cfg
 * at speed v0 > 0, with h the larger of Martin's rigid film
 * 4.894 eta (v0/2) R/fN and the isoviscous-elastic estimate
 * 2.32 (eta (v0/2) R/fN) g^0.8, g = fN/sqrt(eta (v0/2) E' R), E' = 2 Er
 * (relaxed). For sizing the domain (docs/MODEL.md section 9): the pressure of a
 * rigid cylinder spreads over several such lengths, and with the inlet end
 * X lengths upstream its film is short by about 1/(2 X^2) / (1/(4 Hc)),
 * Hc = 1.226 (0.6 % at X = 20). Reads rubber, radius, load, viscosity. */
double vl_contact_inlet_length_m(const vl_contact_config *cfg, double v0_m_s);

/* The dry contact of cfg's profile (the parabola of radius_m, the table or
 * the lip, mirrored or not) on the rubber's relaxed elastic modulus under
 * load_n_per_m, smooth surfaces: the strip [centre - a, centre + a] (m, from
 * the tip), from the closed-form conditions of a two-dimensional punch with
 * free edges (a convex profile). *radius_m (may be NULL): the radius of the
 * cylinder whose Hertz contact is as wide, pi Er0 a^2/(4 fN): the radius
 * that makes the scales a0 = a (docs/MODEL.md section 9). VL_EINPUT for a
 * configuration vl_contact_create would refuse, or a profile on which no
 * width carries the load. */
vl_status vl_contact_profile_contact(const vl_contact_config *cfg, double *centre_m,
                                     double *half_width_m, double *radius_m, vl_error *err);

/* The load and the scales' radius of cfg's static pressure (the rubber
 * set): its integral (trapezoids of the table), and the radius of the
 * cylinder whose relaxed Hertz contact is as wide as the pressure's span
 * (a0 = half the span). VL_EINPUT as vl_contact_create for a table that is
 * not one. */
vl_status vl_contact_static_scales(const vl_contact_config *cfg, double *load_n_per_m,
                                   double *radius_m, vl_error *err);

/* Widens the domain of cfg (a lip or a table: its profile, mirrored and
 * not, as an outstroke and an instroke see it) so that the dry contact of
 * the profile (vl_contact_profile_contact) lies inside it with the margins
 * the cylinder's defaults keep about its Hertz contact [-a0, a0]: 0.6 a0
 * downstream of a wet contact, 0.5 a0 on both sides of a dry one; the
 * grid grows in proportion (the cells keep their width), and a graded inlet
 * starts 1 a0 upstream of the contact (grade_start_a0). The cylinder's
 * configuration is left as it is. VL_EINPUT as vl_contact_profile_contact. */
vl_status vl_contact_numerics_follow_profile(vl_contact_config *cfg, vl_error *err);

#endif
