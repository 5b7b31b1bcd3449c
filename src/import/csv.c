/* A small strict CSV reader for numeric tables (csv.h). */
#define _POSIX_C_SOURCE 200809L

#include "viscolube/csv.h"

#include "abel.h"
#include "edit_distance.h"
#include "import_text.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Longest header cell a PSD column name is looked for in. */
#define CELL_TEXT_MAX 64

/* Edit distance between a header cell and a column name (to decide whether
 * the cell is a misspelling worth suggesting a fix for). */
static size_t distance(vl_span a, const char *b) {
  return vl_edit_distance(a.p, a.n, b, strlen(b), false);
}

vl_status vl_csv_parse_double(const char *text, double *out, const char **why) {
  const char *dummy;
  if (!why) why = &dummy;
  if (!text) {
    *why = "empty cell";
    return VL_EINPUT;
  }
  return vl_import_parse_number(text, strlen(text), 0, out, why);
}

void vl_csv_free(vl_csv *csv) {
  if (!csv) return;
  free(csv->source);
  free(csv->values);
  free(csv->lines);
  free(csv->present);
  free(csv->ignored);
  memset(csv, 0, sizeof *csv);
}

double vl_csv_value(const vl_csv *csv, size_t row, size_t col) {
  if (row >= csv->n_rows || col >= csv->n_cols) return NAN;
  return csv->values[row * csv->n_cols + col];
}

/* "A,tau_s" for messages; optional columns in brackets. */
static void expected_header(const vl_csv_column *cols, size_t n_cols, char *buf, size_t size) {
  size_t k = 0;
  buf[0] = '\0';
  for (size_t c = 0; c < n_cols && k < size; c++) {
    int w = snprintf(buf + k, size - k, "%s%s%s%s", c ? "," : "", cols[c].optional ? "[" : "",
                     cols[c].name, cols[c].optional ? "]" : "");
    if (w < 0) break;
    k += (size_t)w;
  }
}

/* Does cell match one of the '|'-separated spellings in units? */
static int units_match(vl_span cell, const char *units) {
  if (!units) return 1;
  const char *p = units;
  for (;;) {
    const char *bar = strchr(p, '|');
    size_t n = bar ? (size_t)(bar - p) : strlen(p);
    if (cell.n == n && memcmp(cell.p, p, n) == 0) return 1;
    if (!bar) return 0;
    p = bar + 1;
  }
}

/* A field of the file that no requested column takes (ignore_unknown). */
#define IGNORED ((size_t)-1)

/* The units row the file would need, in the file's column order and with
 * its delimiter (a tab shown as <tab>; ignored fields left empty). */
static void expected_units(const vl_csv_column *cols, const size_t *map, size_t n_fields,
                           char delimiter, char *buf, size_t size) {
  size_t k = 0;
  buf[0] = '\0';
  for (size_t f = 0; f < n_fields && k < size; f++) {
    const char *u = map[f] == IGNORED ? "" : cols[map[f]].units ? cols[map[f]].units : "";
    size_t n = strcspn(u, "|");
    const char *sep = !f ? "" : delimiter == '\t' ? "<tab>" : delimiter == ';' ? ";" : ",";
    int w = snprintf(buf + k, size - k, "%s%.*s", sep, (int)n, u);
    if (w < 0) break;
    k += (size_t)w;
  }
}

static vl_status grow(vl_csv *out, size_t *cap) {
  size_t ncap = *cap ? 2 * *cap : 64;
  double *v = realloc(out->values, ncap * out->n_cols * sizeof *v);
  if (!v) return VL_ENOMEM;
  out->values = v;
  size_t *l = realloc(out->lines, ncap * sizeof *l);
  if (!l) return VL_ENOMEM;
  out->lines = l;
  *cap = ncap;
  return VL_OK;
}

/* The state of one vl_csv_read_text. */
typedef struct {
  const char *src;           /* the file name in messages */
  const vl_csv_column *cols; /* the requested columns */
  size_t n_cols;
  vl_csv_options opt;
  vl_span *cells; /* the fields of the current line (cell_cap kept) */
  size_t cell_cap;
  size_t *map;         /* field f of the file holds column map[f], or IGNORED */
  size_t n_fields;     /* fields of the header, hence of every row */
  size_t line_no;      /* 1-based line being read */
  size_t cap;          /* rows allocated in out */
  char hdr[512];       /* the expected header, for messages */
  char units_row[256]; /* the units row the file would need, for messages */
  vl_csv *out;
} csv_reader;

/* The error of a header cell `name` (field f) that names no requested
 * column, with the closest name as a hint when it is a likely misspelling. */
static vl_status unknown_column(const csv_reader *r, vl_span name, size_t f, vl_error *err) {
  char shown[64];
  vl_span_excerpt(name, shown, sizeof shown);
  size_t best = r->n_cols, best_d = 9;
  for (size_t k = 0; k < r->n_cols; k++) {
    size_t d = vl_span_eq_nocase(name, r->cols[k].name) ? 0 : distance(name, r->cols[k].name);
    if (d < best_d) best_d = d, best = k;
  }
  if (best < r->n_cols && best_d <= 2)
    vl_error_set(err,
                 "%s:%zu: header field %zu: unknown column '%s' (did you mean '%s'? "
                 "expected the header '%s')",
                 r->src, r->line_no, f + 1, shown, r->cols[best].name, r->hdr);
  else
    vl_error_set(err, "%s:%zu: header field %zu: unknown column '%s' (expected the header '%s')",
                 r->src, r->line_no, f + 1, shown, r->hdr);
  return VL_EINPUT;
}

/* Appends 'name' to the list of ignored columns of out. */
static vl_status note_ignored(vl_csv *out, vl_span name) {
  char shown[64];
  vl_span_excerpt(name, shown, sizeof shown);
  size_t old = out->ignored ? strlen(out->ignored) : 0, add = strlen(shown) + 4;
  char *s = realloc(out->ignored, old + add + 1);
  if (!s) return VL_ENOMEM;
  snprintf(s + old, add + 1, "%s'%s'", old ? ", " : "", shown);
  out->ignored = s;
  out->n_ignored++;
  return VL_OK;
}

