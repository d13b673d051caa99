/* plan.c - which run goes into which array task, and reading Slurm's answers
 * (plan.h). */
#include "plan.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "job/worker.h"

typedef struct {
	const slurm_plan_run *r;
	long i;
} ord;

/* by packing to build, then as given (a stable order, so a plan is a function of its
 * input) */
static int by_key(const void *a, const void *b)
{
	const ord *x = a, *y = b;
	int c = strcmp(x->r->build_key, y->r->build_key);
	return c ? c : (x->i > y->i) - (x->i < y->i);
}

static int append(char **buf, size_t *len, size_t *cap, const char *a, const char *b)
{
	size_t need = *len + strlen(a) + strlen(b) + 2;
	if (need > *cap) {
		size_t nc = need * 2;
		char *nb = realloc(*buf, nc);
		if (!nb)
			return -1;
		*buf = nb;
		*cap = nc;
	}
	*len += (size_t)snprintf(*buf + *len, *cap - *len, "%s%s%s", *len ? " " : "", a, b);
	return 0;
}

long slurm_plan_task_lines(const slurm_plan_run *runs, long n, long per_task, char ***lines)
{
	*lines = NULL;
	if (per_task < 1)
		per_task = 1;
	long ntasks = (n + per_task - 1) / per_task;
	ord *o = calloc((size_t)n + 1, sizeof *o);
	char **l = calloc((size_t)ntasks + 1, sizeof *l);
	if (!o || !l) {
		free(o);
		free(l);
		return -1;
	}
	for (long i = 0; i < n; i++)
		o[i] = (ord){&runs[i], i};
	if (per_task > 1)
		qsort(o, (size_t)n, sizeof *o, by_key);
	for (long t = 0; t < ntasks; t++) {
		size_t len = 0, cap = 0;
		char *buf = NULL;
		for (long i = t * per_task; i < n && i < (t + 1) * per_task; i++) {
			const char *k = o[i].r->build_key;
			int named = 0; /* this packing already named on this line */
			for (long j = t * per_task; j < i && k[0]; j++)
				named |= !strcmp(o[j].r->build_key, k);
			if ((k[0] && !named && append(&buf, &len, &cap, "c:", k)) || append(&buf, &len, &cap, "r:", o[i].r->id)) {
				free(buf);
				slurm_plan_free_lines(l, t);
				free(o);
				return -1;
			}
		}
		l[t] = buf;
	}
	free(o);
	*lines = l;
	return ntasks;
}

void slurm_plan_free_lines(char **lines, long n)
{
	for (long i = 0; lines && i < n; i++)
		free(lines[i]);
	free(lines);
}

void slurm_plan_array_spec(long ntasks, long throttle, char *out, size_t len)
{
	int l = ntasks > 1 ? snprintf(out, len, "0-%ld", ntasks - 1) : snprintf(out, len, "0");
	if (throttle > 0 && l > 0 && (size_t)l < len)
		snprintf(out + l, len - (size_t)l, "%%%ld", throttle);
}

