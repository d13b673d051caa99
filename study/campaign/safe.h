/* safe.h - what may reach a shell or a path: name checks and POSIX shell quoting.
 * GNU parallel runs every job through a shell, so every word the driver hands it is
 * either checked against a safe alphabet or single-quoted here. */
#ifndef ST_SAFE_H
#define ST_SAFE_H

#include <stddef.h>

/* A campaign name: [A-Za-z0-9_.-], 1..64 characters, not starting with '.' or '-'
 * (so it is one path component that cannot be "..", hidden, or an option). */
int safe_name(const char *s);

/* A file name value (e.g. particles = FILE): [A-Za-z0-9_./+-] only, no "..". */
int safe_path_value(const char *s);
/* what an error says of a value safe_path_value refuses */
#define SAFE_PATH_RULE "is not a plain path ([A-Za-z0-9_./+-], no '..')"

/* Single-quote s for a POSIX shell into out ('it'\''s'); returns -1 if it does not fit. */
int safe_shell_quote(const char *s, char *out, size_t len);

#endif
