/* implicits/brlcad_v5.c -- the v5 ASCII format (g2asc's Tcl): commands of words, a word bare or in braces,
 * braces nesting; a command ends at a newline outside braces or at ';'.
 *
 *   put {name} TYPE KEY VALUE ...     a primitive: ell (or sph) V A B C; tgc (or rec) V H A B C D; arb8 V1..V8;
 *                                     tor V H r_a r_h; half N d; ehy V H A r_1 r_2 c; pipe V0 O0 I0 R0 V1 ...
 *                                     (point, outer and inner diameter, bend radius per point)
 *   put {name} comb region yes|no tree TREE [KEY VALUE ...]
 *                                     TREE: {l name [{16 numbers}]} or {op TREE TREE}, op one of u n - ^
 *   attr set {name} {key} {value} ... region, region_id, aircode (air), color (rgb), inherit count; the rest
 *                                     (shader, los, material_id, ...) does not change the geometry
 *   color low high r g b              a colour-table entry;  title ..., units ...: not needed
 *
 * Attributes are applied after every `put`, so that they may come before or after their object.
 */
#include "brlcad_db.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

typedef struct {
    const char *p, *end;
    int line;
} cursor;

typedef struct {
    const char *s;
    size_t n;
    int line;
} word;

/* The next word; 1, or 0 at the end of the command (a newline or ';' when `command`, else only the end of the
 * text), or -1 (err set) when a brace or quote is not closed. */
static int next_word(cursor *c, int command, word *w, iacsg_error *err) {
    for (;;) {
        while (c->p < c->end && (*c->p == ' ' || *c->p == '\t' || *c->p == '\r' || (!command && *c->p == '\n'))) {
            c->line += *c->p == '\n';
            c->p++;
        }
        if (c->p < c->end && *c->p == '\\' && c->p + 1 < c->end && c->p[1] == '\n') { /* a continued line */
            c->p += 2;
            c->line++;
            continue;
        }
        break;
    }
    if (c->p >= c->end || (command && (*c->p == '\n' || *c->p == ';')))
        return 0;
    w->line = c->line;
    if (*c->p == '{' || *c->p == '"') {
        char close = *c->p == '{' ? '}' : '"';
        int depth = 1, line = c->line;
        const char *s = ++c->p;
        while (c->p < c->end) {
            char ch = *c->p;
            if (ch == '\\' && c->p + 1 < c->end) {
                c->line += c->p[1] == '\n';
                c->p += 2;
                continue;
            }
            c->line += ch == '\n';
            if (close == '}' && ch == '{')
                depth++;
            else if (ch == close && --depth == 0)
                break;
            c->p++;
        }
        if (c->p >= c->end)
            return iacsg_error_set(err, IACSG_ERR_SYNTAX, line, 1, "a '%c' that is never closed",
                                   close == '}' ? '{' : '"'),
                   -1;
        w->s = s;
        w->n = (size_t)(c->p - s);
        c->p++;
        return 1;
    }
    w->s = c->p;
    while (c->p < c->end && *c->p != ' ' && *c->p != '\t' && *c->p != '\r' && *c->p != '\n' &&
           !(command && *c->p == ';'))
        c->p++;
    w->n = (size_t)(c->p - w->s);
    return 1;
}

static int word_is(const word *w, const char *s) { return strlen(s) == w->n && memcmp(w->s, s, w->n) == 0; }

/* The words of a list (a word's text), at most max; returns the count, or -1 (err set) when there are more or
 * a brace is not closed. */
static int list_words(const word *list, word *out, int max, const char *what, iacsg_error *err) {
    cursor c = {list->s, list->s + list->n, list->line};
    int n = 0, r;
    word w;
    while ((r = next_word(&c, 0, &w, err)) == 1) {
        if (n == max)
            return iacsg_error_set(err, IACSG_ERR_SYNTAX, list->line, 1, "%s: more than %d values", what, max), -1;
        out[n++] = w;
    }
    return r < 0 ? -1 : n;
}

static int parse_number(const word *w, double *out) {
    char buf[80];
    if (w->n == 0 || w->n >= sizeof buf)
        return 0;
    memcpy(buf, w->s, w->n);
    buf[w->n] = '\0';
    char *end;
    errno = 0;
    *out = strtod(buf, &end);
    return end == buf + w->n && errno != ERANGE && isfinite(*out);
}

