/* viscolube: random surface roughness (its power spectral density).
 *
 * PSD: isotropic, C(q) in m^4, either self-affine
 *   C(q) = C0 (q/q0)^(-2(1+H)) for q0 <= q <= q1, 0 elsewhere,
 * with h_rms^2 = 2 pi \int q C(q) dq, or tabulated (q_k, C_k) points
 * interpolated as a power law between points (linear in log-log), zero
 * outside [q_first, q_last].
 */
#ifndef VISCOLUBE_ROUGHNESS_H
#define VISCOLUBE_ROUGHNESS_H

#include <stddef.h>

#include "viscolube/status.h"

typedef enum { VL_PSD_SELF_AFFINE = 0, VL_PSD_TABULATED = 1 } vl_psd_kind;

typedef struct {
  vl_psd_kind kind;
  double hurst;  /* self-affine only, 0 < H <= 1 */
  double q0, q1; /* 1/m: the band (tabulated: first and last q) */
  double c0;     /* m^4, self-affine prefactor derived from h_rms */
  double hrms_m; /* rms height */
  size_t n;      /* tabulated points (0 for self-affine) */
  double *q;     /* owned, n values, strictly increasing */
  double *C;     /* owned, n values, > 0 */
} vl_psd;

/* Self-affine PSD from H, q0, q1, h_rms; validates (0 < H <= 1, 0 < q0 < q1,
 * h_rms > 0, all finite) and derives C0. */
vl_status vl_psd_init_self_affine(vl_psd *psd, double hurst, double q0, double q1, double hrms_m,
                                  vl_error *err);

/* Tabulated PSD, copying the arrays; validates (n >= 2, q strictly increasing
 * and > 0, C > 0, finite) and derives h_rms. */
vl_status vl_psd_init_tabulated(vl_psd *psd, size_t n, const double *q, const double *C,
                                vl_error *err);

void vl_psd_free(vl_psd *psd);

double vl_psd_hrms(const vl_psd *psd);      /* sqrt(2 pi \int q C dq) */
double vl_psd_rms_slope(const vl_psd *psd); /* sqrt(<|grad h|^2>) = sqrt(2 pi \int q^3 C dq) */

/* The self-affine law C = c_q0 (q/q0)^(-2(1+H)) closest to a tabulated
 * spectrum: a least-squares line through (log q, log C) of its points
 * from the largest C on (a roll-off at small q is not self-affine; all
 * points when that leaves one), equally weighted. *hurst gets H (any value: outside (0, 1] the
 * surface is not self-affine), *c_q0 (may be NULL) the line's C at psd->q0 and *rms_log10 (may be
 * NULL) its rms misfit in log10 C. For a self-affine psd its own H, C0 and 0. VL_EINPUT when fewer
 * than 2 points. */
vl_status vl_psd_fit_self_affine(const vl_psd *psd, double *hurst, double *c_q0, double *rms_log10,
                                 vl_error *err);

#endif
