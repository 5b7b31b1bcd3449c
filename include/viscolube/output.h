/* viscolube: writers for curves and fields (CSV, JSON). They know nothing of
 * the solver: they format vl_point and vl_fields. A failed point is written
 * with converged = 0 and empty physics cells (null in JSON), never NaN.
 * Files are written whole or not at all (atomic_file.h). */
#ifndef VISCOLUBE_OUTPUT_H
#define VISCOLUBE_OUTPUT_H

#include <stddef.h>

#include "viscolube/json.h"
#include "viscolube/results.h"
#include "viscolube/status.h"

/* What turns a speed into the other sweep coordinates (0 = not defined). */
typedef struct {
  double eta_pa_s; /* for v0_eta_pa_m */
  double tau_s;    /* for deborah = v0 tau / a0 (one-term compounds) */
  double a0_m;
  /* The flow-factor model that produced the curve (vl_flow_factors_name), or
   * NULL where the contact has no rough film (dry or smooth): CSV files then
   * begin with a comment line "# flow_factors = MODEL[, film_cutoff_m = C]"
   * and JSON points carry the key flow_factors. */
  const char *flow_factors;
  double film_cutoff_m; /* persson-emt's g_cut (m); 0 for the other models */
  /* Where sigma_s came from when a stored pair's law gave it
   * (vl_simulation_shear_law_text), else NULL (the constant sigma_s of the
   * scene or the options): CSV files then carry a comment line
   * "# sigma_s = TEXT" and JSON points the key sigma_s_law. */
  const char *shear_law;
} vl_curve_meta;

/* CSV columns of the curve, in order (a NULL-terminated list). */
extern const char *const vl_curve_columns[];
/* The columns a seal scene ([seal] stroke; vl_point.seal) adds after them,
 * NULL-terminated (docs/FORMATS.md). */
extern const char *const vl_seal_columns[];
/* The columns a point contact ([contact] geometry = ball or ellipsoid;
 * vl_point.ball) adds after them (and after a seal's), NULL-terminated
 * (docs/FORMATS.md). */
extern const char *const vl_ball_columns[];
/* The number in point-contact column k (an index of vl_ball_columns, from 1:
 * column 0, `geometry`, is a word) of p, NAN where the CSV cell is empty. */
double vl_ball_column_value(const vl_point *p, size_t k);
/* The number in seal column k (an index of vl_seal_columns, from 1: column 0,
 * `stroke`, is a word) of p, NAN where the CSV cell is empty. */
double vl_seal_column_value(const vl_point *p, size_t k);
/* The columns a scene swept both ways ([sweep] direction = both;
 * vl_point.down) adds after those, NULL-terminated (docs/FORMATS.md), and
 * the number in column k of p (NAN where the CSV cell is empty;
 * converged_down and two_states 1 or 0). */
extern const char *const vl_down_columns[];
double vl_down_column_value(const vl_point *p, size_t k);

/* Writes the curve to path through a temporary renamed into place
 * (atomic_file.h), so a crash leaves no half-written file. VL_EIO with a
 * message naming path when it cannot be written. */
vl_status vl_write_curve_csv(const char *path, size_t n, const vl_point *pts,
                             const vl_curve_meta *meta, vl_error *err);

/* Fields: x_m, x_over_a0, p_f_pa, p_c_pa, u_m, area_ratio, film_fraction, and
 * cell_width_m when fl->width_m is set (a graded grid's cells differ: the
 * load is sum (p_f + p_c) cell_width). */
vl_status vl_write_fields_csv(const char *path, const vl_fields *f, double a0_m, vl_error *err);

/* A point contact's fields, the cells of the solved half y >= 0 (the
 * contact is symmetric in y): x_m, y_m, x_over_a0, y_over_a0, p_c_pa, u_m
 * and, when p_f_pa is not NULL (a lubricated contact), p_f_pa; n rows. */
vl_status vl_write_fields2d_csv(const char *path, size_t n, const double *x_m, const double *y_m,
                                const double *p_c_pa, const double *u_m, const double *p_f_pa,
                                double a0_m, vl_error *err);

/* JSON (json.h), numbers with 10 significant digits as in the CSV: a
 * point is one object with the keys of the CSV columns (on one line); a
 * curve an array of them, a point a line (VL_JSON_ROWS). */
void vl_curve_json(vl_json *w, size_t n, const vl_point *pts, const vl_curve_meta *meta);
/* The members of a point's object, into an object the caller has begun (and
 * ends), for a point written with more keys of its own. */
void vl_point_json_members(vl_json *w, const vl_point *pt, const vl_curve_meta *meta);

/* A seal's table (`viscolube seal`; docs/FORMATS.md "seal.csv"): a row
 * per speed with both strokes, from points whose seal result holds the
 * instroke (vl_point.seal, stroke VL_STROKE_BOTH): friction force per
 * length, mu, minimum and central film, flux per unit circumference and
 * the error estimates of the friction and of the flux, per stroke
 * (columns *_out, *_in); the volumes carried out and back per cycle and
 * whether the seal is tight; convergence, accuracy and warnings per
 * stroke. NULL-terminated column names. */
extern const char *const vl_seal_table_columns[];
/* The number in column k of p's row, NAN where the CSV cell is empty (a
 * stroke that did not converge, a value not known) and for the text
 * columns (accuracy_*, warnings_*). */
double vl_seal_table_value(const vl_point *p, size_t k);
/* The text of column k (accuracy_out, accuracy_in, warnings_out,
 * warnings_in) of p's row, "" when empty; NULL for a number column. */
const char *vl_seal_table_text(const vl_point *p, size_t k);
/* The table as CSV (a '#' line saying what it holds, then the header) to
 * path, through a temporary renamed into place. */
vl_status vl_write_seal_csv(const char *path, size_t n, const vl_point *pts, vl_error *err);
/* The same as JSON: an array of {"v0_m_s", "out": {converged,
 * friction_n_per_m, mu, u_min_m, u_central_m, flux_m2_s, error_estimate,
 * flux_error_estimate, accuracy, warnings}, "in": {...}, "volume_out_m3",
 * "volume_back_m3", "tight"}, a point a line; null where the CSV is empty. */
void vl_seal_json(vl_json *w, size_t n, const vl_point *pts);
vl_status vl_write_seal_json(const char *path, size_t n, const vl_point *pts, vl_error *err);

#endif
