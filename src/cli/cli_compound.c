/* `viscolube compound VERB ...`: rubber compounds, from a Prony series or
 * fitted to measured DMA data; what is stored and derived (E0, the loss
 * peak, the fit report), its curves and figures. */
#define _POSIX_C_SOURCE 200809L

#include <complex.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_materials.h"

#define TWO_PI VL_CLI_TWO_PI

/* ---- help ------------------------------------------------------------- */

static const char compound_help[] =
    "usage: viscolube [--db PATH] compound VERB ...\n"
    "\n"
    "Rubber compounds: a creep-form Prony series (docs/MODEL.md section 2)\n"
    "  1/E(w) = (1/Einf) [1 + sum_i A_i / (1 - i w tau_i)]\n"
    "\n"
    "verbs:\n"
    "  list [--json]          one line per compound: name, class, E0, Einf, nu, loss peak\n"
    "  show NAME [--json] [--curve FILE]\n"
    "                         E0, Einf, nu, loss-tangent peak, Prony terms, fit report;\n"
    "                         --curve writes measured vs fitted E', E'', tan delta (CSV)\n"
    "  add NAME --prony FILE --e-inf PA --nu NU [--class CLASS] [--description TEXT]\n"
    "  add NAME --measured FILE [--tref C] [--class CLASS] ...\n"
    "                         register a compound from its Prony series or from measured\n"
    "                         DMA data (see `compound add --help`)\n"
    "  remove NAME            delete a compound and its data\n"
    "\n"
    "`viscolube compound VERB --help` describes a verb.\n";

/* `compound show --help` */
static const char compound_show_help[] =
    "usage: viscolube [--db PATH] compound show NAME [--json] [--curve FILE]\n"
    "                                         [--plot [--out DIR]]\n"
    "\n"
    "Prints what is stored about compound NAME and the quantities derived from it:\n"
    "E0, Einf, nu, the loss-tangent peak, the Prony terms and, for a compound fitted\n"
    "to measured data, the fit report (rms and largest relative error of E' and E'',\n"
    "terms, frequency window, WLF constants and the shift of each isotherm).\n"
    "For a fitted compound the loss peak is the largest tan delta within the\n"
    "measured window (the master curve's frequencies at tref; 'its upper end: still\n"
    "rising' when the data stop before the peak); the series' own peak follows as\n"
    "'model peak' when it lies outside that window: extrapolated, not measured.\n"
    "'represented' says how well: the fit's rms errors and the WLF residual against\n"
    "the import's warning thresholds (5 % and 0.2 decades). JSON: loss_peak (the\n"
    "model's), loss_peak_in_window (with at_edge lower/upper/null) and\n"
    "loss_peak_outside_decades (0 inside). `run` and `friction` warn at every point\n"
    "whose asperity frequencies v0 q (q0..q1 of the surface) or contact frequency\n"
    "v0/a lie over a decade outside the measured window at the scene's temperature.\n"
    "  --json        print one JSON object instead\n"
    "  --curve FILE  also write FILE (CSV, one row per measured point, sorted by\n"
    "                reduced frequency): omega_rad_s, frequency_hz, temperature_c,\n"
    "                reduced_omega_rad_s (a_T omega at tref), storage_pa and\n"
    "                storage_fit_pa, loss_pa and loss_fit_pa, tan_delta and\n"
    "                tan_delta_fit (fitted at the reduced frequency), source_line;\n"
    "                plot measured against fitted over reduced_omega_rad_s.\n"
    "  --plot        also draw, as PNG and SVG in DIR (default out/compound-NAME):\n"
    "                moduli (E', E'' and tan delta, measured on the master curve and\n"
    "                the Prony series, log-log) and, for isotherms, shifts (log10 a_T\n"
    "                of each isotherm against temperature with the WLF fit).\n";

