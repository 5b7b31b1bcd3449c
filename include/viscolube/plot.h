/* viscolube: figures of curves, fields and moduli as PNG and SVG files,
 * drawn with PLplot's cairo drivers (pngcairo, svgcairo).
 *
 * The module knows nothing of the solver: its inputs are arrays (the
 * vl_point of a curve, the vl_fields of marked speeds, measured and fitted
 * moduli) and labels. Every function writes STEM.png and STEM.svg (or the
 * formats the options select), each through a temporary renamed into place
 * (atomic_file.h) once PLplot has closed it and the file is checked
 * complete, so a failure leaves no half-written figure. Every figure has a
 * title (the options', else what it shows), and the SVG carries the title
 * and subtitle as text too, as its <title> and <desc> elements.
 *
 * Conventions in every figure: axis titles carry units; a legend right of
 * the plot area (never over the data) names each series; logarithmic axes
 * are labelled at whole decades, every decade or every few when they would
 * crowd; a point that did not converge is never joined to its neighbours:
 * its lines have a gap there and it is drawn as a hollow marker on a row
 * just above the x axis (it has no value to plot), listed in the legend as
 * "not converged" (white inside, so that in the SVG each is one path filled
 * white). Series are drawn with pens of 2 px or more in colours that are
 * not greys; axes, grid, reference lines and marker edges are grey or black
 * or thinner, so the series of a figure can be told apart in its SVG.
 *
 * PLplot keeps global state: these functions are not thread-safe. Errors
 * PLplot reports as recoverable are captured (nothing is printed) and
 * returned as VL_EINTERNAL; what can be foreseen (missing driver, file not
 * writable, empty or bad input) is checked first. PLplot itself still ends
 * the process on the errors it treats as fatal (out of memory inside it). */
#ifndef VISCOLUBE_PLOT_H
#define VISCOLUBE_PLOT_H

#include <stdbool.h>
#include <stddef.h>

#include "viscolube/output.h"
#include "viscolube/results.h"
#include "viscolube/scene.h"
#include "viscolube/status.h"

typedef enum { VL_PLOT_PNG = 1u, VL_PLOT_SVG = 2u } vl_plot_format;

typedef struct {
  unsigned formats;        /* VL_PLOT_PNG | VL_PLOT_SVG; 0 = both */
  int width_px, height_px; /* 0 = 1000 x 750 (SVG: points) */
  const char *title;       /* line above the plot; NULL or "" = what the figure shows
                              ("Stribeck curve", "Roughness power spectrum", ...) */
  bool mark_half_load;     /* curves: mark where the fluid starts to carry half
                              of the load (fluid_load_fraction crosses 0.5) */
  const char *subtitle;    /* smaller line under the title (the conditions: materials,
                              load, radius, flow-factor model); NULL or "" = none */
} vl_plot_options;

/* What a call drew (the same in every format). */
typedef struct {
  size_t series;         /* data series drawn, one legend entry each */
  size_t failed_markers; /* hollow markers for points that did not converge */
  size_t files;          /* files written */
  double x_lo, x_hi;     /* the x axis drawn, in data units (fields: x/a0) */
  char title[256];       /* the title drawn (the options', else what the figure shows) */
} vl_plot_report;

/* Both formats, 1000 x 750, no title of the caller's (the figure's kind)
 * or subtitle, no half-load marks. */
void vl_plot_options_defaults(vl_plot_options *opt);

/* True when PLplot has both cairo drivers; otherwise false and err says
 * which is missing (Debian package plplot-driver-cairo). */
bool vl_plot_available(vl_error *err);

/* Writes v as plain UTF-8 text with 3 significant digits: "0.25", "1500",
 * "10⁻⁷", "3.2×10⁵" (powers of ten outside [1e-3, 1e4)), negative values
 * with a true minus sign (U+2212). Returns the
 * length written (truncated to size - 1, always NUL-terminated). For the
 * labels callers build (speeds of marked curves, compound names...). */
