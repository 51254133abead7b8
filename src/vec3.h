/* src/vec3.h -- the dot and cross products of 3-vectors of doubles, for the host's camera code (src/camera.c,
 * the viewer's orbit in src/cli_view_camera.c). */
#ifndef IACSG_VEC3_H
#define IACSG_VEC3_H

static inline double vec3_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static inline void vec3_cross(const double a[3], const double b[3], double out[3]) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

#endif
