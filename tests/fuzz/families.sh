#!/usr/bin/env bash
# families.sh - the hostile-input families of `make fuzz` (docs/testing.md, "make fuzz"):
# inputs made from the seed campaign of tests/fuzz/runs.campaign (its runs directory with
# the seals the driver recorded), each given to an analysis tool or to `study
# run`/`status`/`export` under `timeout`, and classified. Called by tests/fuzz/fuzz.sh
# (which makes the seed runs directory) and by tests/integration/fuzz_families_quick.sh.
#
# Families (a family is a kind of change; what must be seen is said per family):
#   resealed  one run file changed through HDF5 (a dataset's shape, type or values, an
#             attribute, an object deleted or of the other kind, a hard link; h5mut
#             --random-structure) and sealed again, bytes and digest, as a hostile hand
#             would; the database keeps the seal it recorded, so every reader of that
#             file must see it (the file's seal is not the recorded one)
#   links     one dataset made an external link, a soft link, external storage or a
#             virtual dataset pointing at a FIFO, another run file, the file itself or
#             nothing (h5mut --random-link), sealed again and the new seal recorded in
#             the database, so the readers' containment checks are what must see it
#   database  study.db damaged: a random page (the page size from its header) zeroed or
#             bytes of it changed, a row of run/param/result/campaign edited to an odd
#             value, a table dropped
#   paths     a symlink (to a file or directory outside the runs directory, or to
#             nothing), a FIFO, a character device or a directory planted at a path the
#             command writes or reads: an analysis output, the analysis directory, the
#             database and its -journal/-wal/-shm, a run file, the damaged/ folder (with
#             a run file whose bytes no longer match its seal, so that it is moved there)
# Commands: the analysis tools (--no-plot; --no-store but in `paths`), `study run` (every
# run done: nothing to run unless a file is damaged), `study status`, `study export`.
#
# Classes (every input is exactly one):
#   crash   killed by a signal, or a sanitizer report on stderr
#   hang    no exit within FUZZ_TIMEOUT, and again within three times that
#   silent  the change was not seen although it mattered: exit 0, stderr the same as on
#           the unchanged seed (not a word more), no new line of stdout that accounts for
#           a run left out or names the change, and the output (stdout and the files
#           under runs/fz/analysis) different from the unchanged seed's; in `paths` also a
#           planted node at an output that is not left as it was (written through,
#           replaced, removed) or a symlink's target changed, whatever the exit code
#   ok      refused or noted (a non-zero exit, or a word on stderr), or harmless (the
#           output the same as the unchanged seed's: the change touched nothing read)
# An input k of family F is the same for the same FUZZ_SEED and seed campaign.
#
#   families.sh SEALED CAMPAIGN
#     SEALED    the seed runs directory (all done, seals recorded); CAMPAIGN its file
#   Environment: FUZZ_SEED (1), FUZZ_FAMILY_INPUTS (per family, 0 = until the time),
#   FUZZ_FAMILY_SECONDS (0 = none), FUZZ_TIMEOUT (10), FUZZ_FAMILIES (comma-separated,
#   default resealed,links,database,paths), FUZZ_FAMILY_ONLY (F:K: only input K of F,
#   its work directory kept), FUZZ_OUT, FUZZ_WORK, FUZZ_SHAKE (the tools are beside it),
#   FUZZ_STUDY, FUZZ_H5MUT.
# Prints one line per family (inputs, crashes, hangs, silent) and a total; writes
# FUZZ_OUT/families.tsv and one directory per finding with repro.sh. Exit 1 on findings.
set -u
SEALED=$(realpath "$1") || exit 2
CAMPAIGN=$(realpath "$2") || exit 2
SEED="${FUZZ_SEED:-1}"
N="${FUZZ_FAMILY_INPUTS:-0}"
SECS="${FUZZ_FAMILY_SECONDS:-0}"
T="${FUZZ_TIMEOUT:-10}"
FAMS="${FUZZ_FAMILIES:-resealed,links,database,paths}"
ONLY="${FUZZ_FAMILY_ONLY:-}"
OUT=$(realpath -m "${FUZZ_OUT:-build/fuzz/findings}")
WORK=$(realpath -m "${FUZZ_WORK:-build/fuzz/work}")/families
TOOLS=$(dirname "$(realpath "${FUZZ_SHAKE:-build/san/bin/shake}")")
STUDY=$(realpath "${FUZZ_STUDY:-$TOOLS/study}")
H5MUT=$(realpath "${FUZZ_H5MUT:-build/fuzz/h5mut}")
SELF=$(realpath "$0")
[ "$N" != 0 ] || [ "$SECS" != 0 ] || [ -n "$ONLY" ] || { echo "families: FUZZ_FAMILY_INPUTS or FUZZ_FAMILY_SECONDS is needed" >&2; exit 2; }
NAME=fz
read -ra AN <<<"$(make -s --no-print-directory -C "$(dirname "$SELF")/../.." print-campaign-tools)"
[ "${#AN[@]}" -gt 0 ] || { echo "families: make print-campaign-tools gave no list of the tools" >&2; exit 2; }
mapfile -t IDS < <(cd "$SEALED/$NAME" && ls -- *.h5 | sed 's/\.h5$//')
[ "${#IDS[@]}" -ge 2 ] || { echo "families: $SEALED/$NAME holds fewer than two run files" >&2; exit 2; }
mkdir -p "$WORK" "$OUT" || exit 2

