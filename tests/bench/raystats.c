/* tests/bench/raystats.c -- where the bisection's evaluations go, per pixel, on the host (not part of make test).
 *
 * Runs the kernel's own code (kernels/camera.h, kernels/bisect.h, the ia/ headers and the expression's emitted
 * source, all compiled as host C, as the tests do) over every pixel of a view, and reports what a profiler of
 * the device cannot see:
 *   - how the evaluations split between rays that hit, rays that miss inside the bounds, and the percentiles;
 *   - the SIMD efficiency of lockstep execution: sum of evaluations / (lanes x the group's maximum), for groups
 *     of adjacent pixels of several shapes (what a vectorised kernel would pay for divergence);
 *   - the share of min/max nodes whose one operand certainly dominates over the ray box (what tape pruning
 *     could skip, an upper bound at the ray level);
 *   - the neighbour-hit idea: one evaluation over [t_near, t_left_neighbour_hit - margin] and, when it is
 *     root-free, the bisection from there; the evaluations it would take instead.
 * The tile pass of kernels/tile.h is not simulated: these are full-ray bisections from the bounds.
 *
 * Build and run: tests/bench/raystats.sh EXPR [iacsg view options], which emits EXPR with `iacsg compile`.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ia/ia.h"

/* Count min/max nodes and those decided over the box; the emitted source calls ia_min and ia_max. */
static long long mm_calls, mm_decided;
static ia_interval bench_min(ia_interval a, ia_interval b) {
    mm_calls++;
    if (a.hi < b.lo || b.hi < a.lo)
        mm_decided++;
    return ia_min(a, b);
}
static ia_interval bench_max(ia_interval a, ia_interval b) {
    mm_calls++;
    if (a.hi < b.lo || b.hi < a.lo)
        mm_decided++;
    return ia_max(a, b);
}
/* The emitted point function calls OpenCL's pown; on the host, pow does (that function is not used here). */
#define pown(x, n) pow((x), (n))
#define ia_min bench_min
#define ia_max bench_max
#include EXPR_H
#undef ia_min
#undef ia_max
#undef pown

#define KERNEL_STATS
#include "kernels/bisect.h"
#include "kernels/camera.h"
#include "src/camera.h"

static int cmp_u(const void *a, const void *b) {
    unsigned x = *(const unsigned *)a, y = *(const unsigned *)b;
    return x < y ? -1 : x > y;
}

