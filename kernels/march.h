/* kernels/march.h -- a secondary ray's first root of F from off the surface it leaves, by marching
 * (effects_march), in SIMD lanes: the first-root path's effects (kernels/effects.cl, F the expression) and the
 * segment path's secondary rays (kernels/scene_rays.h, F the union of its regions, kernels/scene_union.h).
 * Needs packet.h and the emitted derivative code (PACKET_FDV: packet_Fdv over all of a union's groups).
 */
#ifndef KERNELS_MARCH_H
#define KERNELS_MARCH_H
#include "packet.h"

#define EFFECTS_MARCH_STEPS 32
#define EFFECTS_MARCH_FIRST 4096

/* How far a secondary ray starts off its hit p (at t along its ray): past the hit leaf's distance from the surface
 * (a few eps) and the rounding of the hit point (the frame's depth is float32; the host's: render_effects.c's
 * offset_of). Without it the shadow test sees acne (tests/t_render_effects_fp.c). */
static ia_realv effects_offset(ia_real eps, const ia_realv p[3], ia_realv t) {
    return 4 * eps + (ia_real)4e-6 * (1 + fabs(p[0]) + fabs(p[1]) + fabs(p[2]) + fabs(t));
}

/* The start so of a ray off the surface at p (at t along its ray), on the side its normal n faces: p + off n;
 * returns off (effects_offset). */
static ia_realv effects_off_surface(ia_real eps, const ia_realv p[3], ia_realv t, const ia_realv n[3], ia_realv so[3]) {
    ia_realv off = effects_offset(eps, p, t);
    for (int c = 0; c < 3; c++)
        so[c] = p[c] + off * n[c];
    return off;
}

/* The farthest end t of the rays of `lanes` (0 where there is none), by a tree of halves: stored and read back
 * lane by lane, the loads waited on the store's pieces (a third of effects_trace's CPU samples with transparency). */
static ia_real march_farthest(ia_realv t, ia_maskv lanes) {
    ia_realv v = select(IAV_R(0), t, lanes);
#if IA_VW == 16
    __typeof__(v.lo) v8 = fmax(v.lo, v.hi);
#else
    ia_realv v8 = v;
#endif
    __typeof__(v8.lo) v4 = fmax(v8.lo, v8.hi);
    __typeof__(v4.lo) v2 = fmax(v4.lo, v4.hi);
    return fmax((ia_real)0, fmax(v2.x, v2.y)); /* fmax passes NaN lanes over, as the loop did */
}

/* A march along rays that lie within the boxes of a tile's runs (tile.h: tile_layer_runs; a transparent layer's
 * rays, their starts `tau0` along their camera rays) in the lanes of `lanes`: they search the runs only. */
typedef struct {
    const tile_layer_runs *runs;
    ia_realv tau0;
    ia_maskv lanes;
} march_runs;

/* The first of the runs that ends past t (in the rays' own t, widened by the rounding of t's shift) in [lo, hi];
 * +inf where none does. */
static void march_next_run(const march_runs *m, ia_realv t, ia_realv *lo, ia_realv *hi) {
    *lo = *hi = IAV_R(IA_INF);
    for (int k = m->runs->n - 1; k >= 0; k--) {
        ia_real slack = (ia_real)4e-6 * (1 + fabs(m->runs->hi[k]));
        ia_realv rl = (m->runs->lo[k] - m->tau0) - slack, rh = (m->runs->hi[k] - m->tau0) + slack;
        ia_maskv ends_past = rh > t;
        *lo = select(*lo, rl, ends_past);
        *hi = select(*hi, rh, ends_past);
    }
}

/* A transparent layer's proven crossing, for the next layer on along the same line: in the lanes of `lanes` the
 * march proved F's root in its step [., b] unique (F' of one sign over it) and closed in on it by Newton, so the hit
 * leaf holds it and F is off 0 over (the leaf's end, b], with F at b in fb. In (effects_march): the lanes that start
 * at b with F there fb; out: the lanes whose hit is such a crossing's. */
typedef struct {
    ia_maskv lanes;
    ia_realv b;
    iav fb;
} march_crossing;

