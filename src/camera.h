/* src/camera.h -- the view: eye, target, up and field of view (or orthographic height), and its translation
 * into the kernel's parameter block (kernels/params.h). The convention is stated in kernels/camera.h. */
#ifndef IACSG_CAMERA_H
#define IACSG_CAMERA_H
#include "error.h"

IACSG_API_BEGIN

typedef struct {
    double eye[3], at[3], up[3];
    double fov;          /* vertical field of view in degrees (perspective) */
    double ortho_height; /* > 0: an orthographic view this high, centred on the eye; fov is then unused */
} iacsg_camera;

/* Places the eye the BRL-CAD way: looking at `at` from azimuth az (degrees from +x towards +y) and elevation el
 * (degrees above the xy plane), at the given distance, with +z up (+y up when looking straight down or up). */
void iacsg_camera_set_azel(iacsg_camera *c, const double at[3], double az, double el, double distance);

/* Places the eye by azimuth and elevation (as iacsg_camera_set_azel) looking at c->at, far enough that the
 * sphere around the box `bounds` (x0,y0,z0,x1,y1,z1) fits in the perspective view, or is in front of the
 * orthographic image plane. */
void iacsg_camera_fit_azel(iacsg_camera *c, const double bounds[6], double az, double el);

/* Fills params[0 .. 13] (PARAM_EYE .. PARAM_SCALE_V of kernels/params.h) for a width x height image.
 * IACSG_ERR_ARG when eye == at, up is parallel to the view direction, or fov is not in (0, 180). */
iacsg_status iacsg_camera_params(const iacsg_camera *c, int width, int height, double *params, iacsg_error *err);

IACSG_API_END
#endif