/* `compound add --help` */
static const char compound_add_help[] =
    "usage: viscolube [--db PATH] compound add NAME --prony FILE --e-inf PA --nu NU\n"
    "                 [--class model|filled|unfilled|other] [--description TEXT]\n"
    "                 [--tref C] [--wlf-c1 C1 --wlf-c2 C2_K]\n"
    "       viscolube [--db PATH] compound add NAME --measured FILE [--tref C]\n"
    "                 [--class CLASS] [--description TEXT] [--nu NU]\n"
    "                 [--freq-unit Hz|rad/s] [--modulus-unit Pa|kPa|MPa|GPa]\n"
    "                 [--temp-unit C|K] [--terms-per-decade N]\n"
    "                 [--fit-weights relative|modulus] [--moduli tensile|shear]\n"
    "\n"
    "Registers a rubber compound by its creep-form Prony series\n"
    "  1/E(w) = (1/Einf) [1 + sum_i A_i / (1 - i w tau_i)]  (docs/MODEL.md section 2)\n"
    "given directly (--prony) or fitted to measured DMA data (--measured).\n"
    "\n"
    "  NAME            1-63 characters of A-Z a-z 0-9 . _ + -\n"
    "  --class CLASS   model, filled, unfilled or other (default other)\n"
    "  --description TEXT  free text; note the source of the data here\n"
    "\n"
    "From a Prony series:\n"
    "  --prony FILE    CSV with the header line 'A,tau_s' and one term per row:\n"
    "                  A >= 0 (dimensionless), tau_s > 0 (retardation time, s).\n"
    "                  An optional units row '1,s' may follow the header; lines\n"
    "                  starting with '#' are comments. At most 128 terms.\n"
    "  --e-inf PA      glassy (high-frequency) modulus Einf > 0, Pa\n"
    "  --nu NU         Poisson ratio, 0 <= nu <= 0.5\n"
    "  --tref C        reference temperature of the series, Celsius (default 20)\n"
    "  --wlf-c1 C1, --wlf-c2 C2_K  WLF constants of the compound (both or neither)\n"
    "The relaxed modulus is E0 = Einf / (1 + sum A_i).\n"
    "\n"
    "From measured data (--measured FILE), a DMA export as CSV:\n"
    "  header row     column names in any order (case, blanks, '_' and '-' ignored):\n"
    "                   frequency: f, freq, frequency, omega\n"
    "                   E', E'': E', E_stor, storage / E'', E_loss, loss\n"
    "                   or E' with tan delta (tan delta, tan_del, tand)\n"
    "                   or J', J'': J_stor, J_loss (compliances)\n"
    "                   temperature (optional): T, temp, temperature\n"
    "                   set (optional): which isotherm a row belongs to\n"
    "                 A unit may follow a name: 'f [Hz]', 'E' (MPa)'.\n"
    "  units row      optional, right after the header, e.g. 'Hz,MPa,MPa,C':\n"
    "                 Hz or rad/s; Pa, kPa, MPa or GPa (compliances 1/MPa ...);\n"
    "                 C or K; '-' for tan delta and set. Every column needs a unit\n"
    "                 from the header, the units row or these options (which must\n"
    "                 agree with the file where both are given):\n"
    "  --freq-unit Hz|rad/s  --modulus-unit Pa|kPa|MPa|GPa  --temp-unit C|K\n"
    "  isotherms      with a temperature column, rows are grouped by the set column\n"
    "                 or, without one, by runs of rows within 1 K; the isotherms are\n"
    "                 shifted onto each other (time-temperature superposition on\n"
    "                 log E', and log E'' where it superposes as well) and WLF is\n"
    "                 fitted to the shifts (3 or more isotherms).\n"
    "  --tref C       reference temperature of the master curve. Required for a\n"
    "                 file without temperatures (a master curve) and for a single\n"
    "                 isotherm (then equal to its temperature); with several\n"
    "                 isotherms it defaults to the measured temperature nearest 20 C.\n"
    "  --nu NU        Poisson ratio stored with the fit (default 0.5: DMA in tension\n"
    "                 of a nearly incompressible rubber)\n"
    "  --terms-per-decade N  Prony grid density over the master curve (default 2,\n"
    "                 at most 8); terms the data do not need come out zero\n"
    "  --fit-weights relative|modulus  relative (default): J' and J'' rows each by\n"
    "                 their own magnitude, so E' and E'' are fitted to the same\n"
    "                 relative accuracy; modulus: both by |J|, i.e. the complex\n"
    "                 modulus to a relative and tan delta to an absolute accuracy\n"
    "                 (use it when E'' does not superpose, e.g. glassy secondary\n"
    "                 relaxations)\n"
    "  --moduli tensile|shear  what the moduli are, overriding the column names\n"
    "                 (G', G'', |G*| are shear, E', E'', |E*| and generic names tensile);\n"
    "                 shear moduli are converted E = 2 (1 + nu) G with --nu\n"
    "What the import did (columns ignored, conversions, the dialect, isotherms\n"
    "bridged across thin overlaps) is printed on stderr as 'note: ' lines, and what\n"
    "needs attention as 'warning: ' lines (a WLF residual over 0.2 decades, a fit\n"
    "error over 5 % rms, isotherms that do not join); --quiet drops both.\n"
    "Refused with FILE:LINE and the column: non-numeric, NaN/Inf, zero or negative\n"
    "values, unknown/misspelt/missing columns, wrong or mixed units, E' falling\n"
    "with frequency by over 10 %, isotherms that do not superpose, a master curve\n"
    "under one decade, fewer points than Prony terms + 1. Nothing is stored then.\n"
    "The raw points, shifts, master curve and fit are stored in one transaction;\n"
    "`compound show NAME` prints the fit report.\n";

static int compound_verb_help(const char *verb, FILE *out) {
  if (!strcmp(verb, "show")) return fputs(compound_show_help, out), 1;
  if (!strcmp(verb, "add")) return fputs(compound_add_help, out), 1;
  return 0;
}

/* ---- what is stored and derived -------------------------------------------------------- */

typedef struct {
  double e0_pa;
  int has_peak;
  double omega_peak, tan_peak;
  /* a measured compound: the peak within the master curve's window, where
   * data back the series (at_edge -1/+1: tan delta still rises beyond that
   * end), and how many decades the model's own peak lies outside it */
  int has_window_peak, at_edge;
  double omega_window_peak, tan_window_peak;
  double peak_outside_decades; /* < 0 below the window, > 0 above, 0 inside */
} compound_derived;

static compound_derived compound_derive(const vl_db_compound *c, const vl_db_compound_fit *f) {
  compound_derived d = {.e0_pa = vl_prony_e0(&c->prony)};
  d.has_peak = vl_prony_loss_peak(&c->prony, &d.omega_peak, &d.tan_peak, NULL) == VL_OK;
  if (f && f->has_fit)
    d.has_window_peak =
        vl_prony_loss_peak_in(&c->prony, f->omega_min_rad_s, f->omega_max_rad_s,
                              &d.omega_window_peak, &d.tan_window_peak, &d.at_edge, NULL) == VL_OK;
  /* outside by more than the peak search's resolution (0.01 decade) */
  if (d.has_peak && d.has_window_peak) {
    if (d.omega_peak < f->omega_min_rad_s / 1.0233)
      d.peak_outside_decades = log10(d.omega_peak / f->omega_min_rad_s);
    else if (d.omega_peak > f->omega_max_rad_s * 1.0233)
      d.peak_outside_decades = log10(d.omega_peak / f->omega_max_rad_s);
  }
  return d;
}

/* The fit report of a measured compound (null for a Prony series). */
static void fit_json(vl_json *w, const vl_db_compound_fit *f) {
  vl_json_key(w, "fit");
  if (!f || !f->has_fit) {
    vl_json_null(w);
    return;
  }
  vl_json_object_begin(w, VL_JSON_INLINE);
  vl_json_key_string(w, "input_kind", f->input_kind);
  vl_json_key_string(w, "weights", f->weights);
  vl_json_key_integer(w, "n_points", (long long)f->n_points);
  vl_json_key_integer(w, "n_isotherms", (long long)f->n_isotherms);
  vl_json_key_number(w, "omega_min_rad_s", f->omega_min_rad_s);
  vl_json_key_number(w, "omega_max_rad_s", f->omega_max_rad_s);
  vl_json_key_number(w, "terms_per_decade", f->terms_per_decade);
  vl_json_key_integer(w, "n_grid", (long long)f->n_grid);
  vl_json_key_number(w, "rms_rel_storage", f->rms_rel_storage);
  vl_json_key_number(w, "max_rel_storage", f->max_rel_storage);
  vl_json_key_number(w, "rms_rel_loss", f->rms_rel_loss);
  vl_json_key_number(w, "max_rel_loss", f->max_rel_loss);
  vl_json_key_number(w, "wlf_rms_log10_a_t", f->wlf_rms_log10_a_t);
  vl_json_key(w, "shifts");
  vl_json_array_begin(w, VL_JSON_INLINE);
  for (size_t k = 0; k < f->n_shifts; k++) {
    vl_json_object_begin(w, VL_JSON_INLINE);
    vl_json_key_number(w, "temperature_c", f->shift_temperature_c[k]);
    vl_json_key_number(w, "log10_a_t", f->shift_log10_a_t[k]);
    vl_json_end(w);
  }
  vl_json_end(w);
  vl_json_end(w);
}

