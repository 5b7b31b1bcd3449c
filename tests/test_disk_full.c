/* Writes that cannot complete: a full disk, a file-size limit, a directory
 * where the rollback journal cannot be created, a read-only file with an
 * unfinished transaction in it. Each case runs the real command-line
 * program (fork + exec) and asserts three things: the command fails with
 * the I/O or database exit status and one clear sentence on stderr, the
 * database file is byte-for-byte what it was (nothing lost, nothing half
 * written, no hot journal), and the next command works once the cause is
 * gone.
 *
 * Disk full, two ways:
 *   - RLIMIT_FSIZE in the child (SIGXFSZ ignored), so every write past the
 *     limit fails with EFBIG: portable, no privileges. The limit is swept
 *     from the file's size upwards in 4 KiB steps while `surface add` writes
 *     a 3000-point spectrum (about 30 pages), or `compound add --measured`
 *     a DMA file, so that the write fails at every stage of the
 *     transaction, until it fits; a 128-term compound without room to grow;
 *     and a new database created under limits too small for it.
 *   - a real full file system: a 256 KiB tmpfs (mount needs root and
 *     CAP_SYS_ADMIN; skipped when mount fails), filled but for a few pages.
 * Read-only: a directory without write permission, so SQLite cannot create
 * the journal (the command runs as user nobody when the tests run as root,
 * for whom permission bits do not apply); and a read-only file holding a
 * hot journal, which SQLite must roll back before reading. User nobody runs
 * a copy of the program in a fresh folder under /tmp: the build may live
 * where nobody cannot enter (/root, a mode-700 checkout). */
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
#include <grp.h>
#include <math.h>
#include <signal.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "viscolube/database.h"

#define EXIT_EDB 5
#define EXIT_EIO 6
#define NOBODY 65534

/* ---- helpers ---------------------------------------------------------- */

/* 0 no journal, 1 cold (SQLite ignores it), 2 hot (would be rolled back). */
static int journal_state(const char *db) {
  char path[4200];
  snprintf(path, sizeof path, "%s-journal", db);
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  int c = fgetc(f);
  fclose(f);
  return c == EOF || c == 0 ? 1 : 2;
}

/* ---- the program as user nobody ----------------------------------------- */

static char nobody_dir[64], nobody_cli[128];

static void remove_nobody_copy(void) {
  if (nobody_cli[0]) unlink(nobody_cli);
  if (nobody_dir[0]) rmdir(nobody_dir);
}

/* Copies file src to dst with mode 0755 (0 on success). */
static int copy_program(const char *src, const char *dst) {
  int in = open(src, O_RDONLY), out = open(dst, O_WRONLY | O_CREAT | O_EXCL, 0755);
  int ok = in >= 0 && out >= 0;
  char buf[65536];
  ssize_t got;
  while (ok && (got = read(in, buf, sizeof buf)) != 0) {
    if (got < 0) {
      ok = errno == EINTR;
      continue;
    }
    for (ssize_t done = 0, w; ok && done < got; done += w)
      if ((w = write(out, buf + done, (size_t)(got - done))) < 0) ok = 0;
  }
  if (in >= 0) close(in);
  if (out >= 0 && close(out) != 0) ok = 0;
  return ok && chmod(dst, 0755) == 0 ? 0 : -1;
}

/* The program as user nobody can run it (made once, removed at exit): a
 * copy of $VL_CLI in a fresh folder under /tmp (mode 755), since the build
 * folder may be closed to other users. libviscolube is linked statically
 * into it; what it links dynamically comes from the system. NULL (after
 * printing why) when nobody cannot run even the copy. */
