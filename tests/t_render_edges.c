/* tests/t_render_edges.c -- -aa's edge test in vectors (src/render_effects_edges.c) against the test as written,
 * pair by pair: random frames of widths that are and are not whole vectors or blocks, with and without ids, misses
 * (depth +inf), colours and depths near the thresholds, traced rows that start anywhere, split among 1 to 5 bands
 * (threads); the list against the marked pixels listed in block order. */
#include "render_effects_edges.h"
#include "kernels/params.h"
#include "test.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

static float id_of(const iacsg_frame *fr, size_t p) { return isinf(fr->depth[p]) ? -1 : fr->ids ? fr->ids[p] : 0; }

/* The test as README states it, for the pair (a, b), in float as the vectors compute it. */
static int pair_differs(const iacsg_frame *fr, size_t a, size_t b, float contrast, float near_depth) {
    float ia = id_of(fr, a), ib = id_of(fr, b);
    if (ia != ib)
        return 1;
    for (int c = 0; c < 3; c++)
        if (fabsf(fr->rgb[3 * a + c] - fr->rgb[3 * b + c]) > contrast)
            return 1;
    return ia >= 0 && fabsf(fr->depth[a] - fr->depth[b]) > near_depth * fminf(fr->depth[a], fr->depth[b]);
}

/* A value near `base`, often within a float's rounding of base + step (the threshold's edge). */
static float near(test_rng_t *rng, float base, float step) {
    double u = test_rand_unit(rng);
    return u < 0.5 ? base : u < 0.8 ? base + step * (float)(test_rand_unit(rng) * 2) : base + step;
}

TEST(render_edges_match_the_pairwise_test) {
    test_rng_t *rng = test_rng();
    const float contrast = 1.0f / 16, near_depth = 0.02f;
    long pixels = 0, edges = 0;
    for (int it = 0; it < test_iters(2000); it++) {
        int tall = it % 8 == 0; /* rows for several bands of whole blocks */
        int w = 1 + (int)(test_rand_u64(rng) % 41), h = 1 + (int)(test_rand_u64(rng) % (tall ? 60 : 9));
        int bands = 1 + (int)(test_rand_u64(rng) % 5);
        size_t n = (size_t)w * h;
        iacsg_frame fr = {.width = w, .height = h};
        fr.rgb = malloc(3 * n * sizeof(float));
        fr.depth = malloc(n * sizeof(float));
        fr.ids = test_rand_u64(rng) % 2 ? malloc(n * sizeof(float)) : NULL;
        unsigned char *expected = calloc(n, 1);
        int *listed = malloc((n + 1) * sizeof *listed), *in_order = malloc((n + 1) * sizeof *in_order);
        CHECK(fr.rgb && fr.depth && expected && listed && in_order, "out of memory");
        for (size_t p = 0; p < n; p++) {
            int miss = test_rand_u64(rng) % 5 == 0;
            fr.depth[p] = miss ? INFINITY : near(rng, 3, 0.06f);
            if (fr.ids)
                fr.ids[p] = miss ? -1 : (float)(test_rand_u64(rng) % 3);
            for (int c = 0; c < 3; c++)
                fr.rgb[3 * p + c] = near(rng, 0.5f, contrast);
        }
        int row0 = (int)(test_rand_u64(rng) % (unsigned)h);
        int row1 = row0 + 1 + (int)(test_rand_u64(rng) % (unsigned)(h - row0));
        long got = fx_find_edges_banded(&fr, row0, row1, contrast, near_depth, bands, listed);
        CHECK(got >= 0, "out of memory");
        for (int j = row0; j < row1; j++)
            for (int i = 0; i < w; i++) {
                size_t p = (size_t)j * w + i;
                if (i + 1 < w && pair_differs(&fr, p, p + 1, contrast, near_depth))
                    expected[p] = expected[p + 1] = 1;
                if (j + 1 < row1 && pair_differs(&fr, p, p + w, contrast, near_depth))
                    expected[p] = expected[p + w] = 1;
            }
        long want = 0; /* blocks of PACKET_W x PACKET_H from row0, a block's pixels row by row */
        for (int bj = row0; bj < row1; bj += PACKET_H)
            for (int bi = 0; bi < w; bi += PACKET_W)
                for (int j = bj; j < bj + PACKET_H && j < row1; j++)
                    for (int i = bi; i < bi + PACKET_W && i < w; i++)
                        if (expected[(size_t)j * w + i])
                            in_order[want++] = j * w + i;
        CHECK(got == want, "%dx%d frame, rows %d..%d, %d bands, %s ids: %ld pixels listed, expected %ld", w, h, row0,
              row1 - 1, bands, fr.ids ? "with" : "without", got, want);
        for (long k = 0; k < want; k++)
            CHECK(listed[k] == in_order[k], "%dx%d frame, rows %d..%d, %d bands: entry %ld is pixel (%d, %d), expected "
                  "(%d, %d)", w, h, row0, row1 - 1, bands, k, listed[k] % w, listed[k] / w, in_order[k] % w,
                  in_order[k] / w);
        edges += want;
        pixels += (long)n;
        free(fr.rgb);
        free(fr.depth);
        free(fr.ids);
        free(expected);
        free(listed);
        free(in_order);
    }
    test_note("%ld pixels, %ld on an edge", pixels, edges);
}
