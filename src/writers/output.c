/* Curve and field writers (output.h). */
#include "viscolube/output.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>

#include "output_internal.h"
#include "viscolube/atomic_file.h"

const char *const vl_curve_columns[] = {"v0_m_s",
                                        "v0_eta_pa_m",
                                        "deborah",
                                        "mu",
                                        "mu_Rc",
                                        "mu_Rf",
                                        "mu_Sc",
                                        "mu_Sf",
                                        "u_min_m",
                                        "u_central_m",
                                        "contact_width_m",
                                        "fluid_load_fraction",
                                        "u_min_over_h_rms",
                                        "regime",
                                        "E_wH_pa",
                                        "a_H_m",
                                        "Q",
                                        "x_centroid_m",
                                        "load_error",
                                        "converged",
                                        "iterations",
                                        "residual",
                                        "eps_f_min",
                                        "error_estimate",
                                        "accuracy",
                                        "warnings",
                                        NULL};

/* The columns a seal scene adds after these ([seal] stroke; FORMATS.md):
 * the point's stroke, its flux and friction force, and with stroke = both
 * the instroke's and the volumes per cycle. */
const char *const vl_seal_columns[] = {"stroke",
                                       "flux_m2_s",
                                       "friction_n_per_m",
                                       "converged_in",
                                       "mu_in",
                                       "mu_Sc_in",
                                       "mu_Sf_in",
                                       "u_min_in_m",
                                       "flux_in_m2_s",
                                       "friction_in_n_per_m",
                                       "volume_out_m3",
                                       "volume_back_m3",
                                       "tight",
                                       NULL};

/* The columns of a scene swept both ways ([sweep] direction = both). */
const char *const vl_down_columns[] = {
    "converged_down", "mu_down", "error_estimate_down", "u_min_down_m", "fluid_load_fraction_down",
    "two_states",     NULL};

double vl_down_column_value(const vl_point *p, size_t k) {
  const vl_down_result *d = &p->down;
  bool ok = d->swept && d->converged;
  double v[] = {d->swept ? (d->converged ? 1.0 : 0.0) : NAN,
                ok ? d->mu : NAN,
                ok ? d->error_estimate : NAN,
                ok ? d->u_min_m : NAN,
                ok ? d->fluid_load_fraction : NAN,
                d->swept ? (d->two_states ? 1.0 : 0.0) : NAN};
  return k < sizeof v / sizeof *v ? v[k] : NAN;
}
/* The columns a point contact adds after them ([contact] geometry = ball or
 * ellipsoid; vl_point.ball; FORMATS.md). */
const char *const vl_ball_columns[] = {
    "geometry",     "contact_area_m2", "contact_length_m", "contact_breadth_m", "x_min_film_m",
    "y_min_film_m", "y_peak_m",        "cells_in_contact", "cells_per_a0",      NULL};

static const char *stroke_name(int s) {
  return s == VL_STROKE_OUT ? "out" : s == VL_STROKE_IN ? "in" : s == VL_STROKE_BOTH ? "both" : "";
}

/* -0 (a sum of zeros with a minus sign, e.g. mu_Rf of a dry contact) is
 * written as 0: readers compare text, and "-0" looks like a sign. */
static double plain_zero(double v) { return v == 0.0 ? 0.0 : v; }

static void cell(FILE *f, double v, int ok) {
  if (ok && isfinite(v))
    fprintf(f, ",%.10g", plain_zero(v));
  else
    fputc(',', f);
}

/* The comment line that says which flow-factor model made the curve. */
static void print_model_comment(FILE *out, const vl_curve_meta *meta) {
  if (!meta->flow_factors) return;
  fprintf(out, "# flow_factors = %s", meta->flow_factors);
  if (meta->film_cutoff_m > 0.0) fprintf(out, ", film_cutoff_m = %.6g", meta->film_cutoff_m);
  fputc('\n', out);
}

