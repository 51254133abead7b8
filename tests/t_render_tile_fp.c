/* tests/t_render_tile_fp.c -- the tile pass's box (kernels/tile.h, compiled here as host C with the kernel's
 * precision) holds every pixel ray of its tile, and the rays of -aa's samples between their centres: for random
 * views, tiles, pixels and t ranges, the box of the pixel's own float ray over the range (ray_extent, itself
 * checked in t_render_traverse_fp.c), and of a random sample's of the pixel that lies between the tile's centres,
 * lies inside it. */
#include "ia/ia.h"

/* tile.h's search calls the expression's inclusion function; this test only uses tile_rays_of and tile_box. */
IA_FN ia_interval iacsg_F(ia_interval x, ia_interval y, ia_interval z, ia_interval t) {
    (void)t;
    return ia_add_r(ia_add(ia_add(ia_sqr(x), ia_sqr(y)), ia_sqr(z)), -1);
}

#include "kernels/tile.h"
#include "t_render_util.h"

TEST_FP(render_tile_box_holds_its_rays) {
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
                    ia_real x2 = (ia_real)(2 * i + 1), y2 = (ia_real)(2 * j + 1);
                    if (sample) /* as kernels/effects.cl's for -aa N: cell (a, b) of N x N */
                        random_sample(rng, i, j, &x2, &y2);
                    if (x2 < 2 * i0 + 1 || x2 > 2 * i1 + 1 || y2 < 2 * j0 + 1 || y2 > 2 * j1 + 1)
                        continue; /* past the tile's outer centres: a sample traced from the root */
                    ia_real o[3], d[3];
                    camera_ray_at(p, ortho, x2, y2, w, h, o, d);
                    for (int k = 0; k < 3; k++) {
                        ia_interval x = ray_extent(o[k], d[k], ia_make(a, b));
                        CHECK(box[k].lo <= x.lo && x.hi <= box[k].hi,
                              "%s view, pixel (%d, %d) of tile (%d..%d, %d..%d), ray (%a, %a), axis %d: ray [%a, %a] "
                              "outside the tile box [%a, %a]",
                              ortho ? "orthographic" : "perspective", i, j, i0, i1, j0, j1, (double)x2, (double)y2,
                              k, (double)x.lo, (double)x.hi, (double)box[k].lo, (double)box[k].hi);
                    }
                    checked++;
                }
    }
    test_note("%ld pixel and sample rays checked against their tile's box", checked);
}
