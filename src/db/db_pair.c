/* The material database: pairs (table pair, 0006_pairs.sql), a compound,
 * a surface and a fluid with the law of the shear stress in their real
 * contact area and its provenance. */
#include "db_internal.h"
#include "shear_law_private.h"

#include <stdlib.h>
#include <string.h>

#define PAIR_COLUMNS                                                                               \
  "c.name, s.name, f.name, p.law, p.p1, p.p2, p.p3, p.ci95_1, p.ci95_2, p.ci95_3, p.tref_c, "      \
  "p.eta_ref_pa_s, p.source, p.description, p.measured_file, p.measured_fingerprint, "             \
  "p.n_points, p.load_n_per_m, p.radius_m, p.temperature_c, p.rms_log10_mu, p.created_at "         \
  "FROM pair p JOIN compound c ON c.id = p.compound_id JOIN surface s ON s.id = p.surface_id "     \
  "JOIN fluid f ON f.id = p.fluid_id "

/* One row of PAIR_COLUMNS into out; a law that fails its checks is VL_EDB. */
static vl_status pair_read(vl_db *db, sqlite3_stmt *st, vl_db_pair *out, vl_error *err) {
  memset(out, 0, sizeof *out);
  copy_text(out->compound, sizeof out->compound, sqlite3_column_text(st, 0));
  copy_text(out->surface, sizeof out->surface, sqlite3_column_text(st, 1));
  copy_text(out->fluid, sizeof out->fluid, sqlite3_column_text(st, 2));
  vl_error why = {{0}};
  vl_status s = vl_shear_law_parse((const char *)sqlite3_column_text(st, 3), &out->law.kind, &why);
  for (int k = 0; k < VL_SHEAR_LAW_MAX_PARAMS; k++) {
    out->law.p[k] = column_real(st, 4 + k);
    out->ci95[k] = column_real(st, 7 + k);
  }
  out->law.tref_c = column_real(st, 10);
  out->law.eta_ref_pa_s = column_real(st, 11);
  copy_text(out->source, sizeof out->source, sqlite3_column_text(st, 12));
  copy_text(out->description, sizeof out->description, sqlite3_column_text(st, 13));
  copy_text(out->measured_file, sizeof out->measured_file, sqlite3_column_text(st, 14));
  copy_text(out->measured_fingerprint, sizeof out->measured_fingerprint,
            sqlite3_column_text(st, 15));
  out->n_points = (size_t)sqlite3_column_int64(st, 16);
  out->load_n_per_m = column_real(st, 17);
  out->radius_m = column_real(st, 18);
  out->temperature_c = column_real(st, 19);
  out->rms_log10_mu = column_real(st, 20);
  copy_text(out->created_at, sizeof out->created_at, sqlite3_column_text(st, 21));
  if (s == VL_OK) s = vl_shear_law_validate(&out->law, &why);
  if (s == VL_OK) return VL_OK;
  vl_error_set(err, "database %s: stored pair (%s, %s, %s) has an invalid law: %s", db->path,
               out->compound, out->surface, out->fluid, why.msg);
  return VL_EDB;
}

/* Row ids of the three materials into ids; a missing one is VL_ENOTFOUND
 * with its did-you-mean. */
static vl_status material_ids(vl_db *db, const char *const names[3], sqlite3_int64 ids[3],
                              vl_error *err) {
  static const char *const tables[3] = {"compound", "surface", "fluid"};
  for (int k = 0; k < 3; k++) {
    vl_status s;
    if ((s = vl_db_check_name(names[k], err)) != VL_OK) {
      vl_error_prefix(err, "%s", tables[k]);
      return s;
    }
    ids[k] = vl_dbi_find_id(db, tables[k], names[k], &s, err);
    if (ids[k] < 0) return s;
    if (ids[k] == 0) return vl_dbi_not_found(db, tables[k], names[k], err);
  }
  return VL_OK;
}

/* VL_ENOTFOUND for a pair whose materials exist: names the pairs the
 * compound has, the closest thing to a "did you mean". */
