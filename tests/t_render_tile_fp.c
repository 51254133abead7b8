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
