/* The material database: opening a file (and the default path) and
 * closing it. Opening brings the file to the current schema, creating and
 * seeding a new one (vl_dbi_migrate, db_seed.c); the tables themselves are
 * read and written in db_compound.c, db_surface.c, db_persson.c and
 * db_fluid.c. */
#define _POSIX_C_SOURCE 200809L

#include "database_internal.h"
#include "db_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

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

/* vl_db_open and vl_db_open_readonly: readonly forces a read-only
 * connection to an existing file (nothing is created or migrated). */
static vl_status db_open(const char *path, bool readonly, vl_db **out, vl_error *err) {
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
  if (readonly && stat(path, &sb) != 0) {
    vl_error_set(err, "cannot open database %s read-only: %s", path, strerror(errno));
    s = VL_EIO;
    goto fail;
  }
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
    db->readonly =
        readonly || (sb.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 || access(path, W_OK) != 0;
  }

  int flags = db->readonly ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE;
  int rc = sqlite3_open_v2(path, &db->h, flags, NULL);
  if (rc != SQLITE_OK) {
    s = vl_dbi_fail(db, rc, "opening", err);
    goto fail;
  }
  sqlite3_extended_result_codes(db->h, 1);
  sqlite3_busy_timeout(db->h, BUSY_TIMEOUT_MS);
  /* Defensive mode: no writable_schema tricks from a hostile file. */
  sqlite3_db_config(db->h, SQLITE_DBCONFIG_DEFENSIVE, 1, NULL);
  if ((s = vl_dbi_exec(db, "PRAGMA foreign_keys = ON", "enabling foreign keys", err)) != VL_OK)
    goto fail;
  if ((s = vl_dbi_migrate(db, err)) != VL_OK) goto fail;
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

vl_status vl_db_open(const char *path, vl_db **out, vl_error *err) {
  return db_open(path, false, out, err);
}

vl_status vl_db_open_readonly(const char *path, vl_db **out, vl_error *err) {
  return db_open(path, true, out, err);
}
