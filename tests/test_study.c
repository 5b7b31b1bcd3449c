/* `viscolube study` end to end: a study of 2 compounds x 2 surfaces x 2
 * loads gives the same mu, point for point, serially, with --jobs 2 and
 * under `mpirun --oversubscribe -n 3` (when the build has MPI and mpirun is
 * there: the test says so when not); a study killed after some tasks and
 * started again finishes with every task run once; bad study files are
 * refused with file, line and field, nothing written; a folder of another
 * study is refused. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "study_private.h"
#include "viscolube.h"
#include "vl_test_util.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Rough wet contacts of the shipped SBRs, 3 points a curve on a coarse
 * graded grid: 8 tasks in about 2 s on one core. */
static const char *const STUDY = "; test study\n"
                                 "[study]\n"
                                 "title = test\n"
                                 "compounds = sbr-unfilled, sbr-filled\n"
                                 "surfaces = paper-0.3um, paper-0.5um\n"
                                 "fluids = water\n"
                                 "loads_n_per_m = 117, 234\n"
                                 "radii_m = 0.001\n"
                                 "[contact]\n"
                                 "sigma_s_pa = 1e6\n"
                                 "[sweep]\n"
                                 "quantity = v0_eta\n"
                                 "from = 1e-6\n"
                                 "to = 1e-3\n"
                                 "points = 3\n"
                                 "[effects]\n"
                                 "roughness = on\n"
                                 "fluid = on\n"
                                 "solid_shear = on\n"
                                 "[numerics]\n"
                                 "grid = 300\n"
                                 "target_error = 0.5\n"
                                 "grid_growth = 1.1\n"
                                 "domain_a0 = -12, 1.6\n";
#define N_TASKS 8
#define POINTS 3

/* The rows of a results.csv: compound and mu of each (the factor columns
 * and the mu column found by name in the header). */
typedef struct {
  size_t n;
  char key[64][200]; /* compound,surface,fluid,load,radius,temperature,v0 */
  double mu[64];
} rows;

static size_t column(const char *header, const char *name) {
  size_t k = 0;
  for (const char *p = header; *p && *p != '\n'; k++) {
    size_t len = strcspn(p, ",\n");
    if (len == strlen(name) && !strncmp(p, name, len)) return k;
    p += len + (p[len] == ',');
  }
  fail_msg("no column %s", name);
  return 0;
}

static rows read_results(const char *dir) {
  char path[1400];
  snprintf(path, sizeof path, "%s/results.csv", dir);
  char *text = vl_test_read_file(path);
  if (!text) fail_msg("%s missing", path);
  rows r = {0};
  char *line = text;
  while (*line == '#')
    line = strchr(line, '\n') + 1;
  size_t mu_col = column(line, "mu");
  assert_int_equal(column(line, "compound"), 0);
  assert_int_equal(column(line, "temperature_c"), 5);
  assert_int_equal(column(line, "v0_m_s"), 6);
  for (line = strchr(line, '\n') + 1; *line; line = strchr(line, '\n') + 1) {
    assert_true(r.n < 64);
    const char *p = line;
    for (size_t k = 0; k < mu_col; k++)
      p = strchr(p, ',') + 1;
    size_t key_len = 0;
    for (size_t k = 0; k < 7; k++)
      key_len += strcspn(line + key_len, ",") + 1;
    snprintf(r.key[r.n], sizeof r.key[0], "%.*s", (int)key_len, line);
    r.mu[r.n] = *p == ',' ? NAN : strtod(p, NULL);
    r.n++;
  }
  free(text);
  return r;
}

/* Same rows, same factors, mu within 1e-12 relative. */
static void same_mu(const rows *a, const rows *b) {
  assert_int_equal(a->n, b->n);
  for (size_t i = 0; i < a->n; i++) {
    assert_string_equal(a->key[i], b->key[i]);
    assert_true(isfinite(a->mu[i]) && isfinite(b->mu[i]));
    if (vl_test_rel(a->mu[i], b->mu[i]) > 1e-12)
      fail_msg("row %zu (%s): mu %.17g vs %.17g", i, a->key[i], a->mu[i], b->mu[i]);
  }
}

