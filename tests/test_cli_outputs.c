/* Output folders, end to end: the manifest run.json (what it records,
 * written last, files of an earlier run removed only when its manifest
 * lists them, other files left alone with a warning, an interrupted run
 * leaving no manifest), material fingerprints, a reader of stdout that
 * has gone away (`| head`: the files complete, exit status 6 and a
 * message), two processes writing one folder at once, compare's --axis,
 * and the figures' subtitle. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "viscolube.h"

/* A dry scene of the model rubber: `points` speeds, fields at `fields_at`
 * (a list of Deborah numbers, or "" for none). */
static const char *dry_scene(const char *name, int points, const char *fields_at) {
  char text[2048];
  snprintf(text, sizeof text,
           "[scene]\ntitle = dry test\n[materials]\ncompound = model-rubber\n"
           "[contact]\nradius_m = 0.01\nload_n_per_m = 1000\nsigma_s_pa = 0\n"
           "[sweep]\nquantity = deborah\nfrom = 1e-3\nto = 1e3\npoints = %d\n%s%s%s"
           "[effects]\nviscoelastic = on\nroughness = off\nfluid = off\nsolid_shear = off\n"
           "[numerics]\ngrid = 64\ndomain_a0 = -1.5, 1.5\ntolerance = 1e-9\ntarget_error = 0.5\n",
           points, fields_at[0] ? "fields_at = " : "", fields_at, fields_at[0] ? "\n" : "");
  return vl_test_scratch(name, text);
}

static int exists(const char *dir, const char *name) {
  char path[4400];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  struct stat sb;
  return stat(path, &sb) == 0;
}

static char *read_in(const char *dir, const char *name) {
  char path[4400];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  return vl_test_read_file(path);
}

/* The number of the files of dir whose names start with prefix. */
static size_t count_prefixed(const char *dir, const char *prefix) {
  DIR *d = opendir(dir);
  size_t n = 0;
  for (struct dirent *e; d && (e = readdir(d));)
    n += strncmp(e->d_name, prefix, strlen(prefix)) == 0;
  if (d) closedir(d);
  return n;
}

/* ---- the manifest ------------------------------------------------------ */

static void test_manifest_of_run(void **state) {
  (void)state;
  const char *scene = dry_scene("a.ini", 7, "0.01, 1, 100");
  char dir[1200], *out = NULL, *err = NULL;
  snprintf(dir, sizeof dir, "%s/o", vl_test_dir);
  int rc = vl_test_run(&out, &err, "run %s --out %s", scene, dir);
  if (rc != 0) fail_msg("run: exit %d: %s", rc, err);
  char *m = read_in(dir, "run.json");
  assert_non_null(m);
  printf("run.json:\n%s", m);
  assert_true(vl_test_json_valid(m));
  /* what made the files: command, scene text, material, numerics, times */
  const char *needles[] = {
      "\"command\": [",
      "\"run\", \"",
      "\"scene\": \"[scene]\\ntitle = dry test\\n",
      "{\"role\": \"compound\", \"name\": \"model-rubber\", "
      "\"fingerprint\": \"fnv1a64:",
      "\"grid\": 64, \"cells\": 64, \"grid_growth\": 1, \"domain_min_a0\": -1.5, "
      "\"domain_max_a0\": 1.5, \"tolerance\": 1e-09",
      "\"version\": \"",
      "\"started_utc\": \"20",
      "\"finished_utc\": \"20",
      "\"points\": {\"converged\": 7, \"failed\": 0}",
      "\"files\": [\"fields/",
      "\"curve.csv\"",
      "\"not_written\": []"};
  for (size_t i = 0; i < sizeof needles / sizeof needles[0]; i++)
    if (!strstr(m, needles[i])) fail_msg("run.json lacks %s", needles[i]);
  /* three fields files, each listed */
  size_t listed = 0;
  for (const char *p = m; (p = strstr(p, "\"fields/")); p++)
    listed++;
  assert_int_equal(listed, 3);
  assert_false(exists(dir, ".run.json.previous"));
  free(m), free(out), free(err);
}

