/* tests/t_render_time_fp.c -- the time reaches the kernel as an interval enclosing the real asked for (-time's
 * decimal, frame k of n's k/n), rounded outward to the working precision like every constant, so the depth is
 * never after the first root at the real time. */
#include "ia/decimal.h"
#include "iacsg.h"
#include "image.h"
#include "test.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#ifdef IA_FP64
#define FP64 1
#define ULP_OF_T 0x1p-53 /* the spacing of the working precision's numbers at 0.7 */
#else
#define FP64 0
#define ULP_OF_T 0x1p-24
#endif

/* z - 10^7 (t - c), c = 0.69999992847442626953125 the float one below the float nearest 0.7. At t = 7/10 its
 * root is z = 10^7 (7/10 - c) = 0.7152557373046875 (exact: 7e6 - 10^7 c is a difference of doubles within a
 * factor 2), depth 3 - z from (0, 0, 3) looking down. With t rounded to the float nearest 0.7, one float above
 * c, the root moves to z = 0.596 (depth 2.404): after the real one. */
static const char *plane_text = "z - 10000000*(t - 0.69999992847442626953125)";
static const double root_depth = 3 - 0.7152557373046875;
/* How early the depth may be: the enclosure of t is one ULP_OF_T wide, times 10^7, plus a leaf. */
static const double early_slack = ULP_OF_T * 1e7 + 1e-3;

static iacsg_view plane_view(void) {
    iacsg_view v = {.width = 16, .height = 16, .eps = 0x1p-16, .bounds = {-1, -1, -2, 1, 1, 2},
                    .camera = {.eye = {0, 0, 3}, .at = {0, 0, 0}, .up = {0, 1, 0}, .ortho_height = 1}};
    return v;
}

/* Every pixel hits, at most early_slack before root_depth and never after it. */
static void check_depths(const float *depth, int n, const char *what) {
    float lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < n; k++) {
        CHECK(isfinite(depth[k]), "%s: pixel %d misses the plane", what, k);
        CHECK(depth[k] <= root_depth, "%s: depth %.9g after the root at %.9g", what, depth[k], root_depth);
        CHECK(depth[k] >= root_depth - early_slack, "%s: depth %.9g, more than %g before the root at %.9g", what,
              depth[k], early_slack, root_depth);
        lo = fminf(lo, depth[k]);
        hi = fmaxf(hi, depth[k]);
    }
    test_note("%s: depths %.7g .. %.7g, the root at %.7g", what, lo, hi, root_depth);
}

static void check_render(const double time[2], const char *what) {
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    iacsg_renderer *r = NULL;
    CHECK(iacsg_expr_parse(plane_text, "<test>", &e, &err) == IACSG_OK, "%s", err.message);
    iacsg_render_config config = {.fp64 = FP64};
    iacsg_status st = iacsg_renderer_create_expr(e, &config, &r, &err);
    iacsg_expr_destroy(e);
    CHECK(st == IACSG_OK, "renderer: %s", err.message);
    iacsg_view v = plane_view();
    v.time[0] = time[0];
    v.time[1] = time[1];
    iacsg_frame frame;
    st = iacsg_render(r, &v, &frame, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "render: %s", err.message);
    check_depths(frame.depth, v.width * v.height, what);
    iacsg_frame_free(&frame);
}

TEST_FP(render_time_encloses_the_real_time) {
    double t[2];
    CHECK(ia_decimal_double("0.7", &t[0], &t[1]) == 0 && t[0] < t[1], "0.7 is not enclosed");
    check_render(t, "time 0.7");
    iacsg_frame_time(7, 10, t);
    check_render(t, "frame 7 of 10");
}

/* The same through the command: -time 0.7 is the real 7/10. */
TEST_FP(render_time_cli_encloses_the_real_time) {
    char dir[256], cmd[2048], path[512];
    snprintf(dir, sizeof dir, "/tmp/iacsg-time%d-%ld", FP64, (long)getpid());
    CHECK(mkdir(dir, 0700) == 0, "cannot create %s", dir);
    snprintf(cmd, sizeof cmd,
             "cd '%s' && '%s' '%s' -time 0.7 -eye 0,0,3 -at 0,0,0 -up 0,1,0 -ortho 1 -bounds -1,-1,-2,1,1,2 "
             "-size 16x16 -o t.png -depth t.exr%s >/dev/null 2>&1",
             dir, test_binary_path(), plane_text, FP64 ? " -fp64" : "");
    CHECK(system(cmd) == 0, "%s failed", cmd);
    snprintf(path, sizeof path, "%s/t.exr", dir);
    int w, h, ch;
    float *depth = NULL;
    iacsg_error err = {0};
    CHECK(iacsg_image_read(path, &w, &h, &ch, &depth, &err) == IACSG_OK, "%s", err.message);
    check_depths(depth, w * h, "iacsg -time 0.7");
    free(depth);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0, "cannot clean %s", dir);
}

/* iacsg_frame_time(k, n) encloses k/n, as a point when k/n is a double, else between neighbouring doubles; and
 * so does its outward rounding to the working precision (src/render.c). Checked exactly: the sign of
 * fma(q, n, -k) is that of q - k/n. */
TEST_FP(render_frame_time_encloses_k_over_n) {
    test_rng_t *rng = test_rng();
    long n_iters = test_iters(100000), points = 0;
    for (long it = 0; it < n_iters; it++) {
        int n = 1 + (int)(test_rand_u64(rng) % 100000), k = (int)(test_rand_u64(rng) % (unsigned)n);
        double t[2];
        iacsg_frame_time(k, n, t);
        CHECK(fma(t[0], n, -k) <= 0 && fma(t[1], n, -k) >= 0, "%d/%d: [%a, %a]", k, n, t[0], t[1]);
        CHECK(t[0] == t[1] || nextafter(t[0], INFINITY) == t[1], "%d/%d: [%a, %a] is not tight", k, n, t[0], t[1]);
        points += t[0] == t[1];
        float lo = (float)t[0], hi = (float)t[1];
        lo = (double)lo > t[0] ? nextafterf(lo, -INFINITY) : lo;
        hi = (double)hi < t[1] ? nextafterf(hi, INFINITY) : hi;
        CHECK(fma(lo, n, -k) <= 0 && fma(hi, n, -k) >= 0, "%d/%d: float [%a, %a]", k, n, lo, hi);
    }
    CHECK(points < n_iters, "no k/n needed an interval");
    test_note("%ld fractions, %ld of them doubles", n_iters, points);
}
