# shakebox - top-level Makefile. Knobs first; `make help` lists the targets.
CC      ?= cc
CFLAGS  ?= -O3 -g
# One binary for every CPU of its architecture: everything is built for the baseline
# (x86-64: SSE2), except the vector kernel (core/force/kvec.c), which is built once per
# instruction set and chosen at start-up (docs/engine.md, "One vector kernel for every
# CPU"). MARCH (e.g. MARCH=-march=native) builds the rest for one CPU instead: faster
# nowhere measurable, and then not for other hosts. Results are bit-identical on every
# path: there is no FMA contraction and no reassociation
# (tests/integration/regression.sh runs every path against one reference).
MARCH ?=
TARGET := $(shell $(CC) -dumpmachine 2>/dev/null)
ifneq ($(filter x86_64-%,$(TARGET)),)
  KV_ISAS := avx512 avx2 sse2 w8
else ifneq ($(filter aarch64-%,$(TARGET)),)
  KV_ISAS := neon w8
else
  KV_ISAS := generic w8
endif
KV_FLAGS_avx512 = -march=x86-64-v4 -mtune=generic -Wno-psabi
KV_FLAGS_avx2   = -march=x86-64-v3 -mtune=generic -Wno-psabi
KV_FLAGS_sse2   = -march=x86-64 -mtune=generic -Wno-psabi
KV_FLAGS_neon   = -Wno-psabi
KV_FLAGS_generic = -Wno-psabi
# eight lanes in plain code on any CPU of the architecture: the AVX-512 path's logic,
# tested where AVX-512 is missing (never chosen by itself)
KV_FLAGS_w8     = -Wno-psabi -DSB_KV_W=8 $(if $(filter x86_64-%,$(TARGET)),-march=x86-64 -mtune=generic)
# No -ffast-math and no FMA contraction: a run must be bit-identical on every machine
# that runs the same build (docs/model.md, "Integrators"). -fno-math-errno only drops the
# errno side effect of sqrt (which nobody reads), so that it compiles to one instruction.
BASEFLAGS = -std=c11 -Wall -Wextra -Werror -ffp-contract=off -fno-math-errno -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -MMD -MP
SAN     ?= 0
V       ?= 0
# make check and make quick: T=REGEX runs only the tests whose name matches (tests/run.sh);
# the builds run NPROC compilers at once and the suite NPROC tests at once (TEST_JOBS)
T       ?=
NPROC   ?= $(shell nproc 2>/dev/null || echo 2)

# assert() holds the invariants the fast path and the tables rely on (nlist_check,
# kernel_check, rec_table_check, ...): active in the sanitizer build that make check
# runs, compiled out of the release build (NDEBUG), as SQLite does with SQLITE_DEBUG.
ifeq ($(SAN),1)
  BUILD   := build/san
  BIN     := build/san/bin
  # SAN_G=-g1: the line tables (and inlined frames) by which a sanitizer's report names
  # file:line, without the types and locals of -g, which cost a third of the build's
  # compile time; a debugger wants them (make SAN=1 SAN_G=-g)
  SAN_G   ?= -g1
  XFLAGS  := -O1 $(SAN_G) -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
  # the sanitizer runtimes linked in: a start and the leak check at the exit cost about
  # 27 ms less per process than with libasan.so and libubsan.so (whose 6 MB of .bss the
  # leak check scans as a library's globals), and the suite starts thousands
  SANLDFLAGS := -static-libasan -static-libubsan
  DBGFLAGS :=
else
  BUILD   := build/rel
  BIN     := bin
  XFLAGS  :=
  SANLDFLAGS :=
  DBGFLAGS := -DNDEBUG
endif

# The libraries, by pkg-config (HDF5's is hdf5-serial on Debian, hdf5 elsewhere), or each
# from a directory with include/ and lib/ (HDF5_DIR, GSL_DIR, INIH_DIR, SQLITE_DIR: the
# environment modules of a cluster). scripts/libcheck.sh says what is missing; nothing
# here installs anything (make deps does, on Debian: docs/install.md).
HDF5_DIR   ?=
GSL_DIR    ?=
INIH_DIR   ?=
SQLITE_DIR ?=
HDF5_PC   := $(if $(HDF5_DIR),,$(shell pkg-config --exists hdf5-serial 2>/dev/null && echo hdf5-serial || echo hdf5))
PKGS       = $(HDF5_PC) $(if $(GSL_DIR),,gsl) $(if $(INIH_DIR),,inih) $(if $(SQLITE_DIR),,sqlite3)
comma     := ,
lib_from   = $(if $(1),-L$(1)/lib -Wl$(comma)-rpath$(comma)$(1)/lib $(2))
DIR_CFLAGS = $(foreach d,$(HDF5_DIR) $(GSL_DIR) $(INIH_DIR) $(SQLITE_DIR),-I$(d)/include)
DIR_LIBS   = $(call lib_from,$(HDF5_DIR),-lhdf5) $(call lib_from,$(GSL_DIR),-lgsl -lgslcblas) \
             $(call lib_from,$(INIH_DIR),-linih) $(call lib_from,$(SQLITE_DIR),-lsqlite3)
