/* A seal's table (output.h): both strokes at each speed, as seal.csv, as
 * JSON, and column by column for the Python package. */
#include "viscolube/output.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>

#include "viscolube/atomic_file.h"

const char *const vl_seal_table_columns[] = {"v0_m_s",
                                             "friction_out_n_per_m",
                                             "friction_in_n_per_m",
                                             "mu_out",
                                             "mu_in",
                                             "u_min_out_m",
                                             "u_min_in_m",
                                             "u_central_out_m",
                                             "u_central_in_m",
                                             "flux_out_m2_s",
                                             "flux_in_m2_s",
                                             "error_out",
                                             "error_in",
                                             "flux_error_out",
                                             "flux_error_in",
                                             "volume_out_m3",
                                             "volume_back_m3",
                                             "tight",
                                             "converged_out",
                                             "converged_in",
                                             "accuracy_out",
                                             "accuracy_in",
                                             "warnings_out",
                                             "warnings_in",
                                             NULL};

/* The first text column (accuracy_out): the columns before it are numbers. */
#define FIRST_TEXT 20

/* A stroke's values at one speed, from the point (outstroke) or its seal
 * result (instroke). */
typedef struct {
  bool converged;
  double friction, mu, u_min, u_central, flux, error, flux_error;
  int accuracy;
  const char *warnings;
} stroke_values;

static stroke_values stroke_of(const vl_point *p, bool in) {
  const vl_seal_result *s = &p->seal;
  if (!in)
    return (stroke_values){p->converged,      s->friction_n_per_m,    p->mu,
                           p->u_min_m,        p->u_central_m,         p->flux_m2_s,
                           p->error_estimate, p->flux_error_estimate, p->accuracy,
                           p->warnings};
  return (stroke_values){s->in_converged,      s->in_friction_n_per_m,    s->in_mu,
                         s->in_u_min_m,        s->in_u_central_m,         s->in_flux_m2_s,
                         s->in_error_estimate, s->in_flux_error_estimate, s->in_accuracy,
                         s->in_warnings};
}

double vl_seal_table_value(const vl_point *p, size_t k) {
  if (k == 0) return p->v0_m_s;
  const vl_seal_result *s = &p->seal;
  if (k >= 15 && k <= 17)
    return k == 15         ? s->volume_out_m3
           : k == 16       ? s->volume_back_m3
           : s->tight >= 0 ? (double)s->tight
                           : NAN;
  if (k == 18 || k == 19) return stroke_of(p, k == 19).converged ? 1.0 : 0.0;
  if (k >= FIRST_TEXT || k == 0) return NAN;
  stroke_values v = stroke_of(p, k % 2 == 0);
  if (!v.converged) return NAN;
  switch ((k - 1) / 2) {
  case 0: return v.friction;
  case 1: return v.mu;
  case 2: return v.u_min;
  case 3: return v.u_central;
  case 4: return v.flux;
  case 5: return v.error;
  default: return v.flux_error;
  }
}

const char *vl_seal_table_text(const vl_point *p, size_t k) {
  if (k < FIRST_TEXT || k > FIRST_TEXT + 3) return NULL;
  stroke_values v = stroke_of(p, (k - FIRST_TEXT) % 2 == 1);
  if (k < FIRST_TEXT + 2) return v.converged ? vl_accuracy_name(v.accuracy) : "";
  return v.warnings;
}

/* The table as CSV: a '#' line saying what it holds, the header, a row a
 * speed. */
static void print_seal_csv(FILE *out, size_t n, const vl_point *pts) {
  fputs("# a seal's strokes at each speed: out (the rod leaving the oil side) and in;"
        " flux per unit circumference, volumes per cycle (docs/FORMATS.md)\n",
        out);
  for (size_t c = 0; vl_seal_table_columns[c]; c++)
    fprintf(out, "%s%s", c ? "," : "", vl_seal_table_columns[c]);
  fputc('\n', out);
  for (size_t i = 0; i < n; i++) {
    for (size_t c = 0; vl_seal_table_columns[c]; c++) {
      const char *t = vl_seal_table_text(&pts[i], c);
      double v = t ? NAN : vl_seal_table_value(&pts[i], c);
      if (c) fputc(',', out);
      /* warnings never contain commas or quotes (the solver writes them) */
      if (t)
        fputs(t, out);
      else if (isfinite(v))
        fprintf(out, "%.10g", v == 0.0 ? 0.0 : v);
    }
    fputc('\n', out);
  }
}

vl_status vl_write_seal_csv(const char *path, size_t n, const vl_point *pts, vl_error *err) {
  vl_atomic_file af;
  if (vl_atomic_file_open(&af, path, err) != VL_OK) return VL_EIO;
  print_seal_csv(af.f, n, pts);
  return vl_atomic_file_commit(&af, err);
}

/* A number, null where the CSV cell is empty. */
static void number(vl_json *w, const char *key, double v) {
  vl_json_key(w, key);
  if (isfinite(v))
    vl_json_number_digits(w, v, 17);
  else
    vl_json_null(w);
}

/* One stroke's object. */
static void stroke_json(vl_json *w, const vl_point *p, bool in) {
  stroke_values v = stroke_of(p, in);
  double nan = NAN;
  vl_json_object_begin(w, VL_JSON_INLINE);
  vl_json_key(w, "converged");
  vl_json_bool(w, v.converged);
  number(w, "friction_n_per_m", v.converged ? v.friction : nan);
  number(w, "mu", v.converged ? v.mu : nan);
  number(w, "u_min_m", v.converged ? v.u_min : nan);
  number(w, "u_central_m", v.converged ? v.u_central : nan);
  number(w, "flux_m2_s", v.converged ? v.flux : nan);
  number(w, "error_estimate", v.converged ? v.error : nan);
  number(w, "flux_error_estimate", v.converged ? v.flux_error : nan);
  vl_json_key_string(w, "accuracy", v.converged ? vl_accuracy_name(v.accuracy) : NULL);
  vl_json_key_string(w, "warnings", v.warnings);
  vl_json_end(w);
}

void vl_seal_json(vl_json *w, size_t n, const vl_point *pts) {
  vl_json_array_begin(w, VL_JSON_ROWS);
  for (size_t i = 0; i < n; i++) {
    const vl_point *p = &pts[i];
    vl_json_object_begin(w, VL_JSON_INLINE);
    number(w, "v0_m_s", p->v0_m_s);
    vl_json_key(w, "out");
    stroke_json(w, p, false);
    vl_json_key(w, "in");
    stroke_json(w, p, true);
    number(w, "volume_out_m3", p->seal.volume_out_m3);
    number(w, "volume_back_m3", p->seal.volume_back_m3);
    vl_json_key(w, "tight");
    if (p->seal.tight >= 0)
      vl_json_bool(w, p->seal.tight);
    else
      vl_json_null(w);
    vl_json_end(w);
  }
  vl_json_end(w);
}

vl_status vl_write_seal_json(const char *path, size_t n, const vl_point *pts, vl_error *err) {
  vl_atomic_file af;
  if (vl_atomic_file_open(&af, path, err) != VL_OK) return VL_EIO;
  vl_json w;
  vl_json_init(&w, af.f, 10);
  vl_seal_json(&w, n, pts);
  return vl_atomic_file_commit(&af, err);
}
