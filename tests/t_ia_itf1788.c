/* tests/t_ia_itf1788.c -- the IEEE 1788 test vectors of ITF1788 (tests/data/itf1788, read at test time) against
 * the double intervals of ia/, on the host and on the OpenCL device.
 *
 * Every bare test of an operation ia/ implements is run, in every file (libieeep1788_elem first, then mpfi,
 * fi_lib, c-xsc, then the num and set files). Decorated tests (_dec test cases, [..]_com literals), NaI and
 * string constructors, and operations ia/ does not have are skipped and counted. Input literals are read as
 * the tightest double interval around the decimal numbers (ia/decimal.c). Each result must contain the
 * expected tightest interval (mid: within one step of it; wid: not below it): a violation fails the test.
 * One deviation is by design and counted as contained, not tight: ia_width(empty) is 0, IEEE 1788 says NaN.
 * IACSG_ITF_VERBOSE=1 prints every result that is not tight.
 * Tight results (equal to the expected ones) are counted per op. */
#define IA_FP64 1
#include "ia/decimal.h"
#include "ia/ia.h"
#include "oracle_ia.h"
#include <ctype.h>
#include <stdlib.h>

static const struct {
    const char *itl;
    int op;
} op_map[] = {
    {"neg", ORACLE_NEG},   {"add", ORACLE_ADD},         {"sub", ORACLE_SUB},
    {"mul", ORACLE_MUL},   {"div", ORACLE_DIV},         {"recip", ORACLE_RECIP},
    {"sqr", ORACLE_SQR},   {"sqrt", ORACLE_SQRT},       {"pown", ORACLE_POWN},
    {"pow", ORACLE_POW},   {"exp", ORACLE_EXP},         {"log", ORACLE_LOG},
    {"sin", ORACLE_SIN},   {"cos", ORACLE_COS},         {"tan", ORACLE_TAN},
    {"atan", ORACLE_ATAN}, {"abs", ORACLE_ABS},         {"min", ORACLE_MIN},
    {"max", ORACLE_MAX},   {"convexHull", ORACLE_HULL}, {"intersection", ORACLE_INTERSECT},
    {"mid", ORACLE_MID},   {"wid", ORACLE_WIDTH},
};

typedef struct {
    ia_case k;
    double elo, ehi; /* expected: an interval, or a number twice */
    int op, line;
    const char *file;
} itl_test;

typedef struct {
    itl_test *v;
    long n, cap;
    long skipped_dec, skipped_op, skipped_other;
} itl_set;

/* One operand or result: "[lo, hi]", "[empty]", "[entire]", "[x]" or a bare number. Returns 0 or -1. */
static int parse_value(const char *s, double *lo, double *hi) {
    char buf[256];
    size_t n = strlen(s);
    if (n >= sizeof buf)
        return -1;
    if (s[0] != '[') {
        return ia_decimal_double(s, lo, hi);
    }
    if (s[n - 1] != ']')
        return -1; /* decorated */
    memcpy(buf, s + 1, n - 2);
    buf[n - 2] = '\0';
    char *comma = strchr(buf, ',');
    double d;
    if (!comma) {
        char *t = buf;
        while (isspace((unsigned char)*t))
            t++;
        if (strcmp(t, "empty") == 0) {
            *lo = INFINITY, *hi = -INFINITY;
            return 0;
        }
        if (strcmp(t, "entire") == 0) {
            *lo = -INFINITY, *hi = INFINITY;
            return 0;
        }
        return ia_decimal_double(t, lo, hi);
    }
    *comma = '\0';
    char *a = buf, *b = comma + 1;
    while (isspace((unsigned char)*a))
        a++;
    while (isspace((unsigned char)*b))
        b++;
    for (char *e = a + strlen(a); e > a && isspace((unsigned char)e[-1]); e--)
        e[-1] = '\0';
    for (char *e = b + strlen(b); e > b && isspace((unsigned char)e[-1]); e--)
        e[-1] = '\0';
    if (ia_decimal_double(a, lo, &d) || ia_decimal_double(b, &d, hi))
        return -1;
    return 0;
}

/* Splits a statement into tokens: bracketed literals (with any suffix) and words. */
static int tokenize(const char *s, char tok[][256], int max) {
    int n = 0;
    while (*s && n < max) {
        while (isspace((unsigned char)*s))
            s++;
        if (!*s)
            break;
        const char *b = s;
        if (*s == '[') {
            while (*s && *s != ']')
                s++;
            if (*s)
                s++;
        }
        while (*s && !isspace((unsigned char)*s))
            s++;
        size_t len = (size_t)(s - b);
        if (len >= 256)
            return -1;
        memcpy(tok[n], b, len);
        tok[n][len] = '\0';
        n++;
    }
    return n;
}

static void add_test(itl_set *set, const itl_test *t) {
    if (set->n == set->cap) {
        set->cap = set->cap ? set->cap * 2 : 1024;
        set->v = realloc(set->v, sizeof *set->v * (size_t)set->cap);
        if (!set->v)
            abort();
    }
    set->v[set->n++] = *t;
}

