/* src/render_expr.c -- a renderer for an expression on the first-root path, in one of two programs:
 *   compiled:    the compiler's OpenCL C with the prefix the kernels call (iacsg_Fv, iacsg_Fdv, iacsg_f_grad);
 *   interpreted: the tape interpreter (implicits/tape_cl.c, kernels/tape_eval.h), the same source for every
 *                expression, so PoCL builds it once and finds it in its cache after, and the expression's tape
 *                (implicits/tape.h) in a buffer, the kernel's last argument.
 * Which: config->tape; by default the interpreter from IACSG_TAPE_MIN_NODES operations on, where the compile
 * of the expression's own code costs seconds (a union of 1024 spheres, 3419 operations: 4.6 s) and the
 * interpreter's per-part boxes also skip most of a large union's parts per evaluation; and for unions of
 * IACSG_TAPE_MIN_PARTS parts or more, whose parts may share most of their operations (spheres on a grid share their
 * (x - c)^2): a grid of 128 spheres, 461 operations, builds in 6.0 s compiled against 0.01 s as a tape, and the
 * tape renders it as fast (reference camera, 1024x1024, eps 1e-5: 261 against 248 ms; 256 spheres, 9.0 s of
 * build, 464 against 357 ms; 64, 244 against 298 ms, stay compiled). */
#include "render_internal.h"
#include "implicits/emit.h"
#include "implicits/expr_internal.h"
#include "implicits/tape.h"
#include <stdio.h>
#include <stdlib.h>

extern const char iacsg_cl_tape_kernels[]; /* the first-root kernels for a tape (Makefile: TAPE_KERNEL_SOURCES) */

/* The interpreted renderer, or IACSG_ERR_LIMIT (err set) when the tape cannot hold the expression. */
static iacsg_status create_interpreted(const iacsg_expr *e, const iacsg_render_config *config,
                                       iacsg_renderer **out, iacsg_error *err) {
    iacsg_tape tape;
    double t0 = render_now_seconds();
    iacsg_status st = tape_build(&e->simple, e->root, config->fp64, &tape, err);
    double tape_seconds = render_now_seconds() - t0;
    if (st != IACSG_OK)
        return st;
    char *interpreter = tape_cl();
    st = interpreter ? render_create_first_root(interpreter, iacsg_cl_tape_kernels, config, out, err)
                     : iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory generating code");
    if (st == IACSG_OK) {
        iacsg_renderer *r = *out;
        r->build_seconds += tape_seconds; /* counted in the build (the compiled path does not count its emit) */
        cl_int rc = CL_SUCCESS;
        r->tape = clCreateBuffer(r->rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                 tape.count * sizeof(unsigned), tape.words, &rc);
        snprintf(r->program_note, sizeof r->program_note,
                 "interpreted (tape: %d parts in %d groups, %d instructions, %d registers, %d parts boxed%s)",
                 tape.parts, tape.groups, tape.instructions, tape.max_slots, tape.bounded_parts,
                 tape.newton ? ", Newton" : "");
        if (rc != CL_SUCCESS) {
            st = iacsg_error_set(err, IACSG_ERR_OPENCL, 0, 0, "the tape's buffer (%zu bytes): OpenCL error %d",
                                 tape.count * sizeof(unsigned), (int)rc);
            iacsg_renderer_destroy(r);
            *out = NULL;
        }
    }
    free(interpreter);
    tape_free(&tape);
    return st;
}

/* The number of parts of the expression's union (0 where its root is no union). */
static int union_parts(const iacsg_expr *e) {
    int *parts, n = emit_union_parts(&e->simple, e->root, &parts);
    free(parts);
    return n;
}

iacsg_status iacsg_renderer_create_expr(const iacsg_expr *e, const iacsg_render_config *config,
                                        iacsg_renderer **out, iacsg_error *err) {
    char *source = NULL, why[120] = "";
    *out = NULL;
    int min_nodes = config->tape_min_nodes > 0 ? config->tape_min_nodes : IACSG_TAPE_MIN_NODES;
    if (config->tape == IACSG_TAPE_ALWAYS ||
        (config->tape == IACSG_TAPE_AUTO && (e->count >= min_nodes || union_parts(e) >= IACSG_TAPE_MIN_PARTS))) {
        iacsg_status st = create_interpreted(e, config, out, err);
        if (st != IACSG_ERR_LIMIT || config->tape == IACSG_TAPE_ALWAYS)
            return st;
        snprintf(why, sizeof why, "compiled (%.100s)", err->message); /* the interpreter cannot hold it */
    }
    iacsg_status st = iacsg_expr_emit_cl(e, "iacsg", &source, err);
    if (st == IACSG_OK)
        st = iacsg_renderer_create(source, config, out, err);
    if (st == IACSG_OK)
        snprintf((*out)->program_note, sizeof (*out)->program_note, "%.119s", why);
    free(source);
    return st;
}
