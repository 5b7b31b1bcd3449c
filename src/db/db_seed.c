/* The material database's schema: a new file is created from the embedded
 * materials (every migration materials/NNNN_*.sql, the seeds seed_*.sql and
 * the shipped measured compounds *.csv, in one transaction), an older one
 * is brought up to date one migration at a time (with the shipped measured
 * compounds it lacks, see shipped_measured). Both are the same loop
 * (vl_dbi_migrate), which db_open.c runs on every open; the rows are
 * written through db_compound.c and db_surface.c, names looked up through
 * db_names.c, the statements and transactions through db_sql.c, none of
 * which calls back here. */
#include "db_internal.h"
#include "dma_private.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

/* PRAGMA application_id of our files: "VLUB". Set by 0001_schema.sql; lets
 * us refuse another program's SQLite file instead of migrating it. */
#define VL_APPLICATION_ID 0x564C5542

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
 * weights: the data obey Kramers-Kronig, so E'' is fitted to its noise.
 *
 * SQL cannot import them, so a migration cannot insert them as it inserts
 * the shipped rows a database created before them lacks (0007, 0008):
 * `migration` names the one that gives them to such a database here, each
 * unless a compound of its name exists, in the transaction of the last
 * migration the file gets. Both came with schema 2; the databases of
 * schema 1 lack them (and keep lacking them when a program of schema 2-7
 * migrated them) and get them with 0008. */
static const struct {
  const char *file, *name, *class_name, *description;
  int migration;
} shipped_measured[] = {
    {"sbr-unfilled-synthetic.csv", "sbr-unfilled", "unfilled",
     "SYNTHETIC stand-in for an unfilled SBR, not a measurement: Havriliak-Negami modulus "
     "(E0 2 MPa, Einf 2 GPa, alpha 0.60, beta 0.35, tau 2.5 ms) with WLF (C1 12.57, C2 71.6 K at "
     "20 C), DMA-like sampling 0-100 C, 0.1-100 Hz, 1 % noise (scripts/gen_synthetic_dma.py), "
     "imported and fitted like user data; rolling number near Scaraggi & Persson's "
     "Q_unfilled = 3e-4 (Fig. 15)",
     8},
    {"sbr-filled-synthetic.csv", "sbr-filled", "filled",
     "SYNTHETIC stand-in for a carbon-black filled SBR, not a measurement: Havriliak-Negami "
     "modulus (E0 8 MPa, Einf 3 GPa, alpha 0.50, beta 0.35, tau 2.8 ms) with WLF (C1 12.57, "
     "C2 71.6 K at 20 C), DMA-like sampling 0-100 C, 0.1-100 Hz, 1 % noise "
     "(scripts/gen_synthetic_dma.py), imported and fitted like user data; rolling number near "
     "Scaraggi & Persson's Q_filled = 3e-5 (Fig. 16)",
     8},
};

/* Whether the shipped compound i goes into a file that had schema version
 * `from` (0: a new one): every one into a new file; into an older one when
 * it crosses the compound's migration and the name is free (a user's own
 * compound of that name is kept). */
static vl_status measured_wanted(vl_db *db, size_t i, int from, bool *wanted, vl_error *err) {
  *wanted = from == 0;
  if (from == 0 || from >= shipped_measured[i].migration) return VL_OK;
  vl_status s;
  sqlite3_int64 id = vl_dbi_find_id(db, "compound", shipped_measured[i].name, &s, err);
  *wanted = id == 0;
  return s;
}

/* Registers the shipped measured compounds that measured_wanted picks. */
static vl_status seed_measured(vl_db *db, int from, vl_error *err) {
  for (size_t i = 0; i < sizeof shipped_measured / sizeof *shipped_measured; i++) {
    bool wanted = false;
    vl_status w = measured_wanted(db, i, from, &wanted, err);
    if (w != VL_OK) return w;
    if (!wanted) continue;
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
  return vl_dbi_exec(db, sql, "setting the schema version", err);
}

/* Brings the file to the latest schema. A new (empty) file gets every
 * migration and every seed in one transaction; an older one gets each
 * missing migration in its own transaction. A newer, foreign or corrupt
 * file is refused before anything is written. */
vl_status vl_dbi_migrate(vl_db *db, vl_error *err) {
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
      if ((s = seed_measured(db, 0, err)) != VL_OK) goto fail;
    } else if (target == latest && (s = seed_measured(db, version, err)) != VL_OK) {
      goto fail; /* at the latest schema, which the import code writes, as in a new file */
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
