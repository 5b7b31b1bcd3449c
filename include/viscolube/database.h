/* viscolube: the material database (SQLite).
 *
 * One file holds rubber compounds (Prony series, docs/MODEL.md section 2),
 * roughness power spectra and lubricants. The schema lives in the .sql
 * files of materials/ (embedded in the program): NNNN_*.sql are forward
 * migrations, applied in order, each in its own transaction that also sets
 * PRAGMA user_version; seed_*.sql are the shipped materials, inserted only
 * into a new database, as are the compounds of the shipped measured-style
 * data files materials/NAME.csv, which go through the import of
 * vl_measured_read_text and vl_db_compound_add_measured like user data.
 * A shipped material added later comes with a migration of its own
 * (0007_glycerol_water.sql), which gives it to new and older databases
 * alike and keeps a user's material of the same name.
 *
 * Guarantees:
 *   - Foreign keys are ON; every write runs in one BEGIN IMMEDIATE ... COMMIT
 *     transaction and is rolled back entirely on any failure, so a failed
 *     call leaves the database file byte-for-byte as it was.
 *   - A file whose schema is newer than this program knows, that is not a
 *     viscolube database, or that is corrupt is refused (VL_EDB) and not
 *     touched. A file without write permission (by its permission bits, even
 *     for root) is opened read-only: reads work, writes fail with VL_EDB.
 *   - Derived columns (surface C0, h_rms, rms slope) are computed by the
 *     vl_psd_* functions, for shipped and user-added surfaces alike.
 *   - The one write a reading call may make is vl_db_persson_table (or
 *     vl_db_flow_table) storing
 *     a surface's Persson table, a cache: its failure (read-only file,
 *     lock) is not an error, and removing a surface removes its tables.
 *
 * Names are 1..VL_DB_NAME_MAX-1 characters of [A-Za-z0-9._+-], not starting
 * with '-'. All quantities are SI; temperatures in degrees Celsius. The
 * library never prints; errors come back as a vl_status and one sentence in
 * the caller's vl_error. */
#ifndef VISCOLUBE_DATABASE_H
#define VISCOLUBE_DATABASE_H

#include <stdbool.h>
#include <stddef.h>

#include "viscolube/dma.h"
#include "viscolube/flow_factors.h"
#include "viscolube/fluid.h"
#include "viscolube/persson.h"
#include "viscolube/rheology.h"
#include "viscolube/shear_law.h"
#include "viscolube/status.h"

#define VL_DB_NAME_MAX 64
#define VL_DB_TEXT_MAX 512

typedef struct vl_db vl_db;

/* A compound as stored: the Prony series and its metadata. */
typedef struct {
  char name[VL_DB_NAME_MAX];
  char class_name[16];              /* model | filled | unfilled | other */
  char description[VL_DB_TEXT_MAX]; /* free text, including the source */
  vl_prony prony;                   /* Einf, nu, terms at tref_c */
  double tref_c;                    /* reference temperature of the series */
  double wlf_c1, wlf_c2_k;          /* WLF constants, NAN when absent */
  char source_file[VL_DB_TEXT_MAX]; /* file the terms came from ("" if none) */
  char method[VL_DB_NAME_MAX];      /* 'prony-csv', 'model', a fit method */
  double fit_rms_error;             /* NAN when not fitted */
  char created_at[32];              /* ISO 8601 UTC, set by the database */
} vl_db_compound;

/* A surface as stored (metadata and derived scalars; the spectrum itself is
 * returned by vl_db_surface_get). */
typedef struct {
  char name[VL_DB_NAME_MAX];
  vl_psd_kind kind;
  double hurst;    /* self-affine only (NAN for tabulated) */
  double q0_per_m; /* band (tabulated: first and last q) */
  double q1_per_m;
  double hrms_m;    /* derived by vl_psd_hrms (equals the input for self-affine) */
  double c0_m4;     /* self-affine prefactor (NAN for tabulated) */
  double rms_slope; /* derived by vl_psd_rms_slope */
  size_t n_points;  /* tabulated points (0 for self-affine) */
  char description[VL_DB_TEXT_MAX];
  char source_file[VL_DB_TEXT_MAX];
  char created_at[32];
} vl_db_surface;

