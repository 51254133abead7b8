/* tests/t_render_props_fp.c -- the render guarantee over a class of expressions, not a few examples: random
 * expressions of the compiler tests' generator (t_expr_oracle.h: poles of x^-1, x / y and tan, sqrt, log, pow,
 * min and max, primitives, blends, transforms) and unions of more parts than the group size (emitted in groups),
 * rendered by the library in float and in double (interval Newton on wherever the compiler emits the
 * derivative) from random orthographic and perspective cameras; on every ray the depth must not be after the
 * first root of the ray inside the bounds, and a ray with a root must hit. The two examples of issue 17's item 1
 * (Newton across a pole) are pinned first.
 *
 * The reference, per ray: the float ray the device traced (kernels/camera.h, as in the other render tests), its
 * exact part [tn, tf] inside the bounds, and f in MPFR (expr_oracle: the expression as written, at 256 bits) at
 * SAMPLES points evenly spaced over [tn, T], T = tf on a miss and a little past the depth on a hit. Between two
 * neighbouring samples where f is defined and of opposite signs, bisection in MPFR narrows the bracket
 * BRACKET_HALVINGS times: at a root |f| at its ends falls with the width, at a pole it grows, so the change is a
 * root when the larger |f| at the ends fell below 1e-6 of its first value, a pole when it grew (otherwise, or
 * at an undefined midpoint, the change is undecided, and unchecked). A sample where f is 0 is a root. The
 * reference may miss roots closer together than a sample spacing, and roots where some subexpression is undefined
 * (the oracle's union of a defined and an undefined part is undefined), and never invents one, so the check is
 * weaker than the guarantee, never stricter; the test requires a minimum number of rays with a root, so that it is
 * not vacuous.
 */
#include "t_expr_oracle.h"
#include "t_render_util.h"

#ifdef IA_FP64
#define FP64 1
#else
#define FP64 0
#endif

/* Samples per ray and halvings per sign change of the reference; random views per expression, of VIEW_SIZE^2
 * pixels; parts of a random union (the compiler groups from 16); frames of the pinned examples; rays with a root
 * per random expression asked for. */
enum { SAMPLES = 96, BRACKET_HALVINGS = 44, VIEWS = 3, VIEW_SIZE = 10, UNION_PARTS = 18, PINNED_TIMES = 8 };
enum { MIN_ROOTS = 50 };

/* f at o + t d, into y; 0 where undefined. */
static int f_on_ray(const iacsg_expr *e, const double o[3], const double d[3], double t, double time, mpfr_ptr y) {
    double p[4] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2], time};
    return expr_oracle(e, p, y);
}

typedef enum { CHANGE_ROOT, CHANGE_POLE, CHANGE_UNDECIDED } change_kind;

/* Narrows the sign change between a and b (f defined at both, opposite signs) and tells a root from a pole;
 * *hi is then the bracket's upper end (the root is at or before it). */
static change_kind classify_change(const iacsg_expr *e, const double o[3], const double d[3], double time, double a,
                                   double b, double *hi) {
    mpfr_t fa, fb, fm;
    mpfr_inits2(EXPR_ORACLE_PREC, fa, fb, fm, (mpfr_ptr)0);
    f_on_ray(e, o, d, a, time, fa);
    f_on_ray(e, o, d, b, time, fb);
    double first = fmax(fabs(mpfr_get_d(fa, MPFR_RNDN)), fabs(mpfr_get_d(fb, MPFR_RNDN)));
    change_kind kind = CHANGE_UNDECIDED;
    int k = 0;
    for (; k < BRACKET_HALVINGS; k++) {
        double m = a + 0.5 * (b - a);
        if (!(m > a && m < b))
            break; /* neighbouring doubles */
        if (!f_on_ray(e, o, d, m, time, fm))
            goto done;
        if (mpfr_zero_p(fm)) {
            kind = CHANGE_ROOT;
            b = m;
            goto done;
        }
        if (mpfr_sgn(fm) == mpfr_sgn(fa))
            a = m, mpfr_swap(fa, fm);
        else
            b = m, mpfr_swap(fb, fm);
    }
    double last = fmax(fabs(mpfr_get_d(fa, MPFR_RNDN)), fabs(mpfr_get_d(fb, MPFR_RNDN)));
    kind = k >= 20 && last <= 1e-6 * first ? CHANGE_ROOT : last >= first ? CHANGE_POLE : CHANGE_UNDECIDED;
done:
    *hi = b;
    mpfr_clears(fa, fb, fm, (mpfr_ptr)0);
    return kind;
}

typedef struct {
    long rays, roots, poles, undecided, late, missed;
} props_report;

/* The first root of f on the ray in [tn, T] that the samples see: returns 1 with *root_hi the upper end of its
 * bracket, 0 if none. Counts the poles and undecided changes passed before it. */
