#!/usr/bin/env bash
# reproduce_quick.sh - the make reproduce pipeline on claim 4, cut down (REPRODUCE_QUICK:
# 2 replicates of 8 s runs): the campaign runs, the tools run on it, REPRODUCTION.md holds
# the claim's table, test and computed verdict, its figures exist, and a second call with
# nothing changed simulates nothing and writes the same numbers.
# tier: slow: the whole reproduction pipeline on a small campaign
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1
for b in study shake waiting figures; do
	[ -x "$REPO/bin/$b" ] || { fail setup "$REPO/bin/$b missing (make)"; finish; }
done
W=$TMP/w
run() { REPRODUCE_QUICK=1 REPRODUCE_CLAIMS=4 REPRODUCE_WORK=$W REPRODUCE_NICE=0 JOBS=2 bash "$REPO/scripts/reproduce.sh"; }
run >r1.out 2>r1.err || fail first.exit "exit $?: $(tail -n 3 r1.err)"
R=$W/REPRODUCTION.md
if [ ! -s "$R" ]; then
	fail first.written "no $R: $(tail -n 3 r1.err)"
	finish
fi
grep -q '^## Claim 4: the waiting time at 3.2 Hz' "$R" && ok claim4.section || fail claim4.section "$(head -n 20 "$R")"
# one row per radius ratio of the campaign (2, 2.5, 3, 3.5, 4), each with its runs counted
[ "$(grep -cE '^\| [234](\.[05])? \| 2 \| [0-2] \|' "$R")" = 5 ] && ok claim4.table_rows || fail claim4.table_rows "$(grep '^| [0-9]' "$R")"
grep -qE '^\*\*Verdict: (reproduced|partly|not reproduced|not decided)\*\* \([0-4] of 4 parts hold' "$R" && ok claim4.verdict || fail claim4.verdict "$(grep Verdict "$R")"
# its parts, each judged, and the integrator its runs used with the campaign's reason
[ "$(grep -cE '^\| 4[abcd] \| .* \| (holds|fails|opposite|open) \|$' "$R")" = 4 ] && ok claim4.parts ||
	fail claim4.parts "$(grep -E '^\| 4' "$R")"
grep -qE '^\*Integrator\* \(qr4_waiting\): preset fast \(verlet, Δt = 0.0002 s\)\. The campaign file on the preset: "fast[^"]*" Evidence \(docs/preset_evidence.tsv\): acc-c-wait32: indistinguishable \(.*, make bench-accuracy \(c\), [0-9-]+, [0-9a-f]+\)\.$' "$R" && ok claim4.integrator ||
	fail claim4.integrator "$(grep Integrator "$R")"
grep -qE 'Log-rank test .*p = [0-9.e-]+ \(one diameter\)' "$R" && ok claim4.logrank || fail claim4.logrank "$(grep Log-rank "$R")"
grep -q '10 runs: 10 done, 0 failed' "$R" && ok claim4.accounting || fail claim4.accounting "$(grep 'Runs:' "$R")"
grep -q '| this invocation | .* 10 runs simulated |' "$R" && ok first.counts_runs || fail first.counts_runs "$(grep invocation "$R")"
# the cost table's rates: the driver's measured ones (study/report/calib.c), not '?'
grep -qE 'fast preset [0-9.e+-]+ s, paper preset [0-9.e+-]+ s per step of 950 grains' "$R" && ok first.rates ||
	fail first.rates "$(grep 'per step' "$R")"
for f in claim4_km claim4_fig4; do
	[ -s "$W/figures/$f.png" ] && [ -s "$W/figures/$f.pdf" ] && grep -qF "](figures/$f.png)" "$R" && ok "figure.$f" ||
		fail "figure.$f" "$f.png/.pdf missing from $W/figures or not linked from REPRODUCTION.md"
done
# again, nothing changed: no simulation, the same numbers
sed -n '/^## Claim 4/,/^## What/p' "$R" >claim4.1
run >r2.out 2>r2.err || fail second.exit "exit $?: $(tail -n 3 r2.err)"
grep -q '| this invocation | .* 0 runs simulated |' "$R" && ok second.simulates_nothing || fail second.simulates_nothing "$(grep invocation "$R")"
sed -n '/^## Claim 4/,/^## What/p' "$R" >claim4.2
cmp -s claim4.1 claim4.2 && ok second.same_numbers || fail second.same_numbers "$(diff claim4.1 claim4.2 | head -n 4)"
# the rates still measured when every campaign is finished (the dry run that reads them is
# of a copy whose runs are all to do), and the campaign's cost a number, not '?'
grep -qE 'fast preset [0-9.e+-]+ s, paper preset [0-9.e+-]+ s per step of 950 grains' "$R" && ok second.rates ||
	fail second.rates "$(grep 'per step' "$R")"
grep -qE '^\| qr4_waiting \| 10 \| [0-9]+ \| [0-9]+ \|' "$R" && ! grep -q 'marked ?' "$R" && ok second.cost_known ||
	fail second.cost_known "$(grep -E '^\| qr4_waiting|marked' "$R")"
finish
