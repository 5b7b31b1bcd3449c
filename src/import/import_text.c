/* The text reading shared by the readers of the import layer
 * (import_text.h): spans, whole files, meaningful lines, spreadsheet
 * refusal, dialect detection, strict numbers and problem lists. */
#define _POSIX_C_SOURCE 200809L

#include "import_text.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SAMPLE_LINES 50
#define NUMBER_MAX_CHARS 128
/* Longest excerpt of a cell quoted back in a message. */
#define EXCERPT_MAX_CHARS 40

static int lower(int c) { return c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c; }

/* ---- spans --------------------------------------------------------------- */

int vl_is_blank(char c) { return c == ' ' || c == '\t'; }

vl_span vl_span_trim(vl_span s) {
  while (s.n > 0 && vl_is_blank(s.p[0]))
    s.p++, s.n--;
  while (s.n > 0 && vl_is_blank(s.p[s.n - 1]))
    s.n--;
  return s;
}

vl_span vl_span_unquote(vl_span s) {
  s = vl_span_trim(s);
  if (s.n >= 2 && s.p[0] == '"' && s.p[s.n - 1] == '"') {
    s.p++;
    s.n -= 2;
    s = vl_span_trim(s);
  }
  return s;
}

int vl_span_eq(vl_span s, const char *t) {
  size_t n = strlen(t);
  return s.n == n && memcmp(s.p, t, n) == 0;
}

int vl_span_eq_nocase(vl_span s, const char *t) {
  size_t n = strlen(t);
  if (s.n != n) return 0;
  for (size_t i = 0; i < n; i++)
    if (lower((unsigned char)s.p[i]) != lower((unsigned char)t[i])) return 0;
  return 1;
}

int vl_span_has(vl_span s, char c) { return s.n > 0 && memchr(s.p, c, s.n) != NULL; }

void vl_span_excerpt(vl_span s, char *buf, size_t size) {
  size_t k = 0;
  for (size_t i = 0; i < s.n && k + 4 < size && i < EXCERPT_MAX_CHARS; i++) {
    unsigned char c = (unsigned char)s.p[i];
    buf[k++] = (c < 0x20 || c == 0x7f) ? '?' : (char)c;
  }
  if (s.n > EXCERPT_MAX_CHARS && k + 4 < size) {
    memcpy(buf + k, "...", 3);
    k += 3;
  }
  buf[k] = '\0';
}

/* ---- files and lines ----------------------------------------------------- */

vl_status vl_import_read_file(const char *path, size_t max_bytes, const char *what, char **buf,
                              size_t *len, vl_error *err) {
  vl_status st = VL_OK;
  size_t cap = 0;
  *buf = NULL;
  *len = 0;
  FILE *f = fopen(path, "rb");
  if (!f) {
    vl_error_set(err, "%s: cannot open: %s", path, strerror(errno));
    return VL_EIO;
  }
  for (;;) {
    if (*len == cap) { /* full: grow, unless it has reached the limit */
      if (cap >= max_bytes) {
        vl_error_set(err, "%s: larger than %zu MiB: not %s", path, max_bytes >> 20, what);
        st = VL_EINPUT;
        break;
      }
      size_t ncap = cap ? 2 * cap : 65536;
      char *nb = realloc(*buf, ncap);
      if (!nb) {
        vl_error_set(err, "%s: out of memory", path);
        st = VL_ENOMEM;
        break;
      }
      *buf = nb;
      cap = ncap;
    }
    size_t got = fread(*buf + *len, 1, cap - *len, f);
    *len += got;
    if (got == 0) break;
  }
  if (st == VL_OK && ferror(f)) {
    vl_error_set(err, "%s: cannot read: %s", path, strerror(errno));
    st = VL_EIO;
  }
  fclose(f);
  if (st != VL_OK) {
    free(*buf);
    *buf = NULL;
    *len = 0;
  }
  return st;
}

int vl_import_next_line(const char *text, size_t len, size_t *pos, size_t *line_no, vl_span *line) {
  if (*pos == 0 && len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) *pos = 3;
  while (*pos < len) {
    (*line_no)++;
    const char *start = text + *pos;
    const char *nl = memchr(start, '\n', len - *pos);
    size_t n = nl ? (size_t)(nl - start) : len - *pos;
    *pos += n + 1;
    if (n > 0 && start[n - 1] == '\r') n--;
    vl_span t = vl_span_trim((vl_span){start, n});
    if (t.n == 0 || t.p[0] == '#') continue;
    *line = (vl_span){start, n};
    return 1;
  }
  return 0;
}

void vl_import_sanitise(vl_error *err) {
  if (!err) return;
  for (char *c = err->msg; *c; c++)
    if (((unsigned char)*c < 0x20 && *c != '\n') || *c == 0x7f) *c = '?';
}

/* ---- delimited text ------------------------------------------------------ */