static vl_status pair_not_found(vl_db *db, const char *const names[3], sqlite3_int64 compound_id,
                                vl_error *err) {
  char hint[VL_ERROR_MAX / 2] = "";
  size_t len = 0, count = 0;
  sqlite3_stmt *st = NULL;
  if (sqlite3_prepare_v2(db->h,
                         "SELECT s.name, f.name FROM pair p JOIN surface s ON s.id = p.surface_id "
                         "JOIN fluid f ON f.id = p.fluid_id WHERE p.compound_id = ?1 "
                         "ORDER BY s.name, f.name",
                         -1, &st, NULL) == SQLITE_OK) {
    sqlite3_bind_int64(st, 1, compound_id);
    while (sqlite3_step(st) == SQLITE_ROW && count < 3) {
      int w = snprintf(hint + len, sizeof hint - len, "%s%s in %s", count ? ", " : "",
                       (const char *)sqlite3_column_text(st, 0),
                       (const char *)sqlite3_column_text(st, 1));
      if (w < 0 || (size_t)w >= sizeof hint - len) break;
      len += (size_t)w, count++;
    }
  }
  sqlite3_finalize(st);
  if (count)
    vl_error_set(err,
                 "no pair of compound '%s' on surface '%s' in fluid '%s' in %s (compound '%s' has "
                 "pairs on %s)",
                 names[0], names[1], names[2], db->path, names[0], hint);
  else
    vl_error_set(err, "no pair of compound '%s' on surface '%s' in fluid '%s' in %s", names[0],
                 names[1], names[2], db->path);
  return VL_ENOTFOUND;
}

vl_status vl_db_pair_get(vl_db *db, const char *compound, const char *surface, const char *fluid,
                         vl_db_pair *out, bool *found, vl_error *err) {
  const char *const names[3] = {compound, surface, fluid};
  sqlite3_int64 ids[3];
  sqlite3_stmt *st = NULL;
  if (found) *found = false;
  memset(out, 0, sizeof *out);
  vl_status s = material_ids(db, names, ids, err);
  if (s != VL_OK) return s;
  s = vl_dbi_prepare(db,
                     "SELECT " PAIR_COLUMNS
                     "WHERE p.compound_id = ?1 AND p.surface_id = ?2 AND p.fluid_id = ?3",
                     &st, err);
  if (s != VL_OK) return s;
  for (int k = 0; k < 3; k++)
    sqlite3_bind_int64(st, k + 1, ids[k]);
  int rc = sqlite3_step(st);
  if (rc == SQLITE_ROW) {
    s = pair_read(db, st, out, err);
    if (s == VL_OK && found) *found = true;
  } else if (rc == SQLITE_DONE) {
    s = found ? VL_OK : pair_not_found(db, names, ids[0], err);
  } else {
    s = vl_dbi_fail(db, rc, "reading a pair", err);
  }
  sqlite3_finalize(st);
  return s;
}

/* Checks of a pair before anything is written. */
static vl_status pair_check(const vl_db_pair *p, int *calibrated, vl_error *err) {
  vl_status s;
  if ((s = vl_shear_law_validate(&p->law, err)) != VL_OK) return s;
  if ((s = vl_dbi_check_text("description", p->description, err)) != VL_OK) return s;
  if ((s = vl_dbi_check_text("measured file name", p->measured_file, err)) != VL_OK) return s;
  *calibrated = !strcmp(p->source, VL_DB_SOURCE_CALIBRATED);
  if (!*calibrated && strcmp(p->source, VL_DB_SOURCE_TYPED)) {
    vl_error_set(err, "pair source must be '%s' or '%s' (got '%.20s')", VL_DB_SOURCE_TYPED,
                 VL_DB_SOURCE_CALIBRATED, p->source);
    return VL_EINPUT;
  }
  if (*calibrated && (strncmp(p->measured_fingerprint, "fnv1a64:", 8) || p->n_points == 0 ||
                      !(p->load_n_per_m > 0.0 && isfinite(p->load_n_per_m)) ||
                      !(p->radius_m > 0.0 && isfinite(p->radius_m)) ||
                      !(p->rms_log10_mu >= 0.0 && isfinite(p->rms_log10_mu)))) {
    vl_error_set(err, "a calibrated pair needs the measured file's fingerprint, its points, the "
                      "load, radius and the fit's rms misfit");
    return VL_EINPUT;
  }
  return VL_OK;
}

