/* The command line's internal interface: one entry point per noun. */
#ifndef VL_CLI_H
#define VL_CLI_H

/* The program uses the library through its public header only. */
#include "viscolube.h"

typedef struct {
  const char *db_path; /* --db PATH, else $VISCOLUBE_DB, else NULL = default */
} vl_cli_globals;

/* `compound|surface|fluid VERB ...` (argv[0] is the noun). Returns exit code. */
int vl_cli_materials(const vl_cli_globals *g, int argc, char **argv);

/* `run SCENE [--out DIR] [--json]` (argv[0] is "run"). Returns exit code. */
int vl_cli_run(const vl_cli_globals *g, int argc, char **argv);

/* `friction --compound C --surface S --fluid F --speed V ...`. */
int vl_cli_friction(const vl_cli_globals *g, int argc, char **argv);

/* `compare --compounds A,B --surface S --fluid F ...`. */
int vl_cli_compare(const vl_cli_globals *g, int argc, char **argv);

/* `surface flow-factors NAME` options as given (NULL or 0 when absent);
 * cli_materials.c parses the command line, vl_cli_surface_flow_factors
 * checks the values. */
typedef struct {
  const char *model, *u_range, *points, *film_cutoff, *out;
  int json, plot;
} vl_cli_flow_factor_args;

/* `surface flow-factors` for surface name (a valid name), in
 * cli_surface.c. Returns the exit code. */
int vl_cli_surface_flow_factors(const vl_cli_globals *g, const char *name,
                                const vl_cli_flow_factor_args *a);

/* `surface add NAME --topography FILE [--description TEXT]` (description
 * may be NULL), in cli_surface.c. Returns the exit code. */
int vl_cli_surface_add_topography(const vl_cli_globals *g, const char *name, const char *path,
                                  const char *description);

/* mkdir -p: creates path and its missing parents (0 on success, -1 with
 * errno set). */
int vl_cli_make_dirs(const char *path);

#endif
