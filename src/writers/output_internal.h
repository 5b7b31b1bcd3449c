/* viscolube (private): the curve writers below their public part
 * (viscolube/output.h). Here: a curve's CSV to an open stream and one
 * point's JSON object (for output.c's own use and tests). */
#ifndef VISCOLUBE_OUTPUT_INTERNAL_H
#define VISCOLUBE_OUTPUT_INTERNAL_H

#include <stddef.h>
#include <stdio.h>

#include "viscolube/json.h"
#include "viscolube/output.h"
#include "viscolube/results.h"

/* The curve's CSV, as vl_write_curve_csv writes it, to out. */
void vl_print_curve_csv(FILE *out, size_t n, const vl_point *pts, const vl_curve_meta *meta);

/* A point as one JSON object with the keys of the CSV columns, on one line
 * (numbers with 10 significant digits, as in the CSV). */
void vl_point_json(vl_json *w, const vl_point *pt, const vl_curve_meta *meta);

#endif
