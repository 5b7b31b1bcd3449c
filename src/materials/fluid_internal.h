/* viscolube (private): viscosity laws below their public part
 * (viscolube/fluid.h: the law, its name and the viscosity at a
 * temperature). Here: reading a law's stored name and checking a law (for
 * the database and tests). */
#ifndef VISCOLUBE_FLUID_INTERNAL_H
#define VISCOLUBE_FLUID_INTERNAL_H

#include "viscolube/fluid.h"
#include "viscolube/status.h"

/* The kind named by name ("vogel"); VL_EINPUT for any other name. */
vl_status vl_viscosity_law_parse(const char *name, vl_viscosity_law_kind *kind, vl_error *err);

/* Checks a law together with the reference temperature of the fluid it
 * belongs to: NONE is always valid; VOGEL needs finite B > 0, C >= 0 K,
 * tmin < tmax, tmin + 273.15 > C (the law finite over its range) and
 * tref_c inside [tmin, tmax] (the anchor is one of its data).
 * VL_EINPUT naming the first bad field. */
vl_status vl_viscosity_law_validate(const vl_viscosity_law *law, double tref_c, vl_error *err);

#endif
