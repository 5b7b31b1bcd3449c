/* viscolube: what the text readers of the import layer share (csv.c,
 * psd_file.c, dma.c, topography_file.c): pieces of text (spans), reading a
 * whole file, walking its meaningful lines, refusing spreadsheets,
 * detecting the delimiter and the decimal comma, strict numbers, and
 * collecting the offending lines of a file into one message. Private to
 * the library; it calls no other file of the layer. */
#ifndef VL_IMPORT_TEXT_H
#define VL_IMPORT_TEXT_H

#include <stdarg.h>
#include <stddef.h>

#include "viscolube/status.h"

/* Header fields beyond this are refused by the CSV reader (csv.c): no
 * table of ours has that many. */
#define VL_IMPORT_MAX_FIELDS 256
/* Tables (csv.c, psd_file.c) larger than this are refused before they are
 * read whole: measured tables are kilobytes to a few megabytes, a bigger
 * file is a stray disk image or log. */
#define VL_IMPORT_TABLE_MAX_BYTES ((size_t)256 << 20)

/* ---- spans: a piece of a text held elsewhere ------------------------------ */

/* s.p[0..s.n), not NUL-terminated: the readers parse the file's buffer in
 * place instead of copying every line and cell. */
typedef struct {
  const char *p;
  size_t n;
} vl_span;

/* A blank between fields: space or tab. */
int vl_is_blank(char c);

/* s without the blanks at both ends. */
vl_span vl_span_trim(vl_span s);

/* s trimmed, then without one pair of enclosing double quotes (trimmed
 * again inside them): header and units cells of spreadsheet exports are
 * quoted. */
vl_span vl_span_unquote(vl_span s);

/* Does s hold exactly the text t (vl_span_eq_nocase: ASCII case ignored)? */
int vl_span_eq(vl_span s, const char *t);
int vl_span_eq_nocase(vl_span s, const char *t);

/* Does s hold the byte c? */
int vl_span_has(vl_span s, char c);

/* Copies s into buf[size] for quoting in a message: at most 40 bytes then
 * "...", control bytes as '?' (a cell may hold anything, and the message
 * goes to a terminal). */
void vl_span_excerpt(vl_span s, char *buf, size_t size);

/* ---- files and lines ----------------------------------------------------- */

/* The whole file at path in a malloc'd buffer (*buf, *len; not
 * NUL-terminated; the caller frees it). A file of max_bytes or more is
 * refused as VL_EINPUT "PATH: larger than N MiB: not WHAT" (a stray disk
 * image or log is not read whole; max_bytes is 64 KiB times a power of
 * two, the sizes the buffer doubles through); VL_EIO when it cannot be
 * opened or read, VL_ENOMEM. On failure *buf is NULL. */
vl_status vl_import_read_file(const char *path, size_t max_bytes, const char *what, char **buf,
                              size_t *len, vl_error *err);

/* The next line of text[*pos..len) that is not blank and not a '#'
 * comment, as *line (LF ends a line, a CR before it is dropped; blanks
 * kept). A UTF-8 byte-order mark at the start of the text is skipped.
 * *pos and *line_no (1-based number of the last line read) carry the
 * state from 0, 0. Returns 0 at the end of the text. */
int vl_import_next_line(const char *text, size_t len, size_t *pos, size_t *line_no, vl_span *line);

/* Replaces the control bytes of err's message, but the line breaks
 * between the sentences of a problem list, by '?': messages quote cells of
 * the file and go to a terminal. No-op without err. */
void vl_import_sanitise(vl_error *err);

/* ---- delimited text ------------------------------------------------------ */

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

/* Splits line at the delimiter (outside double quotes) into at most cap
 * cells (cells may be NULL when cap is 0, to count them); returns the
 * total count, which may exceed cap. */
size_t vl_import_split(vl_span line, char delimiter, vl_span *cells, size_t cap);

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
