#!/usr/bin/env bash
# verdicts.sh - every part of every claim's verdict (scripts/verdicts.sh) on synthetic
# databases whose right answer is known: one where the paper's statement holds, one
# where it fails, and one where the data show the opposite (where a part has a
# direction). Seconds; no engine run.
. "$(dirname "$0")/lib.sh"
. "$REPO/scripts/verdicts.sh"
cd "$TMP" || exit 1

# a fresh database with the tables the rules read; the analysis table has the key
# columns the tools add for their grouping keys
newdb() {
	VDB=$TMP/$1.db
	rm -f "$VDB"
	sqlite3 "$VDB" "CREATE TABLE analysis(campaign TEXT, tool TEXT, version TEXT, grp TEXT, key TEXT, value REAL,
		lo REAL, hi REAL, n INTEGER, created TEXT, frequency REAL, radius_ratio REAL, depth REAL, sides TEXT,
		PRIMARY KEY (campaign, tool, grp, key));
		CREATE TABLE onset_group(campaign TEXT, grp TEXT, point INTEGER, replicates INTEGER, searching INTEGER,
		found INTEGER, below INTEGER, above INTEGER, blocked INTEGER, nonmonotone INTEGER, runs INTEGER,
		estimate REAL, ci_lo REAL, ci_hi REAL, width REAL, state TEXT);
		CREATE TABLE onset_replicate(campaign TEXT, grp TEXT, replicate INTEGER, state TEXT, lo REAL, hi REAL,
		lo_run INTEGER, hi_run INTEGER, next REAL, runs INTEGER, nonmonotone INTEGER)"
}
# row CAMPAIGN TOOL KEY VALUE LO HI [frequency radius_ratio depth]
row() {
	local g="f=${7:-} r=${8:-} d=${9:-}"
	sqlite3 "$VDB" "INSERT INTO analysis(campaign, tool, grp, key, value, lo, hi, n, frequency, radius_ratio, depth)
		VALUES ('$1', '$2', '$g', '$3', ${4:-NULL}, ${5:-NULL}, ${6:-NULL}, 16, ${7:-NULL}, ${8:-NULL}, ${9:-NULL})"
}
# state PART: the state the last verdict gave that part; claim: its verdict
state() { awk -F'\t' -v p="$1" '$1 == "part" && $2 == p { print $3 }' "$TMP/out"; }
claim() { awk -F'\t' '$1 == "claim" { print $2 }' "$TMP/out"; }
expect() { # ID PART STATE
	local got
	got=$(state "$2")
	[ "$got" = "$3" ] && ok "$1" || fail "$1" "part $2: expected $3, got '${got}': $(grep -P "^part\t$2\t" "$TMP/out")"
}

# ---- claim 1 ------------------------------------------------------------------------------
reps() { # SPREAD: 8 replicates' brackets of width 0.02 around 2.7 + k SPREAD
	local k
	for k in 0 1 2 3 4 5 6 7; do
		sqlite3 "$VDB" "INSERT INTO onset_replicate(campaign, grp, replicate, state, lo, hi) VALUES
			('on', 'all', $k, 'found', 2.69 + $k * $1, 2.71 + $k * $1)"
	done
}
c1() { verdict_claim1 on up 258 "$1" "$2" | verdict_combine >"$TMP/out"; }
newdb c1h; reps 0.005; row up hysteresis diff_threshold 0.01 -0.01 0.03; c1 up 258
expect verdicts.c1.sharp_holds 1a holds; expect verdicts.c1.no_hysteresis_holds 1b holds
[ "$(claim)" = reproduced ] && ok verdicts.c1.reproduced || fail verdicts.c1.reproduced "$(claim)"
# spread 0.02 per replicate: sd 0.049 (holds, just); 0.03: 0.073 (fails)
newdb c1s; reps 0.02; c1 up 258; expect verdicts.c1.sd_just_below 1a holds
newdb c1f; reps 0.03; row up hysteresis diff_threshold 0.05 0.03 0.07; c1 up 258
expect verdicts.c1.sharp_fails 1a fails; expect verdicts.c1.hysteresis_fails 1b fails
[ "$(claim)" = "not reproduced" ] && ok verdicts.c1.not_reproduced || fail verdicts.c1.not_reproduced "$(claim)"
# the branches differ the other way (down above up): not the paper's either
newdb c1o; reps 0; row up hysteresis diff_threshold -0.05 -0.07 -0.03; c1 up 258
expect verdicts.c1.down_above_up_fails 1b fails
[ "$(claim)" = partly ] && ok verdicts.c1.partly || fail verdicts.c1.partly "$(claim)"
# a split at 258 s that halves at 516 s is a lag, not hysteresis; one that stays is not
newdb c1l; reps 0; row up hysteresis diff_threshold 0.04 0.03 0.05; row slow hysteresis diff_threshold 0.02 0.012 0.028
c1 slow 516; expect verdicts.c1.lag_holds 1b holds
newdb c1k; reps 0; row up hysteresis diff_threshold 0.04 0.03 0.05; row slow hysteresis diff_threshold 0.04 0.032 0.048
c1 slow 516; expect verdicts.c1.hysteresis_stays_fails 1b fails
newdb c1n; c1 up 258; expect verdicts.c1.nothing_open 1a open; expect verdicts.c1.nothing_open_b 1b open
[ "$(claim)" = "not decided" ] && ok verdicts.c1.not_decided || fail verdicts.c1.not_decided "$(claim)"

