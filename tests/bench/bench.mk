# bench.mk - the evidence for speed and accuracy: run time against error (`make bench-accuracy`), the
# numerical-stability stress tests (`make stress`) and what a study costs (`make bench-study`).
# Included by the top-level Makefile; none of these targets is part of `make check`
# (tests/integration/stress_quick.sh is).
# Knobs: ACC_QUICK=1 (a few-minute accuracy run), STRESS_QUICK=1 (a short stress run),
# STUDY_QUICK=1 (a few-minute study-cost run), JOBS (parallel runs, default 2).
ACC_COLL    = $(BUILD)/tests/bench/accuracy_collision
STRESS_OVL  = $(BUILD)/tests/stress/maxoverlap
ACC_QUICK    ?= 0
STRESS_QUICK ?= 0
STUDY_QUICK  ?= 0
JOBS         ?= 2

.PHONY: bench-study

bench-accuracy: build/.deps-ok all $(ACC_COLL)
	$(Q)ACC_QUICK=$(ACC_QUICK) JOBS=$(JOBS) ACC_COLL=$(abspath $(ACC_COLL)) bash tests/bench/accuracy.sh

stress: build/.deps-ok all $(STRESS_OVL)
	$(Q)STRESS_QUICK=$(STRESS_QUICK) JOBS=$(JOBS) STRESS_OVL=$(abspath $(STRESS_OVL)) bash tests/stress/stress.sh

# the claims' questions answered with fixed grids and with stop rules, adaptive search and
# auto replicates: CPU seconds of each, the answers side by side (tests/bench/study.sh)
bench-study: build/.deps-ok all
	$(Q)STUDY_QUICK=$(STUDY_QUICK) JOBS=$(JOBS) bash tests/bench/study.sh
