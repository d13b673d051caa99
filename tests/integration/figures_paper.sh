#!/usr/bin/env bash
# figures_paper.sh - figures fit for a paper from every analysis tool, on tiny campaigns
# run by bin/study (options given as --opt=value): each figure as a PNG and a PDF, both
# written and not empty; nothing on any tool's stderr (no gnuplot warning) and no table
# printed without rows; the gnuplot scripts draw what they should - the onset's f0 as a
# line with its interval as a band and the Gamma axis on top, Fig. 3's band per line
# against the runs' own profiles (bin/dumpflux) and at another level, the Kaplan-Meier curves
# with their band (from the step outline in waiting_km_band.csv), Fig. 1 as the box of
# the runs' width with its walls, legends in words and symbols instead of parameter
# keys; a PDF drawn again is the same file.
# The campaigns are run by the release engine (lib.sh's data_driver_setup: the tools are
# what is tested).
# tier: slow: the campaigns of the paper figures, small
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
data_driver_setup
cd "$TMP" || exit 1

paper_figure_campaigns
t0=$SECONDS
for c in t h w; do
	"$DATA_STUDY" run $c.campaign --runs "$TMP/R" --jobs 2 --no-progress >study_$c.log 2>&1 ||
		{ fail setup.campaigns "study $c: $(tail -c 300 study_$c.log)"; finish; }
done
echo "# campaigns: $((SECONDS - t0)) s"

# figs ID DIR NAME...: every NAME.png is a PNG and NAME.pdf a PDF, neither empty
figs() {
	local id=$1 d=$2 n bad=
	shift 2
	for n in "$@"; do
		[ -s "$d/$n.png" ] && [ "$(head -c 4 "$d/$n.png" | od -An -c | tr -d ' ')" = '211PNG' ] || bad="$bad $n.png"
		[ -s "$d/$n.pdf" ] && [ "$(head -c 5 "$d/$n.pdf")" = '%PDF-' ] || bad="$bad $n.pdf"
	done
	[ -z "$bad" ] && ok "$id" || fail "$id" "missing or not a figure:$bad"
}
# no_keys ID FILE: the titles of a script are in words, not parameter keys
no_keys() {
	grep -E "title .*(radius_ratio|frequency)=" "$2" >/dev/null && fail "$1" "$(grep -E "title .*(radius_ratio|frequency)=" "$2" | head -n 2)" || ok "$1"
}
A=R/t/analysis

# ---- onset ----
tool_quiet fig.onset onset t --runs=R --boot=40 --seed=3
figs fig.onset.png_pdf $A onset
G=$A/onset.gp
# per group with an onset (the threshold crossing: docs/analysis.md, "One onset per
# campaign"): a dashed line at it and a band over its interval, in the group's colour,
# named in the legend
nmark=$(awk -F, 'NR > 1 && $11 != "nan"' $A/onset_summary.csv | wc -l)
nline=$(grep -c '^set arrow [0-9]* from .* graph 0 to .* graph 1 nohead lt [0-9]* dt 2' $G)
nband=$(grep -c '^set object [0-9]* rect from .* graph 0 to .* graph 1 behind fc lt [0-9]* fs transparent solid' $G)
nkey=$(grep -oE "keyentry with lines lt [0-9]+ dt 2 lw 1.5 title 'onset f = [0-9.]+ Hz" $G | wc -l)
[ "$nmark" -ge 1 ] && [ "$nline" = "$nmark" ] && [ "$nkey" = "$nmark" ] && [ "$nband" -ge 1 ] && [ "$nband" -le "$nmark" ] &&
	ok fig.onset.f0_line_and_band || fail fig.onset.f0_line_and_band "groups $nmark, lines $nline, bands $nband, legend $nkey"
# the line of a group with an onset is at it (not at the sigmoid's f0), the band its interval
row=$(awk -F, 'NR > 1 && $11 != "nan" && $12 != "nan" { print; exit }' $A/onset_summary.csv)
if [ -n "$row" ]; then
	f0=$(echo "$row" | awk -F, '{ print $11 }') lo=$(echo "$row" | awk -F, '{ print $12 }')
	grep -q "^set arrow [0-9]* from $f0, graph 0" $G && grep -q "^set object [0-9]* rect from $lo, graph 0" $G &&
		ok fig.onset.f0_values || fail fig.onset.f0_values "f0 $f0, lo $lo not in $G"
fi
# Gamma = A (2 pi f)^2 / g on top: A = 1 cm, g = 981 cm/s^2
k=$(awk 'BEGIN { printf "%.6f", 4 * atan2(0, -1)^2 / 981 }')
grep -q "^set link x2 via ${k}[0-9]*\*x\*\*2 inverse" $G && grep -q "^set x2label 'Γ = A(2πf)²/g'" $G &&
	ok fig.onset.gamma_axis || fail fig.onset.gamma_axis "$(grep -E 'x2' $G)"
grep -q "title 'no intruder'" $G && grep -q "title '𝓡 = 2'" $G && grep -q "set ylabel 'Φ (particles per period)'" $G &&
	grep -q 'N = 60, W = 20 cm, A = 1 cm, depth 1' $G && ok fig.onset.words || fail fig.onset.words "$(grep -E 'title|label' $G)"
