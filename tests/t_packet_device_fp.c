/* tests/t_packet_device_fp.c -- the SIMD kernels' set-up and walk (kernels/packet.h) against their scalar
 * originals (camera.h, traverse.h), on the device, lane by lane and bit for bit: the camera rays, the clip to the
 * bounds, the first node, the ray boxes, the node ends and the step of the walk. The render tests check the
 * images against exact roots; this checks that each lane does exactly what the scalar code the host tests check
 * (t_render_traverse_fp.c, t_render_tile_fp.c) does. A negative control (a box one t-ulp off) must be seen. */
#include "clrt.h"
#include "implicits/expr.h"
#include "kernels/params.h"
#include "src/camera.h"
#include "test.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef IA_FP64
#define TWIN_FP64 1
typedef double real;
#else
#define TWIN_FP64 0
typedef float real;
#endif

extern const char iacsg_cl_ia[], iacsg_cl_kernels[];

/* Counts per work-item, in out[6g .. 6g+5]: mismatches in rays, clip, first node, boxes and node ends, walk
 * steps; and the negative control's differences. Random inputs from a per-work-item xorshift. (Two strings:
 * C compilers need not take a literal over 4095 characters.) */
static const char *const checks_cl[2] = {
    "static inline uint next_u(uint *s) { *s ^= *s << 13; *s ^= *s >> 17; *s ^= *s << 5; return *s; }\n"
    "static inline ia_real unit(uint *s) { return (ia_real)(next_u(s) >> 8) * (ia_real)0x1p-24; }\n"
    "#ifdef IA_FP64\n#define BITS(x) as_ulong(x)\n#else\n#define BITS(x) as_uint(x)\n#endif\n"
    "__kernel void packet_checks(__constant ia_real *p, int width, int height, __global const uint *seeds,\n"
    "                            __global uint *out) {\n"
    "    size_t g = get_global_id(0);\n"
    "    uint s = seeds[g] | 1u, bad_ray = 0, bad_clip = 0, bad_node = 0, bad_box = 0, bad_step = 0, control = 0;\n"
    "    int ortho = (int)(next_u(&s) & 1), i0 = (int)(next_u(&s) % (uint)width);\n"
    "    int j0 = (int)(next_u(&s) % (uint)height);\n"
    "    packet_int lanes = packet_lane_numbers(), col = i0 + lanes % PACKET_W, row = j0 + lanes / PACKET_W;\n"
    "    ia_realv ov[3], dv[3], tn, tf;\n"
    "    packet_rays(p, ortho, min(col, width - 1), min(row, height - 1), width, height, ov, dv);\n"
    "    ia_maskv meets = packet_clip(p, ov, dv, &tn, &tf);\n"
    "    ia_real t0, w;\n"
    "    frame_root(p, &t0, &w);\n"
    "    int level = (int)(next_u(&s) % 16);\n"
    "    packet_index first = packet_node_at(t0, w, level, tn);\n"
    "    ia_real o[3][IA_VW], d[3][IA_VW], n_lo[IA_VW], n_hi[IA_VW], m[IA_VW];\n"
    "    bisect_index f[IA_VW];\n"
    "    for (int c = 0; c < 3; c++) {\n"
    "        IAV_STORE(ov[c], o[c]);\n"
    "        IAV_STORE(dv[c], d[c]);\n"
    "    }\n"
    "    IAV_STORE(tn, n_lo);\n"
    "    IAV_STORE(tf, n_hi);\n"
    "    IAV_STORE(select(IAV_R(0), IAV_R(1), meets), m);\n"
    "    IAV_STORE(first, f);\n"
    "    for (int k = 0; k < IA_VW; k++) {\n"
    "        ia_real os[3], ds[3], a, b;\n"
    "        camera_ray(p, ortho, min(i0 + k % PACKET_W, width - 1), min(j0 + k / PACKET_W, height - 1), width,\n"
    "                   height, os, ds);\n"
    "        for (int c = 0; c < 3; c++)\n"
    "            bad_ray += BITS(os[c]) != BITS(o[c][k]) || BITS(ds[c]) != BITS(d[c][k]);\n"
    "        int hit = camera_clip(p, os, ds, &a, &b);\n"
    "        bad_clip += hit != (m[k] != 0) || (hit && (BITS(a) != BITS(n_lo[k]) || BITS(b) != BITS(n_hi[k])));\n"
    "        if (hit)\n"
    "            bad_node += node_at(t0, w, level, a) != f[k];\n"
    "    }\n"
    ,
    "    /* boxes and node ends at random nodes; one step of the walk from them */\n"
    "    bisect_index idx[IA_VW];\n"
    "    int lv[IA_VW];\n"
    "    ia_real down_r[IA_VW], live_r[IA_VW];\n"
    "    for (int k = 0; k < IA_VW; k++) {\n"
    "        lv[k] = 1 + (int)(next_u(&s) % 20);\n"
    "        idx[k] = (bisect_index)(next_u(&s) & ((1u << lv[k]) - 1));\n"
    "        down_r[k] = (ia_real)(next_u(&s) & 1);\n"
    "        live_r[k] = (ia_real)((next_u(&s) & 7) != 0);\n"
    "    }\n"
    "    packet_int level_v = packet_to_int(IAV_CAT(vload, IA_VW)(0, lv));\n"
    "    packet_index i_v = IAV_LOAD(idx);\n"
    "    ia_realv lo = packet_node_bound(t0, w, level_v, i_v), hi = packet_node_bound(t0, w, level_v, i_v + 1);\n"
    "    iav t = iav_make(lo, hi);\n"
    "    iav box[3];\n"
    "    for (int c = 0; c < 3; c++)\n"
    "        box[c] = packet_extent(ov[c], dv[c], t);\n"
    "    ia_maskv searching = IAV_LOAD(live_r) != 0, down = searching & (IAV_LOAD(down_r) != 0);\n"
    "    packet_advance(&searching, down, &level_v, &i_v);\n"
    "    ia_real lo_a[IA_VW], hi_a[IA_VW], bl[3][IA_VW], bh[3][IA_VW], after[IA_VW];\n"
    "    int lv2[IA_VW];\n"
    "    bisect_index idx2[IA_VW];\n"
    "    IAV_STORE(lo, lo_a);\n"
    "    IAV_STORE(hi, hi_a);\n"
    "    for (int c = 0; c < 3; c++) {\n"
    "        IAV_STORE(box[c].lo, bl[c]);\n"
    "        IAV_STORE(box[c].hi, bh[c]);\n"
    "    }\n"
    "    IAV_STORE(select(IAV_R(0), IAV_R(1), searching), after);\n"
    "    IAV_CAT(vstore, IA_VW)(IAV_CAT(convert_int, IA_VW)(level_v), 0, lv2);\n"
    "    IAV_STORE(i_v, idx2);\n"
    "    for (int k = 0; k < IA_VW; k++) {\n"
    "        ia_real a = node_bound(t0, w, lv[k], idx[k]), b = node_bound(t0, w, lv[k], idx[k] + 1);\n"
    "        bad_box += BITS(a) != BITS(lo_a[k]) || BITS(b) != BITS(hi_a[k]);\n"
    "        ia_interval tk = ia_make(a, b), tk_off = ia_make(nextafter(a, (ia_real)INFINITY), b);\n"
    "        for (int c = 0; c < 3; c++) {\n"
    "            ia_interval x = ray_extent(o[c][k], d[c][k], tk), y = ray_extent(o[c][k], d[c][k], tk_off);\n"
    "            bad_box += BITS(x.lo) != BITS(bl[c][k]) || BITS(x.hi) != BITS(bh[c][k]);\n"
    "            control += BITS(y.lo) != BITS(bl[c][k]) || BITS(y.hi) != BITS(bh[c][k]);\n"
    "        }\n"
    "        int level_k = lv[k], still = live_r[k] != 0;\n"
    "        bisect_index i_k = idx[k];\n"
    "        if (still && down_r[k] != 0) {\n"
    "            level_k += 1;\n"
    "            i_k <<= 1;\n"
    "        } else if (still) {\n"
    "            still = node_next(&level_k, &i_k);\n"
    "        }\n"
    "        bad_step += (still != (after[k] != 0)) || (live_r[k] != 0 && (level_k != lv2[k] || i_k != idx2[k]));\n"
    "    }\n"
    "    out[6 * g] = bad_ray;\n"
    "    out[6 * g + 1] = bad_clip;\n"
    "    out[6 * g + 2] = bad_node;\n"
    "    out[6 * g + 3] = bad_box;\n"
    "    out[6 * g + 4] = bad_step;\n"
    "    out[6 * g + 5] = control;\n"
    "}\n"};

