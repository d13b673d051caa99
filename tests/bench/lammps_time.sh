#!/bin/sh
# lammps_time.sh DATAFILE STEPS [FREQ] [extra lmp args...]
# Time LAMMPS (lammps/vibrated_box.in) on a shakebox state, one core.
# Prints ONE line:  lammps_loop_seconds=<X> steps=<N> atoms=<M>
# parsed from LAMMPS's "Loop time of X on 1 procs for N steps with M atoms"
# (the MD loop only: no startup, read_data or setup).  Extra arguments are
# passed to lmp, e.g. -var amp 0 or -var neigh bin -var skin 0.2.
# Env: LMP (default lmp).  Exits non-zero with a message on failure.
set -u
here=$(cd "$(dirname "$0")" && pwd)
deck="$here/lammps/vibrated_box.in"
LMP=${LMP:-lmp}

if [ $# -lt 2 ]; then
  echo "usage: $0 DATAFILE STEPS [FREQ] [extra lmp args...]" >&2; exit 2
fi
data=$1; steps=$2; shift 2
freq=3.2
if [ $# -ge 1 ]; then freq=$1; shift; fi
[ -r "$data" ] || { echo "lammps_time.sh: cannot read data file '$data'" >&2; exit 2; }
command -v "$LMP" >/dev/null 2>&1 || { echo "lammps_time.sh: '$LMP' not found (apt install lammps)" >&2; exit 2; }

out=$(mktemp "${TMPDIR:-/tmp}/lammps_time.XXXXXX") || exit 2
trap 'rm -f "$out"' EXIT INT TERM

# one core: no mpirun, one OpenMP thread (the OMP variant is not used, but
# OMP_NUM_THREADS also silences LAMMPS's warning and pins any threaded code)
OMP_NUM_THREADS=1 "$LMP" -in "$deck" -log none -screen "$out" -nocite \
  -var data "$data" -var steps "$steps" -var freq "$freq" "$@" >/dev/null 2>&1
rc=$?
if [ $rc -ne 0 ]; then
  echo "lammps_time.sh: lmp failed (exit $rc); last lines of its output:" >&2
  tail -n 15 "$out" >&2
  exit 1
fi
line=$(grep '^Loop time of ' "$out" | tail -n 1)
if [ -z "$line" ]; then
  echo "lammps_time.sh: no 'Loop time of' line in lmp output; last lines:" >&2
  tail -n 15 "$out" >&2
  exit 1
fi
# Loop time of X on P procs for N steps with M atoms
echo "$line" | awk '{ printf "lammps_loop_seconds=%s steps=%s atoms=%s\n", $4, $9, $12 }'
