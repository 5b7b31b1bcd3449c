/* The control of upward.c: the same flags, a header of the layer itself and
 * one of the layer below (base): this compile must succeed. */
#include "slurp.h"
#include "viscolube/rheology.h"
#include "viscolube/status.h"
