/* The strict CSV reader (csv.h): accepted layouts, every class of bad input
 * (each message must name file, line and column), the two material file
 * readers, and a mutation smoke test for memory safety under ASan. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "csv_private.h"
#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "viscolube/csv.h"

static const vl_csv_column prony_cols[] = {
    {.name = "A", .units = "1|-", .sign = VL_CSV_NONNEGATIVE},
    {.name = "tau_s", .units = "s", .sign = VL_CSV_POSITIVE},
};

static const vl_csv_column psd_cols[] = {
    {.name = "q_per_m", .units = "1/m|m^-1", .sign = VL_CSV_POSITIVE, .increasing = 1},
    {.name = "C_m4", .units = "m^4|m4", .sign = VL_CSV_POSITIVE},
};

static vl_status parse(const char *text, const vl_csv_column *cols, vl_csv *csv, vl_error *err) {
  return vl_csv_read_text(text, strlen(text), "in.csv", cols, 2, csv, err);
}

/* Parses text expecting VL_EINPUT with every needle in the message. The
 * message must also start with the file name and a line number. */
static void expect_bad(const char *text, const vl_csv_column *cols, const char *location,
                       const char *needle1, const char *needle2) {
  vl_csv csv;
  vl_error err = {{0}};
  vl_status st = parse(text, cols, &csv, &err);
  if (st != VL_EINPUT) fail_msg("accepted (status %d) bad input:\n%s", (int)st, text);
  if (strncmp(err.msg, location, strlen(location)) != 0)
    fail_msg("message '%s' does not start with '%s'", err.msg, location);
  if (needle1 && !strstr(err.msg, needle1)) fail_msg("message '%s' lacks '%s'", err.msg, needle1);
  if (needle2 && !strstr(err.msg, needle2)) fail_msg("message '%s' lacks '%s'", err.msg, needle2);
  assert_null(csv.values);
  assert_int_equal(csv.n_rows, 0);
  vl_csv_free(&csv);
}

static void test_reads_plain_table(void **state) {
  (void)state;
  vl_csv csv;
  vl_error err;
  assert_int_equal(parse("A,tau_s\n9,0.1\n0.5,1e-3\n0,2.5E+2\n", prony_cols, &csv, &err), VL_OK);
  assert_int_equal(csv.n_rows, 3);
  assert_int_equal(csv.has_units_row, 0);
  assert_true(vl_csv_value(&csv, 0, 0) == 9.0 && vl_csv_value(&csv, 0, 1) == 0.1);
  assert_true(vl_csv_value(&csv, 1, 0) == 0.5 && vl_csv_value(&csv, 1, 1) == 1e-3);
  assert_true(vl_csv_value(&csv, 2, 0) == 0.0 && vl_csv_value(&csv, 2, 1) == 250.0);
  assert_int_equal(csv.lines[0], 2);
  assert_int_equal(csv.lines[2], 4);
  assert_true(isnan(vl_csv_value(&csv, 3, 0))); /* out of range reads NAN */
  vl_csv_free(&csv);
  vl_csv_free(&csv); /* idempotent */
}

/* BOM, CRLF, comments, blank lines, blanks around cells, a quoted header,
 * a units row, columns in another order: all accepted, and line numbers
 * count every physical line. */
static void test_reads_tolerated_layout(void **state) {
  (void)state;
  const char *text = "\xEF\xBB\xBF# measured 2024, sample B\r\n"
                     "\r\n"
                     " \"tau_s\" , A \r\n"
                     "s,1\r\n"
                     "# a comment between rows\r\n"
                     " 0.1 , 9 \r\n"
                     "\r\n"
                     "1e-3,+0.5";
  vl_csv csv;
  vl_error err;
  assert_int_equal(parse(text, prony_cols, &csv, &err), VL_OK);
  assert_int_equal(csv.has_units_row, 1);
  assert_int_equal(csv.n_rows, 2);
  /* stored in the caller's column order (A, tau_s), not the file's */
  assert_true(vl_csv_value(&csv, 0, 0) == 9.0 && vl_csv_value(&csv, 0, 1) == 0.1);
  assert_true(vl_csv_value(&csv, 1, 0) == 0.5 && vl_csv_value(&csv, 1, 1) == 1e-3);
  assert_int_equal(csv.lines[0], 6);
  assert_int_equal(csv.lines[1], 8);
  vl_csv_free(&csv);

  /* the alternative spellings of a unit */
  assert_int_equal(parse("q_per_m,C_m4\nm^-1,m4\n1,2\n3,4\n", psd_cols, &csv, &err), VL_OK);
  assert_int_equal(csv.has_units_row, 1);
  vl_csv_free(&csv);
}

