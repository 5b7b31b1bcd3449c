/* viscolube: the manifest of an output folder, DIR/run.json.
 *
 * A command that writes results into a folder records there what made
 * them: the command line, the scene text or the options, the materials
 * with their database fingerprints, the numerics each contact used, the
 * program's version and source commit, start and end times (UTC, ISO
 * 8601), how many points converged, and the list of files written. The
 * manifest is written last, through a temporary renamed into place
 * (atomic_file.h), so a folder with a run.json holds a complete run:
 *
 *   vl_manifest *m;
 *   vl_manifest_begin(dir, argc, argv, &m, err);  // before anything is written
 *   vl_manifest_set_program(m, "0.1.0", "49efe58");
 *   vl_manifest_add_text(m, "scene", text);
 *   vl_manifest_add_material(m, "compound", name, fingerprint);
 *   ... vl_manifest_add_file(m, path) for every file written ...
 *   vl_manifest_add_counts(m, converged, failed);
 *   vl_manifest_finish(m, err);                    // writes DIR/run.json
 *   ... report vl_manifest_removed / vl_manifest_unclaimed ...
 *   vl_manifest_free(m);
 *
 * Files of an earlier run: begin moves an existing run.json aside (to
 * DIR/.run.json.previous), so that a run interrupted half-way leaves a
 * folder without run.json rather than one whose manifest describes other
 * files; finish removes the files the earlier manifest lists that this run
 * did not write (only those: a listed name that is absolute, climbs out
 * with "..", or is not a regular file is never touched), then the folders
 * they leave empty, and reports every other file of the folder that this
 * run did not write (hidden names aside) as unclaimed, left alone.
 *
 * Interrupted runs: begin also keeps hard links to the earlier run's files
 * (DIR/.run.previous.d) until finish. vl_manifest_interrupt, installed by
 * the program as its SIGINT/SIGTERM handler, puts the earlier run back as
 * it was (its files under their names, the files this run added removed,
 * its run.json in place) before the signal takes its default effect: after
 * Ctrl-C the folder is the earlier complete run, not a mix. A temporary of
 * a file being written at that moment may stay as a hidden name, and a
 * folder the run made but had not yet written a file into stays empty.
 *
 * The add functions copy their arguments; out of memory is remembered and
 * returned by finish. Nothing is printed. */
#ifndef VISCOLUBE_MANIFEST_H
#define VISCOLUBE_MANIFEST_H

#include <stddef.h>

#include "viscolube/contact.h"
#include "viscolube/status.h"

#define VL_MANIFEST_NAME "run.json"

typedef struct vl_manifest vl_manifest;

/* A signal handler (SIGINT, SIGTERM): restores the folder of the run in
 * progress in this process, if any, to the earlier complete run (see
 * above; only async-signal-safe calls), then lets sig take its default
 * action. */
void vl_manifest_interrupt(int sig);

/* Starts the manifest of folder dir (which must exist) for the command
 * argv[0..argc), noting the start time, and moves an earlier DIR/run.json
 * aside (see above). VL_ENOMEM; VL_EIO when the earlier manifest cannot be
 * moved, or DIR/run.json is not one (another program's file is never
 * touched). */
vl_status vl_manifest_begin(const char *dir, int argc, char *const *argv, vl_manifest **out,
                            vl_error *err);

/* The program's version and source commit ("program" member). */
void vl_manifest_set_program(vl_manifest *m, const char *version, const char *commit);

/* A top-level string member, e.g. "scene_path", "scene" (the scene file's
 * text). A key given twice keeps the last value. */
void vl_manifest_add_text(vl_manifest *m, const char *key, const char *value);

/* A member of the "options" object (the options a command was run with,
 * defaults resolved). A key given twice keeps the last value. */
void vl_manifest_add_option(vl_manifest *m, const char *key, const char *value);

/* A material ("compound", "surface", "fluid") with its fingerprint
 * (vl_db_fingerprint); the same role and name twice are recorded once. */
void vl_manifest_add_material(vl_manifest *m, const char *role, const char *name,
                              const char *fingerprint);

/* The numerics of one curve's contact (vl_contact_numerics_of), its
 * scales a0 and p0, under label (a fluid, a compound; NULL = none). */
void vl_manifest_add_numerics(vl_manifest *m, const char *label, const vl_contact_numerics_used *nu,
                              double a0_m, double p0_pa);

/* A file written: path as opened (DIR/...), recorded relative to DIR. */
void vl_manifest_add_file(vl_manifest *m, const char *path);

/* A file that could not be written (e.g. the disk was full), with why. */
void vl_manifest_add_unwritten(vl_manifest *m, const char *path, const char *reason);

/* Adds to the counts of points that converged and that did not. */
void vl_manifest_add_counts(vl_manifest *m, size_t converged, size_t failed);

/* Notes the end time, removes the files of the earlier run this one did
 * not write (see above), then writes DIR/run.json. VL_OK; VL_ENOMEM (an
 * add ran out of memory); VL_EIO with a message naming run.json when it
 * cannot be written (the earlier manifest stays aside). */
vl_status vl_manifest_finish(vl_manifest *m, vl_error *err);

/* After finish: the files of the earlier run removed, and the unclaimed
 * files left alone (both relative to DIR, valid until vl_manifest_free). */
const char *const *vl_manifest_removed(const vl_manifest *m, size_t *n);
const char *const *vl_manifest_unclaimed(const vl_manifest *m, size_t *n);

/* The unwritten files (relative to DIR), in the order added, and why
 * file i was not written. */
const char *const *vl_manifest_unwritten(const vl_manifest *m, size_t *n);
const char *vl_manifest_unwritten_reason(const vl_manifest *m, size_t i);

void vl_manifest_free(vl_manifest *m);

#endif
