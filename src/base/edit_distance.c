/* Edit distance (edit_distance.h): three rolling rows of the dynamic
 * programme, the one before last for transpositions. */
#include "viscolube/edit_distance.h"

#include <stdint.h>
#include <string.h>

size_t vl_edit_distance(const char *a, size_t na, const char *b, size_t nb, bool transpositions) {
  if (na > VL_EDIT_MAX || nb > VL_EDIT_MAX) return SIZE_MAX;
  size_t rows[3][VL_EDIT_MAX + 1];
  size_t *before = rows[0], *prev = rows[1], *cur = rows[2];
  for (size_t j = 0; j <= nb; j++)
    prev[j] = j;
  for (size_t i = 1; i <= na; i++) {
    cur[0] = i;
    for (size_t j = 1; j <= nb; j++) {
      size_t best = prev[j - 1] + (a[i - 1] != b[j - 1]);
      if (prev[j] + 1 < best) best = prev[j] + 1;
      if (cur[j - 1] + 1 < best) best = cur[j - 1] + 1;
      if (transpositions && i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
          before[j - 2] + 1 < best)
        best = before[j - 2] + 1;
      cur[j] = best;
    }
    size_t *t = before;
    before = prev, prev = cur, cur = t;
  }
  return prev[nb];
}
