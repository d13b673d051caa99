/* inifile.c - the one INI reader (core/text/inifile.c) that scene and campaign files share:
 * each key and each section header reaches its callback with the line it is on,
 * comments and indentation are gone, the first error stops the reading and names the
 * file and the line, a malformed line is named by its number, and the line limit
 * holds. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "inifile.h"
#include "testlib.h"

static char tmpdir[] = "/tmp/sb_inifile_XXXXXX";

/* What the callbacks saw, as text: "L:name=value" and "L:[header|name|len]" lines. */
typedef struct seen {
	char log[2048];
	int fail_key_line; /* a key on this line is an error (0: none) */
	int fail_section;  /* a section named "bad" is an error */
} seen;

static int on_section(void *user, const char *header, const char *name, int len, int line, sb_err *e)
{
	seen *s = user;
	size_t l = strlen(s->log);
	snprintf(s->log + l, sizeof s->log - l, "%d:[%s|%.*s|%d]\n", line, header, len > 0 ? len : 0, name, len);
	if (s->fail_section && len == 3 && !strncmp(name, "bad", 3))
		return sb_errf(e, SB_EUSAGE, "x:%d: bad section", line);
	return 0;
}

static int on_key(void *user, const char *name, const char *value, int line, sb_err *e)
{
	seen *s = user;
	size_t l = strlen(s->log);
	snprintf(s->log + l, sizeof s->log - l, "%d:%s=%s\n", line, name, value);
	if (line == s->fail_key_line)
		return sb_errf(e, SB_EUSAGE, "x:%d: %s: bad value", line, name);
	return 0;
}

/* writes text to NAME in the temporary directory, reads it; the path into path */
static int read_text(const char *name, const char *text, seen *s, int max_lines, int sections, sb_err *e, char *path,
		     size_t n)
{
	snprintf(path, n, "%s/%s", tmpdir, name);
	FILE *f = fopen(path, "w");
	if (!f)
		return -1;
	fputs(text, f);
	fclose(f);
	memset(e, 0, sizeof *e);
	const inifile in = {path, "test file", max_lines, sections ? on_section : NULL, on_key, s};
	return inifile_read(&in, e);
}

