-- Materials shipped with viscolube since its first program, inserted into
-- every new database (see 0001_schema.sql for how seeds differ from
-- migrations). A material shipped later is not added here but comes as a
-- migration (0007, 0008), which gives it to the databases an older program
-- created as well: seeds never reach those. Only inputs are
-- written here; the derived surface columns are left NULL and computed by
-- src/database.c with the same code as for user-added surfaces.
-- "Seed paper": M. Scaraggi and B.N.J. Persson, "Theory of viscoelastic
-- lubrication", Tribology International (2014).

-- The seed paper's model rubber (Section 3, Figs. 3-13): one relaxation time
-- tau_r = 0.1 s, Einf/E0 = 10 (so A = Einf/E0 - 1 = 9), E0 = 3.6 MPa (so
-- Einf = 36 MPa), nu = 0.5.
INSERT INTO compound (name, class, description, nu, e_inf_pa, tref_c, method)
VALUES ('model-rubber', 'model',
        'Model rubber of Scaraggi & Persson, Figs. 3-13: one term, tau 0.1 s, Einf/E0 = 10, E0 = 3.6 MPa, nu 0.5',
        0.5, 36.0e6, 20.0, 'model');
INSERT INTO compound_prony (compound_id, idx, A, tau_s)
VALUES ((SELECT id FROM compound WHERE name = 'model-rubber'), 1, 9.0, 0.1);

-- The seed paper's self-affine isotropic surface (Figs. 5, 10, 15-20):
-- fractal dimension Df = 2.2 (H = 3 - Df = 0.8), q0 = 2e5 1/m,
-- q1 = 7.8e9 1/m, at the rms roughnesses the paper uses.
INSERT INTO surface (name, kind, hurst, q0_per_m, q1_per_m, hrms_m, description)
VALUES
  ('paper-0.1um', 'self-affine', 0.8, 2.0e5, 7.8e9, 0.1e-6,
   'Scaraggi & Persson self-affine surface (H 0.8, q0 2e5, q1 7.8e9 1/m), h_rms 0.1 um (Fig. 3)'),
  ('paper-0.3um', 'self-affine', 0.8, 2.0e5, 7.8e9, 0.3e-6,
   'Scaraggi & Persson self-affine surface (H 0.8, q0 2e5, q1 7.8e9 1/m), h_rms 0.3 um (Fig. 3)'),
  ('paper-0.5um', 'self-affine', 0.8, 2.0e5, 7.8e9, 0.5e-6,
   'Scaraggi & Persson self-affine surface (H 0.8, q0 2e5, q1 7.8e9 1/m), h_rms 0.5 um (Figs. 15-18)'),
  ('paper-1um', 'self-affine', 0.8, 2.0e5, 7.8e9, 1.0e-6,
   'Scaraggi & Persson self-affine surface (H 0.8, q0 2e5, q1 7.8e9 1/m), h_rms 1 um (Fig. 3)'),
  ('paper-3um', 'self-affine', 0.8, 2.0e5, 7.8e9, 3.0e-6,
   'Scaraggi & Persson self-affine surface (H 0.8, q0 2e5, q1 7.8e9 1/m), h_rms 3 um (Figs. 5, 10, 19, 20)'),
  ('paper-5um', 'self-affine', 0.8, 2.0e5, 7.8e9, 5.0e-6,
   'Scaraggi & Persson self-affine surface (H 0.8, q0 2e5, q1 7.8e9 1/m), h_rms 5 um (Figs. 17, 18)'),
  ('paper-10um', 'self-affine', 0.8, 2.0e5, 7.8e9, 10.0e-6,
   'Scaraggi & Persson self-affine surface (H 0.8, q0 2e5, q1 7.8e9 1/m), h_rms 10 um (Fig. 3)');

-- Lubricants: low-shear viscosity at tref_c.
INSERT INTO fluid (name, viscosity_pa_s, tref_c, description)
VALUES
  ('water', 1.0e-3, 20.0,
   'Water at 20 C, 1.0e-3 Pa s as used by Scaraggi & Persson (Figs. 14-18); CRC Handbook of Chemistry and Physics gives 1.0016 mPa s'),
  ('model-1e-4', 1.0e-4, 20.0,
   'Model fluid of Scaraggi & Persson, Fig. 5 (eta = 1e-4 Pa s)'),
  ('model-1e-2', 1.0e-2, 20.0,
   'Model fluid of Scaraggi & Persson, Figs. 19-20 (eta = 0.01 Pa s)'),
  ('model-1', 1.0, 20.0,
   'Model fluid of Scaraggi & Persson, Fig. 10 (eta = 1 Pa s)'),
  ('glycerol', 1.41, 20.0,
   'Glycerol (100 %) at 20 C, 1412 mPa s: L.B. Segur and H.E. Oberstar, Ind. Eng. Chem. 43 (1951) 2117');
