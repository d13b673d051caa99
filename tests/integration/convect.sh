#!/usr/bin/env bash
# convect.sh - bin/convect end to end on a tiny real campaign (150 grains in a 20 cm
# box, fast preset, 6 s at 3 and 6 Hz, walls and periodic sides, field = yes and no,
# 3 seeds: 24 runs, about 3 s of CPU in the release build, which runs it: the tool is
# what is tested, lib.sh's data_driver_setup): the table, CSV files,
# figure and stored rows; the runs without a field counted per group as unusable and
# listed with why; every used run's S recomputed here from its file with h5dump and
# awk (band rows from the cell size and the settled surface height, count-weighted
# rms per block, mean after the transient), independently of analysis/measure/convect.c; the
# bed shaken at 6 Hz (Gamma 1.45) convects more than at 3 Hz (0.36). Then the options:
# --band, --no-store, reproducibility, errors.
# tier: slow: a campaign long enough for convection rolls
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
data_driver_setup
cd "$TMP" || exit 1
CONVECT="$BINDIR/convect"
[ -x "$CONVECT" ] || { fail setup "$CONVECT is not an executable (run make)"; finish; }
png_ok() { [ -s "$1" ] && [ "$(head -c 4 "$1" | od -An -c | tr -d ' ')" = '211PNG' ]; }
pdf_ok() { [ -s "$1" ] && [ "$(head -c 4 "$1")" = '%PDF' ]; }
rel() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { if (a == "nan" && b == "nan") exit 0; d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; exit !(a != "" && b != "" && d <= t * m + 1e-12) }'; }

printf '[campaign]\nname = cv\nseed = 3\nreplicates = 3\n[scene]\npreset = fast\n'"$(tiny_scene n_grains=150 radius_ratio=0)"'\namplitude = 1\nduration = 6\nfield_periods = 5\n[grid]\nsides = walls, periodic\nfrequency = 3, 6\nfield = yes, no\n' >cv.campaign
t0=$SECONDS
"$DATA_STUDY" run cv.campaign --runs "$TMP/R" --jobs 2 --no-progress >study.log 2>&1
rc=$?
echo "# campaign: $((SECONDS - t0)) s"
[ "$rc" -eq 0 ] && [ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 24 ] && ok setup.campaign ||
	{ fail setup.campaign "study exit $rc: $(tail -c 300 study.log)"; finish; }

"$CONVECT" cv --runs R --boot 300 --seed 4 >cv.out 2>cv.err
rc=$?
A=R/cv/analysis
[ "$rc" -eq 0 ] && ok convect.exit || fail convect.exit "exit $rc: $(cat cv.err)"
[ ! -s cv.err ] && ok convect.quiet || fail convect.quiet "$(head -c 300 cv.err)"
# the default groups: frequency and the swept sides (field is not a group: its runs are counted)
for g in 'frequency=3 sides=periodic' 'frequency=3 sides=walls' 'frequency=6 sides=periodic' 'frequency=6 sides=walls'; do
	grep -q "^$g  *3  *[0-9]*  *3 " cv.out || { fail convect.table "no row '$g' with 3 used, 3 without field: $(cat cv.out)"; break; }
done
grep -q '^group .*S cm \[t CI\] (n)' cv.out && ok convect.table
[ "$(tail -n +2 $A/convect_runs.csv | wc -l)" = 24 ] && [ "$(tail -n +2 $A/convect_accounting.csv | wc -l)" = 24 ] &&
	[ "$(tail -n +2 $A/convect_summary.csv | wc -l)" = 4 ] && [ "$(tail -n +2 $A/convect_points.csv | wc -l)" = 4 ] &&
	ok convect.csv || fail convect.csv "$(wc -l $A/convect_*.csv)"
png_ok $A/convect.png && pdf_ok $A/convect.pdf && ok convect.figure || fail convect.figure "$(ls $A)"
grep -q "title 'sides = walls'" $A/convect.gp && grep -q "title 'sides = periodic'" $A/convect.gp && ok convect.figure_curves ||
	fail convect.figure_curves "$(grep -c title $A/convect.gp) titles"