/* The peak within the measured window (null for a Prony series). */
static void window_peak_json(vl_json *w, const compound_derived *d) {
  vl_json_key(w, "loss_peak_in_window");
  if (!d->has_window_peak) {
    vl_json_null(w);
    return;
  }
  vl_json_object_begin(w, VL_JSON_INLINE);
  vl_json_key_number(w, "omega_rad_s", d->omega_window_peak);
  vl_json_key_number(w, "frequency_hz", d->omega_window_peak / TWO_PI);
  vl_json_key_number(w, "tan_delta", d->tan_window_peak);
  vl_cli_key_text_or_null(w, "at_edge", d->at_edge < 0 ? "lower" : d->at_edge > 0 ? "upper" : "");
  vl_json_end(w);
  /* decades of the model's peak beyond the window (0: inside it) */
  vl_json_key_number(w, "loss_peak_outside_decades", d->peak_outside_decades);
}

static void compound_json(vl_json *w, const vl_db_compound *c, const vl_db_compound_fit *f) {
  compound_derived d = compound_derive(c, f);
  vl_json_object_begin(w, VL_JSON_INLINE);
  vl_json_key_string(w, "name", c->name);
  vl_json_key_string(w, "class", c->class_name);
  vl_json_key_string(w, "description", c->description);
  vl_json_key_number(w, "e0_pa", d.e0_pa);
  vl_json_key_number(w, "e_inf_pa", c->prony.e_inf_pa);
  vl_json_key_number(w, "nu", c->prony.nu);
  vl_json_key(w, "loss_peak");
  if (d.has_peak) {
    vl_json_object_begin(w, VL_JSON_INLINE);
    vl_json_key_number(w, "omega_rad_s", d.omega_peak);
    vl_json_key_number(w, "frequency_hz", d.omega_peak / TWO_PI);
    vl_json_key_number(w, "tan_delta", d.tan_peak);
    vl_json_end(w);
  } else {
    vl_json_null(w);
  }
  window_peak_json(w, &d);
  vl_json_key_number(w, "tref_c", c->tref_c);
  vl_json_key_number(w, "wlf_c1", c->wlf_c1);
  vl_json_key_number(w, "wlf_c2_k", c->wlf_c2_k);
  vl_cli_key_text_or_null(w, "source_file", c->source_file);
  vl_json_key_string(w, "method", c->method);
  vl_json_key_number(w, "fit_rms_error", c->fit_rms_error);
  vl_json_key_string(w, "created_at", c->created_at);
  fit_json(w, f);
  vl_json_key(w, "prony");
  vl_json_array_begin(w, VL_JSON_INLINE);
  for (size_t i = 0; i < c->prony.n_terms; i++) {
    vl_json_object_begin(w, VL_JSON_INLINE);
    vl_json_key_number(w, "A", c->prony.A[i]);
    vl_json_key_number(w, "tau_s", c->prony.tau_s[i]);
    vl_json_end(w);
  }
  vl_json_end(w);
  vl_json_end(w);
}

/* How well the stored series and shifts represent the data, against the
 * import's warning thresholds (dma.h). */
static void quality_text(FILE *out, const vl_db_compound_fit *f) {
  double fit = fmax(f->rms_rel_storage, f->rms_rel_loss);
  int fit_ok = fit <= VL_DMA_WARN_FIT_RMS;
  int wlf_ok = isnan(f->wlf_rms_log10_a_t) || f->wlf_rms_log10_a_t <= VL_DMA_WARN_WLF_RMS;
  fprintf(out, "  represented   %s: the series within %.3g %% rms of E' and %.3g %% of E''",
          fit_ok && wlf_ok ? "well" : "roughly", 100.0 * f->rms_rel_storage,
          100.0 * f->rms_rel_loss);
  if (!isnan(f->wlf_rms_log10_a_t))
    fprintf(out, ", WLF within %.3g decades rms of the shifts", f->wlf_rms_log10_a_t);
  fprintf(out, " (warned above %g %% and %g decades)\n", 100.0 * VL_DMA_WARN_FIT_RMS,
          VL_DMA_WARN_WLF_RMS);
}

/* Prints the fit report of a measured compound (add and show). */
static void fit_report_text(FILE *out, const vl_db_compound *c, const vl_db_compound_fit *f) {
  fprintf(out, "  fit to data   %zu points (%s), %zu isotherm%s, %s weights\n", f->n_points,
          f->input_kind, f->n_isotherms, f->n_isotherms == 1 ? "" : "s", f->weights);
  fprintf(out, "  window        %.4g to %.4g rad/s at %.6g C (%.2f decades)\n", f->omega_min_rad_s,
          f->omega_max_rad_s, c->tref_c, log10(f->omega_max_rad_s / f->omega_min_rad_s));
  fprintf(out, "  terms         %zu kept of a grid of %zu (%g per decade)\n", c->prony.n_terms,
          f->n_grid, f->terms_per_decade);
  fprintf(out, "  error E'      rms %.3g %%, max %.3g %%\n", 100.0 * f->rms_rel_storage,
          100.0 * f->max_rel_storage);
  fprintf(out, "  error E''     rms %.3g %%, max %.3g %%\n", 100.0 * f->rms_rel_loss,
          100.0 * f->max_rel_loss);
  if (!isnan(f->wlf_rms_log10_a_t))
    fprintf(out, "  WLF residual  rms %.3g in log10 aT\n", f->wlf_rms_log10_a_t);
  quality_text(out, f);
  if (f->n_shifts > 1) {
    fprintf(out, "  shifts        %10s %12s\n", "T (C)", "log10 aT");
    for (size_t k = 0; k < f->n_shifts; k++)
      fprintf(out, "                %10.4g %12.5g\n", f->shift_temperature_c[k],
              f->shift_log10_a_t[k]);
  }
}

