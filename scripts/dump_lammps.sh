#!/usr/bin/env bash
# dump_lammps.sh - a run's snapshots as a LAMMPS text dump (`dump custom` layout: id,
# type, x, y, z, radius, vx, vy), which OVITO and LAMMPS's read_dump open. One frame per
# snapshot (lab frame, its step the engine's): the mobile disks of /particles/bed, then
# the walls of /particles/walls, which stand at their place at rest in every snapshot
# (phase 0) and move with the box's velocity there. Types: 1 grain, 2 intruder, 3 wall, and ids from 1 (as in the engine's LAMMPS
# data files).
#   usage: scripts/dump_lammps.sh RUN.h5 > RUN.dump
set -euo pipefail
f=${1:?usage: dump_lammps.sh RUN.h5 > RUN.dump}
[ -r "$f" ] || { echo "dump_lammps: $f: cannot read" >&2; exit 1; }
B=/particles/bed
h5dump -H -d $B/position/value "$f" >/dev/null 2>&1 ||
	{ echo "dump_lammps: $f: no $B/position (run with snapshots = yes)" >&2; exit 1; }
# a dataset's values, one per line (the first DATA block: the dataset's, not its attributes')
col() { h5dump -m %.17g -d "$2" -y -w 0 "$1" | awk '/DATA \{/ && !done { on = 1; next } on && /\}/ { on = 0; done = 1 }
	on { gsub(/,/, " "); for (i = 1; i <= NF; i++) print $i }'; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
W=/particles/walls
{ col "$f" $B/id; col "$f" $W/id; } >"$tmp/id"
{ col "$f" $B/species; col "$f" $W/species; } >"$tmp/kind"
{ col "$f" $B/radius; col "$f" $W/radius; } >"$tmp/r"
col "$f" $W/position >"$tmp/wp"
col "$f" $B/position/step >"$tmp/step"
col "$f" $B/position/value >"$tmp/p"
col "$f" $B/velocity/value >"$tmp/v"
col "$f" $B/box/offset_velocity/value >"$tmp/bv"
awk -v tmp="$tmp" 'BEGIN {
	while ((getline v < (tmp "/id")) > 0) id[n++] = v
	k = 0; while ((getline v < (tmp "/kind")) > 0) kind[k++] = v
	k = 0; while ((getline v < (tmp "/r")) > 0) r[k++] = v
	nw = 0; while ((getline v < (tmp "/wp")) > 0) { wx[nw] = v; getline wy[nw] < (tmp "/wp"); nw++ }
	nm = n - nw
	K = 0; while ((getline v < (tmp "/step")) > 0) st[K++] = v
	for (s = 0; s < K; s++) {
		for (i = 0; i < nm; i++) {
			getline x[i] < (tmp "/p"); getline y[i] < (tmp "/p")
			getline vx[i] < (tmp "/v"); getline vy[i] < (tmp "/v")
		}
		getline bvx < (tmp "/bv"); getline bvy < (tmp "/bv")
		for (i = nm; i < n; i++) { x[i] = wx[i - nm]; y[i] = wy[i - nm]; vx[i] = bvx; vy[i] = bvy }
		xlo = ylo = 1e300; xhi = yhi = -1e300
		for (i = 0; i < n; i++) {
			if (x[i] - r[i] < xlo) xlo = x[i] - r[i]; if (x[i] + r[i] > xhi) xhi = x[i] + r[i]
			if (y[i] - r[i] < ylo) ylo = y[i] - r[i]; if (y[i] + r[i] > yhi) yhi = y[i] + r[i]
		}
		printf "ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n%d\n", st[s], n
		printf "ITEM: BOX BOUNDS ff ff pp\n%.17g %.17g\n%.17g %.17g\n-0.5 0.5\n", xlo, xhi, ylo, yhi
		print "ITEM: ATOMS id type x y z radius vx vy"
		for (i = 0; i < n; i++)
			printf "%d %d %.17g %.17g 0 %.17g %.17g %.17g\n", id[i] + 1, kind[i] == 0 ? 1 : kind[i] == 1 ? 2 : 3,
				x[i], y[i], r[i], vx[i], vy[i]
	}
}'
