/* bigmem.h - memory for the hot per-disk and per-pair arrays: cache-line aligned
 * (a vector load or store never straddles two lines) and, when large, on transparent
 * huge pages (a 10^5-disk step sweeps ~40 MB: 10^4 small pages overflow the TLB). */
#ifndef SB_BIGMEM_H
#define SB_BIGMEM_H

#include <stddef.h>

/* bytes rounded up to whole 64-byte lines, 64-byte aligned, madvise(MADV_HUGEPAGE) from
 * 4 MiB on; NULL when out of memory. Release with free(). */
void *bigmem_alloc(size_t bytes);

/* Carve k arrays of n elements of size elem out of one bigmem block: *base gets the
 * block, arr[i] the arrays. Their spacing is a whole number of lines but not of 4 KiB
 * pages, so that the same index of two arrays never shares its address bits 0-11 (a
 * load can then be taken for a dependant of a store to another array: "4K
 * aliasing"). Returns 0, or -1 when out of memory (nothing changed). */
int bigmem_slab(void **base, void **arr, int k, size_t n, size_t elem);

/* The size of CPU 0's last-level cache from sysfs (sysconf's figure is the host's in
 * some virtual machines: 384 MiB where the guest has 32), or 32 MiB if unknown. */
size_t bigmem_llc_bytes(void);
/* The size of CPU 0's level-2 cache from sysfs, 0 if unknown. */
size_t bigmem_l2_bytes(void);

#endif
