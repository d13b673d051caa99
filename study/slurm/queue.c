/* queue.c - sbatch and squeue as child processes (queue.h). */
#include "queue.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "plan.h"

/* the last non-empty line of s, trimmed, into out */
static void last_line(const char *s, size_t n, char *out, size_t len)
{
	while (n && (s[n - 1] == '\n' || s[n - 1] == '\r' || s[n - 1] == ' '))
		n--;
	size_t b = n;
	while (b && s[b - 1] != '\n')
		b--;
	snprintf(out, len, "%.*s", (int)(n - b), s + b);
}

int slurm_queue_run(char *const argv[], char **out, char *err, size_t errlen)
{
	int po[2], pe[2];
	*out = NULL;
	err[0] = 0;
	if (pipe(po))
		return snprintf(err, errlen, "pipe: %s", strerror(errno)), 127;
	if (pipe(pe)) {
		close(po[0]), close(po[1]);
		return snprintf(err, errlen, "pipe: %s", strerror(errno)), 127;
	}
	pid_t pid = fork();
	if (pid < 0) {
		close(po[0]), close(po[1]), close(pe[0]), close(pe[1]);
		return snprintf(err, errlen, "fork: %s", strerror(errno)), 127;
	}
	if (pid == 0) {
		int dn = open("/dev/null", O_RDONLY);
		if (dn >= 0)
			dup2(dn, 0);
		dup2(po[1], 1);
		dup2(pe[1], 2);
		close(po[0]), close(po[1]), close(pe[0]), close(pe[1]);
		/* the driver ignores nothing a child should see */
		signal(SIGPIPE, SIG_DFL);
		execvp(argv[0], argv);
		fprintf(stderr, "cannot run %s: %s\n", argv[0], strerror(errno));
		_exit(127);
	}
	close(po[1]);
	close(pe[1]);
	char *buf[2] = {NULL, NULL};
	size_t len[2] = {0, 0}, cap[2] = {0, 0};
	struct pollfd fds[2] = {{po[0], POLLIN, 0}, {pe[0], POLLIN, 0}};
	int open_fds = 2, oom = 0;
	while (open_fds) {
		if (poll(fds, 2, -1) < 0) {
			if (errno == EINTR)
				continue;
			break;
		}
		for (int k = 0; k < 2; k++) {
			if (fds[k].fd < 0 || !(fds[k].revents & (POLLIN | POLLHUP | POLLERR)))
				continue;
			if (cap[k] - len[k] < 4097) {
				char *nb = oom ? NULL : realloc(buf[k], cap[k] * 2 + 8192);
				if (!nb) {
					oom = 1; /* keep draining, so the child is not blocked */
					char sink[4096];
					if (read(fds[k].fd, sink, sizeof sink) <= 0)
						close(fds[k].fd), fds[k].fd = -1, open_fds--;
					continue;
				}
				buf[k] = nb;
				cap[k] = cap[k] * 2 + 8192;
			}
			ssize_t r = read(fds[k].fd, buf[k] + len[k], cap[k] - len[k] - 1);
			if (r > 0)
				len[k] += (size_t)r;
			else if (r == 0 || errno != EINTR)
				close(fds[k].fd), fds[k].fd = -1, open_fds--;
		}
	}
	for (int k = 0; k < 2; k++)
		if (fds[k].fd >= 0)
			close(fds[k].fd);
	int st = 0;
	while (waitpid(pid, &st, 0) < 0 && errno == EINTR)
		;
	if (buf[1])
		last_line(buf[1], len[1], err, errlen);
	free(buf[1]);
	if (oom) {
		free(buf[0]);
		snprintf(err, errlen, "out of memory reading the output of %s", argv[0]);
		return 127;
	}
	if (!buf[0])
		buf[0] = calloc(1, 1);
	else
		buf[0][len[0]] = 0;
	*out = buf[0];
	return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

int slurm_queue_submit(char *const args[], int nargs, long *jobid, sb_err *e)
{
	char **argv = calloc((size_t)nargs + 3, sizeof *argv);
	if (!argv)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	argv[0] = "sbatch";
	argv[1] = "--parsable";
	for (int i = 0; i < nargs; i++)
		argv[i + 2] = args[i];
	char *out, err[600];
	int rc = slurm_queue_run(argv, &out, err, sizeof err);
	free(argv);
	*jobid = out ? slurm_plan_parse_jobid(out) : -1;
	if (rc == 127 && !out)
		sb_errf(e, SB_EIO, "sbatch: %s", err);
	else if (rc == 127)
		sb_errf(e, SB_EIO, "sbatch is not installed (slurm-client)%s%s", err[0] ? ": " : "", err);
	else if (rc || *jobid < 0)
		sb_errf(e, SB_EIO, "sbatch failed (exit %d): %s", rc, err[0] ? err : out ? out : "no output");
	free(out);
	return e->code;
}

int slurm_queue_list(slurm_queue *q, sb_err *e)
{
	q->t = NULL;
	q->n = 0;
	char user[32];
	snprintf(user, sizeof user, "--user=%ld", (long)getuid());
	/* every task on a line of its own (--array), ranges not yet split included */
	char *argv[] = {"squeue", "--noheader", "--array", user, "--format=%i|%T", NULL};
	char *out, err[600];
	int rc = slurm_queue_run(argv, &out, err, sizeof err);
	if (rc) {
		free(out);
		return sb_errf(e, SB_EIO, "squeue %s (exit %d)%s%s", rc == 127 ? "could not be run" : "failed", rc,
			       err[0] ? ": " : "", err);
	}
	long cap = 0;
	for (char *s = out, *line; (line = strsep(&s, "\n"));) {
		slurm_queue_task t;
		if (!slurm_plan_parse_squeue(line, &t.job, &t.index, t.state, sizeof t.state))
			continue;
		if (q->n == cap) {
			cap = cap * 2 + 64;
			slurm_queue_task *nt = realloc(q->t, (size_t)cap * sizeof *nt);
			if (!nt) {
				free(out);
				slurm_queue_free(q);
				return sb_errf(e, SB_ENOMEM, "out of memory");
			}
			q->t = nt;
		}
		q->t[q->n++] = t;
	}
	free(out);
	return 0;
}

const char *slurm_queue_state(const slurm_queue *q, long job, long index)
{
	const char *range = NULL;
	for (long i = 0; i < q->n; i++) {
		if (q->t[i].job != job)
			continue;
		if (q->t[i].index == index)
			return q->t[i].state;
		if (q->t[i].index < 0)
			range = q->t[i].state; /* a pending range not split yet: assume it holds it */
	}
	return range;
}

void slurm_queue_free(slurm_queue *q)
{
	free(q->t);
	q->t = NULL;
	q->n = 0;
}