/* A list of exactly n finite numbers (err names the object and the key). */
static iacsg_status numbers(const word *w, double *out, int n, const char *object, const char *key,
                            iacsg_error *err) {
    word v[16];
    char what[300];
    snprintf(what, sizeof what, "'%s': %s", object, key);
    int got = list_words(w, v, 16, what, err);
    if (got < 0)
        return err->status;
    if (got != n)
        return iacsg_error_set(err, IACSG_ERR_SYNTAX, w->line, 1, "'%s': %s has %d numbers, expected %d", object,
                               key, got, n);
    for (int k = 0; k < n; k++)
        if (!parse_number(&v[k], &out[k]))
            return iacsg_error_set(err, IACSG_ERR_SYNTAX, v[k].line, 1, "'%s': %s: '%.*s' is not a finite number",
                                   object, key, (int)(v[k].n < 40 ? v[k].n : 40), v[k].s);
    return IACSG_OK;
}

/* bu_str_true: anything but empty, n, no, false, off, 0 and (null), case-insensitively. */
static int str_true(const word *w) {
    static const char *const no[] = {"", "n", "no", "false", "off", "(null)"};
    size_t a = 0, b = w->n;
    while (a < b && (w->s[a] == ' ' || w->s[a] == '\t'))
        a++;
    while (b > a && (w->s[b - 1] == ' ' || w->s[b - 1] == '\t'))
        b--;
    for (size_t k = 0; k < sizeof no / sizeof no[0]; k++)
        if (strlen(no[k]) == b - a && strncasecmp(no[k], w->s + a, b - a) == 0)
            return 0;
    size_t k = a + (a < b && (w->s[a] == '-' || w->s[a] == '+'));
    int digits = k < b;
    for (; k < b; k++)
        digits &= w->s[k] >= '0' && w->s[k] <= '9';
    if (digits) {
        for (k = a; k < b; k++)
            if (w->s[k] >= '1' && w->s[k] <= '9')
                return 1;
        return 0;
    }
    return 1;
}

/* The primitives read, their keys in scene.h's parameter order, and each key's count of numbers. */
static const struct {
    const char *type;
    scene_prim_type prim;
    const char *keys[8];
    int sizes[8];
} prim_table[] = {
    {"ell", SCENE_PRIM_ELL, {"V", "A", "B", "C"}, {3, 3, 3, 3}},
    {"tgc", SCENE_PRIM_TGC, {"V", "H", "A", "B", "C", "D"}, {3, 3, 3, 3, 3, 3}},
    {"arb8", SCENE_PRIM_ARB8, {"V1", "V2", "V3", "V4", "V5", "V6", "V7", "V8"}, {3, 3, 3, 3, 3, 3, 3, 3}},
    {"tor", SCENE_PRIM_TOR, {"V", "H", "r_a", "r_h"}, {3, 3, 1, 1}},
    {"half", SCENE_PRIM_HALF, {"N", "d"}, {3, 1}},
    {"ehy", SCENE_PRIM_EHY, {"V", "H", "A", "r_1", "r_2", "c"}, {3, 3, 3, 1, 1, 1}},
    /* librt's labels of ell's and tgc's special cases, stored as ell and tgc (g2asc writes those names) */
    {"sph", SCENE_PRIM_ELL, {"V", "A", "B", "C"}, {3, 3, 3, 3}},
    {"rec", SCENE_PRIM_TGC, {"V", "H", "A", "B", "C", "D"}, {3, 3, 3, 3, 3, 3}},
};
#define NPRIMS ((int)(sizeof prim_table / sizeof prim_table[0]))