static const char *cli_for_nobody(void) {
  if (nobody_cli[0]) return nobody_cli;
  const char *cli_path = getenv("VL_CLI");
  if (!cli_path) fail_msg("VL_CLI is not set (run the tests through ctest)");
  snprintf(nobody_dir, sizeof nobody_dir, "/tmp/vl-nobody-XXXXXX");
  if (!mkdtemp(nobody_dir) || chmod(nobody_dir, 0755) != 0)
    fail_msg("%s: %s", nobody_dir, strerror(errno));
  atexit(remove_nobody_copy);
  snprintf(nobody_cli, sizeof nobody_cli, "%s/viscolube", nobody_dir);
  if (copy_program(cli_path, nobody_cli) != 0)
    fail_msg("copying %s to %s: %s", cli_path, nobody_cli, strerror(errno));
  /* can nobody run it? (`--version` opens no database) */
  pid_t pid = fork();
  if (pid == 0) {
    int null = open("/dev/null", O_RDWR);
    dup2(null, 1);
    dup2(null, 2);
    if (setgroups(0, NULL) != 0 || setgid(NOBODY) != 0 || setuid(NOBODY) != 0) _exit(121);
    execl(nobody_cli, nobody_cli, "--version", (char *)NULL);
    _exit(127);
  }
  int st = 0;
  while (waitpid(pid, &st, 0) < 0)
    if (errno != EINTR) fail_msg("waitpid: %s", strerror(errno));
  if (!WIFEXITED(st) || WEXITSTATUS(st) != 0) {
    printf("user nobody cannot run a copy of the program in %s (exit %d): a library it needs is "
           "out of nobody's reach\n",
           nobody_dir, WIFEXITED(st) ? WEXITSTATUS(st) : -1);
    return NULL;
  }
  return nobody_cli;
}

typedef struct {
  long long fsize_limit; /* RLIMIT_FSIZE in bytes; < 0: none */
  int as_nobody;         /* run as uid/gid 65534 (only when we are root) */
} limits;

/* Runs `$VL_CLI --db DB args...` (args NULL-terminated) under lim; stderr
 * into *err_text (malloc'd). Returns the exit status, or -1 on a signal. */
