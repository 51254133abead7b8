/* implicits/brlcad.h -- BRL-CAD databases in ASCII form (.asc, v4 and v5) as scenes (scene.h): the front end
 * beside the scene language. What is read and what is refused: README, "BRL-CAD models".
 *
 *   text --brlcad_db_read--> database (primitives, combinations, colour table)
 *        --brlcad_model_build (top objects)--> regions as librt makes them, each a tree over instanced solids
 *
 * Errors name the object and the line (err->line, column 1); nothing is skipped without a word.
 */
#ifndef IACSG_BRLCAD_H
#define IACSG_BRLCAD_H
#include "error.h"
#include <stddef.h>

typedef struct brlcad_db brlcad_db;
typedef struct iacsg_scene iacsg_scene;

/* Reads a database: v4 when its first line is an `I` record, else v5 (Tcl `put` lines). text[len] must be
 * NUL; a NUL before it is refused. On failure *out is NULL. */
iacsg_status brlcad_db_read(const char *text, size_t len, brlcad_db **out, iacsg_error *err);
void brlcad_db_destroy(brlcad_db *db);

/* The objects that no combination references (what rt is given by default), in order of definition. */
int brlcad_db_top_count(const brlcad_db *db);
const char *brlcad_db_top_name(const brlcad_db *db, int k);

/* librt's distance tolerance (rt_tol.dist, mm): a model's scene fuses a ray's changes of state closer than this
 * (iacsg_scene's dist_tol, kernels/weave.h), and two placements within it are one instance. */
#define BRLCAD_DIST_TOL 0.0005

/* The regions librt makes of the given top objects (all tops when nobjects is 0): one scene region per librt
 * region, in librt's order, named by its path ("/all/a.r"); solids are the distinct (primitive, matrix)
 * instances. Air regions are left out, as rt does. The scene's dist_tol is BRLCAD_DIST_TOL. */
typedef struct {
    iacsg_scene *scene;
    int *region_ids;  /* per scene item: the BRL-CAD region id */
    int ninstances;   /* = scene->nsolids */
    int nair;         /* air regions left out (each path to one counts) */
} brlcad_model;

iacsg_status brlcad_model_build(const brlcad_db *db, const char *const *objects, int nobjects, brlcad_model *out,
                                iacsg_error *err);
void brlcad_model_free(brlcad_model *m);

/* rt's model box of a scene: the union of its regions' boxes, each from its solids' proven boxes as rt_bound_tree
 * bounds a tree (a union's hull, an intersection's overlap, a difference's left side), unbounded regions (a
 * half-space) left out, rounded out to whole mm (rt_prep); 0 if no region is bounded (or memory ran out). Every
 * bounded region lies inside it. */
int brlcad_scene_bounds(const iacsg_scene *s, double box[6]);

#endif
