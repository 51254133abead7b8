/* kernels/tape_eval.h -- the interpreter of a tape (implicits/tape.h: what a tape is and its layout), for the
 * program of an expression too large to compile quickly (src/render_expr.c). It stands in for the compiled
 * iacsg_Fv_group (packet.h: packet_F, tile.h: tile_groups): the union of a group's parts over IA_VW lanes, each
 * part's instructions run on register slots with tape_apply and tape_own_flags (implicits/tape_cl.c writes them from
 * ops.def: the calls the compiled code makes), its flags for undefined operands as emit.c computes them. So for
 * the same boxes an interpreted group and a compiled one return the same intervals, bit for bit
 * (tests/t_tape_fp.c), unless parts are skipped:
 *
 * Skipping (tape_group given the lanes' hull): a part whose proven box (tape.h: outside it the part is > 0 or
 * undefined) meets none of the lanes' boxes is left out of the union. The min of the parts kept is then < 0, = 0 or > 0
 * on the box wherever the union is (a part left out is > 0 there), which is all the walk decides from (as
 * with the groups, packet_F). The shading's point evaluations do not skip: their differences need the values.
 *
 * Lists (tape_tile_parts, tape_lists): the tile pass keeps, per tile and segment of the frame's tree, the parts it
 * could not prove positive over the tile's box there, less those dominated there (certainly larger than another
 * part at every point of the box, so never the min); the walk and the shading evaluate only the lists of the
 * segments their nodes overlap, merged, and fall back to the groups where a list overflowed (tape.h:
 * TAPE_TILE_RECORD). Never-miss as above: a part left out is > 0 or not the min wherever the rays look.
 *
 * Newton (tape_part_dt, tape_lists_dt): on a tape whose parts are all defined everywhere (TAPE_W_NEWTON), the
 * walk's interval Newton and mean value form (packet.h) take the union's derivative along the rays over one set
 * of parts, the lists' with skipping, and its value at the midpoints over the same set.
 *
 * Private memory: TAPE_SLOTS intervals over lanes and two flags each (tape.h: 8 KiB in float, 16 KiB in
 * double), and with the derivative TAPE_SLOTS intervals more (4 KiB, 8 KiB); the tile pass's lists, 16-bit
 * indices and a lower bound each over the lanes (1.5 KiB in float, 2.4 KiB in double); no recursion. */
#ifndef KERNELS_TAPE_EVAL_H
#define KERNELS_TAPE_EVAL_H
#if defined(IACSG_TAPE) && IA_DEVICE && defined(IA_VW)

typedef const __global uint *tape_ptr;

IA_FN const __global ia_real *tape_reals(tape_ptr tape) {
    return (const __global ia_real *)(tape + tape[TAPE_W_REALS]);
}

/* Part p of the tape over the lanes' boxes, read as the union reads it (through iav_or_outside where it may
 * be undefined); with `slope` (NULL or not at each call, so the compiler keeps a copy of each), also the
 * enclosure of its derivative along the rays over those boxes in *slope, the boxes moving at the rates d[0..2]
 * (t not; constants do not move): the `tderiv` column (tape_apply_dt) as the compiled iacsg_Fdv computes it,
 * only for parts with no instruction that may be undefined (TAPE_W_NEWTON: their flags are not looked at). */
