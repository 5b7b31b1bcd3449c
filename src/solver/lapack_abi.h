/* The BLAS and LAPACK routines the solver calls, by their Fortran ABI
 * (Debian's libblas/liblapack alternatives: OpenBLAS or the reference
 * implementation). Private to the library. */
#ifndef VL_LAPACK_ABI_H
#define VL_LAPACK_ABI_H

#include <stddef.h>

/* LU with partial pivoting, and its solve. */
extern void dgetrf_(const int *m, const int *n, double *a, const int *lda, int *ipiv, int *info);
extern void dgetrs_(const char *trans, const int *n, const int *nrhs, const double *a,
                    const int *lda, const int *ipiv, double *b, const int *ldb, int *info,
                    size_t trans_len);

/* The same in single precision (a first factorisation refined in double:
 * linsol_reduced.c). */
extern void sgetrf_(const int *m, const int *n, float *a, const int *lda, int *ipiv, int *info);
extern void sgetrs_(const char *trans, const int *n, const int *nrhs, const float *a,
                    const int *lda, const int *ipiv, float *b, const int *ldb, int *info,
                    size_t trans_len);

/* y = alpha op(A) x + beta y. */
extern void dgemv_(const char *trans, const int *m, const int *n, const double *alpha,
                   const double *a, const int *lda, const double *x, const int *incx,
                   const double *beta, double *y, const int *incy, size_t trans_len);

/* C = alpha op(A) op(B) + beta C. */
extern void dgemm_(const char *transa, const char *transb, const int *m, const int *n, const int *k,
                   const double *alpha, const double *a, const int *lda, const double *b,
                   const int *ldb, const double *beta, double *c, const int *ldc, size_t transa_len,
                   size_t transb_len);

#endif
