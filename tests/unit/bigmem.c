/* bigmem.c - the hot arrays' memory (core/base/bigmem.h): alignment, and the spacing of a
 * slab's arrays modulo 4 KiB. */
#include "bigmem.h"
#include "testlib.h"

#include <stdint.h>
#include <string.h>

static void test_alloc(void)
{
	const size_t sizes[] = {1, 63, 64, 65, 4096, (size_t)3 << 20, (size_t)5 << 20};
	int aligned = 1, huge_aligned = 1;
	for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++) {
		unsigned char *p = bigmem_alloc(sizes[k]);
		if (!p) {
			CHECK("bigmem.alloc.not_null", 0, "bigmem_alloc(%zu) returned NULL", sizes[k]);
			return;
		}
		memset(p, 0xab, sizes[k]); /* the whole size is usable (ASan checks) */
		aligned &= (uintptr_t)p % 64 == 0;
		if (sizes[k] >= (size_t)4 << 20) /* from 4 MiB on: whole huge pages */
			huge_aligned &= (uintptr_t)p % ((size_t)2 << 20) == 0;
		free(p);
	}
	CHECK("bigmem.alloc.line_aligned", aligned, "a block not on a 64-byte boundary");
	CHECK("bigmem.alloc.large_on_2MiB_boundary", huge_aligned, "a large block not on a 2 MiB boundary");
}

static void test_slab(void)
{
	enum { K = 25 };
	const size_t ns[] = {1, 951, 1024, 4096, 100001};
	for (size_t t = 0; t < sizeof ns / sizeof *ns; t++) {
		void *base, *arr[K];
		const size_t n = ns[t];
		char id[96];
		snprintf(id, sizeof id, "bigmem.slab.n%zu.allocates", n);
		const int made = bigmem_slab(&base, arr, K, n, sizeof(double)) == 0;
		CHECK(id, made, "bigmem_slab failed");
		if (!made)
			continue;
		int aligned = 1, apart = 1, distinct = 1;
		for (int a = 0; a < K; a++) {
			aligned &= (uintptr_t)arr[a] % 64 == 0;
			if (a + 1 < K) /* no overlap: each array has its n elements */
				apart &= (char *)arr[a + 1] - (char *)arr[a] >= (ptrdiff_t)(n * sizeof(double));
			for (int b = 0; b < a; b++) /* the same index never shares address bits 0-11 */
				distinct &= ((uintptr_t)arr[a] - (uintptr_t)arr[b]) % 4096 != 0;
			memset(arr[a], 0, n * sizeof(double));
		}
		snprintf(id, sizeof id, "bigmem.slab.n%zu.line_aligned", n);
		CHECK(id, aligned, "an array not on a 64-byte boundary");
		snprintf(id, sizeof id, "bigmem.slab.n%zu.no_overlap", n);
		CHECK(id, apart, "two arrays overlap");
		snprintf(id, sizeof id, "bigmem.slab.n%zu.no_4k_aliasing", n);
		CHECK(id, distinct, "two arrays start at the same offset modulo 4 KiB");
		free(base);
	}
	size_t llc = bigmem_llc_bytes();
	CHECK("bigmem.llc_bytes.plausible", llc >= ((size_t)256 << 10) && llc <= ((size_t)4 << 30),
	      "%zu bytes", llc);
	/* level 2: 0 where sysfs does not say, else no larger than the last level (and
	 * matching sysfs's own figure where it has one) */
	size_t l2 = bigmem_l2_bytes();
	FILE *f = fopen("/sys/devices/system/cpu/cpu0/cache/index2/level", "r");
	int lv = 0;
	if (f) {
		if (fscanf(f, "%d", &lv) != 1)
			lv = 0;
		fclose(f);
	}
	CHECK("bigmem.l2_bytes.plausible", l2 == 0 || (l2 >= ((size_t)64 << 10) && l2 <= llc), "%zu bytes (last level %zu)",
	      l2, llc);
	CHECK("bigmem.l2_bytes.read_where_sysfs_has_it", lv != 2 || l2 > 0, "sysfs has a level-2 cache, read as %zu", l2);
}

int main(void)
{
	test_alloc();
	test_slab();
	return tl_done();
}
