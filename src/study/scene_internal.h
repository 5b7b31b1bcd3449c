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

/* A ball or an ellipsoid built in code (the queries, query.c), with its
 * numerics from vl_scene_default_numerics: the checks a scene file's point
 * contact passes on what its keys set (point_contact_check: what a point
 * contact does not take yet, e.g. roughness or a fluid on an ellipsoid),
 * and the numerics they set (the point contact's tolerance, automatic
 * numerics), so that the scene is the one `run` would parse from the same
 * keys. VL_EINPUT with err "[section] key: why" (scene->path "", no file)
 * and *failed_key the key's name (e.g. "roughness"); else VL_OK and
 * *failed_key NULL. A cylinder: VL_OK, unchanged. */
vl_status vl_scene_check_point_contact(vl_scene *scene, const char **failed_key, vl_error *err);

#endif
