/* viscolube: calibrating a pair's sigma_s law on a measured Stribeck curve
 * (issue 34).
 *
 * sigma_s does not change the contact's solution, it enters only mu_Sc, so
 *   mu(v) = mu_other(v) + sigma_s(v) I(v),   I = (1/fN) int A/A0 dx,
 * the line contact sliding at v everywhere. One sweep at the measured
 * speeds with a reference sigma_s gives mu_other and I at each speed
 * (vl_calibration_sweep); the law's parameters are then a cheap least-
 * squares fit of log10 mu: the constant law by a linear fit (in relative
 * error, then Gauss-Newton in log10 mu), eyring and dewetting by GSL's
 * trust-region nonlinear least squares started from the best point of a
 * grid in their speed parameter. Intervals (95 %) from the fit's
 * covariance scaled by its residual and Student's t. */
#ifndef VISCOLUBE_CALIBRATE_H
#define VISCOLUBE_CALIBRATE_H

#include <stdbool.h>
#include <stddef.h>

#include "viscolube/database.h"
#include "viscolube/query.h"
#include "viscolube/shear_law.h"
#include "viscolube/status.h"

/* sigma_s of the calibration sweep (any positive value gives the same I). */
#define VL_CALIBRATION_SIGMA_REF_PA 1e6
/* A point whose fitted mu_Sc is below this share of mu tells the fit
 * little about sigma_s: listed as uninformative. */
#define VL_CALIBRATION_MIN_SC_SHARE 0.1
/* A fit whose rms misfit in log10 mu exceeds this (a factor 1.26) is
 * reported as not fitting: it is not stored. */
#define VL_CALIBRATION_MAX_RMS_LOG10 0.1

/* The model's parts at each measured speed. */
typedef struct {
  size_t n;
  double *v_m_s;        /* increasing */
  double *mu;           /* the measured friction coefficient (or, from a pair, the model's) */
  double *mu_other;     /* mu_Rc + mu_Rf + mu_Sf of the sweep */
  double *area;         /* I = (1/fN) int A/A0 dx (1/Pa) */
  bool *converged;      /* the solver reached the point */
  double eta_pa_s;      /* the fluid's viscosity of the sweep */
  double temperature_c; /* NAN without temperature */
  double seconds;       /* the sweep's wall time */
} vl_calibration_sweep;

void vl_calibration_sweep_free(vl_calibration_sweep *s);

/* One sweep of q's conditions at the n speeds v_m_s (any order, > 0,
 * finite) with sigma_s = VL_CALIBRATION_SIGMA_REF_PA (q's sigma choice is
 * ignored), measured mu_measured copied alongside (may be NULL: then mu is
 * the model's with the pair's law if q leaves sigma_s to it, else with
 * q->sigma_s_pa). Sorted by speed. VL_EINPUT (bad speeds, conditions), as
 * vl_simulation_create otherwise. */
vl_status vl_calibration_sweep_run(vl_db *db, const vl_query *q, size_t n, const double *v_m_s,
                                   const double *mu_measured, vl_calibration_sweep *out,
                                   vl_error *err);

/* The outcome of a fit. */
typedef struct {
  vl_shear_law law; /* at the sweep's temperature (tref_c) and viscosity (eta_ref_pa_s) */
  double ci95[VL_SHEAR_LAW_MAX_PARAMS]; /* half-widths of the 95 % intervals */
  double rms_log10_mu;                  /* over the points used */
  size_t n_used;                        /* converged points with mu > 0 */
  size_t n_unreached;                   /* the solver did not converge there */
  size_t n_uninformative;               /* fitted mu_Sc < VL_CALIBRATION_MIN_SC_SHARE mu */
  bool *uninformative;                  /* per point (malloc'd, n of the sweep) */
  bool fits;                            /* fit found and rms within VL_CALIBRATION_MAX_RMS_LOG10 */
  char why[256];                        /* when !fits: why ("" otherwise) */
  int iterations;                       /* of the nonlinear fit (0: linear) */
  double seconds;                       /* the fit's wall time (the sweep's not included) */
} vl_calibration_fit;

void vl_calibration_fit_free(vl_calibration_fit *f);

/* Fits law `kind` to s (its mu the measured values). VL_EINPUT: fewer
 * usable points than parameters + 1, a friction coefficient <= 0. A fit
 * that does not fit is VL_OK with fits false and why said. */
vl_status vl_calibration_fit_law(const vl_calibration_sweep *s, vl_shear_law_kind kind,
                                 vl_calibration_fit *out, vl_error *err);

/* The model's mu at point i of s with law (already at s's conditions). */
double vl_calibration_model_mu(const vl_calibration_sweep *s, size_t i, const vl_shear_law *law);

/* The rms misfit in log10 mu of law over the converged points of s, the
 * law taken to s's temperature and viscosity first (vl_shear_law_at): the
 * prediction check on a curve measured at other conditions. */
double vl_calibration_misfit(const vl_calibration_sweep *s, const vl_shear_law *law);

#endif