static int cli_v(const limits *lim, const char *db, char **err_text, char *const args[]) {
  const char *cli_path = getenv("VL_CLI");
  if (!cli_path) fail_msg("VL_CLI is not set (run the tests through ctest)");
  if (lim && lim->as_nobody && geteuid() == 0 && !(cli_path = cli_for_nobody()))
    fail_msg("user nobody cannot run the program (see above)");
  char *argv[40];
  int argc = 0;
  argv[argc++] = (char *)cli_path;
  argv[argc++] = "--db";
  argv[argc++] = (char *)db;
  for (int i = 0; args[i] && argc < 39; i++)
    argv[argc++] = args[i];
  argv[argc] = NULL;

  /* stderr through a pipe: a file would itself hit the size limit */
  int fds[2];
  if (pipe(fds) != 0) fail_msg("pipe: %s", strerror(errno));
  pid_t pid = fork();
  if (pid == 0) {
    int null = open("/dev/null", O_RDWR);
    dup2(null, 0);
    dup2(null, 1);
    dup2(fds[1], 2);
    close(fds[0]);
    close(fds[1]);
    if (lim && lim->fsize_limit >= 0) {
      /* a write past the limit then fails with EFBIG instead of killing */
      signal(SIGXFSZ, SIG_IGN);
      struct rlimit rl = {(rlim_t)lim->fsize_limit, (rlim_t)lim->fsize_limit};
      if (setrlimit(RLIMIT_FSIZE, &rl) != 0) _exit(120);
    }
    if (lim && lim->as_nobody && geteuid() == 0) {
      if (setgroups(0, NULL) != 0 || setgid(NOBODY) != 0 || setuid(NOBODY) != 0) _exit(121);
    }
    execv(argv[0], argv);
    _exit(127);
  }
  close(fds[1]);
  size_t cap = 4096, n = 0;
  char *text = malloc(cap);
  ssize_t got;
  while ((got = read(fds[0], text + n, cap - n - 1)) != 0) {
    if (got < 0) {
      if (errno == EINTR) continue;
      break;
    }
    n += (size_t)got;
    if (n + 1 == cap) text = realloc(text, cap *= 2);
  }
  text[n] = '\0';
  close(fds[0]);
  int st;
  while (waitpid(pid, &st, 0) < 0)
    if (errno != EINTR) fail_msg("waitpid: %s", strerror(errno));
  if (err_text)
    *err_text = text;
  else
    free(text);
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* cli_v with the arguments listed, NULL-terminated. */
static int cli(const limits *lim, const char *db, char **err_text, ...) {
  char *args[36];
  int n = 0;
  va_list ap;
  va_start(ap, err_text);
  char *a;
  while ((a = va_arg(ap, char *)) != NULL && n < 35)
    args[n++] = a;
  va_end(ap);
  args[n] = NULL;
  return cli_v(lim, db, err_text, args);
}

/* A clear sentence for a failed write: says what failed and that nothing
 * was changed. */
static void assert_clear_write_error(const char *err, const char *what) {
  if (!err || !strstr(err, what) || !strstr(err, "nothing was changed") ||
      strchr(err, '\n') != strrchr(err, '\n'))
    fail_msg("unclear message (wanted '%s' and 'nothing was changed', one line): %s", what,
             err ? err : "(none)");
}

static char dir[4096], db[4200], psd[4200];

static int setup(void **state) {
  (void)state;
  snprintf(dir, sizeof dir, "%s", vl_test_tmpdir());
  chmod(dir, 0755); /* user nobody must reach it */
  snprintf(db, sizeof db, "%s/materials.db", dir);
  snprintf(psd, sizeof psd, "%s/psd.csv", dir);
  vl_db *h = NULL;
  vl_error err;
  assert_int_equal(vl_db_open(db, &h, &err), VL_OK);
  vl_db_close(h);
  /* 3000 points: about 30 pages of new rows in one transaction */
  FILE *f = fopen(psd, "w");
  assert_non_null(f);
  fprintf(f, "q_per_m,C_m4\n");
  for (int k = 0; k < 3000; k++) {
    double q = 1e3 * pow(1e6, k / 2999.0);
    fprintf(f, "%.10g,%.10g\n", q, 1e-20 * pow(q / 1e3, -3.6));
  }
  fclose(f);
  return 0;
}

static int teardown(void **state) {
  (void)state;
  char cmd[4300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) fprintf(stderr, "cannot remove %s\n", dir);
  return 0;
}

/* ---- RLIMIT_FSIZE ----------------------------------------------------- */

/* Runs args under file-size limits from the database's size upwards in
 * 4 KiB steps until the command fits: each failure must be clean. Returns
 * the number of limits that failed. */
static int limit_sweep(const char *label, char *const args[]) {
  vl_test_snapshot before = vl_test_take(db);
  int failed = 0, fit_pages = -1;
  char *err = NULL;
  for (int k = 0; k <= 64; k++) {
    limits lim = {(long long)before.n + 4096LL * k, 0};
    int rc = cli_v(&lim, db, &err, args);
    if (rc == 0) {
      fit_pages = k;
      break;
    }
    failed++;
    if (rc != EXIT_EIO)
      fail_msg("%s, limit +%d pages: exit %d, not the I/O status: %s", label, k, rc, err);
    assert_clear_write_error(err, "full");
    if (!vl_test_same_bytes(db, &before))
      fail_msg("%s, limit +%d pages: the database file changed", label, k);
    if (journal_state(db) == 2) fail_msg("%s, limit +%d pages: a hot journal was left", label, k);
    if (k == 0) printf("file size limit: %s: message: %s", label, err);
    free(err);
    err = NULL;
  }
  free(err);
  free(before.bytes);
  printf("file size limit: %s failed cleanly under %d limits (file size +0 to +%d KiB), database "
         "unchanged each time; succeeded with +%d KiB\n",
         label, failed, 4 * (failed - 1), 4 * fit_pages);
  if (fit_pages < 0) fail_msg("%s never fitted", label);
  return failed;
}

static void test_file_size_limit_sweep(void **state) {
  (void)state;
  char *args[] = {"surface", "add", "big", "--psd", psd, NULL};
  assert_true(limit_sweep("surface add of 3000 points", args) >= 3);
  /* the add that fitted is complete, and everything else is still there */
  vl_db *h = NULL;
  vl_error e;
  assert_int_equal(vl_db_open(db, &h, &e), VL_OK);
  vl_db_surface s;
  assert_int_equal(vl_db_surface_info(h, "big", &s, &e), VL_OK);
  assert_int_equal(s.n_points, 3000);
  assert_int_equal(vl_db_surface_info(h, "paper-1um", &s, &e), VL_OK);
  vl_db_close(h);
}

/* A compound fitted to measured DMA data: points, shifts, series and fit
 * report in one transaction. */
static void test_file_size_limit_measured(void **state) {
  (void)state;
  char file[4200];
  snprintf(file, sizeof file, "%s", vl_test_source_path("materials/sbr-filled-synthetic.csv"));
  char *args[] = {"compound", "add", "measured", "--measured", file, NULL};
  assert_true(limit_sweep("compound add --measured (273 points)", args) >= 2);
  vl_db *h = NULL;
  vl_error e;
  assert_int_equal(vl_db_open(db, &h, &e), VL_OK);
  vl_db_compound *c = malloc(sizeof *c);
  assert_int_equal(vl_db_compound_info(h, "measured", c, &e), VL_OK);
  assert_true(c->prony.n_terms > 0);
  free(c);
  vl_db_close(h);
}

/* No growth allowed at all: a 128-term compound, and a fluid. */
static void test_file_size_limit_compound(void **state) {
  (void)state;
  char prony[4200];
  snprintf(prony, sizeof prony, "%s/prony.csv", dir);
  FILE *f = fopen(prony, "w");
  assert_non_null(f);
  fprintf(f, "A,tau_s\n");
  for (int i = 0; i < 128; i++)
    fprintf(f, "%.6g,%.6g\n", 0.05 + 0.01 * i, 1e-9 * pow(10.0, 18.0 * i / 127.0));
  fclose(f);
  vl_test_snapshot before = vl_test_take(db);
  limits lim = {(long long)before.n, 0};
  char *err = NULL;
  int rc = cli(&lim, db, &err, "compound", "add", "big", "--prony", prony, "--e-inf", "1e9", "--nu",
               "0.5", NULL);
  assert_int_equal(rc, EXIT_EIO);
  assert_clear_write_error(err, "full");
  free(err);
  assert_true(vl_test_same_bytes(db, &before));
  assert_int_not_equal(journal_state(db), 2);
  /* without the limit the same command works */
  assert_int_equal(cli(NULL, db, NULL, "compound", "add", "big", "--prony", prony, "--e-inf", "1e9",
                       "--nu", "0.5", NULL),
                   0);
  free(before.bytes);
}

/* A new database cannot be created under a small limit: clear error, and
 * no file left behind (the program removes the file it created). */
static void test_file_size_limit_create(void **state) {
  (void)state;
  char fresh[4200];
  snprintf(fresh, sizeof fresh, "%s/new.db", dir);
  const long long sizes[] = {0, 4096, 16384, 65536};
  for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++) {
    limits lim = {sizes[i], 0};
    char *err = NULL;
    int rc = cli(&lim, fresh, &err, "fluid", "list", NULL);
    if (rc != EXIT_EIO) fail_msg("limit %lld: exit %d: %s", sizes[i], rc, err);
    if (!strstr(err, "full")) fail_msg("limit %lld: unclear message: %s", sizes[i], err);
    if (i == 0) printf("file size limit, new database: message: %s", err);
    free(err);
    struct stat sb;
    char journal[4300];
    snprintf(journal, sizeof journal, "%s-journal", fresh);
    if (stat(fresh, &sb) == 0 || stat(journal, &sb) == 0)
      fail_msg("limit %lld: a half-created database was left behind", sizes[i]);
  }
  assert_int_equal(cli(NULL, fresh, NULL, "fluid", "list", NULL), 0);
}

