# cross.mk - `make cross-aarch64`: the engine and the test programs built by
# Debian's cross compiler for aarch64 and run under qemu-user; `make
# cross-aarch64-regression`: the engine under qemu on the regression scenes, compared
# with the x86-64 references (docs/cross.md). Included by the top-level Makefile; not
# part of `make check` (it needs `make deps-cross`, and qemu is slow).
#
# The build is this Makefile run again with the cross compiler, a build directory of
# its own and the arm64 pkg-config files, so that whatever core/ holds is built the
# same way as natively: the Makefile picks the vector kernel's instruction sets from
# the compiler's target (-dumpmachine). MARCH, a knob for this machine's CPU, is
# emptied.
CROSS_TRIPLET ?= aarch64-linux-gnu
CROSS_CC      ?= $(CROSS_TRIPLET)-gcc
CROSS_BUILD   ?= build/aarch64
# where scripts/deps_cross.sh unpacked the arm64 HDF5 and GSL development packages
CROSS_ROOT    ?= /opt/shakebox-cross/$(CROSS_TRIPLET)
CROSS_PKGDIR   = $(CROSS_ROOT)/pkgconfig:/usr/lib/$(CROSS_TRIPLET)/pkgconfig:/usr/share/pkgconfig
CROSS_QEMU    ?= qemu-aarch64 -L /usr/$(CROSS_TRIPLET)
# every test program: the engine's unit and physics tests, and those of bin/study's
# modules and of the analysis library (CROSS_TSRC=tests/unit/kernel.c narrows it)
CROSS_TSRC    ?= $(wildcard tests/unit/*.c tests/physics/*.c tests/analysis/*.c)
CROSS_TBIN     = $(CROSS_TSRC:%.c=$(CROSS_BUILD)/%)
CROSS_SHAKE    = $(CROSS_BUILD)/bin/shake
CROSS_VARS     = CC=$(CROSS_CC) BUILD=$(CROSS_BUILD) BIN=$(CROSS_BUILD)/bin SAN=0 MARCH= HDF5_STATIC=0

.PHONY: deps-cross cross-aarch64 cross-aarch64-build cross-aarch64-products cross-aarch64-regression

deps-cross:
	$(Q)CROSS_ROOT=$(CROSS_ROOT) bash scripts/deps_cross.sh

# The flags must be those of every build: no x86 -march, and -ffp-contract=off (GCC
# for aarch64 would otherwise fuse a*b+c into one FMA, which rounds once, and the
# results would differ from x86-64's).
cross-aarch64-build:
	$(Q)CROSS_ROOT=$(CROSS_ROOT) bash scripts/deps_cross.sh
	$(Q)PKG_CONFIG_LIBDIR=$(CROSS_PKGDIR) $(MAKE) --no-print-directory $(CROSS_VARS) cross-aarch64-products
	$(Q)if grep -q -- '-march' $(CROSS_BUILD)/flags || ! grep -q -- '-ffp-contract=off' $(CROSS_BUILD)/flags; then \
		echo "cross-aarch64: wrong flags in $(CROSS_BUILD)/flags: $$(cat $(CROSS_BUILD)/flags)" >&2; exit 1; fi

# made by the Makefile run again (BUILD is the cross build's there)
cross-aarch64-products: $(LIB) $(SHAKE) $(CROSS_TSRC:%.c=$(BUILD)/%)
	@:

# Each test runs under qemu, and natively (this machine's build), and the two outputs
# must be the same (tests/cross/run.sh).
cross-aarch64: cross-aarch64-build $(CROSS_TSRC:%.c=$(BUILD)/%)
	$(Q)QEMU="$(CROSS_QEMU)" NATIVE=$(BUILD) CROSS_BUILD=$(CROSS_BUILD) bash tests/cross/run.sh $(CROSS_TBIN)

cross-aarch64-regression: cross-aarch64-build $(SHAKE)
	$(Q)QEMU="$(CROSS_QEMU)" CROSS_SHAKE=$(CURDIR)/$(CROSS_SHAKE) NATIVE_SHAKE=$(CURDIR)/$(SHAKE) bash tests/cross/regression.sh
