/* The material database: names. What a valid name is
 * (vl_db_check_name), looking a row up by name, the "did you mean" of a
 * name not found, removing a row by name, and listing a whole table: the
 * operations every table (compound, surface, fluid) does alike. */
#include "db_internal.h"

#include "viscolube/edit_distance.h"

#include <stdlib.h>
#include <string.h>

vl_status vl_db_check_name(const char *name, vl_error *err) {
  if (!name || !*name) {
    vl_error_set(err, "a material name must not be empty");
    return VL_EINPUT;
  }
  size_t n = strlen(name);
  if (n >= VL_DB_NAME_MAX) {
    vl_error_set(err, "name '%.40s...' is longer than %d characters", name, VL_DB_NAME_MAX - 1);
    return VL_EINPUT;
  }
  /* material names become folder names (compare's DIR/<compound>/, a
   * multi-fluid run's DIR/<fluid>/): "." and ".." would be the folder
   * itself or its parent */
  if (!strcmp(name, ".") || !strcmp(name, "..")) {
    vl_error_set(err,
                 "name '%s' is refused: it names a folder ('.' or '..'), and material names "
                 "become folder names",
                 name);
    return VL_EINPUT;
  }
  if (name[0] == '-') {
    vl_error_set(err, "name '%s' must not start with '-' (it would read as an option)", name);
    return VL_EINPUT;
  }
  for (size_t i = 0; i < n; i++) {
    char c = name[i];
    int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
             c == '.' || c == '_' || c == '+' || c == '-';
    if (!ok && (c == '/' || c == '\\')) {
      vl_error_set(err,
                   "name '%s': character %zu is a path separator ('%c'); material names "
                   "become folder names and must not contain '/' or '\\'",
                   name, i + 1, c);
      return VL_EINPUT;
    }
    if (!ok) {
      vl_error_set(err, "name '%s': character %zu is not one of A-Z a-z 0-9 . _ + -", name, i + 1);
      return VL_EINPUT;
    }
  }
  return VL_OK;
}

