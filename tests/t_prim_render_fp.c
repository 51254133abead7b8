/* tests/t_prim_render_fp.c -- a scene of every BRL-CAD primitive type as regions (and one region of a boolean
 * over primitives), built with scene_add_primitive and rendered by the segment path, against the exact reference
 * of tests/t_prim_ref.h for EVERY pixel: the region id of the first claimed partition, and the depth, never after
 * the boundary there and at most PRIM_EARLY k eps before it (k = 1 + sum |n_i d_i| / |n.d|, the box of a leaf
 * around the ray; n from the reference's hits of two neighbouring rays). A pixel whose answer changes when its ray
 * moves by the margin (a silhouette, a graze, two surfaces that close) is counted as ambiguous and skipped. */
#include "implicits/prim_place.h"
#include "implicits/scene_emit.h"
#include "t_prim_ref.h"
#include "t_render_util.h"

#define PR_SIZE 112
#define PR_EPS 1e-3
#define PR_MARGIN (4 * PR_EPS)
#define PRIM_EARLY 4
#ifdef IA_FP64
#define PR_FP64 1
#else
#define PR_FP64 0
#endif

enum { PR_SOLIDS = 9 };

typedef struct {
    iacsg_scene *scene;
    scene_prim prims[PR_SOLIDS];
    double params[PR_SOLIDS][32];
} prim_scene;

static void add_prim(prim_scene *ps, int k, scene_prim_type type, const double *q, int n, const double mat[16]) {
    iacsg_error err = {0};
    CHECK(scene_add_primitive(ps->scene, NULL, type, q, n, mat, &err) == k, "scene_add_primitive: %s", err.message);
    memcpy(ps->params[k], q, sizeof(double) * (size_t)n);
    ps->prims[k] = (scene_prim){type, n, ps->params[k], {0}, NULL};
    memcpy(ps->prims[k].mat, mat, 16 * sizeof(double));
}

static void add_region(prim_scene *ps, const uint32_t *nodes, int n) {
    iacsg_error err = {0};
    int root = scene_add_tree(ps->scene, nodes, n, &err);
    CHECK(root >= 0 && scene_add_region(ps->scene, NULL, root, -1, &err) >= 0, "region: %s", err.message);
}

/* A rotation about axis (x, y, z) by the angle whose cosine is c (rows in mat), mat[15] = 1 / scale. */
static void placement(double x, double y, double z, double c, const double at[3], double scale, double mat[16]) {
    double l = sqrt(x * x + y * y + z * z), s = sqrt(1 - c * c), u[3] = {x / l, y / l, z / l}, t = 1 - c;
    double r[9] = {c + u[0] * u[0] * t,        u[0] * u[1] * t - u[2] * s, u[0] * u[2] * t + u[1] * s,
                   u[1] * u[0] * t + u[2] * s, c + u[1] * u[1] * t,        u[1] * u[2] * t - u[0] * s,
                   u[2] * u[0] * t - u[1] * s, u[2] * u[1] * t + u[0] * s, c + u[2] * u[2] * t};
    memset(mat, 0, 16 * sizeof(double));
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            mat[4 * i + j] = r[3 * i + j];
        mat[4 * i + 3] = at[i];
    }
    mat[15] = 1 / scale;
}

/* The reference's first claimed partition along the world ray in (t0, t1): its region (-1: none), start and the
 * solid whose boundary starts it (-1: the bounds). */
static int ref_first(const prim_scene *ps, const ld o[3], const ld d[3], ld t0, ld t1, ld *ts, int *solid) {
    static ld cross[PR_SOLIDS][REF_MAX_CROSSINGS];
    int ncross[PR_SOLIDS], inside[PR_SOLIDS], next[PR_SOLIDS];
    for (int k = 0; k < PR_SOLIDS; k++) {
        ref_line line = ref_local_line(ps->prims[k].mat, o, d);
        ncross[k] = prim_ref_crossings(&ps->prims[k], &line, t0, t1, cross[k], &inside[k]);
        next[k] = 0;
    }
    ld a = t0;
    int from = -1;
    for (;;) {
        signed char sign[PR_SOLIDS];
        for (int k = 0; k < PR_SOLIDS; k++)
            sign[k] = inside[k] ? -1 : 1;
        for (int item = 0; item < ps->scene->nitems; item++)
            if (scene_tree_eval(ps->scene, ps->scene->items[item].tree, sign)) {
                *ts = a;
                *solid = from;
                return item;
            }
        int k_next = -1;
        for (int k = 0; k < PR_SOLIDS; k++)
            if (next[k] < ncross[k] && (k_next < 0 || cross[k][next[k]] < cross[k_next][next[k_next]]))
                k_next = k;
        if (k_next < 0)
            return -1;
        a = cross[k_next][next[k_next]++];
        inside[k_next] = !inside[k_next];
        from = k_next;
    }
}

