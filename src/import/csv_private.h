/* The private part of viscolube/csv.h: the generic strict
 * table reader (its column specifications, tables and options) and the PSD
 * reader on a string, which the import layer, the database and the tests use.
 * Programs read Prony, PSD and DMA files through the public calls. */
#ifndef VISCOLUBE_CSV_PRIVATE_H
#define VISCOLUBE_CSV_PRIVATE_H

#include "viscolube/csv.h"

typedef enum {
  VL_CSV_ANY = 0,         /* any finite number */
  VL_CSV_NONNEGATIVE = 1, /* >= 0 */
  VL_CSV_POSITIVE = 2     /* > 0 */
} vl_csv_sign;

/* What the caller expects of one column. */
typedef struct {
  const char *name;  /* header cell, e.g. "tau_s" */
  const char *units; /* accepted units-row spellings, '|'-separated, e.g. "1/m|m^-1" */
  vl_csv_sign sign;  /* constraint on every value */
  int increasing;    /* nonzero: values must increase strictly down the file */
  int optional;      /* nonzero: the column may be absent from the header */
} vl_csv_column;

/* A parsed table. Values are stored in the caller's column order (not the
 * file's); an absent optional column reads as NAN and present[c] == 0. */
typedef struct {
  char *source;      /* the file name used in messages (owned) */
  size_t n_cols;     /* number of requested columns */
  size_t n_rows;     /* data rows */
  double *values;    /* n_rows * n_cols, row-major (owned) */
  size_t *lines;     /* 1-based source line of each data row (owned) */
  int *present;      /* n_cols flags (owned) */
  int has_units_row; /* the file had a (matching) units row */
  char delimiter;    /* ',', ';' or '\t' as read */
  int decimal_comma; /* numbers were read with a decimal comma */
  size_t n_ignored;  /* header columns ignored (vl_csv_options.ignore_unknown) */
  char *ignored;     /* their names, "'run', 'force'" (owned; NULL when none) */
} vl_csv;

/* How to read (all zero: the defaults of vl_csv_read_text). */
typedef struct {
  int ignore_unknown; /* nonzero: header columns no requested column names are skipped (listed
                         in vl_csv.ignored) instead of refused */
  char delimiter;     /* ',', ';' or '\t'; 0: detected from the file (see above) */
  int decimal_comma;  /* with a given ';' or '\t' delimiter: numbers use a decimal comma */
} vl_csv_options;

/* Reads and checks the CSV file at path against the n_cols column specs.
 * On success *out owns its arrays (release with vl_csv_free); on failure
 * *out is left empty (safe to vl_csv_free) and err names file, line and
 * column. Returns VL_EIO if the file cannot be read, VL_EINPUT for bad
 * content, VL_ENOMEM. */
vl_status vl_csv_read_file(const char *path, const vl_csv_column *cols, size_t n_cols, vl_csv *out,
                           vl_error *err);

/* As vl_csv_read_file for text[0..len) already in memory; source names it in
 * messages. The text need not be NUL-terminated and is not modified. */
vl_status vl_csv_read_text(const char *text, size_t len, const char *source,
                           const vl_csv_column *cols, size_t n_cols, vl_csv *out, vl_error *err);

/* As vl_csv_read_text with options (NULL: the defaults). */
vl_status vl_csv_read_text_opts(const char *text, size_t len, const char *source,
                                const vl_csv_column *cols, size_t n_cols,
                                const vl_csv_options *opts, vl_csv *out, vl_error *err);

/* Releases what a vl_csv owns and empties it; accepts an empty table. */
void vl_csv_free(vl_csv *csv);

/* Value of data row `row`, requested column `col`; NAN when either index is
 * out of range or the column is an absent optional one. */
double vl_csv_value(const vl_csv *csv, size_t row, size_t col);

/* "2d", "1d". */
const char *vl_psd_file_kind_name(vl_psd_file_kind kind);

/* Reads the PSD file text[0..len) (named source in messages) holding the
 * kind of spectrum given. On VL_OK *psd is initialised by
 * vl_psd_init_tabulated (caller vl_psd_free) and *report (may be NULL)
 * says what was done; on failure *psd is empty and err holds the sentence
 * (with FILE:LINE where a row or the header is at fault; every offending
 * row at once). VL_EINPUT, VL_ENOMEM. */
vl_status vl_csv_read_psd_text(const char *text, size_t len, const char *source,
                               vl_psd_file_kind kind, vl_psd *psd, vl_psd_read_report *report,
                               vl_error *err);

/* ---- measured Stribeck curves ------------------------------------------
 *
 * A friction curve (`pair calibrate --measured FILE`): the delimiter,
 * decimal-comma, comment and number rules above; a header naming a
 * sliding-speed column with its unit in brackets or parentheses (v, v0,
 * speed, velocity, sliding speed: m/s, mm/s, um/s, nm/s, cm/s, m/min,
 * mm/min; or v_m_s) and a friction-coefficient column (mu, cof, friction,
 * friction coefficient; unit '-' or '1' if any); other columns ignored.
 * Values are read as written (signs are the caller's to judge); speeds in
 * m/s. On success *v_m_s and *mu are malloc'd (caller frees) with *n rows.
 * VL_EINPUT naming file, line and field; VL_EIO, VL_ENOMEM. */
vl_status vl_friction_curve_read_text(const char *text, size_t len, const char *source,
                                      double **v_m_s, double **mu, size_t *n, vl_error *err);

#endif
