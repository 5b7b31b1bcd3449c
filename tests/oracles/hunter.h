/* Test oracle: exact steady rolling of a rigid smooth cylinder on a standard
 * linear viscoelastic half-space (Hunter 1961), in viscolube's convention.
 *
 * Independent of the library on purpose (GSL + libm only): validation tests
 * compare the numerical solver against it.
 *
 * Convention (docs/MODEL.md §1): cylinder frame, the rubber moves at +v0 along
 * x, material enters at x < 0. Plane strain, frictionless, smooth. Creep form
 *   1/E(w) = (1/Einf) [1 + A/(1 - i w tau)],  A = Einf/E0 - 1,
 * tau the RETARDATION time, reduced moduli Er = E/(1-nu^2). Scales: Hertz with
 * the relaxed modulus, a0 = sqrt(4 fN R/(pi Er0)), p0 = 2 fN/(pi a0); lengths
 * are in a0, pressures in p0, the gap in a0^2/R. The solution depends only on
 * the Deborah number De = v0 tau/a0 and on Einf/E0.
 *
 * Method (derivation in hunter.c): applying (1 + b d/dx), b = v0 tau, to the
 * slope of the surface displacement removes the memory integral; inside the
 * contact the finite Hilbert transform G = (2/pi) PV \int p(s)/(s-x) ds obeys
 *   (1+A) G + b G' = -Er_inf (x + b)/R,
 *   G/p0 = -2 (x/a0 + A De/(1+A)) + C exp(-(1+A)(x - c1)/b).
 * The pressure, bounded at both edges, is a Chebyshev-U series with modified
 * Bessel coefficients; load, solvability and the un-differentiated
 * (memory) equation at the inlet edge fix centre, half width and C, leaving
 * one scalar equation solved by Brent's method. */
#ifndef VL_ORACLE_HUNTER_H
#define VL_ORACLE_HUNTER_H

#include <stddef.h>

typedef struct {
  double mu_R_over_a0;   /* rolling friction mu*R/a0, mu = -(1/(R fN)) \int p x dx */
  double c1_over_a0;     /* inlet edge of the contact (x < c2) */
  double c2_over_a0;     /* outlet edge */
  double centre_over_a0; /* (c1 + c2)/2; < 0 (inlet side) at finite speed */
  double half_width_over_a0;
  double C;              /* amplitude at the inlet edge of the exponential part of G/p0 */
  double p_max_over_p0;  /* maximum pressure (found on the series) */
  double x_pmax_over_a0; /* its position */
  double deborah;        /* inputs, kept so the pressure can be evaluated later */
  double einf_over_e0;
  int iterations; /* Brent iterations of the scalar solve */
  int converged;  /* 1 when the memory condition was solved to tolerance */
} vl_oracle_hunter_solution;

/* Solves Hunter's problem for De = v0 tau/a0 > 0 and Einf/E0 > 1.
 * Valid and tested for De in [1e-4, 1e4] and Einf/E0 in [1.01, 100] (works
 * beyond, at higher cost for small De*E0/Einf: the Bessel series has about
 * 10 sqrt((Einf/E0)/De) terms). Returns 0 on success, -1 on bad input,
 * -2 if the scalar solve failed (out->converged = 0), -3 on allocation
 * failure. Thread-safe (no global state besides GSL's error handler, which
 * it switches off). */
int vl_oracle_hunter_solve(double deborah, double einf_over_e0, vl_oracle_hunter_solution *out);

/* Pressure series of a solution, precomputed for fast repeated evaluation. */
typedef struct vl_oracle_hunter_profile vl_oracle_hunter_profile;

/* Builds the profile of a converged solution; NULL on failure (allocation,
 * GSL, or s not converged). Free with vl_oracle_hunter_profile_free. */
vl_oracle_hunter_profile *vl_oracle_hunter_profile_new(const vl_oracle_hunter_solution *s);

/* p/p0 at x/a0 (0 outside the contact). O(number of Bessel terms). */
double vl_oracle_hunter_profile_pressure(const vl_oracle_hunter_profile *pr, double x_over_a0);

/* Frees a profile (NULL allowed). */
void vl_oracle_hunter_profile_free(vl_oracle_hunter_profile *pr);

/* p/p0 at x/a0 for a solution returned by vl_oracle_hunter_solve (0 outside
 * the contact). Rebuilds the profile on each call: use a profile or the
 * array form for many points. Returns NAN on failure. */
double vl_oracle_hunter_pressure(const vl_oracle_hunter_solution *s, double x_over_a0);

/* p/p0 at n points x_over_a0[i] into p_over_p0[i]. Returns 0, or -1 on
 * failure (allocation, GSL). */
int vl_oracle_hunter_pressure_array(const vl_oracle_hunter_solution *s, size_t n,
                                    const double *x_over_a0, double *p_over_p0);

/* Hertz line contact (docs/VALIDATION.md §1) with modulus Er0*ratio, in the a0/p0
 * scales: half width 1/sqrt(ratio), p_max sqrt(ratio). ratio = 1: relaxed,
 * ratio = Einf/E0: glassy. */
double vl_oracle_hertz_pressure(double ratio, double x_over_a0);

#endif