int main(int argc, char **argv) {
    if (argc != 22) {
        fprintf(stderr, "usage: raystats W H EPS EX EY EZ AX AY AZ UX UY UZ FOV ORTHO X0 Y0 Z0 X1 Y1 Z1 TIME\n");
        return 2;
    }
    int W = atoi(argv[1]), H = atoi(argv[2]);
    double eps = atof(argv[3]);
    iacsg_camera cam;
    memset(&cam, 0, sizeof cam);
    for (int k = 0; k < 3; k++) {
        cam.eye[k] = atof(argv[4 + k]);
        cam.at[k] = atof(argv[7 + k]);
        cam.up[k] = atof(argv[10 + k]);
    }
    cam.fov = atof(argv[13]);
    cam.ortho_height = atof(argv[14]);
    double pd[PARAM_COUNT] = {0};
    iacsg_error err = {0};
    if (iacsg_camera_params(&cam, W, H, pd, &err) != IACSG_OK) {
        fprintf(stderr, "raystats: %s\n", err.message);
        return 1;
    }
    ia_real p[PARAM_COUNT];
    for (int k = 0; k < PARAM_COUNT; k++)
        p[k] = (ia_real)pd[k];
    for (int k = 0; k < 6; k++)
        p[PARAM_BOX + k] = (ia_real)atof(argv[15 + k]);
    p[PARAM_EPS] = (ia_real)eps;
    ia_interval time = ia_point((ia_real)atof(argv[21]));
    int ortho = cam.ortho_height > 0;

    size_t n = (size_t)W * H;
    unsigned *ev = calloc(n, sizeof *ev), *sorted = malloc(n * sizeof *sorted);
    float *hit_t = malloc(n * sizeof *hit_t);
    long long in_box = 0, hits = 0, ev_hit = 0, ev_miss = 0;
    long long nb_tried = 0, nb_proven = 0, nb_evals = 0, nb_base = 0;
    long long mm_calls_all = 0, mm_decided_all = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            size_t px = (size_t)j * W + i;
            ia_real o[3], d[3], tn, tf, lo, hi;
            camera_ray(p, ortho, i, j, W, H, o, d);
            hit_t[px] = INFINITY;
            if (!camera_clip(p, o, d, &tn, &tf))
                continue;
            in_box++;
            kernel_u32 count = 0;
            mm_calls = mm_decided = 0;
            int hit = bisect_first_root(o, d, tn, ia_hi(tf - tn), p[PARAM_EPS], time, &lo, &hi, &count);
            mm_calls_all += mm_calls;
            mm_decided_all += mm_decided;
            ev[px] = count;
            if (hit) {
                hits++;
                ev_hit += count;
                hit_t[px] = (float)lo;
            } else {
                ev_miss += count;
            }
            /* neighbour hit: the left neighbour's start, less 2% of the way, as a guess */
            if (hit && i > 0 && isfinite(hit_t[px - 1])) {
                ia_real guess = (ia_real)hit_t[px - 1] * (ia_real)0.98;
                nb_tried++;
                nb_base += count;
                if (guess > tn) {
                    ia_interval t = ia_make(tn, guess);
                    ia_interval f = iacsg_F(ray_extent(o[0], d[0], t), ray_extent(o[1], d[1], t),
                                            ray_extent(o[2], d[2], t), time);
                    if (!ia_contains_zero(f)) {
                        kernel_u32 c2 = 0;
                        ia_real l2, h2;
                        bisect_first_root(o, d, guess, ia_hi(tf - guess), p[PARAM_EPS], time, &l2, &h2, &c2);
                        nb_proven++;
                        nb_evals += 1 + c2;
                        continue;
                    }
                    nb_evals += 1;
                }
                nb_evals += count;
            }
        }
    long long total = ev_hit + ev_miss;
    memcpy(sorted, ev, n * sizeof *ev);
    qsort(sorted, n, sizeof *sorted, cmp_u);
    printf("rays %zu, in the bounds %lld (%.1f%%), hits %lld (%.1f%%)\n", n, in_box, 100.0 * in_box / n, hits,
           100.0 * hits / n);
    printf("evaluations per ray: mean %.2f (hit rays %.2f, missing rays in the bounds %.2f)\n", (double)total / n,
           hits ? (double)ev_hit / hits : 0, in_box - hits ? (double)ev_miss / (in_box - hits) : 0);
    printf("share of evaluations on hit rays %.1f%%, on rays that miss inside the bounds %.1f%%\n",
           100.0 * ev_hit / total, 100.0 * ev_miss / total);
    printf("percentiles of evaluations per ray: p50 %u, p90 %u, p99 %u, p99.9 %u, max %u\n", sorted[n / 2],
           sorted[n * 9 / 10], sorted[n * 99 / 100], sorted[n * 999 / 1000], sorted[n - 1]);
    /* the heaviest 1% of rays: their share of all evaluations */
    long long top = 0;
    for (size_t k = n - n / 100; k < n; k++)
        top += sorted[k];
    printf("the heaviest 1%% of rays take %.1f%% of the evaluations\n", 100.0 * top / total);
    static const int shapes[][2] = {{4, 1}, {8, 1}, {16, 1}, {2, 2}, {4, 2}, {4, 4}, {8, 2}, {8, 8}};
    printf("SIMD efficiency of lockstep groups (sum / (lanes x group max)):");
    for (size_t s = 0; s < sizeof shapes / sizeof shapes[0]; s++) {
        int gw = shapes[s][0], gh = shapes[s][1];
        double sum = 0, cost = 0;
        for (int j0 = 0; j0 + gh <= H; j0 += gh)
            for (int i0 = 0; i0 + gw <= W; i0 += gw) {
                unsigned m = 0;
                for (int j = j0; j < j0 + gh; j++)
                    for (int i = i0; i < i0 + gw; i++) {
                        unsigned e = ev[(size_t)j * W + i];
                        sum += e;
                        m = e > m ? e : m;
                    }
                cost += (double)m * gw * gh;
            }
        printf(" %dx%d %.0f%%", gw, gh, cost > 0 ? 100.0 * sum / cost : 100.0);
    }
    printf("\n");
    printf("min/max nodes decided over the ray box (one side certainly smaller): %.1f%% of %lld\n",
           mm_calls_all ? 100.0 * mm_decided_all / mm_calls_all : 0, mm_calls_all);
    printf("neighbour hit (left neighbour's start x 0.98, one evaluation to prove [t_near, guess] empty): proven on "
           "%.1f%% of %lld hit rays; their evaluations %lld -> %lld (%.2fx)\n",
           nb_tried ? 100.0 * nb_proven / nb_tried : 0, nb_tried, nb_base, nb_evals,
           nb_evals ? (double)nb_base / nb_evals : 0);
    free(ev);
    free(sorted);
    free(hit_t);
    return 0;
}
