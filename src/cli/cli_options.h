/* The one option parser of the command line: every command describes its
 * options in a table (name, kind, where the value goes) and hands argv to
 * vl_cli_parse, which stores the values, converts and checks the numbers
 * (vl_cli_number) and answers an unknown option with the nearest known one
 * ("unknown option '--sped' (did you mean --speed?)").
 *
 * The commands grew their own messages for the same mistakes, and the
 * tests and scripts read them: a parser keeps each command's wording in
 * its vl_cli_parser (unknown option, missing value, extra argument). */
#ifndef VL_CLI_OPTIONS_H
#define VL_CLI_OPTIONS_H

#include <stddef.h>
#include <stdio.h>

typedef enum {
  VL_CLI_FLAG,   /* no value: *(int *)dest = 1 */
  VL_CLI_TEXT,   /* a value as given: *(const char **)dest */
  VL_CLI_NUMBER, /* a number checked against its rule at once: *(double *)dest */
  VL_CLI_CHOICE, /* one of choices[]: *(int *)dest = its index */
  VL_CLI_LIST,   /* comma-separated positive numbers: dest double[max_values], *n_values */
  VL_CLI_HELP,   /* --help: parsing stops, the usage is printed (see vl_cli_parse) */
} vl_cli_kind;

/* What a number must be, and what is said when it is not. The messages
 * are printf formats given the option's name and the text as it was typed
 * ("" when the value is missing), in that order. */
typedef struct {
  double lo;         /* the value must be >= lo (> lo when lo_open) */
  int lo_open;       /* 1: lo itself is refused */
  double hi;         /* the value must be <= hi (INFINITY: no bound) */
  int whole;         /* 1: a whole number */
  const char *bad;   /* not a number (strict syntax) or below lo */
  const char *range; /* NULL: bad also above hi or not whole; else said when
                      * below range_lo, above hi or not whole */
  double range_lo;   /* with range: the least value range accepts */
} vl_cli_number_rule;

typedef struct {
  const char *name;               /* "--speed" */
  const char *alias;              /* "-q", or NULL */
  vl_cli_kind kind;               /* what it takes */
  const char *metavar;            /* "V_M_S": the value in messages (NULL for a flag) */
  void *dest;                     /* int *, const char **, double * by kind */
  const vl_cli_number_rule *rule; /* VL_CLI_NUMBER */
  const char *const *choices;     /* VL_CLI_CHOICE, NULL-terminated */
  const char *choice_bad;         /* VL_CLI_CHOICE: format (name, text) */
  const char *missing; /* format (name, metavar) of a missing value; NULL: the parser's */
  size_t max_values;   /* VL_CLI_LIST: room in dest */
  size_t *n_values;    /* VL_CLI_LIST: values stored */
  /* a check of the value as soon as it is stored (NULL: none): -1 when
   * fine, else the exit status after the message */
  int (*check)(const char *cmd, void *ctx);
  void *ctx;
  int given; /* set by vl_cli_parse: times given */
} vl_cli_option;

/* Parser flags. */
enum {
  /* `--name=value` is accepted; a value never starts with "--" (that is
   * the next option: the value is missing); an empty value, an option
   * given twice and a flag given a value are refused */
  VL_CLI_STRICT = 1,
  /* an argument that is no option of the table and starts with '-' is an
   * unknown option ('-' and negative numbers included), the others are
   * positionals. With VL_CLI_STRICT instead, "--x" and "-x" with x not a
   * digit or '.' are options (so "-0.3" is a positional); with neither,
   * an argument not starting with '-' is a positional */
  VL_CLI_DASH_IS_OPTION = 2,
  /* the first positional argument ends the options (the global options
   * before the noun): parsing stops there, next says where */
  VL_CLI_STOP_AT_POSITIONAL = 4,
};

typedef struct {
  const char *cmd;     /* "friction", "compound add": messages start "viscolube CMD: " */
  vl_cli_option *opts; /* the table */
  size_t n_opts;
  unsigned flags;
  const char *unknown; /* format (argument, cmd) of an unknown option without a near one */
  const char *missing; /* format (name, metavar) of an option without its value */
  const char **pos;    /* room for max_pos positional arguments */
  size_t max_pos;
  size_t n_pos;             /* set: how many were given */
  const char *extra;        /* format (first positional or "", this one, cmd) of one too many */
  int next;                 /* set: the argument parsing stopped at (argc: all read) */
  void (*usage)(FILE *out); /* the command's --help text; NULL: the caller prints it */
} vl_cli_parser;

#define VL_CLI_HELP_ASKED (-2)

/* Parses argv[first..argc) by p's table. Returns -1 when every argument
 * was fine, 0 after p's usage on stdout when --help was met (without a
 * usage: VL_CLI_HELP_ASKED), else the exit status (2) after one message on
 * stderr. */
int vl_cli_parse(vl_cli_parser *p, int argc, char **argv, int first);

/* The parser of a command with one file argument (into *file) and options
 * that all start with '-' (`run SCENE`, `study STUDY`): a second file is
 * refused with the format extra (first, this, cmd), --help prints usage,
 * an option without its value "option NAME needs a value". */
vl_cli_parser vl_cli_file_command(const char *cmd, vl_cli_option *opts, size_t n_opts,
                                  const char **file, const char *extra, void (*usage)(FILE *));

/* The option named name in p's table (NULL when none). */
vl_cli_option *vl_cli_find(vl_cli_parser *p, const char *name);

/* The one number syntax of options and CSV cells (vl_csv_parse_double: no
 * hex floats, NaN, Inf or trailing units). 1 with *out set, else 0 with
 * *why (may be NULL) saying what is wrong. */
int vl_cli_number(const char *text, double *out, const char **why);

/* text checked against rule: 1 with *out, else 0 after the rule's message
 * ("viscolube CMD: ..."). */
int vl_cli_number_checked(const char *cmd, const char *name, const char *text,
                          const vl_cli_number_rule *rule, double *out);

/* "MIN,MAX": two numbers, 1 with *lo and *hi, else 0. */
int vl_cli_number_pair(const char *text, double *lo, double *hi);

/* The nearest of the table's names to the unknown option arg (at most two
 * edits, a swap of neighbours counting one), or NULL. */
const char *vl_cli_suggest(const vl_cli_parser *p, const char *arg, size_t len);

#endif
