/* Fuzz target: the generic strict CSV reader (vl_csv_read_text) with column
 * specifications chosen by the input, as future readers (DMA files, ...)
 * will call it. The first bytes pick 1-4 columns (name, units, sign,
 * increasing, optional); the rest is the file. The text is not
 * NUL-terminated, so ASan sees any read past its end.
 * The text's length picks whether unknown columns are ignored.
 * Properties: a refused file gets VL_EINPUT, an emptied table and lines
 * each starting with the file name; an accepted one keeps every promise of csv.h
 * (all values finite, signs, strictly increasing columns, absent optional
 * columns NaN, line numbers increasing, at least one row). */
#include "csv_private.h"
#include "vl_fuzz.h"

#include <math.h>
#include <string.h>

#include "viscolube/csv.h"

static const char *const names[] = {"A",   "tau_s", "q_per_m", "C_m4",      "f_hz",
                                    "T_C", "E1_pa", "E2_pa",   "tan_delta", "x"};
static const char *const units[] = {"1|-", "s", "1/m|m^-1", "m^4|m4", "Hz", "C|degC", "Pa", NULL};
#define N_NAMES (sizeof names / sizeof *names)
#define N_UNITS (sizeof units / sizeof *units)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 1) return 0;
  size_t n_cols = 1 + (data[0] & 3u), first = (data[0] >> 2) % N_NAMES;
  if (size < 1 + n_cols) return 0;
  vl_csv_column cols[4];
  for (size_t c = 0; c < n_cols; c++) {
    uint8_t b = data[1 + c];
    cols[c] = (vl_csv_column){.name = names[(first + c) % N_NAMES], /* distinct names */
                              .units = units[(b >> 4) % N_UNITS],
                              .sign = (vl_csv_sign)(b % 3),
                              .increasing = (b >> 2) & 1,
                              .optional = (b >> 3) & 1};
  }
  const char *text = (const char *)data + 1 + n_cols;
  size_t len = size - 1 - n_cols;

  vl_csv csv;
  vl_error err = {{0}};
  vl_csv_options opt = {.ignore_unknown = (int)(len & 1)}; /* the dialect is detected */
  vl_status st = vl_csv_read_text_opts(text, len, "fuzz.csv", cols, n_cols, &opt, &csv, &err);
  if (st != VL_OK) {
    FUZZ_CHECK(st == VL_EINPUT, "status %d: %s", (int)st, err.msg);
    FUZZ_CHECK(!strncmp(err.msg, "fuzz.csv:", 9), "message does not name the file: %s", err.msg);
    FUZZ_CHECK(vl_fuzz_message_clean(err.msg, "fuzz.csv"), "control byte in message: %s", err.msg);
    FUZZ_CHECK(!csv.values && !csv.lines && !csv.present && csv.n_rows == 0,
               "a refused table is not empty");
    vl_csv_free(&csv); /* documented as safe */
    return 0;
  }
  FUZZ_CHECK(csv.n_cols == n_cols && csv.n_rows >= 1, "n_cols %zu, n_rows %zu", csv.n_cols,
             csv.n_rows);
  FUZZ_CHECK(!strcmp(csv.source, "fuzz.csv"), "source '%s'", csv.source);
  for (size_t c = 0; c < n_cols; c++)
    FUZZ_CHECK(csv.present[c] || cols[c].optional, "required column %zu absent", c);
  for (size_t r = 0; r < csv.n_rows; r++) {
    FUZZ_CHECK(csv.lines[r] >= 1 && (r == 0 || csv.lines[r] > csv.lines[r - 1]),
               "line numbers not increasing at row %zu", r);
    for (size_t c = 0; c < n_cols; c++) {
      double v = vl_csv_value(&csv, r, c);
      if (!csv.present[c]) {
        FUZZ_CHECK(isnan(v), "absent column %zu reads %g", c, v);
        continue;
      }
      FUZZ_CHECK(isfinite(v), "row %zu col %zu not finite", r, c);
      FUZZ_CHECK(cols[c].sign != VL_CSV_POSITIVE || v > 0.0, "row %zu col %zu: %g not > 0", r, c,
                 v);
      FUZZ_CHECK(cols[c].sign != VL_CSV_NONNEGATIVE || v >= 0.0, "row %zu col %zu: %g < 0", r, c,
                 v);
      FUZZ_CHECK(!cols[c].increasing || r == 0 || v > vl_csv_value(&csv, r - 1, c),
                 "row %zu col %zu not increasing", r, c);
    }
  }
  FUZZ_CHECK(isnan(vl_csv_value(&csv, csv.n_rows, 0)) && isnan(vl_csv_value(&csv, 0, n_cols)),
             "out-of-range index does not read NaN");
  vl_csv_free(&csv);
  FUZZ_CHECK(!csv.values && csv.n_rows == 0, "vl_csv_free did not empty the table");
  return 0;
}
