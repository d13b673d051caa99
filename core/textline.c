/* textline.c - reading text input files line by line (textline.h). */
#include "textline.h"

int textline_next(textline *t, char *str, int num, sb_err *e)
{
	int ch = 0;
	long len = 0, nul = 0; /* nul: column of the first NUL byte, 1-based */
	while (len < num - 1 && (ch = getc(t->f)) != EOF) {
		if (!ch && !nul)
			nul = len + 1;
		str[len++] = (char)ch;
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
	if (nul) {
		sb_errf(e, SB_EUSAGE, "%s:%d: NUL byte in column %ld (a %s is text)", t->path, t->line, nul, t->kind);
		return -1;
	}
	if (len == num - 1 && str[len - 1] != '\n') {
		/* a line of exactly num - 1 characters fits: only its newline is left */
		ch = getc(t->f);
		if (ch != EOF && ch != '\n') {
			sb_errf(e, SB_EUSAGE, "%s:%d: line too long (the limit is %d characters)", t->path, t->line,
				num - 1);
			return -1;
		}
	}
	return 1;
}
