/* viscolube: a profile's 1-D roughness spectrum -> the isotropic surface's
 * 2-D one (the inverse Abel transform of topography.h, step 6), for the
 * readers that are given a 1-D spectrum: a line scan's (topography_psd.c)
 * and a tabulated one (psd_file.c). Private to the library; implemented
 * in abel.c. */
#ifndef VL_ABEL_H
#define VL_ABEL_H

#include <stddef.h>

#include "viscolube/status.h"

/* C(q) at q[0..n) (strictly increasing, > 0) from the two-sided profile
 * spectrum C1 (h_rms^2 = \int_{-inf}^{inf} C1 dq, m^3) given there:
 * C1 is first made non-increasing (pooling neighbours, weight[k] points
 * each, or 1 each when weight is NULL), continued beyond q[n-1] as a power
 * law with the slope of its last half decade (*tail_out gets
 * -dlnC1/dlnq, may be NULL), and transformed exactly for that piecewise
 * power law. c2[j] (m^4) may come out <= 0 where the pooled C1 is flat to
 * the end: the caller drops such points. VL_ENOMEM, else VL_OK. */
vl_status vl_abel_profile_to_surface(size_t n, const double *q, const double *c1,
                                     const size_t *weight, double *c2, double *tail_out);

#endif