IAV_INLINE iav tape_part_body(tape_ptr tape, uint p, iav x, iav y, iav z, iav t, const iav *d, iav *slope) {
    const __global uint *part = tape + tape[TAPE_W_PART_TABLE] + TAPE_PART_WORDS * p;
    const __global uint *code = tape + tape[TAPE_W_CODE] + TAPE_INSTR_WORDS * part[0];
    const __global ia_real *reals = tape_reals(tape);
    iav v[TAPE_SLOTS], dv[TAPE_SLOTS], still = iav_point(0);
    ia_maskv u[TAPE_SLOTS], e[TAPE_SLOTS];
    v[0] = x;
    v[1] = y;
    v[2] = z;
    v[3] = t;
    if (slope) {
        for (int k = 0; k < 3; k++)
            dv[k] = d[k];
        dv[3] = still;
    }
    for (int k = 0; k < 4; k++)
        u[k] = e[k] = (ia_maskv)0;
    int flagged = part[2] >> 17; /* any instruction may be undefined: else no flag is read or written */
    for (uint c = 0; c < part[1]; c++, code += TAPE_INSTR_WORDS) {
        uint op = code[0] & 0xff, flags = code[0] >> 8 & 0xff, dst = code[0] >> 16;
        uint a = code[1] & 0xffff, b = code[1] >> 16;
        iav K = iav_const(reals[code[3]], reals[code[3] + 1]); /* a constant operand, read in place */
        iav A = (flags & TAPE_A_REAL) ? K : v[a], B = (flags & TAPE_B_REAL) ? K : v[b], R;
        ia_maskv ru = (ia_maskv)0, re = (ia_maskv)0;
        if (op == TAPE_OP_CONST) {
            R = K;
            ru = re = (flags & TAPE_UNDEFINED) ? (ia_maskv)-1 : (ia_maskv)0; /* an empty constant */
        } else {
            R = (flags & TAPE_UNION)    ? iav_union(A, u[a], e[a], B, u[b], e[b])
                : (flags & TAPE_NONNEG) ? tape_apply_nonneg(op, A, B, reals[code[3]])
                                        : tape_apply(op, A, B, (int)code[2], reals[code[3]]);
            if (flags & TAPE_UNDEFINED) { /* own condition or the operands' flags; both for a union */
                if (flags & TAPE_OWN)
                    tape_own_flags(op, A, B, (int)code[2], R, &ru, &re);
                if (op == TAPE_OP_MIN) {
                    ru = u[a] & u[b];
                    re = e[a] & e[b];
                } else { /* a unary operation's b is slot 0, x, never flagged */
                    ru |= u[a] | u[b];
                    re |= e[a] | e[b];
                }
            }
        }
        iav D = still;
        if (slope && op != TAPE_OP_CONST) /* a unary operation's DB (slot 0's) is not read */
            D = tape_apply_dt(op, A, B, (int)code[2], reals[code[3]], R, (flags & TAPE_A_REAL) ? still : dv[a],
                              (flags & TAPE_B_REAL) ? still : dv[b]);
        if (flags & TAPE_THEN_SQR) {
            iav S = tape_apply(TAPE_OP_SQR, R, R, 0, 0);
            if (slope)
                D = tape_apply_dt(TAPE_OP_SQR, R, R, 0, 0, S, D, D);
            R = S;
        }
        if (slope)
            dv[dst] = D;
        v[dst] = R;
        if (flagged) {
            u[dst] = ru;
            e[dst] = re;
        }
    }
    uint result = part[2] & 0xffff;
    if (slope)
        *slope = dv[result];
    return (part[2] >> 16 & 1) ? iav_or_outside(v[result], u[result], e[result]) : v[result];
}

IA_FN iav tape_part(tape_ptr tape, uint p, iav x, iav y, iav z, iav t) {
    return tape_part_body(tape, p, x, y, z, t, 0, 0);
}

/* tape_part and its derivative along the rays d (tape_part_body). */
IA_FN iav tape_part_dt(tape_ptr tape, uint p, iav x, iav y, iav z, iav t, const iav d[3], iav *slope) {
    return tape_part_body(tape, p, x, y, z, t, d, slope);
}

/* The hull of the boxes of the lanes of `live`: x0, y0, z0, x1, y1, z1 (NaN where none, which meets nothing). */
IA_FN void tape_hull(ia_maskv live, iav x, iav y, iav z, ia_real hull[6]) {
    ia_real k[6][IA_VW];
    ia_realv none = IAV_R(NAN); /* fmin and fmax drop it */
    IAV_STORE(select(none, x.lo, live), k[0]);
    IAV_STORE(select(none, y.lo, live), k[1]);
    IAV_STORE(select(none, z.lo, live), k[2]);
    IAV_STORE(select(none, x.hi, live), k[3]);
    IAV_STORE(select(none, y.hi, live), k[4]);
    IAV_STORE(select(none, z.hi, live), k[5]);
    for (int c = 0; c < 6; c++) {
        hull[c] = k[c][0];
        for (int l = 1; l < IA_VW; l++)
            hull[c] = c < 3 ? fmin(hull[c], k[c][l]) : fmax(hull[c], k[c][l]);
    }
}

/* Whether the closed box b (x0, y0, z0, x1, y1, z1) meets the box of a lane of `live`. */
IA_FN int tape_box_meets_lanes(const __global ia_real *b, ia_maskv live, iav x, iav y, iav z) {
    return iav_any(live & (x.lo <= b[3]) & (x.hi >= b[0]) & (y.lo <= b[4]) & (y.hi >= b[1]) & (z.lo <= b[5]) &
                   (z.hi >= b[2]));
}

/* tape_box_meets_lanes, first against the hull of those boxes (a few scalar comparisons, which reject most of
 * the parts of a group), then lane by lane (the lanes of a packet may lie on nodes far apart, so the hull alone
 * keeps many parts that no lane needs). */
IA_FN int tape_box_meets(const __global ia_real *b, const ia_real *hull, ia_maskv live, iav x, iav y, iav z) {
    if (!(hull[0] <= b[3] && hull[3] >= b[0] && hull[1] <= b[4] && hull[4] >= b[1] && hull[2] <= b[5] &&
          hull[5] >= b[2]))
        return 0;
    return tape_box_meets_lanes(b, live, x, y, z);
}

