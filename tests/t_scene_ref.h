/* tests/t_scene_ref.h -- an exact host reference for scenes of regions and surfaces over spheres, boxes and
 * half-spaces, whose insides along a line are one interval in closed form: computed in long double for the
 * pixel's float ray (kernels/camera.h compiled here, as t_render_util.h does), woven into partitions at the
 * solids' crossings and classified with the host's tree evaluation (scene_tree_eval). Independent of the
 * segment path's kernels: none of their code is used.
 *
 *   ref_solid         a sphere |p - c| < r, a box |p_k - c_k| < a_k, a half-space n.p < h
 *   ref_solid_expr    the solid in the scene language (its numbers are dyadic: the text is exact)
 *   ref_span          the solid's inside along the ray, the open interval (in, out); ref_set_ray takes them all
 *                     for one ray, for the functions below
 *   ref_first_claim   the first partition inside the bounds that a region claims: start, end, region
 *   ref_surface_first the first crossing of a surface solid where its condition holds
 *   ref_first_item    the first of them, regions and surfaces
 *   ref_ambiguous     whether a pixel's answer depends on less than a margin (crossings of different solids that
 *                     close, a ray that passes that close to a solid without entering it, a surface point that
 *                     close to a compared solid's boundary)
 *
 * For tests/t_render_*_fp.c (ia_real follows IA_FP64).
 */
#ifndef T_SCENE_REF_H
#define T_SCENE_REF_H
#include "implicits/scene.h"
#include "t_render_util.h"
#include <string.h>

enum { REF_SPHERE, REF_BOX, REF_HALFSPACE };

typedef struct {
    int kind;
    double c[3]; /* centre; the half-space's normal */
    double a[3]; /* the box's half sizes */
    double r;    /* the sphere's radius; the half-space's offset h */
} ref_solid;

static inline ref_solid ref_sphere(double x, double y, double z, double r) {
    return (ref_solid){REF_SPHERE, {x, y, z}, {0, 0, 0}, r};
}
static inline ref_solid ref_box(double x, double y, double z, double a, double b, double c) {
    return (ref_solid){REF_BOX, {x, y, z}, {a, b, c}, 0};
}
static inline ref_solid ref_halfspace(double nx, double ny, double nz, double h) {
    return (ref_solid){REF_HALFSPACE, {nx, ny, nz}, {0, 0, 0}, h};
}

/* The language text of the solid; every number is a short dyadic, printed exactly by %.17g. */
static inline void ref_solid_expr(const ref_solid *s, char *buf, size_t size) {
    const double *c = s->c;
    if (s->kind == REF_SPHERE)
        snprintf(buf, size, "(x - %.17g)^2 + (y - %.17g)^2 + (z - %.17g)^2 - %.17g^2", c[0], c[1], c[2], s->r);
    else if (s->kind == REF_BOX)
        snprintf(buf, size, "max(abs(x - %.17g) - %.17g, abs(y - %.17g) - %.17g, abs(z - %.17g) - %.17g)", c[0],
                 s->a[0], c[1], s->a[1], c[2], s->a[2]);
    else
        snprintf(buf, size, "%.17g * x + %.17g * y + %.17g * z - %.17g", c[0], c[1], c[2], s->r);
}

/* f at p in long double (f < 0 inside). */
static inline long double ref_solid_at(const ref_solid *s, const long double p[3]) {
    long double f = 0;
    for (int k = 0; k < 3; k++) {
        long double u = p[k] - (long double)s->c[k];
        if (s->kind == REF_SPHERE)
            f += u * u;
        else if (s->kind == REF_BOX)
            f = k == 0 ? fabsl(u) - s->a[k] : fmaxl(f, fabsl(u) - s->a[k]);
        else
            f += (long double)s->c[k] * p[k];
    }
    return s->kind == REF_SPHERE ? f - (long double)s->r * s->r : s->kind == REF_BOX ? f : f - s->r;
}

