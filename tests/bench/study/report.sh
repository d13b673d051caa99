#!/usr/bin/env bash
# report.sh WORKDIR QUICK JOBS LOAD0 LOAD1 SECONDS - the report of tests/bench/study.sh from
# WORKDIR/costs.tsv and answers.tsv (what the runs of that invocation measured) and the
# shipped campaign files (what the full grids plan). Run by study.sh; can be run again on
# a finished work directory (bash tests/bench/study/report.sh build/bench-study).
set -uo pipefail
W=$1 QUICK=${2:-0} JOBS=${3:-2} LOAD0=${4:-?} LOAD1=${5:-?} SECS=${6:-?}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
COSTS=$W/costs.tsv ANS=$W/answers.tsv
[ -r "$COSTS" ] && [ -r "$ANS" ] || { echo "report.sh: no $COSTS / $ANS" >&2; exit 1; }

cpu=$(awk -F': *' '/^Model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || true)
[ -n "$cpu" ] || cpu=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo)
echo "# make bench-study$([ "$QUICK" = 1 ] && echo ' STUDY_QUICK=1') JOBS=$JOBS - $(date -u +%Y-%m-%dT%H:%MZ), $(hostname), $cpu, $(nproc) cores"
echo "# git $(git -C "$root" rev-parse --short HEAD 2>/dev/null)$(git -C "$root" diff --quiet HEAD -- core study analysis 2>/dev/null || echo ' (engine/driver/tools modified)'); load average before $LOAD0, after $LOAD1 (a shared machine: CPU seconds are what to compare, wall times move with the load); $SECS s in all"
[ "$QUICK" = 1 ] && echo "# STUDY_QUICK=1: short runs and few seeds - checks the pipeline; these are not the figures"
echo

# --- costs per question and way ---
awk -F'\t' -v ans="$ANS" '
	function fmt(x) { return x == "" ? "-" : sprintf("%.4g", x) }
	BEGIN {
		q[1] = "1 flux onset, no intruder"; q[2] = "2 mean flux mid-bed +-intruder"
		q[3] = "3 ring force +-intruder";  q[4] = "4 median wait per radius ratio"
		q[5] = "5 rise onset, one depth"
		while ((getline l < ans) > 0) {
			split(l, a, "\t"); if (a[1] == "claim") continue
			if (a[3] == "skip" || a[3] == "grid") { reps[a[1], a[3]] += a[8]; pts[a[1], a[3]]++ }
		}
	}
	NR > 1 { k = $1 SUBSEP $2; runs[k] += $4; sim[k] += $5; cpu[k] += $6; eng[k] += $7; wall[k] += $8; seen[$1] = 1 }
	END {
		printf "%-32s %-5s %6s %12s %10s %10s %9s %8s\n", "question", "way", "runs", "simulated s", "CPU s", "engine s", "wall s", "ratio"
		for (c = 1; c <= 5; c++) if (c in seen) {
			for (w = 0; w < 2; w++) {
				way = w ? "skip" : "grid"; k = c SUBSEP way
				if (!(k in runs)) { if (w) printf "%-32s %-5s %6s %12s %10s %10s %9s %8s\n", "", "skip", "-", "-", "-", "-", "-", "no way"; continue }
				r = ""
				if (w && (c SUBSEP "grid") in cpu && cpu[k] > 0) r = sprintf("%.1fx", cpu[c SUBSEP "grid"] / cpu[k])
				printf "%-32s %-5s %6d %12.0f %10.1f %10.1f %9.0f %8s\n", w ? "" : q[c], way, runs[k], sim[k], cpu[k], eng[k], wall[k], r
			}
		}
	}' "$COSTS"
echo
echo "ratio = grid CPU s / skip CPU s (user + system of study run: engines, settling, driver)."
echo "engine s = the engines' shaking loops (runs.wall_seconds) + the packing cache's settling."
echo

