-- viscolube material database, schema version 8: the shipped materials
-- that were added to the seeds after databases had been created, for the
-- databases an older program created without them; no schema change.
--
-- Seeds run only when a database is created, so a database keeps the
-- shipped rows of the program that created it, and a case that names a
-- later one failed on it with "unknown material". As in 0007, these rows
-- come as a migration instead (a new database runs every migration before
-- the seeds, in one transaction): this file is their only copy, and a
-- user's own row of the same name is kept as it is (each row is inserted
-- only where none of its kind has that name). The shipped measured
-- compounds sbr-unfilled and sbr-filled, seeded from schema 2 on, reach
-- the databases of schema 1 with this migration too, imported by the
-- program's C code (src/db/db_seed.c, shipped_measured: SQL cannot fit
-- their data).
--
-- The seal and wiper cases' materials (cases/seals/): nominal values for the
-- cases' statements (issue 33), not measurements of a particular product.
-- They were the seed seed_seals.sql, merged on 2026-11-28 at schema 6:
-- the databases of schema 1 to 6 created before then lack them.
--
-- A ground hydraulic rod (hard chrome or steel), h_rms 0.2 um: the paper's
-- self-affine family (H 0.8, q0 2e5 1/m, q1 7.8e9 1/m) at that roughness.
INSERT INTO surface (name, kind, hurst, q0_per_m, q1_per_m, hrms_m, description)
SELECT 'steel-rod-0.2um', 'self-affine', 0.8, 2.0e5, 7.8e9, 0.2e-6,
       'Ground steel rod, nominal: self-affine H 0.8, q0 2e5, q1 7.8e9 1/m, h_rms 0.2 um (seal cases)'
 WHERE NOT EXISTS (SELECT 1 FROM surface WHERE name = 'steel-rod-0.2um');

-- Float glass (a windscreen), h_rms 10 nm, H 0.8 from q0 = 1e7 1/m (a 0.6 um
-- roll-off: a wiper edge touches over some 10 um, and the mean-field contact
-- wants several roll-off wavelengths in it) to q1 = 7.8e9 1/m.
INSERT INTO surface (name, kind, hurst, q0_per_m, q1_per_m, hrms_m, description)
SELECT 'glass-10nm', 'self-affine', 0.8, 1.0e7, 7.8e9, 10e-9,
       'Glass (windscreen), nominal: self-affine H 0.8, q0 1e7, q1 7.8e9 1/m, h_rms 10 nm (wiper case)'
 WHERE NOT EXISTS (SELECT 1 FROM surface WHERE name = 'glass-10nm');

-- A hydraulic oil at 40 C, 0.046 Pa s as issue 33 states (ISO VG 46's
-- 46 mm^2/s at a density near 0.87 g/cm^3 would be 0.040 Pa s).
INSERT INTO fluid (name, viscosity_pa_s, tref_c, description)
SELECT 'oil-0.046', 0.046, 40.0,
       'Hydraulic oil, nominal 0.046 Pa s at 40 C (ISO VG 46 order of magnitude; seal cases)'
 WHERE NOT EXISTS (SELECT 1 FROM fluid WHERE name = 'oil-0.046');

-- The seed paper's model fluids between its decades, for the viscosity
-- series of Fig. 12 (cases/fig12.ini). Added to seed_shipped.sql
-- 24 minutes after the first program (2026-11-22): the databases of schema
-- 1 created before then have only 1e-4, 1e-2 and 1 Pa s.
INSERT INTO fluid (name, viscosity_pa_s, tref_c, description)
SELECT 'model-1e-3', 1.0e-3, 20.0,
       'Model fluid for the viscosity series of Scaraggi & Persson, Fig. 12 (eta = 1e-3 Pa s)'
 WHERE NOT EXISTS (SELECT 1 FROM fluid WHERE name = 'model-1e-3');
INSERT INTO fluid (name, viscosity_pa_s, tref_c, description)
SELECT 'model-1e-1', 1.0e-1, 20.0,
       'Model fluid for the viscosity series of Scaraggi & Persson, Fig. 12 (eta = 0.1 Pa s)'
 WHERE NOT EXISTS (SELECT 1 FROM fluid WHERE name = 'model-1e-1');
