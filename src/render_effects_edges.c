/* src/render_effects_edges.c -- -aa's edge test (render_effects_edges.h), a row at a time:
 *
 *   each row's ids, colour channels and depths apart (each in an array of its own, padded to whole vectors)
 *   --> the row against itself shifted by one pixel (left-right pairs) and against the next row (up-down pairs),
 *       four pixels at a time in vectors (GCC and Clang's vector extensions: SSE2 on any x86-64)
 *   --> each pixel marked where a pair it belongs to differs.
 *
 * Why: the comparisons of a megapixel's neighbours, two million, one by one (about 30 instructions each, as the
 * compiler keeps them scalar at -O2) took 12-13 ms of the reference view's 75 ms -aa 4 frame, on one CPU; in
 * vectors a third of that. (A kernel on PoCL took 8-9 ms: tried, not kept.) */
#include "render_effects_edges.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef float edge_v4 __attribute__((vector_size(16)));
typedef int edge_m4 __attribute__((vector_size(16)));
enum { EDGE_LANES = 4, EDGE_FIELDS = 5 }; /* per pixel: id, red, green, blue, depth */

/* A row's fields, each padded to whole vectors and one more (the row shifted by one pixel reads past it). */
typedef struct {
    float *field[EDGE_FIELDS];
} edge_row;

static edge_v4 load4(const float *p) {
    edge_v4 v;
    memcpy(&v, p, sizeof v);
    return v;
}

static edge_v4 abs4(edge_v4 v) { return (edge_v4)((edge_m4)v & 0x7fffffff); }

static edge_v4 min4(edge_v4 a, edge_v4 b) {
    edge_m4 less = a < b;
    return (edge_v4)(((edge_m4)a & less) | ((edge_m4)b & ~less));
}

static void fill_row(edge_row *r, const iacsg_frame *fr, int j) {
    size_t p = (size_t)j * (size_t)fr->width;
    for (int i = 0; i < fr->width; i++, p++) {
        float depth = fr->depth[p];
        r->field[0][i] = isinf(depth) ? -1 : fr->ids ? fr->ids[p] : 0;
        for (int c = 0; c < 3; c++)
            r->field[1 + c][i] = fr->rgb[3 * p + c];
        r->field[4][i] = depth;
    }
}

/* out[i] = -1 where pixel a_at + i of row a and pixel b_at + i of row b differ, else 0, for i < n (rounded up to
 * whole vectors). */
static void differ_rows(const edge_row *a, int a_at, const edge_row *b, int b_at, int n, float contrast,
                        float near_depth, int *out) {
    for (int i = 0; i < n; i += EDGE_LANES) {
        edge_v4 id_a = load4(a->field[0] + a_at + i), id_b = load4(b->field[0] + b_at + i);
        edge_m4 differs = id_a != id_b;
        for (int c = 1; c <= 3; c++)
            differs |= abs4(load4(a->field[c] + a_at + i) - load4(b->field[c] + b_at + i)) > contrast;
        edge_v4 d_a = load4(a->field[4] + a_at + i), d_b = load4(b->field[4] + b_at + i);
        differs |= (id_a >= 0) & (abs4(d_a - d_b) > near_depth * min4(d_a, d_b)); /* a miss's inf - inf: false */
        memcpy(out + i, &differs, sizeof differs);
    }
}

int fx_find_edges(const iacsg_frame *fr, int row0, int row1, float contrast, float near_depth, unsigned char *edge) {
    int w = fr->width, padded = (w + EDGE_LANES - 1) / EDGE_LANES * EDGE_LANES + EDGE_LANES;
    float *block = calloc(2 * EDGE_FIELDS * (size_t)padded, sizeof *block);
    int *across = calloc(2 * (size_t)padded, sizeof *across), *down = across ? across + padded : NULL;
    if (!block || !across) {
        free(block);
        free(across);
        return -1;
    }
    edge_row rows[2];
    for (int k = 0; k < 2; k++)
        for (int f = 0; f < EDGE_FIELDS; f++)
            rows[k].field[f] = block + (size_t)(k * EDGE_FIELDS + f) * (size_t)padded;
    edge_row *row = &rows[0], *next = &rows[1];
    if (row0 < row1)
        fill_row(row, fr, row0);
    for (int j = row0; j < row1; j++) {
        differ_rows(row, 0, row, 1, w - 1, contrast, near_depth, across); /* with the pixel to the right */
        across[w - 1] = 0;
        int below = j + 1 < row1;
        if (below) { /* with the pixel below */
            fill_row(next, fr, j + 1);
            differ_rows(row, 0, next, 0, w, contrast, near_depth, down);
        }
        unsigned char *e = edge + (size_t)j * (size_t)w;
        for (int i = 0; i < w; i++)
            e[i] |= (across[i] | (i > 0 ? across[i - 1] : 0) | (below ? down[i] : 0)) & 1;
        for (int i = 0; below && i < w; i++)
            e[w + i] |= down[i] & 1;
        edge_row *swap = row;
        row = next;
        next = swap;
    }
    free(block);
    free(across);
    return 0;
}
