/* shake_main.c - bin/shake: run one scene. Only this file prints and exits. */
#include <errno.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "checkpoint.h"
#include "clock.h"
#include "h5out.h"
#include "kernel.h"
#include "paircoef.h"
#include "provenance.h"
#include "prepare.h"
#include "run.h"
#include "pclass.h"
#include "pfile.h"
#include "sim.h"
#include "validate.h"

static volatile sig_atomic_t g_stop; /* the one piece of global state: signals need it */

static void on_signal(int sig)
{
	(void)sig;
	g_stop = 1;
}

/* The force kernel's paths: for people (--version) or one a line for scripts. */
static void print_kernels(FILE *f, int plain)
{
	sb_kpath p[SB_KPATHS_MAX];
	const int n = kernel_paths(p);
	char cpu[128];
	prov_cpu(cpu, sizeof cpu);
	if (!plain) {
		const char *pick = NULL;
		for (int i = 0; i < n && !pick; i++)
			if (p[i].runnable && !p[i].test)
				pick = p[i].name;
		fprintf(f, "cpu: %s\nkernel path: %s (the widest this CPU runs; %s=NAME forces one)\npaths:", cpu,
			pick ? pick : "none", SB_KERNEL_ENV);
		for (int i = 0; i < n; i++)
			fprintf(f, " %s%s%s", p[i].name, p[i].test ? " (tests)" : "", p[i].runnable ? "" : " (not on this CPU)");
		fprintf(f, "\n");
		return;
	}
	for (int i = 0; i < n; i++)
		fprintf(f, "%s %s %s %s\n", p[i].name, p[i].runnable ? "yes" : "no", p[i].test ? "test" : "-", p[i].needs);
}

/* The run's progress on stderr, one line rewritten in place (the library reports it:
 * sb_progress, core/run/sim.h; only this file prints). */
static void show_progress(void *ctx, const sb_progress *p)
{
	(void)ctx;
	switch (p->kind) {
	case PROG_SETTLING:
		fprintf(stderr, "\rshake: settling, t = %.2f s, kinetic energy %.3g erg per disk (settled below %g) ", p->t,
			p->ke, p->ke_settled);
		break;
	case PROG_SETTLED:
		fprintf(stderr, "\rshake: settled after %.2f s%60s\n", p->t, "");
		break;
	case PROG_SHAKING:
		fprintf(stderr, "\rshake: t = %.2f / %.2f s  %.0f steps/s  ETA %02d:%02d:%02d ", p->t, p->t_end,
			p->steps_per_s, (int)(p->eta / 3600), (int)fmod(p->eta / 60, 60), (int)fmod(p->eta, 60));
		break;
	case PROG_SHAKEN:
		fputc('\n', stderr);
		break;
	}
	fflush(stderr);
}

static void usage(FILE *f)
{
	fprintf(f,
		"usage: shake [SCENE] [key=value ...] [--profile | --contacts]\n"
		"       shake --help | --params | --records | --version | --kernel-paths\n\n"
		"Simulates a vertically vibrated 2D box of soft disks (Poeschel & Herrmann 1995)\n"
		"and writes one HDF5 file (output=...) with an XDMF sidecar for ParaView.\n"
		"SCENE is an INI file of key = value lines (top level or [scene]); key=value\n"
		"arguments override it. Without SCENE the paper preset is used.\n\n"
		"  --help      this text and every scene key with unit, default and range\n"
		"  --params    the parameter table as TSV (for tools)\n"
		"  --records   the table of recorded quantities as TSV: name, key, clock, journal\n"
		"              tag, run-file group, columns (for tools)\n"
		"  --profile   time per phase of the step on stderr at the end\n"
		"  --contacts  what the contact law gives a mean grain pair, a grain and the\n"
		"              intruder, a grain on a wall disk and the lightest pair (m_eff,\n"
		"              gamma_N, restitution, contact time) and the tangential law (its\n"
		"              shear stiffness) for the scene given, and exit\n"
		"  --version   git hash of the build, the CPU and the force kernel's paths\n"
		"  --kernel-paths  the force kernel's paths, one a line: name, runs here (yes/no),\n"
		"              for tests only (test/-), what the CPU needs (for scripts)\n\n"
		"The force kernel runs the widest path this CPU has; SHAKEBOX_KERNEL=NAME forces\n"
		"one (docs/kernel.md). Every path gives the same numbers to the bit.\n\n"
		"Exit codes: 0 ok, 1 bad input, 2 I/O, 3 NaN/Inf, 4 overlap beyond max_overlap,\n"
		"5 a disk left the box, 6 settling did not converge, 7 interrupted (SIGINT/SIGTERM;\n"
		"a checkpoint is written when checkpoint_every > 0 and the run resumes from it).\n\n");
	params_print_help(f);
}

/* --contacts: the pair classes from the scene's keys (pclass.h), the intruder's from
 * radius_ratio, which a particle file's first intruder sets (pfile_scene_intruders); a
 * particle file's own disks are in its run file's /contact_law */
