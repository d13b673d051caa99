#!/usr/bin/env bash
# demo.sh - one short paper scene end to end: settle, shake 10 s at 3.2 Hz, plot the
# intruder's height. (Becomes a small campaign once study/ exists.)
set -euo pipefail
cd "$(dirname "$0")/.."
out=runs/demo
mkdir -p "$out"
echo "demo: settling 950 grains and shaking them for 10 s (paper scene, f = 3.2 Hz) ..."
t0=$SECONDS
bin/shake scenes/paper.scene duration=10 output="$out/paper.h5" progress=yes
echo "demo: simulated in $((SECONDS - t0)) s"
bash scripts/traj.sh "$out/paper.h5" > "$out/intruder.tsv"
gnuplot <<GP
set terminal pngcairo size 900,500
set output "$out/intruder_height.png"
set xlabel "t (s)"; set ylabel "intruder height y (cm)"
set title "Intruder (R = 4 cm) in 950 grains, A = 2 cm, f = 3.2 Hz"
set grid
plot "$out/intruder.tsv" using 1:3 with lines title "centre height (lab frame)"
GP
echo "demo: output        $out/paper.h5 (open $out/paper.xmf in ParaView)"
echo "demo: trajectory    $out/intruder.tsv (t x y vx vy omega)"
echo "demo: plot          $out/intruder_height.png"