# ---- randomness: a 64-bit LCG per input, from (seed, family, index) ----
R=0
rnd() { # rnd N: a number in [0, N) into RV
	R=$((R * 6364136223846793005 + 1442695040888963407))
	RV=$((((R >> 33) & 0x7fffffff) % $1))
}
pick() { # pick WORD...: one of them into PV
	rnd $#
	local a=("$@")
	PV=${a[$RV]}
}
start() { # start FAMILY-NUMBER INDEX
	R=$((SEED * 1000003 + $1 * 7919 + $2 * 104729 + 12345))
	for _ in 1 2 3 4; do rnd 2; done
}

seal() { head -c 64 "$1" 2>/dev/null | sed -n 's/^fnv1a64w \([0-9a-f]*\)$/\1/p'; }

# cmd_argv KEY: the command of KEY into CMD (run from the work directory; the runs
# directory is R)
cmd_argv() {
	case $1 in
	status) CMD=("$STUDY" status "$CAMPAIGN" --runs R) ;;
	export) CMD=("$STUDY" export "$CAMPAIGN" --runs R) ;;
	run) CMD=("$STUDY" run "$CAMPAIGN" --runs R --jobs 1 --retries 0 --no-progress) ;;
	*+store) CMD=("$TOOLS/${1%+store}" "$NAME" --runs R --no-plot) ;;
	*) CMD=("$TOOLS/$1" "$NAME" --runs R --no-plot --no-store) ;;
	esac
}

# output_hash DIR: stdout and the files under R/fz/analysis
output_hash() {
	{
		# (an export names each run's file by its absolute path: the directory the
		# command ran in is not part of what it said)
		sed "s|$(cd "$1" && pwd)/|@DIR@/|g" "$1/stdout"
		(cd "$1" && find R/$NAME/analysis -type f 2>/dev/null | LC_ALL=C sort | xargs -r md5sum)
	} | md5sum | cut -c1-32
}

# run_cmd DIR TIMEOUT: CMD in DIR; RC its exit (124 on a timeout)
run_cmd() {
	(cd "$1" && exec timeout -k 5 "$2" "${CMD[@]}" >stdout 2>stderr </dev/null)
	RC=$?
}

# the unchanged seed's answer for each command: exit, stderr, output
declare -A BASE_RC BASE_ERR BASE_OUT
baseline() { # baseline KEY
	[ -n "${BASE_RC[$1]:-}" ] && return
	local d="$WORK/base"
	rm -rf "$d" && mkdir -p "$d" && cp -r "$SEALED" "$d/R"
	cmd_argv "$1"
	run_cmd "$d" $((3 * T))
	BASE_RC[$1]=$RC
	BASE_ERR[$1]=$(md5sum <"$d/stderr" | cut -c1-32)
	BASE_OUT[$1]=$(output_hash "$d")
	cp "$d/stdout" "$WORK/base.$1.stdout"
	[ "$RC" = 0 ] || { echo "families: $1 fails on the unchanged seed (exit $RC): $(head -c 300 "$d/stderr")" >&2; exit 2; }
	BASE_FILES=$(cd "$d" && find R/$NAME/analysis -type f 2>/dev/null | LC_ALL=C sort | tr '\n' ' ')
	eval "BASE_FILES_${1//[^a-z]/_}=\$BASE_FILES"
}

# said: a line of stdout that the unchanged seed's has not and that accounts for a run
# left out (the tools' accounting: "1 run file could not be read: counted as
# unreadable") or names what was changed
said() {
	grep -vxF -f "$WORK/base.$KEY.stdout" "$W/stdout" 2>/dev/null |
		grep -qiE "unreadable|unusable|could not|damaged|refus|not used|left out|${SEEN:-@@}"
}

