/* fuzz.c - `make fuzz`: mutation fuzzing of scene, campaign and particle files against
 * the sanitizer builds of shake and `study expand`, and of run files (HDF5: shapes,
 * types, attributes, truncation, bit flips, made by h5mut) against every analysis tool
 * and `study run`. Input k is made from the seed corpus by a PRNG seeded with (--seed,
 * k) alone, so the same k gives the same bytes in every run whatever the time limit;
 * findings (a crash, a sanitizer report, a hang, an exit code outside the documented
 * set, an input accepted that the reader must refuse) are kept with a script that
 * reproduces them. */
#define _GNU_SOURCE /* memmem, strndup, nftw, realpath */
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

enum target { T_SCENE, T_CAMPAIGN, T_PARTICLES, T_RUNFILE, NTARGET };
static const char *const TARGET[NTARGET] = {"scene", "campaign", "particles", "runfile"};
/* what reads a run file: the analysis tools (exit 0, 1 or 2) and `study run` (0-4, 7) */
static const char *const RUNFILE_TOOLS[] = {"onset", "hysteresis", "waiting", "figures", "rolls",
					    "ring",  "whale",	   "convect", "study"};
#define NRUNFILE_TOOLS (sizeof RUNFILE_TOOLS / sizeof *RUNFILE_TOOLS)

enum kind { K_CRASH, K_SANITIZER, K_HANG, K_EXIT, K_ACCEPTED, NKIND };
static const char *const KIND[NKIND] = {"crash", "sanitizer", "hang", "exit", "accepted"};

#define MAX_SEEDS 256
#define MAX_ARGS 64
#define MAX_SIGS 4096
#define STDERR_KEEP 65536
#define EXEC_FAILED "fuzz: cannot run the target"

typedef struct buf {
	char *p;
	size_t n, cap;
} buf;

typedef struct seedfile {
	int target;
	char path[4096];
	char name[64]; /* what the input is called in the run directory */
	buf data;
} seedfile;

typedef struct finding_sig {
	int kind, target;
	char sig[256];
	long count, kept;
	char first[4096]; /* the first kept finding's directory */
} finding_sig;

static struct {
	const char *shake, *study, *out, *work;
	/* the runfile target: the runs directory of the seed campaign (all done, and all
	 * pending for `study run` to ingest), its campaign file and name, the tools' directory,
	 * h5mut */
	const char *runs_done, *runs_pending, *runs_campaign, *runs_name, *tools, *h5mut;
	double seconds, timeout;
	long inputs;
	unsigned long long seed;
	long keep;
	int quiet;
	int only[NTARGET], nonly; /* --target: fuzz only these */
	long line_max[NTARGET];
	seedfile seeds[MAX_SEEDS];
	int nseeds;
	char **lines; /* "key = value" lines of every seed file, for key swaps */
	long nlines;
	char **keys;  /* every scene key (shake --params) and the [campaign] keys */
	long nkeys;
	struct keyrow { /* shake --params: what a valid value of each scene key is */
		char name[64], type[16], choices[128];
		double min, max;
	} *rows;
	long nrows;
	const char *particle_args[MAX_ARGS];
	int nparticle_args;
	finding_sig sigs[MAX_SIGS];
	int nsigs;
	long tried[NTARGET], found[NKIND];
	long codes[NTARGET][10]; /* exit codes 0-8, and 9 for the rest (signals, hangs) */
} F = {.out = "build/fuzz/findings", .work = "build/fuzz/work", .timeout = 10, .seed = 1, .keep = 3,
       .line_max = {199, 199, 1023, 0}};

static void die(const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	fputs("fuzz: ", stderr);
	vfprintf(stderr, fmt, ap);
	fputc('\n', stderr);
	va_end(ap);
	exit(2);
}

/* ---- buffers ---- */

static void buf_reserve(buf *b, size_t n)
{
	if (n <= b->cap)
		return;
	size_t c = b->cap ? b->cap : 256;
	while (c < n)
		c *= 2;
	char *p = realloc(b->p, c);
	if (!p)
		die("out of memory");
	b->p = p;
	b->cap = c;
}

static void buf_insert(buf *b, size_t at, const char *s, size_t n)
{
	if (at > b->n)
		at = b->n;
	buf_reserve(b, b->n + n + 1);
	memmove(b->p + at + n, b->p + at, b->n - at);
	memcpy(b->p + at, s, n);
	b->n += n;
}

static void buf_erase(buf *b, size_t at, size_t n)
{
	if (at >= b->n)
		return;
	if (n > b->n - at)
		n = b->n - at;
	memmove(b->p + at, b->p + at + n, b->n - at - n);
	b->n -= n;
}

static void buf_set(buf *b, const char *s, size_t n)
{
	b->n = 0;
	buf_insert(b, 0, s, n);
}

static int read_file(const char *path, buf *b)
{
	FILE *f = fopen(path, "rb");
	if (!f)
		return -1;
	b->n = 0;
	char tmp[65536];
	size_t k;
	while ((k = fread(tmp, 1, sizeof tmp, f)) > 0)
		buf_insert(b, b->n, tmp, k);
	int bad = ferror(f);
	fclose(f);
	return bad ? -1 : 0;
}

static int write_file(const char *path, const char *p, size_t n)
{
	FILE *f = fopen(path, "wb");
	if (!f)
		return -1;
	size_t w = fwrite(p, 1, n, f);
	return fclose(f) || w != n ? -1 : 0;
}

/* ---- randomness: SplitMix64, one stream per input ---- */

static unsigned long long mix64(unsigned long long z)
{
	z += 0x9e3779b97f4a7c15ULL;
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	return z ^ (z >> 31);
}

static unsigned long long rng_state;
static unsigned long long rnd(void)
{
	return mix64(rng_state++);
}
/* uniform in [0, n) (n > 0; the modulo bias is irrelevant here) */
static size_t below(size_t n)
{
	return n ? (size_t)(rnd() % n) : 0;
}

/* ---- lines ---- */

static size_t line_start(const buf *b, size_t at)
{
	while (at > 0 && b->p[at - 1] != '\n')
		at--;
	return at;
}

static size_t line_end(const buf *b, size_t at) /* index of the '\n' or b->n */
{
	while (at < b->n && b->p[at] != '\n')
		at++;
	return at;
}

/* a random line [*s, *e) (without its newline); 0 when the buffer is empty */
static int pick_line(const buf *b, size_t *s, size_t *e)
{
	if (!b->n)
		return 0;
	size_t at = below(b->n);
	*s = line_start(b, at);
	*e = line_end(b, at);
	return 1;
}

/* as the readers measure a line (docs/inputs.md, "Lines"): without a byte-order mark
 * that opens the file and without the CR of a CRLF */
static size_t longest_line(const buf *b)
{
	size_t best = 0, cur = 0, i = b->n >= 3 && !memcmp(b->p, "\xEF\xBB\xBF", 3) ? 3 : 0;
	for (; i < b->n; i++) {
		if (b->p[i] == '\r' && i + 1 < b->n && b->p[i + 1] == '\n')
			continue;
		if (b->p[i] == '\n') {
			if (cur > best)
				best = cur;
			cur = 0;
		} else {
			cur++;
		}
	}
	return cur > best ? cur : best;
}

/* ---- mutations ---- */