/* The comment line that says which stored pair's law gave sigma_s. */
static void print_shear_comment(FILE *out, const vl_curve_meta *meta) {
  if (meta->shear_law) fprintf(out, "# sigma_s = %s\n", meta->shear_law);
}

double vl_seal_column_value(const vl_point *p, size_t k) {
  const vl_seal_result *s = &p->seal;
  bool ok = p->converged, both = s->stroke == VL_STROKE_BOTH, in = both && s->in_converged;
  double v[] = {NAN,
                ok ? p->flux_m2_s : NAN,
                ok ? s->friction_n_per_m : NAN,
                both ? (s->in_converged ? 1.0 : 0.0) : NAN,
                in ? s->in_mu : NAN,
                in ? s->in_mu_Sc : NAN,
                in ? s->in_mu_Sf : NAN,
                in ? s->in_u_min_m : NAN,
                in ? s->in_flux_m2_s : NAN,
                in ? s->in_friction_n_per_m : NAN,
                s->volume_out_m3,
                s->volume_back_m3,
                s->tight >= 0 ? (double)s->tight : NAN};
  return k < sizeof v / sizeof *v ? v[k] : NAN;
}

/* The seal columns of p (after its warnings). */
static void seal_cells(FILE *out, const vl_point *p) {
  const vl_seal_result *s = &p->seal;
  int ok = p->converged, both = s->stroke == VL_STROKE_BOTH, in = both && s->in_converged;
  fprintf(out, ",%s", stroke_name(s->stroke));
  cell(out, p->flux_m2_s, ok);
  cell(out, s->friction_n_per_m, ok);
  if (both)
    fprintf(out, ",%d", s->in_converged ? 1 : 0);
  else
    fputc(',', out);
  cell(out, s->in_mu, in);
  cell(out, s->in_mu_Sc, in);
  cell(out, s->in_mu_Sf, in);
  cell(out, s->in_u_min_m, in);
  cell(out, s->in_flux_m2_s, in);
  cell(out, s->in_friction_n_per_m, in);
  cell(out, s->volume_out_m3, 1);
  cell(out, s->volume_back_m3, 1);
  if (s->tight >= 0)
    fprintf(out, ",%d", s->tight);
  else
    fputc(',', out);
}

double vl_ball_column_value(const vl_point *p, size_t k) {
  const vl_ball_result *b = &p->ball;
  double v[] = {NAN,
                b->contact_area_m2,
                b->contact_length_m,
                b->contact_breadth_m,
                p->x_min_film_m,
                b->y_min_film_m,
                b->y_peak_m,
                (double)b->cells_in_contact,
                b->cells_per_a0};
  return p->converged && k < sizeof v / sizeof *v ? v[k] : NAN;
}

/* The point-contact columns of p (after its warnings). */
static void ball_cells(FILE *out, const vl_point *p) {
  const vl_ball_result *b = &p->ball;
  int ok = p->converged;
  fprintf(out, ",%s", vl_geometry_name(b->geometry));
  cell(out, b->contact_area_m2, ok);
  cell(out, b->contact_length_m, ok);
  cell(out, b->contact_breadth_m, ok);
  cell(out, p->x_min_film_m, ok);
  cell(out, b->y_min_film_m, ok);
  cell(out, b->y_peak_m, ok);
  cell(out, (double)b->cells_in_contact, ok);
  cell(out, b->cells_per_a0, ok);
}

