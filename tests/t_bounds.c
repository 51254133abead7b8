/* tests/t_bounds.c -- iacsg_expr_bounds proves what it says: for the time interval asked (not [0, 1]), and in
 * all of space when it says EVERYWHERE (not only in [-1024, 1024]^3); and the render command renders what lies
 * there and prints what was proven. */
#include "iacsg.h"
#include "image.h"
#include "t_expr_oracle.h"
#include "test.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* A union of moving spheres: sphere k has centre (a + b t, c, d) and radius r. */
typedef struct {
    double a, b, c, d, r;
} moving_sphere;

/* A coordinate of either sign, with magnitude log-uniform from 2^-3 to 2^23 (far beyond the cube), or 0. */
static double far_coordinate(test_rng_t *rng) {
    if (test_rand_u64(rng) % 5 == 0)
        return 0;
    double m = ldexp(1 + test_rand_unit(rng), (int)(test_rand_u64(rng) % 27) - 3);
    return test_rand_u64(rng) & 1 ? m : -m;
}

/* The exact box of the union's surface over t in [t0, t1]: x0,y0,z0,x1,y1,z1. */
static void union_box(const moving_sphere *s, int n, const double t[2], double box[6]) {
    for (int k = 0; k < 3; k++)
        box[k] = INFINITY, box[k + 3] = -INFINITY;
    for (int i = 0; i < n; i++) {
        double x0 = fmin(s[i].a + s[i].b * t[0], s[i].a + s[i].b * t[1]);
        double x1 = fmax(s[i].a + s[i].b * t[0], s[i].a + s[i].b * t[1]);
        double lo[3] = {x0, s[i].c, s[i].d}, hi[3] = {x1, s[i].c, s[i].d};
        for (int k = 0; k < 3; k++) {
            box[k] = fmin(box[k], lo[k] - s[i].r);
            box[k + 3] = fmax(box[k + 3], hi[k] + s[i].r);
        }
    }
}

/* Random unions of one to three moving spheres, some far outside [-1024, 1024]^3, over random time intervals
 * (points among them, and times outside [0, 1]): the proof must be EVERYWHERE for all of them (squares of
 * affine terms are tight over unbounded boxes), and the box must hold the exact box of the surface. */
TEST(bounds_hold_far_and_moving_spheres) {
    test_rng_t *rng = test_rng();
    long n = test_iters(150), everywhere = 0, outside_cube = 0;
    for (long it = 0; it < n; it++) {
        moving_sphere s[3];
        int count = 1 + (int)(test_rand_u64(rng) % 3);
        char text[1024] = "min(", *p = text + 4 * (count > 1);
        for (int i = 0; i < count; i++) {
            s[i] = (moving_sphere){far_coordinate(rng), far_coordinate(rng), far_coordinate(rng), far_coordinate(rng),
                                   ldexp(1 + test_rand_unit(rng), (int)(test_rand_u64(rng) % 8) - 4)};
            p += snprintf(p, (size_t)(text + sizeof text - p), "%s(x-(%.17g)-(%.17g)*t)^2+(y-(%.17g))^2+(z-(%.17g))^2-%.17g^2",
                          i ? ", " : "", s[i].a, s[i].b, s[i].c, s[i].d, s[i].r);
        }
        snprintf(p, (size_t)(text + sizeof text - p), "%s", count > 1 ? ")" : "");
        double t[2] = {ldexp(test_rand_unit(rng) - 0.5, 4), 0};
        t[1] = test_rand_u64(rng) % 3 == 0 ? t[0] : t[0] + ldexp(test_rand_unit(rng), 3);
        iacsg_expr *e;
        iacsg_error err = {0};
        CHECK(iacsg_expr_parse(text, "<test>", &e, &err) == IACSG_OK, "'%s': %s", text, err.message);
        double box[6], exact[6];
        iacsg_bounds_proof proof = iacsg_expr_bounds(e, t, box);
        iacsg_expr_destroy(e);
        union_box(s, count, t, exact);
        CHECK(proof == IACSG_BOUNDS_EVERYWHERE, "'%s' over t in [%.17g, %.17g]: proof %d", text, t[0], t[1], (int)proof);
        for (int k = 0; k < 3; k++) {
            double slack = 1e-9 * (fabs(exact[k]) + fabs(exact[k + 3]) + 1); /* the rounding of union_box */
            CHECK(box[k] <= exact[k] + slack && box[k + 3] >= exact[k + 3] - slack,
                  "'%s' over t in [%.17g, %.17g]: axis %d: box [%.17g, %.17g] misses the surface's [%.17g, %.17g]",
                  text, t[0], t[1], k, box[k], box[k + 3], exact[k], exact[k + 3]);
        }
        everywhere++;
        outside_cube += fmax(fabs(exact[0]), fabs(exact[3])) > IACSG_BOUNDS_CUBE;
    }
    CHECK(outside_cube > n / 4, "only %ld of %ld cases reach outside the cube", outside_cube, n);
    test_note("%ld unions proven everywhere, %ld of them reaching outside [-1024, 1024]^3", everywhere, outside_cube);
}

