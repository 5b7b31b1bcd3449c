/* The segment of a sorted table that holds a value (bracket.h). */
#include "bracket.h"

size_t vl_bracket(const double *x, size_t n, double v) {
  size_t lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    size_t mid = lo + (hi - lo) / 2;
    if (x[mid] <= v)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}
