# validate.mk - `make validate-lammps` (issue #16, point 4): Phi(D) at 3.0 Hz without
# intruder from the same settled beds shaken by the engine and by LAMMPS gran/hooke,
# both counted by the engine's crossing code, compared over the beds
# (tests/bench/validate_lammps.sh). Writes docs/validate_lammps.md and its figure
# (docs/validate_lammps.png, .pdf); the script runs its jobs under nice -n 5 itself.
# Not part of `make check`: even the quick version took about a minute on the shared
# 2-core machine; tests/analysis/dumpflux.c checks the dump -> Phi path there (an
# engine run's snapshots through it give exactly the engine's flux).
# Knobs: VALIDATE_QUICK=1 (2 beds of 6 s into build/validate-quick/: the pipeline
# only), VALIDATE_BEDS (10), VALIDATE_DURATION (80 s), JOBS (2).
VALIDATE_QUICK ?= 0
JOBS           ?= 2

.PHONY: validate-lammps
validate-lammps: build/.deps-ok all
	$(Q)VALIDATE_QUICK=$(VALIDATE_QUICK) JOBS=$(JOBS) bash tests/bench/validate_lammps.sh
