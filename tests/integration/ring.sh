#!/usr/bin/env bash
# ring.sh - claim 3's ring end to end: two tiny campaigns (each with and without
# intruder) run by bin/study, then bin/ring on them. The ring's series in a run file
# (/observables/ring: shape, one shared clock at ring_rate, the fixed centre) and its
# before-the-rise averages against the mean of the series' samples before the waiting
# time, computed here from the file; the tool's table, CSV files, figure and stored
# rows; and a case whose direction is clear: at rest, the grains around a heavy
# intruder carry more force than the same grains without it.
# tier: slow: campaigns for the ring observable
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
cd "$TMP" || exit 1
RING="$BINDIR/ring"
[ -x "$RING" ] || { fail setup "$RING is not an executable (run make)"; finish; }
png_ok() { [ -s "$1" ] && [ "$(head -c 4 "$1" | od -An -c | tr -d ' ')" = '211PNG' ]; }
pdf_ok() { [ -s "$1" ] && [ "$(head -c 4 "$1")" = '%PDF' ]; }
# rel A B TOL : |A - B| <= TOL |B|
rel() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; exit !(a != "" && b != "" && d <= t * m) }'; }

# "shake": observables_rise.sh's scene (100 grains, a 3x intruder that rises within
# ~4 s at 4 Hz, A = 2 cm), the ring at 100 Hz around where the intruder settled
# (without one: ring_y, about where it settles), from 0.5 s on. "rest": the bed at rest
# (no drive) with a 4x intruder (16 grain masses, its weight on the few grains beneath
# it) and without, the ring its first shell (4-6.5 cm from the centre of an intruder of
# radius 4 cm), 12 seeds each: the packings differ a lot (sum |F| 85-170 kdyn without,
# 108-216 kdyn with, over 16 seeds: a ratio of 1.21), so fewer seeds may point either way.
BED="$(tiny_scene n_grains=100 width=24 radius_ratio=-)
ring = yes
ring_centre = settled"
printf '[campaign]\nname = shake\nseed = 11\nreplicates = 2\n[scene]\n%s\namplitude = 2\nduration = 4\nring_rate = 100\nring_y = 4.3\nring_from = 0.5\n[grid]\nradius_ratio = 0, 3\nfrequency = 4, 4.5\n' "$BED" >shake.campaign
printf '[campaign]\nname = rest\nseed = 1\nreplicates = 12\n[scene]\n%s\nfrequency = 0\namplitude = 0\nduration = 0.1\nring_rate = 50\nring_inner = 4\nring_outer = 6.5\nring_y = 5.5\n[grid]\nradius_ratio = 0, 4\n' "$BED" >rest.campaign
# "shake" (8 runs of 4 s, most of this script's time) is run by the release engine (lib.sh's
# data_driver_setup: the tool is under test, and both builds write the same bits); "rest"
# by the engine under test, so that its ring (ring_centre = settled, ring_inner and
# ring_outer) is still written under ASan/UBSan here
data_driver_setup
t0=$SECONDS
"$DATA_STUDY" run shake.campaign --runs "$TMP/R" --jobs 2 --no-progress >study_s.log 2>&1 &&
	"$STUDY" run rest.campaign --runs "$TMP/R" --jobs 2 --no-progress >study_r.log 2>&1
rc=$?
echo "# campaigns: $((SECONDS - t0)) s"
[ "$rc" -eq 0 ] && [ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 32 ] && ok setup.campaigns ||
	{ fail setup.campaigns "study exit $rc: $(tail -c 300 study_s.log study_r.log)"; finish; }

# ---- the series in a run file: a run whose intruder rose ----
run=$(q R/study.db "SELECT run FROM result WHERE campaign = 'shake' AND risen = 1 ORDER BY run LIMIT 1")
F=R/shake/$run.h5
[ -n "$run" ] && [ -s "$F" ] && ok series.a_risen_run || { fail series.a_risen_run "no run of 'shake' rose: $(q R/study.db "SELECT run, risen, waiting_time FROM result WHERE campaign = 'shake'")"; finish; }
G=/observables/ring
n=$(attr "$F" /ring/samples)
dur=$(h5param "$F" duration)
# 100 Hz over 4 s: a sample at 0.01, 0.02, ..., 4 s
[ "$n" = 400 ] && [ "$(dims "$F" $G/mean_force/value)" = 400 ] && [ "$(dims "$F" $G/net_force/value)" = 400 ] &&
	[ "$(dims "$F" $G/temperature/value)" = 400 ] && [ "$(dims "$F" $G/grains/value)" = 400 ] &&
	[ "$(dims "$F" $G/centre/value)" = "400 2" ] && ok series.shape ||
	fail series.shape "samples $n, mean_force $(dims "$F" $G/mean_force/value), centre $(dims "$F" $G/centre/value)"
