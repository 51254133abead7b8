/* tests/t_render_surface_fp.c -- level-set surfaces (Hijazi et al. §4.4) rendered by the segment path, every
 * pixel's id and depth against the exact host reference (tests/t_scene_ref.h: the first crossing of the
 * surface's solid where its condition holds, in long double): a plane's zero set kept inside a sphere (a disc), a
 * sphere's zero set kept where a box is negative, a condition with `!` and `|`, a whole zero set (no condition),
 * surfaces in front of and behind a region, and more surfaces than get a block pass. */
#include "t_scene_check.h"

static const iacsg_camera view_front = {.eye = {3, -4, 2.5}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 35};

TEST_FP(render_surface_disc) {
    static ref_scene rs;
    ref_scene_init(&rs);
    int plane = ref_add_solid(&rs, ref_halfspace(0, 0, 1, 0.25)); /* z = 0.25 */
    ref_add_solid(&rs, ref_sphere(0, 0, 0, 1));
    ref_add_surface(&rs, plane, "<1");
    ref_check_scene("disc", &rs, &view_front, NULL);
}

TEST_FP(render_surface_sphere_in_box) {
    static ref_scene rs;
    ref_scene_init(&rs);
    int ball = ref_add_solid(&rs, ref_sphere(0, 0, 0, 1));
    ref_add_solid(&rs, ref_box(0.5, -0.25, 0.5, 0.75, 0.75, 0.75));
    ref_add_surface(&rs, ball, "<1");
    ref_check_scene("sphere_in_box", &rs, &view_front, NULL);
}

/* A sphere kept outside a box or inside a half-space: x > 0.25 or not in the box, from the inside too (the
 * sphere's far side shows where the near side is dropped). */
TEST_FP(render_surface_not_or) {
    static ref_scene rs;
    ref_scene_init(&rs);
    int ball = ref_add_solid(&rs, ref_sphere(0, 0, 0, 1.25));
    ref_add_solid(&rs, ref_box(0, -1, 0.5, 1, 0.875, 0.5)); /* y from -1.875 to -0.125 */
    ref_add_solid(&rs, ref_halfspace(-1, 0, 0, -0.25)); /* x > 0.25 */
    ref_add_surface(&rs, ball, "u n <1 <2");
    ref_check_scene("not_or", &rs, &view_front, NULL);
}

/* Two surfaces and a region: a whole sphere (no condition), a disc through a box region, ids in declaration
 * order, the nearest wins. */
TEST_FP(render_surface_with_region) {
    static ref_scene rs;
    ref_scene_init(&rs);
    int small = ref_add_solid(&rs, ref_sphere(-1, -0.5, 0.5, 0.375));
    int plane = ref_add_solid(&rs, ref_halfspace(0.25, 0.5, 1, 0)); /* a tilted plane through the origin */
    ref_add_solid(&rs, ref_sphere(0, 0, 0, 1.25));
    ref_add_solid(&rs, ref_box(0.25, 0.25, 0, 0.5, 0.5, 0.5));
    ref_add_surface(&rs, small, NULL);
    ref_add_surface(&rs, plane, "<2");
    ref_add_region(&rs, "<3");
    ref_check_scene("with_region", &rs, &view_front, NULL);
}

/* More surfaces than get a block pass (SURFACE_BLOCK_MAX, kernels/surface.h): the first ones start their rays'
 * walks at their blocks' nodes, the rest walk from the top; every other one is cut by a tilted plane. */
TEST_FP(render_surface_many) {
    static ref_scene rs;
    ref_scene_init(&rs);
    for (int k = 0; k < 12; k++)
        ref_add_solid(&rs, ref_sphere(-1.5 + 0.75 * (k % 4), -1 + 0.75 * (k / 4), 0, 0.3125));
    int cut = ref_add_solid(&rs, ref_halfspace(0.25, 0, 1, 0.0625));
    char condition[16];
    snprintf(condition, sizeof condition, "<%d", cut);
    for (int k = 0; k < 12; k++)
        ref_add_surface(&rs, k, k % 2 ? condition : NULL);
    ref_check_scene("many", &rs, &view_front, NULL);
}
