/* tests/t_render_tile_inexact.c -- a device whose float / and sqrt are not correctly rounded (the OpenCL spec
 * allows 2.5 and 3 ulps): the tile pass's box still holds every pixel ray (and -aa's samples between the tile's
 * centres), and the renderer built for such a device (forced on PoCL with IACSG_INEXACT_DIVIDE_SQRT) misses no
 * pixel.
 *
 * The host model compiles kernels/tile.h with the device's non-correctly-rounded error bounds and draws each
 * pixel's ray, and a random sample's of it, as such a device may compute it: every / and sqrt of camera_ray's chain up to 2 floats off the
 * correctly rounded result (within 2.5 ulps of the exact one), each way. */
#define CAMERA_ULP_DIV 3  /* ia/round.h's figures for a float device without -cl-fp32-correctly-rounded-... */
#define CAMERA_ULP_SQRT 3
#include "ia/ia.h"

/* tile.h's search calls the expression's inclusion function; this test only uses tile_rays_of and tile_box. */
IA_FN ia_interval iacsg_F(ia_interval x, ia_interval y, ia_interval z, ia_interval t) {
    (void)t;
    return ia_add_r(ia_add(ia_add(ia_sqr(x), ia_sqr(y)), ia_sqr(z)), -1);
}

#include "clrt.h"
#include "kernels/tile.h"
#include "t_render_util.h"
#include <string.h>

/* x moved `steps` floats up (down when negative). */
static float step_floats(float x, int steps) {
    for (; steps > 0; steps--)
        x = nextafterf(x, INFINITY);
    for (; steps < 0; steps++)
        x = nextafterf(x, -INFINITY);
    return x;
}

/* The ray through doubled column x2 and row y2 in camera_ray_at's order of operations, with the quotients of s and
 * v, the sqrt and the three divisions moved err[0..5] floats off their correctly rounded values. */
static void inexact_ray(const float *p, int ortho, float x2, float y2, int w, int h, const int err[6], float o[3],
                        float d[3]) {
    float s = (step_floats(x2 / (float)w, err[0]) - 1) * p[PARAM_SCALE_S];
    float v = (1 - step_floats(y2 / (float)h, err[1])) * p[PARAM_SCALE_V];
    for (int k = 0; k < 3; k++) {
        float offset = s * p[PARAM_RIGHT + k] + v * p[PARAM_UP + k];
        o[k] = ortho ? p[PARAM_EYE + k] + offset : p[PARAM_EYE + k];
        d[k] = ortho ? p[PARAM_FORWARD + k] : p[PARAM_FORWARD + k] + offset;
    }
    if (ortho)
        return;
    float len = step_floats(sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), err[2]);
    for (int k = 0; k < 3; k++)
        d[k] = step_floats(d[k] / len, err[3 + k]);
}

TEST(render_tile_box_holds_inexact_rays) {
    test_rng_t *rng = test_rng();
    long checked = 0;
    for (long it = 0; it < test_iters(3000); it++) {
        random_tile t;
        if (!random_tile_draw(rng, &t))
            continue; /* a degenerate random view */
        const ia_real *p = t.p, a = t.a, b = t.b;
        int ortho = t.ortho, w = t.w, h = t.h, i0 = t.i0, i1 = t.i1, j0 = t.j0, j1 = t.j1;
        ia_interval box[3];
        tile_rays rays;
        tile_rays_of(p, ortho, i0, i1, j0, j1, w, h, &rays);
        tile_box(&rays, ia_make(a, b), box);
        for (int j = j0; j <= j1; j++)
            for (int i = i0; i <= i1; i++)
                for (int sample = 0; sample < 2; sample++) {
                    float x2 = (float)(2 * i + 1), y2 = (float)(2 * j + 1);
                    if (sample)
                        random_sample(rng, i, j, &x2, &y2);
                    if (x2 < 2 * i0 + 1 || x2 > 2 * i1 + 1 || y2 < 2 * j0 + 1 || y2 > 2 * j1 + 1)
                        continue; /* past the tile's outer centres: a sample traced from the root */
                    int errs[6];
                    for (int k = 0; k < 6; k++) /* the extremes half of the time */
                        errs[k] = test_rand_u64(rng) & 1 ? (test_rand_u64(rng) & 1 ? 2 : -2)
                                                         : (int)(test_rand_u64(rng) % 5) - 2;
                    float o[3], d[3];
                    inexact_ray(p, ortho, x2, y2, w, h, errs, o, d);
                    for (int k = 0; k < 3; k++) {
                        ia_interval x = ray_extent(o[k], d[k], ia_make(a, b));
                        CHECK(box[k].lo <= x.lo && x.hi <= box[k].hi,
                              "%s view %dx%d, pixel (%d, %d) of tile (%d..%d, %d..%d), ray (%a, %a), errors %d %d %d "
                              "%d %d %d, axis %d: ray [%a, %a] outside the tile box [%a, %a]",
                              ortho ? "orthographic" : "perspective", w, h, i, j, i0, i1, j0, j1, (double)x2,
                              (double)y2, errs[0], errs[1], errs[2], errs[3], errs[4], errs[5], k, (double)x.lo,
                              (double)x.hi, (double)box[k].lo, (double)box[k].hi);
                    }
                    checked++;
                }
    }
    test_note("%ld inexact pixel and sample rays checked against their tile's box", checked);
}

