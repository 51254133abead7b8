/* tests/t_scene_check.h -- ref_check_scene: renders a scene by the segment path and checks EVERY pixel against the
 * exact reference (tests/t_scene_ref.h). With the exact first item R at ts (a region's first claimed partition or
 * a surface's first kept point), or none: the renderer's id is R (-1 and depth +inf for none), its depth is never
 * after ts and, where the ray is not grazing the boundary there (|n.d| > 0.25, n its normal), at most k eps
 * before it, k = 1 + sum |n_i d_i| / |n.d| (README: a leaf holds the boundary, or an earlier leaf's box, not its
 * segment, comes near it); except on the pixels ref_ambiguous calls so, which are counted and must stay few.
 * For tests/t_render_*_fp.c. */
#ifndef T_SCENE_CHECK_H
#define T_SCENE_CHECK_H
#include "t_scene_ref.h"

#ifdef IA_FP64
#define REF_FP64 1
#else
#define REF_FP64 0
#endif

#define REF_SIZE 96
#define REF_EPS 1e-3
#define REF_MARGIN (4 * REF_EPS)

/* Renders the scene (taking it over) at REF_SIZE x REF_SIZE, bounds [-2, 2]^3, eps REF_EPS, and checks every
 * pixel against the reference. Counts in seen[item] (when not NULL) the pixels checked on each item. */
static inline void ref_check_scene(const char *name, ref_scene *rs, const iacsg_camera *camera, long *seen) {
    iacsg_view view = {.width = REF_SIZE, .height = REF_SIZE, .eps = REF_EPS, .camera = *camera,
                       .bounds = {-2, -2, -2, 2, 2, 2}};
    iacsg_render_config config = {.fp64 = REF_FP64};
    iacsg_error err = {0};
    iacsg_renderer *r = NULL;
    CHECK(iacsg_renderer_create_scene(rs->scene, &config, &r, &err) == IACSG_OK, "%s: %s", name, err.message);
    iacsg_frame fr;
    iacsg_status st = iacsg_render(r, &view, &fr, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "%s: %s", name, err.message);
    CHECK(fr.ids && fr.depth, "%s: no ids or depth", name);
    ia_real p[PARAM_COUNT];
    view_params(&view, p);
    long ambiguous = 0, claimed = 0;
    double worst_early = 0;
    for (int j = 0; j < REF_SIZE; j++)
        for (int i = 0; i < REF_SIZE; i++) {
            ref_ray ray;
            ref_pixel_ray(p, &view, i, j, &ray);
            long double t0 = 0, t1 = 0, ts = INFINITY;
            int inside = ref_clip(view.bounds, &ray, &t0, &t1);
            ref_set_ray(rs, &ray);
            int solid = -1, id = inside ? ref_first_item(rs, t0, t1, &ts, &solid) : -1;
            size_t px = (size_t)j * REF_SIZE + (size_t)i;
            int got = (int)fr.ids[px];
            double depth = fr.depth[px];
            claimed += id >= 0;
            if (inside && ref_ambiguous(rs, &ray, t0, t1, id >= 0 ? ts : t1, REF_MARGIN)) {
                ambiguous++;
                continue;
            }
            CHECK(got == id, "%s pixel (%d, %d): id %d, the reference %d (at t = %.9Lg)", name, i, j, got, id, ts);
            if (id < 0) {
                CHECK(depth == INFINITY, "%s pixel (%d, %d): depth %.9g on a miss", name, i, j, depth);
                continue;
            }
            if (seen)
                seen[id]++;
            CHECK(depth <= ts * (1 + 1e-15L), "%s pixel (%d, %d): depth %.9g after the boundary at %.12Lg", name, i,
                  j, depth, ts);
            if (solid < 0)
                continue; /* it starts at the bounds */
            long double q[3], n[3], nd = 0, spread = 0;
            for (int k = 0; k < 3; k++)
                q[k] = ray.o[k] + ts * ray.d[k];
            ref_gradient(&rs->solids[solid], q, n);
            long double len = sqrtl(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int k = 0; k < 3; k++) {
                nd += n[k] * ray.d[k] / len;
                spread += fabsl(n[k] * ray.d[k]) / len;
            }
            if (fabsl(nd) <= 0.25L)
                continue; /* grazing */
            double early = (double)((ts - depth) / (REF_EPS * (1 + spread / fabsl(nd))));
            CHECK(early <= 1, "%s pixel (%d, %d): depth %.9g is %.2f k eps before the boundary at %.12Lg", name, i,
                  j, depth, early, ts);
            worst_early = fmax(worst_early, early);
        }
    iacsg_frame_free(&fr);
    iacsg_scene_destroy(rs->scene);
    rs->scene = NULL;
    test_note("%s: %d pixels, %ld hit, %ld ambiguous (margin %g); depth at most %.2f k eps early", name,
              REF_SIZE * REF_SIZE, claimed, ambiguous, REF_MARGIN, worst_early);
    CHECK(claimed > REF_SIZE * REF_SIZE / 20, "%s: too few pixels hit to test", name);
    CHECK(ambiguous < REF_SIZE * REF_SIZE / 10, "%s: %ld ambiguous pixels, too many to trust the test", name,
          ambiguous);
}

#endif