typedef struct {
    long double o[3], d[3];
} ref_ray;

/* The inside of the solid grown by `grow` (a distance; 0 for the solid itself) along the ray: the open interval
 * (*in, *out), infinite ends for a half-space; returns 0 when the ray misses it. */
static inline int ref_span(const ref_solid *s, const ref_ray *ray, long double grow, long double *in,
                           long double *out) {
    const long double *o = ray->o, *d = ray->d;
    if (s->kind == REF_SPHERE) {
        long double oc[3], a = 0, b = 0, c = 0, r = s->r + grow;
        for (int k = 0; k < 3; k++) {
            oc[k] = o[k] - s->c[k];
            a += d[k] * d[k];
            b += oc[k] * d[k];
            c += oc[k] * oc[k];
        }
        long double disc = b * b - a * (c - r * r);
        if (disc <= 0)
            return 0;
        long double q = -(b + copysignl(sqrtl(disc), b)); /* no cancellation */
        *in = fminl(q / a, (c - r * r) / q);
        *out = fmaxl(q / a, (c - r * r) / q);
        return 1;
    }
    if (s->kind == REF_BOX) {
        *in = -INFINITY;
        *out = INFINITY;
        for (int k = 0; k < 3; k++) {
            long double lo = s->c[k] - s->a[k] - grow, hi = s->c[k] + s->a[k] + grow;
            if (d[k] == 0) {
                if (!(lo < o[k] && o[k] < hi))
                    return 0;
                continue;
            }
            long double t1 = (lo - o[k]) / d[k], t2 = (hi - o[k]) / d[k];
            *in = fmaxl(*in, fminl(t1, t2));
            *out = fminl(*out, fmaxl(t1, t2));
        }
        return *in < *out;
    }
    long double nd = 0, no = 0, len = 0;
    for (int k = 0; k < 3; k++) {
        nd += (long double)s->c[k] * d[k];
        no += (long double)s->c[k] * o[k];
        len += (long double)s->c[k] * s->c[k];
    }
    long double h = s->r + grow * sqrtl(len);
    if (nd == 0) {
        *in = -INFINITY;
        *out = INFINITY;
        return no < h;
    }
    long double t = (h - no) / nd;
    *in = nd > 0 ? -INFINITY : t;
    *out = nd > 0 ? t : INFINITY;
    return 1;
}

/* A scene for the reference and the renderer at once: the solids, and the scene built from their text. */
#define REF_MAX_SOLIDS 512
typedef struct {
    ref_solid solids[REF_MAX_SOLIDS];
    int nsolids;
    iacsg_scene *scene;
    /* the insides (ref_span) of every solid along the ray last given to ref_set_ray */
    unsigned char meets[REF_MAX_SOLIDS];
    long double in[REF_MAX_SOLIDS], out[REF_MAX_SOLIDS];
} ref_scene;

static inline void ref_scene_init(ref_scene *rs) {
    rs->nsolids = 0;
    rs->scene = scene_create();
    CHECK(rs->scene, "out of memory");
}

static inline int ref_add_solid(ref_scene *rs, ref_solid s) {
    CHECK(rs->nsolids < REF_MAX_SOLIDS, "too many solids");
    char text[512];
    ref_solid_expr(&s, text, sizeof text);
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse(text, "solid", &e, &err) == IACSG_OK, "%s: %s", text, err.message);
    int k = scene_add_solid(rs->scene, NULL, e, &err);
    CHECK(k == rs->nsolids, "scene_add_solid: %s", err.message);
    rs->solids[rs->nsolids++] = s;
    return k;
}

/* Parses a tree written in preorder tokens, separated by spaces: "u" union, "i" intersection, "d" difference,
 * "n" not, "<k" solid k inside, ">k" solid k outside (e.g. "d <0 u <1 <2" is 0 \ (1 | 2)). Operands of binary
 * nodes relative to the first node, as scene_add_tree takes them. */
