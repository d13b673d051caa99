/* parallel.c - GNU parallel over a campaign's jobs: the command line (locally, or
 * across hosts with --sshloginfile), the workers' START/DONE lines as they arrive, and
 * the driver's signals. The flags a signal handler sets are the only state that is
 * not the driver's (drv): a handler has no other way to speak. */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/wait.h>

#include "drv.h"
#include "safe.h"
#include "worker.h"

static volatile sig_atomic_t g_stop;
static volatile sig_atomic_t g_parallel;

static void on_signal(int sig)
{
	(void)sig;
	if (!g_stop && g_parallel > 0)
		kill((pid_t)g_parallel, SIGTERM); /* no new jobs; running ones checkpoint */
	g_stop = 1;
}

void parallel_signals(void)
{
	struct sigaction sa;
	memset(&sa, 0, sizeof sa);
	sa.sa_handler = on_signal;
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);
}

int parallel_stopped(void)
{
	return g_stop;
}

void parallel_halt(void)
{
	if (g_parallel > 0)
		kill((pid_t)g_parallel, SIGTERM);
}

static int add_arg(char **argv, int *argc, int max, const char *fmt, const char *a, const char *b)
{
	if (*argc >= max - 1)
		return -1;
	char buf[3 * PATHX];
	snprintf(buf, sizeof buf, fmt, a, b);
	argv[(*argc)++] = strdup(buf);
	argv[*argc] = NULL;
	return 0;
}

/* Runs `study exec` for every name in names through GNU parallel and handles the
 * workers' lines as they arrive. */
