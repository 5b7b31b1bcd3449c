/* viscolube (private): the segment of a sorted table that holds a value. */
#ifndef VISCOLUBE_BRACKET_H
#define VISCOLUBE_BRACKET_H

#include <stddef.h>

/* The index k of the segment [x[k], x[k+1]] of the increasing x[0..n-1]
 * (n >= 2) that holds v, by bisection: k = 0 for v below x[1], n - 2 for v
 * at or above x[n-2]. Tables, layouts and interpolants share it. */
size_t vl_bracket(const double *x, size_t n, double v);

#endif
