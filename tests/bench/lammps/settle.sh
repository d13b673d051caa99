#!/bin/sh
# settle.sh OUT.data [NGRAINS=950] [SEED=1] [STEPS=80000]
# Make a realistic settled bed for benchmarking without the engine:
# grains on a loose lattice (make_test_data.sh), then STEPS steps of the model
# with the walls at rest (amp 0; 80000 steps = 4 s, enough for the kinetic
# energy to decay to ~1e-4 of its peak for 950 grains), written with write_data.
# The output keeps the engine's format (write_data stores density =
# m/(4/3 pi r^3), i.e. the same rho' column; image flags are appended).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
[ $# -ge 1 ] || { echo "usage: $0 OUT.data [NGRAINS] [SEED] [STEPS]" >&2; exit 2; }
out=$1; n=${2:-950}; seed=${3:-1}; steps=${4:-80000}
tmp=$(mktemp "${TMPDIR:-/tmp}/settle.XXXXXX")
trap 'rm -f "$tmp"' EXIT
"$here/make_test_data.sh" "$n" "$seed" > "$tmp"
OMP_NUM_THREADS=1 lmp -in "$here/vibrated_box.in" -log none -screen none -nocite \
  -var data "$tmp" -var steps "$steps" -var amp 0 -var out "$out"
echo "settle.sh: wrote $out ($n grains, $steps steps at rest)"