/* An earlier run's files that the new run does not rewrite: removed when
 * the earlier run.json lists them; a file no manifest lists stays, named
 * in a warning. */
static void test_manifest_supersedes(void **state) {
  (void)state;
  char dir[1200], *out = NULL, *err = NULL;
  snprintf(dir, sizeof dir, "%s/o", vl_test_dir);
  int rc = vl_test_run(&out, &err, "run %s --out %s", dry_scene("a.ini", 7, "0.01, 1, 100"), dir);
  assert_int_equal(rc, 0);
  free(out), free(err);
  char *m = read_in(dir, "run.json");
  assert_non_null(m);
  free(m);
  /* a file of the user's, and one that looks like ours but no manifest lists */
  vl_test_write_file(vl_test_scratch("o/notes.txt", NULL), "mine\n");
  vl_test_write_file(vl_test_scratch("o/fields/999.csv", NULL), "x\n");
  /* fewer points, no fields: the three fields files of the first run go */
  rc = vl_test_run(&out, &err, "run %s --out %s", dry_scene("b.ini", 4, ""), dir);
  if (rc != 0) fail_msg("second run: exit %d: %s", rc, err);
  printf("second run, stderr:\n%s", err);
  assert_non_null(strstr(err, "removed 3 files of the earlier run"));
  assert_non_null(strstr(err, "not written by this run"));
  assert_non_null(strstr(err, "notes.txt"));
  assert_non_null(strstr(err, "fields/999.csv"));
  assert_true(exists(dir, "notes.txt"));
  assert_true(exists(dir, "fields/999.csv"));
  char fields[1300];
  snprintf(fields, sizeof fields, "%s/fields", dir);
  assert_int_equal(count_prefixed(fields, "0"), 0); /* 000.csv ... gone */
  m = read_in(dir, "run.json");
  assert_non_null(strstr(m, "\"files\": [\"curve.csv\"]"));
  assert_non_null(strstr(m, "\"points\": {\"converged\": 4, \"failed\": 0}"));
  free(m), free(out), free(err);
  /* --quiet: the warning goes, the files stay */
  rc = vl_test_run(&out, &err, "--quiet run %s --out %s", dry_scene("b.ini", 4, ""), dir);
  assert_int_equal(rc, 0);
  assert_string_equal(err, "");
  assert_true(exists(dir, "notes.txt"));
  free(out), free(err);
}

/* A run killed after it started (its manifest moved aside, files being
 * written) leaves no run.json; the next complete run removes the files
 * the last complete run listed. */
static void test_manifest_interrupted(void **state) {
  (void)state;
  char dir[1200], *out = NULL, *err = NULL;
  snprintf(dir, sizeof dir, "%s/o", vl_test_dir);
  int rc = vl_test_run(&out, &err, "run %s --out %s", dry_scene("a.ini", 7, "0.01, 1, 100"), dir);
  assert_int_equal(rc, 0);
  free(out), free(err);
  const char *slow = dry_scene("slow.ini", 4000, "0.01");
  pid_t pid = fork();
  if (pid == 0) {
    int null = open("/dev/null", O_RDWR);
    dup2(null, 1), dup2(null, 2);
    execl(getenv("VL_CLI"), "viscolube", "--db", vl_test_db, "run", slow, "--out", dir,
          (char *)NULL);
    _exit(127);
  }
  /* as soon as the run has begun (run.json moved aside), kill it */
  char manifest[1300];
  snprintf(manifest, sizeof manifest, "%s/run.json", dir);
  struct timespec ms = {0, 1000000};
  for (int i = 0; i < 20000 && access(manifest, F_OK) == 0; i++)
    nanosleep(&ms, NULL);
  kill(pid, SIGKILL);
  int st;
  waitpid(pid, &st, 0);
  if (!WIFSIGNALED(st)) fail_msg("the slow run ended before it was killed");
  assert_false(exists(dir, "run.json"));
  assert_true(exists(dir, ".run.json.previous"));
  rc = vl_test_run(&out, &err, "run %s --out %s", dry_scene("b.ini", 4, ""), dir);
  if (rc != 0) fail_msg("run after the killed one: exit %d: %s", rc, err);
  assert_non_null(strstr(err, "removed 3 files of the earlier run"));
  assert_true(exists(dir, "run.json"));
  assert_false(exists(dir, ".run.json.previous"));
  free(out), free(err);
}

