#!/usr/bin/env bash
# analysis_accounting.sh - no run leaves a statistic without a trace. A tiny campaign in
# which a max_overlap just above the usual overlaps stops some runs on physics, mid-way,
# with their output file; then a run of an earlier version of the campaign file
# (current = 0), a pending and a running run, a truncated file and a failed run without
# an output file (bad input), all made with sqlite3 and the shell. Checks, against
# an independent classification from the database and the files (h5dump): every tool's
# counts per group (table, summary CSV, stored rows), the failed runs' treatment in the
# waiting times (risen before the failure: an event; else censored at the failure) and
# in the flux statistics (their periods before the failure used), the earlier version
# left out by default and used with --all-versions, the unreadable file reported.
# The campaigns are run by the release engine (lib.sh's data_driver_setup: the tools are
# what is tested; the engine stops the same runs at the same step in every build).
# tier: slow: campaigns with failed, damaged and older-version runs, read by every tool
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
data_driver_setup
cd "$TMP" || exit 1
vals() { h5vals "$@"; } # lib.sh
# close A B : |A - B| <= 1e-12 (1 + |B|)
close() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; exit !(a != "" && b != "" && d <= 1e-12 * (1 + m)) }'; }
# param CAMPAIGN ID KEY : a run's parameter as the database has it
param() { q R/study.db "SELECT value FROM param WHERE campaign = '$1' AND run = '$2' AND key = '$3'"; }
# col FILE GROUP NAME : the value of column NAME in the row of GROUP of a summary CSV
col() {
	awk -F, -v g="\"$2\"" -v n="$3" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == n) c = i; next }
		$1 == g && c { v = $c; gsub(/"/, "", v); print v; exit }' "$1"
}

SCENE="$(tiny_scene radius_ratio=-)
amplitude = 1
flux = yes
max_overlap = 0.26"
# at 8 Hz the largest overlaps of this bed pass 0.26 of the smaller radius after
# 0.1-1.5 s: those runs stop there with status overlap; at 4 Hz none does
printf '[campaign]\nname = s\nseed = 2\nreplicates = 3\n[scene]\n%s\ntraj_rate = 100\nduration = 1.5\n[grid]\nradius_ratio = 0, 2\nfrequency = 4, 6, 8\n' "$SCENE" >s.campaign
printf '[campaign]\nname = h\nseed = 3\nreplicates = 3\n[scene]\n%s\nradius_ratio = 2\nduration = 3\nramp = updown\nramp_from = 3\nramp_to = 8\n' "$SCENE" >h.campaign
t0=$SECONDS
"$DATA_STUDY" run s.campaign --runs "$TMP/R" --jobs 2 --no-progress >study_s.log 2>&1
rs=$?
"$DATA_STUDY" run h.campaign --runs "$TMP/R" --jobs 2 --no-progress >study_h.log 2>&1
rh=$?
echo "# campaigns: $((SECONDS - t0)) s"
# exit 3: some runs failed (recorded)
[ "$rs" -eq 3 ] && [ "$rh" -eq 3 ] && [ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE state IN ('done', 'failed')")" = 21 ] &&
	ok acc.setup.campaigns || { fail acc.setup.campaigns "study exit $rs, $rh: $(tail -c 300 study_s.log study_h.log)"; finish; }

# The failures this test needs (the engine is deterministic: they come back every time;
# a change of the engine's dynamics may need another max_overlap or seed): failed runs
# with an intruder that rose before the failure and that did not, a failed run with
# periods after the transient, failed ramp runs.
need_risen=0 need_cens=0 need_partly=0
for id in $(q R/study.db "SELECT id FROM run WHERE campaign = 's' AND state = 'failed'"); do
	f=R/s/$id.h5
	[ "$(attr "$f" /status)" = overlap ] || continue
	if [ -n "$(attr "$f" /risen)" ]; then
		[ "$(attr "$f" /risen)" = 1 ] && need_risen=$((need_risen + 1)) || need_cens=$((need_cens + 1))
	fi
	P=$(dims "$f" /observables/flux/phi/time)
	p0=$(awk -v d="$(param s "$id" duration)" -v f="$(param s "$id" frequency)" 'BEGIN { print int(0.2 * int(d * f + 1e-9)) }')
	[ "${P:-0}" -gt "$p0" ] && need_partly=$((need_partly + 1))
done
[ "$need_risen" -ge 1 ] && [ "$need_cens" -ge 2 ] && [ "$need_partly" -ge 2 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE campaign = 'h' AND state = 'failed'")" -ge 1 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE campaign = 'h' AND state = 'done'")" -ge 1 ] && ok acc.setup.failures ||
	{ fail acc.setup.failures "failed runs risen $need_risen, censored $need_cens, with periods after the transient $need_partly; ramps: $(q R/study.db "SELECT group_concat(state) FROM run WHERE campaign = 'h'")"; finish; }

# ---- what happens to a campaign besides failures (made by hand) ----
# run.current exists once bin/study records versions; a database without it is read too
[ "$(q R/study.db "SELECT COUNT(*) FROM pragma_table_info('run') WHERE name = 'current'")" = 1 ] ||
	q R/study.db "ALTER TABLE run ADD COLUMN current INTEGER NOT NULL DEFAULT 1"
# pick CLAUSE : the id of the first run of campaign s (by id) that matches
pick() { q R/study.db "SELECT r.id FROM run r JOIN param a ON a.campaign = r.campaign AND a.run = r.id AND a.key = 'radius_ratio'
	JOIN param b ON b.campaign = r.campaign AND b.run = r.id AND b.key = 'frequency' WHERE r.campaign = 's' AND $1 ORDER BY r.id LIMIT 1"; }
OLD=$(pick "a.value = 2 AND b.value = 4 AND r.state = 'done'")   # of an earlier version
PEND=$(pick "a.value = 0 AND b.value = 4 AND r.state = 'done'")  # queued again
RUNG=$(pick "a.value = 2 AND b.value = 6 AND r.state = 'done'")  # running
TRUNC=$(pick "a.value = 0 AND b.value = 6 AND r.state = 'done'") # its file truncated
# failed without an output file: bad input (no file, no result row, the attempt says why)
NOFILE=$(q R/study.db "SELECT r.id FROM run r JOIN result s ON s.campaign = r.campaign AND s.run = r.id JOIN param a ON a.campaign = r.campaign
	AND a.run = r.id AND a.key = 'radius_ratio' WHERE r.campaign = 's' AND r.state = 'failed' AND a.value = 2 ORDER BY s.status_time LIMIT 1")
q R/study.db "UPDATE run SET current = 0 WHERE campaign = 's' AND id = '$OLD';
   UPDATE run SET state = 'pending' WHERE campaign = 's' AND id = '$PEND';
   UPDATE run SET state = 'running' WHERE campaign = 's' AND id = '$RUNG';
   DELETE FROM result WHERE campaign = 's' AND run = '$NOFILE';
   UPDATE attempt SET status = 'usage', exit_code = 1, message = 'shake: frequency: expected a number in (0, 100], got x'
     WHERE campaign = 's' AND run = '$NOFILE'"
rm -f "R/s/$NOFILE.h5"
truncate -s 3000 "R/s/$TRUNC.h5"
# the database of an older bin/study: no run.current (the runs view reads it)
cp R/study.db nocur.db
sqlite3 nocur.db "DROP VIEW IF EXISTS runs; ALTER TABLE run DROP COLUMN current" || fail acc.setup.nocur "cannot drop run.current"
[ -n "$OLD" ] && [ -n "$PEND" ] && [ -n "$RUNG" ] && [ -n "$TRUNC" ] && [ -n "$NOFILE" ] && ok acc.setup.changes ||
	{ fail acc.setup.changes "old '$OLD' pending '$PEND' running '$RUNG' truncated '$TRUNC' no file '$NOFILE'"; finish; }

# expect_flux ID : what a flux statistic (fixed frequency, transient 0.2 of the planned
# periods) can make of a run: used, failed_used, unusable, unreadable, pending, running
expect_flux() {
	local id=$1 st f P p0
	st=$(q R/study.db "SELECT state FROM run WHERE campaign = 's' AND id = '$id'")
	case $st in pending | running) echo "$st"; return ;; esac
	f=R/s/$id.h5
	if [ ! -e "$f" ]; then [ "$st" = failed ] && echo unusable || echo unreadable; return; fi
	P=$(dims "$f" /observables/flux/phi/time)
	[ -n "$P" ] || { echo unreadable; return; }
	[ "$st" = done ] && { echo used; return; }
	p0=$(awk -v d="$(param s "$id" duration)" -v f="$(param s "$id" frequency)" 'BEGIN { print int(0.2 * int(d * f + 1e-9)) }')
	[ "$P" -gt "$p0" ] && echo failed_used || echo unusable
}
# expect_wait ID : the same for the waiting time (a failed run is observed up to its failure)
expect_wait() {
	local id=$1 st f w
	st=$(q R/study.db "SELECT state FROM run WHERE campaign = 's' AND id = '$id'")
	case $st in pending | running) echo "$st"; return ;; esac
	f=R/s/$id.h5
	if [ ! -e "$f" ]; then [ "$st" = failed ] && echo unusable || echo unreadable; return; fi
	w=$(attr "$f" /waiting_time)
	[ -n "$w" ] && [ -n "$(attr "$f" /risen)" ] || { echo unreadable; return; }
	[ "$st" = done ] && { echo used; return; }
	awk -v w="$w" 'BEGIN { exit !(w > 0) }' && echo failed_used || echo unusable
}
# expected KIND LABELFMT [ALL] : per group "label used failed failed_used unusable unreadable pending running",
# over the current runs (every run with ALL = 1); KIND flux (every run) or wait (radius_ratio > 0);
# LABELFMT an awk printf format of (radius_ratio, frequency)
expected() {
	local kind=$1 fmt=$2 all=${3:-0} id ra fr st cur use
	q R/study.db "SELECT r.id, a.value, b.value, r.state, r.current FROM run r JOIN param a ON a.campaign = r.campaign AND a.run = r.id
		AND a.key = 'radius_ratio' JOIN param b ON b.campaign = r.campaign AND b.run = r.id AND b.key = 'frequency'
		WHERE r.campaign = 's' ORDER BY r.id" | while IFS='|' read -r id ra fr st cur; do
		[ "$cur" = 1 ] || [ "$all" = 1 ] || continue
		if [ "$kind" = wait ]; then
			awk -v r="$ra" 'BEGIN { exit !(r > 0) }' || continue
			use=$(expect_wait "$id")
		else
			use=$(expect_flux "$id")
		fi
		awk -v r="$ra" -v f="$fr" -v fmt="$fmt" -v st="$st" -v u="$use" 'BEGIN { printf fmt " %s %s\n", r, f, st, u }'
	done | awk '{ g = $1 " " $2; n[g]++; st = $3; u = $4
		used[g] += (u == "used" || u == "failed_used"); failed[g] += (st == "failed"); fu[g] += (u == "failed_used")
		un[g] += (u == "unusable"); ur[g] += (u == "unreadable"); pe[g] += (u == "pending"); ru[g] += (u == "running") }
		END { for (g in n) print g, used[g] + 0, failed[g] + 0, fu[g] + 0, un[g] + 0, ur[g] + 0, pe[g] + 0, ru[g] + 0 }' | sort
}
# got CSV : the same from a tool's summary CSV (first column the group)
got() {
	awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
		{ g = $1; gsub(/"/, "", g); print g, $c["runs"], $c["runs_failed"], $c["runs_failed_used"], $c["runs_unusable"],
		  $c["runs_unreadable"], $c["runs_pending"], $c["runs_running"] }' "$1" | sort
}
# same_counts ID WANT GOT
same_counts() {
	if [ -n "$2" ] && [ "$2" = "$3" ]; then ok "$1"; else
		fail "$1" "want [$(echo "$2" | tr '\n' '|')] got [$(echo "$3" | tr '\n' '|')]"; fi
}
A=R/s/analysis

# ---- onset: counts per group, the failed runs' periods, versions, the unreadable file ----
"$BINDIR/onset" s --runs R --boot 20 --no-plot >onset.out 2>onset.err
rc=$?
[ "$rc" -eq 0 ] && ok acc.onset.exit || fail acc.onset.exit "exit $rc: $(cat onset.err)"
want=$(expected flux 'radius_ratio=%g depth=1%.0s')
same_counts acc.onset.summary_counts_per_group "$want" "$(got $A/onset_summary.csv)"
# the printed accounting row of each group says the same, and the table has failed and unfinished columns
bad=0
while read -r g1 g2 used failed fu un ur pe ru; do
	# the row: label, used, failed, failed_used ("N (T of D)"), unusable, unreadable, pending, running, by status
	awk -v g="$g1 $g2" -v want="$used $failed $fu $un $ur $pe $ru" '
		/^group .* failed by status/ { on = 1; next } on && index($0, g " ") == 1 {
		s = substr($0, length(g) + 1); gsub(/\([^)]*\)/, "", s); split(s, f, " ")
		found = (f[1] " " f[2] " " f[3] " " f[4] " " f[5] " " f[6] " " f[7] == want) } END { exit !found }' onset.out ||
		{ bad=1; echo "# $g1 $g2: printed row differs from $used $failed $un $ur $pe $ru"; }