static iacsg_status put_table_prim(brlcad_db *db, const word *name, int row, cursor *c, iacsg_error *err) {
    char obj[256];
    snprintf(obj, sizeof obj, "%.*s", (int)name->n, name->s);
    double p[24];
    int offset[8], have[8] = {0}, nkeys = 0, n = 0;
    for (; nkeys < 8 && prim_table[row].keys[nkeys]; nkeys++) {
        offset[nkeys] = n;
        n += prim_table[row].sizes[nkeys];
    }
    word key, value;
    int r;
    while ((r = next_word(c, 1, &key, err)) == 1) {
        int k = 0;
        while (k < nkeys && !word_is(&key, prim_table[row].keys[k]))
            k++;
        if (k == nkeys)
            return iacsg_error_set(err, IACSG_ERR_SYNTAX, key.line, 1, "%s '%s': unknown key '%.*s'",
                                   prim_table[row].type, obj, (int)(key.n < 40 ? key.n : 40), key.s);
        if ((r = next_word(c, 1, &value, err)) != 1)
            return r < 0 ? err->status
                         : iacsg_error_set(err, IACSG_ERR_SYNTAX, key.line, 1, "%s '%s': key %s has no value",
                                           prim_table[row].type, obj, prim_table[row].keys[k]);
        if (numbers(&value, p + offset[k], prim_table[row].sizes[k], obj, prim_table[row].keys[k], err) != IACSG_OK)
            return err->status;
        have[k] = 1;
    }
    if (r < 0)
        return err->status;
    for (int k = 0; k < nkeys; k++)
        if (!have[k])
            return iacsg_error_set(err, IACSG_ERR_SYNTAX, name->line, 1, "%s '%s' has no %s", prim_table[row].type,
                                   obj, prim_table[row].keys[k]);
    if (prim_table[row].prim == SCENE_PRIM_EHY) { /* A is a direction: a unit vector, as librt keeps it */
        double a = sqrt(p[6] * p[6] + p[7] * p[7] + p[8] * p[8]);
        if (!(a > 0))
            return iacsg_error_set(err, IACSG_ERR_ARG, name->line, 1, "ehy '%s': its A vector is zero", obj);
        for (int k = 6; k < 9; k++)
            p[k] /= a;
    }
    return brlcad_db_add_prim(db, name->s, name->n, name->line, prim_table[row].prim, p, n, err) < 0 ? err->status
                                                                                                      : IACSG_OK;
}

/* pipe: V<i> {x y z} O<i> od I<i> id R<i> bend, for points i = 0 .. n-1, into x y z od id bend per point. */
static iacsg_status put_pipe(brlcad_db *db, const word *name, cursor *c, iacsg_error *err) {
    char obj[256];
    snprintf(obj, sizeof obj, "%.*s", (int)name->n, name->s);
    double *p = NULL;
    unsigned char *have = NULL;
    int npoints = 0, r;
    iacsg_status st = IACSG_OK;
    word key, value;
    while (st == IACSG_OK && (r = next_word(c, 1, &key, err)) == 1) {
        static const char letters[] = "VOIR";
        const char *l = key.n >= 2 ? strchr(letters, key.s[0]) : NULL;
        long i = -1;
        if (l && key.n < 12) {
            char buf[16], *end;
            snprintf(buf, sizeof buf, "%.*s", (int)key.n - 1, key.s + 1);
            i = buf[0] >= '0' && buf[0] <= '9' ? strtol(buf, &end, 10) : -1;
            if (i >= 0 && *end)
                i = -1;
        }
        if (i < 0 || i > 100000) {
            st = iacsg_error_set(err, IACSG_ERR_SYNTAX, key.line, 1, "pipe '%s': unknown key '%.*s'", obj,
                                 (int)(key.n < 40 ? key.n : 40), key.s);
            break;
        }
        if ((r = next_word(c, 1, &value, err)) != 1) {
            st = r < 0 ? err->status
                       : iacsg_error_set(err, IACSG_ERR_SYNTAX, key.line, 1, "pipe '%s': key %.*s has no value", obj,
                                         (int)key.n, key.s);
            break;
        }
        if (i >= npoints) {
            int n = (int)i + 1;
            double *q = realloc(p, (size_t)n * 6 * sizeof *p);
            unsigned char *h = q ? realloc(have, (size_t)n) : NULL;
            if (q)
                p = q;
            if (!h) {
                st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory reading the database");
                break;
            }
            have = h;
            memset(have + npoints, 0, (size_t)(n - npoints));
            npoints = n;
        }
        int which = (int)(l - letters); /* V O I R -> x y z at 0, od at 3, id at 4, bend at 5 */
        char keyname[16];
        snprintf(keyname, sizeof keyname, "%.*s", (int)key.n, key.s);
        st = numbers(&value, p + 6 * i + (which ? 2 + which : 0), which ? 1 : 3, obj, keyname, err);
        have[i] |= (unsigned char)(1u << which);
    }
    if (st == IACSG_OK && r < 0)
        st = err->status;
    if (st == IACSG_OK && npoints < 2)
        st = iacsg_error_set(err, IACSG_ERR_SYNTAX, name->line, 1, "pipe '%s' has %d points, at least 2 are needed",
                             obj, npoints);
    for (int i = 0; st == IACSG_OK && i < npoints; i++)
        if (have[i] != 15)
            st = iacsg_error_set(err, IACSG_ERR_SYNTAX, name->line, 1, "pipe '%s': point %d lacks one of V%d O%d "
                                 "I%d R%d", obj, i, i, i, i, i);
    if (st == IACSG_OK &&
        brlcad_db_add_prim(db, name->s, name->n, name->line, SCENE_PRIM_PIPE, p, 6 * npoints, err) < 0)
        st = err->status;
    free(p);
    free(have);
    return st;
}

