/* tests/t_render_rows.c -- iacsg_view.row_first/row_count, the bands the MPI layer shares out: each band's rows
 * are bit for bit those of the whole frame, whatever else is traced with them, and only they are traced (the
 * frame's count of rays); a band that does not start on IACSG_ROW_ALIGN or overruns the image is refused. */
#include "iacsg.h"
#include "test.h"
#include <string.h>

TEST(render_rows_bands_equal_whole_frame) {
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse("min(sphere, torus)", "<test>", &e, &err) == IACSG_OK, "%s", err.message);
    iacsg_render_config config = {0};
    iacsg_renderer *r = NULL;
    CHECK(iacsg_renderer_create_expr(e, &config, &r, &err) == IACSG_OK, "%s", err.message);
    iacsg_expr_destroy(e);
    iacsg_view v = {.width = 75, .height = 100, .eps = 1e-5, .bounds = {-1.5, -1.5, -1.5, 1.5, 1.5, 1.5},
                    .camera = {.eye = {3, -4, 2}, .up = {0, 0, 1}, .fov = 40}};
    iacsg_frame whole, band;
    CHECK(iacsg_render(r, &v, &whole, &err) == IACSG_OK, "%s", err.message);
    /* bands of 32 rows and the short last one, and one band of two blocks */
    static const int bands[][2] = {{0, 32}, {32, 32}, {64, 36}, {32, 64}};
    for (int b = 0; b < 4; b++) {
        v.row_first = bands[b][0];
        v.row_count = bands[b][1];
        CHECK(iacsg_render(r, &v, &band, &err) == IACSG_OK, "band %d: %s", b, err.message);
        size_t row = 3 * (size_t)v.width, at = row * (size_t)v.row_first;
        int same_rgb = memcmp(band.rgb + at, whole.rgb + at, row * (size_t)v.row_count * sizeof(float)) == 0;
        size_t drow = (size_t)v.width, dat = drow * (size_t)v.row_first;
        int same_depth = memcmp(band.depth + dat, whole.depth + dat, drow * (size_t)v.row_count * sizeof(float)) == 0;
        long long rays = band.rays;
        iacsg_frame_free(&band);
        CHECK(same_rgb && same_depth, "rows %d + %d differ from the whole frame's", v.row_first, v.row_count);
        CHECK(rays == (long long)v.width * v.row_count, "rows %d + %d: %lld rays traced", v.row_first, v.row_count,
              rays);
    }
    static const int bad[][2] = {{16, 32}, {96, 32}, {-32, 32}, {32, 0}};
    for (int b = 0; b < 4; b++) {
        v.row_first = bad[b][0];
        v.row_count = bad[b][1];
        CHECK(iacsg_render(r, &v, &band, &err) == IACSG_ERR_ARG, "rows %d + %d of 100 were not refused",
              v.row_first, v.row_count);
    }
    iacsg_frame_free(&whole);
    iacsg_renderer_destroy(r);
}
