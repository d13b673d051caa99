#!/usr/bin/env bash
# traj.sh RUN.h5 - the intruder trajectory of a run as TSV: t x y vx vy omega (lab frame,
# from the H5MD group /particles/intruder).
set -euo pipefail
[ $# -eq 1 ] || { echo "usage: traj.sh RUN.h5" >&2; exit 1; }
g=/particles/intruder
h5dump -H -d $g/position/value "$1" >/dev/null 2>&1 || { echo "traj.sh: $1: no $g (a run with an intruder)" >&2; exit 1; }
# a dataset's values, one per line (the first DATA block: the dataset's, not its attributes')
col() { h5dump -m %.17g -d "$2" -y -w 0 "$1" | awk '/DATA \{/ && !done { on = 1; next } on && /\}/ { on = 0; done = 1 }
	on { gsub(/,/, " "); for (i = 1; i <= NF; i++) print $i }'; }
echo -e "# t\tx\ty\tvx\tvy\tomega"
paste <(col "$1" $g/position/time) <(col "$1" $g/position/value | paste - -) <(col "$1" $g/velocity/value | paste - -) \
	<(col "$1" $g/angular_velocity/value)
