/* study_slurm.c - the pure part of study submit --slurm (study/slurm/plan.c): runs
 * into array tasks (runs per task, each packing to build named before its first run
 * in a task, runs of one packing together), the --array value with its throttle, the
 * user's sbatch arguments (split, study's own options refused), and reading sbatch's
 * job id, squeue's task lines and the workers' lines. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "slurm/plan.h"
#include "testlib.h"
#include "job/worker.h"

static void test_lines(void)
{
	slurm_plan_run runs[] = {{"a1", "k1"}, {"b1", ""}, {"a2", "k2"}, {"a3", "k1"}, {"b2", ""}};
	char **l;
	long n = slurm_plan_task_lines(runs, 5, 1, &l);
	CHECK("study.slurm.lines.one_per_task.count", n == 5, "%ld tasks", n);
	CHECK("study.slurm.lines.one_per_task.order", n == 5 && !strcmp(l[0], "c:k1 r:a1") && !strcmp(l[1], "r:b1") &&
		      !strcmp(l[2], "c:k2 r:a2") && !strcmp(l[3], "c:k1 r:a3") && !strcmp(l[4], "r:b2"),
	      "'%s' '%s' '%s' '%s' '%s'", l[0], l[1], l[2], l[3], l[4]);
	slurm_plan_free_lines(l, n);

	/* two per task: by packing (runs without one first), each packing named once a
	 * line, before its first run */
	n = slurm_plan_task_lines(runs, 5, 2, &l);
	CHECK("study.slurm.lines.two_per_task", n == 3 && !strcmp(l[0], "r:b1 r:b2") && !strcmp(l[1], "c:k1 r:a1 r:a3") &&
		      !strcmp(l[2], "c:k2 r:a2"),
	      "%ld: '%s' '%s' '%s'", n, l[0], l[1], n > 2 ? l[2] : "");
	slurm_plan_free_lines(l, n);

	n = slurm_plan_task_lines(runs, 5, 10, &l);
	CHECK("study.slurm.lines.all_in_one", n == 1 && !strcmp(l[0], "r:b1 r:b2 c:k1 r:a1 r:a3 c:k2 r:a2"), "'%s'",
	      n ? l[0] : "");
	slurm_plan_free_lines(l, n);

	n = slurm_plan_task_lines(runs, 0, 3, &l);
	CHECK("study.slurm.lines.none", n == 0, "%ld", n);
	slurm_plan_free_lines(l, n);

	/* a stable plan: the same input gives the same lines */
	slurm_plan_run many[7];
	char ids[7][16];
	for (int i = 0; i < 7; i++) {
		snprintf(ids[i], sizeof ids[i], "r%d", i);
		many[i] = (slurm_plan_run){ids[i], i % 2 ? "kb" : "ka"};
	}
	char **l2;
	n = slurm_plan_task_lines(many, 7, 3, &l);
	long n2 = slurm_plan_task_lines(many, 7, 3, &l2);
	int same = n == n2 && n == 3;
	for (long i = 0; same && i < n; i++)
		same = !strcmp(l[i], l2[i]);
	CHECK("study.slurm.lines.stable", same && !strcmp(l[0], "c:ka r:r0 r:r2 r:r4") &&
		      !strcmp(l[1], "c:ka r:r6 c:kb r:r1 r:r3") && !strcmp(l[2], "c:kb r:r5"),
	      "'%s' '%s' '%s'", l[0], l[1], l[2]);
	slurm_plan_free_lines(l, n);
	slurm_plan_free_lines(l2, n2);
}

static void test_spec(void)
{
	char s[64];
	slurm_plan_array_spec(10, 0, s, sizeof s);
	CHECK("study.slurm.spec.range", !strcmp(s, "0-9"), "'%s'", s);
	slurm_plan_array_spec(10, 3, s, sizeof s);
	CHECK("study.slurm.spec.throttle", !strcmp(s, "0-9%3"), "'%s'", s);
	slurm_plan_array_spec(1, 2, s, sizeof s);
	CHECK("study.slurm.spec.one", !strcmp(s, "0%2"), "'%s'", s);
}

