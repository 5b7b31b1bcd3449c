/* DMA import: header and units, isotherms, superposition, WLF, Prony fit
 * (dma.h). The numbers themselves are read by the strict CSV reader of
 * csv.h; this file only recognises the columns, works out their units and
 * hands the reader a column list that names them exactly as the file does,
 * so every cell-level error keeps the reader's FILE:LINE: column form. */
#define _POSIX_C_SOURCE 200809L

#include "viscolube/dma.h"
#include "csv_private.h"
#include "dma_private.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "prony_fit_internal.h"
#include "rheology_internal.h"
#include "tts.h"
#include "viscolube/csv.h"

#include "import_text.h"
#include "viscolube/edit_distance.h"

#define TWO_PI 6.283185307179586476925287
#define MAX_FIELDS 64
#define CELL_MAX 128
#define DEFAULT_TREF_C 20.0
/* A DMA export of VL_DMA_MAX_POINTS rows is a few MB at most. */
#define DMA_MAX_BYTES ((size_t)64 << 20)
/* E', E'' and tan delta (or |E*|) all given: the redundant column must
 * match this well (exports round each column to 4-6 digits on its own). */
#define TAN_CONSISTENCY 0.02
/* A neighbouring pair whose shift points the wrong way by more than this
 * (decades) is not scatter: colder must mean stiffer. */
#define WRONG_WAY_TOL 0.1
/* Plausible values (SI, after unit conversion): a rubber's storage and
 * complex moduli lie between a soft gel's and a glass's; E'' may be a
 * thousandth of E' (tan delta 1e-3) in the rubbery plateau of a soft
 * compound, so its floor is lower. Outside: a unit mistake, which the
 * message names. */
#define MODULUS_MIN_PA 1e4
#define LOSS_MIN_PA 1e1
#define MODULUS_MAX_PA 1e12
#define TEMP_MIN_C (-150.0)
#define TEMP_MAX_C 400.0
#define KELVIN_LIKE_MIN_C 200.0

typedef enum { R_FREQ, R_STORAGE, R_LOSS, R_ABS, R_TAN, R_J1, R_J2, R_TEMP, R_SET, R_COUNT } role;

typedef enum { U_FREQ, U_MODULUS, U_COMPLIANCE, U_TEMP, U_NONE } unit_family;

/* What a modulus column's name says it holds. */
typedef enum { K_GENERIC, K_TENSILE, K_SHEAR } modulus_kind;

static const struct {
  const char *what; /* for messages */
  unit_family family;
} roles[R_COUNT] = {
    [R_FREQ] = {"frequency", U_FREQ},
    [R_STORAGE] = {"storage modulus", U_MODULUS},
    [R_LOSS] = {"loss modulus", U_MODULUS},
    [R_ABS] = {"complex modulus |E*|", U_MODULUS},
    [R_TAN] = {"tan delta", U_NONE},
    [R_J1] = {"storage compliance J'", U_COMPLIANCE},
    [R_J2] = {"loss compliance J''", U_COMPLIANCE},
    [R_TEMP] = {"temperature", U_TEMP},
    [R_SET] = {"set", U_NONE},
};

/* Column names, compared without regard to case, blanks, '_', '-' and
 * '.' (one-letter names exactly); 'δ' reads as "delta" and 'ω' as
 * "omega". */
static const struct {
  const char *alias;
  role r;
  modulus_kind k;
} aliases[] = {
    {"f", R_FREQ, K_GENERIC},
    {"w", R_FREQ, K_GENERIC},
    {"freq", R_FREQ, K_GENERIC},
    {"frequency", R_FREQ, K_GENERIC},
    {"omega", R_FREQ, K_GENERIC},
    {"angular frequency", R_FREQ, K_GENERIC},
    {"ang freq", R_FREQ, K_GENERIC},
    {"E'", R_STORAGE, K_TENSILE},
    {"E_stor", R_STORAGE, K_TENSILE},
    {"E_storage", R_STORAGE, K_TENSILE},
    {"E1", R_STORAGE, K_TENSILE},
    {"E_prime", R_STORAGE, K_TENSILE},
    {"tensile storage modulus", R_STORAGE, K_TENSILE},
    {"storage modulus E'", R_STORAGE, K_TENSILE},
    {"storage", R_STORAGE, K_GENERIC},
    {"storage modulus", R_STORAGE, K_GENERIC},
    {"G'", R_STORAGE, K_SHEAR},
    {"G_stor", R_STORAGE, K_SHEAR},
    {"G_storage", R_STORAGE, K_SHEAR},
    {"G1", R_STORAGE, K_SHEAR},
    {"G_prime", R_STORAGE, K_SHEAR},
    {"shear storage modulus", R_STORAGE, K_SHEAR},
    {"storage shear modulus", R_STORAGE, K_SHEAR},
    {"storage modulus G'", R_STORAGE, K_SHEAR},
    {"E''", R_LOSS, K_TENSILE},
    {"E\"", R_LOSS, K_TENSILE},
    {"E_loss", R_LOSS, K_TENSILE},
    {"E2", R_LOSS, K_TENSILE},
    {"E_double_prime", R_LOSS, K_TENSILE},
    {"tensile loss modulus", R_LOSS, K_TENSILE},
    {"loss modulus E''", R_LOSS, K_TENSILE},
    {"loss", R_LOSS, K_GENERIC},
    {"loss modulus", R_LOSS, K_GENERIC},
    {"G''", R_LOSS, K_SHEAR},
    {"G\"", R_LOSS, K_SHEAR},
    {"G_loss", R_LOSS, K_SHEAR},
    {"G2", R_LOSS, K_SHEAR},
    {"G_double_prime", R_LOSS, K_SHEAR},
    {"shear loss modulus", R_LOSS, K_SHEAR},
    {"loss shear modulus", R_LOSS, K_SHEAR},
    {"loss modulus G''", R_LOSS, K_SHEAR},
    {"|E*|", R_ABS, K_TENSILE},
    {"E*", R_ABS, K_TENSILE},
    {"|E|", R_ABS, K_TENSILE},
    {"E_abs", R_ABS, K_TENSILE},
    {"E_star", R_ABS, K_TENSILE},
    {"E_complex", R_ABS, K_TENSILE},
    {"complex modulus", R_ABS, K_GENERIC},
    {"|G*|", R_ABS, K_SHEAR},
    {"G*", R_ABS, K_SHEAR},
    {"|G|", R_ABS, K_SHEAR},
    {"G_abs", R_ABS, K_SHEAR},
    {"G_star", R_ABS, K_SHEAR},
    {"G_complex", R_ABS, K_SHEAR},
    {"complex shear modulus", R_ABS, K_SHEAR},
    {"tan delta", R_TAN, K_GENERIC},
    {"tan_del", R_TAN, K_GENERIC},
    {"tand", R_TAN, K_GENERIC},
    {"tan(delta)", R_TAN, K_GENERIC},
    {"loss factor", R_TAN, K_GENERIC},
    {"loss tangent", R_TAN, K_GENERIC},
    {"J'", R_J1, K_GENERIC},
    {"J_stor", R_J1, K_GENERIC},
    {"J_storage", R_J1, K_GENERIC},
    {"storage compliance", R_J1, K_GENERIC},
    {"J1", R_J1, K_GENERIC},
    {"J''", R_J2, K_GENERIC},
    {"J\"", R_J2, K_GENERIC},
    {"J_loss", R_J2, K_GENERIC},
    {"loss compliance", R_J2, K_GENERIC},
    {"J2", R_J2, K_GENERIC},
    {"T", R_TEMP, K_GENERIC},
    {"temp", R_TEMP, K_GENERIC},
    {"temperature", R_TEMP, K_GENERIC},
    {"set", R_SET, K_GENERIC},
    {"isotherm", R_SET, K_GENERIC},
};
#define N_ALIASES (sizeof aliases / sizeof *aliases)

typedef struct {
  const char *name; /* as printed; matched without regard to case and blanks */
  double factor;    /* SI value = factor * file value (+ offset for temperatures) */
  double offset;
  int primary;    /* listed in messages */
  int omega_only; /* "1/s": an angular frequency only under an omega name */
} unit_def;

static const unit_def freq_units[] = {{"Hz", TWO_PI, 0.0, 1, 0},    {"rad/s", 1.0, 0.0, 1, 0},
                                      {"rad s^-1", 1.0, 0.0, 0, 0}, {"rad.s-1", 1.0, 0.0, 0, 0},
                                      {"rad*s^-1", 1.0, 0.0, 0, 0}, {"rad/sec", 1.0, 0.0, 0, 0},
                                      {"1/s", 1.0, 0.0, 0, 1},      {"s^-1", 1.0, 0.0, 0, 1},
                                      {"s-1", 1.0, 0.0, 0, 1},      {NULL, 0, 0, 0, 0}};
static const unit_def modulus_units[] = {
    {"Pa", 1.0, 0.0, 1, 0},      {"kPa", 1e3, 0.0, 1, 0},   {"MPa", 1e6, 0.0, 1, 0},
    {"GPa", 1e9, 0.0, 1, 0},     {"N/m^2", 1.0, 0.0, 0, 0}, {"N/m2", 1.0, 0.0, 0, 0},
    {"N/mm^2", 1e6, 0.0, 0, 0},  {"N/mm2", 1e6, 0.0, 0, 0}, {"dyn/cm^2", 0.1, 0.0, 0, 0},
    {"dyn/cm2", 0.1, 0.0, 0, 0}, {NULL, 0, 0, 0, 0}};
static const unit_def compliance_units[] = {
    {"1/Pa", 1.0, 0.0, 1, 0},    {"1/kPa", 1e-3, 0.0, 1, 0},  {"1/MPa", 1e-6, 0.0, 1, 0},
    {"1/GPa", 1e-9, 0.0, 1, 0},  {"Pa^-1", 1.0, 0.0, 0, 0},   {"kPa^-1", 1e-3, 0.0, 0, 0},
    {"MPa^-1", 1e-6, 0.0, 0, 0}, {"GPa^-1", 1e-9, 0.0, 0, 0}, {NULL, 0, 0, 0, 0}};
