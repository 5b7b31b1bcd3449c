/* `viscolube compound|surface|fluid VERB ...`: the dispatch of the
 * material commands to their noun (cli_compound.c, cli_surface.c,
 * cli_fluid.c), and the verbs whose shape is the same for every noun (list,
 * remove). */
#define _POSIX_C_SOURCE 200809L

#include "cli_materials.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
  size_t pairs = 0; /* its pairs go with it (ON DELETE CASCADE): say so */
  if (vl_db_pair_count(db, cx->noun, name, &pairs, &err) != VL_OK) pairs = 0;
  vl_status st = noun->remove(db, name, &err);
  if (st == VL_OK && pairs)
    printf("removed %s '%s' from %s, and its %zu pair%s\n", cx->noun, name, vl_db_path(db), pairs,
           pairs > 1 ? "s" : "");
  else if (st == VL_OK)
    printf("removed %s '%s' from %s\n", cx->noun, name, vl_db_path(db));
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
