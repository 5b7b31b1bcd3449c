/* The material database's plumbing, used by every other file of src/db/:
 * SQLite failures as statuses, statements, and the transaction every write
 * goes through. It calls no other file of src/db/, so that opening
 * (db_open.c), the schema (db_seed.c) and the tables can all lean on it
 * without calling one another in a circle. */
#include "db_internal.h"

#include <errno.h>
#include <string.h>

/* ---- errors and statements -------------------------------------------- */

/* Maps an SQLite failure to a status and one sentence naming the file.
 * Every write is one transaction that SQLite rolls back when it fails (or,
 * after a crash, on the next open), so a failure never changes the stored
 * content: the messages say so. */
vl_status vl_dbi_fail(const vl_db *db, int rc, const char *doing, vl_error *err) {
  const char *msg = db && db->h ? sqlite3_errmsg(db->h) : sqlite3_errstr(rc);
  const char *path = db ? db->path : "?";
  /* the errno behind an I/O failure says more than "disk I/O error" */
  int sys = db && db->h ? sqlite3_system_errno(db->h) : 0;
  if ((rc & 0xff) == SQLITE_FULL ||
      ((rc & 0xff) == SQLITE_IOERR && (sys == ENOSPC || sys == EFBIG || sys == EDQUOT))) {
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

vl_status vl_dbi_prepare(vl_db *db, const char *sql, sqlite3_stmt **st, vl_error *err) {
  int rc = sqlite3_prepare_v2(db->h, sql, -1, st, NULL);
  if (rc != SQLITE_OK) {
    *st = NULL;
    return vl_dbi_fail(db, rc, "preparing a query", err);
  }
  return VL_OK;
}

vl_status vl_dbi_exec(vl_db *db, const char *sql, const char *doing, vl_error *err) {
  int rc = sqlite3_exec(db->h, sql, NULL, NULL, NULL);
  return rc == SQLITE_OK ? VL_OK : vl_dbi_fail(db, rc, doing, err);
}

/* ---- transactions ----------------------------------------------------- */

/* Every write is one BEGIN IMMEDIATE ... COMMIT: the write lock is taken up
 * front so that a concurrent writer makes us wait (busy timeout) rather than
 * fail half-way, and ROLLBACK restores the file exactly. */
vl_status vl_dbi_tx_begin(vl_db *db, const char *doing, vl_error *err) {
  if (db->readonly) {
    vl_error_set(err,
                 "database %s is read-only (no write permission): cannot %s; nothing was changed",
                 db->path, doing);
    return VL_EDB;
  }
  return vl_dbi_exec(db, "BEGIN IMMEDIATE", doing, err);
}

void vl_dbi_tx_rollback(vl_db *db) {
  if (!sqlite3_get_autocommit(db->h)) sqlite3_exec(db->h, "ROLLBACK", NULL, NULL, NULL);
}

vl_status vl_dbi_tx_commit(vl_db *db, const char *doing, vl_error *err) {
  vl_status s = vl_dbi_exec(db, "COMMIT", doing, err);
  if (s != VL_OK) vl_dbi_tx_rollback(db);
  return s;
}
