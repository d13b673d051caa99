/* kmboot.c - the bootstrap of a Kaplan-Meier median over runs: six runs risen at 1..6 s
 * give replicates that are all reached medians among the times, the same for the same
 * seed; four runs all censored give only censored replicates, each bounded below by its
 * resample's longest observation and unbounded above; two risen of six give both kinds;
 * no runs is an error. */
#include <math.h>
#include <string.h>

#include "measure/kmboot.h"
#include "testlib.h"

enum { B = 300 };

int main(void)
{
	static double lo[B], hi[B], lo2[B], hi2[B];
	size_t cens = 99, c2;
	const double t6[6] = {1, 2, 3, 4, 5, 6};
	const int all[6] = {1, 1, 1, 1, 1, 1};
	int rc = kmboot_median(t6, all, 6, B, 3, lo, hi, &cens);
	int good = 1, spread = 0;
	for (int k = 0; k < B; k++) {
		good &= lo[k] == hi[k] && lo[k] == floor(lo[k]) && lo[k] >= 1 && lo[k] <= 6;
		spread |= lo[k] != lo[0];
	}
	CHECK("kmboot.risen.reached", !rc && cens == 0 && good && spread, "rc %d censored %zu, replicate 0 [%g, %g]", rc,
	      cens, lo[0], hi[0]);
	rc = kmboot_median(t6, all, 6, B, 3, lo2, hi2, &c2);
	CHECK("kmboot.reproducible", !rc && !memcmp(lo, lo2, sizeof lo) && !memcmp(hi, hi2, sizeof hi), "seed 3 twice differs");

	const double t4[4] = {2, 3, 4, 5};
	const int none[4] = {0, 0, 0, 0};
	rc = kmboot_median(t4, none, 4, B, 3, lo, hi, &cens);
	int bounded = 1, at5 = 0;
	for (int k = 0; k < B; k++) {
		bounded &= isinf(hi[k]) && hi[k] > 0 && lo[k] >= 2 && lo[k] <= 5 && lo[k] == floor(lo[k]);
		at5 += lo[k] == 5;
	}
	/* a resample holds the longest run (5) with probability 1 - (3/4)^4 = 0.68 */
	CHECK("kmboot.censored.bounded", !rc && cens == B && bounded && at5 > B / 2 && at5 < B * 8 / 10,
	      "rc %d censored %zu of %d, at 5: %d", rc, cens, B, at5);

	const int two[6] = {1, 1, 0, 0, 0, 0};
	const double tc[6] = {1, 2, 5, 5, 5, 5};
	rc = kmboot_median(tc, two, 6, B, 3, lo, hi, &cens);
	int kinds = 1;
	for (int k = 0; k < B; k++)
		kinds &= isinf(hi[k]) ? lo[k] >= 1 && lo[k] <= 5 : lo[k] == hi[k] && (lo[k] == 1 || lo[k] == 2);
	CHECK("kmboot.mixed", !rc && cens > 0 && cens < B && kinds, "rc %d censored %zu of %d", rc, cens, B);
	CHECK("kmboot.no_runs", kmboot_median(t6, all, 0, B, 3, lo, hi, &cens) == -1, "n = 0 accepted");
	return tl_done();
}