/* ---- a real full file system ------------------------------------------ */

/* Unmounts the test's tmpfs, detaching it lazily if it is still busy, so
 * that no mount outlives the test. */
static void unmount(const char *mnt) {
  for (int k = 0; k < 50; k++) {
    if (umount(mnt) == 0 || errno == EINVAL) return;
    usleep(20000);
  }
  if (umount2(mnt, MNT_DETACH) != 0)
    fprintf(stderr, "cannot unmount %s: %s\n", mnt, strerror(errno));
}

/* A 256 KiB tmpfs at dir/name (into mnt). Only a missing privilege
 * excuses the test that asked (the file-size limits of the other tests
 * still run): it is then skipped, saying so; any other mount failure fails
 * it. */
static void mount_small_tmpfs(char *mnt, size_t size, const char *name) {
  snprintf(mnt, size, "%s/%s", dir, name);
  assert_int_equal(mkdir(mnt, 0755), 0);
  if (mount("tmpfs", mnt, "tmpfs", 0, "size=256k,mode=0755") == 0) return;
  int e = errno;
  rmdir(mnt);
  if (e != EPERM) fail_msg("%s: mount failed: %s", name, strerror(e));
  printf("%s: skipped, mounting needs CAP_SYS_ADMIN (%s)\n", name, strerror(e));
  skip();
}

