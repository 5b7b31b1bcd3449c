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

#endif
