#!/usr/bin/env bash
# dump_lammps.sh - a run's snapshots as a LAMMPS text dump (`dump custom` layout: id,
# type, x, y, z, radius), which OVITO and LAMMPS's read_dump open. One frame per
# snapshot (lab frame, at phase 0 of the drive, where the box is at its rest position,
# so the wall disks stand where /final's box-frame positions put them). Types: 1 grain,
# 2 intruder, 3 wall, and ids from 1 (as in the engine's LAMMPS data files).
#   usage: scripts/dump_lammps.sh RUN.h5 > RUN.dump
set -euo pipefail
f=${1:?usage: dump_lammps.sh RUN.h5 > RUN.dump}
[ -r "$f" ] || { echo "dump_lammps: $f: cannot read" >&2; exit 1; }
h5dump -H -d /snapshots/x "$f" >/dev/null 2>&1 || { echo "dump_lammps: $f: no /snapshots (run with snapshots = yes)" >&2; exit 1; }
# a dataset's values, one per line
col() { h5dump -m %.17g -d "$2" -y -w 0 "$1" | awk '/DATA \{/ && !done { on = 1; next } on && /\}/ { on = 0; done = 1 } on' |
	tr ',' '\n' | sed 's/^ *//; /^$/d'; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
col "$f" /particles/id >"$tmp/id"
col "$f" /particles/kind >"$tmp/kind"
col "$f" /particles/radius >"$tmp/r"
col "$f" /final/x >"$tmp/fx"
col "$f" /final/y >"$tmp/fy"
col "$f" /snapshots/time >"$tmp/t"
col "$f" /snapshots/x >"$tmp/x"
col "$f" /snapshots/y >"$tmp/y"
dt=$(h5dump -a /dt -m %.17g "$f" | awk '/\(0\)/ { print $2 }')
awk -v dt="$dt" -v tmp="$tmp" 'BEGIN {
	while ((getline v < (tmp "/id")) > 0) id[n++] = v
	k = 0; while ((getline v < (tmp "/kind")) > 0) kind[k++] = v
	k = 0; while ((getline v < (tmp "/r")) > 0) r[k++] = v
	k = 0; while ((getline v < (tmp "/fx")) > 0) fx[k++] = v
	k = 0; while ((getline v < (tmp "/fy")) > 0) fy[k++] = v
	nm = 0; for (i = 0; i < n; i++) nm += kind[i] != 2
	K = 0; while ((getline v < (tmp "/t")) > 0) t[K++] = v
	for (s = 0; s < K; s++) {
		for (i = 0; i < nm; i++) { getline x[i] < (tmp "/x"); getline y[i] < (tmp "/y") }
		for (i = nm; i < n; i++) { x[i] = fx[i]; y[i] = fy[i] }
		xlo = ylo = 1e300; xhi = yhi = -1e300
		for (i = 0; i < n; i++) {
			if (x[i] - r[i] < xlo) xlo = x[i] - r[i]; if (x[i] + r[i] > xhi) xhi = x[i] + r[i]
			if (y[i] - r[i] < ylo) ylo = y[i] - r[i]; if (y[i] + r[i] > yhi) yhi = y[i] + r[i]
		}
		printf "ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n%d\n", int(t[s] / dt + 0.5), n
		printf "ITEM: BOX BOUNDS ff ff pp\n%.17g %.17g\n%.17g %.17g\n-0.5 0.5\n", xlo, xhi, ylo, yhi
		print "ITEM: ATOMS id type x y z radius"
		for (i = 0; i < n; i++) printf "%d %d %.17g %.17g 0 %.17g\n", id[i] + 1, kind[i] == 0 ? 1 : kind[i] == 1 ? 2 : 3, x[i], y[i], r[i]
	}
}'
