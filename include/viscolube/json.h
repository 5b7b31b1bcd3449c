/* viscolube: a small streaming JSON writer, used by every JSON output of the
 * program (curves, points, materials, flattening).
 *
 * A document is written as it is built: containers are begun and ended,
 * an object's members are a key followed by one value. The writer puts the
 * commas and the spacing; strings are escaped; a number that is not finite
 * is written as null (JSON has none), and -0 as 0 (readers compare text,
 * and "-0" looks like a sign). It never allocates and never fails on its
 * own: output errors are the stream's (ferror), and a misuse (a key outside
 * an object, two keys in a row, nesting deeper than VL_JSON_DEPTH_MAX,
 * ending nothing) is recorded in `misused` for the tests to see.
 *
 *   vl_json w;
 *   vl_json_init(&w, stdout, 10);
 *   vl_json_object_begin(&w, VL_JSON_INLINE);
 *   vl_json_key_number(&w, "mu", 0.25);
 *   vl_json_end(&w);   ->  {"mu": 0.25}
 */
#ifndef VISCOLUBE_JSON_H
#define VISCOLUBE_JSON_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

/* How a container spaces its members. The shapes are those the program's
 * outputs have always had (a reader may depend on the line structure). */
typedef enum {
  VL_JSON_INLINE,  /* {"a": 1, "b": 2}: one line */
  VL_JSON_ROWS,    /* [\n  m1,\n  m2\n]\n: a member a line, indented by two
                      spaces, the closing bracket alone on the last line
                      (and the line ended after it) */
  VL_JSON_STACKED, /* [m1,\n m2]: a member a line, aligned under the first */
  VL_JSON_BLOCKS   /* {\n"k1": m1,\n"k2": m2}: every member starts a line */
} vl_json_layout;

#define VL_JSON_DEPTH_MAX 16

typedef struct {
  unsigned char layout; /* vl_json_layout */
  bool object;
  size_t members; /* written so far */
} vl_json_level;

typedef struct {
  FILE *out;
  int digits;       /* significant digits of vl_json_number; 0: exact (see below) */
  size_t depth;     /* containers open */
  bool key_pending; /* a key was written: its value comes next */
  bool misused;
  vl_json_level level[VL_JSON_DEPTH_MAX];
} vl_json;

/* Starts a document on out. digits: the significant digits of
 * vl_json_number (10 for computed results, as the CSV files have); 0 writes
 * every number exactly, with 15 digits or, when 15 do not read back to the
 * same double, 17. */
void vl_json_init(vl_json *w, FILE *out, int digits);

void vl_json_object_begin(vl_json *w, vl_json_layout layout);
void vl_json_array_begin(vl_json *w, vl_json_layout layout);
/* Ends the innermost open container. */
void vl_json_end(vl_json *w);

/* The key of the next member of the open object. */
void vl_json_key(vl_json *w, const char *key);

/* Values: a member of the open array, the value of the pending key, or the
 * whole document. s NULL writes null. */
void vl_json_string(vl_json *w, const char *s);
void vl_json_number(vl_json *w, double v);
/* v with the given significant digits (0: exact, as for vl_json_init). */
void vl_json_number_digits(vl_json *w, double v, int digits);
void vl_json_integer(vl_json *w, long long v);
void vl_json_bool(vl_json *w, bool v);
void vl_json_null(vl_json *w);

/* A key and its value in one call. */
void vl_json_key_string(vl_json *w, const char *key, const char *s);
void vl_json_key_number(vl_json *w, const char *key, double v);
void vl_json_key_integer(vl_json *w, const char *key, long long v);

#endif
