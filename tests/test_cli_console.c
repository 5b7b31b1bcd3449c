/* What the program says on the console, end to end (vl_test_run): the
 * model-validity warnings after the table of run, compare and friction
 * (one line per kind with the points it applies to; none with --json,
 * whose rows carry them, or with --quiet, global or per command), the
 * points that did not converge (speed, iterations, residual) and the exit
 * status, --version, the exit statuses in --help; material names that
 * would leave an output folder ('.', '..', '/', '\') refused before
 * anything is written; an unusable --out refused before anything is
 * computed. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* A small rough wet scene (the fig05 contact on a short domain, 5 speeds):
 * every point warns "rms slope 9.9 > 1" (paper-3um). tolerance: the
 * Newton tolerance; 1e-16 cannot be met, so every point fails. */
static const char *rough_scene(const char *name, const char *tolerance, const char *fluids) {
  char text[2048];
  snprintf(text, sizeof text,
           "[materials]\ncompound = model-rubber\nsurface = paper-3um\nfluid = %s\n\n"
           "[contact]\nradius_m = 0.01\nload_n_per_m = 1000\nsigma_s_pa = 1e6\n\n"
           "[sweep]\nquantity = v0_eta\nfrom = 1e-10\nto = 1e-6\npoints = 5\n\n"
           "[effects]\nviscoelastic = on\nroughness = on\nfluid = on\nsolid_shear = on\n"
           "flow_factors = patir-cheng\n\n"
           "[numerics]\ngrid = 128\ndomain_a0 = -8, 1.6\ntolerance = %s\n",
           fluids, tolerance);
  return vl_test_scratch(name, text);
}

static int exists(const char *path) {
  struct stat sb;
  return stat(path, &sb) == 0;
}

/* The number of lines of s that start with prefix (s may be NULL). */
static size_t lines_starting(const char *s, const char *prefix) {
  size_t n = 0, len = strlen(prefix);
  for (const char *l = s; l && *l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : l + strlen(l))
    n += strncmp(l, prefix, len) == 0;
  return n;
}

static size_t count_lines(const char *s) {
  size_t n = 0;
  for (; s && *s; s++)
    n += *s == '\n';
  return n;
}

/* ---- warnings --------------------------------------------------------- */

static void test_run_warnings(void **state) {
  (void)state;
  const char *scene = rough_scene("rough.ini", "1e-6", "model-1e-4");
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "run %s --out %s/o", scene, vl_test_dir);
  if (rc != 0) fail_msg("run: exit %d: %s", rc, err);
  printf("run, stderr:\n%s", err);
  /* one line for the kind, with every point, its speeds, after the table */
  if (!strstr(err, "warning: rms slope 9.9 > 1 (small-slope contact theory) \u2014 points 1-5 "
                   "of 5 (v0 = 1e-06..0.01 m/s)\n"))
    fail_msg("no rms-slope line: %s", err);
  assert_int_equal(lines_starting(err, "warning: "), count_lines(err));
  assert_int_equal(lines_starting(err, "warning: rms slope"), 1);
  free(out), free(err);
  /* --quiet per command, and as a global option */
  assert_int_equal(vl_test_run(&out, &err, "run %s --out %s/o --quiet", scene, vl_test_dir), 0);
  assert_string_equal(err, "");
  assert_non_null(strstr(out, "5 converged"));
  free(out), free(err);
  assert_int_equal(vl_test_run(&out, &err, "--quiet run %s --out %s/o", scene, vl_test_dir), 0);
  assert_string_equal(err, "");
  free(out), free(err);
  /* --json: the rows carry them, stderr stays empty */
  assert_int_equal(vl_test_run(&out, &err, "run %s --out %s/o --json", scene, vl_test_dir), 0);
  assert_string_equal(err, "");
  assert_true(vl_test_json_valid(out));
  assert_non_null(strstr(out, "rms slope 9.9 > 1"));
  free(out), free(err);
}

