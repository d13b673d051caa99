/* csv.h - the one CSV writer: RFC 4180 fields (a quote inside is doubled), for the
 * export of bin/study and the tables of the analysis tools. */
#ifndef LIB_CSV_H
#define LIB_CSV_H

#include <stdio.h>

/* A field, quoted only when it holds a comma, quote or line break (as sqlite3 -csv
 * writes): bin/study's export, whose readers take the values as they are. */
void csv_field(FILE *f, const char *s);
/* A text field, always quoted: the analysis tools' labels and reasons, which often
 * hold commas, keep one form whatever they hold (their readers strip the quotes). */
void csv_text(FILE *f, const char *s);

#endif
