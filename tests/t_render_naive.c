/* tests/t_render_naive.c -- why the kernel needs both of its correctness keys: a naive bisection, with ends
 * recomputed as hi = lo + width and no outward rounding (this file is compiled with IA_FAST), misses pixels
 * of a plain sphere that the kernel, rendering the same float rays, never misses.
 *
 * The naive walk runs here on the host, over the kernel's own float rays (kernels/camera.h) and traversal
 * order (kernels/traverse.h); only the node's upper end differs. Float intervals (ulps matter at eps 1e-5). */
#define IA_FAST
#include "kernels/traverse.h"
#include "t_render_util.h"

/* The unit sphere's inclusion function in unrounded interval arithmetic. */
static ia_interval naive_sphere(ia_interval x, ia_interval y, ia_interval z) {
    return ia_add_r(ia_add(ia_add(ia_sqr(x), ia_sqr(y)), ia_sqr(z)), -1);
}

/* The kernel's bisect_first_root with the gap-prone end hi = lo + width. */
static int naive_first_root(const ia_real o[3], const ia_real d[3], ia_real t0, ia_real w, ia_real eps) {
    int level = 0;
    bisect_index i = 0;
    do {
        ia_real lo = node_bound(t0, w, level, i), hi = lo + w * ldexp((ia_real)1, -level);
        ia_interval t = ia_make(lo, hi);
        ia_interval f =
            naive_sphere(ray_extent(o[0], d[0], t), ray_extent(o[1], d[1], t), ray_extent(o[2], d[2], t));
        if (ia_contains_zero(f)) {
            if (hi - lo <= eps || level == BISECT_MAX_LEVEL)
                return 1;
            level += 1;
            i <<= 1;
        } else if (!node_next(&level, &i)) {
            return 0;
        }
    } while (1);
}

TEST(render_naive_kernel_misses_pixels) {
    const sphere s = {{0, 0, 0}, 1};
    /* Looking straight down, as a heightmap renderer does: x and y are exact along each ray, so the enclosure is
     * tight and a root in a gap between two nodes is excluded by both. The box is not a power of two wide, so
     * that the widths of the levels are not dyadic and lo + width rounds. At eps 1e-5 about 0.4 % of these rays
     * have their root in a gap at some level, but the naive rounding slop or a deeper node's overshoot happens
     * to cover it; at eps 1e-6 (a few ulps of t) the naive walk misses for real. */
    iacsg_view v = {.width = 256, .height = 256, .eps = 1e-6, .bounds = {-1.3, -1.3, -1.3, 1.3, 1.3, 1.3},
                    .camera = {.eye = {0, 0, 3.1}, .at = {0, 0, 0}, .up = {0, 1, 0}, .ortho_height = 2.5}};
    char *cl = spheres_cl(s, s, SOLID_A);
    iacsg_render_config config = {0};
    iacsg_frame fr;
    render_cl(cl, &config, &v, &fr);
    free(cl);
    ia_real p[PARAM_COUNT];
    view_params(&v, p);
    for (int k = 0; k < 6; k++)
        p[PARAM_BOX + k] = (ia_real)v.bounds[k];
    long through = 0, naive_misses = 0, kernel_misses = 0;
    for (int j = 0; j < v.height; j++)
        for (int i = 0; i < v.width; i++) {
            ia_real o[3], d[3], tn, tf;
            camera_ray(p, RENDER_ORTHO, i, j, v.width, v.height, o, d);
            double od[3] = {o[0], o[1], o[2]}, dd[3] = {d[0], d[1], d[2]}, t1, t2;
            if (!sphere_span(s, od, dd, &t1, &t2) || t2 - t1 < 1e-6)
                continue; /* only rays that certainly pass through the sphere */
            through++;
            kernel_misses += !isfinite(fr.depth[(size_t)j * v.width + i]);
            naive_misses += !(camera_clip(p, o, d, &tn, &tf) && naive_first_root(o, d, tn, tf - tn, (ia_real)v.eps));
        }
    iacsg_frame_free(&fr);
    test_note("%ld rays through the sphere: the naive bisection misses %ld (%.2f %%), the kernel %ld", through,
              naive_misses, 100.0 * naive_misses / through, kernel_misses);
    CHECK(kernel_misses == 0, "the kernel missed %ld pixels", kernel_misses);
    CHECK(naive_misses > 0, "the naive bisection missed nothing: this test shows nothing");
}
