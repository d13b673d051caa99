/* changes.c - a campaign file changed since its runs were recorded (changes.h). */
#include "changes.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "dirs.h"
#include "layout.h"

static int exists(const char *p)
{
	return access(p, F_OK) == 0;
}

/* Distinct values of a key among a set of runs, as "a, b, c" (at most 6, then "..."). */
static void add_value(char *set, size_t len, const char *v, int *count)
{
	char probe[SB_STR_MAX + 16];
	snprintf(probe, sizeof probe, "|%s|", v);
	if (strstr(set, probe))
		return;
	size_t l = strlen(set);
	if (!l && len > 1) {
		snprintf(set, len, "|");
		l = 1;
	}
	if (*count < 6)
		snprintf(set + l, len - l, "%s|", v);
	else if (*count == 6)
		snprintf(set + l, len - l, "...|");
	(*count)++;
}

/* Every item of a in b and of b in a (sets as "|x|y|"; a truncated one never equals). */
static int same_set(const char *a, const char *b)
{
	for (int pass = 0; pass < 2; pass++, (void)0) {
		const char *x = pass ? b : a, *y = pass ? a : b;
		for (const char *p = x + 1; *p;) {
			const char *q = strchr(p, '|');
			if (!q)
				break;
			char item[SB_STR_MAX + 16];
			snprintf(item, sizeof item, "|%.*s|", (int)(q - p), p);
			if (!strcmp(item, "|...|") || !strstr(y, item))
				return 0;
			p = q + 1;
		}
	}
	return 1;
}

static void show_set(const char *set, char *out, size_t len)
{
	size_t l = 0;
	out[0] = 0;
	for (const char *p = set; *p && l < len;) {
		if (*p == '|') {
			p++;
			continue;
		}
		const char *q = strchr(p, '|');
		int n = q ? (int)(q - p) : (int)strlen(p);
		l += (size_t)snprintf(out + l, len - l, "%s%.*s", l ? ", " : "", n, p);
		p += n;
	}
}

/* The recorded runs of the campaign's current version that its file's grid no longer
 * has: a key of the file changed, or values left an axis. They are never mixed with
 * the new grid silently: the user keeps them as an earlier version (out of every
 * analysis unless asked) or forgets them (rows deleted, files moved aside). */
