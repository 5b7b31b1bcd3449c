/* The private part of viscolube/shear_law.h: building, checking and evaluating a
 * law of sigma_s and the dewetting speed, for the library and the tests; a
 * program stores laws as pairs (database.h) and reads them back as text. */
#ifndef VISCOLUBE_SHEAR_LAW_PRIVATE_H
#define VISCOLUBE_SHEAR_LAW_PRIVATE_H

#include "viscolube/shear_law.h"

/* A constant law of sigma_s_pa (no reference conditions). */
vl_shear_law vl_shear_law_constant(double sigma_s_pa);

/* VL_OK when law can be evaluated: every stress finite and >= 0 (eyring's
 * sigma_e and dewetting's two may be 0), speeds finite and > 0, tref_c NAN
 * or above absolute zero, eta_ref_pa_s NAN, 0 or positive. VL_EINPUT naming
 * the parameter otherwise. */
vl_status vl_shear_law_validate(const vl_shear_law *law, vl_error *err);

/* The law at temperature t_c (NAN: as stored) in a fluid of viscosity
 * eta_pa_s (NAN or 0: as stored): eyring's sigma_e = k_B T / V_a grows with
 * the absolute temperature, V_a fixed (v_e is not shifted: the activated
 * process is the interface layer's, not the rubber's, and one isothermal
 * curve cannot tell its activation energy); dewetting's V_d moves as
 * eta_ref / eta (Eq. 6; S, E and e taken as fixed); constant: unchanged.
 * *out gets the law at those conditions (its tref_c and eta_ref_pa_s
 * updated). VL_EINPUT when t_c is below absolute zero or eta negative. */
vl_status vl_shear_law_at(const vl_shear_law *law, double t_c, double eta_pa_s, vl_shear_law *out,
                          vl_error *err);

/* The seed's Eq. 6, V_d = k S^2 / (eta E e) (m/s). */
double vl_dewetting_speed(double k, double spreading_pressure_n_m, double eta_pa_s, double e_pa,
                          double gap_m);

#endif
