/* `viscolube compound|surface|fluid VERB ...`: the material commands.
 *
 * A thin layer over database.h and csv.h: parse the command line, read and
 * check every input file, and only then open the database, so a bad input
 * never creates or touches it. Messages go to stderr as one line each;
 * results to stdout (text, or JSON with --json). */
#define _POSIX_C_SOURCE 200809L

#include <complex.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"

#define TWO_PI 6.283185307179586476925287

typedef enum { NOUN_COMPOUND, NOUN_SURFACE, NOUN_FLUID } noun_kind;

typedef struct {
  noun_kind kind;
  const char *noun; /* "compound" */
  const char *verb; /* "add", for messages */
} context;

/* ---- messages and help ------------------------------------------------ */

static int fail(const context *cx, vl_status st, const char *msg) {
  if (cx->verb)
    fprintf(stderr, "viscolube %s %s: %s\n", cx->noun, cx->verb, msg);
  else
    fprintf(stderr, "viscolube %s: %s\n", cx->noun, msg);
  return vl_status_exit_code(st);
}

static int failf(const context *cx, vl_status st, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static int failf(const context *cx, vl_status st, const char *fmt, ...) {
  char buf[VL_ERROR_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  return fail(cx, st, buf);
}

static const char *const noun_help[] = {
    [NOUN_COMPOUND] =
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
        "`viscolube compound VERB --help` describes a verb.\n",
    [NOUN_SURFACE] =
        "usage: viscolube [--db PATH] surface VERB ...\n"
        "\n"
        "Surface roughness: an isotropic 2-D power spectrum C(q), self-affine or tabulated.\n"
        "\n"
        "verbs:\n"
        "  list [--json]          one line per surface: name, kind, h_rms, rms slope, band\n"
        "  show NAME [--json]     h_rms, rms slope, C0, q0, q1, H or point count\n"
        "  add NAME --self-affine --hurst H --q0 PER_M --q1 PER_M --hrms M\n"
        "  add NAME --psd FILE\n"
        "  add NAME --topography FILE\n"
        "                         register a surface from its parameters, a tabulated\n"
        "                         spectrum or a measured line scan or height map (see\n"
        "                         `surface add --help`)\n"
        "  remove NAME            delete a surface\n"
        "  flow-factors NAME [--model M] [--u-range MIN,MAX] [--points N]\n"
        "                         the flow factors phi_p, phi_s, phi_fp, phi_fs, phi_f and\n"
        "                         A/A0 against u/h_rms (see `surface flow-factors --help`)\n"
        "\n"
        "`viscolube surface VERB --help` describes a verb.\n",
    [NOUN_FLUID] = "usage: viscolube [--db PATH] fluid VERB ...\n"
                   "\n"
                   "Newtonian lubricants: low-shear viscosity at a reference temperature.\n"
                   "\n"
                   "verbs:\n"
                   "  list [--json]          one line per fluid: name, viscosity\n"
                   "  show NAME [--json]     viscosity, reference temperature, description\n"
                   "  add NAME --viscosity PA_S [--tref C] [--description TEXT]\n"
                   "  remove NAME            delete a fluid\n"
                   "\n"
                   "`viscolube fluid VERB --help` describes a verb.\n",
};

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

/* `surface add --help` */
static const char surface_add_help[] =
    "usage: viscolube [--db PATH] surface add NAME --self-affine --hurst H --q0 PER_M\n"
    "                 --q1 PER_M --hrms M [--description TEXT]\n"
    "       viscolube [--db PATH] surface add NAME --psd FILE [--psd-kind 1d|2d]\n"
    "                 [--description TEXT]\n"
    "       viscolube [--db PATH] surface add NAME --topography FILE [--description TEXT]\n"
    "\n"
    "Registers an isotropic roughness power spectrum C(q) (m^4), with\n"
    "h_rms^2 = 2 pi \\int q C(q) dq.\n"
    "\n"
    "  --self-affine   C(q) = C0 (q/q0)^(-2(1+H)) for q0 <= q <= q1; C0 follows\n"
    "                  from h_rms. Needs all of:\n"
    "    --hurst H     Hurst exponent, 0 < H <= 1 (fractal dimension 3 - H)\n"
    "    --q0 PER_M    low wavevector cut-off, 1/m (> 0)\n"
    "    --q1 PER_M    high wavevector cut-off, 1/m (> q0)\n"
    "    --hrms M      rms roughness, m (> 0)\n"
    "  --psd FILE      tabulated spectrum: CSV with the header line 'q_per_m,C_m4',\n"
    "                  q > 0 strictly increasing, C > 0, at least 2 rows; an optional\n"
    "                  units row '1/m,m^4' may follow the header. Interpolated as a\n"
    "                  power law between points, zero outside. Units may be given in\n"
    "                  the header instead ('q [1/um],C [m^4]'); see docs/FORMATS.md.\n"
    "  --psd-kind 1d|2d  2d (default): the isotropic C(q), m^4; 1d: a profile's\n"
    "                  C1(q), m^3, converted to C(q) (inverse Abel transform).\n"
    "                  What the reading did is printed on stderr as 'note: ' lines.\n"
    "  --topography FILE  measured heights (docs/FORMATS.md), the spectrum estimated\n"
    "                  from them (detrended, Tukey window, FFT, log bins; a line scan's\n"
    "                  1-D spectrum turned 2-D by the inverse Abel transform):\n"
    "                    line scan: a header naming the units, then position,height\n"
    "                      rows ('x [um],z [nm]'; tab, ';', blank or ',' separated)\n"
    "                    height map: '# Width: 10 um', '# Height: 10 um' and\n"
    "                      '# Value units: m' lines, then one row of heights per line\n"
    "                      (Gwyddion and SurfaceTopography 'matrix' exports)\n"
    "                  Reports the measured rms, the PSD's h_rms and their ratio and\n"
    "                  stores how the spectrum was made as the description (after\n"
    "                  --description when given).\n"
    "  --description TEXT  free text; note the source of the data here\n";

/* `surface flow-factors --help` */
static const char surface_flow_factors_help[] =
    "usage: viscolube [--db PATH] surface flow-factors NAME [--model MODEL]\n"
    "                 [--u-range MIN,MAX] [--points N] [--film-cutoff M] [--out FILE]\n"
    "                 [--json] [--plot]\n"
    "\n"
    "The flow and shear-stress factors of the averaged Reynolds equation for surface\n"
    "NAME (docs/FLOW_FACTORS.md) against the average separation u/h_rms, with the\n"
    "contact area A/A0 of Persson's contact law at that separation. Columns:\n"
    "  u_over_hrms, contact_fraction, phi_p, phi_s, phi_fp, phi_fs, phi_f\n"
    "  --model MODEL   persson-emt (default; its table is cached in the database),\n"
    "                  patir-cheng or smooth\n"
    "  --u-range MIN,MAX  u/h_rms range, log spaced (default 0.001,30)\n"
    "  --points N      rows, 2 to 10000 (default 100)\n"
    "  --film-cutoff M persson-emt's film cut-off in (0, 1e-6] m (default 1e-9): gaps\n"
    "                  narrower carry no Couette shear (phi_f)\n"
    "  --out FILE      also write the table as CSV (a '#' line naming the surface,\n"
    "                  model, h_rms and cut-off, then the columns; exact numbers)\n"
    "  --json          print one JSON object (surface, model, hrms_m, film_cutoff_m,\n"
    "                  percolation_u_over_hrms, rows) instead of the table\n"
    "  --plot          draw the factors against u/h_rms as FILE's stem .png and .svg\n"
    "                  (without --out: flow-factors-NAME.png and .svg here)\n"
    "The header gives the percolation point, where the pressure flow stops.\n";

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

static void verb_help(noun_kind kind, const char *verb, FILE *out) {
  const char *noun = kind == NOUN_COMPOUND  ? "compound"
                     : kind == NOUN_SURFACE ? "surface"
                                            : "fluid";
  if (!strcmp(verb, "list")) {
    fprintf(out,
            "usage: viscolube [--db PATH] %s list [--json]\n"
            "\n"
            "Lists every %s, one per line, sorted by name.\n"
            "  --json   print a JSON array of objects instead (the fields of `%s show --json`)\n",
            noun, noun, noun);
  } else if (!strcmp(verb, "show") && kind == NOUN_COMPOUND) {
    fputs(compound_show_help, out);
  } else if (!strcmp(verb, "show") && kind == NOUN_SURFACE) {
    fputs("usage: viscolube [--db PATH] surface show NAME [--json] [--plot FILE]\n"
          "\n"
          "Prints what is stored about surface NAME and the quantities derived from it.\n"
          "  --json       print one JSON object instead\n"
          "  --plot FILE  also draw C(q) against q (log-log) as FILE's stem .png and .svg;\n"
          "               over a tabulated spectrum the closest self-affine law\n"
          "               C ~ q^(-2(1+H)), fitted from the largest C on, dashed, with its\n"
          "               H (printed with the rms misfit in log10 C)\n",
          out);
  } else if (!strcmp(verb, "show")) {
    fprintf(out,
            "usage: viscolube [--db PATH] %s show NAME [--json]\n"
            "\n"
            "Prints what is stored about %s NAME and the quantities derived from it.\n"
            "  --json   print one JSON object instead\n",
            noun, noun);
  } else if (!strcmp(verb, "flow-factors")) {
    fputs(surface_flow_factors_help, out);
  } else if (!strcmp(verb, "remove")) {
    fprintf(out,
            "usage: viscolube [--db PATH] %s remove NAME\n"
            "\n"
            "Deletes %s NAME (and everything that belongs to it) in one transaction.\n",
            noun, noun);
  } else {
    fputs(kind == NOUN_COMPOUND  ? compound_add_help
          : kind == NOUN_SURFACE ? surface_add_help
                                 : fluid_add_help,
          out);
  }
}

/* ---- option parsing --------------------------------------------------- */

typedef struct {
  const char *name;    /* "--e-inf" */
  const char *metavar; /* "PA"; NULL for a flag */
  const char *value;   /* set by parse_args: the value, or "" for a flag */
} option;

/* The text options both `compound add` forms share: --class from the known
 * list, --description and the data file's name (file->name is --prony or
 * --measured) short enough to store. Returns -1 when they are fine, else the
 * exit code after the message. */
static int check_compound_texts(const context *cx, const option *cls, const option *desc,
                                const option *file) {
  if (cls->value && strcmp(cls->value, "model") && strcmp(cls->value, "filled") &&
      strcmp(cls->value, "unfilled") && strcmp(cls->value, "other"))
    return failf(cx, VL_EINPUT, "option --class: '%s' is not one of model, filled, unfilled, other",
                 cls->value);
  if (desc->value && strlen(desc->value) >= VL_DB_TEXT_MAX)
    return failf(cx, VL_EINPUT, "option --description: longer than %d characters",
                 VL_DB_TEXT_MAX - 1);
  if (strlen(file->value) >= VL_DB_TEXT_MAX)
    return failf(cx, VL_EINPUT, "option %s: file name longer than %d characters", file->name,
                 VL_DB_TEXT_MAX - 1);
  return -1;
}

/* Parses argv[first..argc) into options and at most max_pos positional
 * arguments. Returns -1 on success, else the exit code after printing the
 * one error message. */
static int parse_args(const context *cx, int argc, char **argv, int first, option *opts,
                      size_t n_opts, const char **pos, size_t max_pos, size_t *n_pos) {
  *n_pos = 0;
  for (int i = first; i < argc; i++) {
    const char *a = argv[i];
    if (a[0] == '-' && a[1] == '-' && a[2] != '\0') {
      const char *eq = strchr(a, '=');
      size_t len = eq ? (size_t)(eq - a) : strlen(a);
      option *o = NULL;
      for (size_t k = 0; k < n_opts; k++)
        if (strlen(opts[k].name) == len && !strncmp(opts[k].name, a, len)) o = &opts[k];
      if (!o)
        return failf(cx, VL_EINPUT, "unknown option '%.*s' (see viscolube %s %s --help)", (int)len,
                     a, cx->noun, cx->verb);
      if (o->value) return failf(cx, VL_EINPUT, "option %s is given twice", o->name);
      if (!o->metavar) {
        if (eq) return failf(cx, VL_EINPUT, "option %s takes no value", o->name);
        o->value = "";
      } else if (eq) {
        o->value = eq + 1;
      } else {
        /* A following "--x" is another option, not this one's value; a
         * negative number ("-0.3") is a value, so that it can be checked. */
        if (i + 1 >= argc || (argv[i + 1][0] == '-' && argv[i + 1][1] == '-'))
          return failf(cx, VL_EINPUT, "option %s needs a value (%s)", o->name, o->metavar);
        o->value = argv[++i];
      }
      if (o->metavar && o->value[0] == '\0')
        return failf(cx, VL_EINPUT, "option %s needs a non-empty value (%s)", o->name, o->metavar);
    } else if (a[0] == '-' && a[1] != '\0' && !(a[1] >= '0' && a[1] <= '9') && a[1] != '.') {
      return failf(cx, VL_EINPUT, "unknown option '%s' (see viscolube %s %s --help)", a, cx->noun,
                   cx->verb);
    } else {
      if (*n_pos == max_pos)
        return failf(cx, VL_EINPUT, "unexpected argument '%s' (see viscolube %s %s --help)", a,
                     cx->noun, cx->verb);
      pos[(*n_pos)++] = a;
    }
  }
  return -1;
}

static option *find_opt(option *opts, size_t n, const char *name) {
  for (size_t k = 0; k < n; k++)
    if (!strcmp(opts[k].name, name)) return &opts[k];
  return NULL;
}

/* Parses a numeric option value with the CSV reader's strict rules. */
static int number_opt(const context *cx, const option *o, double *out) {
  const char *why;
  if (vl_csv_parse_double(o->value, out, &why) != VL_OK)
    return failf(cx, VL_EINPUT, "option %s: %s (got '%s')", o->name, why, o->value);
  return -1;
}

/* The NAME positional of show/add/remove, checked. */
static int need_name(const context *cx, const char **pos, size_t n_pos, const char **name) {
  if (n_pos < 1)
    return failf(cx, VL_EINPUT, "missing NAME (see viscolube %s %s --help)", cx->noun, cx->verb);
  vl_error err;
  if (vl_db_check_name(pos[0], &err) != VL_OK) return fail(cx, VL_EINPUT, err.msg);
  *name = pos[0];
  return -1;
}

static int open_db(const context *cx, const vl_cli_globals *g, vl_db **db) {
  vl_error err;
  vl_status st = vl_db_open(g->db_path, db, &err);
  if (st != VL_OK) return fail(cx, st, err.msg);
  return -1;
}

/* ---- JSON output ------------------------------------------------------ */

/* Materials are printed exactly (json.h digits 0): what was stored reads
 * back bit for bit. */
static void json_start(vl_json *w, FILE *out) { vl_json_init(w, out, 0); }

/* A stored text that may be empty (a file name): null when it is. */
static void key_text_or_null(vl_json *w, const char *key, const char *v) {
  vl_json_key_string(w, key, v && *v ? v : NULL);
}

/* ---- compounds -------------------------------------------------------- */

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
  key_text_or_null(w, "at_edge", d->at_edge < 0 ? "lower" : d->at_edge > 0 ? "upper" : "");
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
  key_text_or_null(w, "source_file", c->source_file);
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

/* Prints an import's notes (one sentence per line) on stderr: lines
 * starting "warning: " as they are, the others as "note: ". Nothing when
 * quiet. */
static void print_notes(const vl_cli_globals *g, const char *notes) {
  if (g->quiet) return;
  for (const char *l = notes; *l;) {
    size_t n = strcspn(l, "\n");
    if (n) fprintf(stderr, "%s%.*s\n", strncmp(l, "warning: ", 9) ? "note: " : "", (int)n, l);
    l += n + (l[n] == '\n');
  }
}

/* `compound add NAME --measured FILE ...`: import, shift, fit, store. */
static int compound_add_measured(const context *cx, const vl_cli_globals *g, const char *name,
                                 option *opts, size_t n_opts) {
  const char *forbidden[] = {"--prony", "--e-inf", "--wlf-c1", "--wlf-c2"};
  for (size_t k = 0; k < 4; k++) {
    option *o = find_opt(opts, n_opts, forbidden[k]);
    if (o->value)
      return failf(cx, VL_EINPUT,
                   "option %s does not go with --measured (the fit determines the series%s)",
                   o->name, k >= 2 ? " and the WLF constants" : "");
  }
  option *file = find_opt(opts, n_opts, "--measured"), *cls = find_opt(opts, n_opts, "--class");
  option *desc = find_opt(opts, n_opts, "--description"), *tref = find_opt(opts, n_opts, "--tref");
  option *nu = find_opt(opts, n_opts, "--nu"), *fu = find_opt(opts, n_opts, "--freq-unit");
  option *mu = find_opt(opts, n_opts, "--modulus-unit"),
         *tu = find_opt(opts, n_opts, "--temp-unit");
  option *tpd = find_opt(opts, n_opts, "--terms-per-decade");
  option *fw = find_opt(opts, n_opts, "--fit-weights");
  option *mod = find_opt(opts, n_opts, "--moduli");
  vl_dma_options o = vl_dma_options_default();
  int rc;
  if (tref->value) {
    if ((rc = number_opt(cx, tref, &o.tref_c)) >= 0) return rc;
    if (o.tref_c < -273.15)
      return failf(cx, VL_EINPUT, "option --tref: below absolute zero (got '%s')", tref->value);
  }
  if (nu->value) {
    if ((rc = number_opt(cx, nu, &o.nu)) >= 0) return rc;
    if (!(o.nu >= 0.0 && o.nu <= 0.5))
      return failf(cx, VL_EINPUT, "option --nu: the Poisson ratio must lie in [0, 0.5] (got '%s')",
                   nu->value);
  }
  if (fu->value && strcmp(fu->value, "Hz") && strcmp(fu->value, "rad/s"))
    return failf(cx, VL_EINPUT, "option --freq-unit: '%s' is not Hz or rad/s", fu->value);
  if (mu->value && strcmp(mu->value, "Pa") && strcmp(mu->value, "kPa") &&
      strcmp(mu->value, "MPa") && strcmp(mu->value, "GPa"))
    return failf(cx, VL_EINPUT, "option --modulus-unit: '%s' is not one of Pa, kPa, MPa, GPa",
                 mu->value);
  if (tu->value && strcmp(tu->value, "C") && strcmp(tu->value, "K"))
    return failf(cx, VL_EINPUT, "option --temp-unit: '%s' is not C or K", tu->value);
  o.freq_unit = fu->value;
  o.modulus_unit = mu->value;
  o.temp_unit = tu->value;
  if (tpd->value) {
    if ((rc = number_opt(cx, tpd, &o.terms_per_decade)) >= 0) return rc;
    if (!(o.terms_per_decade > 0.0 && o.terms_per_decade <= VL_PRONY_FIT_MAX_PER_DECADE))
      return failf(cx, VL_EINPUT, "option --terms-per-decade: must lie in (0, %g] (got '%s')",
                   VL_PRONY_FIT_MAX_PER_DECADE, tpd->value);
  }
  if (fw->value) {
    if (!strcmp(fw->value, "relative"))
      o.weights = VL_PRONY_WEIGHTS_RELATIVE;
    else if (!strcmp(fw->value, "modulus"))
      o.weights = VL_PRONY_WEIGHTS_MODULUS;
    else
      return failf(cx, VL_EINPUT, "option --fit-weights: '%s' is not relative or modulus",
                   fw->value);
  }
  if (mod->value) {
    if (!strcmp(mod->value, "tensile"))
      o.moduli = VL_DMA_MODULI_TENSILE;
    else if (!strcmp(mod->value, "shear"))
      o.moduli = VL_DMA_MODULI_SHEAR;
    else
      return failf(cx, VL_EINPUT, "option --moduli: '%s' is not tensile or shear", mod->value);
  }
  if ((rc = check_compound_texts(cx, cls, desc, file)) >= 0) return rc;

  vl_error err;
  vl_measured m;
  vl_status st = vl_measured_read_file(file->value, &o, &m, &err);
  if (st != VL_OK) return fail(cx, st, err.msg);
  vl_db_compound *c = calloc(1, sizeof *c);
  vl_db *db = NULL;
  if (!c) {
    vl_measured_free(&m);
    return fail(cx, VL_ENOMEM, "out of memory");
  }
  snprintf(c->name, sizeof c->name, "%s", name);
  snprintf(c->class_name, sizeof c->class_name, "%s", cls->value ? cls->value : "other");
  snprintf(c->description, sizeof c->description, "%s", desc->value ? desc->value : "");
  snprintf(c->source_file, sizeof c->source_file, "%s", file->value);
  if ((rc = open_db(cx, g, &db)) < 0) {
    st = vl_db_compound_add_measured(db, c, &m, &err);
    vl_db_compound_fit f;
    memset(&f, 0, sizeof f);
    if (st == VL_OK) st = vl_db_compound_info(db, name, c, &err);
    if (st == VL_OK) st = vl_db_compound_fit_info(db, name, &f, &err);
    if (st != VL_OK) {
      rc = fail(cx, st, err.msg);
    } else {
      printf("added compound '%s' to %s: fitted to %s\n", name, vl_db_path(db), file->value);
      printf("  E0            %.6g Pa, Einf %.6g Pa, nu %.6g\n", vl_prony_e0(&c->prony),
             c->prony.e_inf_pa, c->prony.nu);
      if (!isnan(c->wlf_c1))
        printf("  WLF           C1 %.6g, C2 %.6g K at %.6g C\n", c->wlf_c1, c->wlf_c2_k, c->tref_c);
      fit_report_text(stdout, c, &f);
      print_notes(g, m.notes);
      rc = 0;
    }
    vl_db_compound_fit_free(&f);
  }
  vl_db_close(db);
  vl_measured_free(&m);
  free(c);
  return rc;
}

static int compound_add(const context *cx, const vl_cli_globals *g, int argc, char **argv) {
  option opts[] = {{"--prony", "FILE", NULL},
                   {"--e-inf", "PA", NULL},
                   {"--nu", "NU", NULL},
                   {"--class", "CLASS", NULL},
                   {"--description", "TEXT", NULL},
                   {"--tref", "C", NULL},
                   {"--wlf-c1", "C1", NULL},
                   {"--wlf-c2", "C2_K", NULL},
                   {"--measured", "FILE", NULL},
                   {"--freq-unit", "UNIT", NULL},
                   {"--modulus-unit", "UNIT", NULL},
                   {"--temp-unit", "UNIT", NULL},
                   {"--terms-per-decade", "N", NULL},
                   {"--fit-weights", "WEIGHTS", NULL},
                   {"--moduli", "KIND", NULL}};
  const size_t n_opts = sizeof opts / sizeof *opts;
  const char *pos[1] = {NULL}, *name = NULL;
  size_t n_pos;
  int rc;
  if ((rc = parse_args(cx, argc, argv, 2, opts, n_opts, pos, 1, &n_pos)) >= 0) return rc;
  if ((rc = need_name(cx, pos, n_pos, &name)) >= 0) return rc;
  if (find_opt(opts, n_opts, "--measured")->value)
    return compound_add_measured(cx, g, name, opts, n_opts);
  const char *measured_only[] = {"--freq-unit",        "--modulus-unit", "--temp-unit",
                                 "--terms-per-decade", "--fit-weights",  "--moduli"};
  for (size_t k = 0; k < 6; k++) {
    option *o = find_opt(opts, n_opts, measured_only[k]);
    if (o->value) return failf(cx, VL_EINPUT, "option %s belongs to --measured FILE", o->name);
  }
  const char *required[] = {"--prony", "--e-inf", "--nu"};
  for (size_t k = 0; k < 3; k++) {
    option *o = find_opt(opts, n_opts, required[k]);
    if (!o->value)
      return failf(cx, VL_EINPUT, "option %s %s is required%s", o->name, o->metavar,
                   k == 0 ? " (or --measured FILE)" : "");
  }
  option *file = find_opt(opts, n_opts, "--prony"), *einf = find_opt(opts, n_opts, "--e-inf");
  option *nu = find_opt(opts, n_opts, "--nu"), *cls = find_opt(opts, n_opts, "--class");
  option *desc = find_opt(opts, n_opts, "--description"), *tref = find_opt(opts, n_opts, "--tref");
  option *c1 = find_opt(opts, n_opts, "--wlf-c1"), *c2 = find_opt(opts, n_opts, "--wlf-c2");
  double e_inf_pa, nu_v, tref_c = 20.0, wlf_c1 = NAN, wlf_c2_k = NAN;
  if ((rc = number_opt(cx, einf, &e_inf_pa)) >= 0) return rc;
  if (!(e_inf_pa > 0.0))
    return failf(cx, VL_EINPUT, "option --e-inf: the glassy modulus must be > 0 Pa (got '%s')",
                 einf->value);
  if ((rc = number_opt(cx, nu, &nu_v)) >= 0) return rc;
  if (!(nu_v >= 0.0 && nu_v <= 0.5))
    return failf(cx, VL_EINPUT, "option --nu: the Poisson ratio must lie in [0, 0.5] (got '%s')",
                 nu->value);
  if ((rc = check_compound_texts(cx, cls, desc, file)) >= 0) return rc;
  if (tref->value) {
    if ((rc = number_opt(cx, tref, &tref_c)) >= 0) return rc;
    if (tref_c < -273.15)
      return failf(cx, VL_EINPUT, "option --tref: below absolute zero (got '%s')", tref->value);
  }
  if ((!c1->value) != (!c2->value))
    return fail(cx, VL_EINPUT, "options --wlf-c1 and --wlf-c2 go together (give both or neither)");
  if (c1->value) {
    if ((rc = number_opt(cx, c1, &wlf_c1)) >= 0) return rc;
    if ((rc = number_opt(cx, c2, &wlf_c2_k)) >= 0) return rc;
    if (!(wlf_c2_k > 0.0))
      return failf(cx, VL_EINPUT, "option --wlf-c2: C2 must be > 0 K (got '%s')", c2->value);
  }

  vl_db_compound *c = calloc(1, sizeof *c);
  if (!c) return fail(cx, VL_ENOMEM, "out of memory");
  snprintf(c->name, sizeof c->name, "%s", name);
  snprintf(c->class_name, sizeof c->class_name, "%s", cls->value ? cls->value : "other");
  snprintf(c->description, sizeof c->description, "%s", desc->value ? desc->value : "");
  snprintf(c->source_file, sizeof c->source_file, "%s", file->value);
  snprintf(c->method, sizeof c->method, "prony-csv");
  c->prony.e_inf_pa = e_inf_pa;
  c->prony.nu = nu_v;
  c->tref_c = tref_c;
  c->wlf_c1 = wlf_c1;
  c->wlf_c2_k = wlf_c2_k;
  c->fit_rms_error = NAN;

  vl_error err;
  vl_db *db = NULL;
  vl_status st = vl_csv_read_prony(file->value, &c->prony, &err);
  if (st == VL_OK) st = vl_prony_validate(&c->prony, &err);
  if (st != VL_OK) {
    rc = fail(cx, st, err.msg);
  } else if ((rc = open_db(cx, g, &db)) < 0) {
    st = vl_db_compound_add(db, c, &err);
    if (st != VL_OK) {
      rc = fail(cx, st, err.msg);
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

/* ---- surfaces --------------------------------------------------------- */

static void surface_json(vl_json *w, const vl_db_surface *s) {
  int tab = s->kind == VL_PSD_TABULATED;
  vl_json_object_begin(w, VL_JSON_INLINE);
  vl_json_key_string(w, "name", s->name);
  vl_json_key_string(w, "kind", tab ? "tabulated" : "self-affine");
  vl_json_key_string(w, "description", s->description);
  vl_json_key_number(w, "hrms_m", s->hrms_m);
  vl_json_key_number(w, "rms_slope", s->rms_slope);
  vl_json_key_number(w, "c0_m4", tab ? NAN : s->c0_m4);
  vl_json_key_number(w, "q0_per_m", s->q0_per_m);
  vl_json_key_number(w, "q1_per_m", s->q1_per_m);
  vl_json_key_number(w, "hurst", tab ? NAN : s->hurst);
  vl_json_key_integer(w, "n_points", (long long)s->n_points);
  key_text_or_null(w, "source_file", s->source_file);
  vl_json_key_string(w, "created_at", s->created_at);
  vl_json_end(w);
}

static void surface_text(FILE *out, const vl_db_surface *s) {
  int tab = s->kind == VL_PSD_TABULATED;
  fprintf(out, "surface %s (%s)\n", s->name, tab ? "tabulated" : "self-affine");
  if (s->description[0]) fprintf(out, "  description   %s\n", s->description);
  fprintf(out, "  h_rms         %.6g m\n", s->hrms_m);
  fprintf(out, "  rms slope     %.6g\n", s->rms_slope);
  if (!tab) {
    fprintf(out, "  C0            %.6g m^4\n", s->c0_m4);
    fprintf(out, "  H             %.6g (fractal dimension %.6g)\n", s->hurst, 3.0 - s->hurst);
  }
  fprintf(out, "  q0            %.6g 1/m\n", s->q0_per_m);
  fprintf(out, "  q1            %.6g 1/m\n", s->q1_per_m);
  if (tab) fprintf(out, "  points        %zu\n", s->n_points);
  if (s->source_file[0]) fprintf(out, "  source file   %s\n", s->source_file);
  fprintf(out, "  created       %s\n", s->created_at);
}

static void surface_line(FILE *out, const vl_db_surface *s) {
  int tab = s->kind == VL_PSD_TABULATED;
  fprintf(out, "%-20s %-11s h_rms %-10.4g m  rms slope %-9.4g q0 %-9.4g q1 %-9.4g 1/m  ", s->name,
          tab ? "tabulated" : "self-affine", s->hrms_m, s->rms_slope, s->q0_per_m, s->q1_per_m);
  if (tab)
    fprintf(out, "%zu points\n", s->n_points);
  else
    fprintf(out, "H %.4g\n", s->hurst);
}

static int surface_add(const context *cx, const vl_cli_globals *g, int argc, char **argv) {
  option opts[] = {{"--self-affine", NULL, NULL},   {"--hurst", "H", NULL},
                   {"--q0", "PER_M", NULL},         {"--q1", "PER_M", NULL},
                   {"--hrms", "M", NULL},           {"--psd", "FILE", NULL},
                   {"--description", "TEXT", NULL}, {"--topography", "FILE", NULL},
                   {"--psd-kind", "KIND", NULL}};
  const size_t n_opts = sizeof opts / sizeof *opts;
  const char *pos[1] = {NULL}, *name = NULL;
  size_t n_pos;
  int rc;
  if ((rc = parse_args(cx, argc, argv, 2, opts, n_opts, pos, 1, &n_pos)) >= 0) return rc;
  if ((rc = need_name(cx, pos, n_pos, &name)) >= 0) return rc;
  option *sa = find_opt(opts, n_opts, "--self-affine"), *psd_opt = find_opt(opts, n_opts, "--psd");
  option *desc = find_opt(opts, n_opts, "--description");
  option *topo = find_opt(opts, n_opts, "--topography");
  const char *sa_opts[] = {"--hurst", "--q0", "--q1", "--hrms"};
  int n_forms = (sa->value != NULL) + (psd_opt->value != NULL) + (topo->value != NULL);
  if (n_forms > 1)
    return fail(cx, VL_EINPUT,
                "give one of --self-affine, --psd FILE and --topography FILE, not several");
  if (n_forms == 0)
    return fail(cx, VL_EINPUT,
                "give --self-affine --hurst H --q0 PER_M --q1 PER_M --hrms M, --psd FILE or "
                "--topography FILE");
  for (size_t k = 0; k < 4; k++) {
    option *o = find_opt(opts, n_opts, sa_opts[k]);
    if (!sa->value && o->value)
      return failf(cx, VL_EINPUT, "option %s belongs to --self-affine, not to %s", o->name,
                   psd_opt->value ? "--psd" : "--topography");
    if (sa->value && !o->value)
      return failf(cx, VL_EINPUT, "--self-affine needs option %s %s", o->name, o->metavar);
  }
  option *pk = find_opt(opts, n_opts, "--psd-kind");
  vl_psd_file_kind kind = VL_PSD_FILE_2D;
  if (pk->value && !psd_opt->value)
    return fail(cx, VL_EINPUT, "option --psd-kind belongs to --psd FILE");
  if (pk->value && vl_psd_file_kind_parse(pk->value, &kind) != VL_OK)
    return failf(cx, VL_EINPUT, "option --psd-kind: '%s' is not 1d or 2d", pk->value);
  if (desc->value && strlen(desc->value) >= VL_DB_TEXT_MAX)
    return failf(cx, VL_EINPUT, "option --description: longer than %d characters",
                 VL_DB_TEXT_MAX - 1);
  if (topo->value) return vl_cli_surface_add_topography(g, name, topo->value, desc->value);

  vl_error err;
  vl_psd psd;
  vl_psd_read_report rep;
  vl_status st;
  memset(&psd, 0, sizeof psd);
  memset(&rep, 0, sizeof rep);
  if (sa->value) {
    double v[4];
    for (size_t k = 0; k < 4; k++)
      if ((rc = number_opt(cx, find_opt(opts, n_opts, sa_opts[k]), &v[k])) >= 0) return rc;
    if (!(v[0] > 0.0 && v[0] <= 1.0))
      return failf(cx, VL_EINPUT, "option --hurst: H must lie in (0, 1] (got '%s')",
                   find_opt(opts, n_opts, "--hurst")->value);
    if (!(v[1] > 0.0))
      return failf(cx, VL_EINPUT, "option --q0: the cut-off must be > 0 1/m (got '%s')",
                   find_opt(opts, n_opts, "--q0")->value);
    if (!(v[2] > v[1]))
      return failf(cx, VL_EINPUT, "option --q1: must be larger than --q0 (got q0 = %s, q1 = %s)",
                   find_opt(opts, n_opts, "--q0")->value, find_opt(opts, n_opts, "--q1")->value);
    if (!(v[3] > 0.0))
      return failf(cx, VL_EINPUT, "option --hrms: the rms roughness must be > 0 m (got '%s')",
                   find_opt(opts, n_opts, "--hrms")->value);
    st = vl_psd_init_self_affine(&psd, v[0], v[1], v[2], v[3], &err);
  } else {
    if (strlen(psd_opt->value) >= VL_DB_TEXT_MAX)
      return failf(cx, VL_EINPUT, "option --psd: file name longer than %d characters",
                   VL_DB_TEXT_MAX - 1);
    st = vl_csv_read_psd_file(psd_opt->value, kind, &psd, &rep, &err);
  }
  if (st != VL_OK) return fail(cx, st, err.msg);

  vl_db *db = NULL;
  if ((rc = open_db(cx, g, &db)) < 0) {
    st = vl_db_surface_add(db, name, &psd, desc->value, psd_opt->value, &err);
    if (st != VL_OK) {
      rc = fail(cx, st, err.msg);
    } else {
      printf("added surface '%s' to %s: %s, h_rms %.6g m, rms slope %.6g\n", name, vl_db_path(db),
             psd.kind == VL_PSD_TABULATED ? "tabulated" : "self-affine", vl_psd_hrms(&psd),
             vl_psd_rms_slope(&psd));
      print_notes(g, rep.notes);
      rc = 0;
    }
  }
  vl_db_close(db);
  vl_psd_free(&psd);
  return rc;
}

/* ---- fluids ----------------------------------------------------------- */

static void fluid_json(vl_json *w, const vl_db_fluid *f) {
  vl_json_object_begin(w, VL_JSON_INLINE);
  vl_json_key_string(w, "name", f->name);
  vl_json_key_number(w, "viscosity_pa_s", f->viscosity_pa_s);
  vl_json_key_number(w, "tref_c", f->tref_c);
  /* the viscosity law: all null when none is stored */
  int law = f->law.kind != VL_VISCOSITY_LAW_NONE;
  key_text_or_null(w, "viscosity_law", law ? vl_viscosity_law_name(f->law.kind) : "");
  vl_json_key_number(w, "vogel_b_k", law ? f->law.vogel_b_k : NAN);
  vl_json_key_number(w, "vogel_c_k", law ? f->law.vogel_c_k : NAN);
  vl_json_key_number(w, "law_tmin_c", law ? f->law.tmin_c : NAN);
  vl_json_key_number(w, "law_tmax_c", law ? f->law.tmax_c : NAN);
  vl_json_key_string(w, "description", f->description);
  key_text_or_null(w, "source_file", f->source_file);
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

static int fluid_add(const context *cx, const vl_cli_globals *g, int argc, char **argv) {
  option opts[] = {{"--viscosity", "PA_S", NULL},
                   {"--tref", "C", NULL},
                   {"--vogel-b", "K", NULL},
                   {"--vogel-c", "K", NULL},
                   {"--law-range", "TMIN_C,TMAX_C", NULL},
                   {"--description", "TEXT", NULL}};
  const size_t n_opts = sizeof opts / sizeof *opts;
  const char *pos[1] = {NULL}, *name = NULL;
  size_t n_pos;
  int rc;
  if ((rc = parse_args(cx, argc, argv, 2, opts, n_opts, pos, 1, &n_pos)) >= 0) return rc;
  if ((rc = need_name(cx, pos, n_pos, &name)) >= 0) return rc;
  vl_db_fluid f;
  memset(&f, 0, sizeof f);
  snprintf(f.name, sizeof f.name, "%s", name);
  f.tref_c = 20.0;
  option *o = find_opt(opts, n_opts, "--viscosity");
  if (!o->value) return fail(cx, VL_EINPUT, "option --viscosity PA_S is required");
  if ((rc = number_opt(cx, o, &f.viscosity_pa_s)) >= 0) return rc;
  if (!(f.viscosity_pa_s > 0.0))
    return failf(cx, VL_EINPUT, "option --viscosity: must be > 0 Pa s (got '%s')", o->value);
  if ((o = find_opt(opts, n_opts, "--tref"))->value) {
    if ((rc = number_opt(cx, o, &f.tref_c)) >= 0) return rc;
    if (f.tref_c < -273.15)
      return failf(cx, VL_EINPUT, "option --tref: below absolute zero (got '%s')", o->value);
  }
  if ((o = find_opt(opts, n_opts, "--description"))->value) {
    if (strlen(o->value) >= sizeof f.description)
      return failf(cx, VL_EINPUT, "option --description: longer than %zu characters",
                   sizeof f.description - 1);
    snprintf(f.description, sizeof f.description, "%s", o->value);
  }
  /* the viscosity law: all three options or none */
  option *vb = find_opt(opts, n_opts, "--vogel-b"), *vc = find_opt(opts, n_opts, "--vogel-c"),
         *vr = find_opt(opts, n_opts, "--law-range");
  int n_law = (vb->value != NULL) + (vc->value != NULL) + (vr->value != NULL);
  if (n_law != 0 && n_law != 3)
    return fail(cx, VL_EINPUT, "options --vogel-b, --vogel-c and --law-range go together");
  if (n_law == 3) {
    f.law.kind = VL_VISCOSITY_LAW_VOGEL;
    if ((rc = number_opt(cx, vb, &f.law.vogel_b_k)) >= 0) return rc;
    if ((rc = number_opt(cx, vc, &f.law.vogel_c_k)) >= 0) return rc;
    char lo[64], *comma = strchr(vr->value, ',');
    size_t len = comma ? (size_t)(comma - vr->value) : 0;
    if (!comma || len >= sizeof lo || vl_csv_parse_double(comma + 1, &f.law.tmax_c, NULL) != VL_OK)
      return failf(cx, VL_EINPUT, "option --law-range: expected TMIN_C,TMAX_C (got '%s')",
                   vr->value);
    memcpy(lo, vr->value, len);
    lo[len] = '\0';
    if (vl_csv_parse_double(lo, &f.law.tmin_c, NULL) != VL_OK)
      return failf(cx, VL_EINPUT, "option --law-range: expected TMIN_C,TMAX_C (got '%s')",
                   vr->value);
  }
  vl_db *db = NULL;
  vl_error err;
  if ((rc = open_db(cx, g, &db)) < 0) {
    vl_status st = vl_db_fluid_add(db, &f, &err);
    if (st != VL_OK) {
      rc = fail(cx, st, err.msg);
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

/* ---- list / show / remove, shared by the nouns ------------------------ */

static int do_list(const context *cx, const vl_cli_globals *g, int argc, char **argv) {
  option opts[] = {{"--json", NULL, NULL}};
  const char *pos[1] = {NULL};
  size_t n_pos;
  int rc;
  if ((rc = parse_args(cx, argc, argv, 2, opts, 1, pos, 0, &n_pos)) >= 0) return rc;
  int json = opts[0].value != NULL;
  vl_db *db = NULL;
  if ((rc = open_db(cx, g, &db)) >= 0) return rc;
  vl_error err;
  vl_status st;
  size_t n = 0;
  vl_json w;
  json_start(&w, stdout);
  if (json) vl_json_array_begin(&w, VL_JSON_STACKED);
  if (cx->kind == NOUN_COMPOUND) {
    vl_db_compound *items;
    if ((st = vl_db_compound_list(db, &items, &n, &err)) == VL_OK) {
      for (size_t i = 0; i < n; i++) {
        if (json) {
          vl_db_compound_fit f;
          if ((st = vl_db_compound_fit_info(db, items[i].name, &f, &err)) != VL_OK) break;
          compound_json(&w, &items[i], &f);
          vl_db_compound_fit_free(&f);
        } else {
          compound_line(stdout, &items[i]);
        }
      }
      free(items);
    }
  } else if (cx->kind == NOUN_SURFACE) {
    vl_db_surface *items;
    if ((st = vl_db_surface_list(db, &items, &n, &err)) == VL_OK) {
      for (size_t i = 0; i < n; i++) {
        if (json) {
          surface_json(&w, &items[i]);
        } else {
          surface_line(stdout, &items[i]);
        }
      }
      free(items);
    }
  } else {
    vl_db_fluid *items;
    if ((st = vl_db_fluid_list(db, &items, &n, &err)) == VL_OK) {
      for (size_t i = 0; i < n; i++) {
        if (json) {
          fluid_json(&w, &items[i]);
        } else {
          fluid_line(stdout, &items[i]);
        }
      }
      free(items);
    }
  }
  if (json) {
    vl_json_end(&w);
    fputc('\n', stdout);
  }
  vl_db_close(db);
  return st == VL_OK ? 0 : fail(cx, st, err.msg);
}

/* Writes the measured vs fitted curve of compound c (see `compound show
 * --help`). Returns the exit code after one message on failure, else -1. */
static int write_curve(const context *cx, vl_db *db, const vl_db_compound *c, const char *path) {
  vl_error err;
  vl_db_measured_point *pts = NULL;
  size_t n = 0;
  vl_status st = vl_db_compound_points(db, c->name, &pts, &n, &err);
  if (st != VL_OK) return fail(cx, st, err.msg);
  if (n == 0)
    return failf(cx, VL_EINPUT,
                 "option --curve: compound '%s' has no measured data (it was entered as a Prony "
                 "series)",
                 c->name);
  vl_atomic_file af;
  if (vl_atomic_file_open(&af, path, &err) != VL_OK) {
    free(pts);
    return failf(cx, VL_EIO, "option --curve: %s", err.msg);
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
    return failf(cx, VL_EIO, "option --curve: %s", err.msg);
  return -1;
}

/* `compound show NAME --plot`: DIR/moduli and, with isotherms, DIR/shifts
 * (plot.h). Returns -1 on success, else the exit code after the message. */
static int plot_compound(const context *cx, vl_db *db, const vl_db_compound *c,
                         const vl_db_compound_fit *fit, const char *dir, int quiet) {
  vl_error err = {{0}};
  vl_db_measured_point *pts = NULL;
  size_t n = 0;
  vl_status st = vl_db_compound_points(db, c->name, &pts, &n, &err);
  if (st != VL_OK) return fail(cx, st, err.msg);
  enum { NFIT = 240 };
  /* the fit over the measured window, else over the series' own times */
  double wlo = INFINITY, whi = 0;
  for (size_t k = 0; k < n; k++) {
    wlo = fmin(wlo, pts[k].reduced_omega_rad_s);
    whi = fmax(whi, pts[k].reduced_omega_rad_s);
  }
  for (size_t k = 0; n == 0 && k < c->prony.n_terms; k++) {
    wlo = fmin(wlo, 0.01 / c->prony.tau_s[k]);
    whi = fmax(whi, 100 / c->prony.tau_s[k]);
  }
  size_t n_fit = c->prony.n_terms > 0 && whi > wlo ? NFIT : 0;
  double *buf = malloc((3 * n + 3 * NFIT + 1) * sizeof *buf);
  if (!buf) {
    free(pts);
    return fail(cx, VL_ENOMEM, "out of memory");
  }
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
  char ml[96], fl[96], title[160], stem[4300];
  snprintf(ml, sizeof ml, fit->n_isotherms > 1 ? "measured, shifted to %g °C" : "measured, %g °C",
           c->tref_c);
  snprintf(fl, sizeof fl, "Prony series, %zu term%s", c->prony.n_terms,
           c->prony.n_terms == 1 ? "" : "s");
  snprintf(title, sizeof title, "compound %s at %g °C", c->name, c->tref_c);
  vl_plot_modulus_data d = {n, w, e1, e2, n_fit, fw, f1, f2, ml, fl};
  vl_plot_options opt;
  vl_plot_options_defaults(&opt);
  opt.title = title;
  int shifts = fit->has_fit && fit->n_shifts >= 2;
  if (n + n_fit == 0) {
    st = VL_EINPUT;
    vl_error_set(&err, "option --plot: compound '%s' is elastic and has no measured data", c->name);
  } else if (vl_cli_make_dirs(dir) != 0) {
    st = VL_EIO;
    vl_error_set(&err, "%s: cannot create directory: %s", dir, strerror(errno));
  } else {
    snprintf(stem, sizeof stem, "%s/moduli", dir);
    st = vl_plot_modulus(stem, &d, &opt, NULL, &err);
    if (st == VL_OK && shifts) {
      snprintf(stem, sizeof stem, "%s/shifts", dir);
      st = vl_plot_shifts(stem, fit->n_shifts, fit->shift_temperature_c, fit->shift_log10_a_t,
                          c->tref_c, c->wlf_c1, c->wlf_c2_k, &opt, NULL, &err);
    }
  }
  free(buf);
  free(pts);
  if (st != VL_OK) return fail(cx, st, err.msg);
  if (!quiet) printf("plots (png, svg) in %s: moduli%s\n", dir, shifts ? ", shifts" : "");
  return -1;
}

/* `compound show`, with its options (see do_show): prints the compound,
 * then writes --curve and --plot. Returns -1 on success, else the exit code
 * after the message. */
static int show_compound(const context *cx, vl_db *db, const char *name, const option *opts,
                         int json) {
  vl_error err;
  vl_db_compound *c = malloc(sizeof *c);
  vl_db_compound_fit f;
  memset(&f, 0, sizeof f);
  int rc = -1;
  vl_status st = c ? vl_db_compound_info(db, name, c, &err) : VL_ENOMEM;
  if (!c) vl_error_set(&err, "out of memory");
  if (st == VL_OK) st = vl_db_compound_fit_info(db, name, &f, &err);
  if (st != VL_OK) {
    rc = fail(cx, st, err.msg);
    goto done;
  }
  /* the curve first: a failure to write it prints nothing else */
  if (opts[1].value && (rc = write_curve(cx, db, c, opts[1].value)) >= 0) goto done;
  if (json) {
    vl_json w;
    json_start(&w, stdout);
    compound_json(&w, c, &f);
    fputc('\n', stdout); /* the object is complete before any message */
  } else {
    compound_text(stdout, c, &f);
  }
  if (opts[2].value) {
    char dir[4200];
    snprintf(dir, sizeof dir, "%s", opts[3].value ? opts[3].value : "");
    if (!opts[3].value) snprintf(dir, sizeof dir, "out/compound-%s", c->name);
    rc = plot_compound(cx, db, c, &f, dir, json);
  }
done:
  vl_db_compound_fit_free(&f);
  free(c);
  return rc;
}

/* The figure's stem: FILE without its extension ("dir/.hidden" keeps its
 * name). */
static void file_stem(char *stem, size_t size, const char *file) {
  snprintf(stem, size, "%s", file);
  char *slash = strrchr(stem, '/'), *base = slash ? slash + 1 : stem, *dot = strrchr(base, '.');
  if (dot && dot > base) *dot = '\0';
}

/* The spectrum of a self-affine surface on a log grid over its band. */
enum { PSD_GRID = 200 };
static void psd_grid(const vl_psd *p, double hurst, double c_q0, double *q, double *c) {
  for (size_t i = 0; i < PSD_GRID; i++) {
    q[i] = p->q0 * pow(p->q1 / p->q0, (double)i / (PSD_GRID - 1));
    c[i] = c_q0 * pow(q[i] / p->q0, -2.0 * (1.0 + hurst));
  }
}

/* `surface show NAME --plot FILE`: C(q) of the surface, with the closest
 * self-affine law over a tabulated one. Returns -1 or the exit code. */
static int plot_surface(const context *cx, vl_db *db, const char *name, const char *file,
                        int quiet) {
  vl_error err;
  vl_psd p;
  memset(&p, 0, sizeof p);
  char stem[4200], label[128], fit_label[128];
  file_stem(stem, sizeof stem, file);
  double gq[PSD_GRID], gc[PSD_GRID], h = NAN, c_q0 = NAN, rms = NAN;
  vl_status st = vl_db_surface_get(db, name, &p, &err);
  if (st == VL_OK) st = vl_psd_fit_self_affine(&p, &h, &c_q0, &rms, &err);
  if (st == VL_OK) {
    int tab = p.kind == VL_PSD_TABULATED;
    psd_grid(&p, h, c_q0, gq, gc);
    snprintf(label, sizeof label, tab ? "%s (tabulated)" : "%s (self-affine H = %.3g)", name, h);
    snprintf(fit_label, sizeof fit_label, "self-affine fit H = %.3g", h);
    vl_plot_psd_data d = {tab ? p.n : PSD_GRID,
                          tab ? p.q : gq,
                          tab ? p.C : gc,
                          label,
                          tab ? PSD_GRID : 0,
                          gq,
                          gc,
                          fit_label};
    vl_plot_options opt;
    vl_plot_options_defaults(&opt);
    st = vl_plot_psd(stem, &d, &opt, NULL, &err);
    if (st == VL_OK && !quiet) {
      printf("wrote %s.png and %s.svg", stem, stem);
      if (tab) printf(" (self-affine fit: H %.4g, rms %.3g in log10 C)", h, rms);
      printf("\n");
    }
  }
  vl_psd_free(&p);
  return st == VL_OK ? -1 : fail(cx, st, err.msg);
}

static int do_show(const context *cx, const vl_cli_globals *g, int argc, char **argv) {
  /* a compound's --plot writes into --out DIR, a surface's into FILE */
  option opts[] = {{"--json", NULL, NULL},
                   {"--curve", "FILE", NULL},
                   {"--plot", NULL, NULL},
                   {"--out", "DIR", NULL}};
  option surface_opts[] = {{"--json", NULL, NULL}, {"--plot", "FILE", NULL}};
  size_t n_opts = cx->kind == NOUN_COMPOUND ? 4 : cx->kind == NOUN_SURFACE ? 2 : 1;
  if (cx->kind == NOUN_SURFACE) memcpy(opts, surface_opts, sizeof surface_opts);
  const char *pos[1] = {NULL}, *name = NULL;
  size_t n_pos;
  int rc;
  if ((rc = parse_args(cx, argc, argv, 2, opts, n_opts, pos, 1, &n_pos)) >= 0) return rc;
  if ((rc = need_name(cx, pos, n_pos, &name)) >= 0) return rc;
  int json = opts[0].value != NULL;
  if (opts[3].value && !opts[2].value) return fail(cx, VL_EINPUT, "option --out goes with --plot");
  vl_db *db = NULL;
  if ((rc = open_db(cx, g, &db)) >= 0) return rc;
  vl_error err;
  vl_status st = VL_OK;
  vl_json w;
  json_start(&w, stdout);
  if (cx->kind == NOUN_COMPOUND) {
    rc = show_compound(cx, db, name, opts, json);
  } else if (cx->kind == NOUN_SURFACE) {
    vl_db_surface s;
    if ((st = vl_db_surface_info(db, name, &s, &err)) == VL_OK) {
      json ? surface_json(&w, &s) : surface_text(stdout, &s);
      if (json) fputc('\n', stdout);
      if (opts[1].value) rc = plot_surface(cx, db, name, opts[1].value, json);
    }
  } else {
    vl_db_fluid f;
    if ((st = vl_db_fluid_info(db, name, &f, &err)) == VL_OK)
      json ? fluid_json(&w, &f) : fluid_text(stdout, &f);
  }
  if (st == VL_OK && json && cx->kind == NOUN_FLUID) fputc('\n', stdout);
  if (st != VL_OK) rc = fail(cx, st, err.msg);
  vl_db_close(db);
  return rc >= 0 ? rc : 0;
}

/* `surface flow-factors NAME ...`: parsed here, computed in cli_surface.c. */
static int do_flow_factors(const context *cx, const vl_cli_globals *g, int argc, char **argv) {
  option opts[] = {{"--model", "MODEL", NULL}, {"--u-range", "MIN,MAX", NULL},
                   {"--points", "N", NULL},    {"--film-cutoff", "M", NULL},
                   {"--out", "FILE", NULL},    {"--json", NULL, NULL},
                   {"--plot", NULL, NULL}};
  const char *pos[1] = {NULL}, *name = NULL;
  size_t n_pos;
  int rc;
  if ((rc = parse_args(cx, argc, argv, 2, opts, 7, pos, 1, &n_pos)) >= 0) return rc;
  if ((rc = need_name(cx, pos, n_pos, &name)) >= 0) return rc;
  vl_cli_flow_factor_args a = {opts[0].value,        opts[1].value, opts[2].value,
                               opts[3].value,        opts[4].value, opts[5].value != NULL,
                               opts[6].value != NULL};
  return vl_cli_surface_flow_factors(g, name, &a);
}

static int do_remove(const context *cx, const vl_cli_globals *g, int argc, char **argv) {
  const char *pos[1] = {NULL}, *name = NULL;
  size_t n_pos;
  int rc;
  if ((rc = parse_args(cx, argc, argv, 2, NULL, 0, pos, 1, &n_pos)) >= 0) return rc;
  if ((rc = need_name(cx, pos, n_pos, &name)) >= 0) return rc;
  vl_db *db = NULL;
  if ((rc = open_db(cx, g, &db)) >= 0) return rc;
  vl_error err;
  size_t pairs = 0; /* its pairs go with it (ON DELETE CASCADE): say so */
  if (vl_db_pair_count(db, cx->noun, name, &pairs, &err) != VL_OK) pairs = 0;
  vl_status st = cx->kind == NOUN_COMPOUND  ? vl_db_compound_remove(db, name, &err)
                 : cx->kind == NOUN_SURFACE ? vl_db_surface_remove(db, name, &err)
                                            : vl_db_fluid_remove(db, name, &err);
  if (st == VL_OK && pairs)
    printf("removed %s '%s' from %s, and its %zu pair%s\n", cx->noun, name, vl_db_path(db), pairs,
           pairs > 1 ? "s" : "");
  else if (st == VL_OK)
    printf("removed %s '%s' from %s\n", cx->noun, name, vl_db_path(db));
  vl_db_close(db);
  return st == VL_OK ? 0 : fail(cx, st, err.msg);
}

/* ---- entry point ------------------------------------------------------ */

int vl_cli_materials(const vl_cli_globals *g, int argc, char **argv) {
  context cx = {.noun = argv[0]};
  if (!strcmp(argv[0], "compound"))
    cx.kind = NOUN_COMPOUND;
  else if (!strcmp(argv[0], "surface"))
    cx.kind = NOUN_SURFACE;
  else if (!strcmp(argv[0], "fluid"))
    cx.kind = NOUN_FLUID;
  else
    return failf(&cx, VL_EINTERNAL, "not a material noun");

  if (argc < 2) {
    fputs(noun_help[cx.kind], stderr);
    return vl_status_exit_code(VL_EINPUT);
  }
  const char *verb = argv[1];
  if (!strcmp(verb, "--help") || !strcmp(verb, "-h") || !strcmp(verb, "help")) {
    fputs(noun_help[cx.kind], stdout);
    return 0;
  }
  static const char *const verbs[] = {"list", "show", "add", "remove", "flow-factors"};
  size_t n_verbs = cx.kind == NOUN_SURFACE ? 5 : 4; /* flow-factors: surfaces only */
  int known = 0;
  for (size_t k = 0; k < n_verbs; k++)
    known |= !strcmp(verb, verbs[k]);
  if (!known)
    return failf(&cx, VL_EINPUT,
                 "unknown verb '%s' (expected list, show, add%s or remove; see "
                 "viscolube %s --help)",
                 verb, cx.kind == NOUN_SURFACE ? ", flow-factors" : "", cx.noun);
  cx.verb = verb;
  /* --help anywhere after the verb wins, so a half-typed command can ask. */
  for (int i = 2; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      verb_help(cx.kind, verb, stdout);
      return 0;
    }
  }
  if (!strcmp(verb, "list")) return do_list(&cx, g, argc, argv);
  if (!strcmp(verb, "show")) return do_show(&cx, g, argc, argv);
  if (!strcmp(verb, "remove")) return do_remove(&cx, g, argc, argv);
  if (!strcmp(verb, "flow-factors")) return do_flow_factors(&cx, g, argc, argv);
  if (cx.kind == NOUN_COMPOUND) return compound_add(&cx, g, argc, argv);
  if (cx.kind == NOUN_SURFACE) return surface_add(&cx, g, argc, argv);
  return fluid_add(&cx, g, argc, argv);
}