/* Parses one statement of test case `tc` at `line`. */
static void parse_statement(itl_set *set, const char *file, const char *tc, int line, const char *st) {
    char tok[16][256];
    int n = tokenize(st, tok, 16);
    if (n <= 0)
        return;
    if (strstr(tc, "_dec") || strstr(st, "]_") || strstr(st, "nai") || strchr(st, '"')) {
        set->skipped_dec++;
        return;
    }
    int op = -1;
    for (size_t i = 0; i < sizeof op_map / sizeof op_map[0]; i++)
        if (strcmp(tok[0], op_map[i].itl) == 0)
            op = op_map[i].op;
    if (op < 0) {
        set->skipped_op++;
        return;
    }
    int eq = -1;
    for (int i = 1; i < n; i++)
        if (strcmp(tok[i], "=") == 0) {
            eq = i;
            break;
        }
    int nargs = eq - 1,
        want = oracle_op_kind[op] == ORACLE_K_BIN || oracle_op_kind[op] == ORACLE_K_SET || op == ORACLE_POWN ? 2 : 1;
    if (eq < 0 || nargs != want || eq + 1 >= n) {
        set->skipped_other++;
        return;
    }
    itl_test t;
    memset(&t, 0, sizeof t);
    t.op = op, t.line = line, t.file = file;
    t.k.b = ia_empty();
    double lo, hi;
    if (parse_value(tok[1], &lo, &hi)) {
        set->skipped_other++;
        return;
    }
    t.k.a = ia_make(lo, hi);
    if (op == ORACLE_POWN) {
        char *end;
        long v = strtol(tok[2], &end, 10);
        if (*end) {
            set->skipped_other++;
            return;
        }
        t.k.n = (int)v;
    } else if (want == 2) {
        if (parse_value(tok[2], &lo, &hi)) {
            set->skipped_other++;
            return;
        }
        t.k.b = ia_make(lo, hi);
    }
    /* the result: the first token after '=' (an accurate bound after "<=" is ignored) */
    if (parse_value(tok[eq + 1], &t.elo, &t.ehi)) {
        set->skipped_other++;
        return;
    }
    add_test(set, &t);
}

/* Parses a whole .itl file into set; returns the number of tests added, or -1 if unreadable. */
static long parse_file(itl_set *set, const char *path, const char *file) {
    char *s = test_read_file(path, NULL);
    if (!s)
        return -1;
    long before = set->n;
    /* blank out comments, keeping newlines for line numbers */
    for (char *p = s; *p; p++) {
        if (p[0] == '/' && p[1] == '*') {
            for (; *p && !(p[0] == '*' && p[1] == '/'); p++)
                if (*p != '\n')
                    *p = ' ';
            if (*p)
                p[0] = p[1] = ' ';
        } else if (p[0] == '/' && p[1] == '/') {
            for (; *p && *p != '\n'; p++)
                *p = ' ';
            if (!*p)
                break;
        }
    }
    int line = 1;
    char tc[256] = "";
    char *p = s;
    while (*p) {
        while (*p && isspace((unsigned char)*p)) {
            if (*p == '\n')
                line++;
            p++;
        }
        if (!*p)
            break;
        if (strncmp(p, "testcase", 8) == 0 && isspace((unsigned char)p[8])) {
            p += 8;
            while (isspace((unsigned char)*p))
                p++;
            size_t k = 0;
            while (*p && !isspace((unsigned char)*p) && *p != '{' && k + 1 < sizeof tc)
                tc[k++] = *p++;
            tc[k] = '\0';
            while (*p && *p != '{')
                p++;
            if (*p)
                p++;
            continue;
        }
        if (*p == '}') {
            p++;
            tc[0] = '\0';
            continue;
        }
        char *end = strchr(p, ';');
        if (!end)
            break;
        *end = '\0';
        int start_line = line;
        for (char *q = p; q < end; q++)
            if (*q == '\n')
                line++;
        parse_statement(set, file, tc, start_line, p);
        p = end + 1;
    }
    free(s);
    return set->n - before;
}

static int same(double x, double y) { return x == y || (isnan(x) && isnan(y)); }

/* Judges one result: 0 violation, 1 contained, 2 contained and tight. */
static int judge(const itl_test *t, const double *r, int ftz) {
    double lo = r[0], hi = r[1];
    if (t->op == ORACLE_MID) {
        if (isnan(t->elo))
            return isnan(lo) ? 2 : 0;
        if (lo == t->elo)
            return 2;
        if (ftz && fabs(lo - t->elo) <= DBL_MIN) /* a build that flushes has no subnormal midpoint */
            return 1;
        return llabs(oracle_steps(t->elo, lo, 53)) <= 1 ? 1 : 0;
    }
    if (t->op == ORACLE_WIDTH) {
        if (isnan(t->ehi) && !(t->k.a.lo <= t->k.a.hi))
            return lo == 0 ? 1 : 0; /* by design ia_width(empty) = 0, not NaN: counted, not tight */
        return lo == t->ehi ? 2 : lo >= t->ehi ? 1 : 0;
    }
    int e_empty = !(t->elo <= t->ehi);
    if (e_empty)
        return lo == INFINITY && hi == -INFINITY ? 2 : isnan(lo) || isnan(hi) ? 0 : 1;
    if (!(lo <= t->elo && hi >= t->ehi))
        return 0;
    return same(lo, t->elo) && same(hi, t->ehi) ? 2 : 1;
}

