/* tests/expr_exercise.c -- see expr_exercise.h. */
#include "expr_exercise.h"
#include "implicits/scene.h"
#include <stdlib.h>
#include <string.h>

/* Bounds cost up to a tenth of a second per expression: only the first solids' are searched. */
#define EXERCISE_BOUNDS_MAX 4

static int has_message(const iacsg_error *err) { return err->status != IACSG_OK && err->message[0] != '\0'; }

/* Emits, bounds (when asked) and evaluates e; 0, or -1 for an error without a message. */
static int exercise_expr(const iacsg_expr *e, int bounds) {
    iacsg_error err = {0};
    int result = 0;
    char *source = NULL;
    if (iacsg_expr_emit_cl(e, "iacsg", &source, &err) != IACSG_OK && !has_message(&err))
        result = -1;
    free(source);
    double box[6], out[2];
    if (bounds)
        iacsg_expr_bounds(e, (double[2]){0, 1}, box);
    const double lo[3] = {-1.5, -0.25, -1}, hi[3] = {1, 0.5, 2};
    for (int fp64 = 0; fp64 <= 1; fp64++)
        if (iacsg_expr_eval_box(e, fp64, lo, hi, 0.5, out, &err) != IACSG_OK && !has_message(&err))
            result = -1;
    return result;
}

/* 1 if the tree at root is well formed: inside the node array, binary operands after their node and inside the
 * tree, leaves naming solids, and (regions) only the operators of regions. */
static int tree_is_sound(const iacsg_scene *s, int root, int region) {
    if (root < 0 || root >= s->nnodes)
        return 0;
    int end = root + scene_tree_size(s, root);
    if (end > s->nnodes)
        return 0;
    for (int k = root; k < end; k++) {
        int op = CSG_NODE_OP(s->nodes[k]), arg = (int)CSG_NODE_ARG(s->nodes[k]);
        if (op > CSG_NOT || (region && (op == CSG_OUTSIDE || op == CSG_NOT)))
            return 0;
        if ((op == CSG_INSIDE || op == CSG_OUTSIDE) && arg >= s->nsolids)
            return 0;
        if (op >= CSG_UNION && op <= CSG_DIFFERENCE && (arg <= k + 1 || arg >= end))
            return 0;
    }
    return 1;
}

/* 1 if the scene keeps its invariants; its trees are evaluated on three sign patterns. */
static int scene_is_sound(const iacsg_scene *s) {
    if ((s->expr != NULL) == (s->nitems > 0))
        return 0;
    for (int k = 0; k < s->nsolids; k++)
        if (!s->solids[k].expr)
            return 0;
    signed char *sign = malloc((size_t)s->nsolids + 1);
    if (!sign)
        return 1;
    int sound = 1;
    for (int k = 0; k < s->nitems && sound; k++) {
        const scene_item *it = &s->items[k];
        int region = it->kind == SCENE_REGION;
        sound = it->material >= -1 && it->material < s->nmaterials &&
                (region ? it->solid == -1 : it->solid >= 0 && it->solid < s->nsolids) &&
                ((!region && it->tree == -1) || tree_is_sound(s, it->tree, region));
        for (int pattern = -1; pattern <= 1 && sound && it->tree >= 0; pattern++) {
            for (int j = 0; j < s->nsolids; j++)
                sign[j] = (signed char)(pattern == 0 ? (j % 3) - 1 : pattern);
            int v = scene_tree_eval(s, it->tree, sign);
            sound = v == 0 || v == 1;
        }
    }
    free(sign);
    return sound;
}

int expr_exercise(const char *data, size_t size) {
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    iacsg_scene *s = NULL;
    iacsg_error err = {0};
    int result = 1;
    if (iacsg_scene_parse(text, "<fuzz>", &s, &err) != IACSG_OK) {
        result = has_message(&err) ? 0 : -1;
    } else {
        if (s->expr && exercise_expr(s->expr, 1) < 0)
            result = -1;
        for (int k = 0; k < s->nsolids; k++)
            if (exercise_expr(s->solids[k].expr, k < EXERCISE_BOUNDS_MAX) < 0)
                result = -1;
        if (!scene_is_sound(s))
            result = -1;
        if (s->nitems > 0) { /* one expression cannot hold them: refused, with a message */
            iacsg_expr *e = NULL;
            iacsg_error refusal = {0};
            if (iacsg_expr_parse(text, "<fuzz>", &e, &refusal) == IACSG_OK || !has_message(&refusal))
                result = -1;
            iacsg_expr_destroy(e);
        }
        iacsg_scene_destroy(s);
    }
    free(text);
    return result;
}