# ---- accounting: the runs without a field, as the database says ----
nf=$(q R/study.db "SELECT COUNT(*) FROM param WHERE campaign = 'cv' AND key = 'field' AND value = 'no'")
st() { q R/study.db "SELECT CAST(SUM(value) AS INT) FROM analysis WHERE campaign = 'cv' AND tool = 'convect' AND key = '$1'"; }
[ "$nf" = 12 ] && [ "$(st runs_unusable)" = "$nf" ] && [ "$(st no_field)" = "$nf" ] && [ "$(st runs)" = 12 ] &&
	[ "$(awk -F, 'NR > 1 && $7 == "unusable" && $10 == "no"' $A/convect_runs.csv | wc -l)" = "$nf" ] &&
	[ "$(grep -c 'field = no: no displacement field recorded' $A/convect_accounting.csv)" = "$nf" ] &&
	ok counts.no_field || fail counts.no_field "database $nf, stored unusable $(st runs_unusable) no_field $(st no_field) runs $(st runs)"
grep -q "^# $nf runs without a displacement field (field = no)" cv.out &&
	[ "$(grep -c '^#   not used: .*field = no' cv.out)" = "$nf" ] && ok counts.listed || fail counts.listed "$(grep '^#' cv.out)"
# every stored estimate says how many runs it rests on
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 'cv' AND tool = 'convect' AND key IN ('strength', 'strength_u', 'strength_boot') AND n = 3 AND lo < value AND value < hi")" = 12 ] &&
	ok store.strength_rows || fail store.strength_rows "$(q R/study.db "SELECT grp, key, value, lo, hi, n FROM analysis WHERE tool = 'convect' AND key GLOB 'strength*'")"
# the stored strength is the mean of the runs' S in the CSV
bad=""
while IFS=, read -r g m; do
	s=$(q R/study.db "SELECT printf('%.17g', value) FROM analysis WHERE campaign = 'cv' AND tool = 'convect' AND key = 'strength' AND grp = '$g'")
	rel "$s" "$m" 1e-12 || bad="$bad $g: stored $s, runs $m;"
