-- viscolube material database, schema version 3: a viscosity-temperature
-- law stored with each fluid (the scene effect `temperature = on`,
-- include/viscolube/fluid.h).
--
-- The one law so far is Vogel's (Vogel-Fulcher-Tammann),
--   log10 eta(T) = A + B / (T - C),   T and C in kelvin,
-- anchored at the fluid's stored reference point: only B and C are stored,
-- A = log10(viscosity_pa_s) - B / (tref_c + 273.15 - C), so eta(tref_c) is
-- the stored viscosity exactly. law_tmin_c .. law_tmax_c is the range of the
-- data behind the law: the program refuses temperatures outside it. A fluid
-- without a law (viscosity_law NULL, the other columns NULL) is known at its
-- reference temperature only. The C code checks the rest (all or none of the
-- columns, tmin < tmax, C below tmin, tref inside the range) on every read
-- and write.

ALTER TABLE fluid ADD COLUMN viscosity_law TEXT
  CHECK (viscosity_law IS NULL OR viscosity_law IN ('vogel'));
ALTER TABLE fluid ADD COLUMN vogel_b_k REAL CHECK (vogel_b_k IS NULL OR vogel_b_k > 0.0);
ALTER TABLE fluid ADD COLUMN vogel_c_k REAL CHECK (vogel_c_k IS NULL OR vogel_c_k >= 0.0);
ALTER TABLE fluid ADD COLUMN law_tmin_c REAL;
ALTER TABLE fluid ADD COLUMN law_tmax_c REAL;

-- The laws of the shipped fluids, for databases created by an older
-- program (a new database gets them from seed_shipped_fluid_laws.sql, which
-- runs after the shipped fluids are inserted; the two files carry the same
-- numbers). Only rows still holding the shipped reference point are
-- changed: a user's own 'water' at another temperature keeps no law.
--
-- Water: B = 247.8 K, C = 140 K, the classic Vogel fit of water's
-- viscosity, eta = 2.414e-5 Pa s * 10^(247.8 K / (T - 140 K)) (e.g.
-- T. Al-Shemmeri, Engineering Fluid Mechanics, 2012; within ~1 % of the
-- IAPWS 2008 formulation, Huber et al., J. Phys. Chem. Ref. Data 38 (2009)
-- 101, from 0 to 100 C). Anchored at the shipped 1.0e-3 Pa s at 20 C (the
-- seed paper's value; IAPWS: 1.0016 mPa s).
UPDATE fluid SET viscosity_law = 'vogel', vogel_b_k = 247.8, vogel_c_k = 140.0,
                 law_tmin_c = 0.0, law_tmax_c = 100.0
 WHERE name = 'water' AND viscosity_law IS NULL AND tref_c = 20.0 AND viscosity_pa_s = 1.0e-3;

-- Glycerol (100 %): B = 684.2 K, C = 162.4 K, a least-squares fit in
-- log10 eta, anchored at the shipped 1.41 Pa s at 20 C, to the table of
-- J.B. Segur and H.E. Oberstar, Ind. Eng. Chem. 43 (1951) 2117 for 0-100 C
-- (12070, 3900, 1410, 612, 284, 142, 81.3, 50.6, 31.9, 21.3, 14.8 mPa s
-- every 10 C): rms 2.2 %, largest 4.8 % (50 C, a point off the smooth trend
-- of its neighbours). N.-S. Cheng, Ind. Eng. Chem. Res. 47 (2008) 3285,
-- agrees with it within 2.7 % over the range.
UPDATE fluid SET viscosity_law = 'vogel', vogel_b_k = 684.2, vogel_c_k = 162.4,
                 law_tmin_c = 0.0, law_tmax_c = 100.0
 WHERE name = 'glycerol' AND viscosity_law IS NULL AND tref_c = 20.0 AND viscosity_pa_s = 1.41;
