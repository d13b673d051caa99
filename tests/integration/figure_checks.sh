#!/usr/bin/env bash
# figure_checks.sh - what a referee would send back about the figures (issue 42's point 5),
# checked on the plotted data and scripts of tiny campaigns: waiting_hist's bars cover
# the bins their waiting times fall in; onset's points inside a padded x range, its
# onset lines labelled apart, no nan in its tables without a reason; identical
# Kaplan-Meier curves said so and offset; every line colour legible on white (contrast
# >= 3:1); Fig. 1's reference arrow to the field's scale, cell, runs and settled
# intruder; Fig. 3's settled surface; Fig. 4's risen level y0 + 2R; convect's lower
# bounds never below 0; rolls' intervals wider than the bed called undecided;
# hysteresis' fits in the key and f_up/f_down marked; ring's figure line only with a figure.
# The campaigns are run by the release engine (lib.sh's data_driver_setup).
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
data_driver_setup
cd "$TMP" || exit 1

paper_figure_campaigns
# two frequencies: no sigmoid
tiny_campaign o2 5 'flux = yes' | sed 's/^duration = 0.2/duration = 1/' >o2.campaign
# the ring at rest, with and without the intruder (a ratio), and with it alone (none)
RING="$(tiny_scene radius_ratio=-)
frequency = 0
amplitude = 0
duration = 0.1
ring = yes
ring_rate = 50
ring_inner = 4
ring_outer = 6.5
ring_y = 5.5"
printf '[campaign]\nname = rg\nseed = 1\nreplicates = 2\n[scene]\n%s\n[grid]\nradius_ratio = 0, 4\n' "$RING" >rg.campaign
printf '[campaign]\nname = rg1\nseed = 1\nreplicates = 2\n[scene]\n%s\n[grid]\nradius_ratio = 4\n' "$RING" >rg1.campaign
t0=$SECONDS

for c in t h w o2 rg rg1; do
	fixture_runs $c.campaign F$c "$DATA_STUDY" || { fail setup.campaigns "study $c: $(tail -c 300 F$c.log)"; finish; }
done
echo "# campaigns: $((SECONDS - t0)) s"

# no_bare_nan ID FILE: no line of the printed tables holds nan without a reason word
no_bare_nan() {
	local bad
	bad=$(grep -iwE 'nan' "$2" | grep -vE 'not fitted|because|n/a|no interval|never|fewer than|no run' | head -n 3)
	[ -z "$bad" ] && ok "$1" || fail "$1" "$bad"
}

# ---- palette: every line type's colour has a contrast of at least 3:1 on white ----
tool_quiet pal onset Ft/t --boot=40 --seed=3 --no-store
G=Ft/t/analysis/onset.gp
grep -oE "^set linetype [0-9]+ lc rgb '#[0-9a-f]{6}'" $G | awk '{ h = substr($6, 3, 6); n++
	for (k = 0; k < 3; k++) { c = 0; for (i = 1; i <= 2; i++) c = c * 16 + index("0123456789abcdef", substr(h, 2 * k + i, 1)) - 1
		c /= 255; c = c <= 0.03928 ? c / 12.92 : ((c + 0.055) / 1.055)^2.4; v[k] = c }
	L = 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2]; if (1.05 / (L + 0.05) < 3) bad = bad " " $6 }
	END { if (bad != "" || n < 8) { print n, bad; exit 1 } }' && ok palette.legible_on_white || fail palette.legible_on_white "$(grep linetype $G)"

# ---- onset ----
# the x range padded: every run's frequency strictly inside, 5 % of the range from a border
awk -F, 'NR == FNR { if ($0 ~ /^set xrange/) { split($0, a, /[\[:\]]/); lo = a[2]; hi = a[3] } next }
	FNR > 1 && $8 != "nan" { if (!(lo != "" && $8 > lo + 0.05 * (hi - lo) && $8 < hi - 0.05 * (hi - lo))) bad = 1; n++ }
	END { exit bad || !n }' $G Ft/t/analysis/onset_runs.csv && ok onset.range_padded ||
	fail onset.range_padded "$(grep xrange $G)"
