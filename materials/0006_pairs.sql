-- viscolube material database, schema version 6: pairs (issue 34).
--
-- A pair is a (compound, surface, fluid) interface with the law of the
-- shear stress in its real contact area, sigma_s (include/viscolube/
-- shear_law.h): 'constant' (p1 = sigma_s_pa), 'eyring' (p1 = sigma_0_pa,
-- p2 = sigma_e_pa, p3 = v_e_m_s) or 'dewetting' (p1 = sigma_dry_pa,
-- p2 = sigma_wet_pa, p3 = v_d_m_s); tref_c and eta_ref_pa_s are the
-- conditions the parameters hold at (NULL: none). ci95_k are the half-widths
-- of the parameters' 95 % intervals (NULL when typed in).
--
-- Provenance: source 'typed' (a value given by the user, described in
-- description) or 'calibrated' (a fit to a measured Stribeck curve: the
-- file, a fingerprint of its bytes, its points, the conditions it was
-- measured at, the rms misfit in log10 mu, and created_at, the date).
--
-- A pair belongs to its three materials: removing any of them removes it
-- (ON DELETE CASCADE). The C code checks the law's parameters on every read
-- and write (the CHECKs below cannot see the law's own rules).

CREATE TABLE pair (
  id                   INTEGER PRIMARY KEY,
  compound_id          INTEGER NOT NULL REFERENCES compound (id) ON DELETE CASCADE,
  surface_id           INTEGER NOT NULL REFERENCES surface (id) ON DELETE CASCADE,
  fluid_id             INTEGER NOT NULL REFERENCES fluid (id) ON DELETE CASCADE,
  law                  TEXT NOT NULL CHECK (law IN ('constant', 'eyring', 'dewetting')),
  p1                   REAL NOT NULL,
  p2                   REAL,
  p3                   REAL,
  ci95_1               REAL,
  ci95_2               REAL,
  ci95_3               REAL,
  tref_c               REAL,
  eta_ref_pa_s         REAL,
  source               TEXT NOT NULL CHECK (source IN ('typed', 'calibrated')),
  description          TEXT NOT NULL DEFAULT '',
  measured_file        TEXT,
  measured_fingerprint TEXT,
  n_points             INTEGER CHECK (n_points IS NULL OR n_points > 0),
  load_n_per_m         REAL CHECK (load_n_per_m IS NULL OR load_n_per_m > 0.0),
  radius_m             REAL CHECK (radius_m IS NULL OR radius_m > 0.0),
  temperature_c        REAL,
  rms_log10_mu         REAL CHECK (rms_log10_mu IS NULL OR rms_log10_mu >= 0.0),
  created_at           TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%SZ', 'now')),
  UNIQUE (compound_id, surface_id, fluid_id),
  CHECK (source = 'typed' OR (measured_fingerprint IS NOT NULL AND n_points IS NOT NULL))
);
CREATE INDEX pair_surface ON pair (surface_id);
CREATE INDEX pair_fluid ON pair (fluid_id);