/* When all of space cannot be proven (inf - inf over unbounded boxes), the proof says that it holds in the
 * cube only, and that box still holds the surface inside the cube. (A tangle with 5.1, no point: the simplifier
 * leaves x^4 - 5.1 x^2 as written, whose dependency defeats the proof beyond the cube; with 5 it completes the
 * squares, and the tangle is proven everywhere: t_expr_parse.c's expr_uses_time_and_bounds.) */
TEST(bounds_say_when_only_the_cube_is_proven) {
    static const struct {
        const char *text;
        double x1; /* the surface's largest x inside the cube */
    } cases[] = {
        {"x^4 - 5.1*x^2 + y^4 - 5.1*y^2 + z^4 - 5.1*z^2 + 11.8", 2.3},
        {"min(x^4 - 5.1*x^2 + y^2 + z^2, (x-2000)^2 + y^2 + z^2 - 1)", 2.25},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        iacsg_expr *e;
        CHECK(iacsg_expr_parse(cases[i].text, "<test>", &e, NULL) == IACSG_OK, "%s", cases[i].text);
        double box[6];
        iacsg_bounds_proof proof = iacsg_expr_bounds(e, (double[2]){0, 0}, box);
        iacsg_expr_destroy(e);
        CHECK(proof == IACSG_BOUNDS_IN_CUBE, "'%s': proof %d", cases[i].text, (int)proof);
        CHECK(box[3] >= cases[i].x1 && box[3] < 8, "'%s': x1 = %g", cases[i].text, box[3]);
    }
}

/* The sign of f at (p, t) by the MPFR oracle: -1, 0 or 1, and 2 where f is undefined; |f| into *mag. */
static int sign_at(const iacsg_expr *e, const double p[3], double t, mpfr_ptr y, double *mag) {
    double v[4] = {p[0], p[1], p[2], t};
    if (!expr_oracle(e, v, y))
        return 2;
    *mag = fabs(mpfr_get_d(y, MPFR_RNDN));
    return mpfr_sgn(y) > 0 ? 1 : mpfr_sgn(y) < 0 ? -1 : 0;
}

/* 1 if f changes sign between p and q (both defined) through a root, found by bisection (down to neighbouring
 * doubles, or 200 halvings) and told from a pole by |f| there; 0 otherwise, or where f is undefined on the way. */