# ---- the families: make input K in directory W (a copy of the seed as W/R), set KEY
# (the command) and NOTE (what was done) ----

fam_resealed() {
	pick "${IDS[@]}"
	local id=$PV
	rnd 10000000
	local hs=$((RV * 7 + 1))
	rnd 10
	if [ "$RV" = 0 ]; then KEY=run; else pick "${AN[@]}"; KEY=$PV; fi
	"$H5MUT" "$SEALED/$NAME/$id.h5" "$W/R/$NAME/$id.h5" --random-structure "$hs" 2>"$W/h5mut.log"
	NOTE="h5mut $id --random-structure $hs: $(tr '\n' ';' <"$W/h5mut.log")"
	SEEN=$id
}

fam_links() {
	pick "${IDS[@]}"
	local id=$PV other
	pick "${IDS[@]}"
	other=$PV
	[ "$other" = "$id" ] && other=${IDS[0]} && [ "$other" = "$id" ] && other=${IDS[1]}
	rnd 10000000
	local hs=$((RV * 7 + 1))
	rnd 10
	if [ "$RV" = 0 ]; then KEY=run; else pick "${AN[@]}"; KEY=$PV; fi
	mkfifo "$W/fifo"
	"$H5MUT" "$SEALED/$NAME/$id.h5" "$W/R/$NAME/$id.h5" --random-link "$hs" "$W/fifo" "$W/R/$NAME/$other.h5" 2>"$W/h5mut.log"
	sqlite3 "$W/R/study.db" "UPDATE result SET file_seal = '$(seal "$W/R/$NAME/$id.h5")' WHERE run = '$id'" &&
		/usr/bin/python3 tests/integration/rowseal.py write "$W/R/study.db"
	NOTE="h5mut $id --random-link $hs FIFO $other, the new seal recorded: $(tr '\n' ';' <"$W/h5mut.log")"
	SEEN=$id
}

fam_database() {
	local db="$W/R/study.db"
	pick status export run "${AN[@]}" # every reader of the database
	KEY=$PV
	local ps np
	ps=$(od -An -tu1 -j16 -N2 "$db" | awk '{ print $1 * 256 + $2 }')
	[ "$ps" = 256 ] && ps=65536 # 1 in the header means 65536
	np=$(($(stat -c %s "$db") / ps))
	rnd 4
	case $RV in
	0)
		rnd "$np"
		NOTE="page $((RV + 1)) of $np (size $ps) zeroed"
		dd if=/dev/zero of="$db" bs="$ps" seek="$RV" count=1 conv=notrunc status=none
		;;
	1)
		rnd "$np"
		local page=$RV n i at
		rnd 16
		n=$((RV + 1))
		NOTE="page $((page + 1)) of $np (size $ps): $n bytes changed at"
		for ((i = 0; i < n; i++)); do
			rnd "$ps"
			at=$((page * ps + RV))
			rnd 256
			printf "$(printf '\\%03o' "$RV")" | dd of="$db" bs=1 seek="$at" conv=notrunc status=none
			NOTE+=" $at"
		done
		;;
	2)
		local sql
		pick "UPDATE param SET value = 'nan' WHERE key = 'frequency'" \
			"UPDATE param SET value = '1e999' WHERE key = 'radius_ratio'" \
			"UPDATE param SET value = 25 WHERE key = 'frequency'" \
			"UPDATE param SET value = '' WHERE key = 'ramp'" \
			"UPDATE param SET value = NULL" \
			"DELETE FROM param WHERE key = 'frequency'" \
			"UPDATE run SET state = 'bogus'" \
			"UPDATE run SET id = 'x' || id" \
			"UPDATE run SET campaign = 'other'" \
			"UPDATE result SET file_seal = '0000000000000000'" \
			"UPDATE result SET status = 'nonsense'" \
			"UPDATE result SET run = 'x' || run" \
			"UPDATE campaign SET name = 'other'" \
			"UPDATE run SET state = 'done' WHERE rowid = 1; UPDATE result SET waiting_time = 'abc'"
		sql=$PV
		NOTE="sqlite: $sql"
		sqlite3 "$db" "$sql" 2>"$W/sql.log" || NOTE+=" (failed: $(head -c 200 "$W/sql.log"))"
		;;
	3)
		pick run param result campaign attempt analysis_run
		NOTE="sqlite: DROP TABLE $PV"
		sqlite3 "$db" "PRAGMA foreign_keys = OFF; DROP TABLE $PV" 2>"$W/sql.log" || NOTE+=" (failed: $(head -c 200 "$W/sql.log"))"
		;;
	esac
	SEEN=study.db
}

