# validate.mk - `make validate-lammps` (issue #16, point 4; "verdicts a referee can
# check", part 6): the engine against LAMMPS gran/hooke on the same settled beds in both
# codes, the engine's own definitions applied to LAMMPS's output
# (tests/bench/validate_lammps.sh):
#   A. Phi(D) at 3.0 Hz without intruder, line by line (10 beds x 80 s);
#   B. the onset of convection: per bed the frequency where Phi through 0.4-0.6 of the
#      surface reaches 2 particles per period, on a grid 2.55-2.85 Hz, paired between
#      the codes (3 beds x 7 frequencies x 48 s);
#   C. claim 5: R = 4 at depth 0 and 1, 2.7 Hz, risen within 120 s by the engine's rule
#      (6 beds per depth; Fisher, McNemar and its power);
#   D. claim 4: R = 4 at the claim-4 campaign's 3.2 Hz, the waiting time per bed, paired
#      (12 beds, up to 30 s).
# B-D run the engine with the LAMMPS deck's integrator and step (verlet, 5e-5 s).
# Writes docs/validate_lammps.md (a summary table, then a section per part, each with
# its **Result:** line, run times, CPU model and date) and its figures
# (docs/validate_lammps.png, docs/validate_lammps_onset.png, and PDFs); the script runs
# its jobs under nice -n 5 itself. About 43 minutes on 2 idle cores, under 50 even if
# no intruder rose (measured rates: docs/benchmarks.md). Not part of
# `make check`: tests/analysis/dumpflux.c checks the dump -> Phi path there (an engine
# run's snapshots through it give exactly the engine's flux), tests/analysis/twocode.c
# the exact statistics.
# Knobs: VALIDATE_QUICK=1 (every part at 2 beds of a few seconds into
# build/validate-quick/: the pipeline only, about a minute on 2 idle cores),
# VALIDATE_PARTS ("A B C D"), JOBS (2), VALIDATE_FRESH=1 (start over; by default an
# interrupted validation resumes: a finished run is not run again); the script's header lists the sizes
# (VALIDATE_BEDS, VALIDATE_ONSET_BEDS, VALIDATE_C_BEDS, VALIDATE_D_BEDS, ...), which
# make passes on from the environment or its command line.
VALIDATE_QUICK ?= 0
VALIDATE_PARTS ?= A B C D
JOBS           ?= 2

.PHONY: validate-lammps
validate-lammps: build/.deps-ok all
	$(Q)VALIDATE_QUICK=$(VALIDATE_QUICK) VALIDATE_PARTS="$(VALIDATE_PARTS)" JOBS=$(JOBS) bash tests/bench/validate_lammps.sh

# `make validate-collisions`: the contact laws (hooke, restitution, hertz, and the shear spring
# with history: spring, hertz_spring) against LAMMPS on single two-disk collisions
# (tests/bench/lammps_collisions.sh: e, contact time, rebound spin; exits 1 on a
# disagreement). Writes docs/validate_lammps_collisions.md, which tests/bench/validate_lammps.sh
# appends to docs/validate_lammps.md. A minute; `make check` runs the same comparison
# (tests/integration/lammps_collisions.sh) without writing the document.
COLL_BIN = $(BUILD)/tests/bench/lammps_collision

.PHONY: validate-collisions
validate-collisions: build/.deps-ok $(COLL_BIN)
	$(Q)COLL_BIN=$(abspath $(COLL_BIN)) COLL_DOC=docs/validate_lammps_collisions.md bash tests/bench/lammps_collisions.sh
