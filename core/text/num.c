/* num.c - strict decimal numbers (num.h). */
#include "num.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Length of the decimal real at s (sign, digits, point, exponent), or 0 when s does
 * not start with one. strtod alone is not the syntax: it reads hex ("0x10" is 16),
 * "inf", "nan" and leading blanks, which no input of ours means. */
static size_t real_syntax(const char *s, size_t n)
{
	size_t i = 0, digits = 0;
	if (i < n && (s[i] == '+' || s[i] == '-'))
		i++;
	while (i < n && s[i] >= '0' && s[i] <= '9')
		i++, digits++;
	if (i < n && s[i] == '.') {
		i++;
		while (i < n && s[i] >= '0' && s[i] <= '9')
			i++, digits++;
	}
	if (!digits)
		return 0;
	if (i < n && (s[i] == 'e' || s[i] == 'E')) {
		size_t j = i + 1, ed = 0;
		if (j < n && (s[j] == '+' || s[j] == '-'))
			j++;
		while (j < n && s[j] >= '0' && s[j] <= '9')
			j++, ed++;
		if (!ed)
			return 0; /* "1e": an exponent without digits is no number */
		i = j;
	}
	return i;
}

int num_real_n(const char *s, size_t n, double *x)
{
	if (!n || real_syntax(s, n) != n)
		return -1;
	/* strtod needs the token as a string: a copy, on the heap for a long one (digits
	 * may run long: 0.000...1) */
	char small[128], *buf = n < sizeof small ? small : malloc(n + 1);
	if (!buf)
		return -1;
	memcpy(buf, s, n);
	buf[n] = 0;
	char *end;
	errno = 0;
	const double v = strtod(buf, &end);
	/* ERANGE: beyond a double (inf) or below its normal range (a subnormal, or 0 for a
	 * number that is not 0) */
	const int bad = *end || errno || !isfinite(v);
	if (buf != small)
		free(buf);
	if (bad)
		return -1;
	*x = v;
	return 0;
}

int num_int_n(const char *s, size_t n, long long *x)
{
	size_t i = 0;
	if (n && (s[0] == '+' || s[0] == '-'))
		i++;
	if (i == n)
		return -1;
	for (size_t k = i; k < n; k++)
		if (s[k] < '0' || s[k] > '9')
			return -1;
	char small[64], *buf = n < sizeof small ? small : malloc(n + 1);
	if (!buf)
		return -1;
	memcpy(buf, s, n);
	buf[n] = 0;
	char *end;
	errno = 0;
	const long long v = strtoll(buf, &end, 10);
	const int bad = *end || errno;
	if (buf != small)
		free(buf);
	if (bad)
		return -1;
	*x = v;
	return 0;
}

int num_real(const char *s, double *x)
{
	return num_real_n(s, strlen(s), x);
}

int num_int(const char *s, long long *x)
{
	return num_int_n(s, strlen(s), x);
}
