/* ia/elem.h -- exp, log, sin, cos, tan, atan, pow: the platform's function at the end points, widened by its
 * documented error (ia/round.h), with interior extrema located by rigorous bounds on pi; float sin and cos on a
 * device with double: their own argument reduction and kernels in double (below). Contract: ia/ia.h. */
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

#ifdef IA_DEVICE_DOUBLE
/* Float exp on the device from a reduction and a polynomial in double, where the device has double: PoCL's vector
 * exp differs from its scalar one in some lanes, so ia/vec.h ran exp lane by lane, 46 % of the sigmoid blend's
 * render (Fig. 8); these operations, the same over lanes (ia/vec.h: iav_exp), give both the same bits, within a
 * step or two of the exact bound where the platform's, widened by its 3 ulps, were up to 12.
 *
 * x is clamped to [IA__EXP_FLOOR, IA__EXP_CEIL], outside which e^x is under half the smallest subnormal or over
 * 2^128 (the bounds below are then 0 and the next float up, or MAX and +inf, as they must). There x = k ln2 + r
 * with k = rint(x / ln2) (|k| <= 160) and r = (x - k L1) - k L2, where L1 + L2 = ln 2 to within 2^-85 and L1 has
 * 32 significant bits (fdlibm's ln2HI, ln2LO): k L1 is exact, and so is x - k L1 (both on the grid of 2^-32 where
 * k != 0, since then |x| > 1/4, and under 1 in size); k = 0 leaves r = x. So r is within 2^-53 |r| + 2^-76 of
 * x - k ln2, and |r| <= ln2/2 up to the rounding of x / ln2. e^r by its Taylor polynomial of degree 12 in Horner's
 * form: the remainder is under (ln2/2)^13/13! e^(ln2/2) < 2^-51 of e^r, the roundings under 26 ulps of double;
 * 2^k scales exactly. So v is within 2^-47 v of e^x, and v -+ 2^-40 v round outward to float (ia__float_below,
 * ia__float_above). */
#define IA__EXP_FLOOR (-110.0)
#define IA__EXP_CEIL 100.0
#define IA__LN2_HI 6.93147180369123816490e-01
#define IA__LN2_LO 1.90821492927058770002e-10
#define IA__INV_LN2 1.44269504088896338700e+00
/* The polynomial, for a double or a vector of doubles (ia/vec.h). */
#define IA__EXP_POLY(r)                                                                                          \
    (1 + (r) * (1 + (r) * (1.0 / 2 + (r) * (1.0 / 6 + (r) * (1.0 / 24 + (r) * (1.0 / 120 + (r) * (1.0 / 720 +        \
     (r) * (1.0 / 5040 + (r) * (1.0 / 40320 + (r) * (1.0 / 362880 + (r) * (1.0 / 3628800 +                        \
     (r) * (1.0 / 39916800 + (r) * (1.0 / 479001600)))))))))))))
/* e^x in double as above (x clamped), and e^x rounded to nearest float: the emitted point code's (ia_exp_point),
 * so that a point's value lies in ia_exp's bounds over any interval holding the point. */
IA_FN double ia__exp_double(ia_real x) {
    double c = fmin(fmax((double)x, IA__EXP_FLOOR), IA__EXP_CEIL), k = rint(c * IA__INV_LN2);
    double r = (c - k * IA__LN2_HI) - k * IA__LN2_LO;
    return IA__EXP_POLY(r) * as_double((long)((int)k + 1023) << 52);
}
IA_FN ia_real ia_exp_point(ia_real x) { return (ia_real)ia__exp_double(x); }
#define IA__EXP_PAD 0x1p-40
#else
IA_FN ia_real ia_exp_point(ia_real x) { return exp(x); }
#endif

