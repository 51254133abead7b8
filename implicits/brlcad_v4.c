/* implicits/brlcad_v4.c -- the v4 ASCII format (asc2g's input when the first line is an `I` record): one record
 * a line, its kind the first character.
 *
 *   I units v4          the first line; the title is the next line
 *   S type name n v1 .. v24          a primitive (the types read: tor 16, tgc 18, ell 19, arb8 20, half 24, ehy 29)
 *   C flag name region_id aircode n ref material los override r g b [nflag pflag inherit]
 *                       a combination (flag Y, R, P or V: a region), then a shader line if nflag, a parameter line
 *                       if pflag, then its members:
 *   M op name m1 .. m16 [x]          op u (a new term), - (subtract), + (intersect): GIFT precedence
 *   m x low high r g b  a colour-table entry;  # a comment
 *
 * Each record becomes the primitive's parameters in scene.h's layout (arb8 vertices made absolute, tor's
 * radii from its vectors' lengths as asc2g does), a combination with its tree, or a colour.
 */
#include "brlcad_db.h"
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_TOKENS 32

typedef struct {
    const char *start[MAX_TOKENS];
    size_t len[MAX_TOKENS];
    int n;          /* tokens on the line (counted beyond MAX_TOKENS) */
    int line;       /* 1-based */
} v4_line;

typedef struct {
    const char *p, *end;
    int line;
} v4_reader;

/* Splits the next line into tokens; 0 at the end of the text. */
static int next_line(v4_reader *r, v4_line *l) {
    if (r->p >= r->end)
        return 0;
    l->line = ++r->line;
    l->n = 0;
    const char *p = r->p;
    while (p < r->end && *p != '\n') {
        while (p < r->end && (*p == ' ' || *p == '\t' || *p == '\r'))
            p++;
        if (p >= r->end || *p == '\n')
            break;
        const char *s = p;
        while (p < r->end && *p != ' ' && *p != '\t' && *p != '\r' && *p != '\n')
            p++;
        if (l->n < MAX_TOKENS) {
            l->start[l->n] = s;
            l->len[l->n] = (size_t)(p - s);
        }
        l->n++;
    }
    r->p = p < r->end ? p + 1 : p;
    return 1;
}

static iacsg_status fail(const v4_line *l, iacsg_error *err, const char *what) {
    return iacsg_error_set(err, IACSG_ERR_SYNTAX, l->line, 1, "%s", what);
}

/* Token k as a finite number; 0 (after setting err, naming the record's object) when it is not one. */
static int number(const v4_line *l, int k, const char *object, double *out, iacsg_error *err) {
    char buf[64];
    size_t n = l->len[k] < sizeof buf - 1 ? l->len[k] : sizeof buf - 1;
    memcpy(buf, l->start[k], n);
    buf[n] = '\0';
    char *end;
    errno = 0;
    *out = strtod(buf, &end);
    if (n == l->len[k] && end == buf + n && n > 0 && errno != ERANGE && isfinite(*out))
        return 1;
    iacsg_error_set(err, IACSG_ERR_SYNTAX, l->line, 1, "'%s': field %d is not a finite number: '%.*s'", object,
                    k + 1, (int)(l->len[k] < 40 ? l->len[k] : 40), l->start[k]);
    return 0;
}

static int integer(const v4_line *l, int k, const char *object, long lo, long hi, int *out, iacsg_error *err) {
    double v;
    if (!number(l, k, object, &v, err))
        return 0;
    if (v != floor(v) || v < (double)lo || v > (double)hi) {
        iacsg_error_set(err, IACSG_ERR_SYNTAX, l->line, 1, "'%s': field %d is not an integer from %ld to %ld: '%.*s'",
                        object, k + 1, lo, hi, (int)(l->len[k] < 40 ? l->len[k] : 40), l->start[k]);
        return 0;
    }
    *out = (int)v;
    return 1;
}

static void name_of(const v4_line *l, int k, char *buf, size_t size) {
    size_t n = l->len[k] < size - 1 ? l->len[k] : size - 1;
    memcpy(buf, l->start[k], n);
    buf[n] = '\0';
}