no_keys fig.onset.no_raw_keys $G
grep -q '^set key below' $G && ! grep -q 'set key outside right' $G && ok fig.onset.legend_below ||
	fail fig.onset.legend_below "$(grep 'set key' $G)"
# the PDF drawn again (no bootstrap change) is the same file: no time stamp in it
cp $A/onset.pdf onset1.pdf
sleep 1
"$BINDIR/onset" t --runs R --boot=40 --seed=3 --no-store >/dev/null 2>&1
cmp -s onset1.pdf $A/onset.pdf && ok fig.onset.pdf_reproducible || fail fig.onset.pdf_reproducible "the PDF changed"

# ---- waiting ----
tool_quiet fig.waiting waiting w --runs=R --level=0.9
W=R/w/analysis
figs fig.waiting.png_pdf $W waiting_km waiting_hist
G=$W/waiting_km.gp
[ "$(grep -c "'waiting_km_band.csv' skip 1 using 2:(\$1==[0-9]*?\$3:1/0):4 with filledcurves lt [0-9]* notitle" $G)" = 2 ] &&
	grep -q "band: 90 % CI" $G && ok fig.waiting.km_band || fail fig.waiting.km_band "$(grep plot -A3 $G)"
# the band's outline: per group (0, 1, 1), then two rows per time of the curve, the band
# before it and after it, lo <= S <= hi after it
awk -F, 'NR == FNR { if (FNR > 1) { n[$1]++; S[$1, n[$1]] = $7; T[$1, n[$1]] = $3 } next }
	FNR > 1 { m[$1]++; if (m[$1] > 1 && (m[$1] % 2) == 1) { i = (m[$1] - 1) / 2 + 1
		if ($2 != T[$1, i] || $3 > S[$1, i] + 1e-12 || $4 < S[$1, i] - 1e-12 || $3 > $4) bad = 1 } }
	END { for (g in n) if (m[g] != 2 * n[g] - 1) bad = 1; exit bad }' $W/waiting_km.csv $W/waiting_km_band.csv &&
	ok fig.waiting.band_outline || fail fig.waiting.band_outline "$(head -n 6 $W/waiting_km_band.csv)"
grep -q "title '𝓡 = 2'" $G && grep -q "title '𝓡 = 3[' ]" $G && ok fig.waiting.words || fail fig.waiting.words "$(grep title $G)"
no_keys fig.waiting.no_raw_keys $G

# ---- hysteresis ----
tool_quiet fig.hysteresis hysteresis h --runs=R --boot=20 --smooth=3
figs fig.hysteresis.png_pdf R/h/analysis hysteresis
G=R/h/analysis/hysteresis.gp
grep -q "^set link x2 via" $G && grep -q "title 'up'" $G && grep -q "title 'down'" $G && grep -q 'no intruder\|𝓡 = 2' $G &&
	ok fig.hysteresis.words_gamma || fail fig.hysteresis.words_gamma "$(grep -E 'title|x2' $G)"
no_keys fig.hysteresis.no_raw_keys $G

# ---- figures ----
# a frequency without runs is refused, naming the ones there are (not an empty row)
"$BINDIR/figures" t --runs=R --freq=5,4 >fig.nofreq.out 2>fig.nofreq.err
rc=$?
[ "$rc" -ne 0 ] && grep -q -- "--freq 4: no fixed-frequency run at this frequency (the runs' frequencies: 3, 5, 7)" fig.nofreq.err &&
	ok fig.figures.freq_without_runs_refused || fail fig.figures.freq_without_runs_refused "exit $rc: $(head -c 300 fig.nofreq.err)"
tool_quiet fig.figures figures t --runs=R --freq=5,7
figs fig.figures.png_pdf $A fig1 fig3 fig4
G=$A/fig1.gp
# the box: x from -2 R_w to W + 2 R_w (W = 20, R_w = 1), walls as grey rectangles at the
# inner faces x = 0, x = W and the floor y = 0
grep -q '^set xrange \[-2:22\]' $G && grep -q "^set object 1 rect from -2, -2 to 0, graph 1 fc rgb '#b0b0b0'" $G &&
	grep -q "^set object 2 rect from 20, -2 to 22, graph 1" $G && grep -q "^set object 3 rect from -2, -2 to 22, 0" $G &&
	ok fig.fig1.box_and_walls || fail fig.fig1.box_and_walls "$(grep -E 'range|object' $G)"
grep -q "^set title 'no intruder, 5 Hz; 2 runs averaged, cell " $G && grep -q "^set title '𝓡 = 2, 7 Hz; 2 runs averaged, cell " $G && ok fig.fig1.words ||
	fail fig.fig1.words "$(grep title $G)"
grep -q "title 'no intruder'" $A/fig3.gp && grep -q "title '𝓡 = 2'" $A/fig3.gp && grep -q "^set title '𝓡 = 2'" $A/fig4.gp &&
	ok fig.fig34.words || fail fig.fig34.words "$(grep title $A/fig3.gp $A/fig4.gp)"
