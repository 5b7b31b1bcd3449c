/* Persson tables cached in the material database (issue 7):
 * vl_persson_serialize / vl_persson_deserialize (roughness.h) and
 * vl_db_persson_table (database.h).
 *
 * The cache must be invisible in the results: every query of a table read
 * back is compared BIT FOR BIT (no tolerance: the table is the same numbers,
 * so any difference at all is a bug) with a table freshly built by
 * vl_persson_build, inside and outside the tabulated range. Then: the
 * second lookup is a cache hit; damaged, stale or foreign blobs are refused
 * and rebuilt; removing or editing a surface drops its tables; a read-only
 * or locked file still gives the right table with no error and no change to
 * the file; and the command line stores and reuses the table. The build and
 * read times are printed (not asserted: the machine is shared). */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <math.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "persson_internal.h"
#include "viscolube/database.h"
#include "viscolube/persson.h"

/* ---- helpers ---------------------------------------------------------- */

static vl_db *open_db(const char *path) {
  vl_db *db = NULL;
  vl_error err;
  if (vl_db_open(path, &db, &err) != VL_OK) fail_msg("vl_db_open(%s): %s", path, err.msg);
  return db;
}

static vl_psd get_psd(vl_db *db, const char *name) {
  vl_psd psd;
  vl_error err;
  if (vl_db_surface_get(db, name, &psd, &err) != VL_OK) fail_msg("surface %s: %s", name, err.msg);
  return psd;
}

/* The cached lookup; fails the test on an error. */
static vl_persson *lookup(vl_db *db, const char *name, const vl_psd *psd, size_t n,
                          bool *from_cache) {
  vl_persson *t = NULL;
  vl_error err;
  vl_status st = vl_db_persson_table(db, name, psd, n, &t, from_cache, &err);
  if (st != VL_OK) fail_msg("vl_db_persson_table(%s, %zu): %s", name, n, err.msg);
  assert_non_null(t);
  return t;
}

