/* tests/t_render_scene_fp.c -- the segment path (src/render_scene.c) against exact references: scenes of
 * spheres, boxes and half-spaces, whose insides along a ray are closed-form t intervals, computed on the host in
 * long double for the very float (or double) ray each pixel traced (t_render_util.h). Regions are evaluated on
 * the exact partitions between those interval ends with the host's tree evaluation (scene_tree_eval).
 *
 * Checked for EVERY pixel: a pixel whose ray passes through a region inside the bounds is hit (never missed); the
 * depth is never after the exact first point of a region, and at most SCENE_TEST_K * k * eps before it (k = 1 +
 * sum |n_i d_i| / |n . d|, n the exact normal there, as the first-root path's README bound) -- or, where the
 * ray passes within SCENE_TEST_NEAR eps of some solid's boundary before that, at that point (the solid's state
 * is undecided there, and a region it may make in claims the partition); the id is the exact first claim's (the
 * first declared region where two are in) except at such points and at the stated margin: pixels where the exact
 * id of a neighbouring pixel differs (silhouettes and the borders between regions), where a hit without an exact
 * one is also allowed (a ray that grazes within the enclosures' width). The counts are printed. */
#include "t_render_util.h"
#include "implicits/scene.h"
#include <string.h>

#define SCENE_TEST_K 1.0L
#define SCENE_TEST_NEAR 4.0L
enum { T_SPHERE, T_BOX, T_HALF };

typedef struct {
    int kind;
    double c[3]; /* centre; T_HALF: the normal n */
    double r[3]; /* sphere: radius r[0]; box: half extents; T_HALF: inside where n . p < r[0] */
} t_solid;

typedef struct {
    t_solid solids[256];
    int nsolids;
    const char *regions[256]; /* prefix notation: U, I, D binary, numbers are solids */
    int nregions;
} t_scene;

/* The solid's expression, in the language, with dyadic constants printed in full (a dyadic number's decimal
 * expansion ends: the compiler takes the same real). */
static void solid_text(const t_solid *s, char *text, size_t size) {
    if (s->kind == T_SPHERE)
        snprintf(text, size, "(x - %.60g)^2 + (y - %.60g)^2 + (z - %.60g)^2 - %.60g", s->c[0], s->c[1], s->c[2],
                 s->r[0] * s->r[0]);
    else if (s->kind == T_BOX)
        snprintf(text, size, "max(max(abs(x - %.60g) - %.60g, abs(y - %.60g) - %.60g), abs(z - %.60g) - %.60g)",
                 s->c[0], s->r[0],
                 s->c[1], s->r[1], s->c[2], s->r[2]);
    else
        snprintf(text, size, "%.60g * x + %.60g * y + %.60g * z - %.60g", s->c[0], s->c[1], s->c[2], s->r[0]);
}

/* Appends the prefix tree at text[*pos] as nodes (relative indices, preorder); returns the number of nodes. */
static int tree_of(const char *text, int *pos, uint32_t *nodes, int n) {
    while (text[*pos] == ' ')
        *pos += 1;
    char c = text[*pos];
    if (c >= '0' && c <= '9') {
        int solid = (int)strtol(text + *pos, NULL, 10);
        while (text[*pos] >= '0' && text[*pos] <= '9')
            *pos += 1;
        nodes[n] = CSG_NODE(CSG_INSIDE, solid);
        return n + 1;
    }
    int op = c == 'U' ? CSG_UNION : c == 'I' ? CSG_INTERSECT : CSG_DIFFERENCE, here = n;
    *pos += 1;
    n = tree_of(text, pos, nodes, n + 1);
    nodes[here] = CSG_NODE(op, n);
    return tree_of(text, pos, nodes, n);
}