size_t vl_plot_format_value(char *buf, size_t size, double v);

/* The Stribeck figure: mu and its four components mu_Rc, mu_Rf, mu_Sc, mu_Sf
 * against the sweep quantity x (v0, v0*eta or v0 tau/a0, from pt->v0_m_s
 * and meta as in the CSV) on a logarithmic axis; friction on a linear axis.
 * A component that is zero at every converged point (no fluid, no sigma_s)
 * is left out; one that is all of mu (dry, smooth: mu = mu_Rc) is named in
 * mu's legend entry instead of being drawn under it. marks[0..n_marks)
 * are indices into pts of the speeds whose fields are plotted: they are
 * numbered 1..n_marks on the mu curve, the numbers vl_plot_fields labels
 * should carry (a mark on a point that did not converge is skipped; its
 * number is not reused).
 * VL_EINPUT: n = 0, x undefined (v0_eta without eta, deborah without tau
 * or a0), a mark out of range; VL_EIO: a file could not be written;
 * VL_EINTERNAL: PLplot reported an error. */
vl_status vl_plot_stribeck(const char *stem, size_t n, const vl_point *pts,
                           const vl_curve_meta *meta, vl_sweep_quantity x, size_t n_marks,
                           const size_t *marks, const vl_plot_options *opt, vl_plot_report *report,
                           vl_error *err);

/* A seal's two strokes against the sliding speed v0 (log axis): above, the
 * friction force per length of the outstroke (solid) and the instroke
 * (dashed); below, the flux per unit circumference of each (logarithmic
 * when positive over more than a factor 30). pts: a seal's points with
 * both strokes (vl_point.seal.stroke VL_STROKE_BOTH). A stroke that did
 * not converge is a hollow marker above the x axis; one above its error
 * target a hollow square. VL_EINPUT: no points, not both strokes, a speed
 * not positive; other errors as vl_plot_stribeck. */
vl_status vl_plot_seal(const char *stem, size_t n, const vl_point *pts, const vl_plot_options *opt,
                       vl_plot_report *report, vl_error *err);

/* The minimum separation against x: u_min/h_rms when h_rms_m > 0, else
 * u_min in um; the y axis is logarithmic when the data span more than a
 * factor 30. Marks and errors as vl_plot_stribeck. */
vl_status vl_plot_separation(const char *stem, size_t n, const vl_point *pts,
                             const vl_curve_meta *meta, vl_sweep_quantity x, double h_rms_m,
                             size_t n_marks, const size_t *marks, const vl_plot_options *opt,
                             vl_plot_report *report, vl_error *err);

typedef enum {
  VL_PLOT_FIELD_PC = 0, /* solid contact pressure p_c / p0 */
  VL_PLOT_FIELD_PF,     /* fluid pressure p_f / p0 */
  VL_PLOT_FIELD_U,      /* separation u / h_rms (log axis when it spans more than a
                           factor 30), or u in um on a linear axis when h_rms = 0 */
  VL_PLOT_FIELD_AREA    /* contact area ratio A/A0 */
} vl_plot_field;

/* Scales of the fields figures: a0, p0 of the Hertz contact (relaxed
 * modulus) and h_rms (0 = smooth surface). */
typedef struct {
  double a0_m, p0_pa, h_rms_m;
} vl_plot_scales;

/* One field against x/a0, one curve per fields[j] (in a sequential colour
 * order: give them by increasing speed), legend labels[j] (plain text; a
 * NULL label draws "j+1"). fields[j].n == 0 stands for a speed that did not
 * converge: no curve, a hollow marker in the legend. Thin dotted lines mark
 * x = +-a0. VL_EINPUT: k = 0, bad scales, a field with NULL arrays. */