static int root_between(const iacsg_expr *e, double p[3], double q[3], double t, mpfr_ptr y) {
    double fp, fq, fm;
    int sp = sign_at(e, p, t, y, &fp), sq = sign_at(e, q, t, y, &fq);
    if (sp == 2 || sq == 2 || sp * sq > 0)
        return 0;
    if (sp == 0 || sq == 0)
        return 1;
    for (int step = 0; step < 200; step++) {
        double m[3];
        int moved = 0;
        for (int k = 0; k < 3; k++) {
            m[k] = p[k] * 0.5 + q[k] * 0.5;
            moved |= m[k] != p[k] && m[k] != q[k];
        }
        if (!moved)
            break;
        int sm = sign_at(e, m, t, y, &fm);
        if (sm == 2)
            return 0;
        if (sm == 0)
            return 1;
        double *side = sm == sp ? p : q;
        memcpy(side, m, sizeof m);
        *(sm == sp ? &fp : &fq) = fm;
    }
    return fmin(fp, fq) < 1e-3;
}

/* A point beyond the face (axis, side) of box, in the region the proof covers (|coordinates| <= limit): the
 * other coordinates near the box or far, the axis' past the face by a log-uniform gap. 0 if there is none. */
static int point_beyond(test_rng_t *rng, const double box[6], int axis, int side, double limit, double p[3]) {
    for (int k = 0; k < 3; k++)
        p[k] = test_rand_u64(rng) % 4 ? box[k] + (box[k + 3] - box[k]) * test_rand_unit(rng) : far_coordinate(rng);
    double face = side > 0 ? box[axis + 3] : box[axis], width = box[axis + 3] - box[axis];
    double gap = test_rand_u64(rng) & 1 ? width * test_rand_unit(rng)
                                        : ldexp(1 + test_rand_unit(rng), (int)(test_rand_u64(rng) % 40) - 30) * fmax(1, fabs(face));
    p[axis] = face + side * gap;
    for (int k = 0; k < 3; k++)
        p[k] = fmax(-limit, fmin(limit, p[k]));
    return side * (p[axis] - face) > 0;
}

/* 1 if the point is in the box, up to the rounding of its computation. */
static int in_box(const double box[6], const double p[3]) {
    for (int k = 0; k < 3; k++) {
        double slack = 1e-12 * fabs(p[k]);
        if (p[k] < box[k] - slack || p[k] > box[k + 3] + slack)
            return 0;
    }
    return 1;
}

/* Random expressions of the compiler's tests (poles, tan, sqrt, log, pow, min/max, primitives, transforms), some
 * cut by or joined with a sphere moving along x (often outside the cube), over random time intervals. Wherever a
 * box is proven: (1) points of the joined sphere, on the surface where the other part is positive (and
 * defined), are in it (or, proven in the cube only, outside the cube); (2) no segment from beyond one of its faces outward (so
 * wholly outside the box, in the region proven) crosses a root of f at a time of the interval. The control runs
 * (2) from the faces of the box halved, and must find roots. */
