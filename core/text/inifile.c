/* inifile.c - the one reader of INI inputs (inifile.h). */
#include "inifile.h"

#include <errno.h>
#include <ini.h> /* libinih */
#include <stdio.h>
#include <string.h>

#include "fsutil.h"
#include "textline.h"

typedef struct reader {
	const inifile *in;
	FILE *f;
	sb_err *e;
	int line;     /* lines read so far: inih calls the key handler right after reading its line */
	int err_line; /* the line of the first error a callback or the line reader found */
} reader;

/* inih's Debian build has no INI_HANDLER_LINENO, so lines are counted here; inih
 * also tells nothing about a section without keys, so headers are checked here; and
 * it keeps "#" comments after a value, so they go here too. */
static char *next_line(char *str, int num, void *stream)
{
	reader *r = stream;
	if (r->err_line)
		return NULL; /* stop at the first error */
	textline tl = {r->f, r->in->path, r->in->kind, r->in->max_lines, r->line};
	const int got = textline_next(&tl, str, num, r->e);
	r->line = tl.line;
	if (got < 0)
		r->err_line = r->line ? r->line : 1;
	if (got <= 0)
		return NULL;
	const size_t lead = strspn(str, " \t");
	if (lead)
		memmove(str, str + lead, strlen(str + lead) + 1);
	for (char *h = strchr(str, '#'); h; h = strchr(h + 1, '#'))
		if (h == str || h[-1] == ' ' || h[-1] == '\t') {
			h[0] = '\n';
			h[1] = 0;
			break;
		}
	if (str[0] == '[' && r->in->section) {
		char header[256];
		snprintf(header, sizeof header, "%.*s", (int)strcspn(str, "\r\n"), str);
		const char *q = strchr(str, ']');
		const int len = q ? (int)(q - str - 1) : -1;
		if (r->in->section(r->in->user, header, str + 1, len, r->line, r->e)) {
			r->err_line = r->line;
			return NULL;
		}
	}
	return str;
}

static int on_key(void *user, const char *section, const char *name, const char *value)
{
	reader *r = user;
	(void)section; /* the section callback has seen it, also when it has no keys */
	if (r->err_line)
		return 1; /* keep only the first error */
	if (r->in->key(r->in->user, name, value, r->line, r->e)) {
		r->err_line = r->line;
		return 0;
	}
	return 1;
}

int inifile_read(const inifile *in, sb_err *e)
{
	if (e->code)
		return e->code;
	FILE *f = fs_open_input(in->path, in->kind, 0, SB_EUSAGE, e);
	if (!f)
		return e->code;
	reader r = {in, f, e, 0, 0};
	const int rc = ini_parse_stream(next_line, &r, on_key, &r);
	const int rerr = ferror(f) ? (errno ? errno : EIO) : 0;
	fclose(f);
	if (rerr && !r.err_line)
		return sb_errf(e, SB_EIO, "%s: cannot read %s: %s", in->path, in->kind, strerror(rerr));
	if (rc > 0 && (!r.err_line || rc < r.err_line)) {
		/* a syntax error inih found before any error of ours */
		e->code = 0;
		return sb_errf(e, SB_EUSAGE, "%s:%d: malformed line (expected key = value or [section])", in->path, rc);
	}
	if (e->code)
		return e->code;
	if (rc < 0)
		return sb_errf(e, SB_EIO, "%s: cannot read %s", in->path, in->kind);
	return 0;
}
