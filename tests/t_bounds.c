/* tests/t_bounds.c -- iacsg_expr_bounds proves what it says: for the time interval asked (not [0, 1]), and in
 * all of space when it says EVERYWHERE (not only in [-1024, 1024]^3); and the render command renders what lies
 * there and prints what was proven. */
#include "iacsg.h"
#include "image.h"
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
 * cube only, and that box still holds the surface inside the cube. */
TEST(bounds_say_when_only_the_cube_is_proven) {
    static const struct {
        const char *text;
        double x1; /* the surface's largest x inside the cube */
    } cases[] = {
        {"x^4 - 5*x^2 + y^4 - 5*y^2 + z^4 - 5*z^2 + 11.8", 2.1},
        {"min(x^4 - 5*x^2 + y^2 + z^2, (x-2000)^2 + y^2 + z^2 - 1)", 2.3},
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
