/* src/cli_view_camera.c -- see cli_view_camera.h. */
#include "cli_view_camera.h"
#include "vec3.h"
#include <math.h>

#define DEGREES_PER_PIXEL 0.4
#define POLE_MARGIN_DEGREES 1.0
#define ZOOM_STEP 0.85

static const double pi = 3.14159265358979323846;

/* Scales v to length 1; returns its former length. */
static double normalize(double v[3]) {
    double n = sqrt(vec3_dot(v, v));
    if (n > 0)
        for (int k = 0; k < 3; k++)
            v[k] /= n;
    return n;
}

/* A unit vector perpendicular to the unit vector u. */
static void any_perpendicular(const double u[3], double out[3]) {
    const double x[3] = {1, 0, 0}, y[3] = {0, 1, 0};
    vec3_cross(u, fabs(u[0]) < 0.9 ? x : y, out);
    normalize(out);
}

void view_camera_orbit(iacsg_camera *c, double dx, double dy) {
    double up[3] = {c->up[0], c->up[1], c->up[2]}, d[3], h[3], side[3];
    normalize(up);
    for (int k = 0; k < 3; k++)
        d[k] = c->eye[k] - c->at[k];
    double dist = normalize(d);
    /* d = cos(polar) up + sin(polar) h, with h the unit horizontal direction of the eye */
    double polar = acos(fmax(-1.0, fmin(1.0, vec3_dot(d, up))));
    for (int k = 0; k < 3; k++)
        h[k] = d[k] - vec3_dot(d, up) * up[k];
    if (normalize(h) < 1e-12)
        any_perpendicular(up, h);
    vec3_cross(up, h, side);
    double turn = -dx * DEGREES_PER_PIXEL * pi / 180;
    double margin = POLE_MARGIN_DEGREES * pi / 180;
    polar = fmax(margin, fmin(pi - margin, polar - dy * DEGREES_PER_PIXEL * pi / 180));
    for (int k = 0; k < 3; k++) {
        double turned = cos(turn) * h[k] + sin(turn) * side[k];
        c->eye[k] = c->at[k] + dist * (cos(polar) * up[k] + sin(polar) * turned);
    }
}

void view_camera_zoom(iacsg_camera *c, double steps) {
    double factor = pow(ZOOM_STEP, steps);
    if (c->ortho_height > 0) {
        c->ortho_height *= factor;
        return;
    }
    for (int k = 0; k < 3; k++)
        c->eye[k] = c->at[k] + factor * (c->eye[k] - c->at[k]);
}

void view_camera_pan(iacsg_camera *c, double dx, double dy, int height) {
    double f[3], right[3], screen_up[3];
    for (int k = 0; k < 3; k++)
        f[k] = c->at[k] - c->eye[k];
    double dist = normalize(f);
    vec3_cross(f, c->up, right);
    if (normalize(right) < 1e-12)
        any_perpendicular(f, right);
    vec3_cross(right, f, screen_up);
    double view_height = c->ortho_height > 0 ? c->ortho_height : 2 * dist * tan(c->fov * pi / 360);
    double per_pixel = view_height / (height > 0 ? height : 1);
    for (int k = 0; k < 3; k++) {
        double move = (-dx * right[k] + dy * screen_up[k]) * per_pixel;
        c->eye[k] += move;
        c->at[k] += move;
    }
}
