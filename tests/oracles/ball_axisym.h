/* Test oracle: a dry rough elastic ball (a rigid smooth sphere pressed on
 * an elastic half-space whose surface is rough) in mean-field contact: in
 * every ring the contact pressure is a given function of the mean
 * separation, p = law(u) (Persson's, from the caller), with
 *   u(r) = h0 + r^2/(2R) + w(r),
 *   w(r) = (4/(pi Er)) \int_0^inf p(s) s/(r + s) K(2 sqrt(r s)/(r + s)) ds
 * (the axisymmetric Boussinesq displacement, Johnson, Contact Mechanics,
 * 3.10; K the complete elliptic integral of the first kind, modulus k), and
 * the load 2 pi \int p r dr = W. Independent of the library's point
 * contact on purpose: rings in polar coordinates (not cells), their
 * influence by adaptive quadrature of the elliptic kernel (GSL), Newton
 * with LAPACK's dgesv. SI units. */
#ifndef VL_ORACLE_BALL_AXISYM_H
#define VL_ORACLE_BALL_AXISYM_H

#include <stddef.h>

/* The contact law: the pressure (Pa) at mean separation u (m), and dp/du. */
typedef double (*vl_oracle_law)(void *user, double u_m, double *dpdu);

typedef struct {
  double radius_m, load_n, er_pa; /* ball, load, reduced modulus E/(1 - nu^2) */
  double r_max_m;                 /* outer radius of the rings (p = 0 beyond) */
  size_t rings;                   /* equal widths */
  vl_oracle_law law;
  void *user;
} vl_oracle_axisym_problem;

typedef struct {
  double h0_m;     /* rigid approach (u at r = 0 minus w(0)) */
  double u0_m;     /* separation at the centre (the first ring's node) */
  double p_max_pa; /* largest ring pressure */
  int iterations;
} vl_oracle_axisym_solution;

/* Solves; p_pa (rings values, may be NULL) gets the ring pressures, r_m
 * (may be NULL) the ring nodes. 0 on success, -1 bad input, -2 no
 * convergence, -3 allocation or LAPACK failure. */
int vl_oracle_axisym_solve(const vl_oracle_axisym_problem *pb, vl_oracle_axisym_solution *sol,
                           double *p_pa, double *r_m);

#endif