/* The union of group g's parts (+inf past the tape's groups), skipping those whose box meets none of the boxes
 * of the lanes of `live` (see the top), whose hull is `hull`; none skipped when hull is NULL. */
IA_FN iav tape_group(tape_ptr tape, int g, const ia_real *hull, ia_maskv live, iav x, iav y, iav z, iav t) {
    iav r = iav_point(IA_INF); /* the identity of min */
    uint ngroups = tape[TAPE_W_GROUPS];
    if (g >= (int)ngroups)
        return r;
    const __global ia_real *reals = tape_reals(tape);
    const __global uint *parts = tape + tape[TAPE_W_PART_TABLE];
    if (hull && !tape_box_meets(reals + tape[TAPE_W_GROUP_TABLE + ngroups + 1 + g], hull, live, x, y, z))
        return r; /* the hull of its parts' boxes */
    for (uint p = tape[TAPE_W_GROUP_TABLE + g]; p < tape[TAPE_W_GROUP_TABLE + g + 1]; p++)
        if (!hull || tape_box_meets(reals + parts[TAPE_PART_WORDS * p + 3], hull, live, x, y, z))
            r = iav_min(r, tape_part(tape, p, x, y, z, t));
    return r;
}

/* The lists of a tile pass (tape.h: TAPE_TILE_RECORD): for each lane's box (a tile's, over a segment of the frame's
 * tree), the parts of the groups in `among` that are not proven positive there (bit g of groups[lane] set for
 * group g when one of its parts is kept, as tile_groups sets it), less those dominated there: a part certainly
 * defined whose lower bound exceeds the upper bound of another certainly defined part (at every point of the box
 * it is larger, so the min of the others is the union there, and on every box inside it). lists[lane][0] is the
 * count, or TAPE_LIST_FULL when more were kept than fit or a part's index does not fit 16 bits. */
IA_FN void tape_tile_parts(tape_ptr tape, ulong among, iav x, iav y, iav z, iav t, ulong groups[IA_VW],
                           ushort lists[IA_VW][TAPE_TILE_RECORD]) {
    ia_real hull[6], least_hi[IA_VW], kept_lo[IA_VW][TAPE_TILE_RECORD - 1];
    tape_hull((ia_maskv)-1, x, y, z, hull);
    uint ngroups = tape[TAPE_W_GROUPS];
    ushort start = tape[TAPE_W_PARTS] < TAPE_LIST_FULL ? 0 : TAPE_LIST_FULL;
    for (int k = 0; k < IA_VW; k++) {
        groups[k] = 0;
        lists[k][0] = start;
        least_hi[k] = IA_INF;
    }
    const __global ia_real *reals = tape_reals(tape);
    const __global uint *parts = tape + tape[TAPE_W_PART_TABLE];
    for (uint g = 0; g < ngroups; g++) {
        if (!(among >> g & 1) ||
            !tape_box_meets(reals + tape[TAPE_W_GROUP_TABLE + ngroups + 1 + g], hull, (ia_maskv)-1, x, y, z))
            continue;
        for (uint p = tape[TAPE_W_GROUP_TABLE + g]; p < tape[TAPE_W_GROUP_TABLE + g + 1]; p++) {
            if (!tape_box_meets(reals + parts[TAPE_PART_WORDS * p + 3], hull, (ia_maskv)-1, x, y, z))
                continue;
            ia_real lo[IA_VW], hi[IA_VW];
            iav v = tape_part(tape, p, x, y, z, t);
            IAV_STORE(v.lo, lo);
            IAV_STORE(v.hi, hi);
            int defined = !(parts[TAPE_PART_WORDS * p + 2] >> 16 & 1);
            for (int k = 0; k < IA_VW; k++) {
                if (lo[k] > 0)
                    continue;
                groups[k] |= (ulong)1 << g;
                uint n = lists[k][0];
                if (n < TAPE_TILE_RECORD - 1) {
                    lists[k][1 + n] = (ushort)p;
                    kept_lo[k][n] = defined ? lo[k] : -IA_INF; /* never dominated */
                    lists[k][0] = (ushort)(n + 1);
                } else {
                    lists[k][0] = TAPE_LIST_FULL;
                }
                if (defined)
                    least_hi[k] = fmin(least_hi[k], hi[k]);
            }
        }
    }
    for (int k = 0; k < IA_VW; k++) { /* the dominated parts out (the part giving least_hi stays: lo <= hi) */
        uint n = lists[k][0], m = 0;
        if (n == TAPE_LIST_FULL)
            continue;
        for (uint j = 0; j < n; j++)
            if (!(kept_lo[k][j] > least_hi[k]))
                lists[k][1 + m++] = lists[k][1 + j];
        lists[k][0] = (ushort)m;
    }
}

