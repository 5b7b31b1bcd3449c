/* Helpers shared by the fuzz targets (vl_fuzz.h). */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif

#include "vl_fuzz.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

int vl_fuzz_report_fd = 2;

void vl_fuzz_fail(const char *file, int line, const char *fmt, ...) {
  char msg[2048];
  int k = snprintf(msg, sizeof msg, "FUZZ CHECK FAILED %s:%d: ", file, line);
  if (k < 0) k = 0;
  va_list ap;
  va_start(ap, fmt);
  if ((size_t)k < sizeof msg) vsnprintf(msg + k, sizeof msg - (size_t)k, fmt, ap);
  va_end(ap);
  size_t n = strlen(msg);
  if (n + 1 < sizeof msg) msg[n++] = '\n';
  if (write(vl_fuzz_report_fd, msg, n) < 0) { /* nothing better to do */
  }
  abort();
}

/* Writes all of buf at offset 0 of fd and cuts the file there. */
static int rewrite(int fd, const uint8_t *buf, size_t size) {
  if (ftruncate(fd, 0) != 0) return -1;
  size_t done = 0;
  while (done < size) {
    ssize_t w = pwrite(fd, buf + done, size - done, (off_t)done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return -1;
    done += (size_t)w;
  }
  return 0;
}

const char *vl_fuzz_file(const uint8_t *data, size_t size) {
  static int fd = -1;
  static char path[64];
  if (fd < 0) {
    /* An anonymous in-memory file: nothing is left on disk when a run is
     * killed, and fopen() of /proc/self/fd/N reads it from the start. */
    fd = memfd_create("vl-fuzz-input", MFD_CLOEXEC);
    if (fd < 0) vl_fuzz_fail(__FILE__, __LINE__, "memfd_create: %s", strerror(errno));
    snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
  }
  if (rewrite(fd, data, size) != 0)
    vl_fuzz_fail(__FILE__, __LINE__, "writing the input file: %s", strerror(errno));
  return path;
}

char *vl_fuzz_strdup(const uint8_t *data, size_t size) {
  char *s = malloc(size + 1);
  if (!s) vl_fuzz_fail(__FILE__, __LINE__, "out of memory");
  if (size) memcpy(s, data, size);
  s[size] = '\0';
  return s;
}

int vl_fuzz_message_clean(const char *msg, const char *path) {
  size_t lp = strlen(path);
  for (const char *c = msg; *c; c++) {
    if (*c == '\n') {
      if (strncmp(c + 1, path, lp) != 0 && strncmp(c + 1, "  ", 2) != 0) return 0;
      continue;
    }
    if ((unsigned char)*c < 0x20 || *c == 0x7f) return 0;
  }
  return 1;
}