/* A combination's tree: {l name [matrix]} or {op left right}; the node index, or -1 (err set). */
static int parse_tree(brlcad_db *db, const word *w, const char *comb, int depth, iacsg_error *err) {
    word v[4];
    if (depth > BRL_DEPTH_MAX)
        return iacsg_error_set(err, IACSG_ERR_LIMIT, w->line, 1, "combination '%s': its tree nests more than %d "
                               "levels deep", comb, BRL_DEPTH_MAX), -1;
    int n = list_words(w, v, 3, comb, err);
    if (n < 0)
        return -1;
    if (n >= 2 && word_is(&v[0], "l")) {
        double m[16];
        if (n == 3 && numbers(&v[2], m, 16, comb, "a member's matrix", err) != IACSG_OK)
            return -1;
        return brlcad_db_leaf(db, v[1].s, v[1].n, v[1].line, n == 3 ? m : NULL, err);
    }
    static const char ops[] = "un-^";
    static const brl_op kinds[] = {BRL_UNION, BRL_INTERSECT, BRL_SUBTRACT, BRL_XOR};
    const char *op = n == 3 && v[0].n == 1 ? strchr(ops, v[0].s[0]) : NULL;
    if (!op || !*op)
        return iacsg_error_set(err, IACSG_ERR_SYNTAX, w->line, 1, "combination '%s': a tree node '%.*s', expected "
                               "{l NAME [MATRIX]} or {OP LEFT RIGHT} with OP one of u n - ^", comb,
                               (int)(w->n < 60 ? w->n : 60), w->s), -1;
    int left = parse_tree(db, &v[1], comb, depth + 1, err);
    int right = left < 0 ? -1 : parse_tree(db, &v[2], comb, depth + 1, err);
    return right < 0 ? -1 : brlcad_db_binary(db, kinds[op - ops], left, right, err);
}

static iacsg_status put_comb(brlcad_db *db, const word *name, cursor *c, iacsg_error *err) {
    char obj[256];
    snprintf(obj, sizeof obj, "%.*s", (int)name->n, name->s);
    int k = brlcad_db_add_comb(db, name->s, name->n, name->line, err), r;
    if (k < 0)
        return err->status;
    word key, value;
    while ((r = next_word(c, 1, &key, err)) == 1) {
        if ((r = next_word(c, 1, &value, err)) != 1)
            return r < 0 ? err->status
                         : iacsg_error_set(err, IACSG_ERR_SYNTAX, key.line, 1, "combination '%s': key '%.*s' has no "
                                           "value", obj, (int)(key.n < 40 ? key.n : 40), key.s);
        if (word_is(&key, "region")) {
            db->objects[k].region = str_true(&value);
        } else if (word_is(&key, "tree")) {
            int root = -1;
            if (value.n > 0 && (root = parse_tree(db, &value, obj, 0, err)) < 0)
                return err->status;
            db->objects[k].tree = root;
        } else if (!(word_is(&key, "id") || word_is(&key, "air") || word_is(&key, "los") ||
                     word_is(&key, "GIFTmater") || word_is(&key, "rgb") || word_is(&key, "shader") ||
                     word_is(&key, "material") || word_is(&key, "inherit") || word_is(&key, "temp"))) {
            return iacsg_error_set(err, IACSG_ERR_SYNTAX, key.line, 1, "combination '%s': unknown key '%.*s'", obj,
                                   (int)(key.n < 40 ? key.n : 40), key.s);
        }
    }
    return r < 0 ? err->status : IACSG_OK;
}