static void print_contacts(const sb_scene *sc)
{
	const sb_law law = sim_law(sc);
	sb_pclass c[SB_NPCLASS];
	pclass_of_scene(&law, sc, c);
	char hz[64];
	snprintf(hz, sizeof hz, "hertz: e and t_c at an impact speed of %g cm/s", PCLASS_HERTZ_V);
	double rlo, rhi, rmean;
	params_grain_radii(sc, &rlo, &rhi, &rmean);
	printf("# the contact law (%s, %s) for the scene's mean grain radius %g cm%s; docs/model.md, \"Restitution\"\n",
	       law.hertz ? hz : "hooke",
	       law.resti ? "restitution given: the damping per pair" : "gamma_n given: the restitution per pair",
	       rmean, sc->particles[0] ? " (not the particle file's grains; the intruder of its radius_ratio, the file's)" : "");
	if (law.spring)
		printf("# tangential = spring: shear_stiffness k_t = %.6g (docs/model.md, \"Tangential law\")\n", law.kt);
	else
		printf("# tangential = viscous: no shear spring\n");
	if (law.table) { /* docs/model.md, "Materials per pair of kinds" */
		printf("# materials per pair of kinds: class stiffness mu gamma_s (the law's units)\n");
		for (int k = -1; k < SB_NPAIRC; k++) {
			const sb_paircoef pc = paircoef_of(sc, k);
			printf("#   %-17s %10.5g %6.4g %10.5g\n", paircoef_name(k), pc.Y, pc.mu, pc.gs);
		}
	}
	printf("%-15s %10s %10s %11s %12s\n", "pair", "m_eff_g", "gamma_n_1/s", "restitution", "contact_time_s");
	for (int k = 0; k < SB_NPCLASS; k++)
		if (c[k].present)
			printf("%-15s %10.5g %10.5g %11.5g %12.5g\n", c[k].name, c[k].m_eff, c[k].gamma_n, c[k].e, c[k].tc);
}

