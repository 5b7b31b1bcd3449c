/* Reading measured topography (topography.h): a height map (an AFM or
 * profilometer export: '# Width:' and '# Value units:' header lines, then
 * a matrix of heights) or a line scan (a header row naming position and
 * height with their units, then two columns), told apart by the first
 * data row. The spectrum of what is read is topography_psd.c's. */
#define _POSIX_C_SOURCE 200809L

#include "topography_private.h"
#include "viscolube/topography.h"

#include "import_text.h"
#include "slurp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Longest field read as a number. */
#define NUMBER_MAX_CHARS 127

typedef enum { D_BLANK, D_SEMICOLON, D_COMMA } delimiter;

/* What a parse needs for its messages. */
typedef struct {
  const char *src;
  vl_error *err;
} reader;

/* ---- text ---------------------------------------------------------------- */

/* The next line of text[*pos..len) (LF, CRLF or CR ends a line). Returns 0
 * at the end of the text. Not vl_import_next_line: blank and '#' lines come
 * back too (the '#' lines of a height map are its header), and a lone CR
 * ends a line. */
static int next_line(const char *text, size_t len, size_t *pos, vl_span *line) {
  if (*pos >= len) return 0;
  size_t i = *pos;
  while (i < len && text[i] != '\n' && text[i] != '\r')
    i++;
  *line = (vl_span){text + *pos, i - *pos};
  if (i < len && text[i] == '\r' && i + 1 < len && text[i + 1] == '\n') i++;
  *pos = i + 1;
  return 1;
}

/* The next field of line from *pos: runs of blanks separate fields in
 * D_BLANK; otherwise the delimiter does, fields are trimmed and a trailing
 * delimiter (an empty last field) is not a field. Returns 0 at the end. */
static int next_field(vl_span line, delimiter d, size_t *pos, vl_span *field) {
  if (d == D_BLANK) {
    size_t i = *pos;
    while (i < line.n && vl_is_blank(line.p[i]))
      i++;
    if (i >= line.n) return 0;
    size_t start = i;
    while (i < line.n && !vl_is_blank(line.p[i]))
      i++;
    *field = (vl_span){line.p + start, i - start};
    *pos = i;
    return 1;
  }
  char sep = d == D_SEMICOLON ? ';' : ',';
  if (*pos > line.n) return 0;
  size_t i = *pos;
  while (i < line.n && line.p[i] != sep)
    i++;
  vl_span f = vl_span_trim((vl_span){line.p + *pos, i - *pos});
  if (i >= line.n && f.n == 0 && *pos > 0) return 0; /* trailing delimiter */
  *field = f;
  *pos = i + 1;
  return 1;
}

static size_t count_fields(vl_span line, delimiter d) {
  size_t pos = 0, n = 0;
  vl_span f;
  while (next_field(line, d, &pos, &f))
    n++;
  return n;
}

/* The delimiter of a data row: tab, else ';', else blanks when they
 * separate fields whose commas are all inside them ("0,5 1,25": decimal
 * commas), else ','. */
static delimiter detect_delimiter(vl_span line) {
  line = vl_span_trim(line);
  if (vl_span_has(line, '\t')) return D_BLANK;
  if (vl_span_has(line, ';')) return D_SEMICOLON;
  if (!vl_span_has(line, ',')) return D_BLANK;
  size_t pos = 0, n = 0;
  vl_span f;
  while (next_field(line, D_BLANK, &pos, &f)) {
    if (f.p[0] == ',' || f.p[f.n - 1] == ',') return D_COMMA;
    n++;
  }
  return n >= 2 ? D_BLANK : D_COMMA;
}

/* The decimal separator, decided by the first data row that shows one:
 * mode -1 (undecided), 0 ('.'), 1 (',' when the delimiter is not ','). */
static int decimal_mode(vl_span row, delimiter d, int mode) {
  if (mode >= 0) return mode;
  if (d != D_COMMA && vl_span_has(row, ',')) return 1;
  return vl_span_has(row, '.') ? 0 : -1;
}

static const char *delimiter_name(delimiter d) {
  switch (d) {
  case D_BLANK: return "blanks";
  case D_SEMICOLON: return "';'";
  case D_COMMA: return "','";
  }
  return "?";
}