static size_t count_task_files(const char *dir) {
  char path[1400];
  snprintf(path, sizeof path, "%s/tasks", dir);
  DIR *d = opendir(path);
  if (!d) return 0;
  size_t n = 0;
  for (struct dirent *e; (e = readdir(d));)
    n += e->d_name[0] != '.';
  closedir(d);
  return n;
}

/* The integer after "key": in run.json. */
static long manifest_int(const char *dir, const char *key) {
  char path[1400], pat[64];
  snprintf(path, sizeof path, "%s/run.json", dir);
  snprintf(pat, sizeof pat, "\"%s\": ", key);
  char *text = vl_test_read_file(path);
  assert_non_null(text);
  assert_true(vl_test_json_valid(text));
  char *p = strstr(text, pat);
  if (!p) fail_msg("no %s in %s", key, path);
  long v = strtol(p + strlen(pat), NULL, 10);
  free(text);
  return v;
}

/* The serial results, kept by the first test for the others (each test
 * has its own scratch database and folders). */
static rows reference;
static int have_reference;

static int run_study(const char *launcher, const char *out, const char *extra) {
  char *o = NULL, *e = NULL, args[4096];
  snprintf(args, sizeof args, "--db %s study %s --out %s %s", vl_test_db,
           vl_test_scratch("s.ini", NULL), out, extra ? extra : "");
  int rc = vl_test_cli(launcher, args, &o, &e);
  if (rc != 0) print_message("exit %d\nstdout: %s\nstderr: %s\n", rc, o, e);
  free(o);
  free(e);
  return rc;
}

static void test_serial_jobs_mpi_agree(void **state) {
  (void)state;
  vl_test_scratch("s.ini", STUDY);
  const char *serial = vl_test_scratch("serial", NULL), *jobs = vl_test_scratch("jobs", NULL);
  assert_int_equal(run_study("env -u VISCOLUBE_DB", serial, NULL), 0);
  rows a = read_results(serial);
  assert_int_equal(a.n, N_TASKS * POINTS);
  reference = a;
  have_reference = 1;
  assert_int_equal(count_task_files(serial), N_TASKS);
  assert_int_equal(manifest_int(serial, "total"), N_TASKS);
  assert_int_equal(manifest_int(serial, "ok"), N_TASKS);
  jobs = vl_test_scratch("jobs", NULL);
  assert_int_equal(run_study("env -u VISCOLUBE_DB", jobs, "--jobs 2"), 0);
  rows b = read_results(jobs);
  same_mu(&a, &b);
  assert_int_equal(manifest_int(jobs, "processes"), 2);

  const char *mpi_build = getenv("VL_HAVE_MPI");
  if (!mpi_build || strcmp(mpi_build, "ON")) {
    print_message("SKIP mpirun: this build has no MPI (VL_HAVE_MPI=%s)\n",
                  mpi_build ? mpi_build : "unset");
    return;
  }
  if (system("command -v mpirun >/dev/null 2>&1") != 0) {
    print_message("SKIP mpirun: no mpirun on PATH\n");
    return;
  }
  const char *mpi = vl_test_scratch("mpi", NULL);
  /* root needs the flag; --oversubscribe: 3 ranks on fewer cores.
   * LeakSanitizer off: Open MPI keeps allocations past MPI_Finalize */
  assert_int_equal(run_study("env -u VISCOLUBE_DB ASAN_OPTIONS=detect_leaks=0 "
                             "mpirun --allow-run-as-root --oversubscribe -n 3",
                             mpi, NULL),
                   0);
  rows c = read_results(mpi);
  same_mu(&a, &c);
  assert_int_equal(manifest_int(mpi, "processes"), 2); /* ranks that compute */
}