done <<<"$want"
[ "$bad" = 0 ] && grep -q '^group .* failed *unfinished$' onset.out && ok acc.onset.printed_counts ||
	fail acc.onset.printed_counts "$(cat onset.out)"
grep -q '^# NOT FINISHED: 1 run pending and 1 running' onset.out && ok acc.onset.says_unfinished ||
	fail acc.onset.says_unfinished "$(grep '^#' onset.out)"
# stored rows: the same counts, and per-status counts of the failures
bad=0
while read -r g1 g2 used failed fu un ur pe ru; do
	got_db=$(q R/study.db "SELECT group_concat(CAST(value AS INTEGER), ' ') FROM (SELECT value FROM analysis WHERE campaign = 's' AND tool = 'onset'
		AND grp = '$g1 $g2' AND key IN ('runs', 'runs_failed', 'runs_failed_used', 'runs_unusable', 'runs_unreadable',
		'runs_pending', 'runs_running') ORDER BY CASE key WHEN 'runs' THEN 1 WHEN 'runs_failed' THEN 2 WHEN 'runs_failed_used'
		THEN 3 WHEN 'runs_unusable' THEN 4 WHEN 'runs_unreadable' THEN 5 WHEN 'runs_pending' THEN 6 ELSE 7 END)")
	[ "$got_db" = "$used $failed $fu $un $ur $pe $ru" ] || { bad=1; echo "# $g1 $g2: stored '$got_db'"; }
	nst=$(q R/study.db "SELECT COALESCE(SUM(value), 0) FROM analysis WHERE campaign = 's' AND tool = 'onset' AND grp = '$g1 $g2' AND key LIKE 'failed\_%' ESCAPE '\' AND key NOT IN ('failed_used_s', 'failed_planned_s')")
	awk -v a="$nst" -v b="$failed" 'BEGIN { exit !(a == b) }' || { bad=1; echo "# $g1 $g2: failed_STATUS sum $nst, failed $failed"; }