int main(int argc, char **argv)
{
	gsl_set_error_handler_off(); /* statuses are checked: GSL's default handler aborts */
	sb_scene sc;
	params_defaults(&sc);
	sb_err e = {0};
	int profile = 0, contacts = 0;
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i];
		if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
			usage(stdout);
			return 0;
		}
		if (!strcmp(a, "--params")) {
			params_print_table(stdout);
			return 0;
		}
		if (!strcmp(a, "--records")) {
			rec_print_table(stdout);
			return 0;
		}
		if (!strcmp(a, "--version")) {
			printf("%s\n", prov_version());
			print_kernels(stdout, 0);
			return 0;
		}
		if (!strcmp(a, "--kernel-paths")) {
			print_kernels(stdout, 1);
			return 0;
		}
		if (!strcmp(a, "--profile")) {
			profile = 1;
			continue;
		}
		if (!strcmp(a, "--contacts")) {
			contacts = 1;
			continue;
		}
		if (a[0] == '-' && a[1] == '-') {
			fprintf(stderr, "shake: unknown option '%s' (see shake --help)\n", a);
			return SB_EUSAGE;
		}
		if (strchr(a, '=') ? params_override(&sc, a, &e)
				   : (i == 1 ? params_load_file(&sc, a, &e)
					     : sb_errf(&e, SB_EUSAGE,
						       "command line: expected key=value, got '%s' (the scene file comes first)", a))) {
			fprintf(stderr, "shake: %s\n", e.msg);
			return SB_EUSAGE;
		}
	}
	/* from here a SIGINT or SIGTERM ends the run as one (exit code 7): reading a large
	 * particle file below takes seconds and polls for them (guard.h) */
	struct sigaction sa;
	memset(&sa, 0, sizeof sa);
	sa.sa_handler = on_signal;
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);
	/* a particle file's intruder decides radius_ratio (docs/model.md, "Units and the
	 * paper's values"): known before the checks, the checkpoint's identity and the run
	 * file's /parameters */
	if (sc.particles[0] && pfile_scene_intruders(&sc, &e)) {
		fprintf(stderr, "shake: %s\n", e.msg);
		return e.code;
	}
	if (params_validate(&sc, &e)) {
		fprintf(stderr, "shake: %s\n", e.msg);
		return SB_EUSAGE;
	}
	if (contacts) {
		print_contacts(&sc);
		return 0;
	}

	/* A run must not find out at its end that it cannot write its output. */
	const int no_output = params_no_output(&sc);
	char dir[SB_STR_MAX];
	snprintf(dir, sizeof dir, "%s", sc.output);
	char *slash = strrchr(dir, '/');
	if (slash)
		*slash = 0;
	if (!no_output && access(slash ? (dir[0] ? dir : "/") : ".", W_OK) != 0) {
		fprintf(stderr, "shake: output: cannot write in directory '%s': %s\n", slash ? dir : ".",
			strerror(errno));
		return SB_EIO;
	}

	sb_sim *s = malloc(sizeof *s);
	if (!s) {
		fprintf(stderr, "shake: out of memory\n");
		return SB_ENOMEM;
	}
	sim_init(s, &sc, &e);
	/* ... nor that its end would be renamed over a device, a FIFO or a directory */
	if (sim_check_outputs(s, &e)) {
		fprintf(stderr, "shake: %s\n", e.msg);
		sim_free(s);
		free(s);
		return e.code;
	}
	const int progress = sc.progress == TRI_YES || (sc.progress == TRI_AUTO && isatty(2));
	s->stop = &g_stop;
	s->profile = profile;
	s->progress = progress ? show_progress : NULL;

	int loaded = sc.restart == TRI_NO ? 0 : ckpt_load(s, &e);
	if (loaded < 0 || e.code) {
		fprintf(stderr, "shake: %s\n", e.msg);
		sim_free(s);
		free(s);
		return e.code ? e.code : SB_EIO;
	}
	if (loaded) { /* always said: a log must show that a run continued another */
		fprintf(stderr, "shake: resuming from %s at t = %.4f s\n", s->ckpt_path, s->step * sc.dt);
	} else if (s->warning[0]) { /* a checkpoint it could not use: the run starts over */
		fprintf(stderr, "shake: warning: %s\n", s->warning);
		/* from a fresh setup: the checkpoint may have been read in part */
		sim_free(s);
		sim_init(s, &sc, &e);
		s->stop = &g_stop;
		s->profile = profile;
		s->progress = progress ? show_progress : NULL;
	}
	if (!loaded) {
		if (s->progress)
			fprintf(stderr, "shake: preparing %s\n", sc.particles[0] ? sc.particles : "the scene");
		int prc = prepare_run(s, &e);
		if (s->warning[0])
			fprintf(stderr, "shake: warning: %s\n", s->warning);
		/* legal (a free fall, a collision test) but more often a file whose walls were
		 * forgotten: LAMMPS would at least have its box, here nothing holds the grains */
		if (sc.particles[0] && (!prc || s->status) && s->st.nm > 0 && s->st.n == s->st.nm)
			fprintf(stderr, "shake: warning: %s: no walls (disks of kind wall, LAMMPS type 3): nothing holds the "
					"grains and no disk can leave the box\n",
				sc.particles);
		if (prc && !s->status) {
			/* bad particle file, out of memory, I/O: nothing ran, nothing to record */
			fprintf(stderr, "shake: %s\n", e.msg);
			int code = e.code;
			sim_free(s);
			free(s);
			return code;
		}
	}
	if (!s->status)
		run_shaking(s, &e);

	int code = s->status;
	if (code == SB_EINTR && sc.checkpoint_every > 0) {
		sb_err e2 = {0};
		if (ckpt_write(s, &e2))
			fprintf(stderr, "shake: %s\n", e2.msg);
		else
			fprintf(stderr, "shake: %s; checkpoint %s written, run again to resume\n", s->status_msg,
				s->ckpt_path);
		journal_close(&s->jr);
	} else if (no_output) {
		if (code)
			fprintf(stderr, "shake: %s (output = none: not recorded)\n", s->status_msg);
	} else if (code == SB_EIO) {
		/* a write that failed while the run shook (its journal, a checkpoint on a full
		 * disk) is the machine's fault, not the run's outcome: no run file records it
		 * (a driver would take that file for the run's end and fail the run); the last
		 * good checkpoint and its journal stay, and the same command resumes there
		 * (docs/scene.md, "Exit codes") */
		journal_close(&s->jr);
		fprintf(stderr, "shake: %s; no run file written%s\n", s->status_msg,
			sc.checkpoint_every > 0 ? ": run again to resume from the last checkpoint" : "");
	} else {
		sb_err e2 = {0};
		const double w0 = sb_now();
		const int wrc = h5out_write_run(s, &e2);
		s->write_seconds = sb_now() - w0;
		if (wrc) {
			fprintf(stderr, "shake: %s\n", e2.msg);
			/* a run that simulated to its end keeps that end as a checkpoint (where
			 * the fault allows): run again, it only writes the file */
			sb_err e3 = {0};
			if (!code && sc.checkpoint_every > 0 && !ckpt_write(s, &e3))
				fprintf(stderr, "shake: checkpoint %s holds the finished run; run again to write the output\n",
					s->ckpt_path);
			if (!code)
				code = e2.code;
		} else {
			sim_cleanup_files(s);
			if (code)
				fprintf(stderr, "shake: %s (recorded in %s)\n", s->status_msg, sc.output);
		}
	}
	if (profile) {
		static const char *names[PH_N] = {"predict", "check", "neighbour", "force", "correct", "record"};
		fprintf(stderr, "profile: kernel path %s on %s\n", kernel_path(s->kern), s->prov.cpu);
		fprintf(stderr, "profile: %ld steps, %ld neighbour builds, %d pairs in the last list (%d of large disks)\n",
			s->step, s->nl.builds, s->nl.npairs + s->nl.nbig, s->nl.nbig);
		for (int k = 0; k < PH_N; k++)
			fprintf(stderr, "profile: %-10s %8.3f s\n", names[k], s->tphase[k]);
		fprintf(stderr, "profile loop_seconds=%.6f steps=%ld mobile=%d walls=%d write_seconds=%.6f\n",
			s->loop_seconds, s->step, s->st.nm, s->st.n - s->st.nm, s->write_seconds);
	}
	sim_free(s);
	free(s);
	return code;
}