/* Killed after k tasks (the program's test hook), then started again:
 * the same results, and the second run ran only the tasks not written. */
static void killed_and_restarted(const char *name, const char *jobs, int k, size_t max_written) {
  vl_test_scratch("s.ini", STUDY);
  const char *dir = vl_test_scratch(name, NULL);
  if (!have_reference) {
    const char *ref = vl_test_scratch("ref", NULL);
    assert_int_equal(run_study("env -u VISCOLUBE_DB", ref, NULL), 0);
    reference = read_results(ref);
    have_reference = 1;
  }
  char env[128];
  snprintf(env, sizeof env, "env -u VISCOLUBE_DB VL_TEST_STUDY_KILL_AFTER=%d", k);
  assert_int_not_equal(run_study(env, dir, jobs), 0);
  size_t written = count_task_files(dir);
  assert_true(written >= (size_t)k && written <= max_written);
  char path[1400];
  snprintf(path, sizeof path, "%s/results.csv", dir);
  assert_int_equal(access(path, F_OK) == 0 && !jobs, 0); /* a killed serial run wrote none */
  assert_int_equal(run_study("env -u VISCOLUBE_DB", dir, jobs), 0);
  assert_int_equal(count_task_files(dir), N_TASKS);
  assert_int_equal(manifest_int(dir, "skipped"), (long)written);
  assert_int_equal(manifest_int(dir, "run"), (long)(N_TASKS - written));
  rows b = read_results(dir);
  same_mu(&reference, &b);
  /* a third run has nothing left to do */
  assert_int_equal(run_study("env -u VISCOLUBE_DB", dir, jobs), 0);
  assert_int_equal(manifest_int(dir, "run"), 0);
  rows c = read_results(dir);
  same_mu(&reference, &c);
}

static void test_restart_serial(void **state) {
  (void)state;
  killed_and_restarted("killed", NULL, 3, 3);
}

static void test_restart_jobs(void **state) {
  (void)state;
  /* each of the two workers dies after its first task */
  killed_and_restarted("killed-jobs", "--jobs 2", 1, 2);
}

/* A study refused: status, "file:line: [section] key" on stderr, no --out. */
static void refused(int code, const char *text, const char *where, const char *field) {
  const char *path = vl_test_scratch("bad.ini", text);
  const char *out = vl_test_scratch("never", NULL);
  char needle[256];
  snprintf(needle, sizeof needle, "%s:%s", path, where);
  vl_test_expect_fail(code, needle, field, "study %s --out %s", path, out);
  struct stat sb;
  assert_int_not_equal(stat(out, &sb), 0);
}

#define SWEEP "[sweep]\nquantity = v0\nfrom = 1e-3\nto = 1\npoints = 3\n"
#define GRID "[study]\ncompounds = model-rubber\nloads_n_per_m = 100\nradii_m = 0.01\n"

static void test_bad_studies(void **state) {
  (void)state;
  assert_int_equal(vl_test_run(NULL, NULL, "compound list"), 0); /* the database exists */
  refused(2, GRID "speeds = 1\n" SWEEP, "5:", "[study] speeds: unknown key");
  refused(2, "[study]\ncompounds = model-rubber\nloads_n_per_m = 100, -1\nradii_m = 0.01\n" SWEEP,
          "3:", "[study] loads_n_per_m");
  refused(2,
          "[study]\ncompounds = model-rubber, model-rubber\nloads_n_per_m = 1\nradii_m = 1\n" SWEEP,
          "2:", "given twice");
  refused(3,
          "[study]\ncompounds = model-rubber, nosuch\nloads_n_per_m = 100\nradii_m = 0.01\n" SWEEP,
          "2:", "'nosuch'");
  refused(2, "[materials]\ncompound = x\n" GRID SWEEP, "2:", "[materials] compound");
  refused(2, GRID "[contact]\nradius_m = 1\n" SWEEP, "6:", "[contact] radius_m");
  refused(2, GRID "[sweep]\nquantity = v0\nfrom = 1e-3\nto = 1\npoints = many\n",
          "9:", "[sweep] points");
  refused(2, "[study]\ncases = model-rubber - - 100 0.01\n  model-rubber - - 100\n" SWEEP,
          "3:", "[study] cases");
  refused(2, "[study]\ncases = model-rubber - - 100 0.01\n  model-rubber - - 100 0.01\n" SWEEP,
          "3:", "the same task as line 2");
  refused(2, GRID "cases = model-rubber - - 100 0.01\n" SWEEP, "2:", "not both");
  /* no WLF constants: the temperatures are refused before any task */
  refused(2, GRID "temperatures_c = 20, 40\n" SWEEP, "5:", "[study] temperatures_c");
}

