#!/usr/bin/env bash
# deps.sh [build|test|all] - install the Debian packages shakebox needs, only those that
# are missing (apt-get, as root or through sudo). The only script that runs a package
# manager: a plain `make` never calls it (scripts/libcheck.sh only looks).
#   build  what `make` and `make demo` need: the compiler, the libraries, and the
#          programs the driver and the tools run (GNU parallel, gnuplot, sqlite3,
#          h5dump, time, ffmpeg for bin/movie)                            (`make deps`)
#   test   what only the suite and the benchmarks add: LAMMPS, sshd and rsync (the
#          multi-host test), Slurm and munge, Debian's Python h5py, MDAnalysis and pandas
#                                                                    (`make deps-test`)
#   all    both (default; `make check` on a fresh machine)
set -euo pipefail
BUILD=(build-essential pkg-config libgsl-dev libhdf5-dev hdf5-tools libsqlite3-dev sqlite3
       libinih-dev parallel gnuplot-nox time ffmpeg)
TEST=(lammps openssh-server openssh-client rsync slurmctld slurmd slurm-client munge
      python3-h5py python3-mdanalysis python3-pandas)
case "${1:-all}" in
build) PKGS=("${BUILD[@]}") ;;
test) PKGS=("${TEST[@]}") ;;
all) PKGS=("${BUILD[@]}" "${TEST[@]}") ;;
-h | --help) sed -n '2,/^set -eu/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
*) echo "deps.sh: unknown group '$1' (build, test or all)" >&2; exit 2 ;;
esac
missing=()
for p in "${PKGS[@]}"; do
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "deps: installing ${missing[*]}" >&2
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