/* The parts of the tile's lists for segments first..last of the frame's tree (`records`: the tile's first,
 * tape_tile_parts), each once: the lists are in increasing order, merged. */
typedef struct {
    const __global ushort *records;
    int first, last;
    uint at[TAPE_MAX_SEGMENTS]; /* each list's next entry */
} tape_merge;

/* 0 when a list is full (the caller takes the groups instead). */
IA_FN int tape_merge_open(tape_merge *m, const __global ushort *records, int first, int last) {
    m->records = records;
    m->first = first;
    m->last = last;
    for (int s = first; s <= last; s++) {
        if (records[TAPE_TILE_RECORD * s] == TAPE_LIST_FULL)
            return 0;
        m->at[s] = 1;
    }
    return 1;
}

/* The next part, TAPE_LIST_FULL after the last. */
IA_FN uint tape_merge_next(tape_merge *m) {
    uint p = TAPE_LIST_FULL; /* the least next entry of the lists, above every index */
    for (int s = m->first; s <= m->last; s++) {
        const __global ushort *list = m->records + TAPE_TILE_RECORD * s;
        if (m->at[s] <= list[0])
            p = min(p, (uint)list[m->at[s]]);
    }
    for (int s = m->first; s <= m->last; s++) {
        const __global ushort *list = m->records + TAPE_TILE_RECORD * s;
        m->at[s] += m->at[s] <= list[0] && list[m->at[s]] == p;
    }
    return p;
}

/* The union of the parts of the tile's lists for segments first..last (tape_merge); with `skip`, those whose box
 * meets none of the boxes of the lanes of `live` left out as in tape_group (lane by lane only: a list is short,
 * and the lanes' hull costs more than the tests it would spare). Returns 0 when a list is full (the caller
 * takes the groups instead), else 1 with the union in *r. */
IA_FN int tape_lists(tape_ptr tape, const __global ushort *records, int first, int last, int skip, ia_maskv live,
                     iav x, iav y, iav z, iav t, iav *r) {
    tape_merge m;
    if (!tape_merge_open(&m, records, first, last))
        return 0;
    const __global ia_real *reals = tape_reals(tape);
    const __global uint *parts = tape + tape[TAPE_W_PART_TABLE];
    *r = iav_point(IA_INF);
    for (uint p; (p = tape_merge_next(&m)) != TAPE_LIST_FULL;)
        if (!skip || tape_box_meets_lanes(reals + parts[TAPE_PART_WORDS * p + 3], live, x, y, z))
            *r = iav_min(*r, tape_part(tape, p, x, y, z, t));
    return 1;
}

/* For interval Newton and the mean value form (kernels/packet.h), on a tape with TAPE_W_NEWTON: tape_lists with
 * skipping over the boxes (x, y, z, t), and over the same parts the enclosure of the union's derivative along the
 * rays d over those boxes (*slope: Clarke's generalized one at the min's kinks, iav_dmin) and the union at the
 * points (xm, ym, zm) of those boxes (*at_m). One set of parts for the three, so that they are one function's,
 * which the mean value theorem needs: a min of parts, each continuous with its derivative in tape_part_dt's
 * enclosure. That function has the union's roots on the boxes: a part left out is > 0 or not the min there. */
IA_FN int tape_lists_dt(tape_ptr tape, const __global ushort *records, int first, int last, ia_maskv live, iav x,
                        iav y, iav z, iav t, const iav d[3], iav xm, iav ym, iav zm, iav *r, iav *slope,
                        iav *at_m) {
    tape_merge m;
    if (!tape_merge_open(&m, records, first, last))
        return 0;
    const __global ia_real *reals = tape_reals(tape);
    const __global uint *parts = tape + tape[TAPE_W_PART_TABLE];
    *r = *at_m = iav_point(IA_INF);
    *slope = iav_point(0); /* the identity's: read by iav_dmin only where a part may be +inf */
    for (uint p; (p = tape_merge_next(&m)) != TAPE_LIST_FULL;) {
        if (!tape_box_meets_lanes(reals + parts[TAPE_PART_WORDS * p + 3], live, x, y, z))
            continue;
        iav dp, v = tape_part_dt(tape, p, x, y, z, t, d, &dp);
        *slope = iav_dmin(*r, v, *slope, dp);
        *r = iav_min(*r, v);
        *at_m = iav_min(*at_m, tape_part(tape, p, xm, ym, zm, t));
    }
    return 1;
}

#endif
#endif