done <<<"$want"
[ "$bad" = 0 ] && [ "$(q R/study.db "SELECT value FROM analysis WHERE campaign = 's' AND tool = 'onset' AND grp = 'radius_ratio=2 depth=1' AND key = 'failed_usage'")" = 1.0 ] &&
	ok acc.onset.stored_counts || fail acc.onset.stored_counts "$(q R/study.db "SELECT grp, key, value FROM analysis WHERE tool = 'onset' AND key LIKE '%runs%' OR key LIKE 'failed%'")"
# every run considered is in the accounting CSV with the use the rules give it
bad=0 n=0
while IFS=, read -r _ _ id _ _ _ _ use _; do
	n=$((n + 1))
	[ "$use" = "$(expect_flux "$id")" ] || { bad=1; echo "# $id: $use, expected $(expect_flux "$id")"; }
done < <(tail -n +2 $A/onset_accounting.csv)
[ "$bad" = 0 ] && [ "$n" = 17 ] && ok acc.onset.every_run_accounted || fail acc.onset.every_run_accounted "$n rows"
# a failed run's Phi is the mean over its periods before the failure after the transient
# of the run as planned (floor(0.2 * duration * f) periods), and it says how far it got
plane_phi() { # FILE P0
	local f=$1 P L S
	set -- $(dims "$f" /observables/flux/phi/value) "$2"
	P=$1 L=$2
	S=$(attr "$f" /observables/flux/surface_height)
	{ vals "$f" /observables/flux/heights; vals "$f" /observables/flux/phi/value; } | awk -v P="$P" -v L="$L" -v S="$S" -v p0="$3" '
		NR <= L { h[NR - 1] = $1; next } { v[NR - 1 - L] = $1 }
		END { n = 0; for (l = 0; l < L; l++) if (h[l] >= 0.4 * S && h[l] <= 0.6 * S) sel[n++] = l
		      s = 0; for (p = p0; p < P; p++) { m = 0; for (i = 0; i < n; i++) m += v[p * L + sel[i]]; s += m / n }
		      printf "%.17g\n", s / (P - p0) }'
}
bad=0 n=0
while IFS=, read -r _ _ id _ _ _ _ _ phi use used_s; do
	[ "$use" = failed_used ] || continue
	n=$((n + 1))
	f=R/s/$id.h5
	p0=$(awk -v d="$(param s "$id" duration)" -v fr="$(param s "$id" frequency)" 'BEGIN { print int(0.2 * int(d * fr + 1e-9)) }')
	close "$phi" "$(plane_phi "$f" "$p0")" || { bad=1; echo "# $id: phi $phi, from the file $(plane_phi "$f" "$p0")"; }
	close "$used_s" "$(vals "$f" /observables/flux/phi/time | tail -n 1)" || { bad=1; echo "# $id: used_s $used_s"; }