#ifdef PACKET_FDV
/* A secondary ray starts next to a surface it leaves (or crosses): bisection must halve its first nodes down to its
 * distance from that surface before one excludes it, some 2 log2(length / distance) evaluations, and then halve its way
 * down again to the next root. Instead the ray marches: from a (t_near on), one evaluation of packet_Fdv over [a, b]
 * gives F's enclosure there and the derivative F' along the ray, bounded (packet.h's theorem), so F over [a, b] lies in
 * the mean value form anchored at the start, F(a) + F' [0, b - a]. Where that (or F's enclosure) excludes 0, a moves to
 * b and the next step is 8 times as long; else a moves as far as the form excludes 0 (F(a) / |F'|: a step of Newton's
 * towards the root ahead, from below), and the next step is twice that; where it cannot move, the step shrinks
 * eightfold. F at the new a is enclosed by the same form (no evaluation; it is evaluated again where that enclosure
 * grew to hold 0). A step no longer than eps whose enclosures hold 0 is the hit leaf, as the walk's. Every part a
 * passes is proven root-free, so the leaf's start is never after the first root. Where the caller asks only `whether`
 * the ray meets a surface (an opaque shadow ray), a step over which F(a) and the form at b have certain, opposite signs
 * ends it too: F crosses 0 in it (the first root lies in [a, b]), so the steps that would close in on that root are
 * saved. For the other rays such a step (its slope then keeps one sign: the root is unique) is closed in on by interval
 * Newton with that slope, one point evaluation a step: a sphere's exit ray, 20.5 -> 17.6 evaluations (before: the
 * march's steps towards the root, two evaluations each). A step that is the rest of the ray is tried by F's enclosure
 * alone first (no slope is needed after it; most reflected and shadow rays leave the scene by it). The lanes still
 * marching after EFFECTS_MARCH_STEPS, or whose F' is unbounded, go on by the walk from their a. The first step is
 * EFFECTS_MARCH_FIRST times the start's distance from the surface `leaving`. Measured on the reference view (eps 1e-5;
 * evaluations per shadow ray, reflected ray, transparent layer): the walk alone (from the root of a tree as long as the
 * packet's rays) 14.8, 16.1, 49.8; marching only off the surface (each step proven whole or the walk) 5.5, 8.0, 28.9;
 * with the steps towards the root 3.9, 4.9, 15.7; the step after one towards the root sized by the bracket [c, e] 3.9,
 * 4.7, 14.4; with the crossings proven and closed in on by Newton 3.8, 4.5, 12.4; first steps of 1024 `leaving` 7.0,
 * 9.1, 28.4 (before the steps towards the root). The lanes of `runs` (NULL: none) step only inside its runs: a
 * step ends at the end of the run a is in, and from there a moves over the gap to the next run, where F is
 * evaluated afresh and the next step is that run's length (a transparent layer of the reference view, 9.67 ->
 * 5.34 evaluations); past the last run the lane is out. The lanes of `crossing` (NULL: none) start past a proven
 * crossing with F known there (no evaluation; the first step, in runs, the rest of the run), and it says on the way
 * out which hits are proven crossings (a layer of the reference view 5.34 -> 4.29 evaluations). */