void vl_print_curve_csv(FILE *out, size_t n, const vl_point *pts, const vl_curve_meta *meta) {
  print_model_comment(out, meta);
  print_shear_comment(out, meta);
  bool seal = n > 0 && pts[0].seal.stroke != VL_STROKE_NONE;
  bool down = n > 0 && pts[0].down.swept;
  bool ball = n > 0 && pts[0].ball.geometry != VL_GEOMETRY_CYLINDER;
  if (n > 0 && pts[0].rolling_na)
    fputs("# mu_Rc, mu_Rf: not applicable (moving = counterface: the rubber at rest, the flat "
          "counter-surface has no slope): empty; mu = mu_Sc + mu_Sf\n",
          out);
  for (size_t c = 0; vl_curve_columns[c]; c++)
    fprintf(out, "%s%s", c ? "," : "", vl_curve_columns[c]);
  for (size_t c = 0; seal && vl_seal_columns[c]; c++)
    fprintf(out, ",%s", vl_seal_columns[c]);
  for (size_t c = 0; down && vl_down_columns[c]; c++)
    fprintf(out, ",%s", vl_down_columns[c]);
  for (size_t c = 0; ball && vl_ball_columns[c]; c++)
    fprintf(out, ",%s", vl_ball_columns[c]);
  fputc('\n', out);
  for (size_t i = 0; i < n; i++) {
    const vl_point *p = &pts[i];
    int ok = p->converged;
    fprintf(out, "%.10g", plain_zero(p->v0_m_s));
    cell(out, p->v0_m_s * meta->eta_pa_s, meta->eta_pa_s > 0);
    cell(out, p->v0_m_s * meta->tau_s / meta->a0_m, meta->tau_s > 0 && meta->a0_m > 0);
    cell(out, p->mu, ok);
    /* not applicable (a moving counter-surface): empty, not a computed 0 */
    cell(out, p->mu_Rc, ok && !p->rolling_na);
    cell(out, p->mu_Rf, ok && !p->rolling_na);
    cell(out, p->mu_Sc, ok);
    cell(out, p->mu_Sf, ok);
    cell(out, p->u_min_m, ok);
    cell(out, p->u_central_m, ok);
    cell(out, p->contact_width_m, ok);
    cell(out, p->fluid_load_fraction, ok);
    cell(out, p->u_min_over_h_rms, ok); /* empty on smooth surfaces */
    fprintf(out, ",%s", ok ? vl_regime_name(p->regime) : "");
    /* derived from the solved state: a failed point has none (its struct
     * holds zeros, which read as values) */
    cell(out, p->E_wH_pa, ok);
    cell(out, p->a_H_m, ok);
    cell(out, p->Q, ok);
    cell(out, p->x_centroid_m, ok);
    cell(out, p->load_error, ok);
    fprintf(out, ",%d,%ld", p->converged ? 1 : 0, p->iterations);
    cell(out, p->residual, 1);
    cell(out, p->eps_f_min, ok); /* viscous flattening: 1 when off */
    /* empty when no estimate could be made (the coarse solve failed) */
    cell(out, p->error_estimate, ok);
    fprintf(out, ",%s", ok ? vl_accuracy_name(p->accuracy) : "");
    /* warnings never contain commas or quotes (contact.c writes them) */
    fprintf(out, ",%s", p->warnings);
    if (seal) seal_cells(out, p);
    for (size_t c = 0; down && vl_down_columns[c]; c++) {
      double v = vl_down_column_value(p, c);
      bool flag = c == 0 || !vl_down_columns[c + 1]; /* converged_down, two_states */
      if (flag && isfinite(v))
        fprintf(out, ",%d", (int)v);
      else
        cell(out, v, 1);
    }
    if (ball) ball_cells(out, p);
    fputc('\n', out);
  }
}

vl_status vl_write_curve_csv(const char *path, size_t n, const vl_point *pts,
                             const vl_curve_meta *meta, vl_error *err) {
  vl_atomic_file af;
  if (vl_atomic_file_open(&af, path, err) != VL_OK) return VL_EIO;
  vl_print_curve_csv(af.f, n, pts, meta);
  return vl_atomic_file_commit(&af, err);
}