done < <(tail -n +2 $A/onset_runs.csv)
[ "$bad" = 0 ] && [ "$n" -ge 2 ] && ok acc.onset.failed_runs_periods_used || fail acc.onset.failed_runs_periods_used "$n failed runs used"
# the run of an earlier version is left out, and the table says so
! grep -q "$OLD" $A/onset_accounting.csv && grep -q '^# runs: 17 of the campaign.s current grid; 1 of earlier versions' onset.out &&
	ok acc.onset.old_version_left_out || fail acc.onset.old_version_left_out "$(grep '^# runs' onset.out)"
# the truncated file is counted as unreadable, with a warning
grep -q "^[0-9]*,\"[^\"]*\",$TRUNC,.*,unreadable," $A/onset_accounting.csv && grep -q "warning: .*$TRUNC" onset.err &&
	! grep -q "$TRUNC" $A/onset_runs.csv && ok acc.onset.truncated_file_unreadable ||
	fail acc.onset.truncated_file_unreadable "$(grep "$TRUNC" $A/onset_accounting.csv; cat onset.err)"
# the failed run without a file is unusable and says why
grep "$NOFILE" $A/onset_accounting.csv | grep -q ',unusable,.*without an output file (usage: shake: frequency' &&
	ok acc.onset.failed_without_file || fail acc.onset.failed_without_file "$(grep "$NOFILE" $A/onset_accounting.csv)"