static void test_args(void)
{
	char *v[8], why[256];
	int n = slurm_plan_split_args("  --partition=short\t--time=01:00:00  --mem 2G ", v, 8, why, sizeof why);
	CHECK("study.slurm.args.split", n == 4 && !strcmp(v[0], "--partition=short") && !strcmp(v[1], "--time=01:00:00") &&
		      !strcmp(v[2], "--mem") && !strcmp(v[3], "2G"),
	      "%d words", n);
	while (n > 0)
		free(v[--n]);
	CHECK("study.slurm.args.empty", slurm_plan_split_args(NULL, v, 8, why, sizeof why) == 0 &&
		      slurm_plan_split_args("   ", v, 8, why, sizeof why) == 0, "words from nothing");
	/* no shell: quotes and metacharacters are plain bytes of a word */
	n = slurm_plan_split_args("--comment='a;b' -J $(x)", v, 8, why, sizeof why);
	CHECK("study.slurm.args.no_shell", n == 3 && !strcmp(v[0], "--comment='a;b'") && !strcmp(v[2], "$(x)"), "%d", n);
	while (n > 0)
		free(v[--n]);
	const char *own[] = {"--array=0-3", "--array", "-a", "-a0-3", "--output=x", "-o", "-ox.out", "--parsable",
			     "--wrap=ls", "--time=5 --array 1", NULL};
	for (int i = 0; own[i]; i++) {
		char id[64];
		snprintf(id, sizeof id, "study.slurm.args.refused.%d", i);
		CHECK(id, slurm_plan_split_args(own[i], v, 8, why, sizeof why) == -1 && strstr(why, "itself"), "'%s' accepted: %s",
		      own[i], why);
	}
	/* options that only begin like study's own are the user's */
	n = slurm_plan_split_args("--array-x --outputs --account=a -A a", v, 8, why, sizeof why);
	CHECK("study.slurm.args.lookalikes", n == 5, "%d: %s", n, why);
	while (n > 0)
		free(v[--n]);
	CHECK("study.slurm.args.too_many", slurm_plan_split_args("-a1 -b -c", v, 2, why, sizeof why) == -1, "3 words into 2");
	/* a word that is no option's value would be sbatch's script: refused, named */
	const char *stray[] = {"job.sh", "--time=5 x", "--exclusive node1", "-p short extra", "-pshort x",
			       "--mem 2G 3G", "-", NULL};
	for (int i = 0; stray[i]; i++) {
		char id[64];
		snprintf(id, sizeof id, "study.slurm.args.no_script.%d", i);
		CHECK(id, slurm_plan_split_args(stray[i], v, 8, why, sizeof why) == -1 && strstr(why, "script"),
		      "'%s' accepted: %s", stray[i], why);
	}
	n = slurm_plan_split_args("-p short --mem 2G --exclusive -N 2", v, 8, why, sizeof why);
	CHECK("study.slurm.args.values", n == 7, "%d: %s", n, why);
	while (n > 0)
		free(v[--n]);
}

