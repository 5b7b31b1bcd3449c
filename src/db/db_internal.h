/* The material database's private parts, shared by the files of src/db/:
 *
 *   db_sql.c       SQLite errors as statuses, statements, transactions
 *   db_open.c      opening, the default path, closing
 *   db_seed.c      the schema: a new file created and seeded from the
 *                  embedded materials, an older one migrated
 *   db_names.c     name checks, look-up by name with "did you mean",
 *                  removal by name, listing a whole table
 *   db_compound.c  compounds: Prony terms, measured data, fit report
 *   db_surface.c   surfaces: the PSD and its derived columns
 *   db_persson.c   the cache of Persson tables of the surfaces
 *   db_fluid.c     fluids and their viscosity laws
 *   db_pair.c      pairs: a compound, surface and fluid with their sigma_s law
 *
 * The public contract is include/viscolube/database.h. Every function here
 * that returns a vl_status sets err on failure, as the public ones do.
 * Private to src/db/. */
#ifndef VL_DB_INTERNAL_H
#define VL_DB_INTERNAL_H

#include "viscolube/database.h"

#include <math.h>
#include <sqlite3.h>
#include <stdio.h>

/* The .sql and .csv files of materials/, embedded by
 * scripts/embed_materials.cmake, sorted by name and terminated by
 * {NULL, NULL}. */
struct vl_embedded_file {
  const char *name;
  const char *text;
};
extern const struct vl_embedded_file vl_embedded_materials[];

/* How long a call waits for another program's lock before failing, and
 * how long storing a cached Persson table waits before giving up (the
 * table is returned anyway: not worth a long stall). */
#define BUSY_TIMEOUT_MS 5000
#define CACHE_BUSY_TIMEOUT_MS 250

struct vl_db {
  sqlite3 *h;
  char *path;
  int readonly;
};

/* ---- column reading and parameter binding ----------------------------- */

static inline void copy_text(char *dst, size_t size, const unsigned char *src) {
  snprintf(dst, size, "%s", src ? (const char *)src : "");
}

static inline double column_real(sqlite3_stmt *st, int col) {
  return sqlite3_column_type(st, col) == SQLITE_NULL ? NAN : sqlite3_column_double(st, col);
}

/* Binds a double, storing NAN as NULL (SQLite would do so anyway, but
 * explicitly keeps the intent visible). */
static inline int bind_real(sqlite3_stmt *st, int idx, double v) {
  return isnan(v) ? sqlite3_bind_null(st, idx) : sqlite3_bind_double(st, idx, v);
}

static inline int bind_text_or_null(sqlite3_stmt *st, int idx, const char *s) {
  return (s && *s) ? sqlite3_bind_text(st, idx, s, -1, SQLITE_TRANSIENT)
                   : sqlite3_bind_null(st, idx);
}

/* ---- errors, statements, transactions (db_sql.c) ---------------------- */

/* Maps the SQLite failure rc, met while `doing` (a phrase: "reading a
 * surface"), to a status and one sentence naming the file. db may be
 * NULL or not yet open. */
vl_status vl_dbi_fail(const vl_db *db, int rc, const char *doing, vl_error *err);

/* sqlite3_prepare_v2 of sql into *st (NULL on failure). */
vl_status vl_dbi_prepare(vl_db *db, const char *sql, sqlite3_stmt **st, vl_error *err);

/* sqlite3_exec of sql, which returns no rows; failures as vl_dbi_fail. */
vl_status vl_dbi_exec(vl_db *db, const char *sql, const char *doing, vl_error *err);

/* Every write is one BEGIN IMMEDIATE ... COMMIT: begin fails at once on a
 * read-only file; commit rolls back itself when it fails; rollback does
 * nothing outside a transaction, so a cleanup: path may always call it. */
vl_status vl_dbi_tx_begin(vl_db *db, const char *doing, vl_error *err);
void vl_dbi_tx_rollback(vl_db *db);
vl_status vl_dbi_tx_commit(vl_db *db, const char *doing, vl_error *err);

