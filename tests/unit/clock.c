/* clock.c - the per-phase profile's TIC/TOC (core/base/clock.h): they time the run
 * they are named (no hidden variable of a fixed name: this run is called r), only when
 * its profile is on, and TOC is one statement, so under an if without braces the else
 * stays that if's (with TOC an unbraced if it took the else: a dangling else). */
#include "clock.h"
#include "testlib.h"

struct run {
	int profile;
	double tphase[2];
};

int main(void)
{
	struct run r = {1, {0, 0}};
	{
		TIC(&r, 0);
		volatile double x = 0;
		for (int i = 0; i < 200000; i++)
			x += i;
		TOC(&r, 0);
	}
	CHECK("clock.tic_toc.the_named_run", r.tphase[0] > 0, "no time added to r.tphase[0]");
	r.profile = 0;
	int other = 0;
	for (int round = 0; round < 2; round++) {
		TIC(&r, 1);
		if (round == 0)
			TOC(&r, 1);
		else
			other++;
	}
	CHECK("clock.toc.one_statement", other == 1, "the else ran %d times for one round of two", other);
	CHECK("clock.tic_toc.profile_off", r.tphase[1] == 0, "time added with the profile off: %g", r.tphase[1]);
	return tl_done();
}