# pending and running runs are not used even though their files exist
! grep -q "$PEND\|$RUNG" $A/onset_runs.csv && ok acc.onset.unfinished_not_used || fail acc.onset.unfinished_not_used "$(grep "$PEND\|$RUNG" $A/onset_runs.csv)"
# --all-versions: the earlier version's run is used, and said to be
"$BINDIR/onset" s --runs R --boot 20 --no-plot --no-store --all-versions --out "$TMP/all" >onset_all.out 2>onset_all.err
rc=$?
want=$(expected flux 'radius_ratio=%g depth=1%.0s' 1)
[ "$rc" -eq 0 ] && grep -q ",$OLD," all/onset_runs.csv && grep -q '^# runs: 18, 1 of them of earlier versions' onset_all.out &&
	[ "$want" = "$(got all/onset_summary.csv)" ] && ok acc.onset.all_versions ||
	fail acc.onset.all_versions "exit $rc: $(grep '^# runs' onset_all.out; cat onset_all.err)"
# a database without run.current: every run is of the current grid, the earlier version's too
"$BINDIR/onset" s --db nocur.db --runs R --boot 10 --no-plot --no-store --out "$TMP/nocur" >nocur.out 2>nocur.err
rc=$?
[ "$rc" -eq 0 ] && grep -q ",$OLD," nocur/onset_runs.csv && ok acc.onset.database_without_current ||
	fail acc.onset.database_without_current "exit $rc: $(cat nocur.err)"

