/* Inputs that look valid to a parser but are not, found by fuzzing the
 * readers (tests/fuzz): each case runs the command-line program and asserts
 * the refusal, a one-line message on stderr without control characters
 * (messages quote file contents and go to a terminal, where an escape
 * sequence or a carriage return could rewrite what the user sees), and the
 * database unchanged. Regression tests for the fixes; the fuzz corpus
 * replays the raw inputs too. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <stdlib.h>
#include <string.h>

/* One line, no control byte but its final newline. */
static void assert_printable_line(const char *err) {
  assert_non_null(err);
  size_t n = strlen(err);
  assert_true(n > 1 && err[n - 1] == '\n');
  for (size_t i = 0; i + 1 < n; i++)
    if ((unsigned char)err[i] < 0x20 || err[i] == 0x7f)
      fail_msg("control byte 0x%02x at %zu in: %s", (unsigned)(unsigned char)err[i], i, err);
}

static int setup(void **state) {
  vl_test_setup_db(state);
  /* the database exists, so that every refusal can be checked to leave it */
  assert_int_equal(vl_test_run(NULL, NULL, "fluid list"), 0);
  return 0;
}

/* Every A_i is finite and >= 0, but their sum overflows: E0 = Einf/(1 +
 * sum A) would be 0 Pa, and with it the Hertz width and pressure. The CSV
 * is well formed, so the database's check refuses it. */
static void test_prony_sum_overflows(void **state) {
  (void)state;
  const char *f = vl_test_scratch("huge.csv", "A,tau_s\n1e308,1\n1e308,2\n");
  vl_test_expect_fail(2, "relaxed modulus", "sum A = inf",
                      "compound add huge --prony %s --e-inf 1e7 --nu 0.5", f);
  /* one term short of overflow is a real (if odd) compound: E0 = 1e-301 Pa
   * is still a positive normal number */
  f = vl_test_scratch("big.csv", "A,tau_s\n1e308,1\n");
  assert_int_equal(vl_test_run(NULL, NULL, "compound add big --prony %s --e-inf 1e7 --nu 0.5", f),
                   0);
}

/* A scene value with an escape sequence and a carriage return: quoted in
 * the message with '?' for each control byte. */
static void test_scene_message_printable(void **state) {
  (void)state;
  const char *scene = vl_test_scratch("s.ini", "[contact]\nradius_m = 1\x1b[2J\rx\n");
  char *err = NULL;
  assert_int_equal(vl_test_run(NULL, &err, "run %s", scene), 2);
  assert_printable_line(err);
  assert_non_null(strstr(err, "radius_m"));
  assert_non_null(strstr(err, "1?[2J?x"));
  free(err);
}

/* The same in a DMA file's header (an unknown column name is quoted). */
static void test_dma_message_printable(void **state) {
  (void)state;
  const char *f =
      vl_test_scratch("d.csv", "f,E\x1b]0;title\x07,E''\nHz,MPa,MPa\n1,2,0.1\n10,3,0.2\n");
  char *err = NULL;
  assert_int_equal(vl_test_run(NULL, &err, "compound add d --measured %s --tref 20", f), 2);
  assert_printable_line(err);
  assert_non_null(strstr(err, "E?]0;title?"));
  free(err);
}

/* Numeric options of friction/compare follow the same strict syntax as
 * every other option and CSV cell: no hex floats, no infinities. */
static void test_query_numbers_strict(void **state) {
  (void)state;
  const char *base = "friction --compound model-rubber --surface paper-1um --fluid water";
  vl_test_expect_fail(2, "--load", "0x10", "%s --speed 1e-2 --load 0x10", base);
  vl_test_expect_fail(2, "--speed", "inf", "%s --speed inf", base);
  vl_test_expect_fail(2, "--radius", "1e-400", "%s --speed 1 --radius 1e-400", base);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_prony_sum_overflows, setup),
      cmocka_unit_test_setup(test_scene_message_printable, setup),
      cmocka_unit_test_setup(test_dma_message_printable, setup),
      cmocka_unit_test_setup(test_query_numbers_strict, setup),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
