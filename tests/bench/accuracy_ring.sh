#!/usr/bin/env bash
# accuracy_ring.sh - part (d) of `make bench-accuracy` (tests/bench/accuracy.sh runs it after
# (c); `ACC_PARTS=d make bench-accuracy` runs it alone): can claim 3 (the contact forces
# around the intruder) be answered with `preset = fast` (verlet, dt 2e-4) instead of
# `preset = paper` (gear5, dt 5e-5)?
#
# Runs campaigns/reproduce/claim3_ring.campaign twice through the driver, as
# tests/bench/accuracy_ring/{paper,fast}.campaign.in (identical to it but for the name,
# the preset and the absolute scene path; the same campaign seed 1300; a warning goes
# into the report when claim3_ring.campaign no longer matches them): 2.6 and 2.8 Hz x
# radius_ratio 0, 4, 16 replicates of 60 s each, i.e. 64 runs per preset, into
# ACC_OUT/ring/ (default build/bench/accuracy/ring/, emptied first). Then `bin/ring` on
# each campaign; from its ring_runs.csv (per run: the averages before the rise of
# force = <sum|F|>, net_force = <|sum F + m g|>, temperature) and ring_summary.csv:
#   * per group (frequency x radius_ratio) and observable: the means of both presets,
#     their difference, its Welch standard error sqrt(s_p^2/n_p + s_f^2/n_f) from the
#     per-run values, and z = difference / standard error;
#   * per frequency and observable, the claim's answer, the with/without-intruder ratio
#     of the group means: fast ratio - paper ratio with a 95 % percentile interval from
#     a bootstrap over runs (each of the eight preset x group samples resampled apart;
#     ACC_RING_BOOT resamples, default 2000, awk's srand(1));
#   * verdict per observable: "indistinguishable" when every |z| < 2 and every ratio
#     difference's interval contains 0, else "DIFFERENT"; the conclusion line is
#     "indistinguishable" only when all three observables are and no run failed;
#   * cost: CPU seconds (user + sys of the whole `bin/study run`, from /usr/bin/time) per
#     simulated second (SUM(status_time) of the campaign's runs), and paper / fast.
# Note: the engine seed of a run hashes the campaign seed, the replicate and the
# preparation keys, and the preset is one: the two presets' replicates are different beds
# (as between any two campaigns): the comparison is unpaired, as the Welch errors assume.
#
# Knobs (environment): ACC_QUICK=1 (3 replicates of 15 s: a pipeline check, a few
# minutes), ACC_RING_REPS (replicates per grid point), ACC_RING_BOOT (bootstrap
# resamples), JOBS (parallel runs, default 2), ACC_OUT (default build/bench/accuracy),
# ACC_REPORT (the report to append the table to; default ACC_OUT/ring/report.txt,
# written fresh). Exit: 0 done (whatever the verdict), 1 bad state (a binary or tool
# missing, `study run` or `bin/ring` failing, runs failed, unreadable CSVs).
# Full size: 128 runs, about 1550 CPU s (two cores: about 15 minutes).
set -u
if [ "${1:-}" = --help ] || [ "${1:-}" = -h ]; then
	sed -n '2,/^set -u/p' "$0" | sed '$d; s/^# \{0,1\}//'
	exit 0
fi
HERE=$(cd "$(dirname "$0")" && pwd)
REPO=$(cd "$HERE/../.." && pwd)
STUDY=$REPO/bin/study
RING=$REPO/bin/ring
SCENE=$REPO/scenes/paper.scene
CLAIM3=$REPO/campaigns/reproduce/claim3_ring.campaign
QUICK=${ACC_QUICK:-0}
JOBS=${JOBS:-2}
OUT=${ACC_OUT:-$REPO/build/bench/accuracy}
DIR=$OUT/ring
RUNS=$DIR/runs
DB=$RUNS/study.db
BOOT=${ACC_RING_BOOT:-2000}
PRESETS="paper fast"

die() {
	echo "accuracy_ring: $*" >&2
	exit 1
}

if [ "$QUICK" = 1 ]; then
	REPS=${ACC_RING_REPS:-3} DUR=15
else
	REPS=${ACC_RING_REPS:-16} DUR=60
