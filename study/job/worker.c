/* worker.c - one job: lock, run bin/shake from an argument file, report. */
#define _GNU_SOURCE /* wait4 */
#include "worker.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fsutil.h"
#include "layout.h"
#include "params.h"
#include "campaign/safe.h"

static volatile sig_atomic_t g_child;

/* Forward SIGINT/SIGTERM to the engine: it writes a checkpoint and exits 7. */
static void forward(int sig)
{
	if (g_child > 0)
		kill((pid_t)g_child, sig == SIGINT ? SIGTERM : sig);
}

/* Copy with truncation (messages are cut, never overflow). */
static void scopy(char *out, size_t len, const char *s)
{
	size_t l = strlen(s);
	if (l >= len)
		l = len - 1;
	memcpy(out, s, l);
	out[l] = 0;
}

static void clean(char *s)
{
	for (; *s; s++)
		if (*s == '\t' || *s == '\n' || *s == '\r')
			*s = ' ';
}

/* The engine's own last word in this attempt (from byte `from` of its log): the last
 * line it prefixed with "shake: " (its error or interruption message), else the last
 * non-empty line. Anything printed after the message (a diagnostic at exit, a
 * sanitizer report) does not replace it. */
void worker_last_message(const char *log, long from, char *out, size_t len)
{
	out[0] = 0;
	sb_err e = {0};
	FILE *f = fs_open_input(log, "run log", 0, SB_EIO, &e); /* a regular file only (docs/inputs.md) */
	if (!f)
		return;
	if (from > 0)
		fseek(f, from, SEEK_SET);
	char line[2048];
	int engine = 0;
	while (fgets(line, sizeof line, f)) {
		line[strcspn(line, "\r\n")] = 0;
		int mine = !strncmp(line, "shake: ", 7);
		if (!strncmp(line, WORKER_USAGE, sizeof WORKER_USAGE - 1))
			continue; /* the worker's own line after the engine's end (worker.h) */
		if (line[strspn(line, " \t")] && (mine || !engine)) {
			scopy(out, len, line);
			engine |= mine;
		}
	}
	fclose(f);
}

int worker_crashed(long code)
{
	if (code <= 128)
		return 0;
	const long sig = code - 128;
	return sig == SIGSEGV || sig == SIGBUS || sig == SIGILL || sig == SIGABRT || sig == SIGFPE;
}

/* The DONE line (worker.h): u NULL when no engine ran (its CPU and memory "-"). */
static void report_usage(const char *name, int code, const char *host, double secs, const db_usage *u,
			 const char *msg)
{
	char m[1024], cpu[32] = "-", rss[32] = "-";
	snprintf(m, sizeof m, "%s", msg);
	clean(m);
	if (u) {
		snprintf(cpu, sizeof cpu, "%.3f", u->cpu_seconds);
		snprintf(rss, sizeof rss, "%ld", u->max_rss_kb);
	}
	printf("%s\t%s\t%d\t%s\t%.3f\t%s\t%s\t%s\n", WORKER_DONE, name, code, host, secs, cpu, rss, m);
	fflush(stdout);
}

static void report_done(const char *name, int code, const char *host, double secs, const char *msg)
{
	report_usage(name, code, host, secs, NULL, msg);
}

int worker_log_usage(const char *log, long from, db_usage *u)
{
	sb_err e = {0};
	FILE *f = fs_open_input(log, "run log", 0, SB_EIO, &e); /* a regular file only (docs/inputs.md) */
	if (!f)
		return 0;
	if (from > 0)
		fseek(f, from, SEEK_SET);
	char line[2048];
	int got = 0;
	while (fgets(line, sizeof line, f)) {
		double cpu;
		long rss;
		if (!strncmp(line, WORKER_USAGE, sizeof WORKER_USAGE - 1) &&
		    sscanf(line + sizeof WORKER_USAGE - 1, "%lf s of CPU, peak memory %ld KiB", &cpu, &rss) == 2 &&
		    cpu >= 0 && rss >= 0) {
			*u = (db_usage){cpu, rss};
			got = 1;
		}
	}
	fclose(f);
	return got;
}