static inline void ref_parse_tree(const char **p, uint32_t *nodes, int *n, int cap) {
    while (**p == ' ')
        (*p)++;
    CHECK(*n < cap && **p, "tree too large or incomplete");
    int self = (*n)++;
    char op = *(*p)++;
    if (op == '<' || op == '>') {
        char *end;
        long k = strtol(*p, &end, 10);
        CHECK(end != *p, "a leaf without a solid");
        *p = end;
        nodes[self] = CSG_NODE(op == '<' ? CSG_INSIDE : CSG_OUTSIDE, (uint32_t)k);
        return;
    }
    CHECK(op == 'u' || op == 'i' || op == 'd' || op == 'n', "bad tree token %c", op);
    ref_parse_tree(p, nodes, n, cap);
    if (op == 'n') {
        nodes[self] = CSG_NODE(CSG_NOT, 0);
        return;
    }
    nodes[self] = CSG_NODE(op == 'u' ? CSG_UNION : op == 'i' ? CSG_INTERSECT : CSG_DIFFERENCE, (uint32_t)*n);
    ref_parse_tree(p, nodes, n, cap);
}

/* Adds the tree to the scene; returns its root in the scene's node array. */
static inline int ref_add_tree(ref_scene *rs, const char *preorder) {
    uint32_t nodes[2048];
    int n = 0;
    ref_parse_tree(&preorder, nodes, &n, 2048);
    iacsg_error err = {0};
    int root = scene_add_tree(rs->scene, nodes, n, &err);
    CHECK(root >= 0, "scene_add_tree: %s", err.message);
    return root;
}

static inline int ref_add_region(ref_scene *rs, const char *preorder) {
    iacsg_error err = {0};
    int id = scene_add_region(rs->scene, NULL, ref_add_tree(rs, preorder), -1, &err);
    CHECK(id >= 0, "scene_add_region: %s", err.message);
    return id;
}

static inline int ref_add_surface(ref_scene *rs, int solid, const char *condition) {
    iacsg_error err = {0};
    int id = scene_add_surface(rs->scene, NULL, solid, condition ? ref_add_tree(rs, condition) : -1, -1, &err);
    CHECK(id >= 0, "scene_add_surface: %s", err.message);
    return id;
}

/* Takes the insides of every solid along the ray, for the functions below. */
static inline void ref_set_ray(ref_scene *rs, const ref_ray *ray) {
    for (int k = 0; k < rs->nsolids; k++)
        rs->meets[k] = (unsigned char)ref_span(&rs->solids[k], ray, 0, &rs->in[k], &rs->out[k]);
}

/* The side of each solid at the point t of the ray: -1 inside, 1 outside, 0 on its boundary. */
static inline void ref_signs_at(const ref_scene *rs, long double t, signed char *sign) {
    for (int k = 0; k < rs->nsolids; k++) {
        int meets = rs->meets[k];
        sign[k] = (signed char)(meets && rs->in[k] < t && t < rs->out[k] ? -1
                                : meets && (t == rs->in[k] || t == rs->out[k]) ? 0
                                                                               : 1);
    }
}

/* Whether the condition at `root` holds at the point t of the ray. */
static inline int ref_holds_at(const ref_scene *rs, int root, long double t) {
    signed char sign[REF_MAX_SOLIDS];
    ref_signs_at(rs, t, sign);
    return scene_tree_eval(rs->scene, root, sign);
}

/* The ray's part inside the bounds, exactly (the renderer's clip is this one widened outward). */
static inline int ref_clip(const double bounds[6], const ref_ray *ray, long double *t0, long double *t1) {
    ref_solid box = ref_box((bounds[0] + bounds[3]) / 2, (bounds[1] + bounds[4]) / 2, (bounds[2] + bounds[5]) / 2,
                            (bounds[3] - bounds[0]) / 2, (bounds[4] - bounds[1]) / 2, (bounds[5] - bounds[2]) / 2);
    if (!ref_span(&box, ray, 0, t0, t1))
        return 0;
    *t0 = fmaxl(*t0, 0);
    return *t0 < *t1;
}