TEST_FP(packet_lanes_match_scalar_walk) {
    clrt rt;
    iacsg_error err = {0};
    CHECK(clrt_open(&rt, 0, &err) == IACSG_OK, "%s", err.message);
    iacsg_expr *e = NULL;
    char *expr_cl = NULL;
    CHECK(iacsg_expr_parse("x^2 + y^2 + z^2 - 1", "<test>", &e, &err) == IACSG_OK, "%s", err.message);
    CHECK(iacsg_expr_emit_cl(e, "iacsg", &expr_cl, &err) == IACSG_OK, "%s", err.message);
    iacsg_expr_destroy(e);
    char options[512];
    CHECK(clrt_ia_options(&rt, TWIN_FP64, 0, options, sizeof options - 32, &err) == IACSG_OK, "%s", err.message);
    snprintf(options + strlen(options), 32, " -D IA_VW=%d", PACKET_LANES);
    const char *sources[] = {iacsg_cl_ia, expr_cl, iacsg_cl_kernels, checks_cl[0], checks_cl[1]};
    cl_program program;
    iacsg_status st = clrt_build(&rt, sources, 5, options, &program, &err);
    free(expr_cl);
    CHECK(st == IACSG_OK, "%s", err.message);

    /* a perspective view and an orthographic one share the block; each work-item picks one */
    iacsg_camera cam = {.eye = {0.3, -4, 2.5}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40, .ortho_height = 0};
    int width = 257, height = 131; /* odd sizes: packets cross the image's edges */
    double pd[PARAM_COUNT] = {0};
    CHECK(iacsg_camera_params(&cam, width, height, pd, &err) == IACSG_OK, "%s", err.message);
    real p[PARAM_COUNT];
    for (int k = 0; k < PARAM_COUNT; k++)
        p[k] = (real)pd[k];
    const real box[6] = {-1.5f, -1.25f, -1, 1.5f, 1.25f, 1};
    for (int k = 0; k < 6; k++)
        p[PARAM_BOX + k] = box[k];
    p[PARAM_TMIN] = (real)0.5;
    p[PARAM_TMAX] = (real)9;

    size_t items = (size_t)test_iters(20000);
    cl_uint *seeds = malloc(items * sizeof *seeds), *out = calloc(6 * items, sizeof *out);
    CHECK(seeds && out, "out of memory");
    test_rng_t *r = test_rng();
    for (size_t g = 0; g < items; g++)
        seeds[g] = (cl_uint)test_rand_u64(r);
    cl_int rc = CL_SUCCESS;
    cl_kernel kernel = clCreateKernel(program, "packet_checks", &rc);
    cl_mem bp = clCreateBuffer(rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof p, p, &rc);
    cl_mem bs = clCreateBuffer(rt.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, items * sizeof *seeds, seeds, &rc);
    cl_mem bo = clCreateBuffer(rt.context, CL_MEM_WRITE_ONLY, 6 * items * sizeof *out, NULL, &rc);
    CHECK(rc == CL_SUCCESS, "buffers: %s", clrt_error_name(rc));
    clSetKernelArg(kernel, 0, sizeof bp, &bp);
    clSetKernelArg(kernel, 1, sizeof width, &width);
    clSetKernelArg(kernel, 2, sizeof height, &height);
    clSetKernelArg(kernel, 3, sizeof bs, &bs);
    clSetKernelArg(kernel, 4, sizeof bo, &bo);
    size_t one = 1; /* as the renderer: PoCL keeps a work-group's private arrays on one thread's stack */
    rc = clEnqueueNDRangeKernel(rt.queue, kernel, 1, NULL, &items, &one, 0, NULL, NULL);
    if (rc == CL_SUCCESS)
        rc = clEnqueueReadBuffer(rt.queue, bo, CL_TRUE, 0, 6 * items * sizeof *out, out, 0, NULL, NULL);
    clReleaseMemObject(bp);
    clReleaseMemObject(bs);
    clReleaseMemObject(bo);
    clReleaseKernel(kernel);
    clReleaseProgram(program);
    clrt_close(&rt);
    long sum[6] = {0};
    for (size_t g = 0; g < items; g++)
        for (int c = 0; c < 6; c++)
            sum[c] += out[6 * g + c];
    free(seeds);
    free(out);
    CHECK(rc == CL_SUCCESS, "run: %s", clrt_error_name(rc));
    long lanes = (long)items * PACKET_LANES;
    test_note("%ld lanes: mismatches in rays %ld, clip %ld, first node %ld, boxes and node ends %ld, walk steps %ld; "
              "control (a box one ulp of t off) differs in %ld",
              lanes, sum[0], sum[1], sum[2], sum[3], sum[4], sum[5]);
    CHECK(sum[0] + sum[1] + sum[2] + sum[3] + sum[4] == 0, "the lanes differ from the scalar code");
    CHECK(sum[5] > 0, "the comparison cannot see a one-ulp difference");
}