static void test_optional_column(void **state) {
  (void)state;
  const vl_csv_column cols[] = {
      {.name = "f_hz", .units = "Hz", .sign = VL_CSV_POSITIVE},
      {.name = "T_c", .units = "C", .optional = 1},
  };
  vl_csv csv;
  vl_error err;
  assert_int_equal(vl_csv_read_text("f_hz\n1\n2\n", 9, "x", cols, 2, &csv, &err), VL_OK);
  assert_int_equal(csv.present[0], 1);
  assert_int_equal(csv.present[1], 0);
  assert_true(isnan(vl_csv_value(&csv, 1, 1)));
  assert_true(vl_csv_value(&csv, 1, 0) == 2.0);
  vl_csv_free(&csv);
}

static void test_bad_cells(void **state) {
  (void)state;
  expect_bad("A,tau_s\n9,0.1\n1,abc\n", prony_cols, "in.csv:3:", "'tau_s'", "not a number");
  expect_bad("A,tau_s\n9,0.1\nNaN,1\n", prony_cols, "in.csv:3:", "'A'", "NaN");
  expect_bad("A,tau_s\n9,0.1\n1,nan\n", prony_cols, "in.csv:3:", "'tau_s'", "NaN");
  expect_bad("A,tau_s\n9,inf\n", prony_cols, "in.csv:2:", "'tau_s'", "infinity");
  expect_bad("A,tau_s\n9,0.1\n1,-Infinity\n", prony_cols, "in.csv:3:", "'tau_s'", "infinity");
  expect_bad("A,tau_s\n9,1e999\n", prony_cols, "in.csv:2:", "'tau_s'", "range");
  expect_bad("A,tau_s\n9,1e-999\n", prony_cols, "in.csv:2:", "'tau_s'", "range");
  expect_bad("A,tau_s\n9,0x1p3\n", prony_cols, "in.csv:2:", "'tau_s'", "not a number");
  expect_bad("A,tau_s\n9,1,000\n", prony_cols, "in.csv:2:", "fields", NULL);
  expect_bad("A,tau_s\n9,\n", prony_cols, "in.csv:2:", "'tau_s'", "empty");
  expect_bad("A,tau_s\n9,0.1 s\n", prony_cols, "in.csv:2:", "'tau_s'", "not a number");
  expect_bad("A,tau_s\n9,1.\n2,.\n", prony_cols, "in.csv:3:", "'tau_s'", "not a number");
  expect_bad("A,tau_s\n9,1e\n", prony_cols, "in.csv:2:", "'tau_s'", "not a number");
  expect_bad("A,tau_s\n9,0.1\n1\n", prony_cols, "in.csv:3:", "expected 2", "found 1");
  expect_bad("A,tau_s\n9,0.1\n1,2,3\n", prony_cols, "in.csv:3:", "expected 2", "found 3");
  /* an embedded NUL byte (text given with explicit length) */
  vl_csv csv;
  vl_error err;
  const char nul[] = "A,tau_s\n9,0\0.1\n";
  assert_int_equal(vl_csv_read_text(nul, sizeof nul - 1, "in.csv", prony_cols, 2, &csv, &err),
                   VL_EINPUT);
  assert_non_null(strstr(err.msg, "in.csv:2:"));
  assert_non_null(strstr(err.msg, "NUL"));
}

