/* tests/t_lanes_run.h -- runs a test kernel over SIMD lanes on the device, as the renderer runs its kernels, for
 * the *_fp.c tests (float or double by IA_FP64): one work-item per group of PACKET_LANES queries, a which[] per
 * work-item, exact doubles in and doubles out. Stages of lanes_run:
 *   1. build the given sources with the interval options and IA_VW = PACKET_LANES;
 *   2. round the queries' inputs to the device's reals (box bounds outward: lower down, upper up);
 *   3. run `kernel(which, extra inputs..., in, out, scratch...)` with work-groups of one;
 *   4. read the outputs back as doubles. */
#ifndef IACSG_T_LANES_RUN_H
#define IACSG_T_LANES_RUN_H
#include "clrt.h"
#include "kernels/params.h"
#include "test.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LANES_MAX_BUFFERS 4
#ifdef IA_FP64
#define LANES_FP64 1
#else
#define LANES_FP64 0
#endif

typedef struct {
    const void *data;
    size_t bytes;
} lanes_buffer;

typedef struct {
    const char **sources; /* the program's sources */
    size_t nsources;
    const char *kernel;   /* its entry point */
    size_t items;         /* work-items; each runs PACKET_LANES queries */
    const int *which;     /* items of them: which case a work-item runs */
    lanes_buffer extra[LANES_MAX_BUFFERS]; /* read-only inputs between which and in */
    int nextra;
    const double *in;     /* in_per_query exact doubles a query */
    size_t in_per_query;
    size_t bounds_per_query; /* the first of them are box bounds in (lower, upper) pairs, rounded outward */
    double *out;          /* out_per_query a query */
    size_t out_per_query;
    size_t scratch_per_item[LANES_MAX_BUFFERS]; /* bytes of device scratch a work-item, after out */
    int nscratch;
} lanes_job;

static inline void lanes_run(const lanes_job *job) {
    clrt rt;
    iacsg_error err = {0};
    CHECK(clrt_open(&rt, 0, &err) == IACSG_OK, "%s", err.message);
    char options[512];
    CHECK(clrt_ia_options(&rt, LANES_FP64, 0, options, sizeof options - 32, &err) == IACSG_OK, "%s", err.message);
    snprintf(options + strlen(options), 32, " -D IA_VW=%d", PACKET_LANES);
    cl_program program;
    CHECK(clrt_build(&rt, job->sources, job->nsources, options, &program, &err) == IACSG_OK, "%s", err.message);
    size_t q = job->items * PACKET_LANES, real = LANES_FP64 ? sizeof(double) : sizeof(float);
    size_t in_bytes = job->in_per_query * q * real, out_bytes = job->out_per_query * q * real;
    void *host_in = malloc(in_bytes), *host_out = malloc(out_bytes);
    CHECK(host_in && host_out, "out of memory");
    for (size_t i = 0; i < job->in_per_query * q; i++) {
        size_t k = i % job->in_per_query;
        float f = (float)job->in[i]; /* a box's lower bounds down, upper bounds up; the rest to nearest */
        if (k < job->bounds_per_query && (k % 2 == 0 ? (double)f > job->in[i] : (double)f < job->in[i]))
            f = nextafterf(f, k % 2 == 0 ? -INFINITY : INFINITY);
        if (LANES_FP64)
            ((double *)host_in)[i] = job->in[i];
        else
            ((float *)host_in)[i] = f;
    }
    cl_int rc = CL_SUCCESS;
    cl_kernel k = clCreateKernel(program, job->kernel, &rc);
    CHECK(rc == CL_SUCCESS, "kernel %s: %s", job->kernel, clrt_error_name(rc));
    cl_mem args[2 * LANES_MAX_BUFFERS + 3];
    int nargs = 0;
    args[nargs++] = clCreateBuffer(rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, job->items * sizeof(int),
                                   (void *)job->which, &rc);
    for (int e = 0; e < job->nextra && rc == CL_SUCCESS; e++)
        args[nargs++] = clCreateBuffer(rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, job->extra[e].bytes,
                                       (void *)job->extra[e].data, &rc);
    int out_arg = nargs + 1;
    if (rc == CL_SUCCESS)
        args[nargs++] = clCreateBuffer(rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, in_bytes, host_in, &rc);
    if (rc == CL_SUCCESS)
        args[nargs++] = clCreateBuffer(rt.context, CL_MEM_WRITE_ONLY, out_bytes, NULL, &rc);
    for (int s = 0; s < job->nscratch && rc == CL_SUCCESS; s++)
        args[nargs++] = clCreateBuffer(rt.context, CL_MEM_READ_WRITE, job->items * job->scratch_per_item[s], NULL, &rc);
    CHECK(rc == CL_SUCCESS, "buffers: %s", clrt_error_name(rc));
    for (cl_uint a = 0; a < (cl_uint)nargs; a++)
        clSetKernelArg(k, a, sizeof(cl_mem), &args[a]);
    size_t one = 1; /* as the renderer: PoCL keeps a work-group's private arrays on one thread's stack */
    size_t items = job->items;
    rc = clEnqueueNDRangeKernel(rt.queue, k, 1, NULL, &items, &one, 0, NULL, NULL);
    if (rc == CL_SUCCESS)
        rc = clEnqueueReadBuffer(rt.queue, args[out_arg], CL_TRUE, 0, out_bytes, host_out, 0, NULL, NULL);
    for (size_t i = 0; i < job->out_per_query * q; i++)
        job->out[i] = LANES_FP64 ? ((double *)host_out)[i] : ((float *)host_out)[i];
    for (int a = 0; a < nargs; a++)
        clReleaseMemObject(args[a]);
    clReleaseKernel(k);
    clReleaseProgram(program);
    clrt_close(&rt);
    free(host_in);
    free(host_out);
    CHECK(rc == CL_SUCCESS, "run: %s", clrt_error_name(rc));
}

/* head, cases and tail joined (the test's kernel source, freed by the caller). */
static inline char *lanes_kernel_source(const char *head, const char *cases, const char *tail) {
    size_t len = strlen(head) + strlen(cases) + strlen(tail) + 1;
    char *kernel = malloc(len);
    CHECK(kernel != NULL, "out of memory");
    snprintf(kernel, len, "%s%s%s", head, cases, tail);
    return kernel;
}

#endif