static iacsg_scene *build_scene(const t_scene *t) {
    iacsg_scene *s = scene_create();
    iacsg_error err = {0};
    for (int k = 0; k < t->nsolids; k++) {
        char text[512];
        iacsg_expr *e = NULL;
        solid_text(&t->solids[k], text, sizeof text);
        CHECK(iacsg_expr_parse(text, "<solid>", &e, &err) == IACSG_OK, "%s: %s", text, err.message);
        CHECK(scene_add_solid(s, NULL, e, &err) == k, "%s", err.message);
    }
    for (int k = 0; k < t->nregions; k++) {
        uint32_t nodes[1024];
        int pos = 0, n = tree_of(t->regions[k], &pos, nodes, 0);
        int root = scene_add_tree(s, nodes, n, &err);
        CHECK(root >= 0 && scene_add_region(s, NULL, root, -1, &err) == k, "%s", err.message);
    }
    return s;
}

/* The open t interval (*a, *b) where the ray is inside the solid; 0 if empty. */
static int inside_span(const t_solid *s, const long double o[3], const long double d[3], long double *a,
                       long double *b) {
    if (s->kind == T_SPHERE) {
        long double oc[3] = {o[0] - s->c[0], o[1] - s->c[1], o[2] - s->c[2]};
        long double qa = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], qb = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
        long double qc = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - (long double)s->r[0] * s->r[0];
        long double disc = qb * qb - qa * qc;
        if (disc <= 0)
            return 0;
        long double q = -(qb + copysignl(sqrtl(disc), qb)), r1 = q / qa, r2 = qc / q;
        *a = fminl(r1, r2);
        *b = fmaxl(r1, r2);
        return 1;
    }
    if (s->kind == T_HALF) {
        long double nd = s->c[0] * d[0] + s->c[1] * d[1] + s->c[2] * d[2];
        long double rest = s->r[0] - (s->c[0] * o[0] + s->c[1] * o[1] + s->c[2] * o[2]);
        *a = -INFINITY;
        *b = INFINITY;
        if (nd == 0)
            return rest > 0;
        if (nd > 0)
            *b = rest / nd;
        else
            *a = rest / nd;
        return 1;
    }
    *a = -INFINITY;
    *b = INFINITY;
    for (int k = 0; k < 3; k++) {
        long double lo = s->c[k] - s->r[k] - o[k], hi = s->c[k] + s->r[k] - o[k];
        if (d[k] == 0) {
            if (!(lo < 0 && hi > 0))
                return 0;
            continue;
        }
        long double t1 = lo / d[k], t2 = hi / d[k];
        *a = fmaxl(*a, fminl(t1, t2));
        *b = fminl(*b, fmaxl(t1, t2));
    }
    return *a < *b;
}

/* The unit outward normal of the solid at p (on its boundary). */
static void solid_normal(const t_solid *s, const long double p[3], long double n[3]) {
    if (s->kind == T_HALF) {
        for (int k = 0; k < 3; k++)
            n[k] = s->c[k];
    } else if (s->kind == T_SPHERE) {
        for (int k = 0; k < 3; k++)
            n[k] = p[k] - s->c[k];
    } else { /* the face whose slab p is at the edge of */
        int best = 0;
        long double gap[3];
        for (int k = 0; k < 3; k++) {
            gap[k] = fabsl(fabsl(p[k] - s->c[k]) - s->r[k]);
            best = gap[k] < gap[best] ? k : best;
        }
        for (int k = 0; k < 3; k++)
            n[k] = k == best ? (p[k] > s->c[k] ? 1 : -1) : 0;
    }
    long double len = sqrtl(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++)
        n[k] /= len;
}

/* The distance from q to the solid's boundary. */
static long double surface_distance(const t_solid *s, const long double q[3]) {
    if (s->kind == T_SPHERE) {
        long double dx = q[0] - s->c[0], dy = q[1] - s->c[1], dz = q[2] - s->c[2];
        return fabsl(sqrtl(dx * dx + dy * dy + dz * dz) - s->r[0]);
    }
    if (s->kind == T_HALF) {
        long double n2 = s->c[0] * s->c[0] + s->c[1] * s->c[1] + s->c[2] * s->c[2];
        return fabsl(s->c[0] * q[0] + s->c[1] * q[1] + s->c[2] * q[2] - s->r[0]) / sqrtl(n2);
    }
    long double out = 0, in = INFINITY; /* outside: to the box; inside: to the nearest face */
    for (int k = 0; k < 3; k++) {
        long double gap = fabsl(q[k] - s->c[k]) - s->r[k];
        out += gap > 0 ? gap * gap : 0;
        in = fminl(in, -gap);
    }
    return out > 0 ? sqrtl(out) : in;
}

