/* viscolube: files written whole or not at all.
 *
 * Every file the program writes (curves, fields, comparisons, flattening
 * tables, measured-vs-fitted curves, figures) goes through a temporary in
 * the same directory, renamed over the final name once it is complete and
 * on disk: a crash, a full disk or a failed write leaves the previous file
 * (or none), never a truncated one. The temporary is named
 * ".NAME.tmp.PID.N.RANDOM" (hidden; the pid and the call's number make it
 * unique on one machine, 32 random bits across machines sharing a folder)
 * and created exclusively (O_EXCL: a name that exists is never reused, and
 * another is drawn), so two writers of one NAME never share a temporary;
 * the last rename wins, whole. A path
 * that is a symbolic link has the file it names replaced; one that exists
 * and is not a regular file (a terminal, a pipe, /dev/null) is written
 * directly, as a rename would replace the device instead of writing to it.
 *
 *   vl_atomic_file af;
 *   if (vl_atomic_file_open(&af, path, err) != VL_OK) return VL_EIO;
 *   fprintf(af.f, ...);
 *   return vl_atomic_file_commit(&af, err);
 */
#ifndef VISCOLUBE_ATOMIC_FILE_H
#define VISCOLUBE_ATOMIC_FILE_H

#include <stdio.h>

#include "viscolube/status.h"

#define VL_ATOMIC_PATH_MAX 4352

typedef struct {
  FILE *f;                       /* write the contents here */
  char path[VL_ATOMIC_PATH_MAX]; /* the final name */
  char tmp[VL_ATOMIC_PATH_MAX];  /* the temporary's name ("" when direct) */
} vl_atomic_file;

/* Creates the temporary for path (mode 0666 less the umask, as fopen).
 * VL_EIO with a message naming path when it cannot be created (missing or
 * read-only directory, name too long). On failure af->f is NULL and there
 * is nothing to commit or abort. */
vl_status vl_atomic_file_open(vl_atomic_file *af, const char *path, vl_error *err);

/* Flushes, fsyncs and closes the temporary, then renames it over path. On
 * any failure (including an earlier write error on af->f) the temporary is
 * removed, path is untouched, and VL_EIO comes with a message naming path.
 * af is finished either way. */
vl_status vl_atomic_file_commit(vl_atomic_file *af, vl_error *err);

/* Closes and removes the temporary, leaving path untouched (the caller's
 * own failure). A no-op on a finished af. */
void vl_atomic_file_abort(vl_atomic_file *af);

#endif