static int first_root(const iacsg_expr *e, const double o[3], const double d[3], double time, double tn, double T,
                      double *root_hi, props_report *rep) {
    mpfr_t prev, cur;
    mpfr_inits2(EXPR_ORACLE_PREC, prev, cur, (mpfr_ptr)0);
    int prev_ok = 0, found = 0;
    double prev_t = tn;
    for (int s = 0; s <= SAMPLES && !found; s++) {
        double t = s == SAMPLES ? T : tn + (T - tn) * s / SAMPLES;
        int ok = f_on_ray(e, o, d, t, time, cur);
        if (ok && mpfr_zero_p(cur)) {
            *root_hi = t;
            found = 1;
        } else if (ok && prev_ok && mpfr_sgn(cur) != mpfr_sgn(prev)) {
            change_kind kind = classify_change(e, o, d, time, prev_t, t, root_hi);
            found = kind == CHANGE_ROOT;
            rep->poles += kind == CHANGE_POLE;
            rep->undecided += kind == CHANGE_UNDECIDED;
        }
        mpfr_swap(prev, cur);
        prev_ok = ok;
        prev_t = t;
    }
    mpfr_clears(prev, cur, (mpfr_ptr)0);
    return found;
}

/* Renders e in view v and checks every ray against the reference. */
static void check_view(const char *text, const iacsg_expr *e, iacsg_renderer *r, const iacsg_view *v,
                       props_report *rep) {
    iacsg_error err = {0};
    iacsg_frame fr;
    CHECK(iacsg_render(r, v, &fr, &err) == IACSG_OK, "'%s': %s", text, err.message);
    ia_real p[PARAM_COUNT];
    view_params(v, p);
    for (int j = 0; j < v->height; j++)
        for (int i = 0; i < v->width; i++) {
            double o[3], d[3], tn, tf, root = 0;
            pixel_ray(p, v, i, j, o, d);
            if (!ray_box_span(v->bounds, o, d, &tn, &tf))
                continue;
            rep->rays++;
            double depth = fr.depth[(size_t)j * v->width + i];
            /* a hit: look for a root before the depth, and a little past it (so that roots are seen) */
            double T = isfinite(depth) ? fmin(tf, depth + (tf - tn) / 8) : tf;
            if (!first_root(e, o, d, v->time[0], tn, T, &root, rep))
                continue;
            rep->roots++;
            int missed = !isfinite(depth), late = !missed && depth > root + 1e-9 * (1 + fabs(root));
            rep->missed += missed;
            rep->late += late;
            if ((missed || late) && rep->missed + rep->late <= 5)
                test_note("'%s' t = %g, eye (%g, %g, %g) at (%g, %g, %g) %s %g, eps %g, pixel (%d, %d): depth %.9g, "
                          "but the first root is at or before %.9g",
                          text, v->time[0], v->camera.eye[0], v->camera.eye[1], v->camera.eye[2], v->camera.at[0],
                          v->camera.at[1], v->camera.at[2], v->camera.ortho_height > 0 ? "ortho" : "fov",
                          v->camera.ortho_height > 0 ? v->camera.ortho_height : v->camera.fov, v->eps, i, j, depth,
                          root);
        }
    iacsg_frame_free(&fr);
}

/* A random view of the bounds [-2, 2]^3 (the eye sometimes inside them), at a random double time (the kernel
 * encloses it, as it does every constant). */
static iacsg_view random_view(test_rng_t *rng) {
    iacsg_view v = {.width = VIEW_SIZE, .height = VIEW_SIZE, .bounds = {-2, -2, -2, 2, 2, 2}};
    double at[3];
    for (int k = 0; k < 3; k++)
        at[k] = test_rand_unit(rng) - 0.5;
    double az = 360 * test_rand_unit(rng), el = 170 * test_rand_unit(rng) - 85;
    iacsg_camera_set_azel(&v.camera, at, az, el, 2.5 + 4 * test_rand_unit(rng));
    if (test_rand_u64(rng) % 2)
        v.camera.ortho_height = 0.5 + 3.5 * test_rand_unit(rng);
    else
        v.camera.fov = 15 + 45 * test_rand_unit(rng);
    v.eps = pow(10, -3 - 3 * test_rand_unit(rng));
    v.time[0] = v.time[1] = test_rand_unit(rng);
    return v;
}

