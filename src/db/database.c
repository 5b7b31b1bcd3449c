/* The material database: open, migrate, seed, CRUD (database.h). */
#define _POSIX_C_SOURCE 200809L

#include "viscolube/database.h"
#include "viscolube/persson.h"

#include "edit_distance.h"

#include <errno.h>
#include <fcntl.h>
#include <float.h>
#include <math.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The .sql files of materials/, embedded by scripts/embed_materials.cmake,
 * sorted by name and terminated by {NULL, NULL}. */
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

/* PRAGMA application_id of our files: "VLUB". Set by 0001_schema.sql; lets
 * us refuse another program's SQLite file instead of migrating it. */
#define VL_APPLICATION_ID 0x564C5542

struct vl_db {
  sqlite3 *h;
  char *path;
  int readonly;
};

/* ---- small helpers ---------------------------------------------------- */

static void copy_text(char *dst, size_t size, const unsigned char *src) {
  snprintf(dst, size, "%s", src ? (const char *)src : "");
}

static double column_real(sqlite3_stmt *st, int col) {
  return sqlite3_column_type(st, col) == SQLITE_NULL ? NAN : sqlite3_column_double(st, col);
}

/* Binds a double, storing NAN as NULL (SQLite would do so anyway, but
 * explicitly keeps the intent visible). */
static int bind_real(sqlite3_stmt *st, int idx, double v) {
  return isnan(v) ? sqlite3_bind_null(st, idx) : sqlite3_bind_double(st, idx, v);
}

static int bind_text_or_null(sqlite3_stmt *st, int idx, const char *s) {
  return (s && *s) ? sqlite3_bind_text(st, idx, s, -1, SQLITE_TRANSIENT)
                   : sqlite3_bind_null(st, idx);
}

/* Maps an SQLite failure to a status and one sentence naming the file.
 * Every write is one transaction that SQLite rolls back when it fails (or,
 * after a crash, on the next open), so a failure never changes the stored
 * content: the messages say so. */
static vl_status db_fail(const vl_db *db, int rc, const char *doing, vl_error *err) {
  const char *msg = db && db->h ? sqlite3_errmsg(db->h) : sqlite3_errstr(rc);
  const char *path = db ? db->path : "?";
  /* the errno behind an I/O failure says more than "disk I/O error" */
  int sys = db && db->h ? sqlite3_system_errno(db->h) : 0;
  if ((rc & 0xff) == SQLITE_FULL || ((rc & 0xff) == SQLITE_IOERR &&
                                     (sys == ENOSPC || sys == EFBIG || sys == EDQUOT))) {
    vl_error_set(err,
                 "database %s: %s: no room to write (%s): the disk is full or a file-size limit "
                 "was reached; nothing was changed",
                 path, doing, sys ? strerror(sys) : msg);
    return VL_EIO;
  }
  /* SQLite's errno is often gone by the time the rollback has run; a
   * failed write is then most likely a lack of space */
  if (rc == SQLITE_IOERR_WRITE) {
    vl_error_set(err,
                 "database %s: %s: a write failed (%s%s%s): is the disk full or a file-size "
                 "limit reached? nothing was changed",
                 path, doing, msg, sys ? ": " : "", sys ? strerror(sys) : "");
    return VL_EIO;
  }
  switch (rc) {
  case SQLITE_READONLY_ROLLBACK:
  case SQLITE_READONLY_RECOVERY:
    vl_error_set(err,
                 "database %s holds an interrupted write (a hot journal %s-journal, left by a "
                 "crash) that must be rolled back before it can be read, but the file is "
                 "read-only: make it writable and run the command again (nothing was changed)",
                 path, path);
    return VL_EDB;
  case SQLITE_READONLY_DIRECTORY:
    vl_error_set(err,
                 "database %s: %s: its directory is not writable, so the rollback journal cannot "
                 "be created next to it (nothing was changed)",
                 path, doing);
    return VL_EDB;
  default: break;
  }
  switch (rc & 0xff) {
  case SQLITE_NOMEM: vl_error_set(err, "out of memory while %s", doing); return VL_ENOMEM;
  case SQLITE_READONLY:
    vl_error_set(err, "database %s is read-only: %s: nothing was changed", path, doing);
    return VL_EDB;
  case SQLITE_NOTADB:
  case SQLITE_CORRUPT:
    vl_error_set(err, "%s is not a valid viscolube database (%s); it was left unchanged", path,
                 msg);
    return VL_EDB;
  case SQLITE_BUSY:
  case SQLITE_LOCKED:
    vl_error_set(err, "database %s is locked by another program while %s", path, doing);
    return VL_EDB;
  case SQLITE_CANTOPEN:
  case SQLITE_IOERR:
    vl_error_set(err, "database %s: %s: I/O error (%s%s%s); nothing was changed", path, doing, msg,
                 sys ? ": " : "", sys ? strerror(sys) : "");
    return VL_EIO;
  default: vl_error_set(err, "database %s: error while %s (%s)", path, doing, msg); return VL_EDB;
  }
}

static vl_status prepare(vl_db *db, const char *sql, sqlite3_stmt **st, vl_error *err) {
  int rc = sqlite3_prepare_v2(db->h, sql, -1, st, NULL);
  if (rc != SQLITE_OK) {
    *st = NULL;
    return db_fail(db, rc, "preparing a query", err);
  }
  return VL_OK;
}

static vl_status exec(vl_db *db, const char *sql, const char *doing, vl_error *err) {
  int rc = sqlite3_exec(db->h, sql, NULL, NULL, NULL);
  return rc == SQLITE_OK ? VL_OK : db_fail(db, rc, doing, err);
}

/* Reads an integer PRAGMA (user_version, application_id). */
static vl_status pragma_int(vl_db *db, const char *sql, int *out, vl_error *err) {
  sqlite3_stmt *st = NULL;
  vl_status s = prepare(db, sql, &st, err);
  if (s != VL_OK) return s;
  int rc = sqlite3_step(st);
  if (rc == SQLITE_ROW) {
    *out = sqlite3_column_int(st, 0);
    s = VL_OK;
  } else {
    s = db_fail(db, rc, "reading the schema version", err);
  }
  sqlite3_finalize(st);
  return s;
}

/* ---- transactions ----------------------------------------------------- */

/* Every write is one BEGIN IMMEDIATE ... COMMIT: the write lock is taken up
 * front so that a concurrent writer makes us wait (busy timeout) rather than
 * fail half-way, and ROLLBACK restores the file exactly. */
static vl_status tx_begin(vl_db *db, const char *doing, vl_error *err) {
  if (db->readonly) {
    vl_error_set(err,
                 "database %s is read-only (no write permission): cannot %s; nothing was changed",
                 db->path, doing);
    return VL_EDB;
  }
  return exec(db, "BEGIN IMMEDIATE", doing, err);
}

static void tx_rollback(vl_db *db) {
  if (!sqlite3_get_autocommit(db->h)) sqlite3_exec(db->h, "ROLLBACK", NULL, NULL, NULL);
}

static vl_status tx_commit(vl_db *db, const char *doing, vl_error *err) {
  vl_status s = exec(db, "COMMIT", doing, err);
  if (s != VL_OK) tx_rollback(db);
  return s;
}

/* ---- names ------------------------------------------------------------ */

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
  if (name[0] == '-') {
    vl_error_set(err, "name '%s' must not start with '-' (it would read as an option)", name);
    return VL_EINPUT;
  }
  for (size_t i = 0; i < n; i++) {
    char c = name[i];
    int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
             c == '.' || c == '_' || c == '+' || c == '-';
    if (!ok) {
      vl_error_set(err, "name '%s': character %zu is not one of A-Z a-z 0-9 . _ + -", name, i + 1);
      return VL_EINPUT;
    }
  }
  return VL_OK;
}

static vl_status check_text(const char *what, const char *s, vl_error *err) {
  if (s && strlen(s) >= VL_DB_TEXT_MAX) {
    vl_error_set(err, "%s is longer than %d characters", what, VL_DB_TEXT_MAX - 1);
    return VL_EINPUT;
  }
  return VL_OK;
}


/* VL_ENOTFOUND with a message naming `name` and the closest names of the
 * same kind (up to three ties): a small edit distance, or one name
 * containing the other, counts as close. */
