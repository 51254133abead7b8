/* implicits/scene.h -- a multi-material scene: materials, solids, regions (booleans over solids) and surfaces
 * (level sets kept where a condition over solids holds), the data both front ends build (the scene language,
 * implicits/scene_parse.c; later the BRL-CAD reader) and the segment path renders. Neither front end knows how
 * it is rendered.
 *
 *   front end --scene_add_*--> iacsg_scene (solids each a compiled iacsg_expr, trees as 32-bit nodes,
 *   kernels/csg_node.h) --> renderer (the segment path)
 *
 * A scene file without `region` or `surface` statements is a plain scene: it has no items, and its final
 * expression is rendered by the first-root path as before (iacsg_scene.expr).
 *
 * Ownership: the scene owns every name, expression and array in it; iacsg_scene_destroy frees them all.
 */
#ifndef IACSG_SCENE_H
#define IACSG_SCENE_H
#include "error.h"
#include "expr.h"
#include "scene_api.h"
#include "kernels/csg_node.h"
#include <stdint.h>

typedef struct {
    char *name;
    float rgb[3];              /* linear albedo in [0, 1] */
    float specular, shininess; /* optional keywords; defaults SCENE_DEFAULT_SPECULAR, _SHININESS */
    float reflect, opacity;    /* the reflected fraction (0) and opacity (1): src/render_effects.c */
} scene_material;

/* The first-root path's highlight (kernels/light.h), so that a solid looks the same on either path. */
#define SCENE_DEFAULT_SPECULAR 0.45f
#define SCENE_DEFAULT_SHININESS 48.0f

/* A BRL-CAD primitive (implicits/brlcad_*.c reads them). Its parameters are as the database stores them, in the
 * primitive's own frame, in mm, in the layout listed here; mat is the matrix accumulated down the combination
 * tree, 16 numbers row-major as the database writes them (x' = M x on homogeneous points: translation in mat[3],
 * mat[7], mat[11]; mat[15] divides, a uniform scale). The renderer places it in the world. */
typedef enum {
    SCENE_PRIM_HALF, /* N d (4): inside where N . x <= d (N not necessarily unit) */
    SCENE_PRIM_ARB8, /* 8 vertices, absolute (24); arb4..arb7 repeat vertices as BRL-CAD stores them */
    SCENE_PRIM_ELL,  /* V A B C (12): centre and three mutually perpendicular semi-axes */
    SCENE_PRIM_TGC,  /* V H A B C D (18): base centre, height vector, base semi-axes A B, top semi-axes C D
                        (C parallel to A, D to B); rcc, rec, trc and tec are its special cases */
    SCENE_PRIM_TOR,  /* V N r_a r_h (8): centre, axis normal (any length), major and minor radii */
    SCENE_PRIM_EHY,  /* V H A r_1 r_2 c (12): vertex, height vector, unit major axis direction, semi-axes, c */
    SCENE_PRIM_PIPE, /* n points, each x y z od id bend (6n): outer and inner diameters, bend radius */
    SCENE_PRIM_TYPES
} scene_prim_type;

typedef struct {
    scene_prim_type type;
    int nparams;
    double *params;
    double mat[16];
    struct prim_placed *placed; /* its placement once made (implicits/prim_place.h: prim_keep), or NULL */
} scene_prim;

typedef struct {
    char *name;        /* NULL for an expression written inline in a region or a condition */
    iacsg_expr *expr;  /* f < 0 inside; NULL for a primitive */
    scene_prim *prim;  /* a primitive, or NULL for an expression */
    int line, column;  /* where it is declared (or written inline), for messages */
    /* The renderer's proven box of an expression that does not depend on t, kept once found (src/scene_tables.c:
     * the command's bounds and the BVH both need it, and for 1000 spheres each proof took ~2 s). */
    int box_known, box_bounded, box_in_cube;
    double box[6];
} scene_solid;

