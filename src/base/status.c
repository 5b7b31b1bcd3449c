#include "viscolube/status.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Messages quote the user's input (a unit, a name, a cell): a control byte
 * there (a carriage return, an escape) would reach the terminal as it is.
 * Every one becomes '?', except the newlines that separate the lines of a
 * message listing several problems. */
static void printable(char *msg) {
  for (char *c = msg; *c; c++)
    if (((unsigned char)*c < 0x20 && *c != '\n') || *c == 0x7f) *c = '?';
}

void vl_error_set(vl_error *err, const char *fmt, ...) {
  if (!err) return;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err->msg, sizeof err->msg, fmt, ap);
  va_end(ap);
  printable(err->msg);
}

void vl_error_prefix(vl_error *err, const char *fmt, ...) {
  if (!err) return;
  char prefix[VL_ERROR_MAX];
  char old[VL_ERROR_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(prefix, sizeof prefix, fmt, ap);
  va_end(ap);
  memcpy(old, err->msg, sizeof old);
  /* prefix + ": " + old, truncated to the buffer */
  size_t lp = strnlen(prefix, sizeof prefix), lo = strnlen(old, sizeof old),
         cap = sizeof err->msg - 1;
  size_t k = lp < cap ? lp : cap;
  memcpy(err->msg, prefix, k);
  for (const char *sep = ": "; *sep && k < cap; sep++)
    err->msg[k++] = *sep;
  size_t rest = lo < cap - k ? lo : cap - k;
  memcpy(err->msg + k, old, rest);
  err->msg[k + rest] = '\0';
  printable(err->msg);
}

const char *vl_status_name(vl_status status) {
  switch (status) {
  case VL_OK: return "ok";
  case VL_EINPUT: return "input error";
  case VL_ENOMEM: return "out of memory";
  case VL_ENOTFOUND: return "not found";
  case VL_EEXIST: return "already exists";
  case VL_EDB: return "database error";
  case VL_EIO: return "I/O error";
  case VL_ENOCONV: return "not converged";
  case VL_EINTERNAL: return "internal error";
  }
  return "unknown status";
}

int vl_status_exit_code(vl_status status) {
  switch (status) {
  case VL_OK: return 0;
  case VL_EINPUT: return 2;
  case VL_ENOTFOUND: return 3;
  case VL_EEXIST: return 4;
  case VL_EDB: return 5;
  case VL_EIO: return 6;
  case VL_ENOCONV: return 7;
  case VL_ENOMEM:
  case VL_EINTERNAL: return 70;
  }
  return 1;
}