/* The build options of device 0 with IACSG_INEXACT_DIVIDE_SQRT set: no correctly rounded / and sqrt asked. */
TEST(render_inexact_divide_sqrt_is_forced) {
    clrt rt;
    iacsg_error err = {0};
    char plain[512] = "", forced[512] = "";
    CHECK(clrt_open(&rt, 0, &err) == IACSG_OK, "%s", err.message);
    iacsg_status st = clrt_ia_options(&rt, 0, 0, plain, sizeof plain, &err);
    clrt_close(&rt);
    CHECK(st == IACSG_OK, "%s", err.message);
    setenv("IACSG_INEXACT_DIVIDE_SQRT", "1", 1);
    st = clrt_open(&rt, 0, &err);
    unsetenv("IACSG_INEXACT_DIVIDE_SQRT");
    CHECK(st == IACSG_OK, "%s", err.message);
    st = clrt_ia_options(&rt, 0, 0, forced, sizeof forced, &err);
    clrt_close(&rt);
    CHECK(st == IACSG_OK, "%s", err.message);
    CHECK(!strstr(forced, "correctly-rounded") && !strstr(forced, "IA_CR_DIVSQRT"), "forced: %s", forced);
    test_note("options: '%s', forced: '%s'", plain, forced);
}

/* Renders the unit sphere in float with the build for inexact / and sqrt, and compares every pixel with the
 * exact intersection of its float ray (on PoCL the device's / and sqrt are still correctly rounded, so the
 * host's camera_ray is the device's ray): no pixel whose ray crosses the sphere (away from grazing) is missed,
 * none is after the first root, none hits where the ray misses. */
static void check_sphere(iacsg_view v, const char *what) {
    const sphere unit = {{0, 0, 0}, 1};
    char *cl = spheres_cl(unit, unit, SOLID_A);
    iacsg_render_config config = {0};
    iacsg_error err = {0};
    iacsg_renderer *r = NULL;
    setenv("IACSG_INEXACT_DIVIDE_SQRT", "1", 1);
    iacsg_status st = iacsg_renderer_create(cl, &config, &r, &err);
    unsetenv("IACSG_INEXACT_DIVIDE_SQRT");
    free(cl);
    CHECK(st == IACSG_OK, "renderer: %s", err.message);
    iacsg_frame frame;
    st = iacsg_render(r, &v, &frame, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "render: %s", err.message);
    float p[PARAM_COUNT];
    view_params(&v, p);
    long hits = 0, missed = 0, late = 0, ghosts = 0;
    for (int j = 0; j < v.height; j++)
        for (int i = 0; i < v.width; i++) {
            double o[3], d[3], t1, t2;
            pixel_ray(p, &v, i, j, o, d);
            float depth = frame.depth[(size_t)j * (size_t)v.width + (size_t)i];
            int crosses = sphere_span(unit, o, d, &t1, &t2) && t2 >= 0;
            /* grazing rays (within 1e-3 of tangent) may go either way */
            double along = -(o[0] * d[0] + o[1] * d[1] + o[2] * d[2]) / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            double gap = hypot(hypot(o[0] + along * d[0], o[1] + along * d[1]), o[2] + along * d[2]) - 1;
            if (fabs(gap) < 1e-3)
                continue;
            hits += isfinite(depth);
            missed += crosses && !isfinite(depth);
            ghosts += !crosses && isfinite(depth);
            late += crosses && isfinite(depth) && depth > fmax(t1, 0);
        }
    iacsg_frame_free(&frame);
    test_note("%s: %ld hits, %ld missed, %ld late, %ld ghosts", what, hits, missed, late, ghosts);
    CHECK(hits > v.width * v.height / 8, "%s: %ld hits", what, hits);
    CHECK(missed == 0 && late == 0 && ghosts == 0, "%s: %ld missed, %ld late, %ld ghost pixels", what, missed, late,
          ghosts);
}

TEST(render_inexact_divide_sqrt_misses_nothing) {
    iacsg_view v = {.width = 97, .height = 83, .eps = 0x1p-16, .bounds = {-2, -2, -2, 2, 2, 2},
                    .camera = {.eye = {0.5, -4, 2.5}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40}};
    check_sphere(v, "perspective");
    v.camera.ortho_height = 2.5;
    check_sphere(v, "orthographic");
}