typedef struct {
    int id;        /* the exact first claim, -1 for none */
    long double t; /* its start */
    long double k; /* 1 + sum |n_i d_i| / |n . d| at the boundary there */
} exact_hit;

static int by_value(const void *a, const void *b) {
    long double x = *(const long double *)a, y = *(const long double *)b;
    return (x > y) - (x < y);
}

/* The exact first claim along the ray within [tn, tf]: the first partition (between consecutive interval ends)
 * where a region is in, the first declared one. */
static exact_hit exact_first(const t_scene *t, const iacsg_scene *s, const long double o[3], const long double d[3],
                             long double tn, long double tf) {
    long double a[256], b[256], ends[514];
    int has[256], n = 0;
    ends[n++] = tn;
    for (int k = 0; k < t->nsolids; k++) {
        has[k] = inside_span(&t->solids[k], o, d, &a[k], &b[k]);
        if (has[k] && a[k] > tn && a[k] < tf)
            ends[n++] = a[k];
        if (has[k] && b[k] > tn && b[k] < tf)
            ends[n++] = b[k];
    }
    qsort(ends, (size_t)n, sizeof ends[0], by_value);
    exact_hit hit = {-1, INFINITY, 1};
    for (int i = 0; i < n; i++) {
        long double lo = ends[i], hi = i + 1 < n ? ends[i + 1] : tf, mid = 0.5L * (lo + hi);
        if (!(hi > lo))
            continue;
        signed char sign[256];
        for (int k = 0; k < t->nsolids; k++)
            sign[k] = has[k] && a[k] < mid && mid < b[k] ? -1 : 1;
        for (int r = 0; r < t->nregions; r++) {
            if (!scene_tree_eval(s, s->items[r].tree, sign))
                continue;
            hit.id = r;
            hit.t = lo;
            /* k from the normal of a solid with an interval end at lo */
            for (int k = 0; k < t->nsolids; k++) {
                if (!has[k] || (a[k] != lo && b[k] != lo))
                    continue;
                long double p[3], nrm[3], nd = 0, sum = 0;
                for (int c = 0; c < 3; c++)
                    p[c] = o[c] + lo * d[c];
                solid_normal(&t->solids[k], p, nrm);
                for (int c = 0; c < 3; c++) {
                    nd += nrm[c] * d[c];
                    sum += fabsl(nrm[c] * d[c]);
                }
                hit.k = fmaxl(hit.k, 1 + sum / fabsl(nd));
            }
            return hit;
        }
    }
    return hit;
}

/* The ray's exact part [tn, tf] (t >= 0) inside the view's bounds; 0 if none. */
static int exact_clip(const iacsg_view *v, const long double o[3], const long double d[3], long double *tn,
                      long double *tf) {
    *tn = 0;
    *tf = INFINITY;
    for (int k = 0; k < 3; k++) {
        long double lo = v->bounds[k] - o[k], hi = v->bounds[k + 3] - o[k];
        if (d[k] == 0) {
            if (lo > 0 || hi < 0)
                return 0;
            continue;
        }
        *tn = fmaxl(*tn, fminl(lo / d[k], hi / d[k]));
        *tf = fminl(*tf, fmaxl(lo / d[k], hi / d[k]));
    }
    return *tn <= *tf;
}

typedef struct {
    long long hits, edge, ghosts, wrong_ids, early, early_ids;
    long double worst_before; /* (t_exact - depth) / (k eps), the largest */
} scene_check;