static void test_tmpfs_full(void **state) {
  (void)state;
  char mnt[4200], small[4300], filler[4300];
  mount_small_tmpfs(mnt, sizeof mnt, "tmpfs");
  snprintf(small, sizeof small, "%s/materials.db", mnt);
  snprintf(filler, sizeof filler, "%s/filler", mnt);
  vl_test_snapshot orig = vl_test_take(db);
  FILE *f = fopen(small, "wb");
  int copied = f && fwrite(orig.bytes, 1, orig.n, f) == orig.n;
  if (f) copied &= fclose(f) == 0;
  free(orig.bytes);
  if (!copied) {
    unmount(mnt);
    fail_msg("the database does not fit the 256 KiB tmpfs");
  }
  /* fill the file system but for 3 pages */
  f = fopen(filler, "wb");
  char page[4096];
  memset(page, 0xAB, sizeof page);
  while (fwrite(page, 1, sizeof page, f) == sizeof page && fflush(f) == 0) {
  }
  fclose(f);
  struct stat sb;
  stat(filler, &sb);
  truncate(filler, sb.st_size > 3 * 4096 ? sb.st_size - 3 * 4096 : 0);

  vl_test_snapshot before = vl_test_take(small);
  char *err = NULL;
  int rc = cli(NULL, small, &err, "surface", "add", "big", "--psd", psd, NULL);
  int unchanged = vl_test_same_bytes(small, &before), js = journal_state(small);
  printf("tmpfs full: surface add: exit %d, message: %s", rc, err);
  /* room again: the same command works, on the same file */
  unlink(filler);
  int rc2 = cli(NULL, small, NULL, "surface", "add", "big", "--psd", psd, NULL);
  unmount(mnt); /* before any assertion: teardown removes the directory */
  rmdir(mnt);
  free(before.bytes);
  assert_int_equal(rc, EXIT_EIO);
  assert_clear_write_error(err, "full");
  free(err);
  assert_true(unchanged);
  assert_int_not_equal(js, 2);
  assert_int_equal(rc2, 0);
}

/* ---- a sweep's results on a full disk ------------------------------------ */

/* A dry scene whose fields files (grid 512: about 50 KB each) are much
 * larger than its curve (7 rows, under 3 KB). */
static const char *big_fields_scene(void) {
  static char path[4300];
  snprintf(path, sizeof path, "%s/fields.ini", dir);
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fputs("[materials]\ncompound = model-rubber\n[contact]\nradius_m = 0.01\n"
        "load_n_per_m = 1000\nsigma_s_pa = 0\n[sweep]\nquantity = deborah\nfrom = 1e-3\n"
        "to = 1e3\npoints = 7\nfields_at = 0.01, 1, 100\n[effects]\nviscoelastic = on\n"
        "roughness = off\nfluid = off\nsolid_shear = off\n[numerics]\ngrid = 512\n"
        "domain_a0 = -1.5, 1.5\ntolerance = 1e-9\n",
        f);
  fclose(f);
  return path;
}

static size_t lines_of(const char *path) {
  FILE *f = fopen(path, "r");
  size_t n = 0;
  for (int c; f && (c = fgetc(f)) != EOF;)
    n += c == '\n';
  if (f) fclose(f);
  return n;
}

/* The files that fit are complete and recorded; the message names those
 * that did not; no temporary is left. out: the run's --out. NULL when so,
 * else what is wrong (static storage): the caller may have a file system
 * to unmount before it fails. */
