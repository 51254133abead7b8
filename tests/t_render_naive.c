/* tests/t_render_naive.c -- the kernel's two correctness keys, one at a time. A host walk over the kernel's own
 * float rays (kernels/camera.h) and traversal order (kernels/traverse.h) changes either key alone:
 *   - its node ends gap-free (node_bound of the next index, as the kernel's) or gap-prone (hi = lo + width);
 *   - its interval arithmetic rounded outward (ia/ and ray_extent, as the kernel's) or not (the same operations in
 *     plain float, as a naive implementation does them);
 * and counts, over the rays that certainly pass through a shape, those that find no root and those whose leaf
 * starts after the exact first root. Float, so that ulps matter at these scales.
 *
 * Each key guards a different failure (the sphere seen from above at eps 1e-6, 32,928 rays through it):
 *   - gaps: at the origin, the gap-prone ends miss 52 rays without rounding, and with rounding, which covers the
 *     one-ulp gaps, still find 16 roots late (the root in a gap, the next node after it); gap-free ends miss none
 *     and are never late, rounded or not;
 *   - rounding: at z = 1000 the floats are 6e-5 apart and a leaf under 1e-6 long, so an unrounded leaf's box is
 *     single floats, and the walk finds the root where the rounded coordinates cross it: gap-free but unrounded,
 *     16,192 rays get a depth after the first root (by up to 3e-5, half that spacing). Rounded outward, the box
 *     holds the ray's points: none is late;
 *   - rounding, again: a rod of radius 2^-16 around y = z = 1024 + 2^-14, between the floats, crossed diagonally:
 *     the unrounded boxes step around the rod's lattice cell, and even the gap-free walk misses 613 of 617 rays
 *     through it; rounded outward, none.
 * The kernel, rendering the same rays (the sphere) or a view along the same diagonal (the rod), misses none and is
 * never late. */
#include "kernels/traverse.h"
#include "t_render_util.h"

/* The shapes, as sums of squares of shifted coordinates, sum over k of ((x_k - c_k) - s_k)^2 (the terms with
 * used[k]) minus r2: the unit sphere at c (s = 0), and the rod along x of radius 2^-16 around y = z = 1024 +
 * 2^-14, which is no float: a program computes it as (y - 1024) - 2^-14. */
typedef struct {
    ia_real c[3], s[3], r2;
    int used[3];
} shape;

/* Whether F of the shape holds 0 over the box of the ray segment t: in ia/'s outward-rounded intervals, or in
 * plain float with the same operations and no widening. */
typedef int (*shape_holds_zero)(const ia_real o[3], const ia_real d[3], ia_interval t, const shape *sh);

static int rounded_holds_zero(const ia_real o[3], const ia_real d[3], ia_interval t, const shape *sh) {
    ia_interval f = ia_point(-sh->r2);
    for (int k = 0; k < 3; k++) {
        if (!sh->used[k])
            continue;
        ia_interval x = ia_add_r(ray_extent(o[k], d[k], t), -sh->c[k]);
        f = ia_add(f, ia_sqr(sh->s[k] != 0 ? ia_add_r(x, -sh->s[k]) : x));
    }
    return ia_contains_zero(f);
}

static int plain_holds_zero(const ia_real o[3], const ia_real d[3], ia_interval t, const shape *sh) {
    ia_real lo = -sh->r2, hi = -sh->r2;
    for (int k = 0; k < 3; k++) {
        if (!sh->used[k])
            continue;
        ia_real first = d[k] >= 0 ? t.lo : t.hi, last = d[k] >= 0 ? t.hi : t.lo;
        ia_real a = fma(d[k], first, o[k]) - sh->c[k] - sh->s[k], b = fma(d[k], last, o[k]) - sh->c[k] - sh->s[k];
        lo += a > 0 ? a * a : b < 0 ? b * b : 0;
        hi += fmax(a * a, b * b);
    }
    return lo <= 0 && 0 <= hi;
}

/* The kernel's walk for the first root in [t0, t0 + w], with the given arithmetic and node ends: the start of
 * the leaf found, +inf if none. */
