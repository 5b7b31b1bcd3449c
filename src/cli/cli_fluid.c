/* `viscolube fluid VERB ...`: Newtonian lubricants, their viscosity at a
 * reference temperature and an optional viscosity-temperature law. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_materials.h"

/* ---- help ------------------------------------------------------------- */

static const char fluid_help[] =
    "usage: viscolube [--db PATH] fluid VERB ...\n"
    "\n"
    "Newtonian lubricants: low-shear viscosity at a reference temperature.\n"
    "\n"
    "verbs:\n"
    "  list [--json]          one line per fluid: name, viscosity\n"
    "  show NAME [--json]     viscosity, reference temperature, description\n"
    "  add NAME --viscosity PA_S [--tref C] [--description TEXT]\n"
    "  remove NAME            delete a fluid\n"
    "\n"
    "`viscolube fluid VERB --help` describes a verb.\n";

/* `fluid add --help` */
static const char fluid_add_help[] =
    "usage: viscolube [--db PATH] fluid add NAME --viscosity PA_S [--tref C]\n"
    "                 [--vogel-b K --vogel-c K --law-range TMIN_C,TMAX_C]\n"
    "                 [--description TEXT]\n"
    "\n"
    "Registers a Newtonian lubricant.\n"
    "  --viscosity PA_S   low-shear viscosity > 0, Pa s (water at 20 C: 1.0e-3)\n"
    "  --tref C           temperature the viscosity was measured at, Celsius\n"
    "                     (default 20)\n"
    "  --vogel-b K, --vogel-c K, --law-range TMIN_C,TMAX_C\n"
    "                     optional viscosity-temperature law (all three or none):\n"
    "                     log10 eta = A + B/(T - C), T in K, anchored at the viscosity\n"
    "                     at tref, trusted from TMIN to TMAX C (the range of its data;\n"
    "                     it must hold tref). Without a law the fluid is known at tref\n"
    "                     only (scenes with temperature = on at another temperature\n"
    "                     are refused). Water: B 247.8, C 140, range 0,100.\n"
    "  --description TEXT free text; note the source of the data here\n";

/* ---- output ------------------------------------------------------------- */

static void fluid_json(vl_json *w, const vl_db_fluid *f) {
  vl_json_object_begin(w, VL_JSON_INLINE);
  vl_json_key_string(w, "name", f->name);
  vl_json_key_number(w, "viscosity_pa_s", f->viscosity_pa_s);
  vl_json_key_number(w, "tref_c", f->tref_c);
  /* the viscosity law: all null when none is stored */
  int law = f->law.kind != VL_VISCOSITY_LAW_NONE;
  vl_cli_key_text_or_null(w, "viscosity_law", law ? vl_viscosity_law_name(f->law.kind) : "");
  vl_json_key_number(w, "vogel_b_k", law ? f->law.vogel_b_k : NAN);
  vl_json_key_number(w, "vogel_c_k", law ? f->law.vogel_c_k : NAN);
  vl_json_key_number(w, "law_tmin_c", law ? f->law.tmin_c : NAN);
  vl_json_key_number(w, "law_tmax_c", law ? f->law.tmax_c : NAN);
  vl_json_key_string(w, "description", f->description);
  vl_cli_key_text_or_null(w, "source_file", f->source_file);
  vl_json_key_string(w, "created_at", f->created_at);
  vl_json_end(w);
}

static void fluid_text(FILE *out, const vl_db_fluid *f) {
  fprintf(out, "fluid %s\n", f->name);
  if (f->description[0]) fprintf(out, "  description   %s\n", f->description);
  fprintf(out, "  viscosity     %.6g Pa s at %.6g C\n", f->viscosity_pa_s, f->tref_c);
  if (f->law.kind == VL_VISCOSITY_LAW_VOGEL) {
    const vl_viscosity_law *l = &f->law;
    fprintf(out, "  law           Vogel: log10 eta = A + %.6g K / (T - %.6g K), %.6g to %.6g C\n",
            l->vogel_b_k, l->vogel_c_k, l->tmin_c, l->tmax_c);
    /* the law's ends, so its size is seen at a glance */
    double lo = NAN, hi = NAN;
    if (vl_fluid_viscosity(l, f->viscosity_pa_s, f->tref_c, l->tmin_c, &lo, NULL) == VL_OK &&
        vl_fluid_viscosity(l, f->viscosity_pa_s, f->tref_c, l->tmax_c, &hi, NULL) == VL_OK)
      fprintf(out,
              "                (through the viscosity above; %.4g Pa s at %.6g C, "
              "%.4g Pa s at %.6g C)\n",
              lo, l->tmin_c, hi, l->tmax_c);
  } else {
    fprintf(out, "  law           none (known at %.6g C only)\n", f->tref_c);
  }
  fprintf(out, "  created       %s\n", f->created_at);
}

static void fluid_line(FILE *out, const vl_db_fluid *f) {
  fprintf(out, "%-20s viscosity %-10.4g Pa s at %.4g C\n", f->name, f->viscosity_pa_s, f->tref_c);
}

/* --vogel-b, --vogel-c and --law-range (all three or none) into f's law:
 * -1, else the exit status after the message. */