/* Splits the header line and sizes the cell arrays for it. */
static vl_status header_cells(csv_reader *r, vl_span line, size_t *count, vl_error *err) {
  *count = vl_import_split(line, r->opt.delimiter, NULL, 0);
  if (*count > VL_IMPORT_MAX_FIELDS) {
    vl_error_set(err, "%s:%zu: the header has %zu fields; a table has at most %d", r->src,
                 r->line_no, *count, VL_IMPORT_MAX_FIELDS);
    return VL_EINPUT;
  }
  r->cell_cap = (*count > r->n_cols ? *count : r->n_cols) + 1;
  r->cells = malloc(r->cell_cap * sizeof *r->cells);
  r->map = malloc(r->cell_cap * sizeof *r->map);
  if (!r->cells || !r->map) {
    vl_error_set(err, "%s: out of memory", r->src);
    return VL_ENOMEM;
  }
  vl_import_split(line, r->opt.delimiter, r->cells, r->cell_cap);
  return VL_OK;
}

/* The header line: every field names a distinct requested column (or is
 * ignored, with ignore_unknown), every column that is not optional is
 * there. Sets map, n_fields, the presence flags of out, its ignored list
 * and the expected units row. */
static vl_status read_header(csv_reader *r, vl_span line, vl_error *err) {
  size_t n_cols = r->n_cols, count;
  vl_status st = header_cells(r, line, &count, err);
  if (st != VL_OK) return st;
  int all_numbers = 1;
  for (size_t f = 0; f < count && all_numbers; f++) {
    double v;
    const char *why;
    if (vl_import_parse_number(r->cells[f].p, r->cells[f].n, r->opt.decimal_comma, &v, &why) !=
        VL_OK)
      all_numbers = 0;
  }
  if (all_numbers) {
    vl_error_set(err, "%s:%zu: missing header: expected the column names '%s' before the numbers",
                 r->src, r->line_no, r->hdr);
    return VL_EINPUT;
  }
  for (size_t f = 0; f < count; f++) {
    vl_span name = vl_span_unquote(r->cells[f]);
    if (name.n == 0) {
      vl_error_set(err, "%s:%zu: header field %zu is empty (expected the header '%s')", r->src,
                   r->line_no, f + 1, r->hdr);
      return VL_EINPUT;
    }
    size_t c = 0;
    while (c < n_cols && !vl_span_eq(name, r->cols[c].name))
      c++;
    if (c == n_cols && !r->opt.ignore_unknown) return unknown_column(r, name, f, err);
    if (c == n_cols) {
      r->map[f] = IGNORED;
      if (note_ignored(r->out, name) != VL_OK) {
        vl_error_set(err, "%s: out of memory", r->src);
        return VL_ENOMEM;
      }
      continue;
    }
    if (r->out->present[c]) {
      vl_error_set(err, "%s:%zu: header field %zu: column '%s' appears twice", r->src, r->line_no,
                   f + 1, r->cols[c].name);
      return VL_EINPUT;
    }
    r->out->present[c] = 1;
    r->map[f] = c;
  }
  for (size_t c = 0; c < n_cols; c++) {
    if (!r->out->present[c] && !r->cols[c].optional) {
      vl_error_set(err, "%s:%zu: the header lacks column '%s' (expected the header '%s')", r->src,
                   r->line_no, r->cols[c].name, r->hdr);
      return VL_EINPUT;
    }
  }
  r->n_fields = count;
  expected_units(r->cols, r->map, r->n_fields, r->opt.delimiter, r->units_row, sizeof r->units_row);
  return VL_OK;
}

/* The first row after the header (split into cells): *is_units = 1 if it
 * is the optional units row, recognised by a non-numeric cell that spells
 * its column's unit; then every cell of a requested column must.
 * Otherwise the row is data. */
static vl_status read_units_row(const csv_reader *r, int *is_units, vl_error *err) {
  *is_units = 0;
  for (size_t f = 0; f < r->n_fields && !*is_units; f++) {
    double v;
    const char *why;
    vl_span u = vl_span_unquote(r->cells[f]);
    if (r->map[f] != IGNORED &&
        vl_import_parse_number(u.p, u.n, r->opt.decimal_comma, &v, &why) != VL_OK &&
        units_match(u, r->cols[r->map[f]].units))
      *is_units = 1;
  }
  if (!*is_units) return VL_OK;
  for (size_t f = 0; f < r->n_fields; f++) {
    vl_span u = vl_span_unquote(r->cells[f]);
    if (r->map[f] != IGNORED && !units_match(u, r->cols[r->map[f]].units)) {
      char shown[64];
      vl_span_excerpt(u, shown, sizeof shown);
      vl_error_set(err,
                   "%s:%zu: column '%s' (field %zu): '%s' is not the expected unit (the "
                   "optional units row after the header must read '%s')",
                   r->src, r->line_no, r->cols[r->map[f]].name, f + 1, shown, r->units_row);
      return VL_EINPUT;
    }
  }
  return VL_OK;
}

/* Field f of a data row: a number of the column's sign that, for an
 * increasing column, exceeds the row before. first_row: a misspelt units
 * row reads as a bad first data row, and the message says so. */
