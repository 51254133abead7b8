/* ia/elem.h -- exp, log, sin, cos, tan, atan, pow: the platform's function at the end points, widened by its
 * documented error (ia/round.h), with interior extrema located by rigorous bounds on pi. Contract: ia/ia.h. */
#ifndef IA_ELEM_H
#define IA_ELEM_H
#include "arith.h"

/* pi and 1/pi: the neighbouring floats on either side of the real number. */
#ifdef IA_FP64
#define IA_PI_LO 0x1.921fb54442d18p+1
#define IA_PI_HI 0x1.921fb54442d19p+1
#define IA_INVPI_LO 0x1.45f306dc9c882p-2
#define IA_INVPI_HI 0x1.45f306dc9c883p-2
#else
#define IA_PI_LO 0x1.921fb4p+1f
#define IA_PI_HI 0x1.921fb6p+1f
#define IA_INVPI_LO 0x1.45f306p-2f
#define IA_INVPI_HI 0x1.45f308p-2f
#endif

/* exp(a): increasing, result >= 0. Empty stays empty; exp(-inf) = 0, exp(+inf) = +inf. */
IA_FN ia_interval ia_exp(ia_interval a) {
    if (ia_is_empty(a))
        return a;
    return ia_make(fmax(ia_lo_k(exp(a.lo), IA_ULP_EXP), (ia_real)0), ia_hi_k(exp(a.hi), IA_ULP_EXP));
}

/* log(a) on its domain (0, +inf]: a is clipped to it; a <= 0 entirely (including [0,0]) gives empty, and a
 * lower bound <= 0 gives -inf. */
IA_FN ia_interval ia_log(ia_interval a) {
    if (ia_is_empty(a) || a.hi <= 0)
        return ia_empty();
    ia_real lo = a.lo <= 0 ? -IA_INF : ia_lo_k(log(a.lo), IA_ULP_LOG);
    return ia_make(lo, ia_hi_k(log(a.hi), IA_ULP_LOG));
}

/* Which integers the real interval a/pi - shift may contain: bit 0 set for an even one, bit 1 for an odd one.
 * The quotient is enclosed outward, so an integer that is merely possible counts; the extremum it adds is then
 * within rounding of an end point's value, so tightness does not suffer. */
IA_FN int ia__pi_multiples(ia_interval a, ia_real shift) {
    ia_interval q = ia_add_r(ia_mul(a, ia_make(IA_INVPI_LO, IA_INVPI_HI)), -shift);
    ia_real m0 = ceil(q.lo), m1 = floor(q.hi);
    if (m0 > m1)
        return 0;
    if (m1 - m0 >= 1)
        return 3;
    return fmod(m0, (ia_real)2) == 0 ? 1 : 2;
}

/* Settles which critical points a contains from the signs of the derivative at its ends (cos for sin, -sin
 * for cos; its zeros are pi apart and simple), for a shorter than 2 pi: a sign change means exactly one zero
 * (a maximum if the derivative falls, a minimum if it rises); no change means none if a is shorter than pi,
 * two (a maximum and a minimum) if it is at least pi long. The sign of a computed cos or sin is exact when
 * nonzero: |sin x| and |cos x| exceed 2^-70 at every float and double x, far above any error bound.
 * Returns the bits of ia__pi_multiples (1: a maximum, 2: a minimum), or -1 when undecided. This is what keeps
 * huge arguments tight, where a / pi cannot be enclosed to within one integer. */
IA_FN int ia__critical(ia_interval a, ia_real d_lo, ia_real d_hi) {
    if (d_lo == 0 || d_hi == 0 || !(ia_hi(a.hi - a.lo) < 2 * IA_PI_LO))
        return -1;
    if ((d_lo > 0) != (d_hi > 0))
        return d_lo > 0 ? 1 : 2;
    if (ia_hi(a.hi - a.lo) < IA_PI_LO)
        return 0;
    return ia_lo(a.hi - a.lo) >= IA_PI_HI ? 3 : -1;
}

/* cos or sin of a, given the end point values, whose maxima (value 1) sit where a/pi - shift is an even
 * integer and minima (value -1) where it is odd: cos has shift 0, sin has shift 1/2. */
