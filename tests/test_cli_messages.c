/* The command line's messages as a new user meets them (issue 32): each
 * failure is one line that adds its context once (no "friction: friction:
 * [materials] compound: ..."), checked word for word on a few
 * representative failures (a bad compound, surface or fluid via friction
 * and compare, a bad name in a scene, a file that is not there, a
 * temperature out of a fluid's range, a study's task); a command given
 * without what it needs says so first, then shows its short usage (not the
 * whole help); friction says how it reached its point without "(1
 * continuation points)"; the console's ranges keep the digits that set a
 * value apart from its limit. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TRIPLE "--compound sbr-unfilled --surface paper-0.5um --fluid water"

/* The scratch database, created (from the shipped materials) so that every
 * message can name it. */
static int setup(void **state) {
  vl_test_setup_db(state);
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "fluid list");
  free(out);
  free(err);
  return rc;
}

/* No context is said twice in a row: "A: B: B: ..." or a command named
 * again after its own prefix ("viscolube friction: friction: ..."). */
static void check_no_repeat(const char *msg) {
  char seg[16][512];
  size_t n = 0;
  for (const char *p = msg; *p && n < 16; n++) {
    const char *e = strstr(p, ": ");
    size_t len = e ? (size_t)(e - p) : strcspn(p, "\n");
    snprintf(seg[n], sizeof seg[n], "%.*s", (int)len, p);
    p = e ? e + 2 : p + len;
  }
  for (size_t k = 1; k < n; k++)
    if (!strcmp(seg[k], seg[k - 1])) fail_msg("'%s' repeats '%s'", msg, seg[k]);
  const char *cmd = strchr(seg[0], ' '); /* "viscolube friction" -> "friction" */
  if (cmd && n > 1 && !strcmp(cmd + 1, seg[1])) fail_msg("'%s' names its command twice", msg);
}

/* `ARGS` (printf-style) fails with exit status code, nothing on stdout and
 * exactly the line want on stderr ("%s" in want standing for the scratch
 * database's path), the database untouched. */
static void expect_message(int code, const char *want, const char *fmt, ...) {
  char args[8192], line[8192];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(args, sizeof args, fmt, ap);
  va_end(ap);
  snprintf(line, sizeof line, want, vl_test_db);
  vl_test_expect_fail(code, line, NULL, "%s", args); /* one line, stdout empty, database kept */
  char *err = NULL;
  assert_int_equal(vl_test_run(NULL, &err, "%s", args), code);
  size_t len = strlen(err);
  assert_true(len > 0 && err[len - 1] == '\n');
  err[len - 1] = '\0';
  if (strcmp(err, line)) fail_msg("`%s`:\n  got  '%s'\n  want '%s'", args, err, line);
  check_no_repeat(err);
  free(err);
}

