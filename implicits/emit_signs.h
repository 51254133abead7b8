/* implicits/emit_signs.h -- stage 5, beside emit.c: which nodes' enclosures over lanes start at 0 or above, and the
 * cheaper operations over lanes (ia/vec.h: iav_add_nn ...) that their consumers take, for the compiled code (emit.c)
 * and the tape (tape.c, tape_cl.c), which must take the same ones to keep its bits. */
#ifndef IACSG_EMIT_SIGNS_H
#define IACSG_EMIT_SIGNS_H
#include "dag.h"

/* nonneg[i] = 1 for the nodes i of order[] (operands before their nodes) whose value over lanes has lo >= 0 in every
 * lane that counts, as the code over lanes computes it with emit_signs_value's forms; else 0. */
void emit_signs_mark(const dag *d, const int *order, int count, unsigned char *nonneg);

/* The ops.def-style template (ia_ read as iav_) of node n's value over lanes where its operands' signs allow a
 * cheaper form, else NULL. *clamped: 1 when that form's lower bound differs from ops.def's (clamped at 0; see
 * emit_signs_clamped), 0 when it has its bits. */
const char *emit_signs_value(const dag *d, const unsigned char *nonneg, const dag_node *n, int *clamped);

/* The clamped form of operation op over lanes for operands >= 0 (the tape's TAPE_NONNEG instructions), or NULL. */
const char *emit_signs_clamped(int op);

#endif