/* The loss peak of a measured compound: within the window of the data,
 * and the model's own when it lies outside (extrapolated). */
static void window_peak_text(FILE *out, const compound_derived *d) {
  fprintf(out, "  tan delta max %.6g at %.6g rad/s (%.6g Hz) within the measured window%s\n",
          d->tan_window_peak, d->omega_window_peak, d->omega_window_peak / TWO_PI,
          d->at_edge > 0   ? " (its upper end: still rising)"
          : d->at_edge < 0 ? " (its lower end: still rising)"
                           : "");
  if (d->has_peak && d->peak_outside_decades != 0.0)
    fprintf(out,
            "  model peak    %.6g at %.6g rad/s (%.6g Hz), %.2g decades %s the measured "
            "window: extrapolated by the Prony series, not measured\n",
            d->tan_peak, d->omega_peak, d->omega_peak / TWO_PI, fabs(d->peak_outside_decades),
            d->peak_outside_decades > 0.0 ? "above" : "below");
}

static void compound_text(FILE *out, const vl_db_compound *c, const vl_db_compound_fit *f) {
  compound_derived d = compound_derive(c, f);
  fprintf(out, "compound %s (%s)\n", c->name, c->class_name);
  if (c->description[0]) fprintf(out, "  description   %s\n", c->description);
  fprintf(out, "  E0            %.6g Pa   (relaxed, Einf / (1 + sum A))\n", d.e0_pa);
  fprintf(out, "  Einf          %.6g Pa   (glassy)\n", c->prony.e_inf_pa);
  fprintf(out, "  nu            %.6g\n", c->prony.nu);
  if (d.has_window_peak)
    window_peak_text(out, &d);
  else if (d.has_peak)
    fprintf(out, "  tan delta max %.6g at %.6g rad/s (%.6g Hz)\n", d.tan_peak, d.omega_peak,
            d.omega_peak / TWO_PI);
  else
    fprintf(out, "  tan delta max none (elastic)\n");
  fprintf(out, "  tref          %.6g C\n", c->tref_c);
  if (!isnan(c->wlf_c1))
    fprintf(out, "  WLF           C1 %.6g, C2 %.6g K\n", c->wlf_c1, c->wlf_c2_k);
  fprintf(out, "  method        %s\n", c->method);
  if (c->source_file[0]) fprintf(out, "  source file   %s\n", c->source_file);
  if (!isnan(c->fit_rms_error)) fprintf(out, "  fit rms error %.6g\n", c->fit_rms_error);
  fprintf(out, "  created       %s\n", c->created_at);
  if (f && f->has_fit) fit_report_text(out, c, f);
  fprintf(out, "  Prony terms (1/E = (1/Einf) [1 + sum A_i / (1 - i w tau_i)]):\n");
  fprintf(out, "  %5s %14s %14s\n", "i", "A", "tau_s");
  for (size_t i = 0; i < c->prony.n_terms; i++)
    fprintf(out, "  %5zu %14.6g %14.6g\n", i + 1, c->prony.A[i], c->prony.tau_s[i]);
}

static void compound_line(FILE *out, const vl_db_compound *c) {
  compound_derived d = compound_derive(c, NULL);
  fprintf(out, "%-20s %-8s E0 %-10.4g Pa  Einf %-10.4g Pa  nu %-5.3g terms %-3zu", c->name,
          c->class_name, d.e0_pa, c->prony.e_inf_pa, c->prony.nu, c->prony.n_terms);
  if (d.has_peak) fprintf(out, "  tan delta max %.3g at %.4g rad/s", d.tan_peak, d.omega_peak);
  fputc('\n', out);
}

/* ---- add ------------------------------------------------------------- */

/* What `compound add NAME` was given (NULL: not given). */
typedef struct {
  const char *name;
  const char *prony, *e_inf, *nu, *cls, *description, *tref, *wlf_c1, *wlf_c2;
  const char *measured, *freq_unit, *modulus_unit, *temp_unit, *terms_per_decade, *fit_weights,
      *moduli;
} add_args;

static int add_args_parse(const vl_cli_context *cx, int argc, char **argv, add_args *a) {
  vl_cli_option opts[] = {
      {.name = "--prony", .kind = VL_CLI_TEXT, .metavar = "FILE", .dest = &a->prony},
      {.name = "--e-inf", .kind = VL_CLI_TEXT, .metavar = "PA", .dest = &a->e_inf},
      {.name = "--nu", .kind = VL_CLI_TEXT, .metavar = "NU", .dest = &a->nu},
      {.name = "--class", .kind = VL_CLI_TEXT, .metavar = "CLASS", .dest = &a->cls},
      {.name = "--description", .kind = VL_CLI_TEXT, .metavar = "TEXT", .dest = &a->description},
      {.name = "--tref", .kind = VL_CLI_TEXT, .metavar = "C", .dest = &a->tref},
      {.name = "--wlf-c1", .kind = VL_CLI_TEXT, .metavar = "C1", .dest = &a->wlf_c1},
      {.name = "--wlf-c2", .kind = VL_CLI_TEXT, .metavar = "C2_K", .dest = &a->wlf_c2},
      {.name = "--measured", .kind = VL_CLI_TEXT, .metavar = "FILE", .dest = &a->measured},
      {.name = "--freq-unit", .kind = VL_CLI_TEXT, .metavar = "UNIT", .dest = &a->freq_unit},
      {.name = "--modulus-unit", .kind = VL_CLI_TEXT, .metavar = "UNIT", .dest = &a->modulus_unit},
      {.name = "--temp-unit", .kind = VL_CLI_TEXT, .metavar = "UNIT", .dest = &a->temp_unit},
      {.name = "--terms-per-decade",
       .kind = VL_CLI_TEXT,
       .metavar = "N",
       .dest = &a->terms_per_decade},
      {.name = "--fit-weights", .kind = VL_CLI_TEXT, .metavar = "WEIGHTS", .dest = &a->fit_weights},
      {.name = "--moduli", .kind = VL_CLI_TEXT, .metavar = "KIND", .dest = &a->moduli},
  };
  return vl_cli_named_args(cx, NULL, argc, argv, opts, sizeof opts / sizeof opts[0], &a->name,
                           NULL);
}

