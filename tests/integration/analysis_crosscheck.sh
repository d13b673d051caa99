#!/usr/bin/env bash
# analysis_crosscheck.sh - the analysis tools' numbers against an independent
# computation (h5dump + awk) from the run files of two tiny campaigns: Phi through the
# plane per run (onset), the stored rows against the CSV, the Phi(D) profile (Fig. 3),
# the count-weighted displacement field (Fig. 1), the fraction risen (waiting); the
# legs of an up-down ramp with a hold (the hold's periods left out, the running mean
# kept within a leg); Fig. 1 and 3 of a campaign read without an intruder system.
# The campaigns are run by the release engine (lib.sh's data_driver_setup: the tools are
# what is tested).
# tier: slow: campaigns whose answers the tools must agree on
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
data_driver_setup
cd "$TMP" || exit 1
vals() { h5vals "$@"; } # lib.sh
# close A B : |A - B| <= 1e-12 (1 + |B|)
close() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; exit !(a != "" && b != "" && d <= 1e-12 * (1 + m)) }'; }

SCENE="$(tiny_scene radius_ratio=-)
amplitude = 1
flux = yes"
printf '[campaign]\nname = c\nseed = 21\nreplicates = 2\n[scene]\n%s\nduration = 1\ntraj_rate = 100\nfield = yes\nfield_periods = 2\n[grid]\nradius_ratio = 0, 2\nfrequency = 4, 6\n' "$SCENE" >c.campaign
printf '[campaign]\nname = d\nseed = 23\n[scene]\n%s\nradius_ratio = 2\nduration = 0.5\n[grid]\ndepth = 0, 1\nfrequency = 4, 6\n' "$(echo "$SCENE" | grep -v '^depth')" >d.campaign
printf '[campaign]\nname = r\nseed = 22\nreplicates = 2\n[scene]\n%s\nradius_ratio = 0\nduration = 4.5\nramp = updown\nramp_from = 3\nramp_to = 7\nramp_hold = 0.5\n' "$SCENE" >r.campaign
t0=$SECONDS
"$DATA_STUDY" run c.campaign --runs "$TMP/R" --jobs 2 --no-progress >study_c.log 2>&1 &&
	"$DATA_STUDY" run r.campaign --runs "$TMP/R" --jobs 2 --no-progress >study_r.log 2>&1 &&
	"$DATA_STUDY" run d.campaign --runs "$TMP/R" --jobs 2 --no-progress >study_d.log 2>&1
rc=$?
echo "# campaigns: $((SECONDS - t0)) s"
[ "$rc" -eq 0 ] && [ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 14 ] && ok setup.campaigns ||
	{ fail setup.campaigns "study exit $rc: $(tail -c 300 study_c.log study_r.log study_d.log)"; finish; }
A=R/c/analysis

# ---- onset: Phi through the plane (lines at 0.4..0.6 of the surface, periods after the first 20 %) ----
"$BINDIR/onset" c --runs R --boot 30 >onset.out 2>onset.err || fail onset.run "$(cat onset.err)"
# plane_phi FILE : the mean over the periods p >= floor(0.2 P) of the mean of phi over the band's lines
plane_phi() {
	local f=$1 P L S
	set -- $(dims "$f" /observables/flux/phi/value)
	P=$1 L=$2
	S=$(attr "$f" /observables/flux/surface_height)
	{ vals "$f" /observables/flux/heights; vals "$f" /observables/flux/phi/value; } | awk -v P="$P" -v L="$L" -v S="$S" '
		NR <= L { h[NR - 1] = $1; next } { v[NR - 1 - L] = $1 }
		END { n = 0; for (l = 0; l < L; l++) if (h[l] >= 0.4 * S && h[l] <= 0.6 * S) sel[n++] = l
		      p0 = int(0.2 * P); s = 0
		      for (p = p0; p < P; p++) { m = 0; for (i = 0; i < n; i++) m += v[p * L + sel[i]]; s += m / n }
		      printf "%.17g\n", s / (P - p0) }'
}
bad=0 n=0
while IFS=, read -r _ _ run _ _ _ _ _ phi _; do
	n=$((n + 1))
	want=$(plane_phi "R/c/$run.h5")
	close "$phi" "$want" || { bad=1; echo "# run $run: onset $phi, from the file $want"; }
