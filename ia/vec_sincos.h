/* ia/vec_sincos.h -- iav_sin and iav_cos (OpenCL C, after ia/vec.h). Float intervals on a device that has double
 * take ia/elem.h's reduction in double in all lanes at once: the same operations in the same order, so every lane
 * holds the bits of ia_sin or ia_cos (tests/t_ia_vec_device_fp.c). Lane by lane, those cost a trigonometric shape
 * most of its render (a gyroid in a ball: ~1.4 s a 1024x1024 frame, six intervals' sin or cos an evaluation).
 * Elsewhere (double intervals, a device without double; the lanes beyond IA__REDUCED_MAX, infinite or NaN)
 * ia/'s scalar operation runs lane by lane.
 *
 * Stages, as ia__sincos_reduced: the lanes' narrow ones by one reduction at their midpoint (ia__sincos_mid_of),
 * where that declines or a lane is wide by the reductions of both ends (ia__sincos_ends_of), each computed only
 * where some lane needs it, then chosen lane by lane. iav_sin_cos takes both from the same reductions.
 *
 * Also sin and cos at points in lanes, iav_sin_point and iav_cos_point (as ia_sin_point, ia_cos_point), for the
 * emitted point code over lanes (P_f_gradv, the kernels' shading).
 */
#ifndef IA_VEC_SINCOS_H
#define IA_VEC_SINCOS_H
#include "vec.h"
#if IA_DEVICE && defined(IA_VW)

__attribute__((noinline)) static iav iav__sin_by_lane(iav a) {
    iav b = a;
    IAV_LANEWISE(ia_sin(A));
}
__attribute__((noinline)) static iav iav__cos_by_lane(iav a) {
    iav b = a;
    IAV_LANEWISE(ia_cos(A));
}

#ifdef IA_DEVICE_DOUBLE
#define iav__to_long IAV_CAT(convert_long, IA_VW)

/* x reduced in lanes (ia__reduced_at): k, r, sin r, cos r. */
typedef struct {
    iav__longv k;
    iav__doublev r, sin_r, cos_r;
} iav__reduced;
IAV_INLINE iav__reduced iav__reduced_at(iav__doublev x) {
    iav__reduced p;
    iav__doublev k = rint(x * IA__INVPIO2);
    p.r = (x - k * IA__PIO2_1) - k * IA__PIO2_1T;
    p.k = iav__to_long(k);
    iav__doublev z = p.r * p.r, ps = IA__SIN_POLY(z), pc = IA__COS_POLY(z);
    p.sin_r = p.r + p.r * z * ps;
    p.cos_r = (1.0 - 0.5 * z) + z * z * pc;
    return p;
}

/* ia__quadrant_cos in lanes. */
IAV_INLINE iav__doublev iav__quadrant_cos(iav__longv q, iav__doublev sin_r, iav__doublev cos_r) {
    iav__doublev v = select(cos_r, sin_r, (q & 1) != 0);
    return select(v, -v, ((q & 3) == 1) | ((q & 3) == 2));
}

/* ia__sincos_pad in lanes. */
IAV_INLINE iav__doublev iav__sincos_pad(iav__doublev v, iav__longv k) {
    return fabs(v) * 0x1p-45 + select((iav__doublev)0, (iav__doublev)0x1p-64, k != 0);
}

/* ia__sincos_bounds in lanes (ia__float_below and ia__float_above: RN, then a step out where it landed inside). */
IAV_INLINE iav iav__sincos_bounds(iav__doublev lo, iav__doublev hi, iav__doublev pad_lo, iav__doublev pad_hi) {
    ia_realv f_lo = iav__float_below(lo - pad_lo), f_hi = iav__float_above(hi + pad_hi);
    return iav_make(select(f_lo, IAV_R(-1), f_lo < -1), select(f_hi, IAV_R(1), f_hi > 1));
}