int run_parallel(drv *d, const char *kind, char **names, long n, char **basefiles, long nbase,
			sb_err *e)
{
	int is_cache = !strcmp(kind, "cache");
	char jobfile[PATHX], joblog[PATHX];
	snprintf(jobfile, sizeof jobfile, "%s/%s.jobs", d->dir, kind);
	snprintf(joblog, sizeof joblog, "+%s/joblog.txt", d->dir);
	FILE *jf = fopen(jobfile, "w");
	if (!jf)
		return sb_errf(e, SB_EIO, "%s: cannot create: %s", jobfile, strerror(errno));
	for (long i = 0; i < n; i++)
		fprintf(jf, "%s\n", names[i]);
	if (fclose(jf))
		return sb_errf(e, SB_EIO, "%s: cannot write", jobfile);

	enum { MAXA = 4096 };
	char **argv = calloc(MAXA, sizeof *argv);
	int argc = 0;
	char njobs[32];
	snprintf(njobs, sizeof njobs, "%d", d->jobs);
	const char *fixed[] = {"parallel", "--will-cite", "--jobs", njobs, "--joblog", joblog, "--arg-file", jobfile};
	for (size_t i = 0; i < sizeof fixed / sizeof *fixed; i++)
		add_arg(argv, &argc, MAXA, "%s%s", fixed[i], "");
	int tty = d->o->progress < 0 ? isatty(2) : d->o->progress;
	if (tty)
		add_arg(argv, &argc, MAXA, "%s%s", "--bar", "");
	char q1[PATHX], q2[PATHX];
	if (d->o->sshloginfile) {
		/* Remote: the binaries go once per host (--basefile), each job's argument file
		 * goes out and its output and log come back (--transferfile, --return). The
		 * "/./" marks where the path relative to the remote work dir starts. Output is
		 * grouped per job, so a DONE line arrives after its files are back. */
		char bindir[PATHX];
		snprintf(bindir, sizeof bindir, "%s", d->o->self);
		*strrchr(bindir, '/') = 0;
		char wd[PATHLEN];
		snprintf(wd, sizeof wd, ".shakebox/%s", d->c.name);
		add_arg(argv, &argc, MAXA, "--sshloginfile%s%s", "", "");
		add_arg(argv, &argc, MAXA, "%s%s", d->o->sshloginfile, "");
		add_arg(argv, &argc, MAXA, "--workdir%s%s", "", "");
		add_arg(argv, &argc, MAXA, "%s%s", wd, "");
		add_arg(argv, &argc, MAXA, "--basefile%s%s", "", "");
		add_arg(argv, &argc, MAXA, "%s/./%s", bindir, "study");
		add_arg(argv, &argc, MAXA, "--basefile%s%s", "", "");
		add_arg(argv, &argc, MAXA, "%s/./%s", bindir, "shake");
		for (long i = 0; i < nbase; i++) {
			add_arg(argv, &argc, MAXA, "--basefile%s%s", "", "");
			add_arg(argv, &argc, MAXA, "%s/./cache/%s.txt", d->dir, basefiles[i]);
		}
		const char *xfer = is_cache ? "%s/./cache/{}.args%s" : "%s/./jobs/{}.args%s";
		add_arg(argv, &argc, MAXA, "--transferfile%s%s", "", "");
		add_arg(argv, &argc, MAXA, xfer, d->dir, "");
		const char *ret_run[] = {"%s/./{}.h5%s", "%s/./logs/{}.log%s", NULL};
		const char *ret_cache[] = {"%s/./cache/{}.h5%s", "%s/./cache/{}.txt%s", "%s/./cache/{}.log%s", NULL};
		for (const char **r = is_cache ? ret_cache : ret_run; *r; r++) {
			add_arg(argv, &argc, MAXA, "--return%s%s", "", "");
			add_arg(argv, &argc, MAXA, *r, d->dir, "");
		}
		add_arg(argv, &argc, MAXA, "%s%s", "./study exec . ", kind);
		add_arg(argv, &argc, MAXA, "%s%s", "{}", "");
	} else {
		/* Local: parallel joins the command words into a shell command line, so the
		 * two paths are single-quoted; the job name is a hex id (and parallel quotes {}). */
		if (safe_shell_quote(d->o->self, q1, sizeof q1) || safe_shell_quote(d->dir, q2, sizeof q2)) {
			free(argv);
			return sb_errf(e, SB_EUSAGE, "path too long");
		}
		add_arg(argv, &argc, MAXA, "--line-buffer%s%s", "", "");
		add_arg(argv, &argc, MAXA, "%s exec %s", q1, q2);
		add_arg(argv, &argc, MAXA, "%s%s", kind, "");
		add_arg(argv, &argc, MAXA, "%s%s", "{}", "");
	}

	int pfd[2];
	if (pipe(pfd)) {
		sb_errf(e, SB_EIO, "pipe: %s", strerror(errno));
		goto out;
	}
	pid_t pid = fork();
	if (pid < 0) {
		sb_errf(e, SB_EIO, "fork: %s", strerror(errno));
		goto out;
	}
	if (pid == 0) {
		/* a driver killed outright takes parallel with it: no new jobs start, and
		 * running ones are stopped with a checkpoint */
		prctl(PR_SET_PDEATHSIG, SIGTERM);
		close(pfd[0]);
		dup2(pfd[1], 1);
		close(pfd[1]);
		int dn = open("/dev/null", O_RDONLY);
		if (dn >= 0)
			dup2(dn, 0);
		execvp(argv[0], argv);
		fprintf(stderr, "study: cannot run GNU parallel: %s\n", strerror(errno));
		_exit(127);
	}
	g_parallel = pid;
	close(pfd[1]);
	FILE *in = fdopen(pfd[0], "r");
	char *line = NULL;
	size_t cap = 0;
	ssize_t got;
	while (in && ((got = getline(&line, &cap, in)) >= 0 || errno == EINTR)) {
		if (got < 0) {
			clearerr(in);
			errno = 0;
			continue;
		}
		line[strcspn(line, "\n")] = 0;
		sb_err le = {0};
		if (!strncmp(line, WORKER_START "\t", sizeof WORKER_START))
			on_start(d, line, &le);
		else if (!strncmp(line, WORKER_DONE "\t", sizeof WORKER_DONE))
			on_done(d, is_cache, line, &le);
		else if (line[0])
			fprintf(stderr, "%s\n", line);
		if (le.code)
			fprintf(stderr, "study: %s\n", le.msg); /* the final sweep repairs it */
	}
	free(line);
	if (in)
		fclose(in);
	int st = 0;
	while (waitpid(pid, &st, 0) < 0 && errno == EINTR)
		;
	g_parallel = 0;
	if (!is_cache)
		unreported(d, e);
	if (WIFEXITED(st) && WEXITSTATUS(st) == 127 && !g_stop)
		sb_errf(e, SB_EIO, "GNU parallel did not start (is it installed? make deps)");
	else if (WIFEXITED(st) && WEXITSTATUS(st) == 255 && !g_stop && !d->io_fault)
		sb_errf(e, SB_EIO, "GNU parallel failed (see the messages above)");
out:
	for (int i = 0; i < argc; i++)
		free(argv[i]);
	free(argv);
	return e->code;
}

