/* Spreadsheet refusal, dialect detection and problem lists shared by the
 * delimited text readers (import_text.h). */
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

static int lower(int c) { return c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c; }

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

size_t vl_import_split(const char *line, size_t n, char delimiter, const char **cell,
                       size_t *cell_n, size_t cap) {
  size_t count = 0;
  const char *start = line, *end = line + n;
  int quoted = 0;
  for (const char *c = line;; c++) {
    if (c < end && *c == '"') quoted = !quoted;
    if (c == end || (*c == delimiter && !quoted)) {
      if (count < cap) cell[count] = start, cell_n[count] = (size_t)(c - start);
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

static int is_blank(char c) { return c == ' ' || c == '\t'; }

vl_status vl_import_parse_number(const char *cell, size_t n, int decimal_comma, double *out,
                                 const char **why) {
  while (n > 0 && is_blank(*cell))
    cell++, n--;
  while (n > 0 && is_blank(cell[n - 1]))
    n--;
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

/* The next line that is not blank and not a '#' comment: its start and
 * length (CR removed); 0 at the end. A leading UTF-8 byte-order mark is
 * skipped. */
static int meaningful_line(const char *text, size_t len, size_t *pos, const char **p, size_t *n,
                           size_t *line_no) {
  if (*pos == 0 && len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) *pos = 3;
  while (*pos < len) {
    (*line_no)++;
    const char *start = text + *pos;
    const char *nl = memchr(start, '\n', len - *pos);
    size_t ln = nl ? (size_t)(nl - start) : len - *pos;
    *pos += ln + 1;
    if (ln > 0 && start[ln - 1] == '\r') ln--;
    size_t i = 0;
    while (i < ln && is_blank(start[i]))
      i++;
    if (i == ln || start[i] == '#') continue;
    *p = start;
    *n = ln;
    return 1;
  }
  return 0;
}

/* A comma between two digits: "0,25" (also inside "1,5e-3"). */
static int has_decimal_comma(const char *cell, size_t n) {
  for (size_t i = 1; i + 1 < n; i++)
    if (cell[i] == ',' && cell[i - 1] >= '0' && cell[i - 1] <= '9' && cell[i + 1] >= '0' &&
        cell[i + 1] <= '9')
      return 1;
  return 0;
}

vl_status vl_import_detect_dialect(const char *text, size_t len, const char *source, vl_dialect *d,
                                   vl_error *err) {
  static const char cand[3] = {'\t', ';', ','};
  const char *src = source ? source : "<text>";
  size_t pos = 0, line_no = 0, n, header_line;
  const char *p;
  d->delimiter = ',';
  d->decimal_comma = 0;
  if (!text || !meaningful_line(text, len, &pos, &p, &n, &line_no)) return VL_OK;
  header_line = line_no;
  size_t hcount[3];
  int fits[3];
  for (int c = 0; c < 3; c++) {
    hcount[c] = vl_import_split(p, n, cand[c], NULL, NULL, 0);
    fits[c] = hcount[c] > 1;
  }
  size_t save = pos, save_line = line_no;
  for (int k = 0; k < SAMPLE_LINES && meaningful_line(text, len, &pos, &p, &n, &line_no); k++)
    for (int c = 0; c < 3; c++)
      if (fits[c] && vl_import_split(p, n, cand[c], NULL, NULL, 0) != hcount[c]) fits[c] = 0;
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
  const char *cell[64];
  size_t cell_n[64];
  for (int k = 0; k < SAMPLE_LINES && meaningful_line(text, len, &pos, &p, &n, &line_no); k++) {
    size_t count = vl_import_split(p, n, d->delimiter, cell, cell_n, 64);
    for (size_t f = 0; f < count && f < 64; f++)
      if (has_decimal_comma(cell[f], cell_n[f])) d->decimal_comma = 1;
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