vl_status vl_dbi_check_text(const char *what, const char *s, vl_error *err) {
  if (s && strlen(s) >= VL_DB_TEXT_MAX) {
    vl_error_set(err, "%s is longer than %d characters", what, VL_DB_TEXT_MAX - 1);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* VL_ENOTFOUND with a message naming `name` and the closest names of the
 * same kind (up to three ties): a small edit distance, or one name
 * containing the other, counts as close. */
vl_status vl_dbi_not_found(vl_db *db, const char *table, const char *name, vl_error *err) {
  char sql[128], hint[VL_ERROR_MAX / 2] = "";
  char best[3][VL_DB_NAME_MAX];
  size_t n_best = 0, best_score = (size_t)-1;
  size_t limit = strlen(name) / 3 > 2 ? strlen(name) / 3 : 2;
  snprintf(sql, sizeof sql, "SELECT name FROM %s ORDER BY name", table);
  sqlite3_stmt *st = NULL;
  if (sqlite3_prepare_v2(db->h, sql, -1, &st, NULL) == SQLITE_OK) {
    while (sqlite3_step(st) == SQLITE_ROW) {
      const char *cand = (const char *)sqlite3_column_text(st, 0);
      if (!cand) continue;
      size_t score = vl_edit_distance(name, strlen(name), cand, strlen(cand), false);
      if (score > limit && strlen(name) >= 3 && (strstr(cand, name) || strstr(name, cand)))
        score = limit;
      if (score > limit || score > best_score) continue;
      if (score < best_score) best_score = score, n_best = 0;
      if (n_best < 3) snprintf(best[n_best++], VL_DB_NAME_MAX, "%s", cand);
    }
  }
  sqlite3_finalize(st);
  for (size_t i = 0, len = 0; i < n_best; i++) {
    int w = snprintf(hint + len, sizeof hint - len, "%s'%s'", i ? " or " : "", best[i]);
    if (w < 0 || (size_t)w >= sizeof hint - len) break;
    len += (size_t)w;
  }
  if (hint[0])
    vl_error_set(err, "no %s named '%s' in %s (did you mean %s?)", table, name, db->path, hint);
  else
    vl_error_set(err, "no %s named '%s' in %s", table, name, db->path);
  return VL_ENOTFOUND;
}

/* Row id of `name` in table (0 when absent, -1 on error with err set). */
sqlite3_int64 vl_dbi_find_id(vl_db *db, const char *table, const char *name, vl_status *s,
                             vl_error *err) {
  char sql[128];
  snprintf(sql, sizeof sql, "SELECT id FROM %s WHERE name = ?1", table);
  sqlite3_stmt *st = NULL;
  *s = vl_dbi_prepare(db, sql, &st, err);
  if (*s != VL_OK) return -1;
  sqlite3_bind_text(st, 1, name, -1, SQLITE_TRANSIENT);
  sqlite3_int64 id = 0;
  int rc = sqlite3_step(st);
  if (rc == SQLITE_ROW)
    id = sqlite3_column_int64(st, 0);
  else if (rc != SQLITE_DONE) {
    *s = vl_dbi_fail(db, rc, "looking up a name", err);
    id = -1;
  }
  sqlite3_finalize(st);
  return id;
}

/* Inside a transaction: VL_EEXIST if `name` is taken in table. */
vl_status vl_dbi_check_free(vl_db *db, const char *table, const char *name, vl_error *err) {
  vl_status s;
  sqlite3_int64 id = vl_dbi_find_id(db, table, name, &s, err);
  if (id < 0) return s;
  if (id > 0) {
    vl_error_set(err, "a %s named '%s' already exists in %s (remove it first or pick another name)",
                 table, name, db->path);
    return VL_EEXIST;
  }
  return VL_OK;
}

/* Deletes the row `name` of table (children go by ON DELETE CASCADE). */
vl_status vl_dbi_remove_named(vl_db *db, const char *table, const char *name, vl_error *err) {
  char sql[128], doing[64];
  snprintf(sql, sizeof sql, "DELETE FROM %s WHERE name = ?1", table);
  snprintf(doing, sizeof doing, "remove %s '%.30s'", table, name);
  sqlite3_stmt *st = NULL;
  vl_status s = vl_dbi_tx_begin(db, doing, err);
  if (s != VL_OK) return s;
  s = vl_dbi_prepare(db, sql, &st, err);
  if (s != VL_OK) goto cleanup;
  sqlite3_bind_text(st, 1, name, -1, SQLITE_TRANSIENT);
  int rc = sqlite3_step(st);
  if (rc != SQLITE_DONE) {
    s = vl_dbi_fail(db, rc, doing, err);
    goto cleanup;
  }
  if (sqlite3_changes(db->h) == 0) {
    s = vl_dbi_not_found(db, table, name, err);
    goto cleanup;
  }
  sqlite3_finalize(st);
  st = NULL;
  s = vl_dbi_tx_commit(db, doing, err);

cleanup:
  sqlite3_finalize(st);
  if (s != VL_OK) vl_dbi_tx_rollback(db);
  return s;
}

/* Ids of every row of table, sorted by name (malloc'd). */
static vl_status all_ids(vl_db *db, const char *table, sqlite3_int64 **ids, size_t *n,
                         vl_error *err) {
  char sql[128];
  snprintf(sql, sizeof sql, "SELECT id FROM %s ORDER BY name", table);
  sqlite3_stmt *st = NULL;
  size_t cap = 0;
  *ids = NULL;
  *n = 0;
  vl_status s = vl_dbi_prepare(db, sql, &st, err);
  if (s != VL_OK) return s;
  int rc;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    if (*n == cap) {
      size_t ncap = cap ? 2 * cap : 16;
      sqlite3_int64 *ni = realloc(*ids, ncap * sizeof *ni);
      if (!ni) {
        vl_error_set(err, "out of memory listing %s", table);
        s = VL_ENOMEM;
        break;
      }
      *ids = ni;
      cap = ncap;
    }
    (*ids)[(*n)++] = sqlite3_column_int64(st, 0);
  }
  if (s == VL_OK && rc != SQLITE_DONE) s = vl_dbi_fail(db, rc, "listing", err);
  sqlite3_finalize(st);
  if (s != VL_OK) {
    free(*ids);
    *ids = NULL;
    *n = 0;
  }
  return s;
}

/* Every row of table read by by_id into a calloc'd array of count items of
 * item_size bytes (*items, caller frees; NULL and *n = 0 when the table is
 * empty or on any failure). plural names the rows in the out-of-memory
 * message. */
vl_status vl_dbi_list_all(vl_db *db, const char *table, const char *plural, size_t item_size,
                          vl_status (*by_id)(vl_db *, sqlite3_int64, void *, vl_error *),
                          void **items, size_t *n, vl_error *err) {
  sqlite3_int64 *ids;
  size_t count;
  *items = NULL;
  *n = 0;
  vl_status s = all_ids(db, table, &ids, &count, err);
  if (s != VL_OK || count == 0) return s;
  unsigned char *arr = calloc(count, item_size);
  if (!arr) {
    free(ids);
    vl_error_set(err, "out of memory listing %s", plural);
    return VL_ENOMEM;
  }
  for (size_t i = 0; i < count && s == VL_OK; i++)
    s = by_id(db, ids[i], arr + i * item_size, err);
  free(ids);
  if (s != VL_OK) {
    free(arr);
    return s;
  }
  *items = arr;
  *n = count;
  return VL_OK;
}
