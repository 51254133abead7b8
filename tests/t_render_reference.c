/* tests/t_render_reference.c -- shaded images of a few scenes against reference images in
 * tests/data/reference/, with a tolerance: the kernel may change the order of its arithmetic or a device may
 * round a shading function differently, but the silhouettes and the shading must not move. Run with
 * IACSG_UPDATE_REFERENCE=1 to rewrite the references after an intended change (and look at them). */
#include "iacsg.h"
#include "test.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *name, *expr;
    iacsg_camera camera;
    double eps;
} reference_scene;

static const reference_scene scenes[] = {
    {"sphere_torus", "min((x-0.5)^2+y^2+z^2-1, (1-sqrt(x^2+y^2))^2+z^2-0.125)",
     {.eye = {0, -4, 2.5}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40}, 1e-5},
    {"cube_minus_sphere", "max(x^500+y^500+z^500-1, -(x^2+y^2+z^2-1.5))",
     {.eye = {3, -4, 3}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 35}, 1e-5},
    {"heightmap_ortho", "min((x-0.5)^2+y^2+z^2-1, (1-sqrt(x^2+y^2))^2+z^2-0.125)",
     {.eye = {0, 0, 3}, .at = {0, 0, 0}, .up = {0, 1, 0}, .ortho_height = 4}, 4.0 / 128},
};

/* Renders a scene at 128x128 in float. */
static void render_scene(const reference_scene *s, iacsg_frame *fr) {
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse(s->expr, s->name, &e, &err) == IACSG_OK, "%s: %s", s->name, err.message);
    iacsg_render_config config = {0};
    iacsg_renderer *r = NULL;
    iacsg_status st = iacsg_renderer_create_expr(e, &config, &r, &err);
    iacsg_expr_destroy(e);
    CHECK(st == IACSG_OK, "%s: %s", s->name, err.message);
    iacsg_view v = {.width = 128, .height = 128, .eps = s->eps, .camera = s->camera,
                    .bounds = {-2, -2, -2, 2, 2, 2}};
    st = iacsg_render(r, &v, fr, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "%s: %s", s->name, err.message);
}

TEST(render_reference_images) {
    const char *update = getenv("IACSG_UPDATE_REFERENCE");
    for (size_t k = 0; k < sizeof scenes / sizeof scenes[0]; k++) {
        const reference_scene *s = &scenes[k];
        char path[1024];
        snprintf(path, sizeof path, "%s/tests/data/reference/%s.png", test_source_dir(), s->name);
        iacsg_frame fr;
        render_scene(s, &fr);
        iacsg_error err = {0};
        if (update && *update == '1') {
            CHECK(iacsg_image_write(path, fr.width, fr.height, 3, fr.rgb, 0, &err) == IACSG_OK, "%s", err.message);
            test_note("%s: reference rewritten", path);
            iacsg_frame_free(&fr);
            continue;
        }
        int w, h, ch;
        float *ref = NULL;
        CHECK(iacsg_image_read(path, &w, &h, &ch, &ref, &err) == IACSG_OK, "%s", err.message);
        CHECK(w == fr.width && h == fr.height && ch == 3, "%s: reference is %dx%dx%d", s->name, w, h, ch);
        /* Tolerance: the references are 8-bit, so a quantization error of 1/510 at most and ~1/1020 on average
         * (measured 0.00091-0.00114, float and fp64 alike); and a few pixels where the shading may move (a device
         * rounding a shading function differently, the kernel reordering its arithmetic): on the cube's edges,
         * x^500's normal turns within a pixel, and the two edge pixels there changed with the normals by
         * differences (0.28 off). A ghost, a miss or a moved silhouette is a whole pixel off. */
        long far_off = 0, n = (long)w * h;
        double sum = 0;
        for (long p = 0; p < n; p++) {
            double worst = 0;
            for (int c = 0; c < 3; c++) {
                double diff = fabs(fr.rgb[3 * p + c] - ref[3 * p + c]);
                sum += diff;
                worst = fmax(worst, diff);
            }
            far_off += worst > 0.1;
        }
        free(ref);
        iacsg_frame_free(&fr);
        test_note("%s: mean difference %.5f, %ld pixels off by more than 0.1", s->name, sum / (3.0 * n), far_off);
        CHECK(sum / (3.0 * n) < 1.0 / 255, "%s: mean difference %.4f", s->name, sum / (3.0 * n));
        CHECK(far_off <= 4, "%s: %ld pixels differ by more than 0.1", s->name, far_off);
    }
}

