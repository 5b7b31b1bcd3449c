/* Measured Stribeck curves (csv.h, vl_friction_curve_read_text): a table
 * of sliding speed, in the unit its header names, and friction
 * coefficient, in the dialects the DMA reader accepts. */
#include "csv_private.h"
#include "viscolube/csv.h"

#include "import_text.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_CELLS 64

/* The cell as lower-case text in buf (blanks and quotes removed). */
static void cell_text(vl_span s, char *buf, size_t size) {
  s = vl_span_unquote(s);
  size_t n = s.n < size - 1 ? s.n : size - 1;
  for (size_t i = 0; i < n; i++)
    buf[i] = (char)tolower((unsigned char)s.p[i]);
  buf[n] = '\0';
}

static const struct {
  const char *unit;
  double to_m_s;
} speed_units[] = {{"m/s", 1.0},          {"mm/s", 1e-3},        {"um/s", 1e-6},
                   {"\xc2\xb5m/s", 1e-6}, {"\xce\xbcm/s", 1e-6}, {"nm/s", 1e-9},
                   {"cm/s", 1e-2},        {"m/min", 1.0 / 60.0}, {"mm/min", 1e-3 / 60.0}};

/* name and unit of a header cell "NAME [UNIT]" or "NAME (UNIT)" */
static void split_unit(char *text, char **unit) {
  *unit = NULL;
  size_t n = strlen(text);
  if (n < 3 || (text[n - 1] != ']' && text[n - 1] != ')')) return;
  char open = text[n - 1] == ']' ? '[' : '(';
  char *o = strrchr(text, open);
  if (!o) return;
  text[n - 1] = '\0';
  *unit = o + 1;
  while (o > text && (o[-1] == ' ' || o[-1] == '_'))
    o--;
  *o = '\0';
}

static int is_speed_name(const char *s) {
  static const char *const names[] = {
      "v", "v0", "speed", "sliding speed", "velocity", "sliding velocity", "u", "v_s", NULL};
  for (size_t k = 0; names[k]; k++)
    if (!strcmp(s, names[k])) return 1;
  return 0;
}

static int is_mu_name(const char *s) {
  static const char *const names[] = {"mu",
                                      "\xc2\xb5",
                                      "\xce\xbc",
                                      "cof",
                                      "friction",
                                      "friction coefficient",
                                      "coefficient of friction",
                                      "f",
                                      NULL};
  for (size_t k = 0; names[k]; k++)
    if (!strcmp(s, names[k])) return 1;
  return 0;
}

/* Finds the two columns in the header; *scale converts the speed to m/s. */
static vl_status header(vl_span line, const vl_dialect *d, const char *source, size_t line_no,
                        size_t *col_v, size_t *col_mu, double *scale, size_t *n_cells,
                        vl_error *err) {
  vl_span cells[MAX_CELLS];
  size_t n = vl_import_split(line, d->delimiter, cells, MAX_CELLS);
  *n_cells = n;
  *col_v = *col_mu = (size_t)-1;
  for (size_t c = 0; c < n && c < MAX_CELLS; c++) {
    char text[128], *unit;
    cell_text(cells[c], text, sizeof text);
    split_unit(text, &unit);
    if (!strcmp(text, "v_m_s") || !strcmp(text, "speed_m_s")) {
      *col_v = c, *scale = 1.0;
    } else if (is_speed_name(text)) {
      if (!unit) {
        vl_error_set(err,
                     "%s:%zu: column '%s' (field %zu): the sliding speed needs its unit in the "
                     "header, e.g. 'v [mm/s]' (m/s, mm/s, um/s, nm/s, cm/s, m/min, mm/min)",
                     source, line_no, text, c + 1);
        return VL_EINPUT;
      }
      size_t k = 0, nu = sizeof speed_units / sizeof *speed_units;
      while (k < nu && strcmp(unit, speed_units[k].unit))
        k++;
      if (k == nu) {
        vl_error_set(err,
                     "%s:%zu: column '%s' (field %zu): unknown speed unit '%s' (m/s, mm/s, um/s, "
                     "nm/s, cm/s, m/min, mm/min)",
                     source, line_no, text, c + 1, unit);
        return VL_EINPUT;
      }
      *col_v = c, *scale = speed_units[k].to_m_s;
    } else if (is_mu_name(text) && (!unit || !strcmp(unit, "-") || !strcmp(unit, "1"))) {
      *col_mu = c;
    }
  }
  if (*col_v == (size_t)-1 || *col_mu == (size_t)-1) {
    vl_error_set(err,
                 "%s:%zu: the header needs a sliding-speed column with its unit ('v [mm/s]', "
                 "'speed (m/s)', 'v_m_s') and a friction-coefficient column ('mu', 'cof', "
                 "'friction')%s",
                 source, line_no, *col_v == (size_t)-1 ? ": no speed column" : ": no mu column");
    return VL_EINPUT;
  }
  return VL_OK;
}

