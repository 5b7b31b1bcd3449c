/* Reading a whole input file (slurp.h): the readers parse text held in
 * memory, and a size limit keeps a wrong file (an image, a log) from being
 * read whole before it is refused. */
#include "slurp.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

vl_status vl_slurp(const char *path, size_t max_bytes, const char *what, char **buf, size_t *len,
                   vl_error *err) {
  vl_status st = VL_OK;
  char *b = NULL;
  size_t n = 0, cap = 0;
  *buf = NULL;
  *len = 0;
  FILE *f = fopen(path, "rb");
  if (!f) {
    vl_error_set(err, "%s: cannot open: %s", path, strerror(errno));
    return VL_EIO;
  }
  for (;;) {
    if (n + 1 >= cap) { /* room for the data and the terminating NUL */
      if (cap >= max_bytes) {
        vl_error_set(err, "%s: larger than %zu MiB: not %s", path, max_bytes >> 20, what);
        st = VL_EINPUT;
        goto cleanup;
      }
      size_t ncap = cap ? 2 * cap : 65536;
      char *nb = realloc(b, ncap);
      if (!nb) {
        vl_error_set(err, "%s: out of memory", path);
        st = VL_ENOMEM;
        goto cleanup;
      }
      b = nb;
      cap = ncap;
    }
    size_t got = fread(b + n, 1, cap - n - 1, f);
    n += got;
    if (got == 0) break;
  }
  if (ferror(f)) {
    vl_error_set(err, "%s: cannot read: %s", path, strerror(errno));
    st = VL_EIO;
    goto cleanup;
  }
  b[n] = '\0';
  *buf = b;
  *len = n;
  b = NULL;

cleanup:
  free(b);
  fclose(f);
  return st;
}

vl_status vl_text_refuse_nul(const char *text, size_t len, const char *path, vl_error *err) {
  const char *nul = memchr(text, '\0', len);
  if (!nul) return VL_OK;
  int line = 1;
  for (const char *p = text; p < nul; p++)
    line += *p == '\n';
  vl_error_set(err, "%s:%d: not a text file (contains a NUL byte)", path, line);
  return VL_EINPUT;
}
