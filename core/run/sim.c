/* sim.c - a run's setup: the scene's derived quantities (intruder, box bounds, the
 * force kernel and the neighbour list), the observables at t = 0, the box motion, and
 * the files a finished run leaves. The run's phases live in prepare.c (preparation),
 * step.c (one step) and run.c (the shaking loop). */
#include "sim.h"

#include <assert.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "dtguard.h"
#include "fsutil.h"
#include "paircoef.h"

double sim_box_y(const sb_sim *s, double t) { return drive_y(&s->drive, t); }
double sim_box_v(const sb_sim *s, double t) { return drive_v(&s->drive, t); }
double sim_box_a(const sb_sim *s, double t) { return drive_a(&s->drive, t); }

sb_law sim_law(const sb_scene *sc)
{
	const int hertz = sc->normal == NORMAL_HERTZ;
	const double Y = hertz ? sc->hertz_stiffness : sc->stiffness;
	sb_law l = {.Y = Y, .gn = sc->gamma_n, .gs = sc->gamma_s, .mu = sc->mu, .max_overlap = sc->max_overlap,
		    .clip = sc->clip_attractive, .resti = sc->restitution > 0, .hertz = hertz,
		    .spring = sc->tangential == TANGENTIAL_SPRING, .kt = dtguard_kt(sc)};
	if (l.resti)
		l.gz = forces_gz(sc->stiffness, sc->restitution);
	/* materials per pair of kinds (paircoef.h): each pair of kinds its class's
	 * coefficients; the paper's one material keeps the vector kernel (table = 0) */
	l.table = !paircoef_uniform(sc);
	for (int a = 0; a < 3; a++)
		for (int b = 0; b < 3; b++) {
			const sb_paircoef c = paircoef_of(sc, forces_pairclass(a, b));
			l.kc[a][b] = (sb_kc){c.Y, l.resti ? forces_gz(c.Y, sc->restitution) : c.gn, c.gs, c.mu, c.kt};
		}
	return l;
}

int sim_init(sb_sim *s, const sb_scene *sc, sb_err *e)
{
	/* what run.c's schedule and h5out.c's writers take for granted (record.h) */
	assert(!rec_table_check());
	memset(s, 0, sizeof *s);
	s->sc = *sc;
	s->stage = "step";
	s->law = sim_law(sc);
	integ_init(&s->in, sc->integrator, sc->dt);
	s->drive = (sb_drive){sc->ramp, sc->amplitude, sc->frequency, sc->ramp_from, sc->ramp_to,
			      sc->duration - sc->ramp_hold, sc->ramp_hold};
	s->intruder = -1;
	s->nsteps = llround(sc->duration / sc->dt);
	/* output = none: no run file, hence no journal to assemble it from and no
	 * checkpoint to resume into it (params_validate refuses asking for one) */
	if (!params_no_output(sc)) {
		snprintf(s->journal_path, sizeof s->journal_path, "%s" SB_JOURNAL_EXT, sc->output);
		sim_xmf_path(sc->output, s->xmf_path, sizeof s->xmf_path);
		if (sc->checkpoint[0])
			snprintf(s->ckpt_path, sizeof s->ckpt_path, "%s", sc->checkpoint);
		else
			snprintf(s->ckpt_path, sizeof s->ckpt_path, "%s" SB_CKPT_EXT, sc->output);
	}
	prov_init(&s->prov);
	(void)e;
	return 0;
}

void sim_free(sb_sim *s)
{
	obs_free(&s->obs);
	journal_close(&s->jr);
	nlist_free(&s->nl);
	kernel_free(s->kern);
	s->kern = NULL;
	state_free(&s->st);
}

int sim_fail(sb_sim *s, int code, double t, long step, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(s->status_msg, sizeof s->status_msg, fmt, ap);
	va_end(ap);
	s->status = code;
	s->status_time = t;
	s->status_step = step;
	return code;
}

