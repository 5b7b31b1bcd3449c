/* viscolube: non-negative linear least squares.
 *
 *   minimise ||A x - b||_2  subject to  x >= 0
 *
 * by the active-set algorithm of Lawson & Hanson ("Solving Least Squares
 * Problems", 1974, chapter 23, algorithm NNLS), with each unconstrained
 * sub-problem solved by GSL's Householder QR. GSL has no NNLS of its own.
 * Used by the Prony fit (prony_fit.h), where the creep form of docs/MODEL.md
 * section 2 is linear in its non-negative coefficients. */
#ifndef VISCOLUBE_NNLS_H
#define VISCOLUBE_NNLS_H

#include <stddef.h>

#include "viscolube/status.h"

/* Solves the problem above for the m x n matrix a (row-major, a[i*n + j])
 * and the m-vector b. Any m, n >= 1 (m < n allowed). Columns are scaled to
 * unit norm internally, so the result does not depend on their units; an
 * all-zero column gets x_j = 0.
 *
 * On VL_OK, x (n values, caller-owned) holds the solution, every x_j >= 0,
 * and *residual_norm (may be NULL) = ||A x - b||_2. The optimality
 * conditions hold to rounding: w = A^T (b - A x) satisfies w_j <= tol for
 * x_j = 0 and |w_j| <= tol for x_j > 0.
 *
 * Errors: VL_EINPUT (a non-finite entry, m or n zero), VL_ENOMEM,
 * VL_ENOCONV (the iteration limit 3n + 30 outer steps was reached, which
 * the algorithm's finite termination makes a sign of severe
 * ill-conditioning), VL_EINTERNAL (a GSL failure). On error x is zeroed. */
vl_status vl_nnls_solve(size_t m, size_t n, const double *a, const double *b, double *x,
                        double *residual_norm, vl_error *err);

#endif