/* ---- rows by name (db_names.c) ----------------------------------------- */

/* VL_EINPUT if s (may be NULL) has VL_DB_TEXT_MAX characters or more; what
 * names it in the message ("description"). */
vl_status vl_dbi_check_text(const char *what, const char *s, vl_error *err);

/* Always VL_ENOTFOUND, with a message naming `name` and the closest names
 * of table (did you mean ...?). */
vl_status vl_dbi_not_found(vl_db *db, const char *table, const char *name, vl_error *err);

/* Row id of `name` in table: 0 when absent, -1 on error (*s and err set;
 * *s is VL_OK otherwise). */
sqlite3_int64 vl_dbi_find_id(vl_db *db, const char *table, const char *name, vl_status *s,
                             vl_error *err);

/* Inside a transaction: VL_EEXIST if `name` is taken in table. */
vl_status vl_dbi_check_free(vl_db *db, const char *table, const char *name, vl_error *err);

/* Deletes the row `name` of table in its own transaction (children go by
 * ON DELETE CASCADE); VL_ENOTFOUND if there is none. */
vl_status vl_dbi_remove_named(vl_db *db, const char *table, const char *name, vl_error *err);

/* Every row of table, sorted by name, read by by_id into a calloc'd array
 * of *n items of item_size bytes (*items, caller frees; NULL and *n = 0
 * when the table is empty or on any failure). plural names the rows in the
 * out-of-memory message. */
vl_status vl_dbi_list_all(vl_db *db, const char *table, const char *plural, size_t item_size,
                          vl_status (*by_id)(vl_db *, sqlite3_int64, void *, vl_error *),
                          void **items, size_t *n, vl_error *err);

/* ---- the schema (db_seed.c) ------------------------------------------- */

/* Brings the open file to the latest schema (vl_db_schema_version): a new,
 * empty file gets every migration and seed in one transaction, an older
 * one each missing migration in its own. A newer, foreign or corrupt file,
 * or an older read-only one, is refused (VL_EDB) before anything is
 * written. */
vl_status vl_dbi_migrate(vl_db *db, vl_error *err);

/* ---- steps of a migration or seed, inside its transaction -------------- */

/* Fills the derived columns of every surface that lacks them (db_surface.c). */
vl_status vl_dbi_surface_fill_derived(vl_db *db, vl_error *err);

/* Inserts the compound of meta (name, class, description, source file)
 * with the Prony series, shifts, points and fit report of the imported m,
 * checked as vl_db_compound_add checks (db_compound.c). */
vl_status vl_dbi_measured_insert(vl_db *db, const vl_db_compound *meta, const vl_measured *m,
                                 const char *doing, vl_error *err);

/* A cache of a table derived from a surface's spectrum (db_cache.c). The
 * SQL binds ?1 the surface id, ?2 the size n, and the optional real key
 * (?3 in select_sql, ?5 in insert_sql; insert binds ?3 format, ?4 data).
 * select_sql returns (format, data). decode returns the table or NULL when
 * the blob fails any check; encode serialises a table. */
typedef struct vl_dbi_cache vl_dbi_cache;
struct vl_dbi_cache {
  const char *what; /* "store a Persson table": for transaction messages */
  const char *select_sql, *insert_sql;
  int format;
  sqlite3_int64 n;
  double key;
  const vl_psd *psd; /* the spectrum the table must have been built from */
  void *(*decode)(const vl_dbi_cache *c, const void *blob, size_t len);
  vl_status (*encode)(const void *table, void **blob, size_t *len, vl_error *err);
};
/* The stored table of surface row id, or NULL (any failure is a miss). */
void *vl_dbi_cache_load(vl_db *db, const vl_dbi_cache *c, sqlite3_int64 id);
/* Stores table under surface row id in its own transaction, replacing any
 * row there; best effort (nothing changes on failure). */
void vl_dbi_cache_store(vl_db *db, const vl_dbi_cache *c, sqlite3_int64 id, const void *table);

#endif