/* A folder with the tasks of another study is refused, and left alone. */
static void test_other_study_refused(void **state) {
  (void)state;
  vl_test_scratch("s.ini", STUDY);
  const char *dir = vl_test_scratch("first", NULL);
  assert_int_equal(run_study("env -u VISCOLUBE_DB", dir, NULL), 0);
  char path[1400];
  snprintf(path, sizeof path, "%s/results.csv", dir);
  vl_test_snapshot before = vl_test_take(path);
  char other[4096];
  snprintf(other, sizeof other, "%s", STUDY);
  strstr(other, "117, 234")[2] = '4'; /* loads 114, 234: another study */
  const char *p = vl_test_scratch("other.ini", other);
  char *out = NULL, *err = NULL;
  assert_int_equal(vl_test_run(&out, &err, "study %s --out %s", p, dir), 2);
  assert_non_null(strstr(err, "not a task of"));
  assert_true(vl_test_same_bytes(path, &before));
  free(before.bytes);
  free(out);
  free(err);
}

/* The shipped example loads: 2 compounds x 2 surfaces x 1 fluid x 3
 * loads, compounds outermost, every task's scene with its factors. */
static void test_shipped_example(void **state) {
  (void)state;
  vl_study *s = NULL;
  vl_error err = {{0}};
  const char *path = vl_test_source_path("studies/example.ini");
  if (vl_study_load(path, &s, &err) != VL_OK) fail_msg("%s", err.msg);
  assert_int_equal(vl_study_n_tasks(s), 12);
  const vl_study_task *first = vl_study_task_at(s, 0), *last = vl_study_task_at(s, 11);
  assert_string_equal(first->compound, "sbr-unfilled");
  assert_string_equal(last->compound, "sbr-filled");
  assert_true(first->load_n_per_m < vl_study_task_at(s, 1)->load_n_per_m);
  vl_scene sc;
  assert_int_equal(vl_study_scene(s, 11, &sc, &err), VL_OK);
  assert_string_equal(sc.surface, last->surface);
  assert_true(sc.load_n_per_m == last->load_n_per_m && sc.radius_m == last->radius_m);
  assert_true(sc.effects.roughness && sc.effects.fluid && sc.points == 12);
  vl_study_free(s);
}

/* One database for all the tests: its tables are built by the first study
 * and read by the others, as a second study on a machine would. */
static char shared_db[1200];

static int setup(void **state) {
  vl_test_setup_db(state);
  if (!shared_db[0]) snprintf(shared_db, sizeof shared_db, "%s", vl_test_db);
  snprintf(vl_test_db, sizeof vl_test_db, "%s", shared_db);
  return 0;
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_shipped_example),
      cmocka_unit_test_setup(test_bad_studies, setup),
      cmocka_unit_test_setup(test_serial_jobs_mpi_agree, setup),
      cmocka_unit_test_setup(test_restart_serial, setup),
      cmocka_unit_test_setup(test_restart_jobs, setup),
      cmocka_unit_test_setup(test_other_study_refused, setup),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