# --- answers side by side ---
echo "Answers [95 % interval] (n = replicates behind it):"
awk -F'\t' '
	function iv(e, lo, hi) { return sprintf("%s [%s, %s]", e == "" ? "none" : sprintf("%.4g", e), lo == "" ? "-inf" : sprintf("%.4g", lo), hi == "" ? "+inf" : sprintf("%.4g", hi)) }
	function lo_(x) { return x == "" ? -1e300 : x + 0 }
	function hi_(x) { return x == "" ? 1e300 : x + 0 }
	function wd(lo, hi) { return (lo == "" || hi == "") ? 1e300 : hi - lo }
	NR == 1 { next }
	{ c = $1; p = $2; w = $3; if (c == 1) p = "onset (Hz)"; if ($8 != "") $8 = sprintf("%d", $8)
	  key = c SUBSEP p SUBSEP w
	  E[key] = $4; L[key] = $5; H[key] = $6; N[key] = $8; S[key] = $9
	  if (!((c SUBSEP p) in havep)) { havep[c SUBSEP p] = 1; P[c, ++np[c]] = p } }
	END {
		printf "%-2s %-30s %-30s %-40s %-10s %s\n", "q", "point", "grid", "skip", "skip<=grid", "agree"
		for (c = 1; c <= 5; c++) {
			if (c == 5) continue
			for (i = 1; i <= np[c]; i++) {
				p = P[c, i]; g = c SUBSEP p SUBSEP "grid"; s = c SUBSEP p SUBSEP "skip"; so = c SUBSEP p SUBSEP "skip-onset"
				if (!(g in E) && !(s in E)) continue
				gs = (g in E) ? sprintf("%s n=%s", iv(E[g], L[g], H[g]), N[g]) : "-"
				ss = (s in E) ? sprintf("%s n=%s %s", iv(E[s], L[s], H[s]), N[s], S[s]) : "-"
				nar = ((g in E) && (s in E)) ? (wd(L[s], H[s]) <= wd(L[g], H[g]) * (1 + 1e-9) ? "yes" : "NO") : "-"
				ag = ((g in E) && (s in E)) ? ((lo_(L[s]) <= hi_(H[g]) && lo_(L[g]) <= hi_(H[s])) ? "yes" : "NO") : "-"
				printf "%-2s %-30s %-30s %-40s %-10s %s\n", c, p, gs, ss, nar, ag
				if (so in E)
					printf "%-2s %-30s %-30s %-40s %-10s %s\n", "", "  (bin/onset on skip runs)", "", sprintf("%s n=%s", iv(E[so], L[so], H[so]), N[so]), (wd(L[so], H[so]) <= wd(L[g], H[g]) * (1 + 1e-9) ? "yes" : "NO"), ((lo_(L[so]) <= hi_(H[g]) && lo_(L[g]) <= hi_(H[so])) ? "yes" : "NO")
			}
		}
		# claim 5: the grid gives the rise fraction per frequency (Clopper-Pearson); its onset
		# is where the fraction first reaches 1/2, and its interval runs between the nearest
		# frequencies on either side whose intervals exclude 1/2 (the tool intervals read
		# off, nothing estimated here)
		fl = ""; nf = 0
		for (i = 1; i <= np[5]; i++) {
			p = P[5, i]; g = 5 SUBSEP p SUBSEP "grid"
			if (!(g in E)) { sk = p; continue }
			f = p; sub(/.*frequency=/, "", f); sub(/ .*/, "", f)
			nf++; F[nf] = f + 0; FE[nf] = E[g]; FL[nf] = L[g]; FH[nf] = H[g]
			n5 = N[g]
		}
		if (nf || sk != "") {
			for (i = 1; i <= nf; i++) for (j = i + 1; j <= nf; j++) if (F[j] < F[i]) {
				t = F[i]; F[i] = F[j]; F[j] = t; t = FE[i]; FE[i] = FE[j]; FE[j] = t
				t = FL[i]; FL[i] = FL[j]; FL[j] = t; t = FH[i]; FH[i] = FH[j]; FH[j] = t }
			for (i = 1; i <= nf; i++) fl = fl sprintf(" %s:%.2f[%.2f,%.2f]", F[i], FE[i], FL[i], FH[i])
			on = 0; for (i = 1; i <= nf; i++) if (FE[i] >= 0.5) { on = i; break }
			top = on ? on : nf + 1
			glo = -1e300; for (i = top - 1; i >= 1; i--) if (FH[i] < 0.5) { glo = F[i]; break }
			ghi = 1e300;  for (i = (on ? on : nf + 1); i <= nf; i++) if (FL[i] > 0.5) { ghi = F[i]; break }
			if (nf == 0) gs = "-"
			else if (on == 0) gs = sprintf("above %.4g [%s, +inf] n=%s", F[nf], glo < -1e299 ? "-inf" : sprintf("%.4g", glo), n5)
			else gs = sprintf("%s %.4g [%s, %s] n=%s", on == 1 ? "<=" : "~", on == 1 ? F[1] : (F[on - 1] + F[on]) / 2,
			                  glo < -1e299 ? "-inf" : sprintf("%.4g", glo), ghi > 1e299 ? "+inf" : sprintf("%.4g", ghi), n5)
			s = 5 SUBSEP sk SUBSEP "skip"
			ss = (s in E) ? sprintf("%s n=%s %s", iv(E[s], L[s], H[s]), N[s], S[s]) : "-"
			nar = (s in E) && nf ? (wd(L[s], H[s]) <= (ghi - glo) * (1 + 1e-9) ? "yes" : "NO") : "-"
			ag = (s in E) && nf ? ((lo_(L[s]) <= ghi && glo <= hi_(H[s])) ? "yes" : "NO") : "-"
			printf "%-2s %-30s %-30s %-40s %-10s %s\n", 5, "onset of rise (Hz)", gs, ss, nar, ag
			if (nf) printf "   grid rise fraction per frequency [Clopper-Pearson]:%s\n", fl
			if (nf) print "   (claim 5, grid: the crossing of 1/2 between two grid frequencies, its interval between the nearest\n    frequencies whose rise-fraction interval excludes 1/2)"
		}
	}' "$ANS"