/* Renders the scene and compares every pixel with the exact reference. */
static scene_check check_scene(const t_scene *t, const iacsg_view *view, const iacsg_render_config *config,
                               iacsg_frame *out) {
    iacsg_scene *s = build_scene(t);
    iacsg_error err = {0};
    iacsg_renderer *r = NULL;
    iacsg_frame f;
    CHECK(iacsg_renderer_create_scene(s, config, &r, &err) == IACSG_OK, "renderer: %s", err.message);
    iacsg_status st = iacsg_render(r, view, &f, &err);
    iacsg_renderer_destroy(r);
    CHECK(st == IACSG_OK, "render: %s", err.message);
    ia_real p[PARAM_COUNT];
    view_params(view, p);
    int w = view->width, h = view->height;
    exact_hit *exact = malloc(sizeof *exact * (size_t)w * (size_t)h);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double od[3], dd[3];
            long double o[3], d[3], tn, tf;
            pixel_ray(p, view, i, j, od, dd);
            for (int k = 0; k < 3; k++) {
                o[k] = od[k];
                d[k] = dd[k];
            }
            exact_hit none = {-1, INFINITY, 1};
            exact[j * w + i] = exact_clip(view, o, d, &tn, &tf) ? exact_first(t, s, o, d, tn, tf) : none;
        }
    scene_check c = {0};
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            size_t px = (size_t)j * w + i;
            exact_hit e = exact[px];
            int id = (int)f.ids[px], edge = 0;
            for (int dj = -1; dj <= 1; dj++)
                for (int di = -1; di <= 1; di++)
                    if (i + di >= 0 && i + di < w && j + dj >= 0 && j + dj < h)
                        edge |= exact[(size_t)(j + dj) * w + i + di].id != e.id;
            c.edge += edge;
            if (e.id < 0) {
                CHECK(id < 0 || edge, "pixel (%d, %d): hit %d where nothing is, away from any edge", i, j, id);
                c.ghosts += id >= 0;
                continue;
            }
            c.hits += 1;
            CHECK(id >= 0, "pixel (%d, %d) misses region %d at t = %.9Lg", i, j, e.id, e.t);
            long double depth = f.depth[px];
            CHECK(depth <= e.t * (1 + 1e-15L), "pixel (%d, %d): depth %.9Lg after the exact %.12Lg", i, j, depth, e.t);
            long double before = (e.t - depth) / (e.k * view->eps);
            if (before <= SCENE_TEST_K) {
                c.worst_before = fmaxl(c.worst_before, before);
                c.wrong_ids += id != e.id;
                CHECK(id == e.id || edge, "pixel (%d, %d): region %d where region %d is first, away from any edge", i,
                      j, id, e.id);
                continue;
            }
            /* earlier: only where the ray passes within SCENE_TEST_NEAR eps of a solid's boundary (its state is
             * undecided there, and the claim is of a region that it may make in) */
            double od[3], dd[3];
            long double q[3];
            pixel_ray(p, view, i, j, od, dd);
            for (int k = 0; k < 3; k++)
                q[k] = od[k] + depth * dd[k];
            long double near = INFINITY;
            for (int k = 0; k < t->nsolids; k++)
                near = fminl(near, surface_distance(&t->solids[k], q));
            CHECK(near <= SCENE_TEST_NEAR * view->eps,
                  "pixel (%d, %d): depth %.9Lg is %.3Lg k eps before the exact %.9Lg, %.3Lg eps from any surface", i, j,
                  depth, before, e.t, near / view->eps);
            c.early += 1;
            c.early_ids += id != e.id;
        }
    free(exact);
    iacsg_scene_destroy(s);
    if (out)
        *out = f;
    else
        iacsg_frame_free(&f);
    return c;
}

static void note(const char *name, scene_check c) {
    test_note("%s: %lld hits, %lld edge pixels (%lld ids differ there, %lld grazing hits), worst depth %.3Lg k eps "
              "before; %lld earlier, near a solid's surface (%lld of another region)",
              name, c.hits, c.edge, c.wrong_ids, c.ghosts, c.worst_before, c.early, c.early_ids);
}

static iacsg_view test_view(int size, double eps) {
    iacsg_view v = {0};
    v.width = v.height = size;
    v.eps = eps;
    v.camera.fov = 40;
    v.camera.up[2] = 1;
    v.camera.eye[0] = 3.25;
    v.camera.eye[1] = 2.5;
    v.camera.eye[2] = 1.75;
    double b[6] = {-1.5, -1.5, -1.5, 1.5, 1.5, 1.5};
    memcpy(v.bounds, b, sizeof b);
    return v;
}

#ifdef IA_FP64
#define FP64 1
#else
#define FP64 0
#endif
static const iacsg_render_config plain_config = {.fp64 = FP64};