h5vals "$F" $G/mean_force/time >t.txt
same=1
for x in net_force temperature grains centre; do
	cmp -s t.txt <(h5vals "$F" $G/$x/time) || same=0
done
awk -v n=400 -v d="$dur" '{ if (($1 - NR * d / n) > 1e-9 || (NR * d / n - $1) > 1e-9) bad = 1 } END { exit bad || NR != n }' t.txt &&
	[ "$same" = 1 ] && ok series.one_clock_at_ring_rate || fail series.one_clock_at_ring_rate "times $(head -3 t.txt | tr '\n' ' ')..."
# the centre: fixed where the intruder settled (box frame), the /ring attributes say so
yc=$(attr "$F" /ring/centre_y)
[ "$(attr "$F" /ring/centre)" = settled ] && rel "$yc" "$(attr "$F" /intruder_settled_y)" 1e-15 &&
	h5vals "$F" $G/centre/value | awk -v y="$yc" 'NR % 2 == 0 && $1 != y { bad = 1 } END { exit bad }' &&
	ok series.settled_centre || fail series.settled_centre "centre '$(attr "$F" /ring/centre)' y $yc, settled $(attr "$F" /intruder_settled_y)"
# before the rise: the mean of the samples at ring_from <= t < waiting_time
wt=$(attr "$F" /waiting_time)
for x in mean_force net_force temperature grains; do
	paste -d' ' t.txt <(h5vals "$F" $G/$x/value) |
		awk -v w="$wt" -v f=0.5 '$1 >= f && $1 < w { s += $2; n++ } END { printf "%d %.17g\n", n, n ? s / n : 0 }' >b.txt
	read -r nb mb <b.txt
	[ "$nb" = "$(attr "$F" /ring/samples_before)" ] && [ "$nb" -gt 0 ] && [ "$nb" -lt 400 ] &&
		rel "$(attr "$F" /ring/${x}_before)" "$mb" 1e-12 && ok "before.$x" ||
		fail "before.$x" "file: $(attr "$F" /ring/samples_before) samples, ${x}_before $(attr "$F" /ring/${x}_before); series before t = $wt: $nb samples, mean $mb"
done
[ "$(attr "$F" /ring/before_to)" = "$wt" ] && ok before.window_ends_at_the_rise ||
	fail before.window_ends_at_the_rise "before_to $(attr "$F" /ring/before_to), waiting_time $wt"

# ---- bin/ring on the shaken campaign ----
"$RING" shake --runs R --boot 200 --seed 3 >ring.out 2>ring.err
rc=$?
A=R/shake/analysis
[ "$rc" -eq 0 ] && ok ring.exit || fail ring.exit "exit $rc: $(cat ring.err)"
[ ! -s ring.err ] && ok ring.quiet || fail ring.quiet "$(head -c 300 ring.err)"
grep -q '^group .*ratio sum|F|' ring.out && grep -q '^radius_ratio=3 frequency=4 ' ring.out &&
	grep -q '^radius_ratio=0 frequency=4.5 ' ring.out && ok ring.table || fail ring.table "$(cat ring.out)"
# 4 groups (0 and 3 at two frequencies), 2 with a ratio of 3 quantities, 8 runs
[ "$(tail -n +2 $A/ring_summary.csv | wc -l)" = 4 ] && [ "$(tail -n +2 $A/ring_ratios.csv | wc -l)" = 6 ] &&
	[ "$(tail -n +2 $A/ring_runs.csv | wc -l)" = 8 ] && [ "$(tail -n +2 $A/ring_accounting.csv | wc -l)" = 8 ] &&
	ok ring.csv || fail ring.csv "$(wc -l $A/ring_*.csv)"
png_ok $A/ring.png && pdf_ok $A/ring.pdf && ok ring.figure || fail ring.figure "$(ls $A)"
grep -q 'paper: +15 %' $A/ring.gp && grep -q '⟨Σ|F|⟩ ratio' $A/ring.gp && ok ring.figure_text || fail ring.figure_text "$(grep -c . $A/ring.gp) lines"
# stored: a ratio of each quantity per group with an intruder (n = its 2 runs), a mean per
# group, the accounting; the censored runs are those the database says did not rise
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 'shake' AND tool = 'ring' AND key IN ('ratio_force',
	'ratio_net_force', 'ratio_temperature') AND radius_ratio = 3 AND n = 2 AND value > 0 AND lo <= value AND hi >= value")" = 6 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE tool = 'ring' AND key = 'force' AND campaign = 'shake' AND value > 0")" = 4 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE tool = 'ring' AND key = 'runs_failed' AND campaign = 'shake'")" = 4 ] &&
	ok ring.db_rows || fail ring.db_rows "$(q R/study.db "SELECT grp, key, value, lo, hi, n FROM analysis WHERE tool = 'ring'")"
