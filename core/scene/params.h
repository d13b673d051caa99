/* params.h - the scene contract: one parameter table drives the scene-file parser,
 * key=value overrides, range checks, --help and the echo into every output file. */
#ifndef SB_PARAMS_H
#define SB_PARAMS_H

#include <stddef.h>
#include <stdio.h>

#include "err.h"

#define SB_STR_MAX 512
#define SB_NKEYS 109  /* the number of keys: params.c's table has exactly this many rows (checked there) */

/* the pair classes with coefficients of their own (paircoef.h names and orders them) */
#define SB_NPAIRC 4

enum sb_integrator { INTEG_GEAR5, INTEG_GEAR4, INTEG_VERLET };
enum sb_normal { NORMAL_HOOKE, NORMAL_HERTZ };
enum sb_tangential { TANGENTIAL_VISCOUS, TANGENTIAL_SPRING };
enum sb_stop { STOP_NONE, STOP_RISEN, STOP_FLUX };
enum sb_wall_mass { WALLMASS_DISK, WALLMASS_INFINITE };
/* the side boundaries (docs/model.md, "Periodic side boundaries") */
enum sb_sides { SIDES_WALLS, SIDES_PERIODIC };
enum sb_tristate { TRI_AUTO, TRI_YES, TRI_NO };
/* where the ring observable is centred (docs/model.md, "Ring force") */
enum sb_ring_centre { RING_AUTO, RING_INTRUDER, RING_SETTLED, RING_FIXED };
/* where a particle file's disks get their masses (docs/inputs.md, "Particle masses") */
enum sb_particle_mass { PMASS_SCENE, PMASS_FILE };
/* how a generated bed's grain radii are drawn (docs/model.md, "Binary beds") */
enum sb_size_dist { SIZE_UNIFORM, SIZE_BINARY };
/* where a generated bed's intruders stand (docs/model.md, "Several intruders") */
enum sb_intruder_place { IPLACE_ROW, IPLACE_COLUMN };

/* The full parameter set of one run. Field names equal the keys of the table. */
struct sb_scene {
	/* preparation */
	long n_grains;
	int size_dist;       /* enum sb_size_dist */
	double r_min, r_max;
	double r_small, r_large, large_fraction;
	double radius_ratio;
	long n_intruders;
	int intruder_place;  /* enum sb_intruder_place */
	long depth;
	double width;
	double wall_radius, wall_spacing, wall_height;
	int sides;           /* enum sb_sides */
	double density, intruder_density, mass_factor;
	long seed;
	char particles[SB_STR_MAX];
	int particle_mass;   /* enum sb_particle_mass */
	int settle;          /* enum sb_tristate */
	double settle_ke, settle_min, settle_max, settle_drag;
	/* dynamics */
	int wall_mass;       /* enum sb_wall_mass */
	double amplitude, frequency, gravity;
	int ramp;            /* enum sb_ramp (drive.h) */
	double ramp_from, ramp_to, ramp_hold;
	double stiffness, gamma_n, gamma_s, mu, restitution;
	int normal;              /* NORMAL_HOOKE, NORMAL_HERTZ */
	double hertz_stiffness;
	int tangential;          /* TANGENTIAL_VISCOUS, TANGENTIAL_SPRING */
	double shear_stiffness;  /* k_t; 0: 2/7 of the normal stiffness */
	/* the coefficients of the pair classes other than grain-grain (paircoef.h);
	 * -1 = the grain-grain key's value */
	double mu_grain_intruder, gamma_n_grain_intruder, gamma_s_grain_intruder, stiffness_grain_intruder;
	double mu_intruder_intruder, gamma_n_intruder_intruder, gamma_s_intruder_intruder, stiffness_intruder_intruder;
	double mu_grain_wall, gamma_n_grain_wall, gamma_s_grain_wall, stiffness_grain_wall;
	double mu_intruder_wall, gamma_n_intruder_wall, gamma_s_intruder_wall, stiffness_intruder_wall;
	int clip_attractive;
	int integrator;      /* enum sb_integrator */
	double dt;
	int dt_guard;        /* 0 refuse, 1 warn, 2 off */
	int preset;          /* 0 paper, 1 fast */
	double skin;
	double max_overlap;
	/* run length, and the rules that end a run when its question is answered */
	double duration;
	int stop;            /* enum sb_stop */
	double stop_after, stop_skip, stop_flux_se, stop_flux_lo, stop_flux_hi, stop_flux_threshold, stop_flux_k;
	/* recording and files */
	char output[SB_STR_MAX];
	double traj_rate, energy_rate, contact_rate; /* the recorded quantities' own keys (record.c) */
	long bed_kinetic_samples, bed_height_samples;
	long segregation_samples, sliding_samples;
	int snapshots;
	long snapshots_per_period; /* N: snapshots at phases k/N (1: the strobe's, phase 0) */
	int snapshot_precision; /* 0 double, 1 single (the default) */
	long compression;
	double checkpoint_every;
	char checkpoint[SB_STR_MAX];
	int restart;         /* enum sb_tristate: auto = continue from the checkpoint if present */
	char write_particles[SB_STR_MAX];
	char write_lammps[SB_STR_MAX];
	int progress;        /* enum sb_tristate */
	char run_id[SB_STR_MAX]; /* the campaign's id of the run, recorded for h5id_check (core/io/h5id.h) */
	/* observables (observe.h) */
	int flux;
	long flux_lines;
	int field;
	long field_periods;
	int ring;
	double ring_inner, ring_outer, ring_x, ring_y;
	int ring_centre;     /* enum sb_ring_centre */
	double ring_rate, ring_from, ring_until;
	long ring_every;
	/* where each key was last set ("FILE:LINE", "command line"; empty: its default),
	 * for the errors that only a combination of keys shows (params_validate) */
	char src[SB_NKEYS][64];
	/* 1: the key holds a preset's value (set where src says, by a preset there): a
	 * later preset replaces it, an explicit key always does (params.c, presets) */
	unsigned char by_preset[SB_NKEYS];
};
typedef struct sb_scene sb_scene;