int main(void)
{
	if (!mkdtemp(tmpdir)) {
		CHECK("inifile.tmpdir", 0, "mkdtemp failed");
		return tl_done();
	}
	char path[256], want[512], id[64];
	sb_err e;
	seen s = {0};
	int rc = read_text("ok.ini",
			   "# comment\n"
			   "top = 1\n"
			   "\n"
			   "[a]  # the first\n"
			   "  k = v   # inline\n"
			   "; another\n"
			   "w = x#y\n"
			   "  [b]\n"
			   "z = 2 ; semicolon\n"
			   "[]\n",
			   &s, 100, 1, &e, path, sizeof path);
	const char *expect = "2:top=1\n4:[[a]  |a|1]\n5:k=v\n7:w=x#y\n8:[[b]|b|1]\n9:z=2\n10:[[]||0]\n";
	CHECK("inifile.lines_comments_indentation", rc == 0 && !strcmp(s.log, expect), "rc %d (%s); saw\n%s", rc, e.msg,
	      s.log);

	memset(&s, 0, sizeof s);
	rc = read_text("nosec.ini", "[x]\nk = 1\n", &s, 100, 0, &e, path, sizeof path);
	CHECK("inifile.no_section_callback", rc == 0 && !strcmp(s.log, "2:k=1\n"), "rc %d; saw %s", rc, s.log);

	memset(&s, 0, sizeof s);
	s.fail_key_line = 3;
	rc = read_text("keyerr.ini", "a = 1\n\nb = 2\nc = 3\nthis is malformed\n", &s, 100, 1, &e, path, sizeof path);
	CHECK("inifile.key_error_stops", rc == SB_EUSAGE && !strcmp(e.msg, "x:3: b: bad value") &&
						 !strcmp(s.log, "1:a=1\n3:b=2\n"),
	      "rc %d '%s'; saw %s", rc, e.msg, s.log);

	memset(&s, 0, sizeof s);
	s.fail_section = 1;
	rc = read_text("secerr.ini", "a = 1\n[bad]\nb = 2\n", &s, 100, 1, &e, path, sizeof path);
	CHECK("inifile.section_error_stops", rc == SB_EUSAGE && !strcmp(e.msg, "x:2: bad section") &&
						     !strstr(s.log, "b=2"),
	      "rc %d '%s'; saw %s", rc, e.msg, s.log);

	memset(&s, 0, sizeof s);
	rc = read_text("open.ini", "a = 1\n[open\nb = 2\n", &s, 100, 1, &e, path, sizeof path);
	CHECK("inifile.header_without_bracket", strstr(s.log, "2:[[open||-1]") != NULL, "saw %s", s.log);
	snprintf(want, sizeof want, "%s:2: malformed line", path);
	CHECK("inifile.header_without_bracket.malformed", rc == SB_EUSAGE && !strncmp(e.msg, want, strlen(want)),
	      "rc %d '%s'", rc, e.msg);

	memset(&s, 0, sizeof s);
	rc = read_text("malformed.ini", "a = 1\n# c\nno equals here\nb = 2\n", &s, 100, 1, &e, path, sizeof path);
	snprintf(want, sizeof want, "%s:3: malformed line (expected key = value or [section])", path);
	CHECK("inifile.malformed_line", rc == SB_EUSAGE && !strcmp(e.msg, want), "rc %d '%s'", rc, e.msg);

	memset(&s, 0, sizeof s);
	rc = read_text("long.ini", "# 1\n# 2\n# 3\na = 1\n", &s, 3, 1, &e, path, sizeof path);
	snprintf(want, sizeof want, "%s:4: more than 3 lines", path);
	CHECK("inifile.max_lines", rc == SB_EUSAGE && !strncmp(e.msg, want, strlen(want)) && !s.log[0], "rc %d '%s'",
	      rc, e.msg);
	memset(&s, 0, sizeof s);
	rc = read_text("fits.ini", "# 1\n# 2\na = 1\n", &s, 3, 1, &e, path, sizeof path);
	CHECK("inifile.max_lines.fits", rc == 0 && !strcmp(s.log, "3:a=1\n"), "rc %d '%s'", rc, e.msg);

	memset(&s, 0, sizeof s);
	memset(&e, 0, sizeof e);
	const inifile dir = {tmpdir, "test file", 100, on_section, on_key, &s};
	rc = inifile_read(&dir, &e);
	CHECK("inifile.directory_refused", rc == SB_EUSAGE && strstr(e.msg, tmpdir), "rc %d '%s'", rc, e.msg);

	/* a database or a run file named where a text file belongs is named as what it is
	 * (not "NUL byte in column 16"); text that only begins like one is still text */
	static const struct {
		const char *name, *bytes, *what;
		size_t n;
	} BIN[] = {
		{"study.db", "SQLite format 3\0\x10\0\x02\x02", "a SQLite database", 21},
		{"run.h5", "\x89HDF\r\n\x1a\n\0\0\0\0", "an HDF5 file", 12},
	};
	for (size_t k = 0; k < sizeof BIN / sizeof *BIN; k++) {
		snprintf(path, sizeof path, "%s/%s", tmpdir, BIN[k].name);
		FILE *f = fopen(path, "wb");
		if (f) {
			fwrite(BIN[k].bytes, 1, BIN[k].n, f);
			fclose(f);
		}
		memset(&s, 0, sizeof s);
		memset(&e, 0, sizeof e);
		const inifile bin = {path, "test file", 100, on_section, on_key, &s};
		rc = inifile_read(&bin, &e);
		snprintf(want, sizeof want, "%s: %s, not a test file", path, BIN[k].what);
		snprintf(id, sizeof id, "inifile.binary.%s", BIN[k].name);
		CHECK(id, rc == SB_EUSAGE && !strncmp(e.msg, want, strlen(want)), "rc %d '%s'", rc, e.msg);
	}
	memset(&s, 0, sizeof s);
	rc = read_text("sqlite.ini", "SQLite = format 3\n", &s, 100, 1, &e, path, sizeof path);
	CHECK("inifile.binary.text_alike", rc == 0 && !strcmp(s.log, "1:SQLite=format 3\n"), "rc %d '%s' %s", rc,
	      e.msg, s.log);

	char cmd[300];
	snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
	if (system(cmd))
		printf("# could not remove %s\n", tmpdir);
	return tl_done();
}