/* Two overlapping spheres: their difference both ways and their intersection. */
TEST_FP(render_scene_booleans) {
    t_scene t = {{{T_SPHERE, {-0.25, 0, 0}, {0.75}}, {T_SPHERE, {0.375, 0.125, 0}, {0.625}}}, 2,
                 {"D 0 1", "I 0 1", "D 1 0"}, 3};
    iacsg_view v = test_view(160, 0x1p-12);
    note("differences, intersection", check_scene(&t, &v, &plain_config, NULL));
}

/* A union, and nested differences exposing inner boundaries: a box minus (a sphere minus a smaller box), and
 * what the box keeps of the inner box. */
TEST_FP(render_scene_nested) {
    t_scene t = {{{T_BOX, {0, 0, 0}, {0.75, 0.75, 0.75}},
                  {T_SPHERE, {0.25, 0.25, 0.25}, {0.75}},
                  {T_BOX, {0.5, 0.5, 0.5}, {0.25, 0.25, 0.25}},
                  {T_SPHERE, {-0.75, -0.75, 0.75}, {0.25}}},
                 4,
                 {"D 0 D 1 2", "I 0 2", "U 3 D 3 0"},
                 3};
    iacsg_view v = test_view(160, 0x1p-12);
    note("nested differences", check_scene(&t, &v, &plain_config, NULL));
}

/* Half-spaces (unbounded solids, infinite boxes) cutting a sphere, and a solid whose inside is the outside of a
 * sphere (its inside reaches beyond its box). */
TEST_FP(render_scene_halfspaces) {
    t_scene t = {{{T_SPHERE, {0, 0, 0}, {1}},
                  {T_HALF, {0.5, 0.25, 1}, {0.25}},
                  {T_BOX, {0, 0, -0.5}, {1.25, 1.25, 0.25}}},
                 3,
                 {"I 0 1", "D 2 0"},
                 2};
    iacsg_view v = test_view(160, 0x1p-12);
    note("half-spaces", check_scene(&t, &v, &plain_config, NULL));
}

/* Touching regions (two boxes), and a region overlapping one of them (a sphere with the first box): the first
 * declared wins, and the overlaps are counted with their pair. */
TEST_FP(render_scene_overlaps) {
    t_scene t = {{{T_BOX, {-0.5, 0, 0}, {0.5, 0.5, 0.5}},
                  {T_BOX, {0.5, 0, 0}, {0.5, 0.5, 0.5}},
                  {T_SPHERE, {0, 0, 0.5}, {0.5}}},
                 3,
                 {"0", "1", "U 2 0"},
                 3};
    iacsg_view v = test_view(160, 0x1p-12);
    iacsg_frame f;
    note("touching and overlapping", check_scene(&t, &v, &plain_config, &f));
    CHECK(f.overlaps > 0, "no overlap counted");
    int pairs_ok = f.noverlap_pairs > 0;
    for (int k = 0; k < f.noverlap_pairs; k++) /* region 2 holds the first box; the boxes only touch */
        pairs_ok &= f.overlap_pairs[k][0] == 0 && f.overlap_pairs[k][1] == 2;
    CHECK(pairs_ok, "overlap pairs: %d, first (%d, %d)", f.noverlap_pairs, f.overlap_pairs[0][0],
          f.overlap_pairs[0][1]);
    test_note("%lld overlapping pixels, pairs (%d, %d)%s", f.overlaps, f.overlap_pairs[0][0], f.overlap_pairs[0][1],
              f.noverlap_pairs > 1 ? " and more" : "");
    iacsg_frame_free(&f);
}

/* A plate 1/8 of eps thick, seen from an angle: every ray through it is hit. */
TEST_FP(render_scene_thin) {
    double eps = 0x1p-10;
    t_scene t = {{{T_BOX, {0, 0, 0}, {eps / 16, 1, 1}}, {T_SPHERE, {0, 0, 0}, {0.875}}}, 2, {"I 0 1"}, 1};
    iacsg_view v = test_view(128, eps);
    scene_check c = check_scene(&t, &v, &plain_config, NULL);
    CHECK(c.hits > 1000, "the plate covers only %lld pixels", c.hits);
    note("a plate eps/8 thick", c);
}

