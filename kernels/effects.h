/* kernels/effects.h -- what the host's effects (src/render_effects.c) and the kernels of both paths
 * (kernels/effects.cl, kernels/scene_effects.cl, light.h) share: the layout of a secondary ray in the ray buffer,
 * of a path (a ray with its weight) and of the effects' parameter block. All in the working precision. */
#ifndef KERNELS_EFFECTS_H
#define KERNELS_EFFECTS_H

/* A ray: origin x y z, direction x y z, the part [tn, tf] of it to search. */
#define EFFECTS_RAY_REALS 8
/* The item of a segment-path ray asked only whether it meets an item (all of them opaque: a shadow ray), that
 * certainly does (kernels/scene_effects.cl); -1 is a miss. */
#define EFFECTS_HIT_BLOCKED (-2)
/* The child a segment-path centre hit gets on the device (kernels/scene_centre.cl), by its item's material: none,
 * its reflected ray, its ray on through a transparent surface, or on into a transparent region (passing it). */
enum { EFFECTS_KID_NONE = 0, EFFECTS_KID_REFLECTED = 1, EFFECTS_KID_THROUGH = 2, EFFECTS_KID_THROUGH_REGION = 3 };

/* A path of the first-root path's effects kernel (a reflected ray off a transparent surface, listed by the
 * kernel for the next launch): origin x y z, direction x y z, its weight in its pixel's colour, the transparent
 * layers it has passed and the reflections it has taken. */
enum { EFFECTS_PATH_O = 0, EFFECTS_PATH_D = 3, EFFECTS_PATH_WEIGHT = 6, EFFECTS_PATH_LAYERS = 7,
       EFFECTS_PATH_BOUNCES = 8, EFFECTS_PATH_REALS = 9 };

/* A light: its kind, three coordinates (a position, a direction towards the light, or for the default rig the
 * right and up coefficients of a direction fixed to the camera, light.h: shade_light_direction), the weight of its
 * diffuse term and of its highlight (times the material's specular). */
enum { EFFECTS_LIGHT_DIR = 0, EFFECTS_LIGHT_POINT = 1, EFFECTS_LIGHT_CAMERA = 2 };
enum { EFFECTS_LIGHT_KIND = 0, EFFECTS_LIGHT_XYZ = 1, EFFECTS_LIGHT_INTENSITY = 4, EFFECTS_LIGHT_HIGHLIGHT = 5,
       EFFECTS_LIGHT_REALS = 6 };
#define EFFECTS_MAX_LIGHTS 8

/* Shading modes (iacsg_shade's order). */
enum { EFFECTS_SHADE_LIT = 0, EFFECTS_SHADE_GRADIENT, EFFECTS_SHADE_NORMALS, EFFECTS_SHADE_DEPTH, EFFECTS_SHADE_IDS };

/* The effects' parameter block: shading mode, lights, shadows, bounces, the expression's material, background
 * (display-encoded, top and bottom), the centre hits' depth range (-shade depth), the palette colour of id 0
 * (-shade ids, linear), then the lights. */
enum {
    EFFECTS_SHADE = 0,
    EFFECTS_NLIGHTS = 1,
    EFFECTS_SHADOWS = 2,
    EFFECTS_BOUNCES = 3,
    EFFECTS_ALBEDO = 4,    /* 3, linear */
    EFFECTS_SPECULAR = 7,
    EFFECTS_SHININESS = 8,
    EFFECTS_REFLECT = 9,
    EFFECTS_OPACITY = 10,
    EFFECTS_BG_TOP = 11,   /* 3 */
    EFFECTS_BG_BOTTOM = 14, /* 3 */
    EFFECTS_DEPTH_LO = 17,
    EFFECTS_DEPTH_HI = 18,
    EFFECTS_ID_RGB = 19,   /* 3 */
    EFFECTS_LIGHTS = 22,
    EFFECTS_COUNT = EFFECTS_LIGHTS + EFFECTS_MAX_LIGHTS * EFFECTS_LIGHT_REALS
};

/* The lighting's constant term, the layers a path passes at most and the weight below which it stops (the rest
 * of it is the background). */
#define EFFECTS_AMBIENT 0.10
#define EFFECTS_MAX_LAYERS 16
#define EFFECTS_MIN_WEIGHT (1.0 / 1024)

/* The effects kernel's modes: the frame's centre rays (their hits the frame's depth and normals), -aa's rays
 * (n x n per listed pixel), or listed paths (reflected rays). */
enum { EFFECTS_MODE_CENTRE = 0, EFFECTS_MODE_AA = 1, EFFECTS_MODE_PATHS = 2 };

/* -aa's walks in rounds (kernels/effects.cl: iacsg_effects): a path left for the next round, its index, the level
 * and node its walk stopped at. */
#define EFFECTS_LEFT_REALS 3

/* Which of -aa's n x n rays of a pixel a launch of EFFECTS_MODE_AA traces: all, the grid's four corners, or the
 * rest (src/render_effects_device.c traces the rest only where the corners differ). */
enum { EFFECTS_AA_ALL = 0, EFFECTS_AA_CORNERS = 1, EFFECTS_AA_REST = 2 };

/* The rays of a pixel in `set` (corners and rest only for aa >= 3). */
static inline int effects_aa_rays(int aa, int set) {
    return set == EFFECTS_AA_CORNERS ? 4 : set == EFFECTS_AA_REST ? aa * aa - 4 : aa * aa;
}

/* The cell (a + aa b: the ray through (i + (a + 1/2) / aa, j + (b + 1/2) / aa) of pixel (i, j)) of ray s of a
 * pixel in `set`: the rest in row-major order, the corners skipped. */
static inline int effects_aa_cell(int aa, int set, int s) {
    if (set == EFFECTS_AA_CORNERS)
        return (s & 1 ? aa - 1 : 0) + (s & 2 ? aa * (aa - 1) : 0);
    if (set == EFFECTS_AA_ALL)
        return s;
    int g = s + 1; /* past cell 0, then past aa - 1 and aa (aa - 1) where reached; aa^2 - 1 never is */
    g += g >= aa - 1;
    g += g >= aa * (aa - 1);
    return g;
}

#endif
