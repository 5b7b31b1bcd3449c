/* The JSON writer (json.h). */
#include "viscolube/json.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The text around the members of a container, by layout: after the opening
 * bracket (written with the first member), between two members, before
 * the closing bracket and after it. */
static const struct {
  const char *open, *sep, *close, *after;
} spacing[] = {
    [VL_JSON_INLINE] = {"", ", ", "", ""},
    [VL_JSON_ROWS] = {"\n  ", ",\n  ", "\n", "\n"},
    [VL_JSON_STACKED] = {"", ",\n ", "", ""},
    [VL_JSON_BLOCKS] = {"\n", ",\n", "", ""},
};

void vl_json_init(vl_json *w, FILE *out, int digits) {
  memset(w, 0, sizeof *w);
  w->out = out;
  w->digits = digits;
}

static vl_json_level *top(vl_json *w) {
  return w->depth > 0 && w->depth <= VL_JSON_DEPTH_MAX ? &w->level[w->depth - 1] : NULL;
}

/* The separator before a member of the open container (nothing for the
 * value of a key, whose separator came before the key). */
static void before_member(vl_json *w) {
  vl_json_level *l = top(w);
  if (!l) return;
  fputs(l->members ? spacing[l->layout].sep : spacing[l->layout].open, w->out);
  l->members++;
}

/* Before any value: a key in an object must come first. */
static void before_value(vl_json *w) {
  vl_json_level *l = top(w);
  if (w->key_pending) {
    w->key_pending = false;
    return;
  }
  if (l && l->object) w->misused = true;
  before_member(w);
}

/* A container nested deeper than VL_JSON_DEPTH_MAX is not written (its
 * members still are): it is counted so that the ends stay paired. */
static void begin(vl_json *w, bool object, vl_json_layout layout) {
  before_value(w);
  if (w->depth >= VL_JSON_DEPTH_MAX) {
    w->misused = true;
  } else {
    fputc(object ? '{' : '[', w->out);
    w->level[w->depth] = (vl_json_level){(unsigned char)layout, object, 0};
  }
  w->depth++;
}

void vl_json_object_begin(vl_json *w, vl_json_layout layout) { begin(w, true, layout); }

void vl_json_array_begin(vl_json *w, vl_json_layout layout) { begin(w, false, layout); }

void vl_json_end(vl_json *w) {
  vl_json_level *l = top(w);
  if (w->depth == 0 || w->key_pending) {
    w->misused = true;
    if (w->depth == 0) return;
  }
  w->depth--;
  if (!l) return; /* beyond VL_JSON_DEPTH_MAX: not written */
  fputs(spacing[l->layout].close, w->out);
  fputc(l->object ? '}' : ']', w->out);
  fputs(spacing[l->layout].after, w->out);
}

/* Quoted, with '"', '\\' and the control characters escaped (\n and \t by
 * name); other bytes, UTF-8 included, as they are. */
static void put_string(FILE *out, const char *s) {
  fputc('"', out);
  for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
    if (*p == '"' || *p == '\\')
      fprintf(out, "\\%c", *p);
    else if (*p == '\n')
      fputs("\\n", out);
    else if (*p == '\t')
      fputs("\\t", out);
    else if (*p < 0x20 || *p == 0x7f)
      fprintf(out, "\\u%04x", *p);
    else
      fputc(*p, out);
  }
  fputc('"', out);
}

void vl_json_key(vl_json *w, const char *key) {
  vl_json_level *l = top(w);
  if (!l || !l->object || w->key_pending) w->misused = true;
  before_member(w);
  put_string(w->out, key ? key : "");
  fputs(": ", w->out);
  w->key_pending = true;
}

void vl_json_string(vl_json *w, const char *s) {
  before_value(w);
  if (s)
    put_string(w->out, s);
  else
    fputs("null", w->out);
}

void vl_json_number_digits(vl_json *w, double v, int digits) {
  before_value(w);
  if (!isfinite(v)) {
    fputs("null", w->out);
    return;
  }
  if (v == 0.0) v = 0.0; /* -0 -> 0 */
  char buf[40];
  if (digits > 0) {
    snprintf(buf, sizeof buf, "%.*g", digits, v);
  } else {
    snprintf(buf, sizeof buf, "%.15g", v);
    if (strtod(buf, NULL) != v) snprintf(buf, sizeof buf, "%.17g", v);
  }
  fputs(buf, w->out);
}

void vl_json_number(vl_json *w, double v) { vl_json_number_digits(w, v, w->digits); }

void vl_json_integer(vl_json *w, long long v) {
  before_value(w);
  fprintf(w->out, "%lld", v);
}

void vl_json_bool(vl_json *w, bool v) {
  before_value(w);
  fputs(v ? "true" : "false", w->out);
}

void vl_json_null(vl_json *w) {
  before_value(w);
  fputs("null", w->out);
}

void vl_json_key_string(vl_json *w, const char *key, const char *s) {
  vl_json_key(w, key);
  vl_json_string(w, s);
}

void vl_json_key_number(vl_json *w, const char *key, double v) {
  vl_json_key(w, key);
  vl_json_number(w, v);
}

void vl_json_key_integer(vl_json *w, const char *key, long long v) {
  vl_json_key(w, key);
  vl_json_integer(w, v);
}
