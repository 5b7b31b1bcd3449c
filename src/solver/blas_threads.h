/* One BLAS thread for every solve: OpenBLAS splits a factorisation's sums
 * over its threads, so the rounding (and, near a fold of the solution, the
 * Newton path: residuals differed at every point of fig05 on paper-0.1um
 * and iterations at 3 of 62) would depend on OPENBLAS_NUM_THREADS. The
 * systems are at most a few thousand unknowns; the parallelism of the
 * program is across curves (viscolube study --jobs, MPI). Private to the
 * library. */
#ifndef VL_BLAS_THREADS_H
#define VL_BLAS_THREADS_H

/* Sets OpenBLAS to one thread; returns the count it had (0 when the BLAS
 * is not OpenBLAS: the reference BLAS has no threads). */
int vl_blas_pin_one_thread(void);

/* Gives OpenBLAS back the count vl_blas_pin_one_thread returned (nothing
 * for 0 or 1): a program around the library (numpy in Python) keeps its
 * own setting. */
void vl_blas_restore_threads(int count);

#endif
