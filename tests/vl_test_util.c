#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "persson_internal.h"
#include "rheology_internal.h"
#include "vl_test_scenes.h"
#include "vl_test_util.h"

#include <sqlite3.h>

#include <ftw.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* Every directory of a test process lives under one root, removed when the
 * process exits (a test run made ~500 directories in /tmp and left them):
 * only by the process that made it, since tests fork children that exit
 * normally; VL_TEST_KEEP=1 keeps it for a look after a failure. */
static char tmp_root[4096];
static pid_t tmp_root_owner;

/* Directories made read-only by a test (test_disk_full) are opened up on the
 * way down, then everything is removed on the way up. */
static int open_up(const char *path, const struct stat *sb, int flag, struct FTW *ftw) {
  (void)ftw;
  if (flag == FTW_D || flag == FTW_DNR) chmod(path, (sb->st_mode & 07777) | S_IRWXU);
  return 0;
}
static int remove_entry(const char *path, const struct stat *sb, int flag, struct FTW *ftw) {
  (void)sb, (void)flag, (void)ftw;
  remove(path);
  return 0;
}

static void remove_tmp_root(void) {
  if (getpid() != tmp_root_owner || getenv("VL_TEST_KEEP")) return;
  nftw(tmp_root, open_up, 16, FTW_PHYS);
  nftw(tmp_root, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

/* A mkdtemp template: prefix followed by the six placeholder characters. */
static void temp_template(char *buf, size_t cap, const char *prefix) {
  int n = snprintf(buf, cap, "%s", prefix);
  if (n < 0 || (size_t)n + 7 > cap) fail_msg("temporary path too long: %s", prefix);
  memset(buf + n, 'X', 6);
  buf[n + 6] = '\0';
}

const char *vl_test_tmpdir(void) {
  static char path[4096 + 16];
  char prefix[4096 + 8];
  if (!tmp_root[0] || tmp_root_owner != getpid()) {
    const char *base = getenv("TMPDIR");
    snprintf(prefix, sizeof tmp_root - 8, "%s/vltest.", base && *base ? base : "/tmp");
    temp_template(tmp_root, sizeof tmp_root, prefix);
    if (!mkdtemp(tmp_root)) fail_msg("mkdtemp failed");
    /* traversable (not listable) by others: tests run the program as
     * another user on a directory of their own below */
    if (chmod(tmp_root, 0711) != 0) fail_msg("chmod %s failed", tmp_root);
    tmp_root_owner = getpid();
    atexit(remove_tmp_root);
  }
  snprintf(prefix, sizeof prefix, "%s/d.", tmp_root);
  temp_template(path, sizeof path, prefix);
  if (!mkdtemp(path)) fail_msg("mkdtemp failed");
  return path;
}

double vl_test_max_rel_diff(const double *x, const double *ref, size_t n) {
  double dmax = 0.0, rmax = 0.0;
  for (size_t i = 0; i < n; i++) {
    dmax = fmax(dmax, fabs(x[i] - ref[i]));
    rmax = fmax(rmax, fabs(ref[i]));
  }
  return dmax / rmax;
}

void vl_test_write_file(const char *path, const char *text) {
  FILE *f = fopen(path, "wb");
  if (!f) fail_msg("cannot write %s", path);
  fputs(text, f);
  fclose(f);
}

char *vl_test_read_file(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  size_t cap = 4096, len = 0;
  char *buf = malloc(cap);
  size_t got;
  while ((got = fread(buf + len, 1, cap - len - 1, f)) > 0) {
    len += got;
    if (cap - len - 1 == 0) buf = realloc(buf, cap *= 2);
  }
  buf[len] = '\0';
  fclose(f);
  return buf;
}

int vl_test_cli(const char *env_prefix, const char *args, char **out, char **err) {
  const char *cli = getenv("VL_CLI");
  if (!cli) fail_msg("VL_CLI is not set (run the tests through ctest)");
  char dir[4096];
  snprintf(dir, sizeof dir, "%s", vl_test_tmpdir());
  char cmd[16384], outp[4200], errp[4200];
  snprintf(outp, sizeof outp, "%s/stdout", dir);
  snprintf(errp, sizeof errp, "%s/stderr", dir);
  snprintf(cmd, sizeof cmd, "%s %s %s </dev/null >%s 2>%s", env_prefix ? env_prefix : "", cli, args,
           outp, errp);
  int st = system(cmd);
  if (out) *out = vl_test_read_file(outp);
  if (err) *err = vl_test_read_file(errp);
  unlink(outp);
  unlink(errp);
  rmdir(dir);
  if (st == -1 || !WIFEXITED(st)) return -1;
  return WEXITSTATUS(st);
}

const char *vl_test_source_path(const char *rel) {
  static char path[4096];
  const char *src = getenv("VL_SOURCE_DIR");
  snprintf(path, sizeof path, "%s/%s", src ? src : ".", rel);
  return path;
}

double vl_test_rel(double a, double b) { return fabs(a - b) / fmax(fabs(b), 1e-300); }

/* ---- JSON --------------------------------------------------------------- */

static void j_ws(const char **p) {
  while (**p == ' ' || **p == '\t' || **p == '\n' || **p == '\r')
    (*p)++;
}

static int j_string(const char **p) {
  if (**p != '"') return 0;
  (*p)++;
  while (**p != '"') {
    unsigned char c = (unsigned char)**p;
    if (c == '\0' || c < 0x20) return 0;
    if (c == '\\') {
      (*p)++;
      if (**p && strchr("\"\\/bfnrt", **p)) {
        (*p)++;
      } else if (**p == 'u') {
        (*p)++;
        for (int k = 0; k < 4; k++, (*p)++)
          if (!**p || !strchr("0123456789abcdefABCDEF", **p)) return 0;
      } else {
        return 0;
      }
    } else {
      (*p)++;
    }
  }
  (*p)++;
  return 1;
}

static int j_digits(const char **p) {
  const char *s = *p;
  while (**p >= '0' && **p <= '9')
    (*p)++;
  return *p > s;
}

static int j_number(const char **p) {
  if (**p == '-') (*p)++;
  if (**p == '0')
    (*p)++;
  else if (!(**p >= '1' && **p <= '9') || !j_digits(p))
    return 0;
  if (**p == '.') {
    (*p)++;
    if (!j_digits(p)) return 0;
  }
  if (**p == 'e' || **p == 'E') {
    (*p)++;
    if (**p == '+' || **p == '-') (*p)++;
    if (!j_digits(p)) return 0;
  }
  return 1;
}

static int j_word(const char **p, const char *w) {
  size_t n = strlen(w);
  if (strncmp(*p, w, n)) return 0;
  *p += n;
  return 1;
}

/* One value at *p; counts in *objects (if not NULL) the objects directly
 * inside a top-level container. */
static int j_value(const char **p, int depth, size_t *objects) {
  if (depth > 32) return 0;
  j_ws(p);
  if (**p == '{' || **p == '[') {
    char close = **p == '{' ? '}' : ']';
    int object = **p == '{';
    if (object && depth == 1 && objects) (*objects)++;
    (*p)++;
    j_ws(p);
    if (**p == close) {
      (*p)++;
      return 1;
    }
    for (;;) {
      if (object) {
        j_ws(p);
        if (!j_string(p)) return 0;
        j_ws(p);
        if (**p != ':') return 0;
        (*p)++;
      }
      if (!j_value(p, depth + 1, objects)) return 0;
      j_ws(p);
      if (**p == ',') {
        (*p)++;
        continue;
      }
      if (**p != close) return 0;
      (*p)++;
      return 1;
    }
  }
  if (**p == '"') return j_string(p);
  if (**p == 't') return j_word(p, "true");
  if (**p == 'f') return j_word(p, "false");
  if (**p == 'n') return j_word(p, "null");
  return j_number(p);
}

int vl_test_json_valid(const char *s) {
  if (!s) return 0;
  const char *p = s;
  if (!j_value(&p, 0, NULL)) return 0;
  j_ws(&p);
  return *p == '\0';
}

int vl_test_json_array_valid(const char *s, size_t *objects) {
  if (!s) return 0;
  const char *p = s;
  j_ws(&p);
  if (*p != '[') return 0;
  *objects = 0;
  if (!j_value(&p, 0, objects)) return 0;
  j_ws(&p);
  return *p == '\0';
}

/* ---- files byte for byte ---------------------------------------------- */

vl_test_snapshot vl_test_take(const char *path) {
  vl_test_snapshot s = {NULL, 0};
  FILE *f = fopen(path, "rb");
  if (!f) fail_msg("cannot read %s", path);
  size_t cap = 0;
  for (;;) {
    if (s.n == cap) {
      cap = cap ? 2 * cap : 65536;
      unsigned char *t = realloc(s.bytes, cap);
      if (!t) fail_msg("out of memory");
      s.bytes = t;
    }
    size_t got = fread(s.bytes + s.n, 1, cap - s.n, f);
    s.n += got;
    if (got == 0) break;
  }
  fclose(f);
  return s;
}

int vl_test_same_bytes(const char *path, const vl_test_snapshot *s) {
  vl_test_snapshot now = vl_test_take(path);
  int eq = now.n == s->n && memcmp(now.bytes, s->bytes, s->n) == 0;
  free(now.bytes);
  return eq;
}

int vl_test_same_db(const char *path, const vl_test_snapshot *s) {
  char journal[4200];
  snprintf(journal, sizeof journal, "%s-journal", path);
  return vl_test_same_bytes(path, s) && access(journal, F_OK) != 0;
}

/* ---- the command line on a per-test scratch database -------------------- */

char vl_test_dir[1024];
char vl_test_db[1200];

int vl_test_setup_db(void **state) {
  (void)state;
  snprintf(vl_test_dir, sizeof vl_test_dir, "%s", vl_test_tmpdir());
  snprintf(vl_test_db, sizeof vl_test_db, "%s/m.db", vl_test_dir);
  return 0;
}

int vl_test_run(char **out, char **err, const char *fmt, ...) {
  char args[8192];
  int k = snprintf(args, sizeof args, "--db %s ", vl_test_db);
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(args + k, sizeof args - (size_t)k, fmt, ap);
  va_end(ap);
  return vl_test_cli("env -u VISCOLUBE_DB", args, out, err);
}

const char *vl_test_scratch(const char *name, const char *text) {
  static char path[8][1300];
  static int next;
  char *p = path[next++ % 8];
  snprintf(p, sizeof path[0], "%s/%s", vl_test_dir, name);
  if (text) vl_test_write_file(p, text);
  return p;
}

void vl_test_expect_fail(int code, const char *needle1, const char *needle2, const char *fmt, ...) {
  char args[8192];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(args, sizeof args, fmt, ap);
  va_end(ap);
  vl_test_snapshot before = vl_test_take(vl_test_db);
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "%s", args);
  if (rc != code) fail_msg("`%s`: exit %d, expected %d (stderr: %s)", args, rc, code, err);
  if (!out || out[0]) fail_msg("`%s`: unexpected stdout: %s", args, out);
  size_t len = err ? strlen(err) : 0;
  if (len < 2 || err[len - 1] != '\n' || strchr(err, '\n') != err + len - 1)
    fail_msg("`%s`: stderr is not exactly one line: '%s'", args, err);
  if (needle1 && !strstr(err, needle1)) fail_msg("`%s`: '%s' lacks '%s'", args, err, needle1);
  if (needle2 && !strstr(err, needle2)) fail_msg("`%s`: '%s' lacks '%s'", args, err, needle2);
  if (!vl_test_same_db(vl_test_db, &before)) fail_msg("`%s` changed the database file", args);
  free(before.bytes);
  free(out);
  free(err);
}

/* ---- the seed's fig05 contact ------------------------------------------- */

vl_persson *vl_test_paper_surface(double hrms_m, vl_psd *psd) {
  vl_error err;
  vl_persson *tab = NULL;
  if (vl_psd_init_self_affine(psd, 0.8, 2e5, 7.8e9, hrms_m, &err) != VL_OK ||
      vl_persson_build(psd, 0, &tab, &err) != VL_OK)
    fail_msg("paper surface, h_rms %g m: %s", hrms_m, err.msg);
  return tab;
}

void vl_test_fig05_config(vl_contact_config *cfg, const vl_persson *tab, double eta_pa_s,
                          size_t grid, double x_min_a0) {
  vl_contact_config_defaults(cfg);
  cfg->rubber = vl_prony_single(3.6e6, 10.0, 0.1, 0.5);
  cfg->radius_m = 0.01;
  cfg->load_n_per_m = 1000.0;
  cfg->sigma_s_pa = 1e6;
  cfg->roughness = tab;
  cfg->eta_pa_s = eta_pa_s;
  cfg->flow_factors = VL_FLOW_FACTORS_PATIR_CHENG;
  cfg->grid = grid;
  cfg->x_min_a0 = x_min_a0;
  cfg->x_max_a0 = 1.6;
}

void vl_test_sql(const char *path, const char *sql) {
  sqlite3 *h = NULL;
  char *msg = NULL;
  assert_int_equal(sqlite3_open(path, &h), SQLITE_OK);
  if (sqlite3_exec(h, sql, NULL, NULL, &msg) != SQLITE_OK) fail_msg("%s: %s", sql, msg);
  sqlite3_close(h);
}

void vl_test_text_add(vl_test_text *t, const char *fmt, ...) {
  va_list ap;
  for (;;) {
    va_start(ap, fmt);
    int w = vsnprintf(t->s ? t->s + t->n : NULL, t->s ? t->cap - t->n : 0, fmt, ap);
    va_end(ap);
    if (t->s && (size_t)w < t->cap - t->n) {
      t->n += (size_t)w;
      return;
    }
    t->cap = 2 * (t->cap + (size_t)w + 64);
    t->s = realloc(t->s, t->cap);
    if (!t->s) fail_msg("out of memory");
    if (t->n == 0) t->s[0] = '\0';
  }
}

#if defined(__SANITIZE_ADDRESS__)
/* Every test that draws a figure in its own process (test_plot,
 * test_cli_outputs): fontconfig, below PLplot's cairo drivers, keeps caches
 * it never frees. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void) { return "leak:libfontconfig.so\n"; }
const char *__lsan_default_options(void);
const char *__lsan_default_options(void) { return "print_suppressions=0"; }
#endif

double vl_test_json_number(const char *json, const char *key, size_t nth) {
  char pat[128];
  snprintf(pat, sizeof pat, "\"%s\":", key);
  const char *p = json;
  for (size_t i = 0; p && i <= nth; i++) {
    p = strstr(p, pat);
    if (p && i < nth) p += strlen(pat);
  }
  if (!p) fail_msg("no key %s (#%zu) in the JSON", key, nth);
  p += strlen(pat);
  while (*p == ' ')
    p++;
  if (!strncmp(p, "null", 4)) return NAN;
  char *end;
  double v = strtod(p, &end);
  if (end == p) fail_msg("key %s is not a number", key);
  return v;
}