static void test_parse(void)
{
	CHECK("study.slurm.jobid.plain", slurm_plan_parse_jobid("12345\n") == 12345, "%ld", slurm_plan_parse_jobid("12345\n"));
	CHECK("study.slurm.jobid.cluster", slurm_plan_parse_jobid("77;cluster\n") == 77, "%ld", slurm_plan_parse_jobid("77;cluster\n"));
	CHECK("study.slurm.jobid.bad", slurm_plan_parse_jobid("") < 0 && slurm_plan_parse_jobid("Submitted batch job 5") < 0 &&
		      slurm_plan_parse_jobid("5x") < 0 && slurm_plan_parse_jobid("0") < 0, "garbage parsed");

	long job, idx;
	char st[24];
	CHECK("study.slurm.squeue.task", slurm_plan_parse_squeue("123_4|RUNNING", &job, &idx, st, sizeof st) && job == 123 &&
		      idx == 4 && !strcmp(st, "RUNNING"), "%ld %ld %s", job, idx, st);
	CHECK("study.slurm.squeue.range", slurm_plan_parse_squeue("123_[5-9%2]|PENDING", &job, &idx, st, sizeof st) &&
		      job == 123 && idx == -1 && !strcmp(st, "PENDING"), "%ld %ld %s", job, idx, st);
	CHECK("study.slurm.squeue.plain_job", slurm_plan_parse_squeue("99|COMPLETING\n", &job, &idx, st, sizeof st) && job == 99 &&
		      idx == -1 && !strcmp(st, "COMPLETING"), "%ld %ld %s", job, idx, st);
	CHECK("study.slurm.squeue.junk", !slurm_plan_parse_squeue("", &job, &idx, st, sizeof st) &&
		      !slurm_plan_parse_squeue("JOBID|STATE", &job, &idx, st, sizeof st) &&
		      !slurm_plan_parse_squeue("12_3", &job, &idx, st, sizeof st) &&
		      !slurm_plan_parse_squeue("12_3|", &job, &idx, st, sizeof st), "junk parsed");

	char name[40];
	long code;
	CHECK("study.slurm.worker.start", slurm_plan_parse_worker(WORKER_START "\tabc\tnode1", name, sizeof name, &code) == 1 &&
		      !strcmp(name, "abc"), "%s", name);
	CHECK("study.slurm.worker.done", slurm_plan_parse_worker(WORKER_DONE "\tabc\t7\tnode1\t1.5\t0.9\t16000\tshake: interrupted", name,
							 sizeof name, &code) == 2 && !strcmp(name, "abc") && code == 7,
	      "%s %ld", name, code);
	/* the DONE line's one parser (worker.h): the engine's usage, none when no engine ran,
	 * and a line of the earlier form without it */
	char l1[] = WORKER_DONE "\tabc\t137\tnode1\t1.5\t0.875\t16044\tkilled by signal 9",
	     l2[] = WORKER_DONE "\tabc\t2\tnode1\t0.000\t-\t-\texec: cannot lock the run",
	     l3[] = WORKER_DONE "\tabc\t7\tnode1\t1.5\tshake: interrupted", l4[] = WORKER_DONE "\tabc\t7\tnode1\t1.5\t0.8\tx";
	worker_done w1, w2, w3, w4;
	CHECK("study.worker.done_usage", worker_done_parse(l1, &w1) && w1.code == 137 && worker_usage(&w1) &&
		      w1.u.cpu_seconds == 0.875 && w1.u.max_rss_kb == 16044 && !strcmp(w1.msg, "killed by signal 9") &&
		      !strcmp(w1.host, "node1"),
	      "code %ld ran %d cpu %g rss %ld msg '%s'", w1.code, w1.ran, w1.u.cpu_seconds, w1.u.max_rss_kb, w1.msg);
	CHECK("study.worker.done_no_engine", worker_done_parse(l2, &w2) && w2.code == 2 && !worker_usage(&w2) &&
		      !strcmp(w2.msg, "exec: cannot lock the run"), "ran %d msg '%s'", w2.ran, w2.msg);
	CHECK("study.worker.done_earlier_form", worker_done_parse(l3, &w3) && w3.code == 7 && !worker_usage(&w3) &&
		      !strcmp(w3.msg, "shake: interrupted"), "ran %d msg '%s'", w3.ran, w3.msg);
	CHECK("study.worker.done_seven_fields", !worker_done_parse(l4, &w4), "a line of 7 fields parsed");
	CHECK("study.slurm.worker.other", !slurm_plan_parse_worker("slurmstepd: error: *** JOB 5 CANCELLED ***", name, sizeof name,
							   &code) &&
		      !slurm_plan_parse_worker(WORKER_DONE "\tabc", name, sizeof name, &code) &&
		      !slurm_plan_parse_worker(WORKER_DONE "\t\t7", name, sizeof name, &code) &&
		      !slurm_plan_parse_worker(WORKER_START "x\tabc", name, sizeof name, &code),
	      "other lines parsed");
}

int main(void)
{
	test_lines();
	test_spec();
	test_args();
	test_parse();
	return tl_done();
}
