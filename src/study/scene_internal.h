/* viscolube (private): scenes below their public part (viscolube/scene.h):
 * the numerics a scene's effects imply, which scene.c fills in and
 * the queries (query.c) use. */
#ifndef VISCOLUBE_SCENE_INTERNAL_H
#define VISCOLUBE_SCENE_INTERNAL_H

#include "viscolube/scene.h"

/* The numerics a scene gets from its effects when it does not set them
 * (grid, grid_growth, domain, tolerance): the solver's defaults for its
 * roughness and fluid effects, vl_contact_numerics_defaults (dry as
 * vl_scene_defaults; wet with a long inlet, graded on a rough surface). */
void vl_scene_default_numerics(vl_scene *scene);

#endif