static int ends_with_nocase(const char *s, const char *suffix) {
  size_t n = strlen(s), m = strlen(suffix);
  if (m > n) return 0;
  for (size_t i = 0; i < m; i++)
    if (lower((unsigned char)s[n - m + i]) != lower((unsigned char)suffix[i])) return 0;
  return 1;
}

vl_status vl_import_refuse_spreadsheet(const char *text, size_t len, const char *source,
                                       vl_error *err) {
  static const char *ext[] = {".xlsx", ".xlsm", ".xls", ".ods"};
  const char *src = source ? source : "<text>";
  const char *what = NULL;
  for (size_t k = 0; k < sizeof ext / sizeof *ext && !what; k++)
    if (ends_with_nocase(src, ext[k])) what = ext[k];
  /* .xlsx, .xlsm and .ods are ZIP archives, .xls an OLE2 compound file */
  if (!what && len >= 4 && text && memcmp(text, "PK\x03\x04", 4) == 0) what = "ZIP (.xlsx, .ods)";
  if (!what && len >= 8 && text && memcmp(text, "\xD0\xCF\x11\xE0\xA1\xB1\x1A\xE1", 8) == 0)
    what = "OLE2 (.xls)";
  if (!what) return VL_OK;
  vl_error_set(err,
               "%s: a spreadsheet file (%s), not text: open it in the spreadsheet program and "
               "save or export the sheet as CSV (comma- or semicolon-separated text), then give "
               "that file",
               src, what);
  return VL_EINPUT;
}

const char *vl_dialect_delimiter_name(char delimiter) {
  switch (delimiter) {
  case ',': return "comma";
  case ';': return "semicolon";
  case '\t': return "tab";
  }
  return "?";
}

size_t vl_import_split(vl_span line, char delimiter, vl_span *cells, size_t cap) {
  size_t count = 0;
  const char *start = line.p, *end = line.p + line.n;
  int quoted = 0;
  for (const char *c = line.p;; c++) {
    if (c < end && *c == '"') quoted = !quoted;
    if (c == end || (*c == delimiter && !quoted)) {
      if (count < cap) cells[count] = (vl_span){start, (size_t)(c - start)};
      count++;
      if (c == end) break;
      start = c + 1;
    }
  }
  return count;
}

/* Strict decimal syntax: [+-]digits[.digits] or [+-].digits, optional
 * exponent (csv.h). */
static int decimal_syntax(const char *s) {
  const char *p = s;
  if (*p == '+' || *p == '-') p++;
  size_t digits = 0;
  while (*p >= '0' && *p <= '9')
    p++, digits++;
  if (*p == '.') {
    p++;
    while (*p >= '0' && *p <= '9')
      p++, digits++;
  }
  if (digits == 0) return 0;
  if (*p == 'e' || *p == 'E') {
    p++;
    if (*p == '+' || *p == '-') p++;
    if (!(*p >= '0' && *p <= '9')) return 0;
    while (*p >= '0' && *p <= '9')
      p++;
  }
  return *p == '\0';
}

vl_status vl_import_parse_number(const char *cell, size_t n, int decimal_comma, double *out,
                                 const char **why) {
  vl_span s = vl_span_trim((vl_span){cell, n});
  cell = s.p, n = s.n;
  char buf[NUMBER_MAX_CHARS + 1];
  if (n == 0) {
    *why = "empty cell";
    return VL_EINPUT;
  }
  if (n > NUMBER_MAX_CHARS) {
    *why = "not a number";
    return VL_EINPUT;
  }
  memcpy(buf, cell, n);
  buf[n] = '\0';
  if (decimal_comma) {
    if (memchr(buf, '.', n) && decimal_syntax(buf)) {
      *why = "a '.' in a file with decimal commas (a thousands separator?)";
      return VL_EINPUT;
    }
    char *c = memchr(buf, ',', n);
    if (c) *c = '.';
  }
  if (!decimal_syntax(buf)) {
    const char *b = buf + (buf[0] == '+' || buf[0] == '-');
    int special = 1;
    const char *words[] = {"nan", "inf", "infinity"};
    for (size_t w = 0; w < 3 && special; w++) {
      size_t k = 0;
      while (words[w][k] && lower((unsigned char)b[k]) == words[w][k])
        k++;
      if (!words[w][k] && !b[k]) special = 2;
    }
    *why = special == 2 ? "NaN and infinity are not allowed" : "not a number";
    return VL_EINPUT;
  }
  errno = 0;
  double v = strtod(buf, NULL);
  /* ERANGE also flags underflow: below 1e-308 in a material file is a unit
   * mistake, not data */
  if (errno == ERANGE || !isfinite(v)) {
    *why = "outside the range of a double";
    return VL_EINPUT;
  }
  *out = v;
  return VL_OK;
}

/* ---- dialect ------------------------------------------------------------- */