int worker_done_parse(char *line, worker_done *w)
{
	char *f[8] = {0};
	int n = 0;
	if (strncmp(line, WORKER_DONE "\t", sizeof WORKER_DONE))
		return 0;
	for (char *s = line, *t; n < 8 && (t = strsep(&s, "\t"));)
		f[n++] = t;
	/* 6 fields: a worker of the version before the usage was reported (a Slurm task's
	 * log written before an upgrade), its message the sixth */
	if ((n != 6 && n < 8) || !f[1][0])
		return 0;
	char *end;
	w->name = f[1];
	w->code = strtol(f[2], &end, 10);
	if (end == f[2])
		return 0;
	w->host = f[3];
	w->wall = strtod(f[4], NULL);
	w->ran = 0;
	w->u = (db_usage){0, 0};
	if (n == 6) {
		w->msg = f[5];
		return 1;
	}
	/* "-": no engine ran (the job never started one) */
	char *end2;
	w->u.cpu_seconds = strtod(f[5], &end);
	w->u.max_rss_kb = strtol(f[6], &end2, 10);
	w->ran = end != f[5] && !*end && w->u.cpu_seconds >= 0 && end2 != f[6] && !*end2 && w->u.max_rss_kb >= 0;
	w->msg = f[7];
	return 1;
}

