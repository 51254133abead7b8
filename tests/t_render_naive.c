/* tests/t_render_naive.c -- the kernel's two correctness keys, one at a time. A host walk over the kernel's own
 * float rays (kernels/camera.h) and traversal order (kernels/traverse.h) changes either key alone:
 *   - its node ends gap-free (node_bound of the next index, as the kernel's) or gap-prone (hi = lo + width);
 *   - its interval arithmetic rounded outward (ia/ and ray_extent, as the kernel's) or not (the same operations in
 *     plain float, as a naive implementation does them);
 * and counts, over the rays that certainly pass through a unit sphere (by more than 1e-6), those that find no root
 * and those whose leaf starts after the exact first root. Float, so that ulps matter at these scales.
 *
 * Each key guards a different failure (the sphere seen from above at eps 1e-6, 32,928 rays through it):
 *   - gaps: at the origin, the gap-prone ends miss 52 rays without rounding, and with rounding, which covers the
 *     one-ulp gaps, still find 16 roots late (the root in a gap, the next node after it); gap-free ends miss none
 *     and are never late, rounded or not;
 *   - rounding: at z = 1000 the floats are 6e-5 apart and a leaf under 1e-6 long, so an unrounded leaf's box is
 *     single floats, and the walk finds the root where the rounded coordinates cross it: gap-free but unrounded,
 *     16,192 rays get a depth after the first root (by up to 3e-5, half that spacing). Rounded outward, the box
 *     holds the ray's points: none is late.
 * The kernel, rendering the same rays, misses none and is never late in either view. */
#include "kernels/traverse.h"
#include "t_render_util.h"

/* Whether F of the unit sphere at c holds 0 over the box of the ray segment t: in ia/'s outward-rounded
 * intervals, or in plain float with the same operations and no widening. */
typedef int (*sphere_holds_zero)(const ia_real o[3], const ia_real d[3], ia_interval t, const ia_real c[3]);

static int rounded_holds_zero(const ia_real o[3], const ia_real d[3], ia_interval t, const ia_real c[3]) {
    ia_interval f = ia_point(-1);
    for (int k = 0; k < 3; k++)
        f = ia_add(f, ia_sqr(ia_add_r(ray_extent(o[k], d[k], t), -c[k])));
    return ia_contains_zero(f);
}

static int plain_holds_zero(const ia_real o[3], const ia_real d[3], ia_interval t, const ia_real c[3]) {
    ia_real lo = -1, hi = -1;
    for (int k = 0; k < 3; k++) {
        ia_real first = d[k] >= 0 ? t.lo : t.hi, last = d[k] >= 0 ? t.hi : t.lo;
        ia_real a = fma(d[k], first, o[k]) - c[k], b = fma(d[k], last, o[k]) - c[k];
        lo += a > 0 ? a * a : b < 0 ? b * b : 0;
        hi += fmax(a * a, b * b);
    }
    return lo <= 0 && 0 <= hi;
}

/* The kernel's walk for the first root in [t0, t0 + w], with the given arithmetic and node ends: the start of
 * the leaf found, +inf if none. */
static ia_real walk_first_root(sphere_holds_zero holds_zero, int gap_free, const ia_real o[3], const ia_real d[3],
                           const ia_real c[3], ia_real t0, ia_real w, ia_real eps) {
    int level = 0;
    bisect_index i = 0;
    do {
        ia_real lo = node_bound(t0, w, level, i);
        ia_real hi = gap_free ? node_bound(t0, w, level, i + 1) : lo + w * node_scale(level);
        if (holds_zero(o, d, ia_make(lo, hi), c)) {
            if (hi - lo <= eps || level == BISECT_MAX_LEVEL)
                return lo;
            level += 1;
            i <<= 1;
        } else if (!node_next(&level, &i)) {
            return IA_INF;
        }
    } while (1);
}

/* Misses and late depths of the four walks (index: 2 * rounded + gap_free) and of the kernel. */
typedef struct {
    long through, missed[4], late[4], kernel_missed, kernel_late;
    double latest[4]; /* the largest depth - root */
} naive_report;

/* Renders the unit sphere at height cz looking straight down, as a heightmap renderer does (x and y are exact along
 * each ray, so the enclosures are tight), and walks every ray that passes through it in the four ways. The box
 * is not a power of two wide, so that the widths of the levels are not dyadic and lo + width rounds. */