static int clip_ld(const double b[6], const ld o[3], const ld d[3], ld *t0, ld *t1) {
    *t0 = 0;
    *t1 = INFINITY;
    for (int c = 0; c < 3; c++) {
        ld a = (b[c] - o[c]) / d[c], e = (b[c + 3] - o[c]) / d[c];
        *t0 = fmaxl(*t0, fminl(a, e));
        *t1 = fminl(*t1, fmaxl(a, e));
    }
    return *t0 < *t1;
}

/* The scene's primitives, solid k of the first arrangement each: type, parameters, and placement (placement()'s
 * axis, cosine, position and scale). */
static const struct {
    scene_prim_type type;
    int n;
    double q[24], axis[4], at[3], scale;
} prim_specs[PR_SOLIDS] = {
    /* 0 half: a floor z < -1.75, tilted */
    {SCENE_PRIM_HALF, 4, {0, 0, 1, -1.75}, {1, 0, 0, 0.995}, {0, 0, 0}, 1},
    /* 1 arb8: a frustum of a box */
    {SCENE_PRIM_ARB8, 24, {-0.5, -0.5, -0.5, 0.5, -0.5, -0.5, 0.5, 0.5, -0.5, -0.5, 0.5, -0.5, -0.25, -0.25, 0.5, 0.25,
                           -0.25, 0.5, 0.25, 0.25, 0.5, -0.25, 0.25, 0.5},
     {0.3, 1, 0.2, 0.8}, {-1.1, -0.9, -0.6}, 1.25},
    /* 2 ell */
    {SCENE_PRIM_ELL, 12, {0, 0, 0, 0.7, 0, 0, 0, 0.45, 0, 0, 0, 0.3}, {1, 1, 0, 0.6}, {1.1, -0.9, -0.8}, 1},
    /* 3 tgc: sheared, elliptical, top axes 1.5 and 0.5 of the base's */
    {SCENE_PRIM_TGC, 18, {0, 0, 0, 0.3, 0.2, 1.2, 0.4, 0, 0, 0, 0.3, 0, 0.6, 0, 0, 0, 0.15, 0}, {0, 1, 1, 0.9},
     {-0.2, 0.9, -1.2}, 1},
    /* 4 tor */
    {SCENE_PRIM_TOR, 8, {0, 0, 0, 0, 0, 2, 0.8, 0.25}, {1, 0, 0.5, 0.5}, {1.0, 0.8, 0.4}, 0.8},
    /* 5 ehy */
    {SCENE_PRIM_EHY, 12, {0, 0, 0, 0, 0, -1.2, 1, 0, 0, 0.6, 0.35, 0.3}, {0, 0, 1, 0.7}, {-1.2, 1.0, 0.7}, 1},
    /* 6 pipe: a bore, two bends, a diameter change */
    {SCENE_PRIM_PIPE, 24, {-1.5, -1, 0, 0.4, 0.25, 0.5, -1.5, 0.8, 0, 0.4, 0.25, 0.5, 0.5, 0.8, 0.4, 0.5, 0.3, 0.6, 1.5,
                           -0.6, 0.4, 0.3, 0, 0.5},
     {0, 0, 1, 1}, {-0.3, -0.2, 0.9}, 1},
    /* 7, 8: an arb4 and a sphere bitten out of it */
    {SCENE_PRIM_ARB8, 24, {-0.5, -0.5, 0, 0.5, -0.5, 0, 0, 0.5, 0, 0, 0.5, 0, 0, 0, 0.75, 0, 0, 0.75, 0, 0, 0.75, 0, 0,
                           0.75},
     {0, 0, 1, 1}, {0.1, -0.2, -1.6}, 1},
    {SCENE_PRIM_ELL, 12, {0, 0, 0, 0.3, 0, 0, 0, 0.3, 0, 0, 0, 0.3}, {0, 0, 1, 1}, {0.1, -0.2, -0.9}, 1},
};

