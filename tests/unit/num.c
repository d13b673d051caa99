/* num.c - the one strict reading of numbers (core/text/num.h): decimal notation only, the
 * whole text, finite, within a double's normal range; integers exact in 64 bits. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "num.h"
#include "testlib.h"

int main(void)
{
	char id[160];
	static const struct {
		const char *s;
		double v;
	} good[] = {{"0", 0},	  {"-0", 0},	  {"1", 1},	  {"+2.5", 2.5},   {"1.", 1},	  {".5", 0.5},
		    {"-.5", -0.5}, {"3e6", 3e6},  {"3E+06", 3e6}, {"2.5e-5", 2.5e-5}, {"1e308", 1e308},
		    {"2.2250738585072014e-308", 2.2250738585072014e-308},
		    {"0.000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000"
		     "0000000000000000000000000000000000000001", 1e-136}};
	for (size_t i = 0; i < sizeof good / sizeof *good; i++) {
		double x = NAN;
		snprintf(id, sizeof id, "num.real.accepts.%zu", i);
		CHECK(id, num_real(good[i].s, &x) == 0 && x == good[i].v, "'%s' -> %g", good[i].s, x);
	}
	static const char *const bad[] = {"",	  " 1",	 "1 ",	"0x10", "0x1p3", "inf", "-inf",	"nan", "NaN",
					  "infinity", "1e", "1e+", ".",	   "-",	    "+",   "--1",  "1..3", "1,5",
					  "1e309", "-1e309", "1e-320", "4.9e-324", "1.5x", "1 2", "\t2", "e5"};
	for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
		double x = 42;
		snprintf(id, sizeof id, "num.real.refuses.%zu", i);
		CHECK(id, num_real(bad[i], &x) == -1 && x == 42, "'%s' accepted as %g", bad[i], x);
	}
	double x;
	CHECK("num.real.token", num_real_n("2.5 rest", 3, &x) == 0 && x == 2.5, "%g", x);
	CHECK("num.real.token_cut", num_real_n("2.5e", 4, &x) == -1, "'2.5e' accepted");

	long long k = 0;
	CHECK("num.int.accepts", num_int("9007199254740993", &k) == 0 && k == 9007199254740993LL, "%lld", k);
	CHECK("num.int.sign", num_int("-12", &k) == 0 && k == -12 && num_int("+7", &k) == 0 && k == 7, "%lld", k);
	CHECK("num.int.max", num_int("9223372036854775807", &k) == 0 && k == 9223372036854775807LL, "%lld", k);
	static const char *const ibad[] = {"",	 "1.5", "1e3", "0x10", " 1", "1 ", "9223372036854775808",
					   "-9223372036854775809", "--1", "+", "1.", "inf"};
	for (size_t i = 0; i < sizeof ibad / sizeof *ibad; i++) {
		k = 42;
		snprintf(id, sizeof id, "num.int.refuses.%zu", i);
		CHECK(id, num_int(ibad[i], &k) == -1 && k == 42, "'%s' accepted as %lld", ibad[i], k);
	}
	CHECK("num.int.token", num_int_n("12 34", 2, &k) == 0 && k == 12, "%lld", k);
	return tl_done();
}
