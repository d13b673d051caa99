/* inifile.h - the one reader of INI inputs (scene files, campaign files): libinih splits
 * key = value, this module feeds it lines and says which line each key came from. */
#ifndef SB_INIFILE_H
#define SB_INIFILE_H

#include <stddef.h>

#include "err.h"

/* A [section] line. header is the line as written (indentation and a comment gone, no
 * line end); name and len the text between its brackets (len < 0: no ']', the line is
 * then malformed unless the callback says more). 0 to go on, else an error code with
 * the message (path:line: ...) in e. */
typedef int (*inifile_section_fn)(void *user, const char *header, const char *name, int len, int line, sb_err *e);
/* A key = value line: 0 to go on, else an error code with the message in e. */
typedef int (*inifile_key_fn)(void *user, const char *name, const char *value, int line, sb_err *e);

typedef struct inifile {
	const char *path;
	const char *kind;       /* "scene file": what the errors call it */
	int max_lines;          /* more is refused (an endless pipe of comments must end) */
	inifile_section_fn section; /* NULL: every section is taken */
	inifile_key_fn key;
	void *user;
} inifile;

/* Reads the file: lines as textline_next gives them (NUL bytes, over-long lines refused),
 * indentation stripped (libinih would take an indented line as the continuation of the
 * previous value), comments dropped (a line that starts with '#' or ';', and " # ..." or
 * " ; ..." after a value), each section header and each key handed to the callbacks
 * with its line number. Stops at the first error: 0, or its code with the message in e
 * naming the file and the line (a line that is neither key = value nor [section]:
 * "malformed line"). A directory or a FIFO is refused before anything is read. */
int inifile_read(const inifile *in, sb_err *e);

#endif
