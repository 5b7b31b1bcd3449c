/* The seed's fig05 contact for the tests (docs/CASES.md), implemented in
 * vl_test_util.c; a header of its own so that tests which do not need the
 * library's contact headers (and their <complex.h>) do not get them. */
#ifndef VL_TEST_SCENES_H
#define VL_TEST_SCENES_H

#include <stddef.h>

#include "viscolube/contact.h"
#include "viscolube/persson.h"

/* ---- the seed's fig05 contact (docs/CASES.md) -------------------------------- */

/* The seed's paper surface: self-affine, H 0.8, q0 2e5 1/m, q1 7.8e9 1/m,
 * of rms roughness hrms_m. Fills *psd and returns its Persson table of the
 * default size; fails the test on error. The caller frees both. */
vl_persson *vl_test_paper_surface(double hrms_m, vl_psd *psd);

/* The contact of fig05 (and fig10, fig12 with other viscosities): the
 * model rubber (E0 3.6 MPa, Einf/E0 10, tau 0.1 s, nu 0.5), R 1 cm, fN
 * 1 kN/m, sigma_s 1 MPa, the roughness table tab, viscosity eta_pa_s,
 * Patir-Cheng flow factors, grid cells on [x_min_a0, 1.6] a0; the rest as
 * vl_contact_config_defaults. */
void vl_test_fig05_config(vl_contact_config *cfg, const vl_persson *tab, double eta_pa_s,
                          size_t grid, double x_min_a0);

#endif
