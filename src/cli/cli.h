/* The command line's internal interface: one entry point per noun. */
#ifndef VL_CLI_H
#define VL_CLI_H

/* The program uses the library through its public header only. */
#include <stdio.h>

#include "viscolube.h"

typedef struct {
  const char *db_path; /* --db PATH, else $VISCOLUBE_DB, else NULL = default */
  int quiet;           /* --quiet: no warnings or progress on stderr */
  int argc;            /* the whole command line, for the manifests (run.json) */
  char **argv;
} vl_cli_globals;

/* `compound|surface|fluid VERB ...` (argv[0] is the noun). Returns exit code. */
int vl_cli_materials(const vl_cli_globals *g, int argc, char **argv);

/* `pair VERB ...` (cli_pair.c, argv[0] is "pair"). Returns exit code. */
int vl_cli_pair(const vl_cli_globals *g, int argc, char **argv);

/* `run SCENE [--out DIR] [--json]` (argv[0] is "run"). Returns exit code. */
int vl_cli_run(const vl_cli_globals *g, int argc, char **argv);

/* `seal SCENE [--out DIR] [--json] [--plot]` (cli_run.c: `run` with both
 * strokes of a seal and the outputs of cli_seal.c). */
int vl_cli_seal(const vl_cli_globals *g, int argc, char **argv);
/* ---- a seal's outputs (cli_seal.c) ---- */
/* The instroke of a seal's points pts[0..n) as points of their own (speed,
 * convergence, iterations, residual, friction, film, flux, estimates,
 * accuracy, warnings), for the lists of failures and warnings; malloc'd,
 * NULL when out of memory. */
vl_point *vl_cli_instroke_points(size_t n, const vl_point *pts);
/* The console table of both strokes at each speed (seal.csv's main columns). */
void vl_cli_print_seal_table(size_t n, const vl_point *pts);
/* Writes out_dir/seal.csv, out_dir/seal.json and, when plot is not NULL,
 * the figure out_dir/seal (png, svg), each recorded in the manifest (a file
 * that could not be written is noted there, not returned). Returns an
 * error of the figure other than VL_EIO. */
vl_status vl_cli_seal_files(vl_manifest *man, const char *out_dir, size_t n, const vl_point *pts,
                            const vl_plot_options *plot, vl_error *err);
/* `study STUDY --out DIR [--jobs N]` (cli_study.c). */
int vl_cli_study(const vl_cli_globals *g, int argc, char **argv);

/* `friction --compound C --surface S --fluid F --speed V ...`. */
int vl_cli_friction(const vl_cli_globals *g, int argc, char **argv);

/* `compare --compounds A,B --surface S --fluid F ...`. */
int vl_cli_compare(const vl_cli_globals *g, int argc, char **argv);

/* `flattening --compound C --surface S --fluid F --speeds V1,...` or
 * `flattening --case SCENE` (cli_flattening.c). */
int vl_cli_flattening(const vl_cli_globals *g, int argc, char **argv);

/* mkdir -p: creates path and its missing parents (0 on success, -1 with
 * errno set). */
int vl_cli_make_dirs(const char *path);

/* A command given without what it needs (a noun, a verb, a scene): the
 * message first ("viscolube run: missing SCENE"), then the command's short
 * usage (the first paragraph of help, its "usage:" lines, or the text
 * usage writes when help is NULL) and where the rest is ("see `viscolube
 * run --help`"), all on stderr. cmd is "" at the top level. Returns the
 * exit status of bad input (2). */
int vl_cli_usage_error(const char *cmd, const char *help, void (*usage)(FILE *), const char *fmt,
                       ...) __attribute__((format(printf, 4, 5)));

/* "s" unless n is 1 ("%zu point%s"). */
const char *vl_cli_plural(size_t n);

/* A temperature for a title or a line of text, to 0.1 C ("18.4" for a
 * stored 18.4029, "20", "-10"): what a reader can use, not the digits a
 * fit happened to give. Returns buf. */