/* The text options both forms share: --class from the known list,
 * --description and the data file's name (option file_opt) short enough
 * to store. -1 when they are fine, else the exit status after the message. */
static int check_texts(const vl_cli_context *cx, const add_args *a, const char *file_opt,
                       const char *file) {
  const char *cls = a->cls;
  if (cls && strcmp(cls, "model") && strcmp(cls, "filled") && strcmp(cls, "unfilled") &&
      strcmp(cls, "other"))
    return vl_cli_failf(cx, VL_EINPUT,
                        "option --class: '%s' is not one of model, filled, unfilled, other", cls);
  int rc = vl_cli_check_description(cx, a->description);
  if (rc >= 0) return rc;
  if (strlen(file) >= VL_DB_TEXT_MAX)
    return vl_cli_failf(cx, VL_EINPUT, "option %s: file name longer than %d characters", file_opt,
                        VL_DB_TEXT_MAX - 1);
  return -1;
}

/* The ranges of the numeric options (vl_cli_number_in). */
static const vl_cli_number_rule nu_rule = {
    .lo = 0.0, .hi = 0.5, .bad = "the Poisson ratio must lie in [0, 0.5]"};
static const vl_cli_number_rule e_inf_rule = {
    .lo = 0.0, .lo_open = 1, .hi = INFINITY, .bad = "the glassy modulus must be > 0 Pa"};
static const vl_cli_number_rule wlf_c2_rule = {
    .lo = 0.0, .lo_open = 1, .hi = INFINITY, .bad = "C2 must be > 0 K"};

/* The name and texts of a new compound c. */
static void compound_named(vl_db_compound *c, const add_args *a, const char *file) {
  snprintf(c->name, sizeof c->name, "%s", a->name);
  snprintf(c->class_name, sizeof c->class_name, "%s", a->cls ? a->cls : "other");
  snprintf(c->description, sizeof c->description, "%s", a->description ? a->description : "");
  snprintf(c->source_file, sizeof c->source_file, "%s", file);
}

/* ---- add --measured --------------------------------------------------- */

/* The units and the fit's options of --measured into o: -1, else the exit
 * status after the message. */
static int measured_units(const vl_cli_context *cx, const add_args *a, vl_dma_options *o) {
  const char *fu = a->freq_unit, *mu = a->modulus_unit, *tu = a->temp_unit;
  if (fu && strcmp(fu, "Hz") && strcmp(fu, "rad/s"))
    return vl_cli_failf(cx, VL_EINPUT, "option --freq-unit: '%s' is not Hz or rad/s", fu);
  if (mu && strcmp(mu, "Pa") && strcmp(mu, "kPa") && strcmp(mu, "MPa") && strcmp(mu, "GPa"))
    return vl_cli_failf(cx, VL_EINPUT,
                        "option --modulus-unit: '%s' is not one of Pa, kPa, MPa, GPa", mu);
  if (tu && strcmp(tu, "C") && strcmp(tu, "K"))
    return vl_cli_failf(cx, VL_EINPUT, "option --temp-unit: '%s' is not C or K", tu);
  o->freq_unit = fu;
  o->modulus_unit = mu;
  o->temp_unit = tu;
  return -1;
}

static int measured_fit(const vl_cli_context *cx, const add_args *a, vl_dma_options *o) {
  int rc;
  if (a->terms_per_decade) {
    if ((rc = vl_cli_number_opt(cx, "--terms-per-decade", a->terms_per_decade,
                                &o->terms_per_decade)) >= 0)
      return rc;
    if (!(o->terms_per_decade > 0.0 && o->terms_per_decade <= VL_PRONY_FIT_MAX_PER_DECADE))
      return vl_cli_failf(cx, VL_EINPUT,
                          "option --terms-per-decade: must lie in (0, %g] (got '%s')",
                          VL_PRONY_FIT_MAX_PER_DECADE, a->terms_per_decade);
  }
  const char *fw = a->fit_weights, *mod = a->moduli;
  if (fw && !strcmp(fw, "relative"))
    o->weights = VL_PRONY_WEIGHTS_RELATIVE;
  else if (fw && !strcmp(fw, "modulus"))
    o->weights = VL_PRONY_WEIGHTS_MODULUS;
  else if (fw)
    return vl_cli_failf(cx, VL_EINPUT, "option --fit-weights: '%s' is not relative or modulus", fw);
  if (mod && !strcmp(mod, "tensile"))
    o->moduli = VL_DMA_MODULI_TENSILE;
  else if (mod && !strcmp(mod, "shear"))
    o->moduli = VL_DMA_MODULI_SHEAR;
  else if (mod)
    return vl_cli_failf(cx, VL_EINPUT, "option --moduli: '%s' is not tensile or shear", mod);
  return -1;
}

/* Every option of --measured checked into o: -1, else the exit status
 * after the message. */
static int measured_options(const vl_cli_context *cx, const add_args *a, vl_dma_options *o) {
  const char *forbidden[] = {a->prony, a->e_inf, a->wlf_c1, a->wlf_c2};
  const char *names[] = {"--prony", "--e-inf", "--wlf-c1", "--wlf-c2"};
  for (size_t k = 0; k < 4; k++)
    if (forbidden[k])
      return vl_cli_failf(cx, VL_EINPUT,
                          "option %s does not go with --measured (the fit determines the series%s)",
                          names[k], k >= 2 ? " and the WLF constants" : "");
  *o = vl_dma_options_default();
  int rc;
  if ((rc = vl_cli_number_in(cx, "--tref", a->tref, &vl_cli_tref_rule, &o->tref_c)) >= 0) return rc;
  if ((rc = vl_cli_number_in(cx, "--nu", a->nu, &nu_rule, &o->nu)) >= 0) return rc;
  if ((rc = measured_units(cx, a, o)) >= 0) return rc;
  if ((rc = measured_fit(cx, a, o)) >= 0) return rc;
  return check_texts(cx, a, "--measured", a->measured);
}

