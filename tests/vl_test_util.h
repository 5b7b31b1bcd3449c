/* Small helpers shared by the cmocka tests: temporary directories, files and
 * running the command-line program. Tests include this after cmocka.h. */
#ifndef VL_TEST_UTIL_H
#define VL_TEST_UTIL_H

#include <stddef.h>

/* A fresh directory under $TMPDIR (or /tmp); the returned string is static
 * storage overwritten by the next call. Aborts the test on failure. */
const char *vl_test_tmpdir(void);

/* Writes text to path (aborts the test on failure). */
void vl_test_write_file(const char *path, const char *text);

/* Reads a whole file into a malloc'd NUL-terminated string (NULL if absent). */
char *vl_test_read_file(const char *path);

/* Runs `$VL_CLI <args>` through /bin/sh with the given extra environment
 * assignments prefix (may be NULL, e.g. "VISCOLUBE_DB=/tmp/x.db"), captures
 * stdout and stderr into malloc'd strings (caller frees; pass NULL to drop)
 * and returns the exit status (or -1 if it did not exit normally). */
int vl_test_cli(const char *env_prefix, const char *args, char **out, char **err);

/* Path of a file in the source tree ($VL_SOURCE_DIR/rel) in static storage. */
const char *vl_test_source_path(const char *rel);

/* Relative difference |a-b|/max(|b|, tiny). */
double vl_test_rel(double a, double b);

#endif