PKG_CFLAGS = $(if $(strip $(PKGS)),$(shell pkg-config --cflags $(PKGS) 2>/dev/null)) $(DIR_CFLAGS)
# HDF5 from its static library where the package ships one beside the shared one (Debian's
# libhdf5-dev does): the shared library loads about 35 others for reading over the network
# (libcurl, TLS, Kerberos) that nothing here uses, and loading them took 28 of the 36 ms a
# bin/shake --version took on the development VM; a campaign and the suite start thousands
# of processes (docs/install.md). Only Debian's package (hdf5-serial) is known to need no
# more than libsz and libz then; HDF5_STATIC=0 links the shared one, and another package,
# a module or HDF5_DIR always does.
HDF5_STATIC ?= 1
HDF5_A    := $(if $(and $(filter 1,$(HDF5_STATIC)),$(filter hdf5-serial,$(HDF5_PC))),$(firstword $(wildcard $(patsubst -L%,%/libhdf5.a,$(filter -L%,$(shell pkg-config --libs-only-L $(HDF5_PC) 2>/dev/null))))))
PKG_LIBS_PC := $(if $(strip $(PKGS)),$(shell pkg-config --libs $(PKGS) 2>/dev/null))
PKG_LIBS   = $(patsubst -lhdf5,$(if $(HDF5_A),$(HDF5_A) -lsz -lz -ldl,-lhdf5),$(PKG_LIBS_PC)) $(DIR_LIBS) -lm
PKG_LIBS_SHARED = $(PKG_LIBS_PC) $(DIR_LIBS) -lm
ALLCFLAGS  = $(BASEFLAGS) $(CFLAGS) $(MARCH) $(XFLAGS) $(DBGFLAGS) $(PKG_CFLAGS) $(CORE_INC)
LDFLAGS   += $(XFLAGS) $(SANLDFLAGS)

ifeq ($(V),1)
  Q :=
else
  Q := @
endif