done < <(tail -n +2 $A/onset_runs.csv)
[ "$n" = 8 ] && [ "$bad" = 0 ] && ok onset.plane_phi_matches_file || fail onset.plane_phi_matches_file "$n runs, mismatch $bad"
# the stored numbers are the summary's
bad=0
while IFS=, read -r grp _ _ _ _ f0 _ _ _ _ thr _; do
	grp=${grp//\"/}
	for kv in "sigmoid_f0 $f0" "threshold_f $thr"; do
		set -- $kv
		v=$(q R/study.db "SELECT printf('%.17g', value) FROM analysis WHERE campaign = 'c' AND tool = 'onset' AND grp = '$grp' AND key = '$1'")
		[ -z "$v" ] && case "$2" in nan | -nan) continue ;; esac
		close "$v" "$2" || { bad=1; echo "# $grp $1: stored '$v', csv '$2'"; }
	done
done < <(tail -n +2 $A/onset_summary.csv)
[ "$bad" = 0 ] && [ "$(tail -n +2 $A/onset_summary.csv | wc -l)" = 2 ] && ok onset.stored_equals_csv ||
	fail onset.stored_equals_csv "stored rows differ from onset_summary.csv"

# ---- figures: Fig. 3 profile and Fig. 1 field of the panel f = 6 Hz, R = 2 ----
"$BINDIR/figures" c --runs R >figures.out 2>figures.err || fail figures.run "$(cat figures.err)"
ids=$(q R/study.db "SELECT id FROM runs WHERE campaign = 'c' AND radius_ratio = 2 AND frequency = 6 ORDER BY id")
# time mean per line after the first 20 % of the periods, averaged over the panel's runs
for id in $ids; do
	set -- $(dims "R/c/$id.h5" /observables/flux/phi/value)
	{ vals "R/c/$id.h5" /observables/flux/heights; vals "R/c/$id.h5" /observables/flux/phi/value; } |
		awk -v P="$1" -v L="$2" 'NR <= L { h[NR - 1] = $1; next } { v[NR - 1 - L] = $1 }
			END { p0 = int(0.2 * P); for (l = 0; l < L; l++) { s = 0; for (p = p0; p < P; p++) s += v[p * L + l]
			      printf "%d %.17g %.17g\n", l, h[l], s / (P - p0) } }'
done | awk '{ D[$1] += $2; F[$1] += $3; n[$1]++ } END { for (l in D) printf "%d %.17g %.17g\n", l, D[l] / n[l], F[l] / n[l] }' |
	sort -n >fig3.want
awk -F, 'NR > 1 && $3 == 6 && $2 == 1 { print $5, $6, $7 }' $A/fig3_profile.csv | sort -n >fig3.got
paste -d' ' fig3.got fig3.want | awk '{ for (k = 2; k <= 3; k++) { d = $k - $(k + 3); if (d < 0) d = -d; if (d > 1e-12 * (1 + ($k < 0 ? -$k : $k))) bad = 1 }
	if ($1 != $4) bad = 1 } END { exit !(NR == 80 && !bad) }' &&
	ok figures.fig3_profile_matches_files || fail figures.fig3_profile_matches_files "$(paste -d' ' fig3.got fig3.want | head -n 3)"
# Fig. 1: per cell the count-weighted mean displacement over every block of both runs;
# the grid is one mean diameter of each run's grains, so the second run's cells go by
# their centres into the first run's grid
id1=$(echo "$ids" | head -n 1)
set -- $(dims "R/c/$id1.h5" /observables/field/count/value)
NY=$2 NX=$3
CELL=$(attr "R/c/$id1.h5" /observables/field/cell) X0=$(attr "R/c/$id1.h5" /observables/field/x0)
for id in $ids; do
	set -- $(dims "R/c/$id.h5" /observables/field/count/value)
	paste -d' ' <(vals "R/c/$id.h5" /observables/field/count/value) <(vals "R/c/$id.h5" /observables/field/ux/value) <(vals "R/c/$id.h5" /observables/field/uy/value) |
		awk -v ny="$2" -v nx="$3" -v ci="$(attr "R/c/$id.h5" /observables/field/cell)" -v xi="$(attr "R/c/$id.h5" /observables/field/x0)" \
			-v cell="$CELL" -v x0="$X0" -v NX="$NX" -v NY="$NY" '
			{ k = (NR - 1) % (nx * ny); c = k % nx; r = int(k / nx)
			  gx = int((xi + (c + 0.5) * ci - x0) / cell); gy = int((r + 0.5) * ci / cell)
			  if ($1 > 0 && gx < NX && gy < NY) printf "%d %.17g %.17g %.17g\n", gy * NX + gx, $1, $1 * $2, $1 * $3 }'
