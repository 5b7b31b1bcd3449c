/* A SUNLinearSolver for Jacobians with many rows that act on their own
 * unknown alone: the complementarity rows of a dry smooth contact's cells
 * out of contact (d FB/d u ~ FB_EPS/u^2 there). Those unknowns are solved
 * row by row and only the rest, the cells in contact and the rigid
 * approach, goes through LAPACK's LU: the active-set (reduced) Newton
 * system of issue 19, found from the Jacobian itself at every set-up.
 * Private to the library. */
#ifndef VL_LINSOL_REDUCED_H
#define VL_LINSOL_REDUCED_H

#include <stdbool.h>
#include <stddef.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

/* A row is solved on its own when every off-diagonal entry is at most this
 * fraction of its diagonal: the step then differs from the full Newton
 * step by about this much (relative), far below any Newton tolerance. */
#define VL_REDUCED_ROW_TOL 1e-13

/* Returns NULL on allocation failure. n is the system size. */
SUNLinearSolver vl_linsol_reduced_create(long n, SUNContext ctx);

/* The rows' kinds known in advance (a dry contact's active-set Newton):
 * while *on, rows i < n with du[i] == 0 are free (their off-diagonal
 * entries are exact zeros), the others coupled, without reading the
 * matrix for it. The arrays stay the caller's and must outlive S.
 * generation: changes whenever the rows' values may (the influence
 * matrix); while it stays, the block's LU is updated for the cells that
 * change set (Sherman-Morrison-Woodbury and bordering) instead of being
 * factorised again. */
void vl_linsol_reduced_set_rows(SUNLinearSolver S, const double *du, long n, const bool *on,
                                const size_t *generation);

/* The size of the last set-up's reduced system (n when no row was free). */
long vl_linsol_reduced_size(SUNLinearSolver S);

#endif