double sim_kinetic(const sb_sim *s)
{
	const sb_state *st = &s->st;
	double ke = 0, idt2 = 1.0 / (s->sc.dt * s->sc.dt);
	for (int i = 0; i < st->nm; i++) {
		double vx = st->q[C_X][1][i], vy = st->q[C_Y][1][i], w = st->q[C_TH][1][i];
		ke += 0.5 * st->m[i] * (vx * vx + vy * vy) + 0.5 * (1.0 / st->inv_i[i]) * w * w;
	}
	return ke * idt2;
}

/* Where the walls are, a grain must stay: the box is the hull of the wall disks in x
 * and above their lowest centre. Without walls there is no box to leave. */
static void set_bounds(sb_sim *s)
{
	const sb_state *st = &s->st;
	s->xlo = -INFINITY;
	s->xhi = INFINITY;
	s->ylo = -INFINITY;
	if (st->n == st->nm)
		return;
	if (s->nl.period > 0) {
		/* periodic sides: x is wrapped at each list build, and between builds a disk
		 * moves less than a skin; half a period beyond is a blow-up, not a crossing */
		const double W = s->nl.period;
		s->xlo = -0.5 * W;
		s->xhi = 1.5 * W;
		s->ylo = INFINITY;
		for (int i = st->nm; i < st->n; i++)
			s->ylo = fmin(s->ylo, st->q[C_Y][0][i]);
		return;
	}
	s->xlo = INFINITY;
	s->xhi = -INFINITY;
	s->ylo = INFINITY;
	for (int i = st->nm; i < st->n; i++) {
		s->xlo = fmin(s->xlo, st->q[C_X][0][i]);
		s->xhi = fmax(s->xhi, st->q[C_X][0][i]);
		s->ylo = fmin(s->ylo, st->q[C_Y][0][i]);
	}
}

int sim_derive(sb_sim *s, sb_err *e)
{
	if (s->st.nm == 0)
		return sb_errf(e, SB_EUSAGE, "%s%sthe scene has no mobile disks (grains or an intruder): nothing to shake",
			       s->sc.particles[0] ? s->sc.particles : "", s->sc.particles[0] ? ": " : "");
	double rs = 0;
	int ng = 0;
	for (int i = 0; i < s->st.nm; i++)
		if (s->st.kind[i] == KIND_GRAIN) {
			rs += s->st.r[i];
			ng++;
		}
	double rlo, rhi, rscene;
	params_grain_radii(&s->sc, &rlo, &rhi, &rscene);
	s->rmean = ng ? rs / ng : rscene;
	double split;
	if (rec_on(&s->sc, 1, REC_SEGREG) && !obs_segregation_split(s->st.r, s->st.kind, s->st.nm, &split))
		return sb_errf(e, SB_EUSAGE,
			       "%s: segregation_samples: the segregation index compares large grains with small, and "
			       "the bed's %d grains are all of radius %g cm (size_dist = binary, or a particle file of "
			       "two sizes)", params_where(&s->sc, "segregation_samples"), ng, ng ? rs / ng : 0.0);
	s->intruder = state_find_intruder(&s->st);
	s->n_intruders = 0;
	for (int i = 0; i < s->st.nm; i++)
		s->n_intruders += s->st.kind[i] == KIND_INTRUDER;
	if (kernel_init(&s->kern, &s->st, e))
		return e->code;
	if (nlist_init(&s->nl, &s->st, s->sc.skin, kernel_pair_shift(), e))
		return e->code;
	s->nl.scan = kernel_scan(s->kern);
	if (s->sc.sides == SIDES_PERIODIC) {
		/* no disk may reach its own image, nor a pair meet both ways round (the seam
		 * list finds each pair of images once); params_validate checked the scene's
		 * keys, this checks the disks, also those of a particle file */
		const double W = s->sc.width;
		int big = 0;
		for (int i = 1; i < s->st.n; i++)
			big = s->st.r[i] > s->st.r[big] ? i : big;
		if (!(W > 2 * s->st.r[big] + s->sc.skin))
			return sb_errf(e, SB_EUSAGE,
				       "%s%ssides = periodic (%s): width %g cm (%s) is the period, and disk %d of radius %g cm "
				       "would meet its own image: the period must exceed its diameter plus the skin (%g cm)",
				       s->sc.particles[0] ? s->sc.particles : "", s->sc.particles[0] ? ": " : "",
				       params_where(&s->sc, "sides"), W, params_where(&s->sc, "width"), s->st.id[big],
				       s->st.r[big], s->sc.skin);
		nlist_set_period(&s->nl, W);
	}
	set_bounds(s);
	return 0;
}

