/* The solver's results do not depend on OpenBLAS's thread count (issue
 * 19: two points flipped between converged and failed with it). fig05 on
 * the fine paper-0.1um surface at its default numerics, where two BLAS
 * threads changed the residual of 56 of 62 points and the iterations of
 * 3 before the solves were pinned to one thread (src/solver/blas_threads.h):
 * the same sweep under 1 and 2 threads must agree bit for bit, and the
 * caller's thread count must be given back. The BLAS must be OpenBLAS
 * (scripts/install-deps.sh installs libopenblas-dev, Debian's libblas.so.3
 * then); any other fails the test, saying so. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "sweep_internal.h"
#include "viscolube/contact.h"
#include "viscolube/sweep.h"
#include "vl_test_scenes.h"
#include "vl_test_util.h"

extern void openblas_set_num_threads(int n) __attribute__((weak));
extern int openblas_get_num_threads(void) __attribute__((weak));

enum { NP = 4 };

static void sweep(const vl_persson *tab, int threads, vl_point *pts) {
  openblas_set_num_threads(threads);
  vl_contact_config cfg;
  vl_test_fig05_config(&cfg, tab, 1e-4, 0, -3.0);
  vl_contact_numerics_defaults(true, true, &cfg);
  double v0[NP];
  for (int i = 0; i < NP; i++)
    v0[i] = 1e-4 * pow(10.0, 0.5 * (double)i); /* the fast half of the curve */
  vl_contact *c;
  vl_error err;
  assert_int_equal(vl_contact_create(&cfg, &c, &err), VL_OK);
  vl_sweep_stats st;
  assert_int_equal(vl_sweep_run(c, NP, v0, NULL, pts, NULL, NULL, &st, &err), VL_OK);
  vl_contact_free(c);
  assert_int_equal(openblas_get_num_threads(), threads); /* given back */
}

static void test_same_bits_at_any_thread_count(void **state) {
  (void)state;
  if (!openblas_set_num_threads || !openblas_get_num_threads)
    fail_msg(
        "the BLAS is not OpenBLAS (update-alternatives --display libblas.so.3-x86_64-linux-gnu)");
  vl_psd psd;
  vl_persson *tab = vl_test_paper_surface(1e-7, &psd);
  vl_point one[NP], two[NP];
  sweep(tab, 1, one);
  sweep(tab, 2, two);
  for (int i = 0; i < NP; i++) {
    assert_int_equal(one[i].converged, two[i].converged);
    assert_int_equal(one[i].iterations, two[i].iterations);
    assert_memory_equal(&one[i].mu, &two[i].mu, sizeof one[i].mu);
    assert_memory_equal(&one[i].residual, &two[i].residual, sizeof one[i].residual);
    assert_memory_equal(&one[i].u_min_m, &two[i].u_min_m, sizeof one[i].u_min_m);
  }
  vl_persson_free(tab);
  vl_psd_free(&psd);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_same_bits_at_any_thread_count),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