static void test_sign_and_order(void **state) {
  (void)state;
  expect_bad("A,tau_s\n9,0.1\n1,-2\n", prony_cols, "in.csv:3:", "'tau_s'", "> 0");
  expect_bad("A,tau_s\n9,0\n", prony_cols, "in.csv:2:", "'tau_s'", "> 0");
  expect_bad("A,tau_s\n-1,2\n", prony_cols, "in.csv:2:", "'A'", ">= 0");
  expect_bad("q_per_m,C_m4\n-1,2\n", psd_cols, "in.csv:2:", "'q_per_m'", "> 0");
  expect_bad("q_per_m,C_m4\n1,0\n", psd_cols, "in.csv:2:", "'C_m4'", "> 0");
  expect_bad("q_per_m,C_m4\n1,1\n3,1\n2,1\n", psd_cols, "in.csv:4:", "'q_per_m'", "line 3");
  expect_bad("q_per_m,C_m4\n1,1\n\n3,1\n3,1\n", psd_cols, "in.csv:5:", "'q_per_m'", "increase");
}

static void test_bad_structure(void **state) {
  (void)state;
  expect_bad("", prony_cols, "in.csv:1:", "empty file", "A,tau_s");
  expect_bad("\n\n  \n", prony_cols, "in.csv:3:", "empty file", NULL);
  expect_bad("# only a comment\n", prony_cols, "in.csv:1:", "empty file", NULL);
  expect_bad("9,0.1\n1,2\n", prony_cols, "in.csv:1:", "missing header", "A,tau_s");
  expect_bad("A,tau\n9,0.1\n", prony_cols, "in.csv:1:", "unknown column 'tau'",
             "did you mean 'tau_s'");
  expect_bad("a,tau_s\n9,0.1\n", prony_cols, "in.csv:1:", "unknown column 'a'", "did you mean 'A'");
  expect_bad("A,tau_s,T\n9,0.1,3\n", prony_cols, "in.csv:1:", "unknown column 'T'", NULL);
  expect_bad("A\n9\n", prony_cols, "in.csv:1:", "lacks column 'tau_s'", NULL);
  expect_bad("A,A\n9,9\n", prony_cols, "in.csv:1:", "appears twice", NULL);
  expect_bad("A,,tau_s\n9,1,0.1\n", prony_cols, "in.csv:1:", "field 2", "empty");
  expect_bad("A,tau_s\n", prony_cols, "in.csv:1:", "no data rows", NULL);
  expect_bad("A,tau_s\n1,s\n# nothing\n", prony_cols, "in.csv:2:", "no data rows", NULL);
}

/* The units-row rule of csv.h: a row with a non-numeric cell spelling its
 * column's unit is a units row, and then every cell must match. */
static void test_units_row(void **state) {
  (void)state;
  expect_bad("A,tau_s\nPa,s\n9,0.1\n", prony_cols, "in.csv:2:", "'Pa'", "must read '1,s'");
  expect_bad("A,tau_s\n1,ms\n9,0.1\n", prony_cols, "in.csv:2:", "'ms'", "1,s");
  expect_bad("q_per_m,C_m4\n1/m,m^2\n1,1\n2,1\n", psd_cols, "in.csv:2:", "'m^2'", "1/m,m^4");
  /* not recognisable as units: read as data, the message still names the
   * units row the file could have */
  expect_bad("A,tau_s\nPa,sec\n9,0.1\n", prony_cols, "in.csv:2:", "not a number", "1,s");
  /* a units row is only allowed directly after the header */
  expect_bad("A,tau_s\n9,0.1\n1,s\n", prony_cols, "in.csv:3:", "not a number", NULL);
  /* a second units row */
  expect_bad("A,tau_s\n1,s\n1,s\n9,0.1\n", prony_cols, "in.csv:3:", "not a number", NULL);
}

