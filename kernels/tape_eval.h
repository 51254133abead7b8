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
 * Private memory: TAPE_SLOTS intervals over lanes and two flags each (tape.h: 8 KiB in float, 16 KiB in
 * double); no recursion. */
#ifndef KERNELS_TAPE_EVAL_H
#define KERNELS_TAPE_EVAL_H
#if defined(IACSG_TAPE) && IA_DEVICE && defined(IA_VW)

typedef const __global uint *tape_ptr;

IA_FN const __global ia_real *tape_reals(tape_ptr tape) {
    return (const __global ia_real *)(tape + tape[TAPE_W_REALS]);
}

/* Part p of the tape over the lanes' boxes, read as the union reads it (through iav_or_outside where it may
 * be undefined). */
IA_FN iav tape_part(tape_ptr tape, uint p, iav x, iav y, iav z, iav t) {
    const __global uint *part = tape + tape[TAPE_W_PART_TABLE] + TAPE_PART_WORDS * p;
    const __global uint *code = tape + tape[TAPE_W_CODE] + TAPE_INSTR_WORDS * part[0];
    const __global ia_real *reals = tape_reals(tape);
    iav v[TAPE_SLOTS];
    ia_maskv u[TAPE_SLOTS], e[TAPE_SLOTS];
    v[0] = x;
    v[1] = y;
    v[2] = z;
    v[3] = t;
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
            R = (flags & TAPE_UNION) ? iav_union(A, u[a], e[a], B, u[b], e[b])
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
        v[dst] = R;
        if (flagged) {
            u[dst] = ru;
            e[dst] = re;
        }
    }
    uint result = part[2] & 0xffff;
    return (part[2] >> 16 & 1) ? iav_or_outside(v[result], u[result], e[result]) : v[result];
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

/* Whether the closed box b (x0, y0, z0, x1, y1, z1) meets the box of a lane of `live`: first against the hull
 * of those boxes (a few scalar comparisons, which reject most parts), then lane by lane (the lanes of a packet
 * may lie on nodes far apart, so the hull alone keeps many parts that no lane needs). */
IA_FN int tape_box_meets(const __global ia_real *b, const ia_real *hull, ia_maskv live, iav x, iav y, iav z) {
    if (!(hull[0] <= b[3] && hull[3] >= b[0] && hull[1] <= b[4] && hull[4] >= b[1] && hull[2] <= b[5] &&
          hull[5] >= b[2]))
        return 0;
    return iav_any(live & (x.lo <= b[3]) & (x.hi >= b[0]) & (y.lo <= b[4]) & (y.hi >= b[1]) & (z.lo <= b[5]) &
                   (z.hi >= b[2]));
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

#endif
#endif
