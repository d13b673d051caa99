/* safe.c - name checks and shell quoting for everything handed to GNU parallel. */
#include "safe.h"

#include <string.h>

static int in_set(const char *s, const char *extra)
{
	for (; *s; s++) {
		char c = *s;
		if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || strchr(extra, c)))
			return 0;
	}
	return 1;
}

int safe_name(const char *s)
{
	size_t l = strlen(s);
	return l >= 1 && l <= 64 && s[0] != '.' && s[0] != '-' && in_set(s, "_.-");
}

int safe_path_value(const char *s)
{
	return *s && in_set(s, "_./+-") && !strstr(s, "..");
}

int safe_shell_quote(const char *s, char *out, size_t len)
{
	size_t k = 0;
	/* Inside single quotes nothing is special but the quote itself, which is closed,
	 * escaped and reopened. */
#define PUT(ch) do { if (k + 1 >= len) return -1; out[k++] = (ch); } while (0)
	PUT('\'');
	for (; *s; s++) {
		if (*s == '\'') {
			PUT('\'');
			PUT('\\');
			PUT('\'');
			PUT('\'');
		} else {
			PUT(*s);
		}
	}
	PUT('\'');
#undef PUT
	out[k] = 0;
	return 0;
}