/* A run.json of another program is neither replaced nor obeyed: the run
 * is refused before anything is computed, the folder unchanged. */
static void test_foreign_manifest(void **state) {
  (void)state;
  char dir[1200];
  snprintf(dir, sizeof dir, "%s/o", vl_test_dir);
  mkdir(dir, 0777);
  char *out = NULL, *err = NULL;
  assert_int_equal(vl_test_run(&out, &err, "fluid list"), 0); /* the database exists */
  free(out), free(err);
  const char *foreign = "{\"files\": [\"keep.txt\"]}\n";
  vl_test_write_file(vl_test_scratch("o/run.json", NULL), foreign);
  vl_test_write_file(vl_test_scratch("o/keep.txt", NULL), "mine\n");
  vl_test_expect_fail(6, "run.json exists and is not a viscolube manifest", NULL, "run %s --out %s",
                      dry_scene("a.ini", 4, ""), dir);
  char *m = read_in(dir, "run.json");
  assert_string_equal(m, foreign);
  free(m);
  assert_true(exists(dir, "keep.txt"));
  assert_false(exists(dir, "curve.csv"));
}

/* ---- fingerprints ------------------------------------------------------ */

static void test_fingerprints(void **state) {
  (void)state;
  vl_db *db = NULL, *other = NULL;
  vl_error err;
  char a[VL_DB_FINGERPRINT_MAX], b[VL_DB_FINGERPRINT_MAX], c[VL_DB_FINGERPRINT_MAX];
  assert_int_equal(vl_db_open(vl_test_db, &db, &err), VL_OK);
  assert_int_equal(vl_db_fingerprint(db, "fluid", "water", a, &err), VL_OK);
  assert_int_equal(strncmp(a, "fnv1a64:", 8), 0);
  assert_int_equal(strlen(a), 8 + 16);
  /* another database with the same shipped material: the same print */
  char path[1300];
  snprintf(path, sizeof path, "%s/other.db", vl_test_dir);
  assert_int_equal(vl_db_open(path, &other, &err), VL_OK);
  assert_int_equal(vl_db_fingerprint(other, "fluid", "water", b, &err), VL_OK);
  assert_string_equal(a, b);
  vl_db_close(other);
  /* every kind; a different material prints differently */
  assert_int_equal(vl_db_fingerprint(db, "compound", "sbr-unfilled", b, &err), VL_OK);
  assert_int_equal(vl_db_fingerprint(db, "compound", "sbr-filled", c, &err), VL_OK);
  assert_string_not_equal(b, c);
  assert_int_equal(vl_db_fingerprint(db, "surface", "paper-0.5um", c, &err), VL_OK);
  assert_int_equal(vl_db_fingerprint(db, "fluid", "nope", c, &err), VL_ENOTFOUND);
  assert_int_equal(vl_db_fingerprint(db, "table", "water", c, &err), VL_EINPUT);
  vl_db_close(db);
  /* a changed row, a changed Prony term: a changed print */
  vl_test_sql(vl_test_db, "UPDATE fluid SET viscosity_pa_s = 0.0011 WHERE name = 'water'");
  vl_test_sql(vl_test_db, "UPDATE compound_prony SET tau_s = tau_s * 1.000001 WHERE idx = 1 AND "
                          "compound_id = (SELECT id FROM compound WHERE name = 'sbr-unfilled')");
  assert_int_equal(vl_db_open(vl_test_db, &db, &err), VL_OK);
  assert_int_equal(vl_db_fingerprint(db, "fluid", "water", c, &err), VL_OK);
  assert_string_not_equal(a, c);
  assert_int_equal(vl_db_fingerprint(db, "compound", "sbr-unfilled", c, &err), VL_OK);
  assert_string_not_equal(b, c);
  vl_db_close(db);
}

