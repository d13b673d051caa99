#!/usr/bin/env bash
# deps.sh - install the Debian packages shakebox needs, only those that are missing.
# Called by `make deps`, and by `make check`/`make demo` on a fresh machine.
set -euo pipefail
PKGS=(build-essential pkg-config libgsl-dev libhdf5-dev hdf5-tools libsqlite3-dev sqlite3
      libinih-dev parallel gnuplot-nox lammps openssh-server openssh-client rsync time
      slurmctld slurmd slurm-client munge python3-h5py python3-mdanalysis)
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
