/* Replays files through a fuzz target without libFuzzer (gcc builds):
 *   fuzz_xxx FILE|DIR...
 * Runs LLVMFuzzerTestOneInput once on every file (directories: every file in
 * them). The code under test's stdout/stderr go to /dev/null (the CLI target
 * prints); sanitizer reports and failed checks still reach the real stderr.
 * Exit status 0 when every input ran; a crash or failed check aborts. */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif

#include "vl_fuzz.h"

#include <dirent.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Present in ASan/UBSan runtimes only. */
extern void __sanitizer_set_report_fd(void *fd) __attribute__((weak));
extern int LLVMFuzzerInitialize(int *argc, char ***argv) __attribute__((weak));

static FILE *report;
static size_t n_inputs;

static int run_file(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) {
    fprintf(report, "replay: cannot open %s\n", path);
    return -1;
  }
  size_t cap = 4096, len = 0;
  uint8_t *buf = malloc(cap);
  size_t got;
  while (buf && (got = fread(buf + len, 1, cap - len, f)) > 0) {
    len += got;
    if (len == cap) {
      uint8_t *nb = realloc(buf, cap *= 2);
      if (!nb) free(buf);
      buf = nb;
    }
  }
  fclose(f);
  if (!buf) {
    fprintf(report, "replay: out of memory reading %s\n", path);
    return -1;
  }
  fprintf(report, "replay: %s (%zu bytes)\n", path, len);
  fflush(report);
  /* an exact-size copy, so ASan sees a read past the input's end */
  uint8_t *exact = malloc(len ? len : 1);
  if (len) memcpy(exact, buf, len);
  free(buf);
  LLVMFuzzerTestOneInput(exact, len);
  free(exact);
  n_inputs++;
  return 0;
}

static int run_path(const char *path) {
  struct stat sb;
  if (stat(path, &sb) != 0) {
    fprintf(report, "replay: no such file or directory: %s\n", path);
    return -1;
  }
  if (!S_ISDIR(sb.st_mode)) return run_file(path);
  DIR *d = opendir(path);
  if (!d) return -1;
  int rc = 0;
  struct dirent *e;
  while ((e = readdir(d)) != NULL) {
    if (e->d_name[0] == '.') continue;
    char child[4096];
    snprintf(child, sizeof child, "%s/%s", path, e->d_name);
    if (run_path(child) != 0) rc = -1;
  }
  closedir(d);
  return rc;
}

int main(int argc, char **argv) {
  int saved = dup(2);
  report = saved >= 0 ? fdopen(saved, "w") : stderr;
  if (saved >= 0) {
    vl_fuzz_report_fd = saved;
    if (__sanitizer_set_report_fd) __sanitizer_set_report_fd((void *)(intptr_t)saved);
    if (!getenv("VL_FUZZ_VERBOSE")) {
      int null = open("/dev/null", O_WRONLY);
      if (null >= 0) {
        dup2(null, 1);
        dup2(null, 2);
        close(null);
      }
    }
  }
  if (LLVMFuzzerInitialize) LLVMFuzzerInitialize(&argc, &argv);
  int rc = 0;
  for (int i = 1; i < argc; i++)
    if (run_path(argv[i]) != 0) rc = 1;
  if (argc < 2) {
    fprintf(report, "usage: %s FILE|DIR...\n", argv[0]);
    rc = 2;
  } else if (n_inputs == 0) {
    fprintf(report, "replay: no input found\n");
    rc = 1;
  }
  fprintf(report, "replay: %zu inputs, %s\n", n_inputs, rc ? "FAILED" : "ok");
  fclose(report);
  return rc;
}