static double length3(const double *v) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/* The solid types of db4.h by number, for messages about the ones not read. */
static const char *v4_type_name(int type) {
    static const char *const names[] = {
        [4] = "arb4",  [5] = "arb5",      [6] = "arb6",  [7] = "arb7",  [8] = "arb8",   [9] = "ell",
        [10] = "ell1", [11] = "sph",      [12] = "rcc",  [13] = "rec",  [14] = "trc",   [15] = "tec",
        [16] = "tor",  [18] = "tgc",      [19] = "ell",  [20] = "arb8", [21] = "ars",   [22] = "ars",
        [23] = "ellg", [24] = "half",     [26] = "rpc",  [27] = "rhc",  [28] = "epa",   [29] = "ehy",
        [30] = "eto",  [31] = "grip",     [32] = "superell",            [33] = "hyp"};
    return type >= 0 && type < (int)(sizeof names / sizeof names[0]) && names[type] ? names[type] : "unknown";
}

static iacsg_status solid_record(brlcad_db *db, const v4_line *l, iacsg_error *err) {
    char name[256];
    if (l->n < 3)
        return fail(l, err, "a solid record (S) needs a type, a name and 24 numbers");
    name_of(l, 2, name, sizeof name);
    int type;
    if (!integer(l, 1, name, 0, 1000, &type, err))
        return err->status;
    if (l->n != 28)
        return iacsg_error_set(err, IACSG_ERR_SYNTAX, l->line, 1,
                               "solid '%s': %d fields, a solid record has 28 (S, type, name, number, 24 values)",
                               name, l->n);
    double v[24], p[24];
    for (int k = 0; k < 24; k++)
        if (!number(l, 4 + k, name, &v[k], err))
            return err->status;
    scene_prim_type t;
    int n;
    switch (type) {
    case 16: { /* tor: V, N whose length is the tube radius, a vector whose length is the major radius */
        double r_a = length3(v + 6), r_h = length3(v + 3);
        memcpy(p, v, 6 * sizeof *p);
        p[6] = r_a;
        p[7] = r_h < r_a ? r_h : r_a; /* as asc2g: the tube radius at most the major one */
        t = SCENE_PRIM_TOR, n = 8;
        break;
    }
    case 18: t = SCENE_PRIM_TGC, n = 18, memcpy(p, v, 18 * sizeof *p); break;
    case 19: t = SCENE_PRIM_ELL, n = 12, memcpy(p, v, 12 * sizeof *p); break;
    case 20: /* V, then 7 vectors relative to V */
        t = SCENE_PRIM_ARB8, n = 24;
        for (int k = 0; k < 24; k++)
            p[k] = k < 3 ? v[k] : v[k] + v[k % 3];
        break;
    case 24: t = SCENE_PRIM_HALF, n = 4, memcpy(p, v, 4 * sizeof *p); break;
    case 29: { /* ehy: V H A r_1 r_2 c, A made a unit vector */
        double a = length3(v + 6);
        if (!(a > 0))
            return iacsg_error_set(err, IACSG_ERR_ARG, l->line, 1, "ehy '%s': its A vector is zero", name);
        memcpy(p, v, 12 * sizeof *p);
        for (int k = 6; k < 9; k++)
            p[k] = v[k] / a;
        t = SCENE_PRIM_EHY, n = 12;
        break;
    }
    default:
        return iacsg_error_set(err, IACSG_ERR_NAME, l->line, 1,
                               "solid '%s' is of type %d (%s), which iacsg does not read (it reads arb8, tgc, ell, "
                               "tor, half, pipe and ehy)",
                               name, type, v4_type_name(type));
    }
    return brlcad_db_add_prim(db, l->start[2], l->len[2], l->line, t, p, n, err) < 0 ? err->status : IACSG_OK;
}

/* The members (M records) after a combination record, in GIFT precedence: a `u` starts a new term, `-` and
 * `+` apply to the term so far; the terms are unioned (balanced: union is associative and keeps its order). */