static int cancel_calls;
static int cancel_at_second(void *ctx) {
    (void)ctx;
    return ++cancel_calls >= 2;
}

/* A cancel callback is asked after each band of rows; its nonzero answer stops the render, with no frame. With
 * one, the first band is narrow (64 rows), so that a frame that would be one launch without it can still be
 * stopped. */
TEST(render_cancel_stops) {
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse("sphere", "<test>", &e, &err) == IACSG_OK, "%s", err.message);
    iacsg_render_config config = {0};
    iacsg_renderer *r = NULL;
    iacsg_status st = iacsg_renderer_create_expr(e, &config, &r, &err);
    iacsg_expr_destroy(e);
    CHECK(st == IACSG_OK, "%s", err.message);
    iacsg_view v = {.width = 8, .height = 2048, .eps = 1e-3, .bounds = {-2, -2, -2, 2, 2, 2}, /* 1 wide band */
                    .camera = {.eye = {0, -4, 0}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40},
                    .cancel = cancel_at_second};
    iacsg_frame fr = {0};
    cancel_calls = 0;
    st = iacsg_render(r, &v, &fr, &err);
    CHECK(st == IACSG_ERR_CANCELLED && !fr.rgb && !fr.depth, "status %d (%s)", st, err.message);
    CHECK(cancel_calls == 2, "asked %d times before stopping", cancel_calls);
    v.cancel = NULL;
    st = iacsg_render(r, &v, &fr, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK && fr.rgb, "%s", err.message);
    iacsg_frame_free(&fr);
}

typedef struct {
    int calls, rising;
    double last;
} progress_log;

static void log_progress(double done, void *ctx) {
    progress_log *p = ctx;
    p->rising &= done > p->last;
    p->last = done;
    p->calls++;
}

/* With a progress callback the bands start narrow and grow (a launch each): the frame is the same, pixel for
 * pixel, as in one launch, every row traced once, and the fractions rise to 1. */
TEST(render_progress_bands_cover_the_frame) {
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse("min(sphere, (1 - sqrt(x^2 + y^2))^2 + z^2 - 0.125)", "<test>", &e, &err) == IACSG_OK,
          "%s", err.message);
    iacsg_render_config config = {0};
    iacsg_renderer *r = NULL;
    iacsg_status st = iacsg_renderer_create_expr(e, &config, &r, &err);
    iacsg_expr_destroy(e);
    CHECK(st == IACSG_OK, "%s", err.message);
    iacsg_view v = {.width = 24, .height = 2000, .eps = 1e-4, .bounds = {-2, -2, -2, 2, 2, 2},
                    .camera = {.eye = {0, -4, 1}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 60}};
    iacsg_frame whole = {0}, banded = {0};
    st = iacsg_render(r, &v, &whole, &err);
    CHECK(st == IACSG_OK, "%s", err.message);
    progress_log log = {0, 1, 0};
    v.progress = log_progress;
    v.progress_ctx = &log;
    st = iacsg_render(r, &v, &banded, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "%s", err.message);
    size_t n = (size_t)v.width * (size_t)v.height;
    long hits = 0;
    for (size_t p = 0; p < n; p++) {
        CHECK(memcmp(&whole.depth[p], &banded.depth[p], sizeof(float)) == 0 &&
                  memcmp(&whole.rgb[3 * p], &banded.rgb[3 * p], 3 * sizeof(float)) == 0,
              "pixel (%d, %d): depth %g in one launch, %g in bands", (int)(p % (size_t)v.width),
              (int)(p / (size_t)v.width), whole.depth[p], banded.depth[p]);
        hits += !isinf(whole.depth[p]);
    }
    test_note("%d bands, %ld of %zu pixels hit", log.calls, hits, n);
    CHECK(log.calls >= 2 && log.rising && log.last == 1, "%d progress calls, rising %d, last %g", log.calls,
          log.rising, log.last);
    CHECK(hits > (long)n / 4, "%ld hits: the view misses the solid", hits);
    iacsg_frame_free(&whole);
    iacsg_frame_free(&banded);
}
