/* implicits/tape.h -- stage 5b, beside emit.c: a large expression as data for one fixed interpreter kernel
 * (tape_cl.c writes its source), so that its render program is built once for every expression (PoCL caches
 * it) instead of compiling each expression's OpenCL C, which for a union of 1024 spheres took 4.6 s.
 *
 * Stages: the root's union parts (emit.c's, or the root alone) -> per part a box outside which it is proven > 0
 * or undefined (tape_part_box: there the union does not need it, kernels/tape_eval.h skips it) -> the parts in
 * the Morton order of their boxes' centres, in up to TAPE_MAX_GROUPS groups of consecutive parts (the kernels'
 * per-tile masks, kernels/tile.h), each group with the hull of its parts' boxes -> per part, its reachable nodes
 * in index order lowered to instructions on register slots (a slot is freed after its last use; the sqr of an
 * operation that nothing else reads is folded into that operation's instruction) -> whether interval Newton may
 * run on the tape (TAPE_W_NEWTON) -> one array of 32-bit words (the layout below), the reals in the working
 * precision.
 *
 * Layout, in words (uint32): a header (TAPE_W_*), the first part of each group (groups + 1 entries from
 * TAPE_W_GROUP_TABLE), the index of each group's box (groups entries), the part table (TAPE_PART_WORDS a part:
 * first instruction, instruction count, result slot | result may be undefined << 16 | some instruction may be
 * << 17, index of its box's 6 reals x0 y0 z0 x1 y1 z1), the instructions
 * (TAPE_INSTR_WORDS each: op | flags << 8 | dst << 16, a | b << 16, n, index of its real(s)), then the reals
 * (float, or double from an even word). Slots 0-3 hold x, y, z, t. */
#ifndef IACSG_TAPE_H
#define IACSG_TAPE_H
#include "dag.h"

/* The slots a part may use (x, y, z, t included): each is an interval over the lanes and two flags in the
 * device's private memory, 256 bytes in float and 512 in double at 16 lanes. A part that needs more is
 * compiled instead (tape_build says so). */
#define TAPE_SLOTS 32
/* A part evaluates all its instructions for every box it meets: one much longer than this would take hours per
 * frame (the compiler refuses expressions of more operations, emit.c). */
#define TAPE_MAX_PART_NODES 16384
/* The groups: as many as the masks of kernels/tile.h can name (a 64-bit mask), of consecutive parts. */
#define TAPE_MAX_GROUPS 64
/* A tile's list, per segment of the frame's tree (kernels/tape_eval.h: tape_tile_parts): the parts the tile pass
 * could not prove positive over the tile's box there, the others left out. TAPE_TILE_RECORD 16-bit words a
 * segment, TAPE_TILE_WORDS ulongs: a count (TAPE_LIST_FULL when more parts than fit, or a part's index above
 * 16 bits: then the rays use the groups' masks, skipping nothing they would not) and up to TAPE_TILE_RECORD - 1
 * part indices. 32 bytes a tile and segment, 512 a tile: 8 MiB more for a 1024x1024 frame (src/render.c). */
#define TAPE_TILE_WORDS 4
#define TAPE_TILE_RECORD (4 * TAPE_TILE_WORDS)
#define TAPE_LIST_FULL 0xffff
/* The most segments whose lists one evaluation merges (kernels/params.h's SEGMENTS: src/render.c checks). */
#define TAPE_MAX_SEGMENTS 16

/* TAPE_W_NEWTON: 1 when the kernels may refine roots by interval Newton on the tape (kernels/packet.h): no
 * instruction of any part may be undefined (so every part is continuous, with its derivative along a ray in
 * tape_apply_dt's enclosure) and Newton pays for every part (emit.c: emit_newton_pays). */
enum { TAPE_W_GROUPS = 0, TAPE_W_PARTS, TAPE_W_PART_TABLE, TAPE_W_CODE, TAPE_W_REALS, TAPE_W_NEWTON,
       TAPE_W_GROUP_TABLE = 8 };
enum { TAPE_PART_WORDS = 4, TAPE_INSTR_WORDS = 4 };
/* The op of an instruction that loads a constant (two reals: lo, hi) into its slot; the others are dag_op. */
#define TAPE_OP_CONST OP_CONST
/* Instruction flags: its value may be undefined (it computes the two flags of ia/vec.h), its own operation's
 * `undefined` column applies (ops.def; not for pown's positive powers), it is a union with a flagged operand,
 * its operand A or B is a constant read from its reals (lo, hi) rather than a slot, its value is then squared
 * (the sqr of a value that nothing else reads, never undefined: the (x - a)^2 of a sphere in one dispatch of
 * the interpreter instead of two, the same two operations), its operands start at 0 or above and it takes the
 * form that clamps its lower bound at 0, as the compiled code does (emit_signs.h: tape_apply_nonneg). */
enum { TAPE_UNDEFINED = 1, TAPE_OWN = 2, TAPE_UNION = 4, TAPE_A_REAL = 8, TAPE_B_REAL = 16, TAPE_THEN_SQR = 32,
       TAPE_NONNEG = 64 };

typedef struct {
    unsigned *words;
    size_t count;          /* words */
    int groups, parts;     /* as in the header */
    int instructions;      /* over all parts */
    int max_slots;         /* the most slots a part uses */
    int bounded_parts;     /* parts whose box is finite on every side */
    int newton;            /* as the header's TAPE_W_NEWTON */
} iacsg_tape;

/* The tape of the sub-DAG of root, its reals in double (fp64) or float. IACSG_ERR_LIMIT with a message when a
 * part needs more than TAPE_SLOTS slots or has more than TAPE_MAX_PART_NODES operations. Free with tape_free. */
iacsg_status tape_build(const dag *d, int root, int fp64, iacsg_tape *out, iacsg_error *err);
void tape_free(iacsg_tape *t);

/* The OpenCL C of the interpreter (kernels/tape_eval.h's operations, from the ops.def columns as emit.c writes
 * them over lanes): the same text for every expression. The caller free()s it; NULL when out of memory. */
char *tape_cl(void);

#endif
