/* What the material commands (`viscolube compound|surface|fluid VERB ...`)
 * share: messages, the command line (the option tables of cli_options.c in
 * their strict form), the database. Each noun is a file of its own
 * (cli_compound.c, cli_surface.c, cli_fluid.c) behind a vl_cli_noun
 * (cli_materials.h), dispatched by cli_nouns.c with the verbs every noun
 * has the same way; this file calls none of them. */
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
