/* parallel.c - GNU parallel over a campaign's jobs: the command line (locally, or
 * across hosts with --sshloginfile) and the workers' START/DONE lines as they arrive,
 * handed to ingest.c; a stop (stop.h) passed on to parallel. */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>

#include "dirs.h"
#include "provenance.h"
#include "campaign/safe.h"
#include "job/worker.h"
#include "drvlocal.h"
#include "progress.h"
#include "stop.h"

/* Copy src to dst (temporary name, rename), executable. */
static int copy_exe(const char *src, const char *dst, sb_err *e)
{
	char tmp[PATHX + 128];
	snprintf(tmp, sizeof tmp, "%s.tmp.%ld", dst, (long)getpid());
	int in = open(src, O_RDONLY | O_CLOEXEC);
	if (in < 0)
		return sb_errf(e, SB_EUSAGE, "%s: %s: the binaries that travel to other hosts are the ones beside bin/study (make)",
			       src, strerror(errno));
	int out = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0755);
	char buf[65536];
	ssize_t n = 0;
	int bad = out < 0;
	while (!bad && (n = read(in, buf, sizeof buf)) > 0)
		bad = write(out, buf, (size_t)n) != n;
	bad |= n < 0;
	close(in);
	if (out >= 0)
		bad |= close(out) != 0;
	if (bad || rename(tmp, dst)) {
		unlink(tmp);
		return sb_errf(e, SB_EIO, "%s: cannot write: %s", dst, strerror(errno));
	}
	return 0;
}

/* What travels to other hosts: the binaries beside this one (study, shake), as
 * NAME/.remote/study and .remote/shake, the names the worker looks for. They run on
 * every CPU of their architecture: the force kernel picks its path on each host at
 * start-up, and every path gives the same bits (docs/kernel.md; regression.sh,
 * study_ssh.sh). A build made for one CPU (MARCH=...) is refused: it may stop with
 * SIGILL on another. */
static int stage_remote(drv *d, char *dir, size_t len, sb_err *e)
{
	char bindir[PATHX], src[PATHX + 32], dst[PATHX + 32];
	if (!prov_portable())
		return sb_errf(e, SB_EUSAGE, "this build is for one CPU only (%s): rebuild without MARCH (make) to run on other hosts",
			       prov_march());
	snprintf(bindir, sizeof bindir, "%s", d->o->self);
	*strrchr(bindir, '/') = 0;
	snprintf(dir, len, "%s/.remote", d->dir);
	if (dirs_make(dir, e))
		return e->code;
	static const char *const names[] = {"study", "shake"};
	for (int i = 0; i < 2; i++) {
		snprintf(src, sizeof src, "%s/%s", bindir, names[i]);
		snprintf(dst, sizeof dst, "%s/%s", dir, names[i]);
		if (copy_exe(src, dst, e))
			return e->code;
	}
	return 0;
}

