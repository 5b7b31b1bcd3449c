/* `viscolube compound|surface|fluid VERB ...`: the material commands.
 *
 * What the nouns share: messages, the command line (the option tables of
 * cli_options.c in their strict form), the database, and the verbs whose
 * shape is the same for every noun (list, remove, the dispatch). Each noun
 * is a file of its own (cli_compound.c, cli_surface.c, cli_fluid.c) behind
 * a vl_cli_noun (cli_materials.h). */
#define _POSIX_C_SOURCE 200809L

#include "cli_materials.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- messages --------------------------------------------------------- */

int vl_cli_fail(const vl_cli_context *cx, vl_status st, const char *msg) {
  if (cx->verb)
    fprintf(stderr, "viscolube %s %s: %s\n", cx->noun, cx->verb, msg);
  else
    fprintf(stderr, "viscolube %s: %s\n", cx->noun, msg);
  return vl_status_exit_code(st);
}

int vl_cli_failf(const vl_cli_context *cx, vl_status st, const char *fmt, ...) {
  char buf[VL_ERROR_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  return vl_cli_fail(cx, st, buf);
}

/* ---- the command line ------------------------------------------------- */

int vl_cli_material_args(const vl_cli_context *cx, int argc, char **argv, vl_cli_option *opts,
                         size_t n_opts, const char **pos, size_t max_pos, size_t *n_pos) {
  char cmd[64];
  snprintf(cmd, sizeof cmd, "%s %s", cx->noun, cx->verb);
  /* the extra format is given the first positional too: printed with no room */
  vl_cli_parser p = vl_cli_file_command(
      cmd, opts, n_opts, pos, "%.0sunexpected argument '%s' (see viscolube %s --help)", NULL);
  p.flags = VL_CLI_STRICT;
  p.missing = "option %s needs a value (%s)";
  p.max_pos = max_pos;
  int rc = vl_cli_parse(&p, argc, argv, 2);
  *n_pos = p.n_pos;
  return rc;
}

int vl_cli_need_name(const vl_cli_context *cx, const char **pos, size_t n_pos, const char **name) {
  if (n_pos < 1)
    return vl_cli_failf(cx, VL_EINPUT, "missing NAME (see viscolube %s %s --help)", cx->noun,
                        cx->verb);
  vl_error err;
  if (vl_db_check_name(pos[0], &err) != VL_OK) return vl_cli_fail(cx, VL_EINPUT, err.msg);
  *name = pos[0];
  return -1;
}

int vl_cli_named_args(const vl_cli_context *cx, const vl_cli_globals *g, int argc, char **argv,
                      vl_cli_option *opts, size_t n_opts, const char **name, vl_db **db) {
  const char *pos[1] = {NULL};
  size_t n_pos;
  int rc = vl_cli_material_args(cx, argc, argv, opts, n_opts, pos, 1, &n_pos);
  if (rc < 0) rc = vl_cli_need_name(cx, pos, n_pos, name);
  if (rc < 0 && db) rc = vl_cli_open_db(cx, g, db);
  return rc;
}

int vl_cli_open_db(const vl_cli_context *cx, const vl_cli_globals *g, vl_db **db) {
  vl_error err;
  vl_status st = vl_db_open(g->db_path, db, &err);
  if (st != VL_OK) return vl_cli_fail(cx, st, err.msg);
  return -1;
}

int vl_cli_number_opt(const vl_cli_context *cx, const char *name, const char *text, double *out) {
  const char *why;
  if (!vl_cli_number(text, out, &why))
    return vl_cli_failf(cx, VL_EINPUT, "option %s: %s (got '%s')", name, why, text);
  return -1;
}

const vl_cli_number_rule vl_cli_tref_rule = {
    .lo = -273.15, .hi = INFINITY, .bad = "below absolute zero"};

int vl_cli_number_in(const vl_cli_context *cx, const char *name, const char *text,
                     const vl_cli_number_rule *r, double *out) {
  if (!text) return -1;
  int rc = vl_cli_number_opt(cx, name, text, out);
  if (rc >= 0) return rc;
  if ((r->lo_open ? *out > r->lo : *out >= r->lo) && *out <= r->hi) return -1;
  return vl_cli_failf(cx, VL_EINPUT, "option %s: %s (got '%s')", name, r->bad, text);
}

int vl_cli_check_description(const vl_cli_context *cx, const char *text) {
  if (text && strlen(text) >= VL_DB_TEXT_MAX)
    return vl_cli_failf(cx, VL_EINPUT, "option --description: longer than %d characters",
                        VL_DB_TEXT_MAX - 1);
  return -1;
}

/* ---- output ----------------------------------------------------------- */

void vl_cli_json_start(vl_json *w, FILE *out) { vl_json_init(w, out, 0); }

void vl_cli_key_text_or_null(vl_json *w, const char *key, const char *v) {
  vl_json_key_string(w, key, v && *v ? v : NULL);
}

void vl_cli_print_notes(const vl_cli_globals *g, const char *notes) {
  if (g->quiet) return;
  for (const char *l = notes; *l;) {
    size_t n = strcspn(l, "\n");
    if (n) fprintf(stderr, "%s%.*s\n", strncmp(l, "warning: ", 9) ? "note: " : "", (int)n, l);
    l += n + (l[n] == '\n');
  }
}

void vl_cli_file_stem(char *stem, size_t size, const char *file) {
  snprintf(stem, size, "%s", file);
  char *slash = strrchr(stem, '/'), *base = slash ? slash + 1 : stem, *dot = strrchr(base, '.');
  if (dot && dot > base) *dot = '\0';
}

/* ---- the verbs every noun has the same way ---------------------------- */

/* `NOUN list|show|remove --help` where the noun has no text of its own. */
static void shared_verb_help(const char *noun, const char *verb, FILE *out) {
  if (!strcmp(verb, "list")) {
    fprintf(out,
            "usage: viscolube [--db PATH] %s list [--json]\n"
            "\n"
            "Lists every %s, one per line, sorted by name.\n"
            "  --json   print a JSON array of objects instead (the fields of `%s show --json`)\n",
            noun, noun, noun);
  } else if (!strcmp(verb, "show")) {
    fprintf(out,
            "usage: viscolube [--db PATH] %s show NAME [--json]\n"
            "\n"
            "Prints what is stored about %s NAME and the quantities derived from it.\n"
            "  --json   print one JSON object instead\n",
            noun, noun);
  } else {
    fprintf(out,
            "usage: viscolube [--db PATH] %s remove NAME\n"
            "\n"
            "Deletes %s NAME (and everything that belongs to it) in one transaction.\n",
            noun, noun);
  }
}

static int do_list(const vl_cli_noun *noun, const vl_cli_context *cx, const vl_cli_globals *g,
                   int argc, char **argv) {
  int json = 0;
  vl_cli_option opts[] = {{.name = "--json", .kind = VL_CLI_FLAG, .dest = &json}};
  size_t n_pos;
  int rc;
  if ((rc = vl_cli_material_args(cx, argc, argv, opts, 1, NULL, 0, &n_pos)) >= 0) return rc;
  vl_db *db = NULL;
  if ((rc = vl_cli_open_db(cx, g, &db)) >= 0) return rc;
  vl_error err;
  vl_json w;
  vl_cli_json_start(&w, stdout);
  if (json) vl_json_array_begin(&w, VL_JSON_STACKED);
  vl_status st = noun->list(db, &w, json, &err);
  if (json) {
    vl_json_end(&w);
    fputc('\n', stdout);
  }
  vl_db_close(db);
  return st == VL_OK ? 0 : vl_cli_fail(cx, st, err.msg);
}

static int do_remove(const vl_cli_noun *noun, const vl_cli_context *cx, const vl_cli_globals *g,
                     int argc, char **argv) {
  const char *name = NULL;
  vl_db *db = NULL;
  int rc = vl_cli_named_args(cx, g, argc, argv, NULL, 0, &name, &db);
  if (rc >= 0) return rc;
  vl_error err;
  vl_status st = noun->remove(db, name, &err);
  if (st == VL_OK) printf("removed %s '%s' from %s\n", cx->noun, name, vl_db_path(db));
  vl_db_close(db);
  return st == VL_OK ? 0 : vl_cli_fail(cx, st, err.msg);
}

/* ---- entry point ------------------------------------------------------ */

/* The verb argv[1] of noun, known: 1, else 0. */
static int known_verb(const vl_cli_noun *noun, const char *verb) {
  static const char *const verbs[] = {"list", "show", "add", "remove"};
  for (size_t k = 0; k < sizeof verbs / sizeof verbs[0]; k++)
    if (!strcmp(verb, verbs[k])) return 1;
  return noun->flow_factors && !strcmp(verb, "flow-factors");
}

int vl_cli_materials(const vl_cli_globals *g, int argc, char **argv) {
  vl_cli_context cx = {.noun = argv[0]};
  const vl_cli_noun *noun = !strcmp(argv[0], "compound")  ? &vl_cli_compound_noun
                            : !strcmp(argv[0], "surface") ? &vl_cli_surface_noun
                            : !strcmp(argv[0], "fluid")   ? &vl_cli_fluid_noun
                                                          : NULL;
  if (!noun) return vl_cli_fail(&cx, VL_EINTERNAL, "not a material noun");
  if (argc < 2) {
    fputs(noun->help, stderr);
    return vl_status_exit_code(VL_EINPUT);
  }
  const char *verb = argv[1];
  if (!strcmp(verb, "--help") || !strcmp(verb, "-h") || !strcmp(verb, "help")) {
    fputs(noun->help, stdout);
    return 0;
  }
  if (!known_verb(noun, verb))
    return vl_cli_failf(&cx, VL_EINPUT,
                        "unknown verb '%s' (expected list, show, add%s or remove; see "
                        "viscolube %s --help)",
                        verb, noun->flow_factors ? ", flow-factors" : "", cx.noun);
  cx.verb = verb;
  /* --help anywhere after the verb wins, so a half-typed command can ask. */
  for (int i = 2; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      if (!noun->verb_help(verb, stdout)) shared_verb_help(noun->name, verb, stdout);
      return 0;
    }
  }
  if (!strcmp(verb, "list")) return do_list(noun, &cx, g, argc, argv);
  if (!strcmp(verb, "show")) return noun->show(&cx, g, argc, argv);
  if (!strcmp(verb, "remove")) return do_remove(noun, &cx, g, argc, argv);
  if (!strcmp(verb, "flow-factors")) return noun->flow_factors(&cx, g, argc, argv);
  return noun->add(&cx, g, argc, argv);
}