static iacsg_status put_command(brlcad_db *db, cursor *c, int line, iacsg_error *err) {
    word name, type;
    int r = next_word(c, 1, &name, err);
    if (r == 1)
        r = next_word(c, 1, &type, err);
    if (r != 1)
        return r < 0 ? err->status : iacsg_error_set(err, IACSG_ERR_SYNTAX, line, 1, "put needs a name and a type");
    if (word_is(&type, "comb"))
        return put_comb(db, &name, c, err);
    if (word_is(&type, "pipe"))
        return put_pipe(db, &name, c, err);
    for (int row = 0; row < NPRIMS; row++)
        if (word_is(&type, prim_table[row].type))
            return put_table_prim(db, &name, row, c, err);
    return iacsg_error_set(err, IACSG_ERR_NAME, line, 1, "'%.*s' is a %.*s, which iacsg does not read (it reads "
                           "arb8, tgc, ell, tor, half, pipe, ehy and comb)", (int)(name.n < 200 ? name.n : 200),
                           name.s, (int)(type.n < 40 ? type.n : 40), type.s);
}

/* An integer attribute value as strtol(.., 0) takes it, the whole text. */
static int attr_integer(const word *w, int *out) {
    char buf[40], *end;
    if (w->n == 0 || w->n >= sizeof buf)
        return 0;
    memcpy(buf, w->s, w->n);
    buf[w->n] = '\0';
    errno = 0;
    long v = strtol(buf, &end, 0);
    if (*end || errno == ERANGE || v < -2147483647L || v > 2147483647L)
        return 0;
    *out = (int)v;
    return 1;
}

static iacsg_status attr_command(brlcad_db *db, cursor *c, int line, iacsg_error *err) {
    word sub, name, key, value;
    int r = next_word(c, 1, &sub, err);
    if (r == 1 && !word_is(&sub, "set"))
        return iacsg_error_set(err, IACSG_ERR_SYNTAX, line, 1, "attr %.*s: only 'attr set' is read",
                               (int)(sub.n < 20 ? sub.n : 20), sub.s);
    if (r == 1)
        r = next_word(c, 1, &name, err);
    if (r != 1)
        return r < 0 ? err->status : iacsg_error_set(err, IACSG_ERR_SYNTAX, line, 1, "attr set needs an object");
    char obj[256];
    snprintf(obj, sizeof obj, "%.*s", (int)name.n, name.s);
    int k = word_is(&name, "_GLOBAL") ? -2 : brlcad_db_find(db, obj);
    if (k == -1)
        return iacsg_error_set(err, IACSG_ERR_NAME, line, 1, "attr set for '%s', which the database does not define",
                               obj);
    while ((r = next_word(c, 1, &key, err)) == 1) {
        if ((r = next_word(c, 1, &value, err)) != 1)
            return r < 0 ? err->status
                         : iacsg_error_set(err, IACSG_ERR_SYNTAX, line, 1, "attr set '%s': attribute '%.*s' has no "
                                           "value", obj, (int)(key.n < 40 ? key.n : 40), key.s);
        if (k < 0 || !db->objects[k].is_comb)
            continue; /* the global object's and primitives' attributes do not change the geometry */
        brl_object *o = &db->objects[k];
        if (word_is(&key, "region")) {
            o->region = str_true(&value);
        } else if (word_is(&key, "region_id") || word_is(&key, "aircode") || word_is(&key, "air")) {
            int v;
            if (!attr_integer(&value, &v))
                return iacsg_error_set(err, IACSG_ERR_SYNTAX, value.line, 1, "'%s': %.*s '%.*s' is not an integer",
                                       obj, (int)key.n, key.s, (int)(value.n < 40 ? value.n : 40), value.s);
            *(key.s[0] == 'r' ? &o->region_id : &o->aircode) = v;
        } else if (word_is(&key, "color") || word_is(&key, "rgb")) {
            int rgb[3], n = 0;
            char buf[64];
            snprintf(buf, sizeof buf, "%.*s", (int)(value.n < 63 ? value.n : 63), value.s);
            n = sscanf(buf, "%3i%*c%3i%*c%3i", &rgb[0], &rgb[1], &rgb[2]);
            if (n == 3 && rgb[0] >= 0 && rgb[1] >= 0 && rgb[2] >= 0) {
                o->rgb_valid = 1;
                for (int j = 0; j < 3; j++)
                    o->rgb[j] = (unsigned char)(rgb[j] > 255 ? 255 : rgb[j]);
            } else if (n == 3 || (n == 1 && rgb[0] < 0)) {
                o->rgb_valid = 0; /* a negative colour is librt's "none" */
            } else {
                return iacsg_error_set(err, IACSG_ERR_SYNTAX, value.line, 1, "'%s': colour '%s' is not R/G/B", obj,
                                       buf);
            }
        } else if (word_is(&key, "inherit")) {
            o->inherit = str_true(&value);
        }
    }
    return r < 0 ? err->status : IACSG_OK;
}