/* exp(a): increasing, result >= 0. Empty stays empty; exp(-inf) = 0, exp(+inf) = +inf. */
IA_FN ia_interval ia_exp(ia_interval a) {
    if (ia_is_empty(a))
        return a;
#ifdef IA_DEVICE_DOUBLE
    double lo = ia__exp_double(a.lo), hi = ia__exp_double(a.hi);
    return ia_make(fmax(ia__float_below(lo - lo * IA__EXP_PAD), (ia_real)0), ia__float_above(hi + hi * IA__EXP_PAD));
#else
    return ia_make(fmax(ia_lo_k(exp(a.lo), IA_ULP_EXP), (ia_real)0), ia_hi_k(exp(a.hi), IA_ULP_EXP));
#endif
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

#ifdef IA_DEVICE_DOUBLE
/* Float sin and cos on the device from one argument reduction in double per end point, where the device has double.
 * PoCL's float cos spent as much in its argument reduction as in its polynomial, each interval took two calls
 * (four where an extremum might lie inside), and the level-set scene icos.csg spent 40 % of its render there;
 * with these, and no branch on the data, its command takes a third less CPU (3.4-3.6 -> 2.3 s, alternated runs).
 *
 * For |x| <= IA__REDUCED_MAX, x = k pi/2 + r with k = rint(x 2/pi) and r = (x - k P1) - k P2, where
 * P1 + P2 = pi/2 to within 2^-86 and P1 has 33 significant bits (fdlibm's pio2_1, pio2_1t): k P1 is exact for
 * |k| < 2^20, so r is off by at most 2^-52 |r| + 2^-66 (two roundings, k P2's rounding and the tail, both 0
 * when k = 0, where r = x exactly); |r| <= pi/4 but for the rounding of x 2/pi. sin r and cos r are fdlibm's
 * kernels (k_sin.c, k_cos.c: within 2^-58 on |r| <= pi/4), and their Horner sums add a few ulps of double. So
 * the double value v of sin or cos at x is within 2^-49 |v| + 2^-66 (|v| >= 0.9 |r| or >= 0.7), and
 * v -+ (2^-45 |v| + 2^-64) (the absolute term only for k != 0) round outward to float (RN, then one step
 * down where it landed above): bounds within an ulp of the exact value, where the platform's were 4 ulps wide. */
#define IA__REDUCED_MAX 0x1p19f
#define IA__PIO2_1 0x1.921fb544p+0
#define IA__PIO2_1T 0x1.0b4611a626331p-34
#define IA__INVPIO2 0x1.45f306dc9c883p-1

/* The reduction of x (a double of at most 2^20 in magnitude): r, and k as the return value. */
IA_FN int ia__reduce(double x, double *r) {
    double k = rint(x * IA__INVPIO2);
    *r = (x - k * IA__PIO2_1) - k * IA__PIO2_1T;
    return (int)k;
}

/* fdlibm's polynomials in z = r^2 of its sin and cos kernels, for a double or a vector of doubles (ia/vec_sincos.h):
 * sin r = r + r z IA__SIN_POLY(z), cos r = (1 - z/2) + z^2 IA__COS_POLY(z). */
#define IA__SIN_POLY(z)                                                                                          \
    (-1.66666666666666324348e-01 +                                                                             \
     (z) * (8.33333333332248946124e-03 +                                                                       \
            (z) * (-1.98412698298579493134e-04 +                                                               \
                   (z) * (2.75573137070700676789e-06 +                                                         \
                          (z) * (-2.50507602534068634195e-08 + (z) * 1.58969099521155010221e-10)))))
#define IA__COS_POLY(z)                                                                                          \
    (4.16666666666666019037e-02 +                                                                              \
     (z) * (-1.38888888888741095749e-03 +                                                                      \
            (z) * (2.48015872894767294178e-05 +                                                                \
                   (z) * (-2.75573143513906633035e-07 +                                                        \
                          (z) * (2.08757232129817482790e-09 + (z) * -1.13596475577881948265e-11)))))

/* sin r and cos r in double (fdlibm's kernels). */
IA_FN void ia__sincos_kernels(double r, double *sin_r, double *cos_r) {
    double z = r * r, ps = IA__SIN_POLY(z), pc = IA__COS_POLY(z);
    *sin_r = r + r * z * ps;
    *cos_r = (1.0 - 0.5 * z) + z * z * pc;
}

/* cos(q pi/2 + r) from sin r and cos r: a choice, not a branch (mispredicted half the time). For sin x, take
 * q = k - 1 (sin x = cos(x - pi/2)). */
IA_FN double ia__quadrant_cos(int q, double sin_r, double cos_r) {
    double v = q & 1 ? sin_r : cos_r;
    return (q & 3) == 1 || (q & 3) == 2 ? -v : v;
}

/* cos (shift 0) or sin (shift 1) of k pi/2 + r, in double. */
IA_FN double ia__sincos_value(int k, double r, int shift) {
    double sin_r, cos_r;
    ia__sincos_kernels(r, &sin_r, &cos_r);
    return ia__quadrant_cos(k - shift, sin_r, cos_r);
}

/* The float bounds below lo and above hi, padded by their error bounds, clipped to [-1, 1]. */
IA_FN ia_interval ia__sincos_bounds(double lo, double hi, double pad_lo, double pad_hi) {
    ia_real f_lo = ia__float_below(lo - pad_lo), f_hi = ia__float_above(hi + pad_hi);
    return ia_make(f_lo < -1 ? (ia_real)-1 : f_lo, f_hi > 1 ? (ia_real)1 : f_hi);
}

/* The pad of a value v computed from a reduction with quotient k. */
IA_FN double ia__sincos_pad(double v, int k) { return fabs(v) * 0x1p-45 + (k != 0 ? 0x1p-64 : 0.0); }

/* Whether the integers first..last hold one of m - shift = 0 mod 4 (bit 1) or 2 mod 4 (bit 2). */
IA_FN int ia__quadrant_extrema(int first, int last, int shift) {
    if (last - first >= 3)
        return 3;
    int hits = 0;
    for (int m = first; m <= last; m++) /* at most three */
        hits |= (0x201 >> (((m - shift) & 3) * 4)) & 3; /* 0 -> 1 (a maximum), 2 -> 2 (a minimum), else 0 */
    return hits;
}

/* The parts below, inlined where they are used: called, the reduced points went through memory. */
#define IA__INLINE IA_FN __attribute__((always_inline))

/* x reduced (ia__reduce) with sin r and cos r: what cos and sin at x are both made of. */
typedef struct {
    int k;
    double r, sin_r, cos_r;
} ia__reduced;
IA__INLINE ia__reduced ia__reduced_at(double x) {
    ia__reduced p;
    p.k = ia__reduce(x, &p.r);
    ia__sincos_kernels(p.r, &p.sin_r, &p.cos_r);
    return p;
}

/* cos (shift 0) or sin (shift 1) of a, both ends within IA__REDUCED_MAX, from its ends' values. The extrema lie
 * where x / (pi/2) is an integer m: a maximum where m - shift = 0 mod 4, a minimum where it is 2 mod 4.
 * a.lo / (pi/2) = k + r 2/pi, so the first such integer in a is k, or k + 1 where r > 0; the last likewise; an end
 * whose r is within r's error of 0 counts its k (an extremum that is merely possible: the bound it sets is within
 * rounding of the end's). */
IA__INLINE ia_interval ia__sincos_ends_of(ia__reduced e0, ia__reduced e1, int shift) {
    int k0 = e0.k, k1 = e1.k;
    int hits = ia__quadrant_extrema(k0 + (e0.r > 0x1p-60 ? 1 : 0), k1 - (e1.r < -0x1p-60 ? 1 : 0), shift);
    double v0 = ia__quadrant_cos(k0 - shift, e0.sin_r, e0.cos_r), v1 = ia__quadrant_cos(k1 - shift, e1.sin_r, e1.cos_r);
    int first_low = v0 <= v1;
    double lo = first_low ? v0 : v1, hi = first_low ? v1 : v0;
    ia_interval b =
        ia__sincos_bounds(lo, hi, ia__sincos_pad(lo, first_low ? k0 : k1), ia__sincos_pad(hi, first_low ? k1 : k0));
    return ia_make(hits & 2 ? (ia_real)-1 : b.lo, hits & 1 ? (ia_real)1 : b.hi);
}
IA_FN ia_interval ia__sincos_ends(ia_interval a, int shift) {
    return ia__sincos_ends_of(ia__reduced_at(a.lo), ia__reduced_at(a.hi), shift);
}

/* The same for a narrow a (half-width at most IA__NARROW), from one reduction at its midpoint m: with f = cos or
 * sin, f(m + h) = f(m) cos h + f'(m) sin h, and for |h| <= d, cos h is in [1 - d^2/2, 1] and |sin h| is at most
 * S = d - d^3/6 + d^5/120. Taken apart, the two products overestimate the range by at most |f(m)| d^2/2 (under
 * 2^-25 of |f(m)|, for d <= 2^-12) and |f(m)| d^4/24 + |f'(m)| d^5/120 (absolute): tight where a bound is not much
 * smaller than |f(m)| + |f'(m)| S, but near a zero of f the sum cancels, the absolute terms and the double's
 * roundings then count, and the end points are taken instead (returns lo = -2). S's rounding is in the pad. Half the
 * cost of the end points: icos.csg's narrow nodes and Newton's point evaluations. */
#define IA__NARROW 0x1p-12
IA_FN double ia__sincos_mid_point(ia_interval a) { return 0.5 * ((double)a.lo + (double)a.hi); } /* any point */
IA_FN double ia__sincos_mid_half(ia_interval a, double m) {
    return fmax((double)a.hi - m, m - (double)a.lo) * (1 + 0x1p-50);
}
IA__INLINE ia_interval ia__sincos_mid_of(ia__reduced c, double d, int shift) {
    double z = d * d;
    int k = c.k;
    double v = ia__quadrant_cos(k - shift, c.sin_r, c.cos_r), low = v * (1 - 0.5 * z);
    double slope =
        fabs(ia__quadrant_cos(k - shift + 1, c.sin_r, c.cos_r)) * (d * (1 - z * (1.0 / 6 - z * (1.0 / 120))));
    double lo = (v < low ? v : low) - slope, hi = (v < low ? low : v) + slope, size = fabs(v) + slope;
    if (fmin(fabs(lo), fabs(hi)) < size * 0x1p-10)
        return ia_make(-2, -2);
    return ia__sincos_bounds(lo, hi, ia__sincos_pad(size, k), ia__sincos_pad(size, k));
}
IA_FN ia_interval ia__sincos_mid(ia_interval a, int shift) {
    double m = ia__sincos_mid_point(a);
    return ia__sincos_mid_of(ia__reduced_at(m), ia__sincos_mid_half(a, m), shift);
}

/* cos (shift 0) or sin (shift 1) at a point, by the same reduction and kernels rounded to nearest: the emitted
 * point code's (ia_cos_point, ia_sin_point), so that a point's value lies in the interval functions' bounds over
 * any interval holding the point (as the platform's cos within the platform's widening did). */
IA_FN ia_real ia__sincos_point(ia_real x, int shift) {
    double r;
    int k = ia__reduce(x, &r);
    return (ia_real)ia__sincos_value(k, r, shift);
}

/* cos (shift 0) or sin (shift 1) of a nonempty bounded a, by one of the above, or -2 in lo where neither applies. */
IA_FN ia_interval ia__sincos_reduced(ia_interval a, int shift) {
    if (!(fabs(a.lo) <= IA__REDUCED_MAX && fabs(a.hi) <= IA__REDUCED_MAX))
        return ia_make(-2, -2);
    if ((double)a.hi - (double)a.lo <= 2 * IA__NARROW) {
        ia_interval c = ia__sincos_mid(a, shift);
        if (c.lo != -2)
            return c;
    }
    return ia__sincos_ends(a, shift);
}

/* sin (*s) and cos (*c) of a as ia__sincos_reduced computes each, from one reduction for both: the derivative of
 * one is the other. 0 where neither way applies. */
IA_FN int ia__sin_cos_reduced(ia_interval a, ia_interval *s, ia_interval *c) {
    if (!(fabs(a.lo) <= IA__REDUCED_MAX && fabs(a.hi) <= IA__REDUCED_MAX))
        return 0;
    *s = *c = ia_make(-2, -2); /* not yet */
    if ((double)a.hi - (double)a.lo <= 2 * IA__NARROW) {
        double m = ia__sincos_mid_point(a), d = ia__sincos_mid_half(a, m);
        ia__reduced p = ia__reduced_at(m);
        *s = ia__sincos_mid_of(p, d, 1);
        *c = ia__sincos_mid_of(p, d, 0);
        if (s->lo != -2 && c->lo != -2)
            return 1;
    }
    ia__reduced e0 = ia__reduced_at(a.lo), e1 = ia__reduced_at(a.hi);
    if (s->lo == -2)
        *s = ia__sincos_ends_of(e0, e1, 1);
    if (c->lo == -2)
        *c = ia__sincos_ends_of(e0, e1, 0);
    return 1;
}
#define IA_SINCOS_REDUCED 1
#endif

/* cos(a). Empty stays empty; an unbounded a gives [-1, 1]. */
IA_FN ia_interval ia_cos(ia_interval a) {
    if (ia_is_empty(a))
        return a;
    if (a.lo == -IA_INF || a.hi == IA_INF)
        return ia_make(-1, 1);
#ifdef IA_SINCOS_REDUCED
    ia_interval c = ia__sincos_reduced(a, 0);
    if (c.lo != -2)
        return c;
#endif
    return ia__sincos(a, cos(a.lo), cos(a.hi), 0);
}

/* cos and sin at a point, for the emitted point code: consistent with ia_cos and ia_sin (above). */
IA_FN ia_real ia_cos_point(ia_real x) {
#ifdef IA_SINCOS_REDUCED
    if (fabs(x) <= IA__REDUCED_MAX)
        return ia__sincos_point(x, 0);
#endif
    return cos(x);
}
IA_FN ia_real ia_sin_point(ia_real x) {
#ifdef IA_SINCOS_REDUCED
    if (fabs(x) <= IA__REDUCED_MAX)
        return ia__sincos_point(x, 1);
#endif
    return sin(x);
}

/* sin(a). Empty stays empty; an unbounded a gives [-1, 1]. */
IA_FN ia_interval ia_sin(ia_interval a) {
    if (ia_is_empty(a))
        return a;
    if (a.lo == -IA_INF || a.hi == IA_INF)
        return ia_make(-1, 1);
#ifdef IA_SINCOS_REDUCED
    ia_interval c = ia__sincos_reduced(a, 1);
    if (c.lo != -2)
        return c;
#endif
    return ia__sincos(a, sin(a.lo), sin(a.hi), (ia_real)0.5);
}

/* sin(a) into *s and cos(a) into *c, each as ia_sin and ia_cos return it, from one argument reduction where they
 * reduce in double: the emitted derivative along a ray needs sin beside cos of the same argument (implicits/emit.c). */
IA_FN void ia_sin_cos(ia_interval a, ia_interval *s, ia_interval *c) {
#ifdef IA_SINCOS_REDUCED
    if (!ia_is_empty(a) && a.lo != -IA_INF && a.hi != IA_INF && ia__sin_cos_reduced(a, s, c))
        return;
#endif
    *s = ia_sin(a);
    *c = ia_cos(a);
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

/* Where a^b (ia_pow) may be undefined over a box, from the bounds a and b of its operands (the lower ones; the
 * point code's points): a < 0, or a <= 0 with b <= 0; and where it is undefined over all of it (the upper ones): a
 * < 0, or a = 0 with b <= 0 (implicits/ops.def's columns, as C on the host and OpenCL C in the emitted code). In &
 * and |: b is often a constant, and clang warns of && and || with a constant operand when it builds a program
 * ("1 warning generated." on stderr). */
#define IA_POW_MAY_BE_UNDEFINED(a, b) (((a) < 0) | (((a) <= 0) & ((b) <= 0)))
#define IA_POW_UNDEFINED(a, b) (((a) < 0) | (((a) == 0) & ((b) <= 0)))

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