static iacsg_status member_records(brlcad_db *db, v4_reader *r, v4_line *l, int comb, int *have_line,
                                   iacsg_error *err) {
    int *terms = NULL, nterms = 0, cap = 0;
    iacsg_status st = IACSG_OK;
    const char *cname = db->objects[comb].name;
    while ((*have_line = next_line(r, l)) && l->n > 0 && l->start[0][0] == 'M' && l->len[0] == 1) {
        if (l->n != 19 && l->n != 20) {
            st = iacsg_error_set(err, IACSG_ERR_SYNTAX, l->line, 1,
                                 "combination '%s': a member record has 19 or 20 fields (M, op, name, 16 matrix "
                                 "numbers), this one %d",
                                 cname, l->n);
            break;
        }
        char op = l->len[1] == 1 ? l->start[1][0] : '?';
        if (op != 'u' && op != '-' && op != '+') {
            st = iacsg_error_set(err, IACSG_ERR_SYNTAX, l->line, 1,
                                 "combination '%s': member operation '%.*s', expected u, - or +", cname,
                                 (int)(l->len[1] < 8 ? l->len[1] : 8), l->start[1]);
            break;
        }
        double m[16];
        for (int k = 0; k < 16 && st == IACSG_OK; k++)
            if (!number(l, 3 + k, cname, &m[k], err))
                st = err->status;
        if (st != IACSG_OK)
            break;
        int identity = 1;
        for (int k = 0; k < 16; k++)
            identity &= m[k] == (k % 5 == 0);
        int leaf = brlcad_db_leaf(db, l->start[2], l->len[2], l->line, identity ? NULL : m, err);
        if (leaf < 0) {
            st = err->status;
            break;
        }
        if (op == 'u' || nterms == 0) { /* a first member's operation counts as union, as in librt */
            if (nterms == cap) {
                cap = cap ? 2 * cap : 16;
                int *g = realloc(terms, (size_t)cap * sizeof *terms);
                if (!g) {
                    st = iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory reading the database");
                    break;
                }
                terms = g;
            }
            terms[nterms++] = leaf;
        } else {
            int t = brlcad_db_binary(db, op == '-' ? BRL_SUBTRACT : BRL_INTERSECT, terms[nterms - 1], leaf, err);
            if (t < 0) {
                st = err->status;
                break;
            }
            terms[nterms - 1] = t;
        }
    }
    /* pairwise unions, level by level, keep the left-to-right order of the terms */
    while (st == IACSG_OK && nterms > 1) {
        int n = 0;
        for (int k = 0; k < nterms && st == IACSG_OK; k += 2) {
            int u = k + 1 < nterms ? brlcad_db_binary(db, BRL_UNION, terms[k], terms[k + 1], err) : terms[k];
            if (u < 0)
                st = err->status;
            terms[n++] = u;
        }
        nterms = n;
    }
    if (st == IACSG_OK && nterms == 1)
        db->objects[comb].tree = terms[0];
    free(terms);
    return st;
}

static iacsg_status comb_record(brlcad_db *db, v4_reader *r, v4_line *l, int *have_line, iacsg_error *err) {
    char name[256];
    *have_line = 0;
    if (l->n < 3)
        return fail(l, err, "a combination record (C) needs a flag and a name");
    name_of(l, 2, name, sizeof name);
    if (l->n < 13 || l->n > 16)
        return iacsg_error_set(err, IACSG_ERR_SYNTAX, l->line, 1,
                               "combination '%s': %d fields, a combination record has 13 to 16", name, l->n);
    char flag = l->len[1] == 1 ? l->start[1][0] : '?';
    if (!strchr("YRPVN", flag))
        return iacsg_error_set(err, IACSG_ERR_SYNTAX, l->line, 1,
                               "combination '%s': region flag '%.*s', expected Y, R, P, V or N", name,
                               (int)(l->len[1] < 8 ? l->len[1] : 8), l->start[1]);
    int f[13] = {0}; /* region_id aircode n ref material los override r g b nflag pflag inherit */
    for (int k = 3; k < l->n; k++)
        if (!integer(l, k, name, -2147483647L, 2147483647L, &f[k - 3], err))
            return err->status;
    for (int k = 7; k < 10; k++)
        if (f[k] < 0 || f[k] > 255)
            return iacsg_error_set(err, IACSG_ERR_SYNTAX, l->line, 1,
                                   "combination '%s': colour component %d is not from 0 to 255", name, f[k]);
    int comb = brlcad_db_add_comb(db, l->start[2], l->len[2], l->line, err);
    if (comb < 0)
        return err->status;
    brl_object *o = &db->objects[comb];
    o->region = flag != 'N';
    o->region_id = f[0];
    o->aircode = f[1];
    o->rgb_valid = f[6] != 0; /* the colour counts only with the override flag, as in asc2g */
    for (int k = 0; k < 3; k++)
        o->rgb[k] = (unsigned char)f[7 + k];
    o->inherit = f[12] != 0;
    for (int k = 0; k < (f[10] != 0) + (f[11] != 0); k++) /* shader name and parameter lines */
        if (!next_line(r, l))
            return iacsg_error_set(err, IACSG_ERR_SYNTAX, r->line, 1,
                                   "combination '%s': the text ends before its shader lines", name);
    return member_records(db, r, l, comb, have_line, err);
}

