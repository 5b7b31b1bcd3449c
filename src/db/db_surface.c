/* The material database: surfaces (tables surface, surface_point). This
 * file is the one place the derived columns (C0, h_rms, rms slope) are
 * computed, by the vl_psd_* functions, for user surfaces on insert and for
 * shipped ones when a migration seeds them. */
#include "db_internal.h"

#include <stdlib.h>
#include <string.h>

/* ---- derived columns -------------------------------------------------- */

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
  s = vl_dbi_prepare(
      db, "SELECT q_per_m, c_m4 FROM surface_point WHERE surface_id = ?1 ORDER BY idx", &st, err);
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
    s = vl_dbi_fail(db, rc, "reading surface points", err);
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
vl_status vl_dbi_surface_fill_derived(vl_db *db, vl_error *err) {
  sqlite3_stmt *sel = NULL, *upd = NULL;
  sqlite3_int64 *ids = NULL;
  size_t n = 0, cap = 0;
  vl_status s =
      vl_dbi_prepare(db,
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
    s = vl_dbi_fail(db, rc, "deriving surface columns", err);
    goto cleanup;
  }
  sqlite3_finalize(sel);
  sel = NULL;
  s = vl_dbi_prepare(
      db, "SELECT kind, hurst, q0_per_m, q1_per_m, hrms_m, name FROM surface WHERE id = ?1", &sel,
      err);
  if (s != VL_OK) goto cleanup;
  s = vl_dbi_prepare(db,
                     "UPDATE surface SET c0_m4 = ?2, derived_hrms_m = ?3, derived_rms_slope = ?4, "
                     "q0_per_m = ?5, q1_per_m = ?6 WHERE id = ?1",
                     &upd, err);
  if (s != VL_OK) goto cleanup;
  for (size_t i = 0; i < n; i++) {
    sqlite3_reset(sel);
    sqlite3_bind_int64(sel, 1, ids[i]);
    if ((rc = sqlite3_step(sel)) != SQLITE_ROW) {
      s = vl_dbi_fail(db, rc, "deriving surface columns", err);
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
      s = vl_dbi_fail(db, rc, "storing derived surface columns", err);
      goto cleanup;
    }
  }

cleanup:
  sqlite3_finalize(sel);
  sqlite3_finalize(upd);
  free(ids);
  return s;
}

/* ---- reading, adding, removing, listing ------------------------------- */

static vl_status surface_by_id(vl_db *db, sqlite3_int64 id, vl_db_surface *out, vl_error *err) {
  sqlite3_stmt *st = NULL;
  memset(out, 0, sizeof *out);
  vl_status s =
      vl_dbi_prepare(db,
                     "SELECT name, kind, hurst, q0_per_m, q1_per_m, hrms_m, c0_m4, "
                     "derived_hrms_m, derived_rms_slope, description, source_file, created_at, "
                     "(SELECT count(*) FROM surface_point WHERE surface_id = ?1) "
                     "FROM surface WHERE id = ?1",
                     &st, err);
  if (s != VL_OK) return s;
  sqlite3_bind_int64(st, 1, id);
  int rc = sqlite3_step(st);
  if (rc != SQLITE_ROW) {
    s = vl_dbi_fail(db, rc == SQLITE_DONE ? SQLITE_CORRUPT : rc, "reading a surface", err);
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
  sqlite3_int64 id = vl_dbi_find_id(db, "surface", name, &s, err);
  if (id < 0) return s;
  if (id == 0) return vl_dbi_not_found(db, "surface", name, err);
  return surface_by_id(db, id, out, err);
}

vl_status vl_db_surface_get(vl_db *db, const char *name, vl_psd *out, vl_error *err) {
  sqlite3_stmt *st = NULL;
  memset(out, 0, sizeof *out);
  vl_status s = vl_dbi_prepare(db,
                               "SELECT id, kind, hurst, q0_per_m, q1_per_m, hrms_m FROM surface "
                               "WHERE name = ?1",
                               &st, err);
  if (s != VL_OK) return s;
  sqlite3_bind_text(st, 1, name, -1, SQLITE_TRANSIENT);
  int rc = sqlite3_step(st);
  if (rc == SQLITE_DONE) {
    s = vl_dbi_not_found(db, "surface", name, err);
  } else if (rc != SQLITE_ROW) {
    s = vl_dbi_fail(db, rc, "reading a surface", err);
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
  if ((s = vl_dbi_check_text("description", description, err)) != VL_OK) return s;
  if ((s = vl_dbi_check_text("source file name", source_file, err)) != VL_OK) return s;
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
  if ((s = vl_dbi_tx_begin(db, doing, err)) != VL_OK) goto cleanup;
  if ((s = vl_dbi_check_free(db, "surface", name, err)) != VL_OK) goto cleanup;
  s = vl_dbi_prepare(db,
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
    s = vl_dbi_fail(db, rc, doing, err);
    goto cleanup;
  }
  sqlite3_int64 id = sqlite3_last_insert_rowid(db->h);
  sqlite3_finalize(st);
  st = NULL;
  if (tab) {
    s = vl_dbi_prepare(
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
        s = vl_dbi_fail(db, rc, doing, err);
        goto cleanup;
      }
    }
    sqlite3_finalize(st);
    st = NULL;
  }
  s = vl_dbi_tx_commit(db, doing, err);

cleanup:
  sqlite3_finalize(st);
  if (s != VL_OK) vl_dbi_tx_rollback(db);
  vl_psd_free(&copy);
  return s;
}

vl_status vl_db_surface_remove(vl_db *db, const char *name, vl_error *err) {
  return vl_dbi_remove_named(db, "surface", name, err);
}

/* vl_dbi_list_all's reader of one surface, typed for its generic array. */
static vl_status surface_at(vl_db *db, sqlite3_int64 id, void *out, vl_error *err) {
  return surface_by_id(db, id, out, err);
}

vl_status vl_db_surface_list(vl_db *db, vl_db_surface **items, size_t *n, vl_error *err) {
  void *arr = NULL;
  vl_status s =
      vl_dbi_list_all(db, "surface", "surfaces", sizeof **items, surface_at, &arr, n, err);
  *items = arr;
  return s;
}
