/* viscolube: result codes and the caller-owned error message.
 *
 * Every fallible library function returns a vl_status and, on failure, writes
 * one human-readable sentence into a vl_error the caller owns (it may be NULL).
 * The library never prints and never exits; the command line does both. */
#ifndef VISCOLUBE_STATUS_H
#define VISCOLUBE_STATUS_H

typedef enum {
  VL_OK = 0,
  VL_EINPUT,    /* bad input: file, line, field or option named in the message */
  VL_ENOMEM,    /* allocation failed */
  VL_ENOTFOUND, /* a named material (compound, surface, fluid) does not exist */
  VL_EEXIST,    /* a name is already taken */
  VL_EDB,       /* database error: corrupt, read-only, locked, newer schema */
  VL_EIO,       /* file could not be read or written */
  VL_ENOCONV,   /* a nonlinear solve did not converge */
  VL_EINTERNAL  /* a bug: an invariant failed */
} vl_status;

#define VL_ERROR_MAX 1024

typedef struct {
  char msg[VL_ERROR_MAX];
} vl_error;

/* Writes a printf-style message into err (no-op when err is NULL). */
void vl_error_set(vl_error *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Prepends "prefix: " to the message already in err (for adding context). */
void vl_error_prefix(vl_error *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* A short stable name for a status ("input error", "not found", ...). */
const char *vl_status_name(vl_status status);

/* Exit code the command line uses for a status (0 for VL_OK). */
int vl_status_exit_code(vl_status status);

#endif