static const char *kept_what_fits(const char *out, int rc, const char *err) {
  static char why[8192];
  printf("run on a full disk: exit %d, stderr:\n%s", rc, err);
  if (rc != EXIT_EIO) return snprintf(why, sizeof why, "exit %d, not %d", rc, EXIT_EIO), why;
  if (!strstr(err, "3 files could not be written (the others are complete): fields/001.csv, "
                   "fields/003.csv, fields/005.csv\n"))
    return snprintf(why, sizeof why, "the files that did not fit are not named: %s", err), why;
  char path[4400];
  snprintf(path, sizeof path, "%s/curve.csv", out);
  if (lines_of(path) != 1 + 7) return "curve.csv is not complete";
  snprintf(path, sizeof path, "%s/run.json", out);
  char *m = vl_test_read_file(path);
  int ok = m && vl_test_json_valid(m) && strstr(m, "\"files\": [\"curve.csv\"]") &&
           strstr(m, "{\"file\": \"fields/001.csv\", \"error\": ");
  snprintf(why, sizeof why, "run.json does not record what was written: %s", m ? m : "(none)");
  free(m);
  if (!ok) return why;
  for (int k = 0; k < 2; k++) {
    snprintf(path, sizeof path, k ? "%s/fields" : "%s", out);
    DIR *d = opendir(path);
    for (struct dirent *e; d && (e = readdir(d));)
      if (strstr(e->d_name, ".tmp.")) {
        snprintf(why, sizeof why, "temporary left: %s/%s", path, e->d_name);
        closedir(d);
        return why;
      }
    if (d) closedir(d);
  }
  return NULL;
}

/* File-size limit (EFBIG): the curve and the manifest fit, the fields do
 * not. Without the limit the same run writes them all. */
static void test_run_keeps_what_fits(void **state) {
  (void)state;
  char out[4300], *err = NULL;
  snprintf(out, sizeof out, "%s/run", dir);
  const char *scene = big_fields_scene();
  limits lim = {16384, 0};
  int rc = cli(&lim, db, &err, "run", scene, "--out", out, NULL);
  const char *why = kept_what_fits(out, rc, err);
  if (why) fail_msg("%s", why);
  assert_non_null(strstr(err, "File too large"));
  free(err);
  rc = cli(NULL, db, &err, "run", scene, "--out", out, NULL);
  if (rc != 0) fail_msg("without the limit: exit %d: %s", rc, err);
  free(err);
  char path[4400];
  snprintf(path, sizeof path, "%s/fields/003.csv", out);
  assert_int_equal(lines_of(path), 1 + 512);
}

/* A real full file system (tmpfs, needs CAP_SYS_ADMIN): the same. */
static void test_run_tmpfs_full(void **state) {
  (void)state;
  char mnt[4200], filler[4300], out[4300];
  mount_small_tmpfs(mnt, sizeof mnt, "tmpfs-run");
  snprintf(filler, sizeof filler, "%s/filler", mnt);
  snprintf(out, sizeof out, "%s/run", mnt);
  FILE *f = fopen(filler, "wb");
  char page[4096];
  memset(page, 0xAB, sizeof page);
  while (f && fwrite(page, 1, sizeof page, f) == sizeof page && fflush(f) == 0) {
  }
  if (f) fclose(f);
  struct stat sb;
  stat(filler, &sb);
  /* room for the folders, the curve and the manifest, not for a fields file */
  truncate(filler, sb.st_size > 8 * 4096 ? sb.st_size - 8 * 4096 : 0);
  char *err = NULL;
  int rc = cli(NULL, db, &err, "run", big_fields_scene(), "--out", out, NULL);
  const char *why = kept_what_fits(out, rc, err);
  int nospace = strstr(err, "No space left on device") != NULL;
  free(err);
  unmount(mnt); /* before any assertion: teardown removes the directory */
  rmdir(mnt);
  if (why) fail_msg("%s", why);
  assert_true(nospace);
}

/* ---- read-only directory and read-only file --------------------------- */

/* The file is writable, its directory is not: SQLite cannot create the
 * rollback journal. Reads work; writes fail clearly; nothing changes. */