/* Orthographic rays grazing a sphere: the top row's middle ray passes 2^-20 inside its silhouette, and is hit. */
TEST_FP(render_scene_grazing) {
    iacsg_view v = test_view(64, 0x1p-14);
    v.width = 65; /* a middle column, at x = 0 */
    v.camera.ortho_height = 2;
    v.camera.eye[0] = 0;
    v.camera.eye[1] = -4;
    v.camera.eye[2] = 0;
    /* row j's rays lie at height z = 1 - (2j + 1)/64; row 0 at 63/64: a sphere of radius 63/64 + 2^-20 */
    t_scene t = {{{T_SPHERE, {0, 0, 0}, {63.0 / 64 + 0x1p-20}}}, 1, {"0"}, 1};
    iacsg_frame f;
    note("grazing", check_scene(&t, &v, &plain_config, &f));
    CHECK(f.ids[v.width / 2] == 0, "the grazing ray of the top row's middle is missed");
    iacsg_frame_free(&f);
}

/* 216 spheres, each its own region, and 8 regions over groups of them. */
TEST_FP(render_scene_many) {
    static t_scene t;
    static char trees[8][256];
    memset(&t, 0, sizeof t);
    for (int k = 0; k < 216; k++) {
        t_solid s = {T_SPHERE, {-1.25 + 0.5 * (k % 6), -1.25 + 0.5 * (k / 6 % 6), -1.25 + 0.5 * (k / 36)}, {0.1875}};
        t.solids[t.nsolids++] = s;
    }
    t.solids[t.nsolids++] = (t_solid){T_BOX, {0, 0, 0}, {1.25, 1.25, 0.125}};
    for (int g = 0; g < 8; g++) { /* region g: the union of spheres g, g + 8, ... minus the box */
        int len = snprintf(trees[g], sizeof trees[g], "D");
        for (int k = g; k + 8 < 216; k += 8)
            len += snprintf(trees[g] + len, sizeof trees[g] - (size_t)len, " U %d", k);
        len += snprintf(trees[g] + len, sizeof trees[g] - (size_t)len, " %d 216", 216 - 8 + g);
        t.regions[t.nregions++] = trees[g];
    }
    iacsg_view v = test_view(200, 0x1p-12);
    note("216 spheres in 8 regions", check_scene(&t, &v, &plain_config, NULL));
    t.nregions = 0;
    static char single[216][12]; /* room for any int, as -Wformat-truncation reckons */
    for (int k = 0; k < 216; k++) {
        snprintf(single[k], sizeof single[k], "%d", k);
        t.regions[t.nregions++] = single[k];
    }
    note("216 spheres, each a region", check_scene(&t, &v, &plain_config, NULL));
}

/* The overflow tests' scene: two spheres and a box, a difference, an intersection, a nested difference. */
static t_scene overflow_scene(void) {
    t_scene t = {{{T_SPHERE, {-0.25, 0, 0}, {0.75}}, {T_SPHERE, {0.375, 0.125, 0}, {0.625}},
                  {T_BOX, {0, 0, -0.5}, {1, 1, 0.25}}},
                 3,
                 {"D 0 1", "I 0 1", "D 2 U 0 1"},
                 3};
    return t;
}

/* Fails unless the frames a (default room) and b (re-traced) are the same bit for bit. */
static void check_same_after_retrace(const iacsg_frame *a, const iacsg_frame *b, size_t n) {
    CHECK(memcmp(a->rgb, b->rgb, 3 * n * sizeof(float)) == 0 && memcmp(a->depth, b->depth, n * sizeof(float)) == 0 &&
              memcmp(a->ids, b->ids, n * sizeof(float)) == 0 &&
              memcmp(a->normal, b->normal, 3 * n * sizeof(float)) == 0,
          "the images differ after re-tracing");
}

/* Per-ray buffers for one candidate: most rays overflow, are traced again with more room, and the images are
 * the same bit for bit. */
