/* pclass.c - the pair classes of a run (pclass.h). A wall disk never moves: the
 * contact's motion is the grain's alone, xi'' = -(Y xi + gamma_N m_eff xi') / m_grain,
 * so its restitution is that of mass m_grain at damping gamma_N m_eff / m_grain; with
 * wall_mass = disk m_eff is smaller than m_grain and a wall contact rebounds more
 * than a grain pair does (docs/model.md, "Restitution"). */
#include "pclass.h"

#include <math.h>

#include "dtguard.h"
#include "place.h"

static void one(const sb_law *law, sb_pclass *c, const char *name, double mi, double mj, int wall)
{
	/* a wall of infinite mass: mj = inf, m_eff = mi */
	const double meff = isinf(mj) ? mi : mi * mj / (mi + mj), mmove = wall ? mi : meff;
	c->name = name;
	c->present = mi > 0 && mj > 0;
	if (!c->present)
		return;
	c->m_eff = meff;
	c->gamma_n = law->resti ? law->gz / sqrt(meff) : law->gn;
	dtguard_pair(law->Y, c->gamma_n * meff / mmove, mmove, &c->e, &c->tc);
}

static void classes(const sb_law *law, double mg, double mint, double mwall, double mmin, sb_pclass out[SB_NPCLASS])
{
	one(law, &out[0], "grain_grain", mg, mg, 0);
	one(law, &out[1], "grain_intruder", mg, mint, 0);
	one(law, &out[2], "grain_wall", mg, mwall, 1);
	one(law, &out[3], "lightest_pair", mmin, mmin, 0);
}

void pclass_of_state(const sb_law *law, const sb_scene *sc, const sb_state *st, sb_pclass out[SB_NPCLASS])
{
	double sum = 0, mint = 0, mwall = 0, mmin = INFINITY;
	long ng = 0;
	for (int i = 0; i < st->n; i++) {
		if (st->kind[i] == KIND_GRAIN) {
			sum += st->m[i];
			ng++;
		} else if (st->kind[i] == KIND_INTRUDER && !(mint > 0)) {
			mint = st->m[i];
		} else if (st->kind[i] == KIND_WALL && !(mwall > 0)) {
			mwall = st->m[i];
		}
		if (i < st->nm)
			mmin = fmin(mmin, st->m[i]);
	}
	if (sc->wall_mass == WALLMASS_INFINITE && mwall > 0)
		mwall = INFINITY;
	classes(law, ng ? sum / (double)ng : 0, mint, mwall, isinf(mmin) ? 0 : mmin, out);
}

void pclass_of_scene(const sb_law *law, const sb_scene *sc, sb_pclass out[SB_NPCLASS])
{
	const double rg = 0.5 * (sc->r_min + sc->r_max);
	const double mint = sc->radius_ratio > 0 ? place_mass(sc, sc->radius_ratio * rg, KIND_INTRUDER) : 0;
	const double mlo = place_mass(sc, sc->r_min, KIND_GRAIN);
	classes(law, place_mass(sc, rg, KIND_GRAIN), mint,
		sc->wall_mass == WALLMASS_INFINITE ? INFINITY : place_mass(sc, sc->wall_radius, KIND_WALL),
		mint > 0 && mint < mlo ? mint : mlo, out);
}