static ia_real walk_first_root(shape_holds_zero holds_zero, int gap_free, const ia_real o[3], const ia_real d[3],
                               const shape *sh, ia_real t0, ia_real w, ia_real eps) {
    int level = 0;
    bisect_index i = 0;
    do {
        ia_real lo = node_bound(t0, w, level, i);
        ia_real hi = gap_free ? node_bound(t0, w, level, i + 1) : lo + w * node_scale(level);
        if (holds_zero(o, d, ia_make(lo, hi), sh)) {
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
    const shape sh = {{0, 0, (ia_real)cz}, {0, 0, 0}, 1, {1, 1, 1}};
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
                double start = walk_first_root(m >= 2 ? rounded_holds_zero : plain_holds_zero, m % 2, o, d, &sh, tn,
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

/* A rod thinner than the float spacing, crossed by rays diagonal to it: the unrounded walk's boxes, single floats
 * on each axis at the finest levels, step around the lattice cell that holds the rod (y first, then z, or the
 * other way), and miss it; the rounded boxes hold the ray's points and find it. Rays aimed within half the
 * radius of the axis from 45 +- 10 degrees, their origins rounded to floats; those whose float line passes within
 * 0.9 radius of the axis (exactly, in double) are counted. */
TEST(render_naive_unrounded_misses_thin_rod) {
    const double centre = 1024 + 0x1p-14, r = 0x1p-16;
    const shape rod = {{0, 1024, 1024}, {0, 0x1p-14f, 0x1p-14f}, (ia_real)(r * r), {0, 1, 1}};
    test_rng_t *rng = test_rng();
    long through = 0, missed[4] = {0};
    for (long n = 0; n < test_iters(2000); n++) {
        double angle = (35 + 20 * test_rand_unit(rng)) * 3.14159265358979 / 180;
        ia_real d[3] = {0, (ia_real)cos(angle), (ia_real)-sin(angle)}, o[3];
        double aim[3] = {0, centre + r * (test_rand_unit(rng) - 0.5), centre + r * (test_rand_unit(rng) - 0.5)};
        for (int k = 0; k < 3; k++)
            o[k] = (ia_real)(aim[k] - 3 * d[k]);
        double dy = d[1], dz = d[2];
        if (fabs((centre - o[1]) * dz - (centre - o[2]) * dy) / sqrt(dy * dy + dz * dz) > 0.9 * r)
            continue;
        through++;
        for (int m = 0; m < 4; m++)
            missed[m] += !isfinite(walk_first_root(m >= 2 ? rounded_holds_zero : plain_holds_zero, m % 2, o, d, &rod,
                                                   0, 6, (ia_real)1e-6));
    }
    /* the kernel, on a view along the same diagonal (its rays' origins round to a few floats near the axis) */
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse("(y - 1024.00006103515625)^2 + (z - 1024.00006103515625)^2 - 2^-32", "<test>", &e, &err) ==
              IACSG_OK, "%s", err.message);
    iacsg_render_config config = {0};
    iacsg_renderer *renderer = NULL;
    CHECK(iacsg_renderer_create_expr(e, &config, &renderer, &err) == IACSG_OK, "%s", err.message);
    iacsg_expr_destroy(e);
    iacsg_view v = {.width = 16, .height = 16, .eps = 1e-6, .bounds = {-1, 1022, 1022, 1, 1026, 1026},
                    .camera = {.eye = {0, 1022, 1026 + 0x1p-13}, .at = {0, centre, centre}, .up = {1, 0, 0},
                               .ortho_height = 8 * r}};
    iacsg_frame fr;
    CHECK(iacsg_render(renderer, &v, &fr, &err) == IACSG_OK, "%s", err.message);
    iacsg_renderer_destroy(renderer);
    ia_real p[PARAM_COUNT];
    view_params(&v, p);
    long kernel_through = 0, kernel_missed = 0;
    for (int j = 0; j < v.height; j++)
        for (int i = 0; i < v.width; i++) {
            double po[3], pd[3];
            pixel_ray(p, &v, i, j, po, pd);
            if (fabs((centre - po[1]) * pd[2] - (centre - po[2]) * pd[1]) / hypot(pd[1], pd[2]) > 0.9 * r)
                continue;
            kernel_through++;
            kernel_missed += !isfinite(fr.depth[(size_t)j * v.width + i]);
        }
    iacsg_frame_free(&fr);
    test_note("a rod of radius 2^-16 at y = z = 1024 + 2^-14, %ld rays through it: missed by the gap-prone "
              "unrounded walk %ld, gap-free unrounded %ld, gap-prone rounded %ld, gap-free rounded %ld; the kernel "
              "missed %ld of %ld",
              through, missed[0], missed[1], missed[2], missed[3], kernel_missed, kernel_through);
    CHECK(kernel_through > 0 && kernel_missed == 0, "the kernel missed %ld of %ld rays through the rod",
          kernel_missed, kernel_through);
    CHECK(through > test_iters(2000) / 4, "only %ld rays through the rod", through);
    CHECK(missed[3] == 0 && missed[2] == 0, "the rounded walks missed %ld and %ld rays", missed[3], missed[2]);
    CHECK(missed[1] > 0, "the unrounded gap-free walk missed nothing: this test shows nothing");
}