static void test_failures_say_their_context_once(void **state) {
  (void)state;
  /* friction: the names as the options gave them; the scene it builds in
   * code is nobody's file (was "friction: friction: [materials] compound: ") */
  expect_message(3, "viscolube friction: no compound named 'nope' in %s",
                 "friction --compound nope --surface paper-0.5um --fluid water --speed 0.01");
  expect_message(3, "viscolube friction: no surface named 'nope' in %s",
                 "friction --compound sbr-unfilled --surface nope --fluid water --speed 0.01");
  expect_message(
      3, "viscolube friction: no fluid named 'nope' in %s",
      "friction --compound sbr-unfilled --surface paper-0.5um --fluid nope --speed 0.01");
  expect_message(3, "viscolube compare: no surface named 'nope' in %s",
                 "compare --compounds sbr-unfilled --surface nope --fluid water --out %s/c",
                 vl_test_dir);
  /* the option once, the temperature once (in the fluid's message) */
  expect_message(2,
                 "viscolube friction: --temperature: fluid 'water': 200 C lies outside the range "
                 "[0, 100] C of its vogel viscosity law (not extrapolated)",
                 "friction " TRIPLE " --speed 0.01 --temperature 200");
  /* a scene file: where in it, once */
  const char *scene = vl_test_scratch("bad.ini", "[materials]\ncompound = nope\nsurface = "
                                                 "paper-0.5um\nfluid = water\n"
                                                 "[contact]\nradius_m = 0.001\n"
                                                 "load_n_per_m = 117\n"
                                                 "[sweep]\nquantity = v0\nfrom = 1e-3\nto = 1\n"
                                                 "points = 3\n"
                                                 "[effects]\nviscoelastic = on\n");
  char want[4400];
  snprintf(want, sizeof want,
           "viscolube run: %s: [materials] compound: no compound named 'nope' in %%s", scene);
  expect_message(3, want, "run %s --out %s/r", scene, vl_test_dir);
  /* a file that is not there */
  const char *absent = vl_test_scratch("absent.csv", NULL);
  snprintf(want, sizeof want, "viscolube compound add: %s: cannot open: No such file or directory",
           absent);
  expect_message(6, want, "compound add x --measured %s", absent);
  snprintf(want, sizeof want, "viscolube surface add: %s: cannot open: No such file or directory",
           absent);
  expect_message(6, want, "surface add x --psd %s", absent);
  /* pair calibrate: the measured file is fine; the compound is not (the
   * file's name no longer stands before the compound's message) */
  const char *curve = vl_test_scratch("curve.csv", "v [m/s],mu\n1e-4,0.5\n1e-3,0.4\n1e-2,0.3\n");
  expect_message(3, "viscolube pair: no compound named 'nope' in %s",
                 "pair calibrate --compound nope --surface paper-0.5um --fluid water "
                 "--measured %s",
                 curve);
  /* a study's task: the study's line, then the fluid's message (was the
   * study's path twice: "ST:13: [study] ... (task 0): ST: [effects] ...") */
  const char *study = vl_test_scratch("hot.ini", "[study]\ncompounds = sbr-unfilled\n"
                                                 "surfaces = paper-0.5um\nfluids = water\n"
                                                 "loads_n_per_m = 117\nradii_m = 0.001\n"
                                                 "temperatures_c = 150\n"
                                                 "[sweep]\nquantity = v0\nfrom = 1e-3\nto = 1\n"
                                                 "points = 3\n"
                                                 "[effects]\nviscoelastic = on\nroughness = on\n"
                                                 "fluid = on\n");
  snprintf(want, sizeof want,
           "viscolube study: %s:7: [study] temperatures_c (task 0): fluid 'water': 150 C lies "
           "outside the range [0, 100] C of its vogel viscosity law (not extrapolated)",
           study);
  expect_message(2, want, "study %s --out %s/s", study, vl_test_dir);
}

/* `ARGS` without what it needs: exit 2, nothing on stdout; on stderr the
 * message first, then the short usage (starting "usage: "), then where
 * the full help is, in at most max_lines lines. */
static void expect_usage(const char *args, const char *first, const char *see, int max_lines) {
  char *out = NULL, *err = NULL;
  assert_int_equal(vl_test_run(&out, &err, "%s", args), 2);
  assert_string_equal(out, "");
  size_t first_len = strlen(first);
  if (strncmp(err, first, first_len) || err[first_len] != '\n')
    fail_msg("`%s`: stderr does not start with '%s': %s", args, first, err);
  if (strncmp(err + first_len + 1, "usage: ", 7))
    fail_msg("`%s`: no short usage after the message: %s", args, err);
  int lines = 0;
  for (const char *c = err; *c; c++)
    lines += *c == '\n';
  if (lines > max_lines) fail_msg("`%s`: %d lines, a wall of help: %s", args, lines, err);
  char tail[128];
  snprintf(tail, sizeof tail, "\nsee `%s`\n", see);
  size_t len = strlen(err), tl = strlen(tail);
  if (len < tl || strcmp(err + len - tl, tail))
    fail_msg("`%s`: does not end '%s': %s", args, see, err);
  free(out);
  free(err);
}