static vl_status read_cell(const csv_reader *r, size_t f, int first_row, double *out,
                           vl_error *err) {
  const vl_csv_column *col = &r->cols[r->map[f]];
  const vl_csv *csv = r->out;
  double v = 0.0;
  const char *why = NULL;
  char shown[64];
  vl_span cell = vl_span_trim(r->cells[f]);
  vl_span_excerpt(cell, shown, sizeof shown);
  if (vl_import_parse_number(cell.p, cell.n, r->opt.decimal_comma, &v, &why) != VL_OK) {
    int hint = first_row && !strcmp(why, "not a number");
    vl_error_set(err, "%s:%zu: column '%s' (field %zu): %s (got '%s')%s%s%s", r->src, r->line_no,
                 col->name, f + 1, why, shown,
                 hint ? "; an optional units row after the header must read '" : "",
                 hint ? r->units_row : "", hint ? "'" : "");
    return VL_EINPUT;
  }
  if ((col->sign == VL_CSV_POSITIVE && !(v > 0.0)) ||
      (col->sign == VL_CSV_NONNEGATIVE && !(v >= 0.0))) {
    vl_error_set(err, "%s:%zu: column '%s' (field %zu): must be %s (got '%s')", r->src, r->line_no,
                 col->name, f + 1, col->sign == VL_CSV_POSITIVE ? "> 0" : ">= 0", shown);
    return VL_EINPUT;
  }
  if (col->increasing && csv->n_rows > 0) {
    double prev = csv->values[(csv->n_rows - 1) * r->n_cols + r->map[f]];
    if (!(v > prev)) {
      vl_error_set(err,
                   "%s:%zu: column '%s' (field %zu): values must increase strictly down the "
                   "file (got %.17g after %.17g on line %zu)",
                   r->src, r->line_no, col->name, f + 1, v, prev, csv->lines[csv->n_rows - 1]);
      return VL_EINPUT;
    }
  }
  *out = v;
  return VL_OK;
}

/* A data row (split into cells) appended to out; the columns absent from
 * the file are NAN. A bad cell leaves out as it was: VL_EINPUT, err says
 * why. */
static vl_status read_data_row(csv_reader *r, int first_row, vl_error *err) {
  vl_csv *out = r->out;
  vl_status st;
  if (out->n_rows == r->cap && (st = grow(out, &r->cap)) != VL_OK) {
    vl_error_set(err, "%s:%zu: out of memory", r->src, r->line_no);
    return st;
  }
  double *row = out->values + out->n_rows * r->n_cols;
  for (size_t c = 0; c < r->n_cols; c++)
    row[c] = NAN;
  for (size_t f = 0; f < r->n_fields; f++)
    if (r->map[f] != IGNORED && (st = read_cell(r, f, first_row, &row[r->map[f]], err)) != VL_OK)
      return st;
  out->lines[out->n_rows++] = r->line_no;
  return VL_OK;
}

/* The sentence for a row with the wrong number of fields. */
static void ragged_row(const csv_reader *r, size_t count, vl_problems *pr) {
  char d = r->opt.delimiter;
  vl_problems_add(pr, r->line_no,
                  "%s:%zu: expected %zu %s-separated fields like the header, found %zu%s", r->src,
                  r->line_no, r->n_fields, vl_dialect_delimiter_name(d), count,
                  d == ',' && count > r->n_fields
                      ? " (numbers with a decimal comma need ';' or a tab between the fields)"
                      : "");
}

/* The options in force: the caller's, the dialect detected when it gives
 * no delimiter. */
static vl_status settle_options(csv_reader *r, const char *text, size_t len,
                                const vl_csv_options *opts, vl_error *err) {
  vl_csv_options o = {0};
  if (opts) o = *opts;
  if (o.delimiter == 0) {
    vl_dialect d;
    vl_status st = vl_import_detect_dialect(text, len, r->src, &d, err);
    if (st != VL_OK) return st;
    o.delimiter = d.delimiter;
    o.decimal_comma = d.decimal_comma;
  } else if (o.delimiter != ',' && o.delimiter != ';' && o.delimiter != '\t') {
    vl_error_set(err, "%s: the delimiter must be ',', ';' or a tab (a bug in the caller)", r->src);
    return VL_EINTERNAL;
  }
  if (o.delimiter == ',') o.decimal_comma = 0;
  r->opt = o;
  r->out->delimiter = o.delimiter;
  r->out->decimal_comma = o.decimal_comma;
  return VL_OK;
}

vl_status vl_csv_read_text_opts(const char *text, size_t len, const char *source,
                                const vl_csv_column *cols, size_t n_cols,
                                const vl_csv_options *opts, vl_csv *out, vl_error *err) {
  vl_status st = VL_OK;
  size_t header_line = 0, last_line = 0;
  enum { HEADER, UNITS, DATA } stage = HEADER;
  csv_reader r = {.src = source ? source : "<text>", .cols = cols, .n_cols = n_cols, .out = out};
  vl_problems pr;
  vl_problems_init(&pr);

  memset(out, 0, sizeof *out);
  if (!cols || n_cols == 0 || (!text && len > 0)) {
    vl_error_set(err, "%s: no columns requested (a bug in the caller)", r.src);
    return VL_EINTERNAL;
  }
  if (!text) text = "";
  expected_header(cols, n_cols, r.hdr, sizeof r.hdr);
  out->source = strdup(r.src);
  out->n_cols = n_cols;
  out->present = calloc(n_cols, sizeof *out->present);
  if (!out->source || !out->present) {
    st = VL_ENOMEM;
    vl_error_set(err, "%s: out of memory", r.src);
    goto cleanup;
  }
  if ((st = vl_import_refuse_spreadsheet(text, len, r.src, err)) != VL_OK) goto cleanup;
  if ((st = settle_options(&r, text, len, opts, err)) != VL_OK) goto cleanup;

  size_t pos = 0;
  if (len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) pos = 3;
  while (pos < len) {
    r.line_no++;
    const char *nl = memchr(text + pos, '\n', len - pos);
    size_t end = nl ? (size_t)(nl - text) : len;
    vl_span line = {text + pos, end - pos};
    pos = end + 1;
    if (line.n > 0 && line.p[line.n - 1] == '\r') line.n--;
    if (memchr(line.p, '\0', line.n)) {
      vl_error_set(err, "%s:%zu: contains a NUL byte (not a text file?)", r.src, r.line_no);
      st = VL_EINPUT;
      goto cleanup;
    }
    vl_span t = vl_span_trim(line);
    if (t.n == 0 || t.p[0] == '#') continue;
    last_line = r.line_no;

    if (stage == HEADER) {
      if ((st = read_header(&r, line, err)) != VL_OK) goto cleanup;
      header_line = r.line_no;
      stage = UNITS;
      continue;
    }
    size_t count = vl_import_split(line, r.opt.delimiter, r.cells, r.n_fields);
    if (count != r.n_fields) {
      ragged_row(&r, count, &pr);
      stage = DATA;
      continue;
    }
    int first_row = stage == UNITS;
    if (stage == UNITS) {
      stage = DATA;
      int is_units;
      if ((st = read_units_row(&r, &is_units, err)) != VL_OK) goto cleanup;
      if (is_units) {
        out->has_units_row = 1;
        continue;
      }
    }
    vl_error one;
    if ((st = read_data_row(&r, first_row, &one)) == VL_EINPUT) {
      vl_problems_add(&pr, r.line_no, "%s", one.msg);
      st = VL_OK;
    } else if (st != VL_OK) {
      vl_error_set(err, "%s", one.msg);
      goto cleanup;
    }
  }

  if (stage == HEADER) {
    vl_error_set(err, "%s:%zu: empty file (expected the header '%s' and data rows)", r.src,
                 r.line_no ? r.line_no : 1, r.hdr);
    st = VL_EINPUT;
  } else if (pr.total > 0) {
    vl_problems_finish(&pr, r.src, err);
    st = VL_EINPUT;
  } else if (out->n_rows == 0) {
    vl_error_set(err, "%s:%zu: no data rows after the header on line %zu", r.src, last_line,
                 header_line);
    st = VL_EINPUT;
  }

cleanup:
  free(r.cells);
  free(r.map);
  if (st != VL_OK) {
    vl_csv_free(out);
    vl_import_sanitise(err);
  }
  return st;
}

