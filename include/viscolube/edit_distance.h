/* viscolube: edit distance, for "did you mean" hints: the library's
 * readers (CSV, DMA, scene files) and name lookups use it, and so does the
 * program for its options. */
#ifndef VISCOLUBE_EDIT_DISTANCE_H
#define VISCOLUBE_EDIT_DISTANCE_H

#include <stdbool.h>
#include <stddef.h>

/* Longest string compared; longer ones are "far" (SIZE_MAX). */
#define VL_EDIT_MAX 64

/* Levenshtein distance of a[0..na) and b[0..nb) (insertions, deletions,
 * substitutions), with `transpositions` also counting a swap of two
 * neighbouring characters as one edit (optimal string alignment). SIZE_MAX
 * if either is longer than VL_EDIT_MAX. */
size_t vl_edit_distance(const char *a, size_t na, const char *b, size_t nb, bool transpositions);

#endif
