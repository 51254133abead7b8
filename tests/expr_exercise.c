/* tests/expr_exercise.c -- see expr_exercise.h. */
#include "expr_exercise.h"
#include "implicits/expr.h"
#include <stdlib.h>
#include <string.h>

static int has_message(const iacsg_error *err) { return err->status != IACSG_OK && err->message[0] != '\0'; }

int expr_exercise(const char *data, size_t size) {
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    iacsg_expr *e = NULL;
    iacsg_error err = {0};
    int result = 1;
    if (iacsg_expr_parse(text, "<fuzz>", &e, &err) != IACSG_OK) {
        result = has_message(&err) ? 0 : -1;
    } else {
        char *source = NULL;
        if (iacsg_expr_emit_cl(e, "iacsg", &source, &err) != IACSG_OK && !has_message(&err))
            result = -1;
        free(source);
        double box[6], out[2];
        iacsg_expr_bounds(e, (double[2]){0, 1}, box);
        const double lo[3] = {-1.5, -0.25, -1}, hi[3] = {1, 0.5, 2};
        for (int fp64 = 0; fp64 <= 1; fp64++)
            if (iacsg_expr_eval_box(e, fp64, lo, hi, 0.5, out, &err) != IACSG_OK && !has_message(&err))
                result = -1;
        iacsg_expr_destroy(e);
    }
    free(text);
    return result;
}
