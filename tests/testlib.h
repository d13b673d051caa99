/* testlib.h - the smallest test harness: one line per check ("ok ID" or "FAIL ID:
 * why"), a summary line, exit status 1 on any failure. IDs say what they test,
 * hierarchically (contact.restitution.head_on). */
#ifndef SB_TESTLIB_H
#define SB_TESTLIB_H

#include <stdio.h>
#include <stdlib.h>

static int tl_pass, tl_fail;

#define CHECK(id, cond, ...)                                                   \
	do {                                                                   \
		if (cond) {                                                    \
			tl_pass++;                                             \
			printf("ok %s\n", id);                                 \
		} else {                                                       \
			tl_fail++;                                             \
			printf("FAIL %s: ", id);                               \
			printf(__VA_ARGS__);                                   \
			printf("  [%s:%d]\n", __FILE__, __LINE__);             \
		}                                                              \
		fflush(stdout);                                                \
	} while (0)

/* Relative error check with the numbers in the message. */
#define CHECK_REL(id, got, want, tol)                                          \
	do {                                                                   \
		double g_ = (got), w_ = (want);                                \
		double r_ = w_ != 0 ? (g_ - w_) / w_ : g_ - w_;                \
		CHECK(id, r_ <= (tol) && r_ >= -(tol),                         \
		      "got %.12g want %.12g rel err %.3g > %.3g", g_, w_, r_, (double)(tol)); \
	} while (0)

static inline int tl_done(void)
{
	printf("# %d passed, %d failed\n", tl_pass, tl_fail);
	return tl_fail ? 1 : 0;
}

#endif
