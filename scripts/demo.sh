#!/usr/bin/env bash
# demo.sh - `make demo`: a small campaign end to end (campaigns/demo.campaign: 5
# frequencies x 2 replicates), a query of its results with sqlite3, and the intruder's
# height in one run plotted. Run it again: nothing is recomputed.
set -euo pipefail
cd "$(dirname "$0")/.."
t0=$SECONDS
# --keep-old: runs of an earlier demo campaign file stay, out of the analysis
bin/study run campaigns/demo.campaign --keep-old
echo "demo: campaign done in $((SECONDS - t0)) s; results (runs/study.db):"
echo
sqlite3 -header -column runs/study.db "
SELECT frequency, replicate, status, from_cache,
       round(intruder_settled_y_box, 2) AS y_settled, round(intruder_final_y_box, 2) AS y_final,
       round(intruder_max_y_box, 2) AS y_max, round(wall_seconds, 2) AS seconds
FROM runs WHERE campaign = 'demo' AND current ORDER BY frequency, replicate;"
echo
sqlite3 -header -column runs/study.db "
SELECT frequency, COUNT(*) AS runs, round(AVG(intruder_rise_box), 3) AS mean_rise_cm
FROM runs WHERE campaign = 'demo' AND current AND status = 'ok' GROUP BY frequency ORDER BY frequency;"
run=$(sqlite3 runs/study.db "SELECT id FROM runs WHERE campaign = 'demo' AND current AND status = 'ok' ORDER BY frequency DESC, replicate LIMIT 1")
out=runs/demo
bash scripts/traj.sh "$out/$run.h5" >"$out/intruder.tsv"
gnuplot <<GP
set terminal pngcairo size 900,500
set output "$out/intruder_height.png"
set xlabel "t (s)"; set ylabel "intruder height y (cm)"
set title "Intruder (R = 2) in 150 grains, A = 1 cm, run $run"
set grid
plot "$out/intruder.tsv" using 1:3 with lines title "centre height (lab frame)"
GP
echo
echo "demo: the onset of convection (bin/onset) and the paper's figures (bin/figures):"
bin/onset demo --boot 200 | tail -n 12
bin/figures demo >/dev/null
echo "demo: status        bin/study status demo"
echo "demo: every run     bin/study export demo > demo.csv"
echo "demo: one run       $out/$run.h5 (open $out/$run.xmf in ParaView)"
echo "demo: plot          $out/intruder_height.png"
echo "demo: figures       $out/analysis/ (onset, Fig. 3 flux profiles, Fig. 4 intruder height)"
