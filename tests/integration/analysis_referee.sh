#!/usr/bin/env bash
# analysis_referee.sh - the statistics a referee asks for (issue #16 point 3), end to end
# on tiny campaigns run by bin/study: bin/rolls (the roll reach per run, its difference
# with - without intruder with Welch intervals, line by line too; the numbers against
# the per-run CSV, a smaller --fraction never raising a run's roll bottom), onset
# --sensitivity (every band and trimmed range, the spread, the main row equal to the
# main estimate), waiting's second definition (the fraction of the way to the surface,
# recomputed here from the trajectory with h5dump + awk; runs stopped by stop = risen
# censored and counted; runs without a trajectory counted, not used; its own log-rank
# test), and Fig. 4 with every replicate and the median run highlighted. Each output:
# CSV, stored rows, PNG and PDF, nothing on stderr.
# The campaigns are run by the release engine (lib.sh's data_driver_setup: the tools are
# what is tested).
# tier: slow: campaigns that the referee checks must pass and fail
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
data_driver_setup
cd "$TMP" || exit 1
fig_ok() { [ -s "$1.png" ] && [ "$(head -c 4 "$1.png" | od -An -c | tr -d ' ')" = '211PNG' ] && [ "$(head -c 5 "$1.pdf")" = '%PDF-' ]; }

SCENE="$(tiny_scene radius_ratio=-)
amplitude = 1"
# with and without intruder at three frequencies, three seeds: rolls, onset, figures
printf '[campaign]\nname = t\nseed = 3\nreplicates = 3\n[scene]\n%s\nflux = yes\ntraj_rate = 100\nduration = 2\n[grid]\nradius_ratio = 0, 2\nfrequency = 3, 5, 7\n' "$SCENE" >t.campaign
# waiting: runs stopped 0.05 s after the engine's rise, and runs without a trajectory
printf '[campaign]\nname = w\nseed = 5\nreplicates = 3\n[scene]\n%s\nradius_ratio = 2\nfrequency = 7\nduration = 2\nstop = risen\nstop_after = 0.05\n[grid]\ntraj_rate = 0, 100\n' "$SCENE" >w.campaign
t0=$SECONDS
for c in t w; do
	"$DATA_STUDY" run $c.campaign --runs "$TMP/R" --jobs 2 --no-progress >study_$c.log 2>&1 ||
		{ fail setup.campaigns "study $c: $(tail -c 300 study_$c.log)"; finish; }
done
echo "# campaigns: $((SECONDS - t0)) s"
A=R/t/analysis W=R/w/analysis

# ---- rolls ----
tool_quiet rolls rolls t --runs=R
R1=$A/rolls_runs.csv
[ "$(tail -n +2 $R1 | wc -l)" = 18 ] && [ "$(tail -n +2 $A/rolls_diff.csv | wc -l)" = 3 ] &&
	[ "$(tail -n +2 $A/rolls_profile.csv | wc -l)" = 240 ] && [ "$(tail -n +2 $A/rolls_summary.csv | wc -l)" = 6 ] &&
	[ -s $A/rolls_accounting.csv ] && ok rolls.csv || fail rolls.csv "$(ls $A; cat rolls.out)"
# reach = surface - roll bottom, the bottom within the bed, on every run
awk -F, -v s="$(csv_col $R1 surface)" -v b="$(csv_col $R1 roll_bottom)" -v r="$(csv_col $R1 reach)" 'NR > 1 {
	d = $s - $b - $r; if (d < -1e-9 || d > 1e-9 || $b < 0 || $b > $s) bad = 1 } END { exit bad }' $R1 &&
	ok rolls.reach_is_surface_minus_bottom || fail rolls.reach_is_surface_minus_bottom "$(head -n 3 $R1)"