vl_status vl_plot_fields(const char *stem, vl_plot_field field, size_t k, const vl_fields *fields,
                         const char *const *labels, const vl_plot_scales *scales,
                         const vl_plot_options *opt, vl_plot_report *report, vl_error *err);

/* A point contact's field on its cells (the solved half y >= 0, cell
 * k = ix ny + iy: y runs fastest; a tensor grid, each cell reaching half
 * way to its neighbours' centres). */
typedef struct {
  size_t nx, ny;
  const double *x_m, *y_m; /* cell centres */
  const double *p_c_pa;    /* for VL_PLOT_FIELD_PC */
  const double *u_m;       /* for VL_PLOT_FIELD_U */
  const double *p_f_pa;    /* for VL_PLOT_FIELD_PF */
} vl_plot_map_data;

/* A point contact's field over the contact plane as a colour map of its
 * cells, x/a0 along the sliding direction and y/a0 across at equal scales
 * (the solved half mirrored to y < 0), with a colour bar and, when both
 * semi-axes are positive, the Hertz ellipse hertz_ax_m x hertz_by_m
 * dashed over it. field: VL_PLOT_FIELD_PC (p_c/p0, the cells out of
 * contact left white), VL_PLOT_FIELD_PF (p_f/p0, the cavitated cells left
 * white) or VL_PLOT_FIELD_U (u in um). VL_EINPUT: another
 * field, no cells, bad scales. */
vl_status vl_plot_map(const char *stem, vl_plot_field field, const vl_plot_map_data *d,
                      const vl_plot_scales *scales, double hertz_ax_m, double hertz_by_m,
                      const vl_plot_options *opt, vl_plot_report *report, vl_error *err);

/* One curve of vl_plot_compare. */
typedef struct {
  const char *label; /* legend text (plain) */
  size_t n;
  const vl_point *pts;
  vl_curve_meta meta;
  double h_rms_m; /* for VL_PLOT_Y_U_MIN; 0 = u_min in um */
} vl_plot_curve;

typedef enum {
  VL_PLOT_Y_MU = 0,
  VL_PLOT_Y_MU_RC,
  VL_PLOT_Y_MU_RF,
  VL_PLOT_Y_MU_SC,
  VL_PLOT_Y_MU_SF,
  VL_PLOT_Y_MU_ROLLING, /* mu_Rc + mu_Rf (the seed's Fig. 13) */
  VL_PLOT_Y_U_MIN,      /* u_min / h_rms */
  VL_PLOT_Y_FLUID_LOAD  /* share of the load carried by the fluid */
} vl_plot_y;

/* k curves of quantity y against x on one axis (8 distinguishable colours,
 * then dash patterns repeat them). With opt->mark_half_load each curve gets
 * a diamond where its fluid load share crosses 0.5. Errors as
 * vl_plot_stribeck; every curve must define x. */
vl_status vl_plot_compare(const char *stem, size_t k, const vl_plot_curve *curves,
                          vl_sweep_quantity x, vl_plot_y y, const vl_plot_options *opt,
                          vl_plot_report *report, vl_error *err);

/* A pair's calibration (`pair calibrate --plot`): the measured friction
 * coefficients against sliding speed, over the fitted mu and its parts. */
typedef struct {
  size_t n;                                /* measured points, >= 1 */
  const double *v_m_s;                     /* positive, increasing */
  const double *mu;                        /* measured (<= 0 or non-finite: not drawn) */
  const double *mu_fit, *mu_other, *mu_sc; /* the model (non-finite: a gap) */
  const bool *informative; /* NULL: all; false: hollow marker (mu_Sc a small share) */
  const char *fit_label;   /* NULL = "fitted mu" */
} vl_plot_calibration_data;

/* One panel, log-log: the fitted mu (line), mu_Sc of the fitted law and
 * mu without sigma_s (thinner lines), the measured points as markers over
 * them, hollow where they inform the fit little. VL_EINPUT: no points, a
 * speed not positive and finite. Other errors as vl_plot_stribeck. */