vl_status vl_csv_read_text(const char *text, size_t len, const char *source,
                           const vl_csv_column *cols, size_t n_cols, vl_csv *out, vl_error *err) {
  return vl_csv_read_text_opts(text, len, source, cols, n_cols, NULL, out, err);
}

vl_status vl_csv_read_file(const char *path, const vl_csv_column *cols, size_t n_cols, vl_csv *out,
                           vl_error *err) {
  char *buf = NULL;
  size_t len = 0;
  memset(out, 0, sizeof *out);
  vl_status st =
      vl_import_read_file(path, VL_IMPORT_TABLE_MAX_BYTES, "a material table", &buf, &len, err);
  if (st == VL_OK) st = vl_csv_read_text(buf, len, path, cols, n_cols, out, err);
  free(buf);
  return st;
}

vl_status vl_csv_read_prony(const char *path, vl_prony *prony, vl_error *err) {
  static const vl_csv_column cols[] = {
      {.name = "A", .units = "1|-", .sign = VL_CSV_NONNEGATIVE},
      {.name = "tau_s", .units = "s", .sign = VL_CSV_POSITIVE},
  };
  vl_csv csv;
  vl_status st = vl_csv_read_file(path, cols, 2, &csv, err);
  if (st != VL_OK) return st;
  if (csv.n_rows > VL_PRONY_MAX_TERMS) {
    vl_error_set(err, "%s:%zu: too many Prony terms (at most %d)", path,
                 csv.lines[VL_PRONY_MAX_TERMS], VL_PRONY_MAX_TERMS);
    vl_csv_free(&csv);
    return VL_EINPUT;
  }
  prony->n_terms = csv.n_rows;
  for (size_t i = 0; i < csv.n_rows; i++) {
    prony->A[i] = vl_csv_value(&csv, i, 0);
    prony->tau_s[i] = vl_csv_value(&csv, i, 1);
  }
  vl_csv_free(&csv);
  return VL_OK;
}

/* ---- tabulated PSD files ------------------------------------------------- */

const char *vl_psd_file_kind_name(vl_psd_file_kind kind) {
  return kind == VL_PSD_FILE_1D ? "1d" : "2d";
}

vl_status vl_psd_file_kind_parse(const char *text, vl_psd_file_kind *kind) {
  if (text && (!strcmp(text, "2d") || !strcmp(text, "2D"))) {
    *kind = VL_PSD_FILE_2D;
    return VL_OK;
  }
  if (text && (!strcmp(text, "1d") || !strcmp(text, "1D"))) {
    *kind = VL_PSD_FILE_1D;
    return VL_OK;
  }
  return VL_EINPUT;
}

/* What a PSD column's name says. */
typedef enum { P_NONE, P_Q, P_C, P_C1D, P_C2D } psd_role;

/* Names compared in lower case without blanks, '_', '-' and '.'. */
static const struct {
  const char *name;
  psd_role r;
} psd_names[] = {
    {"q", P_Q},
    {"wavevector", P_Q},
    {"wavenumber", P_Q},
    {"k", P_Q},
    {"c", P_C},
    {"c(q)", P_C},
    {"psd", P_C},
    {"powerspectraldensity", P_C},
    {"powerspectrum", P_C},
    {"c2d", P_C2D},
    {"c2", P_C2D},
    {"c2(q)", P_C2D},
    {"psd2d", P_C2D},
    {"c2d(q)", P_C2D},
    {"c1d", P_C1D},
    {"c1", P_C1D},
    {"c1(q)", P_C1D},
    {"psd1d", P_C1D},
    {"c1d(q)", P_C1D},
};

static void psd_normalise(const char *s, size_t n, char *out, size_t cap) {
  size_t k = 0;
  for (size_t i = 0; i < n && k + 1 < cap; i++) {
    char c = s[i];
    if (c == ' ' || c == '\t' || c == '_' || c == '-' || c == '.') continue;
    if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
    out[k++] = c;
  }
  out[k] = '\0';
}

