/* tests/t_prim_segments_fp.c -- each primitive type through the segment path's walk as scenes of more than 64 solids
 * run it: the closed forms of kernels/prim_segments.h (the quadrics solved, tori and general tgcs walked as quartics,
 * a pipe as the union of its parts: prim_pipe_segments.h), bisection for the rays the closed forms leave to it;
 * against the exact reference: tests/t_prim_walk.h says what is checked. */
#define SCENE_SOLID_PRIMS 1
#define SCENE_SOLID_PIPES 1
#include "t_prim_walk.h"

TEST_FP(prim_segments_half) { run_type(SCENE_PRIM_HALF, 1, "half"); }
TEST_FP(prim_segments_arb8) { run_type(SCENE_PRIM_ARB8, 4, "arb8"); }
TEST_FP(prim_segments_ell) { run_type(SCENE_PRIM_ELL, 2, "ell"); }
TEST_FP(prim_segments_tgc) { run_type(SCENE_PRIM_TGC, 5, "tgc"); }
/* The streams on which a general tgc's quartic, its coefficients expanded from the start of the range, hid its sign
 * over 0.1 of a ray that passes near the surface and meets it nowhere (a BOUNDARY leaf there, f32): the quartics'
 * coefficients now come from the middle of the range (prim_quartic_solve). */
TEST_FP(prim_segments_tgc_near_streams) {
    const uint64_t seeds[] = {1, 20};
    for (int k = 0; k < 2; k++) {
        test_rng_reseed("prim_segments_tgc_f32", seeds[k]);
        run_type(SCENE_PRIM_TGC, 5, "tgc");
    }
}
TEST_FP(prim_segments_tor) { run_type(SCENE_PRIM_TOR, 1, "tor"); }
TEST_FP(prim_segments_ehy) { run_type(SCENE_PRIM_EHY, 1, "ehy"); }
TEST_FP(prim_segments_pipe) { run_type(SCENE_PRIM_PIPE, 6, "pipe"); }
