/* The private part of viscolube/topography.h: the topography reader on a string and
 * the rms of a topography, for the import layer and the tests. */
#ifndef VISCOLUBE_TOPOGRAPHY_PRIVATE_H
#define VISCOLUBE_TOPOGRAPHY_PRIVATE_H

#include "viscolube/topography.h"

/* Reads text[0..len) (need not be NUL-terminated), named source in
 * messages. On VL_OK *out owns its arrays (release with vl_topography_free);
 * on failure *out is empty (safe to free) and err says why (see above). */
vl_status vl_topography_read_text(const char *text, size_t len, const char *source,
                                  vl_topography *out, vl_error *err);

/* rms height after removing the least-squares line (line scan) or plane
 * (map), in m; NAN for an empty topography. */
double vl_topography_hrms(const vl_topography *t);

#endif