IA_FN ia_interval ia__sincos(ia_interval a, ia_real f_lo, ia_real f_hi, ia_real shift) {
    int hits = ia__pi_multiples(a, shift);
    if (hits != 0) { /* maybe an extremum: check the derivative (cos for sin, -sin for cos) */
        int c = shift == 0 ? ia__critical(a, -sin(a.lo), -sin(a.hi)) : ia__critical(a, cos(a.lo), cos(a.hi));
        if (c >= 0)
            hits = c;
    }
    ia_real lo = hits & 2 ? (ia_real)-1 : ia_lo_k(fmin(f_lo, f_hi), IA_ULP_SINCOS);
    ia_real hi = hits & 1 ? (ia_real)1 : ia_hi_k(fmax(f_lo, f_hi), IA_ULP_SINCOS);
    return ia_make(fmax(lo, (ia_real)-1), fmin(hi, (ia_real)1));
}

/* cos(a). Empty stays empty; an unbounded a gives [-1, 1]. */
IA_FN ia_interval ia_cos(ia_interval a) {
    if (ia_is_empty(a))
        return a;
    if (a.lo == -IA_INF || a.hi == IA_INF)
        return ia_make(-1, 1);
    return ia__sincos(a, cos(a.lo), cos(a.hi), 0);
}

/* sin(a). Empty stays empty; an unbounded a gives [-1, 1]. */
IA_FN ia_interval ia_sin(ia_interval a) {
    if (ia_is_empty(a))
        return a;
    if (a.lo == -IA_INF || a.hi == IA_INF)
        return ia_make(-1, 1);
    return ia__sincos(a, sin(a.lo), sin(a.hi), (ia_real)0.5);
}

/* tan(a): increasing between poles; an interval that may contain a pole (pi/2 + k pi) gives entire, the hull of
 * the two unbounded branches. Empty stays empty; an unbounded a gives entire. */
IA_FN ia_interval ia_tan(ia_interval a) {
    if (ia_is_empty(a))
        return a;
    if (a.lo == -IA_INF || a.hi == IA_INF)
        return ia_entire();
    /* poles are the zeros of cos; if the quotient test cannot exclude one, the signs of cos can */
    if (ia__pi_multiples(a, (ia_real)0.5) != 0 && ia__critical(a, cos(a.lo), cos(a.hi)) != 0)
        return ia_entire();
    return ia_make(ia_lo_k(tan(a.lo), IA_ULP_TAN), ia_hi_k(tan(a.hi), IA_ULP_TAN));
}

/* atan(a): increasing, inside [-pi/2, pi/2] (bounded by the rigorous pi/2). Empty stays empty. */
IA_FN ia_interval ia_atan(ia_interval a) {
    if (ia_is_empty(a))
        return a;
    ia_real half_pi = IA_PI_HI * (ia_real)0.5;
    return ia_make(fmax(ia_lo_k(atan(a.lo), IA_ULP_ATAN), -half_pi), fmin(ia_hi_k(atan(a.hi), IA_ULP_ATAN), half_pi));
}

/* a^b for real exponents, on the domain of IEEE 1788 pow: x > 0, or x = 0 with y > 0. a is clipped to
 * [0, +inf); a wholly negative, or a = [0,0] with b <= 0, gives empty. x^y is monotone in x for each y and in y
 * for each x, so the range over the box is the hull of the four corners (C's pow gives the right limits at 0
 * and infinity: 0^-1 = inf, inf^-1 = 0, 0^0 = 1 = the limit along x > 0). */
IA_FN ia_interval ia_pow(ia_interval a, ia_interval b) {
    if (ia_is_empty(a) || ia_is_empty(b) || a.hi < 0)
        return ia_empty();
    ia_real xlo = fmax(a.lo, (ia_real)0), xhi = a.hi;
    if (xhi == 0) /* only x = 0, so only y > 0 is in the domain */
        return b.hi > 0 ? ia_make(0, 0) : ia_empty();
    ia_real c1 = pow(xlo, b.lo), c2 = pow(xlo, b.hi), c3 = pow(xhi, b.lo), c4 = pow(xhi, b.hi);
    ia_real lo = fmin(fmin(c1, c2), fmin(c3, c4)), hi = fmax(fmax(c1, c2), fmax(c3, c4));
    return ia_make(fmax(ia_lo_k(lo, IA_ULP_POW), (ia_real)0), ia_hi_k(hi, IA_ULP_POW));
}

#endif
