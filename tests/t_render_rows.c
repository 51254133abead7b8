/* tests/t_render_rows.c -- iacsg_view.row_first/row_count, the bands the MPI layer shares out: each band's rows
 * are bit for bit those of the whole frame (rgb, depth, normals, ids; with effects too), whatever else is traced
 * with them, and only they are traced (the frame's count of rays), on the first-root path and on the segment path
 * (its re-traced rays and statistics too); a band that does not start on IACSG_ROW_ALIGN or overruns the image is
 * refused. */
#include "iacsg.h"
#include "test.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* bands of 32 rows and the short last one (together the whole 100 rows), then one band of two blocks and one
 * that ends inside a block and inside a packet of the segment path (rows 60-63) */
static const int bands[][2] = {{0, 32}, {32, 32}, {64, 36}, {32, 64}, {32, 30}};
enum { PARTITION = 3, BANDS = 5 };

/* Whether rows [first, first + count) of images of `floats` floats a pixel are the same bits. */
static int same_rows(const float *a, const float *b, int width, int first, int count, int floats) {
    size_t row = (size_t)floats * (size_t)width;
    return memcmp(a + row * (size_t)first, b + row * (size_t)first, row * (size_t)count * sizeof(float)) == 0;
}

/* Renders each band of `bands` with r and checks its rows against the whole frame's. Returns, over the bands that
 * partition the frame, the sums of the re-traced rays, of the evaluations (the mean times the rays) and of the
 * overlaps, and the whole frame's in `whole_sums`; and each band's re-traced rays in `retraced`. */
static void check_bands(iacsg_renderer *r, iacsg_view v, double sums[3], double whole_sums[3],
                        long long retraced[BANDS]) {
    iacsg_error err = {0};
    iacsg_frame whole, band;
    CHECK(iacsg_render(r, &v, &whole, &err) == IACSG_OK, "%s", err.message);
    whole_sums[0] = (double)whole.retraced_rays;
    whole_sums[1] = whole.evals_mean * (double)whole.rays;
    whole_sums[2] = (double)whole.overlaps;
    sums[0] = sums[1] = sums[2] = 0;
    for (int b = 0; b < BANDS; b++) {
        v.row_first = bands[b][0];
        v.row_count = bands[b][1];
        CHECK(iacsg_render(r, &v, &band, &err) == IACSG_OK, "band %d: %s", b, err.message);
        retraced[b] = band.retraced_rays;
        int same = same_rows(band.rgb, whole.rgb, v.width, v.row_first, v.row_count, 3) &&
                   same_rows(band.depth, whole.depth, v.width, v.row_first, v.row_count, 1) &&
                   same_rows(band.normal, whole.normal, v.width, v.row_first, v.row_count, 3) &&
                   same_rows(band.ids, whole.ids, v.width, v.row_first, v.row_count, 1);
        long long rays = band.rays;
        if (b < PARTITION) {
            sums[0] += (double)band.retraced_rays;
            sums[1] += band.evals_mean * (double)band.rays;
            sums[2] += (double)band.overlaps;
        }
        iacsg_frame_free(&band);
        CHECK(same, "rows %d + %d differ from the whole frame's", v.row_first, v.row_count);
        CHECK(rays == (long long)v.width * v.row_count, "rows %d + %d: %lld rays traced", v.row_first, v.row_count,
              rays);
    }
    iacsg_frame_free(&whole);
}

static const iacsg_view view = {.width = 75, .height = 100, .eps = 1e-5, .bounds = {-1.5, -1.5, -1.5, 1.5, 1.5, 1.5},
                                .camera = {.eye = {3, -4, 2}, .up = {0, 0, 1}, .fov = 40}};

TEST(render_rows_bands_equal_whole_frame) {
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse("min(sphere, torus)", "<test>", &e, &err) == IACSG_OK, "%s", err.message);
    iacsg_render_config config = {0};
    iacsg_renderer *r = NULL;
    CHECK(iacsg_renderer_create_expr(e, &config, &r, &err) == IACSG_OK, "%s", err.message);
    iacsg_expr_destroy(e);
    double sums[3], whole[3];
    long long retraced[BANDS];
    check_bands(r, view, sums, whole, retraced);
    iacsg_view v = view;
    /* the effects that the camera kernel applies itself: a point light casting shadows, one reflection */
    iacsg_effects fx = {.lights = {{IACSG_LIGHT_POINT, {2, -3, 4}, 0.9}}, .nlights = 1, .shadows = 1, .bounces = 1,
                        .reflect = 0.4};
    v.effects = &fx;
    check_bands(r, v, sums, whole, retraced);
    v.effects = NULL;
    iacsg_frame band;
    static const int bad[][2] = {{16, 32}, {96, 32}, {-32, 32}, {32, 0}};
    for (int b = 0; b < 4; b++) {
        v.row_first = bad[b][0];
        v.row_count = bad[b][1];
        CHECK(iacsg_render(r, &v, &band, &err) == IACSG_ERR_ARG, "rows %d + %d of 100 were not refused",
              v.row_first, v.row_count);
    }
    iacsg_renderer_destroy(r);
}

/* The segment path, with room for one candidate a ray, so that rays meeting both solids overflow and are traced
 * again: the bands' re-traced rays and evaluations add up to the whole frame's (a band lists only its own), and
 * rows 32-61 re-trace fewer than rows 32-63, by at most rows 62-63's pixels (the packets of rows 60-63 are traced
 * only in the band's rows). */
TEST(render_rows_scene_bands_equal_whole_frame) {
    /* Fig. 2's cube and sphere, but as overlapping regions: disjoint ones (examples/fig2_cube_sphere_regions.csg)
     * are claimed at the union's leaf without the candidates' buffer (kernels/scene_union.h), and never overflow. */
    const char *text = "solid cube = pseudocube\nsolid ball = sphere(1.3)\nregion cube_part = cube\n"
                       "region ball_part = ball\n";
    iacsg_error err = {0};
    iacsg_scene *s = NULL;
    CHECK(iacsg_scene_parse(text, "<test>", &s, &err) == IACSG_OK, "%s", err.message);
    iacsg_render_config config = {.stats = 1, .ray_candidates = 1};
    iacsg_renderer *r = NULL;
    CHECK(iacsg_renderer_create_scene(s, &config, &r, &err) == IACSG_OK, "%s", err.message);
    iacsg_scene_destroy(s);
    double sums[3], whole[3];
    long long retraced[BANDS];
    check_bands(r, view, sums, whole, retraced);
    CHECK(retraced[4] < retraced[1] && retraced[1] - retraced[4] <= 2 * view.width,
          "rows 32 + 30 re-traced %lld rays, rows 32 + 32 %lld", retraced[4], retraced[1]);
    CHECK(whole[0] > 0, "no ray was traced again: the test does not reach the re-trace pass");
    CHECK(sums[0] == whole[0], "the bands re-traced %.0f rays, the whole frame %.0f", sums[0], whole[0]);
    CHECK(fabs(sums[1] - whole[1]) <= 1e-9 * whole[1] && sums[2] == whole[2],
          "the bands' evaluations %.1f and overlaps %.0f, the whole frame's %.1f and %.0f", sums[1], sums[2], whole[1],
          whole[2]);
    iacsg_renderer_destroy(r);
}
