/* persson-emt flow-factor tables cached in the material database (issue 16):
 * vl_db_flow_table (database.h) over db_cache.c, the same rules as the
 * Persson cache (tests/test_persson_cache.c):
 *   - a table read back answers every query BIT FOR BIT like a fresh
 *     vl_emt_table_build (no tolerance: the same numbers), and the second
 *     lookup is a hit;
 *   - a damaged, stale or foreign row is not used and is rebuilt;
 *   - a row of another film cut-off is not used for this one;
 *   - removing or editing a surface drops its tables;
 *   - a read-only file gives the right table, no error, no change. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <math.h>
#include <sqlite3.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "flow_factors_emt.h"
#include "viscolube/database.h"
#include "viscolube/flow_factors.h"

#define CUT 1e-9

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

static vl_emt_table *lookup(vl_db *db, const char *name, const vl_psd *psd, double cut, bool *hit) {
  vl_emt_table *t = NULL;
  vl_error err;
  if (vl_db_flow_table(db, name, psd, cut, 0, &t, hit, &err) != VL_OK)
    fail_msg("vl_db_flow_table(%s): %s", name, err.msg);
  assert_non_null(t);
  return t;
}

static vl_emt_table *fresh(const vl_psd *psd, double cut) {
  vl_emt_table *t = NULL;
  vl_error err;
  if (vl_emt_table_build(psd, cut, 0, &t, &err) != VL_OK) fail_msg("build: %s", err.msg);
  return t;
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* Every factor and derivative at 400 separations over 1e-6 ... 1e3 h_rms
 * (below, inside and above the table) and every node, bit for bit. */
static void assert_same_table(const vl_emt_table *a, const vl_emt_table *b) {
  assert_int_equal(vl_emt_table_size(a), vl_emt_table_size(b));
  assert_true(same_bits(vl_emt_table_hrms(a), vl_emt_table_hrms(b)));
  double h = vl_emt_table_hrms(a);
  for (int i = 0; i < 400; i++) {
    double u = h * pow(10.0, -6.0 + 9.0 * i / 399.0);
    vl_flow_factor_values va, da, vb, db;
    vl_emt_table_eval(a, u, &va, &da);
    vl_emt_table_eval(b, u, &vb, &db);
    assert_memory_equal(&va, &vb, sizeof va);
    assert_memory_equal(&da, &db, sizeof da);
  }
}

/* Rows of surface `name` (all when NULL), read by another connection. */
static int stored(const char *path, const char *name) {
  sqlite3 *h = NULL;
  sqlite3_stmt *st = NULL;
  assert_int_equal(sqlite3_open_v2(path, &h, SQLITE_OPEN_READONLY, NULL), SQLITE_OK);
  const char *sql = name ? "SELECT count(*) FROM surface_flow_factors WHERE surface_id = "
                           "(SELECT id FROM surface WHERE name = ?1)"
                         : "SELECT count(*) FROM surface_flow_factors";
  if (sqlite3_prepare_v2(h, sql, -1, &st, NULL) != SQLITE_OK) fail_msg("%s", sqlite3_errmsg(h));
  if (name) sqlite3_bind_text(st, 1, name, -1, SQLITE_STATIC);
  assert_int_equal(sqlite3_step(st), SQLITE_ROW);
  int n = sqlite3_column_int(st, 0);
  sqlite3_finalize(st);
  sqlite3_close(h);
  return n;
}

static void test_cached_equals_fresh(void **state) {
  (void)state;
  vl_db *db = open_db(vl_test_db);
  vl_psd psd = get_psd(db, "paper-0.5um");
  bool hit = true;
  vl_emt_table *ref = fresh(&psd, CUT), *t = lookup(db, "paper-0.5um", &psd, CUT, &hit);
  assert_false(hit); /* built and stored */
  assert_same_table(t, ref);
  vl_emt_table_free(t);
  assert_int_equal(stored(vl_test_db, "paper-0.5um"), 1);
  t = lookup(db, "paper-0.5um", &psd, CUT, &hit);
  assert_true(hit);
  assert_same_table(t, ref);
  vl_emt_table_free(t);
  /* another cut-off is another table (phi_f and phi_fs depend on it) */
  t = lookup(db, "paper-0.5um", &psd, 3e-9, &hit);
  assert_false(hit);
  assert_true(vl_emt_table_film_cutoff(t) == 3e-9);
  vl_emt_table_free(t);
  assert_int_equal(stored(vl_test_db, "paper-0.5um"), 2);
  vl_emt_table_free(ref);
  vl_psd_free(&psd);
  vl_db_close(db);
}

