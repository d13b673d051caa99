/* layout.c - the runs directory's layout (layout.h). */
#include "layout.h"

#include <stdio.h>
#include <string.h>

#include "journal.h"

#define LAY_DB "study.db"

int layout_db(const char *runs, const char *db, char *out, size_t len)
{
	if (db)
		return snprintf(out, len, "%s", db);
	return snprintf(out, len, "%s/" LAY_DB, runs ? runs : "runs");
}

int layout_reserved(const char *name, const char *db_file)
{
	const char *f = db_file ? db_file : LAY_DB;
	return *f && !strncmp(name, f, strlen(f));
}

int layout_campaign(const char *runs, const char *name, char *out, size_t len)
{
	return snprintf(out, len, "%s/%s", runs ? runs : "runs", name);
}

int layout_calibration(const char *runs, const char *tag, char *out, size_t len)
{
	return snprintf(out, len, "%s/.calibration%s%s%s", runs ? runs : "runs", tag ? "/" : "", tag ? tag : "",
			tag ? ".txt" : "");
}

int layout_file(const char *dir, int cache, const char *id, enum lay_kind kind, char *out, size_t len)
{
	static const char *const sub[2][LAY_NKINDS] = {{"", "jobs/", "jobs/", "logs/", "", ""},
						       {"cache/", "cache/", "cache/", "cache/", "cache/", "cache/"}};
	static const char *const ext[LAY_NKINDS] = {".h5", ".args", ".lock", ".log", ".h5" SB_JOURNAL_EXT,
						    ".h5" SB_CKPT_EXT};
	return snprintf(out, len, "%s%s%s%s%s", dir, dir[0] ? "/" : "", sub[cache != 0][kind], id, ext[kind]);
}

int layout_cache_particles(const char *dir, const char *key, char *out, size_t len)
{
	return snprintf(out, len, "%s%scache/%s.txt", dir, dir[0] ? "/" : "", key);
}

int layout_sub(const char *dir, const char *sub, char *out, size_t len)
{
	return snprintf(out, len, "%s/%s", dir, sub);
}

int layout_aside(const char *dir, const char *sub, const char *id, long attempt, char *out, size_t len)
{
	return snprintf(out, len, "%s/%s/%s.attempt%ld.h5", dir, sub, id, attempt);
}
