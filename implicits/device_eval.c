/* implicits/device_eval.c -- see device_eval.h. The kernel is generated here: a switch over the expressions,
 * each emitted with the prefix e<k>. */
#include "device_eval.h"
#include "ia/flush.h"
#include "strbuf.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LOCAL_SIZE 16

extern const char iacsg_cl_ia[]; /* the flattened ia/ headers (Makefile: IA_CL_HEADERS) */

static const char kernel_head[] =
    "__kernel void iacsg_eval_queries(__global const int *which, __global const ia_real *in,\n"
    "                                 __global ia_real *out, uint n) {\n"
    "    size_t i = get_global_id(0);\n"
    "    if (i >= n)\n"
    "        return;\n"
    "    __global const ia_real *v = in + 8 * i;\n"
    "    ia_interval x = ia_make(v[0], v[1]), y = ia_make(v[2], v[3]), z = ia_make(v[4], v[5]);\n"
    "    ia_interval t = ia_make(v[6], v[7]);\n"
    "    ia_interval r = ia_empty();\n"
    "    ia_real f = 0, gx = 0, gy = 0, gz = 0;\n"
    "    switch (which[i]) {\n";
static const char kernel_tail[] = "    }\n"
                                  "    __global ia_real *o = out + 6 * i;\n"
                                  "    o[0] = r.lo; o[1] = r.hi; o[2] = f; o[3] = gx; o[4] = gy; o[5] = gz;\n"
                                  "}\n";

static char *program_source(const iacsg_expr *const *exprs, int nexprs, iacsg_error *err) {
    strbuf b = {0};
    for (int k = 0; k < nexprs; k++) {
        char prefix[32], *src;
        snprintf(prefix, sizeof prefix, "e%d", k);
        if (iacsg_expr_emit_cl(exprs[k], prefix, &src, err) != IACSG_OK) {
            free(strbuf_finish(&b));
            return NULL;
        }
        strbuf_printf(&b, "%s", src);
        free(src);
    }
    strbuf_printf(&b, "%s", kernel_head);
    for (int k = 0; k < nexprs; k++)
        strbuf_printf(&b, "    case %d: r = e%d_F(x, y, z, t); f = e%d_f_grad(v[0], v[2], v[4], v[6], &gx, &gy, &gz); "
                          "break;\n",
                      k, k, k);
    strbuf_printf(&b, "%s", kernel_tail);
    char *s = strbuf_finish(&b);
    if (!s)
        iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory");
    return s;
}

/* Outward rounding of box bounds to float (even positions are lower bounds), out of the subnormals too. */
static float to_float(double v, int down) {
    float f = (float)v;
    if (down && (double)f > v)
        f = nextafterf(f, -INFINITY);
    if (!down && (double)f < v)
        f = nextafterf(f, INFINITY);
    return down ? ia_flush_lo_f(f) : ia_flush_hi_f(f);
}

iacsg_status device_eval(clrt *rt, const iacsg_expr *const *exprs, int nexprs, int fp64, size_t n,
                         const int *which, const double *in, double *out, iacsg_error *err) {
    iacsg_error local;
    if (!err)
        err = &local;
    char options[512];
    cl_program program = NULL;
    cl_kernel kernel = NULL;
    cl_mem bufs[3] = {NULL, NULL, NULL};
    cl_int rc = CL_SUCCESS;
    size_t real = fp64 ? sizeof(double) : sizeof(float);
    cl_uint count = (cl_uint)n;
    void *host_in = malloc(DEVICE_EVAL_IN * n * real), *host_out = malloc(DEVICE_EVAL_OUT * n * real);
    char *src = program_source(exprs, nexprs, err);
    iacsg_status st = IACSG_ERR_OPENCL;
    if (!host_in || !host_out || !src) {
        st = src ? iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory") : err->status;
        goto done;
    }
    for (size_t i = 0; i < DEVICE_EVAL_IN * n; i++) {
        if (fp64)
            ((double *)host_in)[i] = i % 2 == 0 ? ia_flush_lo_d(in[i]) : ia_flush_hi_d(in[i]);
        else /* the corner x0, y0, z0, t0 is also the point: round it down with the box */
            ((float *)host_in)[i] = to_float(in[i], i % 2 == 0);
    }
    if ((st = clrt_ia_options(rt, fp64, 0, options, sizeof options, err)) != IACSG_OK)
        goto done;
    const char *sources[] = {iacsg_cl_ia, src};
    if ((st = clrt_build(rt, sources, 2, options, &program, err)) != IACSG_OK)
        goto done;
    st = IACSG_ERR_OPENCL;
    kernel = clCreateKernel(program, "iacsg_eval_queries", &rc);
    CLRT_CHECK(err, rc);
    bufs[0] = clCreateBuffer(rt->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * sizeof(int), (void *)which,
                             &rc);
    CLRT_CHECK(err, rc);
    bufs[1] = clCreateBuffer(rt->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, DEVICE_EVAL_IN * n * real, host_in,
                             &rc);
    CLRT_CHECK(err, rc);
    bufs[2] = clCreateBuffer(rt->context, CL_MEM_WRITE_ONLY, DEVICE_EVAL_OUT * n * real, NULL, &rc);
    CLRT_CHECK(err, rc);
    for (cl_uint k = 0; k < 3; k++)
        CLRT_CHECK(err, clSetKernelArg(kernel, k, sizeof(cl_mem), &bufs[k]));
    CLRT_CHECK(err, clSetKernelArg(kernel, 3, sizeof(cl_uint), &count));
    /* A small explicit work-group: left to itself PoCL groups thousands of work-items, and a kernel with many
     * expressions inlined then overflows its thread's stack. */
    size_t group = LOCAL_SIZE, global = (n + LOCAL_SIZE - 1) / LOCAL_SIZE * LOCAL_SIZE;
    CLRT_CHECK(err, clEnqueueNDRangeKernel(rt->queue, kernel, 1, NULL, &global, &group, 0, NULL, NULL));
    CLRT_CHECK(err, clEnqueueReadBuffer(rt->queue, bufs[2], CL_TRUE, 0, DEVICE_EVAL_OUT * n * real, host_out, 0, NULL,
                                        NULL));
    for (size_t i = 0; i < DEVICE_EVAL_OUT * n; i++)
        out[i] = fp64 ? ((double *)host_out)[i] : ((float *)host_out)[i];
    st = IACSG_OK;
fail:
done:
    for (int k = 0; k < 3; k++)
        if (bufs[k])
            clReleaseMemObject(bufs[k]);
    if (kernel)
        clReleaseKernel(kernel);
    if (program)
        clReleaseProgram(program);
    free(host_in);
    free(host_out);
    free(src);
    return st;
}