static ia_maskv effects_march(const ia_realv o[3], const ia_realv d[3], ia_realv *t_near, ia_realv *t_far_io,
                              ia_maskv *going_io, ia_realv leaving, const march_runs *runs, march_crossing *crossing,
                              ia_real eps, int whether, iav time, ia_realv *hit_lo, ia_realv *hit_hi,
                              packet_index *evals) {
    ia_realv a = *t_near, t_far = *t_far_io, w = EFFECTS_MARCH_FIRST * leaving;
    ia_maskv going = *going_io & (a < t_far), hit = (ia_maskv)0, short_before = (ia_maskv)0;
    iav fa = iav_point(0), rates[3] = {iav_make(d[0], d[0]), iav_make(d[1], d[1]), iav_make(d[2], d[2])};
    ia_maskv known = (ia_maskv)0; /* the lanes whose F at a is known: past a proven crossing */
    ia_realv cross_b = a; /* the end of the step of each lane's crossing, and F there */
    iav cross_fb = fa;
    if (crossing) {
        known = going & crossing->lanes & (a == crossing->b) & ((crossing->fb.lo > 0) | (crossing->fb.hi < 0));
        fa = iav__pick(fa, crossing->fb, known);
    }
    ia_realv run_end = IAV_R(IA_INF); /* the end of the run a lies in (in a gap: a moves to the next run) */
    ia_maskv in_runs = runs ? going & runs->lanes : (ia_maskv)0;
    if (iav_any(in_runs)) {
        ia_realv run_lo;
        march_next_run(runs, a, &run_lo, &run_end);
        run_end = select(IAV_R(IA_INF), run_end, in_runs);
        known &= ~(in_runs & (run_lo > a)); /* moved on to the next run: F there unknown */
        a = select(a, fmax(a, run_lo), in_runs); /* +inf past the last run */
        w = select(w, run_end - a, known & in_runs);
        going &= a < t_far;
    }
    ia_maskv fresh = going & ~known, handed = (ia_maskv)0, proven = (ia_maskv)0;
    iav hs = iav_point(1); /* the handed lanes' slope over [a, t_far] */
    ia_maskv inside = (ia_maskv)0; /* the lanes that start inside a solid (F(a) < 0): a layer through it */
    ia_realv a0 = a, t_mid = IAV_R(IA_INF); /* their start, and where F' along them is 0 by the first step */
    /* the last two points of F of the handed lanes' Newton steps, for a secant; none before the first (f1 - f0 = 0:
     * no guess), and the first step's midpoint with the ray's start at F = 0 puts the second guess behind the part */
    ia_realv t0 = a, f0 = IAV_R(0), t1 = a, f1 = IAV_R(0);
    for (int step = 0; step < EFFECTS_MARCH_STEPS && iav_any(going); step++) {
        iav at_a = iav_make(a, a);
        if (iav_any(fresh)) { /* F at a, where its enclosure is not known or holds 0 */
            iav f0 = packet_F(~(ulong)0, packet_extent(o[0], d[0], at_a), packet_extent(o[1], d[1], at_a),
                              packet_extent(o[2], d[2], at_a), time);
            PACKET_COUNT(*evals, fresh);
            fa = iav_make(select(fa.lo, f0.lo, fresh), select(fa.hi, f0.hi, fresh));
        }
        if (step == 0) { /* a ray through a solid: a first step half as long, to read F's curvature off */
            inside = fa.hi < 0;
            w = select(w, w * (ia_real)0.5, inside);
        }
        ia_realv b = fmin(fmin(a + w, t_far), run_end);
        iav seg = iav_make(a, b), slope;
        ia_maskv rest = step > 0 ? going & (b >= t_far) : (ia_maskv)0;
        if (iav_any(rest)) {
            /* a step that is the rest of the ray: F's enclosure alone may prove it (no F at b is needed after
             * it), at about half the cost of packet_Fdv's; the lanes it fails take the step by Fdv. Tried lane by
             * lane, so that a ray takes the same steps alone as in a packet (test effects_march_lanes_alone) */
            iav fr = packet_F(~(ulong)0, packet_extent(o[0], d[0], seg), packet_extent(o[1], d[1], seg),
                              packet_extent(o[2], d[2], seg), time);
            PACKET_COUNT(*evals, rest);
            ia_maskv out = rest & ((fr.lo > 0) | (fr.hi < 0));
            a = select(a, b, out);
            going &= ~out;
            if (!iav_any(going))
                break;
        }
        iav f = packet_Fdv(~(ulong)0, packet_extent(o[0], d[0], seg), packet_extent(o[1], d[1], seg),
                           packet_extent(o[2], d[2], seg), time, rates, &slope);
        PACKET_COUNT(*evals, going);
        ia_maskv use = going & isfinite(slope.lo) & isfinite(slope.hi); /* NaN is not finite */
        /* lanes not using it multiply by 0: an infinite slope there would send every lane down iav_mul's slow path */
        iav s = iav__pick(iav_point(0), slope, use);
        iav form = iav_add(fa, iav_mul(s, iav_sub(seg, at_a)));
        ia_realv lo = select(f.lo, fmax(f.lo, form.lo), use), hi = select(f.hi, fmin(f.hi, form.hi), use);
        ia_maskv whole = going & ((lo > 0) | (hi < 0)); /* where F' is unbounded, by F's enclosure alone */
        ia_maskv leaf = going & ~whole & (b - a <= eps);
        ia_maskv crossed = (ia_maskv)0, held = (ia_maskv)0;
        iav f_b = fa; /* F at b: read only where crossed or held */
        if (iav_any(going & ~whole & ~leaf)) {
            /* F(a) and the form at b of certain, opposite signs: the first root is in [a, b] */
            f_b = iav_add(fa, iav_mul(s, iav_sub(iav_make(b, b), at_a)));
            crossed = use & ~whole & ~leaf & (((fa.lo > 0) & (f_b.hi < 0)) | ((fa.hi < 0) & (f_b.lo > 0)));
            /* where F' keeps the sign that takes F(a) towards 0 over the step, F at b decides the step: of F(a)'s
             * sign, F is off 0 all over it (monotone between them), of the other it crosses 0 in it, once */
            ia_maskv towards_0 = ((fa.hi < 0) & (s.lo > 0)) | ((fa.lo > 0) & (s.hi < 0));
            ia_maskv monotone = use & ~whole & ~leaf & ~crossed & towards_0;
            if (iav_any(monotone)) {
                iav at_b = iav_make(b, b);
                f_b = packet_F(~(ulong)0, packet_extent(o[0], d[0], at_b), packet_extent(o[1], d[1], at_b),
                               packet_extent(o[2], d[2], at_b), time);
                PACKET_COUNT(*evals, monotone);
                held = monotone & (((fa.hi < 0) & (f_b.hi < 0)) | ((fa.lo > 0) & (f_b.lo > 0)));
                crossed |= monotone & (((fa.hi < 0) & (f_b.lo > 0)) | ((fa.lo > 0) & (f_b.hi < 0)));
                whole |= held;
            }
        }
        if (whether) /* the hit's place unknown: the caller asks only whether there is one */
            leaf |= crossed;
        else
            handed |= crossed;
        hs = iav_make(select(hs.lo, s.lo, crossed), select(hs.hi, s.hi, crossed));
        cross_b = select(cross_b, b, crossed);
        cross_fb = iav__pick(cross_fb, f_b, crossed);
        t_far = select(t_far, b, crossed);
        ia_realv cross_lo = a;
        ia_maskv narrowed = (ia_maskv)0;
        if (iav_any(crossed)) { /* Newton's steps from both ends, free: F there and the slope over [a, b] known */
            iav slope_1 = iav__pick(iav_point(1), s, crossed); /* lanes not crossing divide by 1 */
            iav from_a = iav_sub(at_a, iav_div(fa, slope_1));
            iav from_b = iav_sub(iav_make(b, b), iav_div(f_b, slope_1));
            cross_lo = fmax(from_a.lo, from_b.lo);
            ia_realv cross_hi = fmin(b, fmin(from_a.hi, from_b.hi));
            narrowed = crossed & (cross_lo <= cross_hi); /* both hold the root (false for NaN) */
            t_far = select(t_far, cross_hi, narrowed);
        }
        *hit_lo = select(*hit_lo, a, leaf);
        *hit_hi = select(*hit_hi, b, leaf);
        hit |= leaf;
        /* the failed lanes' part and shorter step (and above, their crossing and monotone tests) are worked out
         * only where some lane's step failed: most packet steps of the rays that leave the scene hold in every
         * lane (one bounce's effects_march, CPU samples: 680 -> 529; shadows 540 -> 418) */
        ia_maskv failed = going & ~whole, part = (ia_maskv)0;
        ia_realv r = IAV_R(0), c = a;
        if (iav_any(failed)) { /* the part [a, c] the form excludes 0 from: F(a) + F' x is off 0 for x < F(a) / |F'| */
            part = use & ~whole & ~leaf;
            r = select(r, fa.lo / -s.lo, (fa.lo > 0) & (s.lo < 0));
            r = select(r, -fa.hi / s.hi, (fa.hi < 0) & (s.hi > 0));
            c = fmin(a + (ia_real)0.99 * r, b);
            iav check = iav_add(fa, iav_mul(s, iav_sub(iav_make(a, c), at_a)));
            part &= (c > a) & ((check.lo > 0) | (check.hi < 0));
        }
        ia_realv next = select(select(a, c, part), b, whole);
        next = select(next, fmax(next, cross_lo), narrowed);
        iav moved = iav_add(fa, iav_mul(s, iav_sub(iav_make(next, next), at_a)));
        fa = iav_make(select(fa.lo, moved.lo, whole | part), select(fa.hi, moved.hi, whole | part));
        fa = iav_make(select(fa.lo, f_b.lo, held), select(fa.hi, f_b.hi, held));
        /* the next step: longer after one that held (twice, after one that fell short); after a step towards a
         * root, twice as far as it went; else an eighth, or straight to a leaf's width when r says the root is
         * that close */
        ia_realv longer = select(w * 8, w * 2, short_before);
        if (step == 0) { /* after a first step that held, the rest of the ray: most reflected rays leave the scene
                          * (evaluations per reflected ray 4.38 -> 4.31, layer 10.76 -> 10.66; after the second step
                          * too: 4.52, 11.06); a ray through a solid does not (twice the step, unless modelled) */
            longer = select(fmax(longer, t_far - b), w * 2, inside);
            /* F along a ray through a solid as a parabola: its slope at the step's start s.lo, growing by its
             * width over the step, is 0 at t_mid, and F is back to F(a0) ~ 0 (the exit) as far past t_mid */
            ia_realv k = (s.hi - s.lo) / (b - a);
            t_mid = select(t_mid, a - s.lo / k, inside & whole & use & (s.lo < 0) & (k > 0));
        }
        /* the steps the parabola suggests (only the steps' lengths: each is proven as any other): past t_mid
         * (the slope then keeps its sign over the next step, so that the monotone test decides it), then to the
         * exit (layer evaluations 10.66 -> 9.66; to t_mid itself, 9.87: rounded, the slope there holds 0) */
        ia_realv target = select(t_mid + (t_mid - a0), t_mid + (ia_real)0.3 * (t_mid - a0), b < t_mid);
        longer = select(longer, target - b, inside & whole & isfinite(t_mid) & (target > b));
        ia_realv shorter = w;
        if (iav_any(failed)) {
            /* where F' keeps one sign over the step, F has crossed 0 by where the form's far bound does: the root
             * lies in [c, e], and a step just past e has a tight F' */
            ia_realv e = select(IAV_R(IA_INF), a + fa.hi / -s.hi, (fa.lo > 0) & (s.hi < 0));
            e = select(e, a + -fa.lo / s.lo, (fa.hi < 0) & (s.lo > 0));
            ia_realv towards = select(2 * (c - a), fmax((ia_real)1.5 * (e - c), (ia_real)0.25 * (c - a)), e <= b);
            /* never under a quarter of the failed step: an eighth of it, then x2 and x8, failed again just as far
             * on through a shallow solid (layers 12.44 -> 11.55 evaluations with the slope below) */
            shorter = select(w * (ia_real)0.125, fmax(towards, w * (ia_real)0.25),
                             part & (c - a >= w * (ia_real)0x1p-6));
            shorter = select(shorter, IAV_R(0), use & ~part & (r < eps));
        }
        w = fmax(select(shorter, longer, whole), (ia_real)0.5 * eps);
        short_before = ~whole;
        a = next;
        going &= ~leaf & ~handed & (a < t_far);
        /* F at a again where its enclosure holds 0, or is loose (wider than a quarter of its distance from 0) and
         * the step fell short, or was not carried by a bounded F' (where F' is unbounded, shorter steps are tried
         * until F's enclosure decides, down to a leaf) */
        ia_realv off0 = fmin(fabs(fa.lo), fabs(fa.hi));
        fresh = going & (iav_contains_zero(fa) | (~whole & (fa.hi - fa.lo > (ia_real)0.25 * off0)) | ~use);
        ia_maskv past = going & (a >= run_end);
        if (iav_any(past)) { /* over the gap to the next run: a step as long as that run, F at its start */
            ia_realv run_lo, next_end;
            march_next_run(runs, a, &run_lo, &next_end);
            a = select(a, fmax(a, run_lo), past);
            run_end = select(run_end, next_end, past);
            w = select(w, next_end - a, past);
            short_before &= ~past;
            going &= a < t_far;
            fresh |= past & going;
        }
    }
    /* F crosses 0 in [a, t_far] of the handed lanes and its slope there, hs, keeps one sign (the root is unique):
     * interval Newton with that slope, [a, t_far] <- [a, t_far] & (m - F(m) / hs), down to a leaf, for any m in the
     * part. A midpoint step keeps the root and at least halves the part (m is outside m - F(m) / hs where F(m)
     * excludes 0); a lane whose midpoint step halves it no more (F(m) holds 0 at a width above eps) goes on by the
     * walk over its part. A step at a secant's guess must only narrow it (layers 9.81 -> 9.64). hs is the march's
     * step's slope, loose over a long step, so that Newton converged only linearly (up to 11 steps): where a step
     * shrank the part by less than 4, F' over the part that is left is evaluated again and hs narrowed to its
     * intersection with it (both enclose F' there), which keeps its sign (layers 12.44 -> 12.04 evaluations). */
    ia_maskv stale = (ia_maskv)0, at_mid = (ia_maskv)0;
    for (int step = 0; step < EFFECTS_MARCH_STEPS && iav_any(handed); step++) {
        stale &= handed;
        if (iav_any(stale)) {
            iav seg = iav_make(a, t_far), slope;
            (void)packet_Fdv(~(ulong)0, packet_extent(o[0], d[0], seg), packet_extent(o[1], d[1], seg),
                             packet_extent(o[2], d[2], seg), time, rates, &slope);
            PACKET_COUNT(*evals, stale);
            ia_maskv use = stale & (fmax(hs.lo, slope.lo) <= fmin(hs.hi, slope.hi)); /* false for NaN */
            hs = iav_make(select(hs.lo, fmax(hs.lo, slope.lo), use), select(hs.hi, fmin(hs.hi, slope.hi), use));
        }
        /* m: the secant's guess at the root from the last two points of F where it lies inside the part (then
         * F(m) is near 0 and the part shrinks to about the guess's error), else the part's midpoint */
        ia_realv guess = t1 - f1 * (t1 - t0) / (f1 - f0);
        ia_maskv guessed = ~at_mid & (guess > a) & (guess < t_far); /* false for NaN */
        ia_realv m = select(a * (ia_real)0.5 + t_far * (ia_real)0.5, guess, guessed);
        iav at_m = iav_make(m, m);
        iav fm = packet_F(~(ulong)0, packet_extent(o[0], d[0], at_m), packet_extent(o[1], d[1], at_m),
                          packet_extent(o[2], d[2], at_m), time);
        PACKET_COUNT(*evals, handed);
        t0 = t1;
        f0 = f1;
        t1 = m;
        f1 = (ia_real)0.5 * (fm.lo + fm.hi);
        iav n = iav_sub(at_m, iav_div(fm, hs));
        /* never narrower than half a leaf, as packet.h's Newton (the walk's leaf test follows it) */
        ia_realv lo = fmax(a, n.lo), hi = fmin(t_far, n.hi);
        hi = fmin(t_far, fmax(hi, lo + (ia_real)0.5 * eps));
        ia_maskv halved = handed & (lo <= hi) & (hi - lo <= (ia_real)0.5 * (t_far - a));
        /* a guess that narrowed the part but did not halve it: the midpoint next */
        ia_maskv ok = halved | (handed & guessed & (lo <= hi) & (hi - lo < t_far - a));
        at_mid = ok & ~halved;
        stale = ok & (hi - lo > (ia_real)0.25 * (t_far - a));
        a = select(a, lo, ok);
        t_far = select(t_far, hi, ok);
        ia_maskv leaf = ok & (t_far - a <= eps);
        *hit_lo = select(*hit_lo, a, leaf);
        *hit_hi = select(*hit_hi, t_far, leaf);
        hit |= leaf;
        proven |= leaf;
        going |= handed & ~ok; /* to the walk */
        handed &= ok & ~leaf;
    }
    *t_near = a;
    *t_far_io = t_far;
    *going_io &= going | handed; /* the lanes the walk goes on with: neither hit nor out */
    if (crossing) {
        crossing->lanes = proven;
        crossing->b = cross_b;
        crossing->fb = cross_fb;
    }
    return hit;
}
#endif