/* The scene of prim_specs with spec j as solid at[j], moved by `shift` (the half-space too), its regions in the same
 * order whatever the arrangement: each of the first seven solids, then the arb4 less the sphere. */
static void build_scene(prim_scene *ps, const int at[PR_SOLIDS], const double shift[3]) {
    ps->scene = scene_create();
    for (int k = 0; k < PR_SOLIDS; k++) {
        int j = 0;
        while (at[j] != k)
            j++;
        double mat[16], to[3];
        for (int c = 0; c < 3; c++)
            to[c] = prim_specs[j].at[c] + shift[c];
        placement(prim_specs[j].axis[0], prim_specs[j].axis[1], prim_specs[j].axis[2], prim_specs[j].axis[3], to,
                  prim_specs[j].scale, mat);
        add_prim(ps, k, prim_specs[j].type, prim_specs[j].q, prim_specs[j].n, mat);
    }
    for (int j = 0; j < 7; j++)
        add_region(ps, (uint32_t[]){CSG_NODE(CSG_INSIDE, (uint32_t)at[j])}, 1);
    add_region(ps, (uint32_t[]){CSG_NODE(CSG_DIFFERENCE, 2), CSG_NODE(CSG_INSIDE, (uint32_t)at[7]),
                                CSG_NODE(CSG_INSIDE, (uint32_t)at[8])}, 3);
}

/* Renders the scene and checks every pixel against the reference. */
static void check_render(prim_scene *ps) {
    iacsg_view view = {.width = PR_SIZE, .height = PR_SIZE, .eps = PR_EPS,
                       .camera = {.eye = {2.5, -6, 3.5}, .at = {0, 0, -0.4}, .up = {0, 0, 1}, .fov = 40},
                       .bounds = {-2.5, -2.5, -2, 2.5, 2.5, 2}};
    iacsg_render_config config = {.fp64 = PR_FP64};
    iacsg_error err = {0};
    iacsg_renderer *r = NULL;
    CHECK(iacsg_renderer_create_scene(ps->scene, &config, &r, &err) == IACSG_OK, "%s", err.message);
    iacsg_frame fr;
    iacsg_status st = iacsg_render(r, &view, &fr, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "%s", err.message);
    ia_real p[PARAM_COUNT];
    view_params(&view, p);
    long ambiguous = 0, seen[8] = {0};
    double worst = 0;
    for (int j = 0; j < PR_SIZE; j++)
        for (int i = 0; i < PR_SIZE; i++) {
            double od[3], dd[3];
            pixel_ray(p, &view, i, j, od, dd);
            ld o[3] = {od[0], od[1], od[2]}, d[3] = {dd[0], dd[1], dd[2]}, t0, t1, ts = INFINITY;
            int solid = -1, id = clip_ld(view.bounds, o, d, &t0, &t1) ? ref_first(ps, o, d, t0, t1, &ts, &solid) : -1;
            /* the same for rays moved by the margin across the ray: a different answer makes the pixel ambiguous */
            ld u[3] = {d[1], -d[0], 0}, v[3], hit[2][3];
            if (fabsl(d[2]) > 0.9L)
                u[0] = 0, u[1] = d[2], u[2] = -d[1];
            ref_unit(u);
            ref_cross(d, u, v);
            ref_unit(v);
            int stable = 1;
            for (int side = 0; side < 4 && stable; side++) {
                ld q[3], a0, a1, tq = INFINITY;
                for (int c = 0; c < 3; c++)
                    q[c] = o[c] + (side & 1 ? -1 : 1) * PR_MARGIN * (side < 2 ? u[c] : v[c]);
                int sq = -1, idq = clip_ld(view.bounds, q, d, &a0, &a1) ? ref_first(ps, q, d, a0, a1, &tq, &sq) : -1;
                stable = idq == id && sq == solid && (id < 0 || fabsl(tq - ts) < 50 * PR_MARGIN);
                if (side % 2 == 0)
                    for (int c = 0; c < 3; c++)
                        hit[side / 2][c] = q[c] + tq * d[c];
            }
            if (!stable || (id >= 0 && ts - t0 < PR_MARGIN)) {
                ambiguous++;
                continue;
            }
            size_t px = (size_t)j * PR_SIZE + (size_t)i;
            CHECK((int)fr.ids[px] == id, "pixel (%d, %d): id %d, the reference %d (at t = %.9Lg)", i, j, (int)fr.ids[px],
                  id, ts);
            if (id < 0)
                continue;
            seen[id]++;
            double depth = fr.depth[px];
            CHECK(depth <= ts * (1 + 1e-15L), "pixel (%d, %d): depth %.9g after the boundary at %.12Lg", i, j, depth, ts);
            if (solid < 0)
                continue;
            ld n[3], e1[3], e2[3], nd = 0, spread = 0;
            for (int c = 0; c < 3; c++) {
                e1[c] = hit[0][c] - (o[c] + ts * d[c]);
                e2[c] = hit[1][c] - (o[c] + ts * d[c]);
            }
            ref_cross(e1, e2, n);
            ref_unit(n);
            for (int c = 0; c < 3; c++) {
                nd += n[c] * d[c];
                spread += fabsl(n[c] * d[c]);
            }
            if (fabsl(nd) <= 0.25L)
                continue; /* grazing */
            double early = (double)((ts - depth) / (PR_EPS * (1 + spread / fabsl(nd))));
            CHECK(early <= PRIM_EARLY, "pixel (%d, %d): depth %.9g is %.2f k eps before the boundary at %.12Lg", i, j,
                  depth, early, ts);
            worst = fmax(worst, early);
        }
    iacsg_frame_free(&fr);
    test_note("%d pixels, %ld ambiguous; pixels per region: half %ld, arb8 %ld, ell %ld, tgc %ld, tor %ld, ehy %ld, pipe "
              "%ld, arb4 - ell %ld; depth at most %.2f k eps early",
              PR_SIZE * PR_SIZE, ambiguous, seen[0], seen[1], seen[2], seen[3], seen[4], seen[5], seen[6], seen[7], worst);
    for (int k = 0; k < 8; k++)
        CHECK(seen[k] > 20, "region %d was checked on %ld pixels only", k, seen[k]);
    CHECK(ambiguous < PR_SIZE * PR_SIZE / 8, "%ld ambiguous pixels, too many to trust the test", ambiguous);
}

