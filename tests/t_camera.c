/* tests/t_camera.c -- the camera convention (README): basis, pixel directions, orthographic origins, and the
 * BRL-CAD azimuth/elevation placement. The rays are made by the kernel's code, compiled here as host C. */
#include "camera.h"
#include "kernels/camera.h"
#include "test.h"
#include <math.h>

static void params_of(const iacsg_camera *c, int w, int h, ia_real p[PARAM_COUNT]) {
    double pd[PARAM_COUNT] = {0};
    iacsg_error err = {0};
    CHECK(iacsg_camera_params(c, w, h, pd, &err) == IACSG_OK, "%s", err.message);
    for (int k = 0; k < PARAM_COUNT; k++)
        p[k] = (ia_real)pd[k];
}

static void expect_vec(const ia_real v[3], double x, double y, double z, double tol, const char *what) {
    CHECK(fabs(v[0] - x) <= tol && fabs(v[1] - y) <= tol && fabs(v[2] - z) <= tol,
          "%s: (%.7g, %.7g, %.7g), expected (%.7g, %.7g, %.7g)", what, (double)v[0], (double)v[1], (double)v[2], x, y,
          z);
}

/* Eye on -y looking at the origin, z up: f = +y, r = f x up = +x, u = r x f = +z. */
TEST(camera_convention_perspective) {
    iacsg_camera c = {.eye = {0, -5, 0}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 90};
    ia_real p[PARAM_COUNT], o[3], d[3];
    params_of(&c, 3, 3, p);
    camera_ray(p, 0, 1, 1, 3, 3, o, d); /* the middle pixel looks straight ahead */
    expect_vec(o, 0, -5, 0, 0, "eye");
    expect_vec(d, 0, 1, 0, 1e-7, "centre direction");
    /* Pixel (0, 0) is top left: s = (1/3 - 1) tan 45 = -2/3, v = +2/3. */
    camera_ray(p, 0, 0, 0, 3, 3, o, d);
    double n = sqrt(1 + 2 * (4.0 / 9));
    expect_vec(d, -2.0 / 3 / n, 1 / n, 2.0 / 3 / n, 1e-6, "top-left direction");
    /* A wide image keeps the vertical field of view: s is scaled by W/H. */
    params_of(&c, 4, 2, p);
    camera_ray(p, 0, 3, 1, 4, 2, o, d); /* s = (7/4 - 1) * 2 = 1.5, v = (1 - 3/2) = -0.5 */
    n = sqrt(1 + 1.5 * 1.5 + 0.25);
    expect_vec(d, 1.5 / n, 1 / n, -0.5 / n, 1e-6, "wide image, bottom-right direction");
}

TEST(camera_convention_ortho) {
    iacsg_camera c = {.eye = {1, 2, 10}, .at = {1, 2, 0}, .up = {0, 1, 0}, .ortho_height = 4};
    ia_real p[PARAM_COUNT], o[3], d[3];
    params_of(&c, 2, 2, p);
    /* f = -z, r = f x up = (0,0,-1) x (0,1,0) = (1,0,0), u = r x f = (0,1,0). Pixel (0,0): s = -1, v = +1. */
    camera_ray(p, RENDER_ORTHO, 0, 0, 2, 2, o, d);
    expect_vec(o, 0, 3, 10, 1e-6, "top-left origin");
    expect_vec(d, 0, 0, -1, 0, "direction");
    camera_ray(p, RENDER_ORTHO, 1, 1, 2, 2, o, d);
    expect_vec(o, 2, 1, 10, 1e-6, "bottom-right origin");
}

TEST(camera_azel_brlcad) {
    iacsg_camera c = {.fov = 40};
    const double at[3] = {1, 0, 0};
    iacsg_camera_set_azel(&c, at, 90, 0, 3); /* from +y, level */
    CHECK(fabs(c.eye[0] - 1) < 1e-12 && fabs(c.eye[1] - 3) < 1e-12 && fabs(c.eye[2]) < 1e-12,
          "az 90 el 0: eye (%g, %g, %g)", c.eye[0], c.eye[1], c.eye[2]);
    iacsg_camera_set_azel(&c, at, 35, 25, 2);
    CHECK(fabs(c.eye[2] - 2 * sin(25 * 3.14159265358979323846 / 180)) < 1e-12 && c.eye[0] > 1 && c.eye[1] > 0,
          "az 35 el 25: eye (%g, %g, %g)", c.eye[0], c.eye[1], c.eye[2]);
    iacsg_camera_set_azel(&c, at, 0, 90, 2); /* straight down: up must not be parallel to the view */
    double p[PARAM_COUNT];
    iacsg_error err = {0};
    CHECK(iacsg_camera_params(&c, 8, 8, p, &err) == IACSG_OK, "el 90: %s", err.message);
}

TEST(camera_rejects_degenerate_views) {
    double p[PARAM_COUNT];
    iacsg_error err = {0};
    iacsg_camera same = {.eye = {1, 1, 1}, .at = {1, 1, 1}, .up = {0, 0, 1}, .fov = 40};
    CHECK(iacsg_camera_params(&same, 8, 8, p, &err) == IACSG_ERR_ARG, "eye == at accepted");
    iacsg_camera parallel = {.eye = {0, 0, 5}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 40};
    CHECK(iacsg_camera_params(&parallel, 8, 8, p, &err) == IACSG_ERR_ARG, "up parallel to the view accepted");
    iacsg_camera wide = {.eye = {0, -5, 0}, .at = {0, 0, 0}, .up = {0, 0, 1}, .fov = 180};
    CHECK(iacsg_camera_params(&wide, 8, 8, p, &err) == IACSG_ERR_ARG, "fov 180 accepted");
}
