/* The material database: fluids (table fluid), a viscosity and an optional
 * temperature law. */
#include "db_internal.h"
#include "fluid_internal.h"

#include <string.h>

/* The viscosity law in columns col.. (name, B, C, tmin, tmax) of a fluid
 * row into out->law. All NULL is no law; anything else must be a whole,
 * valid law (the schema's CHECKs cannot see across columns): VL_EDB. */
static vl_status fluid_law_read(vl_db *db, sqlite3_stmt *st, int col, vl_db_fluid *out,
                                vl_error *err) {
  vl_viscosity_law *law = &out->law;
  memset(law, 0, sizeof *law);
  int nulls = 0;
  for (int k = 0; k < 5; k++)
    nulls += sqlite3_column_type(st, col + k) == SQLITE_NULL;
  if (nulls == 5) return VL_OK;
  vl_error why = {{0}};
  vl_status s = VL_EINPUT;
  if (nulls == 0 && vl_viscosity_law_parse((const char *)sqlite3_column_text(st, col), &law->kind,
                                           &why) == VL_OK) {
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
  vl_status s =
      vl_dbi_prepare(db,
                     "SELECT name, viscosity_pa_s, tref_c, description, source_file, created_at, "
                     "viscosity_law, vogel_b_k, vogel_c_k, law_tmin_c, law_tmax_c "
                     "FROM fluid WHERE id = ?1",
                     &st, err);
  if (s != VL_OK) return s;
  sqlite3_bind_int64(st, 1, id);
  int rc = sqlite3_step(st);
  if (rc != SQLITE_ROW) {
    s = vl_dbi_fail(db, rc == SQLITE_DONE ? SQLITE_CORRUPT : rc, "reading a fluid", err);
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
  sqlite3_int64 id = vl_dbi_find_id(db, "fluid", name, &s, err);
  if (id < 0) return s;
  if (id == 0) return vl_dbi_not_found(db, "fluid", name, err);
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
  if ((s = vl_dbi_check_text("description", f->description, err)) != VL_OK) return s;
  if ((s = vl_dbi_check_text("source file name", f->source_file, err)) != VL_OK) return s;
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
  if ((s = vl_dbi_tx_begin(db, doing, err)) != VL_OK) return s;
  if ((s = vl_dbi_check_free(db, "fluid", f->name, err)) != VL_OK) goto cleanup;
  s = vl_dbi_prepare(db,
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
    s = vl_dbi_fail(db, rc, doing, err);
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

vl_status vl_db_fluid_remove(vl_db *db, const char *name, vl_error *err) {
  return vl_dbi_remove_named(db, "fluid", name, err);
}

/* vl_dbi_list_all's reader of one fluid, typed for its generic array. */
static vl_status fluid_at(vl_db *db, sqlite3_int64 id, void *out, vl_error *err) {
  return fluid_by_id(db, id, out, err);
}

vl_status vl_db_fluid_list(vl_db *db, vl_db_fluid **items, size_t *n, vl_error *err) {
  void *arr = NULL;
  vl_status s = vl_dbi_list_all(db, "fluid", "fluids", sizeof **items, fluid_at, &arr, n, err);
  *items = arr;
  return s;
}
