/* implicits/suggest.c -- see suggest.h. Damerau-Levenshtein (adjacent swaps count as one edit: "tours" is
 * one edit from "torus"), on names no longer than LEX_MAX_NAME. */
#include "suggest.h"
#include "lex.h"
#include <string.h>

static int distance(const char *a, const char *b) {
    int n = (int)strlen(a), m = (int)strlen(b);
    if (n > LEX_MAX_NAME || m > LEX_MAX_NAME)
        return LEX_MAX_NAME;
    static _Thread_local int dp[LEX_MAX_NAME + 1][LEX_MAX_NAME + 1];
    for (int i = 0; i <= n; i++)
        dp[i][0] = i;
    for (int j = 0; j <= m; j++)
        dp[0][j] = j;
    for (int i = 1; i <= n; i++)
        for (int j = 1; j <= m; j++) {
            int cost = a[i - 1] != b[j - 1];
            int d = dp[i - 1][j - 1] + cost;
            if (dp[i - 1][j] + 1 < d)
                d = dp[i - 1][j] + 1;
            if (dp[i][j - 1] + 1 < d)
                d = dp[i][j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && dp[i - 2][j - 2] + 1 < d)
                d = dp[i - 2][j - 2] + 1;
            dp[i][j] = d;
        }
    return dp[n][m];
}

void suggest_init(suggestion *s, const char *name) {
    s->name = name;
    s->best = NULL;
    s->best_distance = strlen(name) <= 4 ? 2 : 3; /* strictly below this counts as close */
}

void suggest_offer(suggestion *s, const char *candidate) {
    int d = distance(s->name, candidate);
    if (d > 0 && d < s->best_distance) {
        s->best = candidate;
        s->best_distance = d;
    }
}