static vl_status pair_insert(vl_db *db, const vl_db_pair *p, const sqlite3_int64 ids[3],
                             int calibrated, const char *doing, vl_error *err) {
  sqlite3_stmt *st = NULL;
  vl_status s = vl_dbi_prepare(
      db,
      "INSERT INTO pair (compound_id, surface_id, fluid_id, law, p1, p2, p3, ci95_1, ci95_2, "
      "ci95_3, tref_c, eta_ref_pa_s, source, description, measured_file, measured_fingerprint, "
      "n_points, load_n_per_m, radius_m, temperature_c, rms_log10_mu) VALUES (?1, ?2, ?3, ?4, "
      "?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16, ?17, ?18, ?19, ?20, ?21)",
      &st, err);
  if (s != VL_OK) return s;
  size_t np = vl_shear_law_n_params(p->law.kind);
  for (int k = 0; k < 3; k++)
    sqlite3_bind_int64(st, k + 1, ids[k]);
  sqlite3_bind_text(st, 4, vl_shear_law_name(p->law.kind), -1, SQLITE_STATIC);
  for (size_t k = 0; k < VL_SHEAR_LAW_MAX_PARAMS; k++) {
    bind_real(st, 5 + (int)k, k < np ? p->law.p[k] : NAN);
    bind_real(st, 8 + (int)k, k < np ? p->ci95[k] : NAN);
  }
  bind_real(st, 11, p->law.tref_c);
  bind_real(st, 12, p->law.eta_ref_pa_s);
  sqlite3_bind_text(st, 13, p->source, -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(st, 14, p->description, -1, SQLITE_TRANSIENT);
  bind_text_or_null(st, 15, calibrated ? p->measured_file : NULL);
  bind_text_or_null(st, 16, calibrated ? p->measured_fingerprint : NULL);
  if (calibrated) sqlite3_bind_int64(st, 17, (sqlite3_int64)p->n_points);
  bind_real(st, 18, calibrated ? p->load_n_per_m : NAN);
  bind_real(st, 19, calibrated ? p->radius_m : NAN);
  bind_real(st, 20, calibrated ? p->temperature_c : NAN);
  bind_real(st, 21, calibrated ? p->rms_log10_mu : NAN);
  int rc = sqlite3_step(st);
  if (rc == SQLITE_CONSTRAINT_UNIQUE) {
    vl_error_set(err,
                 "a pair of compound '%s' on surface '%s' in fluid '%s' already exists in %s "
                 "(remove it first)",
                 p->compound, p->surface, p->fluid, db->path);
    s = VL_EEXIST;
  } else if (rc != SQLITE_DONE) {
    s = vl_dbi_fail(db, rc, doing, err);
  }
  sqlite3_finalize(st);
  return s;
}

vl_status vl_db_pair_add(vl_db *db, const vl_db_pair *p, vl_error *err) {
  int calibrated = 0;
  vl_status s = pair_check(p, &calibrated, err);
  if (s != VL_OK) return s;
  char doing[256];
  snprintf(doing, sizeof doing, "add the pair of '%s', '%s', '%s'", p->compound, p->surface,
           p->fluid);
  if ((s = vl_dbi_tx_begin(db, doing, err)) != VL_OK) return s;
  const char *const names[3] = {p->compound, p->surface, p->fluid};
  sqlite3_int64 ids[3];
  if ((s = material_ids(db, names, ids, err)) == VL_OK &&
      (s = pair_insert(db, p, ids, calibrated, doing, err)) == VL_OK)
    s = vl_dbi_tx_commit(db, doing, err);
  if (s != VL_OK) vl_dbi_tx_rollback(db);
  return s;
}

vl_status vl_db_pair_remove(vl_db *db, const char *compound, const char *surface, const char *fluid,
                            vl_error *err) {
  const char *const names[3] = {compound, surface, fluid};
  sqlite3_int64 ids[3];
  sqlite3_stmt *st = NULL;
  char doing[256];
  snprintf(doing, sizeof doing, "remove the pair of '%.60s', '%.60s', '%.60s'", compound, surface,
           fluid);
  vl_status s = vl_dbi_tx_begin(db, doing, err);
  if (s != VL_OK) return s;
  if ((s = material_ids(db, names, ids, err)) != VL_OK) goto cleanup;
  s = vl_dbi_prepare(
      db, "DELETE FROM pair WHERE compound_id = ?1 AND surface_id = ?2 AND fluid_id = ?3", &st,
      err);
  if (s != VL_OK) goto cleanup;
  for (int k = 0; k < 3; k++)
    sqlite3_bind_int64(st, k + 1, ids[k]);
  int rc = sqlite3_step(st);
  if (rc != SQLITE_DONE)
    s = vl_dbi_fail(db, rc, doing, err);
  else if (sqlite3_changes(db->h) == 0)
    s = pair_not_found(db, names, ids[0], err);
  sqlite3_finalize(st);
  st = NULL;
  if (s == VL_OK) s = vl_dbi_tx_commit(db, doing, err);

cleanup:
  if (s != VL_OK) vl_dbi_tx_rollback(db);
  return s;
}

vl_status vl_db_pair_list(vl_db *db, vl_db_pair **items, size_t *n, vl_error *err) {
  sqlite3_stmt *st = NULL;
  vl_db_pair *arr = NULL;
  size_t cap = 0, count = 0;
  *items = NULL;
  *n = 0;
  vl_status s =
      vl_dbi_prepare(db, "SELECT " PAIR_COLUMNS "ORDER BY c.name, s.name, f.name", &st, err);
  if (s != VL_OK) return s;
  int rc;
  while (s == VL_OK && (rc = sqlite3_step(st)) == SQLITE_ROW) {
    if (count == cap) {
      size_t ncap = cap ? 2 * cap : 8;
      vl_db_pair *na = realloc(arr, ncap * sizeof *na);
      if (!na) {
        vl_error_set(err, "out of memory listing pairs");
        s = VL_ENOMEM;
        break;
      }
      arr = na, cap = ncap;
    }
    s = pair_read(db, st, &arr[count], err);
    if (s == VL_OK) count++;
  }
  if (s == VL_OK && rc != SQLITE_DONE) s = vl_dbi_fail(db, rc, "listing pairs", err);
  sqlite3_finalize(st);
  if (s != VL_OK) {
    free(arr);
    return s;
  }
  *items = count ? arr : (free(arr), NULL);
  *n = count;
  return VL_OK;
}

vl_status vl_db_pair_count(vl_db *db, const char *table, const char *name, size_t *n,
                           vl_error *err) {
  const char *sql = !strcmp(table, "compound")
                        ? "SELECT count(*) FROM pair p JOIN compound m ON m.id = p.compound_id "
                          "WHERE m.name = ?1"
                    : !strcmp(table, "surface")
                        ? "SELECT count(*) FROM pair p JOIN surface m ON m.id = p.surface_id "
                          "WHERE m.name = ?1"
                    : !strcmp(table, "fluid")
                        ? "SELECT count(*) FROM pair p JOIN fluid m ON m.id = p.fluid_id "
                          "WHERE m.name = ?1"
                        : NULL;
  *n = 0;
  if (!sql) {
    vl_error_set(err, "pairs: no kind of material '%s'", table);
    return VL_EINPUT;
  }
  sqlite3_stmt *st = NULL;
  vl_status s = vl_dbi_prepare(db, sql, &st, err);
  if (s != VL_OK) return s;
  sqlite3_bind_text(st, 1, name, -1, SQLITE_TRANSIENT);
  int rc = sqlite3_step(st);
  if (rc == SQLITE_ROW)
    *n = (size_t)sqlite3_column_int64(st, 0);
  else
    s = vl_dbi_fail(db, rc, "counting pairs", err);
  sqlite3_finalize(st);
  return s;
}