static psd_role psd_name_role(vl_span name) {
  char b[64];
  if (name.n >= sizeof b) return P_NONE;
  psd_normalise(name.p, name.n, b, sizeof b);
  for (size_t i = 0; i < sizeof psd_names / sizeof *psd_names; i++)
    if (!strcmp(b, psd_names[i].name)) return psd_names[i].r;
  return P_NONE;
}

/* Length units of q and C, in m. "µ" is the UTF-8 micro sign. */
static const struct {
  const char *name;
  double m;
} psd_lengths[] = {{"m", 1.0},          {"mm", 1e-3},     {"um", 1e-6}, {"\xC2\xB5m", 1e-6},
                   {"\xCE\xBCm", 1e-6}, {"micron", 1e-6}, {"nm", 1e-9}};

/* The length unit spelt by s[0..n) exactly, or 0. */
static double psd_length(const char *s, size_t n) {
  for (size_t i = 0; i < sizeof psd_lengths / sizeof *psd_lengths; i++)
    if (strlen(psd_lengths[i].name) == n && !memcmp(s, psd_lengths[i].name, n))
      return psd_lengths[i].m;
  return 0.0;
}

/* A unit of q: 1/L, L^-1, L-1, per L, /L (L a length); *factor = the SI
 * value of one unit (1/m per unit). */
static int q_unit(vl_span u, double *factor) {
  char b[32];
  if (u.n >= sizeof b) return 0;
  size_t k = 0;
  for (size_t i = 0; i < u.n; i++)
    if (u.p[i] != ' ' && u.p[i] != '_') b[k++] = u.p[i];
  b[k] = '\0';
  const char *len = NULL;
  size_t ln = 0;
  if (!strncmp(b, "1/", 2))
    len = b + 2, ln = k - 2;
  else if (!strncmp(b, "per", 3))
    len = b + 3, ln = k - 3;
  else if (b[0] == '/')
    len = b + 1, ln = k - 1;
  else if (k > 3 && !strcmp(b + k - 3, "^-1"))
    len = b, ln = k - 3;
  else if (k > 2 && !strcmp(b + k - 2, "-1"))
    len = b, ln = k - 2;
  double m = len ? psd_length(len, ln) : 0.0;
  if (!(m > 0.0)) return 0;
  *factor = 1.0 / m;
  return 1;
}

/* A unit of C: L^4 / L4 (2-D) or L^3 / L3 (1-D); *factor = m^p per unit,
 * *power = p. */
static int c_unit(vl_span u, double *factor, int *power) {
  char b[32];
  if (u.n >= sizeof b || u.n < 2) return 0;
  size_t k = 0;
  for (size_t i = 0; i < u.n; i++)
    if (u.p[i] != ' ') b[k++] = u.p[i];
  b[k] = '\0';
  char p = b[k - 1];
  if (p != '3' && p != '4') return 0;
  size_t ln = k - 1 - (k >= 2 && b[k - 2] == '^');
  double m = psd_length(b, ln);
  if (!(m > 0.0)) return 0;
  *power = p - '0';
  *factor = pow(m, *power);
  return 1;
}

/* One PSD column as found in the header: name and unit read apart. */
typedef struct {
  psd_role r;
  size_t field;
  char text[CELL_TEXT_MAX]; /* the header cell */
  int has_unit;
  double factor; /* SI per file unit */
  int power;     /* C: 3 or 4 from the unit */
  char unit[CELL_TEXT_MAX];
} psd_col;

/* Reads "q [1/um]", "C (m^4)", "q_per_m", "C_m4": the role of the name and,
 * when given, the unit. 0 when the cell names no PSD column. */
static int psd_header_cell(vl_span cell, psd_col *c) {
  vl_span t = vl_span_unquote(cell);
  memset(c, 0, sizeof *c);
  if (t.n >= CELL_TEXT_MAX) return 0;
  memcpy(c->text, t.p, t.n);
  c->text[t.n] = '\0';
  if ((c->r = psd_name_role(t)) != P_NONE) return 1;
  char close = t.n ? t.p[t.n - 1] : 0, open = close == ']' ? '[' : close == ')' ? '(' : 0;
  for (size_t i = t.n; open && i-- > 1;) {
    if (t.p[i] != open) continue;
    vl_span name = vl_span_trim((vl_span){t.p, i}),
            unit = vl_span_trim((vl_span){t.p + i + 1, t.n - i - 2});
    if ((c->r = psd_name_role(name)) == P_NONE) return 0;
    c->has_unit = 1;
    memcpy(c->unit, unit.p, unit.n);
    c->unit[unit.n] = '\0';
    return 1;
  }
  for (size_t i = t.n; i-- > 1;) { /* "q_per_m", "C_m4": a unit after a '_' */
    if (t.p[i] != '_') continue;
    vl_span name = {t.p, i}, unit = {t.p + i + 1, t.n - i - 1};
    psd_role r = psd_name_role(name);
    double f;
    int pw;
    if (r == P_NONE || !(r == P_Q ? q_unit(unit, &f) : c_unit(unit, &f, &pw))) continue;
    c->r = r;
    c->has_unit = 1;
    memcpy(c->unit, unit.p, unit.n);
    c->unit[unit.n] = '\0';
    return 1;
  }
  return 0;
}

/* The unit text u of column c: sets factor and power, 0 if not a unit of
 * its column. */
static int psd_unit_of(psd_col *c, const char *u) {
  vl_span s = vl_span_trim((vl_span){u, strlen(u)});
  return c->r == P_Q ? q_unit(s, &c->factor) : c_unit(s, &c->factor, &c->power);
}

/* The layout of a PSD file: which fields hold q and C, in which units. */
typedef struct {
  const char *src;
  vl_dialect d;
  psd_col q, c;
  size_t header_line;
  int has_units_row;
  char units_row[2][CELL_TEXT_MAX];
} psd_layout;

/* Finds the q and C columns in the header line (other columns ignored),
 * then reads the optional units row; every unit settled or an error. */