TEST(ia_itf1788) {
    static const char *files[] = {
        "libieeep1788_elem.itl", "mpfi.itl", "fi_lib.itl", "c-xsc.itl", "libieeep1788_num.itl", "libieeep1788_set.itl"};
    itl_set set;
    memset(&set, 0, sizeof set);
    char path[1024], line[1024];
    size_t len = 0;
    for (size_t f = 0; f < sizeof files / sizeof files[0]; f++) {
        snprintf(path, sizeof path, "%s/tests/data/itf1788/%s", test_source_dir(), files[f]);
        long n = parse_file(&set, path, files[f]);
        CHECK(n >= 0, "cannot read %s", path);
        len += (size_t)snprintf(line + len, sizeof line - len, " %s %ld", files[f], n);
    }
    test_note("tests run per file:%s; skipped: %ld decorated/NaI, %ld of ops ia/ lacks, %ld malformed", line,
              set.skipped_dec, set.skipped_op, set.skipped_other);
    CHECK(set.n > 1000, "only %ld ITF1788 tests parsed", set.n);

    long run[ORACLE_NOPS] = {0}, cont[ORACLE_NOPS] = {0}, tight[ORACLE_NOPS] = {0}, dtight[ORACLE_NOPS] = {0};
    char first[1024] = "";
    long bad = 0;
    int flushes = FP_NAME(ia_dev_flushes)(0);
    for (int op = 0; op < ORACLE_NOPS; op++) {
        long m = 0;
        for (long i = 0; i < set.n; i++)
            m += set.v[i].op == op;
        if (!m)
            continue;
        ia_case *k = malloc(sizeof *k * (size_t)m);
        itl_test **t = malloc(sizeof *t * (size_t)m);
        double *host = malloc(sizeof *host * 2 * (size_t)m), *dev = malloc(sizeof *dev * 2 * (size_t)m);
        CHECK(k && t && host && dev, "out of memory");
        long j = 0;
        for (long i = 0; i < set.n; i++)
            if (set.v[i].op == op) {
                t[j] = &set.v[i];
                k[j] = set.v[i].k;
                ia_apply(op, &k[j], host + 2 * j);
                if (flushes) /* as the device must be given it: its result must still contain the expected one */
                    case_flushed(&k[j], &k[j]);
                j++;
            }
        char err[1024];
        int have_dev = FP_NAME(ia_dev_ops)(0, op, k, m, dev, err, sizeof err) == 0;
        if (!have_dev) {
            free(k), free(t), free(host), free(dev), free(set.v);
            CHECK(0, "%s", err);
        }
        for (j = 0; j < m; j++) {
            int h = judge(t[j], host + 2 * j, 0), d = judge(t[j], dev + 2 * j, flushes);
            run[op]++;
            cont[op] += h > 0;
            tight[op] += h == 2;
            dtight[op] += d == 2;
            if (getenv("IACSG_ITF_VERBOSE") && (h != 2 || d != 2))
                printf("    %s:%d: %s [%a, %a] [%a, %a] n=%d expected [%a, %a], host [%a, %a], device [%a, %a]\n",
                       t[j]->file, t[j]->line, oracle_op_name[op], k[j].a.lo, k[j].a.hi, k[j].b.lo, k[j].b.hi, k[j].n,
                       t[j]->elo, t[j]->ehi, host[2 * j], host[2 * j + 1], dev[2 * j], dev[2 * j + 1]);
            if ((h == 0 || d == 0) && !bad++)
                snprintf(first, sizeof first,
                         "%s:%d: %s [%a, %a] [%a, %a] n=%d expected [%a, %a], host [%a, %a], device [%a, %a]",
                         t[j]->file, t[j]->line, oracle_op_name[op], k[j].a.lo, k[j].a.hi, k[j].b.lo, k[j].b.hi, k[j].n,
                         t[j]->elo, t[j]->ehi, host[2 * j], host[2 * j + 1], dev[2 * j], dev[2 * j + 1]);
        }
        free(k), free(t), free(host), free(dev);
    }
    free(set.v);
    long tr = 0, tc = 0, tt = 0;
    for (int op = 0; op < ORACLE_NOPS; op++) {
        if (!run[op])
            continue;
        test_note("%-12s run %4ld  contained %4ld  tight %4ld (device tight %4ld)", oracle_op_name[op], run[op],
                  cont[op], tight[op], dtight[op]);
        tr += run[op], tc += cont[op], tt += tight[op];
    }
    test_note("all: run %ld, contained %ld, tight %ld", tr, tc, tt);
    CHECK(bad == 0, "%ld results do not contain the expected interval; first: %s", bad, first);
}
