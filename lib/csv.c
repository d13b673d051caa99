/* csv.c - RFC 4180 fields (csv.h). */
#include "csv.h"

#include <string.h>

void csv_text(FILE *f, const char *s)
{
	fputc('"', f);
	for (; *s; s++) {
		if (*s == '"')
			fputc('"', f);
		fputc(*s, f);
	}
	fputc('"', f);
}

void csv_field(FILE *f, const char *s)
{
	if (strpbrk(s, ",\"\r\n"))
		csv_text(f, s);
	else
		fputs(s, f);
}
