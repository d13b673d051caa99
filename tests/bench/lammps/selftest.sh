#!/bin/sh
# selftest.sh — quick check of the LAMMPS benchmark side (a few seconds):
#  1. make a tiny box (100 grains + intruder + 120 wall disks),
#  2. check that LAMMPS's masses equal 2 pi R^2 rho (check_mass.in),
#  3. run vibrated_box.in for 400 steps with a final dump and check the dump,
#  4. run ../lammps_time.sh and check its one-line output.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/lmpself.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
"$here/make_test_data.sh" 100 7 > "$tmp/tiny.data"
OMP_NUM_THREADS=1 lmp -in "$here/check_mass.in" -var data "$tmp/tiny.data" \
  -log none -nocite | grep '^mass_check'
OMP_NUM_THREADS=1 lmp -in "$here/vibrated_box.in" -log none -screen none -nocite \
  -var data "$tmp/tiny.data" -var steps 400 -var final "$tmp/final.dump"
natoms=$(sed -n 's/^\([0-9]*\) atoms$/\1/p' "$tmp/tiny.data")
ndump=$(awk 'f{n++} /^ITEM: ATOMS id type x y vx vy omegaz$/{f=1} END{print n+0}' "$tmp/final.dump")
[ "$ndump" = "$natoms" ] || { echo "selftest: dump has $ndump atoms, expected $natoms" >&2; exit 1; }
# wall disk 1 must sit at y = -1 + A sin(2 pi f t), t = 400*5e-5 s
awk '$1==1 && NF==7 { e = -1 + 2*sin(2*3.141592653589793*3.2*400*5e-5);
      d = $4 - e; if (d < 0) d = -d; if (d > 1e-12) { print "selftest: wall y", $4, "expected", e; exit 1 } }' "$tmp/final.dump"
line=$("$here/../lammps_time.sh" "$tmp/tiny.data" 400)
echo "$line"
echo "$line" | grep -Eq '^lammps_loop_seconds=[0-9.e+-]+ steps=400 atoms='"$natoms"'$' \
  || { echo "selftest: bad lammps_time.sh output" >&2; exit 1; }
echo "selftest: OK"