/* Parses a field as a finite decimal number (csv.h's rules), with ',' as
 * the decimal separator when decimal_comma is set: this reader's own words
 * for an empty field and a '.' among decimal commas, then the strict
 * parser of import_text.h. */
static vl_status parse_number(vl_span s, int decimal_comma, double *out, const char **why) {
  char buf[NUMBER_MAX_CHARS + 1];
  s = vl_span_trim(s);
  if (s.n == 0) {
    *why = "empty field";
    return VL_EINPUT;
  }
  if (s.n > NUMBER_MAX_CHARS) {
    *why = "not a number";
    return VL_EINPUT;
  }
  memcpy(buf, s.p, s.n);
  buf[s.n] = '\0';
  if (decimal_comma) {
    if (strchr(buf, '.')) {
      *why = "a '.' in a file that uses decimal commas";
      return VL_EINPUT;
    }
    for (char *c = buf; *c; c++)
      if (*c == ',') *c = '.';
  }
  return vl_import_parse_number(buf, strlen(buf), 0, out, why);
}

/* ---- units ------------------------------------------------------------- */

static const struct {
  const char *name; /* lower case */
  double factor;    /* m per unit */
} length_units[] = {
    {"m", 1.0},
    {"meter", 1.0},
    {"meters", 1.0},
    {"metre", 1.0},
    {"metres", 1.0},
    {"mm", 1e-3},
    {"millimeter", 1e-3},
    {"millimeters", 1e-3},
    {"millimetre", 1e-3},
    {"millimetres", 1e-3},
    {"um", 1e-6},
    {"\xC2\xB5m", 1e-6},
    {"\xCE\xBCm", 1e-6},
    {"micron", 1e-6},
    {"microns", 1e-6},
    {"micrometer", 1e-6},
    {"micrometers", 1e-6},
    {"micrometre", 1e-6},
    {"micrometres", 1e-6},
    {"nm", 1e-9},
    {"nanometer", 1e-9},
    {"nanometers", 1e-9},
    {"nanometre", 1e-9},
    {"nanometres", 1e-9},
};

#define UNIT_LIST "m, mm, um, \xC2\xB5m or nm"

/* Metres per unit of s (ASCII case ignored), or 0 if s is not a length. */
static double unit_factor(vl_span s) {
  char buf[32];
  s = vl_span_trim(s);
  if (s.n == 0 || s.n >= sizeof buf) return 0.0;
  for (size_t i = 0; i < s.n; i++) {
    char c = s.p[i];
    buf[i] = (c >= 'A' && c <= 'Z') ? (char)(c - 'A' + 'a') : c;
  }
  buf[s.n] = '\0';
  for (size_t k = 0; k < sizeof length_units / sizeof length_units[0]; k++)
    if (!strcmp(buf, length_units[k].name)) return length_units[k].factor;
  return 0.0;
}

/* The unit named by a header cell: the text inside the last [] or (),
 * else after the last '_'. Returns 0 (and an empty vl_span) if none. */
static int header_unit(vl_span cell, vl_span *unit) {
  for (size_t i = cell.n; i-- > 0;) {
    char close = cell.p[i];
    if (close != ']' && close != ')') continue;
    char open = close == ']' ? '[' : '(';
    for (size_t j = i; j-- > 0;)
      if (cell.p[j] == open) {
        *unit = vl_span_trim((vl_span){cell.p + j + 1, i - j - 1});
        return unit->n > 0;
      }
    break;
  }
  for (size_t i = cell.n; i-- > 0;)
    if (cell.p[i] == '_') {
      *unit = vl_span_trim((vl_span){cell.p + i + 1, cell.n - i - 1});
      return unit->n > 0;
    }
  *unit = (vl_span){cell.p, 0};
  return 0;
}

/* ---- topography ---------------------------------------------------------- */

const char *vl_topography_kind_name(vl_topography_kind kind) {
  return kind == VL_TOPOGRAPHY_MAP ? "height map" : "line scan";
}

void vl_topography_free(vl_topography *t) {
  if (!t) return;
  free(t->source);
  free(t->h_m);
  memset(t, 0, sizeof *t);
}

