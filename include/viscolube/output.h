/* viscolube: writers for curves and fields (CSV, JSON). They know nothing of
 * the solver: they format vl_point and vl_fields. A failed point is written
 * with converged = 0 and empty physics cells, never NaN. */
#ifndef VISCOLUBE_OUTPUT_H
#define VISCOLUBE_OUTPUT_H

#include <stddef.h>
#include <stdio.h>

#include "viscolube/results.h"
#include "viscolube/status.h"

/* What turns a speed into the other sweep coordinates (0 = not defined). */
typedef struct {
  double eta_pa_s; /* for v0_eta_pa_m */
  double tau_s;    /* for deborah = v0 tau / a0 (one-term compounds) */
  double a0_m;
} vl_curve_meta;

/* CSV columns of the curve, in order (a NULL-terminated list). */
extern const char *const vl_curve_columns[];

/* Writes the curve to path through a temporary file renamed at the end, so a
 * crash leaves no half-written file. */
vl_status vl_write_curve_csv(const char *path, size_t n, const vl_point *pts,
                             const vl_curve_meta *meta, vl_error *err);
void vl_print_curve_csv(FILE *out, size_t n, const vl_point *pts, const vl_curve_meta *meta);

/* Fields: x_m, x_over_a0, p_f_pa, p_c_pa, u_m, area_ratio, film_fraction, and
 * cell_width_m when fl->width_m is set (a graded grid's cells differ: the
 * load is sum (p_f + p_c) cell_width). */
vl_status vl_write_fields_csv(const char *path, const vl_fields *f, double a0_m, vl_error *err);

/* One JSON object per point; an array for a curve. */
void vl_print_point_json(FILE *out, const vl_point *pt, const vl_curve_meta *meta);
void vl_print_curve_json(FILE *out, size_t n, const vl_point *pts, const vl_curve_meta *meta);

#endif
