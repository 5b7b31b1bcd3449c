/* The material database: the Persson tables of the surfaces (table
 * surface_persson), a cache of vl_persson_build kept per surface and table
 * size. */
#include "db_internal.h"

#include <stdlib.h>

/* The stored table of surface row id with n nodes, if there is one that
 * passes every check of vl_persson_deserialize (NULL otherwise). Any
 * failure (no row, another format, a bad blob, even an SQLite error) is a
 * miss: the caller builds the table instead. */
static vl_persson *persson_load(vl_db *db, sqlite3_int64 id, size_t n, const vl_psd *psd) {
  sqlite3_stmt *st = NULL;
  vl_persson *t = NULL;
  if (sqlite3_prepare_v2(db->h,
                         "SELECT format, data FROM surface_persson "
                         "WHERE surface_id = ?1 AND n_table = ?2",
                         -1, &st, NULL) != SQLITE_OK) {
    sqlite3_finalize(st);
    return NULL;
  }
  sqlite3_bind_int64(st, 1, id);
  sqlite3_bind_int64(st, 2, (sqlite3_int64)n);
  if (sqlite3_step(st) == SQLITE_ROW && sqlite3_column_int64(st, 0) == VL_PERSSON_FORMAT &&
      sqlite3_column_type(st, 1) == SQLITE_BLOB) {
    const void *data = sqlite3_column_blob(st, 1);
    int len = sqlite3_column_bytes(st, 1);
    vl_error ignored;
    if (data && len > 0 && vl_persson_deserialize(psd, data, (size_t)len, &t, &ignored) != VL_OK)
      t = NULL;
    if (t && vl_persson_size(t) != n) { /* a row filed under the wrong size */
      vl_persson_free(t);
      t = NULL;
    }
  }
  sqlite3_finalize(st);
  return t;
}

/* Stores table t of surface row id under n nodes in its own transaction,
 * replacing any row there. Best effort: on any failure (read-only, locked,
 * the surface removed meanwhile, full disk) the transaction is rolled back
 * and nothing changes. */
static void persson_store(vl_db *db, sqlite3_int64 id, size_t n, const vl_persson *t) {
  void *blob = NULL;
  size_t len = 0;
  vl_error ignored;
  sqlite3_stmt *st = NULL;
  if (db->readonly || vl_persson_serialize(t, &blob, &len, &ignored) != VL_OK) return;
  sqlite3_busy_timeout(db->h, CACHE_BUSY_TIMEOUT_MS);
  if (vl_dbi_tx_begin(db, "store a Persson table", &ignored) != VL_OK) goto cleanup;
  if (sqlite3_prepare_v2(db->h,
                         "INSERT OR REPLACE INTO surface_persson (surface_id, n_table, format, "
                         "data) VALUES (?1, ?2, ?3, ?4)",
                         -1, &st, NULL) != SQLITE_OK)
    goto cleanup;
  sqlite3_bind_int64(st, 1, id);
  sqlite3_bind_int64(st, 2, (sqlite3_int64)n);
  sqlite3_bind_int(st, 3, VL_PERSSON_FORMAT);
  if (sqlite3_bind_blob64(st, 4, blob, (sqlite3_uint64)len, SQLITE_STATIC) != SQLITE_OK ||
      sqlite3_step(st) != SQLITE_DONE)
    goto cleanup;
  sqlite3_finalize(st);
  st = NULL;
  vl_dbi_tx_commit(db, "store a Persson table", &ignored); /* rolls back itself on failure */

cleanup:
  sqlite3_finalize(st);
  vl_dbi_tx_rollback(db);
  sqlite3_busy_timeout(db->h, BUSY_TIMEOUT_MS);
  free(blob);
}

vl_status vl_db_persson_table(vl_db *db, const char *name, const vl_psd *psd, size_t n_table,
                              vl_persson **out, bool *from_cache, vl_error *err) {
  *out = NULL;
  if (from_cache) *from_cache = false;
  size_t n = n_table ? n_table : VL_PERSSON_DEFAULT_N_TABLE;
  /* a size the build refuses: let it say why, without touching the file */
  if (n < VL_PERSSON_MIN_N_TABLE || n > VL_PERSSON_MAX_N_TABLE)
    return vl_persson_build(psd, n_table, out, err);
  vl_status s;
  sqlite3_int64 id = vl_dbi_find_id(db, "surface", name, &s, err);
  if (id < 0) return s;
  if (id == 0) return vl_dbi_not_found(db, "surface", name, err);
  *out = persson_load(db, id, n, psd);
  if (*out) {
    if (from_cache) *from_cache = true;
    return VL_OK;
  }
  if ((s = vl_persson_build(psd, n, out, err)) != VL_OK) return s;
  persson_store(db, id, n, *out);
  return VL_OK;
}
