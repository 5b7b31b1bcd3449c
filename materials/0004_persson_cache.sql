-- viscolube material database, schema version 4: each surface's Persson
-- table u(s) (include/viscolube/roughness.h), computed once and kept
-- (issue 7).
--
-- A cache, not an input: a row is written only by vl_db_persson_table
-- (src/database.c) from vl_persson_build and vl_persson_serialize, one row
-- per (surface, table size). n_table is the node count (a request for the
-- default size is stored under VL_PERSSON_DEFAULT_N_TABLE). format is the
-- blob's VL_PERSSON_FORMAT, which also names the build algorithm: rows of
-- another format are rebuilt and replaced when next read. The blob carries
-- a fingerprint of the PSD and a checksum and is fully checked on every
-- read; anything that fails the checks is rebuilt, never used. Deleting
-- rows of this table is always safe.

CREATE TABLE surface_persson (
  surface_id INTEGER NOT NULL REFERENCES surface (id) ON DELETE CASCADE,
  n_table    INTEGER NOT NULL CHECK (n_table > 0),
  format     INTEGER NOT NULL CHECK (format > 0),
  data       BLOB NOT NULL,
  created_at TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%SZ', 'now')),
  PRIMARY KEY (surface_id, n_table)
);

-- A surface's spectrum is not edited in place by the program (surfaces are
-- removed and added again, which the foreign key's cascade covers), but the
-- file may be edited by hand: any change to the inputs of a spectrum drops
-- its tables, so none outlives the spectrum it was built from. (The PSD
-- fingerprint in each blob would catch it anyway; this keeps stale rows
-- from lingering.)
CREATE TRIGGER surface_persson_on_surface
  AFTER UPDATE OF kind, hurst, q0_per_m, q1_per_m, hrms_m ON surface
BEGIN
  DELETE FROM surface_persson WHERE surface_id = OLD.id;
END;

CREATE TRIGGER surface_persson_on_point_insert AFTER INSERT ON surface_point
BEGIN
  DELETE FROM surface_persson WHERE surface_id = NEW.surface_id;
END;

CREATE TRIGGER surface_persson_on_point_update AFTER UPDATE ON surface_point
BEGIN
  DELETE FROM surface_persson WHERE surface_id IN (OLD.surface_id, NEW.surface_id);
END;

CREATE TRIGGER surface_persson_on_point_delete AFTER DELETE ON surface_point
BEGIN
  DELETE FROM surface_persson WHERE surface_id = OLD.surface_id;
END;