static int fluid_law(const vl_cli_context *cx, const char *b, const char *c, const char *range,
                     vl_db_fluid *f) {
  int n_law = (b != NULL) + (c != NULL) + (range != NULL), rc;
  if (n_law != 0 && n_law != 3)
    return vl_cli_fail(cx, VL_EINPUT, "options --vogel-b, --vogel-c and --law-range go together");
  if (n_law == 0) return -1;
  f->law.kind = VL_VISCOSITY_LAW_VOGEL;
  if ((rc = vl_cli_number_opt(cx, "--vogel-b", b, &f->law.vogel_b_k)) >= 0) return rc;
  if ((rc = vl_cli_number_opt(cx, "--vogel-c", c, &f->law.vogel_c_k)) >= 0) return rc;
  if (!vl_cli_number_pair(range, &f->law.tmin_c, &f->law.tmax_c))
    return vl_cli_failf(cx, VL_EINPUT, "option --law-range: expected TMIN_C,TMAX_C (got '%s')",
                        range);
  return -1;
}

/* The options of `fluid add NAME` into f: -1, else the exit status after
 * the message. */
static int fluid_add_args(const vl_cli_context *cx, int argc, char **argv, vl_db_fluid *f) {
  const char *viscosity = NULL, *tref = NULL, *vogel_b = NULL, *vogel_c = NULL, *range = NULL,
             *desc = NULL, *name = NULL;
  vl_cli_option opts[] = {
      {.name = "--viscosity", .kind = VL_CLI_TEXT, .metavar = "PA_S", .dest = &viscosity},
      {.name = "--tref", .kind = VL_CLI_TEXT, .metavar = "C", .dest = &tref},
      {.name = "--vogel-b", .kind = VL_CLI_TEXT, .metavar = "K", .dest = &vogel_b},
      {.name = "--vogel-c", .kind = VL_CLI_TEXT, .metavar = "K", .dest = &vogel_c},
      {.name = "--law-range", .kind = VL_CLI_TEXT, .metavar = "TMIN_C,TMAX_C", .dest = &range},
      {.name = "--description", .kind = VL_CLI_TEXT, .metavar = "TEXT", .dest = &desc},
  };
  int rc = vl_cli_named_args(cx, NULL, argc, argv, opts, sizeof opts / sizeof opts[0], &name, NULL);
  if (rc >= 0) return rc;
  memset(f, 0, sizeof *f);
  snprintf(f->name, sizeof f->name, "%s", name);
  f->tref_c = 20.0;
  if (!viscosity) return vl_cli_fail(cx, VL_EINPUT, "option --viscosity PA_S is required");
  static const vl_cli_number_rule positive = {
      .lo = 0.0, .lo_open = 1, .hi = INFINITY, .bad = "must be > 0 Pa s"};
  if ((rc = vl_cli_number_in(cx, "--viscosity", viscosity, &positive, &f->viscosity_pa_s)) >= 0 ||
      (rc = vl_cli_number_in(cx, "--tref", tref, &vl_cli_tref_rule, &f->tref_c)) >= 0)
    return rc;
  if ((rc = vl_cli_check_description(cx, desc)) >= 0) return rc;
  if (desc) snprintf(f->description, sizeof f->description, "%s", desc);
  return fluid_law(cx, vogel_b, vogel_c, range, f);
}

static int fluid_add(const vl_cli_context *cx, const vl_cli_globals *g, int argc, char **argv) {
  vl_db_fluid f;
  int rc = fluid_add_args(cx, argc, argv, &f);
  if (rc >= 0) return rc;
  vl_db *db = NULL;
  vl_error err;
  if ((rc = vl_cli_open_db(cx, g, &db)) < 0) {
    vl_status st = vl_db_fluid_add(db, &f, &err);
    if (st != VL_OK) {
      rc = vl_cli_fail(cx, st, err.msg);
    } else {
      printf("added fluid '%s' to %s: viscosity %.6g Pa s at %.6g C%s\n", f.name, vl_db_path(db),
             f.viscosity_pa_s, f.tref_c,
             f.law.kind != VL_VISCOSITY_LAW_NONE ? ", with a Vogel viscosity law" : "");
      rc = 0;
    }
  }
  vl_db_close(db);
  return rc;
}

static int fluid_show(const vl_cli_context *cx, const vl_cli_globals *g, int argc, char **argv) {
  int json = 0;
  vl_cli_option opts[] = {{.name = "--json", .kind = VL_CLI_FLAG, .dest = &json}};
  const char *name = NULL;
  vl_db *db = NULL;
  int rc = vl_cli_named_args(cx, g, argc, argv, opts, 1, &name, &db);
  if (rc >= 0) return rc;
  vl_error err;
  vl_db_fluid f;
  vl_status st = vl_db_fluid_info(db, name, &f, &err);
  if (st == VL_OK && json) {
    vl_json w;
    vl_cli_json_start(&w, stdout);
    fluid_json(&w, &f);
    fputc('\n', stdout);
  } else if (st == VL_OK) {
    fluid_text(stdout, &f);
  }
  vl_db_close(db);
  return st == VL_OK ? 0 : vl_cli_fail(cx, st, err.msg);
}

static vl_status fluid_list(vl_db *db, vl_json *w, int json, vl_error *err) {
  vl_db_fluid *items;
  size_t n = 0;
  vl_status st = vl_db_fluid_list(db, &items, &n, err);
  if (st != VL_OK) return st;
  for (size_t i = 0; i < n; i++) {
    if (json)
      fluid_json(w, &items[i]);
    else
      fluid_line(stdout, &items[i]);
  }
  free(items);
  return VL_OK;
}

static int fluid_verb_help(const char *verb, FILE *out) {
  if (strcmp(verb, "add")) return 0;
  fputs(fluid_add_help, out);
  return 1;
}

/* name, help, verb_help, add, show, flow_factors, list, remove */
const vl_cli_noun vl_cli_fluid_noun = {"fluid",    fluid_help, fluid_verb_help, fluid_add,
                                       fluid_show, NULL,       fluid_list,      vl_db_fluid_remove};