vl_status vl_plot_calibration(const char *stem, const vl_plot_calibration_data *d,
                              const vl_plot_options *opt, vl_plot_report *report, vl_error *err);

/* Measured and fitted moduli of a compound. */
typedef struct {
  size_t n; /* measured points (at reduced frequency when shifted); may be 0 */
  const double *omega_rad_s, *storage_pa, *loss_pa;
  size_t n_fit; /* the fitted model on a frequency grid; 0 = none */
  const double *fit_omega_rad_s, *fit_storage_pa, *fit_loss_pa;
  const char *measured_label; /* NULL = "measured" */
  const char *fit_label;      /* NULL = "Prony fit" */
} vl_plot_modulus_data;

/* Two panels against angular frequency, log-log: E' and E'' (top), tan
 * delta = E''/E' (bottom); measured as markers (in a lighter shade), fitted
 * as lines over them. The frequency axis spans the measured points (the
 * fitted ones when there are none). VL_EINPUT: no points at all, a
 * non-positive or non-finite value. */
vl_status vl_plot_modulus(const char *stem, const vl_plot_modulus_data *d,
                          const vl_plot_options *opt, vl_plot_report *report, vl_error *err);

/* Shift factors of time-temperature superposition: log10 a_T of n isotherms
 * against temperature (markers) and, when c1 > 0 and c2_k > 0, the WLF curve
 * log10 a_T = -c1 (T - Tref)/(c2 + T - Tref) over the data's range.
 * VL_EINPUT: n = 0, non-finite values. */
vl_status vl_plot_shifts(const char *stem, size_t n, const double *t_c, const double *log10_a_t,
                         double tref_c, double c1, double c2_k, const vl_plot_options *opt,
                         vl_plot_report *report, vl_error *err);

/* A flow-factor table of one surface (flow_factors.h) against x = u/h_rms. */
typedef struct {
  size_t n;                                              /* rows, >= 2 */
  const double *x;                                       /* u/h_rms, positive and finite */
  const double *phi_p, *phi_s, *phi_fp, *phi_fs, *phi_f; /* a non-finite value is a gap */
  const double *area_ratio; /* A/A0 of the contact law at x; NULL = not drawn */
  double x_percolation;     /* where pressure flow stops; NAN = not marked */
} vl_plot_flow_factor_data;

/* Two panels against x on a logarithmic axis: the flow factors phi_p,
 * phi_fp (dashed, as it coincides with phi_p for smooth surfaces), phi_s
 * and A/A0 (top), the shear factors phi_f and phi_fs (bottom), each with a
 * linear y axis; a dotted grey line at x_percolation when it lies inside
 * the axis. VL_EINPUT: fewer than 2 rows, a NULL factor array, an x that is
 * not positive and finite. */
vl_status vl_plot_flow_factors(const char *stem, const vl_plot_flow_factor_data *d,
                               const vl_plot_options *opt, vl_plot_report *report, vl_error *err);

/* A roughness power spectrum and, optionally, a self-affine law over it. */
typedef struct {
  size_t n;                     /* points of the spectrum, >= 2 */
  const double *q_per_m, *c_m4; /* positive and finite */
  const char *label;            /* NULL = "C(q)" */
  size_t n_fit;                 /* the law on a q grid; 0 = none */
  const double *fit_q_per_m, *fit_c_m4;
  const char *fit_label; /* NULL = "self-affine fit" */
} vl_plot_psd_data;

/* C(q) against q, log-log: the spectrum as a line (markers too when it has
 * at most 60 points, as a measured one), the law dashed over it. The axes
 * span the spectrum. VL_EINPUT: fewer than 2 points, a non-positive or
 * non-finite value. */
vl_status vl_plot_psd(const char *stem, const vl_plot_psd_data *d, const vl_plot_options *opt,
                      vl_plot_report *report, vl_error *err);

#endif