/* A Newtonian lubricant. */
typedef struct {
  char name[VL_DB_NAME_MAX];
  double viscosity_pa_s; /* low-shear viscosity at tref_c */
  double tref_c;
  vl_viscosity_law law; /* viscosity vs temperature (fluid.h); kind NONE = none stored */
  char description[VL_DB_TEXT_MAX];
  char source_file[VL_DB_TEXT_MAX];
  char created_at[32];
} vl_db_fluid;

/* ---- opening ---------------------------------------------------------- */

/* Opens the database at path (NULL = vl_db_default_path, whose directories
 * are created). A missing file is created, migrated and seeded in one
 * transaction (and removed again if that fails); an older schema is
 * migrated forward. On success *out must be closed with vl_db_close; on
 * failure *out is NULL. Errors: VL_EDB (newer schema, foreign or corrupt
 * file, read-only file needing an upgrade, SQLite failure), VL_EIO (cannot
 * create the directory or file), VL_ENOMEM. */
vl_status vl_db_open(const char *path, vl_db **out, vl_error *err);

/* Opens the existing database at path (NULL = vl_db_default_path)
 * read-only, whatever its permissions: nothing is created, migrated or
 * cached (vl_db_persson_table and vl_db_flow_table build what is not
 * stored and keep it in memory only). For the workers of a study, which
 * share one file that the coordinating process has filled beforehand.
 * Errors as vl_db_open; a missing file is VL_EIO, an older schema VL_EDB. */
vl_status vl_db_open_readonly(const char *path, vl_db **out, vl_error *err);

/* Closes and frees db (NULL is a no-op). */
void vl_db_close(vl_db *db);

/* Writes the default path into buf: $VISCOLUBE_DB if set and non-empty, else
 * $XDG_DATA_HOME/viscolube/materials.db, else
 * $HOME/.local/share/viscolube/materials.db. VL_EINPUT if none of the
 * variables is set or buf is too small. Creates nothing. */
vl_status vl_db_default_path(char *buf, size_t size, vl_error *err);

/* The path the database was opened with (owned by db). */
const char *vl_db_path(const vl_db *db);

/* Nonzero if db was opened read-only (file without write permission). */
int vl_db_readonly(const vl_db *db);

/* ---- compounds -------------------------------------------------------- */

/* The Prony series of compound `name` at its reference temperature.
 * VL_ENOTFOUND (message names it and suggests close names). */
vl_status vl_db_compound_get(vl_db *db, const char *name, vl_prony *out, vl_error *err);

/* Everything stored about compound `name`. VL_ENOTFOUND. */
vl_status vl_db_compound_info(vl_db *db, const char *name, vl_db_compound *out, vl_error *err);

/* Adds a compound. Checks the name, class, texts, vl_prony_validate and the
 * WLF pair (both or neither, c2 > 0) before touching the file. created_at
 * is ignored. VL_EINPUT, VL_EEXIST, VL_EDB. */
vl_status vl_db_compound_add(vl_db *db, const vl_db_compound *compound, vl_error *err);

/* Adds a compound fitted to measured data (dma.h): name, class_name,
 * description and source_file come from meta (its other fields are
 * ignored); the Prony series, nu, tref, WLF constants and fit from m. In
 * one transaction it stores the compound (method 'dma-fit', fit_rms_error =
 * m->fit.rms_rel), its terms, every raw point with its reduced frequency
 * (compound_measurement: E', E'' or J', J'' as the file gave them), the
 * shift of each isotherm (compound_shift, files with a temperature column)
 * and the fit report (compound_fit); any failure leaves the file as it
 * was. Checks as vl_db_compound_add. VL_EINPUT, VL_EEXIST, VL_EDB. */
vl_status vl_db_compound_add_measured(vl_db *db, const vl_db_compound *meta, const vl_measured *m,
                                      vl_error *err);

