/* tests/oracle.h -- the MPFR oracle: exact values (to 256 bits, with a certified direction) of the real functions
 * that ia/ encloses, and exact containment and tightness decisions. Any test may reuse it.
 *
 * Points and bounds are passed as double: every float is a double, so one oracle serves both formats.
 * An evaluation returns the value rounded down at ORACLE_PREC bits and its ternary sign (0: exact, < 0: the true
 * value is above it). Because a bound has far fewer bits than ORACLE_PREC, the pair decides "lo <= y <= hi"
 * exactly; no tolerance is involved anywhere.
 */
#ifndef IACSG_ORACLE_H
#define IACSG_ORACLE_H
#include <mpfr.h>
#include <stdint.h>

#define ORACLE_PREC 256

/* The operations of ia/ (one list drives the host tests, the device kernel's numbering and the reports).
 * Kinds: UN  f(a);  BIN  f(a, b);  POWN  a^n;  REAL  f(a, c) for a real c;  NUM  real-valued (mid, width);
 *        QUERY  truth-valued;  SET  set operations (exact: hull, intersect). */
#define ORACLE_OPS(X)                                                                                                  \
    X(ADD, add, BIN)                                                                                                   \
    X(SUB, sub, BIN)                                                                                                   \
    X(MUL, mul, BIN)                                                                                                   \
    X(DIV, div, BIN)                                                                                                   \
    X(RECIP, recip, UN)                                                                                                \
    X(SQR, sqr, UN)                                                                                                    \
    X(POWN, pown, POWN)                                                                                                \
    X(POW, pow, BIN)                                                                                                   \
    X(SQRT, sqrt, UN)                                                                                                  \
    X(EXP, exp, UN)                                                                                                    \
    X(LOG, log, UN)                                                                                                    \
    X(SIN, sin, UN)                                                                                                    \
    X(COS, cos, UN)                                                                                                    \
    X(TAN, tan, UN)                                                                                                    \
    X(ATAN, atan, UN)                                                                                                  \
    X(NEG, neg, UN)                                                                                                    \
    X(ABS, abs, UN)                                                                                                    \
    X(MIN, min, BIN)                                                                                                   \
    X(MAX, max, BIN)                                                                                                   \
    X(HULL, hull, SET)                                                                                                 \
    X(INTERSECT, intersect, SET)                                                                                       \
    X(MID, mid, NUM)                                                                                                   \
    X(WIDTH, width, NUM)                                                                                               \
    X(ADD_R, add_r, REAL)                                                                                              \
    X(MUL_R, mul_r, REAL)                                                                                              \
    X(CNEG, certainly_neg, QUERY)                                                                                      \
    X(CPOS, certainly_pos, QUERY)                                                                                      \
    X(CZERO, contains_zero, QUERY)                                                                                     \
    X(ISEMPTY, is_empty, QUERY)                                                                                        \
    X(ISENTIRE, is_entire, QUERY)                                                                                      \
    X(CONTAINS, contains, QUERY)

enum {
#define X(NAME, name, kind) ORACLE_##NAME,
    ORACLE_OPS(X)
#undef X
        ORACLE_NOPS
};
enum { ORACLE_K_UN, ORACLE_K_BIN, ORACLE_K_POWN, ORACLE_K_REAL, ORACLE_K_NUM, ORACLE_K_QUERY, ORACLE_K_SET };

extern const char *const oracle_op_name[ORACLE_NOPS]; /* "add", ... as in ia_add */
extern const int oracle_op_kind[ORACLE_NOPS];

/* Widens MPFR's exponent range to the maximum (once; every entry point calls it). */
void oracle_init(void);

/* y = f(x, ...) rounded down at ORACLE_PREC bits, for the point functions of UN, BIN, POWN and REAL ops (x is
 * the point of a, yv the point of b or the real c, n the pown exponent). Returns 0 if the point is outside the
 * domain (1/0, log of x <= 0, sqrt of x < 0, pow off its domain: x > 0, or x = 0 with y > 0), else 1 with
 * *ternary < 0 when the exact value is above y, 0 when y is exact. y must be initialised with ORACLE_PREC. */
int oracle_eval(int op, double x, double yv, long n, mpfr_ptr y, int *ternary);

/* Whether the exact value (y, ternary) from oracle_eval lies in [lo, hi]; decided exactly. */
int oracle_in(mpfr_srcptr y, int ternary, double lo, double hi);

/* The libm function behind an elementary op, for ulp measurement: fn(x) or fn(x, y) rounded down, as above. */
enum {
    ORACLE_FN_DIV,
    ORACLE_FN_SQRT,
    ORACLE_FN_EXP,
    ORACLE_FN_LOG,
    ORACLE_FN_SIN,
    ORACLE_FN_COS,
    ORACLE_FN_TAN,
    ORACLE_FN_ATAN,
    ORACLE_FN_POW,
    ORACLE_NFNS
};
extern const char *const oracle_fn_name[ORACLE_NFNS];
void oracle_fn(int fn, double x, double yv, mpfr_ptr y);

/* The error of a computed r (of a format with `mant` bits of precision, 24 or 53, and smallest exponent of a
 * normal number emin: -125 or -1021 in MPFR's convention) relative to the exact y, in ulps of y (the spacing of
 * the format at |y|, which is the subnormal spacing below the normal range). r infinite or NaN: returns +inf
 * unless y is beyond the format's range on the same side (then 0). */
double oracle_ulp_error(double r, mpfr_srcptr y, int mant, int emin);

/* y rounded down or up (dir < 0, > 0) to float (mant = 24) or double (53), subnormals and overflow included. */
double oracle_round(mpfr_srcptr y, int dir, int mant);

/* The position of x in the ordered list of floats (mant 24) or doubles (53): steps(a, b) = the number of
 * format numbers stepped over from a to b, so 0 for equal, 1 for neighbours; +-0 count as one number. */
int64_t oracle_ord(double x, int mant);
/* oracle_ord(b) - oracle_ord(a) without overflow (saturated at +-INT64_MAX). */
int64_t oracle_steps(double a, double b, int mant);

/* "%a" of a double into a static ring of buffers (for failure messages with many numbers). */
const char *oracle_hex(double x);
/* y to 30 significant decimal digits, same ring. */
const char *oracle_str(mpfr_srcptr y);

#endif
