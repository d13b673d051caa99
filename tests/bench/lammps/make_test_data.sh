#!/bin/sh
# make_test_data.sh — write a LAMMPS data file (atom_style sphere) in the same
# format as shakebox's engine writer, for testing vibrated_box.in without the
# engine.  The grains sit on a loose square lattice (NOT settled); settle them
# with settle.in (see README) to get a realistic dense bed.
#
# usage: make_test_data.sh [NGRAINS=950] [SEED=1] [R1=4] [W=60] [NSIDE=44] > file.data
#
# Geometry (docs/model.md defaults):
#   type 3 wall disks, radius 1, touching (spacing 2): bottom row centres at
#   y = -1, x = -1, 1, ..., W+1; side columns at x = -1 and x = W+1,
#   y = 1, 3, ..., 2*NSIDE-1.
#   type 2 intruder, radius R1, at (W/2, R1) i.e. resting on the bottom wall.
#   type 1 grains, radius uniform in [0.85, 1.15], lattice spacing 2.35 cm,
#   sites overlapping the intruder skipped.
# Mass: the engine uses m = 2*pi*R^2*rho (rho = 1).  LAMMPS read_data computes
# m = 4/3*pi*r^3*density even in 2D, so the density column holds
#   rho' = 3 m / (4 pi R^3) = 1.5 * rho / R
# which makes LAMMPS's mass exactly 2*pi*R^2*rho.
N=${1:-950}
SEED=${2:-1}
R1=${3:-4}
W=${4:-60}
NSIDE=${5:-44}
awk -v N="$N" -v seed="$SEED" -v R1="$R1" -v W="$W" -v NSIDE="$NSIDE" '
function rho_p(R) { return 1.5 / R }          # rho = 1 g/cm^2 (2D)
function atom(t, R, x, y) {
  n++; T[n] = t; D[n] = 2*R; P[n] = rho_p(R); X[n] = x; Y[n] = y
}
BEGIN {
  srand(seed)
  n = 0
  # walls (type 3)
  for (x = -1; x <= W + 1 + 1e-9; x += 2) atom(3, 1, x, -1)
  for (k = 0; k < NSIDE; k++) { atom(3, 1, -1, 1 + 2*k); atom(3, 1, W + 1, 1 + 2*k) }
  # intruder (type 2) resting on the bottom wall, centre of the box
  if (R1 > 0) { cx = W/2; cy = R1; atom(2, R1, cx, cy) }
  # grains (type 1) on a lattice
  s = 2.35; ng = 0
  for (j = 0; ng < N; j++) {
    y = 1.2 + j*s
    for (x = 1.2; x <= W - 1.2 + 1e-9 && ng < N; x += s) {
      if (R1 > 0 && (x-cx)^2 + (y-cy)^2 < (R1 + 1.2)^2) continue
      atom(1, 0.85 + 0.3*rand(), x, y); ng++
    }
  }
  ytop = y + 20; if (ytop < 2*NSIDE + 20) ytop = 2*NSIDE + 20
  printf "# shakebox state (test data from make_test_data.sh N=%d seed=%d R1=%g W=%g)\n\n", N, seed, R1, W
  printf "%d atoms\n3 atom types\n\n", n
  printf "%.17g %.17g xlo xhi\n", -2, W + 2
  printf "%.17g %.17g ylo yhi\n", -2, ytop
  printf "-0.5 0.5 zlo zhi\n\nAtoms # sphere\n\n"
  for (i = 1; i <= n; i++)
    printf "%d %d %.17g %.17g %.17g %.17g 0.0\n", i, T[i], D[i], P[i], X[i], Y[i]
  printf "\nVelocities\n\n"
  for (i = 1; i <= n; i++) printf "%d 0.0 0.0 0.0 0.0 0.0 0.0\n", i
}'
