/* What the material nouns share (cli_materials.c): `compound`
 * (cli_compound.c), `surface` (cli_surface.c) and `fluid` (cli_fluid.c).
 *
 * A noun parses its command line, reads and checks every input file, and
 * only then opens the database, so a bad input never creates or touches
 * it. Messages go to stderr as one line each ("viscolube NOUN VERB: ...");
 * results to stdout (text, or JSON with --json). */
#ifndef VL_CLI_MATERIALS_H
#define VL_CLI_MATERIALS_H

#include <stdio.h>

#include "cli.h"
#include "cli_options.h"

#define VL_CLI_TWO_PI 6.283185307179586476925287

/* The command being run: its noun and verb, for messages. */
typedef struct {
  const char *noun; /* "compound" */
  const char *verb; /* "add"; NULL before the verb is known */
} vl_cli_context;

/* A material noun: its texts and its verbs. */
typedef struct {
  const char *name; /* "compound" */
  const char *help; /* `viscolube NOUN --help` */
  /* `NOUN VERB --help` of the verbs the noun words itself; 0 when the verb
   * has the shared text (list, remove, a plain show) */
  int (*verb_help)(const char *verb, FILE *out);
  /* the verbs, each given argv from the noun on; return the exit status */
  int (*add)(const vl_cli_context *cx, const vl_cli_globals *g, int argc, char **argv);
  int (*show)(const vl_cli_context *cx, const vl_cli_globals *g, int argc, char **argv);
  int (*flow_factors)(const vl_cli_context *cx, const vl_cli_globals *g, int argc,
                      char **argv); /* NULL: no such verb */
  /* `list`: every item as a line or (json) into w; the status */
  vl_status (*list)(vl_db *db, vl_json *w, int json, vl_error *err);
  vl_status (*remove)(vl_db *db, const char *name, vl_error *err);
} vl_cli_noun;

extern const vl_cli_noun vl_cli_compound_noun, vl_cli_surface_noun, vl_cli_fluid_noun;

/* One message "viscolube NOUN VERB: msg" on stderr; the exit status of st. */
int vl_cli_fail(const vl_cli_context *cx, vl_status st, const char *msg);
int vl_cli_failf(const vl_cli_context *cx, vl_status st, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Parses argv[2..) (after NOUN VERB) by the table opts, the positionals
 * into pos (at most max_pos, *n_pos of them) in the material commands'
 * strict way (vl_cli_parse with VL_CLI_STRICT). -1 when all were fine,
 * else the exit status after the message. */
int vl_cli_material_args(const vl_cli_context *cx, int argc, char **argv, vl_cli_option *opts,
                         size_t n_opts, const char **pos, size_t max_pos, size_t *n_pos);

/* The NAME positional of show/add/remove (pos[0], n_pos of them), checked
 * into *name. -1, else the exit status after the message. */
int vl_cli_need_name(const vl_cli_context *cx, const char **pos, size_t n_pos, const char **name);

/* The verbs on one material (show, add, remove, flow-factors): argv[2..)
 * parsed by the table opts (vl_cli_material_args) with the NAME checked
 * into *name, then, when db is not NULL, the database opened into *db. -1,
 * else the exit status after the message. */
int vl_cli_named_args(const vl_cli_context *cx, const vl_cli_globals *g, int argc, char **argv,
                      vl_cli_option *opts, size_t n_opts, const char **name, vl_db **db);

/* Opens the database into *db: -1, else the exit status after the message. */
int vl_cli_open_db(const vl_cli_context *cx, const vl_cli_globals *g, vl_db **db);

/* A numeric option's text (the strict syntax, vl_cli_number) into *out:
 * -1, else the exit status after "option NAME: WHY (got 'TEXT')". */
int vl_cli_number_opt(const vl_cli_context *cx, const char *name, const char *text, double *out);

/* The same, when text is given (not NULL), for a number that must lie
 * within r's lo and hi: else "option NAME: R->BAD (got 'TEXT')". */
int vl_cli_number_in(const vl_cli_context *cx, const char *name, const char *text,
                     const vl_cli_number_rule *r, double *out);

/* A temperature in C (--tref): not below absolute zero. */
extern const vl_cli_number_rule vl_cli_tref_rule;

/* --description (may be NULL) short enough to store: -1, else the exit
 * status after the message. */
int vl_cli_check_description(const vl_cli_context *cx, const char *text);

/* Materials are printed exactly (json.h digits 0): what was stored reads
 * back bit for bit. */
void vl_cli_json_start(vl_json *w, FILE *out);

/* A stored text that may be empty (a file name): null when it is. */
void vl_cli_key_text_or_null(vl_json *w, const char *key, const char *v);

/* Prints an import's notes (one sentence per line) on stderr: lines
 * starting "warning: " as they are, the others as "note: ". Nothing when
 * quiet. */
void vl_cli_print_notes(const vl_cli_globals *g, const char *notes);

/* The figure's stem: FILE without its extension ("dir/.hidden" keeps its
 * name). */
void vl_cli_file_stem(char *stem, size_t size, const char *file);

#endif
