/* src/cli_eval.c -- `iacsg eval` (the enclosure of an expression over a box, on the host or the device) and
 * `iacsg compile` (the generated OpenCL C, or the dump of one compiler stage). */
#include "cli.h"
#include "clrt.h"
#include "ia/decimal.h"
#include "implicits/device_eval.h"
#include "implicits/expr_internal.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char eval_usage[] =
    "usage: iacsg eval EXPR|SCENE [--box X0,X1,Y0,Y1,Z0,Z1] [--at X,Y,Z] [--time T] [--device[=N]] [--fp64]\n"
    "Prints [lo, hi], an enclosure of the expression over the box (default -1,1,-1,1,-1,1), or at the point.\n"
    "Decimal numbers are taken as the reals they denote; the bounds printed parse back to the same doubles.\n";
static const char compile_usage[] =
    "usage: iacsg compile EXPR|SCENE [--dump tokens|ast|dag|simple] [--prefix NAME]\n"
    "Prints the OpenCL C generated for the expression (functions NAME_F, NAME_f_grad, NAME_Fv, NAME_f_gradv;\n"
    "NAME = iacsg), or the dump of one compiler stage.\n";

/* The text of a scene file when `input` names a readable file, else the input itself. malloc'ed. */
static char *read_input(const char *input, const char **name) {
    FILE *f = fopen(input, "rb");
    if (!f) {
        *name = "<expr>";
        char *copy = malloc(strlen(input) + 1);
        return copy ? strcpy(copy, input) : NULL;
    }
    *name = input;
    char *text = NULL;
    size_t len = 0;
    for (;;) {
        char *grown = realloc(text, len + 65536 + 1);
        if (!grown)
            break;
        text = grown;
        size_t n = fread(text + len, 1, 65536, f);
        len += n;
        if (n < 65536)
            break;
    }
    int bad = ferror(f) || !text;
    fclose(f);
    if (bad) {
        free(text);
        fprintf(stderr, "iacsg: %s: cannot read the file\n", input);
        return NULL;
    }
    text[len] = '\0';
    return text;
}

/* "iacsg: name:line:col: message", then the source line and a caret under the column. */
static void report(const char *name, const char *text, const iacsg_error *err) {
    if (err->line <= 0) {
        fprintf(stderr, "iacsg: %s: %s\n", name, err->message);
        return;
    }
    fprintf(stderr, "iacsg: %s:%d:%d: %s\n", name, err->line, err->column, err->message);
    const char *line = text;
    for (int l = 1; l < err->line && line; l++)
        line = (line = strchr(line, '\n')) ? line + 1 : NULL;
    if (!line)
        return;
    int len = (int)strcspn(line, "\n");
    int col = err->column - 1, start = 0;
    if (len > 100 && col > 60) /* show a window of long lines around the column */
        start = col - 60;
    int shown = len - start < 100 ? len - start : 100;
    fprintf(stderr, "  %.*s\n  %*s^\n", shown, line + start, col - start, "");
}

static const char *option_value(const char *arg, const char *name, int *i, int argc, char **argv) {
    size_t n = strlen(name);
    const char *a = arg[1] == '-' ? arg + 1 : arg; /* --box and -box alike */
    if (strncmp(a, name, n) != 0)
        return NULL;
    if (a[n] == '=')
        return a + n + 1;
    if (a[n] == '\0' && *i + 1 < argc)
        return argv[++*i];
    return NULL;
}

/* Parses "a,b,c" of decimals into the enclosing intervals lo[k], hi[k]. */
static int parse_reals(const char *s, int count, double *lo, double *hi) {
    for (int k = 0; k < count; k++) {
        char buf[128];
        size_t n = strcspn(s, ",");
        if (n == 0 || n >= sizeof buf)
            return 0;
        memcpy(buf, s, n);
        buf[n] = '\0';
        if (ia_decimal_double(buf, &lo[k], &hi[k]) != 0)
            return 0;
        s += n;
        if (k + 1 < count && *s++ != ',')
            return 0;
    }
    return *s == '\0';
}

/* The shortest decimal that parses back to exactly v. */
static void print_real(double v) {
    char buf[40];
    for (int prec = 1; prec <= 17; prec++) {
        snprintf(buf, sizeof buf, "%.*g", prec, v);
        if (strtod(buf, NULL) == v)
            break;
    }
    fputs(buf, stdout);
}

typedef struct {
    const char *input;
    double vars[8];
    int device, device_index, fp64;
} eval_options;