static iacsg_status colour_record(brlcad_db *db, const v4_line *l, iacsg_error *err) {
    if (l->n != 7)
        return fail(l, err, "a colour record (m) has 7 fields: m, a number, low and high region ids, r, g, b");
    int v[6], rgb[3];
    for (int k = 0; k < 6; k++)
        if (!integer(l, k + 1, "colour table", -2147483647L, 2147483647L, &v[k], err))
            return err->status;
    for (int k = 0; k < 3; k++) {
        if (v[3 + k] < 0 || v[3 + k] > 255)
            return fail(l, err, "a colour record's r, g, b must be from 0 to 255");
        rgb[k] = v[3 + k];
    }
    return brlcad_db_add_colour(db, v[1], v[2], rgb, err) < 0 ? err->status : IACSG_OK;
}

iacsg_status brlcad_read_v4(const char *text, size_t len, brlcad_db **out, iacsg_error *err) {
    brlcad_db *db = brlcad_db_create(4);
    *out = db;
    if (!db)
        return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "out of memory reading the database");
    v4_reader r = {text, text + len, 0};
    v4_line l;
    int have = next_line(&r, &l), seen_ident = 0;
    iacsg_status st = IACSG_OK;
    while (have && st == IACSG_OK) {
        char kind = l.n > 0 ? l.start[0][0] : '#';
        if (l.n > 0 && l.len[0] != 1 && kind != '#') {
            st = iacsg_error_set(err, IACSG_ERR_SYNTAX, l.line, 1, "unknown record '%.*s' (v4 records start with "
                                 "one letter: I, S, C, M, m, #)", (int)(l.len[0] < 20 ? l.len[0] : 20), l.start[0]);
            break;
        }
        switch (kind) {
        case '#': break;
        case 'I':
            if (seen_ident++)
                st = fail(&l, err, "a second identification record (I)");
            else if (!next_line(&r, &l)) /* the title */
                st = fail(&l, err, "the text ends before the title line");
            break;
        case 'S': st = solid_record(db, &l, err); break;
        case 'C': st = comb_record(db, &r, &l, &have, err); continue; /* it read the line after its members */
        case 'M': st = fail(&l, err, "a member record (M) that follows no combination record"); break;
        case 'm': st = colour_record(db, &l, err); break;
        default: {
            static const char kinds[] = "ABPQbDFw";
            static const char *const names[] = {"ars", "ars", "polysolid", "polysolid", "b-spline", "b-spline",
                                                "free", "pipe"};
            const char *k = strchr(kinds, kind);
            st = iacsg_error_set(err, IACSG_ERR_NAME, l.line, 1, "record type '%c'%s%s%s is not read (iacsg reads "
                                 "I, S, C, M, m)", kind, k ? " (" : "", k ? names[k - kinds] : "", k ? ")" : "");
        }
        }
        have = next_line(&r, &l);
    }
    if (st == IACSG_OK && !seen_ident)
        st = iacsg_error_set(err, IACSG_ERR_SYNTAX, 1, 1, "no identification record (I) in the v4 database");
    return st;
}