done | awk '{ n[$1] += $2; sx[$1] += $3; sy[$1] += $4 } END { for (c in n) if (n[c] > 0) printf "%d %.17g %.17g %.17g\n", c, n[c], sx[c] / n[c], sy[c] / n[c] }' >fig1.want
[ "$(echo "$ids" | while read -r id; do attr "R/c/$id.h5" /observables/field/cell; done | sort -u | wc -l)" = 2 ] &&
	ok figures.fig1_replicates_have_own_grids || fail figures.fig1_replicates_have_own_grids "the two runs share a grid: the regridding is not exercised"
# the panel's rows (panel 2 r + sys: f = 6 Hz is row 1, the intruder system 1): arrows
# are drawn centred on their cell, at most the common scale long, in the cell's direction
awk -F, 'NR > 1 && $1 == 3 { print $4 + 0.5 * $9, $5 + 0.5 * $10, $6, $7, $8 }' $A/fig1_field.csv |
	awk -v cell="$CELL" -v x0="$X0" -v nx="$NX" 'NR == FNR { n[$1] = $2; ex[$1] = $3; ey[$1] = $4; if ($2 > 0) pos[np++] = $2; next }
		{ c = int(($2 + 1e-9) / cell) * nx + int(($1 - x0 + 1e-9) / cell); rows++
		  if (!(c in n) || n[c] != $5) { bad = 1; next }
		  le = sqrt(ex[c]^2 + ey[c]^2); lu = sqrt($3^2 + $4^2)
		  if (lu > le * (1 + 1e-9) + 1e-15 || ($3 * ey[c] - $4 * ex[c])^2 > 1e-18 * (1 + le^4)) bad = 1
		  if (lu > le * (1 - 1e-9)) full++ }
		END { exit !(rows > 10 && !bad && full >= 0.5 * rows) }' fig1.want - &&
	ok figures.fig1_field_matches_files || fail figures.fig1_field_matches_files "cells of panel 3 differ from the files' count-weighted means"

# ---- waiting: fraction risen and runs per group from the files' attributes ----
"$BINDIR/waiting" c --runs R >waiting.out 2>waiting.err || fail waiting.run "$(cat waiting.err)"
bad=0
for f in 4 6; do
	r=0 m=0
	for id in $(q R/study.db "SELECT id FROM runs WHERE campaign = 'c' AND radius_ratio = 2 AND frequency = $f"); do
		r=$((r + $(attr "R/c/$id.h5" /risen))) m=$((m + 1))
	done
	v=$(q R/study.db "SELECT printf('%.17g', value) || ' ' || n FROM analysis WHERE campaign = 'c' AND tool = 'waiting' AND grp = 'radius_ratio=2 frequency=$f' AND key = 'fraction_risen'")
	[ "$v" = "$(awk -v r=$r -v m=$m 'BEGIN { printf "%.17g %d", r / m, m }')" ] || { bad=1; echo "# f=$f: stored '$v', files $r of $m"; }
done
[ "$bad" = 0 ] && ok waiting.fraction_matches_files || fail waiting.fraction_matches_files "see above"
# the histogram holds every risen run once, in the bin of its waiting time (the last bin
# closed)
awk -F, 'FNR == 1 { next } FILENAME ~ /waiting_runs/ { if ($7 == 1) { n[$1]++; t[$1, n[$1]] = $6 }; next }
	{ b = nb[$1]++; lo[$1, b] = $3; hi[$1, b] = $4; c[$1, b] = $5 }
	END { for (g in nb) { for (b = 0; b < nb[g]; b++) want[b] = 0
		for (i = 1; i <= n[g]; i++) for (b = 0; b < nb[g]; b++)
			if (t[g, i] >= lo[g, b] && (t[g, i] < hi[g, b] || b == nb[g] - 1)) { want[b]++; break }
		for (b = 0; b < nb[g]; b++) if (want[b] != c[g, b]) exit 1 }
	      exit !(length(nb) == 2) }' $A/waiting_runs.csv $A/waiting_hist.csv &&
	ok waiting.histogram_counts_risen_runs || fail waiting.histogram_counts_risen_runs "$(head -n 5 $A/waiting_hist.csv)"

