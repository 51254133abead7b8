/* ia/decimal.c -- decimal strings to enclosing intervals, through strtod/strtof under directed rounding
 * (glibc's conversions honour the current rounding mode, which makes each bound the correctly rounded one). */
#include "decimal.h"
#include <errno.h>
#include <fenv.h>
#include <stdlib.h>

/* No FENV_ACCESS pragma: GCC ignores it; the strto* calls are opaque, so nothing is moved across fesetround. */

static int whole_string_parsed(const char *s, const char *end) { return end != s && *end == '\0'; }

int ia_decimal_double(const char *s, double *lo, double *hi) {
    int saved = fegetround();
    char *end;
    fesetround(FE_DOWNWARD);
    double l = strtod(s, &end);
    fesetround(FE_UPWARD);
    double h = strtod(s, &end);
    fesetround(saved);
    if (!whole_string_parsed(s, end))
        return -1;
    *lo = l;
    *hi = h;
    return 0;
}

int ia_decimal_float(const char *s, float *lo, float *hi) {
    int saved = fegetround();
    char *end;
    fesetround(FE_DOWNWARD);
    float l = strtof(s, &end);
    fesetround(FE_UPWARD);
    float h = strtof(s, &end);
    fesetround(saved);
    if (!whole_string_parsed(s, end))
        return -1;
    *lo = l;
    *hi = h;
    return 0;
}