fi
case $REPS in '' | *[!0-9]*) die "ACC_RING_REPS: expected an integer >= 2, got '$REPS'" ;; esac
[ "$REPS" -ge 2 ] || die "ACC_RING_REPS: at least 2 replicates are needed for a standard error, got $REPS"
case $BOOT in '' | *[!0-9]*) die "ACC_RING_BOOT: expected an integer >= 100, got '$BOOT'" ;; esac
[ "$BOOT" -ge 100 ] || die "ACC_RING_BOOT: at least 100 resamples, got $BOOT"
case $JOBS in '' | *[!0-9]* | 0) die "JOBS: expected a positive integer, got '$JOBS'" ;; esac

for b in "$STUDY" "$RING" "$REPO/bin/shake"; do
	[ -x "$b" ] || die "$b is missing or not executable: run make (make -j2) first"
done
for t in sqlite3 parallel awk sed sort; do
	command -v "$t" >/dev/null 2>&1 || die "$t is not installed"
done
[ -x /usr/bin/time ] || die "/usr/bin/time is not installed (apt-get install time)"
[ -f "$SCENE" ] || die "$SCENE is missing"
for p in $PRESETS; do
	[ -f "$HERE/accuracy_ring/$p.campaign.in" ] || die "$HERE/accuracy_ring/$p.campaign.in is missing"
done