for g in fig1 fig3 fig4; do no_keys fig.$g.no_raw_keys $A/$g.gp; done
# Fig. 3's band, a known answer: per line the mean of the panel's two runs' profiles
# (bin/dumpflux, the same periods) -+ t(0.95, 1 dof) s / sqrt(2) (equal weights: the
# runs have the same periods), t = 12.706204736174707
ids=$(sqlite3 R/study.db "SELECT id FROM runs WHERE campaign = 't' AND frequency = 5 AND radius_ratio = 0 ORDER BY id")
for id in $ids; do "$BINDIR/dumpflux" run "R/t/$id.h5" | grep -v '^#'; done |
	awk -F'\t' -v T=12.706204736174707 '{ n[$1]++; s[$1] += $3; v[$1, n[$1]] = $3 }
		END { for (l in n) { m = s[l] / n[l]; q = 0; for (i = 1; i <= n[l]; i++) q += (v[l, i] - m)^2
			sd = sqrt(q / (n[l] - 1)); h = T * sd / sqrt(n[l])
			printf "%d %.12g %.12g %.12g %d\n", l, m, m - h, m + h, n[l] } }' | sort -n >band.want
awk -F, 'NR > 1 && $3 == 5 && $2 == 0 { printf "%d %.12g %.12g %.12g %d\n", $5, $7, $9, $10, $8 }' $A/fig3_profile.csv >band.got
paste -d' ' band.got band.want | awk '{ for (k = 2; k <= 4; k++) { d = $k - $(k + 5); if (d < 0) d = -d
		if (d > 1e-9 * (1 + ($k < 0 ? -$k : $k))) bad = 1 } if ($1 != $6 || $5 != 2 || $10 != 2) bad = 1
		if ($4 - $3 > 0) wide++ } END { exit !(NR == 80 && !bad && wide > 0) }' &&
	ok fig.fig3.band_known_answer || fail fig.fig3.band_known_answer "$(paste -d' ' band.got band.want | head -n 3)"
# the printed table: phi_max with the band of |Phi| on its line, as the CSV has them
want=$(awk -F, 'NR > 1 && $3 == 5 && $2 == 0 { a = $7 < 0 ? -$7 : $7; if (a > m) { m = a; lo = $7 < 0 ? -$10 : $9; hi = $7 < 0 ? -$9 : $10 } }
	END { printf "%.4g %.4g %.4g", m, lo, hi }' $A/fig3_profile.csv)
got=$(awk '$1 == "5" && $2 == "0" { print $4, $5, $6 }' fig.figures.out)
[ -n "$got" ] && [ "$got" = "$want" ] && grep -q '^frequency .* phi_max *phi_lo *phi_hi ' fig.figures.out &&
	grep -q "^# fig3: band: 95 % CI of the mean over a curve's runs (Student t, each run weighted by its periods); it rests on a curve's used runs" fig.figures.out &&
	ok fig.fig3.band_printed || fail fig.fig3.band_printed "table '$got', csv '$want': $(grep -E '^(frequency|5 |# fig3)' fig.figures.out)"
# in the figure: a band behind each curve, named in the title, the runs in each row's title
G=$A/fig3.gp
[ "$(grep -c "using 6:(\$1==[0-9]&&\$2==[01]?\$9:1/0):10 with filledcurves lt [12] notitle" $G)" = 4 ] &&
	grep -q "band: 95 % CI of the mean over a curve's runs" $G && grep -q "^set title '5 Hz; runs: 2 no intruder, 2 𝓡 = 2'" $G &&
	ok fig.fig3.band_drawn || fail fig.fig3.band_drawn "$(grep -E 'title|filledcurves' $G | head -n 8)"
# the other direction: at --level 0.5 the band is t(0.5, 1) / t(0.95, 1) = 1 / 12.706204736174707 as wide
"$BINDIR/figures" t --runs=R --freq=5,7 --level=0.5 --no-plot --no-store --out=L50 >fig.l50.out 2>&1
paste -d, <(awk -F, 'NR > 1 { printf "%.17g\n", $10 - $9 }' $A/fig3_profile.csv) <(awk -F, 'NR > 1 { printf "%.17g\n", $10 - $9 }' L50/fig3_profile.csv) |
	awk -F, '$1 > 0 { r = $2 / $1 * 12.706204736174707; if (r < 1 - 1e-6 || r > 1 + 1e-6) bad = 1; n++ } END { exit !(n > 0 && !bad) }' &&
	grep -q '^# fig3: band: 50 % CI' fig.l50.out && ok fig.fig3.band_level || fail fig.fig3.band_level "$(head -n 3 fig.l50.out)"
# a campaign without flux or field: Fig. 4 only, and no table header without rows
tool_quiet fig.figures_noflux figures w --runs=R
figs fig.figures_noflux.fig4 $W fig4
grep -q '^# fig3: no run with flux = yes; skipped' fig.figures_noflux.out && ! grep -q '^frequency ' fig.figures_noflux.out &&
	ok fig.figures_noflux.no_empty_table || fail fig.figures_noflux.no_empty_table "$(head -n 4 fig.figures_noflux.out)"
echo "# total: $((SECONDS - t0)) s"
finish