# ---- waiting: failed runs observed up to the failure ----
"$BINDIR/waiting" s --runs R --no-plot >waiting.out 2>waiting.err
rc=$?
[ "$rc" -eq 0 ] && ok acc.waiting.exit || fail acc.waiting.exit "exit $rc: $(cat waiting.err)"
want=$(expected wait 'radius_ratio=%g frequency=%g')
same_counts acc.waiting.summary_counts_per_group "$want" "$(got $A/waiting_summary.csv)"
# every failed run with a file: risen = the file's, waiting_time = the file's (the time
# of the rise before the failure, or the time observed until it: censored)
bad=0 ev=0 ce=0
for id in $(q R/study.db "SELECT id FROM run WHERE campaign = 's' AND state = 'failed' AND current = 1"); do
	f=R/s/$id.h5
	[ -e "$f" ] && [ -n "$(attr "$f" /risen)" ] || continue
	line=$(grep ",$id," $A/waiting_runs.csv)
	r=$(echo "$line" | awk -F, '{ print $7 }') w=$(echo "$line" | awk -F, '{ print $6 }')
	fr=$(attr "$f" /risen) fw=$(attr "$f" /waiting_time) ft=$(attr "$f" /status_time)
	[ -n "$line" ] && [ "$r" = "$fr" ] && close "$w" "$fw" && echo "$line" | grep -q ',failed,failed_used$' ||
		{ bad=1; echo "# $id: csv '$line', file risen $fr waiting_time $fw"; continue; }
	if [ "$fr" = 1 ]; then
		awk -v w="$fw" -v t="$ft" 'BEGIN { exit !(w < t) }' && ev=$((ev + 1)) || { bad=1; echo "# $id: risen at $fw after the failure at $ft?"; }
	else
		awk -v w="$fw" -v t="$ft" 'BEGIN { d = w - t; exit !(d <= 1e-3 && d >= -1e-3) }' && ce=$((ce + 1)) ||
			{ bad=1; echo "# $id: censored at $fw, failed at $ft"; }
	fi
done
[ "$bad" = 0 ] && [ "$ev" -ge 1 ] && [ "$ce" -ge 2 ] && ok acc.waiting.failed_risen_or_censored ||
	fail acc.waiting.failed_risen_or_censored "events $ev, censored $ce"
grep -q "^# $((ev + ce)) failed runs are observed up to the failure: $ev had risen before it .*, $ce are censored at the failure time; this assumes that the failure is independent of the rise" waiting.out &&
	ok acc.waiting.says_assumption || fail acc.waiting.says_assumption "$(grep '^#' waiting.out)"
# the Kaplan-Meier curve starts with every used run at risk
bad=0
while read -r g1 g2 used _; do
	[ "$(awk -F, -v g="\"$g1 $g2\"" '$2 == g && $3 == 0 { print $4; exit }' $A/waiting_km.csv)" = "$used" ] || bad=1