vl_status vl_friction_curve_read_text(const char *text, size_t len, const char *source,
                                      double **v_m_s, double **mu, size_t *n, vl_error *err) {
  *v_m_s = *mu = NULL;
  *n = 0;
  vl_dialect d;
  vl_status st = vl_import_refuse_spreadsheet(text, len, source, err);
  if (st == VL_OK) st = vl_import_detect_dialect(text, len, source, &d, err);
  if (st != VL_OK) return st;
  size_t pos = 0, line_no = 0, col_v, col_mu, n_cells, cap = 0;
  double scale = 1.0;
  vl_span line;
  if (!vl_import_next_line(text, len, &pos, &line_no, &line)) {
    vl_error_set(err, "%s: no header and no data", source);
    return VL_EINPUT;
  }
  st = header(line, &d, source, line_no, &col_v, &col_mu, &scale, &n_cells, err);
  if (st != VL_OK) {
    vl_import_sanitise(err); /* the header's cells are quoted */
    return st;
  }
  vl_problems pr;
  vl_problems_init(&pr);
  double *v = NULL, *m = NULL;
  size_t count = 0;
  while (vl_import_next_line(text, len, &pos, &line_no, &line)) {
    vl_span cells[MAX_CELLS];
    size_t k = vl_import_split(line, d.delimiter, cells, MAX_CELLS);
    if (k != n_cells) {
      vl_problems_add(&pr, line_no, "%s:%zu: %zu fields, the header has %zu", source, line_no, k,
                      n_cells);
      continue;
    }
    double x[2];
    size_t cols[2] = {col_v, col_mu};
    int bad = 0;
    for (int j = 0; j < 2; j++) {
      const char *why = NULL;
      vl_span s = vl_span_trim(cells[cols[j]]);
      if (vl_import_parse_number(s.p, s.n, d.decimal_comma, &x[j], &why) != VL_OK) {
        char ex[48];
        vl_span_excerpt(s, ex, sizeof ex);
        vl_problems_add(&pr, line_no, "%s:%zu: field %zu: %s (got '%s')", source, line_no,
                        cols[j] + 1, why, ex);
        bad = 1;
      }
    }
    if (bad) continue;
    if (count == cap) {
      cap = cap ? 2 * cap : 64;
      double *nv = realloc(v, cap * sizeof *nv), *nm = nv ? realloc(m, cap * sizeof *nm) : NULL;
      if (nv) v = nv;
      if (nm) m = nm;
      if (!nv || !nm) {
        free(v), free(m);
        vl_error_set(err, "%s: out of memory", source);
        return VL_ENOMEM;
      }
    }
    v[count] = x[0] * scale, m[count] = x[1];
    count++;
  }
  if (pr.total) {
    vl_problems_finish(&pr, source, err);
    vl_import_sanitise(err);
    free(v), free(m);
    return VL_EINPUT;
  }
  if (count == 0) {
    vl_error_set(err, "%s: no data rows", source);
    free(v), free(m);
    return VL_EINPUT;
  }
  *v_m_s = v, *mu = m, *n = count;
  return VL_OK;
}

vl_status vl_friction_curve_read_file(const char *path, double **v_m_s, double **mu, size_t *n,
                                      vl_error *err) {
  char *buf = NULL;
  size_t len = 0;
  *v_m_s = *mu = NULL;
  *n = 0;
  vl_status st =
      vl_import_read_file(path, VL_IMPORT_TABLE_MAX_BYTES, "a friction curve", &buf, &len, err);
  if (st != VL_OK) return st;
  st = vl_friction_curve_read_text(buf, len, path, v_m_s, mu, n, err);
  free(buf);
  return st;
}