static vl_status psd_scan(const char *text, size_t len, psd_layout *pl, vl_error *err) {
  size_t pos = 0, line_no = 0;
  vl_span line, cells[VL_IMPORT_MAX_FIELDS + 1];
  if (!vl_import_next_line(text, len, &pos, &line_no, &line)) return VL_OK; /* the reader says so */
  pl->header_line = line_no;
  size_t count = vl_import_split(line, pl->d.delimiter, cells, VL_IMPORT_MAX_FIELDS + 1);
  psd_col col;
  for (size_t f = 0; f < count && f < VL_IMPORT_MAX_FIELDS; f++) {
    if (!psd_header_cell(cells[f], &col)) continue;
    psd_col *slot = col.r == P_Q ? &pl->q : &pl->c;
    if (slot->text[0]) {
      vl_error_set(err, "%s:%zu: header field %zu: a second %s column ('%s', after '%s')", pl->src,
                   line_no, f + 1, col.r == P_Q ? "q" : "C", col.text, slot->text);
      return VL_EINPUT;
    }
    *slot = col;
    slot->field = f;
  }
  if (!pl->q.text[0] || !pl->c.text[0]) {
    vl_error_set(err,
                 "%s:%zu: the header lacks the %s column: a PSD file has a wavevector column "
                 "'q' and a spectrum column 'C' with their units, e.g. 'q [1/m],C [m^4]' or "
                 "'q_per_m,C_m4'",
                 pl->src, line_no, !pl->q.text[0] ? "wavevector (q)" : "spectrum (C)");
    return VL_EINPUT;
  }
  psd_col *pc[2] = {&pl->q, &pl->c};
  for (int i = 0; i < 2; i++) {
    if (pc[i]->has_unit && !psd_unit_of(pc[i], pc[i]->unit)) {
      vl_error_set(err, "%s:%zu: header field %zu: '%s' in '%s' is not a unit of %s (expected %s)",
                   pl->src, line_no, pc[i]->field + 1, pc[i]->unit, pc[i]->text,
                   i ? "a spectrum" : "a wavevector",
                   i ? "m^4, um^4, nm^4 (2-D) or m^3, um^3, nm^3 (1-D)" : "1/m, 1/um or 1/nm");
      return VL_EINPUT;
    }
  }
  /* the units row: the row after the header, when its q or C cell is a unit */
  if (vl_import_next_line(text, len, &pos, &line_no, &line) &&
      vl_import_split(line, pl->d.delimiter, cells, VL_IMPORT_MAX_FIELDS + 1) == count) {
    double v;
    const char *why;
    int is_units = 0;
    for (int i = 0; i < 2; i++) {
      vl_span u = vl_span_unquote(cells[pc[i]->field]);
      psd_col probe = *pc[i];
      char ut[CELL_TEXT_MAX];
      snprintf(ut, sizeof ut, "%.*s", (int)(u.n < sizeof ut ? u.n : sizeof ut - 1), u.p);
      if (vl_import_parse_number(u.p, u.n, pl->d.decimal_comma, &v, &why) != VL_OK &&
          psd_unit_of(&probe, ut))
        is_units = 1;
      snprintf(pl->units_row[i], sizeof pl->units_row[i], "%s", ut);
    }
    for (int i = 0; is_units && i < 2; i++) {
      psd_col probe = *pc[i];
      if (!psd_unit_of(&probe, pl->units_row[i])) {
        vl_error_set(err, "%s:%zu: column '%s' (field %zu): '%s' is not a unit of %s", pl->src,
                     line_no, pc[i]->text, pc[i]->field + 1, pl->units_row[i],
                     i ? "a spectrum (m^4, um^4, nm^4; 1-D: m^3 ...)"
                       : "a wavevector (1/m, 1/um, "
                         "1/nm)");
        return VL_EINPUT;
      }
      if (pc[i]->has_unit && (probe.factor != pc[i]->factor || probe.power != pc[i]->power)) {
        vl_error_set(err,
                     "%s:%zu: column '%s' (field %zu): mixed units: the header says %s but "
                     "the units row says %s",
                     pl->src, line_no, pc[i]->text, pc[i]->field + 1, pc[i]->unit,
                     pl->units_row[i]);
        return VL_EINPUT;
      }
      *pc[i] = probe;
      pc[i]->has_unit = 1;
    }
    pl->has_units_row = is_units;
  }
  for (int i = 0; i < 2; i++) {
    if (!pc[i]->has_unit) {
      vl_error_set(err,
                   "%s:%zu: column '%s' (field %zu): no unit for the %s: write it in the header, "
                   "e.g. '%s', or give a units row after it",
                   pl->src, pl->header_line, pc[i]->text, pc[i]->field + 1,
                   i ? "spectrum" : "wavevector", i ? "C [m^4]" : "q [1/m]");
      return VL_EINPUT;
    }
  }
  return VL_OK;
}

/* 1-D or 2-D: what the column says (its name or the power of its unit),
 * which must agree with what the caller expects. */
