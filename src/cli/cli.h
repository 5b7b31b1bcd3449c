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

/* mkdir -p: creates path and its missing parents (0 on success, -1 with
 * errno set). */
int vl_cli_make_dirs(const char *path);

#endif