static iacsg_status color_command(brlcad_db *db, cursor *c, int line, iacsg_error *err) {
    int v[5], n = 0, r;
    word w;
    while ((r = next_word(c, 1, &w, err)) == 1) {
        if (n == 5 || !attr_integer(&w, &v[n]))
            return iacsg_error_set(err, IACSG_ERR_SYNTAX, line, 1, "color takes 5 integers: low high r g b");
        n++;
    }
    if (r < 0)
        return err->status;
    if (n != 5 || v[2] < 0 || v[2] > 255 || v[3] < 0 || v[3] > 255 || v[4] < 0 || v[4] > 255)
        return iacsg_error_set(err, IACSG_ERR_SYNTAX, line, 1, "color takes 5 integers: low high r g b (0 to 255)");
    return brlcad_db_add_colour(db, v[0], v[1], v + 2, err) < 0 ? err->status : IACSG_OK;
}

/* Skips the rest of a command. */
static iacsg_status skip_command(cursor *c, iacsg_error *err) {
    word w;
    int r;
    while ((r = next_word(c, 1, &w, err)) == 1)
        ;
    return r < 0 ? err->status : IACSG_OK;
}

/* Runs the commands of the text: attributes only (attrs) or all others. */
static iacsg_status run_commands(brlcad_db *db, const char *text, size_t len, int attrs, iacsg_error *err) {
    cursor c = {text, text + len, 1};
    iacsg_status st = IACSG_OK;
    while (st == IACSG_OK && c.p < c.end) {
        while (c.p < c.end && (*c.p == ' ' || *c.p == '\t' || *c.p == '\r'))
            c.p++;
        if (c.p < c.end && *c.p == '#') { /* a comment, to the end of the line */
            while (c.p < c.end && *c.p != '\n')
                c.p++;
            continue;
        }
        word cmd;
        int r = next_word(&c, 1, &cmd, err);
        if (r < 0)
            return err->status;
        if (r == 0) { /* an empty command */
            c.line += c.p < c.end && *c.p == '\n';
            c.p++;
            continue;
        }
        if (word_is(&cmd, "attr"))
            st = attrs ? attr_command(db, &c, cmd.line, err) : skip_command(&c, err);
        else if (attrs)
            st = skip_command(&c, err);
        else if (word_is(&cmd, "put"))
            st = put_command(db, &c, cmd.line, err);
        else if (word_is(&cmd, "color"))
            st = color_command(db, &c, cmd.line, err);
        else if (word_is(&cmd, "title") || word_is(&cmd, "units"))
            st = skip_command(&c, err);
        else
            st = iacsg_error_set(err, IACSG_ERR_SYNTAX, cmd.line, 1, "unknown command '%.*s' (a v5 database has "
                                 "put, attr, color, title and units)", (int)(cmd.n < 40 ? cmd.n : 40), cmd.s);
    }
    return st;
}

iacsg_status brlcad_read_v5(const char *text, size_t len, brlcad_db **out, iacsg_error *err) {
    *out = brlcad_db_create(5);
    if (!*out)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory reading the database");
    iacsg_status st = run_commands(*out, text, len, 0, err);
    return st == IACSG_OK ? run_commands(*out, text, len, 1, err) : st;
}