/* A growable array of doubles (heights, positions). */
typedef struct {
  double *v;
  size_t n, cap;
} dvec;

static int dvec_push(dvec *a, double x) {
  if (a->n == a->cap) {
    size_t cap = a->cap ? 2 * a->cap : 4096;
    double *v = realloc(a->v, cap * sizeof *v);
    if (!v) return 0;
    a->v = v;
    a->cap = cap;
  }
  a->v[a->n++] = x;
  return 1;
}

static vl_status no_memory(const reader *r) {
  vl_error_set(r->err, "%s: out of memory", r->src);
  return VL_ENOMEM;
}

/* ---- map header ------------------------------------------------------- */

typedef struct {
  double width_m, height_m, value_factor; /* 0: not given */
  size_t width_line, height_line, units_line;
  vl_status bad; /* the first bad header line, reported only if the file is a map */
  vl_error bad_msg;
} map_header;

/* "<number> <unit>" (blanks optional between them), e.g. "10.00 µm". */
static vl_status parse_length(const reader *r, size_t line_no, const char *key, vl_span v,
                              double *out) {
  char shown[64];
  v = vl_span_trim(v);
  size_t i = 0;
  while (i < v.n && (strchr("+-.,eE", v.p[i]) || (v.p[i] >= '0' && v.p[i] <= '9')))
    i++;
  vl_span num = {v.p, i}, unit = vl_span_trim((vl_span){v.p + i, v.n - i});
  double x, f = unit_factor(unit);
  const char *why;
  int comma = vl_span_has(num, ',') && !vl_span_has(num, '.');
  vl_span_excerpt(v, shown, sizeof shown);
  if (parse_number(num, comma, &x, &why) != VL_OK || !(x > 0.0)) {
    vl_error_set(r->err, "%s:%zu: '%s:' must be a positive length such as '10.00 um' (got '%s')",
                 r->src, line_no, key, shown);
    return VL_EINPUT;
  }
  if (f == 0.0) {
    vl_span_excerpt(unit, shown, sizeof shown);
    vl_error_set(r->err, "%s:%zu: '%s:': unknown length unit '%s' (" UNIT_LIST ")", r->src, line_no,
                 key, shown);
    return VL_EINPUT;
  }
  *out = x * f;
  return VL_OK;
}

/* Reads "# key: value" (or '='); keys width, height, value units (case and
 * blanks ignored); anything else is ignored. */
static vl_status map_header_line(const reader *r, size_t line_no, vl_span line, map_header *h) {
  vl_span s = vl_span_trim(line);
  s.p++, s.n--; /* the '#' */
  size_t i = 0;
  while (i < s.n && s.p[i] != ':' && s.p[i] != '=')
    i++;
  if (i >= s.n) return VL_OK;
  vl_span key = vl_span_trim((vl_span){s.p, i}),
          value = vl_span_trim((vl_span){s.p + i + 1, s.n - i - 1});
  char k[32];
  size_t n = 0;
  for (size_t j = 0; j < key.n && n + 1 < sizeof k; j++) {
    char c = key.p[j];
    if (vl_is_blank(c) || c == '_') continue;
    k[n++] = (c >= 'A' && c <= 'Z') ? (char)(c - 'A' + 'a') : c;
  }
  k[n] = '\0';
  if (!strcmp(k, "width")) {
    h->width_line = line_no;
    return parse_length(r, line_no, "Width", value, &h->width_m);
  }
  if (!strcmp(k, "height")) {
    h->height_line = line_no;
    return parse_length(r, line_no, "Height", value, &h->height_m);
  }
  if (!strcmp(k, "valueunits") || !strcmp(k, "valueunit")) {
    char shown[64];
    h->units_line = line_no;
    h->value_factor = unit_factor(value);
    if (h->value_factor == 0.0) {
      vl_span_excerpt(value, shown, sizeof shown);
      vl_error_set(r->err, "%s:%zu: 'Value units:': unknown length unit '%s' (" UNIT_LIST ")",
                   r->src, line_no, shown);
      return VL_EINPUT;
    }
  }
  return VL_OK;
}

/* ---- readers ------------------------------------------------------------- */

