/* kvec.h - private to the kernel module (kernel.c, kvec.c, and their unit test): the
 * vector kernel's data and its per-ISA instances. kvec.c is one source, compiled once
 * per instruction set with that set's -march and a name suffix; kernel.c picks one
 * instance at start-up (docs/kernel.md).
 *
 * The data: every disk's contact data sit in a 64-byte record (x, y, vx, vy, R w, 1/m,
 * R, R), read two per pair; a 32-byte accumulator (Fx, Fy, torque, 0) per disk takes
 * one vector per contact. The fused corrector consumes the accumulators and writes the
 * next step's records in the same pass over the disks. Velocities are the scaled
 * Nordsieck ones (v dt), as everywhere in the kernel. The record's sixth lane is 1/m
 * (0 only for a wall of infinite mass, docs/model.md "Walls"); m_eff = 1 / (1/m_i + 1/m_j)
 * of a pair is formed once per list build, per listed pair (sb_kdata). */
#ifndef SB_KVEC_H
#define SB_KVEC_H

#include "forces.h"
#include "integrate.h"
#include "nlist.h"
#include "state.h"

/* the pair list stores 8 i for disk i: the offset in doubles of its record */
enum { SB_KSHIFT = 3, SB_KCHUNK = 256 };

/* one chunk of the list's contacts, compressed out of the list by the kernel's first
 * pass: the disks (8 i, 8 j) and the pair's m_eff; the second pass writes the force on i
 * and the torques -R_i F_S, R_j F_S (8 spare slots: whole vectors are stored) */
typedef struct sb_kbuf {
	_Alignas(64) double fx[SB_KCHUNK + 8], fy[SB_KCHUNK + 8], ti[SB_KCHUNK + 8], tj[SB_KCHUNK + 8];
	double m[SB_KCHUNK + 8];
	/* a table of materials only: each contact's Y, gamma_N / dt (or gz / dt), gamma_S / dt, mu,
	 * and with the shear spring k_t */
	double c[5][SB_KCHUNK + 8];
	int i[SB_KCHUNK + 8], j[SB_KCHUNK + 8];
	/* tangential = spring only: each contact's shear displacement (the list's, then the
	 * second pass's new one) and its place p in the list */
	double h[SB_KCHUNK + 8];
	int p[SB_KCHUNK + 8];
} sb_kbuf;

typedef struct sb_kdata {
	double *rec;      /* 8 doubles a disk, 64-byte aligned */
	double *facc;     /* 4 doubles a disk */
	sb_kbuf *kb;
	long walls_packed; /* the list build whose wall records rec holds */
	/* per listed pair, in list order, formed once per list build (kernel.c,
	 * pair_consts): m_eff = 1 / (1/m_i + 1/m_j) and R_i + R_j, the lanes' own operations
	 * on the records' numbers, so the same bits; 8 spare slots (m_eff 1, R_i + R_j 0) */
	double *pm, *prs;
	int pcap;
	const sb_nlist *pfor; /* the list and build they were formed for */
	long pbuilt;
	int pn;
	/* a table of materials (forces.h, sb_law.table): each listed pair's coefficients,
	 * forces_kc() of its kinds, the dampings times 1/dt as the scalar law forms them
	 * (pc[0] Y, pc[1] gamma_N / dt or gz / dt, pc[2] gamma_S / dt, pc[3] mu, pc[4] k_t; pcap each),
	 * formed with pm for the table and 1/dt in pkc, pinv */
	double *pc[5];
	int ptable;
	sb_kc pkc[3][3];
	double pinv;
	/* prefetch the far ends of the pairs: set when the per-disk data a step sweeps
	 * outgrow half the last-level cache, where those loads come from memory */
	int prefetch;
	/* tangential = spring: the shear displacements in the order of the current build
	 * (shear.h; kernel.c points it at the kernel's sb_shear before each call) */
	double *shx;
} sb_kdata;

/* One instance: the same functions for one instruction set. */
typedef struct sb_kvec {
	const char *name;  /* "avx512", "avx2", "sse2", "neon", "generic" */
	/* contact forces at st (packed: the records and accumulators are current); keep:
	 * leave them in the accumulators, else into st->f; fsum: the ring's |F| sums.
	 * Returns 1 when an overlap exceeded law->max_overlap, else 0. */
	int (*forces)(sb_kdata *d, const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt,
		      int keep, int packed, double *fsum);
	/* the fused corrector (integ_correct_predict, bit-identical) with the screening
	 * of the predicted state; x, y, vx, vy are left in the records only */
	void (*correct_predict)(sb_kdata *d, const sb_integ *in, sb_state *st, double gy, const sb_nlist *nl,
				sb_screen *scr);
	/* x, y, vx, vy of the mobile disks from the records into st */
	void (*to_state)(const sb_kdata *d, sb_state *st);
	/* the neighbour list's candidate scan (nlist.h, sb_scan_fn) */
	sb_scan_fn scan;
} sb_kvec;

/* The instances this build holds: on x86-64 avx512 (x86-64-v4, 8 lanes), avx2
 * (x86-64-v3, 4 lanes) and sse2 (baseline, 2 lanes); elsewhere the one for the
 * target's baseline (neon on aarch64, 2 lanes). Everywhere w8: 8 lanes in plain code,
 * the widest path's logic for the tests of a CPU without it, never chosen by itself. */
#if defined(__x86_64__)
extern const sb_kvec sb_kvec_avx512, sb_kvec_avx2, sb_kvec_sse2;
#elif defined(__aarch64__)
extern const sb_kvec sb_kvec_neon;
#else
extern const sb_kvec sb_kvec_generic;
#endif
extern const sb_kvec sb_kvec_w8;

#endif