TEST_FP(prim_render_every_type) {
    static prim_scene ps;
    build_scene(&ps, (const int[PR_SOLIDS]){0, 1, 2, 3, 4, 5, 6, 7, 8}, (const double[3]){0, 0, 0});
    check_render(&ps);
    iacsg_scene_destroy(ps.scene);
}

/* A model's primitives are data (implicits/scene_prims.c), not code: another arrangement of the same kinds, the
 * solids in the reverse order, moved, and one more solid, has the very program of the first (so that one cached
 * build serves both) and renders right with it: no solid reads another's parameters. */
TEST_FP(prim_render_same_kinds_share_the_program) {
    static prim_scene first, other;
    build_scene(&first, (const int[PR_SOLIDS]){0, 1, 2, 3, 4, 5, 6, 7, 8}, (const double[3]){0, 0, 0});
    build_scene(&other, (const int[PR_SOLIDS]){8, 7, 6, 5, 4, 3, 2, 1, 0}, (const double[3]){0.15, -0.1, 0.05});
    double mat[16];
    placement(0, 0, 1, 1, (const double[3]){2, 2, 1.5}, 1, mat); /* in no region */
    iacsg_error err = {0};
    CHECK(scene_add_primitive(other.scene, NULL, SCENE_PRIM_ELL, prim_specs[8].q, 12, mat, &err) == PR_SOLIDS,
          "scene_add_primitive: %s", err.message);
    char *a = NULL, *b = NULL;
    CHECK(scene_emit_cl(first.scene, &a, &err) == IACSG_OK && scene_emit_cl(other.scene, &b, &err) == IACSG_OK, "%s",
          err.message);
    CHECK(strcmp(a, b) == 0, "two models of the same kinds have different programs");
    free(a);
    free(b);
    check_render(&other);
    iacsg_scene_destroy(first.scene);
    iacsg_scene_destroy(other.scene);
}
