/* textline.h - one line of a text input file for libinih's stream reader (scene and
 * campaign files), read byte by byte: fgets cannot tell a NUL byte from the end of a
 * line (the rest of the line would vanish), a line longer than the reader's buffer
 * would be cut by inih and its tail read as a line of its own (the end of a long
 * comment could set a key), and a stream that never ends (a pipe) must end. Each is
 * an error naming the file and the line. A UTF-8 byte-order mark that opens the file is
 * dropped, and so is the CR of a CRLF line end: the line is measured without them, as
 * in every reader of text inputs (docs/inputs.md, "Lines"). */
#ifndef SB_TEXTLINE_H
#define SB_TEXTLINE_H

#include <stdio.h>

#include "err.h"

/* the UTF-8 byte-order mark (U+FEFF) that some editors put at the start of a file */
#define TEXTLINE_BOM "\xEF\xBB\xBF"
#define TEXTLINE_BOM_LEN 3

typedef struct textline {
	FILE *f;
	const char *path;
	const char *kind;  /* "scene file", "campaign file": what the error calls it */
	int max_lines;
	int line;          /* lines read so far */
} textline;

/* Reads the next line into str (at most num - 1 characters and its newline, a CRLF
 * given as LF): 1 a line, 0 the end of the file, -1 an error (in e: path:line, the
 * column or the limit). */
int textline_next(textline *t, char *str, int num, sb_err *e);

#endif