/* How a measured compound was fitted (see 0002_measured.sql). */
typedef struct {
  int has_fit;         /* 0: not fitted to measured data; the rest is empty */
  char input_kind[24]; /* storage-loss | storage-tan-delta | compliance */
  char weights[16];    /* relative | modulus */
  size_t n_points, n_isotherms;
  double omega_min_rad_s; /* master-curve window at tref */
  double omega_max_rad_s;
  double terms_per_decade;
  size_t n_grid;                           /* tau grid size (terms kept: the compound's n_terms) */
  double rms_rel_storage, max_rel_storage; /* (fit - measured)/measured of E' */
  double rms_rel_loss, max_rel_loss;       /* the same for E'' */
  double wlf_rms_log10_a_t;                /* NAN without a WLF fit */
  size_t n_shifts;                         /* isotherm shifts, by increasing temperature */
  double *shift_temperature_c;             /* malloc'd (n_shifts values) */
  double *shift_log10_a_t;
} vl_db_compound_fit;

/* The fit report and shifts of compound `name` (has_fit = 0 for a compound
 * entered as a Prony series). Release with vl_db_compound_fit_free.
 * VL_ENOTFOUND, VL_EDB, VL_ENOMEM. */
vl_status vl_db_compound_fit_info(vl_db *db, const char *name, vl_db_compound_fit *out,
                                  vl_error *err);

/* Frees the arrays of fit (and empties it); NULL is fine. */
void vl_db_compound_fit_free(vl_db_compound_fit *fit);

/* One stored measured point; E', E'' computed from J', J'' when the file
 * gave compliances. */
typedef struct {
  double omega_rad_s; /* as measured */
  double temperature_c;
  double reduced_omega_rad_s; /* on the master curve at the compound's tref */
  double storage_pa, loss_pa;
  size_t source_line; /* line in the source file (0 if unknown) */
} vl_db_measured_point;

/* The measured points of compound `name` sorted by reduced frequency, into
 * a malloc'd array (caller free()s *points; NULL when *n is 0, e.g. for a
 * compound entered as a Prony series). VL_ENOTFOUND, VL_EDB, VL_ENOMEM. */
vl_status vl_db_compound_points(vl_db *db, const char *name, vl_db_measured_point **points,
                                size_t *n, vl_error *err);

/* Removes compound `name` and everything that belongs to it (terms,
 * measurements, shift factors, fit). VL_ENOTFOUND, VL_EDB. */
vl_status vl_db_compound_remove(vl_db *db, const char *name, vl_error *err);

/* All compounds sorted by name into a malloc'd array (caller free()s
 * *items; *items is NULL when *n is 0). */
vl_status vl_db_compound_list(vl_db *db, vl_db_compound **items, size_t *n, vl_error *err);

/* ---- surfaces --------------------------------------------------------- */

/* The PSD of surface `name` (tabulated points included). On success the
 * caller owns *out and releases it with vl_psd_free. VL_ENOTFOUND. */
vl_status vl_db_surface_get(vl_db *db, const char *name, vl_psd *out, vl_error *err);

/* Metadata and derived scalars of surface `name`. VL_ENOTFOUND. */
vl_status vl_db_surface_info(vl_db *db, const char *name, vl_db_surface *out, vl_error *err);

/* Adds surface `name` from psd: self-affine (hurst, q0, q1, hrms_m are
 * read) or tabulated (n, q, C are read). The PSD is re-initialised through
 * vl_psd_init_self_affine / vl_psd_init_tabulated, which validate it, and
 * the derived columns are computed from that copy. description and
 * source_file may be NULL. VL_EINPUT, VL_EEXIST, VL_EDB. */
vl_status vl_db_surface_add(vl_db *db, const char *name, const vl_psd *psd, const char *description,
                            const char *source_file, vl_error *err);

/* Removes surface `name` with its points. VL_ENOTFOUND, VL_EDB. */
vl_status vl_db_surface_remove(vl_db *db, const char *name, vl_error *err);

