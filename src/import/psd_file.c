/* Tabulated PSD files (csv.h): finds the wavevector and spectrum columns
 * and their units in the header, has the strict CSV reader (csv.c) read
 * the numbers under the names the file gives them, converts to SI, sorts
 * and merges the points, turns a 1-D spectrum into the 2-D one (abel.c)
 * and refuses an implausible result. */
#define _POSIX_C_SOURCE 200809L

#include "csv_private.h"
#include "viscolube/csv.h"

#include "abel.h"
#include "import_text.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Longest header cell a PSD column name is looked for in. */
#define CELL_TEXT_MAX 64

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

/* The q and C columns of the header line (other columns ignored) and the
 * units their names give, if any; *count gets the number of fields. */
static vl_status psd_header(vl_span line, size_t line_no, psd_layout *pl, size_t *count,
                            vl_error *err) {
  vl_span cells[VL_IMPORT_MAX_FIELDS + 1];
  *count = vl_import_split(line, pl->d.delimiter, cells, VL_IMPORT_MAX_FIELDS + 1);
  psd_col col;
  for (size_t f = 0; f < *count && f < VL_IMPORT_MAX_FIELDS; f++) {
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
  return VL_OK;
}

/* The row after the header (its cells, as many as the header's) is the
 * units row when its q or C cell is not a number but a unit of its column:
 * then both must be units, agreeing with the header's, and they settle the
 * units. Otherwise it is data and pl is left as it is. */
static vl_status psd_units_row(const vl_span *cells, size_t line_no, psd_layout *pl,
                               vl_error *err) {
  psd_col *pc[2] = {&pl->q, &pl->c};
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
                     : "a wavevector (1/m, 1/um, 1/nm)");
      return VL_EINPUT;
    }
    if (pc[i]->has_unit && (probe.factor != pc[i]->factor || probe.power != pc[i]->power)) {
      vl_error_set(err,
                   "%s:%zu: column '%s' (field %zu): mixed units: the header says %s but "
                   "the units row says %s",
                   pl->src, line_no, pc[i]->text, pc[i]->field + 1, pc[i]->unit, pl->units_row[i]);
      return VL_EINPUT;
    }
    *pc[i] = probe;
    pc[i]->has_unit = 1;
  }
  pl->has_units_row = is_units;
  return VL_OK;
}

/* Finds the q and C columns in the header line, then reads the optional
 * units row; every unit settled or an error. */
static vl_status psd_scan(const char *text, size_t len, psd_layout *pl, vl_error *err) {
  size_t pos = 0, line_no = 0, count;
  vl_span line, cells[VL_IMPORT_MAX_FIELDS + 1];
  if (!vl_import_next_line(text, len, &pos, &line_no, &line)) return VL_OK; /* the reader says so */
  pl->header_line = line_no;
  vl_status st = psd_header(line, line_no, pl, &count, err);
  if (st != VL_OK) return st;
  if (vl_import_next_line(text, len, &pos, &line_no, &line) &&
      vl_import_split(line, pl->d.delimiter, cells, VL_IMPORT_MAX_FIELDS + 1) == count &&
      (st = psd_units_row(cells, line_no, pl, err)) != VL_OK)
    return st;
  psd_col *pc[2] = {&pl->q, &pl->c};
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