done <<<"$want"
[ "$bad" = 0 ] && ok acc.waiting.km_at_risk || fail acc.waiting.km_at_risk "$(head -n 4 $A/waiting_km.csv)"
! grep -q "$OLD" $A/waiting_runs.csv && grep -q '1 of earlier versions' waiting.out && grep -q '^# NOT FINISHED: 0 runs pending and 1 running' waiting.out &&
	ok acc.waiting.old_left_out_unfinished_said || fail acc.waiting.old_left_out_unfinished_said "$(grep '^#' waiting.out)"
"$BINDIR/waiting" s --runs R --no-plot --no-store --all-versions --out "$TMP/wall" >waiting_all.out 2>&1
[ $? -eq 0 ] && grep -q ",$OLD," wall/waiting_runs.csv && [ "$(expected wait 'radius_ratio=%g frequency=%g' 1)" = "$(got wall/waiting_summary.csv)" ] &&
	ok acc.waiting.all_versions || fail acc.waiting.all_versions "$(cat waiting_all.out)"
grep "$NOFILE" $A/waiting_accounting.csv | grep -q ',unusable,' && ok acc.waiting.failed_without_file ||
	fail acc.waiting.failed_without_file "$(grep "$NOFILE" $A/waiting_accounting.csv)"

# ---- figures: Fig. 3 pools the failed runs' periods ----
"$BINDIR/figures" s --runs R --no-plot >figures.out 2>figures.err
rc=$?
[ "$rc" -eq 0 ] && ok acc.figures.exit || fail acc.figures.exit "exit $rc: $(cat figures.err)"
bad=0
while read -r g1 g2 used failed fu un ur pe ru; do
	fr=${g2#frequency=} ra=${g1#radius_ratio=}
	v=$(q R/study.db "SELECT group_concat(CAST(value AS INTEGER), ' ') FROM (SELECT value FROM analysis WHERE campaign = 's' AND tool = 'figures'
		AND grp = 'fig3 f=$fr radius_ratio=$ra' AND key IN ('runs', 'runs_failed', 'runs_failed_used', 'runs_unusable',
		'runs_unreadable', 'runs_pending', 'runs_running') ORDER BY CASE key WHEN 'runs' THEN 1 WHEN 'runs_failed' THEN 2
		WHEN 'runs_failed_used' THEN 3 WHEN 'runs_unusable' THEN 4 WHEN 'runs_unreadable' THEN 5 WHEN 'runs_pending' THEN 6 ELSE 7 END)")
	[ "$v" = "$used $failed $fu $un $ur $pe $ru" ] || { bad=1; echo "# f=$fr R=$ra: stored '$v', want $used $failed $fu $un $ur $pe $ru"; }
done < <(expected flux 'radius_ratio=%g frequency=%g')
[ "$bad" = 0 ] && ok acc.figures.stored_counts_per_panel || fail acc.figures.stored_counts_per_panel "see above"
# the panel at 8 Hz without intruder: a failed run's periods after its transient join the
# finished runs' (every period after the transient of every used run, pooled)
ids=$(awk -F, '$2 == "\"f=8 radius_ratio=0\"" && ($8 == "used" || $8 == "failed_used") { print $3 }' $A/figures_accounting.csv)
for id in $ids; do
	f=R/s/$id.h5
	p0=$(awk -v d="$(param s "$id" duration)" -v fr="$(param s "$id" frequency)" 'BEGIN { print int(0.2 * int(d * fr + 1e-9)) }')
	set -- $(dims "$f" /observables/flux/phi/value)
	{ vals "$f" /observables/flux/heights; vals "$f" /observables/flux/phi/value; } | awk -v P="$1" -v L="$2" -v p0="$p0" '
		NR <= L { h[NR - 1] = $1; next } { v[NR - 1 - L] = $1 }
		END { for (l = 0; l < L; l++) for (p = p0; p < P; p++) printf "%d %.17g %.17g\n", l, h[l], v[p * L + l] }'
done | awk '{ D[$1] += $2; F[$1] += $3; n[$1]++ } END { for (l in D) printf "%d %.17g %.17g\n", l, D[l] / n[l], F[l] / n[l] }' |
	sort -n >fig3.want
awk -F, 'NR > 1 && $3 == 8 && $2 == 0 { print $5, $6, $7 }' $A/fig3_profile.csv | sort -n >fig3.got
[ "$(echo "$ids" | while read -r id; do grep ",$id," $A/figures_accounting.csv; done | grep -c ',failed_used,')" -ge 1 ] &&
	paste -d' ' fig3.got fig3.want | awk '{ for (k = 2; k <= 3; k++) { d = $k - $(k + 3); if (d < 0) d = -d; if (d > 1e-12 * (1 + ($k < 0 ? -$k : $k))) bad = 1 }
	if ($1 != $4) bad = 1 } END { exit !(NR == 80 && !bad) }' && ok acc.figures.fig3_pools_failed_periods ||
	fail acc.figures.fig3_pools_failed_periods "$(paste -d' ' fig3.got fig3.want | head -n 3)"