int worker_exec(const char *dir, const char *kind, const char *name, const char *self)
{
	char host[256] = "";
	gethostname(host, sizeof host - 1);
	clean(host);
	int is_cache = !strcmp(kind, "cache");
	if ((!is_cache && strcmp(kind, "run")) || !safe_name(name)) {
		/* exit codes as the engine's: 1 a job that can never run (the driver marks it
		 * failed), 2 an I/O fault (the run stays pending and the driver stops) */
		report_done(name, 1, host, 0, "exec: bad job (kind must be run or cache, the name a plain one)");
		return 0;
	}
	if (chdir(dir) != 0) {
		/* the campaign's directory deleted while it ran (the driver finds the job's
		 * input gone and prepares it again), or one it may not enter: not the run's
		 * fault, never a failed run */
		char m[900];
		snprintf(m, sizeof m, "exec: cannot enter the campaign's directory %.700s: %s", dir, strerror(errno));
		report_done(name, 2, host, 0, m);
		return 0;
	}
	char args[600], log[600], out[600], lockp[600];
	layout_file("", is_cache, name, LAY_ARGS, args, sizeof args);
	layout_file("", is_cache, name, LAY_LOG, log, sizeof log);
	layout_file("", is_cache, name, LAY_OUTPUT, out, sizeof out);
	layout_file("", is_cache, name, LAY_LOCK, lockp, sizeof lockp);
	mkdir("logs", 0777);
	printf("%s\t%s\t%s\n", WORKER_START, name, host);
	fflush(stdout);

	/* One engine per run, ever: a run orphaned by a killed driver still holds this
	 * lock (the engine inherits it), and a new worker waits for it instead of writing
	 * the same checkpoint and output concurrently. */
	/* O_NOFOLLOW: a link planted at a run's files is refused, never written through */
	int lk = open(lockp, O_RDWR | O_CREAT | O_NOFOLLOW, 0666);
	if (lk < 0 || flock(lk, LOCK_EX) != 0) {
		report_done(name, 2, host, 0, "exec: cannot lock the run");
		return 2; /* this host cannot run it: parallel --retries tries another */
	}
	if (access(out, F_OK) == 0) {
		report_done(name, 0, host, 0, "already complete");
		return 0;
	}

	/* a regular file only (docs/inputs.md, "Files"): a FIFO would hang the worker */
	sb_err ae = {0};
	FILE *f = fs_open_input(args, "argument file", 1 << 20, SB_EIO, &ae);
	if (!f) {
		char why[1024]; /* report_done's length: the message's end is what may go */
		snprintf(why, sizeof why, "exec: %.1000s", access(args, F_OK) ? "missing argument file" : ae.msg);
		report_done(name, 2, host, 0, why);
		return 2; /* not transferred to this host: parallel --retries tries another */
	}
	char *argv[129]; /* the engine, 126 lines of the argument file, run_id, NULL */
	int argc = 0;
	char shake[1200];
	/* the engine sits next to this binary (locally: bin/, remotely: the work dir) */
	snprintf(shake, sizeof shake, "%s", self);
	char *sl = strrchr(shake, '/');
	snprintf(sl ? sl + 1 : shake, sizeof shake - (size_t)(sl ? sl + 1 - shake : 0), "shake");
	argv[argc++] = shake;
	char line[1100];
	int toomany = 0;
	while (fgets(line, sizeof line, f)) {
		line[strcspn(line, "\r\n")] = 0;
		if (!line[0])
			continue;
		/* never run the engine with some of its parameters silently dropped */
		if (argc >= 127) {
			toomany = 1;
			break;
		}
		argv[argc++] = strdup(line);
	}
	fclose(f);
	/* the run's id, recorded in its file (core/io/h5id.h): a file later copied or linked
	 * in place of another run's is known by it. Given here, not in the argument file,
	 * so that a run whose arguments were written by an earlier version gets it too. */
	char idarg[300];
	snprintf(idarg, sizeof idarg, "run_id=%s", name);
	if (!toomany)
		argv[argc++] = strdup(idarg);
	argv[argc] = NULL;
	if (toomany) {
		for (int i = 1; i < argc; i++)
			free(argv[i]);
		report_done(name, 1, host, 0, "exec: argument file has more than 126 parameters");
		return 0;
	}

	int lf = open(log, O_WRONLY | O_CREAT | O_APPEND | O_NOFOLLOW, 0666);
	if (lf < 0 && errno == ELOOP) {
		for (int i = 1; i < argc; i++)
			free(argv[i]);
		report_done(name, 2, host, 0, "exec: logs/ is refused: a symbolic link stands at the run's log");
		close(lk);
		return 0;
	}
	long from = lf >= 0 ? (long)lseek(lf, 0, SEEK_END) : 0;
	struct timeval t0, t1;
	gettimeofday(&t0, NULL);
	struct sigaction sa;
	memset(&sa, 0, sizeof sa);
	sa.sa_handler = forward;
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);
	pid_t pid = fork();
	if (pid == 0) {
		int dn = open("/dev/null", O_RDWR);
		if (dn >= 0)
			dup2(dn, 0), dup2(dn, 1);
		if (lf >= 0)
			dup2(lf, 2);
		execv(shake, argv);
		fprintf(stderr, "exec: cannot run %s: %s\n", shake, strerror(errno));
		_exit(2);
	}
	g_child = pid;
	int st = 0, code;
	/* the engine's own CPU and peak memory, whatever ended it (a signal too): every
	 * attempt's cost is recorded (docs/database.md, table attempt) */
	struct rusage ru;
	memset(&ru, 0, sizeof ru);
	while (pid > 0 && wait4(pid, &st, 0, &ru) < 0 && errno == EINTR)
		;
	if (pid < 0)
		code = 2;
	else if (WIFEXITED(st))
		code = WEXITSTATUS(st);
	else
		code = 128 + WTERMSIG(st);
	gettimeofday(&t1, NULL);
	for (int i = 1; i < argc; i++)
		free(argv[i]);
	const db_usage usage = {(double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
					(double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec,
				(long)ru.ru_maxrss}; /* KiB on Linux (getrusage(2)) */
	/* also in the run's log: a DONE line that never reaches the driver (GNU parallel
	 * stopped with it drops a job's output) leaves the usage where ingest finds it */
	if (lf >= 0 && pid > 0)
		dprintf(lf, "%s%.3f s of CPU, peak memory %ld KiB (exit %d)\n", WORKER_USAGE, usage.cpu_seconds,
			usage.max_rss_kb, code);
	if (lf >= 0)
		close(lf);
	char msg[1024];
	worker_last_message(log, from, msg, sizeof msg);
	/* whatever it said last (e.g. "resuming from ...") is not why it stopped */
	if (worker_crashed(code))
		snprintf(msg, sizeof msg, "crashed by signal %d (%s)", code - 128, strsignal(code - 128));
	else if (code >= 128)
		snprintf(msg, sizeof msg, "killed by signal %d", code - 128);
	report_usage(name, code, host, (double)(t1.tv_sec - t0.tv_sec) + 1e-6 * (double)(t1.tv_usec - t0.tv_usec),
		     pid > 0 ? &usage : NULL, msg);
	close(lk);
	return 0; /* reported: see worker.h */
}
