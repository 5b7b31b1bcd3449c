/* The option parser and the number parser of every command (cli_options.h). */
#include "cli_options.h"

#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
/* The library's edit distance, the one behind the "did you mean" of scene
 * keys and material names. Its header is private to the library (not in
 * include/): the only private header the program includes. */
#include "viscolube/edit_distance.h"

/* One message "viscolube CMD: ..." (or "viscolube: ..." without a command)
 * on stderr; the exit status of bad input. */
static int failv(const char *cmd, const char *fmt, ...) {
  va_list ap;
  fprintf(stderr, "viscolube%s%s: ", cmd ? " " : "", cmd ? cmd : "");
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
  return vl_status_exit_code(VL_EINPUT);
}

int vl_cli_number(const char *text, double *out, const char **why) {
  const char *w = NULL;
  double d = 0.0;
  if (!text || vl_csv_parse_double(text, &d, &w) != VL_OK) {
    if (why) *why = w ? w : "not a number";
    return 0;
  }
  *out = d;
  return 1;
}

int vl_cli_number_checked(const char *cmd, const char *name, const char *text,
                          const vl_cli_number_rule *rule, double *out) {
  double d = 0.0;
  int parsed = vl_cli_number(text, &d, NULL);
  int above_lo = rule->lo_open ? d > rule->lo : d >= rule->lo;
  int within = d <= rule->hi && !(rule->whole && d != floor(d));
  if (!parsed || !above_lo || (!rule->range && !within)) {
    failv(cmd, rule->bad, name, text ? text : "");
    return 0;
  }
  if (rule->range && (d < rule->range_lo || !within)) {
    failv(cmd, rule->range, name, text);
    return 0;
  }
  *out = d;
  return 1;
}

int vl_cli_number_pair(const char *text, double *lo, double *hi) {
  const char *comma = strchr(text, ',');
  char first[64];
  size_t len = comma ? (size_t)(comma - text) : 0;
  if (!comma || len >= sizeof first) return 0;
  memcpy(first, text, len);
  first[len] = '\0';
  return vl_cli_number(first, lo, NULL) && vl_cli_number(comma + 1, hi, NULL);
}

vl_cli_parser vl_cli_file_command(const char *cmd, vl_cli_option *opts, size_t n_opts,
                                  const char **file, const char *extra, void (*usage)(FILE *)) {
  return (vl_cli_parser){.cmd = cmd,
                         .opts = opts,
                         .n_opts = n_opts,
                         .flags = VL_CLI_DASH_IS_OPTION,
                         .unknown = "unknown option '%s' (see viscolube %s --help)",
                         .missing = "option %s needs a value",
                         .pos = file,
                         .max_pos = 1,
                         .extra = extra,
                         .usage = usage};
}

vl_cli_option *vl_cli_find(vl_cli_parser *p, const char *name) {
  for (size_t k = 0; k < p->n_opts; k++)
    if (!strcmp(p->opts[k].name, name)) return &p->opts[k];
  return NULL;
}

const char *vl_cli_suggest(const vl_cli_parser *p, const char *arg, size_t len) {
  const char *best = NULL;
  size_t best_d = 3; /* at most two edits, as the scene keys' hints */
  if (arg[0] != '-') return NULL;
  for (size_t k = 0; k < p->n_opts; k++) {
    const char *name = p->opts[k].name;
    size_t d = vl_edit_distance(arg, len, name, strlen(name), true);
    if (d < best_d) best_d = d, best = name;
  }
  return best;
}

/* An argument that is no option of the table: an unknown option, with the
 * nearest name when there is one. */
static int unknown(const vl_cli_parser *p, const char *arg, size_t len) {
  char shown[256];
  snprintf(shown, sizeof shown, "%.*s", (int)(len < 200 ? len : 200), arg);
  const char *near = vl_cli_suggest(p, arg, len);
  if (near) return failv(p->cmd, "unknown option '%s' (did you mean %s?)", shown, near);
  return failv(p->cmd, p->unknown, shown, p->cmd);
}

/* Whether a is a positional argument rather than an option. */
static bool looks_positional(const vl_cli_parser *p, const char *a) {
  if (p->flags & VL_CLI_DASH_IS_OPTION) return a[0] != '-';
  if (p->flags & VL_CLI_STRICT)
    return !(a[0] == '-' && a[1] == '-' && a[2] != '\0') &&
           !(a[0] == '-' && a[1] != '\0' && !(a[1] >= '0' && a[1] <= '9') && a[1] != '.');
  return a[0] != '-';
}

/* The option argument a names (strict: the part before '='), or NULL. */
static vl_cli_option *match(vl_cli_parser *p, const char *a, const char **eq, size_t *len) {
  *eq = (p->flags & VL_CLI_STRICT) && a[0] == '-' && a[1] == '-' ? strchr(a, '=') : NULL;
  *len = *eq ? (size_t)(*eq - a) : strlen(a);
  for (size_t k = 0; k < p->n_opts; k++) {
    const vl_cli_option *o = &p->opts[k];
    if ((strlen(o->name) == *len && !strncmp(o->name, a, *len)) ||
        (o->alias && !*eq && !strcmp(o->alias, a)))
      return &p->opts[k];
  }
  return NULL;
}