static const char *const NUMBERS[] = {
	"0", "-0", "1", "-1", "2", "0.5", "-0.5", "1e-300", "-1e-300", "4.9e-324", "2.2250738585072014e-308",
	"1e308", "-1e308", "1.7976931348623157e308", "1e309", "-1e309", "nan", "NaN", "-nan", "inf", "-inf",
	"infinity", "9223372036854775807", "9223372036854775808", "-9223372036854775808",
	"-9223372036854775809", "18446744073709551615", "18446744073709551616", "2147483647", "2147483648",
	"-2147483649", "4294967295", "4294967296", "9007199254740992", "9007199254740993", "1e15", "1e19",
	"1e6", "1e7", "1e8", "10000001", "100000", "100001", "65536", "1000000000", "0x10", "0x1p3", "1e",
	"1.", ".", "-", "+", "--1", "1e-5", "3e-5", "1e-7", "0.000001", "99999999999999999999999999999",
	"1,2", "1..3", "0:1:0.1", "0:1e308:1e-300", "-1..9223372036854775807", "1:0:1", "5..1", "0..100000",
	"0:1:1e-5", "2.5:3.2:0.05", "1e-320", "3.2", "0.85", "1.15", "60", "950", "",
};

static const char INTERESTING_BYTES[] = {'\0', '\n', '\r', '\t', ' ', '=', ':', '[', ']', '#', ';', ',',
					 '.', '-', '+', 'e', '0', '9', '\'', '"', '\\', '/', (char)0xff,
					 (char)0xc3, (char)0x80};

static const char *const SECTIONS[] = {"[campaign]", "[scene]", "[grid]", "[]", "[", "]", "[scene",
				       "[ scene ]", "[Grid]", "[grid]]", "[campaign] x = 1"};

static const char *const KINDS[] = {"grain", "intruder", "wall", "Grain", "", "grainx", "1", "2", "3",
				    "4", "0", "-1"};

