/* cli.c - the analysis tools' command line: --opt value and --opt=value alike, options
 * before or after the campaign, unambiguous prefixes; an unknown option names the
 * nearest one of the tool, an option of another tool says so, a missing value and a
 * value given to a flag are errors; and the words of parameters in figure text. */
#include <math.h>
#include <string.h>
#include <unistd.h>

#include "common/cli.h"
#include "common/label.h"
#include "testlib.h"

static const char *const ONSET = " by band skip threshold boot seed level ";

/* parses the NULL-terminated words as onset's command line */
static int parse(an_opts *o, sb_err *e, const char *allowed, const char *const *words)
{
	char *argv[32];
	int argc = 0;
	argv[argc++] = "onset";
	for (; *words && argc < 31; words++)
		argv[argc++] = (char *)*words;
	argv[argc] = NULL;
	memset(o, 0, sizeof *o);
	memset(e, 0, sizeof *e);
	o->tool = "onset";
	return cli_parse(o, argc, argv, allowed, e);
}

#define ARGS(...) ((const char *const[]){__VA_ARGS__, NULL})

int main(void)
{
	an_opts o;
	sb_err e;
	int rc = parse(&o, &e, ONSET, ARGS("--band=0.3:0.7", "camp", "--boot", "50", "--seed=9", "--no-plot"));
	CHECK("cli.forms.equals_and_space", rc == 0 && o.band_lo == 0.3 && o.band_hi == 0.7 && o.boot == 50 &&
					      o.seed == 9 && o.no_plot && o.campaign && !strcmp(o.campaign, "camp"),
	      "rc %d band %g:%g boot %ld seed %lu no_plot %d campaign %s (%s)", rc, o.band_lo, o.band_hi, o.boot,
	      o.seed, o.no_plot, o.campaign ? o.campaign : "-", e.msg);
	rc = parse(&o, &e, ONSET, ARGS("camp", "--threshold", "-0.5", "--by=radius_ratio,width", "--runs=R"));
	CHECK("cli.forms.negative_value_and_list", rc == 0 && o.threshold == -0.5 && o.nby == 2 &&
						  !strcmp(o.by[1], "width") && !strcmp(o.runs, "R"),
	      "rc %d threshold %g nby %d runs %s (%s)", rc, o.threshold, o.nby, o.runs, e.msg);
	rc = parse(&o, &e, ONSET, ARGS("camp", "--thr=0.25"));
	CHECK("cli.forms.unique_prefix", rc == 0 && o.threshold == 0.25, "rc %d threshold %g (%s)", rc, o.threshold,
	      e.msg);
	rc = parse(&o, &e, " freq ratio skip where ", ARGS("camp", "--where=depth=1", "--where", "width=30"));
	CHECK("cli.forms.where_equals", rc == 0 && o.nwhere == 2 && !strcmp(o.where_key[0], "depth") &&
						!strcmp(o.where_val[0], "1") && !strcmp(o.where_key[1], "width"),
	      "rc %d nwhere %d (%s)", rc, o.nwhere, e.msg);
	rc = parse(&o, &e, ONSET, ARGS("camp"));
	CHECK("cli.defaults", rc == 0 && o.boot == 1000 && o.level == 0.95 && o.nby == -1 && isnan(o.threshold) &&
				  !strcmp(o.runs, "runs"),
	      "rc %d boot %ld level %g", rc, o.boot, o.level);
	CHECK("cli.help", parse(&o, &e, ONSET, ARGS("--help")) == -1 && parse(&o, &e, ONSET, ARGS("camp", "-h")) == -1,
	      "--help or -h not recognised");

	rc = parse(&o, &e, ONSET, ARGS("camp", "--bnad", "0.3:0.6"));
	CHECK("cli.unknown.suggests_nearest", rc == 1 && !strcmp(e.msg, "--bnad: unknown option; did you mean --band?"),
	      "rc %d '%s'", rc, e.msg);
	rc = parse(&o, &e, ONSET, ARGS("camp", "--treshold=0.5"));
	CHECK("cli.unknown.suggests_with_value", rc == 1 && strstr(e.msg, "--treshold: unknown option; did you mean --threshold?"),
	      "rc %d '%s'", rc, e.msg);
	rc = parse(&o, &e, ONSET, ARGS("camp", "--bogus", "1"));
	CHECK("cli.unknown.far_no_suggestion", rc == 1 && strstr(e.msg, "--bogus: unknown option") && !strstr(e.msg, "did you mean"),
	      "rc %d '%s'", rc, e.msg);
	rc = parse(&o, &e, ONSET, ARGS("camp", "--ratio", "2"));
	CHECK("cli.unknown.other_tools_option", rc == 1 && strstr(e.msg, "--ratio: not an option of onset"), "rc %d '%s'",
	      rc, e.msg);
	rc = parse(&o, &e, ONSET, ARGS("camp", "--b", "1"));
	CHECK("cli.ambiguous_prefix", rc == 1 && strstr(e.msg, "ambiguous") && strstr(e.msg, "--band") &&
					  strstr(e.msg, "--boot") && strstr(e.msg, "--by"),
	      "rc %d '%s'", rc, e.msg);
	rc = parse(&o, &e, ONSET, ARGS("camp", "--band"));
	CHECK("cli.missing_value", rc == 1 && !strcmp(e.msg, "--band needs a value"), "rc %d '%s'", rc, e.msg);
	rc = parse(&o, &e, ONSET, ARGS("camp", "--no-plot=yes"));
	CHECK("cli.flag_with_value", rc == 1 && !strcmp(e.msg, "--no-plot takes no value"), "rc %d '%s'", rc, e.msg);
	rc = parse(&o, &e, ONSET, ARGS("camp", "--boot=many"));
	CHECK("cli.bad_number", rc == 1 && strstr(e.msg, "--boot: expected a number"), "rc %d '%s'", rc, e.msg);
	/* several campaigns: NAME in --runs' database, DIR/NAME in DIR's own; pooled under
	 * "A+B", whose analysis directory is RUNS/A+B/analysis */
	rc = parse(&o, &e, ONSET, ARGS("camp", "--runs", "R", "R2/other"));
	CHECK("cli.two_campaigns", rc == 0 && o.ncamp == 2 && !strcmp(o.campaign, "camp+other") &&
					   !strcmp(o.camp[0].db, "R/study.db") && !strcmp(o.camp[1].name, "other") &&
					   !strcmp(o.camp[1].runs, "R2") && !strcmp(o.camp[1].db, "R2/study.db") &&
					   !strcmp(o.db, "R/study.db") && !strcmp(o.out, "R/camp+other/analysis"),
	      "rc %d n %d campaign %s db %s/%s runs %s out %s (%s)", rc, o.ncamp, o.campaign, o.camp[0].db, o.camp[1].db,
	      o.camp[1].runs, o.out, e.msg);
	/* a campaign file: its [campaign] name, in --runs' database; one without a name refused */
	char cf[] = "/tmp/cli_test_XXXXXX";
	const int fd = mkstemp(cf);
	char cpath[64], bpath[64];
	snprintf(cpath, sizeof cpath, "%s.campaign", cf);
	snprintf(bpath, sizeof bpath, "%s.b.campaign", cf);
	FILE *cfp = fopen(cpath, "w"), *bfp = fopen(bpath, "w");
	if (cfp)
		fputs("# a comment\n[campaign]\nname = amp   # the name\n[scene]\nname = not_this\n", cfp);
	if (bfp)
		fputs("[scene]\nname = x\n", bfp);
	if (cfp)
		fclose(cfp);
	if (bfp)
		fclose(bfp);
	rc = parse(&o, &e, ONSET, ARGS(cpath, "--runs", "R"));
	CHECK("cli.campaign_file", rc == 0 && o.ncamp == 1 && !strcmp(o.campaign, "amp") && !strcmp(o.db, "R/study.db"),
	      "rc %d campaign %s db %s (%s)", rc, o.campaign ? o.campaign : "-", o.db, e.msg);
	rc = parse(&o, &e, ONSET, ARGS(bpath));
	CHECK("cli.campaign_file_no_name", rc == 1 && strstr(e.msg, "no [campaign] name = NAME"), "rc %d '%s'", rc, e.msg);
	rc = parse(&o, &e, ONSET, ARGS("/nonexistent/x.campaign"));
	CHECK("cli.campaign_file_missing", rc != 0 && strstr(e.msg, "/nonexistent/x.campaign"), "rc %d '%s'", rc, e.msg);
	remove(cpath);
	remove(bpath);
	if (fd >= 0) {
		close(fd);
		remove(cf);
	}
	rc = parse(&o, &e, ONSET, ARGS("camp", "camp"));
	CHECK("cli.campaign_twice", rc == 1 && strstr(e.msg, "campaign 'camp' of runs/study.db given twice"), "rc %d '%s'",
	      rc, e.msg);
	rc = parse(&o, &e, ONSET, ARGS("R/"));
	CHECK("cli.campaign_no_name", rc == 1 && strstr(e.msg, "'R/': expected a campaign's name"), "rc %d '%s'", rc,
	      e.msg);
	rc = parse(&o, &e, ONSET, ARGS("a", "b", "c", "d", "e", "f", "g", "h", "i"));
	CHECK("cli.campaigns_at_most", rc == 1 && strstr(e.msg, "'i': at most 8 campaigns"), "rc %d '%s'", rc, e.msg);
	rc = parse(&o, &e, ONSET, ARGS("--boot", "5"));
	CHECK("cli.no_campaign", rc == 1 && strstr(e.msg, "which campaign?"), "rc %d '%s'", rc, e.msg);
	rc = parse(&o, &e, ONSET, ARGS("camp", "-x"));
	CHECK("cli.unknown_short", rc == 1 && strstr(e.msg, "-x: unknown option"), "rc %d '%s'", rc, e.msg);

	CHECK("cli.distance", cli_distance("bnad", "band") == 1 && cli_distance("band", "band") == 0 &&
				      cli_distance("lvel", "level") == 1 && cli_distance("boot", "bins") == 3,
	      "bnad %d lvel %d boot/bins %d", cli_distance("bnad", "band"), cli_distance("lvel", "level"),
	      cli_distance("boot", "bins"));
	const char *n1 = cli_nearest("seeds", ONSET), *n2 = cli_nearest("bins", ONSET);
	CHECK("cli.nearest", n1 && !strcmp(n1, "seed") && !n2, "seeds -> %s, bins -> %s", n1 ? n1 : "-", n2 ? n2 : "-");

	char w[128];
	label_param(w, sizeof w, "radius_ratio", "0");
	CHECK("label.no_intruder", !strcmp(w, "no intruder"), "'%s'", w);
	label_param(w, sizeof w, "radius_ratio", "2.5");
	CHECK("label.ratio_symbol", !strcmp(w, "𝓡 = 2.5"), "'%s'", w);
	label_param(w, sizeof w, "frequency", "2.8000000000000003");
	CHECK("label.frequency_in_hz", !strcmp(w, "2.8 Hz"), "'%s'", w);
	label_param(w, sizeof w, "width", "30.0");
	CHECK("label.width", !strcmp(w, "W = 30 cm"), "'%s'", w);
	label_param(w, sizeof w, "gravity", "981");
	CHECK("label.unit_from_table", !strcmp(w, "g = 981 cm/s²"), "'%s'", w);
	label_param(w, sizeof w, "gamma_n", "100");
	CHECK("label.unit_inverse", !strcmp(w, "γ_N = 100 s⁻¹"), "'%s'", w);
	label_axis(w, sizeof w, "frequency", "frequency");
	CHECK("label.axis_frequency", !strcmp(w, "frequency f (Hz)"), "'%s'", w);
	label_axis(w, sizeof w, "radius_ratio", NULL);
	CHECK("label.axis_dimensionless", !strcmp(w, "radius_ratio"), "'%s'", w);
	label_unit(w, sizeof w, "density");
	CHECK("label.unit_cube", !strcmp(w, "g/cm³"), "'%s'", w);
	label_param(w, sizeof w, "stop", "risen");
	CHECK("label.other_key", !strcmp(w, "stop = risen"), "'%s'", w);
	const char keys[3][48] = {"radius_ratio", "depth", "frequency"};
	const char *vals[] = {"0", "1", "2.8", "4", "1", "2.8", "4", "1", "3.2"};
	label_group(w, sizeof w, keys, 3, vals, 3, 1, 1);
	CHECK("label.group_legend_varying_keys", !strcmp(w, "𝓡 = 4, 2.8 Hz"), "'%s'", w);
	label_group(w, sizeof w, keys, 3, vals, 3, 1, 0);
	CHECK("label.group_title_shared_keys", !strcmp(w, "depth 1"), "'%s'", w);
	label_group(w, sizeof w, keys, 3, vals, 1, 0, 1);
	CHECK("label.one_group_no_legend", !strcmp(w, ""), "'%s'", w);
	return tl_done();
}