vl_status vl_write_fields2d_csv(const char *path, size_t n, const double *x_m, const double *y_m,
                                const double *p_c_pa, const double *u_m, const double *p_f_pa,
                                double a0_m, vl_error *err) {
  vl_atomic_file af;
  if (vl_atomic_file_open(&af, path, err) != VL_OK) return VL_EIO;
  FILE *f = af.f;
  fputs(p_f_pa ? "x_m,y_m,x_over_a0,y_over_a0,p_c_pa,u_m,p_f_pa\n"
               : "x_m,y_m,x_over_a0,y_over_a0,p_c_pa,u_m\n",
        f);
  for (size_t i = 0; i < n; i++) {
    fprintf(f, "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g", plain_zero(x_m[i]), plain_zero(y_m[i]),
            plain_zero(x_m[i] / a0_m), plain_zero(y_m[i] / a0_m), plain_zero(p_c_pa[i]),
            plain_zero(u_m[i]));
    if (p_f_pa) fprintf(f, ",%.10g", plain_zero(p_f_pa[i]));
    fputc('\n', f);
  }
  return vl_atomic_file_commit(&af, err);
}

vl_status vl_write_fields_csv(const char *path, const vl_fields *fl, double a0_m, vl_error *err) {
  vl_atomic_file af;
  if (vl_atomic_file_open(&af, path, err) != VL_OK) return VL_EIO;
  FILE *f = af.f;
  fputs("x_m,x_over_a0,p_f_pa,p_c_pa,u_m,area_ratio,film_fraction", f);
  fputs(fl->width_m ? ",cell_width_m\n" : "\n", f);
  for (size_t i = 0; i < fl->n; i++) {
    fprintf(f, "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g", plain_zero(fl->x_m[i]),
            plain_zero(fl->x_m[i] / a0_m), plain_zero(fl->p_f_pa[i]), plain_zero(fl->p_c_pa[i]),
            plain_zero(fl->u_m[i]), plain_zero(fl->area_ratio[i]),
            fl->film_fraction ? plain_zero(fl->film_fraction[i]) : 1.0);
    if (fl->width_m) fprintf(f, ",%.10g", fl->width_m[i]);
    fputc('\n', f);
  }
  return vl_atomic_file_commit(&af, err);
}

/* A number of the point, null where its CSV cell is empty (not defined,
 * or the point did not converge). */
static void member(vl_json *w, const char *key, double v, int ok) {
  vl_json_key(w, key);
  if (ok) /* 17 digits: the double itself, so JSON readers get what the solver gave */
    vl_json_number_digits(w, v, 17);
  else
    vl_json_null(w);
}

