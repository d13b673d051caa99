/* fpmode.h - the floating-point mode of a time step: subnormal numbers flushed to zero
 * (docs/kernel.md, "Subnormal numbers").
 *
 * Why: the Gear corrector's higher derivatives of a disk that feels no force (a grain
 * in flight, an angle without torque) decay geometrically until they are subnormal.
 * AMD's cores compute with subnormals at full speed; Intel's take a microcode assist
 * of ~100 cycles for every operation that reads or makes one, and the corrector
 * became six times slower there (docs/benchmarks.md). Flushed, they are zero: a
 * subnormal (< 2^-1022) added to any position, velocity or acceleration the model
 * holds (all far above 2^-969) leaves it unchanged to the last bit, so the flush
 * cannot move a disk; the regression references did not change.
 *
 * fpmode_enter() sets the mode of the calling thread and returns the old one;
 * fpmode_leave() puts it back, so a caller (a test, an embedding program) keeps its
 * own. Every kernel path runs inside the same mode: the same bits on all of them.
 * x86-64: MXCSR's FTZ (bit 15) and DAZ (bit 6); AArch64: FPCR's FZ (bit 24), which
 * flushes inputs and results alike. Elsewhere nothing is changed (the numbers stay
 * IEEE's and the speed is the CPU's). */
#ifndef SB_FPMODE_H
#define SB_FPMODE_H

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
typedef unsigned sb_fpmode;
#define SB_FPMODE_FLUSH 0x8040u /* FTZ | DAZ */
#define SB_FPMODE_FLUSHES 1
static inline sb_fpmode fpmode_enter(void)
{
	const sb_fpmode old = _mm_getcsr();
	if ((old & SB_FPMODE_FLUSH) != SB_FPMODE_FLUSH)
		_mm_setcsr(old | SB_FPMODE_FLUSH);
	return old;
}
static inline void fpmode_leave(sb_fpmode old)
{
	if ((old & SB_FPMODE_FLUSH) != SB_FPMODE_FLUSH)
		_mm_setcsr(old);
}
#elif defined(__aarch64__)
typedef unsigned long sb_fpmode;
#define SB_FPMODE_FLUSH (1ul << 24) /* FZ */
#define SB_FPMODE_FLUSHES 1
static inline sb_fpmode fpmode_enter(void)
{
	sb_fpmode old;
	__asm__ volatile("mrs %0, fpcr" : "=r"(old));
	if (!(old & SB_FPMODE_FLUSH))
		__asm__ volatile("msr fpcr, %0" : : "r"(old | SB_FPMODE_FLUSH));
	return old;
}
static inline void fpmode_leave(sb_fpmode old)
{
	if (!(old & SB_FPMODE_FLUSH))
		__asm__ volatile("msr fpcr, %0" : : "r"(old));
}
#else
typedef int sb_fpmode;
#define SB_FPMODE_FLUSHES 0
static inline sb_fpmode fpmode_enter(void)
{
	return 0;
}
static inline void fpmode_leave(sb_fpmode old)
{
	(void)old;
}
#endif

/* 1 when the mode flushes subnormals on this build's CPU family */
static inline int fpmode_flushes(void)
{
	return SB_FPMODE_FLUSHES;
}

#endif
