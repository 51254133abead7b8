/* ia/decimal.h -- host only: the interval of floats that encloses the real number a decimal string denotes.
 * "0.1" gives [pred, succ] around the nearest float to 1/10; "0.5" gives the point [0.5, 0.5]. */
#ifndef IA_DECIMAL_H
#define IA_DECIMAL_H

/* Parse all of s (C syntax for decimal or hexadecimal floating constants, "inf", "-inf") into the tightest
 * enclosing float and double intervals. Returns 0 on success, -1 if s is not a number (nothing written).
 * A finite number beyond the largest float gives an infinite bound on its side only. */
int ia_decimal_float(const char *s, float *lo, float *hi);
int ia_decimal_double(const char *s, double *lo, double *hi);

#endif
