/* src/iacsg.h -- the public library header of iacsg: compile an implicit expression or scene, render it with
 * interval arithmetic on an OpenCL device, write images. examples/embed.c shows the whole use.
 *
 *   iacsg_expr_parse / iacsg_expr_destroy            implicits/expr.h   text -> compiled expression
 *   iacsg_scene_parse / iacsg_scene_destroy          implicits/scene.h  scene text -> solids, regions, surfaces
 *   iacsg_renderer_create_expr / _destroy            src/render.h       expression -> device program
 *   iacsg_renderer_create_scene                      src/render.h       scene -> device program (either path)
 *   iacsg_render / iacsg_frame_free                  src/render.h       one view at one time -> images in memory
 *   iacsg_image_write                                src/image.h        images -> files
 *
 * Every function returns an iacsg_status and fills an iacsg_error (src/error.h); none prints or exits. Every
 * create has its destroy; strings returned through char ** are the caller's to free().
 */
#ifndef IACSG_H
#define IACSG_H
#include "camera.h"
#include "error.h"
#include "image.h"
#include "implicits/expr.h"
#include "implicits/scene.h"
#include "render.h"

#define IACSG_VERSION "0.1.0"

#endif
