/* implicits/scene_api.h -- a scene as the public API sees it: an opaque handle made from a scene file's text,
 * which iacsg_renderer_create_scene (src/render.h) renders. implicits/scene.h has its structure, for the front
 * ends and the renderer. */
#ifndef IACSG_SCENE_API_H
#define IACSG_SCENE_API_H
#include "error.h"

IACSG_API_BEGIN

typedef struct iacsg_scene iacsg_scene;

/* Parses a scene file's text or an expression (name is used in messages). On failure *out is NULL and err holds
 * the message, line and column. Destroy with iacsg_scene_destroy (which accepts NULL). */
iacsg_status iacsg_scene_parse(const char *text, const char *name, iacsg_scene **out, iacsg_error *err);
void iacsg_scene_destroy(iacsg_scene *s);

/* 1 if some solid of the scene, or its expression, depends on the time t. */
int iacsg_scene_uses_time(const iacsg_scene *s);

IACSG_API_END

#endif