/* Reads the matrix from the first data row (at *pos, line first_line) on. */
static vl_status read_map(const reader *r, const char *text, size_t len, size_t pos, size_t line_no,
                          const map_header *h, vl_topography *out) {
  vl_status st = VL_OK;
  dvec z = {0};
  vl_span line, f;
  size_t cols = 0, rows = 0;
  delimiter d = D_BLANK;
  int comma = -1;
  char shown[64];

  if (h->bad != VL_OK) {
    vl_error_set(r->err, "%s", h->bad_msg.msg);
    return h->bad;
  }
  if (!h->width_line || !h->units_line) {
    vl_error_set(r->err,
                 "%s:%zu: a height map needs the header lines '# Width: <length> <unit>' and "
                 "'# Value units: <unit>' before its numbers (a line scan needs a header row "
                 "naming its two columns and their units, e.g. 'x [um], z [nm]')",
                 r->src, line_no);
    return VL_EINPUT;
  }
  line_no--;
  while (next_line(text, len, &pos, &line)) {
    line_no++;
    vl_span t = vl_span_trim(line);
    if (t.n == 0 || t.p[0] == '#') continue;
    if (rows == 0) d = detect_delimiter(t);
    comma = decimal_mode(t, d, comma);
    size_t p = 0, k = 0;
    while (next_field(t, d, &p, &f)) {
      double v;
      const char *why;
      k++;
      if (parse_number(f, comma == 1, &v, &why) != VL_OK) {
        vl_span_excerpt(f, shown, sizeof shown);
        vl_error_set(r->err, "%s:%zu: field %zu: %s (got '%s')", r->src, line_no, k, why, shown);
        st = VL_EINPUT;
        goto cleanup;
      }
      if (!dvec_push(&z, v * h->value_factor)) {
        st = no_memory(r);
        goto cleanup;
      }
    }
    if (rows == 0) cols = k;
    if (k != cols) {
      vl_error_set(r->err,
                   "%s:%zu: row has %zu values, the first row has %zu: a height map's rows must "
                   "have equal length (delimiter %s)",
                   r->src, line_no, k, cols, delimiter_name(d));
      st = VL_EINPUT;
      goto cleanup;
    }
    rows++;
  }
  if (rows < VL_TOPOGRAPHY_MIN_POINTS || cols < VL_TOPOGRAPHY_MIN_POINTS) {
    vl_error_set(r->err, "%s: a height map needs at least %d rows and %d columns (got %zu x %zu)",
                 r->src, VL_TOPOGRAPHY_MIN_POINTS, VL_TOPOGRAPHY_MIN_POINTS, rows, cols);
    st = VL_EINPUT;
    goto cleanup;
  }
  out->kind = VL_TOPOGRAPHY_MAP;
  out->nx = cols;
  out->ny = rows;
  out->dx_m = h->width_m / (double)cols;
  out->square_assumed = !h->height_line;
  out->dy_m = h->height_line ? h->height_m / (double)rows : out->dx_m;
  out->h_m = z.v;
  z.v = NULL;

cleanup:
  free(z.v);
  return st;
}