case $DIR in /*/ring) ;; *) die "refusing to empty '$DIR' (ACC_OUT must be an absolute path)" ;; esac
rm -rf -- "$DIR" || die "cannot empty $DIR"
mkdir -p "$RUNS" "$DIR/campaigns" || die "cannot create $DIR"
REPORT=${ACC_REPORT:-$DIR/report.txt}
[ -n "${ACC_REPORT:-}" ] || : >"$REPORT"

# the campaign files: the templates with the scene path, the replicates and the duration
fill() { # TEMPLATE REPS DUR
	sed -e "s|@SCENE@|$SCENE|" -e "s|@REPLICATES@|$2|" -e "s|@DURATION@|$3|" "$1"
}
for p in $PRESETS; do
	fill "$HERE/accuracy_ring/$p.campaign.in" "$REPS" "$DUR" >"$DIR/campaigns/$p.campaign" || die "cannot write $DIR/campaigns/$p.campaign"
done

# drift: the templates at full size against claim3_ring.campaign, every key but the ones
# allowed to differ (comments and spacing ignored)
norm() {
	sed -e 's/^[[:space:]]*[#;].*//' -e 's/[[:space:]][#;].*//' "$1" | awk '
		/^[[:space:]]*\[/ { gsub(/[[:space:]]/, ""); sec = $0; next }
		index($0, "=") { k = substr($0, 1, index($0, "=") - 1); v = substr($0, index($0, "=") + 1)
			gsub(/^[[:space:]]+|[[:space:]]+$/, "", k); gsub(/^[[:space:]]+|[[:space:]]+$/, "", v)
			if (k != "name" && k != "description" && k != "scene" && k != "preset") print sec " " k " = " v }' | sort
}
DRIFT=
if [ -f "$CLAIM3" ]; then
	for p in $PRESETS; do
		d=$(diff <(fill "$HERE/accuracy_ring/$p.campaign.in" 16 60 | norm /dev/stdin) <(norm "$CLAIM3") | grep '^[<>]' | tr '\n' ';')
		[ -n "$d" ] && DRIFT="$DRIFT $p.campaign.in: $d"
	done
else
	DRIFT=" $CLAIM3 is missing"
fi
[ -n "$DRIFT" ] && echo "accuracy_ring: WARNING: the templates no longer match claim3_ring.campaign:$DRIFT" >&2

# ---------------------------------------------------------------- runs
declare -A CPU WALL SIM STATES
for p in $PRESETS; do
	echo "(d) ring force: study run, preset $p: $((REPS * 4)) runs of $DUR s, $JOBS jobs" >&2
	t0=$(date +%s)
	/usr/bin/time -f '%U %S' -o "$DIR/time_$p.txt" "$STUDY" run "$DIR/campaigns/$p.campaign" \
		--runs "$RUNS" --jobs "$JOBS" --no-progress >"$DIR/study_$p.log" 2>&1
	rc=$?
	WALL[$p]=$(($(date +%s) - t0))
	if [ "$rc" != 0 ]; then
		tail -n 15 "$DIR/study_$p.log" >&2
		# 3: some runs failed (recorded): the comparison below still says how many
		[ "$rc" = 3 ] || die "bin/study run (preset $p) exited $rc (log: $DIR/study_$p.log)"
		echo "accuracy_ring: bin/study run (preset $p): some runs failed (exit 3); see the report" >&2
	fi
	CPU[$p]=$(tail -n 1 "$DIR/time_$p.txt" | awk 'NF == 2 { printf "%.2f", $1 + $2 }')
	[ -n "${CPU[$p]}" ] || die "no CPU time in $DIR/time_$p.txt"
	SIM[$p]=$(sqlite3 "$DB" "SELECT printf('%.3f', SUM(status_time)) FROM runs WHERE campaign = 'acc_ring_$p'") ||
		die "cannot read $DB"
	[ -n "${SIM[$p]}" ] || die "no simulated time recorded for acc_ring_$p in $DB"
	STATES[$p]=$(sqlite3 -separator ' ' "$DB" "SELECT state, COUNT(*) FROM runs WHERE campaign = 'acc_ring_$p' GROUP BY state" |
		awk '{ printf "%s%s %s", (NR > 1 ? ", " : ""), $1, $2 }')
	echo "(d) ring force: bin/ring acc_ring_$p" >&2
	"$RING" "acc_ring_$p" --db "$DB" --runs "$RUNS" --out "$DIR/ring_$p" --no-plot >"$DIR/ring_$p.txt" 2>&1 ||
		{ cat "$DIR/ring_$p.txt" >&2; die "bin/ring acc_ring_$p failed (output: $DIR/ring_$p.txt)"; }
	for f in ring_runs ring_summary; do
		[ -s "$DIR/ring_$p/$f.csv" ] || die "bin/ring wrote no $DIR/ring_$p/$f.csv"
	done
done

# ---------------------------------------------------------------- comparison
# input: both presets' ring_runs.csv then both ring_summary.csv (columns found by name)
awk -v B="$BOOT" -v P=paper -v F=fast -v table="$DIR/table.txt" '
	function csv(line, a,    n, i, c, q, f) { # split one CSV line into a[1..n]
		n = 0; f = ""; q = 0
		for (i = 1; i <= length(line); i++) { c = substr(line, i, 1)
			if (q) { if (c == "\"") { if (substr(line, i + 1, 1) == "\"") { f = f c; i++ } else q = 0 } else f = f c }
			else if (c == "\"") q = 1
			else if (c == ",") { a[++n] = f; f = "" }
			else f = f c }
		a[++n] = f
		return n
	}
	function need(name) { if (!(name in col)) { print "ERROR " FILENAME ": no column " name; bad = 1; exit 1 } return col[name] }
	function gparse(g, r,    n, t, i, kv) { # "radius_ratio=4 frequency=2.6" -> r["radius_ratio"], r["frequency"]
		delete r; n = split(g, t, " ")
		for (i = 1; i <= n; i++) if (split(t[i], kv, "=") == 2) r[kv[1]] = kv[2]
	}
	function qsort(A, lo, hi,    i, last, t) {
		if (lo >= hi) return
		t = A[lo]; A[lo] = A[int((lo + hi) / 2)]; A[int((lo + hi) / 2)] = t
		last = lo
		for (i = lo + 1; i <= hi; i++) if (A[i] < A[lo]) { last++; t = A[last]; A[last] = A[i]; A[i] = t }
		t = A[lo]; A[lo] = A[last]; A[last] = t
		qsort(A, lo, last - 1); qsort(A, last + 1, hi)
	}
	function abs(x) { return x < 0 ? -x : x }
	FNR == 1 {
		delete col; nc = csv($0, h); for (i = 1; i <= nc; i++) col[h[i]] = i
		file++  # 1, 2: ring_runs of paper, fast; 3, 4: ring_summary of paper, fast
		pr = (file == 1 || file == 3) ? P : F
		next
	}
	file <= 2 {
		csv($0, a); g = a[need("group")]; gparse(g, kv)
		if (!("radius_ratio" in kv) || !("frequency" in kv)) { print "ERROR " FILENAME ": group without radius_ratio and frequency: " g; bad = 1; exit 1 }
		if (!(g in gseen)) { gseen[g] = 1; gl[++ng] = g; gf[g] = kv["frequency"] + 0; gr[g] = kv["radius_ratio"] + 0 }
		u = a[need("use")]; nuse[pr, u]++; guse[pr, g, u]++
		if (u != "used" && u != "failed_used") next
		k = ++n[pr, g]
		v[pr, g, k, 1] = a[need("force")] + 0; v[pr, g, k, 2] = a[need("net_force")] + 0; v[pr, g, k, 3] = a[need("temperature")] + 0
		next
	}
	{
		csv($0, a); g = a[need("group")]
		sruns[pr, g] = a[need("runs")]; scens[pr, g] = a[need("runs_censored")]; sfail[pr, g] = a[need("runs_failed")]
		sm[pr, g, 1] = a[need("force")]; sm[pr, g, 2] = a[need("net_force")]; sm[pr, g, 3] = a[need("temperature")]
		for (o = 1; o <= 3; o++) { rn = "ratio_" on[o]
			sr[pr, g, o] = a[need(rn)]; srlo[pr, g, o] = a[need(rn "_lo")]; srhi[pr, g, o] = a[need(rn "_hi")] }
	}
	BEGIN { on[1] = "force"; on[2] = "net_force"; on[3] = "temperature"; srand(1) }
	END {
		if (bad) exit 1
		if (file != 4) { print "ERROR: expected 4 CSV files, read " file; exit 1 }
		# groups ordered by frequency, then radius_ratio
		for (i = 2; i <= ng; i++) { t = gl[i]; for (j = i - 1; j >= 1 && (gf[gl[j]] > gf[t] || (gf[gl[j]] == gf[t] && gr[gl[j]] > gr[t])); j--) gl[j + 1] = gl[j]; gl[j + 1] = t }
		for (i = 1; i <= ng; i++) { g = gl[i]
			if (gr[g] == 0) ref0[gf[g]] = g
			for (q = 0; q < 2; q++) { pr = q ? F : P
				if (n[pr, g] < 2) { print "ERROR: group " g ", preset " pr ": " n[pr, g] + 0 " usable runs (need 2)"; exit 1 }
				if (sruns[pr, g] != n[pr, g]) { print "ERROR: group " g ", preset " pr ": " n[pr, g] " runs in ring_runs.csv, " sruns[pr, g] " in ring_summary.csv"; exit 1 }
				for (o = 1; o <= 3; o++) { s = 0; for (k = 1; k <= n[pr, g]; k++) s += v[pr, g, k, o]
					m[pr, g, o] = s / n[pr, g]; ss = 0
					for (k = 1; k <= n[pr, g]; k++) ss += (v[pr, g, k, o] - m[pr, g, o]) ^ 2
					se2[pr, g, o] = ss / (n[pr, g] - 1) / n[pr, g]
					# my parsing against bin/ring own means
					if (abs(m[pr, g, o] - sm[pr, g, o]) > 1e-9 * abs(sm[pr, g, o]) + 1e-12) {
						print "ERROR: group " g ", preset " pr ", " on[o] ": mean " m[pr, g, o] " but ring_summary.csv says " sm[pr, g, o]; exit 1 } } } }
		nrg = 0
		for (i = 1; i <= ng; i++) { g = gl[i]; if (gr[g] > 0) { if (!(gf[g] in ref0)) { print "ERROR: no radius_ratio = 0 group at " gf[g] " Hz"; exit 1 }
			rg[++nrg] = g; g0[g] = ref0[gf[g]]
			for (o = 1; o <= 3; o++) { rp[g, o] = m[P, g, o] / m[P, g0[g], o]; rf[g, o] = m[F, g, o] / m[F, g0[g], o] } } }
		# bootstrap: every preset x group sample resampled apart, in a fixed order
		for (b = 1; b <= B; b++) {
			for (i = 1; i <= ng; i++) { g = gl[i]; for (q = 0; q < 2; q++) { pr = q ? F : P; nn = n[pr, g]
				s1 = s2 = s3 = 0
				for (k = 1; k <= nn; k++) { j = int(rand() * nn) + 1; s1 += v[pr, g, j, 1]; s2 += v[pr, g, j, 2]; s3 += v[pr, g, j, 3] }
				bm[pr, g, 1] = s1 / nn; bm[pr, g, 2] = s2 / nn; bm[pr, g, 3] = s3 / nn } }
			for (i = 1; i <= nrg; i++) { g = rg[i]
				for (o = 1; o <= 3; o++) d[g, o, b] = bm[F, g, o] / bm[F, g0[g], o] - bm[P, g, o] / bm[P, g0[g], o] } }
		ilo = int(0.025 * B); if (ilo < 1) ilo = 1; ihi = B - ilo + 1
		for (i = 1; i <= nrg; i++) { g = rg[i]; for (o = 1; o <= 3; o++) {
			delete A; for (b = 1; b <= B; b++) A[b] = d[g, o, b]; qsort(A, 1, B)
			dlo[g, o] = A[ilo]; dhi[g, o] = A[ihi] } }
		# table 1: group means
		printf "    %-14s %-11s %5s %21s %21s %11s %7s %6s\n", "group", "observable", "runs", "paper mean +- se", "fast mean +- se", "fast-paper", "rel", "z" > table
		for (o = 1; o <= 3; o++) { maxz[o] = 0; okz[o] = 1 }
		for (i = 1; i <= ng; i++) { g = gl[i]; for (o = 1; o <= 3; o++) {
			dd = m[F, g, o] - m[P, g, o]; sew = sqrt(se2[P, g, o] + se2[F, g, o])
			z = sew > 0 ? dd / sew : (dd == 0 ? 0 : 1e9)
			if (abs(z) >= 2) okz[o] = 0
			if (abs(z) > abs(maxz[o])) { maxz[o] = z; maxzg[o] = g }
			fmt = m[P, g, o] >= 1000 ? "%11.0f +- %7.0f" : "%11.3f +- %7.3f"
			printf "    %-14s %-11s %2d/%-2d " fmt " " fmt " %11.4g %+6.1f%% %6.2f\n", sprintf("%.2f Hz R=%g", gf[g], gr[g]), on[o], n[P, g], n[F, g],
				m[P, g, o], sqrt(se2[P, g, o]), m[F, g, o], sqrt(se2[F, g, o]), dd, 100 * dd / m[P, g, o], z > table } }
		# table 2: ratios
		printf "\n    %-14s %-11s %25s %25s %31s\n", "ratio R>0/R=0", "observable", "paper [bin/ring 95 %]", "fast [bin/ring 95 %]", "fast-paper [bootstrap 95 %]" > table
		for (o = 1; o <= 3; o++) okr[o] = 1
		for (i = 1; i <= nrg; i++) { g = rg[i]; for (o = 1; o <= 3; o++) {
			dd = rf[g, o] - rp[g, o]; c0 = dlo[g, o] <= 0 && dhi[g, o] >= 0; if (!c0) okr[o] = 0
			printf "    %-14s %-11s %7.4f [%7.4f, %7.4f] %7.4f [%7.4f, %7.4f] %+8.4f [%+8.4f, %+8.4f]%s\n", sprintf("%.2f Hz R=%g", gf[g], gr[g]), on[o],
				rp[g, o], srlo[P, g, o], srhi[P, g, o], rf[g, o], srlo[F, g, o], srhi[F, g, o], dd, dlo[g, o], dhi[g, o], c0 ? "" : "  excludes 0" > table
			if (abs(sr[P, g, o] - rp[g, o]) > 1e-9 * rp[g, o] || abs(sr[F, g, o] - rf[g, o]) > 1e-9 * rf[g, o]) {
				print "ERROR: ratio of " g " " on[o] " differs from ring_summary.csv"; exit 1 } } }
		# censored runs (the intruder rose: averaged before the rise) and accounting
		cen = ""; for (i = 1; i <= nrg; i++) { g = rg[i]; cen = cen sprintf("%s%.2f Hz R=%g %d/%d", (i > 1 ? ", " : ""), gf[g], gr[g], n[P, g] - scens[P, g], n[F, g] - scens[F, g]) }
		print "ROSE " cen
		for (q = 0; q < 2; q++) { pr = q ? F : P; s = ""; tot = 0
			for (kk in nuse) { split(kk, tt, SUBSEP); if (tt[1] == pr) { s = s " " tt[2] "=" nuse[kk]; if (tt[2] != "used") notall[pr] += nuse[kk]; tot += nuse[kk] } }
			print "USE " pr " " tot " " notall[pr] + 0 s }
		for (o = 1; o <= 3; o++) {
			why = ""
			if (!okz[o]) why = sprintf("|z| = %.2f at %.2f Hz R=%g", abs(maxz[o]), gf[maxzg[o]], gr[maxzg[o]])
			if (!okr[o]) { for (i = 1; i <= nrg; i++) { g = rg[i]; if (!(dlo[g, o] <= 0 && dhi[g, o] >= 0))
				why = why (why == "" ? "" : "; ") sprintf("ratio difference at %.2f Hz %+.4f [%+.4f, %+.4f]", gf[g], rf[g, o] - rp[g, o], dlo[g, o], dhi[g, o]) } }
			printf "VERDICT %s %s %.2f %s\n", on[o], (okz[o] && okr[o]) ? "indistinguishable" : "DIFFERENT", abs(maxz[o]), why == "" ? "-" : why }
		for (i = 1; i <= nrg; i++) { g = rg[i]
			printf "RATIO %.2f %.4f %.4f %+.4f %+.4f %+.4f\n", gf[g], rp[g, 1], rf[g, 1], rf[g, 1] - rp[g, 1], dlo[g, 1], dhi[g, 1] }
	}' "$DIR/ring_paper/ring_runs.csv" "$DIR/ring_fast/ring_runs.csv" \
	"$DIR/ring_paper/ring_summary.csv" "$DIR/ring_fast/ring_summary.csv" >"$DIR/compare.txt"
rc=$?
if [ "$rc" != 0 ] || grep -q '^ERROR' "$DIR/compare.txt"; then
	grep '^ERROR' "$DIR/compare.txt" >&2
	die "the comparison failed (bin/ring's CSV columns changed?): $DIR/compare.txt"
fi

# ---------------------------------------------------------------- report
read -r _ np_tot np_bad np_use <<<"$(grep '^USE paper ' "$DIR/compare.txt" | cut -d' ' -f2-)"
read -r _ nf_tot nf_bad nf_use <<<"$(grep '^USE fast ' "$DIR/compare.txt" | cut -d' ' -f2-)"
cps() { awk -v c="${CPU[$1]}" -v s="${SIM[$1]}" 'BEGIN { printf "%.4f", (s > 0 ? c / s : 0) }'; }
SPEED=$(awk -v a="$(cps paper)" -v b="$(cps fast)" 'BEGIN { printf "%.2f", (b > 0 ? a / b : 0) }')
ALL_OK=1
while read -r _ o v _; do [ "$v" = indistinguishable ] || ALL_OK=0; done < <(grep '^VERDICT' "$DIR/compare.txt")
{
	echo "(d) Ring force (claim 3): campaigns/reproduce/claim3_ring.campaign run with preset = paper (gear5,"
	echo "    dt 5e-5) and preset = fast (verlet, dt 2e-4): 2.6 and 2.8 Hz x radius_ratio 0, 4, $REPS replicates"
	echo "    of $DUR s per point ($((REPS * 4)) runs per preset; campaign seed 1300 in both, but the engine seed hashes"
	echo "    the preparation keys, the preset among them: the presets' beds are independent draws, an"
	echo "    unpaired comparison). Per run bin/ring's averages before the rise, from 2 s: force = <sum|F|>"
	echo "    and net_force = <|sum F + m g|> [dyn], temperature [cm^2/s^2]. runs = used paper/fast;"
	echo "    +- = standard error over runs; z = (fast - paper) / Welch standard error."
	[ -n "$DRIFT" ] && echo "    WARNING: the templates no longer match claim3_ring.campaign:$DRIFT"
	grep -v '^#' "$DIR/table.txt"
	echo "    ratio = mean with intruder / mean without at the same frequency (the claim's answer; the paper: +15 %);"
	echo "    bin/ring's intervals per preset (ring_{paper,fast}/ring_summary.csv in $DIR);"
	echo "    the difference's interval: percentile bootstrap, $BOOT resamples, each of the 8 preset x group"
	echo "    samples resampled apart (awk srand(1))."
	echo "    Runs whose intruder rose before the end (averaged up to the rise), paper/fast: $(grep '^ROSE' "$DIR/compare.txt" | cut -d' ' -f2-)."
	echo "    runs by state: paper: ${STATES[paper]}; fast: ${STATES[fast]} (bin/ring use: paper: $np_use; fast: $nf_use)"
	printf '    %-6s %5s %12s %9s %17s %8s\n' preset runs "simulated s" "CPU s" "CPU s / sim. s" "wall s"
	for p in $PRESETS; do
		printf '    %-6s %5s %12s %9s %17s %8s\n' "$p" "$(sqlite3 "$DB" "SELECT COUNT(*) FROM runs WHERE campaign = 'acc_ring_$p'")" \
			"${SIM[$p]}" "${CPU[$p]}" "$(cps "$p")" "${WALL[$p]}"
	done
	echo "    CPU s: user + sys of the whole bin/study run (settling, runs, driver); fast is ${SPEED}x cheaper per simulated s."
	echo "    Verdict per observable (every |z| < 2 and every ratio difference's interval contains 0):"
	grep '^VERDICT' "$DIR/compare.txt" | while read -r _ o v mz why; do
		printf '      %-12s %-17s max |z| %s%s\n' "$o" "$v" "$mz" "$([ "$why" = - ] || echo "; $why")"
	done
	echo "    (12 z tests and 6 intervals: even two identical presets fail one of them now and then; a"
	echo "    DIFFERENT in one observable at |z| just above 2 asks for more replicates, not a verdict.)"
	rat=$(grep '^RATIO' "$DIR/compare.txt" | awk '{ printf "%s%s Hz %s vs %s, %s [%s, %s]", (NR > 1 ? "; " : ""), $2, $4, $3, $5, $6, $7 }')
	vs=$(grep '^VERDICT' "$DIR/compare.txt" | awk '{ printf "%s%s %s", (NR > 1 ? ", " : ""), $2, ($3 == "indistinguishable" ? "ok" : "DIFFERENT") }')
	basis="$np_tot paper + $nf_tot fast runs"
	if [ "$np_bad" != 0 ] || [ "$nf_bad" != 0 ]; then
		basis="$basis, NOT ALL USED: paper: $np_use; fast: $nf_use"
		[ "$nf_bad" != 0 ] && ALL_OK=0
	fi
	echo "Conclusion (d)"
	[ "$QUICK" = 1 ] && echo "    ACC_QUICK=1: $REPS replicates of $DUR s, a check of the pipeline, not an answer."
	if [ "$np_bad" != 0 ] && [ "$nf_bad" = 0 ]; then
		echo "    ring force: not decided: paper-preset runs failed ($basis)"
	elif [ "$ALL_OK" = 1 ]; then
		echo "    ring force: fast preset indistinguishable from paper ($vs; force ratio fast vs paper: $rat; $basis; ${SPEED}x cheaper)"
	else
		echo "    ring force: DIFFERENT ($vs; force ratio fast vs paper: $rat; $basis; ${SPEED}x cheaper)"
	fi
	echo
} >>"$REPORT"
[ -n "${ACC_REPORT:-}" ] || cat "$REPORT"
# claim 3's evidence row (scripts/preset_evidence.sh); a quick run's numbers are not evidence
if [ "$QUICK" != 1 ] && [ "$np_bad" = 0 ]; then
	bash "$REPO/scripts/preset_evidence.sh" set acc-d-ring "$([ "$ALL_OK" = 1 ] && echo indistinguishable || echo differ)" \
		"make bench-accuracy (d), $(date +%Y-%m-%d), $(git -C "$REPO" rev-parse --short HEAD 2>/dev/null)" \
		"claim 3's campaign with each preset ($basis): $vs; the with/without-intruder force ratio fast vs paper: $rat" ||
		die "cannot write docs/preset_evidence.tsv"
fi
if [ "$np_bad" != 0 ] || [ "$nf_bad" != 0 ]; then
	die "runs failed or were not usable (paper: $np_use; fast: $nf_use): see $REPORT"
fi
exit 0