/* The stored compound c and its fit (from file), as `add` reports it. */
static void measured_report(vl_db *db, const vl_db_compound *c, const vl_db_compound_fit *f,
                            const char *file) {
  printf("added compound '%s' to %s: fitted to %s\n", c->name, vl_db_path(db), file);
  printf("  E0            %.6g Pa, Einf %.6g Pa, nu %.6g\n", vl_prony_e0(&c->prony),
         c->prony.e_inf_pa, c->prony.nu);
  if (!isnan(c->wlf_c1))
    printf("  WLF           C1 %.6g, C2 %.6g K at %.6g C\n", c->wlf_c1, c->wlf_c2_k, c->tref_c);
  fit_report_text(stdout, c, f);
}

/* `compound add NAME --measured FILE ...`: import, shift, fit, store. */
static int compound_add_measured(const vl_cli_context *cx, const vl_cli_globals *g,
                                 const add_args *a) {
  vl_dma_options o;
  int rc = measured_options(cx, a, &o);
  if (rc >= 0) return rc;
  vl_error err;
  vl_measured m;
  vl_status st = vl_measured_read_file(a->measured, &o, &m, &err);
  if (st != VL_OK) return vl_cli_fail(cx, st, err.msg);
  vl_db_compound *c = calloc(1, sizeof *c);
  vl_db *db = NULL;
  if (!c) {
    vl_measured_free(&m);
    return vl_cli_fail(cx, VL_ENOMEM, "out of memory");
  }
  compound_named(c, a, a->measured);
  if ((rc = vl_cli_open_db(cx, g, &db)) < 0) {
    vl_db_compound_fit f;
    memset(&f, 0, sizeof f);
    st = vl_db_compound_add_measured(db, c, &m, &err);
    if (st == VL_OK) st = vl_db_compound_info(db, a->name, c, &err);
    if (st == VL_OK) st = vl_db_compound_fit_info(db, a->name, &f, &err);
    if (st == VL_OK) {
      measured_report(db, c, &f, a->measured);
      vl_cli_print_notes(g, m.notes);
      rc = 0;
    } else {
      rc = vl_cli_fail(cx, st, err.msg);
    }
    vl_db_compound_fit_free(&f);
  }
  vl_db_close(db);
  vl_measured_free(&m);
  free(c);
  return rc;
}

/* ---- add --prony ------------------------------------------------------ */

/* The options of the Prony form checked into c (all but the series): -1,
 * else the exit status after the message. */
static int prony_options(const vl_cli_context *cx, const add_args *a, vl_db_compound *c) {
  const char *measured_only[] = {a->freq_unit,        a->modulus_unit, a->temp_unit,
                                 a->terms_per_decade, a->fit_weights,  a->moduli};
  const char *names[] = {"--freq-unit",        "--modulus-unit", "--temp-unit",
                         "--terms-per-decade", "--fit-weights",  "--moduli"};
  for (size_t k = 0; k < 6; k++)
    if (measured_only[k])
      return vl_cli_failf(cx, VL_EINPUT, "option %s belongs to --measured FILE", names[k]);
  if (!a->prony)
    return vl_cli_fail(cx, VL_EINPUT, "option --prony FILE is required (or --measured FILE)");
  if (!a->e_inf) return vl_cli_fail(cx, VL_EINPUT, "option --e-inf PA is required");
  if (!a->nu) return vl_cli_fail(cx, VL_EINPUT, "option --nu NU is required");
  int rc;
  c->tref_c = 20.0, c->wlf_c1 = NAN, c->wlf_c2_k = NAN, c->fit_rms_error = NAN;
  if ((rc = vl_cli_number_in(cx, "--e-inf", a->e_inf, &e_inf_rule, &c->prony.e_inf_pa)) >= 0)
    return rc;
  if ((rc = vl_cli_number_in(cx, "--nu", a->nu, &nu_rule, &c->prony.nu)) >= 0) return rc;
  if ((rc = check_texts(cx, a, "--prony", a->prony)) >= 0) return rc;
  if ((rc = vl_cli_number_in(cx, "--tref", a->tref, &vl_cli_tref_rule, &c->tref_c)) >= 0) return rc;
  if ((!a->wlf_c1) != (!a->wlf_c2))
    return vl_cli_fail(cx, VL_EINPUT,
                       "options --wlf-c1 and --wlf-c2 go together (give both or neither)");
  if (!a->wlf_c1) return -1;
  if ((rc = vl_cli_number_opt(cx, "--wlf-c1", a->wlf_c1, &c->wlf_c1)) >= 0) return rc;
  return vl_cli_number_in(cx, "--wlf-c2", a->wlf_c2, &wlf_c2_rule, &c->wlf_c2_k);
}

/* `compound add NAME --prony FILE --e-inf PA --nu NU ...`. */
static int compound_add_prony(const vl_cli_context *cx, const vl_cli_globals *g,
                              const add_args *a) {
  vl_db_compound *c = calloc(1, sizeof *c);
  if (!c) return vl_cli_fail(cx, VL_ENOMEM, "out of memory");
  int rc = prony_options(cx, a, c);
  if (rc >= 0) {
    free(c);
    return rc;
  }
  compound_named(c, a, a->prony);
  snprintf(c->method, sizeof c->method, "prony-csv");
  vl_error err;
  vl_db *db = NULL;
  double e_inf_pa = c->prony.e_inf_pa, nu = c->prony.nu;
  vl_status st = vl_csv_read_prony(a->prony, &c->prony, &err);
  c->prony.e_inf_pa = e_inf_pa, c->prony.nu = nu;
  if (st == VL_OK) st = vl_prony_validate(&c->prony, &err);
  if (st != VL_OK) {
    rc = vl_cli_fail(cx, st, err.msg);
  } else if ((rc = vl_cli_open_db(cx, g, &db)) < 0) {
    st = vl_db_compound_add(db, c, &err);
    if (st != VL_OK) {
      rc = vl_cli_fail(cx, st, err.msg);
    } else {
      printf("added compound '%s' to %s: %zu Prony terms, E0 %.6g Pa, Einf %.6g Pa, nu %.6g\n",
             c->name, vl_db_path(db), c->prony.n_terms, vl_prony_e0(&c->prony), c->prony.e_inf_pa,
             c->prony.nu);
      rc = 0;
    }
  }
  vl_db_close(db);
  free(c);
  return rc;
}

