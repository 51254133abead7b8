/* src/render_effects_edges.c -- -aa's edge test (render_effects_edges.h), a band of rows per CPU:
 *
 *   per band (whole rows of packets' blocks, one a thread): each row's ids, colour channels and depths apart (each
 *   in an array of its own, padded to whole vectors)
 *   --> the row against itself shifted by one pixel (left-right pairs) and against the next row (up-down pairs),
 *       four pixels at a time in vectors (GCC and Clang's vector extensions: SSE2 on any x86-64)
 *   --> each pixel of a row of blocks marked where a pair it belongs to differs, then listed in block order
 *   --> the bands' lists, each written where its rows' pixels would start, closed up in order.
 *
 * Why: the comparisons of a megapixel's neighbours, two million, one by one (about 30 instructions each, as the
 * compiler keeps them scalar at -O2) took 12-13 ms of the reference view's 75 ms -aa 4 frame, on one CPU; in
 * vectors a third of that. (A kernel on PoCL took 8-9 ms: tried, not kept.) Then the frame's byte map of edges
 * (a megapixel's page faults, ~3.5 ms here) and the pass that listed it in block order went, and the rows were
 * shared among the CPUs, which wait for this list with the device idle: 9.5 -> 3.5 ms on two CPUs. */
#include "render_effects_edges.h"
#include "kernels/params.h"
#include "parallel.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef float edge_v4 __attribute__((vector_size(16)));
typedef int edge_m4 __attribute__((vector_size(16)));
enum { EDGE_LANES = 4, EDGE_FIELDS = 5 }; /* per pixel: id, red, green, blue, depth */
enum { EDGE_BANDS_MAX = 8, EDGE_BAND_MIN_ROWS = 64 }; /* a band a thread */

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

/* A band's work: rows first .. last - 1 (whole rows of blocks but for the frame's last) of the traced rows row0 ..
 * row1 - 1, its edge pixels listed from out on; n how many, -1 out of memory. */
typedef struct {
    const iacsg_frame *fr;
    int row0, row1, first, last;
    float contrast, near_depth;
    int *out;
    long n;
} edge_band;

/* Lists the marked pixels of the row of blocks whose rows first .. first + rows - 1 have marks[] (width bytes a
 * row), in block order: blocks left to right, a block's pixels row by row. */
static long list_blocks(const unsigned char *marks, int width, int first, int rows, int *out) {
    long n = 0;
    for (int bi = 0; bi < width; bi += PACKET_W)
        for (int y = 0; y < rows; y++)
            for (int i = bi; i < bi + PACKET_W && i < width; i++)
                if (marks[(size_t)y * (size_t)width + (size_t)i])
                    out[n++] = (first + y) * width + i;
    return n;
}

static void *find_band(void *arg) {
    edge_band *b = arg;
    const iacsg_frame *fr = b->fr;
    int w = fr->width, padded = (w + EDGE_LANES - 1) / EDGE_LANES * EDGE_LANES + EDGE_LANES;
    float *fields = calloc(2 * EDGE_FIELDS * (size_t)padded, sizeof *fields);
    int *across = calloc(3 * (size_t)padded, sizeof *across), *down = across ? across + padded : NULL;
    int *up = across ? across + 2 * (size_t)padded : NULL; /* the pairs with the row above: its down */
    unsigned char *marks = malloc((size_t)PACKET_H * (size_t)w);
    b->n = -1;
    if (fields && across && marks) {
        edge_row rows[2];
        for (int k = 0; k < 2; k++)
            for (int f = 0; f < EDGE_FIELDS; f++)
                rows[k].field[f] = fields + (size_t)(k * EDGE_FIELDS + f) * (size_t)padded;
        edge_row *row = &rows[0], *next = &rows[1];
        int above = b->first > b->row0; /* the band's first row has a traced row above it */
        if (above) {
            fill_row(next, fr, b->first - 1);
            fill_row(row, fr, b->first);
            differ_rows(next, 0, row, 0, w, b->contrast, b->near_depth, up);
        } else if (b->first < b->last) {
            fill_row(row, fr, b->first);
        }
        b->n = 0;
        for (int j = b->first; j < b->last; j++) {
            int y = (j - b->row0) % PACKET_H, below = j + 1 < b->row1;
            differ_rows(row, 0, row, 1, w - 1, b->contrast, b->near_depth, across); /* with the pixel to the right */
            across[w - 1] = 0;
            if (below) { /* with the pixel below */
                fill_row(next, fr, j + 1);
                differ_rows(row, 0, next, 0, w, b->contrast, b->near_depth, down);
            }
            unsigned char *m = marks + (size_t)y * (size_t)w;
            for (int i = 0; i < w; i++)
                m[i] = (across[i] | (i > 0 ? across[i - 1] : 0) | (above ? up[i] : 0) | (below ? down[i] : 0)) & 1;
            if (y == PACKET_H - 1 || j + 1 == b->last)
                b->n += list_blocks(marks, w, j - y, y + 1, b->out + b->n);
            edge_row *swap = row;
            row = next;
            next = swap;
            int *was = up;
            up = down;
            down = was;
            above = below;
        }
    }
    free(fields);
    free(across);
    free(marks);
    return NULL;
}

long fx_find_edges_banded(const iacsg_frame *fr, int row0, int row1, float contrast, float near_depth, int bands,
                          int *out) {
    int blocks = (row1 - row0 + PACKET_H - 1) / PACKET_H;
    bands = bands > blocks ? blocks : bands > EDGE_BANDS_MAX ? EDGE_BANDS_MAX : bands;
    bands = bands < 1 ? 1 : bands;
    edge_band band[EDGE_BANDS_MAX];
    for (int k = 0; k < bands; k++) {
        int first = row0 + blocks * k / bands * PACKET_H, last = row0 + blocks * (k + 1) / bands * PACKET_H;
        band[k] = (edge_band){fr, row0, row1, first, last < row1 ? last : row1, contrast, near_depth,
                              out + (size_t)(first - row0) * (size_t)fr->width, 0};
    }
    parallel_each(find_band, band, sizeof band[0], bands);
    long n = 0;
    for (int k = 0; k < bands && n >= 0; k++) {
        if (band[k].n < 0) {
            n = -1;
            break;
        }
        memmove(out + n, band[k].out, (size_t)band[k].n * sizeof *out);
        n += band[k].n;
    }
    return n;
}

long fx_find_edges(const iacsg_frame *fr, int row0, int row1, float contrast, float near_depth, int *out) {
    int bands = (row1 - row0) / EDGE_BAND_MIN_ROWS, cpus = parallel_cpus(EDGE_BANDS_MAX);
    return fx_find_edges_banded(fr, row0, row1, contrast, near_depth, cpus < bands ? cpus : bands, out);
}