int changes_check(const changes_ctx *x, sb_err *e)
{
	sqlite3_stmt *q;
	if (sql_exec(x->db, e, &q,
		    "SELECT r.id, r.state, r.replicate, (SELECT value FROM param p WHERE p.campaign = r.campaign"
		    " AND p.run = r.id AND p.key = 'frequency') FROM run r WHERE r.campaign = ? AND r.current = 1",
		    "t", x->c->name))
		return e->code;
	char **stale = NULL;
	long ns = 0, cap = 0, nd = 0, nf = 0;
	while (sqlite3_step(q) == SQLITE_ROW) {
		const char *id = (const char *)sqlite3_column_text(q, 0), *st = (const char *)sqlite3_column_text(q, 1);
		/* an [onset] campaign's runs are its chains' so far, and more may come: a
		 * recorded run belongs to it when some chain can ask for it */
		if (!id || x->member(x->ctx, id, (long)sqlite3_column_int64(q, 2), sqlite3_column_double(q, 3)))
			continue;
		if (ns == cap) {
			cap = cap ? 2 * cap : 64;
			char **x = realloc(stale, sizeof *x * (size_t)cap);
			if (!x)
				break;
			stale = x;
		}
		stale[ns++] = strdup(id);
		nd += st && !strcmp(st, "done");
		nf += st && !strcmp(st, "failed");
	}
	if (sql_done(x->db, q, e) || !ns) {
		for (long i = 0; i < ns; i++)
			free(stale[i]);
		free(stale);
		return e->code;
	}
	if (!x->keep_old && !x->forget_old) {
		/* what changed: per key, the values of the runs that left against the grid's */
		char msg[3000];
		size_t l = (size_t)snprintf(msg, sizeof msg,
					    "campaign %s changed since it was recorded: %ld recorded runs (%ld done, %ld failed) "
					    "are no longer in %s:\n",
					    x->c->name, ns, nd, nf, x->c->path);
		size_t np;
		const sb_param *t = params_table(&np);
		sqlite3_stmt *pv = NULL;
		sql_exec(x->db, e, &pv, "SELECT value FROM param WHERE campaign = ? AND run = ? AND key = ?", "");
		int shown = 0;
		for (size_t k = 0; pv && k < np && l < sizeof msg - 200; k++) {
			if ((t[k].flags & PF_DRIVER) || !strcmp(t[k].name, "seed")) /* seed: the replicate's */
				continue;
			char olds[1024] = "", news[1024] = "";
			int no = 0, nn = 0;
			for (long i = 0; i < ns && i < 2000; i++) {
				sqlite3_reset(pv);
				sqlite3_bind_text(pv, 1, x->c->name, -1, SQLITE_STATIC);
				sqlite3_bind_text(pv, 2, stale[i], -1, SQLITE_STATIC);
				sqlite3_bind_text(pv, 3, t[k].name, -1, SQLITE_STATIC);
				if (sqlite3_step(pv) == SQLITE_ROW && sqlite3_column_text(pv, 0)) {
					/* the canonical text of the value, as the grid's are printed
					 * (a REAL read back as text would lose digits) */
					sb_scene sc;
					params_defaults(&sc);
					char v[SB_STR_MAX + 8], raw[64];
					const char *txt = (const char *)sqlite3_column_text(pv, 0);
					if (sqlite3_column_type(pv, 0) == SQLITE_FLOAT) {
						snprintf(raw, sizeof raw, "%.17g", sqlite3_column_double(pv, 0));
						txt = raw;
					}
					sb_err pe = {0};
					if (!params_set(&sc, t[k].name, txt, "", &pe))
						params_format(&sc, &t[k], v, sizeof v);
					else
						snprintf(v, sizeof v, "%s", txt);
					add_value(olds, sizeof olds, v, &no);
				}
			}
			for (long i = 0; i < x->g->n; i++) {
				sb_scene sc;
				char v[SB_STR_MAX + 8];
				grid_scene(x->g, &x->g->runs[i], &sc);
				params_format(&sc, &t[k], v, sizeof v);
				add_value(news, sizeof news, v, &nn);
			}
			if (!olds[0] || same_set(olds, news))
				continue;
			char a[512], b[512];
			show_set(olds, a, sizeof a);
			show_set(news, b, sizeof b);
			l += (size_t)snprintf(msg + l, sizeof msg - l, "  %s: %s -> %s\n", t[k].name, a, b);
			shown++;
		}
		sqlite3_finalize(pv);
		if (!shown)
			l += (size_t)snprintf(msg + l, sizeof msg - l, "  (no key differs in value: replicates or seeds changed)\n");
		snprintf(msg + l, sizeof msg - l,
			 "Nothing was run. Run again with --keep-old to keep those runs as an earlier version of the "
			 "campaign (out of every analysis unless a tool is given --all-versions), or with --forget-old to "
			 "delete their rows and move their files to %s/forgotten/.",
			 x->dir);
		sb_errf(e, SB_EUSAGE, "%s", msg);
		goto out;
	}
	if (db_begin(x->db, e))
		goto out;
	if (x->keep_old)
		sql_exec(x->db, e, NULL, "UPDATE campaign SET version = version + 1 WHERE name = ?", "t", x->c->name);
	for (long i = 0; i < ns && !e->code; i++) {
		if (x->keep_old) {
			sql_exec(x->db, e, NULL, "UPDATE run SET current = 0 WHERE campaign = ? AND id = ?", "tt", x->c->name,
				stale[i]);
			continue;
		}
		static const char *const tables[] = {"DELETE FROM run WHERE campaign = ?1 AND id = ?2",
						     "DELETE FROM param WHERE campaign = ?1 AND run = ?2",
						     "DELETE FROM attempt WHERE campaign = ?1 AND run = ?2",
						     "DELETE FROM result WHERE campaign = ?1 AND run = ?2"};
		for (size_t k = 0; k < sizeof tables / sizeof *tables && !e->code; k++)
			sql_exec(x->db, e, NULL, tables[k], "tt", x->c->name, stale[i]);
	}
	if (e->code || db_commit(x->db, e)) {
		db_rollback(x->db);
		goto out;
	}
	if (x->forget_old) {
		char dir[CHANGES_PATH];
		layout_sub(x->dir, "forgotten", dir, sizeof dir);
		if (dirs_own(dir, e))
			goto out;
		for (long i = 0; i < ns; i++) {
			static const enum lay_kind kinds[] = {LAY_OUTPUT, LAY_ARGS, LAY_LOG};
			for (size_t k = 0; k < sizeof kinds / sizeof *kinds + 1; k++) {
				char from[CHANGES_PATH], to[CHANGES_PATH + 64];
				if (k < sizeof kinds / sizeof *kinds)
					layout_file(x->dir, 0, stale[i], kinds[k], from, sizeof from);
				else { /* the output's ParaView sidecar: ID.xmf beside ID.h5 */
					int l = layout_file(x->dir, 0, stale[i], LAY_OUTPUT, from, sizeof from);
					if (l < 3 || (size_t)l + 2 > sizeof from)
						continue;
					memcpy(from + l - 3, ".xmf", 5);
				}
				snprintf(to, sizeof to, "%s/%s", dir, strrchr(from, '/') + 1);
				if (exists(from) && rename(from, to))
					fprintf(stderr, "study: %s: cannot move aside: %s\n", from, strerror(errno));
			}
		}
	}
	fprintf(stderr, "study: %s: %ld runs of the earlier campaign file %s\n", x->c->name, ns,
		x->keep_old ? "kept as an earlier version (current = 0 in the runs view)" : "forgotten");
out:
	for (long i = 0; i < ns; i++)
		free(stale[i]);
	free(stale);
	return e->code;
}