/* Builds the renderer of `text` (the compiler's error ends the test) and checks it in `count` views. */
static void check_expression(const char *text, const iacsg_view *views, int count, props_report *rep) {
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse(text, "<test>", &e, &err) == IACSG_OK, "'%s': %s", text, err.message);
    iacsg_render_config config = {.fp64 = FP64};
    iacsg_renderer *r = NULL;
    CHECK(iacsg_renderer_create_expr(e, &config, &r, &err) == IACSG_OK, "'%s': %s", text, err.message);
    for (int k = 0; k < count; k++)
        check_view(text, e, r, &views[k], rep);
    iacsg_renderer_destroy(r);
    iacsg_expr_destroy(e);
}

/* Whether e is defined at 16 random points of [-2, 2]^3 x [0, 1]: a part of a union that is undefined at a
 * point makes the reference's union undefined there (t_expr_oracle.h), so a union of such parts would leave
 * little to check. */
static int mostly_defined(test_rng_t *rng, const char *text) {
    iacsg_expr *e = NULL;
    CHECK(iacsg_expr_parse(text, "<test>", &e, NULL) == IACSG_OK, "'%s' does not compile", text);
    mpfr_t y;
    mpfr_init2(y, EXPR_ORACLE_PREC);
    int defined = 1;
    for (int k = 0; k < 16 && defined; k++) {
        double p[4] = {4 * test_rand_unit(rng) - 2, 4 * test_rand_unit(rng) - 2, 4 * test_rand_unit(rng) - 2,
                       test_rand_unit(rng)};
        defined = expr_oracle(e, p, y);
    }
    mpfr_clear(y);
    iacsg_expr_destroy(e);
    return defined;
}

/* A union of UNION_PARTS random parts (defined at random points: mostly_defined): past the group size, so
 * emitted in groups. */
static void random_union(test_rng_t *rng, char *buf, size_t size) {
    char part[4096];
    size_t len = (size_t)snprintf(buf, size, "min(");
    for (int k = 0; k < UNION_PARTS; k++) {
        do
            expr_random_text(rng, 2, part, sizeof part);
        while (!mostly_defined(rng, part));
        len += (size_t)snprintf(buf + len, size - len, "%s%s", k ? ", " : "", part);
    }
    snprintf(buf + len, size - len, ")");
}

TEST_FP(render_props_depth_never_late) {
    props_report rep = {0};
    /* Pinned: issue 17's item 1, a pole between the first root and a later one, where interval Newton's
     * derivative enclosure is one-signed: the pole and the roots shifted by t/16 (times k/8, exact), so that
     * in some frame a node that Newton steps holds the first root and has its midpoint past the pole. */
    iacsg_view along_x[PINNED_TIMES];
    for (int k = 0; k < PINNED_TIMES; k++)
        along_x[k] = (iacsg_view){.width = 16, .height = 16, .eps = 0x1p-16, .bounds = {-2, -2, -2, 2, 2, 2},
                                  .time = {k / (double)PINNED_TIMES, k / (double)PINNED_TIMES},
                                  .camera = {.eye = {-3, 0, 0}, .at = {0, 0, 0}, .up = {0, 0, 1}, .ortho_height = 4}};
    check_expression("(x+0.52+t/16)^-1 - 1000*(x+0.52+t/16)", along_x, PINNED_TIMES, &rep);
    check_expression("tan(x+2.0907963267948966+t/16) + 1000*(x+0.52+t/16)", along_x, PINNED_TIMES, &rep);
    test_note("pinned: %ld rays in the bounds, %ld with a root; %ld missed, %ld late", rep.rays, rep.roots,
              rep.missed, rep.late);
    /* Random expressions (one in two a union) until n are done and they gave MIN_ROOTS rays with a root each
     * (many random expressions are constants, or undefined in most of the bounds), at most 4 n. */
    props_report pinned = rep, random = {0};
    long n = test_iters(4), k = 0;
    static char text[1 << 16];
    for (; k < 4 * n && (k < n || random.roots < n * MIN_ROOTS); k++) {
        if (k % 2)
            random_union(test_rng(), text, sizeof text);
        else
            expr_random_text(test_rng(), 4, text, sizeof text);
        iacsg_view views[VIEWS];
        for (int m = 0; m < VIEWS; m++)
            views[m] = random_view(test_rng());
        check_expression(text, views, VIEWS, &random);
    }
    test_note("%ld random expressions, %ld rays in the bounds: %ld with a root, %ld poles and %ld undecided sign "
              "changes before it; %ld missed, %ld late",
              k, random.rays, random.roots, random.poles, random.undecided, random.missed, random.late);
    CHECK(pinned.missed == 0 && pinned.late == 0, "pinned: %ld rays missed their first root, %ld hit after it",
          pinned.missed, pinned.late);
    CHECK(random.missed == 0 && random.late == 0, "%ld rays missed their first root, %ld hit after it",
          random.missed, random.late);
    CHECK(random.roots >= n * MIN_ROOTS, "only %ld rays with a root: the test checks too little", random.roots);
}