static vl_status not_found(vl_db *db, const char *table, const char *name, vl_error *err) {
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
static sqlite3_int64 find_id(vl_db *db, const char *table, const char *name, vl_status *s,
                             vl_error *err) {
  char sql[128];
  snprintf(sql, sizeof sql, "SELECT id FROM %s WHERE name = ?1", table);
  sqlite3_stmt *st = NULL;
  *s = prepare(db, sql, &st, err);
  if (*s != VL_OK) return -1;
  sqlite3_bind_text(st, 1, name, -1, SQLITE_TRANSIENT);
  sqlite3_int64 id = 0;
  int rc = sqlite3_step(st);
  if (rc == SQLITE_ROW)
    id = sqlite3_column_int64(st, 0);
  else if (rc != SQLITE_DONE) {
    *s = db_fail(db, rc, "looking up a name", err);
    id = -1;
  }
  sqlite3_finalize(st);
  return id;
}

/* Inside a transaction: VL_EEXIST if `name` is taken in table. */
static vl_status check_free(vl_db *db, const char *table, const char *name, vl_error *err) {
  vl_status s;
  sqlite3_int64 id = find_id(db, table, name, &s, err);
  if (id < 0) return s;
  if (id > 0) {
    vl_error_set(err, "a %s named '%s' already exists in %s (remove it first or pick another name)",
                 table, name, db->path);
    return VL_EEXIST;
  }
  return VL_OK;
}

/* Deletes the row `name` of table (children go by ON DELETE CASCADE). */
static vl_status remove_named(vl_db *db, const char *table, const char *name, vl_error *err) {
  char sql[128], doing[64];
  snprintf(sql, sizeof sql, "DELETE FROM %s WHERE name = ?1", table);
  snprintf(doing, sizeof doing, "remove %s '%.30s'", table, name);
  sqlite3_stmt *st = NULL;
  vl_status s = tx_begin(db, doing, err);
  if (s != VL_OK) return s;
  s = prepare(db, sql, &st, err);
  if (s != VL_OK) goto cleanup;
  sqlite3_bind_text(st, 1, name, -1, SQLITE_TRANSIENT);
  int rc = sqlite3_step(st);
  if (rc != SQLITE_DONE) {
    s = db_fail(db, rc, doing, err);
    goto cleanup;
  }
  if (sqlite3_changes(db->h) == 0) {
    s = not_found(db, table, name, err);
    goto cleanup;
  }
  sqlite3_finalize(st);
  st = NULL;
  s = tx_commit(db, doing, err);

cleanup:
  sqlite3_finalize(st);
  if (s != VL_OK) tx_rollback(db);
  return s;
}

/* ---- surfaces: the one place derived columns are computed ------------- */

/* Derived scalars of a validated PSD: C0 (self-affine; NAN otherwise),
 * h_rms and rms slope by vl_psd_hrms / vl_psd_rms_slope. */
static vl_status surface_derive(const vl_psd *psd, double *c0, double *hrms, double *slope,
                                vl_error *err) {
  *c0 = psd->kind == VL_PSD_SELF_AFFINE ? psd->c0 : NAN;
  *hrms = vl_psd_hrms(psd);
  *slope = vl_psd_rms_slope(psd);
  if (!(isfinite(*hrms) && *hrms > 0.0 && isfinite(*slope) && *slope > 0.0) ||
      (psd->kind == VL_PSD_SELF_AFFINE && !(isfinite(*c0) && *c0 > 0.0))) {
    vl_error_set(err, "the spectrum's h_rms or rms slope is not a finite positive number "
                      "(values out of floating-point range?)");
    return VL_EINPUT;
  }
  return VL_OK;
}

/* Builds the PSD of surface row `id` through vl_psd_init_* (which validate
 * it). kind/hurst/q0/q1/hrms are that row's input columns. */
static vl_status surface_load_psd(vl_db *db, sqlite3_int64 id, const char *kind, double hurst,
                                  double q0, double q1, double hrms, vl_psd *out, vl_error *err) {
  vl_status s = VL_OK;
  memset(out, 0, sizeof *out);
  if (kind && !strcmp(kind, "self-affine")) {
    s = vl_psd_init_self_affine(out, hurst, q0, q1, hrms, err);
    if (s != VL_OK) {
      vl_error_prefix(err, "database %s: stored surface is invalid", db->path);
      return VL_EDB;
    }
    return VL_OK;
  }
  sqlite3_stmt *st = NULL;
  double *q = NULL, *C = NULL;
  size_t n = 0, cap = 0;
  s = prepare(db, "SELECT q_per_m, c_m4 FROM surface_point WHERE surface_id = ?1 ORDER BY idx", &st,
              err);
  if (s != VL_OK) return s;
  sqlite3_bind_int64(st, 1, id);
  int rc;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    if (n == cap) {
      size_t ncap = cap ? 2 * cap : 64;
      double *nq = realloc(q, ncap * sizeof *q);
      if (nq) q = nq;
      double *nC = nq ? realloc(C, ncap * sizeof *C) : NULL;
      if (nC) C = nC;
      if (!nq || !nC) {
        vl_error_set(err, "out of memory reading a tabulated surface");
        s = VL_ENOMEM;
        goto cleanup;
      }
      cap = ncap;
    }
    q[n] = column_real(st, 0);
    C[n] = column_real(st, 1);
    n++;
  }
  if (rc != SQLITE_DONE) {
    s = db_fail(db, rc, "reading surface points", err);
    goto cleanup;
  }
  s = vl_psd_init_tabulated(out, n, q, C, err);
  if (s == VL_EINPUT) {
    vl_error_prefix(err, "database %s: stored surface is invalid", db->path);
    s = VL_EDB;
  }

cleanup:
  sqlite3_finalize(st);
  free(q);
  free(C);
  return s;
}

/* Fills the derived columns of every surface that lacks them (shipped
 * seeds, or rows a migration added), with the code user surfaces go
 * through. Runs inside the caller's transaction. */
static vl_status fill_derived(vl_db *db, vl_error *err) {
  sqlite3_stmt *sel = NULL, *upd = NULL;
  sqlite3_int64 *ids = NULL;
  size_t n = 0, cap = 0;
  vl_status s = prepare(db,
                        "SELECT id FROM surface WHERE derived_hrms_m IS NULL OR "
                        "derived_rms_slope IS NULL OR (kind = 'self-affine' AND c0_m4 IS NULL)",
                        &sel, err);
  if (s != VL_OK) return s;
  int rc;
  while ((rc = sqlite3_step(sel)) == SQLITE_ROW) {
    if (n == cap) {
      size_t ncap = cap ? 2 * cap : 16;
      sqlite3_int64 *ni = realloc(ids, ncap * sizeof *ids);
      if (!ni) {
        vl_error_set(err, "out of memory deriving surface columns");
        s = VL_ENOMEM;
        goto cleanup;
      }
      ids = ni;
      cap = ncap;
    }
    ids[n++] = sqlite3_column_int64(sel, 0);
  }
  if (rc != SQLITE_DONE) {
    s = db_fail(db, rc, "deriving surface columns", err);
    goto cleanup;
  }
  sqlite3_finalize(sel);
  sel = NULL;
  s = prepare(db, "SELECT kind, hurst, q0_per_m, q1_per_m, hrms_m, name FROM surface WHERE id = ?1",
              &sel, err);
  if (s != VL_OK) goto cleanup;
  s = prepare(db,
              "UPDATE surface SET c0_m4 = ?2, derived_hrms_m = ?3, derived_rms_slope = ?4, "
              "q0_per_m = ?5, q1_per_m = ?6 WHERE id = ?1",
              &upd, err);
  if (s != VL_OK) goto cleanup;
  for (size_t i = 0; i < n; i++) {
    sqlite3_reset(sel);
    sqlite3_bind_int64(sel, 1, ids[i]);
    if ((rc = sqlite3_step(sel)) != SQLITE_ROW) {
      s = db_fail(db, rc, "deriving surface columns", err);
      goto cleanup;
    }
    char kind[32], name[VL_DB_NAME_MAX];
    copy_text(kind, sizeof kind, sqlite3_column_text(sel, 0));
    copy_text(name, sizeof name, sqlite3_column_text(sel, 5));
    vl_psd psd;
    s = surface_load_psd(db, ids[i], kind, column_real(sel, 1), column_real(sel, 2),
                         column_real(sel, 3), column_real(sel, 4), &psd, err);
    double c0, hrms, slope;
    if (s == VL_OK) s = surface_derive(&psd, &c0, &hrms, &slope, err);
    if (s != VL_OK) {
      vl_psd_free(&psd);
      vl_error_prefix(err, "surface '%s'", name);
      goto cleanup;
    }
    sqlite3_reset(upd);
    sqlite3_bind_int64(upd, 1, ids[i]);
    bind_real(upd, 2, c0);
    bind_real(upd, 3, hrms);
    bind_real(upd, 4, slope);
    bind_real(upd, 5, psd.q0);
    bind_real(upd, 6, psd.q1);
    vl_psd_free(&psd);
    if ((rc = sqlite3_step(upd)) != SQLITE_DONE) {
      s = db_fail(db, rc, "storing derived surface columns", err);
      goto cleanup;
    }
  }

cleanup:
  sqlite3_finalize(sel);
  sqlite3_finalize(upd);
  free(ids);
  return s;
}

/* ---- schema: migrations and seeds ------------------------------------- */

