/* params.c - the parameter table and everything it drives (parse, check, help, echo). */
#include "params.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "fnv.h"
#include "num.h"
#include "inifile.h"
#include "words.h"

/* A row's type and field in one macro: the offset, and a compile-time check that the
 * field has the C type the parser will write through it (a row whose type does not
 * match its field does not compile). */
#define TYPED(f, T)                                                                      \
	(offsetof(sb_scene, f) +                                                         \
	 0 * sizeof(struct {                                                             \
		 _Static_assert(_Generic(((sb_scene *)0)->f, T: 1, default: 0),          \
				"sb_scene." #f " does not have the row's type " #T);     \
		 int unused_;                                                            \
	 }))
#define INT(f) PT_INT, TYPED(f, long)
#define REAL(f) PT_REAL, TYPED(f, double)
#define BOOL(f) PT_BOOL, TYPED(f, int)
#define ENUM(f) PT_ENUM, TYPED(f, int)
#define STR(f) PT_STR, TYPED(f, char *)
#define BIG 1e300


/* The presets, in the order of the preset row's choices: each a list of key, value
 * pairs (the paper preset's values are also the table's defaults; tests/unit/params.c
 * holds the two to each other and the names to the row's choices). */
const sb_preset PRESETS[] = {
	{"paper", {"integrator", "gear5", "dt", "5e-05", NULL}},
	{"fast", {"integrator", "verlet", "dt", "0.0002", NULL}},
	{NULL, {NULL}},
};

/* Defaults are the `paper` preset (docs/model.md); every row names its unit. */
static const sb_param TABLE[] = {
	/* --- preparation --- */
	{"n_grains", INT(n_grains), "", "950", 0, 10000000, NULL, PF_PREP,
	 "number of small grains"},
	{"size_dist", ENUM(size_dist), "", "uniform", 0, 0, "uniform|binary", PF_PREP,
	 "grain radii of a generated bed: uniform = uniform in [r_min, r_max] (the paper's); binary = two "
	 "sizes, r_large with probability large_fraction, else r_small (docs/model.md, \"Binary beds\")"},
	{"r_min", REAL(r_min), "cm", "0.85", 0, 1000, NULL, PF_PREP | PF_MINX,
	 "smallest grain radius (size_dist = uniform: radii uniform in [r_min, r_max])"},
	{"r_max", REAL(r_max), "cm", "1.15", 0, 1000, NULL, PF_PREP | PF_MINX,
	 "largest grain radius (size_dist = uniform)"},
	{"r_small", REAL(r_small), "cm", "1", 0, 1000, NULL, PF_PREP | PF_MINX,
	 "size_dist = binary: radius of the small grains"},
	{"r_large", REAL(r_large), "cm", "2", 0, 1000, NULL, PF_PREP | PF_MINX,
	 "size_dist = binary: radius of the large grains (above r_small)"},
	{"large_fraction", REAL(large_fraction), "", "0.2", 0, 1, NULL, PF_PREP,
	 "size_dist = binary: the number fraction of large grains, each grain large with this probability "
	 "(0.2 at the default radii: the two sizes fill equal areas)"},
	{"radius_ratio", REAL(radius_ratio), "", "4", 0, 100, NULL, PF_PREP,
	 "intruder radius / mean grain radius (0 = no intruder); with particles the file's: its first intruder's "
	 "radius over the scene's mean grain radius, 0 without one, and a value given beside it that disagrees is "
	 "refused (docs/model.md, \"Units and the paper's values\")"},
	{"n_intruders", INT(n_intruders), "", "1", 1, 1000, NULL, PF_PREP,
	 "number of intruders of a generated bed (radius_ratio > 0), each tracked: its rise and waiting time "
	 "(docs/model.md, \"Several intruders\")"},
	{"intruder_place", ENUM(intruder_place), "", "row", 0, 0, "row|column", PF_PREP,
	 "n_intruders > 1: row = side by side at one depth, evenly across the width (x = width k / (n + 1)); "
	 "column = one above the other at the box's centre, the lowest at depth"},
	{"depth", INT(depth), "", "1", 0, 100000, NULL, PF_PREP,
	 "rows of small grains placed beneath the intruder (0 = on the bottom wall)"},
	{"width", REAL(width), "cm", "60", 0, 1e7, NULL, PF_PREP | PF_MINX,
	 "inner width of the box"},
	{"wall_radius", REAL(wall_radius), "cm", "1", 0, 1000, NULL, PF_PREP | PF_MINX,
	 "radius of the disks the walls are made of"},
	{"wall_spacing", REAL(wall_spacing), "cm", "2", 0, 2000, NULL, PF_PREP | PF_MINX,
	 "centre distance of neighbouring wall disks (at most 2 wall_radius)"},
	{"wall_height", REAL(wall_height), "cm", "0", 0, 1e7, NULL, PF_PREP,
	 "height of the side walls above the bottom (0 = twice the loose bed height)"},
	{"sides", ENUM(sides), "", "walls", 0, 0, "walls|periodic", PF_PREP | PF_DYN,
	 "side boundaries: walls = columns of wall disks at x = 0 and width; periodic = no side walls, "
	 "x wraps with period width (disks interact across x = 0 / width by the minimum image; the bottom "
	 "row tiles [0, width))"},
	{"density", REAL(density), "g/cm^3", "1", 0, 1e6, NULL, PF_PREP | PF_MINX,
	 "material density rho of the grains and the walls"},
	{"intruder_density", REAL(intruder_density), "g/cm^3", "0", 0, 1e6, NULL, PF_PREP,
	 "material density of the intruder (0 = density: the grains' material); its mass and moment of "
	 "inertia follow the mass model with it (docs/model.md, \"Units and the paper's values\")"},
	{"mass_factor", REAL(mass_factor), "cm", "6.283185307179586", 0, 1e6, NULL, PF_PREP | PF_MINX,
	  "m = mass_factor * rho * R^2 (the paper prints 2 pi)"},
	{"seed", INT(seed), "", "1", 0, 9007199254740992.0, NULL, PF_PREP,
	 "random seed of the preparation (radii, placement)"},
	{"particles", STR(particles), "", "", 0, 0, NULL, PF_PREP,
	 "start from this particle file (text 'x y r kind [vx vy omega [m]]' or LAMMPS data) instead of placing"},
	{"particle_mass", ENUM(particle_mass), "", "scene", 0, 0, "scene|file", PF_PREP,
	 "masses of a particle file's disks: scene = the mass model (density, intruder_density), and a file's "
	 "mass or density column that disagrees with it is refused with its line; file = the file's column "
	 "(text: the eighth, m in g; LAMMPS: density, m = 4/3 pi R^3 density), required on every line"},
	{"settle", ENUM(settle), "", "auto", 0, 0, "auto|yes|no", PF_PREP,
	 "settle without vibration before shaking (auto: yes unless particles is set)"},
	{"settle_ke", REAL(settle_ke), "erg", "0.01", 0, BIG, NULL, PF_PREP | PF_MINX,
	 "settled when the mean kinetic energy per mobile disk falls below this"},
	{"settle_min", REAL(settle_min), "s", "1", 0, 1e6, NULL, PF_PREP,
	 "settle at least this long"},
	{"settle_drag", REAL(settle_drag), "1/s", "20", 0, 1e6, NULL, PF_PREP,
	 "viscous drag -settle_drag m v while settling: the loose packing collapses gently and rattlers come to rest (0 = none)"},
	{"settle_max", REAL(settle_max), "s", "30", 0, 1e6, NULL, PF_PREP | PF_MINX,
	 "give up (exit code 6) if not settled after this long"},
	/* --- dynamics --- */
	{"wall_mass", ENUM(wall_mass), "", "disk", 0, 0, "disk|infinite", PF_PREP | PF_DYN,
	 "mass of a wall disk in m_eff: its own (disk) or infinite (m_eff = m_grain)"},
	{"amplitude", REAL(amplitude), "cm", "2", 0, 1e4, NULL, PF_DYN,
	 "A in y_box = A sin(2 pi f t)"},
	{"frequency", REAL(frequency), "Hz", "3.2", 0, 1000, NULL, PF_DYN,
	 "f in y_box = A sin(2 pi f t)"},
	{"ramp", ENUM(ramp), "", "none", 0, 0, "none|linear|updown", PF_DYN,
	 "frequency ramp over the run (continuous phase): linear ramp_from -> ramp_to, updown ramp_from -> ramp_to -> ramp_from; none uses frequency"},
	{"ramp_from", REAL(ramp_from), "Hz", "2.5", 0, 1000, NULL, PF_DYN | PF_MINX,
	 "frequency at the start of a ramp"},
	{"ramp_to", REAL(ramp_to), "Hz", "3.2", 0, 1000, NULL, PF_DYN | PF_MINX,
	 "frequency at the end (linear) or the turning point (updown) of a ramp"},
	{"ramp_hold", REAL(ramp_hold), "s", "0", 0, 1e8, NULL, PF_DYN,
	 "hold ramp_from this long before the ramp starts (the ramp spans the rest of the run)"},
	{"gravity", REAL(gravity), "cm/s^2", "981", 0, 1e7, NULL, PF_PREP | PF_DYN,
	 "g, acting in -y"},
	{"stiffness", REAL(stiffness), "g/s^2", "3e6", 0, 1e13, NULL, PF_PREP | PF_DYN | PF_MINX,
	  "normal spring constant Y"},
	{"gamma_n", REAL(gamma_n), "1/s", "100", 0, 1e8, NULL, PF_PREP | PF_DYN,
	 "normal damping gamma_N"},
	{"normal", ENUM(normal), "", "hooke", 0, 0, "hooke|hertz", PF_PREP | PF_DYN,
	 "normal contact law: hooke = the paper's linear spring, F_N = Y xi + gamma_N m_eff xidot; hertz = "
	 "sqrt(xi R_eff) (hertz_stiffness xi + gamma_N m_eff xidot), R_eff = R_i R_j / (R_i + R_j), the shear "
	 "damping scaled by sqrt(xi R_eff) too, as LAMMPS gran/hertz/history (docs/model.md, \"Normal law\")"},
	{"hertz_stiffness", REAL(hertz_stiffness), "g/(cm^0.5 s^2)", "3.15e7", 0, 1e15, NULL, PF_PREP | PF_DYN | PF_MINX,
	 "normal = hertz: the stiffness K of F_N = K sqrt(R_eff) xi^1.5; the default gives a mean grain pair "
	 "(m_eff = pi g, R_eff = 0.5 cm) the hooke law's contact time 3.21 ms at an impact speed of 20 cm/s"},
	{"restitution", REAL(restitution), "", "0", 0, 1, NULL, PF_PREP | PF_DYN,
	 "normal coefficient of restitution e of every pair (grain, intruder, wall): the normal damping set per pair, "
	 "gamma_N = 2 zeta sqrt(Y / m_eff), zeta = -ln e / sqrt(pi^2 + ln^2 e), as LAMMPS's damping "
	 "coeff_restitution; 0 = off: gamma_n for every pair (docs/model.md, \"Restitution\")"},
	{"tangential", ENUM(tangential), "", "viscous", 0, 0, "viscous|spring", PF_PREP | PF_DYN,
	 "tangential contact law: viscous = the paper's, F_S = -sign(v_t) min(gamma_S m_eff |v_t|, mu |F_N|), no "
	 "memory; spring = Cundall-Strack as LAMMPS gran/hooke/history: a shear displacement xi_t per contact, "
	 "accumulated while it lasts, F_S = -(k_t xi_t + gamma_S m_eff v_t) capped at mu |F_N| with the spring "
	 "rescaled on sliding, reset when the contact ends (docs/model.md, \"Tangential law\")"},
	{"shear_stiffness", REAL(shear_stiffness), "g/s^2", "0", 0, 1e15, NULL, PF_PREP | PF_DYN,
	 "tangential = spring: k_t, in the normal stiffness's unit (hertz: times sqrt(xi R_eff), as "
	 "hertz_stiffness); 0 = 2/7 of the normal stiffness (stiffness or hertz_stiffness), LAMMPS's default"},
	{"gamma_s", REAL(gamma_s), "1/s", "1", 0, 1e8, NULL, PF_PREP | PF_DYN,
	 "shear damping gamma_S"},
	{"mu", REAL(mu), "", "0.5", 0, 100, NULL, PF_PREP | PF_DYN,
	 "Coulomb friction coefficient"},
	/* the pair classes' own coefficients (docs/model.md, "Materials per pair of kinds"),
	 * like LAMMPS's pair_coeff I J: four rows per class, in paircoef.h's order; their
	 * default -1 (`same`) is the grain-grain key's value, so that a scene without them
	 * is the paper's single material to the bit */
	{"mu_grain_intruder", REAL(mu_grain_intruder), "", "same", 0, 100, NULL, PF_PREP | PF_DYN | PF_SAME,
	 "Coulomb friction coefficient of a grain and an intruder (same = mu)"},
	{"gamma_n_grain_intruder", REAL(gamma_n_grain_intruder), "1/s", "same", 0, 1e8, NULL, PF_PREP | PF_DYN | PF_SAME,
	 "normal damping gamma_N of a grain and an intruder (same = gamma_n; not beside restitution)"},
	{"gamma_s_grain_intruder", REAL(gamma_s_grain_intruder), "1/s", "same", 0, 1e8, NULL, PF_PREP | PF_DYN | PF_SAME,
	 "shear damping gamma_S of a grain and an intruder (same = gamma_s)"},
	{"stiffness_grain_intruder", REAL(stiffness_grain_intruder), "g/s^2", "same", 0, 1e15, NULL, PF_PREP | PF_DYN | PF_MINX | PF_SAME,
	 "normal stiffness of a grain and an intruder (same = stiffness; normal = hertz: hertz_stiffness's unit and value; "
	 "tangential = spring with shear_stiffness 0: k_t is 2/7 of it)"},
	{"mu_intruder_intruder", REAL(mu_intruder_intruder), "", "same", 0, 100, NULL, PF_PREP | PF_DYN | PF_SAME,
	 "Coulomb friction coefficient of two intruders (same = mu)"},
	{"gamma_n_intruder_intruder", REAL(gamma_n_intruder_intruder), "1/s", "same", 0, 1e8, NULL, PF_PREP | PF_DYN | PF_SAME,
	 "normal damping gamma_N of two intruders (same = gamma_n; not beside restitution)"},
	{"gamma_s_intruder_intruder", REAL(gamma_s_intruder_intruder), "1/s", "same", 0, 1e8, NULL, PF_PREP | PF_DYN | PF_SAME,
	 "shear damping gamma_S of two intruders (same = gamma_s)"},
	{"stiffness_intruder_intruder", REAL(stiffness_intruder_intruder), "g/s^2", "same", 0, 1e15, NULL, PF_PREP | PF_DYN | PF_MINX | PF_SAME,
	 "normal stiffness of two intruders (same = stiffness; normal = hertz: hertz_stiffness's unit and value; "
	 "tangential = spring with shear_stiffness 0: k_t is 2/7 of it)"},
	{"mu_grain_wall", REAL(mu_grain_wall), "", "same", 0, 100, NULL, PF_PREP | PF_DYN | PF_SAME,
	 "Coulomb friction coefficient of a grain and a wall disk (same = mu)"},
	{"gamma_n_grain_wall", REAL(gamma_n_grain_wall), "1/s", "same", 0, 1e8, NULL, PF_PREP | PF_DYN | PF_SAME,
	 "normal damping gamma_N of a grain and a wall disk (same = gamma_n; not beside restitution)"},
	{"gamma_s_grain_wall", REAL(gamma_s_grain_wall), "1/s", "same", 0, 1e8, NULL, PF_PREP | PF_DYN | PF_SAME,
	 "shear damping gamma_S of a grain and a wall disk (same = gamma_s)"},
	{"stiffness_grain_wall", REAL(stiffness_grain_wall), "g/s^2", "same", 0, 1e15, NULL, PF_PREP | PF_DYN | PF_MINX | PF_SAME,
	 "normal stiffness of a grain and a wall disk (same = stiffness; normal = hertz: hertz_stiffness's unit and value; "
	 "tangential = spring with shear_stiffness 0: k_t is 2/7 of it)"},
	{"mu_intruder_wall", REAL(mu_intruder_wall), "", "same", 0, 100, NULL, PF_PREP | PF_DYN | PF_SAME,
	 "Coulomb friction coefficient of an intruder and a wall disk (same = mu)"},
	{"gamma_n_intruder_wall", REAL(gamma_n_intruder_wall), "1/s", "same", 0, 1e8, NULL, PF_PREP | PF_DYN | PF_SAME,
	 "normal damping gamma_N of an intruder and a wall disk (same = gamma_n; not beside restitution)"},
	{"gamma_s_intruder_wall", REAL(gamma_s_intruder_wall), "1/s", "same", 0, 1e8, NULL, PF_PREP | PF_DYN | PF_SAME,
	 "shear damping gamma_S of an intruder and a wall disk (same = gamma_s)"},
	{"stiffness_intruder_wall", REAL(stiffness_intruder_wall), "g/s^2", "same", 0, 1e15, NULL, PF_PREP | PF_DYN | PF_MINX | PF_SAME,
	 "normal stiffness of an intruder and a wall disk (same = stiffness; normal = hertz: hertz_stiffness's unit and value; "
	 "tangential = spring with shear_stiffness 0: k_t is 2/7 of it)"},
	{"clip_attractive", BOOL(clip_attractive), "", "no", 0, 0, NULL, PF_PREP | PF_DYN,
	 "clip the normal force at zero (no attraction at the end of a contact)"},
	{"preset", ENUM(preset), "", "paper", 0, 0, "paper|fast", PF_PREP | PF_DYN,
	 "sets integrator and dt: paper = gear5, 5e-5 s; fast = verlet, 2e-4 s (make bench-accuracy: "
	 "statistically indistinguishable observables at 1/3 of the cost); applied first: integrator and dt given "
	 "explicitly win wherever they appear"},
	{"integrator", ENUM(integrator), "", "gear5", 0, 0, "gear5|gear4|verlet", PF_PREP | PF_DYN,
	  "gear5 (6-value, paper), gear4 (5-value) or velocity verlet"},
	{"dt", REAL(dt), "s", "5e-05", 0, 0.01, NULL, PF_PREP | PF_DYN | PF_MINX,
	 "time step"},
	{"dt_guard", ENUM(dt_guard), "", "refuse", 0, 0, "refuse|warn|off", PF_OUT,
	 "a dt beyond the integrator's measured stability limit for this stiffness: refuse, warn or allow"},
	{"skin", REAL(skin), "cm", "0.5", 0, 100, NULL, PF_PREP | PF_DYN | PF_MINX,
	 "Verlet-list skin (results do not depend on it, only speed)"},
	{"max_overlap", REAL(max_overlap), "", "1", 0, 2, NULL, PF_PREP | PF_DYN | PF_MINX,
	 "safety net against a blow-up, not a physics criterion: stop (exit code 4) when an overlap "
	 "exceeds this fraction of the smaller radius (at 1 a disk's centre reaches the other's surface, "
	 "where the contact law stops making sense; the largest overlap of every run is recorded)"},
	/* --- run length --- */
	{"duration", REAL(duration), "s", "10", 0, 1e8, NULL, PF_LEN,
	 "seconds of shaking after preparation (the longest a run lasts with a stop rule)"},
	{"stop", ENUM(stop), "", "none", 0, 0, "none|risen|flux", PF_LEN,
	 "end the run when its question is answered: risen = stop_after seconds after the intruder rose "
	 "(waiting time); flux = once the running mean of the per-period flux in the band stop_flux_lo..hi "
	 "is known (after stop_skip seconds and at least 20 periods): on which side of stop_flux_threshold "
	 "it lies, by stop_flux_k standard errors, or, without a threshold, to a standard error below "
	 "stop_flux_se"},
	{"stop_after", REAL(stop_after), "s", "0", 0, 1e8, NULL, PF_LEN,
	 "stop = risen: shaking kept after the rise (for the intruder's motion at the top)"},
	{"stop_skip", REAL(stop_skip), "s", "0", 0, 1e8, NULL, PF_LEN,
	 "stop = flux: the transient whose periods the rule ignores"},
	{"stop_flux_se", REAL(stop_flux_se), "1/period", "0.05", 0, 1e6, NULL, PF_LEN | PF_MINX,
	 "stop = flux without stop_flux_threshold: the standard error of the band's mean flux at which the "
	 "run ends"},
	{"stop_flux_threshold", REAL(stop_flux_threshold), "1/period", "0", 0, 1e6, NULL, PF_LEN,
	 "stop = flux: the flux |Phi| that divides convecting runs from still ones (the onset search's "
	 "threshold); the run ends once its mean is stop_flux_k standard errors clear of it, on either side, "
	 "and a run near it runs on; 0 = none (the stop_flux_se rule)"},
	{"stop_flux_k", REAL(stop_flux_k), "", "3", 1, 100, NULL, PF_LEN,
	 "stop = flux with stop_flux_threshold: the margin, in standard errors of the mean, by which the "
	 "mean must clear the threshold (checked once a period, so a larger k guards a run near the "
	 "threshold against a chance early verdict)"},
	{"stop_flux_lo", REAL(stop_flux_lo), "", "0.4", 0, 1, NULL, PF_LEN,
	 "stop = flux: lower edge of the band of flux lines, fraction of the settled surface height"},
	{"stop_flux_hi", REAL(stop_flux_hi), "", "0.6", 0, 1, NULL, PF_LEN,
	 "stop = flux: upper edge of the band"},
	/* --- recording --- */
	{"output", STR(output), "", "run.h5", 0, 0, NULL, PF_OUT | PF_DRIVER,
	 "HDF5 output file (an XDMF sidecar .xmf is written beside it; a path where something other than a "
	 "regular file stands is refused); none = no run file, no journal, no checkpoint (a file named none: ./none)"},
	/* the keys of one recorded quantity each (its row of core/scene/record.c names it) */
	{"traj_rate", REAL(traj_rate), "Hz", "100", 0, 1e6, NULL, PF_OUT,
	 "samples per second of the intruder trajectory (0 = none)"},
	{"energy_rate", REAL(energy_rate), "Hz", "0", 0, 1e6, NULL, PF_OUT,
	 "samples per second of the energy series (kinetic: translational and rotational, elastic, "
	 "centre-of-mass height, largest overlap; /observables/energy; 0 = none)"},
	{"contact_rate", REAL(contact_rate), "Hz", "0", 0, 1e6, NULL, PF_OUT,
	 "samples per second of the contact dump (every contact: the two disks, normal and tangential "
	 "force, normal, place; /observables/contacts, for force chains; 0 = none)"},
	{"bed_kinetic_samples", INT(bed_kinetic_samples), "", "0", 0, 100000, NULL, PF_OUT,
	 "samples per drive period of the bed's kinetic energy (box frame), averaged per period "
	 "(/observables/bed_kinetic) and over the run (bed_kinetic_mean); 0 = none"},
	{"bed_height_samples", INT(bed_height_samples), "", "0", 0, 100000, NULL, PF_OUT,
	 "samples per drive period of the bed's centre-of-mass height (box frame), averaged per period "
	 "(/observables/bed_height) and over the run (bed_height_mean); 0 = none"},
	{"segregation_samples", INT(segregation_samples), "", "0", 0, 100000, NULL, PF_OUT,
	 "samples per drive period of the grains' segregation index (docs/model.md, \"Segregation index\": +1 "
	 "large grains all above the small, -1 all below), averaged per period (/observables/segregation) and "
	 "summarised over the run (segregation_index_mean, segregation_index_final); 0 = none"},
	{"sliding_samples", INT(sliding_samples), "", "0", 0, 100000, NULL, PF_OUT,
	 "samples per drive period of the fraction of contacts at the Coulomb limit (sliding), averaged per "
	 "period (/observables/sliding) and over the run (sliding_mean); 0 = none"},
	{"snapshots", BOOL(snapshots), "", "yes", 0, 0, NULL, PF_OUT,
	 "record all disks once per period at phase 0 (snapshots_per_period: more often)"},
	{"snapshots_per_period", INT(snapshots_per_period), "", "1", 1, 1000, NULL, PF_OUT,
	 "snapshots per drive period, at phases k/N (1: at phase 0 only, the stroboscopic view; more "
	 "to see the motion within a period, e.g. for bin/movie)"},
	{"snapshot_precision", ENUM(snapshot_precision), "", "single", 0, 0, "double|single", PF_OUT,
	 "floating-point precision of the snapshots in the HDF5 file (single: half the size of double, 7 "
	 "digits, what ParaView, OVITO and MDAnalysis hold; the engine and every other record are double)"},
	{"compression", INT(compression), "", "4", 0, 9, NULL, PF_OUT | PF_NOID,
	 "deflate level of the HDF5 file's large datasets, shuffled first (0 = none, 9 = smallest)"},
	{"checkpoint_every", REAL(checkpoint_every), "s", "0", 0, 1e8, NULL, PF_OUT | PF_NOID,
	 "write a checkpoint every this many simulated seconds (0 = never)"},
	{"checkpoint", STR(checkpoint), "", "", 0, 0, NULL, PF_OUT | PF_DRIVER,
	 "checkpoint file (default: OUTPUT.ckpt)"},
	{"restart", ENUM(restart), "", "auto", 0, 0, "auto|yes|no", PF_OUT | PF_DRIVER,
	 "continue from the checkpoint: auto = if it exists, yes = it must exist, no = never"},
	{"write_particles", STR(write_particles), "", "", 0, 0, NULL, PF_OUT | PF_DRIVER,
	 "after preparation, write the state as a text particle file"},
	{"write_lammps", STR(write_lammps), "", "", 0, 0, NULL, PF_OUT | PF_DRIVER,
	 "after preparation, write the state as a LAMMPS data file (atom_style sphere)"},
	/* --- observables: off unless asked for; they never change the dynamics --- */
	{"flux", BOOL(flux), "", "no", 0, 0, NULL, PF_OUT,
	 "record the convective flux per period through flux_lines height lines (Fig. 3)"},
	{"flux_lines", INT(flux_lines), "", "80", 1, 100000, NULL, PF_OUT,
	 "number of height lines between the bottom and the settled free surface"},
	{"field", BOOL(field), "", "no", 0, 0, NULL, PF_OUT,
	 "record the displacement field between stroboscopic samples on a grid (Fig. 1)"},
	{"field_periods", INT(field_periods), "", "50", 1, 10000000, NULL, PF_OUT,
	 "periods averaged into one displacement field"},
	{"ring", BOOL(ring), "", "no", 0, 0, NULL, PF_OUT,
	 "record the contact force, net force and granular temperature of the grains in a ring "
	 "(series and averages)"},
	{"ring_inner", REAL(ring_inner), "cm", "4.5", 0, 1e6, NULL, PF_OUT,
	 "inner radius of the ring around its centre (ring_centre)"},
	{"ring_outer", REAL(ring_outer), "cm", "8", 0, 1e6, NULL, PF_OUT | PF_MINX,
	 "outer radius of the ring"},
	{"ring_centre", ENUM(ring_centre), "", "auto", 0, 0, "auto|intruder|settled|fixed", PF_OUT,
	 "the ring's centre (box frame): intruder = follows it, settled = fixed where it settled "
	 "(without one: ring_x, ring_y), fixed = ring_x, ring_y; auto = fixed when ring_y is set, "
	 "else intruder"},
	{"ring_x", REAL(ring_x), "cm", "-1", -1, 1e7, NULL, PF_OUT,
	 "ring centre x for a fixed centre (-1 = box centre)"},
	{"ring_y", REAL(ring_y), "cm", "-1", -1, 1e7, NULL, PF_OUT,
	 "ring centre height above the box floor for a fixed centre (-1 = none; required without an "
	 "intruder)"},
	{"ring_rate", REAL(ring_rate), "Hz", "200", 0, 1e9, NULL, PF_OUT | PF_MINX,
	 "ring samples per second of shaking (one series row each)"},
	{"ring_every", INT(ring_every), "", "0", 0, 100000000, NULL, PF_OUT,
	 "sample the ring every this many steps instead of at ring_rate (0 = use ring_rate)"},
	{"ring_from", REAL(ring_from), "s", "0", 0, 1e9, NULL, PF_OUT,
	 "the ring's before-the-rise averages start at this time (skip the start of the shaking)"},
	{"ring_until", REAL(ring_until), "s", "0", 0, 1e9, NULL, PF_OUT,
	 "... and end at this time at the latest (0 = the rise or the end of the run)"},
	{"progress", ENUM(progress), "", "auto", 0, 0, "auto|yes|no", PF_OUT | PF_DRIVER,
	 "progress on stderr (auto: when stderr is a terminal)"},
	{"run_id", STR(run_id), "", "", 0, 0, NULL, PF_OUT | PF_DRIVER,
	 "the study driver's id of this run, recorded so that a file copied or linked in place of another "
	 "run's is known (docs/inputs.md, \"Run files\"); empty outside a campaign"},
};

#define NTABLE (sizeof TABLE / sizeof TABLE[0])
_Static_assert(NTABLE == SB_NKEYS, "SB_NKEYS (params.h) is the number of rows of the table");

int params_no_output(const sb_scene *s)
{
	return !strcmp(s->output, SB_OUTPUT_NONE);
}

const char *params_where(const sb_scene *s, const char *key)
{
	const sb_param *p = params_find(key);
	return p && s->src[p - TABLE][0] ? s->src[p - TABLE] : "default";
}

const sb_param *params_table(size_t *n)
{
	*n = NTABLE;
	return TABLE;
}

const char *params_nearest(const char *key)
{
	/* a typo, not another word: at most a third of the key's letters (and 3) apart */
	int best = 4, lim = (int)strlen(key) / 3;
	const char *name = NULL;
	for (size_t i = 0; i < NTABLE; i++) {
		int dist = words_distance(key, TABLE[i].name);
		if (dist < best && dist <= (lim > 1 ? lim : 1)) {
			best = dist;
			name = TABLE[i].name;
		}
	}
	return name;
}

const sb_param *params_find(const char *name)
{
	for (size_t i = 0; i < NTABLE; i++)
		if (strcmp(TABLE[i].name, name) == 0)
			return &TABLE[i];
	return NULL;
}

static int enum_index(const char *choices, const char *v)
{
	int idx = 0;
	size_t vl = strlen(v);
	for (const char *c = choices; *c; idx++) {
		const char *bar = strchr(c, '|');
		size_t l = bar ? (size_t)(bar - c) : strlen(c);
		if (l == vl && strncmp(c, v, l) == 0)
			return idx;
		if (!bar)
			break;
		c = bar + 1;
	}
	return -1;
}

static void range_text(const sb_param *p, char *buf, size_t len)
{
	const char *lo = (p->flags & PF_MINX) ? "(" : "[";
	if (p->type == PT_INT)
		snprintf(buf, len, "[%.0f, %.0f]", p->min, p->max);
	else if (p->max >= BIG)
		snprintf(buf, len, "%s%g, inf)", lo, p->min);
	else
		snprintf(buf, len, "%s%g, %g]", lo, p->min, p->max);
	if (p->flags & PF_SAME) {
		const size_t l = strlen(buf);
		snprintf(buf + l, len - l, " or same");
	}
}

/* Trim leading/trailing blanks into a local copy. */
static void trim(const char *in, char *out, size_t len)
{
	while (*in == ' ' || *in == '\t')
		in++;
	snprintf(out, len, "%s", in);
	size_t l = strlen(out);
	while (l && (out[l - 1] == ' ' || out[l - 1] == '\t' || out[l - 1] == '\r' || out[l - 1] == '\n'))
		out[--l] = 0;
}

/* An INT row's bound as an integer (the table's bounds are whole numbers within
 * 2^53, so the conversion is exact; tests/unit/params.c checks it). */
static long long int_bound(double b)
{
	return b >= 9.2e18 ? LLONG_MAX : b <= -9.2e18 ? LLONG_MIN : (long long)b;
}

static int set_value(sb_scene *s, const char *key, const char *value, const char *where, sb_err *e);

int params_set(sb_scene *s, const char *key, const char *value, const char *where, sb_err *e)
{
	const int rc = set_value(s, key, value, where, e);
	const sb_param *p = params_find(key);
	if (!rc && p) { /* defaults leave no trace: "default" is what an empty source says */
		snprintf(s->src[p - TABLE], sizeof s->src[0], "%s", strcmp(where, "default") ? where : "");
		s->by_preset[p - TABLE] = 0;
	}
	return rc;
}

/* docs/model.md, "Units and the paper's values": a preset is applied first and the keys
 * given explicitly win wherever they appear - before it or after it, in a scene file, on
 * the command line, in a campaign's [scene] or [grid]. So a preset sets only the keys
 * that hold their default or another preset's value; "dt = 1e-5" then "preset = fast"
 * runs verlet at 1e-5, as "preset = fast" then "dt = 1e-5" does. This is the one place
 * the rule lives: scene files, key=value and campaigns all set keys through params_set. */
static int apply_preset(sb_scene *s, int k, const char *where, sb_err *e)
{
	for (const char *const *kv = PRESETS[k].set; *kv; kv += 2) {
		const size_t i = (size_t)(params_find(kv[0]) - TABLE);
		if (s->src[i][0] && !s->by_preset[i])
			continue; /* explicit: it stays */
		if (params_set(s, kv[0], kv[1], where, e))
			return e->code;
		s->by_preset[i] = strcmp(where, "default") != 0;
	}
	return 0;
}

static int set_value(sb_scene *s, const char *key, const char *value, const char *where, sb_err *e)
{
	const sb_param *p = params_find(key);
	if (!p)
	{
		const char *near = params_nearest(key);
		if (near)
			return sb_errf(e, SB_EUSAGE, "%s: unknown key '%s'; did you mean %s? (shake --help lists the keys)",
				       where, key, near);
		return sb_errf(e, SB_EUSAGE, "%s: unknown key '%s' (shake --help lists the keys)", where, key);
	}
	if (strlen(value) >= SB_STR_MAX)
		return sb_errf(e, SB_EUSAGE, "%s: %s: value longer than %d characters", where, key, SB_STR_MAX - 1);
	char v[SB_STR_MAX];
	trim(value, v, sizeof v);
	char *base = (char *)s + p->offset;
	char rng[96];
	range_text(p, rng, sizeof rng);
	switch (p->type) {
	case PT_INT: {
		/* compared as integers: as doubles, 2^53 + 1 would equal a bound of 2^53 */
		long long x;
		if (num_int(v, &x) || x < int_bound(p->min) || x > int_bound(p->max))
			return sb_errf(e, SB_EUSAGE, "%s: %s: expected an integer in %s, got '%s'",
				       where, key, rng, v);
		*(long *)base = (long)x;
		return 0;
	}
	case PT_REAL: {
		double x;
		const int same = (p->flags & PF_SAME) && (!strcmp(v, "same") || (!num_real(v, &x) && x == -1));
		if (same) {
			*(double *)base = -1;
			return 0;
		}
		int bad = num_real(v, &x) || x > p->max || ((p->flags & PF_MINX) ? x <= p->min : x < p->min);
		if (bad)
			return sb_errf(e, SB_EUSAGE, "%s: %s: expected a number in %s, got '%s'",
				       where, key, rng, v);
		*(double *)base = x;
		return 0;
	}
	case PT_BOOL: {
		int b = -1;
		if (!strcasecmp(v, "yes") || !strcasecmp(v, "true") || !strcasecmp(v, "on") || !strcmp(v, "1"))
			b = 1;
		if (!strcasecmp(v, "no") || !strcasecmp(v, "false") || !strcasecmp(v, "off") || !strcmp(v, "0"))
			b = 0;
		if (b < 0)
			return sb_errf(e, SB_EUSAGE, "%s: %s: expected yes or no, got '%s'", where, key, v);
		*(int *)base = b;
		return 0;
	}
	case PT_ENUM: {
		int k = enum_index(p->choices, v);
		if (k < 0)
			return sb_errf(e, SB_EUSAGE, "%s: %s: expected one of %s, got '%s'",
				       where, key, p->choices, v);
		*(int *)base = k;
		if (!strcmp(key, "preset"))
			return apply_preset(s, k, where, e);
		return 0;
	}
	case PT_STR:
		if (strpbrk(v, "\n\r"))
			return sb_errf(e, SB_EUSAGE, "%s: %s: value must be one line", where, key);
		memcpy(base, v, strlen(v) + 1);
		return 0;
	}
	return sb_errf(e, SB_EUSAGE, "%s: %s: bad parameter type", where, key);
}

void params_defaults(sb_scene *s)
{
	memset(s, 0, sizeof *s);
	sb_err e = {0};
	for (size_t i = 0; i < NTABLE; i++)
		params_set(s, TABLE[i].name, TABLE[i].def, "default", &e);
	/* A bad default is a programming error: the table test checks e stays clear. */
}

void params_grain_radii(const sb_scene *s, double *lo, double *hi, double *mean)
{
	if (s->size_dist == SIZE_BINARY) {
		*lo = s->r_small;
		*hi = s->r_large;
		*mean = (1 - s->large_fraction) * s->r_small + s->large_fraction * s->r_large;
	} else { /* the paper's: the expressions the references were made with */
		*lo = s->r_min;
		*hi = s->r_max;
		*mean = 0.5 * (s->r_min + s->r_max);
	}
}

/* A scene is a few dozen keys; the bound keeps the line counter far from overflowing
 * on an endless stream (a pipe of comments). */
#define SCENE_MAX_LINES 100000

struct scene_file {
	sb_scene *s;
	const char *path;
	int seen[NTABLE]; /* line where each key of the table was set, 0 if not yet */
};

/* Keys at the top or under [scene]; a '[' without ']' is the reader's malformed line. */
static int scene_section(void *user, const char *header, const char *name, int len, int line, sb_err *e)
{
	const struct scene_file *c = user;
	(void)header;
	if (len <= 0 || (len == 5 && !strncmp(name, "scene", 5)))
		return 0;
	return sb_errf(e, SB_EUSAGE, "%s:%d: unknown section [%.*s] (a scene file has keys at the top or in [scene])",
		       c->path, line, len, name);
}

static int scene_key(void *user, const char *name, const char *value, int line, sb_err *e)
{
	struct scene_file *c = user;
	char where[SB_STR_MAX + 32];
	snprintf(where, sizeof where, "%s:%d", c->path, line);
	/* a key given twice is a mistake that "last one wins" would hide */
	const sb_param *p = params_find(name);
	if (p) {
		const size_t k = (size_t)(p - TABLE);
		if (c->seen[k])
			return sb_errf(e, SB_EUSAGE, "%s: %s: set twice (first on line %d)", where, name, c->seen[k]);
		c->seen[k] = line;
	}
	return params_set(c->s, name, value, where, e);
}

int params_load_file(sb_scene *s, const char *path, sb_err *e)
{
	struct scene_file c = {s, path, {0}};
	const inifile in = {path, "scene file", SCENE_MAX_LINES, scene_section, scene_key, &c};
	return inifile_read(&in, e);
}

int params_override(sb_scene *s, const char *arg, sb_err *e)
{
	const char *eq = strchr(arg, '=');
	if (!eq || eq == arg)
		return sb_errf(e, SB_EUSAGE, "command line: expected key=value, got '%s'", arg);
	char key[128];
	size_t kl = (size_t)(eq - arg);
	if (kl >= sizeof key)
		return sb_errf(e, SB_EUSAGE, "command line: key too long in '%s'", arg);
	memcpy(key, arg, kl);
	key[kl] = 0;
	char k2[128];
	trim(key, k2, sizeof k2);
	return params_set(s, k2, eq + 1, "command line", e);
}

/* Errors that only a combination of keys shows name where the key at fault was set,
 * and where the other one was. */
void params_format(const sb_scene *s, const sb_param *p, char *buf, size_t len)
{
	const char *base = (const char *)s + p->offset;
	switch (p->type) {
	case PT_INT: snprintf(buf, len, "%ld", *(const long *)base); break;
	case PT_REAL:
		if ((p->flags & PF_SAME) && *(const double *)base == -1)
			snprintf(buf, len, "same");
		else
			snprintf(buf, len, "%.17g", *(const double *)base);
		break;
	case PT_BOOL: snprintf(buf, len, "%s", *(const int *)base ? "yes" : "no"); break;
	case PT_ENUM: {
		int k = *(const int *)base;
		const char *c = p->choices;
		for (int i = 0; i < k && c; i++) {
			c = strchr(c, '|');
			if (c)
				c++;
		}
		const char *bar = c ? strchr(c, '|') : NULL;
		snprintf(buf, len, "%.*s", c ? (bar ? (int)(bar - c) : (int)strlen(c)) : 0, c ? c : "");
		break;
	}
	case PT_STR: snprintf(buf, len, "%s", base); break;
	}
}

unsigned long long params_hash(const sb_scene *s, unsigned mask)
{
	uint64_t h = SB_FNV_BASIS;
	char buf[SB_STR_MAX + 64];
	for (size_t i = 0; i < NTABLE; i++) {
		if (!(TABLE[i].flags & mask))
			continue;
		char v[SB_STR_MAX + 8];
		params_format(s, &TABLE[i], v, sizeof v);
		int l = snprintf(buf, sizeof buf, "%s=%s\n", TABLE[i].name, v);
		h = sb_fnv(h, buf, (size_t)l);
	}
	return h;
}

unsigned long long params_hash_nondefault(const sb_scene *s, unsigned mask)
{
	/* Like params_hash, but a key at its default value contributes nothing, so that
	 * adding a key to the table later (with a default that keeps the old behaviour)
	 * leaves every existing run identity unchanged. */
	sb_scene def;
	params_defaults(&def);
	uint64_t h = SB_FNV_BASIS;
	char buf[2 * SB_STR_MAX + 64];
	for (size_t i = 0; i < NTABLE; i++) {
		if (!(TABLE[i].flags & mask))
			continue;
		char v[SB_STR_MAX + 8], d[SB_STR_MAX + 8];
		params_format(s, &TABLE[i], v, sizeof v);
		params_format(&def, &TABLE[i], d, sizeof d);
		if (!strcmp(v, d))
			continue;
		int l = snprintf(buf, sizeof buf, "%s=%s\n", TABLE[i].name, v);
		h = sb_fnv(h, buf, (size_t)l);
	}
	return h;
}

static const char *type_name(const sb_param *p)
{
	switch (p->type) {
	case PT_INT: return "int";
	case PT_REAL: return "real";
	case PT_BOOL: return "bool";
	case PT_ENUM: return "enum";
	case PT_STR: return "string";
	}
	return "?";
}

void params_print_help(FILE *f)
{
	fprintf(f, "Scene keys (units cgs; defaults are the paper preset of docs/model.md):\n");
	for (size_t i = 0; i < NTABLE; i++) {
		const sb_param *p = &TABLE[i];
		char rng[96] = "";
		if (p->type == PT_INT || p->type == PT_REAL)
			range_text(p, rng, sizeof rng);
		else if (p->type == PT_ENUM)
			snprintf(rng, sizeof rng, "%s", p->choices);
		else if (p->type == PT_BOOL)
			snprintf(rng, sizeof rng, "yes|no");
		fprintf(f, "  %-16s %-7s %-8s default %-10s %s\n      %s\n", p->name, type_name(p),
			p->unit[0] ? p->unit : "-", p->def[0] ? p->def : "''", rng, p->help);
	}
}

void params_print_table(FILE *f)
{
	fprintf(f, "name\ttype\tunit\tdefault\tmin\tmax\tchoices\tflags\thelp\n");
	for (size_t i = 0; i < NTABLE; i++) {
		const sb_param *p = &TABLE[i];
		fprintf(f, "%s\t%s\t%s\t%s\t%.17g\t%.17g\t%s\t%u\t%s\n", p->name, type_name(p), p->unit,
			p->def, p->min, p->max, p->choices ? p->choices : "", p->flags, p->help);
	}
}
