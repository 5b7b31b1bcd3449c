/* A SUNLinearSolver over LAPACK dgetrf/dgetrs acting on a SUNDIALS dense
 * matrix (column-major, contiguous). SUNDIALS 6.4 on Debian ships no LAPACK
 * linear solver, and its own dense LU is 20-50x slower than an optimised
 * dgetrf at the sizes we use (n = 500...2000). Private to the library. */
#ifndef VL_LINSOL_LAPACK_H
#define VL_LINSOL_LAPACK_H

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

/* Returns NULL on allocation failure. n is the system size. */
SUNLinearSolver vl_linsol_lapack_create(long n, SUNContext ctx);

#endif