static void test_parse_double(void **state) {
  (void)state;
  double v = 0.0;
  const char *why = NULL;
  assert_int_equal(vl_csv_parse_double(" -1.5e-3 ", &v, &why), VL_OK);
  assert_true(v == -1.5e-3);
  assert_int_equal(vl_csv_parse_double(".5", &v, &why), VL_OK);
  assert_true(v == 0.5);
  assert_int_equal(vl_csv_parse_double("36e6", &v, &why), VL_OK);
  assert_true(v == 36e6);
  const char *bad[] = {"",     " ",   "abc",  "1x",    "--1", "1e",
                       "0x10", "nan", "-inf", "1e400", "1,5", "e5"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
    why = NULL;
    if (vl_csv_parse_double(bad[i], &v, &why) != VL_EINPUT) fail_msg("accepted '%s'", bad[i]);
    assert_non_null(why);
  }
  assert_int_equal(vl_csv_parse_double(NULL, &v, &why), VL_EINPUT);
}

static void test_read_file_errors(void **state) {
  (void)state;
  vl_csv csv;
  vl_error err;
  char path[4200];
  snprintf(path, sizeof path, "%s/missing.csv", vl_test_tmpdir());
  assert_int_equal(vl_csv_read_file(path, prony_cols, 2, &csv, &err), VL_EIO);
  assert_non_null(strstr(err.msg, path));
  /* a directory is not a file */
  const char *dir = vl_test_tmpdir();
  assert_int_equal(vl_csv_read_file(dir, prony_cols, 2, &csv, &err), VL_EIO);
  assert_non_null(strstr(err.msg, dir));
}

static void test_prony_reader(void **state) {
  (void)state;
  const char *dir = vl_test_tmpdir();
  char path[4200];
  snprintf(path, sizeof path, "%s/p.csv", dir);
  vl_test_write_file(path, "A,tau_s\n1,s\n9,0.1\n2,1e-4\n");
  vl_prony p = {.e_inf_pa = 1.0, .nu = 0.3};
  vl_error err;
  assert_int_equal(vl_csv_read_prony(path, &p, &err), VL_OK);
  assert_int_equal(p.n_terms, 2);
  assert_true(p.A[0] == 9.0 && p.tau_s[0] == 0.1 && p.A[1] == 2.0 && p.tau_s[1] == 1e-4);
  assert_true(p.e_inf_pa == 1.0 && p.nu == 0.3); /* untouched */

  /* one more term than fits: the message names the line of term 129 */
  size_t cap = 64 * (VL_PRONY_MAX_TERMS + 2);
  char *text = malloc(cap);
  size_t k = (size_t)snprintf(text, cap, "A,tau_s\n");
  for (int i = 0; i <= VL_PRONY_MAX_TERMS; i++)
    k += (size_t)snprintf(text + k, cap - k, "1,%d\n", i + 1);
  vl_test_write_file(path, text);
  free(text);
  assert_int_equal(vl_csv_read_prony(path, &p, &err), VL_EINPUT);
  char where[4300];
  snprintf(where, sizeof where, "%s:%d:", path, VL_PRONY_MAX_TERMS + 2);
  if (!strstr(err.msg, where)) fail_msg("'%s' lacks '%s'", err.msg, where);
}

/* A tabulated power law C = Cs (q/qs)^(-2(1+H)) on [qa, qb] has
 * h_rms^2 = 2 pi \int q C dq = (pi Cs qs^2 / H) [(qa/qs)^(-2H) - (qb/qs)^(-2H)],
 * a closed form independent of the reader and of psd.c; the two-point table
 * represents the power law exactly (log-log interpolation). Tolerance 1e-12:
 * only rounding separates the two. */
