-- viscolube material database, schema version 5: each surface's table of
-- persson-emt flow factors (include/viscolube/flow_factors.h), computed once
-- per (surface, film cut-off, table size) and kept (issue 16).
--
-- A cache, like surface_persson: rows are written only by the program from
-- the table it built, checked in full on every read (format, PSD
-- fingerprint, cut-off, checksum, values) and rebuilt when anything fails.
-- format names the build algorithm as well as the layout: rows of another
-- format are rebuilt and replaced. Deleting rows is always safe.

CREATE TABLE surface_flow_factors (
  surface_id     INTEGER NOT NULL REFERENCES surface (id) ON DELETE CASCADE,
  film_cutoff_m  REAL NOT NULL CHECK (film_cutoff_m > 0),
  n_points       INTEGER NOT NULL CHECK (n_points > 0),
  format         INTEGER NOT NULL CHECK (format > 0),
  data           BLOB NOT NULL,
  created_at     TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%SZ', 'now')),
  PRIMARY KEY (surface_id, film_cutoff_m, n_points)
);

-- Any change to a spectrum's inputs drops its tables (as for surface_persson).
CREATE TRIGGER surface_flow_factors_on_surface
  AFTER UPDATE OF kind, hurst, q0_per_m, q1_per_m, hrms_m ON surface
BEGIN
  DELETE FROM surface_flow_factors WHERE surface_id = OLD.id;
END;

CREATE TRIGGER surface_flow_factors_on_point_insert AFTER INSERT ON surface_point
BEGIN
  DELETE FROM surface_flow_factors WHERE surface_id = NEW.surface_id;
END;

CREATE TRIGGER surface_flow_factors_on_point_update AFTER UPDATE ON surface_point
BEGIN
  DELETE FROM surface_flow_factors WHERE surface_id IN (OLD.surface_id, NEW.surface_id);
END;

CREATE TRIGGER surface_flow_factors_on_point_delete AFTER DELETE ON surface_point
BEGIN
  DELETE FROM surface_flow_factors WHERE surface_id = OLD.surface_id;
END;