/* The crossings of the ray with every solid's boundary inside (t0, t1), sorted, with the solid of each. */
typedef struct {
    long double t;
    int solid;
} ref_crossing;

static inline int ref_cmp_crossing(const void *a, const void *b) {
    long double x = ((const ref_crossing *)a)->t, y = ((const ref_crossing *)b)->t;
    return (x > y) - (x < y);
}

static inline int ref_crossings(const ref_scene *rs, long double t0, long double t1, ref_crossing *out) {
    int n = 0;
    for (int k = 0; k < rs->nsolids; k++) {
        if (!rs->meets[k])
            continue;
        if (rs->in[k] > t0 && rs->in[k] < t1)
            out[n++] = (ref_crossing){rs->in[k], k};
        if (rs->out[k] > t0 && rs->out[k] < t1)
            out[n++] = (ref_crossing){rs->out[k], k};
    }
    qsort(out, (size_t)n, sizeof *out, ref_cmp_crossing);
    return n;
}

/* The first partition of (t0, t1) that a region claims: its start, end and region (the first declared of those
 * whose tree holds at its midpoint), and the solid whose boundary it starts at (-1: the bounds); returns -1 when
 * none does. */
static inline int ref_first_claim(const ref_scene *rs, long double t0, long double t1, long double *start,
                                  long double *end, int *solid) {
    static ref_crossing c[2 * REF_MAX_SOLIDS + 2];
    signed char sign[REF_MAX_SOLIDS];
    int n = ref_crossings(rs, t0, t1, c);
    for (int k = 0; k <= n; k++) {
        long double a = k == 0 ? t0 : c[k - 1].t, b = k == n ? t1 : c[k].t;
        if (!(a < b))
            continue;
        ref_signs_at(rs, (a + b) / 2, sign);
        for (int item = 0; item < rs->scene->nitems; item++) {
            const scene_item *it = &rs->scene->items[item];
            if (it->kind == SCENE_REGION && scene_tree_eval(rs->scene, it->tree, sign)) {
                *start = a;
                *end = b;
                *solid = k == 0 ? -1 : c[k - 1].solid;
                return item;
            }
        }
    }
    return -1;
}

/* The first crossing in (t0, t1) of surface item `item`'s solid where its condition holds; returns 0 if none. */
static inline int ref_surface_first(const ref_scene *rs, int item, long double t0, long double t1, long double *t) {
    const scene_item *it = &rs->scene->items[item];
    if (!rs->meets[it->solid])
        return 0;
    long double cand[2] = {rs->in[it->solid], rs->out[it->solid]};
    for (int k = 0; k < 2; k++)
        if (cand[k] > t0 && cand[k] < t1 && (it->tree < 0 || ref_holds_at(rs, it->tree, cand[k]))) {
            *t = cand[k];
            return 1;
        }
    return 0;
}

/* The first item the ray meets in (t0, t1): a region's first claimed partition or a surface's first kept point,
 * the earlier (the first declared on a tie), with the solid whose boundary is there (-1: the bounds); returns -1
 * when none. */
static inline int ref_first_item(const ref_scene *rs, long double t0, long double t1, long double *t, int *solid) {
    long double start, end;
    int id = ref_first_claim(rs, t0, t1, &start, &end, solid);
    *t = id >= 0 ? start : INFINITY;
    for (int item = 0; item < rs->scene->nitems; item++) {
        long double ts;
        if (rs->scene->items[item].kind == SCENE_SURFACE && ref_surface_first(rs, item, t0, t1, &ts) &&
            (ts < *t || (ts == *t && item < id))) {
            *t = ts;
            *solid = rs->scene->items[item].solid;
            id = item;
        }
    }
    return id;
}