/* All surfaces sorted by name (caller free()s *items). */
vl_status vl_db_surface_list(vl_db *db, vl_db_surface **items, size_t *n, vl_error *err);

/* The Persson table (roughness.h) of surface `name` with n_table nodes (0:
 * VL_PERSSON_DEFAULT_N_TABLE), computed once per (surface, size) and kept
 * in the database (table surface_persson, 0004_persson_cache.sql). psd must
 * be the surface's spectrum as vl_db_surface_get returned it.
 *
 * A stored table is used only if it passes every check of the stored blob
 * (format, checksum, PSD fingerprint, values): it then answers every query
 * bit for bit like a freshly built one. Otherwise (absent, another
 * format, corrupt, another PSD) the table is built and stored with INSERT
 * OR REPLACE in its own transaction. Storing is an optimisation: when it
 * fails (read-only file, locked by another program for more than a short
 * wait, disk full) the built table is returned all the same and the file is
 * left as it was. *from_cache (may be NULL) tells whether the table was
 * read. On success the caller owns *out (vl_persson_free); on failure *out
 * is NULL. Errors: VL_ENOTFOUND (no such surface), VL_EINPUT (n_table out
 * of range, or the PSD), VL_ENOMEM, VL_EDB (the surface lookup failed). */
vl_status vl_db_persson_table(vl_db *db, const char *name, const vl_psd *psd, size_t n_table,
                              vl_persson **out, bool *from_cache, vl_error *err);

/* The persson-emt flow-factor table of surface name (whose PSD is psd) for
 * film cut-off film_cutoff_m (m) and n_points nodes (0: the default),
 * cached exactly like vl_db_persson_table (table surface_flow_factors):
 * used only when it passes every check of the stored blob (format, PSD
 * fingerprint, cut-off, checksum, values), else built (about a second) and
 * stored best effort. On success the caller owns *out
 * (vl_emt_table_free). Errors: VL_ENOTFOUND, VL_EINPUT (size or cut-off
 * out of range, the PSD), VL_ENOMEM, VL_EDB. */
vl_status vl_db_flow_table(vl_db *db, const char *name, const vl_psd *psd, double film_cutoff_m,
                           size_t n_points, vl_emt_table **out, bool *from_cache, vl_error *err);

/* ---- fluids ----------------------------------------------------------- */

/* Low-shear viscosity (Pa s) of fluid `name` at its reference temperature.
 * VL_ENOTFOUND. */
vl_status vl_db_fluid_get(vl_db *db, const char *name, double *eta_pa_s, vl_error *err);

/* Everything stored about fluid `name`, its viscosity law included (a
 * stored law that is not valid, fluid.h: VL_EDB). VL_ENOTFOUND. */
vl_status vl_db_fluid_info(vl_db *db, const char *name, vl_db_fluid *out, vl_error *err);

/* Adds a fluid (viscosity > 0 and finite, tref finite, the law valid for
 * tref as fluid.h states; a zeroed law is NONE). created_at is ignored.
 * VL_EINPUT, VL_EEXIST, VL_EDB. */
vl_status vl_db_fluid_add(vl_db *db, const vl_db_fluid *fluid, vl_error *err);

/* Removes fluid `name`. VL_ENOTFOUND, VL_EDB. */
vl_status vl_db_fluid_remove(vl_db *db, const char *name, vl_error *err);

/* All fluids sorted by name (caller free()s *items). */
vl_status vl_db_fluid_list(vl_db *db, vl_db_fluid **items, size_t *n, vl_error *err);

/* ---- pairs ------------------------------------------------------------ */

/* A (compound, surface, fluid) pair: the law of the shear stress in its
 * real contact area (shear_law.h) and where the numbers came from
 * (0006_pairs.sql). A pair belongs to its three materials: removing one of
 * them removes its pairs. */