grep -q "warning: .*$TRUNC" figures.err && grep -q "^[0-9]*,\"[^\"]*\",$TRUNC,.*,unreadable," $A/figures_accounting.csv &&
	ok acc.figures.truncated_file_unreadable || fail acc.figures.truncated_file_unreadable "$(cat figures.err)"
! grep -q "$OLD" $A/figures_accounting.csv && "$BINDIR/figures" s --runs R --no-plot --no-store --all-versions --out "$TMP/fall" >fall.out 2>&1 &&
	grep -q ",$OLD,.*,used," fall/figures_accounting.csv && ok acc.figures.all_versions || fail acc.figures.all_versions "$(cat fall.out)"

# ---- hysteresis: a ramp cut short by its failure is used as far as it got ----
"$BINDIR/hysteresis" h --runs R --boot 20 --no-plot >hyst.out 2>hyst.err
rc=$?
H=R/h/analysis
[ "$rc" -eq 0 ] && ok acc.hysteresis.exit || fail acc.hysteresis.exit "exit $rc: $(cat hyst.err)"
nf=$(q R/study.db "SELECT COUNT(*) FROM run WHERE campaign = 'h' AND state = 'failed'")
[ "$(col $H/hysteresis_summary.csv 'radius_ratio=2 depth=1' runs)" = 3 ] &&
	[ "$(col $H/hysteresis_summary.csv 'radius_ratio=2 depth=1' runs_failed)" = "$nf" ] &&
	[ "$(col $H/hysteresis_summary.csv 'radius_ratio=2 depth=1' runs_failed_used)" = "$nf" ] &&
	[ "$(col $H/hysteresis_summary.csv 'radius_ratio=2 depth=1' failed_by_status)" = "overlap=$nf" ] &&
	ok acc.hysteresis.counts || fail acc.hysteresis.counts "$(cat $H/hysteresis_summary.csv)"
bad=0
for id in $(q R/study.db "SELECT id FROM run WHERE campaign = 'h' AND state = 'failed'"); do
	P=$(dims "R/h/$id.h5" /observables/flux/phi/time)
	[ "$(awk -F, -v id="$id" '$3 == id && $10 == "failed_used"' $H/hysteresis_periods.csv | wc -l)" = "$P" ] ||
		{ bad=1; echo "# $id: $P periods in the file, $(grep -c ",$id," $H/hysteresis_periods.csv) in the CSV"; }
done
[ "$bad" = 0 ] && ok acc.hysteresis.failed_runs_periods_used || fail acc.hysteresis.failed_runs_periods_used "see above"

# ---- every tool: --all-versions is an option, --help says what is counted ----
for n in onset waiting figures hysteresis; do
	"$BINDIR/$n" --help >help.out && grep -q -- '--all-versions' help.out && grep -qi 'failed' help.out &&
		ok acc.$n.help || fail acc.$n.help "$(head -n 3 help.out)"
done
echo "# total: $((SECONDS - t0)) s"
finish
