/* src/camera.c -- see camera.h. */
#include "camera.h"
#include "kernels/params.h"
#include "vec3.h"
#include <math.h>

static const double pi = 3.14159265358979323846;

/* Scales v to unit length; returns 0 (leaving v) when it is too short to have a direction. */
static int normalize3(double v[3]) {
    double len = sqrt(vec3_dot(v, v));
    if (!(len > 1e-300) || !isfinite(len))
        return 0;
    for (int k = 0; k < 3; k++)
        v[k] /= len;
    return 1;
}

void iacsg_camera_set_azel(iacsg_camera *c, const double at[3], double az, double el, double distance) {
    double a = az * pi / 180, e = el * pi / 180;
    double dir[3] = {cos(e) * cos(a), cos(e) * sin(a), sin(e)};
    for (int k = 0; k < 3; k++) {
        c->at[k] = at[k];
        c->eye[k] = at[k] + distance * dir[k];
        c->up[k] = k == 2;
    }
    if (fabs(dir[2]) > 0.999999) { /* straight down or up: +z is the view axis, use +y as the screen's up */
        c->up[1] = 1;
        c->up[2] = 0;
    }
}

void iacsg_camera_fit_azel(iacsg_camera *c, const double bounds[6], double az, double el) {
    double radius = 0, at[3] = {c->at[0], c->at[1], c->at[2]};
    for (int k = 0; k < 3; k++) { /* the farthest corner from `at` */
        double far = fmax(fabs(bounds[k] - at[k]), fabs(bounds[k + 3] - at[k]));
        radius += far * far;
    }
    radius = sqrt(radius);
    double distance = c->ortho_height > 0 ? 2 * radius : 1.05 * radius / sin(c->fov * pi / 360);
    iacsg_camera_set_azel(c, at, az, el, distance);
}

iacsg_status iacsg_camera_params(const iacsg_camera *c, int width, int height, double *params, iacsg_error *err) {
    double f[3], r[3], u[3], up[3] = {c->up[0], c->up[1], c->up[2]};
    for (int k = 0; k < 3; k++)
        f[k] = c->at[k] - c->eye[k];
    if (!normalize3(f))
        return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "the eye and the target point coincide");
    if (!normalize3(up))
        return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "the up vector is zero");
    vec3_cross(f, up, r);
    if (sqrt(vec3_dot(r, r)) < 1e-9 || !normalize3(r))
        return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "the up vector is parallel to the view direction");
    vec3_cross(r, f, u);
    double half;
    if (c->ortho_height > 0)
        half = c->ortho_height / 2;
    else if (c->fov > 0 && c->fov < 180)
        half = tan(c->fov * pi / 360);
    else
        return iacsg_error_set(err, IACSG_ERR_ARG, 0, 0, "field of view %g is not in (0, 180) degrees", c->fov);
    for (int k = 0; k < 3; k++) {
        params[PARAM_EYE + k] = c->eye[k];
        params[PARAM_FORWARD + k] = f[k];
        params[PARAM_RIGHT + k] = r[k];
        params[PARAM_UP + k] = u[k];
    }
    params[PARAM_SCALE_S] = half * width / height;
    params[PARAM_SCALE_V] = half;
    return IACSG_OK;
}
