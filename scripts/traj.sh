#!/usr/bin/env bash
# traj.sh RUN.h5 - the intruder trajectory of a run as TSV: t x y vx vy omega.
set -euo pipefail
[ $# -eq 1 ] || { echo "usage: traj.sh RUN.h5" >&2; exit 1; }
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
h5dump -d /intruder/trajectory -m "%.17g" -y -o "$tmp" --ddl=/dev/null "$1" >/dev/null
echo -e "# t\tx\ty\tvx\tvy\tomega"
tr -s ', \n' '\n' < "$tmp" | awk 'NF { v[n++ % 6] = $1; if (n % 6 == 0) print v[0] "\t" v[1] "\t" v[2] "\t" v[3] "\t" v[4] "\t" v[5] }'
