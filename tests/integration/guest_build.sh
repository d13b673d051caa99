#!/usr/bin/env bash
# guest_build.sh - `make` is a guest on the user's machine (docs/install.md): it builds
# without running a package manager, and says what is missing instead. A copy of the
# tracked files is built with apt-get, apt, dpkg, dpkg-query, sudo, dnf, yum and spack
# shadowed by stubs that fail loudly and record that they were called, as on a cluster's
# login node without root: a plain `make` must build every program and call none of
# them; with the libraries hidden from pkg-config it must stop naming each one and its
# packages, having built and installed nothing; a library given as HDF5_DIR (a prefix
# with include/ and lib/, as environment modules give) must be found there.
# tier: slow: three builds of a copy of the tree (at -O0)
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

mkdir -p src stubs
(cd "$REPO" && git ls-files -z | tar --null -T - -cf -) | tar -xf - -C src ||
	{ fail setup "cannot copy the tracked files"; finish; }
for c in apt-get apt dpkg dpkg-query sudo dnf yum spack; do
	printf '#!/bin/sh\necho "%s $*" >>"%s/called"\necho "stub: %s must not be called by make" >&2\nexit 1\n' \
		"$c" "$TMP" "$c" >"stubs/$c"
	chmod +x "stubs/$c"
done
# the checker: a stub called by hand records the call
PATH="$TMP/stubs:$PATH" apt-get install x 2>/dev/null
check guest.selftest.stub_records "a stub did not record its call" grep -q '^apt-get install x' called
rm -f called
# a new directory for the build products: no stamp of this tree's builds is reused
J="-j${NPROC:-2}"

# a plain make: every program, no package manager
PATH="$TMP/stubs:$PATH" make -C src $J CFLAGS=-O0 >make.log 2>&1
rc=$?
check guest.make_builds "exit $rc: $(tail -n 3 make.log)" test "$rc" = 0
check guest.make_calls_no_package_manager "make called: $(cat called 2>/dev/null)" test ! -e called
n=0
for b in $(make -s -C src print-tools); do
	[ -x "src/bin/$b" ] && n=$((n + 1)) || fail "guest.make_builds.$b" "src/bin/$b was not built"
done
check guest.make_builds_every_tool "only $n programs built" test "$n" -ge 8
quiet() { "$@" >/dev/null 2>&1; }
check guest.shake_runs "$(src/bin/shake --version 2>&1 | head -n 2)" quiet src/bin/shake --version
# Debian's HDF5 linked from its static library (the Makefile's HDF5_STATIC says why), and
# only where the package ships one: then no libhdf5*.so is needed, nor libcurl
needed() { readelf -d "$1" 2>/dev/null | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | tr '\n' ' '; }
if pkg-config --exists hdf5-serial && [ -f "$(pkg-config --libs-only-L hdf5-serial | sed 's/^-L//; s/ *$//')/libhdf5.a" ]; then
	check guest.hdf5_static "src/bin/shake needs: $(needed src/bin/shake)" \
		eval '! needed src/bin/shake | grep -q "libhdf5\|libcurl"'
else
	skip guest.hdf5_static "no Debian libhdf5.a here (pkg-config hdf5-serial)"
fi

# the libraries hidden: stops naming each, with its packages; nothing built or installed
PATH="$TMP/stubs:$PATH" PKG_CONFIG_LIBDIR=/nonexistent make -C src BUILD=build/hidden BIN=build/hidden/bin \
	build/hidden/bin/shake >hidden.log 2>&1
rc=$?
ok_hidden=1
for w in "cannot build: missing libraries" "HDF5 (pkg-config: hdf5-serial or hdf5; or HDF5_DIR=DIR)" "GSL" "inih" \
	"SQLite" "apt-get install libhdf5-dev libgsl-dev libinih-dev libsqlite3-dev" "dnf install hdf5-devel" \
	"spack install hdf5~mpi" "nothing was installed"; do
	grep -qF -- "$w" hidden.log || { ok_hidden=0; fail guest.missing_named "no '$w' in: $(head -c 400 hidden.log)"; }
done
[ "$ok_hidden" = 1 ] && ok guest.missing_named
check guest.missing_exit "exit $rc (want non-zero)" test "$rc" != 0
check guest.missing_builds_nothing "$(ls src/build/hidden 2>&1 | tr '\n' ' ')" \
	test -z "$(find src/build/hidden -name '*.o' 2>/dev/null)"
check guest.missing_calls_no_package_manager "make called: $(cat called 2>/dev/null)" test ! -e called

# HDF5 from a prefix, as a module gives it (Debian's headers and library linked there)
arch=$(cc -dumpmachine)
mkdir -p h5prefix
ln -s /usr/include/hdf5/serial h5prefix/include
ln -s "/usr/lib/$arch/hdf5/serial" h5prefix/lib
PATH="$TMP/stubs:$PATH" make -C src $J CFLAGS=-O0 HDF5_DIR="$TMP/h5prefix" BUILD=build/prefix BIN=build/prefix/bin \
	build/prefix/bin/shake >prefix.log 2>&1
rc=$?
check guest.hdf5_dir_builds "exit $rc: $(tail -n 3 prefix.log)" test "$rc" = 0
check guest.hdf5_dir_used "the compiler was not pointed at the prefix: $(grep -m1 -- '-I' src/build/prefix/flags)" \
	grep -qF -- "-I$TMP/h5prefix/include" src/build/prefix/flags
check guest.hdf5_dir_links_shared "src/build/prefix/bin/shake needs: $(needed src/build/prefix/bin/shake)" \
	eval 'needed src/build/prefix/bin/shake | grep -q libhdf5'
check guest.hdf5_dir_runs "$(src/build/prefix/bin/shake --version 2>&1 | head -n 2)" quiet src/build/prefix/bin/shake --version
PATH="$TMP/stubs:$PATH" make -C src HDF5_DIR="$TMP/nowhere" BUILD=build/nowhere BIN=build/nowhere/bin \
	build/nowhere/bin/shake >nowhere.log 2>&1
rc=$?
check guest.hdf5_dir_missing_named "exit $rc: $(head -c 300 nowhere.log)" \
	eval '[ "$rc" != 0 ] && grep -qF "HDF5 (HDF5_DIR=$TMP/nowhere has no include/hdf5.h and lib/)" nowhere.log'
check guest.no_package_manager_at_all "make called: $(cat called 2>/dev/null)" test ! -e called
finish
