/* viscolube (private): the Prony series below its public part
 * (viscolube/rheology.h: the series, its check, E0, the complex modulus and
 * the loss peak). Here: the other quantities of the series, time-temperature
 * shifts and the asperity state the layers above and the tests use. */
#ifndef VISCOLUBE_RHEOLOGY_INTERNAL_H
#define VISCOLUBE_RHEOLOGY_INTERNAL_H

#include <complex.h>

#include "viscolube/rheology.h"

/* A single-term "standard linear solid" with relaxed modulus E0 and ratio
 * Einf/E0 (>= 1), retardation time tau. */
vl_prony vl_prony_single(double e0_pa, double einf_over_e0, double tau_s, double nu);

double vl_prony_sum_A(const vl_prony *prony);
double vl_prony_reduced_factor(const vl_prony *prony); /* 1/(1 - nu^2) */

double complex vl_prony_compliance(const vl_prony *prony, double omega); /* J' - i J'' */
double vl_prony_tan_delta(const vl_prony *prony, double omega);

/* Multiplies every tau_i by a_T (time-temperature superposition). */
void vl_prony_shift(vl_prony *prony, double a_T);

/* WLF: log10 a_T = -C1 (T - Tref) / (C2 + T - Tref). Returns NAN when the
 * denominator is not positive (outside the WLF domain). */
double vl_wlf_log10_shift(double c1, double c2_k, double t_c, double tref_c);

/* |Er(wH)| and a_H at speed v0 from the fixed point wH = pi v0 / a_H,
 * a_H^2 = 4 fN R/(pi |Er(wH)|) (docs/MODEL.md section 4). Reduced moduli. */
void vl_asperity_state(const vl_prony *rubber, double load_n_per_m, double radius_m, double v0_m_s,
                       double *E_abs_pa, double *a_H_m, double *omega_H);
/* The same for a ball of radius R under the force W: a_H the Hertz radius
 * (3 W R/(4 |Er|))^(1/3) (docs/POINT_CONTACT.md section 10). */
void vl_asperity_state_ball(const vl_prony *rubber, double load_n, double radius_m, double v0_m_s,
                            double *E_abs_pa, double *a_H_m, double *omega_H);

#endif
