/* A small strict CSV reader for numeric tables, and Prony series files read
 * with it (csv.h). The tabulated PSD files of csv.h are read in psd_file.c. */
#define _POSIX_C_SOURCE 200809L

#include "viscolube/csv.h"
#include "csv_private.h"

#include "import_text.h"
#include "viscolube/edit_distance.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