static const unit_def temp_units[] = {{"C", 1.0, 0.0, 1, 0},
                                      {"\xC2\xB0"
                                       "C",
                                       1.0, 0.0, 0, 0},
                                      {"\xC2\xBA"
                                       "C",
                                       1.0, 0.0, 0, 0},
                                      {"\xE2\x84\x83", 1.0, 0.0, 0, 0},
                                      {"degC", 1.0, 0.0, 0, 0},
                                      {"deg C", 1.0, 0.0, 0, 0},
                                      {"celsius", 1.0, 0.0, 0, 0},
                                      {"K", 1.0, -273.15, 1, 0},
                                      {"kelvin", 1.0, -273.15, 0, 0},
                                      {NULL, 0, 0, 0, 0}};
static const unit_def none_units[] = {
    {"-", 1.0, 0.0, 1, 0}, {"1", 1.0, 0.0, 1, 0}, {"", 1.0, 0.0, 1, 0}, {NULL, 0, 0, 0, 0}};

static const unit_def *family_units(unit_family f) {
  switch (f) {
  case U_FREQ: return freq_units;
  case U_MODULUS: return modulus_units;
  case U_COMPLIANCE: return compliance_units;
  case U_TEMP: return temp_units;
  default: return none_units;
  }
}

/* "Hz|rad/s" for the CSV reader and for messages ("Hz, rad/s"): the
 * primary spellings. */
static void family_list(unit_family f, const char *sep, char *buf, size_t size) {
  size_t k = 0;
  buf[0] = '\0';
  for (const unit_def *u = family_units(f); u->name && k < size; u++) {
    if (u->primary && (!strcmp(sep, "|") || u->name[0])) {
      int w = snprintf(buf + k, size - k, "%s%s", k ? sep : "", u->name);
      if (w < 0) break;
      k += (size_t)w;
    }
  }
}

/* Unit text compared without blanks and, but for one exception, case:
 * "mpa" is MPa (a millipascal modulus is no rubber's). */