static int compound_add(const vl_cli_context *cx, const vl_cli_globals *g, int argc, char **argv) {
  add_args a = {0};
  int rc = add_args_parse(cx, argc, argv, &a);
  if (rc >= 0) return rc;
  return a.measured ? compound_add_measured(cx, g, &a) : compound_add_prony(cx, g, &a);
}

/* Writes the measured vs fitted curve of compound c (see `compound show
 * --help`). Returns the exit code after one message on failure, else -1. */
static int write_curve(const vl_cli_context *cx, vl_db *db, const vl_db_compound *c,
                       const char *path) {
  vl_error err;
  vl_db_measured_point *pts = NULL;
  size_t n = 0;
  vl_status st = vl_db_compound_points(db, c->name, &pts, &n, &err);
  if (st != VL_OK) return vl_cli_fail(cx, st, err.msg);
  if (n == 0)
    return vl_cli_failf(
        cx, VL_EINPUT,
        "option --curve: compound '%s' has no measured data (it was entered as a Prony "
        "series)",
        c->name);
  vl_atomic_file af;
  if (vl_atomic_file_open(&af, path, &err) != VL_OK) {
    free(pts);
    return vl_cli_failf(cx, VL_EIO, "option --curve: %s", err.msg);
  }
  FILE *f = af.f;
  fprintf(f,
          "# viscolube compound %s: measured points and the stored Prony fit at the reduced\n"
          "# frequency a_T omega of the master curve at tref = %.6g C (source %s)\n",
          c->name, c->tref_c, c->source_file[0] ? c->source_file : "?");
  fputs("omega_rad_s,frequency_hz,temperature_c,reduced_omega_rad_s,storage_pa,storage_fit_pa,"
        "loss_pa,loss_fit_pa,tan_delta,tan_delta_fit,source_line\n",
        f);
  for (size_t k = 0; k < n; k++) {
    const vl_db_measured_point *p = &pts[k];
    double complex e = vl_prony_modulus(&c->prony, p->reduced_omega_rad_s);
    fprintf(f, "%.9g,%.9g,%.6g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%zu\n", p->omega_rad_s,
            p->omega_rad_s / TWO_PI, p->temperature_c, p->reduced_omega_rad_s, p->storage_pa,
            creal(e), p->loss_pa, cimag(e), p->loss_pa / p->storage_pa, cimag(e) / creal(e),
            p->source_line);
  }
  free(pts);
  if (vl_atomic_file_commit(&af, &err) != VL_OK)
    return vl_cli_failf(cx, VL_EIO, "option --curve: %s", err.msg);
  return -1;
}

enum { NFIT = 240 }; /* points of the fitted curve in the figure */

/* The frequencies the fitted curve is drawn over: the measured window,
 * else the series' own times; the points of that curve (0: none). */
static size_t fit_window(const vl_db_compound *c, const vl_db_measured_point *pts, size_t n,
                         double *wlo, double *whi) {
  *wlo = INFINITY, *whi = 0;
  for (size_t k = 0; k < n; k++) {
    *wlo = fmin(*wlo, pts[k].reduced_omega_rad_s);
    *whi = fmax(*whi, pts[k].reduced_omega_rad_s);
  }
  for (size_t k = 0; n == 0 && k < c->prony.n_terms; k++) {
    *wlo = fmin(*wlo, 0.01 / c->prony.tau_s[k]);
    *whi = fmax(*whi, 100 / c->prony.tau_s[k]);
  }
  return c->prony.n_terms > 0 && *whi > *wlo ? NFIT : 0;
}

/* The measured points and the fitted curve into d's arrays, laid out in
 * buf (3 n + 3 NFIT values). */
static void modulus_data(const vl_db_compound *c, const vl_db_measured_point *pts, size_t n,
                         size_t n_fit, double wlo, double whi, double *buf,
                         vl_plot_modulus_data *d) {
  double *w = buf, *e1 = buf + n, *e2 = buf + 2 * n, *fw = buf + 3 * n, *f1 = fw + NFIT,
         *f2 = f1 + NFIT;
  for (size_t k = 0; k < n; k++) {
    w[k] = pts[k].reduced_omega_rad_s;
    e1[k] = pts[k].storage_pa;
    e2[k] = pts[k].loss_pa;
  }
  for (size_t k = 0; k < n_fit; k++) {
    fw[k] = wlo * pow(whi / wlo, (double)k / (NFIT - 1));
    double complex e = vl_prony_modulus(&c->prony, fw[k]);
    f1[k] = creal(e);
    f2[k] = cimag(e);
  }
  *d = (vl_plot_modulus_data){n, w, e1, e2, n_fit, fw, f1, f2, d->measured_label, d->fit_label};
}

/* DIR/moduli and, with two isotherms or more, DIR/shifts. */
static vl_status draw_compound(const char *dir, const vl_db_compound *c,
                               const vl_db_compound_fit *fit, const vl_plot_modulus_data *d,
                               vl_error *err) {
  char title[160], stem[4300];
  snprintf(title, sizeof title, "compound %s at %g °C", c->name, c->tref_c);
  vl_plot_options opt;
  vl_plot_options_defaults(&opt);
  opt.title = title;
  if (d->n + d->n_fit == 0) {
    vl_error_set(err, "option --plot: compound '%s' is elastic and has no measured data", c->name);
    return VL_EINPUT;
  }
  if (vl_cli_make_dirs(dir) != 0) {
    vl_error_set(err, "%s: cannot create directory: %s", dir, strerror(errno));
    return VL_EIO;
  }
  snprintf(stem, sizeof stem, "%s/moduli", dir);
  vl_status st = vl_plot_modulus(stem, d, &opt, NULL, err);
  if (st != VL_OK || !(fit->has_fit && fit->n_shifts >= 2)) return st;
  snprintf(stem, sizeof stem, "%s/shifts", dir);
  return vl_plot_shifts(stem, fit->n_shifts, fit->shift_temperature_c, fit->shift_log10_a_t,
                        c->tref_c, c->wlf_c1, c->wlf_c2_k, &opt, NULL, err);
}

