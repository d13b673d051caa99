/* validate.c - the checks of a scene that involve more than one key (r_min <= r_max,
 * an intruder that fits the box, ramps, rings, the time step against its stability
 * limit, ...): each error names where the key at fault was set. */
#include "validate.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dtguard.h"
#include "paircoef.h"

int params_validate(const sb_scene *s, sb_err *e)
{
#define W(key) params_where(s, key)
	/* step counts are integers: a dt that makes one overflow is refused here, not
	 * cast (1e15 steps are thousands of years of CPU at the engine's speed) */
	static const char *const lens[] = {"duration", "settle_max", "settle_min"};
	const double len[] = {s->duration, s->settle_max, s->settle_min};
	for (int k = 0; k < 3; k++)
		if (len[k] / s->dt > 1e15)
			return sb_errf(e, SB_EUSAGE, "%s: %s / dt = %g steps (dt %g, %s): at most 1e15", W(lens[k]), lens[k],
				       len[k] / s->dt, s->dt, W("dt"));
	if (s->stop == STOP_FLUX && !s->flux)
		return sb_errf(e, SB_EUSAGE, "%s: stop = flux needs flux = yes (%s)", W("stop"), W("flux"));
	if (s->stop == STOP_FLUX && !(s->stop_flux_lo < s->stop_flux_hi))
		return sb_errf(e, SB_EUSAGE, "%s: stop_flux_lo (%g) must be below stop_flux_hi (%g, %s)", W("stop_flux_lo"),
			       s->stop_flux_lo, s->stop_flux_hi, W("stop_flux_hi"));
	/* with particles, radius_ratio is the file's (bin/shake sets it before these checks:
	 * core/io/pfile.h, pfile_scene_intruders), 0 for a file without intruder */
	if (s->stop == STOP_RISEN && s->radius_ratio == 0)
		return sb_errf(e, SB_EUSAGE, "%s: stop = risen needs an intruder (radius_ratio is 0, %s)", W("stop"),
			       W("radius_ratio"));
	/* restitution sets every pair's normal damping: a gamma_n beside it would be ignored */
	if (s->restitution > 0 && strcmp(W("gamma_n"), "default"))
		return sb_errf(e, SB_EUSAGE, "%s: restitution = %g sets the normal damping of every pair; gamma_n (%s) "
			       "cannot be set beside it: leave one out", W("restitution"), s->restitution, W("gamma_n"));
	/* nor would a pair class's (paircoef.h): restitution gives every class e */
	for (int c = 0; c < SB_NPAIRC; c++) {
		char key[48];
		snprintf(key, sizeof key, "gamma_n_%s", paircoef_name(c));
		if (s->restitution > 0 && paircoef_given(s, c, PCK_GAMMA_N) != -1)
			return sb_errf(e, SB_EUSAGE, "%s: restitution = %g sets the normal damping of every pair; %s (%s) "
				       "cannot be set beside it: leave one out", W("restitution"), s->restitution, key, W(key));
	}
	/* with hertz the damping's restitution depends on the impact speed: no e per pair */
	if (s->restitution > 0 && s->normal == NORMAL_HERTZ)
		return sb_errf(e, SB_EUSAGE, "%s: restitution is for normal = hooke (%s): with hertz the restitution of "
			       "its damping depends on the impact speed; set gamma_n (shake --contacts shows the e it gives)",
			       W("restitution"), W("normal"));
	/* a shear stiffness beside the viscous law would be ignored */
	if (s->shear_stiffness > 0 && s->tangential != TANGENTIAL_SPRING)
		return sb_errf(e, SB_EUSAGE, "%s: shear_stiffness = %g is for tangential = spring (%s: viscous has no shear "
			       "spring): leave it out or set tangential = spring", W("shear_stiffness"), s->shear_stiffness,
			       W("tangential"));
	if (s->r_min > s->r_max)
		return sb_errf(e, SB_EUSAGE, "%s: r_min (%g) must not exceed r_max (%g, %s)", W("r_min"), s->r_min,
			       s->r_max, W("r_max"));
	/* size_dist picks one set of radius keys; the other set, given a value of its own,
	 * would be ignored (at its default it may be given: the study driver passes every key) */
	static const char *const uni[] = {"r_min", "r_max"}, *const bin[] = {"r_small", "r_large", "large_fraction"};
	const int binary = s->size_dist == SIZE_BINARY;
	for (int k = 0; k < (binary ? 2 : 3); k++) {
		const char *key = binary ? uni[k] : bin[k];
		const sb_param *p = params_find(key);
		if (*(const double *)((const char *)s + p->offset) != strtod(p->def, NULL))
			return sb_errf(e, SB_EUSAGE, "%s: %s is for size_dist = %s, and size_dist is %s (%s): leave it out",
				       W(key), key, binary ? "uniform" : "binary", binary ? "binary" : "uniform",
				       W("size_dist"));
	}
	if (binary && !(s->r_small < s->r_large))
		return sb_errf(e, SB_EUSAGE, "%s: size_dist = binary: r_small (%g) must be below r_large (%g, %s)",
			       W("r_small"), s->r_small, s->r_large, W("r_large"));
	double rlo, rhi, rmean;
	params_grain_radii(s, &rlo, &rhi, &rmean);
	const char *hikey = binary ? "r_large" : "r_max";
	if (s->wall_spacing > 2 * s->wall_radius)
		return sb_errf(e, SB_EUSAGE, "%s: wall_spacing (%g) must be at most 2 wall_radius (%g, %s): grains would fall through",
			       W("wall_spacing"), s->wall_spacing, 2 * s->wall_radius, W("wall_radius"));
	/* Periodic sides: the period must hold more than a grain's reach, so that no disk
	 * touches its own image and the images of a pair never meet both ways round
	 * (docs/model.md, "Periodic side boundaries"). */
	if (s->sides == SIDES_PERIODIC && s->width < 4 * rhi)
		return sb_errf(e, SB_EUSAGE,
			       "%s: sides = periodic (%s) needs a period of at least two grains: width %g < 4 %s = %g (%s %s)",
			       W("width"), W("sides"), s->width, hikey, 4 * rhi, hikey, W(hikey));
	const double r1 = s->radius_ratio * rmean;
	if (s->sides == SIDES_PERIODIC && !s->particles[0] && 2 * r1 > s->width - 2 * rhi)
		return sb_errf(e, SB_EUSAGE,
			       "%s: sides = periodic (%s): radius_ratio %g gives an intruder of diameter %g cm, wider than the "
			       "period width %g (%s) less a grain diameter: it would meet its own image",
			       W("radius_ratio"), W("sides"), s->radius_ratio, 2 * r1, s->width, W("width"));
	if (!s->particles[0] && s->width < 4 * rhi)
		return sb_errf(e, SB_EUSAGE, "%s: width (%g) must hold at least two grains (4 %s = %g, %s %s)",
			       W("width"), s->width, hikey, 4 * rhi, hikey, W(hikey));
	if (!s->particles[0] && 2 * r1 > s->width - 2 * rhi)
		return sb_errf(e, SB_EUSAGE, "%s: radius_ratio %g gives an intruder of diameter %g cm that does not fit width %g (%s)",
			       W("radius_ratio"), s->radius_ratio, 2 * r1, s->width, W("width"));
	/* several intruders side by side: each its own slot of the width, with a grain's
	 * room beside it (docs/model.md, "Several intruders") */
	if (!s->particles[0] && r1 > 0 && s->n_intruders > 1 && s->intruder_place == IPLACE_ROW &&
	    s->width / (double)(s->n_intruders + 1) < 2 * r1 + 2 * rhi)
		return sb_errf(e, SB_EUSAGE,
			       "%s: n_intruders %ld side by side (intruder_place = row, %s) stand width / (n + 1) = %g cm "
			       "apart, less than an intruder's diameter %g cm and a grain's %g: fewer intruders, a "
			       "wider box (width, %s) or intruder_place = column",
			       W("n_intruders"), s->n_intruders, W("intruder_place"), s->width / (double)(s->n_intruders + 1),
			       2 * r1, 2 * rhi, W("width"));
	if (!s->output[0])
		return sb_errf(e, SB_EUSAGE, "%s: output: must not be empty", W("output"));
	if (s->ramp != 0 && !(s->duration > s->ramp_hold)) {
		char ramp[32];
		params_format(s, params_find("ramp"), ramp, sizeof ramp);
		return sb_errf(e, SB_EUSAGE, "%s: ramp = %s needs duration (%g s, %s) > ramp_hold (%g s, %s): the ramp spans the rest of the run",
			       W("ramp"), ramp, s->duration, W("duration"), s->ramp_hold, W("ramp_hold"));
	}
	if (s->ring && s->ring_inner >= s->ring_outer)
		return sb_errf(e, SB_EUSAGE, "%s: ring_inner (%g) must be smaller than ring_outer (%g, %s)",
			       W("ring_inner"), s->ring_inner, s->ring_outer, W("ring_outer"));
	/* a particle file without intruder meets these in obs_init (core/model/observe.c),
	 * once the file is known to hold mobile disks at all */
	if (s->ring && s->radius_ratio == 0 && !s->particles[0] && s->ring_centre == RING_INTRUDER)
		return sb_errf(e, SB_EUSAGE, "%s: ring_centre = intruder, but there is no intruder (radius_ratio = 0)",
			       W("ring_centre"));
	if (s->ring && s->radius_ratio == 0 && !s->particles[0] && s->ring_y < 0)
		return sb_errf(e, SB_EUSAGE, "%s: ring: without an intruder (radius_ratio = 0) set the ring centre height ring_y",
			       W("ring"));
	if (s->ring && s->ring_centre == RING_FIXED && s->ring_y < 0)
		return sb_errf(e, SB_EUSAGE, "%s: ring_centre = fixed needs the centre's height ring_y", W("ring_centre"));
	if (s->ring && s->ring_until > 0 && s->ring_until <= s->ring_from)
		return sb_errf(e, SB_EUSAGE, "%s: ring_until (%g s) must be after ring_from (%g s, %s), or 0",
			       W("ring_until"), s->ring_until, s->ring_from, W("ring_from"));
	if (!s->particles[0]) {
		/* the lightest disk of a generated scene is a grain of the smallest radius, or
		 * the intruder when it is of a light enough material (intruder_density) */
		char warn[8];
		double m_min = s->mass_factor * s->density * rlo * rlo;
		if (r1 > 0 && s->intruder_density > 0)
			m_min = fmin(m_min, s->mass_factor * s->intruder_density * r1 * r1);
		if (dtguard_check(s, m_min, warn, sizeof warn, e))
			return e->code;
	}
	if (s->particle_mass == PMASS_FILE && !s->particles[0])
		return sb_errf(e, SB_EUSAGE, "%s: particle_mass = file, but there is no particle file (particles) to take "
			       "masses from", W("particle_mass"));
	if (s->settle_min > s->settle_max)
		return sb_errf(e, SB_EUSAGE, "%s: settle_min (%g) must not exceed settle_max (%g, %s)", W("settle_min"),
			       s->settle_min, s->settle_max, W("settle_max"));
	/* a checkpoint holds the journal's length and resumes into the run file: a run
	 * without one (output = none) has neither */
	static const char *const ck[] = {"checkpoint_every", "checkpoint", "restart"};
	const int asks[] = {s->checkpoint_every > 0, s->checkpoint[0] != 0, s->restart == TRI_YES};
	for (int k = 0; k < 3 && params_no_output(s); k++)
		if (asks[k])
			return sb_errf(e, SB_EUSAGE, "%s: %s: a checkpoint resumes a run into its run file, and output = none "
				       "(%s) has none", W(ck[k]), ck[k], W("output"));
	if (s->restart == TRI_YES && s->checkpoint_every <= 0 && !s->checkpoint[0])
		return sb_errf(e, SB_EUSAGE, "%s: restart = yes needs a checkpoint file (checkpoint or checkpoint_every)",
			       W("restart"));
	return 0;
#undef W
}

