/* tests/t_render_bytes_fp.c -- view.rgb_bytes (kernels/render.cl: RENDER_BYTES): where the camera kernel's
 * colours are the frame's, it writes them as bytes, and they are exactly the bytes the image writer makes of the
 * float frame (src/image_bytes.c); where a pass after the frame writes colours (-aa), the frame stays floats. In
 * float and double, on a view whose edge packets are partly outside the image (37 x 29), plain and with effects
 * the camera kernel applies (transparency and shadows). */
#include "t_render_util.h"
#include "iacsg.h"
#include "image_bytes.h"
#include <stdlib.h>
#include <string.h>

#ifdef IA_FP64
#define FP64 1
#else
#define FP64 0
#endif

/* Renders expr's view with and without rgb_bytes; checks which image each frame has, and that the bytes (or the
 * floats, where the frame stays floats) are the floats' as the writer converts them. */
static void check_bytes(const char *expr, iacsg_view view, int bytes_expected) {
    iacsg_render_config config = {.fp64 = FP64};
    iacsg_frame floats = {0}, bytes = {0};
    render_expr_text(expr, &config, &view, &floats);
    view.rgb_bytes = 1;
    render_expr_text(expr, &config, &view, &bytes);
    size_t n = 3 * (size_t)view.width * (size_t)view.height;
    unsigned char *expected = malloc(n), *got = malloc(n);
    CHECK(expected && got, "out of memory");
    CHECK(floats.rgb && !floats.rgb8, "without rgb_bytes: floats only");
    CHECK(bytes_expected ? bytes.rgb8 && !bytes.rgb : bytes.rgb && !bytes.rgb8, "rgb_bytes: %s expected",
          bytes_expected ? "bytes" : "floats");
    image_floats_to_bytes(floats.rgb, expected, n);
    if (bytes.rgb8)
        memcpy(got, bytes.rgb8, n);
    else
        image_floats_to_bytes(bytes.rgb, got, n);
    size_t differ = 0, first = n;
    for (size_t k = 0; k < n; k++)
        if (expected[k] != got[k]) {
            differ++;
            first = first < n ? first : k;
        }
    CHECK(differ == 0, "%s: %zu of %zu channels differ, the first at pixel %zu: %u against %u", expr, differ, n,
          first / 3, first < n ? got[first] : 0, first < n ? expected[first] : 0);
    iacsg_frame_free(&floats);
    iacsg_frame_free(&bytes);
    free(expected);
    free(got);
}

static iacsg_view odd_view(void) {
    iacsg_view v = {.width = 37, .height = 29, .eps = 1e-4,
                    .camera = {.eye = {0, -4, 2.5}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40},
                    .bounds = {-2, -2, -2, 2, 2, 2}, .no_depth = 1, .no_normals = 1, .no_ids = 1};
    return v;
}

static const char *const two_balls = "min(x^2+y^2+z^2-1, (x-0.9)^2+(y+0.5)^2+(z-0.3)^2-0.2)";

TEST_FP(render_bytes_plain) { check_bytes(two_balls, odd_view(), 1); }

TEST_FP(render_bytes_effects_in_camera) {
    iacsg_effects fx = {.shadows = 1, .nlights = 1, .transparency = 0.5,
                        .lights = {{.kind = IACSG_LIGHT_POINT, .xyz = {1.5, -2, 4}, .intensity = 0.9}}};
    iacsg_view v = odd_view();
    v.effects = &fx;
    check_bytes(two_balls, v, 1);
}

TEST_FP(render_bytes_not_with_aa) {
    iacsg_effects fx = {.aa = 2};
    iacsg_view v = odd_view();
    v.effects = &fx;
    check_bytes(two_balls, v, 0);
}
