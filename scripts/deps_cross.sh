#!/usr/bin/env bash
# deps_cross.sh - what `make cross-aarch64` needs (docs/cross.md): Debian's cross
# compiler for aarch64, qemu-user to run its programs, and the engine's libraries
# (HDF5, GSL, inih, SQLite) for arm64. Installs only what is missing; a no-op when
# everything is there. Called by `make deps-cross`.
#
# The arm64 libraries come through Debian multiarch (dpkg --add-architecture arm64),
# beside the amd64 ones. libhdf5-dev and libgsl-dev cannot be installed for two
# architectures at once (they are not Multi-Arch: same), so their arm64 packages, with
# the runtime libraries the link needs, are unpacked (dpkg-deb -x) into CROSS_ROOT,
# and CROSS_ROOT/pkgconfig holds their .pc files pointing there. The runtime libraries
# themselves are installed for arm64 too, so the programs find them under qemu.
set -euo pipefail
ARCH=arm64
TRIPLET=aarch64-linux-gnu
CROSS_ROOT=${CROSS_ROOT:-/opt/shakebox-cross/$TRIPLET}
HOST_PKGS=("gcc-$TRIPLET" "binutils-$TRIPLET" qemu-user pkg-config)
# co-installable with the amd64 ones: the libraries and headers the engine links,
# and the runtime libraries of the two that are unpacked
ARM_PKGS=(libinih-dev libsqlite3-dev libhdf5-103-1 libgsl27 libgslcblas0)
# unpacked into CROSS_ROOT (their exact versions follow the installed runtime ones)
UNPACK=(libhdf5-dev:libhdf5-103-1 libgsl-dev:libgsl27 libgslcblas0:libgslcblas0 libhdf5-103-1:libhdf5-103-1 libgsl27:libgsl27)

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
version() { dpkg-query -W -f='${Version}' "$1" 2>/dev/null; }
updated=0
update() { [ $updated -eq 1 ] || { $SUDO apt-get update -qq; updated=1; }; }

missing=()
for p in "${HOST_PKGS[@]}"; do installed "$p" || missing+=("$p"); done
if ! dpkg --print-foreign-architectures | grep -qx $ARCH; then
	echo "deps-cross: adding the $ARCH architecture (dpkg multiarch)" >&2
	$SUDO dpkg --add-architecture $ARCH
	updated=0
	update
fi
for p in "${ARM_PKGS[@]}"; do installed "$p:$ARCH" || missing+=("$p:$ARCH"); done
if [ ${#missing[@]} -gt 0 ]; then
	echo "deps-cross: installing ${missing[*]}" >&2
	update
	$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi

# The unpacked tree: redone when a runtime library it matches changed version.
want=""
for u in "${UNPACK[@]}"; do want+="${u%%:*}=$(version "${u#*:}:$ARCH")"$'\n'; done
if [ -f "$CROSS_ROOT/versions" ] && [ "$(cat "$CROSS_ROOT/versions")" = "${want%$'\n'}" ]; then
	exit 0
fi
echo "deps-cross: unpacking the $ARCH development packages of HDF5 and GSL into $CROSS_ROOT" >&2
tmp=$(mktemp -d)
# apt-get download writes the files as the _apt user (else it warns and writes as root)
if [ "$(id -u)" -eq 0 ] && id _apt >/dev/null 2>&1; then chown _apt "$tmp"; fi
trap 'rm -rf "$tmp"' EXIT
update
for u in "${UNPACK[@]}"; do
	(cd "$tmp" && apt-get download -qq "${u%%:*}:$ARCH=$(version "${u#*:}:$ARCH")")
done
$SUDO rm -rf "$CROSS_ROOT.new"
$SUDO mkdir -p "$CROSS_ROOT.new/pkgconfig"
for d in "$tmp"/*.deb; do $SUDO dpkg-deb -x "$d" "$CROSS_ROOT.new"; done
# the .pc files with their absolute paths moved into the unpacked tree
for pc in hdf5-serial gsl; do
	sed "s|/usr/|$CROSS_ROOT/usr/|g" "$CROSS_ROOT.new/usr/lib/$TRIPLET/pkgconfig/$pc.pc" |
		$SUDO tee "$CROSS_ROOT.new/pkgconfig/$pc.pc" >/dev/null
done
printf '%s' "${want%$'\n'}" | $SUDO tee "$CROSS_ROOT.new/versions" >/dev/null
$SUDO rm -rf "$CROSS_ROOT"
$SUDO mv "$CROSS_ROOT.new" "$CROSS_ROOT"