static void test_psd_reader(void **state) {
  (void)state;
  const char *dir = vl_test_tmpdir();
  char path[4200];
  snprintf(path, sizeof path, "%s/psd.csv", dir);
  const double H = 0.8, qa = 1e5, qb = 1e8, Cs = 1e-22; /* h_rms 2 um, rms slope 1.5 */
  double Cb = Cs * pow(qb / qa, -2.0 * (1.0 + H));
  char text[256];
  snprintf(text, sizeof text, "q_per_m,C_m4\n1/m,m^4\n%.17g,%.17g\n%.17g,%.17g\n", qa, Cs, qb, Cb);
  vl_test_write_file(path, text);
  vl_psd psd;
  vl_error err;
  assert_int_equal(vl_csv_read_psd(path, &psd, &err), VL_OK);
  assert_int_equal(psd.kind, VL_PSD_TABULATED);
  assert_int_equal(psd.n, 2);
  double h2 = 3.14159265358979323846 * Cs * qa * qa / H * (1.0 - pow(qb / qa, -2.0 * H));
  assert_true(vl_test_rel(psd.hrms_m, sqrt(h2)) < 1e-12);
  vl_psd_free(&psd);

  vl_test_write_file(path, "q_per_m,C_m4\n1e5,1e-20\n");
  assert_int_equal(vl_csv_read_psd(path, &psd, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, ":2:"));
  assert_non_null(strstr(err.msg, "at least 2"));
  vl_test_write_file(path, "q_per_m,C_m4\n1e5,1e-20\n1e5,1e-21\n");
  assert_int_equal(vl_csv_read_psd(path, &psd, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, ":3:"));
  assert_null(psd.q);
}

/* The dialects of csv.h: ';' or tab delimiters with or without decimal
 * commas read the same numbers as commas; the delimiter that fits no line
 * leaves the ragged line named; two that fit are refused; ignored columns
 * are listed and not parsed; every bad row is reported at once. */
static void test_dialects(void **state) {
  (void)state;
  const char *texts[] = {"A,tau_s\n9,0.25\n0.5,1e-3\n", "A;tau_s\n9;0,25\n0,5;1e-3\n",
                         "A\ttau_s\n9\t0,25\n0,5\t1e-3\n", "A;tau_s\n9;0.25\n0.5;1e-3\n",
                         "\"A\";\"tau_s\"\n1;s\n9;0,25\n0,5;0,001\n"};
  for (size_t i = 0; i < sizeof texts / sizeof *texts; i++) {
    vl_csv csv;
    vl_error err;
    if (parse(texts[i], prony_cols, &csv, &err) != VL_OK) fail_msg("%s: %s", texts[i], err.msg);
    assert_int_equal(csv.n_rows, 2);
    assert_true(vl_csv_value(&csv, 0, 1) == 0.25 && vl_csv_value(&csv, 1, 0) == 0.5);
    assert_true(vl_csv_value(&csv, 1, 1) == 1e-3);
    assert_int_equal(csv.decimal_comma, i == 1 || i == 2 || i == 4);
    assert_int_equal(csv.delimiter, i == 0 ? ',' : i == 2 ? '\t' : ';');
    vl_csv_free(&csv);
  }
  expect_bad("A;tau_s\n9;0,25\n1.5;2\n", prony_cols, "in.csv:3:", "'A'", "thousands separator");
  expect_bad("A;tau_s\n9;0,25\n1;2;3\n", prony_cols, "in.csv:3:", "semicolon-separated", "found 3");
  expect_bad("A,tau_s\n9,0,25\n", prony_cols, "in.csv:2:", "found 3", "decimal comma");
  expect_bad("A;x,tau_s\n9;1,0\n", prony_cols, "in.csv:1:", "cannot tell the delimiter", NULL);
  /* every bad row, in file order, in one message */
  expect_bad("A,tau_s\n9,x\n1,2\n-1,2\n3\n", prony_cols, "in.csv:2: column 'tau_s'",
             "\nin.csv:4: column 'A' (field 1): must be >= 0", "\nin.csv:5: expected 2");
  /* a spreadsheet */
  vl_csv csv;
  vl_error err;
  assert_int_equal(vl_csv_read_text("PK\x03\x04", 4, "t.csv", prony_cols, 2, &csv, &err),
                   VL_EINPUT);
  assert_non_null(strstr(err.msg, "export the sheet as CSV"));
  /* ignored columns */
  vl_csv_options o = {.ignore_unknown = 1};
  const char *extra = "note,A,tau_s,T\n-,1,s,C\nfirst,9,0.1,x\n,2,1e-4,\n";
  assert_int_equal(
      vl_csv_read_text_opts(extra, strlen(extra), "e.csv", prony_cols, 2, &o, &csv, &err), VL_OK);
  assert_int_equal(csv.n_rows, 2);
  assert_int_equal(csv.n_ignored, 2);
  assert_string_equal(csv.ignored, "'note', 'T'");
  assert_true(csv.has_units_row && vl_csv_value(&csv, 1, 0) == 2.0);
  vl_csv_free(&csv);
  /* a given delimiter is used as given */
  vl_csv_options semi = {.delimiter = ';', .decimal_comma = 1};
  const char *given = "A;tau_s\n1;0,5\n";
  assert_int_equal(
      vl_csv_read_text_opts(given, strlen(given), "s.csv", prony_cols, 2, &semi, &csv, &err),
      VL_OK);
  assert_true(vl_csv_value(&csv, 0, 1) == 0.5);
  vl_csv_free(&csv);
}