/* The units of a line scan's header row, split with the data delimiter. */
static vl_status line_header(const reader *r, size_t line_no, vl_span header, delimiter d,
                             double factor[2]) {
  vl_span cells[2], unit;
  char shown[64];
  size_t n = count_fields(header, d);
  if (n == 2) {
    size_t p = 0;
    next_field(header, d, &p, &cells[0]);
    next_field(header, d, &p, &cells[1]);
  } else if (d == D_BLANK) {
    /* "position (m) height (m)": names with blanks; take the two unit groups */
    size_t found = 0;
    for (size_t i = 0; i < header.n; i++) {
      if (header.p[i] != '[' && header.p[i] != '(') continue;
      char close = header.p[i] == '[' ? ']' : ')';
      const char *e = memchr(header.p + i, close, header.n - i);
      if (!e) break;
      size_t end = (size_t)(e - header.p) + 1;
      if (found < 2) cells[found] = (vl_span){header.p + i, end - i};
      found++;
      i = end - 1;
    }
    if (found == 2 || found > n) n = found;
  }
  if (n != 2) {
    vl_span_excerpt(vl_span_trim(header), shown, sizeof shown);
    vl_error_set(r->err,
                 "%s:%zu: a line scan has two columns, position and height, but its header has "
                 "%zu (delimiter %s; got '%s')",
                 r->src, line_no, n, delimiter_name(d), shown);
    return VL_EINPUT;
  }
  for (int c = 0; c < 2; c++) {
    const char *what = c == 0 ? "position" : "height";
    vl_span_excerpt(vl_span_trim(cells[c]), shown, sizeof shown);
    if (!header_unit(cells[c], &unit)) {
      vl_error_set(
          r->err,
          "%s:%zu: field %d: the %s column '%s' names no unit (write e.g. '%s [um]'; " UNIT_LIST
          ")",
          r->src, line_no, c + 1, what, shown, c == 0 ? "x" : "z");
      return VL_EINPUT;
    }
    factor[c] = unit_factor(unit);
    if (factor[c] == 0.0) {
      char u[64];
      vl_span_excerpt(unit, u, sizeof u);
      vl_error_set(r->err, "%s:%zu: field %d: unknown length unit '%s' for the %s (" UNIT_LIST ")",
                   r->src, line_no, c + 1, u, what);
      return VL_EINPUT;
    }
  }
  return VL_OK;
}

/* Positions on a uniform increasing grid; dx from the end points. */
static vl_status check_grid(const reader *r, const dvec *x, const size_t *lines, double factor,
                            double *dx) {
  size_t n = x->n;
  double step = (x->v[n - 1] - x->v[0]) / (double)(n - 1);
  for (size_t i = 1; i < n; i++) {
    if (!(x->v[i] > x->v[i - 1])) {
      vl_error_set(r->err,
                   "%s:%zu: position %g does not increase (previous %g, same unit as the header): "
                   "a line scan must be sampled at increasing positions",
                   r->src, lines[i], x->v[i] / factor, x->v[i - 1] / factor);
      return VL_EINPUT;
    }
    double off = (x->v[i] - (x->v[0] + (double)i * step)) / step;
    if (fabs(off) > VL_TOPOGRAPHY_GRID_TOL) {
      vl_error_set(r->err,
                   "%s:%zu: position %g is %.2f spacings off the uniform grid %g + i * %g "
                   "(header unit): the spacing is not uniform, and a line scan must be "
                   "uniformly sampled (within %g of a spacing)",
                   r->src, lines[i], x->v[i] / factor, off, x->v[0] / factor, step / factor,
                   VL_TOPOGRAPHY_GRID_TOL);
      return VL_EINPUT;
    }
  }
  *dx = step;
  return VL_OK;
}

/* Reads a line scan whose header is `header` (line header_line); data from
 * *pos on. */
