/* implicits/prim_place.h -- a BRL-CAD primitive (implicits/scene.h: scene_prim) placed in the world: the parameters
 * of its inclusion functions (kernels/prim.h) as double intervals holding the exact values that the database's
 * numbers and its matrix define, and a proven world box.
 *
 *   scene_prim (database layout, mat) --prim_place--> prim_placed --> scene_prims.c's table, scene_tables.c's box
 *   (brlcad_tree.c keeps each primitive's placement once made, prim_keep: the later calls copy it)
 */
#ifndef IMPLICITS_PRIM_PLACE_H
#define IMPLICITS_PRIM_PLACE_H
#include "scene.h"

typedef struct prim_placed {
    int type;      /* PRIM_* of kernels/prim.h */
    int n;         /* the number of intervals */
    double *lo, *hi;
    double box[6]; /* x0 y0 z0 x1 y1 z1, rounded outward; infinite for a half-space */
} prim_placed;

/* Places solid `name` (for messages; may be NULL). A primitive that does not describe a solid (a zero axis,
 * dependent axes, too few faces, a matrix with perspective) is IACSG_ERR_ARG, naming the solid and the reason.
 * A kept placement (prim_keep) is copied. */
iacsg_status prim_place(const scene_prim *p, const char *name, prim_placed *out, iacsg_error *err);
void prim_placed_free(prim_placed *out);

/* Places p once and keeps the placement in p->placed, for prim_place and prim_world_box: a command asks for a
 * primitive's box twice (rt's model box, the BVH) and for its parameters once. Keeps nothing when p is not valid
 * (prim_place then says why) or memory runs out. */
void prim_keep(scene_prim *p);
/* Frees what prim_keep kept. */
void prim_unkeep(scene_prim *p);

/* A bound as a float, rounded outward (down for a lower bound), and a subnormal one moved out to 0 or the
 * smallest normal number (ia/flush.h): the parameters of a float program. */
float prim_float_bound(double x, int upper);

/* The primitive's world box (infinite where it is unbounded, as a half-space); 1 if bounded, 0 if not or if the
 * primitive is not valid (prim_place says why when the program is made). */
int prim_world_box(const scene_prim *p, double box[6]);

#endif
