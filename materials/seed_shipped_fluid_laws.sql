-- Viscosity-temperature laws of the shipped fluids, for a new database.
-- Seeds run after every migration and after seed_shipped.sql (name order),
-- so the fluids exist here; 0003_fluid_viscosity_law.sql carries the same
-- numbers, with their sources, for databases created by an older program.
-- Kept apart from seed_shipped.sql so that seed stays valid against the
-- schema of version 1 (tests build old databases from it).
UPDATE fluid SET viscosity_law = 'vogel', vogel_b_k = 247.8, vogel_c_k = 140.0,
                 law_tmin_c = 0.0, law_tmax_c = 100.0
 WHERE name = 'water';
UPDATE fluid SET viscosity_law = 'vogel', vogel_b_k = 684.2, vogel_c_k = 162.4,
                 law_tmin_c = 0.0, law_tmax_c = 100.0
 WHERE name = 'glycerol';
