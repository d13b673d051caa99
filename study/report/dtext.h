/* dtext.h - a double as the text a user would write. */
#ifndef ST_DTEXT_H
#define ST_DTEXT_H

#include <stddef.h>

/* The shortest text that reads back as the same double (0.85, not
 * 0.84999999999999998; 20, not 2e+01): what the user wrote, and still exact. */
void dtext_shortest(double v, char *buf, size_t len);

/* A duration in seconds as "42 s", "3.5 min", "2.1 h" ("unknown" when negative): the
 * ETAs' and the calibration's age's one form. */
void dtext_duration(double s, char *buf, size_t len);

#endif