/* output = none: a run without a run file (docs/output.md), for a preparation that
 * only writes write_particles / write_lammps or a run whose exit code is all that is
 * wanted. Never what the study driver passes: it reads every run's file. */
#define SB_OUTPUT_NONE "none"
int params_no_output(const sb_scene *s);

/* Where key was last set (FILE:LINE, "command line"), or "default". */
const char *params_where(const sb_scene *s, const char *key);

enum sb_ptype { PT_INT, PT_REAL, PT_BOOL, PT_ENUM, PT_STR };

/* What a parameter influences. The study driver hashes PREP keys for the packing
 * cache and every key but the DRIVER and NOID ones for the run identity (study/campaign/grid.c: what is recorded changes a run's output too); a
 * checkpoint is only resumed when every PREP|DYN key equals the scene's. */
enum sb_pflag {
	PF_PREP = 1,   /* changes the prepared (settled) state */
	PF_DYN = 2,    /* changes the dynamics after preparation */
	PF_LEN = 4,    /* changes how long the run is */
	PF_OUT = 8,    /* only where and what is written */
	PF_MINX = 16,  /* the minimum is exclusive */
	PF_DRIVER = 32, /* set by the campaign driver for every run (paths, restart,
			 * progress): refused in a campaign file, never in a run's id */
	PF_NOID = 64,  /* a campaign may set it, but it is not in a run's id (when the
			* state is saved, not what a run computes) */
	PF_SAME = 128, /* a REAL that may also be -1 (written `same` or -1): "the value of
			* the key it refines" (the pair classes' coefficients, paircoef.h) */
};

typedef struct sb_param {
	const char *name;
	enum sb_ptype type;
	size_t offset;        /* of the field in sb_scene (its type checked: params.c) */
	const char *unit;     /* "" for dimensionless */
	const char *def;      /* default, as text (parsed like any input) */
	double min, max;      /* range for INT/REAL */
	const char *choices;  /* "a|b|c" for ENUM */
	unsigned flags;
	const char *help;
} sb_param;

const sb_param *params_table(size_t *n);
/* The known key nearest to a mistyped one (frequncy -> frequency), or NULL. */
const char *params_nearest(const char *key);

/* A named set of values (the preset key): key, value pairs, NULL-terminated. */
typedef struct sb_preset {
	const char *name;
	const char *set[8];
} sb_preset;
extern const sb_preset PRESETS[]; /* ends with a NULL name */
const sb_param *params_find(const char *name);

void params_defaults(sb_scene *s);

/* A generated bed's grain radii by size_dist: the smallest, the largest and the mean
 * (uniform: r_min, r_max and their midpoint; binary: r_small, r_large and the number-
 * weighted mean by large_fraction). The placement's lattice, the intruder's radius
 * (radius_ratio times the mean), the dt guard and the pair classes read them here. */
void params_grain_radii(const sb_scene *s, double *lo, double *hi, double *mean);

/* Parse and range-check one value; `where` prefixes the message ("file:12", "command line"). */
int params_set(sb_scene *s, const char *key, const char *value, const char *where, sb_err *e);

/* Load an INI scene file: keys at top level or in [scene]. */
int params_load_file(sb_scene *s, const char *path, sb_err *e);

/* One "key=value" command-line override. */
int params_override(sb_scene *s, const char *arg, sb_err *e);


/* Canonical text of a value: what --help shows, what goes into HDF5 and hashes.
 * Reals use %.17g so that the text round-trips exactly. */
void params_format(const sb_scene *s, const sb_param *p, char *buf, size_t len);

/* 64-bit FNV-1a hash of "key=value\n" over all keys whose flags intersect mask. */
unsigned long long params_hash(const sb_scene *s, unsigned mask);

/* The same over the keys whose value differs from the default: stable identities
 * (the study driver's run ids and packing keys) when keys are added to the table. */
unsigned long long params_hash_nondefault(const sb_scene *s, unsigned mask);

void params_print_help(FILE *f);
/* Machine-readable table: name, type, unit, default, min, max, choices, flags, help (TSV). */
void params_print_table(FILE *f);

#endif
