-- Materials of the seal and wiper cases (issue 33, cases/seals/), inserted into
-- every new database. Nominal values for the cases' statements, not
-- measurements of a particular product.

-- A ground hydraulic rod (hard chrome or steel), h_rms 0.2 um: the paper's
-- self-affine family (H 0.8, q0 2e5 1/m, q1 7.8e9 1/m) at that roughness.
-- Float glass (a windscreen), h_rms 10 nm, H 0.8 from q0 = 1e7 1/m (a 0.6 um
-- roll-off: a wiper edge touches over some 10 um, and the mean-field contact
-- wants several roll-off wavelengths in it) to q1 = 7.8e9 1/m.
INSERT INTO surface (name, kind, hurst, q0_per_m, q1_per_m, hrms_m, description)
VALUES
  ('steel-rod-0.2um', 'self-affine', 0.8, 2.0e5, 7.8e9, 0.2e-6,
   'Ground steel rod, nominal: self-affine H 0.8, q0 2e5, q1 7.8e9 1/m, h_rms 0.2 um (seal cases)'),
  ('glass-10nm', 'self-affine', 0.8, 1.0e7, 7.8e9, 10e-9,
   'Glass (windscreen), nominal: self-affine H 0.8, q0 1e7, q1 7.8e9 1/m, h_rms 10 nm (wiper case)');

-- A hydraulic oil at 40 C, 0.046 Pa s as issue 33 states (ISO VG 46's
-- 46 mm^2/s at a density near 0.87 g/cm^3 would be 0.040 Pa s).
INSERT INTO fluid (name, viscosity_pa_s, tref_c, description)
VALUES
  ('oil-0.046', 0.046, 40.0,
   'Hydraulic oil, nominal 0.046 Pa s at 40 C (ISO VG 46 order of magnitude; seal cases)');
