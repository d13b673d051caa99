/* label.h - parameters in figure text: the words and symbols a reader of a paper
 * expects ("𝓡 = 2.5", "no intruder", "2.8 Hz", "W = 30 cm") instead of the keys and
 * values of the parameter table ("radius_ratio=2.5"). gnuplot's cairo terminals take
 * the UTF-8 as it is. */
#ifndef AN_LABEL_H
#define AN_LABEL_H

#include <stddef.h>

/* KEY = VAL in words into buf (a number as %g; a key without words as "key = val"). */
void label_param(char *buf, size_t n, const char *key, const char *val);

/* The same of a number x ("2.8 Hz" of frequency 2.8). */
void label_num(char *buf, size_t n, const char *key, double x);

/* The unit of a key of the parameter table (core/scene/params.c) as a figure prints it
 * ("cm/s²", "s⁻¹", "Hz"); "" for a dimensionless or unknown key. */
void label_unit(char *buf, size_t n, const char *key);

/* A figure's axis for a key: words, the key's symbol (f for frequency; else the key)
 * and its unit in parentheses ("frequency f (Hz)"); words may be NULL or "". */
void label_axis(char *buf, size_t n, const char *key, const char *words);

/* Group j of ng (vals[j * nk + k]: its value of keys[k]) in words, the parameters
 * joined by ", ": those whose value differs between the groups (vary = 1, a legend
 * entry) or those every group shares (vary = 0, for a title). "" when none. */
void label_group(char *buf, size_t n, const char keys[][48], int nk, const char *const *vals, int ng, int j, int vary);

#endif