# each onset line labelled in its group's colour at its own height
nl=$(grep -c '^set arrow [0-9]* from .* graph 0 to .* graph 1 nohead lt [0-9]* dt 2' $G)
labels=$(grep -E "^set label [0-9]+ '.*onset f = .* Hz' at .*, graph [0-9.]+ left offset 0.5, 0 tc lt [0-9]+ front" $G)
[ "$nl" -ge 1 ] && [ "$(echo "$labels" | wc -l)" = "$nl" ] &&
	[ "$(echo "$labels" | grep -oE 'graph [0-9.]+' | sort -u | wc -l)" = "$nl" ] &&
	echo "$labels" | awk '{ n = $3; lt = $NF; sub(/ front$/, "") } 1' >/dev/null &&
	[ "$(grep -E '^set (arrow|label) [0-9]+ ' $G | awk '{ print $3, ($2 == "arrow" ? $(NF - 4) : $(NF - 1)) }' | sort -u | awk '{ print $1 }' | uniq -d | wc -l)" = 0 ] &&
	ok onset.lines_labelled_apart || fail onset.lines_labelled_apart "lines $nl: $(grep -E '^set (arrow|label)' $G)"
no_bare_nan onset.no_bare_nan pal.out
# two frequencies: the sigmoid not fitted, said why, and no nan
tool_quiet o2 onset Fo2/o2 --boot=40 --no-store
grep -q '^#   radius_ratio=2 depth=1: sigmoid f0 and width -: not fitted: 2 distinct frequencies, a sigmoid needs at least 3' o2.out &&
	ok onset.two_frequencies_said || fail onset.two_frequencies_said "$(head -n 5 o2.out)"
no_bare_nan onset.two_frequencies_no_nan o2.out

# ---- waiting ----
tool_quiet w waiting Fw/w --no-store
W=Fw/w/analysis
# the histogram: a bar per bin centred on it and as wide; the runs risen within its
# [lo, hi) (the longest in the last) are its count
bw=$(awk -F, 'NR == 2 { printf "%.12g", $4 - $3 }' $W/waiting_hist.csv)
grep -qE "^set boxwidth $bw[0-9]* absolute" $W/waiting_hist.gp &&
	[ "$(grep -c "'waiting_hist.csv' skip 1 using ((\$3+\$4)/2):(\$1==[0-9]*?\$5:1/0) with boxes" $W/waiting_hist.gp)" = 2 ] &&
	ok waiting.hist_bars_span_bins || fail waiting.hist_bars_span_bins "width $bw: $(grep -E 'boxwidth|boxes' $W/waiting_hist.gp)"