# the node planted at W/P: kind and what it points at, to check afterwards
plant() { # plant PATH KIND
	local p="$W/$1"
	rm -rf "$p"
	mkdir -p "$(dirname "$p")"
	case $2 in
	symlink) ln -s "$W/victim" "$p" ;;
	symlink-dir) ln -s "$W/victimdir" "$p" ;;
	symlink-run) ln -s "$W/other.h5" "$p" ;;
	dangling) ln -s "$W/nowhere/x" "$p" ;;
	fifo) mkfifo "$p" ;;
	chardev) mknod "$p" c 1 3 2>/dev/null || ln -s /dev/null "$p" ;;
	dir) mkdir "$p" && echo keep >"$p/keep" ;;
	esac
}
node_state() { # node_state PATH: its kind and contents, as planted
	local p="$W/$1"
	if [ -L "$p" ]; then echo "link $(readlink "$p")"
	elif [ -p "$p" ]; then echo fifo
	elif [ -c "$p" ]; then echo chardev
	elif [ -d "$p" ]; then echo "dir $(ls -A "$p" | tr '\n' ' ')"
	elif [ -e "$p" ]; then echo "file $(md5sum <"$p" | cut -c1-32)"
	else echo none; fi
}
victims() { md5sum "$W/victim" "$W/other.h5" 2>/dev/null | cut -c1-32 | tr '\n' ' '; ls -A "$W/victimdir" | tr '\n' ' '; }

fam_paths() {
	echo victim >"$W/victim"
	mkdir -p "$W/victimdir"
	local id
	pick "${IDS[@]}"
	id=$PV
	pick "${IDS[@]}"
	cp "$SEALED/$NAME/$PV.h5" "$W/other.h5"
	pick "${AN[@]}"
	local tool=$PV where kind
	rnd 8
	case $RV in
	0 | 1)
		KEY=$tool+store
		baseline "$KEY"
		local v="BASE_FILES_${KEY//[^a-z]/_}"
		local files=(${!v})
		pick "${files[@]}"
		where=$PV
		pick symlink dangling fifo chardev dir
		kind=$PV
		;;
	2)
		KEY=$tool+store
		where=R/$NAME/analysis
		pick symlink-dir dangling fifo chardev
		kind=$PV
		;;
	3)
		pick "$tool+store" status export run
		KEY=$PV
		pick R/study.db R/study.db-journal R/study.db-wal R/study.db-shm
		where=$PV
		pick symlink dangling fifo chardev dir
		kind=$PV
		;;
	4 | 5)
		pick "$tool" "$tool" run
		KEY=$PV
		where=R/$NAME/$id.h5
		pick symlink-run dangling fifo chardev dir
		kind=$PV
		;;
	*)
		# a run file whose bytes no longer match its seal, moved aside by `study run`
		# into damaged/, where the node is
		KEY=run
		printf 'X' | dd of="$W/R/$NAME/$id.h5" bs=1 seek=2000 conv=notrunc status=none
		pick R/$NAME/damaged R/$NAME/damaged/$id.h5
		where=$PV
		pick symlink symlink-dir dangling fifo chardev dir
		kind=$PV
		;;
	esac
	plant "$where" "$kind"
	NODE=$where
	NODE_BEFORE=$(node_state "$where")
	VICTIMS_BEFORE=$(victims)
	NOTE="$kind at $where"
	SEEN=$(basename "$where")
}

# ---- the loop ----

declare -A NIN NCRASH NHANG NSILENT
IFS=, read -r -a FL <<<"$FAMS"
for f in "${FL[@]}"; do
	case $f in resealed | links | database | paths) ;; *) echo "families: unknown family '$f'" >&2; exit 2 ;; esac
	NIN[$f]=0 NCRASH[$f]=0 NHANG[$f]=0 NSILENT[$f]=0
done
famno() { case $1 in resealed) echo 1 ;; links) echo 2 ;; database) echo 3 ;; paths) echo 4 ;; esac; }
rm -f "$OUT/families.tsv"
printf 'family\tindex\tclass\tcommand\twhat\treproduce\n' >"$OUT/families.tsv"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}" UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"

