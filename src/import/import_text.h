/* viscolube: what every delimited text reader of the import layer shares
 * (csv.c, dma.c): refusing spreadsheets, detecting the delimiter and the
 * decimal comma, and collecting the offending lines of a file into one
 * message. Private to the library. */
#ifndef VL_IMPORT_TEXT_H
#define VL_IMPORT_TEXT_H

#include <stdarg.h>
#include <stddef.h>

#include "viscolube/status.h"

/* Offending lines reported in one message before "and N more". */
#define VL_IMPORT_MAX_PROBLEMS 20

/* How a file separates its fields and writes its numbers. */
typedef struct {
  char delimiter;    /* ',', ';' or '\t' */
  int decimal_comma; /* numbers written "1,5" (only with ';' or '\t') */
} vl_dialect;

/* VL_EINPUT with a sentence telling the user to export the sheet as CSV
 * when source ends in .xlsx, .xlsm, .xls or .ods (any case) or text starts
 * with a ZIP or OLE2 signature (the containers of those formats); VL_OK
 * otherwise. */
vl_status vl_import_refuse_spreadsheet(const char *text, size_t len, const char *source,
                                       vl_error *err);

/* The dialect of text (blank and '#' lines skipped; the first other line
 * is the header, the next up to 50 are sampled). A candidate delimiter
 * (tab, ';', ',') fits when it splits the header and every sampled line
 * into the same number (> 1) of fields; double-quoted text does not count.
 * Exactly one must fit; none fitting falls back to the delimiter the
 * header holds most of (tab, then ';', then ','; ',' when it holds none),
 * so that the reader names the first ragged line. Two fitting is
 * ambiguous: VL_EINPUT naming both. With ';' or tab, a comma between
 * digits in a sampled cell ("0,25") makes the file decimal-comma. */
vl_status vl_import_detect_dialect(const char *text, size_t len, const char *source, vl_dialect *d,
                                   vl_error *err);

/* "comma", "semicolon" or "tab". */
const char *vl_dialect_delimiter_name(char delimiter);

/* Splits line[0..n) at the delimiter (outside double quotes) into at most
 * cap cells (start, length); returns the total count, which may exceed
 * cap. */
size_t vl_import_split(const char *line, size_t n, char delimiter, const char **cell,
                       size_t *cell_n, size_t cap);

/* Parses cell[0..n) (blanks around allowed) as a strict decimal number
 * (csv.h's rules), with ',' as the decimal separator when decimal_comma
 * (a '.' is then refused: it would be a thousands separator). VL_OK, or
 * VL_EINPUT with *why a short static reason. */
vl_status vl_import_parse_number(const char *cell, size_t n, int decimal_comma, double *out,
                                 const char **why);

/* The offending lines of one file, gathered so that a user sees them all
 * at once: the first VL_IMPORT_MAX_PROBLEMS that fit in a vl_error, one
 * sentence per line, then "and N more". */
typedef struct {
  char text[VL_ERROR_MAX];
  size_t len;              /* bytes used in text */
  size_t shown;            /* sentences in text */
  size_t total;            /* sentences added */
  size_t last_line, lines; /* distinct source lines at fault */
} vl_problems;

void vl_problems_init(vl_problems *p);

/* Adds one sentence about source line `line` (printf-style). */
void vl_problems_add(vl_problems *p, size_t line, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Writes the gathered sentences into err, one per line, with "and N more
 * problems on M lines" when some did not fit. No-op without problems. */
void vl_problems_finish(const vl_problems *p, const char *source, vl_error *err);

/* Appends one sentence, as a line, to the notes buffer notes[size] of an
 * import report; silently cut when the buffer is full. */
void vl_import_note_v(char *notes, size_t size, const char *fmt, va_list ap)
    __attribute__((format(printf, 3, 0)));

#endif
