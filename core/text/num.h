/* num.h - the one strict reading of a number in a text input (scene, campaign and
 * particle files, key=value arguments, the parameters of a campaign database): plain
 * decimal notation, all of the text, nothing else (docs/inputs.md, "Numbers"). */
#ifndef SB_NUM_H
#define SB_NUM_H

#include <stddef.h>

/* A real: [+-] digits [. digits] [e|E [+-] digits] (a leading or trailing point is
 * fine: "1.", ".5"), finite and within the range of a double (no hex, no inf or nan,
 * no underflow to a subnormal); no blanks. 0 and *x set, or -1 (*x untouched). */
int num_real(const char *s, double *x);

/* An integer: [+-] digits, within long long; no blanks, no point, no exponent, no hex.
 * 0 and *x set, or -1 (*x untouched). */
int num_int(const char *s, long long *x);

/* The same for the first n bytes of s (a token of a line): the token as a string. */
int num_real_n(const char *s, size_t n, double *x);
int num_int_n(const char *s, size_t n, long long *x);

#endif