/* ia__sincos_mid_of in lanes: lo -2 in the lanes where it declines. */
IAV_INLINE iav iav__sincos_mid_of(iav__reduced c, iav__doublev d, int shift) {
    iav__doublev z = d * d;
    iav__doublev v = iav__quadrant_cos(c.k - shift, c.sin_r, c.cos_r), low = v * (1 - 0.5 * z);
    iav__doublev slope = fabs(iav__quadrant_cos(c.k - shift + 1, c.sin_r, c.cos_r)) *
                         (d * (1 - z * (1.0 / 6 - z * (1.0 / 120))));
    iav__doublev lo = select(low, v, v < low) - slope, hi = select(v, low, v < low) + slope, size = fabs(v) + slope;
    iav b = iav__sincos_bounds(lo, hi, iav__sincos_pad(size, c.k), iav__sincos_pad(size, c.k));
    ia_maskv declined = iav__to_mask(fmin(fabs(lo), fabs(hi)) < size * 0x1p-10);
    return iav_make(select(b.lo, IAV_R(-2), declined), select(b.hi, IAV_R(-2), declined));
}

/* ia__quadrant_extrema in lanes: of the integers first..last (at most three where fewer than 3 apart), bit 1 where
 * one has m - shift = 0 mod 4 (a maximum), bit 2 where one has 2 mod 4 (a minimum). */
IAV_INLINE iav__longv iav__quadrant_extrema(iav__longv first, iav__longv last, int shift) {
    iav__longv hits = (iav__longv)0;
    for (int j = 0; j < 3; j++) {
        iav__longv m = first + j, q = (m - shift) & 3;
        hits |= select((iav__longv)0, select((iav__longv)0, select((iav__longv)1, (iav__longv)2, q == 2), (q & 1) == 0),
                       m <= last);
    }
    return select(hits, (iav__longv)3, last - first >= 3);
}

/* ia__sincos_ends_of in lanes. */
IAV_INLINE iav iav__sincos_ends_of(iav__reduced e0, iav__reduced e1, int shift) {
    iav__longv first = e0.k + select((iav__longv)0, (iav__longv)1, e0.r > 0x1p-60);
    iav__longv last = e1.k - select((iav__longv)0, (iav__longv)1, e1.r < -0x1p-60);
    ia_maskv hits = iav__to_mask(iav__quadrant_extrema(first, last, shift));
    iav__doublev v0 = iav__quadrant_cos(e0.k - shift, e0.sin_r, e0.cos_r);
    iav__doublev v1 = iav__quadrant_cos(e1.k - shift, e1.sin_r, e1.cos_r);
    iav__longv first_low = v0 <= v1;
    iav__doublev lo = select(v1, v0, first_low), hi = select(v0, v1, first_low);
    iav b = iav__sincos_bounds(lo, hi, iav__sincos_pad(lo, select(e1.k, e0.k, first_low)),
                               iav__sincos_pad(hi, select(e0.k, e1.k, first_low)));
    return iav_make(select(b.lo, IAV_R(-1), (hits & 2) != 0), select(b.hi, IAV_R(1), (hits & 1) != 0));
}

/* sin (into *s where want_sin) and cos (*c where want_cos) of a whose lanes all lie within IA__REDUCED_MAX:
 * ia__sincos_reduced's choices, each point the lanes need (the midpoint of the narrow ones, both ends where that
 * declines or a lane is wide) reduced once for both. want_sin and want_cos are constants after inlining. */
IAV_INLINE void iav__sincos_reduced(iav a, int want_sin, int want_cos, iav *s, iav *c) {
    iav__doublev lo = iav__to_double(a.lo), hi = iav__to_double(a.hi);
    ia_maskv narrow = iav__to_mask(hi - lo <= 2 * IA__NARROW);
    *s = *c = iav_make(IAV_R(-2), IAV_R(-2));
    if (iav_any(narrow)) {
        iav__doublev m = 0.5 * (lo + hi), d = fmax(hi - m, m - lo) * (1 + 0x1p-50);
        iav__reduced p = iav__reduced_at(m);
        if (want_sin)
            *s = iav__pick(*s, iav__sincos_mid_of(p, d, 1), narrow);
        if (want_cos)
            *c = iav__pick(*c, iav__sincos_mid_of(p, d, 0), narrow);
    }
    ia_maskv ends_s = want_sin ? s->lo == -2 : (ia_maskv)0, ends_c = want_cos ? c->lo == -2 : (ia_maskv)0;
    if (iav_any(ends_s | ends_c)) {
        iav__reduced e0 = iav__reduced_at(lo), e1 = iav__reduced_at(hi);
        if (iav_any(ends_s))
            *s = iav__pick(*s, iav__sincos_ends_of(e0, e1, 1), ends_s);
        if (iav_any(ends_c))
            *c = iav__pick(*c, iav__sincos_ends_of(e0, e1, 0), ends_c);
    }
}

