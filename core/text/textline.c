/* textline.c - reading text input files line by line (textline.h). */
#include "textline.h"

#include <string.h>

/* The binary files a user may name by mistake where a text file belongs (the campaign's
 * database for its campaign file, a run file for its scene), known by how they begin. */
static const char *binary_kind(const char *s, long len)
{
	static const struct {
		const char *magic, *what;
	} KINDS[] = {
		{"SQLite format 3", "a SQLite database"},
		{"\x89HDF", "an HDF5 file"},
	};
	for (size_t k = 0; k < sizeof KINDS / sizeof *KINDS; k++) {
		const size_t m = strlen(KINDS[k].magic);
		if ((size_t)len >= m && !memcmp(s, KINDS[k].magic, m))
			return KINDS[k].what;
	}
	return NULL;
}

int textline_next(textline *t, char *str, int num, sb_err *e)
{
	int ch = 0;
	long len = 0, nul = 0; /* nul: column of the first NUL byte, 1-based */
	int first = t->line == 0;
	while (len < num - 1 && (ch = getc(t->f)) != EOF) {
		if (ch == '\r') {
			/* CRLF: the line ends at the LF and is measured without the CR */
			const int nx = getc(t->f);
			if (nx == '\n') {
				str[len++] = '\n';
				break;
			}
			if (nx != EOF)
				ungetc(nx, t->f);
		}
		if (!ch && !nul)
			nul = len + 1;
		str[len++] = (char)ch;
		if (first && len == TEXTLINE_BOM_LEN && !memcmp(str, TEXTLINE_BOM, TEXTLINE_BOM_LEN)) {
			len = 0; /* the byte-order mark opens the file, it is no part of its first line */
			first = 0;
			continue;
		}
		if (ch == '\n')
			break;
	}
	if (!len)
		return 0;
	str[len] = 0;
	if (t->line >= t->max_lines) {
		sb_errf(e, SB_EUSAGE, "%s:%d: more than %d lines (a %s is a few dozen)", t->path, t->line + 1,
			t->max_lines, t->kind);
		return -1;
	}
	t->line++;
	const char *binary = t->line == 1 ? binary_kind(str, len) : NULL;
	if (binary) {
		sb_errf(e, SB_EUSAGE, "%s: %s, not a %s (a %s is text)", t->path, binary, t->kind, t->kind);
		return -1;
	}
	if (nul) {
		sb_errf(e, SB_EUSAGE, "%s:%d: NUL byte in column %ld (a %s is text)", t->path, t->line, nul, t->kind);
		return -1;
	}
	if (len == num - 1 && str[len - 1] != '\n') {
		/* a line of exactly num - 1 characters fits: only its newline (LF or CRLF) is left */
		ch = getc(t->f);
		if (ch == '\r') {
			ch = getc(t->f);
			if (ch != '\n')
				ch = 'x';
		}
		if (ch != EOF && ch != '\n') {
			sb_errf(e, SB_EUSAGE, "%s:%d: line too long (the limit is %d characters)", t->path, t->line,
				num - 1);
			return -1;
		}
	}
	return 1;
}
