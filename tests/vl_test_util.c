#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

const char *vl_test_tmpdir(void) {
  static char path[4096];
  const char *base = getenv("TMPDIR");
  snprintf(path, sizeof path, "%s/vltest.XXXXXX", base && *base ? base : "/tmp");
  if (!mkdtemp(path)) fail_msg("mkdtemp failed");
  return path;
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
  snprintf(cmd, sizeof cmd, "%s %s %s </dev/null >%s 2>%s", env_prefix ? env_prefix : "", cli,
           args, outp, errp);
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

double vl_test_rel(double a, double b) {
  return fabs(a - b) / fmax(fabs(b), 1e-300);
}