TEST_FP(render_scene_overflow) {
    t_scene t = overflow_scene();
    iacsg_view v = test_view(96, 0x1p-12);
    iacsg_render_config tiny = plain_config;
    tiny.ray_candidates = 1;
    iacsg_frame a, b;
    check_scene(&t, &v, &plain_config, &a);
    check_scene(&t, &v, &tiny, &b);
    size_t n = (size_t)v.width * (size_t)v.height;
    CHECK(a.retraced_rays == 0 && b.retraced_rays > 0, "retraced: %lld with the default room, %lld with 1",
          a.retraced_rays, b.retraced_rays);
    check_same_after_retrace(&a, &b, n);
    test_note("%lld of %zu rays re-traced, images identical", b.retraced_rays, n);
    iacsg_frame_free(&a);
    iacsg_frame_free(&b);
}

/* The same with a level-set surface in front of the regions (a sphere's zero set where the box is not): a
 * re-traced ray walks the surface from its packet's block pass as in the first pass, so the frames are again
 * identical (walked from the top instead, its leaves and so its depth came from another tree). */
TEST_FP(render_scene_overflow_surface) {
    t_scene t = overflow_scene();
    iacsg_view v = test_view(96, 0x1p-12);
    iacsg_render_config tiny = plain_config;
    tiny.ray_candidates = 1;
    iacsg_frame f[2];
    for (int k = 0; k < 2; k++) {
        iacsg_scene *s = build_scene(&t);
        iacsg_error err = {0};
        iacsg_expr *e = NULL;
        CHECK(iacsg_expr_parse("x^2 + y^2 + (z - 0.125)^2 - 1.125", "<surface>", &e, &err) == IACSG_OK, "%s",
              err.message);
        int solid = scene_add_solid(s, NULL, e, &err);
        uint32_t outside_box = CSG_NODE(CSG_OUTSIDE, 2);
        int condition = scene_add_tree(s, &outside_box, 1, &err);
        CHECK(solid >= 0 && condition >= 0 && scene_add_surface(s, NULL, solid, condition, -1, &err) >= 0, "%s",
              err.message);
        iacsg_renderer *r = NULL;
        CHECK(iacsg_renderer_create_scene(s, k ? &tiny : &plain_config, &r, &err) == IACSG_OK, "%s", err.message);
        CHECK(iacsg_render(r, &v, &f[k], &err) == IACSG_OK, "%s", err.message);
        iacsg_renderer_destroy(r);
        iacsg_scene_destroy(s);
    }
    size_t n = (size_t)v.width * (size_t)v.height;
    long surface = 0;
    for (size_t k = 0; k < n; k++)
        surface += f[0].ids[k] == 3;
    CHECK(f[0].retraced_rays == 0 && f[1].retraced_rays > 0 && surface > 100,
          "retraced: %lld with the default room, %lld with 1; %ld pixels of the surface", f[0].retraced_rays,
          f[1].retraced_rays, surface);
    check_same_after_retrace(&f[0], &f[1], n);
    test_note("%lld of %zu rays re-traced, %ld pixels of the surface, images identical", f[1].retraced_rays, n,
              surface);
    iacsg_frame_free(&f[0]);
    iacsg_frame_free(&f[1]);
}

/* A scene without items renders its expression by the first-root path; its ids are 0 where hit, -1 where not. */
TEST_FP(render_scene_plain) {
    iacsg_scene *s = scene_create();
    iacsg_error err = {0};
    CHECK(iacsg_expr_parse("sphere", "<expr>", &s->expr, &err) == IACSG_OK, "%s", err.message);
    iacsg_renderer *r = NULL;
    CHECK(iacsg_renderer_create_scene(s, &plain_config, &r, &err) == IACSG_OK, "%s", err.message);
    iacsg_view v = test_view(48, 0x1p-12);
    iacsg_frame f;
    CHECK(iacsg_render(r, &v, &f, &err) == IACSG_OK, "%s", err.message);
    int both = 1, hits = 0;
    for (int k = 0; k < v.width * v.height; k++) {
        both &= f.ids[k] == (isinf(f.depth[k]) ? -1.0f : 0.0f);
        hits += f.ids[k] == 0;
    }
    CHECK(both && hits > 100, "ids against depth: %d hits", hits);
    iacsg_frame_free(&f);
    iacsg_renderer_destroy(r);
    iacsg_scene_destroy(s);
}
