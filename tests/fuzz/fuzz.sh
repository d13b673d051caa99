#!/usr/bin/env bash
# fuzz.sh - `make fuzz`: the seed corpus (scenes/, campaigns/, small particle files the
# engine writes, text and LAMMPS, and the run files of tests/fuzz/runs.campaign) and the
# keys (shake --params), then the mutation fuzzer against the sanitizer builds. Knobs
# (environment):
#   FUZZ_SECONDS  time limit (default 600; 0 = none, then FUZZ_INPUTS is needed)
#   FUZZ_INPUTS   number of inputs (default 0 = no limit)
#   FUZZ_SEED     PRNG seed (default 1): input k is the same for the same seed and corpus
#   FUZZ_TIMEOUT  seconds after which a run is a hang (default 10)
#   FUZZ_RSS_MB   memory (MB) past which ASan stops a run and reports it (default 1024)
#   FUZZ_TARGETS  comma-separated subset of scene,campaign,particles,runfile and of the
#                 families resealed,links,database,paths (tests/fuzz/families.sh says
#                 what each is and what counts as silent; default all)
#   FUZZ_FAMILY_INPUTS  inputs per family (default 0: half of FUZZ_SECONDS for the
#                 families, half for the text and run-file targets)
#   FUZZ_FAMILY_ONLY  FAMILY:K: only input K of that family, its files kept (a finding's
#                 reproduction)
#   FUZZ_OUT      findings directory, emptied first (default build/fuzz/findings)
#   FUZZ_WORK     scratch directory (default build/fuzz/work)
#   FUZZ_SHAKE, FUZZ_STUDY, FUZZ_BIN, FUZZ_H5MUT  the binaries (default
#                 build/san/bin/{shake,study}, build/fuzz/{fuzz,h5mut}); the analysis
#                 tools are the ones beside FUZZ_SHAKE
# Exits 1 when there are findings (each under FUZZ_OUT with repro.sh), 2 on a setup error.
set -u
cd "$(dirname "$0")/../.." || exit 2
SECONDS_LIMIT="${FUZZ_SECONDS:-600}"
INPUTS="${FUZZ_INPUTS:-0}"
SEED="${FUZZ_SEED:-1}"
FUZZ_TARGETS="${FUZZ_TARGETS:-}"
# the families (families.sh) apart from fuzz.c's targets
FAMILIES="" TEXT_TARGETS=""
for t in ${FUZZ_TARGETS//,/ }; do
	case $t in resealed | links | database | paths) FAMILIES+="${FAMILIES:+,}$t" ;; *) TEXT_TARGETS+="${TEXT_TARGETS:+,}$t" ;; esac
done
[ -z "$FUZZ_TARGETS" ] && FAMILIES=resealed,links,database,paths
[ -n "${FUZZ_FAMILY_ONLY:-}" ] && FAMILIES=${FUZZ_FAMILY_ONLY%%:*} TEXT_TARGETS=none
[ -n "$FUZZ_TARGETS" ] && [ -z "$TEXT_TARGETS" ] && TEXT_TARGETS=none
FUZZ_TARGETS=$TEXT_TARGETS
TIMEOUT="${FUZZ_TIMEOUT:-10}"
OUT="${FUZZ_OUT:-build/fuzz/findings}"
WORK="${FUZZ_WORK:-build/fuzz/work}"
SHAKE="${FUZZ_SHAKE:-build/san/bin/shake}"
STUDY="${FUZZ_STUDY:-build/san/bin/study}"
FUZZ="${FUZZ_BIN:-build/fuzz/fuzz}"
H5MUT="${FUZZ_H5MUT:-build/fuzz/h5mut}"
for b in "$SHAKE" "$STUDY" "$FUZZ"; do
	[ -x "$b" ] || { echo "fuzz: $b is not an executable (make fuzz builds it)" >&2; exit 2; }
done
SHAKE=$(realpath "$SHAKE")
# a run past FUZZ_RSS_MB of memory is stopped by ASan and reported: the machine is shared
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}:hard_rss_limit_mb=${FUZZ_RSS_MB:-1024}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
# HDF5's own leak on a corrupt object header (the file says why)
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$(realpath tests/fuzz/lsan-hdf5.supp)}"

rm -rf "$OUT" "$WORK"
mkdir -p "$OUT" "$WORK/corpus" || exit 2
C="$WORK/corpus"
"$SHAKE" --params >"$C/keys.tsv" || { echo "fuzz: $SHAKE --params failed" >&2; exit 2; }