# the stored difference is mean(with) - mean(without) of the per-run reaches, inside its interval
bad=0
for f in 3 5 7; do
	want=$(awk -F, -v r="$(csv_col $R1 reach)" -v f=$f -v fc="$(csv_col $R1 frequency)" -v rc="$(csv_col $R1 radius_ratio)" '
		NR > 1 && $fc == f { if ($rc > 0) { a += $r; na++ } else { b += $r; nb++ } }
		END { printf "%.12g", a / na - b / nb }' $R1)
	got=$(q R/study.db "SELECT printf('%.12g', value) || ' ' || (lo <= value AND value <= hi) || ' ' || n FROM analysis
		WHERE campaign = 't' AND tool = 'rolls' AND key = 'reach_diff' AND frequency = $f AND radius_ratio = 2")
	awk -v w="$want" -v g="${got%% *}" 'BEGIN { d = w - g; exit !(d < 1e-9 && d > -1e-9) }' && [ "${got#* }" = "1 6" ] ||
		{ bad=1; echo "# $f Hz: want $want, stored '$got'"; }
done
[ "$bad" = 0 ] && ok rolls.diff_of_means_in_interval || fail rolls.diff_of_means_in_interval "see above"
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 't' AND tool = 'rolls' AND key = 'reach' AND n = 3")" = 6 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE tool = 'rolls' AND grp LIKE '% vs no intruder' AND key IN
		('reach_diff', 'roll_bottom_diff', 'lines_differ', 'runs_with', 'runs_without')")" = 15 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE tool = 'rolls' AND key = 'runs_failed'")" = 6 ] &&
	ok rolls.db_rows || fail rolls.db_rows "$(q R/study.db "SELECT grp, key, value FROM analysis WHERE tool = 'rolls'" | head)"
grep -q '^with intruder - without' rolls.out && grep -q 'Welch intervals at 95 %' rolls.out && grep -q '^# runs: 18 ' rolls.out &&
	ok rolls.table || fail rolls.table "$(cat rolls.out)"
fig_ok $A/rolls && grep -q "title 'no intruder'" $A/rolls.gp && grep -q "title '𝓡 = 2'" $A/rolls.gp &&
	grep -q "title 'with − without intruder'" $A/rolls.gp && grep -q 'filledcurves' $A/rolls.gp &&
	ok rolls.figure || fail rolls.figure "$(ls $A)"
# a lower fraction of the maximum can only move a run's roll bottom down (or leave it)
cp $R1 rolls_half.csv
tool_quiet rolls_quarter rolls t --runs R --fraction=0.25 --no-store --no-plot --out "$TMP/q"
paste -d, rolls_half.csv q/rolls_runs.csv | awk -F, -v b="$(csv_col $R1 roll_bottom)" -v n="$(head -n 1 $R1 | tr ',' '\n' | wc -l)" '
	NR > 1 && $(n + b) > $b + 1e-9 { bad = 1 } END { exit bad }' && ok rolls.fraction_monotone ||
	fail rolls.fraction_monotone "a bottom rose with --fraction 0.25"
# each part on its own: the help names the option, a misspelling is named, and a
# fraction out of range is refused with exit 1 (a ';' here once cut the chain)
"$BINDIR/rolls" --help | grep -q -- '--fraction Q' && ok rolls.options.help || fail rolls.options.help "no --fraction Q in --help"
"$BINDIR/rolls" t --runs R --fractoin 0.3 2>&1 | grep -q 'did you mean --fraction' && ok rolls.options.misspelt ||
	fail rolls.options.misspelt "--fractoin not named"
"$BINDIR/rolls" t --runs R --fraction 2 >"$TMP/rf.out" 2>&1
rc=$?
[ "$rc" = 1 ] && grep -q 'fraction' "$TMP/rf.out" && ok rolls.options.range ||
	fail rolls.options.range "--fraction 2: exit $rc, $(head -c 200 "$TMP/rf.out")"

# ---- onset --sensitivity ----
tool_quiet sens onset t --runs R --boot 40 --sensitivity
S=$A/onset_sensitivity.csv
[ "$(tail -n +2 $S | wc -l)" = 12 ] && [ "$(cut -d, -f3 $S | sort -u | tr '\n' ' ')" = "band_0.2_0.4 band_0.4_0.6 band_0.6_0.8 main no_highest_f no_lowest_f variant " ] &&
	ok sens.csv_variants || fail sens.csv_variants "$(cut -d, -f2,3 $S)"
# the main row is the main estimate; the trimmed ranges leave out one frequency's runs
awk -F, 'FNR == 1 { next } FILENAME ~ /summary/ { thr[$1] = $11; next } $3 == "main" && thr[$2] != $9 { bad = 1 }
	$3 ~ /^no_/ && $8 != 6 { bad = 1 } $3 ~ /^band/ && $8 != 9 { bad = 1 } END { exit bad }' $A/onset_summary.csv $S &&
	ok sens.main_and_runs || fail sens.main_and_runs "$(cat $S)"
[ "$(grep -c 'spread over the 6 variants: threshold f' sens.out)" = 2 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE tool = 'onset' AND key IN ('sens_spread_threshold_f', 'sens_spread_sigmoid_f0')")" = 4 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE tool = 'onset' AND key GLOB 'sens_threshold_f_*'")" = 10 ] &&
	ok sens.table_rows || fail sens.table_rows "$(grep spread sens.out)"
"$BINDIR/onset" t --runs R --sensitivity=1 2>&1 | grep -q 'takes no value' && ok sens.flag || fail sens.flag "accepted a value"

# ---- waiting: the second definition ----
tool_quiet way waiting w --runs R
V=$W/waiting_way_runs.csv
[ "$(tail -n +2 $V | wc -l)" = 6 ] && [ -s $W/waiting_way_km.csv ] && [ "$(tail -n +2 $W/waiting_way_summary.csv | wc -l)" = 2 ] &&
	fig_ok $W/waiting_way && ok way.outputs || fail way.outputs "$(ls $W)"
# without a trajectory: counted, not used
[ "$(awk -F, '$2 == "\"radius_ratio=2 traj_rate=0\"" && $10 == "no"' $V | wc -l)" = 3 ] &&
	[ "$(q R/study.db "SELECT value || ' ' || n FROM analysis WHERE tool = 'waiting' AND traj_rate = 0 AND key = 'way_no_trajectory'")" = "3.0 3" ] &&
	[ "$(q R/study.db "SELECT value FROM analysis WHERE tool = 'waiting' AND traj_rate = 0 AND key = 'way_runs'")" = 0.0 ] &&
	ok way.no_trajectory_counted || fail way.no_trajectory_counted "$(cat $V)"
# every trajectory's time recomputed from the file: box frame y - A sin(2 pi f t), half
# the way from intruder_settled_y to surface_height, interpolated; else censored at the last sample
bad=0 stopc=0
while IFS=, read -r gi g id rep seed wt rs wy wr tr use; do
	[ "$tr" = yes ] || continue
	f=R/w/$id.h5
	want=$(h5traj "$f" | awk -v y0="$(attr "$f" /intruder_settled_y)" -v hs="$(attr "$f" /surface_height)" -v A=1 -v fr=7 '
		BEGIN { pi = atan2(0, -1); lev = y0 + 0.5 * (hs - y0) }
		{ y = $3 - A * sin(2 * pi * fr * $1) }
		y >= lev && !done { if (NR == 1 || y <= py) print $1 " 1"; else print pt + ($1 - pt) * (lev - py) / (y - py) " 1"; done = 1 }
		{ pt = $1; py = y } END { if (!done) print pt " 0" }')
	awk -v a="${want% *}" -v b="$wy" 'BEGIN { d = a - b; exit !(d < 1e-6 && d > -1e-6) }' && [ "${want#* }" = "$wr" ] ||
		{ bad=1; echo "# $id: csv $wy $wr, recomputed $want"; }
	[ "$wr" = 0 ] && [ "$(attr "$f" /stopped_by)" = risen ] && stopc=$((stopc + 1))
done < <(tail -n +2 $V)
[ "$bad" = 0 ] && ok way.times_from_trajectory || fail way.times_from_trajectory "see above"
[ "$(q R/study.db "SELECT CAST(value AS INTEGER) FROM analysis WHERE tool = 'waiting' AND traj_rate = 100 AND key = 'way_stop_censored'")" = "$stopc" ] &&
	{ [ "$stopc" = 0 ] || grep -q "^# $stopc runs\? stopped by stop = risen .* censored at their end" way.out; } &&
	ok way.stop_censored_counted || fail way.stop_censored_counted "stopped and censored: $stopc; $(grep stop way.out)"
grep -q '^# both definitions: one diameter' way.out &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 'w' AND tool = 'waiting' AND key = 'way_median'")" = 2 ] &&
	ok way.side_by_side || fail way.side_by_side "$(cat way.out)"
# three groups with trajectories: the second definition's own log-rank test, printed and stored
tool_quiet way_q waiting t --runs R --fraction 0.25 --no-plot --out "$TMP/wq"
grep -q '^# second definition: log-rank test .* across the 3 groups (9 runs' way_q.out &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 't' AND tool = 'waiting' AND grp = 'all groups' AND key GLOB 'way_logrank_*'")" = 3 ] &&
	ok way.logrank || fail way.logrank "$(grep log-rank way_q.out)"
[ "$(tail -n +2 wq/waiting_way_summary.csv | wc -l)" = 3 ] &&
	awk -F, 'NR > 1 && $2 != 0.25 { bad = 1 } END { exit bad }' wq/waiting_way_summary.csv &&
	ok way.fraction_option || fail way.fraction_option "$(cat wq/waiting_way_summary.csv)"

# ---- figures: Fig. 4 with every replicate ----
tool_quiet fig4 figures t --runs R
F4=$A/fig4_traj.csv
[ "$(awk -F, 'NR > 1 { print $3 }' $F4 | sort -u | wc -l)" = 3 ] && [ "$(awk -F, 'NR > 1 && $9 == 1 { print $3 }' $F4 | sort -u | wc -l)" = 1 ] &&
	ok fig4.every_replicate_one_representative || fail fig4.every_replicate_one_representative "$(cut -d, -f3,9 $F4 | sort -u)"
# the representative: the median run by waiting time (risen runs first) among the 7 Hz runs with R = 2
rep=$(awk -F, 'NR > 1 && $9 == 1 { print $3; exit }' $F4)
want=$(q R/study.db "SELECT id FROM runs WHERE campaign = 't' AND radius_ratio = 2 AND frequency = 7
	ORDER BY risen DESC, waiting_time, replicate LIMIT 1 OFFSET 1")
[ "$rep" = "$want" ] && grep -q "median run: replicate" $A/fig4.gp && fig_ok $A/fig4 && ok fig4.median_run ||
	fail fig4.median_run "drawn $rep, median $want"
finish
