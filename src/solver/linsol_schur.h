/* A SUNLinearSolver for the rough wet contact's Jacobian that eliminates
 * the Reynolds rows first. Private to the library.
 *
 * Layout (contact_internal.h): unknowns [u_0..u_{n-1}, pf_0..pf_{n-1}, h0]. The
 * Reynolds rows (of..of+n-1) depend on pf only through the fluxes of their
 * two faces, so their pf block Bp is tridiagonal; it is an M-matrix (the
 * Poiseuille conductances and the Fischer-Burmeister weights are >= 0).
 * Eliminating pf leaves the (n+1)^2 Schur complement
 *     S = A - B Bp^{-1} C
 * (A: elasticity and load rows on u, h0; B: those rows on pf, dense; C:
 * the Reynolds rows on u, h0, banded), whose LU costs 1/8 of the full
 * (2n+1)^2 one. Bp^{-1} is applied by the Thomas algorithm without
 * pivoting, stable for an M-matrix; B Bp^{-1} is formed column by column,
 * C by its nonzeros only, so the set-up is O(n^2) plus the LU of S.
 *
 * The matrix is left untouched. Each solve checks its residual against the
 * full matrix (one O(n^2) product) and refines; if the block pivots are not
 * positive, or refinement does not reach 1e-10 of
 * the right-hand side in 3 steps, it falls back to the plain LU of the full
 * matrix (counted in vl_linsol_schur_fallbacks). */
#ifndef VL_LINSOL_SCHUR_H
#define VL_LINSOL_SCHUR_H

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

/* n: grid nodes; the system has 2n + 1 unknowns: u at 0..n-1, pf at
 * of..of+n-1, h0 at ih (of = n, ih = 2n in the contact). NULL on allocation
 * failure. */
SUNLinearSolver vl_linsol_schur_create(long n, long of, long ih, SUNContext ctx);

/* Declares that C's u column j (the Reynolds rows' dependence on u_j) is
 * zero outside Reynolds rows j-lower .. j+upper, so that each set-up reads
 * only that band of it instead of the whole column (an O(n^2) scan, a
 * quarter of the set-up's own work at n = 208). The h0 column is always read
 * whole. A nonzero outside the band would be left out of S: the residual
 * check of every solve then fails and the full LU takes over (correct, and
 * slow). Negative values: no band (the default). */
void vl_linsol_schur_set_band(SUNLinearSolver S, int lower, int upper);

/* Number of set-ups or solves that fell back to the full LU so far. */
long vl_linsol_schur_fallbacks(SUNLinearSolver S);

#endif