#if IA_DEVICE && defined(IA_VW) && !defined(IACSG_SCALAR_CODE) /* (as packet.h's lanes) */
/* Where F has no derivative code (implicits/emit.c: newton_pays, e.g. pow, x^500), the same march by F's enclosure
 * over each step alone: a step whose enclosure excludes 0 is root-free (a moves to b; the next step 8 times as
 * long, twice after one that fell short), else the step is halved, down to a leaf no longer than eps whose
 * enclosure holds 0 (the hit; every part a passed is root-free, so the leaf's start is never after the first
 * root). Where the caller asks only `whether` the ray meets F's zero set (F > 0 at its start), a failed step at
 * whose end F < 0 ends it too: F crosses 0 in it. The first step is MARCH_ENCLOSURE_FIRST times the start's
 * distance from the surface `leaving` (a step's box reaches back towards the surface the ray leaves as far as
 * it is long). The lanes still marching after EFFECTS_MARCH_STEPS go on by the walk from their a (*going_io). */
#define MARCH_ENCLOSURE_FIRST 16
static ia_maskv march_enclosure(const ia_realv o[3], const ia_realv d[3], ia_realv *t_near, ia_realv t_far,
                                ia_maskv *going_io, ia_realv leaving, ia_real eps, int whether, iav time,
                                ia_realv *hit_lo, ia_realv *hit_hi, packet_index *evals) {
    ia_realv a = *t_near, w = MARCH_ENCLOSURE_FIRST * leaving;
    ia_maskv going = *going_io & (a < t_far), hit = (ia_maskv)0, short_before = (ia_maskv)0;
    for (int step = 0; step < EFFECTS_MARCH_STEPS && iav_any(going); step++) {
        ia_realv b = fmin(a + w, t_far);
        iav seg = iav_make(a, b);
        iav f = packet_F(~(ulong)0, packet_extent(o[0], d[0], seg), packet_extent(o[1], d[1], seg),
                         packet_extent(o[2], d[2], seg), time);
        PACKET_COUNT(*evals, going);
        ia_maskv whole = going & ((f.lo > 0) | (f.hi < 0)), leaf = going & ~whole & (b - a <= eps);
        if (whether && iav_any(going & ~whole & ~leaf)) { /* F < 0 at b, F > 0 at a: F crosses 0 in [a, b] */
            ia_maskv failed = going & ~whole & ~leaf;
            iav at_b = iav_make(b, b);
            iav fb = packet_F(~(ulong)0, packet_extent(o[0], d[0], at_b), packet_extent(o[1], d[1], at_b),
                              packet_extent(o[2], d[2], at_b), time);
            PACKET_COUNT(*evals, failed);
            leaf |= failed & (fb.hi < 0);
        }
        *hit_lo = select(*hit_lo, a, leaf);
        *hit_hi = select(*hit_hi, b, leaf);
        hit |= leaf;
        a = select(a, b, whole);
        w = select(fmax(w * (ia_real)0.5, (ia_real)0.5 * eps), select(w * 8, w * 2, short_before), whole);
        short_before = ~whole;
        going &= ~leaf & (a < t_far);
    }
    *t_near = a;
    *going_io &= going;
    return hit;
}

#endif

#endif
