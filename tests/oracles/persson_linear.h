/* Test oracle: Persson's linear-order rolling friction (docs/VALIDATION.md §3),
 * for a standard linear solid 1/Er(w) = (1/Er_inf)[1 + A/(1 - i w tau)],
 * A = Einf/E0 - 1, tau the retardation time. GSL + libm only.
 *
 *   mu = (8 fN/(pi a)) \int_0^inf (J1(s)/s)^2 |Im 1/Er(s v0/a)| ds
 *
 * for a Hertz pressure of half width a = a0 = sqrt(4 fN R/(pi Er0)). With
 * fN/(pi a0) = Er0 a0/(4R), Im 1/Er(w) = (A/Er_inf) w tau/(1 + w^2 tau^2)
 * and Er_inf = (1+A) Er0, in terms of De = v0 tau/a0:
 *
 *   mu R/a0 = (2A/(1+A)) De \int_0^inf J1(s)^2 / (s (1 + De^2 s^2)) ds.
 *
 * Exact to first order in A (small loss); low speed mu R/a0 -> A De/(1+A). */
#ifndef VL_ORACLE_PERSSON_LINEAR_H
#define VL_ORACLE_PERSSON_LINEAR_H

/* mu R/a0 by quadrature: GSL Gauss-Kronrod on [0, 64 pi] cut at the
 * oscillation period, and the tail from the Hankel expansion of J1^2
 * (non-oscillating part by QAGIU, sin/cos parts by QAWF). Relative accuracy
 * ~1e-10 for De in [1e-6, 1e6]. Returns NAN for De <= 0, Einf/E0 < 1, or if
 * a GSL routine fails. */
double vl_oracle_persson_linear_mu(double deborah, double einf_over_e0);

/* Same quantity in closed form, \int_0^inf J1^2/(s(1+De^2 s^2)) ds
 * = 1/2 - I1(1/De) K1(1/De) (partial fractions and Gradshteyn-Ryzhik 6.535,
 * \int_0^inf x J_nu(bx)^2/(x^2+c^2) dx = I_nu(bc) K_nu(bc)). Loses about
 * log10(De^2) digits to cancellation for De >> 1 (1e-8 relative at De = 1e4).
 * Returns NAN on bad input. */
double vl_oracle_persson_linear_mu_closed(double deborah, double einf_over_e0);

#endif
