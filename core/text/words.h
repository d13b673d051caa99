/* words.h - how far apart two words are, for the "did you mean ...?" of a mistyped
 * key or option (the engine's parameter table, the analysis tools' options). */
#ifndef SB_WORDS_H
#define SB_WORDS_H

/* Edits between a and b (insert, delete, replace, and a swap of two adjacent letters
 * counts one: "bnad" is one edit from "band"); words of 48 letters or more are 48 apart. */
int words_distance(const char *a, const char *b);

#endif
