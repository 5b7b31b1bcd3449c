/* The material database: the persson-emt flow-factor tables of the surfaces
 * (table surface_flow_factors, migration 0005), a cache of
 * vl_emt_table_build kept per surface, film cut-off and table size
 * (db_cache.c gives the rules). */
#include "db_internal.h"

#include "flow_factors_emt.h"

static void *emt_decode(const vl_dbi_cache *c, const void *blob, size_t len) {
  vl_emt_table *t = NULL;
  vl_error ignored;
  if (vl_emt_table_deserialize(c->psd, c->key, blob, len, &t, &ignored) != VL_OK) return NULL;
  if (vl_emt_table_size(t) != (size_t)c->n) { /* a row filed under the wrong size */
    vl_emt_table_free(t);
    return NULL;
  }
  return t;
}

static vl_status emt_encode(const void *t, void **blob, size_t *len, vl_error *err) {
  return vl_emt_table_serialize(t, blob, len, err);
}

vl_status vl_db_flow_table(vl_db *db, const char *name, const vl_psd *psd, double film_cutoff_m,
                           size_t n_points, vl_emt_table **out, bool *from_cache, vl_error *err) {
  *out = NULL;
  if (from_cache) *from_cache = false;
  size_t n = n_points ? n_points : VL_EMT_DEFAULT_N_POINTS;
  /* a request the build refuses: let it say why, without touching the file */
  if (n < VL_EMT_MIN_N_POINTS || n > VL_EMT_MAX_N_POINTS || !(film_cutoff_m > 0.0) ||
      !isfinite(film_cutoff_m))
    return vl_emt_table_build(psd, film_cutoff_m, n_points, out, err);
  vl_status s;
  sqlite3_int64 id = vl_dbi_find_id(db, "surface", name, &s, err);
  if (id < 0) return s;
  if (id == 0) return vl_dbi_not_found(db, "surface", name, err);
  const vl_dbi_cache cache = {
      .what = "store a flow-factor table",
      .select_sql = "SELECT format, data FROM surface_flow_factors WHERE surface_id = ?1 AND "
                    "n_points = ?2 AND film_cutoff_m = ?3",
      .insert_sql = "INSERT OR REPLACE INTO surface_flow_factors (surface_id, n_points, format, "
                    "data, film_cutoff_m) VALUES (?1, ?2, ?3, ?4, ?5)",
      .format = VL_EMT_FORMAT,
      .n = (sqlite3_int64)n,
      .key = film_cutoff_m,
      .psd = psd,
      .decode = emt_decode,
      .encode = emt_encode};
  *out = vl_dbi_cache_load(db, &cache, id);
  if (*out) {
    if (from_cache) *from_cache = true;
    return VL_OK;
  }
  if ((s = vl_emt_table_build(psd, film_cutoff_m, n, out, err)) != VL_OK) return s;
  vl_dbi_cache_store(db, &cache, id, *out);
  return VL_OK;
}
