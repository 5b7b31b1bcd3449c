/* An independent viscoelastic model for the import tests: a
 * Havriliak-Negami modulus E = Einf + (E0 - Einf)/(1 + (i w tau)^a)^b with
 * WLF time-temperature shifts, from which isotherms and master curves are
 * written as a user's DMA export would hold them. */
#ifndef VL_TEST_HN_H
#define VL_TEST_HN_H

#include <complex.h>

typedef struct {
  double e0, einf, tau, a, b; /* HN: E = Einf + (E0 - Einf)/(1 + (i w tau)^a)^b */
  double c1, c2, tref;        /* WLF about tref */
} hn_model;

/* log10 a_T at temperature t (C). */
static inline double wlf(const hn_model *m, double t) {
  return -m->c1 * (t - m->tref) / (m->c2 + t - m->tref);
}

/* The complex modulus at angular frequency w at tref. */
static inline double complex hn(const hn_model *m, double w) {
  return m->einf + (m->e0 - m->einf) / cpow(1.0 + cpow(I * w * m->tau, m->a), m->b);
}

#endif
