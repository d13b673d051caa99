# fuzz.mk - `make fuzz`: time-bounded mutation fuzzing of scene, campaign and particle
# files against the sanitizer builds of bin/shake and `study expand`, and of run files
# (HDF5, changed by tests/fuzz/h5mut.c) against every analysis tool and `study run`
# (tests/fuzz/fuzz.sh drives tests/fuzz/fuzz.c), and the families of hostile inputs of
# tests/fuzz/families.sh (run files edited and sealed again, links and virtual datasets,
# database corruptions, planted nodes). Included by the top-level Makefile;
# not part of `make check`, which runs tests/integration/fuzz_quick.sh and
# fuzz_runfile_quick.sh and fuzz_families_quick.sh (a fixed seed, a fixed number of
# inputs). Findings go to
# FUZZ_OUT, one directory each with repro.sh.
# Knobs: FUZZ_SECONDS (default 600), FUZZ_SEED (1), FUZZ_INPUTS (0 = no limit),
# FUZZ_TIMEOUT (seconds after which a run is a hang, 10), FUZZ_OUT (build/fuzz/findings).
FUZZ_BIN      = build/fuzz/fuzz
FUZZ_SECONDS ?= 600
FUZZ_SEED    ?= 1
FUZZ_INPUTS  ?= 0
FUZZ_TIMEOUT ?= 10
FUZZ_OUT     ?= build/fuzz/findings
# the families of tests/fuzz/families.sh: inputs per family (0: half of FUZZ_SECONDS),
# and a subset of the targets and families (default all)
FUZZ_FAMILY_INPUTS ?= 0
FUZZ_TARGETS ?=

.PHONY: fuzz

# The fuzzer is a tool, not what is tested: one plain build for every flavour.
$(FUZZ_BIN): tests/fuzz/fuzz.c | $(BUILD)/.libs-ok
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  CC    $<")
	$(Q)$(CC) $(BASEFLAGS) -O2 -g -o $@ $< -lm

# h5mut changes run files on purpose (the runfile target, hostile_runs.sh); it links HDF5
H5MUT_BIN = build/fuzz/h5mut
# and seals them again with the engine's digest (core/io/h5id.c, reading with core/io/h5read.c)
$(H5MUT_BIN): tests/fuzz/h5mut.c core/io/h5id.c core/io/h5id.h core/io/h5seal.c core/io/h5seal.h core/io/h5read.c core/io/h5md.c core/base/fsutil.c core/base/err.c | $(BUILD)/.libs-ok
	@mkdir -p $(dir $@)
	@$(if $(filter 0,$(V)),echo "  CC    $<")
	$(Q)$(CC) $(BASEFLAGS) -O1 -g $(CORE_INC) $(PKG_CFLAGS) -o $@ $(filter %.c,$^) $(PKG_LIBS)

tests: $(FUZZ_BIN) $(H5MUT_BIN)

fuzz: build/.deps-ok $(FUZZ_BIN) $(H5MUT_BIN)
	$(Q)$(MAKE) --no-print-directory SAN=1 build/san/bin/shake build/san/bin/study \
		$(AN_MAIN:%=build/san/bin/%)
	$(Q)FUZZ_SECONDS=$(FUZZ_SECONDS) FUZZ_SEED=$(FUZZ_SEED) FUZZ_INPUTS=$(FUZZ_INPUTS) \
		FUZZ_TIMEOUT=$(FUZZ_TIMEOUT) FUZZ_OUT=$(FUZZ_OUT) FUZZ_FAMILY_INPUTS=$(FUZZ_FAMILY_INPUTS) \
		FUZZ_TARGETS=$(FUZZ_TARGETS) bash tests/fuzz/fuzz.sh
