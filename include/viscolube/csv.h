/* viscolube: a small strict reader of numeric CSV files.
 *
 * Used for material tables (Prony terms, tabulated PSDs) and for measured
 * data (DMA files). The format is deliberately narrow so that a mistake in
 * a file is reported instead of silently misread:
 *
 *   - Lines end in LF or CRLF; a UTF-8 byte-order mark is skipped. Lines that
 *     are blank or whose first non-blank character is '#' are ignored (they
 *     still count for line numbers), so a file can carry its provenance.
 *   - Fields are separated by commas, semicolons or tabs, as the file shows:
 *     the delimiter that splits the header and the first 50 rows after it
 *     into the same number of fields (ambiguity is an error naming both).
 *     With ';' or a tab, numbers may use a decimal comma ("0,25"); then a
 *     '.' in a number is refused (it would be a thousands separator).
 *   - Spreadsheets (.xlsx, .xlsm, .xls, .ods, or a ZIP or OLE2 signature at
 *     the start) are refused with a sentence telling how to export CSV.
 *   - The first other line is the header: column names, matched exactly
 *     (case-sensitive, surrounding blanks and one pair of double quotes
 *     removed). Every required column must appear once; no unknown column is
 *     allowed unless the caller ignores them (vl_csv_options); the order is
 *     free.
 *   - Units row (optional). The line after the header is a units row exactly
 *     when at least one of its cells is not a number; it is then accepted only
 *     if every cell is one of the expected spellings of its column's units
 *     (e.g. "1,s" for A,tau_s or "1/m,m^4" for q_per_m,C_m4). Anything else
 *     there (e.g. "Pa,s", or a typo in a number) is an error naming the cell
 *     and the units row the file would need. A row of numbers is data.
 *   - Every data row has as many cells as the header; every cell of a
 *     requested column is a decimal number ([+-]digits[.digits][e[+-]digits]),
 *     finite and within double range. NaN, Inf, hex floats, empty cells and
 *     thousands separators are rejected. Per-column sign and ordering
 *     constraints are checked here. Cells of ignored columns are not read.
 *   - At least one data row.
 *
 * Every error is one sentence of the form
 *   "FILE:LINE: column 'NAME' (field K): what is wrong (got 'TEXT')"
 * (file-level errors omit the column). Data rows are all read before the
 * reader gives up: the message then holds one such sentence per offending
 * line, one per text line, up to 20 (as many as fit in a vl_error), then
 * "FILE: and N more problems (M lines at fault in all)". The reader never
 * prints. */
#ifndef VISCOLUBE_CSV_H
#define VISCOLUBE_CSV_H

#include <stddef.h>

#include "viscolube/rheology.h"
#include "viscolube/roughness.h"
#include "viscolube/status.h"

/* Parses a whole string as a finite decimal number with the reader's rules
 * (surrounding blanks allowed). Returns VL_OK, or VL_EINPUT with *why set to
 * a short static reason ("not a number", "NaN and infinity are not allowed",
 * "outside the range of a double", "empty cell"). Used for command-line values. */
vl_status vl_csv_parse_double(const char *text, double *out, const char **why);

/* Prony file: header "A,tau_s" (optional units row "1,s"), one creep term
 * per row (docs/MODEL.md section 2), A >= 0, tau_s > 0, at most
 * VL_PRONY_MAX_TERMS rows. Fills prony->n_terms, A and tau_s only (Einf
 * and nu are left as they were). */
vl_status vl_csv_read_prony(const char *path, vl_prony *prony, vl_error *err);

/* ---- tabulated PSD files -------------------------------------------------
 *
 * The delimiter, decimal-comma, comment and number rules above. The header
 * names a wavevector column and a spectrum column (any order; other
 * columns are ignored and listed in the notes), each with its unit:
 *   q: q, wavevector, wavenumber, k            1/m, 1/mm, 1/um (1/µm), 1/nm;
 *                                              also m^-1, per_m, ...
 *   C: C, C(q), PSD (2-D unless the unit says otherwise), C2D, C2, PSD2D
 *      (2-D), C1D, C1, PSD1D (1-D)             m^4, mm^4, um^4, nm^4 (2-D),
 *                                              m^3 ... nm^3 (1-D); m4, um4 ...
 * Names are compared in any case without blanks, '_', '-' and '.'; the
 * unit in brackets ("q [1/um]", "C (m^4)"), after a '_' ("q_per_m",
 * "C_m4"), or in a units row right after the header ("1/m,m^4"); header
 * and units row must agree. Rows in any order of q (sorted, noted); rows
 * repeating a q (within 1e-9 relative) are merged into one with the mean
 * C (noted); q > 0, C > 0; at least 2 distinct q.
 *
 * A 2-D spectrum is the isotropic C(q) of this project (h_rms^2 =
 * 2 pi \int q C dq). A 1-D one is a profile's two-sided C1(q)
 * (h_rms^2 = \int_{-inf}^{inf} C1 dq, m^3), converted by the inverse Abel
 * transform of topography.h (step 6) when the caller asks for it
 * (VL_PSD_FILE_1D); given where a 2-D one is expected (VL_PSD_FILE_2D), a
 * column whose name or unit says 1-D is refused with a sentence naming the
 * option. Plausibility: a spectrum whose h_rms lies outside
 * [VL_PSD_HRMS_MIN_M, VL_PSD_HRMS_MAX_M] or whose rms slope exceeds
 * VL_PSD_SLOPE_MAX is refused, naming which and the likely unit mistake. */

#define VL_PSD_HRMS_MIN_M 1e-10 /* 0.1 nm: below an atomic step */
#define VL_PSD_HRMS_MAX_M 1e-3  /* 1 mm: no contact roughness */
#define VL_PSD_SLOPE_MAX 10.0   /* rms slope: beyond ~84 degrees on average */

/* What a PSD file holds (see above). */
typedef enum {
  VL_PSD_FILE_2D = 0, /* the isotropic 2-D C(q), m^4 */
  VL_PSD_FILE_1D = 1  /* a profile's 1-D C1(q), m^3, converted to C(q) */
} vl_psd_file_kind;

/* "2d"/"2D" or "1d"/"1D" into *kind; VL_EINPUT otherwise. */
vl_status vl_psd_file_kind_parse(const char *text, vl_psd_file_kind *kind);

/* What reading a PSD file did, for the caller to tell the user. */
typedef struct {
  size_t n_rows;    /* data rows read */
  size_t n_merged;  /* rows merged into another of the same q */
  int reordered;    /* the rows were not in increasing q (sorted) */
  int converted_1d; /* a 1-D spectrum converted to the 2-D one */
  size_t n_dropped; /* 1-D points whose 2-D C came out <= 0 (dropped) */
  double hrms_m;    /* of the tabulated 2-D spectrum */
  double rms_slope;
  char notes[1024]; /* one sentence per line ('\n' after each): the dialect, ignored columns,
                       unit conversion, sorting, merging, the 1-D conversion */
} vl_psd_read_report;

/* As vl_csv_read_psd_text for the file at path; VL_EIO if unreadable. */
vl_status vl_csv_read_psd_file(const char *path, vl_psd_file_kind kind, vl_psd *psd,
                               vl_psd_read_report *report, vl_error *err);

/* vl_csv_read_psd_file for a 2-D spectrum, without the report. */
vl_status vl_csv_read_psd(const char *path, vl_psd *psd, vl_error *err);

vl_status vl_friction_curve_read_file(const char *path, double **v_m_s, double **mu, size_t *n,
                                      vl_error *err);

#endif