/* `compound show NAME --plot`: DIR/moduli and, with isotherms, DIR/shifts
 * (plot.h). Returns -1 on success, else the exit code after the message. */
static int plot_compound(const vl_cli_context *cx, vl_db *db, const vl_db_compound *c,
                         const vl_db_compound_fit *fit, const char *dir, int quiet) {
  vl_error err = {{0}};
  vl_db_measured_point *pts = NULL;
  size_t n = 0;
  vl_status st = vl_db_compound_points(db, c->name, &pts, &n, &err);
  if (st != VL_OK) return vl_cli_fail(cx, st, err.msg);
  double wlo, whi;
  size_t n_fit = fit_window(c, pts, n, &wlo, &whi);
  double *buf = malloc((3 * n + 3 * NFIT + 1) * sizeof *buf);
  if (!buf) {
    free(pts);
    return vl_cli_fail(cx, VL_ENOMEM, "out of memory");
  }
  char ml[96], fl[96];
  snprintf(ml, sizeof ml, fit->n_isotherms > 1 ? "measured, shifted to %g °C" : "measured, %g °C",
           c->tref_c);
  snprintf(fl, sizeof fl, "Prony series, %zu term%s", c->prony.n_terms,
           c->prony.n_terms == 1 ? "" : "s");
  vl_plot_modulus_data d = {.measured_label = ml, .fit_label = fl};
  modulus_data(c, pts, n, n_fit, wlo, whi, buf, &d);
  st = draw_compound(dir, c, fit, &d, &err);
  free(buf);
  free(pts);
  if (st != VL_OK) return vl_cli_fail(cx, st, err.msg);
  int shifts = fit->has_fit && fit->n_shifts >= 2;
  if (!quiet) printf("plots (png, svg) in %s: moduli%s\n", dir, shifts ? ", shifts" : "");
  return -1;
}

/* Prints compound c with its fit f (json or text), then --plot into dir
 * (NULL: no figure; "": the default folder). -1 on success, else the exit
 * status after the message. */
static int show_compound(const vl_cli_context *cx, vl_db *db, const vl_db_compound *c,
                         const vl_db_compound_fit *f, int json, const char *dir) {
  if (json) {
    vl_json w;
    vl_cli_json_start(&w, stdout);
    compound_json(&w, c, f);
    fputc('\n', stdout); /* the object is complete before any message */
  } else {
    compound_text(stdout, c, f);
  }
  if (!dir) return -1;
  char buf[4200];
  if (dir[0])
    snprintf(buf, sizeof buf, "%s", dir);
  else
    snprintf(buf, sizeof buf, "out/compound-%s", c->name);
  return plot_compound(cx, db, c, f, buf, json);
}

/* ---- the noun --------------------------------------------------------- */

/* `compound show NAME`: prints the compound, then writes --curve and
 * --plot. The exit status. */
static int compound_show(const vl_cli_context *cx, const vl_cli_globals *g, int argc, char **argv) {
  int json = 0, plot = 0;
  const char *curve = NULL, *out = NULL, *name = NULL;
  /* a compound's --plot writes into --out DIR */
  vl_cli_option opts[] = {
      {.name = "--json", .kind = VL_CLI_FLAG, .dest = &json},
      {.name = "--curve", .kind = VL_CLI_TEXT, .metavar = "FILE", .dest = &curve},
      {.name = "--plot", .kind = VL_CLI_FLAG, .dest = &plot},
      {.name = "--out", .kind = VL_CLI_TEXT, .metavar = "DIR", .dest = &out},
  };
  int rc = vl_cli_named_args(cx, g, argc, argv, opts, 4, &name, NULL);
  if (rc >= 0) return rc;
  if (out && !plot) return vl_cli_fail(cx, VL_EINPUT, "option --out goes with --plot");
  vl_db *db = NULL;
  if ((rc = vl_cli_open_db(cx, g, &db)) >= 0) return rc;
  vl_error err;
  vl_db_compound *c = malloc(sizeof *c);
  vl_db_compound_fit f;
  memset(&f, 0, sizeof f);
  rc = -1;
  vl_status st = c ? vl_db_compound_info(db, name, c, &err) : VL_ENOMEM;
  if (!c) vl_error_set(&err, "out of memory");
  if (st == VL_OK) st = vl_db_compound_fit_info(db, name, &f, &err);
  if (st != VL_OK) rc = vl_cli_fail(cx, st, err.msg);
  /* the curve first: a failure to write it prints nothing else */
  if (rc < 0 && curve) rc = write_curve(cx, db, c, curve);
  if (rc < 0) rc = show_compound(cx, db, c, &f, json, plot ? (out ? out : "") : NULL);
  vl_db_compound_fit_free(&f);
  free(c);
  vl_db_close(db);
  return rc >= 0 ? rc : 0;
}

static vl_status compound_list(vl_db *db, vl_json *w, int json, vl_error *err) {
  vl_db_compound *items;
  size_t n = 0;
  vl_status st = vl_db_compound_list(db, &items, &n, err);
  if (st != VL_OK) return st;
  for (size_t i = 0; st == VL_OK && i < n; i++) {
    vl_db_compound_fit f;
    if (!json)
      compound_line(stdout, &items[i]);
    else if ((st = vl_db_compound_fit_info(db, items[i].name, &f, err)) == VL_OK) {
      compound_json(w, &items[i], &f);
      vl_db_compound_fit_free(&f);
    }
  }
  free(items);
  return st;
}

/* name, help, verb_help, add, show, flow_factors, list, remove */
const vl_cli_noun vl_cli_compound_noun = {"compound",    compound_help,        compound_verb_help,
                                          compound_add,  compound_show,        NULL,
                                          compound_list, vl_db_compound_remove};
