/* implicits/suggest.h -- "did you mean" for unknown names: the closest candidate by edit distance. */
#ifndef IACSG_SUGGEST_H
#define IACSG_SUGGEST_H

typedef struct {
    const char *name;
    const char *best;
    int best_distance;
} suggestion;

/* Starts a search for names close to `name`; offer each candidate, then read .best (NULL if none is close:
 * at most 1 edit for names up to 4 letters, 2 for longer ones). */
void suggest_init(suggestion *s, const char *name);
void suggest_offer(suggestion *s, const char *candidate);

#endif