static void test_usage_errors_come_first(void **state) {
  (void)state;
  expect_usage("",
               "viscolube: missing NOUN (compound, surface, fluid, pair, run, study, friction, "
               "compare or flattening)",
               "viscolube --help", 5);
  expect_usage("run", "viscolube run: missing SCENE", "viscolube run --help", 4);
  expect_usage("compound", "viscolube compound: missing VERB (list, show, add or remove)",
               "viscolube compound --help", 4);
  expect_usage("surface",
               "viscolube surface: missing VERB (list, show, add, flow-factors or remove)",
               "viscolube surface --help", 4);
  expect_usage("fluid", "viscolube fluid: missing VERB (list, show, add or remove)",
               "viscolube fluid --help", 4);
  expect_usage("pair", "viscolube pair: missing VERB (list, show, add, remove or calibrate)",
               "viscolube pair --help", 13);
  expect_usage("study", "viscolube study: missing STUDY", "viscolube study --help", 5);
  expect_usage("study x.ini", "viscolube study: missing --out DIR", "viscolube study --help", 5);
  /* the full help is still there when asked for, on stdout */
  char *out = NULL, *err = NULL;
  assert_int_equal(vl_test_run(&out, &err, "run --help"), 0);
  assert_non_null(strstr(out, "curve.csv"));
  assert_string_equal(err, "");
  free(out), free(err);
}

/* friction says how its point was reached: a direct solve, or
 * continuation over N points (was "(1 continuation points)"), and "the
 * point" rather than "1 of 1 points". */
static void test_friction_wording(void **state) {
  (void)state;
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err,
                       "friction --compound model-rubber --surface paper-3um --fluid model-1e-4 "
                       "--speed 0.01 --radius 0.01 --load 1000 --grid 128");
  assert_int_equal(rc, 8); /* coarse: above its 1 % target, and says so */
  assert_non_null(strstr(out, " Newton iterations, residual "));
  assert_true(strstr(out, "(a direct solve)\n") || strstr(out, "(continuation from the boundary "
                                                               "regime over "));
  assert_null(strstr(out, "continuation points"));
  /* the regime label says what it means, next to u_min/h_rms (1.86 here) */
  assert_non_null(strstr(out, " h_rms)\n  solid contact carries 100.0 % of the load; regime: "
                              "boundary (the fluid carries under 5 % of the load and u_min < 3 "
                              "h_rms)\n"));
  assert_non_null(strstr(err, "viscolube friction: the point is not known to its error target"));
  assert_null(strstr(err, "1 of 1 points"));
  free(out), free(err);
}

/* The console sums a kind of warning up over the points as a range; its
 * ends keep the digits the points wrote, so a value set apart from its
 * limit stays apart ("contact half-width 0.202..0.21 R > 0.2 R", was
 * "0.2..0.21 R > 0.2 R"): the shipped fig03-rough-10um scene, whose
 * slowest points exceed 0.2 R by a hair. The range's low end must be the
 * smallest value as curve.csv writes it, whatever the solver gives. */
static void test_console_range_digits(void **state) {
  (void)state;
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "run %s --out %s/f10",
                       vl_test_source_path("cases/fig03-rough-10um.ini"), vl_test_dir);
  assert_true(rc == 0 || rc == 8);
  char *csv = vl_test_read_file(vl_test_scratch("f10/curve.csv", NULL));
  assert_non_null(csv);
  const char *key = "contact half-width ";
  double lo = INFINITY;
  char lo_text[32] = "";
  for (const char *p = strstr(csv, key); p; p = strstr(p + 1, key)) {
    const char *v = p + strlen(key);
    size_t len = strcspn(v, " ");
    double x = strtod(v, NULL);
    if (x < lo) lo = x, snprintf(lo_text, sizeof lo_text, "%.*s", (int)len, v);
  }
  if (!lo_text[0]) fail_msg("no half-width warning in curve.csv: the scene no longer tests this");
  char want[96];
  snprintf(want, sizeof want, "warning: contact half-width %s..", lo_text);
  printf("  smallest in curve.csv: %s; console: %.120s\n", lo_text, strstr(err, key));
  if (!strstr(err, want)) fail_msg("console lacks '%s': %s", want, err);
  assert_string_not_equal(lo_text, "0.2"); /* apart from its limit */
  free(csv), free(out), free(err);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_failures_say_their_context_once, setup),
      cmocka_unit_test_setup(test_usage_errors_come_first, vl_test_setup_db),
      cmocka_unit_test_setup(test_friction_wording, setup),
      cmocka_unit_test_setup(test_console_range_digits, setup),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