[ "$(q R/study.db "SELECT CAST(SUM(value) AS INT) FROM analysis WHERE tool = 'ring' AND campaign = 'shake' AND key = 'runs_censored'")" = \
	"$(q R/study.db "SELECT COUNT(*) FROM result WHERE campaign = 'shake' AND risen = 0")" ] && ok ring.censored_counted ||
	fail ring.censored_counted "$(q R/study.db "SELECT grp, value FROM analysis WHERE tool = 'ring' AND key = 'runs_censored'")"
# the ratio is the ratio of the groups' means, which are the runs' before-the-rise averages
m3=$(awk -F, 'NR > 1 && $2 == "\"radius_ratio=3 frequency=4\"" { s += $12; n++ } END { printf "%.17g", s / n }' $A/ring_runs.csv)
m0=$(awk -F, 'NR > 1 && $2 == "\"radius_ratio=0 frequency=4\"" { s += $12; n++ } END { printf "%.17g", s / n }' $A/ring_runs.csv)
r=$(q R/study.db "SELECT value FROM analysis WHERE tool = 'ring' AND campaign = 'shake' AND key = 'ratio_force' AND frequency = 4")
rel "$r" "$(awk -v a="$m3" -v b="$m0" 'BEGIN { printf "%.17g", a / b }')" 1e-12 && ok ring.ratio_of_means ||
	fail ring.ratio_of_means "stored $r, runs $m3 / $m0"
# reproducible: the same seed gives the same rows
q R/study.db "SELECT grp, key, value, lo, hi FROM analysis WHERE tool = 'ring' ORDER BY grp, key" >rows1
"$RING" shake --runs R --boot 200 --seed 3 --no-plot >/dev/null 2>&1
q R/study.db "SELECT grp, key, value, lo, hi FROM analysis WHERE tool = 'ring' ORDER BY grp, key" >rows2
cmp -s rows1 rows2 && ok ring.reproducible || fail ring.reproducible "$(diff rows1 rows2 | head -4)"

# ---- the clear case: at rest, a heavy intruder's first shell carries more ----
"$RING" rest --runs R --boot 200 >rest.out 2>rest.err
rc=$?
rf=$(q R/study.db "SELECT value FROM analysis WHERE tool = 'ring' AND campaign = 'rest' AND key = 'ratio_force' AND radius_ratio = 4")
[ "$rc" -eq 0 ] && awk -v r="$rf" 'BEGIN { exit !(r > 1) }' && ok rest.heavier_intruder_raises_force ||
	fail rest.heavier_intruder_raises_force "exit $rc, ratio of sum|F| $rf: $(cat rest.out rest.err | head -c 400)"
# at rest nothing moves: the temperature with and without is tiny against the shaken one
tr=$(q R/study.db "SELECT MAX(value) FROM analysis WHERE tool = 'ring' AND campaign = 'rest' AND key = 'temperature'")
ts=$(q R/study.db "SELECT MIN(value) FROM analysis WHERE tool = 'ring' AND campaign = 'shake' AND key = 'temperature'")
awk -v a="$tr" -v b="$ts" 'BEGIN { exit !(a >= 0 && a < 0.01 * b) }' && ok rest.no_temperature ||
	fail rest.no_temperature "at rest $tr, shaken $ts cm^2/s^2"

# ---- usage ----
"$RING" --help >help.out 2>&1 && grep -q '^usage: ring CAMPAIGN' help.out && ok usage.help || fail usage.help "$(head -3 help.out)"
"$RING" shake --runs R --boto 5 >bad.out 2>&1
[ $? -eq 1 ] && grep -q 'did you mean --boot' bad.out && ok usage.bad_option || fail usage.bad_option "$(cat bad.out)"
"$RING" shake --runs R --by frequency >by.out 2>&1
[ $? -eq 1 ] && grep -q 'radius_ratio' by.out && ok usage.by_needs_radius_ratio || fail usage.by_needs_radius_ratio "$(cat by.out)"
"$RING" nosuch --runs R >none.out 2>&1
[ $? -eq 1 ] && grep -q "campaign 'nosuch' is not in" none.out && ok usage.unknown_campaign || fail usage.unknown_campaign "$(cat none.out)"
echo "# ring.sh: $((SECONDS - t0)) s"
finish