# Particle seeds: a small bed with a 2x intruder (the integration tests' FAST scene) and
# one without an intruder, as the engine writes them; the runs of the particle target
# use the same box width.
PW=20
gen() { # NAME args...
	local name=$1
	shift
	(cd "$C" && "$SHAKE" "$@" width=$PW settle_ke=1 settle_min=0.2 duration=0 progress=no \
		write_particles="$name.txt" write_lammps="$name.data" output="$name.h5" >"$name.log" 2>&1) ||
		{ echo "fuzz: could not write the particle seed $name: $(head -c 300 "$C/$name.log")" >&2; exit 2; }
	rm -f "$C/$name.h5" "$C/$name.xmf"
}
# (only when particle files are fuzzed: a few seconds of the sanitizer build)
PARTICLES=0
case ",${FUZZ_TARGETS:-particles}," in *,particles,*) PARTICLES=1 ;; esac
if [ "$PARTICLES" = 1 ]; then
	gen bed n_grains=60 radius_ratio=2 depth=1
	gen bed0 n_grains=30 radius_ratio=0
	# a few lines of each are enough: mutations act on the structure, and a short file
	# keeps each run short
	head -n 24 "$C/bed.txt" >"$C/bed_short.txt"
fi

# Scene seeds beside scenes/paper.scene (whose 950 grains the budget cuts to 150, too
# few to settle in the budget's 0.3 s): small beds that settle at once, so that
# mutations reach the shaking, the ramps and the observables too.
cat >"$C/small.scene" <<EOF
# the integration tests' FAST scene, shaken fast enough (Gamma = 1) for a few
# periods in the fuzzer's time budget
n_grains = 60
width = 20
radius_ratio = 2
depth = 1
settle_ke = 1
settle_min = 0.1
duration = 0.05
snapshots = yes
traj_rate = 200
frequency = 50
amplitude = 0.01
EOF
cat >"$C/observe.scene" <<EOF
[scene]
n_grains = 40
width = 16
radius_ratio = 1.5
depth = 0
settle_ke = 1
settle_min = 0.1
preset = fast
ramp = linear
ramp_from = 30
ramp_to = 50
amplitude = 0.02
duration = 0.05
flux = yes
flux_lines = 10
field = yes
field_periods = 1
ring = yes
ring_every = 2
checkpoint_every = 0.01
EOF

args=(--shake "$SHAKE" --study "$STUDY" --seed "$SEED" --timeout "$TIMEOUT" --out "$OUT" --work "$WORK"
	--keys "$C/keys.tsv" --particle-arg "width=$PW" --particle-arg settle=no)

