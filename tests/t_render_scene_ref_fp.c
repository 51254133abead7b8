/* tests/t_render_scene_ref_fp.c -- scenes of regions rendered by the segment path, compared for EVERY pixel with
 * the exact host reference of tests/t_scene_ref.h (closed-form insides of spheres, boxes and half-spaces in long
 * double, woven and classified on the host): unions, intersections, differences, nested differences, touching
 * and overlapping regions, disjoint regions (claimed at the union's leaf), a region thinner than eps, rays grazing
 * spheres, and 216 solids.
 *
 * The checks per pixel are ref_check_scene's (tests/t_scene_ref.h). */
#include "t_scene_check.h"

static const iacsg_camera view_front = {.eye = {3, -4, 2.5}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 35};

TEST_FP(render_scene_ref_booleans) {
    static ref_scene rs;
    ref_scene_init(&rs);
    ref_add_solid(&rs, ref_sphere(-0.5, 0, 0, 0.75));    /* 0 */
    ref_add_solid(&rs, ref_sphere(0.5, 0, 0, 0.75));     /* 1 */
    ref_add_solid(&rs, ref_box(0, 0, 1, 1.5, 0.25, 0.25)); /* 2: a bar above */
    ref_add_solid(&rs, ref_halfspace(0, 0, 1, -0.75));    /* 3: z < -0.75 */
    ref_add_solid(&rs, ref_box(0, 0, -1, 1.5, 1.5, 0.5)); /* 4 */
    ref_add_region(&rs, "i <0 <1");                        /* the lens, declared first: it wins the overlap */
    ref_add_region(&rs, "u <0 <1");                        /* both balls (overlaps the lens) */
    ref_add_region(&rs, "d <2 u <0 <1");                   /* the bar minus the balls */
    ref_add_region(&rs, "i <3 <4");                        /* a floor: half-space and box */
    ref_check_scene("booleans", &rs, &view_front, NULL);
}

TEST_FP(render_scene_ref_differences) {
    static ref_scene rs;
    ref_scene_init(&rs);
    ref_add_solid(&rs, ref_box(0, 0, 0, 1, 1, 1));        /* 0 */
    ref_add_solid(&rs, ref_sphere(0, 0, 0, 1.25));        /* 1 */
    ref_add_solid(&rs, ref_sphere(0, 0, 0, 0.75));        /* 2 */
    ref_add_solid(&rs, ref_box(0, 0, 0, 0.25, 0.25, 1.75)); /* 3: a rod along z */
    ref_add_region(&rs, "d <0 <1");                        /* the box's corners */
    ref_add_region(&rs, "d <1 d <0 <2");                   /* nested: the ball's caps and the inner ball */
    ref_add_region(&rs, "d i <3 <1 <2");                   /* the rod inside the ball, outside the inner one */
    ref_add_region(&rs, "d <3 u <0 <1");                   /* the rod's ends */
    ref_check_scene("differences", &rs, &view_front, NULL);
}

/* Regions no two of which can be in at one point whatever the shapes (implicits/scene_emit.c: regions_disjoint),
 * which the union's pre-pass claims at its leaf without weaving (kernels/scene_union.h: scene_union_claim): the
 * box's corners outside a ball, the ball's shell cut by a half-space (above the cut the corners' inner, spherical
 * boundary is in view), the inner ball, and a sheet thinner than eps in front. */
TEST_FP(render_scene_ref_disjoint) {
    static ref_scene rs;
    ref_scene_init(&rs);
    ref_add_solid(&rs, ref_box(0, 0, 0, 1, 1, 1));                          /* 0 */
    ref_add_solid(&rs, ref_sphere(0, 0, 0, 1.25));                          /* 1 */
    ref_add_solid(&rs, ref_sphere(0, 0, 0, 0.75));                          /* 2 */
    ref_add_solid(&rs, ref_box(1, -1.5, 0.5, 0.5, 0.000244140625, 0.5));   /* 3: a sheet 2^-11 thick */
    ref_add_solid(&rs, ref_halfspace(0, 0, 1, -0.25));                      /* 4: z < -0.25 */
    ref_add_region(&rs, "d <0 <1");         /* the box's corners */
    ref_add_region(&rs, "i d <1 <2 <4");    /* the shell below z = -0.25 */
    ref_add_region(&rs, "i <2 <1");         /* the inner ball, above the cut too */
    ref_add_region(&rs, "d <3 u <0 <1");    /* the sheet outside both */
    long seen[4] = {0};
    ref_check_scene("disjoint", &rs, &view_front, seen);
    test_note("pixels checked on each region: %ld, %ld, %ld, the sheet %ld", seen[0], seen[1], seen[2], seen[3]);
    CHECK(seen[1] > 200 && seen[2] > 50 && seen[3] > 200, "regions checked on too few pixels");
}

TEST_FP(render_scene_ref_touching_thin) {
    static ref_scene rs;
    ref_scene_init(&rs);
    ref_add_solid(&rs, ref_box(-0.5, 0, 0, 0.5, 0.5, 0.5));     /* 0 */
    ref_add_solid(&rs, ref_box(0.5, 0, 0, 0.5, 0.5, 0.5));      /* 1: shares the face x = 0 with 0 */
    ref_add_solid(&rs, ref_sphere(0, 0, 1, 0.5));               /* 2: rests on their top face */
    ref_add_solid(&rs, ref_box(0, 1.25, 0, 1.25, 0.000244140625, 1)); /* 3: a sheet 2^-11 thick (< eps / 2) */
    ref_add_solid(&rs, ref_sphere(1.375, 1.75, 0, 0.5));          /* 4: partly behind the sheet */
    ref_add_region(&rs, "<0");
    ref_add_region(&rs, "<1");
    ref_add_region(&rs, "<2");
    ref_add_region(&rs, "<3");
    ref_add_region(&rs, "<4");
    long seen[5] = {0};
    ref_check_scene("touching_thin", &rs, &view_front, seen);
    test_note("pixels checked on each region: %ld, %ld, %ld, the sheet %ld, behind it %ld", seen[0], seen[1], seen[2],
              seen[3], seen[4]);
    CHECK(seen[3] > 200, "the thin sheet was checked on %ld pixels only", seen[3]);
}

/* 216 small spheres, each its own region, and boxes across them (overlaps: the spheres, declared first, win). */
TEST_FP(render_scene_ref_many) {
    static ref_scene rs;
    ref_scene_init(&rs);
    char tree[32];
    for (int k = 0; k < 216; k++) {
        int a = k % 6, b = k / 6 % 6, c = k / 36;
        ref_add_solid(&rs, ref_sphere(-0.625 + 0.25 * a, -0.625 + 0.25 * b, -0.625 + 0.25 * c, 0.09375));
        snprintf(tree, sizeof tree, "<%d", k);
        ref_add_region(&rs, tree);
    }
    ref_add_solid(&rs, ref_box(0, 0, 0, 1, 0.0625, 0.0625));
    ref_add_solid(&rs, ref_box(0, 0, -0.125, 0.0625, 1, 0.0625));
    ref_add_region(&rs, "u <216 <217");
    ref_check_scene("many", &rs, &view_front, NULL);
}