/* sin and cos as wanted (above): the lanes within IA__REDUCED_MAX (not NaN nor infinite) reduced in double, the
 * others by ia/'s scalar operation, lane by lane where any is left. */
IAV_INLINE void iav__sincos(iav a, int want_sin, int want_cos, iav *s, iav *c) {
    *s = *c = a; /* (every lane is set below) */
    ia_maskv reduces = fabs(a.lo) <= (ia_real)IA__REDUCED_MAX & fabs(a.hi) <= (ia_real)IA__REDUCED_MAX;
    if (iav_any(reduces))
        iav__sincos_reduced(iav_make(select(IAV_R(0), a.lo, reduces), select(IAV_R(0), a.hi, reduces)), want_sin,
                            want_cos, s, c);
    if (iav_any(~reduces)) {
        if (want_sin)
            *s = iav__pick(iav__sin_by_lane(a), *s, reduces);
        if (want_cos)
            *c = iav__pick(iav__cos_by_lane(a), *c, reduces);
    }
}
#else
IAV_INLINE void iav__sincos(iav a, int want_sin, int want_cos, iav *s, iav *c) {
    if (want_sin)
        *s = iav__sin_by_lane(a);
    if (want_cos)
        *c = iav__cos_by_lane(a);
}
#endif

IA_FN iav iav_sin(iav a) {
    iav s, unused;
    iav__sincos(a, 1, 0, &s, &unused);
    return s;
}
IA_FN iav iav_cos(iav a) {
    iav unused, c;
    iav__sincos(a, 0, 1, &unused, &c);
    return c;
}
/* Both, with the bits of iav_sin and iav_cos, from one reduction: the emitted code pairs a sin and a cos of one
 * argument (implicits/emit.c), as a gyroid's three arguments have. */
IA_FN void iav_sin_cos(iav a, iav *s, iav *c) { iav__sincos(a, 1, 1, s, c); }

/* cos (shift 0) or sin (shift 1) at points, as ia_cos_point and ia_sin_point: the lanes within IA__REDUCED_MAX by
 * ia__sincos_point's reduction and kernels in double, the others (and all where that reduction is not compiled)
 * lane by lane (ia/vec.h: IAV_POINT_LANEWISE), only where some lane needs it. */
IA_FN ia_realv iav__sin_point_by_lane(ia_realv a) {
    ia_realv b = a;
    IAV_POINT_LANEWISE(ia_sin_point(A));
}
IA_FN ia_realv iav__cos_point_by_lane(ia_realv a) {
    ia_realv b = a;
    IAV_POINT_LANEWISE(ia_cos_point(A));
}
IAV_INLINE ia_realv iav__sincos_point(ia_realv x, int shift) {
#ifdef IA_SINCOS_REDUCED
    ia_maskv far = ~(fabs(x) <= (ia_real)IA__REDUCED_MAX);
    iav__reduced p = iav__reduced_at(iav__to_double(select(x, IAV_R(0), far)));
    ia_realv v = iav__to_real(iav__quadrant_cos(p.k - shift, p.sin_r, p.cos_r));
    if (!iav_any(far))
        return v;
    return select(v, shift ? iav__sin_point_by_lane(x) : iav__cos_point_by_lane(x), far);
#else
    return shift ? iav__sin_point_by_lane(x) : iav__cos_point_by_lane(x);
#endif
}
IA_FN ia_realv iav_sin_point(ia_realv x) { return iav__sincos_point(x, 1); }
IA_FN ia_realv iav_cos_point(ia_realv x) { return iav__sincos_point(x, 0); }

#endif
#endif