TEST(bounds_hold_every_root_of_random_expressions) {
    test_rng_t *rng = test_rng();
    mpfr_t y;
    mpfr_init2(y, EXPR_ORACLE_PREC);
    /* Far points make exp overflow: beyond 2^16384 the oracle calls it infinite (undefined) at once, where tan of
     * it would take MPFR seconds of argument reduction. */
    mpfr_exp_t emax = mpfr_get_emax();
    mpfr_set_emax(1 << 14);
    long n = test_iters(300), proven = 0, known = 0, segments = 0, control_roots = 0;
    for (long it = 0; it < n; it++) {
        char text[4608], body[4096], moving[256];
        expr_random_text(rng, 4, body, sizeof body);
        moving_sphere m = {far_coordinate(rng), far_coordinate(rng), far_coordinate(rng), far_coordinate(rng),
                           sqrt(0.25 + 8 * test_rand_unit(rng))};
        snprintf(moving, sizeof moving, "(x-(%.17g)-(%.17g)*t)^2+(y-(%.17g))^2+(z-(%.17g))^2-%.17g", m.a, m.b, m.c,
                 m.d, m.r * m.r);
        int variant = (int)(test_rand_u64(rng) % 3);
        if (variant == 0)
            snprintf(text, sizeof text, "max(%s, %s)", body, moving);
        else if (variant == 1) /* positive outside the unit ball but on the moving sphere */
            snprintf(text, sizeof text, "min(max(%s, x^2+y^2+z^2-1), %s)", body, moving);
        else
            snprintf(text, sizeof text, "%s", body);
        iacsg_expr *e;
        if (iacsg_expr_parse(text, "<test>", &e, NULL) != IACSG_OK)
            continue;
        double t[2] = {ldexp(test_rand_unit(rng) - 0.5, 3), 0}, box[6];
        t[1] = test_rand_u64(rng) % 3 == 0 ? t[0] : t[0] + test_rand_unit(rng);
        iacsg_bounds_proof proof = iacsg_expr_bounds(e, t, box);
        if (proof == IACSG_BOUNDS_NONE) {
            iacsg_expr_destroy(e);
            continue;
        }
        proven++;
        double limit = proof == IACSG_BOUNDS_EVERYWHERE ? INFINITY : IACSG_BOUNDS_CUBE, halved[6];
        for (int k = 0; k < 3; k++) {
            double mid = box[k] * 0.5 + box[k + 3] * 0.5, half = box[k + 3] * 0.5 - box[k] * 0.5;
            halved[k] = mid - half / 2;
            halved[k + 3] = mid + half / 2;
        }
        for (int k = 0; variant == 1 && k < 24; k++) {
            double at = t[0] + (t[1] - t[0]) * test_rand_unit(rng), p[3] = {m.a + m.b * at, m.c, m.d}, u[3], len2 = 0;
            for (int c = 0; c < 3; c++) { /* a direction, not quite uniform: only that it spreads */
                u[c] = 2 * test_rand_unit(rng) - 1;
                len2 += u[c] * u[c];
            }
            for (int c = 0; c < 3; c++)
                p[c] += m.r * u[c] / sqrt(len2);
            double mag;
            if (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] < 1.01 ||
                fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2]))) > limit || sign_at(e, p, at, y, &mag) == 2)
                continue; /* inside the unit ball, outside the region proven, or where the other part is undefined */
            known++;
            CHECK(in_box(box, p), "'%s' over t in [%.17g, %.17g], proof %d: box %g,%g,%g,%g,%g,%g misses the surface "
                  "point (%.17g, %.17g, %.17g) at t = %.17g", text, t[0], t[1], (int)proof, box[0], box[1], box[2],
                  box[3], box[4], box[5], p[0], p[1], p[2], at);
        }
        for (int s = 0; s < 40; s++) {
            int axis = (int)(test_rand_u64(rng) % 3), side = test_rand_u64(rng) & 1 ? 1 : -1, control = s % 2;
            double p[3], q[3], at = t[0] + (t[1] - t[0]) * test_rand_unit(rng);
            if (!point_beyond(rng, control ? halved : box, axis, side, limit, p))
                continue;
            memcpy(q, p, sizeof q); /* outward, perpendicular to the face */
            q[axis] += side * ldexp(1 + test_rand_unit(rng), (int)(test_rand_u64(rng) % 30) - 10);
            q[axis] = fmax(-limit, fmin(limit, q[axis]));
            double p0[3] = {p[0], p[1], p[2]}, q0[3] = {q[0], q[1], q[2]};
            int root = root_between(e, p, q, at, y);
            control_roots += control && root;
            segments += !control;
            CHECK(control || !root, "'%s' over t in [%.17g, %.17g], proof %d, box %g,%g,%g,%g,%g,%g: a root near "
                  "(%.17g, %.17g, %.17g) at t = %.17g, between (%g, %g, %g) and (%g, %g, %g)", text, t[0], t[1],
                  (int)proof, box[0], box[1], box[2], box[3], box[4], box[5], p[0], p[1], p[2], at, p0[0], p0[1],
                  p0[2], q0[0], q0[1], q0[2]);
        }
        iacsg_expr_destroy(e);
    }
    mpfr_clear(y);
    mpfr_set_emax(emax);
    test_note("%ld of %ld expressions bounded; %ld known surface points in their boxes, %ld segments beyond their "
              "faces root-free; control: %ld roots beyond the halved boxes", proven, n, known, segments,
              control_roots);
    CHECK(proven >= n / 10 && known >= n / 20 && control_roots >= 5, "too few to mean anything");
}