echo
echo "skip<=grid: the skip way's interval is at most as wide as the grid's (its target was the grid's width at the"
echo "point; NO = max_replicates reached first). agree: the two intervals overlap."
echo "Claim 1: grid = bin/onset --threshold 2 (threshold crossing of the mean flux, bootstrap over"
echo "seeds); skip = the search's median switch over replicates with its order-statistic interval;"
echo "the extra line is bin/onset on the search's own runs (the grid's statistic). Claims 2, 4: the"
echo "driver's mean_flux (Student t) and median_wait (Kaplan-Meier, order statistics) both ways."
echo "Claim 3: bin/ring's ratio of the ring force with/without the intruder (bootstrap) both ways;"
echo "n = the runs with the intruder (as many without)."
echo

# --- the full shipped grids, computed ---
rate() { # WAY PRESET-CLAIMS -> CPU s per simulated s over those claims' rows
	awk -F'\t' -v way="$1" -v cl=" $2 " 'NR > 1 && $2 == way && index(cl, " " $1 " ") { s += $5; c += $6 } END { if (s > 0) printf "%.6g", c / s }' "$COSTS"
}
RF=$(rate grid "1 2 4 5")
RP=$(rate grid "3")
RFS=$(rate skip "1 2 4 5")
planned() { # CAMPAIGN-FILE -> runs and simulated s it plans
	local f=$1 d
	d=$(awk -F'=' '/^[ \t]*duration[ \t]*=/ { gsub(/[ \t]|#.*/, "", $2); print $2; exit }' "$f")
	"$root/bin/study" expand "$f" 2>/dev/null | awk -F'\t' -v d="$d" '
		NR == 1 { for (i = 1; i <= NF; i++) if ($i == "duration") col = i; next }
		{ n++; s += col ? $col : d } END { printf "%d\t%.0f\n", n, s }'
}
echo "The full shipped grids (COMPUTED: the CPU s per simulated s measured above x the simulated"
echo "seconds each campaign file plans; fast rate $RF (grid runs of claims 1, 2, 4, 5), paper rate ${RP:-n/a} (claim 3)):"
printf '%-36s %6s %12s %16s %16s\n' "campaign" "runs" "simulated s" "CPU h, paper" "CPU h, fast"
tr=0 ts=0
for f in claim1_onset claim1_hysteresis claim2_rolls claim3_ring_force claim3_ring_none claim4_waiting_time claim5_depth; do
	[ -r "$root/campaigns/$f.campaign" ] || continue
	IFS=$'\t' read -r n s < <(planned "$root/campaigns/$f.campaign")
	tr=$((tr + n)) ts=$((ts + s))
	printf '%-36s %6d %12d %16s %16s\n' "$f" "$n" "$s" \
		"$([ -n "$RP" ] && awk "BEGIN { printf \"%.2f\", $s * $RP / 3600 }" || echo -)" \
		"$([ -n "$RF" ] && awk "BEGIN { printf \"%.2f\", $s * $RF / 3600 }" || echo -)"
