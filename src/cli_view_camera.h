/* src/cli_view_camera.h -- the viewer's mouse on the camera: orbit about the look-at point, zoom towards it,
 * pan across the view. Amounts are in pixels of a window `height` pixels high; the up vector is kept. */
#ifndef IACSG_CLI_VIEW_CAMERA_H
#define IACSG_CLI_VIEW_CAMERA_H
#include "camera.h"

/* A drag of (dx, dy) pixels: dx turns the eye about the up axis through c->at, dy raises or lowers it
 * (short of the poles, where the view would be along the up vector). */
void view_camera_orbit(iacsg_camera *c, double dx, double dy);

/* Wheel steps: each step up brings the eye 15% closer to the look-at point (or makes the orthographic view
 * 15% smaller); down moves it away. */
void view_camera_zoom(iacsg_camera *c, double steps);

/* A drag of (dx, dy) pixels moves the eye and the look-at point so that the point under the cursor at the
 * look-at distance follows it. */
void view_camera_pan(iacsg_camera *c, double dx, double dy, int height);

#endif
