/* Curve and field writers (output.h). */
#include "viscolube/output.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

const char *const vl_curve_columns[] = {
    "v0_m_s", "v0_eta_pa_m", "deborah", "mu", "mu_Rc", "mu_Rf", "mu_Sc", "mu_Sf", "u_min_m",
    "u_central_m", "contact_width_m", "fluid_load_fraction", "regime", "E_wH_pa", "a_H_m", "Q",
    "x_centroid_m", "load_error", "converged", "iterations", "residual", "eps_f_min", "warnings", NULL};

/* -0 (a sum of zeros with a minus sign, e.g. mu_Rf of a dry contact) is
 * written as 0: readers compare text, and "-0" looks like a sign. */
static double plain_zero(double v) { return v == 0.0 ? 0.0 : v; }

static void cell(FILE *f, double v, int ok) {
  if (ok && isfinite(v)) fprintf(f, ",%.10g", plain_zero(v));
  else fputc(',', f);
}

void vl_print_curve_csv(FILE *out, size_t n, const vl_point *pts, const vl_curve_meta *meta) {
  for (size_t c = 0; vl_curve_columns[c]; c++)
    fprintf(out, "%s%s", c ? "," : "", vl_curve_columns[c]);
  fputc('\n', out);
  for (size_t i = 0; i < n; i++) {
    const vl_point *p = &pts[i];
    int ok = p->converged;
    fprintf(out, "%.10g", plain_zero(p->v0_m_s));
    cell(out, p->v0_m_s * meta->eta_pa_s, meta->eta_pa_s > 0);
    cell(out, p->v0_m_s * meta->tau_s / meta->a0_m, meta->tau_s > 0 && meta->a0_m > 0);
    cell(out, p->mu, ok);
    cell(out, p->mu_Rc, ok);
    cell(out, p->mu_Rf, ok);
    cell(out, p->mu_Sc, ok);
    cell(out, p->mu_Sf, ok);
    cell(out, p->u_min_m, ok);
    cell(out, p->u_central_m, ok);
    cell(out, p->contact_width_m, ok);
    cell(out, p->fluid_load_fraction, ok);
    fprintf(out, ",%s", ok ? vl_regime_name(p->regime) : "");
    cell(out, p->E_wH_pa, 1);
    cell(out, p->a_H_m, 1);
    cell(out, p->Q, 1);
    cell(out, p->x_centroid_m, ok);
    cell(out, p->load_error, ok);
    fprintf(out, ",%d,%ld", p->converged ? 1 : 0, p->iterations);
    cell(out, p->residual, 1);
    cell(out, p->eps_f_min, ok); /* viscous flattening: 1 when off */
    /* warnings never contain commas or quotes (contact.c writes them) */
    fprintf(out, ",%s\n", p->warnings);
  }
}

/* Opens path.tmp for writing; the caller renames it into place. */
static FILE *open_tmp(const char *path, char *tmp, size_t size, vl_error *err) {
  snprintf(tmp, size, "%s.tmp", path);
  FILE *f = fopen(tmp, "w");
  if (!f) vl_error_set(err, "%s: cannot write: %s", tmp, strerror(errno));
  return f;
}

static vl_status close_rename(FILE *f, const char *tmp, const char *path, vl_error *err) {
  int bad = ferror(f);
  if (fclose(f) != 0 || bad || rename(tmp, path) != 0) {
    vl_error_set(err, "%s: write failed: %s", path, strerror(errno));
    remove(tmp);
    return VL_EIO;
  }
  return VL_OK;
}

vl_status vl_write_curve_csv(const char *path, size_t n, const vl_point *pts,
                             const vl_curve_meta *meta, vl_error *err) {
  char tmp[4200];
  FILE *f = open_tmp(path, tmp, sizeof tmp, err);
  if (!f) return VL_EIO;
  vl_print_curve_csv(f, n, pts, meta);
  return close_rename(f, tmp, path, err);
}

vl_status vl_write_fields_csv(const char *path, const vl_fields *fl, double a0_m, vl_error *err) {
  char tmp[4200];
  FILE *f = open_tmp(path, tmp, sizeof tmp, err);
  if (!f) return VL_EIO;
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
  return close_rename(f, tmp, path, err);
}

static void jnum(FILE *out, const char *key, double v, int ok, int comma) {
  if (ok && isfinite(v)) fprintf(out, "\"%s\": %.10g", key, plain_zero(v));
  else fprintf(out, "\"%s\": null", key);
  if (comma) fputs(", ", out);
}

void vl_print_point_json(FILE *out, const vl_point *p, const vl_curve_meta *meta) {
  int ok = p->converged;
  fputc('{', out);
  jnum(out, "v0_m_s", p->v0_m_s, 1, 1);
  jnum(out, "v0_eta_pa_m", p->v0_m_s * meta->eta_pa_s, meta->eta_pa_s > 0, 1);
  jnum(out, "deborah", meta->a0_m > 0 ? p->v0_m_s * meta->tau_s / meta->a0_m : 0,
       meta->tau_s > 0 && meta->a0_m > 0, 1);
  jnum(out, "mu", p->mu, ok, 1);
  jnum(out, "mu_Rc", p->mu_Rc, ok, 1);
  jnum(out, "mu_Rf", p->mu_Rf, ok, 1);
  jnum(out, "mu_Sc", p->mu_Sc, ok, 1);
  jnum(out, "mu_Sf", p->mu_Sf, ok, 1);
  jnum(out, "u_min_m", p->u_min_m, ok, 1);
  jnum(out, "u_central_m", p->u_central_m, ok, 1);
  jnum(out, "contact_width_m", p->contact_width_m, ok, 1);
  jnum(out, "fluid_load_fraction", p->fluid_load_fraction, ok, 1);
  if (ok) fprintf(out, "\"regime\": \"%s\", ", vl_regime_name(p->regime));
  else fputs("\"regime\": null, ", out);
  jnum(out, "E_wH_pa", p->E_wH_pa, 1, 1);
  jnum(out, "a_H_m", p->a_H_m, 1, 1);
  jnum(out, "Q", p->Q, 1, 1);
  jnum(out, "x_centroid_m", p->x_centroid_m, ok, 1);
  jnum(out, "load_error", p->load_error, ok, 1);
  fprintf(out, "\"converged\": %s, \"iterations\": %ld, ", ok ? "true" : "false", p->iterations);
  jnum(out, "residual", p->residual, 1, 1);
  jnum(out, "eps_f_min", p->eps_f_min, ok, 1);
  fprintf(out, "\"warnings\": \"%s\"}", p->warnings);
}

void vl_print_curve_json(FILE *out, size_t n, const vl_point *pts, const vl_curve_meta *meta) {
  fputs("[\n", out);
  for (size_t i = 0; i < n; i++) {
    fputs("  ", out);
    vl_print_point_json(out, &pts[i], meta);
    fputs(i + 1 < n ? ",\n" : "\n", out);
  }
  fputs("]\n", out);
}
