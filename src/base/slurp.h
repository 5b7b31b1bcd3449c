/* viscolube (private): reading a whole input file into memory. */
#ifndef VISCOLUBE_SLURP_H
#define VISCOLUBE_SLURP_H

#include <stddef.h>

#include "viscolube/status.h"

/* Reads the file at path into a malloc'd buffer (*buf, *len; the caller
 * free()s it; one extra byte, a NUL, follows the data). A file larger than
 * max_bytes is refused as VL_EINPUT "PATH: larger than N MiB: not WHAT";
 * VL_EIO when it cannot be opened or read, VL_ENOMEM. On failure *buf is
 * NULL. */
vl_status vl_slurp(const char *path, size_t max_bytes, const char *what, char **buf, size_t *len,
                   vl_error *err);

/* VL_EINPUT "PATH:LINE: not a text file (contains a NUL byte)" when
 * text[0..len) holds a NUL byte (LINE is where the first one is), else
 * VL_OK. */
vl_status vl_text_refuse_nul(const char *text, size_t len, const char *path, vl_error *err);

#endif