/* Random single-byte mutations of a valid file: the reader must never
 * crash or leak (ASan/UBSan build), and every rejection names the file and
 * a line. A fixed seed keeps the test reproducible. */
static void test_mutations(void **state) {
  (void)state;
  const char base[] = "# comment\nq_per_m,C_m4\n1/m,m^4\n1e5,2e-20\n2e5,3.5e-21\n4e5,1e-22\n";
  const char alphabet[] = "0123456789.,eE+-\n\r #\"aznNiI/^\t";
  unsigned long seed = 12345;
  char buf[sizeof base];
  int accepted = 0;
  for (int trial = 0; trial < 3000; trial++) {
    memcpy(buf, base, sizeof base);
    int edits = 1 + trial % 3;
    size_t len = sizeof base - 1;
    for (int e = 0; e < edits; e++) {
      seed = seed * 6364136223846793005UL + 1442695040888963407UL;
      size_t at = (seed >> 33) % len;
      seed = seed * 6364136223846793005UL + 1442695040888963407UL;
      buf[at] = alphabet[(seed >> 33) % (sizeof alphabet - 1)];
    }
    seed = seed * 6364136223846793005UL + 1442695040888963407UL;
    if ((seed >> 40) % 7 == 0) len = (seed >> 33) % len; /* truncate sometimes */
    vl_csv csv;
    vl_error err = {{0}};
    vl_status st = vl_csv_read_text(buf, len, "m.csv", psd_cols, 2, &csv, &err);
    if (st == VL_OK) {
      accepted++;
      for (size_t r = 0; r < csv.n_rows; r++) {
        assert_true(isfinite(vl_csv_value(&csv, r, 0)) && vl_csv_value(&csv, r, 0) > 0.0);
        assert_true(isfinite(vl_csv_value(&csv, r, 1)) && vl_csv_value(&csv, r, 1) > 0.0);
        if (r) assert_true(vl_csv_value(&csv, r, 0) > vl_csv_value(&csv, r - 1, 0));
      }
    } else {
      assert_int_equal(st, VL_EINPUT);
      if (strncmp(err.msg, "m.csv:", 6) != 0) fail_msg("message '%s' lacks file:line", err.msg);
    }
    vl_csv_free(&csv);
  }
  assert_true(accepted > 0 && accepted < 3000);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_reads_plain_table), cmocka_unit_test(test_reads_tolerated_layout),
      cmocka_unit_test(test_optional_column),   cmocka_unit_test(test_bad_cells),
      cmocka_unit_test(test_sign_and_order),    cmocka_unit_test(test_bad_structure),
      cmocka_unit_test(test_units_row),         cmocka_unit_test(test_parse_double),
      cmocka_unit_test(test_read_file_errors),  cmocka_unit_test(test_prony_reader),
      cmocka_unit_test(test_psd_reader),        cmocka_unit_test(test_dialects),
      cmocka_unit_test(test_mutations),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
