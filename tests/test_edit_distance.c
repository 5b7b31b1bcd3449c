/* The edit distance behind every "did you mean" hint (include/viscolube/edit_distance.h,
 * private: included by path), against distances worked out by hand. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "viscolube/edit_distance.h"

static size_t d(const char *a, const char *b, bool t) {
  return vl_edit_distance(a, strlen(a), b, strlen(b), t);
}

static void test_known_distances(void **state) {
  (void)state;
  assert_int_equal(d("kitten", "sitting", false), 3); /* k->s, e->i, +g */
  assert_int_equal(d("", "abc", false), 3);
  assert_int_equal(d("abc", "", true), 3);
  assert_int_equal(d("same", "same", false), 0);
  assert_int_equal(d("temprature", "temperature", true), 1);
  /* a swap of neighbours: two edits, or one with transpositions */
  assert_int_equal(d("gird", "grid", false), 2);
  assert_int_equal(d("gird", "grid", true), 1);
  assert_int_equal(d("ca", "abc", true), 3); /* OSA: no edit of a swapped pair */
  /* a prefix of the first string (spans of a CSV line) */
  assert_int_equal(vl_edit_distance("E_storX", 6, "E_stor", 6, false), 0);
}

static void test_too_long_is_far(void **state) {
  (void)state;
  char long_name[VL_EDIT_MAX + 2];
  memset(long_name, 'a', sizeof long_name - 1);
  long_name[sizeof long_name - 1] = '\0';
  assert_true(d(long_name, "a", false) == SIZE_MAX);
  long_name[VL_EDIT_MAX] = '\0'; /* exactly the limit: computed */
  assert_int_equal(d(long_name, long_name, true), 0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_known_distances),
      cmocka_unit_test(test_too_long_is_far),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
