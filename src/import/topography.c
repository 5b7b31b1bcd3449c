/* Measured topography -> isotropic 2-D PSD (topography.h): the two readers,
 * then detrend, window, FFT, band, log bins and, for line scans, the
 * inverse Abel transform (abel.c) from the profile's spectrum to the
 * surface's. */
#define _POSIX_C_SOURCE 200809L

#include "viscolube/topography.h"

#include "slurp.h"

#include <errno.h>
#include <fftw3.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "viscolube/csv.h"
#include "viscolube/roughness.h"

#include "abel.h"

#define PI 3.14159265358979323846
#define TWO_PI 6.283185307179586476925287
/* Longest field read as a number, and the excerpt quoted in a message. */
#define NUMBER_MAX_CHARS 127
#define SHOW_MAX_CHARS 40
/* Detrended rms below this fraction of the raw rms: rounding, not roughness. */
#define FLAT_TOL 1e-9

typedef struct {
  const char *p;
  size_t n;
} span;

typedef enum { D_BLANK, D_SEMICOLON, D_COMMA } delimiter;

/* What a parse needs for its messages. */
typedef struct {
  const char *src;
  vl_error *err;
} reader;

/* ---- text ---------------------------------------------------------------- */

static int is_blank(char c) { return c == ' ' || c == '\t'; }

static span trim(span s) {
  while (s.n > 0 && is_blank(s.p[0]))
    s.p++, s.n--;
  while (s.n > 0 && is_blank(s.p[s.n - 1]))
    s.n--;
  return s;
}

static int span_has(span s, char c) { return s.n > 0 && memchr(s.p, c, s.n) != NULL; }

/* Copies s for quoting in a message: truncated, control bytes as '?'. */
static void show(span s, char *buf, size_t size) {
  size_t k = 0;
  for (size_t i = 0; i < s.n && k + 4 < size && i < SHOW_MAX_CHARS; i++) {
    unsigned char c = (unsigned char)s.p[i];
    buf[k++] = (c < 0x20 || c == 0x7f) ? '?' : (char)c;
  }
  if (s.n > SHOW_MAX_CHARS && k + 4 < size) {
    memcpy(buf + k, "...", 3);
    k += 3;
  }
  buf[k] = '\0';
}

/* The next line of text[*pos..len) (LF, CRLF or CR ends a line). Returns 0
 * at the end of the text. */
static int next_line(const char *text, size_t len, size_t *pos, span *line) {
  if (*pos >= len) return 0;
  size_t i = *pos;
  while (i < len && text[i] != '\n' && text[i] != '\r')
    i++;
  *line = (span){text + *pos, i - *pos};
  if (i < len && text[i] == '\r' && i + 1 < len && text[i + 1] == '\n') i++;
  *pos = i + 1;
  return 1;
}

/* The next field of line from *pos: runs of blanks separate fields in
 * D_BLANK; otherwise the delimiter does, fields are trimmed and a trailing
 * delimiter (an empty last field) is not a field. Returns 0 at the end. */
static int next_field(span line, delimiter d, size_t *pos, span *field) {
  if (d == D_BLANK) {
    size_t i = *pos;
    while (i < line.n && is_blank(line.p[i]))
      i++;
    if (i >= line.n) return 0;
    size_t start = i;
    while (i < line.n && !is_blank(line.p[i]))
      i++;
    *field = (span){line.p + start, i - start};
    *pos = i;
    return 1;
  }
  char sep = d == D_SEMICOLON ? ';' : ',';
  if (*pos > line.n) return 0;
  size_t i = *pos;
  while (i < line.n && line.p[i] != sep)
    i++;
  span f = trim((span){line.p + *pos, i - *pos});
  if (i >= line.n && f.n == 0 && *pos > 0) return 0; /* trailing delimiter */
  *field = f;
  *pos = i + 1;
  return 1;
}

static size_t count_fields(span line, delimiter d) {
  size_t pos = 0, n = 0;
  span f;
  while (next_field(line, d, &pos, &f))
    n++;
  return n;
}