done < <(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "strength") k = i; next }
	$7 == "used" { gsub(/"/, "", $2); s[$2] += $k; n[$2]++ } END { for (g in s) printf "%s,%.17g\n", g, s[g] / n[g] }' $A/convect_runs.csv)
[ -z "$bad" ] && ok store.mean_of_runs || fail store.mean_of_runs "$bad"
# the persistence: stored per group on the runs with a pair of blocks; P = sqrt(max(0, C))
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis a JOIN analysis b ON a.grp = b.grp AND a.campaign = b.campaign AND a.tool = b.tool
	WHERE a.campaign = 'cv' AND a.tool = 'convect' AND a.key = 'persistent' AND b.key = 'persistence_c' AND a.n = 3
	AND abs(a.value - sqrt(max(0, b.value))) < 1e-12")" = 4 ] && ok store.persistence ||
	fail store.persistence "$(q R/study.db "SELECT grp, key, value, lo, hi, n FROM analysis WHERE tool = 'convect' AND key GLOB 'persist*'")"

# ---- each used run's S recomputed from its file ----
nchk=0 bad=""
while IFS=, read -r run blocks used S; do
	f=R/cv/$run.h5
	cell=$(attr "$f" /observables/field/cell)
	hs=$(attr "$f" /surface_height)
	read -r ny nx <<<"$(dims "$f" /observables/field/count/value | awk '{ print $2, $3 }')"
	read -r b2 u2 s2 <<<"$(paste -d' ' <(h5vals "$f" /observables/field/count/value) <(h5vals "$f" /observables/field/uy/value) |
		awk -v ny="$ny" -v nx="$nx" -v cell="$cell" -v hs="$hs" -v skip=0.2 '
		{ q = NR - 1; b = int(q / (ny * nx)); r = int((q % (ny * nx)) / nx); yc = (r + 0.5) * cell
		  if (b > B) B = b
		  if (yc >= 0.3 * hs && yc <= 0.7 * hs && $1 > 0) { w[b] += $1; s[b] += $1 * $2 * $2 } }
		END { B++; first = int(skip * B); if (first >= B) first = B - 1
		  for (b = first; b < B; b++) if (w[b] > 0) { m += sqrt(s[b] / w[b]); k++ }
		  printf "%d %d %.17g\n", B, k, m / k }')"
	nchk=$((nchk + 1))
	{ [ "$b2" = "$blocks" ] && [ "$u2" = "$used" ] && rel "$s2" "$S" 1e-9; } || bad="$bad $run: blocks $blocks/$b2 used $used/$u2 S $S/$s2;"
done < <(awk -F, 'NR > 1 && $7 == "used" { print $3 "," $11 "," $13 "," $16 }' $A/convect_runs.csv)
[ "$nchk" = 12 ] && [ -z "$bad" ] && ok recompute.runs_from_files || fail recompute.runs_from_files "$nchk runs checked:$bad"

# the strongly shaken bed convects more, with walls and without
sv() { q R/study.db "SELECT value FROM analysis WHERE campaign = 'cv' AND tool = 'convect' AND key = 'strength' AND grp = '$1'"; }
awk -v a="$(sv 'frequency=6 sides=walls')" -v b="$(sv 'frequency=3 sides=walls')" -v c="$(sv 'frequency=6 sides=periodic')" \
	-v d="$(sv 'frequency=3 sides=periodic')" 'BEGIN { exit !(a > 2 * b && c > 2 * d) }' && ok physics.stronger_at_6hz ||
	fail physics.stronger_at_6hz "$(q R/study.db "SELECT grp, value FROM analysis WHERE tool = 'convect' AND key = 'strength'")"

# ---- options ----
q R/study.db "SELECT grp, key, value, lo, hi, n FROM analysis WHERE tool = 'convect' ORDER BY grp, key" >rows1
"$CONVECT" cv --runs R --boot 300 --seed 4 --no-plot >/dev/null 2>&1
q R/study.db "SELECT grp, key, value, lo, hi, n FROM analysis WHERE tool = 'convect' ORDER BY grp, key" >rows2
cmp -s rows1 rows2 && ok convect.reproducible || fail convect.reproducible "$(diff rows1 rows2 | head -4)"
"$CONVECT" cv --runs R --band=0:2 --no-store --no-plot --out whole >/dev/null 2>e.txt
rc=$?
cmp -s rows1 <(q R/study.db "SELECT grp, key, value, lo, hi, n FROM analysis WHERE tool = 'convect' ORDER BY grp, key") &&
	[ "$rc" -eq 0 ] && ok convect.no_store || fail convect.no_store "exit $rc: $(cat e.txt)"
awk -F, 'NR > 1 && $7 == "used" && $15 <= rows { bad++ } NR > 1 && $7 == "used" { n++ } END { exit !(n == 12 && !bad) }' \
	rows="$(awk -F, 'NR == 2 { print $15 }' $A/convect_runs.csv)" whole/convect_runs.csv && ok convect.band_option ||
	fail convect.band_option "$(head -3 whole/convect_runs.csv)"
"$CONVECT" --help | grep -q -- '--band LO:HI' && "$CONVECT" --help | grep -q 'default 0.3:0.7' && ok cli.help || fail cli.help "no --band in the help"
"$CONVECT" cv --runs R --band 0.7:0.3 >/dev/null 2>e.txt
[ $? -eq 1 ] && grep -q -- '--band: LO must not exceed HI' e.txt && ok cli.bad_band || fail cli.bad_band "$(cat e.txt)"
"$CONVECT" cv --runs R --bnad 0.1:0.2 >/dev/null 2>e.txt
[ $? -eq 1 ] && grep -q 'did you mean --band' e.txt && ok cli.misspelt || fail cli.misspelt "$(cat e.txt)"
"$CONVECT" nosuch --runs R >/dev/null 2>e.txt
[ $? -eq 1 ] && grep -q "campaign 'nosuch' is not in" e.txt && ok cli.unknown_campaign || fail cli.unknown_campaign "$(cat e.txt)"
finish