/* Migration number of an embedded file named NNNN_*.sql, else 0. */
static int migration_number(const char *name) {
  for (int i = 0; i < 4; i++)
    if (name[i] < '0' || name[i] > '9') return 0;
  if (name[4] != '_') return 0;
  return (name[0] - '0') * 1000 + (name[1] - '0') * 100 + (name[2] - '0') * 10 + (name[3] - '0');
}

static int is_seed(const char *name) { return strncmp(name, "seed_", 5) == 0; }

/* Shipped measured data (*.csv), imported by seed_measured. */
static int is_data(const char *name) {
  size_t n = strlen(name);
  return n > 4 && strcmp(name + n - 4, ".csv") == 0;
}

static vl_status seed_measured(vl_db *db, vl_error *err);

int vl_db_schema_version(void) {
  int latest = 0;
  for (const struct vl_embedded_file *f = vl_embedded_materials; f->name; f++) {
    int v = migration_number(f->name);
    if (v > latest) latest = v;
  }
  return latest;
}

/* The embedded migrations must be numbered 1..latest without gaps. */
static vl_status check_embedded(vl_error *err) {
  int latest = vl_db_schema_version(), expect = 1;
  for (const struct vl_embedded_file *f = vl_embedded_materials; f->name; f++) {
    int v = migration_number(f->name);
    if (v == 0 && !is_seed(f->name) && !is_data(f->name)) {
      vl_error_set(err, "embedded material file '%s' is neither NNNN_*.sql, seed_*.sql nor *.csv",
                   f->name);
      return VL_EINTERNAL;
    }
    if (v && v != expect++) {
      vl_error_set(err, "embedded migration '%s' is out of sequence (expected %04d)", f->name,
                   expect - 1);
      return VL_EINTERNAL;
    }
  }
  if (latest < 1) {
    vl_error_set(err, "no schema migration is embedded in the program");
    return VL_EINTERNAL;
  }
  return VL_OK;
}

static vl_status apply_sql(vl_db *db, const struct vl_embedded_file *f, vl_error *err) {
  char *msg = NULL;
  int rc = sqlite3_exec(db->h, f->text, NULL, NULL, &msg);
  if (rc == SQLITE_OK) return VL_OK;
  vl_status s = db_fail(db, rc, "applying an embedded material file", err);
  vl_error_prefix(err, "%s", f->name);
  sqlite3_free(msg);
  return s;
}

static vl_status set_version(vl_db *db, int version, vl_error *err) {
  char sql[64];
  snprintf(sql, sizeof sql, "PRAGMA user_version = %d", version);
  return exec(db, sql, "setting the schema version", err);
}

/* Brings the file to the latest schema. A new (empty) file gets every
 * migration and every seed in one transaction; an older one gets each
 * missing migration in its own transaction. A newer, foreign or corrupt
 * file is refused before anything is written. */
static vl_status migrate(vl_db *db, vl_error *err) {
  int latest = vl_db_schema_version(), version = 0, app = 0, tables = 0;
  vl_status s = check_embedded(err);
  if (s != VL_OK) return s;
  if ((s = pragma_int(db, "PRAGMA user_version", &version, err)) != VL_OK) return s;
  if ((s = pragma_int(db, "PRAGMA application_id", &app, err)) != VL_OK) return s;
  if ((s = pragma_int(db, "SELECT count(*) FROM sqlite_master", &tables, err)) != VL_OK) return s;
  if (version > latest) {
    vl_error_set(err,
                 "database %s has schema version %d, newer than the %d this program knows: "
                 "use a newer viscolube (the file was not changed)",
                 db->path, version, latest);
    return VL_EDB;
  }
  if ((version > 0 || app != 0 || tables > 0) && app != VL_APPLICATION_ID) {
    vl_error_set(err,
                 "%s is an SQLite file of another program, not a viscolube database "
                 "(it was not changed)",
                 db->path);
    return VL_EDB;
  }
  if (version == latest) return VL_OK;
  if (db->readonly) {
    vl_error_set(err, "database %s has schema version %d < %d and is read-only: cannot upgrade it",
                 db->path, version, latest);
    return VL_EDB;
  }
  int fresh = version == 0;
  for (int target = version + 1; target <= latest; target++) {
    if (fresh && target > 1) break; /* one transaction did everything */
    if ((s = tx_begin(db, "upgrade the schema", err)) != VL_OK) return s;
    /* Re-read under the write lock: another process may have migrated. */
    int now = 0;
    if ((s = pragma_int(db, "PRAGMA user_version", &now, err)) != VL_OK) goto fail;
    if (now >= target) {
      tx_rollback(db);
      continue;
    }
    for (const struct vl_embedded_file *f = vl_embedded_materials; f->name; f++) {
      int v = migration_number(f->name);
      int wanted = fresh ? (v >= 1) : (v == target);
      if (wanted && (s = apply_sql(db, f, err)) != VL_OK) goto fail;
    }
    if (fresh) {
      for (const struct vl_embedded_file *f = vl_embedded_materials; f->name; f++)
        if (is_seed(f->name) && (s = apply_sql(db, f, err)) != VL_OK) goto fail;
      if ((s = seed_measured(db, err)) != VL_OK) goto fail;
    }
    if ((s = fill_derived(db, err)) != VL_OK) goto fail;
    if ((s = set_version(db, fresh ? latest : target, err)) != VL_OK) goto fail;
    if ((s = tx_commit(db, "upgrade the schema", err)) != VL_OK) return s;
  }
  return VL_OK;

fail:
  tx_rollback(db);
  return s;
}

/* ---- opening ---------------------------------------------------------- */