/* A multi-fluid scene: each curve's warnings are labelled with its fluid. */
static void test_run_warnings_per_fluid(void **state) {
  (void)state;
  const char *scene = rough_scene("two.ini", "1e-6", "model-1e-4, water");
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "run %s --out %s/o", scene, vl_test_dir);
  if (rc != 0) fail_msg("run: exit %d: %s", rc, err);
  assert_int_equal(lines_starting(err, "warning: model-1e-4: rms slope 9.9"), 1);
  assert_int_equal(lines_starting(err, "warning: water: rms slope 9.9"), 1);
  free(out), free(err);
}

/* The example of the tracker: friction at 1 cm/s warned only in --json. */
static void test_friction_warnings(void **state) {
  (void)state;
  const char *args = "friction --compound sbr-unfilled --surface paper-0.5um --fluid water "
                     "--speed 1e-2";
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "%s", args);
  if (rc != 0) fail_msg("friction: exit %d: %s", rc, err);
  printf("friction, stderr:\n%s", err);
  assert_string_equal(err, "warning: rms slope 1.6 > 1 (small-slope contact theory)\n"
                           "warning: a_H = 0.36 lambda0 < 5 (contact too small for mean-field "
                           "roughness)\n");
  assert_non_null(strstr(out, "mu      ="));
  free(out), free(err);
  assert_int_equal(vl_test_run(&out, &err, "%s --quiet", args), 0);
  assert_string_equal(err, "");
  free(out), free(err);
  assert_int_equal(vl_test_run(&out, &err, "%s --json", args), 0);
  assert_string_equal(err, "");
  assert_non_null(strstr(out, "\"warnings\": \"rms slope 1.6 > 1"));
  free(out), free(err);
}

static void test_compare_warnings(void **state) {
  (void)state;
  char *out = NULL, *err = NULL;
  const char *args = "compare --compounds sbr-unfilled,sbr-filled --surface paper-0.5um "
                     "--fluid water --points 3 --grid 512 --target-error 0.5";
  int rc = vl_test_run(&out, &err, "%s --out %s/c", args, vl_test_dir);
  if (rc != 0) fail_msg("compare: exit %d: %s", rc, err);
  printf("compare, stderr:\n%s", err);
  assert_int_equal(lines_starting(err, "warning: sbr-unfilled: rms slope 1.6 > 1 (small-slope "
                                       "contact theory) \u2014 points 1-3 of 3"),
                   1);
  assert_int_equal(lines_starting(err, "warning: sbr-filled: a_H = 0.21..3.7 lambda0 < 5"), 1);
  /* the progress lines and the warnings, nothing else */
  assert_int_equal(lines_starting(err, "warning: ") + lines_starting(err, "compare: "),
                   count_lines(err));
  free(out), free(err);
  assert_int_equal(vl_test_run(&out, &err, "--quiet %s --out %s/c", args, vl_test_dir), 0);
  assert_string_equal(err, "");
  free(out), free(err);
}

/* Points that did not converge: listed after the table with speed,
 * iterations and residual; exit status 7, as --help says. */
static void test_failed_points(void **state) {
  (void)state;
  const char *scene = rough_scene("fail.ini", "1e-16", "model-1e-4");
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "run %s --out %s/f --quiet", scene, vl_test_dir);
  printf("failed points, stderr:\n%s", err);
  assert_int_equal(rc, 7);
  char first[1400];
  snprintf(first, sizeof first,
           "viscolube run: 5 of 5 points did not converge (exit status 7); written with "
           "converged = 0 in %s/f/curve.csv\n",
           vl_test_dir);
  assert_non_null(strstr(err, first));
  assert_int_equal(lines_starting(err, "  point "), 5);
  assert_non_null(strstr(err, "  point 1: v0 = 1e-06 m/s, "));
  assert_non_null(strstr(err, " iterations, residual "));
  assert_int_equal(count_lines(err), 6);
  free(out), free(err);
  /* --help states the status */
  assert_int_equal(vl_test_run(&out, &err, "--help"), 0);
  assert_non_null(strstr(out, "exit status:"));
  assert_non_null(strstr(out, "  7   some points did not converge"));
  assert_non_null(strstr(out, "  6   a file or folder could not be read or written"));
  assert_non_null(strstr(out, "--quiet"));
  assert_non_null(strstr(out, "--version"));
  free(out), free(err);
}