static double mono(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
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
	if (stop_requested())
		return 0; /* stopped before this pass began: it starts nothing */
	int is_cache = !strcmp(kind, "cache");
	char jobfile[PATHX], joblog[PATHX];
	snprintf(jobfile, sizeof jobfile, "%s/%s.jobs", d->dir, kind);
	snprintf(joblog, sizeof joblog, "+%s/joblog.txt", d->dir);
	/* GNU parallel follows a link at its joblog: none is written through one */
	if (dirs_own_file(jobfile, e) || dirs_own_file(joblog + 1, e))
		return e->code;
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
	snprintf(njobs, sizeof njobs, "%d", d->loc->jobs);
	const char *fixed[] = {"parallel", "--will-cite", "--jobs", njobs, "--joblog", joblog, "--arg-file", jobfile};
	for (size_t i = 0; i < sizeof fixed / sizeof *fixed; i++)
		add_arg(argv, &argc, MAXA, "%s%s", fixed[i], "");
	char q1[PATHX], q2[PATHX];
	if (d->o->sshloginfile) {
		/* Remote: the binaries go once per host (--basefile), each job's argument file
		 * goes out and its output and log come back (--transferfile, --return). The
		 * "/./" marks where the path relative to the remote work dir starts. Output is
		 * grouped per job, so a DONE line arrives after its files are back. */
		char bindir[PATHX];
		if (stage_remote(d, bindir, sizeof bindir, e)) {
			free(argv);
			return e->code;
		}
		char wd[PATHLEN], tries[32];
		/* hosts down at the start are left out; a job whose host dies under it (ssh
		 * fails: no output, no DONE line) is tried again on another host. The worker
		 * exits 0 whenever it reported, so a run's own failure is never tried again
		 * here; killed and I/O-failed runs are the driver's to retry, attempt by
		 * attempt (driver.c). */
		snprintf(tries, sizeof tries, "%d", d->o->retries + 1);
		add_arg(argv, &argc, MAXA, "--filter-hosts%s%s", "", "");
		add_arg(argv, &argc, MAXA, "--retries%s%s", "", "");
		add_arg(argv, &argc, MAXA, "%s%s", tries, "");
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
	/* A signal between the fork and stop_child would find no parallel to
	 * stop, and this one would start every job: held until the pid is known, then
	 * passed on if it came. */
	sigset_t hold, was;
	sigemptyset(&hold);
	sigaddset(&hold, SIGINT);
	sigaddset(&hold, SIGTERM);
	sigprocmask(SIG_BLOCK, &hold, &was);
	pid_t pid = fork();
	if (pid < 0) {
		sigprocmask(SIG_SETMASK, &was, NULL);
		sb_errf(e, SB_EIO, "fork: %s", strerror(errno));
		goto out;
	}
	if (pid == 0) {
		/* a driver killed outright takes parallel with it: no new jobs start, and
		 * running ones are stopped with a checkpoint */
		prctl(PR_SET_PDEATHSIG, SIGTERM);
		sigprocmask(SIG_SETMASK, &was, NULL);
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
	stop_child(pid);
	sigprocmask(SIG_SETMASK, &was, NULL);
	if (stop_requested())
		kill(pid, SIGTERM); /* the signal came before the pid was known */
	close(pfd[1]);
	/* the workers' lines as they come, and a look for the progress line every
	 * interval in between */
	double interval = progress_tty(d->prog) ? 1 : 2, next = mono() + interval;
	size_t cap = 65536, have = 0;
	char *buf = malloc(cap);
	/* GNU parallel ignores SIGTERM until its first jobs start ("Dummy until jobs
	 * really start"): one sent in that moment is lost and every job would run. After
	 * a stop it is sent again every second until parallel is gone (the engines take
	 * a repeated SIGTERM as one). */
	double resend = -1;
	for (int open_ = buf != NULL; open_;) {
		struct pollfd pf = {pfd[0], POLLIN, 0};
		int ms = d->prog ? (int)((next - mono()) * 1000) : -1;
		if (stop_requested()) {
			if (resend < 0)
				resend = mono() + 1;
			else if (mono() >= resend) {
				kill(pid, SIGTERM);
				resend = mono() + 1;
			}
			int left = (int)((resend - mono()) * 1000) + 1;
			ms = ms < 0 || left < ms ? left : ms;
		}
		int pr = poll(&pf, 1, d->prog && ms < 0 ? 0 : ms);
		if (d->prog && mono() >= next) {
			progress_show(d->prog, &d->db, 0);
			next = mono() + interval;
		}
		if (pr < 0 && errno != EINTR)
			break;
		if (pr <= 0)
			continue;
		if (have + 1 >= cap) { /* a line longer than the buffer: keep its head */
			have = 0;
			continue;
		}
		ssize_t got = read(pfd[0], buf + have, cap - 1 - have);
		if (got < 0 && errno == EINTR)
			continue;
		if (got <= 0) {
			open_ = 0;
			if (have == 0)
				break;
			buf[have++] = '\n'; /* the last line without its newline */
		} else {
			have += (size_t)got;
		}
		size_t from = 0;
		for (char *nl; (nl = memchr(buf + from, '\n', have - from));) {
			*nl = 0;
			char *line = buf + from;
			from = (size_t)(nl - buf) + 1;
			sb_err le = {0};
			if (!strncmp(line, WORKER_START "\t", sizeof WORKER_START))
				ingest_on_start(d, line, &le);
			else if (!strncmp(line, WORKER_DONE "\t", sizeof WORKER_DONE))
				ingest_on_done(d, is_cache, line, &le);
			else if (line[0])
				fprintf(stderr, "%s%s\n", progress_tty(d->prog) ? "\r\033[K" : "", line);
			if (le.code)
				fprintf(stderr, "study: %s\n", le.msg); /* the final sweep repairs it */
		}
		memmove(buf, buf + from, have - from);
		have -= from;
	}
	free(buf);
	close(pfd[0]);
	if (!is_cache)
		progress_show(d->prog, &d->db, 1);
	int st = 0;
	while (waitpid(pid, &st, 0) < 0 && errno == EINTR)
		;
	stop_child(0);
	if (!is_cache)
		ingest_unreported(d, e);
	if (WIFEXITED(st) && WEXITSTATUS(st) == 127 && !stop_requested())
		sb_errf(e, SB_EIO, "GNU parallel did not start (is it installed? make deps)");
	else if (WIFEXITED(st) && WEXITSTATUS(st) == 255 && !stop_requested() && !d->io_fault)
		sb_errf(e, SB_EIO, "GNU parallel failed (see the messages above)");
out:
	for (int i = 0; i < argc; i++)
		free(argv[i]);
	free(argv);
	return e->code;
}

