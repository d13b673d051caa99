/* bigmem.c - aligned blocks on transparent huge pages (see bigmem.h). */
#include "bigmem.h"

#include <stdio.h>
#include <stdlib.h>
#include <sys/mman.h>

enum { LINE = 64, HUGE = 2 << 20, HUGE_FROM = 4 << 20, PAGE = 4096 };

void *bigmem_alloc(size_t bytes)
{
	size_t n = (bytes + LINE - 1) / LINE * LINE;
	if (n == 0)
		n = LINE;
	if (n < HUGE_FROM)
		return aligned_alloc(LINE, n);
	/* a huge page backs only a 2 MiB-aligned 2 MiB range of the block */
	n = (n + HUGE - 1) / HUGE * HUGE;
	void *p = aligned_alloc(HUGE, n);
#ifdef MADV_HUGEPAGE
	if (p)
		(void)madvise(p, n, MADV_HUGEPAGE); /* advice: without THP it is ignored */
#endif
	return p;
}

int bigmem_slab(void **base, void **arr, int k, size_t n, size_t elem)
{
	/* lines per array rounded up to whole pages, plus 5 lines: array a then starts
	 * at 5a mod 64 lines into a page, distinct for a < 64 */
	size_t stride = (n * elem + PAGE - 1) / PAGE * PAGE + 5 * LINE;
	char *p = bigmem_alloc(stride * (size_t)k);
	if (!p)
		return -1;
	*base = p;
	for (int a = 0; a < k; a++)
		arr[a] = p + stride * (size_t)a;
	return 0;
}

/* the size of cpu0's cache of that level (0: the highest), 0 when sysfs does not say */
static size_t cache_bytes(int want)
{
	size_t best = 0;
	int best_level = 0;
	for (int k = 0; k < 8; k++) {
		char path[96], buf[32];
		int level = 0;
		snprintf(path, sizeof path, "/sys/devices/system/cpu/cpu0/cache/index%d/level", k);
		FILE *f = fopen(path, "r");
		if (!f)
			break;
		if (fscanf(f, "%d", &level) != 1)
			level = 0;
		fclose(f);
		snprintf(path, sizeof path, "/sys/devices/system/cpu/cpu0/cache/index%d/size", k);
		f = fopen(path, "r");
		if (!f)
			continue;
		unsigned long v = 0;
		char unit = 0;
		if (fgets(buf, sizeof buf, f) && sscanf(buf, "%lu%c", &v, &unit) >= 1 &&
		    (want ? level == want : level > best_level)) {
			best_level = level;
			best = v * (unit == 'K' ? 1024UL : unit == 'M' ? 1024UL * 1024 : 1);
		}
		fclose(f);
	}
	return best;
}

size_t bigmem_llc_bytes(void)
{
	const size_t b = cache_bytes(0);
	return b ? b : (size_t)32 << 20;
}

size_t bigmem_l2_bytes(void)
{
	return cache_bytes(2);
}