static int parse_eval_options(int argc, char **argv, eval_options *o) {
    double init[8] = {-1, 1, -1, 1, -1, 1, 0, 0};
    memcpy(o->vars, init, sizeof init);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v;
        double lo[6], hi[6];
        if (a[0] != '-' || (a[1] >= '0' && a[1] <= '9') || a[1] == '.') { /* "-x" is an expression too */
            if (o->input)
                return fprintf(stderr, "iacsg: eval takes one expression (quote it)\n%s", eval_usage), 2;
            o->input = a;
        } else if ((v = option_value(a, "-box", &i, argc, argv))) {
            if (!parse_reals(v, 6, lo, hi))
                return fprintf(stderr, "iacsg: --box wants six numbers X0,X1,Y0,Y1,Z0,Z1, got '%s'\n", v), 2;
            for (int k = 0; k < 3; k++) {
                o->vars[2 * k] = lo[2 * k];
                o->vars[2 * k + 1] = hi[2 * k + 1];
                if (!(lo[2 * k] <= hi[2 * k + 1]))
                    return fprintf(stderr, "iacsg: --box: each lower bound must be at most its upper bound\n"), 2;
            }
        } else if ((v = option_value(a, "-at", &i, argc, argv))) {
            if (!parse_reals(v, 3, lo, hi))
                return fprintf(stderr, "iacsg: --at wants three numbers X,Y,Z, got '%s'\n", v), 2;
            for (int k = 0; k < 3; k++)
                o->vars[2 * k] = lo[k], o->vars[2 * k + 1] = hi[k];
        } else if ((v = option_value(a, "-time", &i, argc, argv))) {
            if (!parse_reals(v, 1, lo, hi))
                return fprintf(stderr, "iacsg: --time wants a number, got '%s'\n", v), 2;
            o->vars[6] = lo[0], o->vars[7] = hi[0];
        } else if (strcmp(a, "--device") == 0 || strcmp(a, "-device") == 0) {
            o->device = 1;
        } else if (strncmp(a, "--device=", 9) == 0) {
            o->device = 1;
            o->device_index = atoi(a + 9);
        } else if (strcmp(a, "--fp64") == 0 || strcmp(a, "-fp64") == 0) {
            o->fp64 = 1;
        } else if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            return fputs(eval_usage, stdout), 1;
        } else {
            return fprintf(stderr, "iacsg: unknown option %s\n%s", a, eval_usage), 2;
        }
    }
    if (!o->input)
        return fprintf(stderr, "%s", eval_usage), 2;
    return 0;
}

/* The expression named by input, compiled, or NULL after printing the error. */
static iacsg_expr *compile_input(const char *input, char **text, const char **name) {
    iacsg_error err = {0};
    iacsg_expr *e = NULL;
    *text = read_input(input, name);
    if (*text && iacsg_expr_parse(*text, *name, &e, &err) != IACSG_OK)
        report(*name, *text, &err);
    return e;
}

static int eval_on_device(const eval_options *o, const iacsg_expr *e, double out[2]) {
    clrt rt;
    iacsg_error err = {0};
    int which = 0;
    double in[DEVICE_EVAL_IN] = {0}, result[DEVICE_EVAL_OUT];
    memcpy(in, o->vars, 8 * sizeof(double));
    if (clrt_open(&rt, o->device_index, &err) != IACSG_OK) {
        fprintf(stderr, "iacsg: %s\n", err.message);
        return 1;
    }
    iacsg_status st = device_eval(&rt, &e, 1, o->fp64, 1, &which, in, result, &err);
    clrt_close(&rt);
    if (st != IACSG_OK) {
        fprintf(stderr, "iacsg: %s\n", err.message);
        return 1;
    }
    out[0] = result[0], out[1] = result[1];
    return 0;
}

int cli_eval(int argc, char **argv) {
    eval_options o = {0};
    int rc = parse_eval_options(argc, argv, &o);
    if (rc)
        return rc == 1 ? 0 : rc;
    char *text;
    const char *name;
    iacsg_expr *e = compile_input(o.input, &text, &name);
    double out[2];
    iacsg_error err = {0};
    if (e) {
        if (o.device)
            rc = eval_on_device(&o, e, out);
        else if (iacsg_expr_eval_vars(e, o.fp64, o.vars, out, &err) != IACSG_OK) {
            fprintf(stderr, "iacsg: %s\n", err.message);
            rc = 1;
        }
        if (rc == 0) {
            printf("[");
            print_real(out[0]);
            printf(", ");
            print_real(out[1]);
            printf("]\n");
        }
    }
    iacsg_expr_destroy(e);
    free(text);
    return e ? rc : 1;
}

int cli_compile(int argc, char **argv) {
    const char *input = NULL, *stage = NULL, *prefix = "iacsg", *v;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if ((v = option_value(a, "-dump", &i, argc, argv)))
            stage = v;
        else if ((v = option_value(a, "-prefix", &i, argc, argv)))
            prefix = v;
        else if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0)
            return fputs(compile_usage, stdout), 0;
        else if (a[0] == '-' && a[1] == '-')
            return fprintf(stderr, "iacsg: unknown option %s\n%s", a, compile_usage), 2;
        else if (input)
            return fprintf(stderr, "iacsg: compile takes one expression (quote it)\n%s", compile_usage), 2;
        else
            input = a;
    }
    if (!input)
        return fprintf(stderr, "%s", compile_usage), 2;
    const char *name;
    char *text, *out = NULL;
    iacsg_error err = {0};
    iacsg_expr *e = stage ? NULL : compile_input(input, &text, &name);
    if (stage) {
        text = read_input(input, &name);
        if (text && !(out = iacsg_expr_dump(text, stage, &err)))
            report(name, text, &err);
    } else if (e && iacsg_expr_emit_cl(e, prefix, &out, &err) != IACSG_OK) {
        fprintf(stderr, "iacsg: %s\n", err.message);
    }
    if (out)
        fputs(out, stdout);
    int rc = out ? 0 : 1;
    free(out);
    iacsg_expr_destroy(e);
    free(text);
    return rc;
}
