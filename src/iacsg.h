/* src/iacsg.h -- the public library header of iacsg, installed as <iacsg/iacsg.h>: compile an implicit
 * expression or scene, render it with interval arithmetic on an OpenCL device, write images.
 * examples/embed.c shows the whole use.
 *
 *   iacsg_expr_parse / iacsg_expr_destroy            implicits/expr.h   text -> compiled expression
 *   iacsg_expr_bounds                                implicits/expr.h   expression, times -> a box proven to hold it
 *   iacsg_scene_parse / iacsg_scene_destroy          implicits/scene_api.h  scene text -> regions, surfaces
 *   iacsg_renderer_create_expr / _destroy            src/render.h       expression -> device program
 *   iacsg_renderer_create_scene                      src/render.h       scene -> device program (either path)
 *   iacsg_render / iacsg_frame_free                  src/render.h       one view at one time -> images in memory
 *   iacsg_image_write                                src/image.h        images -> files
 *
 * Every function returns an iacsg_status and fills an iacsg_error (src/error.h); none prints or exits. The
 * handles (iacsg_expr, iacsg_renderer) are opaque: each create has its destroy, which accepts NULL. Each
 * declaration says who owns what it returns; strings returned through char ** are the caller's to free().
 *
 * The public headers are the files of PUBLIC_HEADERS in the Makefile, installed flat under include/iacsg/
 * (src/tools/public_headers.sh reduces their quoted includes of one another to file names). A new public
 * header: add it there and include it here; its declarations go between IACSG_API_BEGIN and IACSG_API_END.
 */
#ifndef IACSG_H
#define IACSG_H
#include "camera.h"
#include "error.h"
#include "image.h"
#include "implicits/expr.h"
#include "implicits/scene_api.h"
#include "render.h"

IACSG_API_BEGIN

/* The version of these headers (the Makefile reads it from here: libiacsg.so.MAJOR is the library's SONAME). */
#define IACSG_VERSION_MAJOR 0
#define IACSG_VERSION_MINOR 1
#define IACSG_VERSION_PATCH 0
#define IACSG_VERSION "0.1.0"

/* The version of the library linked at run time, "MAJOR.MINOR.PATCH" (a static string, not to be freed): it
 * may be newer than IACSG_VERSION where the shared library was updated after the program was compiled. */
const char *iacsg_version(void);

IACSG_API_END
#endif
