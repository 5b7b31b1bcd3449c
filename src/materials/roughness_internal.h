/* viscolube (private): the power spectrum below its public part
 * (viscolube/roughness.h: making and freeing a PSD, h_rms, the rms slope,
 * the self-affine fit). Here: C(q) and its moments, for Persson's theory,
 * the flow factors and tests. */
#ifndef VISCOLUBE_ROUGHNESS_INTERNAL_H
#define VISCOLUBE_ROUGHNESS_INTERNAL_H

#include "viscolube/roughness.h"

/* C(q) in m^4: the self-affine law or the tabulated power law at q (1/m),
 * 0 outside the band. */
double vl_psd_value(const vl_psd *psd, double q);
/* \int_{qa}^{qb} q^k C(q) dq, exact for both kinds (clipped to the band). */
double vl_psd_moment(const vl_psd *psd, int k, double qa, double qb);

#endif
