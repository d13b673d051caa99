# bench.mk - the evidence for speed and accuracy: run time against error (`make bench-accuracy`) and the
# numerical-stability stress tests (`make stress`). Included by the top-level Makefile;
# neither target is part of `make check` (tests/integration/stress_quick.sh is).
# Knobs: ACC_QUICK=1 (a few-minute accuracy run), STRESS_QUICK=1 (a short stress run),
# JOBS (parallel runs, default 2).
ACC_COLL    = $(BUILD)/tests/bench/accuracy_collision
STRESS_OVL  = $(BUILD)/tests/stress/maxoverlap
ACC_QUICK    ?= 0
STRESS_QUICK ?= 0
JOBS         ?= 2

bench-accuracy: build/.deps-ok all $(ACC_COLL)
	$(Q)ACC_QUICK=$(ACC_QUICK) JOBS=$(JOBS) ACC_COLL=$(abspath $(ACC_COLL)) bash tests/bench/accuracy.sh

stress: build/.deps-ok all $(STRESS_OVL)
	$(Q)STRESS_QUICK=$(STRESS_QUICK) JOBS=$(JOBS) STRESS_OVL=$(abspath $(STRESS_OVL)) bash tests/stress/stress.sh
