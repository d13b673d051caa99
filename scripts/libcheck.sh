#!/usr/bin/env bash
# libcheck.sh - are the libraries the build links there? Looks, never installs: a plain
# `make` runs it before compiling (the Makefile's build/.libs-ok), and stops naming each
# missing library with the package that provides it on Debian, Fedora/RHEL and Spack.
# A library is found by pkg-config, or in a directory given as HDF5_DIR, GSL_DIR,
# INIH_DIR or SQLITE_DIR (DIR/include, DIR/lib: module-based clusters). Exits 0 when
# every one is there, 1 naming what is missing (nothing is installed), 2 on bad usage.
set -u
# name | pkg-config names | its directory variable | a header it must have | Debian | Fedora/RHEL | Spack
LIBS="HDF5|hdf5-serial hdf5|HDF5_DIR|hdf5.h|libhdf5-dev|hdf5-devel|hdf5~mpi
GSL|gsl|GSL_DIR|gsl/gsl_errno.h|libgsl-dev|gsl-devel|gsl
inih|inih|INIH_DIR|ini.h|libinih-dev|inih-devel|inih
SQLite|sqlite3|SQLITE_DIR|sqlite3.h|libsqlite3-dev|sqlite-devel|sqlite"
case "${1:-}" in -h | --help) sed -n '2,/^set -u/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
missing=() deb=() rpm=() spack=()
have_pc=1
command -v pkg-config >/dev/null 2>&1 || have_pc=0
while IFS='|' read -r name pcs var header d r s; do
	dir=${!var:-}
	if [ -n "$dir" ]; then
		if [ -f "$dir/include/$header" ] && [ -d "$dir/lib" ]; then continue; fi
		missing+=("$name ($var=$dir has no include/$header and lib/)")
	else
		found=0
		for pc in $pcs; do
			[ "$have_pc" = 1 ] && pkg-config --exists "$pc" 2>/dev/null && { found=1; break; }
		done
		[ "$found" = 1 ] && continue
		missing+=("$name (pkg-config: $(echo "$pcs" | sed 's/ / or /g'); or $var=DIR)")
	fi
	deb+=("$d") rpm+=("$r") spack+=("$s")
done <<<"$LIBS"
[ ${#missing[@]} -eq 0 ] && exit 0
{
	echo "make: cannot build: missing libraries:"
	printf '  %s\n' "${missing[@]}"
	[ "$have_pc" = 1 ] || echo "  (and pkg-config itself is not installed: Debian pkg-config, Fedora/RHEL pkgconf)"
	echo "install them, then run make again:"
	echo "  Debian/Ubuntu:  sudo apt-get install ${deb[*]}   (or: make deps, which installs everything make demo needs)"
	echo "  Fedora/RHEL:    sudo dnf install ${rpm[*]}"
	echo "  Spack:          spack install ${spack[*]} && spack load ${spack[*]%%~*}"
	echo "  modules:        module load the libraries, or give each one's prefix: HDF5_DIR=/path make"
	echo "nothing was installed (docs/install.md)"
} >&2
exit 1
