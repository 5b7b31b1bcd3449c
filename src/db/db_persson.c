/* The material database: the Persson tables of the surfaces (table
 * surface_persson), a cache of vl_persson_build kept per surface and table
 * size (db_cache.c gives the rules). */
#include "db_internal.h"
#include "persson_internal.h"

#include <stdlib.h>

/* A stored blob as a table of this PSD and size, or NULL. */
static void *persson_decode(const vl_dbi_cache *c, const void *blob, size_t len) {
  vl_persson *t = NULL;
  vl_error ignored;
  if (vl_persson_deserialize(c->psd, blob, len, &t, &ignored) != VL_OK) return NULL;
  if (vl_persson_size(t) != (size_t)c->n) { /* a row filed under the wrong size */
    vl_persson_free(t);
    return NULL;
  }
  return t;
}

static vl_status persson_encode(const void *t, void **blob, size_t *len, vl_error *err) {
  return vl_persson_serialize(t, blob, len, err);
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
  const vl_dbi_cache cache = {
      .what = "store a Persson table",
      .select_sql = "SELECT format, data FROM surface_persson WHERE surface_id = ?1 AND "
                    "n_table = ?2",
      .insert_sql = "INSERT OR REPLACE INTO surface_persson (surface_id, n_table, format, data) "
                    "VALUES (?1, ?2, ?3, ?4)",
      .format = VL_PERSSON_FORMAT,
      .n = (sqlite3_int64)n,
      .psd = psd,
      .decode = persson_decode,
      .encode = persson_encode};
  *out = vl_dbi_cache_load(db, &cache, id);
  if (*out) {
    if (from_cache) *from_cache = true;
    return VL_OK;
  }
  if ((s = vl_persson_build(psd, n, out, err)) != VL_OK) return s;
  vl_dbi_cache_store(db, &cache, id, *out);
  return VL_OK;
}
