/* Fingerprints of stored materials (vl_db_fingerprint, database.h): a hash
 * of the rows that define a material, so that a run's manifest can say
 * which version of "sbr-unfilled" produced it. */
#include <stdint.h>
#include <string.h>

#include "db_internal.h"

/* 64-bit FNV-1a: enough to tell two versions of a material apart (it is a
 * fingerprint against accidents, not a defence against forgery). */
#define FNV_OFFSET 14695981039346656037ull
#define FNV_PRIME 1099511628211ull

static void mix(uint64_t *h, const void *data, size_t n) {
  const unsigned char *p = data;
  for (size_t i = 0; i < n; i++) {
    *h ^= p[i];
    *h *= FNV_PRIME;
  }
}

/* Every value with its type and length in front, so that ("ab", "c") and
 * ("a", "bc") hash differently. Integers and reals in a fixed byte order. */
static void mix_value(uint64_t *h, sqlite3_stmt *st, int col) {
  int type = sqlite3_column_type(st, col);
  unsigned char tag = (unsigned char)type, bytes[8];
  mix(h, &tag, 1);
  uint64_t v = 0;
  if (type == SQLITE_INTEGER) {
    v = (uint64_t)sqlite3_column_int64(st, col);
  } else if (type == SQLITE_FLOAT) {
    double d = sqlite3_column_double(st, col);
    memcpy(&v, &d, sizeof v);
  } else if (type == SQLITE_TEXT || type == SQLITE_BLOB) {
    const void *p = type == SQLITE_TEXT ? (const void *)sqlite3_column_text(st, col)
                                        : sqlite3_column_blob(st, col);
    size_t n = (size_t)sqlite3_column_bytes(st, col);
    v = n;
    for (int k = 0; k < 8; k++)
      bytes[k] = (unsigned char)(v >> (8 * k));
    mix(h, bytes, 8);
    if (p) mix(h, p, n);
    return;
  }
  for (int k = 0; k < 8; k++)
    bytes[k] = (unsigned char)(v >> (8 * k));
  mix(h, bytes, 8);
}

/* Row ids and creation times differ between two databases holding the
 * same material; they are not part of it. */
static int skipped(const char *column) {
  return !strcmp(column, "id") || !strcmp(column, "created_at") ||
         (strlen(column) > 3 && !strcmp(column + strlen(column) - 3, "_id"));
}

/* Mixes every row of sql (?1 = the material's row id) into *h, each
 * column's name and value. */
static vl_status mix_rows(vl_db *db, const char *sql, sqlite3_int64 id, uint64_t *h,
                          vl_error *err) {
  sqlite3_stmt *st = NULL;
  vl_status s = vl_dbi_prepare(db, sql, &st, err);
  if (s != VL_OK) return s;
  sqlite3_bind_int64(st, 1, id);
  int rc;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    for (int c = 0; c < sqlite3_column_count(st); c++) {
      const char *name = sqlite3_column_name(st, c);
      if (skipped(name)) continue;
      mix(h, name, strlen(name) + 1);
      mix_value(h, st, c);
    }
    mix(h, "\n", 1);
  }
  if (rc != SQLITE_DONE) s = vl_dbi_fail(db, rc, "fingerprinting a material", err);
  sqlite3_finalize(st);
  return s;
}

/* The rows of each kind of material, in a fixed order. The caches of
 * derived tables (Persson, flow factors) are left out: they follow from
 * the rows hashed here. */
static const char *const compound_sql[] = {
    "SELECT * FROM compound WHERE id = ?1",
    "SELECT * FROM compound_prony WHERE compound_id = ?1 ORDER BY idx",
    "SELECT * FROM compound_shift WHERE compound_id = ?1 ORDER BY temperature_c",
    "SELECT * FROM compound_fit WHERE compound_id = ?1",
    "SELECT * FROM compound_measurement WHERE compound_id = ?1 ORDER BY id",
    NULL};
static const char *const surface_sql[] = {
    "SELECT * FROM surface WHERE id = ?1",
    "SELECT * FROM surface_point WHERE surface_id = ?1 ORDER BY idx", NULL};
static const char *const fluid_sql[] = {"SELECT * FROM fluid WHERE id = ?1", NULL};

vl_status vl_db_fingerprint(vl_db *db, const char *table, const char *name,
                            char out[VL_DB_FINGERPRINT_MAX], vl_error *err) {
  out[0] = '\0';
  const char *const *sql = !strcmp(table, "compound")  ? compound_sql
                           : !strcmp(table, "surface") ? surface_sql
                           : !strcmp(table, "fluid")   ? fluid_sql
                                                       : NULL;
  if (!sql) {
    vl_error_set(err, "fingerprint: no kind of material '%s'", table);
    return VL_EINPUT;
  }
  vl_status s = VL_OK;
  sqlite3_int64 id = vl_dbi_find_id(db, table, name, &s, err);
  if (id < 0) return s;
  if (id == 0) return vl_dbi_not_found(db, table, name, err);
  uint64_t h = FNV_OFFSET;
  mix(&h, table, strlen(table) + 1);
  for (size_t k = 0; sql[k] && s == VL_OK; k++)
    s = mix_rows(db, sql[k], id, &h, err);
  if (s == VL_OK) snprintf(out, VL_DB_FINGERPRINT_MAX, "fnv1a64:%016llx", (unsigned long long)h);
  return s;
}

void vl_db_fingerprint_bytes(const void *data, size_t n, char out[VL_DB_FINGERPRINT_MAX]) {
  uint64_t h = FNV_OFFSET;
  mix(&h, data, n);
  snprintf(out, VL_DB_FINGERPRINT_MAX, "fnv1a64:%016llx", (unsigned long long)h);
}