# Run-file seeds: tests/fuzz/runs.campaign run by the study driver (a few seconds), its
# runs directory kept twice: all done (what the analysis tools read) and all pending
# (what `study run` ingests, every file once, with nothing left to run).
case ",${FUZZ_TARGETS:-runfile},${FAMILIES:+runfile}," in
*,runfile,*)
	an=$(make -s --no-print-directory print-campaign-tools) && [ -n "$an" ] ||
		{ echo "fuzz: make print-campaign-tools gave no list of the tools" >&2; exit 2; }
	for b in "$H5MUT" $an; do
		[ "$b" = "$H5MUT" ] || b=$(dirname "$SHAKE")/$b
		[ -x "$b" ] || { echo "fuzz: $b is not an executable (make fuzz builds it)" >&2; exit 2; }
	done
	mkdir -p "$C/runfile" && cp tests/fuzz/runs.campaign "$C/runfile/fz.campaign" || exit 2
	"$STUDY" run "$C/runfile/fz.campaign" --runs "$C/runfile/done" --jobs 2 --no-progress >"$C/runfile/study.log" 2>&1 ||
		{ echo "fuzz: could not run the run-file seeds: $(tail -c 300 "$C/runfile/study.log")" >&2; exit 2; }
	# no seal recorded: a mutated file sealed again (half of them) then reaches the
	# checks behind the seal, not only the database's record of it (which
	# tests/integration/hostile_runs.sh tests)
	# ... and a copy with the seals recorded, for the families
	cp -r "$C/runfile/done" "$C/runfile/sealed" || exit 2
	# (the rows' own seal written again, as the driver would have: lib/rowseal.h)
	sqlite3 "$C/runfile/done/study.db" "UPDATE result SET file_seal = NULL" &&
		/usr/bin/python3 tests/integration/rowseal.py write "$C/runfile/done/study.db" || exit 2
	cp -r "$C/runfile/done" "$C/runfile/pending" &&
		sqlite3 "$C/runfile/pending/study.db" "UPDATE run SET state = 'pending'; DELETE FROM result;" || exit 2
	args+=(--runs-done "$C/runfile/done" --runs-pending "$C/runfile/pending" --runs-name fz
		--runs-campaign "$C/runfile/fz.campaign" --h5mut "$H5MUT")
	for f in "$C"/runfile/done/fz/*.h5; do args+=(--runfile "$f"); done
	;;
esac
for t in ${FUZZ_TARGETS//,/ }; do args+=(--target "$t"); done
# the time shared: half for fuzz.c's targets, half for the families
FAM_INPUTS="${FUZZ_FAMILY_INPUTS:-0}" FAM_SECONDS=0 TEXT_SECONDS=$SECONDS_LIMIT
if [ -n "$FAMILIES" ] && [ "$TEXT_TARGETS" != none ] && [ "$SECONDS_LIMIT" != 0 ] && [ "$FAM_INPUTS" = 0 ]; then
	TEXT_SECONDS=$((SECONDS_LIMIT / 2)) FAM_SECONDS=$((SECONDS_LIMIT - SECONDS_LIMIT / 2))
elif [ -n "$FAMILIES" ] && [ "$FAM_INPUTS" = 0 ]; then
	FAM_SECONDS=$SECONDS_LIMIT
fi
[ "$TEXT_SECONDS" != 0 ] && args+=(--seconds "$TEXT_SECONDS")
[ "$INPUTS" != 0 ] && args+=(--inputs "$INPUTS")
for f in scenes/*.scene "$C/small.scene" "$C/observe.scene"; do args+=(--scene "$f"); done
for f in campaigns/*.campaign; do args+=(--campaign "$f"); done
if [ "$PARTICLES" = 1 ]; then
	for f in "$C"/bed.txt "$C"/bed.data "$C"/bed0.txt "$C"/bed0.data "$C"/bed_short.txt; do args+=(--particles "$f"); done
fi
rc=0
if [ "$TEXT_TARGETS" != none ]; then
	"$FUZZ" "${args[@]}" | tee "$WORK/fuzz.log"
	rc=${PIPESTATUS[0]}
	[ "$rc" -gt 1 ] && exit "$rc"
fi
if [ -n "$FAMILIES" ]; then
	FUZZ_FAMILIES=$FAMILIES FUZZ_FAMILY_INPUTS=$FAM_INPUTS FUZZ_FAMILY_SECONDS=$FAM_SECONDS FUZZ_SEED=$SEED \
		FUZZ_TIMEOUT=$TIMEOUT FUZZ_OUT=$OUT FUZZ_WORK=$WORK FUZZ_SHAKE=$SHAKE FUZZ_STUDY=$STUDY FUZZ_H5MUT=$H5MUT \
		bash tests/fuzz/families.sh "$C/runfile/sealed" "$C/runfile/fz.campaign" | tee "$WORK/families.log"
	frc=${PIPESTATUS[0]}
	[ "$frc" -gt 1 ] && exit "$frc"
	[ "$frc" = 1 ] && rc=1
fi
# one table: fuzz.c's targets (a sanitizer report or an undocumented exit code counted
# as a crash, an input that must be refused and was not as silent) and the families
if [ "$TEXT_TARGETS" != none ] && [ -s "$OUT/summary.tsv" ]; then
	line=$(grep -m1 '^fuzz: [0-9]* inputs in' "$WORK/fuzz.log")
	{
		for t in scene campaign particles runfile; do
			n=$(sed -n "s/.*[(, ]$t \\([0-9]*\\).*/\\1/p" <<<"$line")
			[ "${n:-0}" = 0 ] && continue
			awk -F'\t' -v t="$t" -v n="$n" 'NR > 1 && $2 == t { if ($1 == "hang") h += $3; else if ($1 == "accepted") s += $3; else c += $3 }
				END { printf "%s %d %d %d %d\n", t, n, c, h, s }' "$OUT/summary.tsv"
		done
		[ -n "$FAMILIES" ] && sed -n 's/^fuzz: \(resealed\|links\|database\|paths\) /\1 /p' "$WORK/families.log"
	} | awk 'BEGIN { printf "fuzz: %-9s %7s %8s %6s %7s\n", "family", "inputs", "crashes", "hangs", "silent" }
		{ printf "fuzz: %-9s %7d %8d %6d %7d\n", $1, $2, $3, $4, $5; n += $2; c += $3; h += $4; s += $5 }
		END { printf "fuzz: %-9s %7d %8d %6d %7d\n", "total", n, c, h, s }'
fi
exit "$rc"