/* The inner faces of the side walls: the hull of the wall disks less their radii
 * (x = 0 and width for a generated scene); with periodic sides 0 and the period. */
int sim_obs_init(sb_sim *s, sb_err *e)
{
	const sb_state *st = &s->st;
	if (s->nl.period > 0) /* periodic sides: the period is the box */
		return obs_init(&s->obs, &s->sc, st, s->intruder, s->surface0, 0, s->nl.period, e);
	double x0 = INFINITY, x1 = -INFINITY;
	for (int i = st->nm; i < st->n; i++) {
		x0 = fmin(x0, st->q[C_X][0][i] + st->r[i]);
		x1 = fmax(x1, st->q[C_X][0][i] - st->r[i]);
	}
	if (!(x0 < x1)) { /* no walls: the extent of the disks */
		x0 = INFINITY;
		x1 = -INFINITY;
		for (int i = 0; i < st->nm; i++) {
			x0 = fmin(x0, st->q[C_X][0][i] - st->r[i]);
			x1 = fmax(x1, st->q[C_X][0][i] + st->r[i]);
		}
	}
	return obs_init(&s->obs, &s->sc, st, s->intruder, s->surface0, x0, x1, e);
}

void sim_xmf_path(const char *h5path, char *out, size_t len)
{
	size_t l = strlen(h5path);
	snprintf(out, len, "%.*s.xmf", (int)(l > 3 && !strcmp(h5path + l - 3, ".h5") ? l - 3 : l), h5path);
}

int sim_check_outputs(const sb_sim *s, sb_err *e)
{
	const sb_scene *sc = &s->sc;
	const int ck = sc->checkpoint[0] != 0;
	const struct {
		const char *key, *path, *what;
	} out[] = {
		{"output", sc->output, ""},
		{"output", s->xmf_path, " (its XDMF sidecar)"},
		{"output", s->journal_path, " (its journal)"},
		{ck ? "checkpoint" : "output", s->ckpt_path, ck ? "" : " (its checkpoint)"},
		{"write_particles", sc->write_particles, ""},
		{"write_lammps", sc->write_lammps, ""},
	};
	const size_t n = sizeof out / sizeof *out;
	/* two outputs at one file: the run would delete (the journal and checkpoint at
	 * its end) or overwrite one with the other, and say nothing (docs/output.md) */
	for (size_t k = 0; k < n; k++)
		for (size_t j = k + 1; j < n && out[k].path[0]; j++) {
			if (!out[j].path[0] || (k == 0 && params_no_output(sc)) || !fs_same_file(out[k].path, out[j].path))
				continue;
			return sb_errf(e, SB_EUSAGE,
				       "%s: %s: '%s'%s is the same file as %s: '%s'%s (%s): one would delete or overwrite "
				       "the other; give them different paths",
				       params_where(sc, out[j].key), out[j].key, out[j].path, out[j].what, out[k].key,
				       out[k].path, out[k].what, params_where(sc, out[k].key));
		}
	for (size_t k = 0; k < n; k++) {
		const char *kind;
		if (!out[k].path[0] || (k == 0 && params_no_output(sc)) || fs_replaceable(out[k].path, &kind))
			continue;
		return sb_errf(e, SB_EUSAGE,
			       "%s: %s: '%s'%s is %s, not a regular file: a run writes its files under a temporary "
			       "name and renames them into place, which would replace it%s",
			       params_where(sc, out[k].key), out[k].key, out[k].path, out[k].what, kind,
			       k == 0 ? " (output = none runs without a run file)" : "");
	}
	return 0;
}

/* Only regular files: what else stands there now is not the run's (fsutil.c). */
static void remove_regular(const char *path)
{
	const char *kind;
	if (path[0] && fs_replaceable(path, &kind))
		unlink(path);
}

void sim_cleanup_files(sb_sim *s)
{
	journal_close(&s->jr);
	remove_regular(s->journal_path);
	remove_regular(s->ckpt_path);
}