# ---- claim 2 ------------------------------------------------------------------------------
phicsv() { # PHI_LOW_0 PHI_LOW_4: 4 runs per bed at 2.6 Hz with Phi = x +- 0.1
	{ echo 'group,run,frequency,radius_ratio,phi'
	  for d in -0.1 0 0.1 0; do echo "g,r,2.6,0,$(awk -v a="$1" -v d="$d" 'BEGIN { print a + d }')"
		  echo "g,r,2.6,4,$(awk -v a="$2" -v d="$d" 'BEGIN { print a + d }')"; done; } >"$TMP/phi.csv"
}
c2() { verdict_claim2 r2 "$TMP/phi.csv" 2 2.6 2.8 3.0 | verdict_combine >"$TMP/out"; }
newdb c2h; phicsv 0.2 0.3; row r2 rolls reach_diff 1 0.3 1.7 2.8 4; row r2 rolls reach_diff 0.2 -0.3 0.7 3.0 4; c2
expect verdicts.c2.fluctuate_holds 2a holds; expect verdicts.c2.deeper_holds 2b holds; expect verdicts.c2.alike_holds 2c holds
[ "$(claim)" = reproduced ] && ok verdicts.c2.reproduced || fail verdicts.c2.reproduced "$(claim)"
newdb c2f; phicsv 0.2 5; row r2 rolls reach_diff 0.2 -0.5 0.9 2.8 4; row r2 rolls reach_diff 0.6 0.2 1.1 3.0 4; c2
expect verdicts.c2.intruder_bed_convects_fails 2a fails; expect verdicts.c2.not_deeper_fails 2b fails
expect verdicts.c2.not_alike_fails 2c fails
newdb c2o; phicsv 0.2 0.3; row r2 rolls reach_diff -1 -1.7 -0.3 2.8 4; c2
expect verdicts.c2.shallower_opposite 2b opposite; expect verdicts.c2.missing_open 2c open
# a mean whose interval straddles the threshold decides nothing
newdb c2u; phicsv 1.95 0.3; c2; expect verdicts.c2.straddle_open 2a open

# ---- claim 3 ------------------------------------------------------------------------------
c3() { verdict_claim3 r3 2.8 2.6 | verdict_combine >"$TMP/out"; }
newdb c3h; row r3 ring ratio_force 1.14 1.1 1.18 2.8 4; row r3 ring ratio_force 1.05 1.02 1.08 2.6 4
row r3 ring ratio_temperature 1.01 0.95 1.07 2.8 4; c3
for p in 3a 3b 3c 3d; do expect "verdicts.c3.holds_$p" $p holds; done
[ "$(claim)" = reproduced ] && ok verdicts.c3.reproduced || fail verdicts.c3.reproduced "$(claim)"
newdb c3f; row r3 ring ratio_force 1.02 0.99 1.05 2.8 4; row r3 ring ratio_force 1.2 1.15 1.25 2.6 4
row r3 ring ratio_temperature 1.3 1.2 1.4 2.8 4; c3
for p in 3a 3b 3c 3d; do expect "verdicts.c3.fails_$p" $p fails; done
[ "$(claim)" = "not reproduced" ] && ok verdicts.c3.not_reproduced || fail verdicts.c3.not_reproduced "$(claim)"
newdb c3o; row r3 ring ratio_force 0.9 0.85 0.95 2.8 4; row r3 ring ratio_force 0.9 0.85 0.95 2.6 4
row r3 ring ratio_temperature 1 0.7 1.4 2.8 4; c3
expect verdicts.c3.smaller_opposite 3a opposite; expect verdicts.c3.smaller_opposite_b 3b opposite
expect verdicts.c3.smaller_opposite_c 3c opposite; expect verdicts.c3.wide_temperature_open 3d open
# the fast preset's 2.8 Hz ratio (1.048 [1.019, 1.080]): larger, but not by 15 %
newdb c3p; row r3 ring ratio_force 1.048 1.019 1.080 2.8 4; c3
expect verdicts.c3.fast_larger 3a holds; expect verdicts.c3.fast_not_15 3b fails

