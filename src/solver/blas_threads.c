/* OpenBLAS's thread count around the solves (blas_threads.h). */
#include "blas_threads.h"

/* OpenBLAS's own entry points, weak: the reference BLAS (the other
 * libblas.so.3 alternative on Debian) has neither, and then they are NULL. */
extern void openblas_set_num_threads(int n) __attribute__((weak));
extern int openblas_get_num_threads(void) __attribute__((weak));

int vl_blas_pin_one_thread(void) {
  if (!openblas_set_num_threads || !openblas_get_num_threads) return 0;
  int n = openblas_get_num_threads();
  if (n > 1) openblas_set_num_threads(1);
  return n;
}

void vl_blas_restore_threads(int count) {
  if (count > 1 && openblas_set_num_threads) openblas_set_num_threads(count);
}