# core/ in rooms, lowest first (core/README.md): every source includes core's headers by
# name, so each room's folder is on the include path; tests/integration/floors.sh holds
# the rooms to including only their own and lower rooms' headers.
CORE_ROOMS = base text scene model force io run
CORE_INC  = $(CORE_ROOMS:%=-Icore/%)
CORE_SRC  = $(filter-out core/run/shake_main.c core/force/kvec.c,$(wildcard $(CORE_ROOMS:%=core/%/*.c)))
CORE_OBJ  = $(CORE_SRC:%.c=$(BUILD)/%.o) $(KV_ISAS:%=$(BUILD)/core/force/kvec_%.o)
LIB       = $(BUILD)/libshake.a
TEST_SRC  = $(wildcard tests/unit/*.c tests/physics/*.c)
TEST_BIN  = $(TEST_SRC:%.c=$(BUILD)/%)
SHAKE     = $(BIN)/shake

.PHONY: all deps deps-test install check quick bench bench-accuracy stress demo help clean tests faults fuzz mutate reproduce docs
all: $(SHAKE)

help:
	@echo "make            build bin/shake"
	@echo "make deps       install the Debian packages make and make demo need (apt-get; make itself never installs)"
	@echo "make deps-test  install what only the suite and the benchmarks add (LAMMPS, Slurm, sshd, Python packages)"
	@echo "make install    the programs, man pages, bash completion and python/shakebox into PREFIX (/usr/local; PREFIX=\$$HOME/.local without root)"
	@echo "make check      the whole test suite (unit, physics, integration; ASan/UBSan build), NPROC tests"
	@echo "                at a time; T=REGEX only the tests whose name matches (make check T=study_run)"
	@echo "make quick      the tier for daily work, under 2 minutes: make check without the scripts marked"
	@echo "                slow (docs/testing.md, \"Tiers\"; T= works here too)"
	@echo "make bench      speed: shakebox vs LAMMPS gran/hooke on the paper scene, ns/particle-step"
	@echo "make bench-accuracy  run time against error for every integrator (work-precision plot)"
	@echo "make bench-study  what a study costs: the claims' questions by fixed grids and by stop rules, adaptive"
	@echo "                search and auto replicates, CPU seconds and answers side by side (STUDY_QUICK=1, JOBS=2)"
	@echo "make stress     numerical-stability stress tests (largest stable dt, long rest, violent driving)"
	@echo "make validate-lammps  shakebox against LAMMPS gran/hooke on the same settled beds: A Phi(D) at 3.0 Hz,"
	@echo "                B the onset of convection, C claim 5 (depth 0 vs 1 at 2.7 Hz), D claim 4 (R = 4 at 3.2 Hz)"
	@echo "                (docs/validate_lammps.md; ~43 min on 2 idle cores; VALIDATE_QUICK=1, VALIDATE_PARTS='A B C D', JOBS=2)"
	@echo "make validate-collisions  the contact laws (hooke, restitution, hertz, spring, hertz_spring) against LAMMPS on two-disk collisions:"
	@echo "                e, contact time, rebound spin (docs/validate_lammps.md \"Two-disk collisions\"; seconds)"
	@echo "make demo       install what is missing, build, run a small campaign end to end"
	@echo "make reproduce  the paper's claims: campaigns/reproduce/ run (resumable), REPRODUCTION.md written from the"
	@echo "                database (REPRODUCE_QUICK=1: a few-minute pipeline check under build/reproduce-quick)"
	@echo "make faults     fault injection: I/O faults at random moments, damaged outputs, deleted run dirs, litter (FAULT_ROUNDS=8)"
	@echo "make figures    regenerate analysis/figures/ (PNG and PDF, and the tools' tables) from campaigns/figures/ (FIG_JOBS=2)"
	@echo "make mutate     plant the bugs of tests/mutate/mutations.tsv one at a time, run the tests named for each: caught or survived"
	@echo "make fuzz       mutation fuzzing of scene, campaign and particle files, and of run files (HDF5) read"
	@echo "                by every analysis tool and study run, against the sanitizer build"
	@echo "                (FUZZ_SECONDS=600, FUZZ_SEED=1; findings with repro.sh in build/fuzz/findings)"
	@echo "make cross-aarch64  the engine and every test program built for aarch64, run under qemu (deps-cross; -regression; docs/cross.md)"
	@echo "make docs       rewrite the docs' generated lists (scene keys, result columns) from the code"
	@echo "make print-tools  the programs the build makes (print-campaign-tools: the tools that read a campaign's runs)"
	@echo "make clean      remove build products (never runs/)"
	@echo "knobs: CC, CFLAGS, MARCH (e.g. -march=native: this CPU only), V=1 (show commands),"
	@echo "       SAN=1 (sanitizer build in build/san; SAN_G=-g for a debugger), NPROC (compilers and tests at once, default: the CPUs),"
	@echo "       T=REGEX (check, quick); SHAKEBOX_KERNEL=NAME forces a kernel path at run time"

# Install what is missing on Debian (apt-get; a no-op when everything is there): deps
# what make and make demo need, deps-test what only the suite and the benchmarks add.
# Only the targets that run the suite, the demo or the benchmarks call them; a build
# never does (it checks, $(BUILD)/.libs-ok).
deps:
	$(Q)bash scripts/deps.sh build
deps-test:
	$(Q)bash scripts/deps.sh test

build/.deps-ok: scripts/deps.sh
	$(Q)bash scripts/deps.sh all
	$(Q)mkdir -p build && touch $@
build/.deps-build-ok: scripts/deps.sh
	$(Q)bash scripts/deps.sh build
	$(Q)mkdir -p build && touch $@

# Are the libraries there? Looks, never installs; stops naming what is missing.
$(BUILD)/.libs-ok: scripts/libcheck.sh $(BUILD)/flags
	$(Q)HDF5_DIR='$(HDF5_DIR)' GSL_DIR='$(GSL_DIR)' INIH_DIR='$(INIH_DIR)' SQLITE_DIR='$(SQLITE_DIR)' bash scripts/libcheck.sh
	@touch $@

# Objects depend on the flags they were built with: a changed CFLAGS rebuilds.
$(BUILD)/flags: FORCE
	@mkdir -p $(dir $@)
	@echo '$(CC) $(ALLCFLAGS)' > $@.new; if cmp -s $@.new $@; then rm $@.new; else mv $@.new $@; fi

$(BUILD)/%.o: %.c $(BUILD)/flags | $(BUILD)/.libs-ok
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  CC    $<")
	$(Q)$(CC) $(ALLCFLAGS) -c $< -o $@

# the vector kernel, once per instruction set (kvec.h)
$(KV_ISAS:%=$(BUILD)/core/force/kvec_%.o): $(BUILD)/core/force/kvec_%.o: core/force/kvec.c $(BUILD)/flags | $(BUILD)/.libs-ok
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  CC    $< ($*)")
	$(Q)$(CC) $(ALLCFLAGS) $(KV_FLAGS_$*) -DSB_KV_NAME=$* -c $< -o $@

# provenance.c gets the git hash and the compiler flags; version.h changes only when
# they do, so an unchanged tree does not rebuild.
$(BUILD)/core/base/provenance.o: $(BUILD)/version.h
$(BUILD)/version.h: FORCE | $(BUILD)/.libs-ok
	@mkdir -p $(dir $@)
	$(Q)bash scripts/version.sh "$(CC)" "$(BASEFLAGS) $(CFLAGS) $(MARCH) $(XFLAGS) $(DBGFLAGS)" "$(strip $(MARCH))" > $@.new
	$(Q)if cmp -s $@.new $@; then rm $@.new; else mv $@.new $@; fi
$(BUILD)/core/base/provenance.o: ALLCFLAGS += -I$(BUILD)
FORCE:

# The sanitizer build compiles the engine's hot loops (the force kernel, the
# integrator, the step) at -O2, still instrumented: an engine run of the suite costs
# about a quarter less, and ASan and UBSan check every access as before. Only the
# kernel paths a CPU chooses by itself: w8 (tests only) and sse2 (pre-AVX2 CPUs) stay
# at -O1, where the sanitizer build compiles them in half the time (w8: 23 s at -O2).
KV_HOT := $(filter-out w8 sse2,$(KV_ISAS))
ifeq ($(SAN),1)
$(BUILD)/core/model/integrate.o $(BUILD)/core/run/step.o $(KV_HOT:%=$(BUILD)/core/force/kvec_%.o): ALLCFLAGS += -O2
endif

$(LIB): $(CORE_OBJ)
	@$(if $(filter 0,$(V)),echo "  AR    $@")
	$(Q)rm -f $@ && ar rcs $@ $^

$(SHAKE): $(BUILD)/core/run/shake_main.o $(LIB)
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  LD    $@")
	$(Q)$(CC) $(LDFLAGS) -o $@ $^ $(PKG_LIBS)

$(BUILD)/tests/%: tests/%.c $(LIB) tests/testlib.h $(BUILD)/flags
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  CC    $<")
	$(Q)$(CC) $(ALLCFLAGS) -Itests $(LDFLAGS) -o $@ $< $(LIB) $(PKG_LIBS)

# The fault shim (tests/faults/iofail.c) is preloaded into the tools, so it is built
# plain, without the sanitizers, whichever build the tests use.
FAULT_SHIM = build/faults/iofail.so
$(FAULT_SHIM): tests/faults/iofail.c
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  CC    $<")
	$(Q)$(CC) -std=c11 -Wall -Wextra -Werror -O1 -shared -fPIC -o $@ $< -ldl

# The shim also hooks HDF5's own functions (H5Dclose, H5Lvisit), which it can only where
# HDF5 is a shared library: the fault tests that need it run these links of the same
# objects with the shared HDF5, $(BIN)/h5shared/ (tests/integration/lib.sh, h5shared).
H5SHARED = $(BIN)/h5shared
$(H5SHARED)/shake: $(BUILD)/core/run/shake_main.o $(LIB)
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  LD    $@")
	$(Q)$(CC) $(LDFLAGS) -o $@ $^ $(PKG_LIBS_SHARED)

# the engine's side of the two-disk LAMMPS comparison (tests/integration/lammps_collisions.sh)
tests: $(SHAKE) $(TEST_BIN) $(FAULT_SHIM) $(H5SHARED)/shake $(BUILD)/tests/bench/lammps_collision

# The suite runs the sanitizer build (ASan/UBSan) of every unit and physics test and
# the integration scripts; the release programs (make all) run the regression test on
# every kernel path this CPU has, and the campaigns whose engine is not what a script
# tests. The release build of the test programs is not needed: the suite runs none of
# them. It ends with "N passed, N failed". The two builds one after the other: they
# share build/fuzz and build/faults.
check: build/.deps-ok
	$(Q)$(MAKE) --no-print-directory $(BUILD_JOBS) all
	$(Q)$(MAKE) --no-print-directory $(BUILD_JOBS) SAN=1 tests
	$(Q)T='$(T)' TEST_JOBS=$(NPROC) bash tests/run.sh

# make check without the scripts whose header says "# tier: slow" (tests/run.sh)
quick: build/.deps-ok
	$(Q)$(MAKE) --no-print-directory $(BUILD_JOBS) all
	$(Q)$(MAKE) --no-print-directory $(BUILD_JOBS) SAN=1 tests
	$(Q)T='$(T)' TEST_JOBS=$(NPROC) bash tests/run.sh --quick

# -jNPROC, unless make was given -j itself (then its job server is shared)
BUILD_JOBS = $(if $(findstring jobserver,$(MAKEFLAGS)),,-j$(NPROC))

# Fault injection (I/O faults at random moments, damaged outputs, deleted run
# directories and packing caches, litter, a second driver) against the sanitizer
# build; FAULT_ROUNDS rounds (make check runs one).
FAULT_ROUNDS ?= 8
# not in make check: a sanitizer build in a scratch copy, then one rebuild and test run per bug
mutate: build/.deps-ok
	$(Q)bash tests/mutate/mutate.sh $(ID)

faults: build/.deps-ok
	$(Q)$(MAKE) --no-print-directory SAN=1 tests
	$(Q)FAULT_ROUNDS=$(FAULT_ROUNDS) SHAKE=$(CURDIR)/build/san/bin/shake bash tests/integration/faults.sh

# the dispatched binary is also timed against a build for this CPU only (build/native)
bench: build/.deps-ok all
	$(Q)$(MAKE) --no-print-directory MARCH=-march=native BUILD=build/native BIN=build/native/bin build/native/bin/shake
	$(Q)NATIVE=build/native/bin/shake bash tests/bench/bench.sh

demo: build/.deps-build-ok all
	$(Q)bash scripts/demo.sh

# The paper claim by claim: campaigns/reproduce/, then REPRODUCTION.md and
# docs/reproduction/ from the database (resumes; nothing to simulate when nothing changed).
REPRODUCE_QUICK ?= 0
reproduce: build/.deps-ok all
	$(Q)JOBS=$(JOBS) REPRODUCE_QUICK=$(REPRODUCE_QUICK) bash scripts/reproduce.sh

# The release programs, their man pages, bash completion and the Python package into $(DESTDIR)$(PREFIX)
# (PREFIX=$$HOME/.local without root); nothing else is written (scripts/install.sh).
PREFIX  ?= /usr/local
DESTDIR ?=
install: all
	$(Q)bash scripts/install.sh $(BIN) "$(DESTDIR)$(PREFIX)" "$(PREFIX)"

clean:
	rm -rf build bin

# The lists the code knows, in the docs (scripts/docs_lists.sh: the scene keys of
# docs/scene.md, the result columns of docs/database.md and the options of
# docs/campaigns.md are written from bin/shake and bin/study;
# tests/integration/docs_lists.sh checks them and the lists it cannot generate).
docs: all
	$(Q)bash scripts/docs_lists.sh write

# make print-VAR: a variable's value, for scripts. make print-tools: every program the
# build makes (bin/shake, bin/study, the analysis tools of analysis/analysis.mk's
# AN_MAIN); make print-campaign-tools: the analysis tools that read a campaign's runs
# (AN_CAMPAIGN). The scripts and tests that go over the tools read these, and
# scripts/docs_lists.sh checks the docs and the one list in C (tests/fuzz/fuzz.c)
# against them, and fails on a line anywhere else that names the tools by hand.
.PHONY: print-tools print-campaign-tools
print-tools:
	@echo shake study $(AN_MAIN)
print-campaign-tools:
	@echo $(AN_CAMPAIGN)
print-%:
	@echo '$($*)'

# The floor both upper rooms share, the campaign driver and the analysis tools bring
# their own rules.
-include lib/lib.mk
-include study/study.mk
-include analysis/analysis.mk
-include tests/bench/bench.mk
-include tests/bench/validate.mk
-include tests/fuzz/fuzz.mk
-include tests/cross/cross.mk

# the header dependencies of every build: those under build/ and those of a BUILD elsewhere
# (BUILD=/tmp/o0: without its own .d files a changed header would leave its objects stale)
-include $(sort $(shell find build $(BUILD) -name '*.d' 2>/dev/null))
