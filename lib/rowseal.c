/* rowseal.c - the seal of a run's rows in the study database (rowseal.h). */
#include "rowseal.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "fnv.h"
#include "schema.h"

/* A value of a column as its type and bytes: 'N' null, 'I' a 64-bit integer and 'R' a
 * double as 8 little-endian bytes (the bits, not a printed form), 'T' text and 'B' a
 * blob with their length; then the name. Two values mix the same only when they are the
 * same typed value, so a number edited into text ('abc', '25') changes the seal. */
static uint64_t mix_value(uint64_t h, const char *name, sqlite3_stmt *q, int i)
{
	unsigned char b[8];
	uint64_t v = 0;
	char tag;
	const void *p = NULL;
	size_t n = 0;
	switch (sqlite3_column_type(q, i)) {
	case SQLITE_INTEGER: tag = 'I'; v = (uint64_t)sqlite3_column_int64(q, i); break;
	case SQLITE_FLOAT: {
		double d = sqlite3_column_double(q, i);
		tag = 'R';
		memcpy(&v, &d, sizeof v);
		break;
	}
	case SQLITE_TEXT:
		tag = 'T';
		p = sqlite3_column_text(q, i);
		n = (size_t)sqlite3_column_bytes(q, i);
		v = n;
		break;
	case SQLITE_BLOB:
		tag = 'B';
		p = sqlite3_column_blob(q, i);
		n = (size_t)sqlite3_column_bytes(q, i);
		v = n;
		break;
	default: tag = 'N'; break;
	}
	h = sb_fnv(h, name, strlen(name) + 1);
	h = sb_fnv(h, &tag, 1);
	for (int k = 0; k < 8; k++)
		b[k] = (unsigned char)(v >> (8 * k));
	h = sb_fnv(h, b, sizeof b);
	return p ? sb_fnv(h, p, n) : h;
}

/* every column of the statement's row mixed in, but the seal's own */
static uint64_t mix_row(uint64_t h, sqlite3_stmt *q)
{
	for (int i = 0; i < sqlite3_column_count(q); i++) {
		const char *name = sqlite3_column_name(q, i);
		if (strcmp(name, ROWSEAL_COLUMN))
			h = mix_value(h, name, q, i);
	}
	return h;
}

/* The seal of the rows, and the seal recorded (stored: 1 when the result row has one). */
static int seal_rows(sql_db *d, const char *campaign, const char *run, char seal[17], char recorded[17],
		     sb_err *e)
{
	sqlite3_stmt *q;
	seal[0] = recorded[0] = 0;
	if (sql_exec(d, e, &q, "SELECT * FROM result WHERE campaign = ? AND run = ?", "tt", campaign, run))
		return e->code;
	int rc = sqlite3_step(q);
	if (rc != SQLITE_ROW) {
		sql_done(d, q, e);
		return e->code;
	}
	uint64_t h = sb_fnv(SB_FNV_BASIS, campaign, strlen(campaign) + 1);
	h = sb_fnv(h, run, strlen(run) + 1);
	h = mix_row(h, q);
	for (int i = 0; i < sqlite3_column_count(q); i++)
		if (!strcmp(sqlite3_column_name(q, i), ROWSEAL_COLUMN) && sqlite3_column_text(q, i))
			snprintf(recorded, 17, "%s", (const char *)sqlite3_column_text(q, i));
	if (sql_done(d, q, e))
		return e->code;
	if (sql_exec(d, e, &q, "SELECT replicate, seed, cache_key FROM run WHERE campaign = ? AND id = ?", "tt", campaign,
		     run))
		return e->code;
	if ((rc = sqlite3_step(q)) == SQLITE_ROW)
		h = mix_row(h, q);
	if (sql_done(d, q, e))
		return e->code;
	if (sql_exec(d, e, &q, "SELECT key, value FROM param WHERE campaign = ? AND run = ? ORDER BY key", "tt",
		     campaign, run))
		return e->code;
	while ((rc = sqlite3_step(q)) == SQLITE_ROW)
		h = mix_row(h, q);
	if (sql_done(d, q, e))
		return e->code;
	snprintf(seal, 17, "%016llx", (unsigned long long)h);
	return 0;
}

int rowseal_of(sql_db *d, const char *campaign, const char *run, char seal[17], sb_err *e)
{
	char recorded[17];
	return seal_rows(d, campaign, run, seal, recorded, e);
}

int rowseal_put(sql_db *d, const char *campaign, const char *run, sb_err *e)
{
	char seal[17];
	if (rowseal_of(d, campaign, run, seal, e))
		return e->code;
	if (!seal[0])
		return sb_errf(e, SB_EIO, "%s: run %s: no result row to seal", d->path, run);
	return sql_exec(d, e, NULL, "UPDATE result SET " ROWSEAL_COLUMN " = ? WHERE campaign = ? AND run = ?", "ttt", seal,
			campaign, run);
}

int rowseal_bad(sql_db *d, const char *campaign, const char *after, int done_needs_result, char *run, size_t rlen,
		char *why, size_t wlen, sb_err *e)
{
	run[0] = why[0] = 0;
	if (!schema_result_current(d)) /* another version's columns: not its seal */
		return 0;
	sqlite3_stmt *q;
	if (sql_exec(d, e, &q,
		     "SELECT r.id, r.state, s.run IS NOT NULL FROM run r LEFT JOIN result s ON s.campaign = r.campaign"
		     " AND s.run = r.id WHERE r.campaign = ? AND (?2 IS NULL OR r.id > ?2) ORDER BY r.id",
		     "tt", campaign, after))
		return e->code;
	int bad = 0, rc;
	while (!bad && !e->code && (rc = sqlite3_step(q)) == SQLITE_ROW) {
		const char *id = (const char *)sqlite3_column_text(q, 0), *state = (const char *)sqlite3_column_text(q, 1);
		if (!id)
			continue;
		if (!sqlite3_column_int(q, 2)) {
			if (done_needs_result && state && !strcmp(state, "done")) {
				bad = 1;
				snprintf(run, rlen, "%s", id);
				snprintf(why, wlen, "run %s: recorded done without its row in table result", id);
			}
			continue;
		}
		char seal[17], recorded[17];
		if (seal_rows(d, campaign, id, seal, recorded, e))
			break;
		if (strcmp(seal, recorded)) {
			bad = 1;
			snprintf(run, rlen, "%s", id);
			snprintf(why, wlen, "run %s: its rows in tables run, param and result are not those recorded (row seal %s, "
				 "recorded %s)", id, seal, recorded[0] ? recorded : "none");
		}
	}
	sql_done(d, q, e);
	return e->code ? e->code : bad;
}

int rowseal_check(sql_db *d, const char *campaign, sb_err *e)
{
	char run[128], why[600];
	int r = rowseal_bad(d, campaign, NULL, 1, run, sizeof run, why, sizeof why, e);
	if (r <= 0 || e->code)
		return e->code;
	/* an edit, or a page damaged where SQLite's reads do not fail: a quick check tells */
	char bad[512];
	if (sql_check(d, bad, sizeof bad))
		return sb_errf(e, SB_EIO, "%s: the database is corrupt (quick_check: %s): %s", d->path, bad, SQL_REBUILD);
	return sb_errf(e, SB_EIO, "%s: campaign '%s': %s: edited or damaged since the run was recorded: study run on its "
		       "campaign file writes its rows again from the campaign and run files (docs/database.md, \"A "
		       "damaged database\")", d->path, campaign, why);
}