# ---- a campaign over depth: onset and waiting keep the depths apart ----
"$BINDIR/onset" d --runs R --boot 10 >od.out 2>od.err && "$BINDIR/waiting" d --runs R >wd.out 2>wd.err
rc=$?
[ "$rc" -eq 0 ] && [ "$(q R/study.db "SELECT group_concat(grp, '|') FROM (SELECT DISTINCT grp FROM analysis WHERE campaign = 'd' AND tool = 'onset' ORDER BY grp)")" = \
	'radius_ratio=2 depth=0|radius_ratio=2 depth=1' ] &&
	[ "$(q R/study.db "SELECT COUNT(DISTINCT grp) FROM analysis WHERE campaign = 'd' AND tool = 'waiting' AND grp LIKE '%depth=%'")" = 4 ] &&
	ok tools.groups_by_depth || fail tools.groups_by_depth "exit $rc: $(cat od.err wd.err; q R/study.db "SELECT DISTINCT tool, grp FROM analysis WHERE campaign = 'd'")"

# ---- hysteresis: the hold (0.5 s at 3 Hz) is no leg; the running mean stays in its leg ----
"$BINDIR/hysteresis" r --runs R --boot 20 >hyst.out 2>hyst.err
rc=$?
[ "$rc" -eq 0 ] && ok hysteresis.ramp_with_hold || fail hysteresis.ramp_with_hold "exit $rc: $(cat hyst.err)"
H=R/r/analysis/hysteresis_periods.csv
bad=0
for id in $(q R/study.db "SELECT id FROM runs WHERE campaign = 'r'"); do
	P=$(dims "R/r/$id.h5" /observables/flux/phi/time)
	nh=$(vals "R/r/$id.h5" /observables/flux/phi/time | awk '{ if ((prev + $1) / 2 < 0.5) n++; prev = $1 } END { print n + 0 }')
	got=$(awk -F, -v id="$id" '$3 == id { if (min == "" || $6 < min) min = $6; n++ } END { print min, n }' $H)
	[ "$nh" -ge 1 ] && [ "$got" = "$nh $((P - nh))" ] || { bad=1; echo "# $id: hold periods $nh of $P, csv (first, rows) $got"; }
done
[ "$bad" = 0 ] && ok hysteresis.hold_left_out || fail hysteresis.hold_left_out "see above"
# default K = 5: an interior period averages p-2..p+2; the first period of the down leg
# averages only the down leg's first three (the up leg's last periods are not mixed in)
id=$(q R/study.db "SELECT id FROM runs WHERE campaign = 'r' ORDER BY id LIMIT 1")
awk -F, -v id="$id" '$3 == id { br[$6] = $5; raw[$6] = $8; sm[$6] = $9; if ($5 == "down" && (d0 == "" || $6 < d0)) d0 = $6
		if ($5 == "up" && (u0 == "" || $6 < u0)) u0 = $6 }
	function near(a, b) { return (a - b) ^ 2 <= 1e-24 * (1 + b * b) }
	END { p = u0 + 4; m = (raw[p - 2] + raw[p - 1] + raw[p] + raw[p + 1] + raw[p + 2]) / 5
	      f = (raw[d0] + raw[d0 + 1] + raw[d0 + 2]) / 3
	      exit !(d0 > u0 + 6 && br[d0 - 1] == "up" && near(sm[p], m) && near(sm[d0], f)) }' $H &&
	ok hysteresis.smoothing_within_leg || fail hysteresis.smoothing_within_leg "$(awk -F, -v id="$id" '$3 == id' $H | head -n 4)"

# ---- figures without the intruder system (--ratio 0), and on a campaign of ramps only ----
"$BINDIR/figures" c --runs R --ratio 0 --out "$TMP/f0" --no-store >f0.out 2>f0.err
rc=$?
[ "$rc" -eq 0 ] && ! awk -F, 'NR > 1 && $2 == 1 { found = 1 } END { exit !found }' f0/fig3_profile.csv &&
	grep -q 'layout 1,2' f0/fig1.gp && ! grep -q '𝓡 =' f0/fig3.gp f0/fig1.gp && [ -s f0/fig1.png ] && [ -s f0/fig3.png ] &&
	ok figures.no_intruder_system || fail figures.no_intruder_system "exit $rc: $(cat f0.err; grep -c '𝓡 =' f0/*.gp)"
"$BINDIR/figures" r --runs R >fr.out 2>fr.err
rc=$?
[ "$rc" -eq 1 ] && grep -q "no finished fixed-frequency run" fr.err && ok figures.ramps_only || fail figures.ramps_only "exit $rc: $(cat fr.err)"
echo "# total: $((SECONDS - t0)) s"
finish