int slurm_plan_split_args(const char *s, char **argv, int max, char *why, size_t whylen)
{
	/* what study submit says itself: the tasks, where their lines go (the collector
	 * reads them there), the job id's format, the script */
	static const char *const own[] = {"-a", "--array", "-o", "--output", "--parsable", "--wrap", NULL};
	/* sbatch's options that take no separate value (those whose value is optional take
	 * it only after '='): after one of these, or after a value, a word that is no option
	 * would be sbatch's script, and study's own script its argument */
	static const char *const bare[] = {"--contiguous", "--exclusive", "-H", "--hold", "--ignore-pbs", "-k",
					   "--no-kill", "--no-requeue", "--requeue", "-O", "--overcommit", "-Q",
					   "--quiet", "--spread-job", "--test-only", "-v", "--verbose", "-V",
					   "--version", "-W", "--wait", "--use-min-nodes", "-h", "--help", "--usage",
					   "-s", "--oversubscribe", "--reboot", "--get-user-env", "--nice", NULL};
	int n = 0, takes = 0; /* takes: the last word was an option that may take the next */
	why[0] = 0;
	for (const char *p = s ? s : ""; *p;) {
		while (*p && isspace((unsigned char)*p))
			p++;
		if (!*p)
			break;
		size_t l = 0;
		while (p[l] && !isspace((unsigned char)p[l]))
			l++;
		for (int k = 0; own[k]; k++) {
			size_t ol = strlen(own[k]);
			/* --array, --array=..., and the short forms glued to their value (-a3) */
			int hit = !strncmp(p, own[k], ol) &&
				  (l == ol || p[ol] == '=' || (own[k][1] != '-' && l > ol));
			if (hit) {
				snprintf(why, whylen, "%.*s: study submit sets %s itself (--throttle for the array's %%)", (int)l,
					 p, own[k]);
				goto bad;
			}
		}
		if (p[0] != '-' || l == 1) {
			if (!takes) {
				snprintf(why, whylen, "'%.*s' is no option: sbatch would take it for its script "
					 "(options begin with '-'; a value follows its option or its '=')", (int)l, p);
				goto bad;
			}
			takes = 0;
		} else {
			/* -p VALUE and --mem VALUE; not -pVALUE, --mem=VALUE or a bare flag */
			takes = !memchr(p, '=', l) && (p[1] == '-' || l == 2);
			for (int k = 0; takes && bare[k]; k++)
				takes = !(strlen(bare[k]) == l && !strncmp(p, bare[k], l));
		}
		if (n >= max) {
			snprintf(why, whylen, "more than %d words", max);
			goto bad;
		}
		argv[n] = malloc(l + 1);
		if (!argv[n]) {
			snprintf(why, whylen, "out of memory");
			goto bad;
		}
		memcpy(argv[n], p, l);
		argv[n++][l] = 0;
		p += l;
	}
	return n;
bad:
	while (n > 0)
		free(argv[--n]);
	return -1;
}

long slurm_plan_parse_jobid(const char *out)
{
	while (*out && isspace((unsigned char)*out))
		out++;
	if (!isdigit((unsigned char)*out))
		return -1;
	char *end;
	long id = strtol(out, &end, 10);
	if (id <= 0 || (*end && *end != ';' && !isspace((unsigned char)*end)))
		return -1;
	return id;
}

int slurm_plan_parse_squeue(const char *line, long *job, long *index, char *state, size_t slen)
{
	char *end;
	if (!isdigit((unsigned char)*line))
		return 0;
	*job = strtol(line, &end, 10);
	*index = -1;
	if (*end == '_') {
		if (isdigit((unsigned char)end[1]))
			*index = strtol(end + 1, &end, 10);
		else
			end = strchr(end, '|') ? strchr(end, '|') : end + strlen(end);
	}
	if (*end != '|')
		return 0;
	snprintf(state, slen, "%.*s", (int)strcspn(end + 1, " \r\n"), end + 1);
	return state[0] != 0;
}

int slurm_plan_parse_worker(const char *line, char *name, size_t nlen, long *code)
{
	*code = 0;
	if (!strncmp(line, WORKER_START "\t", sizeof WORKER_START)) {
		const char *p = line + sizeof WORKER_START;
		size_t l = strcspn(p, "\t\r\n");
		if (!l || l >= nlen)
			return 0;
		memcpy(name, p, l);
		name[l] = 0;
		return 1;
	}
	/* a DONE line as worker.h reads it (its one parser) */
	char *copy = strdup(line);
	worker_done w;
	int kind = 0;
	if (copy && worker_done_parse(copy, &w) && strlen(w.name) < nlen && !strpbrk(w.name, "\r\n")) {
		snprintf(name, nlen, "%s", w.name);
		*code = w.code;
		kind = 2;
	}
	free(copy);
	return kind;
}