static void test_version(void **state) {
  (void)state;
  char *out = NULL, *err = NULL;
  assert_int_equal(vl_test_run(&out, &err, "--version"), 0);
  unsigned a, b, c;
  char source[128] = "";
  if (sscanf(out, "viscolube %u.%u.%u (source %127[^)])", &a, &b, &c, source) != 4 || !source[0])
    fail_msg("--version: '%s'", out);
  printf("--version: %s", out);
  assert_string_equal(err, "");
  assert_false(exists(vl_test_db)); /* opens no database */
  free(out), free(err);
}

/* ---- names ------------------------------------------------------------ */

static void test_names_refused(void **state) {
  (void)state;
  char *out = NULL, *err = NULL;
  assert_int_equal(vl_test_run(&out, &err, "fluid list"), 0); /* the database exists */
  free(out), free(err);
  const char *prony = vl_test_scratch("p.csv", "A,tau_s\n9,0.1\n");
  const char *psd = vl_test_scratch("psd.csv", "q_per_m,C_m4\n1e3,1e-20\n1e4,1e-23\n1e5,1e-26\n");
  static const char *const bad[] = {".", "..", "a/b", "../x", "a\\\\b", "''"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
    const char *needle = i < 2 ? "folder" : i < 5 ? "path separator" : "empty";
    vl_test_expect_fail(2, needle, NULL, "compound add %s --prony %s --e-inf 36e6 --nu 0.5", bad[i],
                        prony);
    vl_test_expect_fail(2, needle, NULL, "surface add %s --psd %s", bad[i], psd);
    vl_test_expect_fail(2, needle, NULL, "fluid add %s --viscosity 0.1", bad[i]);
  }
  /* the queries refuse them too, whatever an older database may hold */
  vl_test_expect_fail(2, "--compounds", "folder",
                      "compare --compounds sbr-filled,.. --surface paper-0.5um --fluid water "
                      "--out %s/cmp",
                      vl_test_dir);
  vl_test_expect_fail(2, "--fluid", "path separator",
                      "friction --compound sbr-filled --surface paper-0.5um --fluid a/b "
                      "--speed 1");
  char path[1400];
  snprintf(path, sizeof path, "%s/cmp", vl_test_dir);
  assert_false(exists(path));
  snprintf(path, sizeof path, "%s/curve.csv", vl_test_dir);
  assert_false(exists(path));
  /* a multi-fluid scene writes DIR/<fluid>/: '..' is refused, nothing
   * written (not even DIR) */
  const char *scene = rough_scene("dots.ini", "1e-6", "model-1e-4, ..");
  vl_test_expect_fail(2, "[materials] fluid", "folder", "run %s --out %s/dots", scene, vl_test_dir);
  snprintf(path, sizeof path, "%s/dots", vl_test_dir);
  assert_false(exists(path));
}

/* A database written by an older program may hold a compound named '..':
 * compare still refuses to write DIR/../curve.csv. */