# ---- claim 4 ------------------------------------------------------------------------------
c4() { verdict_claim4 r4 "${1:-}" | verdict_combine >"$TMP/out"; }
waits() { # MEDIAN LO HI for R = 2, 3 and R4_MEDIAN R4_LO R4_HI
	row r4 waiting median "$1" "$2" "$3" "" 2; row r4 waiting median "$1" "$2" "$3" "" 3
	row r4 waiting median "$4" "$5" "$6" "" 4
}
newdb c4h; waits 30 22 41 1.2 0.8 2.1; row q5 whale risen 10; row q5 whale with_period 8; c4 q5
for p in 4a 4b 4c 4d; do expect "verdicts.c4.holds_$p" $p holds; done
[ "$(claim)" = reproduced ] && ok verdicts.c4.reproduced || fail verdicts.c4.reproduced "$(claim)"
newdb c4f; waits 30 22 41 18 12 29; row r4 waiting median 120 100 150 "" 3.5; row q5 whale risen 10; row q5 whale with_period 2; c4 q5
expect verdicts.c4.r4_waits_fails 4a fails; expect verdicts.c4.too_long_fails 4b fails
expect verdicts.c4.depends_fails 4c fails; expect verdicts.c4.no_whale_fails 4d fails
# the median of R = 4 not reached within the runs: it did not rise at once
newdb c4n; waits 30 22 41 "" "" ""; row r4 waiting median 150 "" "" "" 4 2>/dev/null
sqlite3 "$VDB" "UPDATE analysis SET value = NULL WHERE radius_ratio = 4"; c4
expect verdicts.c4.r4_never_open 4a open; expect verdicts.c4.whale_not_run_open 4d open
newdb c4w; waits 30 22 41 6 4 9; c4; expect verdicts.c4.r4_straddles_open 4a open
# medians never reached within 180 s runs: R = 4 did not rise at once, R < 4 waited longer than 90 s
newdb c4t; waits 30 22 41 "" "" ""; sqlite3 "$VDB" "UPDATE analysis SET value = NULL WHERE radius_ratio IN (3, 4)"
row r4 waiting t_max 180 "" "" "" 4; row r4 waiting t_max 180 "" "" "" 3; c4
expect verdicts.c4.r4_censored_fails 4a fails; expect verdicts.c4.censored_long_fails 4b fails

# ---- claim 5 ------------------------------------------------------------------------------
# bin/waiting's rows under the higher start's group: lower_fraction_diff (lower − this),
# lower_fisher_p, lower_risen
pair() { # F DEPTH DIFF P LOWER_RISEN
	row r5 waiting lower_fraction_diff "$3" "" "" "$1" 4 "$2"; row r5 waiting lower_fisher_p "$4" "" "" "$1" 4 "$2"
	row r5 waiting lower_risen "$5" "" "" "$1" 4 "$2"
}
c5() { verdict_claim5 r5 | verdict_combine >"$TMP/out"; }
# the committed report's 2.7 Hz numbers: 13/16 at depth 1, 4/16 one row lower (depth 0)
newdb c5h; pair 2.7 1 -0.5625 0.0034 4; pair 2.7 2 -0.0625 1 13; c5
expect verdicts.c5.lower_rises_less_holds 5a holds; expect verdicts.c5.not_altogether 5b fails
[ "$(claim)" = partly ] && ok verdicts.c5.partly || fail verdicts.c5.partly "$(claim)"
newdb c5a; pair 2.7 1 -0.6 0.001 0; c5; expect verdicts.c5.altogether_holds 5b holds
[ "$(claim)" = reproduced ] && ok verdicts.c5.reproduced || fail verdicts.c5.reproduced "$(claim)"
newdb c5f; pair 2.7 1 -0.1 0.7 9; pair 2.75 1 0.05 1 15; c5; expect verdicts.c5.no_difference_fails 5a fails
newdb c5o; pair 2.7 1 0.5 0.003 12; c5; expect verdicts.c5.lower_rises_more_opposite 5a opposite
newdb c5n; c5; expect verdicts.c5.nothing_open 5a open
# the old reading (depth + 1 as "one row lower") gave the opposite on these numbers: the
# rule takes the direction from bin/waiting's rows alone
grep -q 'depth *[-+] *1' "$REPO/scripts/verdicts.sh" && fail verdicts.c5.direction_in_one_place \
	"scripts/verdicts.sh restates the depth direction" || ok verdicts.c5.direction_in_one_place