static int unit_eq(const char *a, const char *b) {
  for (;;) {
    while (*a == ' ')
      a++;
    while (*b == ' ')
      b++;
    char x = *a, y = *b;
    if (x >= 'A' && x <= 'Z') x = (char)(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = (char)(y - 'A' + 'a');
    if (x != y) return 0;
    if (!x) return 1;
    a++, b++;
  }
}

static const unit_def *find_unit(unit_family f, const char *s) {
  for (const unit_def *u = family_units(f); u->name; u++)
    if (unit_eq(u->name, s)) return u;
  return NULL;
}

const char *vl_dma_kind_name(vl_dma_kind kind) {
  switch (kind) {
  case VL_DMA_STORAGE_LOSS: return "storage-loss";
  case VL_DMA_STORAGE_TAN_DELTA: return "storage-tan-delta";
  case VL_DMA_COMPLIANCE: return "compliance";
  }
  return "?";
}

const char *vl_dma_moduli_name(vl_dma_moduli moduli) {
  switch (moduli) {
  case VL_DMA_MODULI_AUTO: return "auto";
  case VL_DMA_MODULI_TENSILE: return "tensile";
  case VL_DMA_MODULI_SHEAR: return "shear";
  }
  return "?";
}

vl_dma_options vl_dma_options_default(void) {
  vl_dma_options o = {
      NULL, NULL, NULL, NAN, 0.0, VL_PRONY_WEIGHTS_RELATIVE, 0.5, VL_DMA_MODULI_AUTO};
  return o;
}

void vl_measured_free(vl_measured *m) {
  if (!m) return;
  free(m->source);
  free(m->line);
  free(m->omega_rad_s);
  free(m->temperature_c);
  free(m->storage_pa);
  free(m->loss_pa);
  free(m->j1_per_pa);
  free(m->j2_per_pa);
  free(m->isotherm);
  free(m->reduced_omega_rad_s);
  free(m->iso_temperature_c);
  free(m->iso_log10_a_t);
  free(m->iso_points);
  free(m->iso_join_rms);
  free(m->iso_join_step);
  free(m->iso_tan_delta_rise);
  memset(m, 0, sizeof *m);
}

/* Appends one sentence (a line) to m->notes; silently cut when full. */
static void note(vl_measured *m, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void note(vl_measured *m, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vl_import_note_v(m->notes, sizeof m->notes, fmt, ap);
  va_end(ap);
}

/* ---- header recognition ----------------------------------------------- */

/* The cell without its blanks and one pair of double quotes, as the CSV
 * reader matches header and units cells, into a NUL-terminated copy.
 * Returns 0 if too long. */
static int cell_text(vl_span cell, char *out, size_t cap) {
  vl_span t = vl_span_unquote(cell);
  if (t.n >= cap) return 0;
  memcpy(out, t.p, t.n);
  out[t.n] = '\0';
  return 1;
}

/* Lower case without blanks, '_', '-' and '.', 'δ' as "delta" and 'ω' as
 * "omega": "E_Stor" and "e stor" compare equal to "estor", "tan δ" to
 * "tandelta". */
static void normalise(const char *s, char *out, size_t cap) {
  size_t k = 0;
  for (; *s && k + 1 < cap; s++) {
    char c = *s;
    const char *word = NULL;
    if (s[0] == '\xCE' && s[1] == '\xB4') word = "delta";
    if (s[0] == '\xCF' && s[1] == '\x89') word = "omega";
    if (word) {
      for (; *word && k + 1 < cap; word++)
        out[k++] = *word;
      s++;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '_' || c == '-' || c == '.') continue;
    if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
    out[k++] = c;
  }
  out[k] = '\0';
}

static int alias_match(const char *alias, const char *name) {
  if (strlen(alias) == 1) return !strcmp(alias, name);
  char a[CELL_MAX], b[CELL_MAX];
  normalise(alias, a, sizeof a);
  normalise(name, b, sizeof b);
  return a[0] && !strcmp(a, b);
}

/* Role (R_COUNT if none) and modulus kind of a header name. */
static role name_role(const char *name, modulus_kind *k) {
  for (size_t i = 0; i < N_ALIASES; i++) {
    if (alias_match(aliases[i].alias, name)) {
      *k = aliases[i].k;
      return aliases[i].r;
    }
  }
  return R_COUNT;
}

/* The closest alias to an unknown name, or NULL if none is close. */
static const char *suggest(const char *name) {
  char b[CELL_MAX];
  normalise(name, b, sizeof b);
  const char *best = NULL;
  size_t len = strlen(b), limit = len / 2 < 1 ? 1 : len / 2 > 2 ? 2 : len / 2;
  size_t best_d = limit + 1;
  for (size_t i = 0; i < N_ALIASES; i++) {
    char a[CELL_MAX];
    normalise(aliases[i].alias, a, sizeof a);
    if (strlen(a) < 3) continue;
    size_t d = vl_edit_distance(a, strlen(a), b, strlen(b), false);
    if (d < best_d) best_d = d, best = aliases[i].alias;
  }
  return best;
}

typedef struct {
  role r;              /* R_COUNT: an ignored column */
  modulus_kind k;      /* what a modulus column's name says */
  char text[CELL_MAX]; /* the cell as the CSV reader will match it */
  char inline_unit[CELL_MAX];
  int has_inline_unit;
  char row_unit[CELL_MAX];
  int has_row_unit;
} field;

/* Splits "E' [MPa]" / "f (Hz)" / "G_storage_pa" / "temperature_C" into a
 * known name and its unit when the whole text is not itself a known name;
 * R_COUNT when no reading names a known column. */
static role parse_header_cell(field *f) {
  role r = name_role(f->text, &f->k);
  if (r != R_COUNT) return r;
  size_t n = strlen(f->text);
  char name[CELL_MAX], unit[CELL_MAX];
  char close = n ? f->text[n - 1] : 0, open = close == ']' ? '[' : close == ')' ? '(' : 0;
  const char *o = open ? strrchr(f->text, open) : NULL;
  if (o && o != f->text &&
      cell_text((vl_span){f->text, (size_t)(o - f->text)}, name, sizeof name) &&
      cell_text((vl_span){o + 1, (size_t)(f->text + n - 1 - (o + 1))}, unit, sizeof unit)) {
    r = name_role(name, &f->k);
    if (r == R_COUNT) return R_COUNT;
    snprintf(f->inline_unit, sizeof f->inline_unit, "%s", unit);
    f->has_inline_unit = 1;
    return r;
  }
  /* a unit after the last '_' or blank: only when it is one of the unit
   * spellings of that column, so "E_stor" is not read as E with unit stor */
  for (size_t i = n; i-- > 1;) {
    if (f->text[i] != '_' && f->text[i] != ' ') continue;
    if (!cell_text((vl_span){f->text, i}, name, sizeof name) ||
        !cell_text((vl_span){f->text + i + 1, n - i - 1}, unit, sizeof unit))
      continue;
    modulus_kind k;
    r = name_role(name, &k);
    if (r == R_COUNT || !unit[0]) continue;
    const unit_def *u = find_unit(roles[r].family, unit);
    if (!u || roles[r].family == U_NONE) continue;
    f->k = k;
    snprintf(f->inline_unit, sizeof f->inline_unit, "%s", unit);
    f->has_inline_unit = 1;
    return r;
  }
  return R_COUNT;
}

/* Is the frequency column named as an angular frequency (so "1/s" is
 * rad/s)? */
static int omega_name(const field *f) {
  char norm[CELL_MAX];
  normalise(f->text, norm, sizeof norm);
  return (f->text[0] == 'w' && (f->text[1] == '\0' || f->text[1] == ' ' || f->text[1] == '[' ||
                                f->text[1] == '(' || f->text[1] == '_')) ||
         !strncmp(norm, "omega", 5) || !strncmp(norm, "angular", 7) || !strncmp(norm, "ang", 3);
}

/* ---- the import ------------------------------------------------------- */

typedef struct {
  const char *src;
  vl_dialect dialect;
  field fields[MAX_FIELDS];
  size_t n_fields;
  size_t header_line, units_line;
  int col_of_role[R_COUNT]; /* requested column index, or -1 */
  int field_of_role[R_COUNT];
  const unit_def *unit[R_COUNT];
  int shear;           /* the moduli are shear moduli G (converted to E) */
  double shear_factor; /* E / G = 2 (1 + nu) */
  char ignored[512];   /* "'run', 'force'": the columns not used */
  size_t n_ignored;
} layout;

static int is_number(const layout *lay, const char *s) {
  double v;
  const char *why;
  return vl_import_parse_number(s, strlen(s), lay->dialect.decimal_comma, &v, &why) == VL_OK;
}

/* A header field no known column takes: refused when its name is a likely
 * misspelling of one (or time-domain data), else listed as ignored. */
static vl_status unknown_field(layout *lay, size_t k, size_t line_no, vl_error *err) {
  field *f = &lay->fields[k];
  char norm[CELL_MAX];
  normalise(f->text, norm, sizeof norm);
  if (!strcmp(f->text, "t") || !strcmp(norm, "time") || !strncmp(norm, "erelax", 6)) {
    vl_error_set(err,
                 "%s:%zu: header field %zu: '%.40s' looks like time-domain (relaxation) data; "
                 "only frequency sweeps (f, E', E'' or tan delta, or J', J'') can be imported",
                 lay->src, line_no, k + 1, f->text);
    return VL_EINPUT;
  }
  const char *s = suggest(f->text);
  if (s) {
    vl_error_set(err,
                 "%s:%zu: header field %zu: unknown column '%.40s' (did you mean '%s'? known: "
                 "frequency f, E' or G' (storage), E'' or G'' (loss), |E*| or |G*|, tan delta, "
                 "J', J'', T, set; see compound add --help)",
                 lay->src, line_no, k + 1, f->text, s);
    return VL_EINPUT;
  }
  f->r = R_COUNT;
  size_t len = strlen(lay->ignored);
  snprintf(lay->ignored + len, sizeof lay->ignored - len, "%s'%.40s'", len ? ", " : "", f->text);
  lay->n_ignored++;
  return VL_OK;
}

/* The role of every header field (lay->fields[0..count), their text already
 * read): a known column name, none twice, or an ignored column. Sets
 * lay->n_fields. */
static vl_status header_roles(layout *lay, size_t count, size_t line_no, vl_error *err) {
  for (size_t k = 0; k < count; k++) {
    field *f = &lay->fields[k];
    if (!f->text[0]) {
      vl_error_set(err, "%s:%zu: header field %zu is empty (every column needs a name)", lay->src,
                   line_no, k + 1);
      return VL_EINPUT;
    }
    role r = parse_header_cell(f);
    if (r == R_COUNT) {
      vl_status st = unknown_field(lay, k, line_no, err);
      if (st != VL_OK) return st;
      continue;
    }
    if (lay->field_of_role[r] >= 0) {
      vl_error_set(err,
                   "%s:%zu: header field %zu: a second %s column ('%.40s', after '%.40s' in "
                   "field %d)",
                   lay->src, line_no, k + 1, roles[r].what, f->text,
                   lay->fields[lay->field_of_role[r]].text, lay->field_of_role[r] + 1);
      return VL_EINPUT;
    }
    f->r = r;
    lay->field_of_role[r] = (int)k;
  }
  lay->n_fields = count;
  return VL_OK;
}

/* Tensile or shear: what the names say (generic names follow the named
 * ones, else the option, else tensile), refused when they disagree with
 * each other or with the option. */
static vl_status modulus_kind_of(layout *lay, const vl_dma_options *o, size_t line_no,
                                 vl_error *err) {
  int first[3] = {-1, -1, -1};
  const role mods[3] = {R_STORAGE, R_LOSS, R_ABS};
  for (int i = 0; i < 3; i++) {
    int f = lay->field_of_role[mods[i]];
    if (f >= 0 && first[lay->fields[f].k] < 0) first[lay->fields[f].k] = f;
  }
  if (first[K_TENSILE] >= 0 && first[K_SHEAR] >= 0) {
    vl_error_set(err,
                 "%s:%zu: the header mixes tensile and shear moduli ('%s' and '%s'): give E', "
                 "E'' or G', G''",
                 lay->src, line_no, lay->fields[first[K_TENSILE]].text,
                 lay->fields[first[K_SHEAR]].text);
    return VL_EINPUT;
  }
  int named = first[K_SHEAR] >= 0 ? K_SHEAR : first[K_TENSILE] >= 0 ? K_TENSILE : K_GENERIC;
  if (o->moduli != VL_DMA_MODULI_AUTO && named != K_GENERIC &&
      (named == K_SHEAR) != (o->moduli == VL_DMA_MODULI_SHEAR)) {
    vl_error_set(err, "%s:%zu: column '%s' holds %s moduli but the options say %s", lay->src,
                 line_no, lay->fields[first[named]].text, named == K_SHEAR ? "shear" : "tensile",
                 vl_dma_moduli_name(o->moduli));
    return VL_EINPUT;
  }
  lay->shear = named == K_SHEAR || (named == K_GENERIC && o->moduli == VL_DMA_MODULI_SHEAR);
  lay->shear_factor = 2.0 * (1.0 + o->nu);
  return VL_OK;
}

/* The columns a DMA file needs together: a frequency, and E' with E'' or
 * tan delta, or E'' or |E*| with tan delta, or J' with J''. */
static vl_status check_roles(const layout *lay, size_t line_no, vl_error *err) {
  const int *fr = lay->field_of_role;
  const char *ign = lay->n_ignored ? "; columns not recognised: " : "";
  if (fr[R_FREQ] < 0) {
    vl_error_set(err, "%s:%zu: the header lacks a frequency column (f, freq or omega)%s%s",
                 lay->src, line_no, ign, lay->ignored);
    return VL_EINPUT;
  }
  int moduli = fr[R_STORAGE] >= 0 || fr[R_LOSS] >= 0 || fr[R_TAN] >= 0 || fr[R_ABS] >= 0;
  int compl = fr[R_J1] >= 0 || fr[R_J2] >= 0;
  if (moduli && compl ) {
    vl_error_set(err,
                 "%s:%zu: the header has both moduli and compliances: give E' with E'' (or "
                 "tan delta), or J' with J''",
                 lay->src, line_no);
    return VL_EINPUT;
  }
  if (compl &&(fr[R_J1] < 0 || fr[R_J2] < 0)) {
    vl_error_set(err, "%s:%zu: the header lacks the %s column (J' and J'' go together)", lay->src,
                 line_no, fr[R_J1] < 0 ? "storage compliance J'" : "loss compliance J''");
    return VL_EINPUT;
  }
  int tan = fr[R_TAN] >= 0;
  int pair = (fr[R_STORAGE] >= 0 && (fr[R_LOSS] >= 0 || tan)) ||
             (tan && (fr[R_LOSS] >= 0 || fr[R_ABS] >= 0));
  if (!compl &&!pair) {
    vl_error_set(err,
                 "%s:%zu: the header lacks the %s column (need E' with E'' or tan delta, |E*| or "
                 "E'' with tan delta, or J' with J''; G for shear moduli)%s%s",
                 lay->src, line_no,
                 fr[R_STORAGE] < 0 && !tan ? "storage modulus E' (E_stor, G')"
                 : !tan                    ? "loss modulus E'' (E_loss, G'') or tan delta"
                                           : "storage modulus E' (E_stor, G')",
                 ign, lay->ignored);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* The line after the header (p, n; line line_no) is the units row when one
 * of its cells is not a number but spells its column's unit (the CSV reader
 * applies the same rule); then every cell of a known column must, and the
 * fields get their row_unit. Otherwise it is data and lay is left as it
 * is. */
static vl_status scan_units_row(layout *lay, vl_span line, size_t line_no, vl_error *err) {
  vl_span cells[MAX_FIELDS + 1];
  size_t count = vl_import_split(line, lay->dialect.delimiter, cells, MAX_FIELDS + 1);
  if (count != lay->n_fields) return VL_OK;
  char u[MAX_FIELDS][CELL_MAX];
  int is_units = 0;
  for (size_t k = 0; k < count; k++) {
    if (!cell_text(cells[k], u[k], CELL_MAX)) u[k][0] = '\x01', u[k][1] = '\0';
    if (lay->fields[k].r == R_COUNT) continue;
    unit_family fam = roles[lay->fields[k].r].family;
    if (!is_number(lay, u[k]) && find_unit(fam, u[k])) is_units = 1;
  }
  if (!is_units) return VL_OK;
  lay->units_line = line_no;
  for (size_t k = 0; k < count; k++) {
    field *f = &lay->fields[k];
    if (f->r == R_COUNT) continue;
    unit_family fam = roles[f->r].family;
    if (!find_unit(fam, u[k])) {
      char list[128];
      family_list(fam, ", ", list, sizeof list);
      vl_error_set(err,
                   "%s:%zu: column '%s' (field %zu): '%.40s' is not a unit of %s "
                   "(expected %s%s)",
                   lay->src, line_no, f->text, k + 1, u[k][0] == '\x01' ? "?" : u[k],
                   roles[f->r].what, fam == U_NONE ? "'-', '1' or nothing" : "one of ",
                   fam == U_NONE ? "" : list);
      return VL_EINPUT;
    }
    /* a unit find_unit knows always fits; checked, not assumed */
    int w = snprintf(f->row_unit, sizeof f->row_unit, "%s", u[k]);
    if (w < 0 || (size_t)w >= sizeof f->row_unit) {
      vl_error_set(err, "%s:%zu: column '%s' (field %zu): unit '%.40s' is too long", lay->src,
                   line_no, f->text, k + 1, u[k]);
      return VL_EINPUT;
    }
    f->has_row_unit = 1;
  }
  return VL_OK;
}

/* Reads the header and the optional units row; fills lay. */
static vl_status scan_header(const char *text, size_t len, layout *lay, const vl_dma_options *o,
                             vl_error *err) {
  size_t pos = 0, line_no = 0;
  vl_span line, cells[MAX_FIELDS + 1];
  for (int r = 0; r < R_COUNT; r++)
    lay->col_of_role[r] = lay->field_of_role[r] = -1;
  if (!vl_import_next_line(text, len, &pos, &line_no, &line)) {
    vl_error_set(err,
                 "%s:%zu: empty file (expected a header such as 'f,E_stor,E_loss,T' and data "
                 "rows)",
                 lay->src, line_no ? line_no : 1);
    return VL_EINPUT;
  }
  lay->header_line = line_no;
  size_t count = vl_import_split(line, lay->dialect.delimiter, cells, MAX_FIELDS + 1);
  if (count > MAX_FIELDS) {
    vl_error_set(err, "%s:%zu: the header has %zu columns; a DMA file has at most %d", lay->src,
                 line_no, count, MAX_FIELDS);
    return VL_EINPUT;
  }
  int all_numbers = 1;
  for (size_t k = 0; k < count; k++) {
    field *f = &lay->fields[k];
    memset(f, 0, sizeof *f);
    if (!cell_text(cells[k], f->text, sizeof f->text)) {
      vl_error_set(err, "%s:%zu: header field %zu is too long to be a column name", lay->src,
                   line_no, k + 1);
      return VL_EINPUT;
    }
    if (!is_number(lay, f->text)) all_numbers = 0;
  }
  if (all_numbers) {
    vl_error_set(err,
                 "%s:%zu: missing header: expected column names such as 'f,E_stor,E_loss,T' "
                 "before the numbers",
                 lay->src, line_no);
    return VL_EINPUT;
  }
  vl_status st = header_roles(lay, count, line_no, err);
  if (st == VL_OK) st = check_roles(lay, line_no, err);
  if (st == VL_OK) st = modulus_kind_of(lay, o, line_no, err);
  if (st == VL_OK && vl_import_next_line(text, len, &pos, &line_no, &line))
    st = scan_units_row(lay, line, line_no, err);
  return st;
}

/* Settles the unit of every column from the header, the units row and the
 * options, which must agree. */
static vl_status resolve_units(layout *lay, const vl_dma_options *o, vl_error *err) {
  const unit_def *family_seen[U_NONE + 1] = {0};
  int family_field[U_NONE + 1] = {0};
  for (size_t k = 0; k < lay->n_fields; k++) {
    field *f = &lay->fields[k];
    if (f->r == R_COUNT) continue;
    unit_family fam = roles[f->r].family;
    const unit_def *from_header = NULL, *from_row = NULL, *from_opt = NULL;
    const char *opt_name = NULL, *opt_text = NULL;
    char list[128], inv[32];
    family_list(fam, ", ", list, sizeof list);
    if (f->has_inline_unit && !(from_header = find_unit(fam, f->inline_unit))) {
      vl_error_set(err,
                   "%s:%zu: header field %zu: '%.40s' in '%s' is not a unit of %s (expected %s%s)",
                   lay->src, lay->header_line, k + 1, f->inline_unit, f->text, roles[f->r].what,
                   fam == U_NONE ? "'-' or '1'" : "one of ", fam == U_NONE ? "" : list);
      return VL_EINPUT;
    }
    if (f->has_row_unit) from_row = find_unit(fam, f->row_unit);
    if (fam == U_FREQ) opt_name = "frequency unit", opt_text = o->freq_unit;
    if (fam == U_MODULUS) opt_name = "modulus unit", opt_text = o->modulus_unit;
    if (fam == U_TEMP) opt_name = "temperature unit", opt_text = o->temp_unit;
    if (fam == U_COMPLIANCE && o->modulus_unit) {
      opt_name = "modulus unit";
      snprintf(inv, sizeof inv, "1/%s", o->modulus_unit);
      opt_text = inv;
    }
    if (opt_text) {
      from_opt = find_unit(fam, opt_text);
      if (!from_opt && fam == U_COMPLIANCE) from_opt = find_unit(fam, o->modulus_unit);
      if (!from_opt) {
        vl_error_set(err, "the %s '%s' is not one of %s", opt_name, opt_text, list);
        return VL_EINPUT;
      }
    }
    /* the same physical unit may be spelt two ways (C, degC) */
    const unit_def *u = from_header ? from_header : from_row ? from_row : from_opt;
    const unit_def *pair[3] = {from_header, from_row, from_opt};
    const char *where[3] = {"the header", "the units row", "the options"};
    for (int a = 0; a < 3; a++) {
      for (int b = a + 1; b < 3; b++) {
        if (pair[a] && pair[b] &&
            (pair[a]->factor != pair[b]->factor || pair[a]->offset != pair[b]->offset)) {
          vl_error_set(err,
                       "%s:%zu: column '%s' (field %zu): mixed units: %s says %s but %s says %s",
                       lay->src, (a == 1 || b == 1) ? lay->units_line : lay->header_line, f->text,
                       k + 1, where[a], pair[a]->name, where[b], pair[b]->name);
          return VL_EINPUT;
        }
      }
    }
    if (!u && fam != U_NONE) {
      vl_error_set(err,
                   "%s:%zu: column '%s' (field %zu): no unit for the %s (give a units row with "
                   "one of %s after the header, write it as '%s [unit]', or give the %s option)",
                   lay->src, lay->header_line, f->text, k + 1, roles[f->r].what, list, f->text,
                   opt_name ? opt_name : "unit");
      return VL_EINPUT;
    }
    if (u && u->omega_only && !omega_name(f)) {
      vl_error_set(err,
                   "%s:%zu: column '%s' (field %zu): '%s' is ambiguous for a frequency (Hz or "
                   "rad/s?): write Hz or rad/s, or name the column omega",
                   lay->src, lay->header_line, f->text, k + 1, u->name);
      return VL_EINPUT;
    }
    if (!u) u = &none_units[0];
    if (fam == U_MODULUS || fam == U_COMPLIANCE) {
      if (family_seen[fam] && family_seen[fam]->factor != u->factor) {
        vl_error_set(err,
                     "%s:%zu: column '%s' (field %zu): mixed units: %s but '%s' (field %d) is in "
                     "%s; give both in the same unit",
                     lay->src, lay->units_line ? lay->units_line : lay->header_line, f->text, k + 1,
                     u->name, lay->fields[family_field[fam]].text, family_field[fam] + 1,
                     family_seen[fam]->name);
        return VL_EINPUT;
      }
      family_seen[fam] = u;
      family_field[fam] = (int)k;
    }
    lay->unit[f->r] = u;
  }
  return VL_OK;
}

typedef vl_dma_order order_key;

static int cmp_key(const void *pa, const void *pb) {
  const order_key *a = pa, *b = pb;
  if (a->iso != b->iso) return a->iso < b->iso ? -1 : 1;
  if (a->omega != b->omega) return a->omega < b->omega ? -1 : 1;
  return a->idx < b->idx ? -1 : a->idx > b->idx;
}

typedef struct {
  double mean;
  size_t id;
} group_key;

static int cmp_group(const void *pa, const void *pb) {
  const group_key *a = pa, *b = pb;
  if (a->mean != b->mean) return a->mean < b->mean ? -1 : 1;
  return a->id < b->id ? -1 : a->id > b->id;
}

static vl_status alloc_arrays(vl_measured *m, size_t n, int compliance) {
  m->line = calloc(n, sizeof *m->line);
  m->omega_rad_s = calloc(n, sizeof *m->omega_rad_s);
  m->temperature_c = calloc(n, sizeof *m->temperature_c);
  m->storage_pa = calloc(n, sizeof *m->storage_pa);
  m->loss_pa = calloc(n, sizeof *m->loss_pa);
  m->isotherm = calloc(n, sizeof *m->isotherm);
  m->reduced_omega_rad_s = calloc(n, sizeof *m->reduced_omega_rad_s);
  if (compliance) {
    m->j1_per_pa = calloc(n, sizeof *m->j1_per_pa);
    m->j2_per_pa = calloc(n, sizeof *m->j2_per_pa);
    if (!m->j1_per_pa || !m->j2_per_pa) return VL_ENOMEM;
  }
  if (!m->line || !m->omega_rad_s || !m->temperature_c || !m->storage_pa || !m->loss_pa ||
      !m->isotherm || !m->reduced_omega_rad_s)
    return VL_ENOMEM;
  return VL_OK;
}

/* The isotherms of group_isotherms as first found, before merging: by the
 * set column when there is one, else runs of consecutive points within
 * VL_DMA_ISOTHERM_TOL_K of the run's first temperature. Arrays of m->n. */
typedef struct {
  size_t n;            /* groups found */
  size_t *gid;         /* the group of each point */
  size_t *cnt, *first; /* points of each group; its first point */
  double *sum, *gset;  /* sum of its temperatures; its set value */
  double *tmin, *tmax; /* range of its temperatures */
} raw_groups;

static void raw_groups_free(raw_groups *rg) {
  free(rg->gid);
  free(rg->cnt);
  free(rg->first);
  free(rg->sum);
  free(rg->gset);
  free(rg->tmin);
  free(rg->tmax);
}

/* Finds the raw groups of m's points (rg allocated for m->n points). A set
 * spanning more than twice the tolerance is refused. */
static vl_status find_groups(const vl_measured *m, const double *set, const layout *lay,
                             raw_groups *rg, vl_error *err) {
  size_t ng = 0;
  for (size_t k = 0; k < m->n; k++) {
    double t = m->temperature_c[k];
    size_t g = ng;
    if (set) {
      for (size_t j = 0; j < ng; j++)
        if (rg->gset[j] == set[k]) g = j;
    } else if (ng > 0 && fabs(t - m->temperature_c[rg->first[ng - 1]]) <= VL_DMA_ISOTHERM_TOL_K) {
      g = ng - 1;
    }
    if (g == ng) {
      rg->gset[ng] = set ? set[k] : 0.0;
      rg->first[ng] = k;
      rg->sum[ng] = 0.0;
      rg->tmin[ng] = rg->tmax[ng] = t;
      ng++;
    }
    rg->gid[k] = g;
    rg->sum[g] += t;
    rg->cnt[g]++;
    rg->tmin[g] = fmin(rg->tmin[g], t);
    rg->tmax[g] = fmax(rg->tmax[g], t);
    if (set && rg->tmax[g] - rg->tmin[g] > 2.0 * VL_DMA_ISOTHERM_TOL_K) {
      vl_error_set(err,
                   "%s:%zu: column '%s' (field %d): set %g spans %.4g to %.4g C; an isotherm "
                   "must be measured at one temperature (within %g K)",
                   m->source, m->line[k], lay->fields[lay->field_of_role[R_TEMP]].text,
                   lay->field_of_role[R_TEMP] + 1, set[k], rg->tmin[g], rg->tmax[g],
                   2.0 * VL_DMA_ISOTHERM_TOL_K);
      rg->n = ng;
      return VL_EINPUT;
    }
  }
  rg->n = ng;
  return VL_OK;
}

/* Sorts the raw groups by mean temperature and merges neighbours within
 * the tolerance into the isotherms of m (isotherm, n_isotherms,
 * iso_temperature_c, iso_points; iso_log10_a_t allocated). VL_ENOMEM
 * without a message. */
static vl_status merge_groups(vl_measured *m, const raw_groups *rg) {
  size_t ng = rg->n;
  vl_status st = VL_OK;
  group_key *keys = malloc(ng * sizeof *keys);
  size_t *map = malloc(ng * sizeof *map);
  if (!keys || !map) {
    st = VL_ENOMEM;
    goto cleanup;
  }
  for (size_t g = 0; g < ng; g++)
    keys[g] = (group_key){rg->sum[g] / (double)rg->cnt[g], g};
  qsort(keys, ng, sizeof *keys, cmp_group);
  size_t out = 0;
  double msum = 0.0, mcnt = 0.0;
  for (size_t i = 0; i < ng; i++) {
    size_t g = keys[i].id;
    if (i > 0 && keys[i].mean - msum / mcnt <= VL_DMA_ISOTHERM_TOL_K) {
      map[g] = out - 1;
    } else {
      msum = mcnt = 0.0;
      map[g] = out++;
    }
    msum += rg->sum[g];
    mcnt += (double)rg->cnt[g];
  }
  m->n_isotherms = out;
  m->iso_temperature_c = calloc(out, sizeof *m->iso_temperature_c);
  m->iso_log10_a_t = calloc(out, sizeof *m->iso_log10_a_t);
  m->iso_points = calloc(out, sizeof *m->iso_points);
  if (!m->iso_temperature_c || !m->iso_log10_a_t || !m->iso_points) {
    st = VL_ENOMEM;
    goto cleanup;
  }
  for (size_t k = 0; k < m->n; k++) {
    size_t g = map[rg->gid[k]];
    m->isotherm[k] = g;
    m->iso_temperature_c[g] += m->temperature_c[k];
    m->iso_points[g]++;
  }
  for (size_t g = 0; g < out; g++)
    m->iso_temperature_c[g] /= (double)m->iso_points[g];

cleanup:
  free(keys);
  free(map);
  return st;
}

/* Groups the points into isotherms (see dma.h); fills m->isotherm,
 * n_isotherms, iso_temperature_c (increasing) and iso_points. */
static vl_status group_isotherms(vl_measured *m, const double *set, const layout *lay,
                                 vl_error *err) {
  size_t n = m->n;
  vl_status st = VL_OK;
  raw_groups rg = {0};
  rg.gid = malloc(n * sizeof *rg.gid);
  rg.sum = malloc(n * sizeof *rg.sum);
  rg.gset = malloc(n * sizeof *rg.gset);
  rg.tmin = malloc(n * sizeof *rg.tmin);
  rg.tmax = malloc(n * sizeof *rg.tmax);
  rg.cnt = calloc(n, sizeof *rg.cnt);
  rg.first = malloc(n * sizeof *rg.first);
  if (!rg.gid || !rg.sum || !rg.gset || !rg.tmin || !rg.tmax || !rg.cnt || !rg.first) {
    st = VL_ENOMEM;
    goto cleanup;
  }
  if ((st = find_groups(m, set, lay, &rg, err)) != VL_OK) goto cleanup;
  if ((st = merge_groups(m, &rg)) != VL_OK) goto cleanup;
  for (size_t k = 0; k < n && m->n_isotherms > 1; k++) {
    if (m->iso_points[m->isotherm[k]] < 2) {
      vl_error_set(err,
                   "%s:%zu: the isotherm at %.4g C has a single point: each temperature needs a "
                   "frequency sweep of several points",
                   m->source, m->line[k], m->iso_temperature_c[m->isotherm[k]]);
      st = VL_EINPUT;
      goto cleanup;
    }
  }

cleanup:
  if (st == VL_ENOMEM) vl_error_set(err, "%s: out of memory grouping isotherms", m->source);
  raw_groups_free(&rg);
  return st;
}

/* The field that gave E' (for messages): E', else J', |E*| or E''. */
static int storage_field(const layout *lay) {
  const role order[4] = {R_STORAGE, R_J1, R_ABS, R_LOSS};
  for (int i = 0; i < 4; i++)
    if (lay->field_of_role[order[i]] >= 0) return lay->field_of_role[order[i]];
  return 0;
}

/* E' must not fall with frequency within an isotherm (beyond scatter);
 * every point where it does is reported. */
static vl_status check_increasing(const vl_measured *m, const order_key *ord, const layout *lay,
                                  vl_error *err) {
  size_t best = 0;
  vl_problems pr;
  vl_problems_init(&pr);
  int fld = storage_field(lay), compl = m->kind == VL_DMA_COMPLIANCE;
  for (size_t i = 0; i < m->n; i++) {
    size_t k = ord[i].idx;
    if (i == 0 || ord[i].iso != ord[i - 1].iso) {
      best = k;
      continue;
    }
    if (m->storage_pa[k] < (1.0 - VL_DMA_DECREASE_TOL) * m->storage_pa[best]) {
      vl_problems_add(&pr, m->line[k],
                      "%s:%zu: column '%s' (field %d): the storage modulus%s decreases with "
                      "frequency (%.4g Pa at %.4g rad/s, %.0f %% below %.4g Pa at %.4g rad/s on "
                      "line %zu%s): a linear viscoelastic solid's E' never decreases with "
                      "frequency",
                      m->source, m->line[k], lay->fields[fld].text, fld + 1,
                      compl ? " E' = J'/(J'^2 + J''^2)" : "", m->storage_pa[k], m->omega_rad_s[k],
                      100.0 * (1.0 - m->storage_pa[k] / m->storage_pa[best]), m->storage_pa[best],
                      m->omega_rad_s[best], m->line[best],
                      m->has_temperature ? ", same isotherm" : "");
      continue;
    }
    if (m->storage_pa[k] > m->storage_pa[best]) best = k;
  }
  if (pr.total == 0) return VL_OK;
  vl_problems_finish(&pr, m->source, err);
  return VL_EINPUT;
}

/* superpose with nothing to shift: a master curve (no temperature column),
 * whose reference temperature must be given, or a single isotherm, which
 * must lie at tref_c (if given). */
static vl_status no_shift(vl_measured *m, double tref_c, vl_error *err) {
  const double tol = VL_DMA_ISOTHERM_TOL_K;
  double tmin = m->iso_temperature_c[0];
  if (!m->has_temperature) {
    if (isnan(tref_c)) {
      vl_error_set(err,
                   "%s: no temperature column, so this is a master curve: give its reference "
                   "temperature (--tref C)",
                   m->source);
      return VL_EINPUT;
    }
    m->tref_c = tref_c;
    return VL_OK;
  }
  if (isnan(tref_c)) {
    vl_error_set(err,
                 "%s: every row is at one temperature (%.4g C): give --tref %.4g to take this "
                 "isotherm as the master curve (one isotherm cannot be shifted)",
                 m->source, tmin, tmin);
    return VL_EINPUT;
  }
  if (fabs(tref_c - tmin) > tol) {
    vl_error_set(err,
                 "%s: a single isotherm at %.4g C cannot be shifted to %.4g C without WLF "
                 "constants: measure more temperatures or use --tref %.4g",
                 m->source, tmin, tref_c, tmin);
    return VL_EINPUT;
  }
  m->tref_c = tref_c;
  return VL_OK;
}

/* The reference temperature of two or more isotherms: *tref_c, or when it
 * is NAN the isotherm nearest room temperature, within the measured range;
 * *ref gets the isotherm nearest to it, which with only two isotherms (no
 * WLF fit to interpolate) must be at it. */
static vl_status reference_isotherm(const vl_measured *m, double *tref_c, size_t *ref,
                                    vl_error *err) {
  size_t ni = m->n_isotherms;
  const double tol = VL_DMA_ISOTHERM_TOL_K;
  double tmin = m->iso_temperature_c[0], tmax = m->iso_temperature_c[ni - 1];
  if (isnan(*tref_c)) { /* default: the isotherm nearest room temperature */
    *tref_c = m->iso_temperature_c[0];
    for (size_t g = 1; g < ni; g++)
      if (fabs(m->iso_temperature_c[g] - DEFAULT_TREF_C) < fabs(*tref_c - DEFAULT_TREF_C))
        *tref_c = m->iso_temperature_c[g];
  }
  if (*tref_c < tmin - tol || *tref_c > tmax + tol) {
    vl_error_set(err,
                 "%s: reference temperature %.4g C lies outside the measured %.4g to %.4g C: "
                 "the shifts cannot be extrapolated",
                 m->source, *tref_c, tmin, tmax);
    return VL_EINPUT;
  }
  *ref = 0;
  for (size_t g = 1; g < ni; g++)
    if (fabs(m->iso_temperature_c[g] - *tref_c) < fabs(m->iso_temperature_c[*ref] - *tref_c))
      *ref = g;
  if (ni == 2 && fabs(m->iso_temperature_c[*ref] - *tref_c) > tol) {
    vl_error_set(err,
                 "%s: with two isotherms (%.4g and %.4g C) there is no WLF fit to interpolate "
                 "the shift: use one of their temperatures as --tref",
                 m->source, tmin, tmax);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* Notes on the pairs that had to be bridged (tts.h): their shift rests on
 * the curves' trends, not on common points. */
static void bridge_notes(vl_measured *m, const vl_tts_pair_info *info) {
  for (size_t g = 0; g + 1 < m->n_isotherms; g++) {
    const vl_tts_pair_info *p = &info[g];
    if (p->no_join) {
      note(m,
           "warning: the isotherms at %.4g and %.4g C share too little of their windows to "
           "compare (%.2f decades) and do not join into one smooth curve either: their shift "
           "of %.2f decades is only a bound (is the material thermorheologically simple "
           "there?)",
           m->iso_temperature_c[g], m->iso_temperature_c[g + 1], p->overlap_decades,
           fabs(p->shift));
      m->n_warnings++;
    }
    if (!p->bridged) continue;
    m->n_extrapolated++;
    if (p->at_limit) {
      note(m,
           "warning: the isotherms at %.4g and %.4g C lie too far apart to join (their windows "
           "are at least %.2f decades apart after the %.2f-decade shift found): that shift is "
           "a lower bound and the master curve beyond it is unreliable; measure isotherms "
           "closer in temperature or over a wider frequency range",
           m->iso_temperature_c[g], m->iso_temperature_c[g + 1], -p->overlap_decades,
           fabs(p->shift));
      m->n_warnings++;
    } else {
      note(m,
           "the isotherms at %.4g and %.4g C %s %.2f decades after their shift of %.2f decades: "
           "too little to compare point by point, so the shift joins the two curves' trends "
           "(a cubic in log frequency across the junction%s)",
           m->iso_temperature_c[g], m->iso_temperature_c[g + 1],
           p->overlap_decades >= 0.0 ? "overlap by" : "leave a gap of", fabs(p->overlap_decades),
           fabs(p->shift), p->loss_used ? ", E' and E''" : ", E' alone");
    }
  }
}

/* lat[g] = log10 a_T of isotherm g relative to isotherm ref, by
 * vl_tts_chain_info over the points in the order ord (isotherm,
 * frequency). A warmer isotherm that shifts the wrong way is refused. */
static vl_status chain_shifts(vl_measured *m, const order_key *ord, size_t ref, double *lat,
                              vl_error *err) {
  size_t ni = m->n_isotherms;
  vl_status st = VL_OK;
  vl_tts_isotherm *iso = calloc(ni, sizeof *iso);
  vl_tts_pair_info *info = calloc(ni, sizeof *info);
  double *lw = malloc(m->n * sizeof *lw), *l1 = malloc(m->n * sizeof *l1);
  double *l2 = malloc(m->n * sizeof *l2);
  if (!iso || !info || !lw || !l1 || !l2) {
    vl_error_set(err, "%s: out of memory shifting isotherms", m->source);
    st = VL_ENOMEM;
    goto cleanup;
  }
  for (size_t i = 0; i < m->n; i++) {
    size_t k = ord[i].idx;
    lw[i] = log10(m->omega_rad_s[k]);
    l1[i] = log10(m->storage_pa[k]);
    l2[i] = log10(m->loss_pa[k]);
  }
  for (size_t i = 0, g = 0; g < ni; g++) {
    iso[g] = (vl_tts_isotherm){m->iso_temperature_c[g], m->iso_points[g], lw + i, l1 + i, l2 + i};
    i += m->iso_points[g];
  }
  if ((st = vl_tts_chain_info(ni, iso, ref, lat, info, err)) != VL_OK) {
    vl_error_prefix(err, "%s", m->source);
    goto cleanup;
  }
  for (size_t g = 0; g + 1 < ni; g++) {
    if (lat[g + 1] - lat[g] > WRONG_WAY_TOL) {
      vl_error_set(err,
                   "%s: the isotherm at %.4g C superposes %.2f decades above the colder one at "
                   "%.4g C: warmer must mean softer (is the temperature column right, and the "
                   "material thermorheologically simple?)",
                   m->source, m->iso_temperature_c[g + 1], lat[g + 1] - lat[g],
                   m->iso_temperature_c[g]);
      st = VL_EINPUT;
      goto cleanup;
    }
  }
  bridge_notes(m, info);

cleanup:
  free(iso);
  free(info);
  free(lw);
  free(l1);
  free(l2);
  return st;
}

/* With three isotherms or more: fits WLF to the shifts lat about the
 * reference isotherm ref, re-refers it to tref_c into m->wlf_*, and makes
 * lat relative to tref_c. */
static vl_status wlf_refer(vl_measured *m, size_t ref, double tref_c, double *lat, vl_error *err) {
  size_t ni = m->n_isotherms;
  double tr = m->iso_temperature_c[ref];
  double c1, c2, rms;
  vl_status st = vl_wlf_fit(ni, m->iso_temperature_c, lat, tr, &c1, &c2, &rms, err);
  if (st != VL_OK) {
    vl_error_prefix(err, "%s", m->source);
    return st;
  }
  /* WLF about tr re-referred to tref exactly: with u = tref - tr,
   * C2' = C2 + u, C1' = C1 C2 / C2', and every shift loses a_T(tref). */
  double u = tref_c - tr, c2n = c2 + u;
  if (!(c2n > 0.0)) {
    vl_error_set(err, "%s: the WLF fit (C2 = %.4g K about %.4g C) does not reach %.4g C", m->source,
                 c2, tr, tref_c);
    return VL_EINPUT;
  }
  double at_tref = vl_wlf_log10_shift(c1, c2, tref_c, tr);
  for (size_t g = 0; g < ni; g++)
    lat[g] -= at_tref;
  m->wlf_c1 = c1 * c2 / c2n;
  m->wlf_c2_k = c2n;
  m->wlf_rms = rms;
  return VL_OK;
}

/* Shifts the isotherms to tref (see dma.h) and fills the reduced
 * frequencies. */
static vl_status superpose(vl_measured *m, const order_key *ord, double tref_c, vl_error *err) {
  if (!m->has_temperature || m->n_isotherms == 1) return no_shift(m, tref_c, err);
  size_t ni = m->n_isotherms, ref = 0;
  vl_status st = reference_isotherm(m, &tref_c, &ref, err);
  if (st != VL_OK) return st;
  double *lat = malloc(ni * sizeof *lat);
  if (!lat) {
    vl_error_set(err, "%s: out of memory shifting isotherms", m->source);
    return VL_ENOMEM;
  }
  if ((st = chain_shifts(m, ord, ref, lat, err)) != VL_OK) goto cleanup;
  m->wlf_c1 = m->wlf_c2_k = m->wlf_rms = NAN;
  if (ni >= 3 && (st = wlf_refer(m, ref, tref_c, lat, err)) != VL_OK) goto cleanup;
  for (size_t g = 0; g < ni; g++)
    m->iso_log10_a_t[g] = lat[g];
  for (size_t k = 0; k < m->n; k++)
    m->reduced_omega_rad_s[k] = m->omega_rad_s[k] * pow(10.0, lat[m->isotherm[k]]);
  m->tref_c = tref_c;

cleanup:
  free(lat);
  return st;
}

/* The column list for the CSV reader, one column per role present in role
 * order, named as in this file, with the unit its units row spelt (or the
 * units of its family: then the file has no units row and the spelling
 * never matters); unit_lists holds their text and lay->col_of_role gets
 * their indices. Returns their count. */
static size_t csv_columns(layout *lay, vl_csv_column *cols, char (*unit_lists)[160]) {
  size_t nc = 0;
  for (int r = 0; r < R_COUNT; r++) {
    int f = lay->field_of_role[r];
    if (f < 0) continue;
    if (lay->fields[f].has_row_unit)
      snprintf(unit_lists[r], sizeof unit_lists[r], "%s", lay->fields[f].row_unit);
    else
      family_list(roles[r].family, "|", unit_lists[r], sizeof unit_lists[r]);
    cols[nc] = (vl_csv_column){.name = lay->fields[f].text,
                               .units = unit_lists[r],
                               .sign = (r == R_TEMP || r == R_SET) ? VL_CSV_ANY : VL_CSV_POSITIVE};
    lay->col_of_role[r] = (int)nc++;
  }
  return nc;
}

/* Value of role r in row k of csv, in SI units (moduli as tensile: shear
 * ones times 2 (1 + nu)). */
static double si_value(const vl_csv *csv, size_t k, const layout *lay, role r) {
  double v = vl_csv_value(csv, k, (size_t)lay->col_of_role[r]) * lay->unit[r]->factor;
  if (roles[r].family == U_MODULUS && lay->shear) v *= lay->shear_factor;
  return v;
}

/* A redundant column (tan delta or |E*|) that disagrees with the pair the
 * moduli came from: one problem naming the line. */
static void check_redundant(const vl_measured *m, size_t k, const layout *lay, role r, double given,
                            double derived, vl_problems *pr) {
  if (fabs(given - derived) <= TAN_CONSISTENCY * derived) return;
  int f = lay->field_of_role[r];
  const char *what = r == R_TAN ? "tan delta" : r == R_ABS ? "|E*|" : "E''";
  const char *from = r == R_TAN   ? "E''/E'"
                     : r == R_ABS ? "sqrt(E'^2 + E''^2)"
                                  : "|E*| tan delta / sqrt(1 + tan delta^2)";
  vl_problems_add(pr, m->line[k],
                  "%s:%zu: column '%s' (field %d): %s %.6g differs from %s = %.6g by more than "
                  "%.0f %% (are the columns mixed up?)",
                  lay->src, m->line[k], lay->fields[f].text, f + 1, what, given, from, derived,
                  100.0 * TAN_CONSISTENCY);
}

/* E' and E'' (and J', J'' for compliances) of point k from row k of csv in
 * SI units: from J' and J'', or E' with E'' or tan delta, or |E*| or E''
 * with tan delta; a redundant column must agree (problems in pr). */
static void point_moduli(vl_measured *m, size_t k, const vl_csv *csv, const layout *lay,
                         vl_problems *pr) {
  const int *cr = lay->col_of_role;
  if (m->kind == VL_DMA_COMPLIANCE) {
    double j1 = vl_csv_value(csv, k, (size_t)cr[R_J1]) * lay->unit[R_J1]->factor;
    double j2 = vl_csv_value(csv, k, (size_t)cr[R_J2]) * lay->unit[R_J2]->factor;
    double mag2 = j1 * j1 + j2 * j2; /* E = 1/J with J = J' - i J'' */
    m->j1_per_pa[k] = j1;
    m->j2_per_pa[k] = j2;
    m->storage_pa[k] = j1 / mag2;
    m->loss_pa[k] = j2 / mag2;
    return;
  }
  double td = cr[R_TAN] >= 0 ? vl_csv_value(csv, k, (size_t)cr[R_TAN]) : NAN;
  double e1, e2;
  int from_abs = 0;
  if (cr[R_STORAGE] >= 0) {
    e1 = si_value(csv, k, lay, R_STORAGE);
    e2 = cr[R_LOSS] >= 0 ? si_value(csv, k, lay, R_LOSS) : td * e1;
    if (cr[R_LOSS] >= 0 && cr[R_TAN] >= 0) check_redundant(m, k, lay, R_TAN, td, e2 / e1, pr);
  } else if (cr[R_ABS] >= 0) { /* with tan delta: |E*| (cos d, sin d) */
    double a = si_value(csv, k, lay, R_ABS);
    e1 = a / sqrt(1.0 + td * td);
    e2 = e1 * td;
    from_abs = 1;
    if (cr[R_LOSS] >= 0) check_redundant(m, k, lay, R_LOSS, si_value(csv, k, lay, R_LOSS), e2, pr);
  } else { /* E'' with tan delta */
    e2 = si_value(csv, k, lay, R_LOSS);
    e1 = e2 / td;
  }
  if (cr[R_ABS] >= 0 && !from_abs)
    check_redundant(m, k, lay, R_ABS, si_value(csv, k, lay, R_ABS), hypot(e1, e2), pr);
  m->storage_pa[k] = e1;
  m->loss_pa[k] = e2;
}

/* A modulus of point k outside [lo, hi] Pa: one problem naming the likely
 * unit mistake ("MPa numbers under a Pa header?"). */
static void check_modulus(const vl_measured *m, size_t k, const layout *lay, const char *what,
                          double v, double lo, double hi, vl_problems *pr) {
  if (v >= lo && v <= hi) return;
  int f = m->kind == VL_DMA_COMPLIANCE ? lay->field_of_role[R_J1] : storage_field(lay);
  if (!strcmp(what, "E''") && lay->field_of_role[R_LOSS] >= 0) f = lay->field_of_role[R_LOSS];
  const unit_def *u = lay->unit[lay->fields[f].r];
  char hint[160] = "a unit mistake?";
  if (m->kind != VL_DMA_COMPLIANCE && v < lo && u->factor < 1e9)
    snprintf(hint, sizeof hint, "MPa or GPa numbers under the unit %s?", u->name);
  if (m->kind != VL_DMA_COMPLIANCE && v > hi && u->factor > 1.0)
    snprintf(hint, sizeof hint, "Pa numbers under the unit %s?", u->name);
  vl_problems_add(pr, m->line[k],
                  "%s:%zu: column '%s' (field %d): %s = %.4g Pa%s lies outside the %g to %g Pa "
                  "a rubber's can have: %s",
                  lay->src, m->line[k], lay->fields[f].text, f + 1, what, v,
                  lay->shear ? " (2 (1 + nu) times the shear modulus)" : "", lo, hi, hint);
}

/* Point k of m from row k of csv, in SI units: line, frequency, moduli,
 * temperature (tref_c, or 0 if NAN, without a temperature column) and set
 * value (when set is not NULL); implausible values go to pr. */
static void convert_point(vl_measured *m, size_t k, const vl_csv *csv, const layout *lay,
                          double tref_c, double *set, vl_problems *pr) {
  const int *cr = lay->col_of_role;
  size_t before = pr->total;
  m->line[k] = csv->lines[k];
  m->omega_rad_s[k] = vl_csv_value(csv, k, (size_t)cr[R_FREQ]) * lay->unit[R_FREQ]->factor;
  point_moduli(m, k, csv, lay, pr);
  if (!(isfinite(m->omega_rad_s[k]) && isfinite(m->storage_pa[k]) && isfinite(m->loss_pa[k]) &&
        m->storage_pa[k] > 0.0 && m->loss_pa[k] > 0.0 && m->omega_rad_s[k] > 0.0)) {
    vl_problems_add(pr, m->line[k], "%s:%zu: a value is out of range after conversion to SI units",
                    lay->src, m->line[k]);
    return;
  }
  if (pr->total == before) {
    check_modulus(m, k, lay, "E'", m->storage_pa[k], MODULUS_MIN_PA, MODULUS_MAX_PA, pr);
    if (pr->total == before)
      check_modulus(m, k, lay, "E''", m->loss_pa[k], LOSS_MIN_PA, MODULUS_MAX_PA, pr);
  }
  if (!m->has_temperature) {
    m->temperature_c[k] = isnan(tref_c) ? 0.0 : tref_c;
    return;
  }
  double raw = vl_csv_value(csv, k, (size_t)cr[R_TEMP]);
  double t = raw + lay->unit[R_TEMP]->offset;
  int tf = lay->field_of_role[R_TEMP], kelvin = lay->unit[R_TEMP]->offset != 0.0;
  if (!(t > -273.15)) {
    vl_problems_add(pr, m->line[k],
                    "%s:%zu: column '%s' (field %d): %.6g %s is not above "
                    "absolute zero%s",
                    lay->src, m->line[k], lay->fields[tf].text, tf + 1, raw,
                    lay->unit[R_TEMP]->name, kelvin ? " (Celsius numbers under a K unit?)" : "");
  } else if (t < TEMP_MIN_C || t > TEMP_MAX_C) {
    vl_problems_add(pr, m->line[k],
                    "%s:%zu: column '%s' (field %d): %.6g %s = %.4g C lies outside the %g to %g C "
                    "of a DMA measurement: %s",
                    lay->src, m->line[k], lay->fields[tf].text, tf + 1, raw,
                    lay->unit[R_TEMP]->name, t, TEMP_MIN_C, TEMP_MAX_C,
                    kelvin           ? "Celsius numbers under a K unit?"
                    : t > TEMP_MAX_C ? "kelvin numbers under a C unit (give K)?"
                                     : "a unit mistake?");
  }
  m->temperature_c[k] = t;
  if (set) set[k] = vl_csv_value(csv, k, (size_t)cr[R_SET]);
}

/* The one isotherm of a file without temperatures (a master curve). */
static vl_status one_isotherm(vl_measured *m, vl_error *err) {
  m->n_isotherms = 1;
  m->iso_temperature_c = calloc(1, sizeof *m->iso_temperature_c);
  m->iso_log10_a_t = calloc(1, sizeof *m->iso_log10_a_t);
  m->iso_points = calloc(1, sizeof *m->iso_points);
  if (!m->iso_temperature_c || !m->iso_log10_a_t || !m->iso_points) {
    vl_error_set(err, "%s: out of memory", m->source);
    return VL_ENOMEM;
  }
  m->iso_points[0] = m->n;
  m->iso_temperature_c[0] = m->temperature_c[0];
  return VL_OK;
}

/* The Prony fit of the master curve (the reduced frequencies) into
 * m->prony and m->fit. A curve of less than a decade, or with too few
 * points for the grid, is refused here with the file's own figures. */
static vl_status fit_master_curve(vl_measured *m, const vl_dma_options *o, vl_error *err) {
  double wmin = INFINITY, wmax = 0.0;
  for (size_t k = 0; k < m->n; k++) {
    wmin = fmin(wmin, m->reduced_omega_rad_s[k]);
    wmax = fmax(wmax, m->reduced_omega_rad_s[k]);
  }
  if (!(wmax >= 10.0 * wmin * (1.0 - 1e-12))) {
    vl_error_set(err,
                 "%s: the %s spans %.2f decades of frequency (%.4g to %.4g rad/s): a Prony fit "
                 "needs at least one decade",
                 m->source, m->n_isotherms > 1 ? "master curve" : "data", log10(wmax / wmin), wmin,
                 wmax);
    return VL_EINPUT;
  }
  double per_decade =
      o->terms_per_decade > 0.0 ? o->terms_per_decade : VL_PRONY_FIT_DEFAULT_PER_DECADE;
  size_t ng = vl_prony_fit_grid(wmin, wmax, per_decade, NULL, 0);
  if (ng > 0 && m->n < ng + 1) {
    vl_error_set(err,
                 "%s: %zu points cannot determine %zu Prony terms and Einf over %.2f decades at "
                 "%g terms per decade: give more points or fewer terms per decade",
                 m->source, m->n, ng, log10(wmax / wmin), per_decade);
    return VL_EINPUT;
  }
  vl_status st = vl_prony_fit(m->n, m->reduced_omega_rad_s, m->storage_pa, m->loss_pa,
                              o->terms_per_decade, o->weights, o->nu, &m->prony, &m->fit, err);
  if (st != VL_OK) vl_error_prefix(err, "%s", m->source);
  return st;
}

/* The notes of a successful read: the dialect, the ignored columns, the
 * shear conversion. */
static void read_notes(vl_measured *m, const layout *lay, const vl_dma_options *o) {
  m->delimiter = lay->dialect.delimiter;
  m->decimal_comma = lay->dialect.decimal_comma;
  m->n_ignored = lay->n_ignored;
  m->shear = lay->shear;
  if (lay->dialect.delimiter != ',' || lay->dialect.decimal_comma)
    note(m, "read as %s-separated%s", vl_dialect_delimiter_name(lay->dialect.delimiter),
         lay->dialect.decimal_comma ? " with decimal commas" : "");
  if (lay->n_ignored)
    note(m, "ignored %zu column%s not used for the fit: %s", lay->n_ignored,
         lay->n_ignored == 1 ? "" : "s", lay->ignored);
  if (lay->shear) {
    char cols[3 * (CELL_MAX + 4)] = "";
    const role mods[3] = {R_STORAGE, R_LOSS, R_ABS};
    for (int i = 0; i < 3; i++) {
      int f = lay->field_of_role[mods[i]];
      size_t len = strlen(cols);
      if (f >= 0)
        snprintf(cols + len, sizeof cols - len, "%s'%s'", len ? ", " : "", lay->fields[f].text);
    }
    note(m,
         "shear moduli (%s) converted to tensile ones: E = 2 (1 + nu) G = %.6g G with Poisson "
         "ratio nu = %.6g (the --nu given, else 0.5)",
         cols, lay->shear_factor, o->nu);
  } else if (lay->field_of_role[R_STORAGE] >= 0 &&
             lay->fields[lay->field_of_role[R_STORAGE]].k == K_GENERIC) {
    note(m,
         "'%s' read as the tensile storage modulus E' (if the data are shear moduli G', say "
         "so: they are converted with E = 2 (1 + nu) G)",
         lay->fields[lay->field_of_role[R_STORAGE]].text);
  }
}

/* Every temperature between KELVIN_LIKE_MIN_C and TEMP_MAX_C under a
 * Celsius unit from the file: room-temperature kelvin numbers under a C
 * header (293 K read as 293 C) fall there, and a rubber's DMA does not
 * (it degrades). Refused unless the options confirm Celsius. */
static vl_status kelvin_as_celsius(const vl_measured *m, const layout *lay, const vl_dma_options *o,
                                   vl_error *err) {
  if (!m->has_temperature || lay->unit[R_TEMP]->offset != 0.0 || o->temp_unit) return VL_OK;
  double tmin = INFINITY;
  size_t first = 0;
  for (size_t k = 0; k < m->n; k++)
    if (m->temperature_c[k] < tmin) tmin = m->temperature_c[k], first = k;
  if (!(tmin >= KELVIN_LIKE_MIN_C)) return VL_OK;
  int tf = lay->field_of_role[R_TEMP];
  vl_error_set(err,
               "%s:%zu: column '%s' (field %d): every temperature lies between %g and %g C "
               "(%.6g C here), where no rubber is measured: kelvin numbers under a C unit? Give "
               "the unit K, or confirm Celsius with the temperature unit option (--temp-unit C)",
               lay->src, m->line[first], lay->fields[tf].text, tf + 1, KELVIN_LIKE_MIN_C,
               TEMP_MAX_C, tmin);
  return VL_EINPUT;
}

/* Reads the numbers of text (dialect in lay) into m's points in SI units,
 * *set (the set column, or NULL) allocated for the caller. Every
 * implausible point is reported at once. */
static vl_status read_points(const char *text, size_t len, layout *lay, const vl_dma_options *o,
                             vl_measured *m, double **set, vl_error *err) {
  vl_csv csv;
  vl_csv_column cols[R_COUNT];
  char unit_lists[R_COUNT][160];
  vl_csv_options copt = {.ignore_unknown = 1,
                         .delimiter = lay->dialect.delimiter,
                         .decimal_comma = lay->dialect.decimal_comma};
  size_t nc = csv_columns(lay, cols, unit_lists);
  vl_status st = vl_csv_read_text_opts(text, len, lay->src, cols, nc, &copt, &csv, err);
  if (st != VL_OK) return st;
  const int *cr = lay->col_of_role;
  if (csv.n_rows > VL_DMA_MAX_POINTS) {
    vl_error_set(err, "%s:%zu: more than %d data points: thin the data first", lay->src,
                 csv.lines[VL_DMA_MAX_POINTS], VL_DMA_MAX_POINTS);
    st = VL_EINPUT;
    goto cleanup;
  }
  m->n = csv.n_rows;
  m->kind = cr[R_J1] >= 0                           ? VL_DMA_COMPLIANCE
            : cr[R_STORAGE] >= 0 && cr[R_LOSS] >= 0 ? VL_DMA_STORAGE_LOSS
                                                    : VL_DMA_STORAGE_TAN_DELTA;
  m->has_temperature = cr[R_TEMP] >= 0;
  if ((st = alloc_arrays(m, m->n, m->kind == VL_DMA_COMPLIANCE)) != VL_OK) {
    vl_error_set(err, "%s: out of memory", lay->src);
    goto cleanup;
  }
  if (cr[R_SET] >= 0 && cr[R_TEMP] >= 0 && !(*set = malloc(m->n * sizeof **set))) {
    vl_error_set(err, "%s: out of memory", lay->src);
    st = VL_ENOMEM;
    goto cleanup;
  }
  vl_problems pr;
  vl_problems_init(&pr);
  for (size_t k = 0; k < m->n; k++)
    convert_point(m, k, &csv, lay, o->tref_c, *set, &pr);
  if (pr.total > 0) {
    vl_problems_finish(&pr, lay->src, err);
    st = VL_EINPUT;
  } else {
    st = kelvin_as_celsius(m, lay, o, err);
  }

cleanup:
  vl_csv_free(&csv);
  return st;
}

/* The warnings of a finished import: large WLF residual, large fit error. */
static void fit_warnings(vl_measured *m) {
  if (m->n_isotherms >= 3 && m->wlf_rms > VL_DMA_WARN_WLF_RMS) {
    note(m,
         "warning: the WLF equation misses the shifts by %.2f decades rms (above %.2g): the "
         "isotherms do not follow one WLF law (not thermorheologically simple, or a shift is "
         "wrong); the master curve uses the shifts themselves",
         m->wlf_rms, VL_DMA_WARN_WLF_RMS);
    m->n_warnings++;
  }
  if (m->fit.rms_rel_storage > VL_DMA_WARN_FIT_RMS || m->fit.rms_rel_loss > VL_DMA_WARN_FIT_RMS) {
    note(m,
         "warning: the Prony series misses the master curve by %.1f %% rms in E' and %.1f %% "
         "in E'' (above %.0f %%): the data are represented only roughly (E'' inconsistent with "
         "E', isotherms that do not superpose, or outliers)",
         100.0 * m->fit.rms_rel_storage, 100.0 * m->fit.rms_rel_loss, 100.0 * VL_DMA_WARN_FIT_RMS);
    m->n_warnings++;
  }
}

vl_status vl_measured_read_text(const char *text, size_t len, const char *source,
                                const vl_dma_options *opts, vl_measured *out, vl_error *err) {
  vl_status st = VL_OK;
  vl_dma_options o = opts ? *opts : vl_dma_options_default();
  layout lay;
  order_key *ord = NULL;
  double *set = NULL;
  memset(out, 0, sizeof *out);
  memset(&lay, 0, sizeof lay);
  out->wlf_c1 = out->wlf_c2_k = out->wlf_rms = NAN;
  out->tref_c = NAN;
  out->source = strdup(source ? source : "<text>");
  if (!out->source) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  lay.src = out->source;
  if (!text && len > 0) {
    vl_error_set(err, "%s: no text", lay.src);
    st = VL_EINTERNAL;
    goto cleanup;
  }
  if (!text) text = "";
  if ((st = vl_import_refuse_spreadsheet(text, len, lay.src, err)) != VL_OK) goto cleanup;
  if ((st = vl_import_detect_dialect(text, len, lay.src, &lay.dialect, err)) != VL_OK) goto cleanup;
  if ((st = scan_header(text, len, &lay, &o, err)) != VL_OK) goto cleanup;
  if ((st = resolve_units(&lay, &o, err)) != VL_OK) goto cleanup;
  vl_measured *m = out;
  if ((st = read_points(text, len, &lay, &o, m, &set, err)) != VL_OK) goto cleanup;
  read_notes(m, &lay, &o);

  if (m->has_temperature)
    st = group_isotherms(m, set, &lay, err);
  else
    st = one_isotherm(m, err);
  if (st != VL_OK) goto cleanup;
  if (!(ord = malloc(m->n * sizeof *ord))) {
    vl_error_set(err, "%s: out of memory", lay.src);
    st = VL_ENOMEM;
    goto cleanup;
  }
  for (size_t k = 0; k < m->n; k++)
    ord[k] = (order_key){m->isotherm[k], m->omega_rad_s[k], k};
  qsort(ord, m->n, sizeof *ord, cmp_key);
  if ((st = check_increasing(m, ord, &lay, err)) != VL_OK) goto cleanup;
  for (size_t k = 0; k < m->n; k++)
    m->reduced_omega_rad_s[k] = m->omega_rad_s[k];
  if ((st = superpose(m, ord, o.tref_c, err)) != VL_OK) goto cleanup;
  if (!m->has_temperature) {
    m->iso_temperature_c[0] = m->tref_c;
  } else if (m->n_isotherms == 1) {
    m->iso_log10_a_t[0] = 0.0;
  }
  if ((st = fit_master_curve(m, &o, err)) != VL_OK) goto cleanup;
  fit_warnings(m);
  st = vl_dma_quality(m, ord, err);

cleanup:
  free(ord);
  free(set);
  if (st != VL_OK) {
    vl_measured_free(out);
    vl_import_sanitise(err);
  }
  return st;
}

vl_status vl_measured_read_file(const char *path, const vl_dma_options *opts, vl_measured *out,
                                vl_error *err) {
  char *buf = NULL;
  size_t len = 0;
  memset(out, 0, sizeof *out);
  vl_status st = vl_import_read_file(path, DMA_MAX_BYTES, "a DMA export", &buf, &len, err);
  if (st == VL_OK) st = vl_measured_read_text(buf, len, path, opts, out, err);
  free(buf);
  return st;
}