one() { # one FAMILY INDEX: make, run and classify input INDEX of FAMILY
	local fam=$1 k=$2
	W="$WORK/in"
	rm -rf "$W" && mkdir -p "$W" && cp -r "$SEALED" "$W/R"
	NODE="" SEEN=""
	start "$(famno "$fam")" "$k"
	"fam_$fam"
	baseline "$KEY"
	cmd_argv "$KEY"
	run_cmd "$W" "$T"
	if [ "$RC" = 124 ] || [ "$RC" = 137 ]; then
		# a busy machine stretches a run: a hang is one that three times the time confirms
		local keep=$NOTE
		rm -rf "$W" && mkdir -p "$W" && cp -r "$SEALED" "$W/R"
		start "$(famno "$fam")" "$k"
		"fam_$fam"
		NOTE=$keep
		cmd_argv "$KEY"
		run_cmd "$W" $((3 * T))
	fi
	local class=ok why=""
	if grep -qE 'runtime error:|AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer' "$W/stderr"; then
		class=crash why="sanitizer: $(grep -m1 -E 'SUMMARY|runtime error' "$W/stderr" | head -c 200)"
	elif [ "$RC" = 124 ] || [ "$RC" = 137 ]; then
		class=hang why="no exit within $((3 * T)) s"
	elif [ "$RC" -ge 128 ]; then
		class=crash why="killed by signal $((RC - 128))"
	elif [ -n "$NODE" ] && [[ $NODE != R/$NAME/*.h5 ]] && [[ $NODE != R/$NAME/damaged* ]] &&
		[ "$(node_state "$NODE")" != "$NODE_BEFORE" ]; then
		class=silent why="the planted node changed: $NODE_BEFORE -> $(node_state "$NODE")"
	elif [ -n "$NODE" ] && [ "$(victims)" != "$VICTIMS_BEFORE" ]; then
		class=silent why="written through the planted node (its target changed)"
	elif [ "$RC" = 0 ] && [ "$(md5sum <"$W/stderr" | cut -c1-32)" = "${BASE_ERR[$KEY]}" ] &&
		! said && [ "$(output_hash "$W")" != "${BASE_OUT[$KEY]}" ]; then
		class=silent why="exit 0, nothing said, and the output differs from the unchanged seed's"
	fi
	NIN[$fam]=$((NIN[$fam] + 1))
	case $class in
	crash) NCRASH[$fam]=$((NCRASH[$fam] + 1)) ;;
	hang) NHANG[$fam]=$((NHANG[$fam] + 1)) ;;
	silent) NSILENT[$fam]=$((NSILENT[$fam] + 1)) ;;
	esac
	local repro="FUZZ_SEED=$SEED FUZZ_FAMILY_ONLY=$fam:$k bash tests/fuzz/fuzz.sh"
	if [ "$class" != ok ]; then
		printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$fam" "$k" "$class" "$KEY" "$NOTE; $why" "$repro" >>"$OUT/families.tsv"
		local d="$OUT/$fam-$k"
		rm -rf "$d" && mkdir -p "$d"
		cp "$W/stderr" "$d/stderr" 2>/dev/null
		printf '%s\n%s\n%s\nexit %s\n' "$fam input $k (seed $SEED): $class: $why" "$NOTE" "${CMD[*]}" "$RC" >"$d/what.txt"
		printf '#!/bin/sh\n# %s\ncd "%s" && %s\n' "$class: $why" "$(dirname "$(dirname "$SELF")")/.." "$repro" >"$d/repro.sh"
		echo "fuzz: $fam input $k: $class: $KEY: $NOTE; $why" >&2
	fi
	[ -n "$ONLY" ] && { echo "fuzz: $fam input $k: $class (exit $RC) $KEY: $NOTE${why:+; $why}"; echo "fuzz: its files: $W"; }
}

t0=$SECONDS
if [ -n "$ONLY" ]; then
	one "${ONLY%%:*}" "${ONLY#*:}"
else
	for ((k = 0; ; k++)); do
		[ "$N" != 0 ] && [ "$k" -ge "$N" ] && break
		[ "$SECS" != 0 ] && [ $((SECONDS - t0)) -ge "$SECS" ] && break
		for f in "${FL[@]}"; do one "$f" "$k"; done
	done
fi
ti=0 tc=0 th=0 ts=0
printf 'fuzz: %-9s %7s %8s %6s %7s\n' family inputs crashes hangs silent
for f in "${FL[@]}"; do
	printf 'fuzz: %-9s %7d %8d %6d %7d\n' "$f" "${NIN[$f]}" "${NCRASH[$f]}" "${NHANG[$f]}" "${NSILENT[$f]}"
	ti=$((ti + NIN[$f])) tc=$((tc + NCRASH[$f])) th=$((th + NHANG[$f])) ts=$((ts + NSILENT[$f]))
done
printf 'fuzz: %-9s %7d %8d %6d %7d  (%d s, seed %s)\n' families "$ti" "$tc" "$th" "$ts" $((SECONDS - t0)) "$SEED"
[ $((tc + th + ts)) = 0 ]
