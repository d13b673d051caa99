/* csv.c - the CSV writer (lib/csv.c) against an independent RFC 4180 reader: fields
 * holding quotes, commas, line breaks (LF, CR LF, a lone CR) and nothing are written
 * with csv_field and csv_text, read back by Python's csv module (Debian's
 * /usr/bin/python3, the reader a user would take), and must come back byte for byte. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "csv.h"
#include "testlib.h"

static const char *FIELDS[] = {
	"plain", "", "a,b", "say \"hi\"", "\"", "\"\"", "two\nlines", "cr\r\nlf", "lone\rcr", "trailing,",
	",leading", " spaces ", "Φ(D) [cm⁻¹]", "x=1,y=\"2\"\n\"z\"",
};
enum { NF = sizeof FIELDS / sizeof FIELDS[0] };

int main(void)
{
	char dir[] = "/tmp/sb_csv_XXXXXX";
	if (!mkdtemp(dir)) {
		printf("FAIL csv.setup: mkdtemp\n");
		return 1;
	}
	char path[256], out[256], cmd[1024];
	snprintf(path, sizeof path, "%s/t.csv", dir);
	snprintf(out, sizeof out, "%s/back.txt", dir);
	FILE *f = fopen(path, "wb");
	/* row 1 through csv_field (quoted only when needed), row 2 through csv_text */
	for (int row = 0; row < 2; row++) {
		for (int i = 0; i < NF; i++) {
			if (i)
				fputc(',', f);
			(row ? csv_text : csv_field)(f, FIELDS[i]);
		}
		fputs("\r\n", f);
	}
	fclose(f);
	/* each field read back, as hex, one per line: no quoting question on the way back */
	snprintf(cmd, sizeof cmd,
		 "/usr/bin/python3 -c 'import csv,sys\n"
		 "with open(sys.argv[1], newline=\"\", encoding=\"utf-8\") as f:\n"
		 "  for r in csv.reader(f, strict=True):\n"
		 "    print(len(r)); [print(x.encode().hex()) for x in r]' %s >%s 2>&1",
		 path, out);
	int rc = system(cmd);
	CHECK("csv.python_reads", rc == 0, "python3's csv refused the file (exit %d)", rc);
	FILE *b = fopen(out, "r");
	char line[4096];
	for (int row = 0; row < 2 && b; row++) {
		const char *how = row ? "text" : "field";
		char id[96];
		int n = fgets(line, sizeof line, b) ? atoi(line) : -1;
		snprintf(id, sizeof id, "csv.%s.field_count", how);
		CHECK(id, n == NF, "%d fields read back, %d written", n, NF);
		for (int i = 0; i < NF && n == NF; i++) {
			char want[512] = "";
			for (const unsigned char *p = (const unsigned char *)FIELDS[i]; *p; p++)
				snprintf(want + strlen(want), sizeof want - strlen(want), "%02x", *p);
			if (!fgets(line, sizeof line, b))
				line[0] = 0;
			line[strcspn(line, "\n")] = 0;
			snprintf(id, sizeof id, "csv.%s.round_trip.%d", how, i);
			CHECK(id, !strcmp(line, want), "field %d: read back %s, written %s", i, line, want);
		}
	}
	if (b)
		fclose(b);
	unlink(path);
	unlink(out);
	rmdir(dir);
	return tl_done();
}