/* Damaged, stale and foreign rows are refused and rebuilt. */
static void test_damaged_rows_rebuilt(void **state) {
  (void)state;
  vl_db *db = open_db(vl_test_db);
  vl_psd psd = get_psd(db, "paper-1um"), other = get_psd(db, "paper-3um");
  vl_emt_table *ref = fresh(&psd, CUT);
  bool hit;
  vl_emt_table_free(lookup(db, "paper-1um", &psd, CUT, &hit));
  vl_emt_table_free(lookup(db, "paper-3um", &other, CUT, &hit));
  const char *damage[] = {
      /* truncated */
      "UPDATE surface_flow_factors SET data = substr(data, 1, length(data) / 2) WHERE "
      "surface_id = (SELECT id FROM surface WHERE name = 'paper-1um')",
      /* one byte changed (the checksum catches it) */
      "UPDATE surface_flow_factors SET data = substr(data, 1, 100) || x'ff' || "
      "substr(data, 102) WHERE surface_id = (SELECT id FROM surface WHERE name = 'paper-1um')",
      /* an older program's format */
      "UPDATE surface_flow_factors SET format = format + 1",
      /* another surface's table under this surface */
      "UPDATE surface_flow_factors SET data = (SELECT data FROM surface_flow_factors WHERE "
      "surface_id = (SELECT id FROM surface WHERE name = 'paper-3um')) WHERE surface_id = "
      "(SELECT id FROM surface WHERE name = 'paper-1um')",
  };
  for (size_t k = 0; k < sizeof damage / sizeof *damage; k++) {
    vl_test_sql(vl_test_db, damage[k]);
    hit = true;
    vl_emt_table *t = lookup(db, "paper-1um", &psd, CUT, &hit);
    if (hit) fail_msg("damage %zu: the row was used", k);
    assert_same_table(t, ref);
    vl_emt_table_free(t);
    t = lookup(db, "paper-1um", &psd, CUT, &hit); /* repaired */
    if (!hit) fail_msg("damage %zu: not repaired", k);
    assert_same_table(t, ref);
    vl_emt_table_free(t);
    vl_emt_table_free(lookup(db, "paper-3um", &other, CUT, &hit));
  }
  vl_emt_table_free(ref);
  vl_psd_free(&psd);
  vl_psd_free(&other);
  vl_db_close(db);
}

/* Removing a surface drops its tables (the foreign key's cascade); editing
 * its spectrum by hand drops them too (the triggers). */
static void test_remove_and_edit(void **state) {
  (void)state;
  vl_db *db = open_db(vl_test_db);
  vl_error err;
  bool hit;
  const double q[] = {1e4, 1e5, 1e6, 1e7}, c[] = {1e-20, 1e-23, 1e-26, 1e-29};
  vl_psd tab;
  assert_int_equal(vl_psd_init_tabulated(&tab, 4, q, c, &err), VL_OK);
  assert_int_equal(vl_db_surface_add(db, "tab", &tab, "test", NULL, &err), VL_OK);
  vl_psd p1 = get_psd(db, "paper-1um");
  vl_emt_table_free(lookup(db, "tab", &tab, CUT, &hit));
  vl_emt_table_free(lookup(db, "paper-1um", &p1, CUT, &hit));
  assert_int_equal(stored(vl_test_db, NULL), 2);
  assert_int_equal(vl_db_surface_remove(db, "tab", &err), VL_OK);
  assert_int_equal(stored(vl_test_db, NULL), 1);
  vl_test_sql(vl_test_db, "UPDATE surface SET hurst = 0.7 WHERE name = 'paper-1um'");
  assert_int_equal(stored(vl_test_db, NULL), 0);
  vl_psd_free(&tab);
  vl_psd_free(&p1);
  vl_db_close(db);
}

/* A read-only file: the stored table is used, a missing one built; no error
 * and the file byte for byte as it was. */
static void test_readonly(void **state) {
  (void)state;
  vl_db *db = open_db(vl_test_db);
  vl_psd psd = get_psd(db, "paper-0.5um");
  bool hit;
  vl_emt_table_free(lookup(db, "paper-0.5um", &psd, CUT, &hit));
  vl_db_close(db);
  assert_int_equal(chmod(vl_test_db, 0444), 0);
  vl_test_snapshot snap = vl_test_take(vl_test_db);
  db = open_db(vl_test_db);
  vl_emt_table *t = lookup(db, "paper-0.5um", &psd, CUT, &hit), *ref = fresh(&psd, 2e-9);
  assert_true(hit);
  vl_emt_table_free(t);
  t = lookup(db, "paper-0.5um", &psd, 2e-9, &hit);
  assert_false(hit);
  assert_same_table(t, ref);
  vl_emt_table_free(t);
  vl_emt_table_free(ref);
  vl_db_close(db);
  assert_true(vl_test_same_db(vl_test_db, &snap));
  free(snap.bytes);
  chmod(vl_test_db, 0644);
  vl_psd_free(&psd);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_cached_equals_fresh, vl_test_setup_db),
      cmocka_unit_test_setup(test_damaged_rows_rebuilt, vl_test_setup_db),
      cmocka_unit_test_setup(test_remove_and_edit, vl_test_setup_db),
      cmocka_unit_test_setup(test_readonly, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