static int is_num_char(char c)
{
	return (c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '-' || c == '+';
}

/* a random number token [*s, *e); 0 if there is none */
static int pick_number(const buf *b, size_t *s, size_t *e)
{
	if (!b->n)
		return 0;
	size_t start = below(b->n);
	for (size_t k = 0; k < b->n; k++) {
		size_t i = (start + k) % b->n;
		if (b->p[i] >= '0' && b->p[i] <= '9') {
			size_t a = i, z = i;
			while (a > 0 && is_num_char(b->p[a - 1]))
				a--;
			while (z < b->n && is_num_char(b->p[z]))
				z++;
			*s = a;
			*e = z;
			return 1;
		}
	}
	return 0;
}

/* the value of a "key = value" line: [*s, *e) after the separator; 0 if none */
static int pick_value(const buf *b, size_t *s, size_t *e)
{
	size_t ls, le;
	for (int tries = 0; tries < 8; tries++) {
		if (!pick_line(b, &ls, &le))
			return 0;
		const char *eq = memchr(b->p + ls, '=', le - ls);
		if (!eq)
			continue;
		size_t v = (size_t)(eq - b->p) + 1;
		while (v < le && (b->p[v] == ' ' || b->p[v] == '\t'))
			v++;
		size_t z = v;
		while (z < le && b->p[z] != ';' && b->p[z] != '#')
			z++;
		while (z > v && (b->p[z - 1] == ' ' || b->p[z - 1] == '\t'))
			z--;
		*s = v;
		*e = z;
		return 1;
	}
	return 0;
}

static void fill(char *p, size_t n, char c)
{
	memset(p, c, n);
}

/* A line of 200+, 1024+ or 4096+ bytes: a comment, a value padded with blanks or
 * digits, or a valid key hidden behind the reader's limit. */
static void mut_long_line(buf *b, int target)
{
	static const size_t base[] = {200, 1024, 4096};
	size_t len = base[below(3)] + below(64) - 8;
	char *l = malloc(len + 64);
	if (!l)
		die("out of memory");
	size_t n = 0, s, e;
	switch (below(5)) {
	case 0: /* a comment */
		l[n++] = target == T_PARTICLES ? '#' : (below(2) ? '#' : ';');
		fill(l + n, len, 'x');
		n += len;
		break;
	case 1: /* an existing line padded with blanks: what is past the limit is blank */
		if (pick_line(b, &s, &e) && e > s) {
			size_t pad = len > e - s ? len - (e - s) : 1;
			fill(l, pad, below(2) ? ' ' : '\t');
			buf_insert(b, e, l, pad);
			free(l);
			return;
		}
		fill(l, len, ' ');
		n = len;
		break;
	case 2: /* a long number */
		n = (size_t)snprintf(l, 48, "%.40s = ", target == T_PARTICLES ? "1 2" : F.nkeys ?
				     F.keys[below((size_t)F.nkeys)] : "x");
		fill(l + n, len - n, '1');
		n = len;
		break;
	case 3: { /* padding, then what a reader that cuts the line would take for a line */
		const char *tail = target == T_PARTICLES ? "5 5 1 grain" : target == T_CAMPAIGN ? "frequency = 3"
												: "n_grains = 20";
		n = (size_t)snprintf(l, 32, "%s", target == T_PARTICLES ? "# " : "description = ");
		fill(l + n, len - n, 'y');
		n = len;
		memcpy(l + n, tail, strlen(tail));
		n += strlen(tail);
		break;
	}
	default: /* garbage */
		for (size_t i = 0; i < len; i++)
			l[n++] = (char)(33 + below(94));
		break;
	}
	l[n++] = '\n';
	size_t at = line_start(b, below(b->n + 1));
	buf_insert(b, at, l, n);
	free(l);
}

static void mut_number(buf *b, int target)
{
	size_t s, e;
	if (!pick_number(b, &s, &e))
		return;
	const char *v = NUMBERS[below(sizeof NUMBERS / sizeof NUMBERS[0])];
	char tmp[64];
	if (target == T_PARTICLES && below(4) == 0) { /* a nearby value: overlaps, touching disks */
		double x = strtod(b->p + s, NULL);
		snprintf(tmp, sizeof tmp, "%.17g", x * (below(2) ? 1.0000001 : 0.5) + (below(2) ? 1e-9 : 0));
		v = tmp;
	}
	buf_erase(b, s, e - s);
	buf_insert(b, s, v, strlen(v));
}

static void mut_key_swap(buf *b)
{
	if (!F.nlines)
		return;
	const char *l = F.lines[below((size_t)F.nlines)];
	size_t s, e;
	if (below(2) && pick_line(b, &s, &e)) { /* replace a line */
		buf_erase(b, s, e - s);
		buf_insert(b, s, l, strlen(l));
	} else { /* insert one */
		size_t at = line_start(b, below(b->n + 1));
		buf_insert(b, at, "\n", 1);
		buf_insert(b, at, l, strlen(l));
	}
}

static void mut_key_rename(buf *b)
{
	size_t s, e;
	if (!F.nkeys || !pick_line(b, &s, &e))
		return;
	const char *eq = memchr(b->p + s, '=', e - s);
	size_t ke = eq ? (size_t)(eq - b->p) : e;
	const char *k = F.keys[below((size_t)F.nkeys)];
	buf_erase(b, s, ke - s);
	buf_insert(b, s, k, strlen(k));
	if (!eq)
		buf_insert(b, s + strlen(k), " = 1", 4);
}

static void mut_value_syntax(buf *b)
{
	static const char *const V[] = {"1, 2, 3", "1..1000", "0:1:0.25", "2.6, 2.60, 2.6e0", ",", ", ,",
					"1..", "..1", "1:2", "1:2:3:4", "0:1:-1", "1..2..3", "a..b",
					"1, 1..3, 0:2:1", "0..99999", "1e-5:1:1e-5", "yes", "no", "paper",
					"fast", "x y", "'1'", "\"1\"", "1 # c", "1 ;c", "1#c", "../x", "/etc/passwd",
					"$(touch fuzz-pwned)", "a b c", "derived", "literal"};
	size_t s, e;
	if (!pick_value(b, &s, &e))
		return;
	const char *v = V[below(sizeof V / sizeof V[0])];
	buf_erase(b, s, e - s);
	buf_insert(b, s, v, strlen(v));
}

/* A scene key set to a value at or just past the edges of its valid range (from the
 * parameter table), or to an extreme inside it: where the engine's arithmetic on valid
 * input overflows, divides by almost zero or loops for ever. The key's line is
 * replaced when the file has one (a key given twice is refused before anything runs),
 * else appended. */
static void mut_key_boundary(buf *b)
{
	if (!F.nrows)
		return;
	const struct keyrow *r = &F.rows[below((size_t)F.nrows)];
	char v[700];
	if (!strcmp(r->type, "int") || !strcmp(r->type, "real")) {
		int isint = !strcmp(r->type, "int");
		double span = r->max - r->min;
		double x;
		switch (below(10)) {
		case 0: x = r->min; break;
		case 1: x = r->max; break;
		case 2: x = isint ? r->max + 1 : r->max * (1 + 1e-15); break;
		case 3: x = isint ? r->min - 1 : r->min - 1e-300; break;
		case 4: x = isint ? r->min + 1 : r->min + 1e-300; break;
		case 5: x = isint ? r->max - 1 : r->min + span * 1e-12; break;
		case 6: x = r->min + span / 2; break;
		default: /* log-uniform over the range's magnitudes */
			x = pow(10, (double)below(600) / 600.0 * (log10(r->max > 1 ? r->max : 1) + 12) - 12);
			if (x > r->max)
				x = r->max;
			break;
		}
		if (isint)
			snprintf(v, sizeof v, "%.0f", x);
		else
			snprintf(v, sizeof v, "%.17g", x);
	} else if (!strcmp(r->type, "enum")) {
		char c[128];
		snprintf(c, sizeof c, "%s", r->choices);
		char *opt[16];
		int n = 0;
		for (char *p = strtok(c, "|"); p && n < 16; p = strtok(NULL, "|"))
			opt[n++] = p;
		snprintf(v, sizeof v, "%s", n && below(5) ? opt[below((size_t)n)] : below(2) ? "" : "AUTO");
	} else if (!strcmp(r->type, "bool")) {
		static const char *const B[] = {"yes", "no", "on", "off", "1", "0", "true", "maybe", ""};
		snprintf(v, sizeof v, "%s", B[below(sizeof B / sizeof B[0])]);
	} else { /* a path */
		static const char *const S[] = {"", "x", "/dev/null", "/nonexistent/dir/x", "a b", "../x", "-",
						".", "run.h5", "input.scene"};
		if (below(6) == 0) {
			size_t n = 500 + below(40);
			fill(v, n, 'p');
			v[n] = 0;
		} else {
			snprintf(v, sizeof v, "%s", S[below(sizeof S / sizeof S[0])]);
		}
	}
	/* replace the key's last line, else append a line */
	size_t kl = strlen(r->name), at = b->n, ls = 0, le = 0;
	int found = 0;
	for (size_t a = 0; a < b->n;) {
		size_t e = line_end(b, a), i = a;
		while (i < e && (b->p[i] == ' ' || b->p[i] == '\t'))
			i++;
		if (e - i > kl && !memcmp(b->p + i, r->name, kl) &&
		    (b->p[i + kl] == ' ' || b->p[i + kl] == '=' || b->p[i + kl] == '\t')) {
			ls = a;
			le = e;
			found = 1;
		}
		a = e + 1;
	}
	char line[800];
	int n = snprintf(line, sizeof line, "%s = %s", r->name, v);
	if (found) {
		buf_erase(b, ls, le - ls);
		buf_insert(b, ls, line, (size_t)n);
	} else {
		if (b->n && b->p[b->n - 1] != '\n')
			buf_insert(b, b->n, "\n", 1);
		at = b->n;
		buf_insert(b, at, line, (size_t)n);
		buf_insert(b, b->n, "\n", 1);
	}
}

static void mutate_once(buf *b, int target, const seedfile *self)
{
	size_t s, e, s2, e2;
	unsigned op = (unsigned)below(21);
	if (target == T_PARTICLES && (op == 11 || op == 12 || op >= 16) && below(2))
		op = below(2) ? 15 : 9; /* particle files have no keys: kinds and numbers instead */
	if (op >= 17 && target != T_PARTICLES) {
		mut_key_boundary(b);
		return;
	}
	switch (op) {
	case 0: /* bit flip */
		if (b->n)
			b->p[below(b->n)] ^= (char)(1u << below(8));
		break;
	case 1: /* an interesting byte */
		if (b->n)
			b->p[below(b->n)] = INTERESTING_BYTES[below(sizeof INTERESTING_BYTES)];
		break;
	case 2: { /* insert bytes */
		char tmp[8];
		size_t n = 1 + below(8);
		for (size_t i = 0; i < n; i++)
			tmp[i] = below(2) ? INTERESTING_BYTES[below(sizeof INTERESTING_BYTES)] : (char)below(256);
		buf_insert(b, below(b->n + 1), tmp, n);
		break;
	}
	case 3: /* delete a range */
		if (b->n)
			buf_erase(b, below(b->n), 1 + below(16));
		break;
	case 4: /* duplicate a line */
		if (pick_line(b, &s, &e)) {
			size_t n = e < b->n ? e + 1 - s : e - s;
			char *tmp = malloc(n + 1);
			if (!tmp)
				die("out of memory");
			memcpy(tmp, b->p + s, n);
			if (e >= b->n)
				tmp[n++] = '\n';
			buf_insert(b, line_start(b, below(b->n + 1)), tmp, n);
			free(tmp);
		}
		break;
	case 5: /* delete a line */
		if (pick_line(b, &s, &e))
			buf_erase(b, s, e - s + (e < b->n));
		break;
	case 6: /* swap two lines */
		if (pick_line(b, &s, &e) && pick_line(b, &s2, &e2) && s != s2) {
			if (s2 < s) {
				size_t t = s; s = s2; s2 = t;
				t = e; e = e2; e2 = t;
			}
			char *a = strndup(b->p + s, e - s), *c = strndup(b->p + s2, e2 - s2);
			if (!a || !c)
				die("out of memory");
			buf_erase(b, s2, e2 - s2);
			buf_insert(b, s2, a, strlen(a));
			buf_erase(b, s, e - s);
			buf_insert(b, s, c, strlen(c));
			free(a);
			free(c);
		}
		break;
	case 7: /* a long line */
		mut_long_line(b, target);
		break;
	case 8: /* a NUL byte */
		buf_insert(b, below(b->n + 1), "", 1);
		break;
	case 9: case 10: /* a huge, tiny, negative, NaN, inf, ... number */
		mut_number(b, target);
		break;
	case 11: /* a line of another file (any kind) */
		mut_key_swap(b);
		break;
	case 12: /* another key */
		mut_key_rename(b);
		break;
	case 13: { /* a section header */
		const char *h = SECTIONS[below(sizeof SECTIONS / sizeof SECTIONS[0])];
		size_t at = line_start(b, below(b->n + 1));
		buf_insert(b, at, "\n", 1);
		buf_insert(b, at, h, strlen(h));
		break;
	}
	case 14: /* truncate, or line endings and indentation */
		if (below(3) == 0) {
			b->n = below(b->n + 1);
		} else if (below(2)) {
			for (size_t i = 0; i < b->n; i++)
				if (b->p[i] == '\n') {
					buf_insert(b, i, "\r", 1);
					i++;
				}
		} else if (pick_line(b, &s, &e)) {
			buf_insert(b, s, below(2) ? "    " : "\t", below(2) ? 4 : 1);
		}
		break;
	case 15: /* particle kinds / a word swap */
		if (pick_line(b, &s, &e)) {
			const char *k = KINDS[below(sizeof KINDS / sizeof KINDS[0])];
			/* the fourth field of a text particle line, else the line's last word */
			size_t w = e;
			while (w > s && b->p[w - 1] != ' ' && b->p[w - 1] != '\t')
				w--;
			buf_erase(b, w, e - w);
			buf_insert(b, w, k, strlen(k));
		}
		break;
	default: /* 16: campaign value syntax, or splice with another seed of the target */
		if (below(2) || target == T_PARTICLES) {
			int cand[MAX_SEEDS], nc = 0;
			for (int i = 0; i < F.nseeds; i++)
				if (F.seeds[i].target == target && &F.seeds[i] != self)
					cand[nc++] = i;
			if (nc) {
				const buf *o = &F.seeds[cand[below((size_t)nc)]].data;
				size_t cut = line_start(b, below(b->n + 1)), from = line_start(o, below(o->n + 1));
				b->n = cut;
				buf_insert(b, cut, o->p + from, o->n - from);
				break;
			}
		}
		mut_value_syntax(b);
		break;
	}
}

/* ---- running a target ---- */

static double now(void)
{
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Runs argv in cwd with stderr to errpath; returns 1 when it outlived the timeout
 * (then it and its process group are killed), 0 otherwise with *status set. The wait
 * sleeps in sigtimedwait until SIGCHLD (blocked here, so that an exit between the
 * waitpid and the wait is not lost) or the timeout: a nap of fixed length would idle
 * after every short run, and most inputs end in a fraction of a second. */
static int run(char *const argv[], const char *cwd, const char *errpath, int *status)
{
	sigset_t chld, old;
	sigemptyset(&chld);
	sigaddset(&chld, SIGCHLD);
	sigprocmask(SIG_BLOCK, &chld, &old);
	pid_t pid = fork();
	if (pid < 0)
		die("fork: %s", strerror(errno));
	if (!pid) {
		sigprocmask(SIG_SETMASK, &old, NULL); /* the target starts with the mask we had */
		setpgid(0, 0);
		int fd = open(errpath, O_WRONLY | O_CREAT | O_TRUNC, 0644);
		int nul = open("/dev/null", O_RDWR);
		if (fd < 0 || nul < 0 || chdir(cwd))
			_exit(127);
		dup2(nul, 0);
		dup2(nul, 1);
		dup2(fd, 2);
		execv(argv[0], argv);
		dprintf(2, "%s: %s: %s\n", EXEC_FAILED, argv[0], strerror(errno));
		_exit(127);
	}
	setpgid(pid, pid);
	double t0 = now();
	int hung = 0;
	for (;;) {
		pid_t w = waitpid(pid, status, WNOHANG);
		if (w == pid)
			break;
		if (w < 0 && errno != EINTR)
			die("waitpid: %s", strerror(errno));
		double left = F.timeout - (now() - t0);
		if (left <= 0) {
			kill(-pid, SIGKILL);
			kill(pid, SIGKILL);
			while (waitpid(pid, status, 0) < 0 && errno == EINTR)
				;
			hung = 1;
			break;
		}
		/* a SIGCHLD of an earlier child only costs one more turn of the loop */
		struct timespec wait = {(time_t)left, (long)((left - (double)(time_t)left) * 1e9)};
		sigtimedwait(&chld, NULL, &wait);
	}
	sigprocmask(SIG_SETMASK, &old, NULL);
	return hung;
}

static int rm_one(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
	(void)st;
	(void)flag;
	if (ftw->level > 0)
		remove(path);
	return 0;
}

static void clear_dir(const char *dir)
{
	nftw(dir, rm_one, 16, FTW_DEPTH | FTW_PHYS);
}

static void mkdirs(const char *path)
{
	char tmp[4096];
	snprintf(tmp, sizeof tmp, "%s", path);
	for (char *p = tmp + 1; *p; p++)
		if (*p == '/') {
			*p = 0;
			mkdir(tmp, 0755);
			*p = '/';
		}
	if (mkdir(tmp, 0755) && errno != EEXIST)
		die("%s: %s", path, strerror(errno));
}

/* The value a scene file gives key (its last "key = number" line); 0 if none parses. */
static int scene_number(const buf *b, const char *key, double *x)
{
	size_t kl = strlen(key);
	int found = 0;
	for (size_t s = 0; s < b->n;) {
		size_t e = line_end(b, s);
		size_t i = s;
		while (i < e && (b->p[i] == ' ' || b->p[i] == '\t'))
			i++;
		if (e - i > kl && !memcmp(b->p + i, key, kl)) {
			size_t j = i + kl;
			while (j < e && (b->p[j] == ' ' || b->p[j] == '\t'))
				j++;
			if (j < e && (b->p[j] == '=' || b->p[j] == ':')) {
				char tmp[128];
				size_t n = e - j - 1 < sizeof tmp - 1 ? e - j - 1 : sizeof tmp - 1;
				memcpy(tmp, b->p + j + 1, n);
				tmp[n] = 0;
				char *end;
				double v = strtod(tmp, &end);
				while (*end == ' ' || *end == '\t' || *end == '\r')
					end++;
				found = end != tmp && (!*end || *end == ';' || *end == '#');
				if (found)
					*x = v;
			}
		}
		s = e + 1;
	}
	return found;
}

/* What a scene run may cost: the keys whose valid values make a run long in
 * proportion to what they ask for (grains, wall disks, simulated time, time step,
 * checkpoints) are forced to small values on the command line unless the file's own
 * value is already within the budget, so that every run takes well under a second
 * unless it hangs, and small or broken values in the file still reach the engine. */
static const struct budget {
	const char *key;
	double lo, hi;
	int zero_ok; /* 0 is within the budget too (0 = off) */
	const char *force;
	/* forced instead when n_grains was and the file gives no settle_ke (paper.scene's
	 * 950 grains cut to 150, settled below the default 0.01 erg): such a bed settles in
	 * neither 0.3 s nor 1 s, and the same exit 6 at 0.3 s costs a third; a settle_ke of
	 * the file's own may let it settle in between, and shake */
	const char *force_cut;
} BUDGET[] = {
	{"n_grains", 0, 300, 0, "n_grains=150", NULL},
	{"duration", 0, 0.05, 0, "duration=0.02", NULL},
	{"settle_max", 0, 1, 0, "settle_max=1", "settle_max=0.3"},
	{"settle_min", 0, 0.3, 0, "settle_min=0.1", NULL},
	{"dt", 2e-5, 0.01, 0, "dt=5e-05", NULL},
	{"width", 0, 400, 0, "width=60", NULL},
	{"wall_height", 0, 400, 0, "wall_height=0", NULL},
	{"wall_spacing", 0.1, 2000, 0, "wall_spacing=2", NULL},
	{"checkpoint_every", 0.005, 1e8, 1, "checkpoint_every=0", NULL},
};

static int build_argv(int target, const buf *b, const char *input, char **argv)
{
	int n = 0;
	switch (target) {
	case T_SCENE:
		argv[n++] = (char *)F.shake;
		argv[n++] = (char *)input;
		double ke;
		int cut = 0; /* n_grains forced (the first row) and no settle_ke */
		const int own_ke = scene_number(b, "settle_ke", &ke);
		for (size_t i = 0; i < sizeof BUDGET / sizeof BUDGET[0]; i++) {
			double x;
			if (!scene_number(b, BUDGET[i].key, &x) ||
			    !((x >= BUDGET[i].lo && x <= BUDGET[i].hi) || (x == 0 && BUDGET[i].zero_ok))) {
				cut |= i == 0 && !own_ke;
				argv[n++] = (char *)(cut && BUDGET[i].force_cut ? BUDGET[i].force_cut : BUDGET[i].force);
			}
		}
		argv[n++] = "output=run.h5";
		argv[n++] = "progress=no";
		argv[n++] = "write_particles=";
		argv[n++] = "write_lammps=";
		argv[n++] = "checkpoint=";
		break;
	case T_CAMPAIGN:
		argv[n++] = (char *)F.study;
		argv[n++] = "expand";
		argv[n++] = (char *)input;
		break;
	default: {
		static char pbuf[4200];
		argv[n++] = (char *)F.shake;
		for (int i = 0; i < F.nparticle_args && n < MAX_ARGS - 8; i++)
			argv[n++] = (char *)F.particle_args[i];
		snprintf(pbuf, sizeof pbuf, "particles=%s", input);
		argv[n++] = pbuf;
		argv[n++] = "duration=0.02";
		argv[n++] = "output=run.h5";
		argv[n++] = "progress=no";
		break;
	}
	}
	argv[n] = NULL;
	return n;
}

/* A run-file input runs tool k of RUNFILE_TOOLS on the runs directory R (a copy of the
 * seed campaign's, with one file changed), from the run directory. */
static void runfile_argv(int k, char **argv)
{
	static char tool[4200];
	int n = 0;
	if (!strcmp(RUNFILE_TOOLS[k], "study")) {
		/* every run pending: `study run` ingests every file, the changed one too, and
		 * has nothing left to run (no retries: an ingest that fails is a failed run) */
		argv[n++] = (char *)F.study;
		argv[n++] = "run";
		argv[n++] = (char *)F.runs_campaign;
		argv[n++] = "--runs";
		argv[n++] = "R";
		argv[n++] = "--jobs";
		argv[n++] = "1";
		argv[n++] = "--retries";
		argv[n++] = "0";
		argv[n++] = "--no-progress";
	} else {
		snprintf(tool, sizeof tool, "%s/%s", F.tools, RUNFILE_TOOLS[k]);
		argv[n++] = tool;
		argv[n++] = (char *)F.runs_name;
		argv[n++] = "--runs";
		argv[n++] = "R";
		argv[n++] = "--out";
		argv[n++] = "R/out";
		argv[n++] = "--no-plot";
		argv[n++] = "--no-store";
	}
	argv[n] = NULL;
}

/* cp -r from to (the seed runs directory into a run directory) */
static void copy_tree(const char *from, const char *to)
{
	char *av[] = {"/bin/cp", "-r", (char *)from, (char *)to, NULL};
	char err[4200];
	int st;
	snprintf(err, sizeof err, "%s/cp.stderr", F.work);
	if (run(av, ".", err, &st) || !WIFEXITED(st) || WEXITSTATUS(st))
		die("cannot copy %s to %s", from, to);
}

/* ---- findings ---- */

static void shell_quote(FILE *f, const char *s)
{
	fputc('\'', f);
	for (; *s; s++)
		if (*s == '\'')
			fputs("'\\''", f);
		else
			fputc(*s, f);
	fputc('\'', f);
}

/* The part of a report that names the bug, not the run: the first UBSan message up to
 * its values, ASan's SUMMARY line, or the first frame of the engine's own code. */
static void signature(int kind, int status, const char *err, char *sig, size_t len)
{
	const char *p;
	if (kind == K_HANG) {
		snprintf(sig, len, "no exit within the timeout");
	} else if (kind == K_SANITIZER && (p = strstr(err, "runtime error: "))) {
		const char *ls = p;
		while (ls > err && ls[-1] != '\n')
			ls--;
		const char *colon = strchr(p + 15, ':');
		const char *nl = strchr(p, '\n');
		const char *end = colon && (!nl || colon < nl) ? colon : nl ? nl : p + strlen(p);
		snprintf(sig, len, "%.*s", (int)(end - ls), ls);
	} else if (kind == K_SANITIZER && strstr(err, "hard rss limit exhausted")) {
		snprintf(sig, len, "AddressSanitizer: hard rss limit exhausted (a memory blow-up)");
	} else if (kind == K_SANITIZER && strstr(err, "LeakSanitizer")) {
		/* the first frame in shakebox's own code says where the leak was made */
		const char *f = strstr(err, "Direct leak");
		if (!f)
			f = strstr(err, "Indirect leak");
		const char *fr = f ? strstr(f, " in ") : NULL;
		while (fr && (strstr(fr, " in ") != fr || !strncmp(fr, " in __interceptor", 17) ||
			      !strncmp(fr, " in malloc", 10) || !strncmp(fr, " in calloc", 10) ||
			      !strncmp(fr, " in realloc", 11) || !strncmp(fr, " in strdup", 10)))
			fr = strstr(fr + 4, " in ");
		if (fr) {
			const char *nl = strchr(fr, '\n');
			snprintf(sig, len, "LeakSanitizer: leak made%.*s", nl ? (int)(nl - fr) : (int)strlen(fr), fr);
		} else {
			snprintf(sig, len, "LeakSanitizer: detected memory leaks");
		}
	} else if (kind == K_SANITIZER && (p = strstr(err, "SUMMARY: "))) {
		const char *nl = strchr(p, '\n');
		snprintf(sig, len, "%.*s", nl ? (int)(nl - p - 9) : (int)strlen(p + 9), p + 9);
	} else if (kind == K_SANITIZER) {
		snprintf(sig, len, "sanitizer report");
	} else if (kind == K_CRASH) {
		snprintf(sig, len, "killed by signal %d", WTERMSIG(status));
	} else if (kind == K_EXIT) {
		snprintf(sig, len, "exit code %d", WEXITSTATUS(status));
	}
	for (char *q = sig; *q; q++)
		if (*q == '\t' || *q == '\n' || *q == '\r')
			*q = ' ';
}

static void copy_file(const char *from, const char *to)
{
	buf b = {0};
	if (!read_file(from, &b))
		write_file(to, b.p ? b.p : "", b.n);
	free(b.p);
}

static void keep(long iter, int kind, int target, const char *sig, const buf *in, const char *input_name,
		 char **argv, const char *errpath, const char *why)
{
	finding_sig *fs = NULL;
	for (int i = 0; i < F.nsigs; i++)
		if (F.sigs[i].kind == kind && F.sigs[i].target == target && !strcmp(F.sigs[i].sig, sig))
			fs = &F.sigs[i];
	if (!fs) {
		if (F.nsigs == MAX_SIGS)
			fs = &F.sigs[MAX_SIGS - 1]; /* past the table: counted with the last */
		else {
			fs = &F.sigs[F.nsigs++];
			memset(fs, 0, sizeof *fs);
			fs->kind = kind;
			fs->target = target;
			snprintf(fs->sig, sizeof fs->sig, "%s", sig);
		}
	}
	fs->count++;
	F.found[kind]++;
	if (fs->kept >= F.keep)
		return;
	fs->kept++;
	char dir[4096], path[4400];
	snprintf(dir, sizeof dir, "%s/%s-%s-%06ld", F.out, KIND[kind], TARGET[target], iter);
	snprintf(path, sizeof path, "%s/run", dir);
	mkdirs(path);
	if (!fs->first[0])
		snprintf(fs->first, sizeof fs->first, "%s", dir);
	snprintf(path, sizeof path, "%s/run/%s", dir, input_name);
	if (target == T_RUNFILE) { /* the input is one file of a runs directory */
		char runs[4400];
		snprintf(runs, sizeof runs, "%s/run/R", dir);
		copy_tree(strcmp(argv[0], F.study) ? F.runs_done : F.runs_pending, runs);
	}
	write_file(path, in->p ? in->p : "", in->n);
	if (target == T_CAMPAIGN) { /* `scene = ../scenes/X` resolves beside run/ */
		snprintf(path, sizeof path, "%s/scenes", dir);
		mkdirs(path);
		for (int i = 0; i < F.nseeds; i++)
			if (F.seeds[i].target == T_SCENE) {
				char to[4400];
				snprintf(to, sizeof to, "%s/scenes/%s", dir, strrchr(F.seeds[i].path, '/') ?
					 strrchr(F.seeds[i].path, '/') + 1 : F.seeds[i].path);
				copy_file(F.seeds[i].path, to);
			}
	}
	snprintf(path, sizeof path, "%s/stderr.txt", dir);
	copy_file(errpath, path);
	snprintf(path, sizeof path, "%s/repro.sh", dir);
	FILE *f = fopen(path, "w");
	if (!f)
		die("%s: %s", path, strerror(errno));
	fprintf(f, "#!/bin/sh\n# fuzz finding: %s (%s, input %ld of seed %llu)\n# %s\n# %s\n", KIND[kind],
		TARGET[target], iter, F.seed, sig, why);
	fprintf(f, "cd \"$(dirname \"$0\")/run\" || exit 2\n");
	fprintf(f, "ASAN_OPTIONS=");
	shell_quote(f, getenv("ASAN_OPTIONS"));
	fprintf(f, " UBSAN_OPTIONS=");
	shell_quote(f, getenv("UBSAN_OPTIONS"));
	fprintf(f, " LSAN_OPTIONS=");
	shell_quote(f, getenv("LSAN_OPTIONS") ? getenv("LSAN_OPTIONS") : "");
	fprintf(f, " \\\n  timeout %g", F.timeout);
	for (int i = 0; argv[i]; i++) {
		fputc(' ', f);
		shell_quote(f, argv[i]);
	}
	fprintf(f, "\necho \"exit $?\"\n");
	fclose(f);
	chmod(path, 0755);
}

/* ---- setup ---- */

static void add_seed(int target, const char *path)
{
	if (F.nseeds == MAX_SEEDS)
		die("more than %d seed files", MAX_SEEDS);
	seedfile *s = &F.seeds[F.nseeds];
	memset(s, 0, sizeof *s);
	s->target = target;
	snprintf(s->path, sizeof s->path, "%s", path);
	if (read_file(path, &s->data))
		die("%s: %s", path, strerror(errno));
	const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
	const char *dot = strrchr(base, '.');
	snprintf(s->name, sizeof s->name, "input%s", target == T_SCENE ? ".scene" : target == T_CAMPAIGN ?
		 ".campaign" : dot ? dot : ".txt");
	if (target == T_RUNFILE) { /* a file of the runs directory, by its own name */
		snprintf(s->name, sizeof s->name, "%s", base);
		F.nseeds++;
		return;
	}
	if (target == T_CAMPAIGN && !memmem(s->data.p, s->data.n, "max_runs", 8)) {
		/* expanding is a few milliseconds a point in the sanitizer build: a grid the
		 * mutations blow up stays below the timeout */
		char *h = memmem(s->data.p, s->data.n, "[campaign]\n", 11);
		if (h)
			buf_insert(&s->data, (size_t)(h - s->data.p) + 11, "max_runs = 1000\n", 16);
	}
	/* its "key = value" lines serve the key swaps of every target */
	for (size_t a = 0; a < s->data.n;) {
		size_t e = line_end(&s->data, a);
		if (memchr(s->data.p + a, '=', e - a) && e - a < 200) {
			char **nl = realloc(F.lines, sizeof *nl * (size_t)(F.nlines + 1));
			if (!nl || !(nl[F.nlines] = strndup(s->data.p + a, e - a)))
				die("out of memory");
			F.lines = nl;
			F.nlines++;
		}
		a = e + 1;
	}
	F.nseeds++;
}

static void add_key(const char *k)
{
	char **nk = realloc(F.keys, sizeof *nk * (size_t)(F.nkeys + 1));
	if (!nk || !(nk[F.nkeys] = strdup(k)))
		die("out of memory");
	F.keys = nk;
	F.nkeys++;
}

static void load_keys(const char *path)
{
	FILE *f = fopen(path, "r");
	if (!f)
		die("%s: %s", path, strerror(errno));
	char line[4096];
	int first = 1;
	while (fgets(line, sizeof line, f)) {
		line[strcspn(line, "\n")] = 0;
		char *col[8] = {0};
		int nc = 0;
		for (char *p = line, *t; nc < 8 && p; p = t) {
			t = strchr(p, '\t');
			if (t)
				*t++ = 0;
			col[nc++] = p;
		}
		if (!first && nc >= 7 && *col[0]) {
			add_key(col[0]);
			struct keyrow *r = realloc(F.rows, sizeof *r * (size_t)(F.nrows + 1));
			if (!r)
				die("out of memory");
			F.rows = r;
			r = &F.rows[F.nrows++];
			snprintf(r->name, sizeof r->name, "%s", col[0]);
			snprintf(r->type, sizeof r->type, "%s", col[1]);
			snprintf(r->choices, sizeof r->choices, "%s", col[6]);
			r->min = atof(col[4]);
			r->max = atof(col[5]);
		}
		first = 0;
	}
	fclose(f);
	static const char *const ck[] = {"name", "description", "scene", "seed", "seeds", "replicates",
					 "max_runs"};
	for (size_t i = 0; i < sizeof ck / sizeof ck[0]; i++)
		add_key(ck[i]);
}

static const char USAGE[] =
	"usage: fuzz --shake BIN --study BIN [options] (--scene|--campaign|--particles FILE)...\n"
	"  --seconds S       stop after S seconds (0: no limit)\n"
	"  --inputs N        stop after N inputs (0: no limit; one of the two limits is needed)\n"
	"  --seed N          the PRNG seed (input k depends on (N, k) only); default 1\n"
	"  --timeout S       a run longer than S seconds is a hang; default 10\n"
	"  --out DIR         findings (one directory each, with repro.sh); default build/fuzz/findings\n"
	"  --work DIR        scratch directory; default build/fuzz/work\n"
	"  --keys FILE       shake --params output: keys for the key mutations\n"
	"  --keep N          findings kept per distinct signature; default 3\n"
	"  --particle-arg K=V  a scene key for the particle-file runs (repeatable)\n"
	"  --line-max TARGET=N  the reader's line limit (scene=199, campaign=199, particles=1023)\n"
	"  --target T        fuzz only target T (scene, campaign, particles, runfile; repeatable)\n"
	"  --runfile FILE    a run file of the seed runs directory (the runfile target; repeatable)\n"
	"  --runs-done DIR, --runs-pending DIR  the seed runs directory, its runs done, and pending\n"
	"  --runs-campaign FILE  its campaign file; --runs-name NAME its campaign name\n"
	"  --tools DIR       the analysis tools (default: beside --shake); --h5mut BIN the run-file changer\n"
	"  --quiet           no progress lines\n"
	"Prints a summary and writes OUT/summary.tsv; exits 1 when there are findings.\n";

int main(int argc, char **argv)
{
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i];
		const char *v = i + 1 < argc ? argv[i + 1] : NULL;
		int used = 1;
		if (!strcmp(a, "--quiet")) {
			F.quiet = 1;
			used = 0;
		} else if (!strcmp(a, "--help")) {
			fputs(USAGE, stdout);
			return 0;
		} else if (!v) {
			die("%s: needs a value\n%s", a, USAGE);
		} else if (!strcmp(a, "--shake")) {
			F.shake = v;
		} else if (!strcmp(a, "--study")) {
			F.study = v;
		} else if (!strcmp(a, "--seconds")) {
			F.seconds = atof(v);
		} else if (!strcmp(a, "--inputs")) {
			F.inputs = atol(v);
		} else if (!strcmp(a, "--seed")) {
			F.seed = strtoull(v, NULL, 10);
		} else if (!strcmp(a, "--timeout")) {
			F.timeout = atof(v);
		} else if (!strcmp(a, "--out")) {
			F.out = v;
		} else if (!strcmp(a, "--work")) {
			F.work = v;
		} else if (!strcmp(a, "--keep")) {
			F.keep = atol(v);
		} else if (!strcmp(a, "--keys")) {
			load_keys(v);
		} else if (!strcmp(a, "--scene")) {
			add_seed(T_SCENE, v);
		} else if (!strcmp(a, "--campaign")) {
			add_seed(T_CAMPAIGN, v);
		} else if (!strcmp(a, "--particles")) {
			add_seed(T_PARTICLES, v);
		} else if (!strcmp(a, "--runfile")) {
			add_seed(T_RUNFILE, v);
		} else if (!strcmp(a, "--runs-done")) {
			F.runs_done = v;
		} else if (!strcmp(a, "--runs-pending")) {
			F.runs_pending = v;
		} else if (!strcmp(a, "--runs-campaign")) {
			F.runs_campaign = v;
		} else if (!strcmp(a, "--runs-name")) {
			F.runs_name = v;
		} else if (!strcmp(a, "--tools")) {
			F.tools = v;
		} else if (!strcmp(a, "--h5mut")) {
			F.h5mut = v;
		} else if (!strcmp(a, "--particle-arg")) {
			if (F.nparticle_args == MAX_ARGS - 16)
				die("too many --particle-arg");
			F.particle_args[F.nparticle_args++] = v;
		} else if (!strcmp(a, "--target")) {
			int t;
			for (t = 0; t < NTARGET && strcmp(v, TARGET[t]); t++)
				;
			if (t == NTARGET)
				die("--target %s: expected scene, campaign, particles or runfile", v);
			F.only[t] = 1;
			F.nonly++;
		} else if (!strcmp(a, "--line-max")) {
			int t;
			for (t = 0; t < NTARGET; t++)
				if (!strncmp(v, TARGET[t], strlen(TARGET[t])) && v[strlen(TARGET[t])] == '=')
					break;
			if (t == NTARGET)
				die("--line-max %s: expected scene=N, campaign=N or particles=N", v);
			F.line_max[t] = atol(v + strlen(TARGET[t]) + 1);
		} else {
			die("unknown option '%s'\n%s", a, USAGE);
		}
		i += used;
	}
	if (!F.shake || !F.study || !F.nseeds || (F.seconds <= 0 && F.inputs <= 0))
		die("needs --shake, --study, seed files and --seconds or --inputs\n%s", USAGE);
	char abs_shake[4096], abs_study[4096];
	if (!realpath(F.shake, abs_shake) || !realpath(F.study, abs_study))
		die("%s, %s: %s", F.shake, F.study, strerror(errno));
	F.shake = abs_shake;
	F.study = abs_study;
	/* the run-file target's paths, absolute: its inputs run in the run directory */
	static char abs_done[4096], abs_pending[4096], abs_cp[4096], abs_tools[4096], abs_h5mut[4096];
	if (!F.tools) {
		snprintf(abs_tools, sizeof abs_tools, "%s", F.shake);
		*strrchr(abs_tools, '/') = 0;
		F.tools = abs_tools;
	} else if (realpath(F.tools, abs_tools)) {
		F.tools = abs_tools;
	}
	int runfiles = 0;
	for (int i = 0; i < F.nseeds; i++)
		runfiles += F.seeds[i].target == T_RUNFILE;
	if (runfiles && (!F.nonly || F.only[T_RUNFILE])) {
		if (!F.runs_done || !F.runs_pending || !F.runs_campaign || !F.runs_name || !F.h5mut)
			die("--runfile needs --runs-done, --runs-pending, --runs-campaign, --runs-name and --h5mut");
		if (!realpath(F.runs_done, abs_done) || !realpath(F.runs_pending, abs_pending) ||
		    !realpath(F.runs_campaign, abs_cp) || !realpath(F.h5mut, abs_h5mut))
			die("%s, %s, %s, %s: %s", F.runs_done, F.runs_pending, F.runs_campaign, F.h5mut, strerror(errno));
		F.runs_done = abs_done;
		F.runs_pending = abs_pending;
		F.runs_campaign = abs_cp;
		F.h5mut = abs_h5mut;
	}
	setenv("ASAN_OPTIONS", "detect_leaks=1", 0);
	setenv("UBSAN_OPTIONS", "print_stacktrace=1", 0);

	/* work/scenes holds the scene seeds, so that a campaign's `scene = ../scenes/X`
	 * finds them from work/run, where every input runs */
	char rundir[4096], scenedir[4096], errpath[4200], summary[4200];
	snprintf(rundir, sizeof rundir, "%s/run", F.work);
	snprintf(scenedir, sizeof scenedir, "%s/scenes", F.work);
	snprintf(errpath, sizeof errpath, "%s/stderr", F.work);
	mkdirs(rundir);
	mkdirs(scenedir);
	mkdirs(F.out);
	for (int i = 0; i < F.nseeds; i++)
		if (F.seeds[i].target == T_SCENE) {
			char to[8200];
			const char *b = strrchr(F.seeds[i].path, '/');
			snprintf(to, sizeof to, "%s/%s", scenedir, b ? b + 1 : F.seeds[i].path);
			copy_file(F.seeds[i].path, to);
		}
	int per[NTARGET][MAX_SEEDS], nper[NTARGET] = {0};
	for (int i = 0; i < F.nseeds; i++)
		if (!F.nonly || F.only[F.seeds[i].target])
			per[F.seeds[i].target][nper[F.seeds[i].target]++] = i;
	/* the targets in turn, each with seeds: input k is target active[k % nactive], so the
	 * text targets' inputs are the same as before run files were fuzzed unless they are */
	int active[NTARGET], nactive = 0;
	for (int t = 0; t < NTARGET; t++)
		if (nper[t])
			active[nactive++] = t;
	if (!nactive)
		die("no seed files for the targets asked for");

	double t0 = now(), last = t0;
	long iter;
	buf in = {0};
	char *err = malloc(STDERR_KEEP + 1);
	if (!err)
		die("out of memory");
	for (iter = 0;; iter++) {
		if (F.inputs > 0 && iter >= F.inputs)
			break;
		if (F.seconds > 0 && now() - t0 >= F.seconds)
			break;
		rng_state = mix64(F.seed) ^ mix64(0x5eedULL + (unsigned long long)iter);
		const int target = active[iter % nactive];
		const seedfile *sf = &F.seeds[per[target][below((size_t)nper[target])]];
		buf_set(&in, sf->data.p ? sf->data.p : "", sf->data.n);
		int tool = -1;
		char input_name[300], note[300] = "";
		snprintf(input_name, sizeof input_name, "%s", sf->name);
		clear_dir(rundir);
		if (target == T_RUNFILE) {
			/* h5mut changes the structure or the bytes (its seed from this input's
			 * stream); the tool that reads it is drawn from the same stream */
			char mut[4300], mseed[32];
			snprintf(mut, sizeof mut, "%s/mutated.h5", F.work);
			snprintf(mseed, sizeof mseed, "%llu", rnd());
			char *hv[] = {(char *)F.h5mut, (char *)sf->path, mut, "--random", mseed, NULL};
			int hs;
			if (run(hv, ".", errpath, &hs) || !WIFEXITED(hs) || WEXITSTATUS(hs) || read_file(mut, &in))
				buf_set(&in, sf->data.p ? sf->data.p : "", sf->data.n); /* unchanged: rare */
			/* what h5mut changed, for the finding's repro.sh */
			FILE *nf = fopen(errpath, "rb");
			const size_t nn = nf ? fread(note, 1, sizeof note - 1, nf) : 0;
			if (nf)
				fclose(nf);
			note[nn] = 0;
			for (char *q = note; *q; q++)
				if (*q == '\n' || *q == '\r')
					*q = *(q + 1) ? ';' : 0;
			tool = (int)below(NRUNFILE_TOOLS);
			char runs[4300];
			snprintf(runs, sizeof runs, "%s/R", rundir);
			copy_tree(strcmp(RUNFILE_TOOLS[tool], "study") ? F.runs_done : F.runs_pending, runs);
			snprintf(input_name, sizeof input_name, "R/%.64s/%.200s", F.runs_name, sf->name);
		} else {
			size_t nm = 1 + (below(10) < 5 ? 0 : below(4));
			for (size_t m = 0; m < nm; m++)
				mutate_once(&in, target, sf);
		}
		char input[4400];
		snprintf(input, sizeof input, "%s/%s", rundir, input_name);
		if (write_file(input, in.p ? in.p : "", in.n))
			die("%s: %s", input, strerror(errno));
		char *av[MAX_ARGS];
		if (target == T_RUNFILE)
			runfile_argv(tool, av);
		else
			build_argv(target, &in, sf->name, av);
		int status = 0, hung;
		size_t en;
		/* a binary that is being rebuilt is missing for a moment: not a finding */
		for (int tries = 0;; tries++) {
			hung = run(av, rundir, errpath, &status);
			if (hung) {
				/* a machine busy with other work can stretch a short run past the
				 * timeout: a hang is one that a second run with three times the time
				 * confirms (from a fresh copy of its inputs) */
				const double t = F.timeout;
				F.timeout = 3 * t;
				if (target == T_RUNFILE) {
					char runs[4300];
					snprintf(runs, sizeof runs, "%s/R", rundir);
					clear_dir(rundir);
					copy_tree(strcmp(RUNFILE_TOOLS[tool], "study") ? F.runs_done : F.runs_pending, runs);
				} else {
					clear_dir(rundir);
				}
				if (write_file(input, in.p ? in.p : "", in.n))
					die("%s: %s", input, strerror(errno));
				hung = run(av, rundir, errpath, &status);
				F.timeout = t;
			}
			FILE *ef = fopen(errpath, "rb");
			en = ef ? fread(err, 1, STDERR_KEEP, ef) : 0;
			if (ef)
				fclose(ef);
			err[en] = 0;
			if (hung || !WIFEXITED(status) || WEXITSTATUS(status) != 127 || !strstr(err, EXEC_FAILED))
				break;
			if (tries == 10)
				die("%s", err);
			sleep(1);
		}
		F.tried[target]++;
		for (size_t i = 0; i < en; i++)
			if (!err[i])
				err[i] = ' ';
		int kind = -1, code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
		F.codes[target][!hung && code >= 0 && code < 9 ? code : 9]++;
		char why[512] = "";
		if (hung) {
			kind = K_HANG;
			snprintf(why, sizeof why, "still running after %g s, and after %g s again", F.timeout,
				 3 * F.timeout);
		} else if (strstr(err, "runtime error:") || strstr(err, "AddressSanitizer") ||
			   strstr(err, "LeakSanitizer") || strstr(err, "UndefinedBehaviorSanitizer")) {
			kind = K_SANITIZER;
			snprintf(why, sizeof why, "a sanitizer report on stderr");
		} else if (WIFSIGNALED(status)) {
			kind = K_CRASH;
			snprintf(why, sizeof why, "killed by signal %d", WTERMSIG(status));
		} else if (target == T_RUNFILE ? (tool == (int)NRUNFILE_TOOLS - 1 ? (code > 4 && code != 7) : code > 2)
			   : target == T_CAMPAIGN ? code > 2 : code > 7) {
			/* shake: docs/scene.md "Exit codes" (0-7); study expand: 0 ok, 1 bad input, 2 other;
			 * the analysis tools: 0, 1 usage or nothing usable, 2 I/O; study run: 0-4, 7 */
			kind = K_EXIT;
			snprintf(why, sizeof why, "exit code %d, outside the documented set", code);
		} else if (target != T_RUNFILE && code != 1 && code != 2) {
			size_t ll = longest_line(&in);
			if (memchr(in.p ? in.p : "", 0, in.n)) {
				kind = K_ACCEPTED;
				snprintf(why, sizeof why, "exit %d on an input with a NUL byte", code);
			} else if (ll > (size_t)F.line_max[target]) {
				kind = K_ACCEPTED;
				snprintf(why, sizeof why, "exit %d on an input with a line of %zu bytes (the limit is %ld)",
					 code, ll, F.line_max[target]);
			}
		}
		if (kind >= 0) {
			char sig[256];
			if (kind == K_ACCEPTED)
				snprintf(sig, sizeof sig, "%s", strstr(why, "NUL") ? "a NUL byte accepted"
										  : "a line past the limit accepted");
			else
				signature(kind, status, err, sig, sizeof sig);
			/* a run file's finding is the tool's: one signature per tool */
			if (target == T_RUNFILE) {
				char tsig[256];
				snprintf(tsig, sizeof tsig, "%s: %.200s", RUNFILE_TOOLS[tool], sig);
				snprintf(sig, sizeof sig, "%s", tsig);
			}
			if (note[0]) {
				const size_t wl = strlen(why);
				snprintf(why + wl, sizeof why - wl, " (h5mut: %s)", note);
			}
			keep(iter, kind, target, sig, &in, input_name, av, errpath, why);
			if (!F.quiet)
				fprintf(stderr, "fuzz: input %ld (%s): %s: %s\n", iter, TARGET[target], KIND[kind], sig);
		}
		if (!F.quiet && now() - last > 30) {
			last = now();
			long nf = 0;
			for (int k = 0; k < NKIND; k++)
				nf += F.found[k];
			fprintf(stderr, "fuzz: %ld inputs in %.0f s, %ld findings\n", iter + 1, last - t0, nf);
		}
	}
	free(err);
	free(in.p);

	double secs = now() - t0;
	long nf = 0;
	for (int k = 0; k < NKIND; k++)
		nf += F.found[k];
	printf("fuzz: %ld inputs in %.0f s (scene %ld, campaign %ld, particles %ld, runfile %ld), seed %llu\n", iter,
	       secs, F.tried[T_SCENE], F.tried[T_CAMPAIGN], F.tried[T_PARTICLES], F.tried[T_RUNFILE], F.seed);
	printf("fuzz: findings: crash %ld, sanitizer %ld, hang %ld, exit %ld, accepted %ld (inputs); %d distinct\n",
	       F.found[K_CRASH], F.found[K_SANITIZER], F.found[K_HANG], F.found[K_EXIT], F.found[K_ACCEPTED],
	       F.nsigs);
	/* how deep the inputs got: exit 1 is a refusal at the input, 0 and 3-7 a run */
	for (int t = 0; t < NTARGET; t++) {
		printf("fuzz: %s exit codes:", TARGET[t]);
		for (int k = 0; k < 10; k++)
			if (F.codes[t][k] && k < 9)
				printf(" %d: %ld", k, F.codes[t][k]);
			else if (F.codes[t][k])
				printf(" signal or hang: %ld", F.codes[t][k]);
		printf("\n");
	}
	snprintf(summary, sizeof summary, "%s/summary.tsv", F.out);
	FILE *sf = fopen(summary, "w");
	if (!sf)
		die("%s: %s", summary, strerror(errno));
	fprintf(sf, "kind\ttarget\tinputs\tsignature\treproduce\n");
	for (int i = 0; i < F.nsigs; i++) {
		const finding_sig *s = &F.sigs[i];
		printf("  %-9s %-9s %5ldx  %s\n            sh %s/repro.sh\n", KIND[s->kind], TARGET[s->target],
		       s->count, s->sig, s->first);
		fprintf(sf, "%s\t%s\t%ld\t%s\tsh %s/repro.sh\n", KIND[s->kind], TARGET[s->target], s->count, s->sig,
			s->first);
	}
	fclose(sf);
	return nf ? 1 : 0;
}
