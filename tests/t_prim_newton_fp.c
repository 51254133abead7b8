/* tests/t_prim_newton_fp.c -- each primitive type through the segment path's walk with interval Newton on prim_Fd
 * (as scenes of at most 64 solids run it), against the exact reference: tests/t_prim_walk.h says what is checked;
 * Newton must neither skip a crossing nor prove a node that holds one. */
#define SCENE_SOLID_FD 1
#include "t_prim_walk.h"

TEST_FP(prim_newton_half) { run_type(SCENE_PRIM_HALF, 1, "half"); }
TEST_FP(prim_newton_arb8) { run_type(SCENE_PRIM_ARB8, 4, "arb8"); }
TEST_FP(prim_newton_ell) { run_type(SCENE_PRIM_ELL, 2, "ell"); }
TEST_FP(prim_newton_tgc) { run_type(SCENE_PRIM_TGC, 5, "tgc"); }
TEST_FP(prim_newton_tor) { run_type(SCENE_PRIM_TOR, 1, "tor"); }
TEST_FP(prim_newton_ehy) { run_type(SCENE_PRIM_EHY, 1, "ehy"); }
TEST_FP(prim_newton_pipe) { run_type(SCENE_PRIM_PIPE, 6, "pipe"); }
