#!/usr/bin/env bash
# study_adaptive.sh - the [onset] search with the real engine (docs/driver.md,
# "Adaptive onset search"). A tiny bed whose intruder's rise is measured first on a
# fixed frequency grid holding every point the search can ask for; the search must
# find, replicate by replicate, the bracket a bisection over those measurements gives,
# with runs identical to the grid's; killed mid-search (the driver alone, or its whole
# process group) and run again it asks for the same points in the same order;
# replicates = auto adds batches up to its maximum, stops at the first batch whose
# interval is narrow enough, and reuses the runs of a search with fixed replicates;
# study status shows the brackets and the interval; a search over the flux classifies a
# run by bin/onset's Phi; a run that fails blocks its replicate; bad [onset] input and a
# changed range are refused with file, line and key.
# tier: slow: adaptive searches, one killed and resumed
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1

# 60 grains, an intruder of 1.5 mean radii, 2 s of the fast preset, ended at the rise:
# the intruder rises between about 6 and 8 Hz at A = 1 cm, differently per packing
campaign() { # NAME [CAMPAIGN-LINES...]: the [campaign] and [scene] sections
	printf '[campaign]\nname = %s\nseed = 11\n' "$1"
	shift
	[ $# -gt 0 ] && printf '%s\n' "$@"
	cat <<C
[scene]
preset = fast
$(tiny_scene width=16 radius_ratio=1.5 depth=-)
amplitude = 1
duration = 2
stop = risen
traj_rate = 0
snapshots = no
C
}
# from 5 to 9 Hz to 0.5 Hz: three halvings, so every point a chain can ask for (7; 6, 8;
# 5.5 ... 8.5; and the ends) is on the grid 5:9:0.5
onset() { # extra [onset] lines
	printf '[onset]\nobservable = rise\nfrom = 5\nto = 9\ntolerance = 0.5\n'
	printf '%s\n' "$@"
}

# --- bad input: refused before anything runs, with file, line and key ---
bad() { # ID EXPECTED [onset] lines...
	local id=$1 want=$2
	shift 2
	{ campaign bad; printf '%s\n' "$@"; } >bad.campaign
	local out rc
	out=$("$STUDY" run bad.campaign --runs "$TMP/BAD" 2>&1)
	rc=$?
	if [ "$rc" -eq 1 ] && printf '%s' "$out" | grep -qF -- "$want" && [ ! -e BAD/bad ]; then ok "$id"; else
		fail "$id" "exit $rc: $out"; fi
}
bad adaptive.bad.tolerance "bad.campaign:20: tolerance: expected a number in (0, 1000] (Hz), got 'fine'" \
	'[onset]' 'observable = rise' 'from = 5' 'to = 9' 'tolerance = fine'
bad adaptive.bad.range "bad.campaign:19: to: expected a frequency above from = 5 (line 18), got 4" \
	'[onset]' 'observable = rise' 'from = 5' 'to = 4' 'tolerance = 0.5'
bad adaptive.bad.observable "bad.campaign:17: observable: expected one of rise|flux, got 'convection'" \
	'[onset]' 'observable = convection'
bad adaptive.bad.missing "bad.campaign:16: [onset] has no tolerance" \
	'[onset]' 'observable = rise' 'from = 5' 'to = 9'
bad adaptive.bad.replicates "bad.campaign:20: replicates: expected auto or an integer in [1, 1000], got '0'" \
	'[onset]' 'observable = rise' 'from = 5' 'to = 9' 'replicates = 0' 'tolerance = 0.5'
bad adaptive.bad.flux_records "bad.campaign:17: observable: flux needs the flux records: set flux = yes" \
	'[onset]' 'observable = flux' 'from = 5' 'to = 9' 'tolerance = 0.5' 'threshold = 1'
bad adaptive.bad.frequency_axis "bad.campaign:17: frequency: chosen by the [onset] search" \
	'[grid]' 'frequency = 6, 7' '[onset]' 'observable = rise' 'from = 5' 'to = 9' 'tolerance = 0.5'

# --- the transition measured first: every point the search can ask for, 3 replicates
# (by the release engine, lib.sh's data_driver_setup: these are the answers the search is
# held to, not the search; both builds write the same bits) ---
data_driver_setup
{ campaign scan 'replicates = 3'; printf '[grid]\nfrequency = 5:9:0.5\n'; } >scan.campaign
"$DATA_STUDY" run scan.campaign --runs "$TMP/SCAN" --jobs 2 >scan.log 2>&1
rc=$?
[ "$rc" -eq 0 ] && ok adaptive.scan.measured || { fail adaptive.scan.measured "exit $rc: $(tail -c 300 scan.log)"; finish; }
sqlite3 SCAN/study.db "SELECT replicate, printf('%g', frequency), risen, id FROM runs WHERE campaign = 'scan'
	ORDER BY replicate, frequency" >scan.tsv
echo "# measured (replicate: frequency:risen): $(awk -F'|' '{ a[$1] = a[$1] " " $2 ":" $3 } END { for (r in a) printf "%s:%s;", r, a[r] }' scan.tsv)"
# the bisection over the measurements, per replicate: state lo hi and the chain's points
awk -F'|' '{ risen[$1 "," $2] = $3; reps[$1] = 1 }
	END {
		for (r in reps) {
			lo = 5; hi = 9; ls = 0; hs = 0; chain = ""
			while (hi - lo > 0.5 + 1e-9) {
				m = (lo + hi) / 2; chain = chain " " m
				if (risen[r "," m]) { hi = m; hs = 1 } else { lo = m; ls = 1 }
			}
			state = "found"
			if (!ls) { chain = chain " 5"; if (risen[r ",5"]) state = "below"; else ls = 1 }
			if (state == "found" && !hs) { chain = chain " 9"; if (!risen[r ",9"]) state = "above" }
			if (state == "below") { lo = ""; hi = 5 }
			if (state == "above") { lo = 9; hi = "" }
			printf "%s|%s|%s|%s|%s\n", r, state, lo, hi, substr(chain, 2)
		}
	}' scan.tsv | sort >want.tsv

# --- the search ---
{ campaign rise; onset 'replicates = 3'; } >rise.campaign
"$STUDY" expand rise.campaign >expand.tsv 2>expand.err
[ "$(awk -F'\t' 'NR > 1 { print $3 ":" $5 }' expand.tsv | sort | tr '\n' ' ')" = "1:7 2:7 3:7 " ] &&
	head -n 1 expand.tsv | grep -q 'frequency$' && ok adaptive.expand.first_round ||
	fail adaptive.expand.first_round "$(cat expand.tsv expand.err)"
t0=$(date +%s%N)
"$STUDY" run rise.campaign --runs "$TMP/REF" --jobs 2 >ref.log 2>&1
rc=$?
ref_ms=$((($(date +%s%N) - t0) / 1000000))
echo "# the search: $ref_ms ms, $(grep -c 'onset round' ref.log) rounds"
[ "$rc" -eq 0 ] && grep -q "rise: all: onset .* Hz, 95% interval .*: done" ref.log && ok adaptive.run.completes ||
	{ fail adaptive.run.completes "exit $rc: $(tail -c 400 ref.log)"; finish; }
# the search's answer per replicate, as want.tsv (an unbounded end empty)
sqlite3 REF/study.db "SELECT r.replicate, r.state, CASE WHEN r.lo IS NULL THEN '' ELSE printf('%g', r.lo) END,
	CASE WHEN r.hi IS NULL THEN '' ELSE printf('%g', r.hi) END,
	(SELECT group_concat(f, ' ') FROM (SELECT printf('%g', frequency) AS f FROM onset_run o
	 WHERE o.campaign = r.campaign AND o.replicate = r.replicate ORDER BY step))
	FROM onset_replicate r WHERE r.campaign = 'rise' ORDER BY r.replicate" >got.tsv
cmp -s want.tsv got.tsv && ok adaptive.finds_measured_transition ||
	fail adaptive.finds_measured_transition "measured $(tr '\n' ';' <want.tsv), searched $(tr '\n' ';' <got.tsv)"
# every run of the search is a run of the scan: same parameters, same id, same result
sqlite3 REF/study.db "SELECT replicate, printf('%g', frequency), risen, id FROM runs WHERE campaign = 'rise'
	ORDER BY replicate, frequency" >rise.tsv
sort -o rise.tsv rise.tsv
sort -o scan.tsv scan.tsv
[ -s rise.tsv ] && [ -z "$(comm -23 rise.tsv scan.tsv)" ] && ok adaptive.runs_are_ordinary_runs ||
	fail adaptive.runs_are_ordinary_runs "$(comm -23 rise.tsv scan.tsv | head -n 3)"
# each bracket, by the engine's own results: off at lo, on at hi, at most the tolerance wide
bad_brackets=$(sqlite3 REF/study.db "SELECT b.replicate FROM onset_replicate b WHERE b.campaign = 'rise' AND b.state = 'found'
	AND NOT (b.hi - b.lo <= 0.5
	AND (SELECT risen FROM runs r WHERE r.campaign = 'rise' AND r.replicate = b.replicate AND r.frequency = b.lo) = 0
	AND (SELECT risen FROM runs r WHERE r.campaign = 'rise' AND r.replicate = b.replicate AND r.frequency = b.hi) = 1)")
[ -z "$bad_brackets" ] && [ "$(sqlite3 REF/study.db "SELECT COUNT(*) FROM onset_replicate WHERE state = 'found'")" -gt 0 ] &&
	ok adaptive.brackets_hold || fail adaptive.brackets_hold "replicates $bad_brackets"
"$STUDY" status rise --runs "$TMP/REF" >status.txt 2>&1
grep -q "onset search (done; " status.txt && grep -qE "^ +all +3 +0 .* done$" status.txt &&
	grep -qE "brackets of all: 1 " status.txt && ok adaptive.status.shows_search || fail adaptive.status.shows_search "$(cat status.txt)"
"$STUDY" run rise.campaign --runs "$TMP/REF" --jobs 2 >again.log 2>&1
rc=$?
[ "$rc" -eq 0 ] && ! grep -q "onset round" again.log && [ "$(sqlite3 REF/study.db "SELECT COUNT(*) FROM attempt")" = \
	"$(sqlite3 REF/study.db "SELECT COUNT(*) FROM run")" ] && ok adaptive.rerun_runs_nothing ||
	fail adaptive.rerun_runs_nothing "exit $rc: $(tail -c 300 again.log)"

# --- killed mid-search (SIGKILL: the driver alone, then its whole process group), resumed ---
sequence() { # DB: every chain's runs in order
	sqlite3 "$1" "SELECT grp, replicate, step, printf('%.17g', frequency), run, class FROM onset_run
		WHERE campaign = 'rise' ORDER BY grp, replicate, step"
}
# The moment of each kill is decided by the state, not a time: once the search has
# recorded one run more than before this invocation and is still searching. A search
# that ends before that is a failure of the check, not a comment.
partial=0
qk() { sqlite3 -cmd '.timeout 2000' K/study.db "$1" 2>/dev/null; }
for k in 1 2; do
	before=$(qk "SELECT COUNT(*) FROM run WHERE state = 'done'")
	setsid "$STUDY" run rise.campaign --runs "$TMP/K" --jobs 2 >"kill$k.log" 2>&1 &
	pid=$!
	t0=$(date +%s%N)
	for i in $(seq 1200); do
		n=$(qk "SELECT COUNT(*) FROM run WHERE state = 'done'")
		[ "${n:-0}" -gt "${before:-0}" ] && [ "$(qk "SELECT state FROM onset_search")" = searching ] && break
		kill -0 $pid 2>/dev/null || break
		sleep 0.05
	done
	ms=$((($(date +%s%N) - t0) / 1000000))
	if [ "$k" -eq 1 ]; then kill -KILL $pid 2>/dev/null; else kill -KILL -- -$pid 2>/dev/null; fi
	wait $pid 2>/dev/null
	# processes of the killed group are gone; a killed driver's workers finish on their own
	for i in $(seq 100); do pgrep -f "exec $TMP/K/rise run" >/dev/null || break; sleep 0.1; done
	n=$(sqlite3 K/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'" 2>/dev/null)
	[ "$(sqlite3 K/study.db "SELECT state FROM onset_search" 2>/dev/null)" = searching ] && partial=$((partial + 1))
	echo "# kill $k after $ms ms: ${n:-0} runs done, search $(sqlite3 K/study.db "SELECT state FROM onset_search" 2>/dev/null)"
done
"$STUDY" run rise.campaign --runs "$TMP/K" --jobs 2 >resume.log 2>&1
rc=$?
sequence REF/study.db >ref.seq
sequence K/study.db >k.seq
[ "$rc" -eq 0 ] && [ -s ref.seq ] && cmp -s ref.seq k.seq && ok adaptive.resume.same_sequence ||
	fail adaptive.resume.same_sequence "exit $rc: $(diff ref.seq k.seq | head -n 4) $(tail -c 200 resume.log)"
[ "$partial" = 2 ] && ok adaptive.resume.killed_mid_search ||
	fail adaptive.resume.killed_mid_search "$partial of 2 kills landed mid-search (see the '# kill' lines)"
[ "$(sqlite3 K/study.db "SELECT COUNT(*) FROM attempt WHERE status = 'ok'")" = "$(sqlite3 K/study.db "SELECT COUNT(*) FROM run")" ] &&
	ok adaptive.resume.one_ok_attempt_each || fail adaptive.resume.one_ok_attempt_each \
	"$(sqlite3 K/study.db "SELECT run, n, status FROM attempt")"
# (h5diff calls the empty trajectory and snapshot datasets of these runs not comparable:
# the files are compared as text, %.17g, without /provenance)
same=0 total=0
for f in REF/rise/*.h5; do
	total=$((total + 1))
	dump_noprov "$f" >a.dump
	dump_noprov "K/rise/$(basename "$f")" >b.dump 2>/dev/null
	[ -s a.dump ] && cmp -s a.dump b.dump && same=$((same + 1))
done
[ "$same" = "$total" ] && ok adaptive.resume.bit_identical || fail adaptive.resume.bit_identical "$same of $total identical"

# --- replicates = auto: the same campaign, extended ---
# level 0.5: an interval from 2 replicates; batches of 2 up to 6; a target no interval
# reaches (finer than a bracket): every batch runs, and the search stops at the maximum
{ campaign rise; onset 'replicates = auto' 'level = 0.5' 'batch = 2' 'max_replicates = 6' 'target = 0.001'; } >auto.campaign
"$STUDY" run auto.campaign --runs "$TMP/REF" --jobs 2 >auto.log 2>&1
rc=$?
row=$(sqlite3 REF/study.db "SELECT replicates || '|' || state FROM onset_group WHERE campaign = 'rise'")
[ "$rc" -eq 0 ] && [ "$row" = "6|max_replicates" ] && grep -q "rise: all: .* 6 replicates .*: max_replicates" auto.log &&
	ok adaptive.auto.stops_at_max || fail adaptive.auto.stops_at_max "exit $rc, group '$row': $(tail -c 300 auto.log)"
# the fixed search's replicates 1-3 are reused as they were: one attempt each, same chains
sequence REF/study.db | awk -F'|' '$2 <= 3' >auto123.seq
[ "$(sqlite3 REF/study.db "SELECT COUNT(*) FROM attempt WHERE n > 1")" = 0 ] && cmp -s ref.seq auto123.seq &&
	ok adaptive.auto.extends_fixed_search || fail adaptive.auto.extends_fixed_search "$(diff ref.seq auto123.seq | head -n 4)"
# a target the first batch reaches: done with 2 replicates, nothing runs; the interval
# (level 0.5, 2 replicates: rank 1) is the lowest lower end to the highest upper end
sed 's/^target = 0.001$/target = 100/' auto.campaign >auto2.campaign
"$STUDY" run auto2.campaign --runs "$TMP/REF" --jobs 2 >auto2.log 2>&1
rc=$?
row=$(sqlite3 REF/study.db "SELECT replicates || '|' || state || '|' || printf('%g|%g', ci_lo, ci_hi) FROM onset_group
	WHERE campaign = 'rise'")
want=$(sqlite3 REF/study.db "SELECT '2|done|' || printf('%g|%g', MIN(lo), MAX(hi)) FROM onset_replicate WHERE campaign = 'rise'")
[ "$rc" -eq 0 ] && [ "$row" = "$want" ] && ! grep -q "onset round" auto2.log && ok adaptive.auto.stops_at_target ||
	fail adaptive.auto.stops_at_target "exit $rc: group $row, want $want: $(tail -c 300 auto2.log)"
"$STUDY" status rise --runs "$TMP/REF" >status2.txt 2>&1
grep -q "replicates auto: 2 at a time, at most 6, until the 50% interval is at most 100 Hz wide" status2.txt &&
	grep -qE "^ +all +2 +0 .* \[[0-9.]+, [0-9.]+\] .* done$" status2.txt && ok adaptive.auto.status_interval ||
	fail adaptive.auto.status_interval "$(cat status2.txt)"

# --- the flux observable: a bed without intruder, on when the mean flux through the band
# (after the transient) is at least the threshold; the value is bin/onset's Phi of the run ---
{ campaign flux; printf 'flux = yes\n'; onset 'replicates = 2' 'threshold = 0.3'; } |
	sed 's/^radius_ratio = 1.5$/radius_ratio = 0/; s/^stop = risen$//; s/^observable = rise$/observable = flux/; s/^duration = 2$/duration = 3/; s/^tolerance = 0.5$/tolerance = 1/' >flux.campaign
"$STUDY" run flux.campaign --runs "$TMP/FLUX" --jobs 2 >flux.log 2>&1
rc=$?
[ "$rc" -eq 0 ] && grep -q "flux: all: onset .*: done" flux.log && ok adaptive.flux.completes ||
	fail adaptive.flux.completes "exit $rc: $(tail -c 400 flux.log)"
sqlite3 FLUX/study.db "SELECT run, printf('%!.17g', value), class FROM onset_run ORDER BY run" >flux.got
awk -F'|' '{ v = $2 < 0 ? -$2 : $2; if (($3 == "on") != (v >= 0.3)) bad = bad " " $1 } END { exit bad != "" }' flux.got &&
	[ "$(sqlite3 FLUX/study.db "SELECT COUNT(*) FROM onset_replicate r WHERE state = 'found' AND
		(SELECT ABS(value) FROM onset_run o WHERE o.replicate = r.replicate AND o.frequency = r.lo) < 0.3 AND
		(SELECT ABS(value) FROM onset_run o WHERE o.replicate = r.replicate AND o.frequency = r.hi) >= 0.3")" = 2 ] &&
	ok adaptive.flux.brackets_hold || fail adaptive.flux.brackets_hold "$(cat flux.got; sqlite3 FLUX/study.db 'SELECT * FROM onset_replicate')"
ONSET="$(dirname "$SHAKE")/onset"
if [ -x "$ONSET" ]; then
	"$ONSET" flux --runs "$TMP/FLUX" --no-plot --no-store --out "$TMP/FLUXAN" >onset.log 2>&1
	awk -F, 'NR > 1 { print $3 "|" $9 }' FLUXAN/onset_runs.csv 2>/dev/null | sort >onset.phi
	cut -d'|' -f1,2 flux.got >flux.phi
	[ -s flux.phi ] && cmp -s onset.phi flux.phi && ok adaptive.flux.value_is_onset_phi ||
		fail adaptive.flux.value_is_onset_phi "search $(tr '\n' ' ' <flux.phi), bin/onset $(tr '\n' ' ' <onset.phi) $(tail -c 200 onset.log)"
fi

# --- a run that fails before it answers blocks its replicate, which keeps the bracket
# it had; the group is blocked (never done) with the failure as its reason; the search
# ends (exit 3: runs failed) and says so ---
{ campaign blocked; printf 'max_overlap = 0.02\n'; onset 'replicates = 2'; } >blocked.campaign
"$STUDY" run blocked.campaign --runs "$TMP/BLK" --jobs 2 >blocked.log 2>&1
rc=$?
"$STUDY" status blocked --runs "$TMP/BLK" >blocked.txt 2>&1
row=$(sqlite3 BLK/study.db "SELECT blocked || '|' || state || '|' || IFNULL(estimate, 'none') FROM onset_group")
reason=$(sqlite3 BLK/study.db "SELECT reason FROM onset_group")
[ "$rc" -eq 3 ] && [ "$row" = "2|blocked|none" ] && grep -q "onset none (no replicate answered)" blocked.log &&
	grep -q "all: .*: blocked (replicate 1 at 7 Hz: overlap before shaking: settling: overlap of disks" blocked.log &&
	grep -q "blocked: 1 of 1 search groups blocked, 2 runs failed" blocked.log &&
	case $reason in "replicate 1 at 7 Hz: overlap before shaking: "*) true ;; *) false ;; esac &&
	[ "$(sqlite3 BLK/study.db "SELECT state FROM onset_search")" = blocked ] &&
	grep -qF "brackets of all: 1 [~5, ~9] failed at 7; 2 [~5, ~9] failed at 7" blocked.txt &&
	grep -qF "all blocked: replicate 1 at 7 Hz: overlap before shaking: " blocked.txt &&
	ok adaptive.failed_run_blocks_group || fail adaptive.failed_run_blocks_group "exit $rc, group $row, reason '$reason': $(cat blocked.log blocked.txt)"

# --- a bed that throws grains over its walls while shaking (left_box) is far above the
# onset: the run counts as on and the bracket moves down past it; with walls 12 cm high
# every point of this range does, so the replicate's onset lies below the range, and the
# campaign ends well (exit 0: those runs are outcomes, not failures). The
# same failure while the bed settles says nothing of the drive: blocked ---
{ campaign leftbox; printf 'wall_height = 12\n'; onset 'replicates = 1'; } >leftbox.campaign
"$STUDY" run leftbox.campaign --runs "$TMP/LB" --jobs 2 >leftbox.log 2>&1
rc=$?
chain=$(sqlite3 LB/study.db "SELECT group_concat(printf('%g', frequency) || ':' || class, ' ') FROM (SELECT * FROM onset_run
	ORDER BY step)")
st=$(sqlite3 LB/study.db "SELECT r.state || '|' || g.state FROM onset_replicate r JOIN onset_group g USING (campaign, grp)")
fails=$(sqlite3 LB/study.db "SELECT COUNT(*) FROM runs WHERE status = 'left_box' AND steps > 0")
# every group done: exit 0, the runs said as what they were (not as failures)
[ "$rc" -eq 0 ] && [ "$chain" = "7:on 6:on 5.5:on 5:on" ] && [ "$st" = "below|done" ] && [ "$fails" = 4 ] &&
	grep -qF "4 runs ended early, their outcome used by the search as designed (4 left_box" leftbox.log &&
	! grep -q "runs failed" leftbox.log &&
	ok adaptive.left_box_counts_on || fail adaptive.left_box_counts_on "exit $rc, chain '$chain', state $st, $fails left_box: $(tail -c 400 leftbox.log)"
sed 's/^wall_height = 12$/wall_height = 9/; s/^name = leftbox$/name = spills/' leftbox.campaign >spills.campaign
"$STUDY" run spills.campaign --runs "$TMP/LB" --jobs 2 >spills.log 2>&1
rc=$?
row=$(sqlite3 LB/study.db "SELECT state || '|' || reason FROM onset_group WHERE campaign = 'spills'")
case $row in "blocked|replicate 1 at 7 Hz: left_box before shaking: "*) r=1 ;; *) r=0 ;; esac
[ "$rc" -eq 3 ] && [ "$r" = 1 ] && ok adaptive.left_box_settling_blocks ||
	fail adaptive.left_box_settling_blocks "exit $rc, group '$row': $(tail -c 300 spills.log)"

# --- one range for every amplitude: a search in Gamma; each group runs its own
# frequencies, f = sqrt(Gamma g / A) / 2 pi, and the first points are said before the
# start, with a warning where the model fails (above Gamma 1.6 at the first point) ---
{ campaign gamma; printf '[grid]\namplitude = 1, 3\n[onset]\nobservable = rise\naxis = gamma\nfrom = 0.5\nto = 2.9\n'
	printf 'tolerance = 1\nreplicates = 1\n'; } | sed 's/^amplitude = 1$//' >gamma.campaign
"$STUDY" expand gamma.campaign >gexp.tsv 2>gexp.err
f=$(awk -F'\t' 'NR > 1 { print $5 ":" $6 }' gexp.tsv | sort | tr '\n' ' ')
# the first point, Gamma 1.7: at A = 1 cm 6.49949 Hz, at 3 cm 3.75248 Hz
f1=$(awk 'BEGIN { printf "%.12g %.12g", sqrt(1.7 * 981 / 1) / 6.283185307179586, sqrt(1.7 * 981 / 3) / 6.283185307179586 }')
[ "$f" = "1:${f1% *} 3:${f1#* } " ] && [ "$f1" = "6.49948724824 3.75248071237" ] &&
	grep -qF "group amplitude=3 (amplitude 3 cm): first point 3.75248 Hz (Gamma 1.7, v 70.7 cm/s)" gexp.err &&
	grep -qF "warning: group amplitude=3: the first point, 3.75248 Hz, is at Gamma 1.7, at or above 1.6" gexp.err &&
	ok adaptive.gamma.first_points || fail adaptive.gamma.first_points "runs '$f': $(cat gexp.err)"
"$STUDY" run gamma.campaign --runs "$TMP/GM" --jobs 2 >gamma.log 2>&1
rc=$?
bad=$(sqlite3 GM/study.db "SELECT o.run FROM onset_run o JOIN runs r ON r.campaign = o.campaign AND r.id = o.run
	WHERE abs(r.gamma - o.axis_value) > 1e-9 * o.axis_value OR abs(o.frequency - r.frequency) > 0")
n=$(sqlite3 GM/study.db "SELECT COUNT(*) FROM onset_run")
grep -q "warning: group amplitude=3" gamma.log && [ "$n" -ge 2 ] && [ -z "$bad" ] &&
	[ "$(sqlite3 GM/study.db "SELECT axis FROM onset_search")" = gamma ] && ok adaptive.gamma.runs_at_their_gamma ||
	fail adaptive.gamma.runs_at_their_gamma "exit $rc, $n runs, off: '$bad': $(tail -c 400 gamma.log)"

# --- a changed range: the recorded runs are no chain's any more: refused, nothing runs ---
sed 's/^to = 9$/to = 8/' rise.campaign >changed.campaign
out=$("$STUDY" run changed.campaign --runs "$TMP/REF" 2>&1)
rc=$?
[ "$rc" -eq 1 ] && printf '%s' "$out" | grep -q "campaign rise changed since it was recorded" && ok adaptive.changed_range_refused ||
	fail adaptive.changed_range_refused "exit $rc: $out"
finish
