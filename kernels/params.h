/* kernels/params.h -- the parameter block of a render, shared by the host and the device.
 *
 * The host fills an array of PARAM_COUNT reals of the working precision (float, or double with IA_FP64) and
 * the device reads it from __constant memory. An array indexed by this enum, rather than a struct, keeps the
 * layout identical on both sides whatever the precision: no padding, no float3, no size_t.
 */
#ifndef KERNELS_PARAMS_H
#define KERNELS_PARAMS_H
#include "compat.h"

enum {
    PARAM_EYE = 0,       /* 3: the eye (perspective) or the centre of the image plane (orthographic) */
    PARAM_FORWARD = 3,   /* 3: f = normalize(at - eye) */
    PARAM_RIGHT = 6,     /* 3: r = normalize(f x up) */
    PARAM_UP = 9,        /* 3: u = r x f */
    PARAM_SCALE_S = 12,  /* tan(fov/2) * W/H, or HEIGHT/2 * W/H when orthographic */
    PARAM_SCALE_V = 13,  /* tan(fov/2), or HEIGHT/2 */
    PARAM_BOX = 14,      /* 6: x0, y0, z0, x1, y1, z1, the bounds every ray is clipped to */
    PARAM_EPS = 20,      /* the width of a leaf of the bisection, in units of t (the distance along the ray) */
    PARAM_TIME_LO = 21,  /* [TIME_LO, TIME_HI] encloses the value of the variable t of the expression */
    PARAM_TIME_HI = 22,
    PARAM_TMIN = 23,     /* every ray's part inside the box lies in t in [TMIN, TMAX] (src/render.c) */
    PARAM_TMAX = 24,
    PARAM_COUNT = 25
};

/* Flags, an int argument of the render kernels. */
#define RENDER_ORTHO 1
/* The colours as 3 bytes a pixel (light.h's display colours clamped to [0, 1], x 255, + 0.5, truncated: as
 * src/image_bytes.c converts floats), not 3 floats: the frame then goes to an 8-bit image as it is. */
#define RENDER_BYTES 2

/* The pixels of a tile (kernels/tile.h) are those of one work-group of the render kernel. */
#define TILE_SIZE 8
/* The runs of a tile that its transparent layers search (kernels/tile.h: tile_runs), and the layers of a path
 * that use them (the further ones search their whole rays: their start drifts further off the camera ray). */
#define TILE_RUNS 6
#define TILE_RUN_LAYERS 4

/* A work-item of the render kernel traces PACKET_W x PACKET_H pixels of one tile in as many SIMD lanes
 * (kernels/packet.h); the host builds the program with -D IA_VW=PACKET_LANES. The first-root path's packets are
 * 2 pixels wide on a device whose vectors hold 8 lanes or fewer (src/render.c: render_packet_w, which passes
 * -D PACKET_W): a 16-lane vector is two AVX2 registers, and a packet waits for its slowest ray. The host reads
 * the width its renderer chose (render_packet_lanes, render_block_w); its own PACKET_LANES (16) only pads. */
#ifndef PACKET_W
#define PACKET_W 4
#endif
#define PACKET_H 4
#define PACKET_LANES (PACKET_W * PACKET_H)

/* For a union emitted in groups, the tile pass keeps a mask of the groups that can matter per tile and per
 * segment of the frame's tree: the SEGMENTS nodes at level SEGMENT_LEVEL (kernels/packet.h). */
#define SEGMENT_LEVEL 4
#define SEGMENTS (1 << SEGMENT_LEVEL)

#endif