/* The delimiter of a data row: tab, else ';', else blanks when they
 * separate fields whose commas are all inside them ("0,5 1,25": decimal
 * commas), else ','. */
static delimiter detect_delimiter(span line) {
  line = trim(line);
  if (span_has(line, '\t')) return D_BLANK;
  if (span_has(line, ';')) return D_SEMICOLON;
  if (!span_has(line, ',')) return D_BLANK;
  size_t pos = 0, n = 0;
  span f;
  while (next_field(line, D_BLANK, &pos, &f)) {
    if (f.p[0] == ',' || f.p[f.n - 1] == ',') return D_COMMA;
    n++;
  }
  return n >= 2 ? D_BLANK : D_COMMA;
}

/* The decimal separator, decided by the first data row that shows one:
 * mode -1 (undecided), 0 ('.'), 1 (',' when the delimiter is not ','). */
static int decimal_mode(span row, delimiter d, int mode) {
  if (mode >= 0) return mode;
  if (d != D_COMMA && span_has(row, ',')) return 1;
  return span_has(row, '.') ? 0 : -1;
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
 * the decimal separator when decimal_comma is set. */
static vl_status parse_number(span s, int decimal_comma, double *out, const char **why) {
  char buf[NUMBER_MAX_CHARS + 1];
  s = trim(s);
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
  return vl_csv_parse_double(buf, out, why);
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
static double unit_factor(span s) {
  char buf[32];
  s = trim(s);
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
 * else after the last '_'. Returns 0 (and an empty span) if none. */
static int header_unit(span cell, span *unit) {
  for (size_t i = cell.n; i-- > 0;) {
    char close = cell.p[i];
    if (close != ']' && close != ')') continue;
    char open = close == ']' ? '[' : '(';
    for (size_t j = i; j-- > 0;)
      if (cell.p[j] == open) {
        *unit = trim((span){cell.p + j + 1, i - j - 1});
        return unit->n > 0;
      }
    break;
  }
  for (size_t i = cell.n; i-- > 0;)
    if (cell.p[i] == '_') {
      *unit = trim((span){cell.p + i + 1, cell.n - i - 1});
      return unit->n > 0;
    }
  *unit = (span){cell.p, 0};
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
static vl_status parse_length(const reader *r, size_t line_no, const char *key, span v,
                              double *out) {
  char shown[64];
  v = trim(v);
  size_t i = 0;
  while (i < v.n && (strchr("+-.,eE", v.p[i]) || (v.p[i] >= '0' && v.p[i] <= '9')))
    i++;
  span num = {v.p, i}, unit = trim((span){v.p + i, v.n - i});
  double x, f = unit_factor(unit);
  const char *why;
  int comma = span_has(num, ',') && !span_has(num, '.');
  show(v, shown, sizeof shown);
  if (parse_number(num, comma, &x, &why) != VL_OK || !(x > 0.0)) {
    vl_error_set(r->err, "%s:%zu: '%s:' must be a positive length such as '10.00 um' (got '%s')",
                 r->src, line_no, key, shown);
    return VL_EINPUT;
  }
  if (f == 0.0) {
    show(unit, shown, sizeof shown);
    vl_error_set(r->err, "%s:%zu: '%s:': unknown length unit '%s' (" UNIT_LIST ")", r->src, line_no,
                 key, shown);
    return VL_EINPUT;
  }
  *out = x * f;
  return VL_OK;
}

/* Reads "# key: value" (or '='); keys width, height, value units (case and
 * blanks ignored); anything else is ignored. */
static vl_status map_header_line(const reader *r, size_t line_no, span line, map_header *h) {
  span s = trim(line);
  s.p++, s.n--; /* the '#' */
  size_t i = 0;
  while (i < s.n && s.p[i] != ':' && s.p[i] != '=')
    i++;
  if (i >= s.n) return VL_OK;
  span key = trim((span){s.p, i}), value = trim((span){s.p + i + 1, s.n - i - 1});
  char k[32];
  size_t n = 0;
  for (size_t j = 0; j < key.n && n + 1 < sizeof k; j++) {
    char c = key.p[j];
    if (is_blank(c) || c == '_') continue;
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
      show(value, shown, sizeof shown);
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
  span line, f;
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
    span t = trim(line);
    if (t.n == 0 || t.p[0] == '#') continue;
    if (rows == 0) d = detect_delimiter(t);
    comma = decimal_mode(t, d, comma);
    size_t p = 0, k = 0;
    while (next_field(t, d, &p, &f)) {
      double v;
      const char *why;
      k++;
      if (parse_number(f, comma == 1, &v, &why) != VL_OK) {
        show(f, shown, sizeof shown);
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
static vl_status line_header(const reader *r, size_t line_no, span header, delimiter d,
                             double factor[2]) {
  span cells[2], unit;
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
      if (found < 2) cells[found] = (span){header.p + i, end - i};
      found++;
      i = end - 1;
    }
    if (found == 2 || found > n) n = found;
  }
  if (n != 2) {
    show(trim(header), shown, sizeof shown);
    vl_error_set(r->err,
                 "%s:%zu: a line scan has two columns, position and height, but its header has "
                 "%zu (delimiter %s; got '%s')",
                 r->src, line_no, n, delimiter_name(d), shown);
    return VL_EINPUT;
  }
  for (int c = 0; c < 2; c++) {
    const char *what = c == 0 ? "position" : "height";
    show(trim(cells[c]), shown, sizeof shown);
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
      show(unit, u, sizeof u);
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
                                size_t header_line, span header, vl_topography *out) {
  vl_status st = VL_OK;
  dvec x = {0}, z = {0};
  size_t *lines = NULL, cap = 0, line_no = header_line;
  double factor[2] = {0, 0}, dx = 0.0;
  delimiter d = D_BLANK;
  int comma = -1, have_header_units = 0;
  span line, f[3];
  char shown[64];

  while (next_line(text, len, &pos, &line)) {
    line_no++;
    span t = trim(line);
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
      show(t, shown, sizeof shown);
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
        show(f[c], shown, sizeof shown);
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
  span line;

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
    span t = trim(line);
    if (t.n == 0) continue;
    if (t.p[0] == '#') { /* a line scan's comments need not parse as a map's header */
      reader quiet = {r.src, &h.bad_msg};
      if (h.bad == VL_OK) h.bad = map_header_line(&quiet, line_no, line, &h);
      continue;
    }
    size_t p = 0;
    span first;
    double v;
    const char *why;
    delimiter d = detect_delimiter(t);
    next_field(t, d, &p, &first);
    if (parse_number(first, d != D_COMMA && span_has(t, ','), &v, &why) == VL_OK)
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

/* ---- detrending ---------------------------------------------------------- */

/* The least-squares plane h ~ a + bx (j - cx) + by (i - cy) over the grid
 * (a line for ny = 1): with centred indices the three basis functions are
 * orthogonal on the full grid, so each coefficient is a projection. */
typedef struct {
  double a, bx, by, cx, cy;
} plane;

static plane fit_plane(const vl_topography *t) {
  plane p = {0.0, 0.0, 0.0, 0.5 * (double)(t->nx - 1), 0.5 * (double)(t->ny - 1)};
  double s = 0.0, sx = 0.0, sy = 0.0, xx = 0.0, yy = 0.0;
  for (size_t j = 0; j < t->nx; j++)
    xx += ((double)j - p.cx) * ((double)j - p.cx);
  for (size_t i = 0; i < t->ny; i++)
    yy += ((double)i - p.cy) * ((double)i - p.cy);
  for (size_t i = 0; i < t->ny; i++)
    for (size_t j = 0; j < t->nx; j++) {
      double h = t->h_m[i * t->nx + j];
      s += h;
      sx += h * ((double)j - p.cx);
      sy += h * ((double)i - p.cy);
    }
  p.a = s / ((double)t->nx * (double)t->ny);
  p.bx = xx > 0.0 ? sx / (xx * (double)t->ny) : 0.0;
  p.by = yy > 0.0 ? sy / (yy * (double)t->nx) : 0.0;
  return p;
}

/* rms about the mean, for telling a plane from a rough surface */
/* The scale the flatness test compares with: the rms of the heights about
 * their mean, and at least their magnitude (a constant height map has a
 * zero rms about its mean, and its detrended rms is round-off of the
 * magnitude: 3.7e-26 m was accepted as a surface). */
static double raw_rms(const vl_topography *t) {
  size_t n = t->nx * t->ny;
  double m = 0.0, s = 0.0, big = 0.0;
  for (size_t k = 0; k < n; k++) {
    m += t->h_m[k];
    big = fmax(big, fabs(t->h_m[k]));
  }
  m /= (double)n;
  for (size_t k = 0; k < n; k++)
    s += (t->h_m[k] - m) * (t->h_m[k] - m);
  return fmax(sqrt(s / (double)n), big);
}

static double residual(const vl_topography *t, const plane *p, size_t i, size_t j) {
  return t->h_m[i * t->nx + j] - p->a - p->bx * ((double)j - p->cx) - p->by * ((double)i - p->cy);
}

double vl_topography_hrms(const vl_topography *t) {
  if (!t || !t->h_m || t->nx == 0 || t->ny == 0) return NAN;
  plane p = fit_plane(t);
  double s = 0.0;
  for (size_t i = 0; i < t->ny; i++)
    for (size_t j = 0; j < t->nx; j++) {
      double r = residual(t, &p, i, j);
      s += r * r;
    }
  return sqrt(s / ((double)t->nx * (double)t->ny));
}

/* ---- window, bins -------------------------------------------------------- */

/* Periodic Tukey window into w[0..n): cosine tapers over a fraction taper
 * of the length (half at each end), 1 between; taper 1 is the periodic
 * Hann window, 0 no window. Returns mean(w^2). */
static double make_window(double taper, size_t n, double *w) {
  double s = 0.0;
  for (size_t k = 0; k < n; k++) {
    double u = (double)k / (double)n, edge = fmin(u, 1.0 - u);
    w[k] = edge < 0.5 * taper ? 0.5 * (1.0 - cos(TWO_PI * edge / taper)) : 1.0;
    s += w[k] * w[k];
  }
  return s / (double)n;
}

/* Log bins centred on q_min 10^(j/b): sums of weight, weight*C and
 * weight*ln q per bin. */
typedef struct {
  double q_min, q_max, per_decade;
  size_t n;
  double *w, *wc, *wlnq;
  double band_power;   /* \sum C dq^d over the kept wavevectors */
  double window_power; /* mean(w^2) */
} bins;

static int bins_init(bins *b, double q_min, double q_max, double per_decade) {
  b->q_min = q_min;
  b->q_max = q_max;
  b->per_decade = per_decade;
  b->n = (size_t)floor(per_decade * log10(q_max / q_min) + 0.5) + 1;
  b->w = calloc(b->n, sizeof *b->w);
  b->wc = calloc(b->n, sizeof *b->wc);
  b->wlnq = calloc(b->n, sizeof *b->wlnq);
  b->band_power = 0.0;
  return b->w && b->wc && b->wlnq;
}

static void bins_free(bins *b) {
  free(b->w);
  free(b->wc);
  free(b->wlnq);
}

/* Adds C at |q| with weight (the number of lattice points it stands for)
 * to the bin means, and power (C times the lattice cells it stands for) to
 * the band power, if q is in the band. The band's edges get a relative
 * slack of 1e-9 (rounding of 2 pi k/L). */
static void bins_add(bins *b, double q, double c, double weight, double power) {
  if (q < b->q_min * (1.0 - 1e-9) || q > b->q_max * (1.0 + 1e-9)) return;
  double x = floor(b->per_decade * log10(q / b->q_min) + 0.5);
  size_t j = x <= 0.0 ? 0 : (size_t)x;
  if (j >= b->n) j = b->n - 1;
  b->w[j] += weight;
  b->wc[j] += weight * c;
  b->wlnq[j] += weight * log(q);
  b->band_power += power;
}

/* The non-empty bins as points (q, C, count); returns how many. A bin of
 * zero power (a spectral line elsewhere, no window) has no point: the
 * tabulated PSD is positive. */
static size_t bins_points(const bins *b, double *q, double *c, size_t *count) {
  size_t m = 0;
  for (size_t j = 0; j < b->n; j++) {
    if (!(b->w[j] > 0.0 && b->wc[j] > 0.0)) continue;
    q[m] = exp(b->wlnq[j] / b->w[j]);
    c[m] = b->wc[j] / b->w[j];
    count[m] = (size_t)llround(b->w[j]);
    m++;
  }
  return m;
}

/* ---- spectra ----------------------------------------------------------- */

/* The detrended, windowed heights of t into in[] (row-major); returns
 * mean(w^2) of the (separable) window, or -1 without memory. Without a
 * window (periodic data) only the mean is removed: a plane would turn the
 * periodic heights into a sawtooth whose jump leaks power ~ q^-2. */
static double windowed(const vl_topography *t, double taper, double *in) {
  double *wx = malloc(t->nx * sizeof *wx), *wy = malloc(t->ny * sizeof *wy);
  double w2 = -1.0;
  if (!wx || !wy) goto cleanup;
  w2 = make_window(taper, t->nx, wx);
  if (t->ny > 1)
    w2 *= make_window(taper, t->ny, wy);
  else
    wy[0] = 1.0;
  plane p = fit_plane(t);
  if (taper == 0.0) p.bx = p.by = 0.0;
  for (size_t i = 0; i < t->ny; i++)
    for (size_t j = 0; j < t->nx; j++)
      in[i * t->nx + j] = wy[i] * wx[j] * residual(t, &p, i, j);

cleanup:
  free(wx);
  free(wy);
  return w2;
}

/* Map: 2-D FFT, every wavevector of the half plane FFTW returns (weight 2
 * where its mirror -q is not stored), C from step 3 of topography.h. */
static vl_status map_spectrum(const vl_topography *t, double taper, bins *b) {
  vl_status st = VL_ENOMEM;
  size_t nx = t->nx, ny = t->ny, hx = nx / 2 + 1;
  double *in = fftw_alloc_real(nx * ny);
  fftw_complex *out = fftw_alloc_complex(ny * hx);
  fftw_plan plan = NULL;
  if (!in || !out) goto cleanup;
  plan = fftw_plan_dft_r2c_2d((int)ny, (int)nx, in, out, FFTW_ESTIMATE);
  if (!plan) goto cleanup;
  double w2 = windowed(t, taper, in);
  if (w2 < 0.0) goto cleanup;
  b->window_power = w2;
  fftw_execute(plan);
  double lx = (double)nx * t->dx_m, ly = (double)ny * t->dy_m;
  double dqx = TWO_PI / lx, dqy = TWO_PI / ly;
  double scale = (t->dx_m * t->dy_m) * (t->dx_m * t->dy_m) / (TWO_PI * TWO_PI * lx * ly) / w2;
  for (size_t i = 0; i < ny; i++) {
    double ky = i <= ny / 2 ? (double)i : (double)i - (double)ny;
    for (size_t j = 0; j < hx; j++) {
      double qx = dqx * (double)j, qy = dqy * ky;
      double q = hypot(qx, qy);
      if (q == 0.0) continue;
      double re = out[i * hx + j][0], im = out[i * hx + j][1];
      double weight = (j == 0 || 2 * j == nx) ? 1.0 : 2.0;
      double c = (re * re + im * im) * scale;
      bins_add(b, q, c, weight, weight * c * dqx * dqy);
    }
  }
  st = VL_OK;

cleanup:
  if (plan) fftw_destroy_plan(plan);
  fftw_free(in);
  fftw_free(out);
  return st;
}

/* Line: 1-D FFT, C1 of step 3 at q_k = 2 pi k / L for k >= 1; the band
 * power counts +-q (weight 2, 1 for the Nyquist frequency), the bin means
 * are over k > 0 alone (C1 is even). */
static vl_status line_spectrum(const vl_topography *t, double taper, bins *b) {
  vl_status st = VL_ENOMEM;
  size_t n = t->nx, h = n / 2 + 1;
  double *in = fftw_alloc_real(n);
  fftw_complex *out = fftw_alloc_complex(h);
  fftw_plan plan = NULL;
  if (!in || !out) goto cleanup;
  plan = fftw_plan_dft_r2c_1d((int)n, in, out, FFTW_ESTIMATE);
  if (!plan) goto cleanup;
  double w2 = windowed(t, taper, in);
  if (w2 < 0.0) goto cleanup;
  b->window_power = w2;
  fftw_execute(plan);
  double l = (double)n * t->dx_m, dq = TWO_PI / l;
  double scale = t->dx_m * t->dx_m / (TWO_PI * l) / w2;
  for (size_t k = 1; k < h; k++) {
    double re = out[k][0], im = out[k][1], c1 = (re * re + im * im) * scale;
    bins_add(b, dq * (double)k, c1, 1.0, (2 * k == n ? 1.0 : 2.0) * c1 * dq);
  }
  st = VL_OK;

cleanup:
  if (plan) fftw_destroy_plan(plan);
  fftw_free(in);
  fftw_free(out);
  return st;
}

/* ---- the PSD ------------------------------------------------------------- */

vl_topography_psd_options vl_topography_psd_options_default(void) {
  vl_topography_psd_options o = {VL_TOPOGRAPHY_TAPER, 10.0, 1.0, 0.5, 1};
  return o;
}

void vl_topography_spectrum_free(vl_topography_spectrum *p) {
  if (!p) return;
  free(p->q_per_m);
  free(p->c_m4);
  free(p->count);
  free(p->q1_per_m);
  free(p->c1_m3);
  memset(p, 0, sizeof *p);
}

static vl_status check_options(const vl_topography *t, const vl_topography_psd_options *o,
                               vl_error *err) {
  if (!t || !t->h_m || t->nx < VL_TOPOGRAPHY_MIN_POINTS ||
      (t->kind == VL_TOPOGRAPHY_MAP && t->ny < VL_TOPOGRAPHY_MIN_POINTS) || !(t->dx_m > 0.0) ||
      (t->kind == VL_TOPOGRAPHY_MAP && !(t->dy_m > 0.0)) || t->nx > INT_MAX || t->ny > INT_MAX) {
    vl_error_set(err, "%s: not a readable topography (size or pixel)",
                 t && t->source ? t->source : "<topography>");
    return VL_EINPUT;
  }
  if (!(isfinite(o->taper) && o->taper >= 0.0 && o->taper <= 1.0)) {
    vl_error_set(err, "topography PSD: the window taper must be in [0, 1] (1: Hann; got %g)",
                 o->taper);
    return VL_EINPUT;
  }
  if (!(isfinite(o->bins_per_decade) && o->bins_per_decade > 0.0 && o->bins_per_decade <= 100.0)) {
    vl_error_set(err, "topography PSD: bins per decade must be in (0, 100] (got %g)",
                 o->bins_per_decade);
    return VL_EINPUT;
  }
  if (!(isfinite(o->long_cut) && o->long_cut >= 1.0)) {
    vl_error_set(err, "topography PSD: the long-wavelength cut must be >= 1 (x 2 pi/L; got %g)",
                 o->long_cut);
    return VL_EINPUT;
  }
  if (!(isfinite(o->short_cut) && o->short_cut > 0.0 && o->short_cut <= 1.0)) {
    vl_error_set(err,
                 "topography PSD: the short-wavelength cut must be in (0, 1] (x pi/dx; got "
                 "%g)",
                 o->short_cut);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* Line scans: keeps the binned C1 in out and replaces (q, c) by the 2-D
 * points with C > 0 (inverse Abel transform, abel.h, each bin weighted by
 * the wavevectors it holds); *m is updated. */
static vl_status line_to_2d(vl_topography_spectrum *out, double *q, double *c, size_t *count,
                            size_t *m) {
  size_t n = *m;
  vl_status st = VL_ENOMEM;
  double *c2 = malloc(n * sizeof *c2);
  out->q1_per_m = malloc(n * sizeof *out->q1_per_m);
  out->c1_m3 = malloc(n * sizeof *out->c1_m3);
  if (c2 && out->q1_per_m && out->c1_m3)
    st = vl_abel_profile_to_surface(n, q, c, count, c2, &out->tail_slope);
  if (st != VL_OK) {
    free(c2);
    return st;
  }
  memcpy(out->q1_per_m, q, n * sizeof *q);
  memcpy(out->c1_m3, c, n * sizeof *c);
  out->n1 = n;
  size_t kept = 0;
  for (size_t j = 0; j < n; j++) {
    if (!(c2[j] > 0.0 && isfinite(c2[j]))) {
      out->n_dropped++;
      continue;
    }
    q[kept] = q[j];
    c[kept] = c2[j];
    count[kept] = count[j];
    kept++;
  }
  *m = kept;
  free(c2);
  return VL_OK;
}

/* Step 7: the first point's C continued down to the radius q_e of a disc of
 * one lattice cell. The cells of the wavevectors |q| >= 2 pi/L tile the
 * plane outside the cell of q = 0, so the tabulated spectrum, which is
 * zero below its first point, would otherwise drop about half the power of
 * the lowest ring (four wavevectors at 2 pi/L: a large share of h_rms^2
 * when nothing rolls off within the measurement). A line scan of length L
 * is treated as a square L x L. */
static void extend_low(const vl_topography *t, vl_topography_spectrum *out) {
  double lx = (double)t->nx * t->dx_m;
  double ly = t->kind == VL_TOPOGRAPHY_MAP ? (double)t->ny * t->dy_m : lx;
  double qe = sqrt(TWO_PI / lx * TWO_PI / ly / PI);
  if (!(qe < out->q_per_m[0])) return;
  memmove(out->q_per_m + 1, out->q_per_m, out->n * sizeof *out->q_per_m);
  memmove(out->c_m4 + 1, out->c_m4, out->n * sizeof *out->c_m4);
  memmove(out->count + 1, out->count, out->n * sizeof *out->count);
  out->q_per_m[0] = qe;
  out->c_m4[0] = out->c_m4[1];
  out->count[0] = 0;
  out->n++;
  out->extended = 1;
}

static void provenance(const vl_topography *t, const vl_topography_psd_options *o,
                       vl_topography_spectrum *out) {
  char size[160], steps[200];
  char window[64];
  if (o->taper >= 1.0)
    snprintf(window, sizeof window, "Hann window");
  else if (o->taper > 0.0)
    snprintf(window, sizeof window, "Tukey window (taper %.3g)", o->taper);
  else
    snprintf(window, sizeof window, "no window");
  if (t->kind == VL_TOPOGRAPHY_MAP)
    snprintf(size, sizeof size, "height map %zu x %zu px, %.4g x %.4g m (pixel %.4g x %.4g m%s)",
             t->nx, t->ny, (double)t->nx * t->dx_m, (double)t->ny * t->dy_m, t->dx_m, t->dy_m,
             t->square_assumed ? ", square assumed: no '# Height:'" : "");
  else
    snprintf(size, sizeof size, "line scan %zu points over %.4g m (dx %.4g m)", t->nx,
             (double)t->nx * t->dx_m, t->dx_m);
  if (t->kind == VL_TOPOGRAPHY_MAP)
    snprintf(steps, sizeof steps, "plane removed; %s (power / %.4g); 2-D FFT, radial average",
             window, out->window_power);
  else
    snprintf(steps, sizeof steps,
             "line removed; %s (power / %.4g); 1-D FFT, inverse Abel "
             "transform to 2-D (C1 tail slope %.3g; %zu points dropped, C <= 0)",
             window, out->window_power, out->tail_slope, out->n_dropped);
  snprintf(out->provenance, sizeof out->provenance,
           "%s; %s; %.3g log bins per decade over q = %.4g ... %.4g 1/m (%.3g x 2 pi/L ... %.3g x "
           "pi/dx); %zu points; h_rms: topography %.4g m, band %.4g m, tabulated PSD %.4g m",
           size, steps, o->bins_per_decade, out->q_min_per_m, out->q_max_per_m, o->long_cut,
           o->short_cut, out->n, out->hrms_topography_m, out->hrms_band_m, out->hrms_psd_m);
}

vl_status vl_topography_psd(const vl_topography *t, const vl_topography_psd_options *opt,
                            vl_topography_spectrum *out, vl_error *err) {
  vl_topography_psd_options o = opt ? *opt : vl_topography_psd_options_default();
  vl_status st;
  bins b = {0};
  vl_psd tab = {0};
  int map = t && t->kind == VL_TOPOGRAPHY_MAP;
  const char *src = t && t->source ? t->source : "<topography>";

  memset(out, 0, sizeof *out);
  st = check_options(t, &o, err);
  if (st != VL_OK) return st;
  double l = map ? fmin((double)t->nx * t->dx_m, (double)t->ny * t->dy_m) : (double)t->nx * t->dx_m;
  double pixel = map ? fmax(t->dx_m, t->dy_m) : t->dx_m;
  out->q_min_per_m = o.long_cut * TWO_PI / l;
  out->q_max_per_m = o.short_cut * PI / pixel;
  if (!(out->q_max_per_m > out->q_min_per_m)) {
    vl_error_set(err, "%s: the band is empty (q_min %g >= q_max %g 1/m)", src, out->q_min_per_m,
                 out->q_max_per_m);
    return VL_EINPUT;
  }
  st = VL_ENOMEM;
  if (!bins_init(&b, out->q_min_per_m, out->q_max_per_m, o.bins_per_decade)) goto cleanup;
  st = map ? map_spectrum(t, o.taper, &b) : line_spectrum(t, o.taper, &b);
  if (st != VL_OK) goto cleanup;
  st = VL_ENOMEM;
  out->window_power = b.window_power;
  out->q_per_m = malloc((b.n + 1) * sizeof *out->q_per_m); /* + 1: step 7 */
  out->c_m4 = malloc((b.n + 1) * sizeof *out->c_m4);
  out->count = malloc((b.n + 1) * sizeof *out->count);
  if (!out->q_per_m || !out->c_m4 || !out->count) goto cleanup;
  out->n = bins_points(&b, out->q_per_m, out->c_m4, out->count);
  out->hrms_topography_m = vl_topography_hrms(t);
  out->hrms_band_m = sqrt(b.band_power);
  if (!(b.band_power > 0.0) || !(out->hrms_topography_m > FLAT_TOL * raw_rms(t))) {
    vl_error_set(err, "%s: no roughness left after removing the %s: the heights are flat", src,
                 map ? "plane" : "line");
    st = VL_EINPUT;
    goto cleanup;
  }
  if (!map && out->n >= 2) {
    st = line_to_2d(out, out->q_per_m, out->c_m4, out->count, &out->n);
    if (st != VL_OK) goto cleanup;
  }
  if (o.extend_low && o.long_cut == 1.0 && out->n >= 2) extend_low(t, out);
  if (out->n < 2) {
    vl_error_set(err,
                 "%s: only %zu point(s) of the spectrum in the band q = %g ... %g 1/m: too "
                 "short a measurement for a PSD",
                 src, out->n, out->q_min_per_m, out->q_max_per_m);
    st = VL_EINPUT;
    goto cleanup;
  }
  st = vl_psd_init_tabulated(&tab, out->n, out->q_per_m, out->c_m4, err);
  if (st != VL_OK) {
    vl_error_prefix(err, "%s: the estimated PSD", src);
    goto cleanup;
  }
  out->hrms_psd_m = vl_psd_hrms(&tab);
  provenance(t, &o, out);
  st = VL_OK;

cleanup:
  if (st == VL_ENOMEM) vl_error_set(err, "%s: out of memory for the PSD", src);
  bins_free(&b);
  vl_psd_free(&tab);
  if (st != VL_OK) vl_topography_spectrum_free(out);
  return st;
}