/* ---- stdout gone ------------------------------------------------------- */

/* Runs the program with stdout a pipe whose reader has already gone (as
 * `| head` once head has exited); stderr into *err. The exit status, or
 * -1 on a signal (*sig). */
static int run_reader_gone(char **err, int *sig, char *const args[]) {
  int fds[2];
  assert_int_equal(pipe(fds), 0);
  close(fds[0]); /* the reader is gone before the first write */
  char errp[1300];
  snprintf(errp, sizeof errp, "%s/stderr", vl_test_dir);
  pid_t pid = fork();
  if (pid == 0) {
    signal(SIGPIPE, SIG_DFL); /* as a shell gives it */
    int e = open(errp, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fds[1], 1), dup2(e, 2);
    execv(getenv("VL_CLI"), args);
    _exit(127);
  }
  close(fds[1]);
  int st;
  waitpid(pid, &st, 0);
  *err = vl_test_read_file(errp);
  *sig = WIFSIGNALED(st) ? WTERMSIG(st) : 0;
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static size_t count_lines(const char *s) {
  size_t n = 0;
  for (; s && *s; s++)
    n += *s == '\n';
  return n;
}

static void test_compare_reader_gone(void **state) {
  (void)state;
  char dir[1200];
  snprintf(dir, sizeof dir, "%s/cmp", vl_test_dir);
  char *args[] = {
      "viscolube", "--db",        vl_test_db, "compare", "--compounds", "sbr-unfilled,sbr-filled",
      "--surface", "paper-0.5um", "--fluid",  "water",   "--points",    "40",
      "--plot",    "--out",       dir,        "--quiet", NULL};
  char *err = NULL;
  int sig = 0, rc = run_reader_gone(&err, &sig, args);
  printf("compare | (reader gone): exit %d, signal %d, stderr: %s", rc, sig, err);
  /* not killed by SIGPIPE: an exit status and a message */
  assert_int_equal(sig, 0);
  assert_int_equal(rc, 6);
  assert_non_null(strstr(err, "cannot write to standard output: Broken pipe"));
  /* every file complete under its final name, the manifest last */
  char *csv = read_in(dir, "compare.csv");
  assert_non_null(csv);
  assert_int_equal(count_lines(csv), 2 + 40);
  const char *files[] = {"compare-mu.png",   "compare-mu.svg",         "compare-umin.png",
                         "compare-umin.svg", "sbr-unfilled/curve.csv", "sbr-filled/curve.csv"};
  for (size_t i = 0; i < sizeof files / sizeof files[0]; i++)
    if (!exists(dir, files[i])) fail_msg("missing: %s", files[i]);
  char *m = read_in(dir, "run.json");
  assert_non_null(m);
  assert_true(vl_test_json_valid(m));
  assert_non_null(strstr(m, "\"compare.csv\""));
  assert_non_null(strstr(m, "\"points\": {\"converged\": 80, \"failed\": 0}"));
  assert_int_equal(count_prefixed(dir, ".compare"), 0); /* no temporaries */
  free(m), free(csv), free(err);
}

/* ---- two writers in one folder ----------------------------------------- */

/* Two processes write the same name in one folder 300 times each through
 * atomic files: no temporary is shared or left behind, every write
 * succeeds, and the file is always one writer's whole content. */
static void test_two_writers(void **state) {
  (void)state;
  char path[1300];
  snprintf(path, sizeof path, "%s/same.csv", vl_test_dir);
  pid_t pids[2];
  for (int w = 0; w < 2; w++) {
    pids[w] = fork();
    if (pids[w] == 0) {
      for (int k = 0; k < 300; k++) {
        vl_atomic_file af;
        vl_error err;
        if (vl_atomic_file_open(&af, path, &err) != VL_OK) _exit(1);
        for (int line = 0; line < 2000; line++)
          fprintf(af.f, "writer %d, line %d\n", w, line);
        if (vl_atomic_file_commit(&af, &err) != VL_OK) _exit(2);
      }
      _exit(0);
    }
  }
  /* meanwhile, every read sees one writer's file, whole */
  size_t reads = 0;
  for (int alive = 2; alive;) {
    char *text = vl_test_read_file(path);
    if (text) {
      int w = text[7] - '0';
      char last[64];
      snprintf(last, sizeof last, "writer %d, line 1999\n", w);
      size_t len = strlen(text);
      assert_true(len > strlen(last) && !strcmp(text + len - strlen(last), last));
      assert_int_equal(count_lines(text), 2000);
      reads++;
      free(text);
    }
    alive = 0;
    for (int w = 0; w < 2; w++) {
      int st;
      if (pids[w] && waitpid(pids[w], &st, WNOHANG) == pids[w]) {
        assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 0);
        pids[w] = 0;
      }
      alive += pids[w] != 0;
    }
  }
  printf("two writers: 600 writes, %zu whole reads, %zu temporaries left\n", reads,
         count_prefixed(vl_test_dir, ".same.csv"));
  assert_int_equal(count_prefixed(vl_test_dir, ".same.csv"), 0);
}