static vl_status read_line_scan(const reader *r, const char *text, size_t len, size_t pos,
                                size_t header_line, vl_span header, vl_topography *out) {
  vl_status st = VL_OK;
  dvec x = {0}, z = {0};
  size_t *lines = NULL, cap = 0, line_no = header_line;
  double factor[2] = {0, 0}, dx = 0.0;
  delimiter d = D_BLANK;
  int comma = -1, have_header_units = 0;
  vl_span line, f[3];
  char shown[64];

  while (next_line(text, len, &pos, &line)) {
    line_no++;
    vl_span t = vl_span_trim(line);
    if (t.n == 0 || t.p[0] == '#') continue;
    if (!have_header_units) {
      d = detect_delimiter(t);
      st = line_header(r, header_line, header, d, factor);
      if (st != VL_OK) goto cleanup;
      have_header_units = 1;
    }
    comma = decimal_mode(t, d, comma);
    size_t p = 0, k = 0;
    while (k < 3 && next_field(t, d, &p, &f[k]))
      k++;
    if (k != 2) {
      vl_span_excerpt(t, shown, sizeof shown);
      vl_error_set(r->err,
                   "%s:%zu: a line scan row has two fields, position and height "
                   "(delimiter %s; got '%s')",
                   r->src, line_no, delimiter_name(d), shown);
      st = VL_EINPUT;
      goto cleanup;
    }
    double v[2];
    for (size_t c = 0; c < 2; c++) {
      const char *why;
      if (parse_number(f[c], comma == 1, &v[c], &why) != VL_OK) {
        vl_span_excerpt(f[c], shown, sizeof shown);
        vl_error_set(r->err, "%s:%zu: field %zu: %s (got '%s')", r->src, line_no, c + 1, why,
                     shown);
        st = VL_EINPUT;
        goto cleanup;
      }
    }
    if (x.n == cap) {
      cap = cap ? 2 * cap : 4096;
      size_t *nl = realloc(lines, cap * sizeof *nl);
      if (!nl) {
        st = no_memory(r);
        goto cleanup;
      }
      lines = nl;
    }
    lines[x.n] = line_no;
    if (!dvec_push(&x, v[0] * factor[0]) || !dvec_push(&z, v[1] * factor[1])) {
      st = no_memory(r);
      goto cleanup;
    }
  }
  if (x.n < VL_TOPOGRAPHY_MIN_POINTS) {
    vl_error_set(r->err,
                 "%s: a line scan needs at least %d points (got %zu after the header on "
                 "line %zu)",
                 r->src, VL_TOPOGRAPHY_MIN_POINTS, x.n, header_line);
    st = VL_EINPUT;
    goto cleanup;
  }
  st = check_grid(r, &x, lines, factor[0], &dx);
  if (st != VL_OK) goto cleanup;
  out->kind = VL_TOPOGRAPHY_LINE;
  out->nx = z.n;
  out->ny = 1;
  out->dx_m = dx;
  out->dy_m = 0.0;
  out->h_m = z.v;
  z.v = NULL;

cleanup:
  free(x.v);
  free(z.v);
  free(lines);
  return st;
}

vl_status vl_topography_read_text(const char *text, size_t len, const char *source,
                                  vl_topography *out, vl_error *err) {
  vl_status st = VL_OK;
  reader r = {source ? source : "<text>", err};
  map_header h = {0};
  size_t pos = 0, line_no = 0;
  vl_span line;

  memset(out, 0, sizeof *out);
  if (!text) len = 0;
  if (len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) pos = 3;
  if (memchr(text ? text : "", '\0', len)) {
    vl_error_set(err, "%s: contains a NUL byte (not a text file?)", r.src);
    return VL_EINPUT;
  }
  out->source = strdup(r.src);
  if (!out->source) return no_memory(&r);
  for (;;) {
    size_t start = pos;
    if (!next_line(text, len, &pos, &line)) { /* no data: a bad map header says more */
      st = h.bad != VL_OK ? h.bad : VL_EINPUT;
      if (h.bad != VL_OK)
        vl_error_set(err, "%s", h.bad_msg.msg);
      else
        vl_error_set(err,
                     "%s: empty: no heights (a line scan needs a header row naming its "
                     "units, a height map '# Width:' and '# Value units:' header lines, then "
                     "numbers)",
                     r.src);
      break;
    }
    line_no++;
    vl_span t = vl_span_trim(line);
    if (t.n == 0) continue;
    if (t.p[0] == '#') { /* a line scan's comments need not parse as a map's header */
      reader quiet = {r.src, &h.bad_msg};
      if (h.bad == VL_OK) h.bad = map_header_line(&quiet, line_no, line, &h);
      continue;
    }
    size_t p = 0;
    vl_span first;
    double v;
    const char *why;
    delimiter d = detect_delimiter(t);
    next_field(t, d, &p, &first);
    if (parse_number(first, d != D_COMMA && vl_span_has(t, ','), &v, &why) == VL_OK)
      st = read_map(&r, text, len, start, line_no, &h, out);
    else
      st = read_line_scan(&r, text, len, pos, line_no, t, out);
    break;
  }
  if (st != VL_OK) vl_topography_free(out);
  return st;
}

vl_status vl_topography_read_file(const char *path, vl_topography *out, vl_error *err) {
  char *buf = NULL;
  size_t len = 0;
  memset(out, 0, sizeof *out);
  vl_status st = vl_slurp(path, VL_TOPOGRAPHY_MAX_BYTES, "a topography file", &buf, &len, err);
  if (st == VL_OK) st = vl_topography_read_text(buf, len, path, out, err);
  free(buf);
  return st;
}