static vl_persson *fresh(const vl_psd *psd, size_t n) {
  vl_persson *t = NULL;
  vl_error err;
  if (vl_persson_build(psd, n, &t, &err) != VL_OK) fail_msg("vl_persson_build: %s", err.msg);
  return t;
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* Every query of a against b, bit for bit: s(u) and ds/du at 600 u from
 * -h_rms (the linear wall below the table) to 80 h_rms (the exponential
 * tail above it), u(s) and A/A0, dA/ds at 600 s from 1e-60 to 1e3 and at
 * s <= 0, the scalars, the size, and one exact (quadrature) u(s), which
 * uses the table's private PSD copy. */
static void assert_same_table(const vl_persson *a, const vl_persson *b) {
  assert_int_equal(vl_persson_size(a), vl_persson_size(b));
  assert_true(same_bits(vl_persson_g(a), vl_persson_g(b)));
  assert_true(same_bits(vl_persson_ustar(a), vl_persson_ustar(b)));
  assert_true(same_bits(vl_persson_hrms(a), vl_persson_hrms(b)));
  double h = vl_persson_hrms(b);
  for (int i = 0; i <= 600; i++) {
    double u = h * (-1.0 + 81.0 * i / 600.0), da, db;
    double sa = vl_persson_pressure(a, u, &da), sb = vl_persson_pressure(b, u, &db);
    if (!same_bits(sa, sb) || !same_bits(da, db))
      fail_msg("s(u = %g m): %.17g vs %.17g (ds/du %.17g vs %.17g)", u, sa, sb, da, db);
  }
  for (int i = -2; i <= 600; i++) {
    double s = i < 0 ? (i == -1 ? 0.0 : -1.0) : pow(10.0, -60.0 + 63.0 * i / 600.0);
    double ua = vl_persson_separation(a, s), ub = vl_persson_separation(b, s), ga, gb;
    if (!same_bits(ua, ub)) fail_msg("u(s = %g): %.17g vs %.17g", s, ua, ub);
    double ra = vl_persson_area_ratio(a, s, &ga), rb = vl_persson_area_ratio(b, s, &gb);
    if (!same_bits(ra, rb) || !same_bits(ga, gb)) fail_msg("A/A0(s = %g) differs", s);
  }
  double s_mid = vl_persson_pressure(b, 0.5 * h, NULL);
  assert_true(
      same_bits(vl_persson_separation_exact(a, s_mid), vl_persson_separation_exact(b, s_mid)));
}

/* Number of stored tables of surface `name` (all of them when NULL), read
 * by a separate connection as another program would. */
static int stored_tables(const char *path, const char *name) {
  sqlite3 *h = NULL;
  sqlite3_stmt *st = NULL;
  assert_int_equal(sqlite3_open_v2(path, &h, SQLITE_OPEN_READONLY, NULL), SQLITE_OK);
  const char *sql = name ? "SELECT count(*) FROM surface_persson WHERE surface_id = "
                           "(SELECT id FROM surface WHERE name = ?1)"
                         : "SELECT count(*) FROM surface_persson";
  if (sqlite3_prepare_v2(h, sql, -1, &st, NULL) != SQLITE_OK) fail_msg("%s", sqlite3_errmsg(h));
  if (name) sqlite3_bind_text(st, 1, name, -1, SQLITE_STATIC);
  assert_int_equal(sqlite3_step(st), SQLITE_ROW);
  int n = sqlite3_column_int(st, 0);
  sqlite3_finalize(st);
  sqlite3_close(h);
  return n;
}

/* Replaces the stored blob of (surface, n_table) by data (len bytes). */
static void put_blob(const char *path, const char *name, size_t n_table, const void *data,
                     size_t len) {
  sqlite3 *h = NULL;
  sqlite3_stmt *st = NULL;
  assert_int_equal(sqlite3_open(path, &h), SQLITE_OK);
  assert_int_equal(sqlite3_prepare_v2(h,
                                      "UPDATE surface_persson SET data = ?1 WHERE n_table = ?2 "
                                      "AND surface_id = (SELECT id FROM surface WHERE name = ?3)",
                                      -1, &st, NULL),
                   SQLITE_OK);
  sqlite3_bind_blob64(st, 1, data, len, SQLITE_STATIC);
  sqlite3_bind_int64(st, 2, (sqlite3_int64)n_table);
  sqlite3_bind_text(st, 3, name, -1, SQLITE_STATIC);
  assert_int_equal(sqlite3_step(st), SQLITE_DONE);
  assert_int_equal(sqlite3_changes(h), 1);
  sqlite3_finalize(st);
  sqlite3_close(h);
}

/* The blob's trailing checksum, FNV-1a 64 of all the bytes before it,
 * little-endian (the layout documented in persson.c), recomputed here so a
 * test can forge a blob whose checksum is right and whose content is not:
 * the value checks must catch it on their own. */
static void reseal(unsigned char *b, size_t len) {
  uint64_t h = 0xcbf29ce484222325ULL;
  for (size_t i = 0; i + 8 < len; i++) {
    h ^= b[i];
    h *= 0x100000001b3ULL;
  }
  for (int i = 0; i < 8; i++)
    b[len - 8 + (size_t)i] = (unsigned char)(h >> (8 * i));
}

/* Offsets in the blob (persson.c): 16-byte header, 64-byte PSD
 * fingerprint, 3 scalars, then x[n], y[n], d[n], u[n]. */
#define OFF_FORMAT 4
#define OFF_N 8
#define OFF_X 104
static void put_double(unsigned char *p, double v) {
  uint64_t b;
  memcpy(&b, &v, sizeof b);
  for (int i = 0; i < 8; i++)
    p[i] = (unsigned char)(b >> (8 * i));
}

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A tabulated spectrum with a roll-off: C flat at 1e-22 m^4 below
 * q_r = 1e5 1/m, ~ q^-3.6 above, 40 points from 1e4 to 1e9 1/m
 * (h_rms ~ 2 um). */
static void add_tabulated(vl_db *db, const char *name, double scale) {
  double q[40], C[40];
  for (int k = 0; k < 40; k++) {
    q[k] = 1e4 * pow(10.0, 5.0 * k / 39.0);
    C[k] = scale * 1e-22 * pow(fmax(q[k], 1e5) / 1e5, -3.6);
  }
  vl_psd psd;
  vl_error err;
  assert_int_equal(vl_psd_init_tabulated(&psd, 40, q, C, &err), VL_OK);
  if (vl_db_surface_add(db, name, &psd, "cache test", NULL, &err) != VL_OK)
    fail_msg("add %s: %s", name, err.msg);
  vl_psd_free(&psd);
}

static void add_self_affine(vl_db *db, const char *name, double H, double q0, double q1,
                            double hrms) {
  vl_psd psd;
  vl_error err;
  assert_int_equal(vl_psd_init_self_affine(&psd, H, q0, q1, hrms, &err), VL_OK);
  if (vl_db_surface_add(db, name, &psd, NULL, NULL, &err) != VL_OK)
    fail_msg("add %s: %s", name, err.msg);
  vl_psd_free(&psd);
}

/* ---- (a) + (b): identical results, second lookup from the cache -------- */

static void test_cached_equals_fresh(void **state) {
  (void)state;
  vl_db *db = open_db(vl_test_db);
  add_tabulated(db, "tab", 1.0);
  add_self_affine(db, "sa-h05", 0.5, 1e4, 1e8, 2e-6);
  const char *names[] = {"paper-3um", "tab", "sa-h05"};
  const size_t sizes[] = {0, 64, 700};
  for (int i = 0; i < 3; i++) {
    vl_psd psd = get_psd(db, names[i]);
    for (int j = 0; j < 3; j++) {
      bool hit = true;
      vl_persson *first = lookup(db, names[i], &psd, sizes[j], &hit);
      assert_false(hit); /* nothing stored yet */
      vl_persson *second = lookup(db, names[i], &psd, sizes[j], &hit);
      assert_true(hit);
      vl_persson *ref = fresh(&psd, sizes[j]);
      assert_same_table(first, ref);  /* the built one is a plain build */
      assert_same_table(second, ref); /* the stored one answers the same */
      vl_persson_free(first);
      vl_persson_free(second);
      vl_persson_free(ref);
    }
    /* n_table 0 is the default size: the same stored table */
    bool hit = false;
    vl_persson *t = lookup(db, names[i], &psd, VL_PERSSON_DEFAULT_N_TABLE, &hit);
    assert_true(hit);
    assert_int_equal(vl_persson_size(t), VL_PERSSON_DEFAULT_N_TABLE);
    vl_persson_free(t);
    assert_int_equal(stored_tables(vl_test_db, names[i]), 3);
    vl_psd_free(&psd);
  }
  /* a size the build refuses is refused the same way, and stores nothing */
  vl_psd psd = get_psd(db, "tab");
  vl_persson *t = NULL;
  vl_error err;
  assert_int_equal(vl_db_persson_table(db, "tab", &psd, 10, &t, NULL, &err), VL_EINPUT);
  assert_null(t);
  assert_int_equal(vl_db_persson_table(db, "no-such", &psd, 0, &t, NULL, &err), VL_ENOTFOUND);
  assert_null(t);
  vl_psd_free(&psd);
  vl_db_close(db);
  assert_int_equal(stored_tables(vl_test_db, NULL), 9);
}

/* ---- (c) damaged, stale and foreign blobs ------------------------------ */

/* vl_persson_deserialize must refuse blob (VL_EINPUT, *out NULL). */
static void assert_refused(const vl_psd *psd, const unsigned char *blob, size_t len,
                           const char *what) {
  vl_persson *t = (vl_persson *)(uintptr_t)1;
  vl_error err = {{0}};
  vl_status st = vl_persson_deserialize(psd, blob, len, &t, &err);
  if (st != VL_EINPUT) fail_msg("%s: accepted (status %d)", what, (int)st);
  assert_null(t);
  assert_true(err.msg[0] != '\0');
}

static void test_blob_checks(void **state) {
  (void)state;
  vl_error err;
  vl_psd a, b;
  assert_int_equal(vl_psd_init_self_affine(&a, 0.8, 2e5, 7.8e9, 3e-6, &err), VL_OK);
  /* differs from a in h_rms only (and so in C0): another PSD */
  assert_int_equal(vl_psd_init_self_affine(&b, 0.8, 2e5, 7.8e9, 3.000001e-6, &err), VL_OK);
  vl_persson *t = fresh(&a, 64);
  void *vblob = NULL;
  size_t len = 0;
  assert_int_equal(vl_persson_serialize(t, &vblob, &len, &err), VL_OK);
  unsigned char *blob = vblob, *bad = malloc(len);
  assert_int_equal(len, 104 + 32 * 64 + 8);

  vl_persson *back = NULL;
  assert_int_equal(vl_persson_deserialize(&a, blob, len, &back, &err), VL_OK);
  assert_same_table(back, t);
  vl_persson_free(back);

  assert_refused(&b, blob, len, "another PSD");
  assert_refused(&a, blob, len - 1, "truncated by one byte");
  assert_refused(&a, blob, 50, "truncated to 50 bytes");
  assert_refused(&a, blob, 0, "empty");
  assert_refused(&a, NULL, 0, "NULL");
  /* every single-byte change is caught (by the checksum at least) */
  for (size_t i = 0; i < len; i += 7) {
    memcpy(bad, blob, len);
    bad[i] ^= 0x10;
    assert_refused(&a, bad, len, "a flipped byte");
  }
  /* forged blobs with a right checksum: the value checks alone */
  memcpy(bad, blob, len);
  bad[OFF_FORMAT] = (unsigned char)(VL_PERSSON_FORMAT + 1);
  reseal(bad, len);
  assert_refused(&a, bad, len, "another format");
  memcpy(bad, blob, len);
  bad[OFF_N] = 65; /* announces 65 nodes in a 64-node blob */
  reseal(bad, len);
  assert_refused(&a, bad, len, "a wrong node count");
  memcpy(bad, blob, len);
  put_double(bad + OFF_X + 8 * 10, NAN);
  reseal(bad, len);
  assert_refused(&a, bad, len, "NaN in x");
  memcpy(bad, blob, len);
  put_double(bad + OFF_X + 8 * 64 * 3 + 8 * 20, INFINITY); /* u[20] */
  reseal(bad, len);
  assert_refused(&a, bad, len, "inf in u");
  memcpy(bad, blob, len);
  memcpy(bad + OFF_X + 8 * 64 + 8 * 5, blob + OFF_X + 8 * 64 + 8 * 3, 8); /* y[5] = y[3] */
  reseal(bad, len);
  assert_refused(&a, bad, len, "non-monotone y");
  memcpy(bad, blob, len);
  memcpy(bad + OFF_X + 8 * 30, blob + OFF_X + 8 * 31, 8); /* x[30] = x[31] */
  reseal(bad, len);
  assert_refused(&a, bad, len, "repeated x");
  memcpy(bad, blob, len);
  put_double(bad + OFF_X + 8 * 64 * 2 + 8 * 7, 1.0); /* d[7] > 0: rising ln s */
  reseal(bad, len);
  assert_refused(&a, bad, len, "rising slope");

  free(bad);
  free(blob);
  vl_persson_free(t);
  vl_psd_free(&a);
  vl_psd_free(&b);
}

/* Stored damage is detected by vl_db_persson_table, the table rebuilt
 * (identical to a fresh build) and the row repaired. */
static void test_damaged_rows_rebuilt(void **state) {
  (void)state;
  vl_db *db = open_db(vl_test_db);
  add_tabulated(db, "tab", 1.0);
  vl_psd psd = get_psd(db, "tab"), other = get_psd(db, "paper-1um");
  vl_persson *ref = fresh(&psd, 0), *t;
  bool hit;
  vl_persson_free(lookup(db, "paper-1um", &other, 0, &hit));
  vl_persson_free(lookup(db, "tab", &psd, 0, &hit));
  void *good = NULL, *foreign = NULL;
  size_t len = 0, flen = 0;
  vl_error err;
  assert_int_equal(vl_persson_serialize(ref, &good, &len, &err), VL_OK);
  vl_persson *ot = fresh(&other, 0);
  assert_int_equal(vl_persson_serialize(ot, &foreign, &flen, &err), VL_OK);
  vl_persson_free(ot);
  unsigned char *bad = malloc(len);

  for (int kind = 0; kind < 5; kind++) {
    const char *what = "";
    size_t blen = len;
    memcpy(bad, good, len);
    switch (kind) {
    case 0:
      what = "truncated";
      blen = len / 2;
      put_blob(vl_test_db, "tab", 256, bad, blen);
      break;
    case 1:
      what = "NaN inside";
      put_double(bad + OFF_X + 8 * 100, NAN);
      put_blob(vl_test_db, "tab", 256, bad, len);
      break;
    case 2:
      what = "another format in the blob";
      bad[OFF_FORMAT] = 0;
      reseal(bad, len);
      put_blob(vl_test_db, "tab", 256, bad, len);
      break;
    case 3:
      what = "another format in the row (an older program's table)";
      vl_test_sql(vl_test_db, "UPDATE surface_persson SET format = format + 1");
      break;
    case 4:
      what = "another surface's table";
      put_blob(vl_test_db, "tab", 256, foreign, flen);
      break;
    }
    hit = true;
    t = lookup(db, "tab", &psd, 0, &hit);
    if (hit) fail_msg("%s: used", what);
    assert_same_table(t, ref);
    vl_persson_free(t);
    t = lookup(db, "tab", &psd, 0, &hit); /* repaired */
    if (!hit) fail_msg("%s: not repaired", what);
    assert_same_table(t, ref);
    vl_persson_free(t);
  }
  /* a row under the wrong size is not used for that size */
  vl_test_sql(vl_test_db, "UPDATE surface_persson SET n_table = 300 WHERE n_table = 256 AND "
                          "surface_id = (SELECT id FROM surface WHERE name = 'tab')");
  t = lookup(db, "tab", &psd, 300, &hit);
  assert_false(hit);
  assert_int_equal(vl_persson_size(t), 300);
  vl_persson_free(t);

  free(bad);
  free(good);
  free(foreign);
  vl_persson_free(ref);
  vl_psd_free(&psd);
  vl_psd_free(&other);
  vl_db_close(db);
}

/* ---- (d) removing or editing a surface drops its tables ---------------- */

static void test_remove_and_edit(void **state) {
  (void)state;
  vl_db *db = open_db(vl_test_db);
  vl_error err;
  bool hit;
  add_tabulated(db, "tab", 1.0);
  vl_psd psd = get_psd(db, "tab"), p1 = get_psd(db, "paper-1um");
  vl_persson_free(lookup(db, "tab", &psd, 0, &hit));
  vl_persson_free(lookup(db, "tab", &psd, 64, &hit));
  vl_persson_free(lookup(db, "paper-1um", &p1, 0, &hit));
  assert_int_equal(stored_tables(vl_test_db, "tab"), 2);
  assert_int_equal(vl_db_surface_remove(db, "tab", &err), VL_OK);
  assert_int_equal(stored_tables(vl_test_db, NULL), 1); /* paper-1um's stays */

  /* the same name again, another spectrum: built afresh for it */
  add_tabulated(db, "tab", 4.0);
  vl_psd psd2 = get_psd(db, "tab");
  vl_persson *t = lookup(db, "tab", &psd2, 0, &hit), *ref = fresh(&psd2, 0);
  assert_false(hit);
  assert_same_table(t, ref);
  vl_persson_free(t);
  vl_persson_free(ref);

  /* edited in place by hand (not something the program does): dropped */
  assert_int_equal(stored_tables(vl_test_db, "tab"), 1);
  vl_test_sql(vl_test_db, "UPDATE surface_point SET c_m4 = 2.0 * c_m4 WHERE idx = 3 AND "
                          "surface_id = (SELECT id FROM surface WHERE name = 'tab')");
  assert_int_equal(stored_tables(vl_test_db, "tab"), 0);
  assert_int_equal(stored_tables(vl_test_db, "paper-1um"), 1);
  vl_test_sql(vl_test_db, "UPDATE surface SET hurst = 0.7 WHERE name = 'paper-1um'");
  assert_int_equal(stored_tables(vl_test_db, NULL), 0);
  /* and even a stale row that escaped the triggers is not used: the
   * fingerprint (tested in test_damaged_rows_rebuilt) */
  vl_psd_free(&psd);
  vl_psd_free(&psd2);
  vl_psd_free(&p1);
  vl_db_close(db);
}

/* ---- (e) read-only and locked files ------------------------------------ */

static void test_readonly_and_locked(void **state) {
  (void)state;
  vl_db *db = open_db(vl_test_db);
  bool hit;
  vl_psd psd = get_psd(db, "paper-3um");
  vl_persson_free(lookup(db, "paper-3um", &psd, 0, &hit));
  vl_db_close(db);

  /* locked: another program holds the write lock; the table comes back
   * built, after the short wait, and nothing is stored */
  sqlite3 *h = NULL;
  assert_int_equal(sqlite3_open(vl_test_db, &h), SQLITE_OK);
  assert_int_equal(sqlite3_exec(h, "BEGIN IMMEDIATE", NULL, NULL, NULL), SQLITE_OK);
  db = open_db(vl_test_db);
  double t0 = now_s();
  vl_persson *t = lookup(db, "paper-3um", &psd, 128, &hit), *ref = fresh(&psd, 128);
  double waited = now_s() - t0;
  assert_false(hit);
  assert_same_table(t, ref);
  vl_persson_free(t);
  t = lookup(db, "paper-3um", &psd, 0, &hit); /* reading under the lock works */
  assert_true(hit);
  vl_persson_free(t);
  vl_db_close(db);
  assert_int_equal(sqlite3_exec(h, "ROLLBACK", NULL, NULL, NULL), SQLITE_OK);
  sqlite3_close(h);
  printf("  locked file: table returned unstored after %.3f s\n", waited);
  assert_int_equal(stored_tables(vl_test_db, "paper-3um"), 1);

  /* read-only: the stored table is used, a missing one is built; no error
   * and the file byte for byte as it was */
  assert_int_equal(chmod(vl_test_db, 0444), 0);
  vl_test_snapshot snap = vl_test_take(vl_test_db);
  db = open_db(vl_test_db);
  assert_int_equal(vl_db_readonly(db), 1);
  t = lookup(db, "paper-3um", &psd, 0, &hit);
  assert_true(hit);
  vl_persson_free(t);
  t = lookup(db, "paper-3um", &psd, 128, &hit);
  assert_false(hit);
  assert_same_table(t, ref);
  vl_persson_free(t);
  vl_db_close(db);
  assert_true(vl_test_same_db(vl_test_db, &snap));
  free(snap.bytes);

  /* the command line on the read-only file: runs, changes nothing */
  snap = vl_test_take(vl_test_db);
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err,
                       "friction --compound model-rubber --surface paper-1um --fluid water "
                       "--speed 1e-2");
  if (rc != 0) fail_msg("friction on a read-only database: exit %d: %s", rc, err);
  assert_true(vl_test_same_db(vl_test_db, &snap));
  free(snap.bytes);
  free(out), free(err);
  chmod(vl_test_db, 0644);
  vl_persson_free(ref);
  vl_psd_free(&psd);
}

