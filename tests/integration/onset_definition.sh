#!/usr/bin/env bash
# onset_definition.sh - one onset per campaign (docs/analysis.md, "One onset per
# campaign"; docs/campaigns.md, "One onset definition"): a tiny [onset] search over the
# flux whose runs stop by the flux gets the search's threshold as their
# stop_flux_threshold; bin/onset takes the search's threshold, band and skip as its
# defaults, prints the search's onset beside its own with both intervals and whether
# they overlap, and says so when an option changes the definition; a campaign whose
# stop_flux_threshold or band differs from [onset]'s is refused with file, line and key.
# tier: slow: four small [onset] searches run with the engine
. "$(dirname "$0")/lib.sh"
STUDY="${STUDY:-$(dirname "$SHAKE")/study}"
ONSET="$(dirname "$SHAKE")/onset"
[ -x "$STUDY" ] && [ -x "$ONSET" ] || { fail setup "no $STUDY or $ONSET (run make)"; finish; }
cd "$TMP" || exit 1

# 60 grains without intruder, 3 s of the fast preset at A = 1 cm: the mean flux through
# the middle of the bed crosses 0.3 particles per period between 5 and 9 Hz
campaign() { # extra [scene] lines
	cat <<C
[campaign]
name = od
seed = 11
[scene]
preset = fast
$(tiny_scene width=16 radius_ratio=0 depth=-)
amplitude = 1
duration = 3
traj_rate = 0
snapshots = no
flux = yes
stop = flux
stop_skip = 1
C
	[ $# -gt 0 ] && printf '%s\n' "$@"
	printf '[onset]\nobservable = flux\nfrom = 5\nto = 9\ntolerance = 1\nthreshold = 0.3\nband = 0.35:0.65\n'
	printf 'skip = 0.25\nreplicates = 3\nlevel = 0.5\n'
}

# --- the driver: a different stop threshold or band is refused, before anything runs ---
refused() { # ID EXPECTED [scene] lines...
	local id=$1 want=$2
	shift 2
	campaign "$@" >bad.campaign
	local out rc
	out=$("$STUDY" run bad.campaign --runs "$TMP/BAD" 2>&1)
	rc=$?
	if [ "$rc" -eq 1 ] && printf '%s' "$out" | grep -qF -- "$want" && [ ! -e BAD/od ]; then ok "$id"; else
		fail "$id" "exit $rc: $out"; fi
}
refused onset_def.driver.threshold_mismatch \
	"bad.campaign:18: stop_flux_threshold: 0.5 differs from [onset] threshold = 0.3 (line 24)" 'stop_flux_threshold = 0.5'
refused onset_def.driver.band_mismatch \
	"bad.campaign:18: stop_flux_lo: 0.4 differs from [onset] band = 0.35:0.65 (line 25)" 'stop_flux_lo = 0.4'
# the same values are no conflict
campaign 'stop_flux_threshold = 0.3' >same.campaign
"$STUDY" expand same.campaign --runs "$TMP/SAME" >same.out 2>same.err &&
	ok onset_def.driver.same_accepted || fail onset_def.driver.same_accepted "$(cat same.err)"

# --- the search; its runs stop by [onset]'s threshold and band ---
campaign >od.campaign
"$STUDY" run od.campaign --runs "$TMP/R" --jobs 2 >run.log 2>&1
rc=$?
[ "$rc" -eq 0 ] && grep -q "od: all: onset .*: done" run.log && ok onset_def.search.done ||
	{ fail onset_def.search.done "exit $rc: $(tail -c 400 run.log)"; finish; }
got=$(sqlite3 R/study.db "SELECT key || '=' || value FROM param WHERE key IN ('stop_flux_threshold',
	'stop_flux_lo', 'stop_flux_hi') GROUP BY key, value ORDER BY key")
[ "$(echo $got)" = "stop_flux_hi=0.65 stop_flux_lo=0.35 stop_flux_threshold=0.3" ] &&
	ok onset_def.driver.stop_from_onset || fail onset_def.driver.stop_from_onset "params: $(echo $got)"

# --- bin/onset: the search's definition by default, its onset beside ---
"$ONSET" od --runs "$TMP/R" --out "$TMP/A" --no-plot --boot 200 >a.out 2>&1
rc=$?
grep -q "^# onset: first f with mean Φ ≥ 0.3 in band 0.35–0.65, skip 0.25 (the \[onset\] search's definition)" a.out &&
	[ "$rc" -eq 0 ] && ok onset_def.onset.defaults_from_search || fail onset_def.onset.defaults_from_search "exit $rc: $(cat a.out)"
# the search's row: its estimate and interval in Hz as the driver stored them
want=$(sqlite3 R/study.db "SELECT printf('%.3f [%.3f, %.3f]', estimate, ci_lo, ci_hi) FROM onset_group WHERE campaign = 'od'")
row=$(grep -A1 "search f \[CI\] (Hz)" a.out | tail -n 1)
case "$row" in
*"$want done"*"Hz apart, within one bracket"* | *"$want done"*"Hz apart, more than one bracket"*) ok onset_def.onset.search_beside ;;
*) fail onset_def.onset.search_beside "want '$want done ... Hz apart ... bracket' in '$row'" ;;
esac
# agreement: the two estimates (the same replicates' runs) at most one bracket apart,
# the search's tolerance of 1 Hz here; the row says how far apart they are
read -r se te <<<"$(printf '%s\n' "$row" | sed 's/[][,]/ /g' | awk '{ print $3, $7 }')"
agree=$(awk -v a="$se" -v b="$te" 'BEGIN { d = a - b; if (d < 0) d = -d; print d <= 1 + 1e-9 ? "yes" : "no" }')
said=$(printf '%s\n' "$row" | sed -n 's/.* \(yes\|no\): \([0-9.]*\) Hz apart.*(1.000 Hz)$/\1 \2/p')
# (the row's gap from the unrounded estimates: within the rounding of the printed ones)
awk -v s="$said" -v w="$agree" -v a="$se" -v b="$te" 'BEGIN { split(s, v, " "); d = a - b; if (d < 0) d = -d
	exit !(v[1] == w && v[2] - d <= 0.0011 && d - v[2] <= 0.0011) }' && ok onset_def.onset.agreement ||
	fail onset_def.onset.agreement "estimates $se and $te: want '$agree: (their gap) Hz apart (1.000 Hz)' in '$row'"
