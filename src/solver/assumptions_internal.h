/* viscolube (private): the checks of the model's assumptions (the
 * assumptions and their thresholds are described with vl_assumption in
 * viscolube/assumptions.h). A simulation runs them on every point
 * (src/study/simulation.c); tests call them directly. */
#ifndef VISCOLUBE_ASSUMPTIONS_INTERNAL_H
#define VISCOLUBE_ASSUMPTIONS_INTERNAL_H

#include <stddef.h>

#include "viscolube/assumptions.h"
#include "viscolube/contact.h"
#include "viscolube/persson.h"

/* Appends the warning w to the ';'-separated warnings (capacity cap) as
 * the checks below do: not repeated, left out when it does not fit whole.
 * w holds no commas, quotes or ';'. */
void vl_warnings_append(char *warnings, size_t cap, const char *w);

/* Checks the point pt, solved with configuration cfg, against the
 * assumptions of vl_assumption. psd is the surface behind cfg->roughness, or NULL
 * (smooth, or not at hand: the rms slope then comes from the Persson table,
 * 8 vl_persson_g = 2 pi \int q^3 C dq, and the homogenisation check, which
 * needs q0, is skipped). Appends one short warning per violated assumption
 * to the NUL-terminated string warnings (capacity cap bytes, may already
 * hold warnings), ';'-separated as vl_point.warnings; a warning already
 * present is not repeated, and one that does not fit whole is left out
 * (never cut). Warnings hold no commas or quotes (they go into CSV and
 * JSON columns). warnings may be pt->warnings. Returns the mask of violated
 * assumptions (vl_assumption bits), including any left out for space. */
unsigned vl_assumptions_check(const vl_contact_config *cfg, const vl_psd *psd, const vl_point *pt,
                              char *warnings, size_t cap);

/* The frequencies at which the sliding point pt excites the rubber against
 * the measured window [omega_min_rad_s, omega_max_rad_s] of its compound's
 * master curve, at the temperature the contact uses: the asperity
 * frequencies v0 q over the surface's wavevectors q0..q1 (psd; none when
 * NULL) and the contact frequency v0/a, a half the contact width of a
 * converged point, else the Hertz-like a_H of vl_asperity_state. Each that
 * lies more than a decade outside the window (a factor VL_WINDOW_MARGIN)
 * appends one warning as vl_assumptions_check does. Nothing for v0 <= 0 or
 * an invalid window (a Prony series not fitted to data). Returns
 * VL_ASSUME_MEASURED_WINDOW when it warned, else 0. */
#define VL_WINDOW_MARGIN 10.0
unsigned vl_assumptions_check_window(const vl_contact_config *cfg, const vl_psd *psd,
                                     const vl_point *pt, double omega_min_rad_s,
                                     double omega_max_rad_s, char *warnings, size_t cap);

/* "rms slope", "homogenisation", ... : a short name for one bit (for
 * summaries); "unknown" for anything else. */
const char *vl_assumption_name(unsigned bit);

#endif