awk -F, -v g="$(csv_col $W/waiting_runs.csv group)" -v r="$(csv_col $W/waiting_runs.csv risen)" -v wt="$(csv_col $W/waiting_runs.csv waiting_time)" '
	NR == FNR { if (FNR > 1 && $r == 1) { gsub(/"/, "", $g); t[++n] = $wt; grp[n] = $g } next }
	FNR > 1 { gsub(/"/, "", $2); c = 0; for (i = 1; i <= n; i++) if (grp[i] == $2 && t[i] >= $3 && (t[i] < $4 || $4 >= last[$2])) c++
		if (c != $5) bad = 1 } { last[$2] = $4 > last[$2] ? $4 : last[$2] }
	END { exit bad }' $W/waiting_runs.csv $W/waiting_hist.csv && ok waiting.hist_counts_inside_bars ||
	fail waiting.hist_counts_inside_bars "$(head -n 4 $W/waiting_hist.csv)"
# both curves are one (every run censored at 1 s): the second said so and drawn a hair higher
grep -q "using 3:(\$1==1?\$7+0.012:1/0) with steps .* title '𝓡 = 3 (same as 𝓡 = 2, drawn 0.012 higher)'" $W/waiting_km.gp &&
	grep -q "using 3:(\$1==0?\$7+0:1/0) with steps" $W/waiting_km.gp && ok waiting.km_identical_said ||
	fail waiting.km_identical_said "$(grep steps $W/waiting_km.gp)"

# ---- figures ----
tool_quiet f figures Ft/t --freq=5,7 --no-store
A=Ft/t/analysis
G=$A/fig1.gp
# per panel: the reference arrow's length over its value is the field's dx / ux (the same scale)
awk -F, 'NR == FNR { if ($0 ~ /^set title /) p++
		if ($0 ~ /^set arrow 1 from /) { s = $0; sub(/.* from /, "", s); split(s, v, /[ ,]+/); len[p - 1] = v[4] - v[1] }
		if ($0 ~ /^set label 1 .* cm per period/) { s = $0; sub(/^set label 1 \047/, "", s); u[p - 1] = s + 0 }
		next }
	FNR > 1 && $6 != 0 { r = ($9 / $6) / (len[$1] / u[$1]); if (r < 0.99 || r > 1.01) bad = 1; n++ }
	END { for (q = 0; q < p; q++) if (!(len[q] > 0)) bad = 1; exit bad || !n || p != 4 }' $G $A/fig1_field.csv &&
	ok fig1.reference_arrow || fail fig1.reference_arrow "$(grep -E '^set (arrow 1|label 1|title)' $G)"
grep -qE "^set title 'no intruder, 5 Hz; 2 runs averaged, cell [0-9.]+ cm'" $G && grep -qE "^set title '𝓡 = 2, 7 Hz; 2 runs averaged, cell [0-9.]+ cm'" $G &&
	ok fig1.cell_and_runs || fail fig1.cell_and_runs "$(grep title $G)"
# the intruder's settled place: one row per run with an intruder, y its intruder_settled_y
ids=$(sqlite3 Ft/study.db "SELECT id FROM runs WHERE campaign = 't' AND radius_ratio = 2 AND frequency IN (5, 7)")
bad=0
for id in $ids; do
	y=$(attr Ft/t/$id.h5 /intruder_settled_y)
	awk -F, -v id=$id -v y="$y" '$2 == id && $4 == y && $5 == 2 { f = 1 } END { exit !f }' $A/fig1_intruder.csv || bad=1
done
[ "$bad" = 0 ] && [ "$(tail -n +2 $A/fig1_intruder.csv | wc -l)" = 4 ] && [ "$(grep -c "'fig1_intruder.csv' .* with circles" $G)" = 2 ] &&
	ok fig1.settled_intruder || fail fig1.settled_intruder "$(cat $A/fig1_intruder.csv)"
# Fig. 3: each curve's settled surface, the mean of its runs' surface_height
hs=$(for id in $(sqlite3 Ft/study.db "SELECT id FROM runs WHERE campaign = 't' AND radius_ratio = 0 AND frequency = 5"); do
	attr Ft/t/$id.h5 /surface_height; done | awk '{ s += $1; n++ } END { printf "%.3g", s / n }')
grep -q "title 'settled surface h_s = $hs cm (no intruder)'" $A/fig3.gp && [ "$(grep -c '^set arrow [12] from .* nohead lt [12] dt 3' $A/fig3.gp)" = 4 ] &&
	ok fig3.settled_surface || fail fig3.settled_surface "h_s $hs: $(grep -E 'surface|arrow' $A/fig3.gp)"
# Fig. 4: the risen level y0 + 2R of the representative run
rep=$(awk -F, 'NR > 1 && $9 == 1 { print $3; exit }' $A/fig4_traj.csv)
lvl=$(awk -v y="$(attr Ft/t/$rep.h5 /intruder_settled_y)" -v r="$(attr Ft/t/$rep.h5 /intruder_radius)" 'BEGIN { printf "%.3g", y + 2 * r }')
grep -q "title 'risen level y₀ + 2R = $lvl cm (the engine''s rule)'" $A/fig4.gp && ok fig4.risen_level ||
	fail fig4.risen_level "want $lvl: $(grep risen $A/fig4.gp)"

# ---- convect: no lower bound below 0, and the clipping said ----
tool_quiet c convect Ft/t --boot=100 --no-store
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i ~ /_lo$/ && $i != "band_lo") c[i] = 1; next }
	{ for (i in c) if ($i != "nan" && $i < 0) bad = 1 } END { exit bad || !length(c) }' Ft/t/analysis/convect_summary.csv &&
	awk -F, 'NR > 1 && ($6 < 0 || $9 < 0 || $12 < 0) { bad = 1 } END { exit bad }' Ft/t/analysis/convect_points.csv &&
	! grep -E '^[a-z].*\[-[0-9]' c.out && grep -qE '^# [0-9]+ Student-t lower bounds? of S or S_u below 0 clipped at 0' c.out &&
	ok convect.no_negative_bound || fail convect.no_negative_bound "$(grep -E '^(freq|#.*clipped)' c.out)"

# ---- rolls: an interval wider than the bed is undecided, and only such a one ----
tool_quiet r rolls Ft/t --no-store
A=Ft/t/analysis
awk -F, -v g="$(csv_col $A/rolls_runs.csv group)" -v s="$(csv_col $A/rolls_runs.csv surface)" -v u="$(csv_col $A/rolls_runs.csv use)" '
	FILENAME ~ /runs/ { if (FNR > 1 && $u ~ /used/) { gsub(/"/, "", $g); h[$g] += $s; n[$g]++ } next }
	FNR > 1 { gsub(/"/, "", $2); gsub(/"/, "", $3); bed = h[$2] / n[$2]; if (h[$3] / n[$3] > bed) bed = h[$3] / n[$3]
		print $2 "|" ($10 - $9 > bed ? "wide" : "narrow") }' $A/rolls_runs.csv $A/rolls_diff.csv >rolls.want
nw=0
while IFS='|' read -r grp want; do
	line=$(grep "^$grp  *[0-9]*/[0-9]" r.out)
	case $want in
	wide) echo "$line" | grep -q 'reach diff: interval wider than the bed (.* cm > h_s = .* cm): undecided' || nw=$((nw + 1)) ;;
	narrow) echo "$line" | grep -q 'reach diff: interval wider' && nw=$((nw + 1)) ;;
	esac
done <rolls.want
[ -s rolls.want ] && [ "$nw" = 0 ] && grep -q wide rolls.want && ok rolls.wider_than_bed_undecided ||
	fail rolls.wider_than_bed_undecided "$(cat rolls.want; grep -A4 '^with intruder' r.out)"

# ---- hysteresis: the fits in the key, f_up and f_down marked ----
tool_quiet h hysteresis Fh/h --boot=20 --no-store
G=Fh/h/analysis/hysteresis.gp
# per leg with a fitted sigmoid (hysteresis_summary.csv: up_sigmoid_f, down_sigmoid_f)
nfit=0 ok_h=1
for leg in up down; do
	v=$(awk -F, -v c=$([ $leg = up ] && echo 4 || echo 7) 'NR == 2 && $c != "nan" { printf "%.3g", $c }' Fh/h/analysis/hysteresis_summary.csv)
	[ -n "$v" ] || continue
	nfit=$((nfit + 1))
	grep -q "with lines lw 2 dt [12] lt [0-9]* title '.*$leg: fitted sigmoid, f_$leg = $v Hz" $G &&
		grep -qE "^set label [0-9]+ '.*f_$leg = $v Hz' at " $G || ok_h=0
done
[ "$ok_h" = 1 ] && [ "$nfit" -ge 1 ] && ! grep -qE 's0_[01]\(x\) with lines .* notitle' $G &&
	[ "$(grep -c '^set arrow [0-9]* from .* nohead lt [0-9]* dt 3' $G)" = "$nfit" ] &&
	ok hysteresis.fits_in_key_and_marked || fail hysteresis.fits_in_key_and_marked "fits $nfit: $(grep -E 'arrow|label|s0_' $G)"

# ---- ring: the figure line only with a figure ----
tool_quiet rg ring Frg/rg --boot=50 --no-store
grep -q '^# figure: .*ring.{png,pdf}' rg.out && [ -s Frg/rg/analysis/ring.png ] && ok ring.figure_line_with_figure ||
	fail ring.figure_line_with_figure "$(grep -E '^# (figure|no ratio)' rg.out)"
tool_quiet rg1 ring Frg1/rg1 --boot=50 --no-store
grep -q '^# no ratio to draw: no figure' rg1.out && ! grep -q '^# figure' rg1.out && [ ! -e Frg1/rg1/analysis/ring.png ] &&
	ok ring.no_figure_line_without || fail ring.no_figure_line_without "$(grep -E '^# (figure|no ratio)' rg1.out)"
echo "# total: $((SECONDS - t0)) s"
finish
