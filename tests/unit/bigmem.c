/* bigmem.c - the hot arrays' memory (core/bigmem.h) and, in the AVX-512 build, the force
 * kernel's per-disk records (core/krec.h): alignment, the spacing of a slab's arrays
 * modulo 4 KiB, and records and accumulators that give back exactly what went in. */
#include "bigmem.h"
#include "krec.h"
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
}

#if SB_KERNEL_AVX512
/* a distinct, exactly representable value per disk and field */
static double val(int disk, int field) { return 1000.0 * disk + field + 0.25; }

static void test_records(void)
{
	double *rec = bigmem_alloc(sizeof(double) * 8 * 16), *acc = bigmem_alloc(sizeof(double) * 4 * 16);
	double f[7][8];
	for (int k = 0; k < 8; k++)
		for (int c = 0; c < 7; c++)
			f[c][k] = val(k, c);
	for (int i = 0; i < 8 * 16; i++)
		rec[i] = -1;
	__m512d v[7];
	for (int c = 0; c < 7; c++)
		v[c] = _mm512_loadu_pd(f[c]);
	/* fields: x y vx vy w R 1/m -> record (x, y, vx, vy, R w, 1/m, R, R) */
	krec_store8(rec, v[0], v[1], v[2], v[3], v[4], v[5], v[6], 8);
	int ok = 1;
	for (int k = 0; k < 8; k++) {
		const double *q = rec + 8 * k;
		ok &= q[0] == f[0][k] && q[1] == f[1][k] && q[2] == f[2][k] && q[3] == f[3][k] &&
		      q[4] == f[5][k] * f[4][k] && q[5] == f[6][k] && q[6] == f[5][k] && q[7] == f[5][k];
	}
	CHECK("krec.store8.layout", ok, "a record is not (x, y, vx, vy, R w, 1/m, R, R)");
	__m512d x, y, vx, vy;
	krec_load8(rec, &x, &y, &vx, &vy);
	double g[4][8];
	_mm512_storeu_pd(g[0], x);
	_mm512_storeu_pd(g[1], y);
	_mm512_storeu_pd(g[2], vx);
	_mm512_storeu_pd(g[3], vy);
	ok = 1;
	for (int k = 0; k < 8; k++)
		for (int c = 0; c < 4; c++)
			ok &= g[c][k] == f[c][k];
	CHECK("krec.load8.round_trip", ok, "x, y, vx, vy do not come back from the records");
	/* a partial block writes its first records only (the walls' follow) */
	krec_store8(rec + 64, v[0], v[1], v[2], v[3], v[4], v[5], v[6], 3);
	ok = rec[64 + 8 * 2] == f[0][2];
	for (int i = 64 + 8 * 3; i < 8 * 16; i++)
		ok &= rec[i] == -1;
	CHECK("krec.store8.partial_leaves_the_rest", ok, "a partial store wrote past its count");
	/* accumulators (Fx, Fy, T, pad) -> three vectors */
	for (int k = 0; k < 8; k++)
		for (int c = 0; c < 4; c++)
			acc[4 * k + c] = val(k, 10 + c);
	__m512d fx, fy, t;
	krec_load_acc8(acc, &fx, &fy, &t);
	_mm512_storeu_pd(g[0], fx);
	_mm512_storeu_pd(g[1], fy);
	_mm512_storeu_pd(g[2], t);
	ok = 1;
	for (int k = 0; k < 8; k++)
		for (int c = 0; c < 3; c++)
			ok &= g[c][k] == val(k, 10 + c);
	CHECK("krec.load_acc8.fx_fy_torque", ok, "the accumulators do not unpack to Fx, Fy, T");
	free(rec);
	free(acc);
}
#endif

int main(void)
{
	test_alloc();
	test_slab();
#if SB_KERNEL_AVX512
	test_records();
#endif
	return tl_done();
}