done
printf '%-36s %6d %12d %16s %16s\n' "all" "$tr" "$ts" \
	"$([ -n "$RP" ] && awk "BEGIN { printf \"%.1f\", $ts * $RP / 3600 }" || echo -)" \
	"$([ -n "$RF" ] && awk "BEGIN { printf \"%.1f\", $ts * $RF / 3600 }" || echo -)"
echo

# --- all five questions at 16 replicates per point, the skip way, computed ---
echo "All five questions at 16 replicates per point the skip way (COMPUTED from this invocation's"
echo "skip runs: measured CPU s per replicate of a point or search group x 16 x the points or groups of"
echo "the full shipped question):"
awk -F'\t' -v costs="$COSTS" -v jobs="$JOBS" '
	BEGIN {
		while ((getline l < costs) > 0) { split(l, a, "\t"); if (a[2] == "skip") cpu[a[1]] += a[6] }
		full[1] = 1;  what[1] = "1 group (no intruder)"
		full[2] = 6;  what[2] = "6 points (2.6-3.0 Hz x R = 0, 4)"
		full[3] = 3;  what[3] = "3 frequencies (2.6-3.0 Hz), R = 0 and 4"
		full[4] = 12; what[4] = "12 points (R = 2 ... 8)"
		full[5] = 8;  what[5] = "8 groups (R = 3, 4 x depth 0 ... 3)"
	}
	NR > 1 && ($3 == "skip") { reps[$1] += $8 }
	END {
		tot = 0
		printf "%-6s %-42s %12s %14s\n", "claim", "full question", "CPU s/rep", "CPU s at 16"
		for (c = 1; c <= 5; c++) {
			if (!(c in cpu) || reps[c] == 0) { printf "%-6s %-42s %12s %14s\n", c, what[c], "-", "not run"; miss = 1; continue }
			per = cpu[c] / reps[c]; x = per * 16 * full[c]; tot += x
			printf "%-6s %-42s %12.1f %14.0f\n", c, what[c], per, x
		}
		printf "%-6s %-42s %12s %14.0f  = %.1f CPU h, %.0f min wall on %d cores if they stay busy%s\n", "all", "", "", tot, tot / 3600, tot / 60 / jobs, jobs, miss ? " (claims not run left out)" : ""
	}' "$ANS"
echo "(CPU s/rep is what the subset measured: claim 1 over its range, claim 2 at 2.8 Hz, claim 3 at 2.8 Hz (both"
echo "systems), claim 4 the mean of its"
echo "ratios, claim 5 its group and search - a full question has ranges, frequencies and groups that cost more"
echo "or less per replicate. Claim 1's hysteresis ramps - no skip way - are not among these five questions.)"
