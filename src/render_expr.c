/* src/render_expr.c -- a renderer for a compiled expression: the compiler's OpenCL C, with the prefix the
 * kernels call (iacsg_Fv, iacsg_Fdv, iacsg_f_grad), built by iacsg_renderer_create. */
#include "render.h"
#include <stdlib.h>

iacsg_status iacsg_renderer_create_expr(const iacsg_expr *e, const iacsg_render_config *config,
                                        iacsg_renderer **out, iacsg_error *err) {
    char *source = NULL;
    *out = NULL;
    iacsg_status st = iacsg_expr_emit_cl(e, "iacsg", &source, err);
    if (st == IACSG_OK)
        st = iacsg_renderer_create(source, config, out, err);
    free(source);
    return st;
}
