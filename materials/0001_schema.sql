-- viscolube material database, schema version 1.
--
-- How the files in materials/ are used (src/database.c):
--   NNNN_*.sql  a forward migration from schema version NNNN-1 to NNNN. The
--               numbers are consecutive from 0001; each file runs in its own
--               transaction which also sets PRAGMA user_version = NNNN. A
--               migration is never edited once shipped: change the schema with
--               a new file.
--   seed_*.sql  shipped materials, applied (in name order) only when a new
--               database is created, after all migrations and in the same
--               transaction. Seeds are written against the latest schema and
--               insert only inputs; derived columns (surface c0, h_rms, rms
--               slope) are left NULL and filled by the same C code that
--               inserts user materials.
-- All quantities are SI: Pa, s, m, 1/m, m^4, Pa s; temperatures in Celsius.

PRAGMA application_id = 1447843138; -- 0x564C5542, "VLUB": marks our files

-- Rubber compounds: the creep-form Prony series of MODEL.md section 2,
--   1/E(w) = (1/Einf) [1 + sum_i A_i / (1 - i w tau_i)],
-- valid at the reference temperature tref_c; optional WLF constants shift
-- every tau_i with temperature.
CREATE TABLE compound (
  id            INTEGER PRIMARY KEY,
  name          TEXT NOT NULL UNIQUE,
  class         TEXT NOT NULL DEFAULT 'other'
                CHECK (class IN ('model', 'filled', 'unfilled', 'other')),
  description   TEXT NOT NULL DEFAULT '',
  nu            REAL NOT NULL CHECK (nu >= 0.0 AND nu <= 0.5),
  e_inf_pa      REAL NOT NULL CHECK (e_inf_pa > 0.0),
  tref_c        REAL NOT NULL DEFAULT 20.0,
  wlf_c1        REAL,
  wlf_c2_k      REAL CHECK (wlf_c2_k IS NULL OR wlf_c2_k > 0.0),
  -- provenance: the file the series came from, how it was obtained
  -- ('prony-csv', 'model', a fit method), and the fit's rms error if fitted
  source_file   TEXT,
  method        TEXT NOT NULL DEFAULT 'prony-csv',
  fit_rms_error REAL,
  created_at    TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%SZ', 'now')),
  CHECK ((wlf_c1 IS NULL) = (wlf_c2_k IS NULL))
);

-- One row per Prony term; idx counts from 1 in file order.
CREATE TABLE compound_prony (
  compound_id INTEGER NOT NULL REFERENCES compound (id) ON DELETE CASCADE,
  idx         INTEGER NOT NULL CHECK (idx >= 1),
  A           REAL NOT NULL CHECK (A >= 0.0),
  tau_s       REAL NOT NULL CHECK (tau_s > 0.0),
  PRIMARY KEY (compound_id, idx)
) WITHOUT ROWID;

-- Raw measured points of a compound (DMA or creep), filled by a later
-- command: either the modulus (storage, loss) or the compliance (j1, j2).
CREATE TABLE compound_measurement (
  id              INTEGER PRIMARY KEY,
  compound_id     INTEGER NOT NULL REFERENCES compound (id) ON DELETE CASCADE,
  frequency_rad_s REAL NOT NULL CHECK (frequency_rad_s > 0.0),
  temperature_c   REAL NOT NULL,
  storage_pa      REAL,
  loss_pa         REAL,
  j1_per_pa       REAL,
  j2_per_pa       REAL,
  source_file     TEXT,
  source_line     INTEGER,
  CHECK ((storage_pa IS NOT NULL AND loss_pa IS NOT NULL)
         OR (j1_per_pa IS NOT NULL AND j2_per_pa IS NOT NULL))
);
CREATE INDEX compound_measurement_by_compound ON compound_measurement (compound_id);

-- Measured time-temperature shift factors of a compound (master curve).
CREATE TABLE compound_shift (
  compound_id   INTEGER NOT NULL REFERENCES compound (id) ON DELETE CASCADE,
  temperature_c REAL NOT NULL,
  log10_a_t     REAL NOT NULL,
  PRIMARY KEY (compound_id, temperature_c)
) WITHOUT ROWID;

-- Roughness power spectra. Inputs: kind and (self-affine) hurst, q0, q1,
-- hrms_m, or (tabulated) the points in surface_point. Derived columns
-- c0_m4 (self-affine), derived_hrms_m and derived_rms_slope are written by
-- C code only (vl_psd_*), never by hand; NULL means "not yet derived".
CREATE TABLE surface (
  id                INTEGER PRIMARY KEY,
  name              TEXT NOT NULL UNIQUE,
  kind              TEXT NOT NULL CHECK (kind IN ('self-affine', 'tabulated')),
  hurst             REAL CHECK (hurst IS NULL OR (hurst > 0.0 AND hurst <= 1.0)),
  q0_per_m          REAL CHECK (q0_per_m IS NULL OR q0_per_m > 0.0),
  q1_per_m          REAL,
  hrms_m            REAL CHECK (hrms_m IS NULL OR hrms_m > 0.0),
  c0_m4             REAL,
  derived_hrms_m    REAL,
  derived_rms_slope REAL,
  description       TEXT NOT NULL DEFAULT '',
  source_file       TEXT,
  created_at        TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%SZ', 'now')),
  CHECK (q1_per_m IS NULL OR q1_per_m > q0_per_m),
  CHECK (kind <> 'self-affine'
         OR (hurst IS NOT NULL AND q0_per_m IS NOT NULL AND q1_per_m IS NOT NULL
             AND hrms_m IS NOT NULL))
);

-- Points of a tabulated PSD, idx from 1 in increasing q.
CREATE TABLE surface_point (
  surface_id INTEGER NOT NULL REFERENCES surface (id) ON DELETE CASCADE,
  idx        INTEGER NOT NULL CHECK (idx >= 1),
  q_per_m    REAL NOT NULL CHECK (q_per_m > 0.0),
  c_m4       REAL NOT NULL CHECK (c_m4 > 0.0),
  PRIMARY KEY (surface_id, idx)
) WITHOUT ROWID;

-- Newtonian lubricants: low-shear viscosity at the reference temperature.
CREATE TABLE fluid (
  id             INTEGER PRIMARY KEY,
  name           TEXT NOT NULL UNIQUE,
  viscosity_pa_s REAL NOT NULL CHECK (viscosity_pa_s > 0.0),
  tref_c         REAL NOT NULL DEFAULT 20.0,
  description    TEXT NOT NULL DEFAULT '',
  source_file    TEXT,
  created_at     TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%SZ', 'now'))
);
