/* study_safe.c - what may reach a shell or a path (study/campaign/safe.c): campaign names are
 * one plain path component, file values plain relative or absolute names without "..",
 * and shell quoting gives back every byte of its input through /bin/sh, runs nothing,
 * and refuses what does not fit its buffer. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "campaign/safe.h"
#include "testlib.h"

static char tmpdir[] = "/tmp/sb_safe_XXXXXX";

static void test_names(void)
{
	char long64[65], long65[66], id[128];
	memset(long64, 'a', 64);
	long64[64] = 0;
	memset(long65, 'b', 65);
	long65[65] = 0;
	const char *good[] = {"demo", "a", "Z", "claim4_waiting_time", "A-b_c.9", "x.", "1..2", long64, NULL};
	const char *bad[] = {"", ".", "..", ".hidden", "-rf", "a/b", "/abs", "a b", "a;b", "$x", "a'b", "a\"b", "`x`",
			     "a\nb", "a\tb", "caf\xc3\xa9", "*", "a\\b", long65, NULL};
	for (int i = 0; good[i]; i++) {
		snprintf(id, sizeof id, "study.safe.name.ok.%d", i);
		CHECK(id, safe_name(good[i]), "'%s' refused", good[i]);
	}
	for (int i = 0; bad[i]; i++) {
		snprintf(id, sizeof id, "study.safe.name.refused.%d", i);
		CHECK(id, !safe_name(bad[i]), "'%s' accepted", bad[i]);
	}
}

static void test_path_values(void)
{
	char id[128];
	const char *good[] = {"bed.txt", "dir/bed.txt", "/abs/p+q-r_s.txt", "cache/0123abcd.txt", "./x", "a.b.c", NULL};
	const char *bad[] = {"", "..", "../x", "a/../b", "a/..", "x..y", "a b", "a;b", "$(x)", "a'b", "~/x", "a\\b",
			     "a\nb", "a*", "a|b", "caf\xc3\xa9", NULL};
	for (int i = 0; good[i]; i++) {
		snprintf(id, sizeof id, "study.safe.path.ok.%d", i);
		CHECK(id, safe_path_value(good[i]), "'%s' refused", good[i]);
	}
	for (int i = 0; bad[i]; i++) {
		snprintf(id, sizeof id, "study.safe.path.refused.%d", i);
		CHECK(id, !safe_path_value(bad[i]), "'%s' accepted", bad[i]);
	}
}

/* What /bin/sh makes of `printf %s QUOTED`: the bytes printf was given (len), or -1. */
static long through_shell(const char *quoted, char *out, size_t cap)
{
	char cmd[4096];
	snprintf(cmd, sizeof cmd, "cd '%s' && printf %%s %s", tmpdir, quoted);
	FILE *p = popen(cmd, "r");
	if (!p)
		return -1;
	size_t n = fread(out, 1, cap, p);
	return pclose(p) == 0 ? (long)n : -1;
}

static void test_quote(void)
{
	char q[1024];
	CHECK("study.safe.quote.plain", !safe_shell_quote("abc", q, sizeof q) && !strcmp(q, "'abc'"), "got %s", q);
	CHECK("study.safe.quote.empty", !safe_shell_quote("", q, sizeof q) && !strcmp(q, "''"), "got %s", q);
	CHECK("study.safe.quote.single_quote", !safe_shell_quote("it's", q, sizeof q) && !strcmp(q, "'it'\\''s'"),
	      "got %s", q);
	/* the exact fit: 'abc' and its NUL are 6 bytes */
	CHECK("study.safe.quote.fits", !safe_shell_quote("abc", q, 6) && !strcmp(q, "'abc'"), "6 bytes refused");
	CHECK("study.safe.quote.too_long", safe_shell_quote("abc", q, 5) == -1, "5 bytes accepted");
	CHECK("study.safe.quote.too_long_quote", safe_shell_quote("'", q, 6) == -1 && !safe_shell_quote("'", q, 7),
	      "the escaped quote ''\\''' needs 7 bytes");
	CHECK("study.safe.quote.no_room", safe_shell_quote("", q, 0) == -1 && safe_shell_quote("", q, 2) == -1,
	      "an empty buffer accepted");

	/* hostile words come back byte for byte through a real shell, and run nothing */
	const char *words[] = {"plain", "two words", "it's", "'''", "$(touch pwned)", "`touch pwned`", "${HOME}", "$HOME",
			       "a\"b", "\\", "\\'", "x; touch pwned", "a && touch pwned", "*", "~", "line\nbreak",
			       "tab\there", "!event", "#comment", "-n", "caf\xc3\xa9", "", NULL};
	for (int i = 0; words[i]; i++) {
		char id[96], out[1024];
		snprintf(id, sizeof id, "study.safe.quote.shell.%d", i);
		long n = safe_shell_quote(words[i], q, sizeof q) ? -2 : through_shell(q, out, sizeof out);
		CHECK(id, n == (long)strlen(words[i]) && !memcmp(out, words[i], (size_t)n), "'%s' came back as %ld bytes",
		      words[i], n);
	}
	char pwned[128];
	snprintf(pwned, sizeof pwned, "%s/pwned", tmpdir);
	struct stat st;
	CHECK("study.safe.quote.ran_nothing", stat(pwned, &st) != 0, "a quoted word ran a command");
	unlink(pwned);
}

int main(void)
{
	if (!mkdtemp(tmpdir)) {
		printf("FAIL study.safe.setup: cannot make a temporary directory\n");
		return 1;
	}
	test_names();
	test_path_values();
	test_quote();
	rmdir(tmpdir);
	return tl_done();
}