static void test_old_database_dots(void **state) {
  (void)state;
  char *out = NULL, *err = NULL;
  assert_int_equal(vl_test_run(&out, &err, "compound list"), 0);
  free(out), free(err);
  sqlite3 *h = NULL;
  assert_int_equal(sqlite3_open(vl_test_db, &h), SQLITE_OK);
  char *msg = NULL;
  if (sqlite3_exec(h, "UPDATE compound SET name = '..' WHERE name = 'sbr-filled'", NULL, NULL,
                   &msg) != SQLITE_OK)
    fail_msg("sqlite: %s", msg);
  sqlite3_close(h);
  vl_test_expect_fail(2, "--compounds", "'..'",
                      "compare --compounds .. --surface paper-0.5um --fluid water --out %s/in/cmp",
                      vl_test_dir);
  char path[1400];
  snprintf(path, sizeof path, "%s/in/curve.csv", vl_test_dir);
  assert_false(exists(path));
}

/* ---- --out ------------------------------------------------------------ */

/* An unusable --out fails at once: status 6, one line naming the folder,
 * nothing on stdout (the table would come after the sweep), within a
 * few seconds (the default sweep of compare takes longer). */
static void expect_out_refused(const char *why, const char *fmt, ...) {
  char args[4096];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(args, sizeof args, fmt, ap);
  va_end(ap);
  struct timespec t0, t1;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  vl_test_expect_fail(6, "--out", why, "%s", args);
  clock_gettime(CLOCK_MONOTONIC, &t1);
  double s = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
  printf("refused in %.3f s: %s\n", s, args);
  if (s > 3.0) fail_msg("`%s` took %.2f s: something was computed", args, s);
}

static void test_out_checked_first(void **state) {
  (void)state;
  char *out = NULL, *err = NULL;
  assert_int_equal(vl_test_run(&out, &err, "fluid list"), 0);
  free(out), free(err);
  const char *file = vl_test_scratch("afile", "not a folder\n");
  const char *scene = rough_scene("rough.ini", "1e-6", "model-1e-4");
  const char *cmp = "compare --compounds sbr-unfilled,sbr-filled --surface paper-0.5um "
                    "--fluid water";
  /* a file in the way: the folder itself, or one the command makes in it */
  expect_out_refused("a file is in the way", "run %s --out %s", scene, file);
  expect_out_refused("a file is in the way", "%s --out %s", cmp, file);
  expect_out_refused("Not a directory", "%s --out %s/sub", cmp, file);
  char dir[1400], sub[1500];
  snprintf(dir, sizeof dir, "%s/withfile", vl_test_dir);
  snprintf(sub, sizeof sub, "%s/sbr-filled", dir);
  assert_int_equal(mkdir(dir, 0755), 0);
  vl_test_write_file(sub, "in the way\n");
  expect_out_refused("a file is in the way", "%s --out %s", cmp, dir);
  /* a folder nobody can write in: /proc refuses even root */
  expect_out_refused("cannot write", "run %s --out /proc", scene);
  expect_out_refused("cannot write", "%s --out /proc", cmp);
  /* and, when permission bits apply (not root), a read-only folder */
  if (geteuid() != 0) {
    snprintf(dir, sizeof dir, "%s/ro", vl_test_dir);
    assert_int_equal(mkdir(dir, 0555), 0);
    expect_out_refused("cannot write", "run %s --out %s", scene, dir);
    expect_out_refused("cannot", "%s --out %s/new", cmp, dir);
    chmod(dir, 0755);
  } else {
    printf("read-only folder: covered by /proc (permission bits do not bind root)\n");
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_run_warnings, vl_test_setup_db),
      cmocka_unit_test_setup(test_run_warnings_per_fluid, vl_test_setup_db),
      cmocka_unit_test_setup(test_friction_warnings, vl_test_setup_db),
      cmocka_unit_test_setup(test_compare_warnings, vl_test_setup_db),
      cmocka_unit_test_setup(test_failed_points, vl_test_setup_db),
      cmocka_unit_test_setup(test_version, vl_test_setup_db),
      cmocka_unit_test_setup(test_names_refused, vl_test_setup_db),
      cmocka_unit_test_setup(test_old_database_dots, vl_test_setup_db),
      cmocka_unit_test_setup(test_out_checked_first, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