static void test_readonly_directory(void **state) {
  (void)state;
  char sub[4200], path[4300];
  snprintf(sub, sizeof sub, "%s/ro", dir);
  snprintf(path, sizeof path, "%s/materials.db", sub);
  assert_int_equal(mkdir(sub, 0755), 0);
  vl_test_snapshot orig = vl_test_take(db);
  FILE *f = fopen(path, "wb");
  assert_non_null(f);
  assert_int_equal(fwrite(orig.bytes, 1, orig.n, f), orig.n);
  fclose(f);
  free(orig.bytes);
  assert_int_equal(chmod(path, 0666), 0);
  assert_int_equal(chmod(sub, 0555), 0);
  limits lim = {-1, 1};
  /* root ignores permission bits: the commands run as nobody, from a copy
   * of the program nobody can reach; skipped only when even that fails */
  if (geteuid() == 0 && !cli_for_nobody()) {
    printf("read-only folder: skipped, user nobody cannot run even a copy of the program "
           "in a fresh /tmp folder (root ignores permission bits, so the case needs nobody)\n");
    skip();
  }
  vl_test_snapshot before = vl_test_take(path);
  char *err = NULL;
  int rc = cli(&lim, path, &err, "fluid", "show", "water", NULL);
  if (rc != 0) fail_msg("reading as user nobody: exit %d: %s", rc, err);
  free(err);
  rc = cli(&lim, path, &err, "fluid", "add", "oil", "--viscosity", "0.1", NULL);
  printf("read-only directory: fluid add: exit %d, message: %s", rc, err ? err : "(none)\n");
  assert_true(rc == EXIT_EIO || rc == EXIT_EDB);
  assert_clear_write_error(err, "journal");
  free(err);
  rc = cli(&lim, path, &err, "compound", "remove", "model-rubber", NULL);
  assert_true(rc == EXIT_EIO || rc == EXIT_EDB);
  free(err);
  assert_true(vl_test_same_bytes(path, &before));
  chmod(sub, 0777); /* writable for nobody too: the same command works */
  assert_int_equal(cli(&lim, path, NULL, "fluid", "add", "oil", "--viscosity", "0.1", NULL), 0);
  free(before.bytes);
}

/* A crash left a hot journal (an interrupted write) and then the file was
 * made read-only: the program cannot roll the journal back, so it must not
 * read the half-written pages; it says what to do. */
static void test_readonly_file_with_hot_journal(void **state) {
  (void)state;
  vl_test_snapshot before = vl_test_take(db);
  /* a child that dies in the middle of a large write, after SQLite has
   * spilled pages into the file (cache of 2 pages) */
  pid_t pid = fork();
  if (pid == 0) {
    sqlite3 *h;
    if (sqlite3_open(db, &h) != SQLITE_OK) _exit(1);
    sqlite3_exec(h,
                 "PRAGMA cache_size = 2; BEGIN; UPDATE surface SET description = "
                 "printf('%.*c', 3000, 'x'); UPDATE fluid SET description = "
                 "printf('%.*c', 3000, 'y');",
                 NULL, NULL, NULL);
    _exit(0); /* no COMMIT, no close: as a kill would leave it */
  }
  int st;
  waitpid(pid, &st, 0);
  assert_int_equal(journal_state(db), 2);
  assert_false(vl_test_same_bytes(db, &before)); /* the file itself was written */
  assert_int_equal(chmod(db, 0444), 0);
  char *err = NULL;
  int rc = cli(NULL, db, &err, "fluid", "list", NULL);
  printf("read-only file with a hot journal: fluid list: exit %d, message: %s", rc,
         err ? err : "(none)\n");
  assert_int_equal(rc, EXIT_EDB);
  if (!strstr(err, "interrupted") || !strstr(err, "writable")) fail_msg("unclear message: %s", err);
  free(err);
  assert_int_equal(journal_state(db), 2); /* still there: nothing lost */
  /* writable again: the next run rolls the journal back, content as before */
  assert_int_equal(chmod(db, 0644), 0);
  assert_int_equal(cli(NULL, db, NULL, "fluid", "list", NULL), 0);
  assert_int_equal(journal_state(db), 0);
  assert_true(vl_test_same_bytes(db, &before));
  free(before.bytes);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup_teardown(test_file_size_limit_sweep, setup, teardown),
      cmocka_unit_test_setup_teardown(test_file_size_limit_measured, setup, teardown),
      cmocka_unit_test_setup_teardown(test_file_size_limit_compound, setup, teardown),
      cmocka_unit_test_setup_teardown(test_file_size_limit_create, setup, teardown),
      cmocka_unit_test_setup_teardown(test_tmpfs_full, setup, teardown),
      cmocka_unit_test_setup_teardown(test_run_keeps_what_fits, setup, teardown),
      cmocka_unit_test_setup_teardown(test_run_tmpfs_full, setup, teardown),
      cmocka_unit_test_setup_teardown(test_readonly_directory, setup, teardown),
      cmocka_unit_test_setup_teardown(test_readonly_file_with_hot_journal, setup, teardown),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
