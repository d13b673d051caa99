/* pool.c - several campaigns analysed as one (pool.h). */
#include "pool.h"

#include <stdlib.h>
#include <string.h>

#include "params.h"

/* r's runs appended to *runs (taking them over: r is freed, not its strings) */
static int append(an_run **runs, int *nr, an_run *r, int n, int camp, sb_err *e)
{
	an_run *q = realloc(*runs, sizeof *q * (size_t)(*nr + n > 0 ? *nr + n : 1));
	if (!q) {
		adb_runs_free(r, n);
		return sb_errf(e, SB_ENOMEM, "out of memory");
	}
	for (int i = 0; i < n; i++) {
		r[i].camp = camp;
		r[i].unit = r[i].replicate + camp * POOL_UNIT_STRIDE;
	}
	if (n)
		memcpy(q + *nr, r, sizeof *r * (size_t)n);
	free(r);
	*runs = q;
	*nr += n;
	return 0;
}

static void add_axes(char axes[][48], int *na, char ax[][48], int n)
{
	for (int i = 0; i < n && *na < AN_MAXKEYS; i++) {
		int dup = 0;
		for (int j = 0; j < *na; j++)
			dup |= !strcmp(axes[j], ax[i]);
		if (!dup)
			memcpy(axes[(*na)++], ax[i], 48);
	}
}

int pool_read(const an_opts *o, adb *d, an_run **runs, int *nr, char axes[][48], int *na, sb_err *e)
{
	*runs = NULL;
	*nr = *na = 0;
	for (int c = 0; c < o->ncamp && !e->code; c++) {
		const an_camp *k = &o->camp[c];
		adb other, *db = d;
		if (c && adb_open(&other, k->db, 0, e))
			return e->code;
		if (c)
			db = &other;
		int yes = 1, n = 0;
		an_run *r = NULL;
		char ax[AN_MAXKEYS][48];
		int nax = 0;
		if (o->ncamp > 1 && !adb_campaign_exists(db, k->name, &yes, e) && !yes)
			sb_errf(e, SB_EUSAGE, "campaign '%s' is not in %s", k->name, k->db);
		if (!e->code && !adb_runs(db, k->name, k->runs, &r, &n, e) && !adb_axes(db, k->name, ax, AN_MAXKEYS, &nax, e)) {
			if (!append(runs, nr, r, n, c, e))
				add_axes(axes, na, ax, nax);
		} else
			adb_runs_free(r, n);
		if (c)
			adb_close(&other);
	}
	return e->code;
}

static int in_keys(char keys[][48], int nk, const char *key)
{
	for (int k = 0; k < nk; k++)
		if (!strcmp(keys[k], key))
			return 1;
	return 0;
}

static const char *val(const an_run *r, const char *key)
{
	const char *v = an_str(r, key);
	return v ? v : "";
}

/* 1 when some run's value of key differs from that of the first run of another
 * campaign: then two runs of different campaigns differ (if none does, every run has
 * the first runs' value, and those agree) */
static int differs(const an_run *runs, int n, const char *key)
{
	int first[AN_MAXCAMP];
	for (int c = 0; c < AN_MAXCAMP; c++)
		first[c] = -1;
	for (int i = 0; i < n; i++)
		if (runs[i].camp >= 0 && runs[i].camp < AN_MAXCAMP && first[runs[i].camp] < 0)
			first[runs[i].camp] = i;
	for (int i = 0; i < n; i++)
		for (int c = 0; c < AN_MAXCAMP; c++)
			if (first[c] >= 0 && c != runs[i].camp && strcmp(val(&runs[i], key), val(&runs[first[c]], key)))
				return 1;
	return 0;
}

int pool_keys(const an_run *runs, int n, const char *const *drop, char keys[][48], int *nk)
{
	int added = 0;
	for (int i = 0; i < n; i++)
		for (int p = 0; p < runs[i].nparam && *nk < AN_MAXKEYS; p++) {
			const char *key = runs[i].key[p];
			const sb_param *P = params_find(key);
			int dropped = !strcmp(key, "seed") || strlen(key) >= 48;
			for (const char *const *d = drop; d && *d; d++)
				dropped |= !strcmp(*d, key);
			if (!P || (P->flags & (PF_OUT | PF_DRIVER | PF_NOID)) || dropped || in_keys(keys, *nk, key) || !differs(runs, n, key))
				continue;
			snprintf(keys[(*nk)++], 48, "%s", key);
			added++;
		}
	return added;
}

void pool_sources(const an_opts *o, const an_run *runs, int n, int j, char *buf, size_t len)
{
	int from[AN_MAXCAMP] = {0};
	size_t l = 0;
	buf[0] = 0;
	for (int i = 0; i < n; i++)
		if (runs[i].group == j && runs[i].camp >= 0 && runs[i].camp < AN_MAXCAMP)
			from[runs[i].camp] = 1;
	for (int c = 0; c < o->ncamp && l < len; c++)
		if (from[c])
			l += (size_t)snprintf(buf + l, len - l, "%s%s", l ? ", " : "", o->camp[c].name);
}

void pool_print(FILE *f, const an_opts *o, const an_run *runs, int n, char **labels, int ng, const char keys[][48], int nk,
		int nadded)
{
	if (o->ncamp < 2)
		return;
	fprintf(f, "# %d campaigns pooled (a group: the runs alike in the grouping keys, whatever campaign they came"
		   " from):", o->ncamp);
	for (int c = 0; c < o->ncamp; c++)
		fprintf(f, "%s %s (%s)", c ? "," : "", o->camp[c].name, o->camp[c].db);
	fputc('\n', f);
	if (nadded > 0) {
		fprintf(f, "# grouped also by");
		for (int k = nk - nadded; k < nk; k++)
			fprintf(f, "%s %s", k > nk - nadded ? "," : "", keys[k]);
		fprintf(f, ": %s between the campaigns (--by sets the keys)\n", nadded == 1 ? "it differs" : "they differ");
	}
	int w = 24;
	for (int j = 0; j < ng; j++)
		w = (int)strlen(labels[j]) > w ? (int)strlen(labels[j]) : w;
	fprintf(f, "# %-*s  %s\n", w, "group", "campaigns");
	for (int j = 0; j < ng; j++) {
		char src[AN_MAXCAMP * 70];
		pool_sources(o, runs, n, j, src, sizeof src);
		fprintf(f, "# %-*s  %s\n", w, labels[j], src);
	}
}