/* The gradient of the solid at p (the box's: the outward axis of its nearest face). */
static inline void ref_gradient(const ref_solid *s, const long double p[3], long double g[3]) {
    int face = 0;
    for (int k = 0; k < 3; k++) {
        long double u = p[k] - s->c[k];
        g[k] = s->kind == REF_SPHERE ? 2 * u : s->kind == REF_HALFSPACE ? s->c[k] : 0;
        if (fabsl(u) - s->a[k] > fabsl(p[face] - s->c[face]) - s->a[face])
            face = k;
    }
    if (s->kind == REF_BOX)
        g[face] = p[face] < s->c[face] ? -1 : 1;
}

/* The distance from p to the solid's boundary. */
static inline long double ref_distance(const ref_solid *s, const long double p[3]) {
    long double u[3], outside = 0, inside = INFINITY, len = 0, f = ref_solid_at(s, p);
    for (int k = 0; k < 3; k++) {
        u[k] = fabsl(p[k] - s->c[k]) - s->a[k];
        outside += u[k] > 0 ? u[k] * u[k] : 0;
        inside = fminl(inside, -u[k]);
        len += (long double)s->c[k] * s->c[k];
    }
    if (s->kind == REF_SPHERE)
        return fabsl(sqrtl(f + (long double)s->r * s->r) - s->r);
    if (s->kind == REF_BOX)
        return f > 0 ? sqrtl(outside) : inside;
    return fabsl(f) / sqrtl(len);
}

/* Whether the answer up to `until` may change when boundaries move by less than `margin` (a distance along the
 * ray, which is a unit vector): two crossings of different solids that close (touching or coincident faces), a
 * solid the ray passes within `margin` of without entering it (a graze), or a condition's solid crossed within
 * `margin` of a surface point. A solid thinner than `margin` alone is not ambiguous: it must not be lost. */
static inline int ref_ambiguous(const ref_scene *rs, const ref_ray *ray, long double t0, long double t1,
                                long double until, long double margin) {
    static ref_crossing c[2 * REF_MAX_SOLIDS + 2];
    int n = ref_crossings(rs, t0 - margin, t1 + margin, c);
    for (int k = 0; k < n && c[k].t <= until + margin; k++) {
        if (fabsl(c[k].t - t0) <= margin || fabsl(c[k].t - t1) <= margin) /* at the bounds' faces */
            return 1;
        for (int j = k + 1; j < n && c[j].t - c[k].t <= margin; j++)
            if (c[j].solid != c[k].solid)
                return 1;
    }
    for (int k = 0; k < rs->nsolids; k++) {
        long double gin, gout;
        if (!rs->meets[k] && ref_span(&rs->solids[k], ray, margin, &gin, &gout) &&
            gin <= until + margin && gout >= t0)
            return 1;
    }
    /* a surface's condition is decided over boxes around the ray: near a crossing of the surface's solid, a
     * compared solid's boundary that close in space (not only along the ray) leaves it undecided */
    for (int k = 0; k < n && c[k].t <= until + margin; k++) {
        int surface = 0;
        for (int item = 0; item < rs->scene->nitems; item++)
            surface |= rs->scene->items[item].kind == SCENE_SURFACE && rs->scene->items[item].solid == c[k].solid;
        long double q[3];
        for (int j = 0; j < 3; j++)
            q[j] = ray->o[j] + c[k].t * ray->d[j];
        for (int j = 0; surface && j < rs->nsolids; j++)
            if (j != c[k].solid && ref_distance(&rs->solids[j], q) <= margin)
                return 1;
    }
    return 0;
}

/* Pixel (i, j)'s float ray in long double (exactly the values the device traced). */
static inline void ref_pixel_ray(const ia_real p[PARAM_COUNT], const iacsg_view *view, int i, int j, ref_ray *ray) {
    double o[3], d[3];
    pixel_ray(p, view, i, j, o, d);
    for (int k = 0; k < 3; k++) {
        ray->o[k] = o[k];
        ray->d[k] = d[k];
    }
}

#endif
