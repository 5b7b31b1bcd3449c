/* The material database: compounds (tables compound, compound_prony) with,
 * for those imported from measured data, their points
 * (compound_measurement), shift factors (compound_shift) and fit report
 * (compound_fit). */
#include "db_internal.h"
#include "dma_private.h"
#include "rheology_internal.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

/* ---- compounds -------------------------------------------------------- */

static const char *const compound_classes[] = {"model", "filled", "unfilled", "other"};

/* Loads the compound row `id` (metadata and terms). */
static vl_status compound_by_id(vl_db *db, sqlite3_int64 id, vl_db_compound *out, vl_error *err) {
  sqlite3_stmt *st = NULL;
  memset(out, 0, sizeof *out);
  vl_status s =
      vl_dbi_prepare(db,
                     "SELECT name, class, description, nu, e_inf_pa, tref_c, wlf_c1, wlf_c2_k, "
                     "source_file, method, fit_rms_error, created_at FROM compound WHERE id = ?1",
                     &st, err);
  if (s != VL_OK) return s;
  sqlite3_bind_int64(st, 1, id);
  int rc = sqlite3_step(st);
  if (rc != SQLITE_ROW) {
    s = vl_dbi_fail(db, rc == SQLITE_DONE ? SQLITE_CORRUPT : rc, "reading a compound", err);
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

  s = vl_dbi_prepare(db, "SELECT A, tau_s FROM compound_prony WHERE compound_id = ?1 ORDER BY idx",
                     &st, err);
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
    s = vl_dbi_fail(db, rc, "reading Prony terms", err);
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
  sqlite3_int64 id = vl_dbi_find_id(db, "compound", name, &s, err);
  if (id < 0) return s;
  if (id == 0) return vl_dbi_not_found(db, "compound", name, err);
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
  if ((s = vl_dbi_check_text("description", c->description, err)) != VL_OK) return s;
  if ((s = vl_dbi_check_text("source file name", c->source_file, err)) != VL_OK) return s;
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
  if ((s = vl_dbi_check_free(db, "compound", c->name, err)) != VL_OK) return s;
  s = vl_dbi_prepare(
      db,
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
    s = vl_dbi_fail(db, rc, doing, err);
    goto cleanup;
  }
  *id = sqlite3_last_insert_rowid(db->h);
  sqlite3_finalize(st);
  st = NULL;
  s = vl_dbi_prepare(
      db, "INSERT INTO compound_prony (compound_id, idx, A, tau_s) VALUES (?1, ?2, ?3, ?4)", &st,
      err);
  if (s != VL_OK) goto cleanup;
  for (size_t i = 0; i < c->prony.n_terms; i++) {
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, *id);
    sqlite3_bind_int64(st, 2, (sqlite3_int64)i + 1);
    bind_real(st, 3, c->prony.A[i]);
    bind_real(st, 4, c->prony.tau_s[i]);
    if ((rc = sqlite3_step(st)) != SQLITE_DONE) {
      s = vl_dbi_fail(db, rc, doing, err);
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
  if ((s = vl_dbi_tx_begin(db, doing, err)) != VL_OK) return s;
  sqlite3_int64 id;
  if ((s = compound_insert(db, c, doing, &id, err)) == VL_OK) s = vl_dbi_tx_commit(db, doing, err);
  if (s != VL_OK) vl_dbi_tx_rollback(db);
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

/* Steps of vl_dbi_measured_insert, each for the compound row id: the
 * points of m (source_file names their file), its shift factors, its fit
 * report. */
static vl_status measured_insert_points(vl_db *db, sqlite3_int64 id, const vl_measured *m,
                                        const char *source_file, const char *doing, vl_error *err) {
  sqlite3_stmt *st = NULL;
  int compliance = m->kind == VL_DMA_COMPLIANCE;
  vl_status s = vl_dbi_prepare(
      db,
      "INSERT INTO compound_measurement (compound_id, frequency_rad_s, temperature_c, "
      "storage_pa, loss_pa, j1_per_pa, j2_per_pa, source_file, source_line, "
      "reduced_frequency_rad_s) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10)",
      &st, err);
  if (s != VL_OK) return s;
  for (size_t k = 0; k < m->n; k++) {
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, id);
    bind_real(st, 2, m->omega_rad_s[k]);
    bind_real(st, 3, m->temperature_c[k]);
    bind_real(st, 4, compliance ? NAN : m->storage_pa[k]);
    bind_real(st, 5, compliance ? NAN : m->loss_pa[k]);
    bind_real(st, 6, compliance ? m->j1_per_pa[k] : NAN);
    bind_real(st, 7, compliance ? m->j2_per_pa[k] : NAN);
    bind_text_or_null(st, 8, source_file);
    sqlite3_bind_int64(st, 9, (sqlite3_int64)m->line[k]);
    bind_real(st, 10, m->reduced_omega_rad_s[k]);
    int rc = sqlite3_step(st);
    if (rc != SQLITE_DONE) {
      s = vl_dbi_fail(db, rc, doing, err);
      break;
    }
  }
  sqlite3_finalize(st);
  return s;
}

static vl_status measured_insert_shifts(vl_db *db, sqlite3_int64 id, const vl_measured *m,
                                        const char *doing, vl_error *err) {
  sqlite3_stmt *st = NULL;
  vl_status s = vl_dbi_prepare(db,
                               "INSERT INTO compound_shift (compound_id, temperature_c, log10_a_t) "
                               "VALUES (?1, ?2, ?3)",
                               &st, err);
  if (s != VL_OK) return s;
  for (size_t g = 0; g < m->n_isotherms; g++) {
    sqlite3_reset(st);
    sqlite3_bind_int64(st, 1, id);
    bind_real(st, 2, m->iso_temperature_c[g]);
    bind_real(st, 3, m->iso_log10_a_t[g]);
    int rc = sqlite3_step(st);
    if (rc != SQLITE_DONE) {
      s = vl_dbi_fail(db, rc, doing, err);
      break;
    }
  }
  sqlite3_finalize(st);
  return s;
}

static vl_status measured_insert_fit(vl_db *db, sqlite3_int64 id, const vl_measured *m,
                                     const char *doing, vl_error *err) {
  sqlite3_stmt *st = NULL;
  vl_status s = vl_dbi_prepare(
      db,
      "INSERT INTO compound_fit (compound_id, input_kind, weights, n_points, n_isotherms, "
      "omega_min_rad_s, omega_max_rad_s, terms_per_decade, n_grid, rms_rel_storage, "
      "max_rel_storage, rms_rel_loss, max_rel_loss, wlf_rms_log10_a_t) "
      "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14)",
      &st, err);
  if (s != VL_OK) return s;
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
  int rc = sqlite3_step(st);
  if (rc != SQLITE_DONE) s = vl_dbi_fail(db, rc, doing, err);
  sqlite3_finalize(st);
  return s;
}

/* Inside a transaction: the compound of meta (name, class, description,
 * source file) with the series, shifts, points and fit of m. */
vl_status vl_dbi_measured_insert(vl_db *db, const vl_db_compound *meta, const vl_measured *m,
                                 const char *doing, vl_error *err) {
  vl_status s;
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
  if ((s = measured_insert_points(db, id, m, c->source_file, doing, err)) != VL_OK) goto cleanup;
  if (m->has_temperature && (s = measured_insert_shifts(db, id, m, doing, err)) != VL_OK)
    goto cleanup;
  s = measured_insert_fit(db, id, m, doing, err);

cleanup:
  free(c);
  return s;
}

vl_status vl_db_compound_add_measured(vl_db *db, const vl_db_compound *meta, const vl_measured *m,
                                      vl_error *err) {
  vl_status s;
  if ((s = measured_check(m, err)) != VL_OK) return s;
  char doing[128];
  snprintf(doing, sizeof doing, "add compound '%s'", meta->name);
  if ((s = vl_dbi_tx_begin(db, doing, err)) != VL_OK) return s;
  if ((s = vl_dbi_measured_insert(db, meta, m, doing, err)) == VL_OK)
    s = vl_dbi_tx_commit(db, doing, err);
  if (s != VL_OK) vl_dbi_tx_rollback(db);
  return s;
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
  sqlite3_int64 id = vl_dbi_find_id(db, "compound", name, &s, err);
  if (id < 0) return s;
  if (id == 0) return vl_dbi_not_found(db, "compound", name, err);
  s = vl_dbi_prepare(db,
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
    s = vl_dbi_fail(db, rc, "reading a compound fit", err);
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
  s = vl_dbi_prepare(db,
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
  if (rc != SQLITE_DONE) s = vl_dbi_fail(db, rc, "reading shift factors", err);

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
  sqlite3_int64 id = vl_dbi_find_id(db, "compound", name, &s, err);
  if (id < 0) return s;
  if (id == 0) return vl_dbi_not_found(db, "compound", name, err);
  s = vl_dbi_prepare(db,
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
  if (rc != SQLITE_DONE) s = vl_dbi_fail(db, rc, "reading measured points", err);

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
  return vl_dbi_remove_named(db, "compound", name, err);
}

/* vl_dbi_list_all's reader of one compound, typed for its generic array. */
static vl_status compound_at(vl_db *db, sqlite3_int64 id, void *out, vl_error *err) {
  return compound_by_id(db, id, out, err);
}

vl_status vl_db_compound_list(vl_db *db, vl_db_compound **items, size_t *n, vl_error *err) {
  void *arr = NULL;
  vl_status s =
      vl_dbi_list_all(db, "compound", "compounds", sizeof **items, compound_at, &arr, n, err);
  *items = arr;
  return s;
}
