/* The material database: opening a file (and the default path), SQLite
 * failures as statuses, statements and transactions, the schema
 * migrations of the embedded materials/NNNN_*.sql, and the seeding of a new
 * file with the shipped materials (seed_*.sql and the measured-style data
 * files *.csv). The tables themselves are read and written in
 * db_compound.c, db_surface.c, db_persson.c and db_fluid.c. */
#define _POSIX_C_SOURCE 200809L

#include "database_internal.h"
#include "db_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* PRAGMA application_id of our files: "VLUB". Set by 0001_schema.sql; lets
 * us refuse another program's SQLite file instead of migrating it. */
#define VL_APPLICATION_ID 0x564C5542

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

static vl_status exec(vl_db *db, const char *sql, const char *doing, vl_error *err) {
  int rc = sqlite3_exec(db->h, sql, NULL, NULL, NULL);
  return rc == SQLITE_OK ? VL_OK : vl_dbi_fail(db, rc, doing, err);
}

/* Reads an integer PRAGMA (user_version, application_id). */
static vl_status pragma_int(vl_db *db, const char *sql, int *out, vl_error *err) {
  sqlite3_stmt *st = NULL;
  vl_status s = vl_dbi_prepare(db, sql, &st, err);
  if (s != VL_OK) return s;
  int rc = sqlite3_step(st);
  if (rc == SQLITE_ROW) {
    *out = sqlite3_column_int(st, 0);
    s = VL_OK;
  } else {
    s = vl_dbi_fail(db, rc, "reading the schema version", err);
  }
  sqlite3_finalize(st);
  return s;
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
  return exec(db, "BEGIN IMMEDIATE", doing, err);
}

void vl_dbi_tx_rollback(vl_db *db) {
  if (!sqlite3_get_autocommit(db->h)) sqlite3_exec(db->h, "ROLLBACK", NULL, NULL, NULL);
}

vl_status vl_dbi_tx_commit(vl_db *db, const char *doing, vl_error *err) {
  vl_status s = exec(db, "COMMIT", doing, err);
  if (s != VL_OK) vl_dbi_tx_rollback(db);
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

int vl_db_schema_version(void) {
  int latest = 0;
  for (const struct vl_embedded_file *f = vl_embedded_materials; f->name; f++) {
    int v = migration_number(f->name);
    if (v > latest) latest = v;
  }
  return latest;
}

/* Compounds shipped as measured-style data files in materials/, registered
 * in every new database through the import path of user data
 * (vl_measured_read_text, then vl_dbi_measured_insert) inside the creating
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
      s = vl_dbi_measured_insert(db, meta, &m, "seed the shipped compounds", err);
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
  vl_status s = vl_dbi_fail(db, rc, "applying an embedded material file", err);
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
    if ((s = vl_dbi_tx_begin(db, "upgrade the schema", err)) != VL_OK) return s;
    /* Re-read under the write lock: another process may have migrated. */
    int now = 0;
    if ((s = pragma_int(db, "PRAGMA user_version", &now, err)) != VL_OK) goto fail;
    if (now >= target) {
      vl_dbi_tx_rollback(db);
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
    if ((s = vl_dbi_surface_fill_derived(db, err)) != VL_OK) goto fail;
    if ((s = set_version(db, fresh ? latest : target, err)) != VL_OK) goto fail;
    if ((s = vl_dbi_tx_commit(db, "upgrade the schema", err)) != VL_OK) return s;
  }
  return VL_OK;

fail:
  vl_dbi_tx_rollback(db);
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

vl_status vl_db_open(const char *path, vl_db **out, vl_error *err) {
  return db_open(path, false, out, err);
}

vl_status vl_db_open_readonly(const char *path, vl_db **out, vl_error *err) {
  return db_open(path, true, out, err);
}
