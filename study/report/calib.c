/* calib.c - the engine's measured cost on this machine, cached per build, CPU and
 * integrator in the runs directory (calib.h). */
#define _GNU_SOURCE /* wait4 */
#include "report/calib.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "fsutil.h"
#include "layout.h"
#include "params.h"
#include "provenance.h"
#include "sql.h"
#include "report/dtext.h"

/* The two calibration runs' shaking: 0.5 s, and that plus CAL_STEPS steps (2 s of the
 * paper preset, 8 s of the fast one): the difference is the shaking alone, long enough
 * to stand out of a loaded machine's noise; settling and the start are the same in both. */
static const double CAL_SHORT = 0.5, CAL_STEPS = 40000;

/* Runs argv[0] with argv; its stdout into out (when out), its stderr to /dev/null.
 * *cpu: the user + system seconds it used. 0, or the error. */
static int child(char *const argv[], char *out, size_t len, double *cpu, sb_err *e)
{
	int fd[2];
	if (pipe(fd))
		return sb_errf(e, SB_EIO, "pipe: %s", strerror(errno));
	pid_t pid = fork();
	if (pid < 0) {
		close(fd[0]);
		close(fd[1]);
		return sb_errf(e, SB_EIO, "fork: %s", strerror(errno));
	}
	if (pid == 0) {
		int null = open("/dev/null", O_WRONLY);
		dup2(fd[1], 1);
		dup2(null, 2);
		close(fd[0]);
		close(fd[1]);
		execv(argv[0], argv);
		_exit(127);
	}
	close(fd[1]);
	size_t n = 0;
	char buf[512];
	ssize_t r;
	while ((r = read(fd[0], buf, sizeof buf)) > 0 || (r < 0 && errno == EINTR))
		for (ssize_t i = 0; i < r && out && n + 1 < len; i++)
			out[n++] = buf[i];
	if (out && len)
		out[n] = 0;
	close(fd[0]);
	int st;
	struct rusage ru;
	while (wait4(pid, &st, 0, &ru) < 0)
		if (errno != EINTR)
			return sb_errf(e, SB_EIO, "wait: %s", strerror(errno));
	if (!WIFEXITED(st) || WEXITSTATUS(st))
		return sb_errf(e, SB_EIO, "%s failed (%s %d)", argv[0], WIFEXITED(st) ? "exit" : "signal",
			       WIFEXITED(st) ? WEXITSTATUS(st) : WTERMSIG(st));
	*cpu = (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_sec +
	       1e-6 * (double)ru.ru_stime.tv_usec;
	return 0;
}

void calib_fit(double cpu_a, double steps_a, double cpu_b, double steps_b, long n, calib *k)
{
	const double g = n > 0 ? (double)n : 1;
	k->step = (cpu_b - cpu_a) / (steps_b - steps_a) / g;
	if (!(k->step > 0))
		k->step = 1e-12;
	k->settle = (cpu_a - k->step * g * steps_a) / g;
	if (!(k->settle > 0))
		k->settle = 0;
}

/* 64-bit FNV-1a of text, the tag's first part */
static unsigned long long fnv(const char *s)
{
	unsigned long long h = 14695981039346656037ULL;
	for (; *s; s++)
		h = (h ^ (unsigned char)*s) * 1099511628211ULL;
	return h;
}

void calib_age(const char *date, char *out, size_t len)
{
	struct tm tm;
	memset(&tm, 0, sizeof tm);
	char z = 0;
	if (sscanf(date, "%d-%d-%dT%d:%d:%d%c", &tm.tm_year, &tm.tm_mon, &tm.tm_mday, &tm.tm_hour, &tm.tm_min, &tm.tm_sec,
		   &z) != 7 || z != 'Z') {
		snprintf(out, len, "age unknown");
		return;
	}
	tm.tm_year -= 1900;
	tm.tm_mon -= 1;
	const double age = difftime(time(NULL), timegm(&tm));
	char d[32];
	dtext_duration(age, d, sizeof d);
	if (age < 0)
		snprintf(out, len, "in the future: a clock set wrong");
	else if (age < 2 * 86400)
		snprintf(out, len, "%s ago", d);
	else
		snprintf(out, len, "%.0f days ago", age / 86400);
}

int calib_learn(sql_db *d, const char *campaign, int integrator, calib *k, sb_err *e)
{
	char cols[1024];
	sql_columns(d, "attempt", cols, sizeof cols);
	if (!strstr(cols, ",cpu_seconds,") && strncmp(cols, "cpu_seconds,", 12))
		return 0; /* a database of an earlier version: no CPU recorded */
	sb_scene sc;
	params_defaults(&sc);
	sc.integrator = integrator;
	char integ[64];
	params_format(&sc, params_find("integrator"), integ, sizeof integ);
	/* every done run of the campaign at this integrator whose every attempt has its CPU
	 * (a resumed run's attempts together simulated its status_time) */
	sqlite3_stmt *q;
#define PARAM(key) "(SELECT p.value FROM param p WHERE p.campaign = r.campaign AND p.run = r.id AND p.key = '" key "')"
	if (sql_exec(d, e, &q,
		     "SELECT " PARAM("n_grains") ", " PARAM("dt") ", s.status_time, r.from_cache, " PARAM("particles") ", "
		     PARAM("settle") ", (SELECT TOTAL(a.cpu_seconds) FROM attempt a WHERE a.campaign = r.campaign AND"
		     " a.run = r.id) FROM run r JOIN result s ON s.campaign = r.campaign AND s.run = r.id WHERE"
		     " r.campaign = ?1 AND r.state = 'done' AND " PARAM("integrator") " = ?2 AND s.status_time > 0 AND"
		     " NOT EXISTS (SELECT 1 FROM attempt a WHERE a.campaign = r.campaign AND a.run = r.id AND"
		     " a.cpu_seconds IS NULL)",
		     "tt", campaign, integ))
		return e->code;
#undef PARAM
	long n = 0;
	double cpu = 0, grain_steps = 0;
	while (sqlite3_step(q) == SQLITE_ROW) {
		const double grains = sqlite3_column_double(q, 0), dt = sqlite3_column_double(q, 1),
			     t = sqlite3_column_double(q, 2);
		const char *particles = (const char *)sqlite3_column_text(q, 4), *settle = (const char *)sqlite3_column_text(q, 5);
		if (!(grains > 0) || !(dt > 0))
			continue;
		/* a run that settled its own packing spent that first (cost.c counts it apart) */
		const int settled = !sqlite3_column_int(q, 3) && (!particles || !particles[0]) && !(settle && !strcmp(settle, "no"));
		cpu += sqlite3_column_double(q, 6) - (settled ? k->settle * grains : 0);
		grain_steps += ceil(t / dt - 1e-9) * grains;
		n++;
	}
	if (sql_done(d, q, e) || n == 0 || !(grain_steps > 0) || !(cpu > 0))
		return e->code;
	char was[sizeof k->source];
	snprintf(was, sizeof was, "%s", k->source);
	k->step = cpu / grain_steps;
	snprintf(k->source, sizeof k->source, "%.60s, rate from %ld finished run%s of this campaign (their CPU per "
		 "grain-step, in %.900s); %s%.3800s", integ, n, n == 1 ? "" : "s", d->path,
		 k->settle > 0 ? "settling at the rate of the " : "the settling's rate not measured yet, not counted: ",
		 strchr(was, ' ') ? strchr(was, ' ') + 1 : was);
	return 0;
}

static int calib_read(const char *runs, const char *shake, int integrator, int measure, calib *k, sb_err *e);

int calib_get(const char *runs, const char *shake, int integrator, calib *k, sb_err *e)
{
	return calib_read(runs, shake, integrator, 1, k, e);
}

int calib_cached(const char *runs, const char *shake, int integrator, calib *k, sb_err *e)
{
	return calib_read(runs, shake, integrator, 0, k, e);
}

static int calib_read(const char *runs, const char *shake, int integrator, int measure, calib *k, sb_err *e)
{
	char version[2048], integ[64], tag[128], path[4200], dir[4200];
	double ignored;
	memset(k, 0, sizeof *k);
	if (child((char *[]){(char *)shake, "--version", NULL}, version, sizeof version, &ignored, e))
		return sb_errf(e, SB_EIO, "%s --version: %s", shake, e->msg);
	/* the integrator's name as the parameter table spells it */
	sb_scene s;
	params_defaults(&s);
	s.integrator = integrator;
	params_format(&s, params_find("integrator"), integ, sizeof integ);
	snprintf(tag, sizeof tag, "%016llx.%s", fnv(version), integ);
	layout_calibration(runs, NULL, dir, sizeof dir);
	layout_calibration(runs, tag, path, sizeof path);

	/* a regular file only: a FIFO planted there would hang the driver */
	sb_err re = {0};
	FILE *f = fs_open_input(path, "calibration", 1 << 20, SB_EIO, &re);
	if (f) {
		char date[64] = "", load[512] = "";
		double la = NAN;
		long ncpu = 0;
		const int got = fscanf(f, "%lg %lg %63s %lg %ld", &k->step, &k->settle, date, &la, &ncpu);
		fclose(f);
		if (got >= 3 && k->step > 0 && k->settle >= 0) {
			/* how busy the machine was then: a rate measured beside other work may be
			 * slow (a file of an older build has no load: not said) */
			if (got == 5 && isfinite(la) && ncpu > 0)
				snprintf(load, sizeof load, ", at load %.2f on %ld cores%s", la, ncpu,
					 la > 0.5 * (double)ncpu ? ", a busy machine: the rate may be slow (remove the file to "
								   "measure again)"
								 : "");
			char age[48];
			calib_age(date, age, sizeof age);
			snprintf(k->source, sizeof k->source, "%s, calibration measured %s (%s) on this machine%s (%.4200s)",
				 integ, date, age, load, path);
			return 0;
		}
	}
	if (!measure) {
		k->step = k->settle = 0;
		snprintf(k->source, sizeof k->source, "%s: not measured on this machine yet (study run --dry-run "
			 "measures it once, two short runs of the paper bed)", integ);
		return 1;
	}

	/* the preset whose integrator this is gives its time step; else the default's */
	char preset[80];
	snprintf(preset, sizeof preset, "integrator=%s", integ);
	for (const sb_preset *p = PRESETS; p->name; p++)
		for (int i = 0; p->set[i] && p->set[i + 1]; i += 2)
			if (!strcmp(p->set[i], "integrator") && !strcmp(p->set[i + 1], integ))
				snprintf(preset, sizeof preset, "preset=%s", p->name);
	if (mkdir(runs ? runs : "runs", 0777) && errno != EEXIST)
		return sb_errf(e, SB_EIO, "%s: %s", runs ? runs : "runs", strerror(errno));
	if (mkdir(dir, 0777) && errno != EEXIST)
		return sb_errf(e, SB_EIO, "%s: %s", dir, strerror(errno));
	/* the scene the two runs run (the defaults, the preset or integrator) */
	params_defaults(&s);
	const char *eq = strchr(preset, '=');
	char key[16];
	snprintf(key, sizeof key, "%.*s", (int)(eq - preset), preset);
	if (params_set(&s, key, eq + 1, "calibration", e))
		return e->code;
	const double cal_long = CAL_SHORT + CAL_STEPS * s.dt;
	char out[4300], outarg[4400], xmf[4300], dur[2][40];
	snprintf(out, sizeof out, "%.4000s/%.100s.run.h5", dir, tag);
	snprintf(outarg, sizeof outarg, "output=%s", out);
	snprintf(dur[0], sizeof dur[0], "duration=%g", CAL_SHORT);
	snprintf(dur[1], sizeof dur[1], "duration=%.17g", cal_long);
	double cpu[2];
	struct timespec t0, t1;
	clock_gettime(CLOCK_MONOTONIC, &t0);
	for (int i = 0; i < 2; i++) {
		char *argv[] = {(char *)shake, preset, "radius_ratio=0", dur[i], "snapshots=no", "traj_rate=0",
				"progress=no", outarg, NULL};
		if (child(argv, NULL, 0, &cpu[i], e)) {
			remove(out);
			return sb_errf(e, SB_EIO, "calibrating the engine (%s %s %s): %s", shake, preset, dur[i], e->msg);
		}
	}
	clock_gettime(CLOCK_MONOTONIC, &t1);
	remove(out);
	snprintf(xmf, sizeof xmf, "%.4000s/%.100s.run.xmf", dir, tag);
	remove(xmf);
	calib_fit(cpu[0], ceil(CAL_SHORT / s.dt - 1e-9), cpu[1], ceil(cal_long / s.dt - 1e-9), s.n_grains, k);

	char date[32];
	prov_now(date);
	double la[1] = {NAN};
	if (getloadavg(la, 1) != 1)
		la[0] = NAN;
	const long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
	/* through a temporary (fsutil.h): a reader never sees half of it, and nothing but a
	 * regular file at its name is replaced */
	sb_file sf;
	if (fs_open_tmp(&sf, path, e))
		return e->code;
	fprintf(sf.f,
		"%.6g %.6g %s %.2f %ld\n# CPU s per grain-step, CPU s per grain of a settling, when, the load average "
		"(1 min) then and the cores; measured with %s on:\n%s",
		k->step, k->settle, date, la[0], ncpu, preset, version);
	if (fs_commit(&sf, e))
		return e->code;
	const double secs = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
	snprintf(k->source, sizeof k->source, "%s, calibration measured now in %.1f s on this machine, at load %.2f on %ld "
		 "cores%s (%.4200s)", integ, secs, la[0], ncpu,
		 la[0] > 0.5 * (double)ncpu ? ", a busy machine: the rate may be slow (remove the file to measure again)"
					    : "",
		 path);
	return 0;
}
