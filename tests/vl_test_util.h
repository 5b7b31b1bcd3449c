/* Small helpers shared by the cmocka tests: temporary directories, files,
 * running the command-line program (also on a per-test scratch database),
 * a strict JSON validator and byte-for-byte file snapshots. Tests include
 * this after cmocka.h. */
#ifndef VL_TEST_UTIL_H
#define VL_TEST_UTIL_H

#include <stddef.h>

/* A fresh directory under $TMPDIR (or /tmp); the returned string is static
 * storage overwritten by the next call. Aborts the test on failure. */
const char *vl_test_tmpdir(void);

/* max |x - ref| / max |ref| over n values (a solve against a reference). */
double vl_test_max_rel_diff(const double *x, const double *ref, size_t n);

/* Writes text to path (aborts the test on failure). */
void vl_test_write_file(const char *path, const char *text);

/* Reads a whole file into a malloc'd NUL-terminated string (NULL if absent). */
char *vl_test_read_file(const char *path);

/* The number after the nth (0-based) occurrence of the key "key": in the
 * JSON text (NAN for null); fails the test when the key is missing or its
 * value is not a number. */
double vl_test_json_number(const char *json, const char *key, size_t nth);

/* A growing text (free s when done): vl_test_text_add appends printf-style,
 * failing the test when out of memory. */
typedef struct {
  char *s;
  size_t n, cap;
} vl_test_text;
void vl_test_text_add(vl_test_text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Runs `$VL_CLI <args>` through /bin/sh with the given extra environment
 * assignments prefix (may be NULL, e.g. "VISCOLUBE_DB=/tmp/x.db"), captures
 * stdout and stderr into malloc'd strings (caller frees; pass NULL to drop)
 * and returns the exit status (or -1 if it did not exit normally). */
int vl_test_cli(const char *env_prefix, const char *args, char **out, char **err);

/* Path of a file in the source tree ($VL_SOURCE_DIR/rel) in static storage. */
const char *vl_test_source_path(const char *rel);

/* Relative difference |a-b|/max(|b|, tiny). */
double vl_test_rel(double a, double b);

/* ---- JSON: a strict validator (RFC 8259 grammar), independent of the
 * program's writer ---------------------------------------------------- */

/* 1 if s (may be NULL: 0) is exactly one JSON value with optional white
 * space around it, nesting at most 32 deep. */
int vl_test_json_valid(const char *s);

/* As vl_test_json_valid, and the top level must be an array; *objects =
 * the number of objects directly inside it. */
int vl_test_json_array_valid(const char *s, size_t *objects);

/* ---- files byte for byte --------------------------------------------- */

typedef struct {
  unsigned char *bytes; /* malloc'd; the caller frees */
  size_t n;
} vl_test_snapshot;

/* The bytes of the file at path (fails the test if unreadable). */
vl_test_snapshot vl_test_take(const char *path);

/* 1 if the file at path holds exactly the bytes of s. */
int vl_test_same_bytes(const char *path, const vl_test_snapshot *s);

/* 1 if the database file at path holds exactly the bytes of s and no
 * rollback journal (path-journal) is left beside it. */
int vl_test_same_db(const char *path, const vl_test_snapshot *s);

/* ---- the command line on a per-test scratch database -------------------- */

/* The running test's scratch directory and database path (dir/m.db, not
 * created), set by vl_test_setup_db. */
extern char vl_test_dir[1024];
extern char vl_test_db[1200];

/* cmocka setup: a fresh vl_test_dir and its vl_test_db. Returns 0. */
int vl_test_setup_db(void **state);

/* Runs `$VL_CLI --db vl_test_db ARGS` (ARGS printf-style) with
 * VISCOLUBE_DB unset, as vl_test_cli. */
int vl_test_run(char **out, char **err, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* Path vl_test_dir/name in static storage (eight buffers in turn), written
 * with text when text is not NULL. */
const char *vl_test_scratch(const char *name, const char *text);

/* One failing command `--db vl_test_db ARGS`: exit status code, nothing on
 * stdout, exactly one line on stderr holding both needles (each may be
 * NULL), and the database file unchanged (vl_test_same_db). Fails the test
 * otherwise. */
void vl_test_expect_fail(int code, const char *needle1, const char *needle2, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* Runs sql on the database file at path through a connection of its own,
 * as another program would; fails the test on an error. */
void vl_test_sql(const char *path, const char *sql);

#endif
