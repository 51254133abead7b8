/* tests/t_render_tile_fp.c -- the tile pass's box (kernels/tile.h, compiled here as host C with the kernel's
 * precision) holds every pixel ray of its tile: for random views, tiles, pixels and t ranges, the box of the
 * pixel's own float ray over the range (ray_extent, itself checked in t_render_traverse_fp.c) lies inside it. */
#include "ia/ia.h"

/* tile.h's search calls the expression's inclusion function; this test only uses tile_rays_of and tile_box. */
IA_FN ia_interval iacsg_F(ia_interval x, ia_interval y, ia_interval z, ia_interval t) {
    (void)t;
    return ia_add_r(ia_add(ia_add(ia_sqr(x), ia_sqr(y)), ia_sqr(z)), -1);
}

#include "kernels/tile.h"
#include "t_render_util.h"

static double uniform(test_rng_t *rng, double lo, double hi) { return lo + (hi - lo) * test_rand_unit(rng); }

TEST_FP(render_tile_box_holds_its_rays) {
    test_rng_t *rng = test_rng();
    long checked = 0;
    for (long it = 0; it < test_iters(3000); it++) {
        int ortho = (int)(test_rand_u64(rng) & 1), w = 1 + (int)(test_rand_u64(rng) % 300),
            h = 1 + (int)(test_rand_u64(rng) % 300);
        iacsg_view v = {.width = w, .height = h,
                        .camera = {.eye = {uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -5, 5)},
                                   .at = {uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)},
                                   .up = {uniform(rng, -1, 1), uniform(rng, -1, 1), 1},
                                   .fov = uniform(rng, 5, 150),
                                   .ortho_height = ortho ? uniform(rng, 0.1, 8) : 0}};
        double pd[PARAM_COUNT];
        iacsg_error err = {0};
        if (iacsg_camera_params(&v.camera, w, h, pd, &err) != IACSG_OK)
            continue; /* a degenerate random view */
        ia_real p[PARAM_COUNT];
        view_params(&v, p);
        int tx = (int)(test_rand_u64(rng) % (unsigned)((w + TILE_SIZE - 1) / TILE_SIZE));
        int ty = (int)(test_rand_u64(rng) % (unsigned)((h + TILE_SIZE - 1) / TILE_SIZE));
        int i0 = tx * TILE_SIZE, j0 = ty * TILE_SIZE;
        int i1 = (i0 + TILE_SIZE < w ? i0 + TILE_SIZE : w) - 1, j1 = (j0 + TILE_SIZE < h ? j0 + TILE_SIZE : h) - 1;
        ia_real a = (ia_real)uniform(rng, 0, 10), b = a + (ia_real)uniform(rng, 0, 1);
        ia_interval box[3];
        tile_rays rays;
        tile_rays_of(p, ortho, i0, i1, j0, j1, w, h, &rays);
        tile_box(&rays, ia_make(a, b), box);
        for (int j = j0; j <= j1; j++)
            for (int i = i0; i <= i1; i++) {
                ia_real o[3], d[3];
                camera_ray(p, ortho, i, j, w, h, o, d);
                for (int k = 0; k < 3; k++) {
                    ia_interval x = ray_extent(o[k], d[k], ia_make(a, b));
                    CHECK(box[k].lo <= x.lo && x.hi <= box[k].hi,
                          "%s view, pixel (%d, %d) of tile (%d..%d, %d..%d), axis %d: ray [%a, %a] outside the tile "
                          "box [%a, %a]",
                          ortho ? "orthographic" : "perspective", i, j, i0, i1, j0, j1, k, (double)x.lo,
                          (double)x.hi, (double)box[k].lo, (double)box[k].hi);
                }
                checked++;
            }
    }
    test_note("%ld pixel rays checked against their tile's box", checked);
}