static naive_report walk_sphere_view(double cz) {
    const sphere s = {{0, 0, cz}, 1};
    const ia_real c[3] = {0, 0, (ia_real)cz};
    iacsg_view v = {.width = 256, .height = 256, .eps = 1e-6,
                    .bounds = {-1.3, -1.3, cz - 1.3, 1.3, 1.3, cz + 1.3},
                    .camera = {.eye = {0, 0, cz + 3.1}, .at = {0, 0, cz}, .up = {0, 1, 0}, .ortho_height = 2.5}};
    char *cl = spheres_cl(s, s, SOLID_A);
    iacsg_render_config config = {0};
    iacsg_frame fr;
    render_cl(cl, &config, &v, &fr);
    free(cl);
    ia_real p[PARAM_COUNT];
    view_params(&v, p);
    for (int k = 0; k < 6; k++)
        p[PARAM_BOX + k] = (ia_real)v.bounds[k];
    naive_report rep = {0};
    for (int j = 0; j < v.height; j++)
        for (int i = 0; i < v.width; i++) {
            ia_real o[3], d[3], tn, tf;
            camera_ray(p, RENDER_ORTHO, i, j, v.width, v.height, o, d);
            double od[3] = {o[0], o[1], o[2]}, dd[3] = {d[0], d[1], d[2]}, t1, t2;
            if (!sphere_span(s, od, dd, &t1, &t2) || t2 - t1 < 1e-6 || !camera_clip(p, o, d, &tn, &tf))
                continue; /* only rays that certainly pass through the sphere */
            rep.through++;
            double depth = fr.depth[(size_t)j * v.width + i];
            rep.kernel_missed += !isfinite(depth);
            rep.kernel_late += isfinite(depth) && depth > t1;
            for (int m = 0; m < 4; m++) {
                double start = walk_first_root(m >= 2 ? rounded_holds_zero : plain_holds_zero, m % 2, o, d, c, tn,
                                               tf - tn, (ia_real)v.eps);
                rep.missed[m] += !isfinite(start);
                rep.late[m] += isfinite(start) && start > t1;
                if (isfinite(start))
                    rep.latest[m] = fmax(rep.latest[m], start - t1);
            }
        }
    iacsg_frame_free(&fr);
    static const char *const walks[] = {"gap-prone unrounded", "gap-free unrounded", "gap-prone rounded",
                                        "gap-free rounded"};
    test_note("sphere at z = %g, %ld rays through it; the kernel: %ld missed, %ld late", cz, rep.through,
              rep.kernel_missed, rep.kernel_late);
    for (int m = 0; m < 4; m++)
        test_note("    %s walk: %ld missed, %ld late (by up to %.3g)", walks[m], rep.missed[m], rep.late[m],
                  rep.latest[m]);
    CHECK(rep.through > 30000, "only %ld rays through the sphere", rep.through);
    CHECK(rep.kernel_missed == 0 && rep.kernel_late == 0, "the kernel missed %ld pixels, %ld late",
          rep.kernel_missed, rep.kernel_late);
    CHECK(rep.missed[3] == 0 && rep.late[3] == 0, "the walk with the kernel's two keys missed %ld rays, %ld late",
          rep.missed[3], rep.late[3]);
    return rep;
}

/* Gap-prone ends lose roots; gap-free ones need no rounding to find these. */
TEST(render_naive_gaps_miss_pixels) {
    naive_report rep = walk_sphere_view(0);
    CHECK(rep.missed[0] > 0, "hi = lo + width without rounding missed nothing: this test shows nothing");
    CHECK(rep.late[2] > 0, "hi = lo + width with rounding was never late: this test shows nothing");
    CHECK(rep.missed[1] == 0 && rep.late[1] == 0, "near the origin, gap-free ends without rounding missed %ld rays, "
          "%ld late", rep.missed[1], rep.late[1]);
}

/* Far from the origin, gap-free ends without outward rounding give depths after the first root. */
TEST(render_naive_unrounded_depth_late) {
    naive_report rep = walk_sphere_view(1000);
    CHECK(rep.late[1] > 0, "the unrounded gap-free walk was never late: this test shows nothing");
}
