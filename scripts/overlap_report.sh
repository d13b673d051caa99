#!/usr/bin/env bash
# overlap_report.sh - the distribution of the largest overlap per run of the
# overlap_safety campaigns (paper and fast preset), as the Markdown table docs/benchmarks.md
# quotes: runs, how many the max_overlap stop ended, quantiles of overlap_max, and the
# largest per frequency. Usage: scripts/overlap_report.sh [RUNS-DIR [FIGURE]] (default
# runs; with FIGURE also a histogram FIGURE.png and FIGURE.pdf)
set -euo pipefail
RUNS=${1:-runs}
DB=$RUNS/study.db
[ -f "$DB" ] || { echo "overlap_report: $DB: no study database (run the campaigns first)" >&2; exit 1; }
q() { sqlite3 -batch -noheader -separator ' ' "$DB" "$1"; }
echo "| preset | runs done / failed / pending | stopped by max_overlap | median | 90 % | 99 % | largest | largest at 2.7 / 2.8 / 2.9 / 3.0 / 3.1 / 3.2 Hz |"
echo "|---|---|---|---|---|---|---|---|"
for c in overlap_safety overlap_safety_fast; do
	n=$(q "SELECT COUNT(*) FROM runs WHERE campaign = '$c' AND current")
	[ "${n:-0}" -gt 0 ] || continue
	counts=$(q "SELECT SUM(state = 'done') || ' / ' || SUM(state = 'failed') || ' / ' || SUM(state IN ('pending', 'running')) FROM runs WHERE campaign = '$c' AND current")
	stops=$(q "SELECT COUNT(*) FROM runs WHERE campaign = '$c' AND current AND status = 'overlap'")
	# quantiles of the runs with a file (nearest rank)
	qs=$(q "SELECT overlap_max FROM runs WHERE campaign = '$c' AND current AND overlap_max IS NOT NULL ORDER BY overlap_max" |
		awk '{ v[NR] = $1 } END { if (!NR) { print "- - - -"; exit }
			split("0.5 0.9 0.99", p, " "); s = "";
			for (k = 1; k <= 3; k++) { r = int(p[k] * NR + 0.999999); if (r < 1) r = 1; s = s sprintf("%.3f ", v[r]) }
			printf "%s%.3f\n", s, v[NR] }')
	perf=$(q "SELECT CASE WHEN MAX(overlap_max) IS NULL THEN '-' ELSE printf('%.3f', MAX(overlap_max)) END FROM runs WHERE campaign = '$c' AND current GROUP BY frequency ORDER BY frequency" | paste -sd/ | sed 's|/| / |g')
	preset=$(q "SELECT preset FROM runs WHERE campaign = '$c' LIMIT 1")
	read -r q50 q90 q99 qmax <<<"$qs"
	echo "| $preset | $counts | $stops | $q50 | $q90 | $q99 | $qmax | $perf |"
done

# with a second argument: a histogram of overlap_max per preset (gnuplot, PNG and PDF)
if [ -n "${2:-}" ]; then
	out=$2
	tmp=$(mktemp -d)
	trap 'rm -rf "$tmp"' EXIT
	for c in overlap_safety overlap_safety_fast; do
		q "SELECT overlap_max FROM runs WHERE campaign = '$c' AND current AND overlap_max IS NOT NULL" >"$tmp/$c.txt"
	done
	np=$(wc -l <"$tmp/overlap_safety.txt") nf=$(wc -l <"$tmp/overlap_safety_fast.txt")
	for term in "pngcairo size 800,480 font 'DejaVu Sans,11'|$out.png" "pdfcairo size 6in,3.6in font 'DejaVu Sans,10'|$out.pdf"; do
		gnuplot <<GP
set terminal ${term%%|*}
set output '${term#*|}'
set title 'Largest overlap per run: paper scene, 120 s, 2.7–3.2 Hz, 𝓡 = 0, 3, 4'
set xlabel 'largest overlap / smaller radius'
set ylabel 'runs per bin of 0.01'
set xrange [0.3:1.05]
set style fill transparent solid 0.5 noborder
set boxwidth 0.01
set arrow from 1, graph 0 to 1, graph 1 nohead dt 2 lc rgb 'black'
set label 'max\_overlap stop (1)' at 0.99, graph 0.9 right
set key top left
bin(x) = 0.01 * floor(x / 0.01) + 0.005
plot '$tmp/overlap_safety.txt' using (bin(\$1)):(1.0) smooth frequency with boxes lc rgb '#1f77b4' title 'paper preset (gear5, 5e-5 s), $np runs', \
     '$tmp/overlap_safety_fast.txt' using (bin(\$1)):(1.0) smooth frequency with boxes lc rgb '#d62728' title 'fast preset (verlet, 2e-4 s), $nf runs'
GP
	done
	echo "wrote $out.png and $out.pdf"
fi