vl_status vl_db_default_path(char *buf, size_t size, vl_error *err) {
  const char *env = getenv("VISCOLUBE_DB"), *xdg = getenv("XDG_DATA_HOME"), *home = getenv("HOME");
  int n;
  if (env && *env)
    n = snprintf(buf, size, "%s", env);
  else if (xdg && xdg[0] == '/') /* XDG: relative values are invalid, ignore */
    n = snprintf(buf, size, "%s/viscolube/materials.db", xdg);
  else if (home && *home)
    n = snprintf(buf, size, "%s/.local/share/viscolube/materials.db", home);
  else {
    vl_error_set(err, "no default database path: set VISCOLUBE_DB, XDG_DATA_HOME or HOME");
    return VL_EINPUT;
  }
  if (n < 0 || (size_t)n >= size) {
    vl_error_set(err, "the default database path is longer than %zu characters", size - 1);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* mkdir -p of the directory part of path. */
static vl_status make_parents(const char *path, vl_error *err) {
  char dir[4096];
  if (snprintf(dir, sizeof dir, "%s", path) >= (int)sizeof dir) {
    vl_error_set(err, "database path is too long");
    return VL_EINPUT;
  }
  char *slash = strrchr(dir, '/');
  if (!slash || slash == dir) return VL_OK;
  *slash = '\0';
  for (char *p = dir + 1;; p++) {
    if (*p == '/' || *p == '\0') {
      char c = *p;
      *p = '\0';
      if (mkdir(dir, 0755) != 0 && errno != EEXIST) {
        vl_error_set(err, "cannot create directory %s: %s", dir, strerror(errno));
        return VL_EIO;
      }
      *p = c;
      if (c == '\0') break;
    }
  }
  return VL_OK;
}

void vl_db_close(vl_db *db) {
  if (!db) return;
  sqlite3_close(db->h);
  free(db->path);
  free(db);
}

const char *vl_db_path(const vl_db *db) { return db->path; }

int vl_db_readonly(const vl_db *db) { return db->readonly; }

vl_status vl_db_open(const char *path, vl_db **out, vl_error *err) {
  char defpath[4096];
  vl_status s = VL_OK;
  int created = 0;
  *out = NULL;
  if (!path) {
    if ((s = vl_db_default_path(defpath, sizeof defpath, err)) != VL_OK) return s;
    if ((s = make_parents(defpath, err)) != VL_OK) return s;
    path = defpath;
  }
  if (!*path) {
    vl_error_set(err, "the database path is empty");
    return VL_EINPUT;
  }
  vl_db *db = calloc(1, sizeof *db);
  if (!db || !(db->path = strdup(path))) {
    free(db);
    vl_error_set(err, "out of memory opening %s", path);
    return VL_ENOMEM;
  }

  struct stat sb;
  if (stat(path, &sb) != 0) {
    if (errno != ENOENT) {
      vl_error_set(err, "cannot access database %s: %s", path, strerror(errno));
      s = VL_EIO;
      goto fail;
    }
    /* Create the file ourselves (O_EXCL) so that on a failed seed we remove
     * only a file we made, never one another process just created. */
    int fd = open(path, O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd >= 0) {
      close(fd);
      created = 1;
    } else if (errno != EEXIST) {
      vl_error_set(err, "cannot create database %s: %s", path, strerror(errno));
      s = VL_EIO;
      goto fail;
    }
  } else if (!S_ISREG(sb.st_mode)) {
    vl_error_set(err, "database %s is not a regular file", path);
    s = VL_EDB;
    goto fail;
  } else {
    /* Root ignores permission bits, so access() alone would let root write
     * a file its owner marked read-only: honour the bits as well. */
    db->readonly = (sb.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 || access(path, W_OK) != 0;
  }

  int flags = db->readonly ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE;
  int rc = sqlite3_open_v2(path, &db->h, flags, NULL);
  if (rc != SQLITE_OK) {
    s = db_fail(db, rc, "opening", err);
    goto fail;
  }
  sqlite3_extended_result_codes(db->h, 1);
  sqlite3_busy_timeout(db->h, BUSY_TIMEOUT_MS);
  /* Defensive mode: no writable_schema tricks from a hostile file. */
  sqlite3_db_config(db->h, SQLITE_DBCONFIG_DEFENSIVE, 1, NULL);
  if ((s = exec(db, "PRAGMA foreign_keys = ON", "enabling foreign keys", err)) != VL_OK) goto fail;
  if ((s = migrate(db, err)) != VL_OK) goto fail;
  *out = db;
  return VL_OK;

fail:
  vl_db_close(db);
  if (created) {
    char journal[4200];
    unlink(path);
    snprintf(journal, sizeof journal, "%s-journal", path);
    unlink(journal);
  }
  return s;
}

/* ---- compounds -------------------------------------------------------- */

static const char *const compound_classes[] = {"model", "filled", "unfilled", "other"};

/* Loads the compound row `id` (metadata and terms). */
static vl_status compound_by_id(vl_db *db, sqlite3_int64 id, vl_db_compound *out, vl_error *err) {
  sqlite3_stmt *st = NULL;
  memset(out, 0, sizeof *out);
  vl_status s =
      prepare(db,
              "SELECT name, class, description, nu, e_inf_pa, tref_c, wlf_c1, wlf_c2_k, "
              "source_file, method, fit_rms_error, created_at FROM compound WHERE id = ?1",
              &st, err);
  if (s != VL_OK) return s;
  sqlite3_bind_int64(st, 1, id);
  int rc = sqlite3_step(st);
  if (rc != SQLITE_ROW) {
    s = db_fail(db, rc == SQLITE_DONE ? SQLITE_CORRUPT : rc, "reading a compound", err);
    goto cleanup;
  }
  copy_text(out->name, sizeof out->name, sqlite3_column_text(st, 0));
  copy_text(out->class_name, sizeof out->class_name, sqlite3_column_text(st, 1));
  copy_text(out->description, sizeof out->description, sqlite3_column_text(st, 2));
  out->prony.nu = column_real(st, 3);
  out->prony.e_inf_pa = column_real(st, 4);
  out->tref_c = column_real(st, 5);
  out->wlf_c1 = column_real(st, 6);
  out->wlf_c2_k = column_real(st, 7);
  copy_text(out->source_file, sizeof out->source_file, sqlite3_column_text(st, 8));
  copy_text(out->method, sizeof out->method, sqlite3_column_text(st, 9));
  out->fit_rms_error = column_real(st, 10);
  copy_text(out->created_at, sizeof out->created_at, sqlite3_column_text(st, 11));
  sqlite3_finalize(st);
  st = NULL;

  s = prepare(db, "SELECT A, tau_s FROM compound_prony WHERE compound_id = ?1 ORDER BY idx", &st,
              err);
  if (s != VL_OK) goto cleanup;
  sqlite3_bind_int64(st, 1, id);
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    if (out->prony.n_terms == VL_PRONY_MAX_TERMS) {
      vl_error_set(err, "database %s: compound '%s' has more than %d Prony terms", db->path,
                   out->name, VL_PRONY_MAX_TERMS);
      s = VL_EDB;
      goto cleanup;
    }
    out->prony.A[out->prony.n_terms] = column_real(st, 0);
    out->prony.tau_s[out->prony.n_terms] = column_real(st, 1);
    out->prony.n_terms++;
  }
  if (rc != SQLITE_DONE) {
    s = db_fail(db, rc, "reading Prony terms", err);
    goto cleanup;
  }
  if (vl_prony_validate(&out->prony, err) != VL_OK) {
    vl_error_prefix(err, "database %s: stored compound '%s' is invalid", db->path, out->name);
    s = VL_EDB;
  }

cleanup:
  sqlite3_finalize(st);
  return s;
}

vl_status vl_db_compound_info(vl_db *db, const char *name, vl_db_compound *out, vl_error *err) {
  vl_status s;
  sqlite3_int64 id = find_id(db, "compound", name, &s, err);
  if (id < 0) return s;
  if (id == 0) return not_found(db, "compound", name, err);
  return compound_by_id(db, id, out, err);
}

vl_status vl_db_compound_get(vl_db *db, const char *name, vl_prony *out, vl_error *err) {
  vl_db_compound *c = malloc(sizeof *c);
  if (!c) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  vl_status s = vl_db_compound_info(db, name, c, err);
  if (s == VL_OK) *out = c->prony;
  free(c);
  return s;
}

/* Everything vl_db_compound_add checks before touching the file. */
static vl_status compound_check(const vl_db_compound *c, vl_error *err) {
  vl_status s;
  if ((s = vl_db_check_name(c->name, err)) != VL_OK) return s;
  int class_ok = 0;
  for (size_t i = 0; i < sizeof compound_classes / sizeof *compound_classes; i++)
    class_ok |= !strcmp(c->class_name, compound_classes[i]);
  if (!class_ok) {
    vl_error_set(err, "class '%s' is not one of model, filled, unfilled, other", c->class_name);
    return VL_EINPUT;
  }
  if ((s = check_text("description", c->description, err)) != VL_OK) return s;
  if ((s = check_text("source file name", c->source_file, err)) != VL_OK) return s;
  if ((s = vl_prony_validate(&c->prony, err)) != VL_OK) return s;
  if (c->prony.n_terms == 0) {
    vl_error_set(err, "compound '%s' has no Prony terms", c->name);
    return VL_EINPUT;
  }
  /* finite terms can still sum to infinity: E0 = Einf / (1 + sum A) would
   * then be 0 (or subnormal), and so every contact scale built on it */
  double sum_a = vl_prony_sum_A(&c->prony), e0 = vl_prony_e0(&c->prony);
  if (!(isfinite(sum_a) && e0 >= DBL_MIN)) {
    vl_error_set(err,
                 "compound '%s': the relaxed modulus E0 = Einf / (1 + sum A) = %g Pa is not a "
                 "positive number (sum A = %g)",
                 c->name, e0, sum_a);
    return VL_EINPUT;
  }
  if (!isfinite(c->tref_c) || c->tref_c < -273.15) {
    vl_error_set(err, "reference temperature must be a finite temperature above -273.15 C (got %g)",
                 c->tref_c);
    return VL_EINPUT;
  }
  if (isnan(c->wlf_c1) != isnan(c->wlf_c2_k) ||
      (!isnan(c->wlf_c1) && !(isfinite(c->wlf_c1) && isfinite(c->wlf_c2_k) && c->wlf_c2_k > 0.0))) {
    vl_error_set(err, "WLF constants: give both C1 and C2 > 0 K, or neither");
    return VL_EINPUT;
  }
  if (!isnan(c->fit_rms_error) && !(isfinite(c->fit_rms_error) && c->fit_rms_error >= 0.0)) {
    vl_error_set(err, "fit rms error must be finite and >= 0 (got %g)", c->fit_rms_error);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* Inside a transaction: inserts a checked compound and its terms; *id gets
 * its row id. */
static vl_status compound_insert(vl_db *db, const vl_db_compound *c, const char *doing,
                                 sqlite3_int64 *id, vl_error *err) {
  vl_status s;
  sqlite3_stmt *st = NULL;
  if ((s = check_free(db, "compound", c->name, err)) != VL_OK) return s;
  s = prepare(db,
              "INSERT INTO compound (name, class, description, nu, e_inf_pa, tref_c, wlf_c1, "
              "wlf_c2_k, source_file, method, fit_rms_error) "
              "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11)",
              &st, err);
  if (s != VL_OK) return s;
  sqlite3_bind_text(st, 1, c->name, -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(st, 2, c->class_name, -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(st, 3, c->description, -1, SQLITE_TRANSIENT);
  bind_real(st, 4, c->prony.nu);
  bind_real(st, 5, c->prony.e_inf_pa);
  bind_real(st, 6, c->tref_c);
  bind_real(st, 7, c->wlf_c1);
  bind_real(st, 8, c->wlf_c2_k);
  bind_text_or_null(st, 9, c->source_file);
  sqlite3_bind_text(st, 10, c->method[0] ? c->method : "prony-csv", -1, SQLITE_TRANSIENT);
  bind_real(st, 11, c->fit_rms_error);
  int rc = sqlite3_step(st);
  if (rc != SQLITE_DONE) {
    s = db_fail(db, rc, doing, err);
    goto cleanup;
  }
  *id = sqlite3_last_insert_rowid(db->h);
  sqlite3_finalize(st);
  st = NULL;
  s = prepare(db, "INSERT INTO compound_prony (compound_id, idx, A, tau_s) VALUES (?1, ?2, ?3, ?4)",
              &st, err);
  if (s != VL_OK) goto cleanup;
  for (size_t i = 0; i < c->prony.n_terms; i++) {
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, *id);
    sqlite3_bind_int64(st, 2, (sqlite3_int64)i + 1);
    bind_real(st, 3, c->prony.A[i]);
    bind_real(st, 4, c->prony.tau_s[i]);
    if ((rc = sqlite3_step(st)) != SQLITE_DONE) {
      s = db_fail(db, rc, doing, err);
      goto cleanup;
    }
  }

cleanup:
  sqlite3_finalize(st);
  return s;
}

vl_status vl_db_compound_add(vl_db *db, const vl_db_compound *c, vl_error *err) {
  vl_status s;
  if ((s = compound_check(c, err)) != VL_OK) return s;
  char doing[128];
  snprintf(doing, sizeof doing, "add compound '%s'", c->name);
  if ((s = tx_begin(db, doing, err)) != VL_OK) return s;
  sqlite3_int64 id;
  if ((s = compound_insert(db, c, doing, &id, err)) == VL_OK) s = tx_commit(db, doing, err);
  if (s != VL_OK) tx_rollback(db);
  return s;
}

/* ---- measured compounds ----------------------------------------------- */

/* Checks that m is a complete import (as vl_measured_read_* leave it). */
static vl_status measured_check(const vl_measured *m, vl_error *err) {
  if (!m || m->n == 0 || !m->omega_rad_s || !m->storage_pa || !m->loss_pa || !m->temperature_c ||
      !m->reduced_omega_rad_s || !m->line || !m->isotherm || m->n_isotherms == 0 ||
      !m->iso_temperature_c || !m->iso_log10_a_t ||
      (m->kind == VL_DMA_COMPLIANCE && (!m->j1_per_pa || !m->j2_per_pa))) {
    vl_error_set(err, "the measured data are incomplete (not from vl_measured_read_*)");
    return VL_EINPUT;
  }
  for (size_t k = 0; k < m->n; k++) {
    if (!(m->omega_rad_s[k] > 0.0 && isfinite(m->omega_rad_s[k]) &&
          m->reduced_omega_rad_s[k] > 0.0 && isfinite(m->reduced_omega_rad_s[k]) &&
          isfinite(m->temperature_c[k]) && m->isotherm[k] < m->n_isotherms)) {
      vl_error_set(err, "measured point %zu is invalid", k + 1);
      return VL_EINPUT;
    }
  }
  return VL_OK;
}

/* Inside a transaction: the compound of meta (name, class, description,
 * source file) with the series, shifts, points and fit of m. */
static vl_status measured_insert(vl_db *db, const vl_db_compound *meta, const vl_measured *m,
                                 const char *doing, vl_error *err) {
  vl_status s;
  sqlite3_stmt *st = NULL;
  vl_db_compound *c = malloc(sizeof *c);
  if (!c) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  memset(c, 0, sizeof *c);
  snprintf(c->name, sizeof c->name, "%s", meta->name);
  snprintf(c->class_name, sizeof c->class_name, "%s", meta->class_name);
  snprintf(c->description, sizeof c->description, "%s", meta->description);
  snprintf(c->source_file, sizeof c->source_file, "%s", meta->source_file);
  snprintf(c->method, sizeof c->method, "dma-fit");
  c->prony = m->prony;
  c->tref_c = m->tref_c;
  c->wlf_c1 = m->wlf_c1;
  c->wlf_c2_k = m->wlf_c2_k;
  c->fit_rms_error = m->fit.rms_rel;
  sqlite3_int64 id = 0;
  if ((s = compound_check(c, err)) != VL_OK) goto cleanup;
  if ((s = compound_insert(db, c, doing, &id, err)) != VL_OK) goto cleanup;

  int compliance = m->kind == VL_DMA_COMPLIANCE;
  s = prepare(db,
              "INSERT INTO compound_measurement (compound_id, frequency_rad_s, temperature_c, "
              "storage_pa, loss_pa, j1_per_pa, j2_per_pa, source_file, source_line, "
              "reduced_frequency_rad_s) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10)",
              &st, err);
  if (s != VL_OK) goto cleanup;
  int rc;
  for (size_t k = 0; k < m->n; k++) {
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, id);
    bind_real(st, 2, m->omega_rad_s[k]);
    bind_real(st, 3, m->temperature_c[k]);
    bind_real(st, 4, compliance ? NAN : m->storage_pa[k]);
    bind_real(st, 5, compliance ? NAN : m->loss_pa[k]);
    bind_real(st, 6, compliance ? m->j1_per_pa[k] : NAN);
    bind_real(st, 7, compliance ? m->j2_per_pa[k] : NAN);
    bind_text_or_null(st, 8, c->source_file);
    sqlite3_bind_int64(st, 9, (sqlite3_int64)m->line[k]);
    bind_real(st, 10, m->reduced_omega_rad_s[k]);
    if ((rc = sqlite3_step(st)) != SQLITE_DONE) {
      s = db_fail(db, rc, doing, err);
      goto cleanup;
    }
  }
  sqlite3_finalize(st);
  st = NULL;
  if (m->has_temperature) {
    s = prepare(db,
                "INSERT INTO compound_shift (compound_id, temperature_c, log10_a_t) "
                "VALUES (?1, ?2, ?3)",
                &st, err);
    if (s != VL_OK) goto cleanup;
    for (size_t g = 0; g < m->n_isotherms; g++) {
      sqlite3_reset(st);
      sqlite3_bind_int64(st, 1, id);
      bind_real(st, 2, m->iso_temperature_c[g]);
      bind_real(st, 3, m->iso_log10_a_t[g]);
      if ((rc = sqlite3_step(st)) != SQLITE_DONE) {
        s = db_fail(db, rc, doing, err);
        goto cleanup;
      }
    }
    sqlite3_finalize(st);
    st = NULL;
  }
  s = prepare(db,
              "INSERT INTO compound_fit (compound_id, input_kind, weights, n_points, n_isotherms, "
              "omega_min_rad_s, omega_max_rad_s, terms_per_decade, n_grid, rms_rel_storage, "
              "max_rel_storage, rms_rel_loss, max_rel_loss, wlf_rms_log10_a_t) "
              "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14)",
              &st, err);
  if (s != VL_OK) goto cleanup;
  const vl_prony_fit_report *f = &m->fit;
  sqlite3_bind_int64(st, 1, id);
  sqlite3_bind_text(st, 2, vl_dma_kind_name(m->kind), -1, SQLITE_STATIC);
  sqlite3_bind_text(st, 3, vl_prony_weights_name(f->weights), -1, SQLITE_STATIC);
  sqlite3_bind_int64(st, 4, (sqlite3_int64)m->n);
  sqlite3_bind_int64(st, 5, (sqlite3_int64)m->n_isotherms);
  bind_real(st, 6, f->omega_min_rad_s);
  bind_real(st, 7, f->omega_max_rad_s);
  bind_real(st, 8, f->terms_per_decade);
  sqlite3_bind_int64(st, 9, (sqlite3_int64)f->n_grid);
  bind_real(st, 10, f->rms_rel_storage);
  bind_real(st, 11, f->max_rel_storage);
  bind_real(st, 12, f->rms_rel_loss);
  bind_real(st, 13, f->max_rel_loss);
  bind_real(st, 14, m->wlf_rms);
  if ((rc = sqlite3_step(st)) != SQLITE_DONE) s = db_fail(db, rc, doing, err);

cleanup:
  sqlite3_finalize(st);
  free(c);
  return s;
}

vl_status vl_db_compound_add_measured(vl_db *db, const vl_db_compound *meta, const vl_measured *m,
                                      vl_error *err) {
  vl_status s;
  if ((s = measured_check(m, err)) != VL_OK) return s;
  char doing[128];
  snprintf(doing, sizeof doing, "add compound '%s'", meta->name);
  if ((s = tx_begin(db, doing, err)) != VL_OK) return s;
  if ((s = measured_insert(db, meta, m, doing, err)) == VL_OK) s = tx_commit(db, doing, err);
  if (s != VL_OK) tx_rollback(db);
  return s;
}

/* Compounds shipped as measured-style data files in materials/, registered
 * in every new database through the import path of user data
 * (vl_measured_read_text, then measured_insert) inside the creating
 * transaction. Both are SYNTHETIC: no public, licensed measurement of an
 * unfilled and a filled rubber exists; scripts/gen_synthetic_dma.py made
 * them from the documented model in their header comments. Relative
 * weights: the data obey Kramers-Kronig, so E'' is fitted to its noise. */
static const struct {
  const char *file, *name, *class_name, *description;
} shipped_measured[] = {
    {"sbr-unfilled-synthetic.csv", "sbr-unfilled", "unfilled",
     "SYNTHETIC stand-in for an unfilled SBR, not a measurement: Havriliak-Negami modulus "
     "(E0 2 MPa, Einf 2 GPa, alpha 0.60, beta 0.35, tau 2.5 ms) with WLF (C1 12.57, C2 71.6 K at "
     "20 C), DMA-like sampling 0-100 C, 0.1-100 Hz, 1 % noise (scripts/gen_synthetic_dma.py), "
     "imported and fitted like user data; rolling number near Scaraggi & Persson's "
     "Q_unfilled = 3e-4 (Fig. 15)"},
    {"sbr-filled-synthetic.csv", "sbr-filled", "filled",
     "SYNTHETIC stand-in for a carbon-black filled SBR, not a measurement: Havriliak-Negami "
     "modulus (E0 8 MPa, Einf 3 GPa, alpha 0.50, beta 0.35, tau 2.8 ms) with WLF (C1 12.57, "
     "C2 71.6 K at 20 C), DMA-like sampling 0-100 C, 0.1-100 Hz, 1 % noise "
     "(scripts/gen_synthetic_dma.py), imported and fitted like user data; rolling number near "
     "Scaraggi & Persson's Q_filled = 3e-5 (Fig. 16)"},
};

static vl_status seed_measured(vl_db *db, vl_error *err) {
  for (size_t i = 0; i < sizeof shipped_measured / sizeof *shipped_measured; i++) {
    const struct vl_embedded_file *f = vl_embedded_materials;
    while (f->name && strcmp(f->name, shipped_measured[i].file))
      f++;
    if (!f->name) {
      vl_error_set(err, "shipped data file materials/%s is not embedded in the program",
                   shipped_measured[i].file);
      return VL_EINTERNAL;
    }
    char source[VL_DB_TEXT_MAX];
    snprintf(source, sizeof source, "materials/%s", f->name);
    vl_dma_options o = vl_dma_options_default();
    o.tref_c = 20.0;
    o.weights = VL_PRONY_WEIGHTS_RELATIVE;
    vl_measured m;
    vl_status s = vl_measured_read_text(f->text, strlen(f->text), source, &o, &m, err);
    if (s == VL_OK) {
      vl_db_compound *meta = calloc(1, sizeof *meta);
      if (!meta) {
        vl_measured_free(&m);
        vl_error_set(err, "out of memory");
        return VL_ENOMEM;
      }
      snprintf(meta->name, sizeof meta->name, "%s", shipped_measured[i].name);
      snprintf(meta->class_name, sizeof meta->class_name, "%s", shipped_measured[i].class_name);
      snprintf(meta->description, sizeof meta->description, "%s", shipped_measured[i].description);
      snprintf(meta->source_file, sizeof meta->source_file, "%s", source);
      s = measured_insert(db, meta, &m, "seed the shipped compounds", err);
      free(meta);
      vl_measured_free(&m);
    }
    if (s != VL_OK) {
      /* shipped data that do not import are a bug of this program */
      vl_error_prefix(err, "shipped compound '%s'", shipped_measured[i].name);
      return s == VL_EINPUT ? VL_EINTERNAL : s;
    }
  }
  return VL_OK;
}

void vl_db_compound_fit_free(vl_db_compound_fit *fit) {
  if (!fit) return;
  free(fit->shift_temperature_c);
  free(fit->shift_log10_a_t);
  memset(fit, 0, sizeof *fit);
}

vl_status vl_db_compound_fit_info(vl_db *db, const char *name, vl_db_compound_fit *out,
                                  vl_error *err) {
  vl_status s;
  sqlite3_stmt *st = NULL;
  memset(out, 0, sizeof *out);
  sqlite3_int64 id = find_id(db, "compound", name, &s, err);
  if (id < 0) return s;
  if (id == 0) return not_found(db, "compound", name, err);
  s = prepare(db,
              "SELECT input_kind, weights, n_points, n_isotherms, omega_min_rad_s, "
              "omega_max_rad_s, terms_per_decade, n_grid, rms_rel_storage, max_rel_storage, "
              "rms_rel_loss, max_rel_loss, wlf_rms_log10_a_t FROM compound_fit "
              "WHERE compound_id = ?1",
              &st, err);
  if (s != VL_OK) return s;
  sqlite3_bind_int64(st, 1, id);
  int rc = sqlite3_step(st);
  if (rc == SQLITE_DONE) goto cleanup; /* not fitted: has_fit stays 0 */
  if (rc != SQLITE_ROW) {
    s = db_fail(db, rc, "reading a compound fit", err);
    goto cleanup;
  }
  out->has_fit = 1;
  copy_text(out->input_kind, sizeof out->input_kind, sqlite3_column_text(st, 0));
  copy_text(out->weights, sizeof out->weights, sqlite3_column_text(st, 1));
  out->n_points = (size_t)sqlite3_column_int64(st, 2);
  out->n_isotherms = (size_t)sqlite3_column_int64(st, 3);
  out->omega_min_rad_s = column_real(st, 4);
  out->omega_max_rad_s = column_real(st, 5);
  out->terms_per_decade = column_real(st, 6);
  out->n_grid = (size_t)sqlite3_column_int64(st, 7);
  out->rms_rel_storage = column_real(st, 8);
  out->max_rel_storage = column_real(st, 9);
  out->rms_rel_loss = column_real(st, 10);
  out->max_rel_loss = column_real(st, 11);
  out->wlf_rms_log10_a_t = column_real(st, 12);
  sqlite3_finalize(st);
  st = NULL;
  s = prepare(db,
              "SELECT temperature_c, log10_a_t FROM compound_shift WHERE compound_id = ?1 "
              "ORDER BY temperature_c",
              &st, err);
  if (s != VL_OK) goto cleanup;
  sqlite3_bind_int64(st, 1, id);
  size_t cap = 0;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    if (out->n_shifts == cap) {
      size_t ncap = cap ? 2 * cap : 16;
      double *t = realloc(out->shift_temperature_c, ncap * sizeof *t);
      if (t) out->shift_temperature_c = t;
      double *l = t ? realloc(out->shift_log10_a_t, ncap * sizeof *l) : NULL;
      if (l) out->shift_log10_a_t = l;
      if (!t || !l) {
        vl_error_set(err, "out of memory reading shift factors");
        s = VL_ENOMEM;
        goto cleanup;
      }
      cap = ncap;
    }
    out->shift_temperature_c[out->n_shifts] = column_real(st, 0);
    out->shift_log10_a_t[out->n_shifts] = column_real(st, 1);
    out->n_shifts++;
  }
  if (rc != SQLITE_DONE) s = db_fail(db, rc, "reading shift factors", err);

cleanup:
  sqlite3_finalize(st);
  if (s != VL_OK) vl_db_compound_fit_free(out);
  return s;
}

vl_status vl_db_compound_points(vl_db *db, const char *name, vl_db_measured_point **points,
                                size_t *n, vl_error *err) {
  vl_status s;
  sqlite3_stmt *st = NULL;
  *points = NULL;
  *n = 0;
  sqlite3_int64 id = find_id(db, "compound", name, &s, err);
  if (id < 0) return s;
  if (id == 0) return not_found(db, "compound", name, err);
  s = prepare(db,
              "SELECT frequency_rad_s, temperature_c, coalesce(reduced_frequency_rad_s, "
              "frequency_rad_s), storage_pa, loss_pa, j1_per_pa, j2_per_pa, "
              "coalesce(source_line, 0) FROM compound_measurement WHERE compound_id = ?1 "
              "ORDER BY 3, id",
              &st, err);
  if (s != VL_OK) return s;
  sqlite3_bind_int64(st, 1, id);
  size_t cap = 0;
  int rc;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    if (*n == cap) {
      size_t ncap = cap ? 2 * cap : 256;
      vl_db_measured_point *np = realloc(*points, ncap * sizeof *np);
      if (!np) {
        vl_error_set(err, "out of memory reading measured points");
        s = VL_ENOMEM;
        goto cleanup;
      }
      *points = np;
      cap = ncap;
    }
    vl_db_measured_point *p = &(*points)[*n];
    p->omega_rad_s = column_real(st, 0);
    p->temperature_c = column_real(st, 1);
    p->reduced_omega_rad_s = column_real(st, 2);
    p->storage_pa = column_real(st, 3);
    p->loss_pa = column_real(st, 4);
    if (isnan(p->storage_pa)) { /* stored as compliance: E = 1/(J' - i J'') */
      double j1 = column_real(st, 5), j2 = column_real(st, 6), m2 = j1 * j1 + j2 * j2;
      p->storage_pa = j1 / m2;
      p->loss_pa = j2 / m2;
    }
    p->source_line = (size_t)sqlite3_column_int64(st, 7);
    (*n)++;
  }
  if (rc != SQLITE_DONE) s = db_fail(db, rc, "reading measured points", err);

cleanup:
  sqlite3_finalize(st);
  if (s != VL_OK) {
    free(*points);
    *points = NULL;
    *n = 0;
  }
  return s;
}

vl_status vl_db_compound_remove(vl_db *db, const char *name, vl_error *err) {
  return remove_named(db, "compound", name, err);
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
  vl_status s = prepare(db, sql, &st, err);
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
  if (s == VL_OK && rc != SQLITE_DONE) s = db_fail(db, rc, "listing", err);
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
static vl_status list_all(vl_db *db, const char *table, const char *plural, size_t item_size,
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

/* list_all's reader of one compound, typed for its generic array. */
static vl_status compound_at(vl_db *db, sqlite3_int64 id, void *out, vl_error *err) {
  return compound_by_id(db, id, out, err);
}

vl_status vl_db_compound_list(vl_db *db, vl_db_compound **items, size_t *n, vl_error *err) {
  void *arr = NULL;
  vl_status s = list_all(db, "compound", "compounds", sizeof **items, compound_at, &arr, n, err);
  *items = arr;
  return s;
}

/* ---- surfaces --------------------------------------------------------- */

static vl_status surface_by_id(vl_db *db, sqlite3_int64 id, vl_db_surface *out, vl_error *err) {
  sqlite3_stmt *st = NULL;
  memset(out, 0, sizeof *out);
  vl_status s = prepare(db,
                        "SELECT name, kind, hurst, q0_per_m, q1_per_m, hrms_m, c0_m4, "
                        "derived_hrms_m, derived_rms_slope, description, source_file, created_at, "
                        "(SELECT count(*) FROM surface_point WHERE surface_id = ?1) "
                        "FROM surface WHERE id = ?1",
                        &st, err);
  if (s != VL_OK) return s;
  sqlite3_bind_int64(st, 1, id);
  int rc = sqlite3_step(st);
  if (rc != SQLITE_ROW) {
    s = db_fail(db, rc == SQLITE_DONE ? SQLITE_CORRUPT : rc, "reading a surface", err);
    goto cleanup;
  }
  copy_text(out->name, sizeof out->name, sqlite3_column_text(st, 0));
  const char *kind = (const char *)sqlite3_column_text(st, 1);
  out->kind = kind && !strcmp(kind, "tabulated") ? VL_PSD_TABULATED : VL_PSD_SELF_AFFINE;
  out->hurst = out->kind == VL_PSD_SELF_AFFINE ? column_real(st, 2) : NAN;
  out->q0_per_m = column_real(st, 3);
  out->q1_per_m = column_real(st, 4);
  out->c0_m4 = column_real(st, 6);
  out->hrms_m = column_real(st, 7);
  out->rms_slope = column_real(st, 8);
  copy_text(out->description, sizeof out->description, sqlite3_column_text(st, 9));
  copy_text(out->source_file, sizeof out->source_file, sqlite3_column_text(st, 10));
  copy_text(out->created_at, sizeof out->created_at, sqlite3_column_text(st, 11));
  out->n_points = (size_t)sqlite3_column_int64(st, 12);

cleanup:
  sqlite3_finalize(st);
  return s;
}

vl_status vl_db_surface_info(vl_db *db, const char *name, vl_db_surface *out, vl_error *err) {
  vl_status s;
  sqlite3_int64 id = find_id(db, "surface", name, &s, err);
  if (id < 0) return s;
  if (id == 0) return not_found(db, "surface", name, err);
  return surface_by_id(db, id, out, err);
}

vl_status vl_db_surface_get(vl_db *db, const char *name, vl_psd *out, vl_error *err) {
  sqlite3_stmt *st = NULL;
  memset(out, 0, sizeof *out);
  vl_status s = prepare(db,
                        "SELECT id, kind, hurst, q0_per_m, q1_per_m, hrms_m FROM surface "
                        "WHERE name = ?1",
                        &st, err);
  if (s != VL_OK) return s;
  sqlite3_bind_text(st, 1, name, -1, SQLITE_TRANSIENT);
  int rc = sqlite3_step(st);
  if (rc == SQLITE_DONE) {
    s = not_found(db, "surface", name, err);
  } else if (rc != SQLITE_ROW) {
    s = db_fail(db, rc, "reading a surface", err);
  } else {
    char kind[32];
    copy_text(kind, sizeof kind, sqlite3_column_text(st, 1));
    s = surface_load_psd(db, sqlite3_column_int64(st, 0), kind, column_real(st, 2),
                         column_real(st, 3), column_real(st, 4), column_real(st, 5), out, err);
  }
  sqlite3_finalize(st);
  return s;
}

vl_status vl_db_surface_add(vl_db *db, const char *name, const vl_psd *psd, const char *description,
                            const char *source_file, vl_error *err) {
  vl_status s;
  sqlite3_stmt *st = NULL;
  vl_psd copy;
  memset(&copy, 0, sizeof copy);
  if ((s = vl_db_check_name(name, err)) != VL_OK) return s;
  if ((s = check_text("description", description, err)) != VL_OK) return s;
  if ((s = check_text("source file name", source_file, err)) != VL_OK) return s;
  if (psd->kind == VL_PSD_SELF_AFFINE)
    s = vl_psd_init_self_affine(&copy, psd->hurst, psd->q0, psd->q1, psd->hrms_m, err);
  else if (psd->kind == VL_PSD_TABULATED)
    s = vl_psd_init_tabulated(&copy, psd->n, psd->q, psd->C, err);
  else {
    vl_error_set(err, "unknown PSD kind %d", (int)psd->kind);
    s = VL_EINPUT;
  }
  if (s != VL_OK) return s;
  double c0, hrms, slope;
  if ((s = surface_derive(&copy, &c0, &hrms, &slope, err)) != VL_OK) {
    vl_psd_free(&copy);
    return s;
  }
  int tab = copy.kind == VL_PSD_TABULATED;
  char doing[128];
  snprintf(doing, sizeof doing, "add surface '%s'", name);
  if ((s = tx_begin(db, doing, err)) != VL_OK) goto cleanup;
  if ((s = check_free(db, "surface", name, err)) != VL_OK) goto cleanup;
  s = prepare(db,
              "INSERT INTO surface (name, kind, hurst, q0_per_m, q1_per_m, hrms_m, c0_m4, "
              "derived_hrms_m, derived_rms_slope, description, source_file) "
              "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11)",
              &st, err);
  if (s != VL_OK) goto cleanup;
  sqlite3_bind_text(st, 1, name, -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(st, 2, tab ? "tabulated" : "self-affine", -1, SQLITE_STATIC);
  bind_real(st, 3, tab ? NAN : copy.hurst);
  bind_real(st, 4, copy.q0);
  bind_real(st, 5, copy.q1);
  bind_real(st, 6, tab ? NAN : copy.hrms_m);
  bind_real(st, 7, c0);
  bind_real(st, 8, hrms);
  bind_real(st, 9, slope);
  sqlite3_bind_text(st, 10, description ? description : "", -1, SQLITE_TRANSIENT);
  bind_text_or_null(st, 11, source_file);
  int rc = sqlite3_step(st);
  if (rc != SQLITE_DONE) {
    s = db_fail(db, rc, doing, err);
    goto cleanup;
  }
  sqlite3_int64 id = sqlite3_last_insert_rowid(db->h);
  sqlite3_finalize(st);
  st = NULL;
  if (tab) {
    s = prepare(
        db, "INSERT INTO surface_point (surface_id, idx, q_per_m, c_m4) VALUES (?1, ?2, ?3, ?4)",
        &st, err);
    if (s != VL_OK) goto cleanup;
    for (size_t k = 0; k < copy.n; k++) {
      sqlite3_reset(st);
      sqlite3_bind_int64(st, 1, id);
      sqlite3_bind_int64(st, 2, (sqlite3_int64)k + 1);
      bind_real(st, 3, copy.q[k]);
      bind_real(st, 4, copy.C[k]);
      if ((rc = sqlite3_step(st)) != SQLITE_DONE) {
        s = db_fail(db, rc, doing, err);
        goto cleanup;
      }
    }
    sqlite3_finalize(st);
    st = NULL;
  }
  s = tx_commit(db, doing, err);

cleanup:
  sqlite3_finalize(st);
  if (s != VL_OK) tx_rollback(db);
  vl_psd_free(&copy);
  return s;
}

vl_status vl_db_surface_remove(vl_db *db, const char *name, vl_error *err) {
  return remove_named(db, "surface", name, err);
}

/* list_all's reader of one surface, typed for its generic array. */
static vl_status surface_at(vl_db *db, sqlite3_int64 id, void *out, vl_error *err) {
  return surface_by_id(db, id, out, err);
}

vl_status vl_db_surface_list(vl_db *db, vl_db_surface **items, size_t *n, vl_error *err) {
  void *arr = NULL;
  vl_status s = list_all(db, "surface", "surfaces", sizeof **items, surface_at, &arr, n, err);
  *items = arr;
  return s;
}

/* ---- Persson tables: a cache of vl_persson_build -------------------- */

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
  if (tx_begin(db, "store a Persson table", &ignored) != VL_OK) goto cleanup;
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
  tx_commit(db, "store a Persson table", &ignored); /* rolls back itself on failure */

cleanup:
  sqlite3_finalize(st);
  tx_rollback(db);
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
  sqlite3_int64 id = find_id(db, "surface", name, &s, err);
  if (id < 0) return s;
  if (id == 0) return not_found(db, "surface", name, err);
  *out = persson_load(db, id, n, psd);
  if (*out) {
    if (from_cache) *from_cache = true;
    return VL_OK;
  }
  if ((s = vl_persson_build(psd, n, out, err)) != VL_OK) return s;
  persson_store(db, id, n, *out);
  return VL_OK;
}

/* ---- fluids ----------------------------------------------------------- */

/* The viscosity law in columns col.. (name, B, C, tmin, tmax) of a fluid
 * row into out->law. All NULL is no law; anything else must be a whole,
 * valid law (the schema's CHECKs cannot see across columns): VL_EDB. */
static vl_status fluid_law_read(vl_db *db, sqlite3_stmt *st, int col, vl_db_fluid *out,
                                vl_error *err) {
  vl_viscosity_law *law = &out->law;
  memset(law, 0, sizeof *law);
  int nulls = 0;
  for (int k = 0; k < 5; k++) nulls += sqlite3_column_type(st, col + k) == SQLITE_NULL;
  if (nulls == 5) return VL_OK;
  vl_error why = {{0}};
  vl_status s = VL_EINPUT;
  if (nulls == 0 &&
      vl_viscosity_law_parse((const char *)sqlite3_column_text(st, col), &law->kind, &why) ==
          VL_OK) {
    law->vogel_b_k = column_real(st, col + 1);
    law->vogel_c_k = column_real(st, col + 2);
    law->tmin_c = column_real(st, col + 3);
    law->tmax_c = column_real(st, col + 4);
    s = vl_viscosity_law_validate(law, out->tref_c, &why);
  } else if (nulls != 0) {
    vl_error_set(&why, "some of its columns are NULL");
  }
  if (s == VL_OK) return VL_OK;
  vl_error_set(err, "database %s: stored fluid '%s' has an invalid viscosity law: %s", db->path,
               out->name, why.msg);
  memset(law, 0, sizeof *law);
  return VL_EDB;
}

static vl_status fluid_by_id(vl_db *db, sqlite3_int64 id, vl_db_fluid *out, vl_error *err) {
  sqlite3_stmt *st = NULL;
  memset(out, 0, sizeof *out);
  vl_status s = prepare(db,
                        "SELECT name, viscosity_pa_s, tref_c, description, source_file, created_at, "
                        "viscosity_law, vogel_b_k, vogel_c_k, law_tmin_c, law_tmax_c "
                        "FROM fluid WHERE id = ?1",
                        &st, err);
  if (s != VL_OK) return s;
  sqlite3_bind_int64(st, 1, id);
  int rc = sqlite3_step(st);
  if (rc != SQLITE_ROW) {
    s = db_fail(db, rc == SQLITE_DONE ? SQLITE_CORRUPT : rc, "reading a fluid", err);
  } else {
    copy_text(out->name, sizeof out->name, sqlite3_column_text(st, 0));
    out->viscosity_pa_s = column_real(st, 1);
    out->tref_c = column_real(st, 2);
    copy_text(out->description, sizeof out->description, sqlite3_column_text(st, 3));
    copy_text(out->source_file, sizeof out->source_file, sqlite3_column_text(st, 4));
    copy_text(out->created_at, sizeof out->created_at, sqlite3_column_text(st, 5));
    if (!(isfinite(out->viscosity_pa_s) && out->viscosity_pa_s > 0.0)) {
      vl_error_set(err, "database %s: stored fluid '%s' has an invalid viscosity", db->path,
                   out->name);
      s = VL_EDB;
    } else {
      s = fluid_law_read(db, st, 6, out, err);
    }
  }
  sqlite3_finalize(st);
  return s;
}

vl_status vl_db_fluid_info(vl_db *db, const char *name, vl_db_fluid *out, vl_error *err) {
  vl_status s;
  sqlite3_int64 id = find_id(db, "fluid", name, &s, err);
  if (id < 0) return s;
  if (id == 0) return not_found(db, "fluid", name, err);
  return fluid_by_id(db, id, out, err);
}

vl_status vl_db_fluid_get(vl_db *db, const char *name, double *eta_pa_s, vl_error *err) {
  vl_db_fluid f;
  vl_status s = vl_db_fluid_info(db, name, &f, err);
  if (s == VL_OK) *eta_pa_s = f.viscosity_pa_s;
  return s;
}

vl_status vl_db_fluid_add(vl_db *db, const vl_db_fluid *f, vl_error *err) {
  vl_status s;
  sqlite3_stmt *st = NULL;
  if ((s = vl_db_check_name(f->name, err)) != VL_OK) return s;
  if ((s = check_text("description", f->description, err)) != VL_OK) return s;
  if ((s = check_text("source file name", f->source_file, err)) != VL_OK) return s;
  if (!(isfinite(f->viscosity_pa_s) && f->viscosity_pa_s > 0.0)) {
    vl_error_set(err, "viscosity must be a positive finite number in Pa s (got %g)",
                 f->viscosity_pa_s);
    return VL_EINPUT;
  }
  if (!isfinite(f->tref_c) || f->tref_c < -273.15) {
    vl_error_set(err, "reference temperature must be a finite temperature above -273.15 C (got %g)",
                 f->tref_c);
    return VL_EINPUT;
  }
  if ((s = vl_viscosity_law_validate(&f->law, f->tref_c, err)) != VL_OK) return s;
  int has_law = f->law.kind != VL_VISCOSITY_LAW_NONE;
  char doing[128];
  snprintf(doing, sizeof doing, "add fluid '%s'", f->name);
  if ((s = tx_begin(db, doing, err)) != VL_OK) return s;
  if ((s = check_free(db, "fluid", f->name, err)) != VL_OK) goto cleanup;
  s = prepare(db,
              "INSERT INTO fluid (name, viscosity_pa_s, tref_c, description, source_file, "
              "viscosity_law, vogel_b_k, vogel_c_k, law_tmin_c, law_tmax_c) "
              "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10)",
              &st, err);
  if (s != VL_OK) goto cleanup;
  sqlite3_bind_text(st, 1, f->name, -1, SQLITE_TRANSIENT);
  bind_real(st, 2, f->viscosity_pa_s);
  bind_real(st, 3, f->tref_c);
  sqlite3_bind_text(st, 4, f->description, -1, SQLITE_TRANSIENT);
  bind_text_or_null(st, 5, f->source_file);
  /* no law: every law column NULL (fluid_law_read's "none") */
  bind_text_or_null(st, 6, has_law ? vl_viscosity_law_name(f->law.kind) : NULL);
  bind_real(st, 7, has_law ? f->law.vogel_b_k : NAN);
  bind_real(st, 8, has_law ? f->law.vogel_c_k : NAN);
  bind_real(st, 9, has_law ? f->law.tmin_c : NAN);
  bind_real(st, 10, has_law ? f->law.tmax_c : NAN);
  int rc = sqlite3_step(st);
  if (rc != SQLITE_DONE) {
    s = db_fail(db, rc, doing, err);
    goto cleanup;
  }
  sqlite3_finalize(st);
  st = NULL;
  s = tx_commit(db, doing, err);

cleanup:
  sqlite3_finalize(st);
  if (s != VL_OK) tx_rollback(db);
  return s;
}

vl_status vl_db_fluid_remove(vl_db *db, const char *name, vl_error *err) {
  return remove_named(db, "fluid", name, err);
}

/* list_all's reader of one fluid, typed for its generic array. */
static vl_status fluid_at(vl_db *db, sqlite3_int64 id, void *out, vl_error *err) {
  return fluid_by_id(db, id, out, err);
}

vl_status vl_db_fluid_list(vl_db *db, vl_db_fluid **items, size_t *n, vl_error *err) {
  void *arr = NULL;
  vl_status s = list_all(db, "fluid", "fluids", sizeof **items, fluid_at, &arr, n, err);
  *items = arr;
  return s;
}