# the threshold interval holds the sampled frequencies around the crossing
awk -F, 'NR > 1 { print $8 }' A/onset_runs.csv | sort -gu >freqs
thr=$(awk -F, 'NR == 2 { print $11, $12, $13 }' A/onset_summary.csv)
awk -v t="$thr" 'BEGIN { split(t, v, " ") } { if ($1 < v[1]) a = $1; else if (b == "") b = $1 }
	END { exit !(a != "" && b != "" && v[2] <= a && v[3] >= b) }' freqs &&
	ok onset_def.onset.interval_resolved || fail onset_def.onset.interval_resolved "onset $thr, frequencies $(echo $(cat freqs))"
[ "$(sqlite3 R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 'od' AND tool = 'onset' AND key = 'search_f'")" = 1 ] &&
	ok onset_def.onset.search_stored || fail onset_def.onset.search_stored "no search_f row"

# the intervals at the search's level (0.5 here), so that "agree" compares like with
# like; --level sets another, and then nothing is taken from the search
grep -q "^# intervals at 50 %: the \[onset\] search's level" a.out &&
	[ "$(sqlite3 R/study.db "SELECT COUNT(*) FROM analysis_def WHERE campaign = 'od' AND tool = 'onset'
		AND options LIKE '%level=0.5%'")" = 1 ] && ok onset_def.onset.level_from_search ||
	fail onset_def.onset.level_from_search "$(head -n 4 a.out; sqlite3 R/study.db "SELECT options FROM analysis_def")"
"$ONSET" od --runs "$TMP/R" --out "$TMP/L" --no-plot --no-store --boot 200 --level 0.8 >l.out 2>&1
! grep -q "^# intervals at" l.out && grep -q "its 50 % interval" l.out && ok onset_def.onset.level_given ||
	fail onset_def.onset.level_given "$(head -n 4 l.out)"

# --- an option that changes the definition is flagged; one that repeats it is not ---
"$ONSET" od --runs "$TMP/R" --out "$TMP/B" --no-plot --no-store --boot 200 --threshold 0.5 >b.out 2>&1
grep -q "^# onset: first f with mean Φ ≥ 0.5 in band 0.35–0.65, skip 0.25 (set on the command line: differs from the search's)" b.out &&
	grep -q "^# the search's: first f with |mean Φ| ≥ 0.3 in band 0.35–0.65, skip 0.25" b.out &&
	ok onset_def.onset.override_flagged || fail onset_def.onset.override_flagged "$(head -n 3 b.out)"
"$ONSET" od --runs "$TMP/R" --out "$TMP/C" --no-plot --no-store --boot 200 --band 0.35:0.65 >c.out 2>&1
grep -q "(the \[onset\] search's definition)" c.out && ! grep -q "differs" c.out &&
	ok onset_def.onset.same_not_flagged || fail onset_def.onset.same_not_flagged "$(head -n 3 c.out)"

# --- several campaigns: their common definition, or none when their searches differ ---
# (the same search under other names, in the same database: the recorded ids are reused)
pooled() { # NAME THRESHOLD
	campaign | sed "s/^name = od$/name = $1/; s/^threshold = 0.3$/threshold = $2/" >"$1.campaign"
	"$STUDY" run "$1.campaign" --runs "$TMP/R" --jobs 2 >"$1.log" 2>&1 || fail "onset_def.pooled.$1" "$(tail -c 300 "$1.log")"
}
pooled od2 0.3
pooled od3 0.5
"$ONSET" od od2 --runs "$TMP/R" --out "$TMP/P" --no-plot --no-store --boot 200 >p.out 2>&1
grep -q "^# onset: first f with mean Φ ≥ 0.3 in band 0.35–0.65, skip 0.25 (the \[onset\] searches' definition, the same in every campaign)" p.out &&
	! grep -q "search f \[CI\]" p.out && ok onset_def.pooled.same_definition || fail onset_def.pooled.same_definition "$(head -n 3 p.out)"
"$ONSET" od od3 --runs "$TMP/R" --out "$TMP/Q" --no-plot --no-store --boot 200 >q.out 2>&1
grep -q "^# several campaigns, their searches' definitions differ: no \[onset\] definition applies" q.out &&
	grep -q "^# onset: first f with mean Φ halfway up the step of band 0.4–0.6, skip 0.2 (this tool's)" q.out &&
	ok onset_def.pooled.definitions_differ || fail onset_def.pooled.definitions_differ "$(head -n 3 q.out)"
finish