/* A comma between two digits: "0,25" (also inside "1,5e-3"). */
static int has_decimal_comma(vl_span cell) {
  const char *c = cell.p;
  for (size_t i = 1; i + 1 < cell.n; i++)
    if (c[i] == ',' && c[i - 1] >= '0' && c[i - 1] <= '9' && c[i + 1] >= '0' && c[i + 1] <= '9')
      return 1;
  return 0;
}

vl_status vl_import_detect_dialect(const char *text, size_t len, const char *source, vl_dialect *d,
                                   vl_error *err) {
  static const char cand[3] = {'\t', ';', ','};
  const char *src = source ? source : "<text>";
  size_t pos = 0, line_no = 0, header_line;
  vl_span line;
  d->delimiter = ',';
  d->decimal_comma = 0;
  if (!text || !vl_import_next_line(text, len, &pos, &line_no, &line)) return VL_OK;
  header_line = line_no;
  size_t hcount[3];
  int fits[3];
  for (int c = 0; c < 3; c++) {
    hcount[c] = vl_import_split(line, cand[c], NULL, 0);
    fits[c] = hcount[c] > 1;
  }
  size_t save = pos, save_line = line_no;
  for (int k = 0; k < SAMPLE_LINES && vl_import_next_line(text, len, &pos, &line_no, &line); k++)
    for (int c = 0; c < 3; c++)
      if (fits[c] && vl_import_split(line, cand[c], NULL, 0) != hcount[c]) fits[c] = 0;
  int nfit = fits[0] + fits[1] + fits[2], pick = 2;
  if (nfit > 1) {
    int a = fits[0] ? 0 : 1, b = fits[2] ? 2 : 1;
    vl_error_set(err,
                 "%s:%zu: cannot tell the delimiter: every line splits into %zu fields at each "
                 "%s and into %zu at each %s; keep one delimiter (a name containing the other "
                 "can be put in double quotes)",
                 src, header_line, hcount[a], vl_dialect_delimiter_name(cand[a]), hcount[b],
                 vl_dialect_delimiter_name(cand[b]));
    return VL_EINPUT;
  }
  if (nfit == 1) {
    pick = fits[0] ? 0 : fits[1] ? 1 : 2;
  } else { /* ragged: the delimiter the header holds most of names the bad line */
    size_t best = 1;
    for (int c = 0; c < 3; c++)
      if (hcount[c] > best) best = hcount[c], pick = c;
  }
  d->delimiter = cand[pick];
  if (d->delimiter == ',') return VL_OK;
  pos = save, line_no = save_line;
  vl_span cells[64];
  for (int k = 0; k < SAMPLE_LINES && vl_import_next_line(text, len, &pos, &line_no, &line); k++) {
    size_t count = vl_import_split(line, d->delimiter, cells, 64);
    for (size_t f = 0; f < count && f < 64; f++)
      if (has_decimal_comma(cells[f])) d->decimal_comma = 1;
  }
  return VL_OK;
}

/* ---- problem lists ------------------------------------------------------- */

/* Room kept at the end of the message for the "and N more" line. */
#define TAIL_ROOM 96

void vl_problems_init(vl_problems *p) { memset(p, 0, sizeof *p); }

void vl_problems_add(vl_problems *p, size_t line, const char *fmt, ...) {
  p->total++;
  if (line != p->last_line) p->lines++, p->last_line = line;
  if (p->shown >= VL_IMPORT_MAX_PROBLEMS) return;
  char one[VL_ERROR_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(one, sizeof one, fmt, ap);
  va_end(ap);
  for (char *c = one; *c; c++) /* one sentence per line, whatever the cell held */
    if ((unsigned char)*c < 0x20 || *c == 0x7f) *c = '?';
  size_t n = strlen(one), sep = p->shown ? 1 : 0;
  /* the first sentence always goes in (truncated if it must) */
  if (p->shown > 0 && p->len + sep + n + TAIL_ROOM >= sizeof p->text) return;
  if (sep) p->text[p->len++] = '\n';
  size_t room = sizeof p->text - 1 - p->len;
  if (n > room) n = room;
  memcpy(p->text + p->len, one, n);
  p->len += n;
  p->text[p->len] = '\0';
  p->shown++;
}

void vl_problems_finish(const vl_problems *p, const char *source, vl_error *err) {
  if (!err || p->total == 0) return;
  size_t more = p->total - p->shown;
  if (more == 0) {
    vl_error_set(err, "%s", p->text);
    return;
  }
  vl_error_set(err,
               "%s\n%s: and %zu more problem%s (%zu line%s at fault in all); fix these and "
               "read the file again",
               p->text, source ? source : "<text>", more, more == 1 ? "" : "s", p->lines,
               p->lines == 1 ? "" : "s");
}

void vl_import_note_v(char *notes, size_t size, const char *fmt, va_list ap) {
  size_t len = strlen(notes);
  if (len + 2 >= size) return;
  vsnprintf(notes + len, size - len - 1, fmt, ap);
  len = strlen(notes);
  notes[len] = '\n';
  notes[len + 1] = '\0';
}
