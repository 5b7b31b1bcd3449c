/* An independent viscoelastic model for the import tests: a
 * Havriliak-Negami modulus E = Einf + (E0 - Einf)/(1 + (i w tau)^a)^b with
 * WLF time-temperature shifts, from which isotherms and master curves are
 * written as a user's DMA export would hold them. */
#ifndef VL_TEST_HN_H
#define VL_TEST_HN_H

#include <complex.h>
#include <math.h>

#include "viscolube/rheology.h"

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

/* Largest relative difference of E' and E'' of two Prony series over
 * [wlo, whi] (61 log-spaced frequencies): how far two imports of the same
 * data disagree. */
static inline double series_diff(const vl_prony *p, const vl_prony *q, double wlo, double whi) {
  double d = 0.0;
  for (int k = 0; k <= 60; k++) {
    double w = wlo * pow(whi / wlo, k / 60.0);
    double complex a = vl_prony_modulus(p, w), b = vl_prony_modulus(q, w);
    d = fmax(d, fabs(creal(a) / creal(b) - 1.0));
    d = fmax(d, fabs(cimag(a) / cimag(b) - 1.0));
  }
  return d;
}

#endif