/* The value of option o met at argv[*i] (eq: its "=value" part, strict
 * only): 1 with *value, else 0 with *value NULL when it is missing. */
static int take_value(const vl_cli_parser *p, const char *eq, int argc, char **argv, int *i,
                      const char **value) {
  *value = NULL;
  if (eq) {
    *value = eq + 1;
    return 1;
  }
  /* strict: a following "--x" is another option, not this one's value; a
   * negative number ("-0.3") is a value, so that it can be checked */
  if (*i + 1 >= argc ||
      ((p->flags & VL_CLI_STRICT) && argv[*i + 1][0] == '-' && argv[*i + 1][1] == '-'))
    return 0;
  *value = argv[++*i];
  return 1;
}

/* The message of option o without its value. */
static int missing(const vl_cli_parser *p, const vl_cli_option *o) {
  const char *fmt = o->missing ? o->missing : p->missing;
  if (fmt) return failv(p->cmd, fmt, o->name, o->metavar ? o->metavar : "");
  if (o->kind == VL_CLI_CHOICE) return failv(p->cmd, o->choice_bad, o->name, "");
  if (o->kind == VL_CLI_NUMBER) return failv(p->cmd, o->rule->bad, o->name, "");
  return failv(p->cmd, "option %s needs a value", o->name);
}

/* Comma-separated positive numbers (strict syntax) into o's destination:
 * -1, else the exit status after the message. */
static int store_list(const vl_cli_parser *p, vl_cli_option *o, const char *text) {
  char buf[2048];
  double *vals = o->dest;
  size_t *n = o->n_values;
  if (strlen(text) >= sizeof buf)
    return failv(p->cmd, "option %s needs a comma-separated list", o->name);
  snprintf(buf, sizeof buf, "%s", text);
  *n = 0;
  char *save = NULL;
  for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
    double d = 0.0;
    if (*n == o->max_values)
      return failv(p->cmd, "option %s takes at most %zu values", o->name, o->max_values);
    if (!vl_cli_number(t, &d, NULL) || !(d > 0.0))
      return failv(p->cmd, "option %s needs positive numbers (got '%s')", o->name, t);
    vals[(*n)++] = d;
  }
  if (*n == 0) return failv(p->cmd, "option %s needs at least one value", o->name);
  return -1;
}

/* Stores value into o's destination by its kind: -1, else the exit status
 * after the message. */
static int store(const vl_cli_parser *p, vl_cli_option *o, const char *value) {
  if (o->kind == VL_CLI_TEXT) {
    *(const char **)o->dest = value;
  } else if (o->kind == VL_CLI_LIST) {
    return store_list(p, o, value);
  } else if (o->kind == VL_CLI_NUMBER) {
    if (!vl_cli_number_checked(p->cmd, o->name, value, o->rule, o->dest))
      return vl_status_exit_code(VL_EINPUT);
  } else {
    int k = 0;
    while (o->choices[k] && strcmp(o->choices[k], value))
      k++;
    if (!o->choices[k]) return failv(p->cmd, o->choice_bad, o->name, value);
    *(int *)o->dest = k;
  }
  return -1;
}

/* Option o met at argv[*i]: its value taken and stored. -1 to go on,
 * VL_CLI_HELP_ASKED, else the exit status after the message. */
static int one_option(vl_cli_parser *p, vl_cli_option *o, const char *eq, int argc, char **argv,
                      int *i) {
  int strict = (p->flags & VL_CLI_STRICT) != 0;
  if (strict && o->given) return failv(p->cmd, "option %s is given twice", o->name);
  o->given++;
  if (o->kind == VL_CLI_HELP) return VL_CLI_HELP_ASKED;
  if (o->kind == VL_CLI_FLAG) {
    if (eq) return failv(p->cmd, "option %s takes no value", o->name);
    if (o->dest) *(int *)o->dest = 1;
    return -1;
  }
  const char *value;
  if (!take_value(p, eq, argc, argv, i, &value)) return missing(p, o);
  if (strict && value[0] == '\0')
    return failv(p->cmd, "option %s needs a non-empty value (%s)", o->name, o->metavar);
  int rc = store(p, o, value);
  return rc == -1 && o->check ? o->check(p->cmd, o->ctx) : rc;
}

int vl_cli_parse(vl_cli_parser *p, int argc, char **argv, int first) {
  p->n_pos = 0;
  p->next = argc;
  for (int i = first; i < argc; i++) {
    const char *a = argv[i], *eq;
    size_t len;
    vl_cli_option *o = match(p, a, &eq, &len);
    p->next = i;
    if (o) {
      int rc = one_option(p, o, eq, argc, argv, &i);
      if (rc == VL_CLI_HELP_ASKED && p->usage) {
        p->usage(stdout);
        return 0;
      }
      if (rc != -1) return rc;
    } else if (looks_positional(p, a) && (p->flags & VL_CLI_STOP_AT_POSITIONAL)) {
      return -1;
    } else if (looks_positional(p, a) && p->n_pos < p->max_pos) {
      p->pos[p->n_pos++] = a;
    } else if (looks_positional(p, a) && p->extra) {
      return failv(p->cmd, p->extra, p->n_pos ? p->pos[0] : "", a, p->cmd);
    } else {
      return unknown(p, a, len);
    }
  }
  p->next = argc;
  return -1;
}