/* ---- the command line stores the table and reuses it ------------------- */

static void test_cli_reuses(void **state) {
  (void)state;
  const char *cmd = "friction --compound model-rubber --surface paper-1um --fluid water "
                    "--speed 1e-2";
  char *out1 = NULL, *out2 = NULL, *err = NULL;
  if (vl_test_run(&out1, &err, "%s", cmd) != 0) fail_msg("friction: %s", err);
  free(err);
  assert_int_equal(stored_tables(vl_test_db, "paper-1um"), 1);
  assert_int_equal(stored_tables(vl_test_db, NULL), 1);
  vl_test_snapshot snap = vl_test_take(vl_test_db);
  if (vl_test_run(&out2, &err, "%s", cmd) != 0) fail_msg("friction: %s", err);
  free(err);
  assert_string_equal(out1, out2);                 /* the same result from the stored table */
  assert_true(vl_test_same_db(vl_test_db, &snap)); /* and nothing written again */
  free(snap.bytes);
  free(out1), free(out2);
}

/* ---- (f) time: build vs read ------------------------------------------- */

static void test_timing(void **state) {
  (void)state;
  vl_db *db = open_db(vl_test_db);
  vl_psd psd = get_psd(db, "paper-3um");
  const size_t sizes[] = {0, 2048};
  for (int j = 0; j < 2; j++) {
    double t0 = now_s();
    vl_persson *t = fresh(&psd, sizes[j]);
    double build = now_s() - t0;
    vl_persson_free(t);
    bool hit;
    vl_persson_free(lookup(db, "paper-3um", &psd, sizes[j], &hit)); /* store it */
    double best = INFINITY;
    for (int k = 0; k < 10; k++) {
      t0 = now_s();
      t = lookup(db, "paper-3um", &psd, sizes[j], &hit);
      double dt = now_s() - t0;
      assert_true(hit);
      vl_persson_free(t);
      best = fmin(best, dt);
    }
    printf("  paper-3um, %zu nodes: build %.2f ms, read from the database %.3f ms\n",
           sizes[j] ? sizes[j] : (size_t)VL_PERSSON_DEFAULT_N_TABLE, 1e3 * build, 1e3 * best);
  }
  vl_psd_free(&psd);
  vl_db_close(db);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_cached_equals_fresh, vl_test_setup_db),
      cmocka_unit_test(test_blob_checks),
      cmocka_unit_test_setup(test_damaged_rows_rebuilt, vl_test_setup_db),
      cmocka_unit_test_setup(test_remove_and_edit, vl_test_setup_db),
      cmocka_unit_test_setup(test_readonly_and_locked, vl_test_setup_db),
      cmocka_unit_test_setup(test_cli_reuses, vl_test_setup_db),
      cmocka_unit_test_setup(test_timing, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