const char *vl_cli_celsius(char *buf, size_t size, double t_c);

/* --out names a folder in every command (one meaning per option, issue
 * 32); `surface flow-factors` and `pair calibrate` once took a file there.
 * VL_OK, else VL_EINPUT when path ends as such a file would (.csv, .png,
 * .svg), with a message naming files, what goes into the folder now. */
vl_status vl_cli_out_is_folder(const char *path, const char *files, vl_error *err);

/* Monotonic wall clock (s), for progress lines and timings. */
double vl_cli_now_s(void);

/* Checks an output folder before anything is computed: creates it (and
 * its parents) if missing, and makes sure it is a folder the program can
 * write in (a probe file is created and removed). VL_OK, else VL_EIO with
 * a message naming the folder and the option that gave it. */
vl_status vl_cli_check_out_dir(const char *option, const char *path, vl_error *err);

/* The model-validity warnings of points pts[0..n) (vl_point.warnings), one
 * line per kind ("warning: [label: ]TEXT — points 1-45 of 45 (v0 = ...)"),
 * a number that varies over the points shown as its range; for n = 1
 * without the points. label may be NULL. Returns the number of lines. */
size_t vl_cli_print_warnings(FILE *out, const char *label, size_t n, const vl_point *pts);

/* The points that did not converge: a line with their count and the exit
 * status, then one line each (speed, iterations, residual; at most ten).
 * where (may be NULL) is appended to the first line. Returns the count. */
size_t vl_cli_print_failures(FILE *out, const char *cmd, const char *label, size_t n,
                             const vl_point *pts, const char *where);

/* Exit status when every point converged but some are above their error
 * target or have no estimate (vl_point_unreliable): a result of its own,
 * after 7 (not converged) in precedence. */
#define VL_CLI_EXIT_UNRELIABLE 8

/* The points that converged but are not known to their error target, on
 * out: how many, and each with its speed and estimate (at most 10); returns
 * the count (0: nothing printed). */
size_t vl_cli_print_unreliable(FILE *out, const char *cmd, const char *label, size_t n,
                               const vl_point *pts);

/* The exit status of a command's points: 7 when some failed, else 8 when
 * some are unreliable, else 0. */
int vl_cli_points_status(size_t failed, size_t unreliable);

/* ---- output folders and their manifests (cli_manifest.c) ---- */

/* Starts the manifest of folder dir (vl_manifest_begin) with the whole
 * command line and the program's version; NULL after the message on
 * stderr ("viscolube CMD: ...") with *rc the exit code. */
vl_manifest *vl_cli_manifest_begin(const vl_cli_globals *g, const char *cmd, const char *dir,
                                   int *rc);

/* Records a material with its database fingerprint (role "compound",
 * "surface", "fluid"); a fingerprint that cannot be read is recorded as
 * "unknown: REASON". */
void vl_cli_manifest_material(vl_manifest *m, vl_db *db, const char *role, const char *name);

/* Records the outcome of writing path: a file written (st VL_OK), else a
 * file that could not be written (with err's message). */
void vl_cli_manifest_file(vl_manifest *m, const char *path, vl_status st, const vl_error *err);

/* The same for the figure stem.png and stem.svg (both formats). */
void vl_cli_manifest_figure(vl_manifest *m, const char *stem, vl_status st, const vl_error *err);

/* Writes the manifest (vl_manifest_finish) and frees it; on stderr the
 * files of the earlier run it removed, the unclaimed ones (unless quiet),
 * and the files that could not be written. Returns rc, or the I/O exit
 * code when files could not be written or the manifest failed. */
int vl_cli_manifest_finish(vl_manifest *m, const char *cmd, int quiet, int rc);

/* Text of a whole (small) file, malloc'd and NUL-terminated; NULL on
 * failure (errno set). */
char *vl_cli_read_text(const char *path);

#endif
