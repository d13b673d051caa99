/* sim.h - one run's state and setup. Its phases have their own modules: prepare.h
 * (preparation), step.h (one step), run.h (the shaking loop), checkpoint.h, h5out.h. */
#ifndef SB_SIM_H
#define SB_SIM_H

#include <signal.h>

#include "drive.h"
#include "forces.h"
#include "integrate.h"
#include "journal.h"
#include "kernel.h"
#include "nlist.h"
#include "observe.h"
#include "params.h"
#include "provenance.h"
#include "record.h"
#include "state.h"

enum sb_phase { PH_PREDICT, PH_CHECK, PH_NEIGH, PH_FORCE, PH_CORRECT, PH_RECORD, PH_N };

/* What a run reports while it runs, for whoever shows it: the library prints nothing
 * (docs/engine.md); bin/shake shows a line on stderr when the progress key says so. */
enum sb_progress_kind {
	PROG_SETTLING, /* settling: t, ke (mean kinetic energy per mobile disk, erg), ke_settled */
	PROG_SETTLED,  /* settled at t */
	PROG_SHAKING,  /* shaking: t of t_end, steps_per_s, eta (s) */
	PROG_SHAKEN,   /* the loop ended (after its last PROG_SHAKING) */
};
typedef struct sb_progress {
	enum sb_progress_kind kind;
	double t, t_end;
	double ke, ke_settled;
	double steps_per_s, eta;
} sb_progress;
typedef void sb_progress_fn(void *ctx, const sb_progress *p);

typedef struct sb_sim {
	sb_scene sc;
	sb_state st;
	sb_nlist nl;
	sb_kernel *kern;         /* the force kernel and its fast path */
	sb_law law;
	sb_integ in;
	sb_prov prov;
	sb_drive drive;
	int intruder;            /* index of the recorded intruder, -1 if none */
	int n_intruders;         /* how many the state holds (docs/model.md, "Several intruders") */
	double xlo, xhi, ylo;    /* a mobile centre outside these has left the box */
	double rmean;            /* mean grain radius (surface columns) */

	/* preparation results (recorded in the output) */
	long settle_steps;
	double settle_time, surface0, intruder_y0;

	/* shaking */
	long step, nsteps;
	int predicted;           /* the next step's predictor already ran (fused) */
	sb_screen screen;        /* ... and screened the predicted state (when screen.done) */
	int ov_track;            /* shaking: the kernel's overlap threshold is the record so
				  * far (obs.ov_max), not the stop (step.c, step_arm_overlap) */
	long rec_n[REC_N];       /* records written so far, per recorded quantity (record.h) */
	long rec_next[REC_N];    /* the step the next sample of a rate row is due */
	long n_strobe, next_strobe_step; /* stroboscopic samples taken; the next one's step */
	long next_ckpt_step, n_ckpt;
	long max_contacts;       /* the largest contact record so far (the reader's buffer) */
	sb_obs obs;
	sb_journal jr;
	char journal_path[4200]; /* "" without a run file (output = none) */
	char ckpt_path[4200];    /* the same */
	char xmf_path[4200];     /* the XDMF sidecar of the run file (the same) */

	char warning[512];       /* for main to print, e.g. a dt close to its limit */
	/* how it ended */
	int status;
	char status_msg[1024];
	double status_time;
	long status_step;

	/* diagnostics */
	int profile;
	double tphase[PH_N];
	double loop_seconds;
	double write_seconds; /* assembling the HDF5 file at the end (--profile) */
	volatile sig_atomic_t *stop;
	sb_progress_fn *progress; /* NULL: nobody wants progress */
	void *progress_ctx;
	const char *stage;        /* what a step's failure says it was doing ("settling",
				   * "shaking"; "step" outside the two) */
} sb_sim;

/* The contact law a scene asks for (forces.h). */
sb_law sim_law(const sb_scene *sc);
int sim_init(sb_sim *s, const sb_scene *sc, sb_err *e);
void sim_free(sb_sim *s);

/* Derived quantities of a state in place (intruder, box bounds, the force kernel and
 * the neighbour list); used by the preparation (prepare.h) and by a restart. */
int sim_derive(sb_sim *s, sb_err *e);
/* Set up the observables for the state at t = 0 (also after a restart). */
int sim_obs_init(sb_sim *s, sb_err *e);
/* Remove journal and checkpoint after the output is in place (regular files only). */
void sim_cleanup_files(sb_sim *s);
/* Before anything runs: every path the run will write (output, its sidecar, journal
 * and checkpoint, write_particles, write_lammps) holds nothing or a regular file; a
 * device, FIFO, socket, directory or symbolic link there is refused, naming the key,
 * where it was set and what stands there (the rename at the end would replace it). */
int sim_check_outputs(const sb_sim *s, sb_err *e);
/* The XDMF sidecar of a run file: RUN.h5 -> RUN.xmf, else PATH.xmf. */
void sim_xmf_path(const char *h5path, char *out, size_t len);

/* Box motion y_box = A sin(omega t) and its derivatives. */
double sim_box_y(const sb_sim *s, double t);
double sim_box_v(const sb_sim *s, double t);
double sim_box_a(const sb_sim *s, double t);

/* Kinetic energy (translation + rotation) of the mobile disks in the box frame. */
double sim_kinetic(const sb_sim *s);

/* How the run ended, the one place it is set: status code (err.h), the simulated time
 * and step where it ended, and the message (printf-style) that main shows and the run
 * file records. Returns code. */
int sim_fail(sb_sim *s, int code, double t, long step, const char *fmt, ...)
	__attribute__((format(printf, 5, 6)));

#endif
