/* h5sum.h - the summary of one finished run, read from its HDF5 output. */
#ifndef ST_H5SUM_H
#define ST_H5SUM_H

#include "err.h"

typedef struct h5sum {
	char status[32];
	long exit_code;
	char message[1024];
	double status_time;
	long steps;
	double settle_time;
	long settle_steps;
	double surface_height;
	double intruder_settled_y;
	double intruder_settled_depth;
	long n_mobile;
	long neighbour_builds;
	double loop_seconds;
	char host[256];
	char git_hash[64];
	long git_dirty;
	char start_time[64], end_time[64];
	/* from /intruder/trajectory (has_traj = 0 without one) */
	int has_traj;
	long traj_rows;
	double intruder_radius;   /* 0 without an intruder */
	double final_y, max_y, min_y, mean_y;
	/* first time the centre rose more than one intruder diameter above its settled
	 * height (MODEL.md waiting time); < 0 when it never did (right-censored) */
	double rise_time;
} h5sum;

/* Read the summary; missing optional parts stay 0. */
int h5sum_read(const char *path, h5sum *s, sb_err *e);

#endif
