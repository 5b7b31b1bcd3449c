/* The material database: caches of tables derived from a surface's spectrum
 * (the Persson table, the persson-emt flow factors), one row per surface and
 * key, stored as a checked blob. The rules are the same for every cache:
 *   - a row is used only if it decodes and passes its own checks (format,
 *     fingerprint of the PSD, checksum, values); anything else is a miss;
 *   - a miss builds the table, which is then stored in its own transaction,
 *     best effort: read-only, locked or full files are left as they were. */
#include "db_internal.h"

#include <stdlib.h>

void *vl_dbi_cache_load(vl_db *db, const vl_dbi_cache *c, sqlite3_int64 id) {
  sqlite3_stmt *st = NULL;
  void *obj = NULL;
  if (sqlite3_prepare_v2(db->h, c->select_sql, -1, &st, NULL) != SQLITE_OK) {
    sqlite3_finalize(st);
    return NULL;
  }
  sqlite3_bind_int64(st, 1, id);
  sqlite3_bind_int64(st, 2, c->n);
  if (sqlite3_bind_parameter_count(st) >= 3) sqlite3_bind_double(st, 3, c->key);
  if (sqlite3_step(st) == SQLITE_ROW && sqlite3_column_int64(st, 0) == c->format &&
      sqlite3_column_type(st, 1) == SQLITE_BLOB) {
    const void *data = sqlite3_column_blob(st, 1);
    int len = sqlite3_column_bytes(st, 1);
    if (data && len > 0) obj = c->decode(c, data, (size_t)len);
  }
  sqlite3_finalize(st);
  return obj;
}

void vl_dbi_cache_store(vl_db *db, const vl_dbi_cache *c, sqlite3_int64 id, const void *obj) {
  void *blob = NULL;
  size_t len = 0;
  vl_error ignored;
  sqlite3_stmt *st = NULL;
  if (db->readonly || c->encode(obj, &blob, &len, &ignored) != VL_OK) return;
  sqlite3_busy_timeout(db->h, CACHE_BUSY_TIMEOUT_MS);
  if (vl_dbi_tx_begin(db, c->what, &ignored) != VL_OK) goto cleanup;
  if (sqlite3_prepare_v2(db->h, c->insert_sql, -1, &st, NULL) != SQLITE_OK) goto cleanup;
  sqlite3_bind_int64(st, 1, id);
  sqlite3_bind_int64(st, 2, c->n);
  sqlite3_bind_int(st, 3, c->format);
  if (sqlite3_bind_parameter_count(st) >= 5) sqlite3_bind_double(st, 5, c->key);
  if (sqlite3_bind_blob64(st, 4, blob, (sqlite3_uint64)len, SQLITE_STATIC) != SQLITE_OK ||
      sqlite3_step(st) != SQLITE_DONE)
    goto cleanup;
  sqlite3_finalize(st);
  st = NULL;
  vl_dbi_tx_commit(db, c->what, &ignored); /* rolls back itself on failure */

cleanup:
  sqlite3_finalize(st);
  vl_dbi_tx_rollback(db);
  sqlite3_busy_timeout(db->h, BUSY_TIMEOUT_MS);
  free(blob);
}
