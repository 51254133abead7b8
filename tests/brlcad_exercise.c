/* tests/brlcad_exercise.c -- see brlcad_exercise.h. */
#include "brlcad_exercise.h"
#include "implicits/brlcad.h"
#include "implicits/scene.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The parameter count of each primitive type (pipe: 6 a point, at least 2 points). */
static int params_ok(const scene_prim *p) {
    static const int count[SCENE_PRIM_TYPES] = {[SCENE_PRIM_HALF] = 4, [SCENE_PRIM_ARB8] = 24, [SCENE_PRIM_ELL] = 12,
                                                [SCENE_PRIM_TGC] = 18, [SCENE_PRIM_TOR] = 8,  [SCENE_PRIM_EHY] = 12};
    if ((int)p->type < 0 || p->type >= SCENE_PRIM_TYPES)
        return 0;
    return p->type == SCENE_PRIM_PIPE ? p->nparams >= 12 && p->nparams % 6 == 0 : p->nparams == count[p->type];
}

static int scene_ok(const brlcad_model *m) {
    const iacsg_scene *s = m->scene;
    if (s->nsolids != m->ninstances || s->nitems < 1)
        return 0;
    for (int k = 0; k < s->nsolids; k++)
        if (!s->solids[k].prim || s->solids[k].expr || !params_ok(s->solids[k].prim) || !s->solids[k].name)
            return 0;
    for (int r = 0; r < s->nitems; r++) {
        const scene_item *it = &s->items[r];
        if (it->kind != SCENE_REGION || !it->name || it->name[0] != '/' || it->material < -1 ||
            it->material >= s->nmaterials || it->tree < 0 || it->tree >= s->nnodes)
            return 0;
        int last = it->tree + scene_tree_size(s, it->tree);
        if (last > s->nnodes)
            return 0;
        for (int k = it->tree; k < last; k++) {
            int op = CSG_NODE_OP(s->nodes[k]), arg = (int)CSG_NODE_ARG(s->nodes[k]);
            if (op == CSG_INSIDE ? arg >= s->nsolids
                                 : (op != CSG_UNION && op != CSG_INTERSECT && op != CSG_DIFFERENCE) || arg <= k ||
                                       arg >= last)
                return 0;
        }
    }
    return 1;
}

/* rt's model box, when there is one, is a box (rounded to whole mm). */
static int bounds_ok(const brlcad_model *m) {
    double b[6];
    if (!brlcad_scene_bounds(m->scene, b))
        return 1;
    for (int k = 0; k < 3; k++)
        if (!(b[k] <= b[k + 3]) || b[k] != floor(b[k]) || b[k + 3] != ceil(b[k + 3]))
            return 0;
    return 1;
}

int brlcad_exercise(const char *data, size_t size) {
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    brlcad_db *db = NULL;
    iacsg_error err = {0};
    int result = -1;
    if (brlcad_db_read(text, size, &db, &err) != IACSG_OK) {
        result = db == NULL && err.message[0] ? 0 : -1;
    } else {
        int tops_ok = 1;
        for (int k = 0; k < brlcad_db_top_count(db); k++)
            tops_ok &= brlcad_db_top_name(db, k)[0] != '\0';
        brlcad_model m;
        iacsg_status st = brlcad_model_build(db, NULL, 0, &m, &err);
        if (st != IACSG_OK)
            result = tops_ok && m.scene == NULL && err.message[0] ? 0 : -1;
        else
            result = tops_ok && scene_ok(&m) && bounds_ok(&m) ? 1 : -1;
        if (st == IACSG_OK)
            brlcad_model_free(&m);
        brlcad_db_destroy(db);
    }
    free(text);
    return result;
}