static vl_status psd_dimension(const psd_layout *pl, vl_psd_file_kind kind, vl_error *err) {
  int says_1d = pl->c.power == 3 || pl->c.r == P_C1D;
  int says_2d = pl->c.power == 4 || pl->c.r == P_C2D;
  if (says_1d && says_2d) {
    vl_error_set(err,
                 "%s:%zu: column '%s' (field %zu): the name and the unit disagree on a 1-D "
                 "(m^3) or 2-D (m^4) spectrum",
                 pl->src, pl->header_line, pl->c.text, pl->c.field + 1);
    return VL_EINPUT;
  }
  if (kind == VL_PSD_FILE_2D && says_1d) {
    vl_error_set(err,
                 "%s:%zu: column '%s' (field %zu): a 1-D (profile) spectrum C1(q) in m^3, but "
                 "a surface needs the isotropic 2-D C(q) in m^4: give the PSD kind 1d "
                 "(--psd-kind 1d) to convert it",
                 pl->src, pl->header_line, pl->c.text, pl->c.field + 1);
    return VL_EINPUT;
  }
  if (kind == VL_PSD_FILE_1D && says_2d) {
    vl_error_set(err,
                 "%s:%zu: column '%s' (field %zu): the PSD kind 1d was given but the column "
                 "holds a 2-D spectrum (m^4); a 1-D one is in m^3",
                 pl->src, pl->header_line, pl->c.text, pl->c.field + 1);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* Appends one sentence (a line) to rep->notes. */
static void psd_note(vl_psd_read_report *rep, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static void psd_note(vl_psd_read_report *rep, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vl_import_note_v(rep->notes, sizeof rep->notes, fmt, ap);
  va_end(ap);
}

typedef struct {
  double q, c;
  size_t line;
} psd_point;

static int cmp_psd_point(const void *pa, const void *pb) {
  const psd_point *a = pa, *b = pb;
  if (a->q != b->q) return a->q < b->q ? -1 : 1;
  return a->line < b->line ? -1 : a->line > b->line;
}

/* Sorts the points by q (noted when the file was not in order: reversed
 * files are common, wavelength-ordered exports) and merges repeated q
 * (within 1e-9 relative) into one point with their mean C. Returns the
 * points kept. */
static size_t psd_order(psd_point *p, size_t n, vl_psd_read_report *rep) {
  int increasing = 1, decreasing = 1;
  for (size_t k = 1; k < n; k++) {
    if (p[k].q < p[k - 1].q) increasing = 0;
    if (p[k].q > p[k - 1].q) decreasing = 0;
  }
  if (!increasing) {
    rep->reordered = 1;
    psd_note(rep, "the rows were not in increasing q (%s): sorted",
             decreasing ? "they decrease" : "mixed order");
  }
  qsort(p, n, sizeof *p, cmp_psd_point);
  size_t out = 0, first_merge = 0;
  for (size_t k = 0; k < n;) {
    /* p[k] itself always counts: a q that does not compare equal to itself
     * must not stall the walk (the reader refuses non-finite values, but
     * this loop writes by it) */
    size_t j = k + 1;
    double sum = p[k].c;
    while (j < n && fabs(p[j].q - p[k].q) <= 1e-9 * p[k].q)
      sum += p[j++].c;
    if (j - k > 1 && rep->n_merged == 0) first_merge = p[k + 1].line;
    rep->n_merged += j - k - 1;
    p[out] = p[k];
    p[out].c = sum / (double)(j - k);
    out++;
    k = j;
  }
  if (rep->n_merged)
    psd_note(rep,
             "%zu row%s repeated a q already given (the first on line %zu): merged, C averaged "
             "(%zu points kept)",
             rep->n_merged, rep->n_merged == 1 ? "" : "s", first_merge, out);
  return out;
}

/* h_rms and rms slope of a tabulated spectrum that no measured surface
 * has: the sentence names which and the likely unit mistake. */
static vl_status psd_plausible(const char *src, const vl_psd *psd, vl_psd_read_report *rep,
                               vl_error *err) {
  rep->hrms_m = vl_psd_hrms(psd);
  rep->rms_slope = vl_psd_rms_slope(psd);
  double cmin = INFINITY, cmax = 0.0;
  for (size_t k = 0; k < psd->n; k++)
    cmin = fmin(cmin, psd->C[k]), cmax = fmax(cmax, psd->C[k]);
  char where[160];
  snprintf(where, sizeof where, "q from %.4g to %.4g 1/m, C from %.4g to %.4g m^4", psd->q[0],
           psd->q[psd->n - 1], cmin, cmax);
  if (!(rep->hrms_m >= VL_PSD_HRMS_MIN_M && rep->hrms_m <= VL_PSD_HRMS_MAX_M)) {
    vl_error_set(err,
                 "%s: implausible h_rms %.3g m (a measured surface has %g to %g m): a unit "
                 "mistake in q or C (1/um or 1/nm read as 1/m? um^4 read as m^4?); as read, %s",
                 src, rep->hrms_m, VL_PSD_HRMS_MIN_M, VL_PSD_HRMS_MAX_M, where);
    return VL_EINPUT;
  }
  if (!(rep->rms_slope <= VL_PSD_SLOPE_MAX)) {
    vl_error_set(err,
                 "%s: implausible rms slope %.3g (above %g: surfaces steeper than ~85 degrees "
                 "on average): a unit mistake in q or C, or a spectrum that does not fall fast "
                 "enough at large q; as read, %s",
                 src, rep->rms_slope, VL_PSD_SLOPE_MAX, where);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* The 2-D spectrum from the 1-D one in p[0..*n) (inverse Abel transform,
 * abel.h); points where it is not positive are dropped. */
static vl_status psd_from_profile(psd_point *p, size_t *n, const char *src, vl_psd_read_report *rep,
                                  vl_error *err) {
  double *q = malloc(*n * sizeof *q), *c1 = malloc(*n * sizeof *c1), *c2 = malloc(*n * sizeof *c2);
  double tail = 0.0;
  vl_status st = VL_ENOMEM;
  if (q && c1 && c2) {
    for (size_t k = 0; k < *n; k++)
      q[k] = p[k].q, c1[k] = p[k].c;
    st = vl_abel_profile_to_surface(*n, q, c1, NULL, c2, &tail);
  }
  if (st == VL_OK) {
    size_t kept = 0;
    for (size_t k = 0; k < *n; k++) {
      if (!(c2[k] > 0.0 && isfinite(c2[k]))) {
        rep->n_dropped++;
        continue;
      }
      p[kept] = p[k];
      p[kept++].c = c2[k];
    }
    *n = kept;
    rep->converted_1d = 1;
    psd_note(rep,
             "1-D (profile) spectrum converted to the isotropic 2-D one by the inverse Abel "
             "transform (C1 taken two-sided, h_rms^2 = integral of C1 over all q; tail slope "
             "%.3g beyond the last point%s)",
             tail, rep->n_dropped ? "; points where C came out <= 0 dropped" : "");
  } else {
    vl_error_set(err, "%s: out of memory", src);
  }
  free(q);
  free(c1);
  free(c2);
  return st;
}

vl_status vl_csv_read_psd_text(const char *text, size_t len, const char *source,
                               vl_psd_file_kind kind, vl_psd *psd, vl_psd_read_report *report,
                               vl_error *err) {
  vl_psd_read_report local;
  vl_psd_read_report *rep = report ? report : &local;
  psd_layout pl = {.src = source ? source : "<text>"};
  vl_csv csv;
  psd_point *pts = NULL;
  memset(psd, 0, sizeof *psd);
  memset(rep, 0, sizeof *rep);
  memset(&csv, 0, sizeof csv);
  if (!text) text = "";
  vl_status st = vl_import_refuse_spreadsheet(text, len, pl.src, err);
  if (st == VL_OK) st = vl_import_detect_dialect(text, len, pl.src, &pl.d, err);
  if (st == VL_OK) st = psd_scan(text, len, &pl, err);
  if (st == VL_OK && pl.q.text[0]) st = psd_dimension(&pl, kind, err);
  if (st != VL_OK) goto cleanup;
  /* the units row as spelt (then the reader matches it), else any units */
  vl_csv_column cols[2] = {
      {.name = pl.q.text,
       .units = pl.has_units_row ? pl.units_row[0] : "1/m",
       .sign = VL_CSV_POSITIVE},
      {.name = pl.c.text,
       .units = pl.has_units_row ? pl.units_row[1] : "m^4",
       .sign = VL_CSV_POSITIVE},
  };
  vl_csv_options copt = {
      .ignore_unknown = 1, .delimiter = pl.d.delimiter, .decimal_comma = pl.d.decimal_comma};
  if (!pl.q.text[0]) cols[0].name = "q_per_m", cols[1].name = "C_m4"; /* empty file */
  if ((st = vl_csv_read_text_opts(text, len, pl.src, cols, 2, &copt, &csv, err)) != VL_OK)
    goto cleanup;
  rep->n_rows = csv.n_rows;
  if (!(pts = malloc(csv.n_rows * sizeof *pts))) {
    vl_error_set(err, "%s: out of memory", pl.src);
    st = VL_ENOMEM;
    goto cleanup;
  }
  for (size_t k = 0; k < csv.n_rows && st == VL_OK; k++) {
    pts[k] = (psd_point){vl_csv_value(&csv, k, 0) * pl.q.factor,
                         vl_csv_value(&csv, k, 1) * pl.c.factor, csv.lines[k]};
    if (!isfinite(pts[k].q) || !isfinite(pts[k].c) || !(pts[k].q > 0.0) || !(pts[k].c > 0.0)) {
      vl_error_set(err, "%s:%zu: q = %g, C = %g: out of the range of double in SI units", pl.src,
                   csv.lines[k], vl_csv_value(&csv, k, 0), vl_csv_value(&csv, k, 1));
      st = VL_EINPUT;
    }
  }
  if (st != VL_OK) goto cleanup;
  if (pl.d.delimiter != ',' || pl.d.decimal_comma)
    psd_note(rep, "read as %s-separated%s", vl_dialect_delimiter_name(pl.d.delimiter),
             pl.d.decimal_comma ? " with decimal commas" : "");
  if (csv.n_ignored)
    psd_note(rep, "ignored %zu column%s: %s", csv.n_ignored, csv.n_ignored == 1 ? "" : "s",
             csv.ignored);
  if (pl.q.factor != 1.0 || pl.c.factor != 1.0)
    psd_note(rep, "units converted to SI: q x %.6g (from %s), C x %.6g (from %s)", pl.q.factor,
             pl.has_units_row ? pl.units_row[0] : pl.q.unit, pl.c.factor,
             pl.has_units_row ? pl.units_row[1] : pl.c.unit);
  size_t n = psd_order(pts, csv.n_rows, rep);
  if (st == VL_OK && kind == VL_PSD_FILE_1D && n >= 2)
    st = psd_from_profile(pts, &n, pl.src, rep, err);
  if (st != VL_OK) goto cleanup;
  if (n < 2) {
    vl_error_set(err, "%s:%zu: a tabulated PSD needs at least 2 points of distinct q (found %zu)",
                 pl.src, csv.lines[csv.n_rows - 1], n);
    st = VL_EINPUT;
    goto cleanup;
  }
  double *q = (double *)malloc(n * sizeof *q), *C = (double *)malloc(n * sizeof *C);
  if (!q || !C) {
    vl_error_set(err, "%s: out of memory", pl.src);
    st = VL_ENOMEM;
  } else {
    for (size_t k = 0; k < n; k++)
      q[k] = pts[k].q, C[k] = pts[k].c;
    st = vl_psd_init_tabulated(psd, n, q, C, err);
    if (st != VL_OK) vl_error_prefix(err, "%s", pl.src);
  }
  free(q);
  free(C);
  if (st == VL_OK && (st = psd_plausible(pl.src, psd, rep, err)) != VL_OK) vl_psd_free(psd);

cleanup:
  free(pts);
  vl_csv_free(&csv);
  if (st != VL_OK) vl_import_sanitise(err);
  return st;
}

vl_status vl_csv_read_psd_file(const char *path, vl_psd_file_kind kind, vl_psd *psd,
                               vl_psd_read_report *report, vl_error *err) {
  char *buf = NULL;
  size_t len = 0;
  memset(psd, 0, sizeof *psd);
  vl_status st =
      vl_import_read_file(path, VL_IMPORT_TABLE_MAX_BYTES, "a material table", &buf, &len, err);
  if (st == VL_OK) st = vl_csv_read_psd_text(buf, len, path, kind, psd, report, err);
  free(buf);
  return st;
}

vl_status vl_csv_read_psd(const char *path, vl_psd *psd, vl_error *err) {
  return vl_csv_read_psd_file(path, VL_PSD_FILE_2D, psd, NULL, err);
}