#define VL_DB_SOURCE_TYPED "typed"
#define VL_DB_SOURCE_CALIBRATED "calibrated"
#define VL_DB_FINGERPRINT_MAX 32
typedef struct {
  char compound[VL_DB_NAME_MAX], surface[VL_DB_NAME_MAX], fluid[VL_DB_NAME_MAX];
  vl_shear_law law;
  double ci95[VL_SHEAR_LAW_MAX_PARAMS]; /* half-widths of the 95 % intervals; NAN if unknown */
  char source[16];                      /* VL_DB_SOURCE_TYPED or VL_DB_SOURCE_CALIBRATED */
  char description[VL_DB_TEXT_MAX];
  /* a calibration's measured curve and its conditions (typed: "", 0, NAN) */
  char measured_file[VL_DB_TEXT_MAX];
  char measured_fingerprint[VL_DB_FINGERPRINT_MAX]; /* vl_db_fingerprint_bytes of the file */
  size_t n_points;
  double load_n_per_m, radius_m, temperature_c; /* temperature NAN: materials at reference */
  double rms_log10_mu;
  char created_at[32]; /* ISO 8601 UTC, set by the database: the date of the calibration */
} vl_db_pair;

/* Adds pair (its three materials must exist: VL_ENOTFOUND naming the one
 * missing, with did-you-mean). Checks the law (vl_shear_law_validate), the
 * source, the texts and, for a calibrated pair, its fingerprint, points and
 * conditions. created_at is ignored. VL_EINPUT, VL_ENOTFOUND, VL_EEXIST
 * (remove the pair first), VL_EDB. */
vl_status vl_db_pair_add(vl_db *db, const vl_db_pair *pair, vl_error *err);

/* The pair of compound, surface and fluid. *found (may be NULL) tells
 * whether it exists: with found given, a missing pair is VL_OK and
 * *found false (the default path of friction, run, study); with NULL it is
 * VL_ENOTFOUND naming the missing material or saying which pairs the
 * compound has. A stored law that fails validation is VL_EDB. */
vl_status vl_db_pair_get(vl_db *db, const char *compound, const char *surface, const char *fluid,
                         vl_db_pair *out, bool *found, vl_error *err);

/* Removes the pair. VL_ENOTFOUND (as vl_db_pair_get), VL_EDB. */
vl_status vl_db_pair_remove(vl_db *db, const char *compound, const char *surface, const char *fluid,
                            vl_error *err);

/* All pairs sorted by compound, surface, fluid (caller free()s *items). */
vl_status vl_db_pair_list(vl_db *db, vl_db_pair **items, size_t *n, vl_error *err);

/* The number of pairs that name material `name` of table ("compound",
 * "surface", "fluid"): what removing it would take along. VL_EINPUT for
 * another table, VL_EDB. */
vl_status vl_db_pair_count(vl_db *db, const char *table, const char *name, size_t *n,
                           vl_error *err);

/* "fnv1a64:" and 16 hex digits of the n bytes at data: the fingerprint of
 * a measured file as a calibration stores it. */
void vl_db_fingerprint_bytes(const void *data, size_t n, char out[VL_DB_FINGERPRINT_MAX]);

/* ---- helpers ---------------------------------------------------------- */

/* VL_OK if name is a valid material name, else VL_EINPUT saying why. */
vl_status vl_db_check_name(const char *name, vl_error *err);

/* The fingerprint of a stored material: "fnv1a64:" and 16 hex digits, a
 * hash of the rows that define it (table "compound": the compound row, its
 * Prony terms, shift factors, fit report and measured points; "surface":
 * the surface row and its tabulated points; "fluid": the fluid row), each
 * column's name, type and value, leaving out row ids and creation times
 * (and the caches derived from the rows). Two databases holding the same
 * material give the same fingerprint; any change to what a simulation
 * reads changes it. out gets "" on failure. VL_EINPUT (unknown table),
 * VL_ENOTFOUND, VL_EDB. */
vl_status vl_db_fingerprint(vl_db *db, const char *table, const char *name,
                            char out[VL_DB_FINGERPRINT_MAX], vl_error *err);

#endif
