/* Compiled as if it were a file of the materials layer (with that layer's
 * include path): it names a header of the study layer above, which the
 * build must refuse ("file not found"). tests/CMakeLists.txt expects this
 * compile to fail; allowed.c, with the same flags, to succeed. */
#include "viscolube/scene.h"
