-- viscolube material database, schema version 7: the shipped fluid
-- glycerol-water-85 (the soft-tribology lubricant of a steel ball on a
-- rubber disc in glycerol-water, docs/POINT_CONTACT.md), no schema change.
--
-- A shipped material added after databases have been created comes as a
-- migration, not as a seed: a new database runs every migration before the
-- seeds, in the same transaction, so this one file gives the fluid to new
-- databases and to those an older program created alike (a seed copy would
-- collide with this row). A user's own fluid of the same name is kept as it
-- is: the row is inserted only where no fluid has that name.
--
-- 85 wt% glycerol in water at 20 C: 0.1108 Pa s, from N.-S. Cheng,
-- "Formula for the viscosity of a glycerol-water mixture", Ind. Eng. Chem.
-- Res. 47 (2008) 3285, for a glycerol mass fraction Cm = 0.85 (T in C,
-- mPa s): mu = mu_w^alpha mu_g^(1 - alpha) with
-- mu_g = 12100 exp((-1233 + T) T / (9900 + 70 T)),
-- mu_w = 1.790 exp((-1230 - T) T / (36100 + 360 T)), a = 0.705 - 0.0017 T,
-- b = (4.9 + 0.036 T) a^2.5, alpha = 1 - Cm + a b Cm (1 - Cm) / (a Cm +
-- b (1 - Cm)). At 0, 10, ..., 100 C it gives 538.6, 229.3, 110.8, 59.34,
-- 34.55, 21.56, 14.27, 9.922, 7.198, 5.416, 4.208 mPa s; the stored 20 C
-- value is 110.83 rounded to four digits. Segur & Oberstar (Ind. Eng.
-- Chem. 43 (1951) 2117, the table behind the shipped glycerol) give 540,
-- 223, 109, 58.0, 33.5 mPa s at 0-40 C: Cheng is 1.7 % above their 109 at
-- 20 C and within -0.3 .. +3.1 % of them at 0-40 C.
--
-- Vogel law: B = 465.4 K, C = 166.8 K, a least-squares fit in log10 eta
-- to Cheng's eleven values, anchored at the stored 0.1108 Pa s at 20 C as
-- the other shipped laws are (scripts/fit_glycerol_water.py): against
-- Cheng, rms 0.87 %, largest 1.73 % (100 C; 1.39 % at 0 C, the other
-- points within 1.03 %).
INSERT INTO fluid (name, viscosity_pa_s, tref_c, description, viscosity_law, vogel_b_k,
                   vogel_c_k, law_tmin_c, law_tmax_c)
SELECT 'glycerol-water-85', 0.1108, 20.0,
       'Glycerol-water, 85 wt% glycerol, at 20 C: 110.8 mPa s by N.-S. Cheng, Ind. Eng. Chem. Res. 47 (2008) 3285 (Segur & Oberstar 1951: 109 mPa s); Vogel law fitted to Cheng over 0-100 C, within 1.8 %',
       'vogel', 465.4, 166.8, 0.0, 100.0
 WHERE NOT EXISTS (SELECT 1 FROM fluid WHERE name = 'glycerol-water-85');