/* Two runs of the program into one folder at once: both succeed, the
 * folder holds one complete manifest. */
static void test_two_runs(void **state) {
  (void)state;
  char dir[1200];
  snprintf(dir, sizeof dir, "%s/both", vl_test_dir);
  const char *scene = dry_scene("a.ini", 40, "0.01, 1, 100");
  pid_t pids[2];
  for (int w = 0; w < 2; w++) {
    pids[w] = fork();
    if (pids[w] == 0) {
      int null = open("/dev/null", O_RDWR);
      dup2(null, 1), dup2(null, 2);
      execl(getenv("VL_CLI"), "viscolube", "--db", vl_test_db, "run", scene, "--out", dir,
            (char *)NULL);
      _exit(127);
    }
  }
  for (int w = 0; w < 2; w++) {
    int st;
    waitpid(pids[w], &st, 0);
    assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 0);
  }
  char *m = read_in(dir, "run.json");
  assert_non_null(m);
  assert_true(vl_test_json_valid(m));
  char *csv = read_in(dir, "curve.csv");
  assert_int_equal(count_lines(csv), 1 + 43);
  assert_int_equal(count_prefixed(dir, ".curve"), 0);
  free(m), free(csv);
}

/* ---- compare --axis ---------------------------------------------------- */

static void test_compare_axis(void **state) {
  (void)state;
  char *csv[2];
  const char *axes[] = {"speed", "v0eta"};
  for (int k = 0; k < 2; k++) {
    char *out = NULL, *err = NULL, dir[1300];
    snprintf(dir, sizeof dir, "%s/%s", vl_test_dir, axes[k]);
    int rc = vl_test_run(&out, &err,
                         "compare --compounds sbr-filled --surface paper-0.5um --fluid water "
                         "--points 3 --axis %s --out %s",
                         axes[k], dir);
    if (rc != 0) fail_msg("--axis %s: exit %d: %s", axes[k], rc, err);
    assert_non_null(strstr(out, k ? " v0_eta_pa_m " : "      v0_m_s "));
    csv[k] = read_in(dir, "compare.csv");
    assert_non_null(csv[k]);
    free(out), free(err);
  }
  /* the same rows but for the first column: v0 = v0 eta / eta (water) */
  const char *l0 = strchr(csv[0], '\n') + 1, *l1 = strchr(csv[1], '\n') + 1;
  assert_int_equal(strncmp(l0, "v0_m_s,", 7), 0);
  assert_int_equal(strncmp(l1, "v0_eta_pa_m,", 12), 0);
  for (int row = 0; row < 3; row++) {
    l0 = strchr(l0, '\n') + 1, l1 = strchr(l1, '\n') + 1;
    double v = strtod(l0, NULL), ve = strtod(l1, NULL);
    assert_true(fabs(v * 1e-3 / ve - 1.0) < 1e-9);
    const char *r0 = strchr(l0, ','), *r1 = strchr(l1, ',');
    assert_int_equal(strcspn(r0, "\n"), strcspn(r1, "\n"));
    assert_memory_equal(r0, r1, strcspn(r0, "\n"));
  }
  free(csv[0]), free(csv[1]);
  vl_test_expect_fail(2, "--axis", "speed or v0eta",
                      "compare --compounds sbr-filled --surface paper-0.5um --fluid water "
                      "--axis time");
}

