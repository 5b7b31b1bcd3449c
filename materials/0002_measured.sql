-- viscolube material database, schema version 2: compounds fitted to
-- measured DMA data (`compound add NAME --measured FILE`, src/dma.c).
--
-- The raw points go to compound_measurement (schema 1) in the form the file
-- gave them (E', E'' or J', J''; tan delta is stored as E'' = E' tan delta),
-- each with the reduced frequency a_T w it has on the master curve at the
-- compound's tref_c; the shift of each isotherm goes to compound_shift; the
-- Prony series to compound_prony and the WLF constants to compound; the
-- quality of the fit to compound_fit below. All of it is written in one
-- transaction.

ALTER TABLE compound_measurement ADD COLUMN reduced_frequency_rad_s REAL
  CHECK (reduced_frequency_rad_s IS NULL OR reduced_frequency_rad_s > 0.0);

-- How the series of a measured compound was fitted, and how well: relative
-- errors (fit - measured)/measured of E' and E'' over the master-curve
-- points (rms and largest), the frequency window of the master curve at
-- tref_c, the tau grid, and the rms residual of the WLF fit to the shifts
-- (NULL with fewer than three isotherms).
CREATE TABLE compound_fit (
  compound_id       INTEGER PRIMARY KEY REFERENCES compound (id) ON DELETE CASCADE,
  input_kind        TEXT NOT NULL
                    CHECK (input_kind IN ('storage-loss', 'storage-tan-delta', 'compliance')),
  weights           TEXT NOT NULL CHECK (weights IN ('relative', 'modulus')),
  n_points          INTEGER NOT NULL CHECK (n_points > 0),
  n_isotherms       INTEGER NOT NULL CHECK (n_isotherms > 0),
  omega_min_rad_s   REAL NOT NULL CHECK (omega_min_rad_s > 0.0),
  omega_max_rad_s   REAL NOT NULL,
  terms_per_decade  REAL NOT NULL CHECK (terms_per_decade > 0.0),
  n_grid            INTEGER NOT NULL CHECK (n_grid > 0),
  rms_rel_storage   REAL NOT NULL CHECK (rms_rel_storage >= 0.0),
  max_rel_storage   REAL NOT NULL CHECK (max_rel_storage >= 0.0),
  rms_rel_loss      REAL NOT NULL CHECK (rms_rel_loss >= 0.0),
  max_rel_loss      REAL NOT NULL CHECK (max_rel_loss >= 0.0),
  wlf_rms_log10_a_t REAL CHECK (wlf_rms_log10_a_t IS NULL OR wlf_rms_log10_a_t >= 0.0),
  CHECK (omega_max_rad_s > omega_min_rad_s)
);