/* Runs the command in `dir` with stdout into `out` (size bytes); returns its exit status. */
static int run_capture(const char *dir, const char *args, char *out, size_t size) {
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "cd '%s' && '%s' %s 2>&1", dir, test_binary_path(), args);
    FILE *f = popen(cmd, "r");
    size_t n = f ? fread(out, 1, size - 1, f) : 0;
    out[n] = '\0';
    return f ? pclose(f) : -1;
}

/* The two commands: the sphere at x = 6 (t = 2) is rendered, and the union with a sphere at x = 2000 is
 * not bounded by +-1.19 "(proven ...)". */
TEST(bounds_cli_renders_the_time_and_space_asked) {
    char dir[256], out[4096], path[512];
    snprintf(dir, sizeof dir, "/tmp/iacsg-bounds-%ld", (long)getpid());
    CHECK(mkdir(dir, 0700) == 0, "cannot create %s", dir);
    int rc = run_capture(dir, "'(x-3*t)^2+y^2+z^2-1' -time 2 -size 32x32 -o a.png -depth a.exr", out, sizeof out);
    CHECK(rc == 0, "exit %d: %s", rc, out);
    double b[6];
    CHECK(sscanf(out, "bounds %lg,%lg,%lg,%lg,%lg,%lg", &b[0], &b[1], &b[2], &b[3], &b[4], &b[5]) == 6, "%s", out);
    CHECK(b[0] <= 5 && b[3] >= 7 && strstr(out, "(proven to enclose the surface at t = 2)"), "%s", out);
    snprintf(path, sizeof path, "%s/a.exr", dir);
    int w, h, ch, hits = 0;
    float *depth = NULL;
    iacsg_error err = {0};
    CHECK(iacsg_image_read(path, &w, &h, &ch, &depth, &err) == IACSG_OK, "%s", err.message);
    for (int k = 0; k < w * h; k++)
        hits += isfinite(depth[k]);
    free(depth);
    CHECK(hits > w * h / 20, "the sphere at t = 2 covers %d pixels of %d", hits, w * h);

    rc = run_capture(dir, "'min(sphere, (x-2000)^2+y^2+z^2-1)' -size 8x8 -o b.png", out, sizeof out);
    CHECK(rc == 0, "exit %d: %s", rc, out);
    CHECK(sscanf(out, "bounds %lg,%lg,%lg,%lg,%lg,%lg", &b[0], &b[1], &b[2], &b[3], &b[4], &b[5]) == 6, "%s", out);
    CHECK(b[3] >= 2001 || !strstr(out, "proven to enclose"), "%s", out);
    test_note("%.*s", (int)strcspn(out, "\n"), out);

    rc = run_capture(dir, "'move(sphere, 4*t, 0, 0)' -frames 3 -size 8x8 -o c.png", out, sizeof out);
    CHECK(rc == 0, "exit %d: %s", rc, out);
    CHECK(sscanf(out, "bounds %lg,%lg,%lg,%lg,%lg,%lg", &b[0], &b[1], &b[2], &b[3], &b[4], &b[5]) == 6, "%s", out);
    CHECK(b[3] >= 4 * 2.0 / 3 + 1 && strstr(out, "for t = 0/3 .. 2/3"), "%s", out);
    snprintf(path, sizeof path, "rm -rf '%s'", dir);
    CHECK(system(path) == 0, "cannot clean %s", dir);
}