typedef enum { SCENE_REGION, SCENE_SURFACE } scene_item_kind;

/* A region or a surface; its id is its index in iacsg_scene.items (the order of declaration). */
typedef struct {
    scene_item_kind kind;
    char *name;
    int material; /* index into materials, or -1: the palette colour of the item's id */
    int tree;     /* region: the root of its boolean tree in nodes; surface: the root of its condition, or -1 */
    int solid;    /* surface: the solid whose zero set it is; region: -1 */
    int line, column;
} scene_item;

#define SCENE_MAX_LIGHTS 8

/* A light (`light NAME = point(X, Y, Z) intensity I`, or dir(X, Y, Z): the direction towards the light). */
typedef struct {
    int dir;
    double xyz[3];
    double intensity; /* >= 0, default 1 */
} scene_light;

struct iacsg_scene {
    scene_material *materials;
    int nmaterials, cap_materials;
    scene_light *lights;
    int nlights, cap_lights;
    scene_solid *solids;
    int nsolids, cap_solids;
    scene_item *items;
    int nitems, cap_items;
    uint32_t *nodes; /* every tree and condition, kernels/csg_node.h */
    int nnodes, cap_nodes;
    iacsg_expr *expr; /* a plain scene's final expression (then nitems == 0), else NULL */
    double dist_tol;  /* world units: a ray's changes of state closer than this are fused (kernels/weave.h); 0: none */
};
typedef struct iacsg_scene iacsg_scene;

/* Parses a scene file's text or an expression (name is used in messages). A text with regions or surfaces has
 * items and no final expression, and its solids are those the items use (declared or inline, in order); any
 * other has expr set, as iacsg_expr_parse would make it, no solids (its `solid` statements are bindings) and its
 * materials listed. On failure *out is NULL and err holds the message, line and column. Destroy with
 * iacsg_scene_destroy. The language: docs/language.md, "Regions, surfaces and materials". */
iacsg_status iacsg_scene_parse(const char *text, const char *name, iacsg_scene **out, iacsg_error *err);
void iacsg_scene_destroy(iacsg_scene *s);

/* The builder, for front ends and tests. Each returns the new entry's index, or -1 when out of memory (err set).
 * Names are copied (NULL allowed for inline solids and for items); expressions are taken over by the scene (also
 * on failure). */
iacsg_scene *scene_create(void);
int scene_add_material(iacsg_scene *s, const char *name, const float rgb[3], iacsg_error *err);
int scene_add_solid(iacsg_scene *s, const char *name, iacsg_expr *e, iacsg_error *err);
int scene_add_light(iacsg_scene *s, const scene_light *light, iacsg_error *err);
/* A primitive (layout of params above, copied with mat); its name may be NULL. */
int scene_add_primitive(iacsg_scene *s, const char *name, scene_prim_type type, const double *params, int nparams,
                        const double mat[16], iacsg_error *err);
/* Appends a tree of n nodes whose operands of binary nodes are indices relative to its first node (as a front
 * end builds one on its own); returns the index of its root in s->nodes, operands rebased. */
int scene_add_tree(iacsg_scene *s, const uint32_t *nodes, int n, iacsg_error *err);
int scene_add_region(iacsg_scene *s, const char *name, int tree, int material, iacsg_error *err);
int scene_add_surface(iacsg_scene *s, const char *name, int solid, int condition, int material, iacsg_error *err);

/* The value (0 or 1) of the tree or condition at node `root` at a point where solid k's f has the sign of
 * sign[k] (< 0 inside, > 0 outside, 0 on its boundary, where neither an INSIDE nor an OUTSIDE leaf holds). The
 * host's reference for the device's classification; no recursion. */
int scene_tree_eval(const iacsg_scene *s, int root, const signed char *sign);

/* The number of nodes of the tree at `root` (its extent in s->nodes). */
int scene_tree_size(const iacsg_scene *s, int root);

#endif
