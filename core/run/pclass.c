/* pclass.c - the pair classes of a run (pclass.h). A wall disk never moves: the
 * contact's motion is the grain's alone, xi'' = -(Y xi + gamma_N m_eff xi') / m_grain,
 * so its restitution is that of mass m_grain at damping gamma_N m_eff / m_grain; with
 * wall_mass = disk m_eff is smaller than m_grain and a wall contact rebounds more
 * than a grain pair does (docs/model.md, "Restitution"). */
#include "pclass.h"

#include <math.h>

#include "dtguard.h"
#include "place.h"

static void one(const sb_law *law, sb_pclass *c, const char *name, double mi, double mj, double ri, double rj, int ki,
		int kj)
{
	const int wall = kj == KIND_WALL;
	const sb_kc k = forces_kc(law, ki, kj); /* the class's coefficients (paircoef.h) */
	/* a wall of infinite mass: mj = inf, m_eff = mi */
	const double meff = isinf(mj) ? mi : mi * mj / (mi + mj), mmove = wall ? mi : meff;
	c->name = name;
	c->present = mi > 0 && mj > 0;
	if (!c->present)
		return;
	c->m_eff = meff;
	c->gamma_n = law->resti ? k.gn / sqrt(meff) : k.gn;
	c->Y = k.Y;
	c->mu = k.mu;
	c->gamma_s = k.gs;
	if (law->hertz)
		dtguard_hertz(k.Y, ri * rj / (ri + rj), c->gamma_n * meff, mmove, PCLASS_HERTZ_V, &c->e, &c->tc);
	else
		dtguard_pair(k.Y, c->gamma_n * meff / mmove, mmove, &c->e, &c->tc);
}

/* masses m and radii r of a grain (g), the intruder (i), a wall disk (w), the lightest
 * (l, of kind kl) */
static void classes(const sb_law *law, const double m[4], const double r[4], int kl, sb_pclass out[SB_NPCLASS])
{
	one(law, &out[0], "grain_grain", m[0], m[0], r[0], r[0], KIND_GRAIN, KIND_GRAIN);
	one(law, &out[1], "grain_intruder", m[0], m[1], r[0], r[1], KIND_GRAIN, KIND_INTRUDER);
	one(law, &out[2], "grain_wall", m[0], m[2], r[0], r[2], KIND_GRAIN, KIND_WALL);
	one(law, &out[3], "lightest_pair", m[3], m[3], r[3], r[3], kl, kl);
}

void pclass_of_state(const sb_law *law, const sb_scene *sc, const sb_state *st, sb_pclass out[SB_NPCLASS])
{
	double m[4] = {0, 0, 0, INFINITY}, r[4] = {0, 0, 0, 0}, rsum = 0;
	long ng = 0;
	int kl = KIND_GRAIN;
	for (int i = 0; i < st->n; i++) {
		if (st->kind[i] == KIND_GRAIN) {
			m[0] += st->m[i];
			rsum += st->r[i];
			ng++;
		} else if (st->kind[i] == KIND_INTRUDER && !(m[1] > 0)) {
			m[1] = st->m[i];
			r[1] = st->r[i];
		} else if (st->kind[i] == KIND_WALL && !(m[2] > 0)) {
			m[2] = st->m[i];
			r[2] = st->r[i];
		}
		if (i < st->nm && st->m[i] < m[3]) {
			m[3] = st->m[i];
			r[3] = st->r[i];
			kl = st->kind[i];
		}
	}
	m[0] = ng ? m[0] / (double)ng : 0; /* the mean grain: its mean mass and radius */
	r[0] = ng ? rsum / (double)ng : 0;
	if (sc->wall_mass == WALLMASS_INFINITE && m[2] > 0)
		m[2] = INFINITY;
	if (isinf(m[3]))
		m[3] = 0;
	classes(law, m, r, kl, out);
}

void pclass_of_scene(const sb_law *law, const sb_scene *sc, sb_pclass out[SB_NPCLASS])
{
	double rlo, rhi, rg;
	params_grain_radii(sc, &rlo, &rhi, &rg);
	const double ri = sc->radius_ratio * rg;
	const double mint = sc->radius_ratio > 0 ? place_mass(sc, ri, KIND_INTRUDER) : 0;
	const double mlo = place_mass(sc, rlo, KIND_GRAIN);
	const int ilight = mint > 0 && mint < mlo;
	const double m[4] = {place_mass(sc, rg, KIND_GRAIN), mint,
			     sc->wall_mass == WALLMASS_INFINITE ? INFINITY : place_mass(sc, sc->wall_radius, KIND_WALL),
			     ilight ? mint : mlo};
	const double r[4] = {rg, ri, sc->wall_radius, ilight ? ri : rlo};
	classes(law, m, r, ilight ? KIND_INTRUDER : KIND_GRAIN, out);
}