/* ---- the figures' subtitle ---------------------------------------------- */

/* The glyphs of an SVG figure (cairo draws text as <use> of glyphs). */
static size_t glyphs(const char *stem) {
  char path[1400];
  snprintf(path, sizeof path, "%s.svg", stem);
  char *svg = vl_test_read_file(path);
  size_t n = 0;
  for (const char *p = svg; p && (p = strstr(p, "<use xlink:href=\"#glyph")); p++)
    n++;
  free(svg);
  return n;
}

static void test_figure_subtitle(void **state) {
  (void)state;
  vl_point pts[4] = {{0}};
  for (int i = 0; i < 4; i++) {
    pts[i].v0_m_s = pow(10.0, i - 2);
    pts[i].mu = pts[i].mu_Rc = 0.1 + 0.01 * i;
    pts[i].converged = 1;
  }
  vl_curve_meta meta = {0};
  vl_plot_options opt;
  vl_plot_options_defaults(&opt);
  opt.formats = VL_PLOT_SVG;
  opt.title = "title";
  vl_error err;
  char a[1300], b[1300];
  snprintf(a, sizeof a, "%s/plain", vl_test_dir);
  snprintf(b, sizeof b, "%s/sub", vl_test_dir);
  assert_int_equal(vl_plot_stribeck(a, 4, pts, &meta, VL_SWEEP_V0, 0, NULL, &opt, NULL, &err),
                   VL_OK);
  opt.subtitle = "abcdefghij";
  assert_int_equal(vl_plot_stribeck(b, 4, pts, &meta, VL_SWEEP_V0, 0, NULL, &opt, NULL, &err),
                   VL_OK);
  size_t ga = glyphs(a), gb = glyphs(b);
  printf("glyphs: %zu without subtitle, %zu with a 10-letter one\n", ga, gb);
  assert_int_equal(gb, ga + 10);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_manifest_of_run, vl_test_setup_db),
      cmocka_unit_test_setup(test_manifest_supersedes, vl_test_setup_db),
      cmocka_unit_test_setup(test_manifest_interrupted, vl_test_setup_db),
      cmocka_unit_test_setup(test_foreign_manifest, vl_test_setup_db),
      cmocka_unit_test_setup(test_fingerprints, vl_test_setup_db),
      cmocka_unit_test_setup(test_compare_reader_gone, vl_test_setup_db),
      cmocka_unit_test_setup(test_two_writers, vl_test_setup_db),
      cmocka_unit_test_setup(test_two_runs, vl_test_setup_db),
      cmocka_unit_test_setup(test_compare_axis, vl_test_setup_db),
      cmocka_unit_test_setup(test_figure_subtitle, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