# ---- the open questions ----------------------------------------------------------------------
answer() { awk -F'\t' '$1 == "answer" { print $2 }' "$TMP/out"; }
expect_answer() { # ID WORD
	local got
	got=$(answer)
	[ "$got" = "$2" ] && ok "$1" || fail "$1" "expected $2, got '$got': $(cat "$TMP/out")"
}
# q1: rows Y f lo hi Gamma Gamma_lo Gamma_hi f_el, softest first
printf '3e6 2.68 2.65 2.69 0.58 0.57 0.59 9\n3e8 4.5 4.4 4.6 1.6 1.55 1.7 90\n' >q1.dat
answer_q1 q1.dat 2 2 >"$TMP/out"; expect_answer verdicts.q1.yes yes
printf '3e6 2.68 2.65 2.69 0.58 0.57 0.59 9\n3e8 3 2.9 3.1 0.72 0.68 0.77 90\n' >q1.dat
answer_q1 q1.dat 2 2 >"$TMP/out"; expect_answer verdicts.q1.part part
printf '3e6 2.68 2.65 2.69 0.58 0.57 0.59 9\n3e8 2.6 2.5 2.7 0.54 0.5 0.59 90\n' >q1.dat
answer_q1 q1.dat 2 2 >"$TMP/out"; expect_answer verdicts.q1.no no
answer_q1 q1.dat 1 2 >"$TMP/out"; expect_answer verdicts.q1.running running
# an onset above the searched range: Gamma "-", its lower bound above 1
printf '3e6 2.68 2.65 2.69 0.58 0.57 0.59 9\n3e8 - 6 - - 1.2 - 90\n' >q1.dat
answer_q1 q1.dat 2 2 >"$TMP/out"; expect_answer verdicts.q1.above_range_yes yes
# q2: onset intervals per width
og() { sqlite3 "$VDB" "INSERT INTO onset_group(campaign, grp, point, estimate, ci_lo, ci_hi, state) VALUES ('q2', '$1', $2, $3, $4, $5, '${6:-done}')"; }
newdb q2d; og width=40 0 2.6 2.55 2.63; og width=160 1 2.75 2.7 2.8; answer_q2 q2 >"$TMP/out"; expect_answer verdicts.q2.depends depends
newdb q2n; og width=40 0 2.6 2.55 2.7; og width=160 1 2.65 2.6 2.7; answer_q2 q2 >"$TMP/out"; expect_answer verdicts.q2.no no
newdb q2r; og width=40 0 2.6 2.55 2.7; og width=160 1 2.65 2.6 2.7 searching; answer_q2 q2 >"$TMP/out"; expect_answer verdicts.q2.running running
# q3: persistence C per side and frequency
pc() { sqlite3 "$VDB" "INSERT INTO analysis(campaign, tool, grp, key, value, lo, hi, frequency, sides)
	VALUES ('q3', 'convect', 's=$1 f=$2', 'persistence_c', $3, $4, $5, $2, '$1')"; }
newdb q3y; pc walls 3 1 0.5 1.5; pc periodic 3 0.5 0.1 0.9; answer_q3 q3 >"$TMP/out"; expect_answer verdicts.q3.yes yes
newdb q3n; pc walls 3 1 0.5 1.5; pc periodic 3 0.1 -0.2 0.4; answer_q3 q3 >"$TMP/out"; expect_answer verdicts.q3.no no
newdb q3z; pc walls 3 0.1 -0.1 0.3; pc periodic 3 0.1 -0.2 0.4; answer_q3 q3 >"$TMP/out"; expect_answer verdicts.q3.none none
# q4: fraction risen per R
newdb q4a; row q4 waiting fraction_risen 1 "" "" "" 4; row q4 waiting fraction_risen 1 "" "" "" 8
answer_q4 q4 >"$TMP/out"; expect_answer verdicts.q4.none_critical none_critical
newdb q4s; row q4 waiting fraction_risen 0.5 "" "" "" 4; row q4 waiting fraction_risen 1 "" "" "" 8
answer_q4 q4 >"$TMP/out"; expect_answer verdicts.q4.some_stay some_stay
# q5: the depth's trend with R
tr5() { row q5 whale trend_depth_rho "$1"; sqlite3 "$VDB" "INSERT INTO analysis(campaign, tool, grp, key, value) VALUES ('q5', 'whale', 'f= r= d=', 'trend_depth_p', $2)"; }
newdb q5d; tr5 -0.6 0.001; answer_q5 q5 >"$TMP/out"; expect_answer verdicts.q5.decreases decreases
newdb q5i; tr5 0.6 0.001; answer_q5 q5 >"$TMP/out"; expect_answer verdicts.q5.increases increases
newdb q5n; tr5 -0.1 0.6; answer_q5 q5 >"$TMP/out"; expect_answer verdicts.q5.no_trend no_trend
newdb q5o; answer_q5 q5 >"$TMP/out"; expect_answer verdicts.q5.open open
# q6: the onset in Gamma against 1, the fraction risen against 1/2
q6() { # STATE EST LO HI FRAC FLO FHI
	sqlite3 "$VDB" "INSERT INTO onset_group(campaign, grp, point, estimate, ci_lo, ci_hi, state) VALUES ('q6o', 'all', 0, $2, $3, $4, '$1')"
	[ -z "$5" ] || { row q6r waiting fraction_risen "$5" "$6" "$7"; row q6r waiting risen "$(awk -v f="$5" 'BEGIN { print int(16 * f + 0.5) }')"; }
}
newdb q6a; q6 done 0.62 0.6 0.65 0.81 0.54 0.96; answer_q6 q6o q6r >"$TMP/out"; expect_answer verdicts.q6.below1_rises below1_rises
newdb q6b; q6 done 1.2 1.1 1.3 0.12 0.02 0.38; answer_q6 q6o q6r >"$TMP/out"; expect_answer verdicts.q6.above1_stays above1_stays
newdb q6c; q6 done 0.98 0.9 1.05 0.5 0.25 0.75; answer_q6 q6o q6r >"$TMP/out"; expect_answer verdicts.q6.at1_undecided at1_undecided
newdb q6d; q6 searching 0.98 0.9 1.05 0.5 0.25 0.75; answer_q6 q6o q6r >"$TMP/out"; expect_answer verdicts.q6.running_search running
newdb q6e; q6 done 0.62 0.6 0.65 "" "" ""; answer_q6 q6o q6r >"$TMP/out"; expect_answer verdicts.q6.running_rise running
# the sentence carries the numbers it rests on
newdb q6f; q6 done 0.62 0.6 0.65 0.81 0.54 0.96; answer_q6 q6o q6r >"$TMP/out"
grep -q 'Γ = 0.62 \[0.6, 0.65\]: below Γ = 1.* rose in 13 of 16 beds (fraction 0.81 \[0.54, 0.96\]): it still rises' "$TMP/out" &&
	ok verdicts.q6.sentence || fail verdicts.q6.sentence "$(cat "$TMP/out")"

# ---- one list of parts: docs/model.md's table names exactly the parts the rules judge ----------
doc=$(grep -oE '^\| [0-9][a-z] \|' "$REPO/docs/model.md" | tr -d '| ' | sort | tr '\n' ' ')
code=$(grep -oE 'vpart [0-9][a-z] ' "$REPO/scripts/verdicts.sh" | cut -d' ' -f2 | sort -u | tr '\n' ' ')
[ -n "$doc" ] && [ "$doc" = "$code" ] && ok verdicts.parts_documented || fail verdicts.parts_documented "docs/model.md: $doc; scripts/verdicts.sh: $code"

# ---- the claim line ---------------------------------------------------------------------------
printf 'part\ta\tholds\tx\ty\npart\tb\topposite\tx\ty\n' | verdict_combine >"$TMP/out"
[ "$(claim)" = partly ] && grep -q $'1 of 2 parts hold; b opposite' "$TMP/out" && ok verdicts.combine.counts ||
	fail verdicts.combine.counts "$(cat "$TMP/out")"
finish