void vl_point_json_members(vl_json *w, const vl_point *p, const vl_curve_meta *meta) {
  int ok = p->converged;
  member(w, "v0_m_s", p->v0_m_s, 1);
  member(w, "v0_eta_pa_m", p->v0_m_s * meta->eta_pa_s, meta->eta_pa_s > 0);
  member(w, "deborah", meta->a0_m > 0 ? p->v0_m_s * meta->tau_s / meta->a0_m : 0,
         meta->tau_s > 0 && meta->a0_m > 0);
  member(w, "mu", p->mu, ok);
  member(w, "mu_Rc", p->mu_Rc, ok && !p->rolling_na);
  member(w, "mu_Rf", p->mu_Rf, ok && !p->rolling_na);
  member(w, "mu_Sc", p->mu_Sc, ok);
  member(w, "mu_Sf", p->mu_Sf, ok);
  member(w, "u_min_m", p->u_min_m, ok);
  member(w, "u_central_m", p->u_central_m, ok);
  member(w, "contact_width_m", p->contact_width_m, ok);
  member(w, "fluid_load_fraction", p->fluid_load_fraction, ok);
  member(w, "u_min_over_h_rms", p->u_min_over_h_rms,
         ok && !isnan(p->u_min_over_h_rms)); /* null: smooth */
  vl_json_key_string(w, "regime", ok ? vl_regime_name(p->regime) : NULL);
  member(w, "E_wH_pa", p->E_wH_pa, ok);
  member(w, "a_H_m", p->a_H_m, ok);
  member(w, "Q", p->Q, ok);
  member(w, "x_centroid_m", p->x_centroid_m, ok);
  member(w, "load_error", p->load_error, ok);
  vl_json_key(w, "converged");
  vl_json_bool(w, ok);
  vl_json_key_integer(w, "iterations", p->iterations);
  member(w, "residual", p->residual, 1);
  member(w, "eps_f_min", p->eps_f_min, ok);
  member(w, "error_estimate", p->error_estimate, ok && isfinite(p->error_estimate));
  vl_json_key_string(w, "accuracy", ok && p->accuracy ? vl_accuracy_name(p->accuracy) : NULL);
  vl_json_key_string(w, "warnings", p->warnings);
  const vl_ball_result *b = &p->ball;
  if (b->geometry != VL_GEOMETRY_CYLINDER) {
    vl_json_key_string(w, "geometry", vl_geometry_name(b->geometry));
    member(w, "contact_area_m2", b->contact_area_m2, ok);
    member(w, "contact_length_m", b->contact_length_m, ok);
    member(w, "contact_breadth_m", b->contact_breadth_m, ok);
    member(w, "x_min_film_m", p->x_min_film_m, ok);
    member(w, "y_min_film_m", b->y_min_film_m, ok);
    member(w, "y_peak_m", b->y_peak_m, ok);
    member(w, "cells_in_contact", (double)b->cells_in_contact, ok);
    member(w, "cells_per_a0", b->cells_per_a0, ok);
  }
  const vl_seal_result *s = &p->seal;
  if (s->stroke != VL_STROKE_NONE) {
    int both = s->stroke == VL_STROKE_BOTH, in = both && s->in_converged;
    vl_json_key_string(w, "stroke", stroke_name(s->stroke));
    member(w, "flux_m2_s", p->flux_m2_s, ok);
    member(w, "friction_n_per_m", s->friction_n_per_m, ok);
    if (both) {
      vl_json_key(w, "converged_in");
      vl_json_bool(w, s->in_converged);
      member(w, "mu_in", s->in_mu, in);
      member(w, "mu_Sc_in", s->in_mu_Sc, in);
      member(w, "mu_Sf_in", s->in_mu_Sf, in);
      member(w, "u_min_in_m", s->in_u_min_m, in);
      member(w, "flux_in_m2_s", s->in_flux_m2_s, in);
      member(w, "friction_in_n_per_m", s->in_friction_n_per_m, in);
      member(w, "volume_out_m3", s->volume_out_m3, isfinite(s->volume_out_m3));
      member(w, "volume_back_m3", s->volume_back_m3, isfinite(s->volume_back_m3));
      vl_json_key(w, "tight");
      if (s->tight >= 0)
        vl_json_bool(w, s->tight);
      else
        vl_json_null(w);
    }
  }
  const vl_down_result *d = &p->down;
  if (d->swept) {
    vl_json_key(w, "converged_down");
    vl_json_bool(w, d->converged);
    for (size_t c = 1; vl_down_columns[c + 1]; c++)
      member(w, vl_down_columns[c], vl_down_column_value(p, c),
             isfinite(vl_down_column_value(p, c)));
    vl_json_key(w, "two_states");
    vl_json_bool(w, d->two_states);
  }
  if (meta->flow_factors) {
    vl_json_key_string(w, "flow_factors", meta->flow_factors);
    if (meta->film_cutoff_m > 0.0) member(w, "film_cutoff_m", meta->film_cutoff_m, 1);
  }
  if (meta->shear_law) vl_json_key_string(w, "sigma_s_law", meta->shear_law);
}

void vl_point_json(vl_json *w, const vl_point *p, const vl_curve_meta *meta) {
  vl_json_object_begin(w, VL_JSON_INLINE);
  vl_point_json_members(w, p, meta);
  vl_json_end(w);
}

void vl_curve_json(vl_json *w, size_t n, const vl_point *pts, const vl_curve_meta *meta) {
  vl_json_array_begin(w, VL_JSON_ROWS);
  for (size_t i = 0; i < n; i++)
    vl_point_json(w, &pts[i], meta);
  vl_json_end(w);
}
