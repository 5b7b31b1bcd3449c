/* Curve writers (output.h) on a failed point: every cell derived from the
 * solved state is empty in the CSV and null in the JSON, E_wH_pa, a_H_m and
 * Q included (a failed point's struct holds zeros, which would read as
 * values); the speed coordinates, converged = 0, the iterations and the
 * residual are written. A converged point next to it keeps its values. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "output_internal.h"
#include "viscolube/output.h"
#include "vl_test_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Two points: a converged one and a failed one (zeros, as vl_contact_solve
 * leaves it). */
static void two_points(vl_point p[2]) {
  memset(p, 0, 2 * sizeof *p);
  p[0].v0_m_s = 1e-3;
  p[0].converged = true;
  p[0].mu = 0.25;
  p[0].E_wH_pa = 4e6;
  p[0].a_H_m = 1e-3;
  p[0].Q = 0.5;
  p[0].iterations = 5;
  p[0].residual = 1e-9;
  p[0].eps_f_min = 1.0;
  p[1].v0_m_s = 1e-2;
  p[1].converged = false;
  p[1].iterations = 200;
  p[1].residual = 3.5;
}

/* The cell of column `name` in CSV line `line` (no quoting: the writer
 * never quotes), copied into out. */
static void csv_cell(const char *header, const char *line, const char *name, char *out,
                     size_t size) {
  size_t col = 0;
  const char *h = header;
  size_t len = strlen(name);
  for (;;) {
    if (!strncmp(h, name, len) && (h[len] == ',' || h[len] == '\n' || h[len] == '\0')) break;
    h = strchr(h, ',');
    assert_non_null(h);
    h++;
    col++;
  }
  const char *c = line;
  for (size_t k = 0; k < col; k++) {
    c = strchr(c, ',');
    assert_non_null(c);
    c++;
  }
  size_t n = strcspn(c, ",\n");
  assert_true(n < size);
  memcpy(out, c, n);
  out[n] = '\0';
}

static void test_csv_failed_point(void **state) {
  (void)state;
  vl_point p[2];
  two_points(p);
  vl_curve_meta meta = {1e-3, 0.0, 1e-3, NULL, 0.0, NULL};
  char *buf = NULL;
  size_t size = 0;
  FILE *f = open_memstream(&buf, &size);
  assert_non_null(f);
  vl_print_curve_csv(f, 2, p, &meta);
  fclose(f);
  char *header = buf, *row0 = strchr(header, '\n') + 1, *row1 = strchr(row0, '\n') + 1;
  char cell[64];
  static const char *const empty[] = {
      "mu",      "mu_Rc", "mu_Rf", "mu_Sc",        "mu_Sf",      "u_min_m",   "regime",
      "E_wH_pa", "a_H_m", "Q",     "x_centroid_m", "load_error", "eps_f_min", "error_estimate"};
  for (size_t k = 0; k < sizeof empty / sizeof empty[0]; k++) {
    csv_cell(header, row1, empty[k], cell, sizeof cell);
    if (cell[0]) fail_msg("failed point: column %s is '%s', not empty", empty[k], cell);
  }
  csv_cell(header, row1, "converged", cell, sizeof cell);
  assert_string_equal(cell, "0");
  csv_cell(header, row1, "iterations", cell, sizeof cell);
  assert_string_equal(cell, "200");
  csv_cell(header, row1, "residual", cell, sizeof cell);
  assert_string_equal(cell, "3.5");
  csv_cell(header, row1, "v0_eta_pa_m", cell, sizeof cell);
  assert_string_equal(cell, "1e-05");
  /* the converged point keeps its values */
  csv_cell(header, row0, "E_wH_pa", cell, sizeof cell);
  assert_string_equal(cell, "4000000");
  csv_cell(header, row0, "a_H_m", cell, sizeof cell);
  assert_string_equal(cell, "0.001");
  csv_cell(header, row0, "Q", cell, sizeof cell);
  assert_string_equal(cell, "0.5");
  free(buf);
}

static void test_json_failed_point(void **state) {
  (void)state;
  vl_point p[2];
  two_points(p);
  vl_curve_meta meta = {1e-3, 0.0, 1e-3, NULL, 0.0, NULL};
  char *buf = NULL;
  size_t size = 0;
  FILE *f = open_memstream(&buf, &size);
  assert_non_null(f);
  vl_json w;
  vl_json_init(&w, f, 10);
  vl_curve_json(&w, 2, p, &meta);
  fclose(f);
  char *second = strstr(buf, "\"v0_m_s\": 0.01");
  assert_non_null(second);
  assert_non_null(strstr(second, "\"E_wH_pa\": null"));
  assert_non_null(strstr(second, "\"a_H_m\": null"));
  assert_non_null(strstr(second, "\"Q\": null"));
  assert_non_null(strstr(second, "\"mu\": null"));
  assert_non_null(strstr(second, "\"converged\": false"));
  *second = '\0'; /* the first point alone */
  assert_non_null(strstr(buf, "\"E_wH_pa\": 4000000"));
  assert_non_null(strstr(buf, "\"Q\": 0.5"));
  free(buf);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_csv_failed_point),
      cmocka_unit_test(test_json_failed_point),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
