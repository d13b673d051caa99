#!/usr/bin/env bash
# hostile_runs.sh - run files and campaign databases that are not what they claim are
# read by every tool and by bin/study without a crash, a hang or a number made of them
# (docs/inputs.md, "Files", "Numbers", "Run files"): a dataset whose shape the file
# cannot hold (its element count wrapping to 0 in 64 bits) and an array where one value
# belongs make the run unreadable, with the dataset and the reason; a FIFO where a run
# file belongs is refused at once; NaN in Φ, the heights, risen or waiting_time, and a
# parameter that is no number in the database, make the run unusable with the reason;
# a run whose grouping key is missing or no number makes the tool refuse the campaign.
# A file whose bytes do not match its seal (a flipped bit anywhere, the global heap's
# virtual-dataset source name included), or whose seal is not the one the database
# recorded, is refused before HDF5 parses it; links, external storage and virtual
# datasets that leave the file are refused without being opened (a FIFO: no hang);
# values the engine cannot write and database parameters that are not the file's make
# the run unreadable; Fig. 1 counts a run whose field it cannot use.
# The runs are tests/fuzz/runs.campaign's; build/fuzz/h5mut changes them (and seals
# them again, as a hostile hand would), and `fresh` records the new seal in the copy's
# database, so that the checks behind the seal are what is tested; `planted` does not.
# tier: slow: a campaign whose files are then made hostile, read by every tool
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
H5MUT="${H5MUT:-$REPO/build/fuzz/h5mut}"
[ -x "$H5MUT" ] || { fail setup "$H5MUT is not an executable (run make tests)"; finish; }
cd "$TMP" || exit 1
LIMIT=30 # seconds before a tool counts as hung

cp "$REPO/tests/fuzz/runs.campaign" fz.campaign
fixture_runs fz.campaign R &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 4 ] && ok setup.campaign ||
	{ fail setup.campaign "$(tail -c 400 R.log)"; finish; }
# the run with an intruder at the fixed frequency, and one without
ID=$(q R/study.db "SELECT r.id FROM run r JOIN param a ON a.run = r.id AND a.key = 'radius_ratio' AND a.value > 0
	JOIN param b ON b.run = r.id AND b.key = 'ramp' AND b.value = 'none'")
ID0=$(q R/study.db "SELECT r.id FROM run r JOIN param a ON a.run = r.id AND a.key = 'radius_ratio' AND a.value = 0
	JOIN param b ON b.run = r.id AND b.key = 'ramp' AND b.value = 'none'")

# seal FILE: the seal in FILE's user block ("" when none)
seal() { head -c 64 "$1" | sed -n 's/^fnv1a64w \([0-9a-f]*\)$/\1/p'; }
# planted NAME [RUN H5MUT-OPS...]: a copy NAME of the runs with RUN's file changed
planted() {
	local d=$1 id=${2:-}
	rm -rf "$d" && cp -r R "$d" || return 1
	[ -n "$id" ] || return 0
	shift 2
	"$H5MUT" "$d/fz/$id.h5" "$d/fz/$id.h5.new" "$@" && mv "$d/fz/$id.h5.new" "$d/fz/$id.h5" ||
		{ fail "setup.$d" "h5mut $*"; return 1; }
}
# fresh NAME [RUN H5MUT-OPS...]: the same, the new seal recorded in NAME's database
# (a database without the column, an earlier version's, is left as it is)
fresh() {
	planted "$@" || return 1
	[ -z "${2:-}" ] || { q "$1/study.db" "UPDATE result SET file_seal = '$(seal "$1/fz/$2.h5")' WHERE run = '$2'" &&
		reseal_rows "$1/study.db"; } 2>/dev/null
	return 0
}

# tool_on ID TOOL DIR: runs TOOL on DIR's campaign (TOOL.out, TOOL.err in DIR); returns
# its exit code, 124 when it hung
tool_on() {
	local id=$1 t=$2 d=$3
	timeout -k 5 "$LIMIT" "$BINDIR/$t" fz --runs "$d" --no-plot --no-store --out "$d/out" >"$d/$t.out" 2>"$d/$t.err"
}

# counted ID TOOL DIR RUN USE NEEDLE: TOOL exits 0 without a sanitizer report and counts
# RUN as USE in its accounting CSV, with NEEDLE in the reason
counted() {
	local id=$1 t=$2 d=$3 run=$4 use=$5 needle=$6 rc row
	tool_on "$id" "$t" "$d"
	rc=$?
	row=$(grep -F ",$run," "$d/out/${t}_accounting.csv" 2>/dev/null)
	if [ "$rc" -ne 0 ]; then
		fail "$id" "exit $rc: $(head -c 300 "$d/$t.err")"
	elif grep -qE 'runtime error|AddressSanitizer|LeakSanitizer' "$d/$t.err"; then
		fail "$id" "sanitizer: $(grep -m1 -E 'runtime error|Sanitizer' "$d/$t.err")"
	elif ! grep -qF ",$use," <<<"$row" || ! grep -qF -- "$needle" <<<"$row"; then
		fail "$id" "run $run: '$row' (want $use and '$needle')"
	else
		ok "$id"
	fi
}

# refused ID TOOL DIR NEEDLE...: TOOL exits 1 with every NEEDLE on stderr
refused() {
	local id=$1 t=$2 d=$3 rc n why=""
	shift 3
	tool_on "$id" "$t" "$d"
	rc=$?
	[ "$rc" -eq 1 ] || why="exit $rc, expected 1"
	for n in "$@"; do
		[ -z "$why" ] && ! grep -qF -- "$n" "$d/$t.err" && why="stderr lacks '$n'"
	done
	[ -z "$why" ] && ok "$id" || fail "$id" "$why: $(head -c 300 "$d/$t.err") $(head -c 200 "$d/$t.out")"
}

# ingested ID DIR NEEDLE: bin/study ingests DIR's file of run $ID (made pending): it
# exits 3 with the run failed, NEEDLE in the attempt's message, no sanitizer report
ingested() {
	local id=$1 d=$2 needle=$3 rc st msg
	q "$d/study.db" "UPDATE run SET state = 'pending' WHERE id = '$ID'; DELETE FROM result WHERE run = '$ID'"
	timeout -k 5 "$LIMIT" "$STUDY" run fz.campaign --runs "$d" --jobs 1 --no-progress >"$d.study.log" 2>&1
	rc=$?
	st=$(q "$d/study.db" "SELECT state FROM run WHERE id = '$ID'")
	msg=$(q "$d/study.db" "SELECT message FROM attempt WHERE run = '$ID' ORDER BY n DESC LIMIT 1")
	[ "$rc" -eq 3 ] && [ "$st" = failed ] && grep -qF -- "$needle" <<<"$msg" && ! grep -q Sanitizer "$d.study.log" &&
		ok "$id" || fail "$id" "exit $rc, state '$st', message '$msg': $(tail -c 300 "$d.study.log")"
}

# ---- sizes: a shape is a claim, checked before anything is allocated ----
# the displacement field of (1, 2^32, 2^32): its count wrapped to 0, and convect
# crashed and figures wrote past its buffer
big=1,4294967296,4294967296
fresh W1 "$ID0" --shape /observables/field/ux/value $big --shape /observables/field/uy/value $big \
	--shape /observables/field/count/value $big --shape /observables/field/ux/time 1
counted size.field_wraps.convect convect W1 "$ID0" unreadable "element count overflows"
counted size.field_wraps.figures figures W1 "$ID0" unreadable "element count overflows"
# Φ of 3 x 2^31 values that the file does not hold (no byte of it is written)
fresh W2 "$ID" --shape /observables/flux/phi/value 3,2147483648
counted size.unwritten.onset onset W2 "$ID" unreadable "but the file holds 0"
counted size.unwritten.rolls rolls W2 "$ID" unreadable "but the file holds 0"
# an array where one value belongs: H5Aread wrote all of it over the one double
fresh W3 "$ID" --attr-array / waiting_time 2000
counted size.array_attribute.waiting waiting W3 "$ID" unreadable "no valid root attributes"
counted size.array_attribute.whale whale W3 "$ID" unreadable "no valid root attributes"
# bin/study reads the same way (h5sum.c): a run whose file claims 2^32 x 2^32
# trajectory rows, or has an array for its status, is a damaged output, not a result
fresh S1 "$ID" --shape /particles/intruder/position/value 4294967296,4294967296,2
ingested size.study_rows S1 "element count overflows"
fresh S2 "$ID" --attr-array / exit_code 2000
ingested size.study_array S2 "exit_code: not one integer"

# ---- a FIFO where a run file belongs: every reader opened it and waited for a writer ----
fresh F && rm F/fz/"$ID".h5 && mkfifo F/fz/"$ID".h5
AN_TOOLS=$(make -s --no-print-directory -C "$REPO" print-campaign-tools)
check tools.listed "make print-campaign-tools named no tool" test -n "$AN_TOOLS"
for t in $AN_TOOLS; do
	# the ramp runs are hysteresis's: its FIFO is the ramp run's
	[ $t = hysteresis ] && continue
	counted fifo.$t $t F "$ID" unreadable "not a regular file"
done
IDR=$(q R/study.db "SELECT r.id FROM run r JOIN param a ON a.run = r.id AND a.key = 'radius_ratio' AND a.value > 0
	JOIN param b ON b.run = r.id AND b.key = 'ramp' AND b.value = 'updown'")
rm F/fz/"$IDR".h5 && mkfifo F/fz/"$IDR".h5
counted fifo.hysteresis hysteresis F "$IDR" unreadable "not a regular file"
# bin/study: the pending run's FIFO is ingested as a failure (the done run's file is
# back, or the driver would run it again)
rm F/fz/"$IDR".h5 && cp R/fz/"$IDR".h5 F/fz/
ingested fifo.study F "not a regular file"

# ---- values that are no number: the run is unusable, with the reason ----
fresh N1 "$ID" --set /observables/flux/phi/value 3 nan
counted nan.phi.onset onset N1 "$ID" unusable "phi/value[3] = nan"
counted nan.phi.rolls rolls N1 "$ID" unusable "phi/value[3] = nan"
counted nan.phi.figures figures N1 "$ID" unusable "phi/value[3] = nan"
fresh N2 "$ID" --set /observables/flux/heights 2 inf
counted nan.heights.onset onset N2 "$ID" unusable "heights[2] = inf"
# NaN where docs/inputs.md says every value is checked: a flux time, a flux frequency,
# the field, the intruder's trajectory
fresh N9 "$ID" --set /observables/flux/phi/time 1 nan
counted nan.flux_time.onset onset N9 "$ID" unusable "phi/time[1] = nan: not a finite number"
fresh N10 "$ID" --set /observables/flux/frequency/value 1 nan
counted nan.flux_frequency.onset onset N10 "$ID" unusable "frequency/value[1] = nan: not a finite number"
fresh N11 "$ID" --set /observables/field/ux/value 0 nan
counted nan.field.convect convect N11 "$ID" unusable "nan"
fresh N12 "$ID" --set /particles/intruder/position/value 3 nan
counted nan.trajectory.whale whale N12 "$ID" unusable "nan"
fresh N3 "$ID" --attr / waiting_time nan
counted nan.waiting_time.waiting waiting N3 "$ID" unusable "waiting_time = nan"
counted nan.waiting_time.figures figures N3 "$ID" unusable "waiting_time = nan"
counted nan.waiting_time.whale whale N3 "$ID" unusable "waiting_time = nan"
fresh N4 "$ID" --attr / risen nan
counted nan.risen.ring ring N4 "$ID" unusable "risen = nan"
# bin/study records no result with a value that is no number (an Inf waiting time
# entered the median of replicates = auto as a time)
fresh S3 "$ID" --attr / waiting_time inf
ingested nan.waiting_time.study S3 "waiting_time = inf"
fresh N5 && q N5/study.db "UPDATE param SET value = 'nan' WHERE run = '$ID' AND key = 'frequency'"
counted nan.param.onset onset N5 "$ID" unusable "frequency = 'nan'"
# the other values docs/inputs.md names ('' and Inf), and a key every run has missing
fresh N6 && q N6/study.db "UPDATE param SET value = '' WHERE run = '$ID' AND key = 'amplitude'"
counted empty.param.onset onset N6 "$ID" unusable "amplitude = ''"
fresh N7 && q N7/study.db "UPDATE param SET value = 'Inf' WHERE run = '$ID' AND key = 'duration'"
counted inf.param.waiting waiting N7 "$ID" unusable "duration = 'Inf'"
fresh N8 && q N8/study.db "DELETE FROM param WHERE run = '$ID' AND key = 'width'"
counted missing.param.width.onset onset N8 "$ID" unusable "width"
# a group whose key is missing or no number is refused (figures pooled the run with
# an intruder among those without one: radius_ratio read as 0)
fresh M && q M/study.db "DELETE FROM param WHERE run = '$ID' AND key = 'radius_ratio'"
for t in onset waiting figures; do
	refused group.missing_key.$t $t M "run $ID" "radius_ratio: no row in the param table"
done
fresh M2 && q M2/study.db "UPDATE param SET value = 'abc' WHERE run = '$ID' AND key = 'radius_ratio'"
refused group.not_a_number.onset onset M2 "run $ID" "radius_ratio = 'abc'"

# ---- the seal: a changed byte is refused before HDF5 parses the file ----
# one bit of the global heap, the NUL after bed_xyz's source name ".": HDF5 1.10.8 ran
# strlen past its buffer in every reader (ASan), the release build read on silently
planted V1 "$ID" --flip-vds-name --stale-seal
for t in onset waiting ring whale; do
	counted seal.vds_name.$t $t V1 "$ID" unreadable "its bytes do not match its seal"
done
ingested seal.vds_name.study V1 "its bytes do not match its seal"
# a value edited through HDF5 (Fletcher32 computed anew) without sealing again
planted V2 "$ID" --set /observables/flux/phi/value 3 7 --stale-seal
counted seal.edited.onset onset V2 "$ID" unreadable "its bytes do not match its seal"
# sealed again by hand, or another run's (another campaign's) sealed file in its place:
# not the seal the driver recorded, refused before HDF5 opens it
planted V3 "$ID" --set /observables/flux/phi/value 3 7
counted seal.resealed.onset onset V3 "$ID" unreadable "but the database recorded"
planted V4 && cp R/fz/"$ID0".h5 V4/fz/"$ID".h5
counted seal.other_file.rolls rolls V4 "$ID" unreadable "but the database recorded"
# the done run's file resealed: the sweep puts the run back in the queue as damaged
timeout -k 5 "$LIMIT" "$STUDY" run fz.campaign --runs V3 --jobs 1 --no-progress >V3.study.log 2>&1
[ -e V3/fz/damaged/"$ID".attempt1.h5 ] && grep -qF "but the database recorded" V3.study.log &&
	[ "$(q V3/study.db "SELECT state FROM run WHERE id = '$ID'")" = done ] && ok seal.resealed.study ||
	fail seal.resealed.study "$(ls V3/fz/damaged 2>&1) $(tail -c 300 V3.study.log)"
# a shakebox-run-2 file (read unchecked, older) where the database recorded a sealed one
planted V5 "$ID0" --attr-str / format shakebox-run-2 && cp V5/fz/"$ID0".h5 V5/fz/"$ID".h5
counted seal.format2.waiting waiting V5 "$ID" unreadable "but the database recorded"
# ... and one without a seal at all (its user block cut off: HDF5 finds its superblock
# at byte 0 then)
planted V6 "$ID0" --attr-str / format shakebox-run-2 && tail -c +513 V6/fz/"$ID0".h5 >V6/fz/"$ID".h5 &&
	counted seal.format2_unsealed.waiting waiting V6 "$ID" unreadable "sealed not at all (an older format), but the database recorded"

# ---- HDF5 crashing while it walks a file: the reader refuses the file and lives ----
# HDF5 1.10.8 frees a wild pointer in H5Lvisit on a dense link table overwritten with
# 0xff and sealed again (make fuzz, run-file input 43 of seed 1); with no seal recorded
# the readers walk a file first in a child process. The shim makes H5Lvisit crash so on
# the run's file (the crash, not the one file's layout, is what is tested).
SHIM="${IOFAIL:-$REPO/build/faults/iofail.so}"
h5shared_setup waiting whale
planted W1 && q W1/study.db "UPDATE result SET file_seal = NULL" && reseal_rows W1/study.db
for t in waiting whale; do
	BINDIR=$H5SHARED LD_PRELOAD="$SHIM" IOFAIL_H5WALK="$ID.h5" ASAN_OPTIONS="${ASAN_OPTIONS:-}:verify_asan_link_order=0" \
		counted h5walk_crash.$t $t W1 "$ID" unreadable "the HDF5 library failed while walking the file's links and objects"
done
# ... and one that loops forever there is refused at the walk's time limit
# (SHAKEBOX_H5_WALK_SECONDS), not waited for (make fuzz, run-file input 1047 of seed 31);
# 4 s, not less: the healthy run beside it must walk within the limit on a loaded machine
# (the sanitizer build at load 15-20 took over 1 s)
t0=$(date +%s)
BINDIR=$H5SHARED LD_PRELOAD="$SHIM" IOFAIL_H5WALK_HANG="$ID.h5" SHAKEBOX_H5_WALK_SECONDS=4 ASAN_OPTIONS="${ASAN_OPTIONS:-}:verify_asan_link_order=0" \
	counted h5walk_hang.waiting waiting W1 "$ID" unreadable "did not finish walking the file's links and objects within 4 s"
check h5walk_hang.within_limit "the tool took $(($(date +%s) - t0)) s" test $(($(date +%s) - t0)) -lt 20
# a limit that is no number is refused at the start, by every program that reads run files
bad=""
for t in waiting study dumpflux; do
	case $t in study) args=(status fz --runs W1) ;; dumpflux) args=(run "W1/fz/$ID.h5") ;; *) args=(fz --runs W1 --no-plot --no-store) ;; esac
	SHAKEBOX_H5_WALK_SECONDS=abc "$BINDIR/$t" "${args[@]}" >lim.out 2>lim.err
	rc=$?
	[ "$rc" = 1 ] && grep -qF "SHAKEBOX_H5_WALK_SECONDS = 'abc': expected a number of seconds in [0.1, 3600]" lim.err ||
		bad="$bad $t: exit $rc, $(head -c 200 lim.err);"
done
[ -z "$bad" ] && ok h5walk_limit.bad_value_refused || fail h5walk_limit.bad_value_refused "$bad"

# ---- nothing outside the file: links, external storage and virtual datasets ----
mkfifo pipe && cp R/fz/"$ID0".h5 other.h5
PHI=/observables/flux/phi/value
for how in elink extern vds; do
	for to in pipe other; do
		tgt=$TMP/pipe
		[ $to = other ] && tgt=$TMP/other.h5
		fresh X "$ID" --$how $PHI "$tgt" || { fail outside.$how.$to "h5mut --$how"; continue; }
		for t in onset rolls figures; do
			counted outside.$how.$to.$t $t X "$ID" unreadable "$PHI"
		done
		timeout -k 5 "$LIMIT" "$BINDIR/dumpflux" run X/fz/"$ID".h5 >X/d.out 2>X/d.err
		rc=$?
		[ $rc = 2 ] && grep -qF "$PHI" X/d.err && grep -qE "another file|external link" X/d.err &&
			ok outside.$how.$to.dumpflux || fail outside.$how.$to.dumpflux "exit $rc: $(head -c 300 X/d.err)"
	done
done
fresh X "$ID" --elink $PHI "$TMP/pipe"
ingested outside.elink.study X "is an external link"
# a virtual dataset whose source is itself (in this file, "."): HDF5 1.10.8 recursed
# until the stack was gone (make fuzz, links input 352 of seed 11: bin/figures)
fresh X "$ID" --vds $PHI . || fail outside.vds_itself "h5mut --vds $PHI ."
for t in onset figures; do
	counted outside.vds_itself.$t $t X "$ID" unreadable "itself virtual"
done
# bin/dumpflux run checked neither a file's format nor its digest
for how in "digest|--stale-digest --attr / steps 5|do not match their digest" \
	"format|--attr-str / format shakebox-run-9|format 'shakebox-run-9'"; do
	IFS='|' read -r name ops needle <<<"$how"
	# shellcheck disable=SC2086
	fresh D "$ID" $ops || { fail dumpflux.$name "h5mut $ops"; continue; }
	timeout -k 5 "$LIMIT" "$BINDIR/dumpflux" run D/fz/"$ID".h5 >D/d.out 2>D/d.err
	rc=$?
	[ $rc = 2 ] && grep -qF "$needle" D/d.err && [ ! -s D/d.out ] && ok dumpflux.$name ||
		fail dumpflux.$name "exit $rc: $(head -c 300 D/d.err)"
done

# ---- values the engine cannot write ----
range() { # ID TOOL NEEDLE H5MUT-OPS...
	local id=$1 t=$2 n=$3
	shift 3
	fresh Y "$ID" "$@" && counted "$id" "$t" Y "$ID" unreadable "$n" || fail "$id" "h5mut $*"
}
range range.heights_reversed.onset onset "heights[1] = 0.001: the lines rise" --set /observables/flux/heights 1 0.001
h0=$(h5dump -m %.17g -d /observables/flux/heights -y -w 0 R/fz/"$ID".h5 | sed -n 's/^ *\([0-9][0-9.e+-]*\),.*/\1/p' | head -1)
range range.heights_constant.rolls rolls "heights[1] = $(printf %g "$h0"): the lines rise" --set /observables/flux/heights 1 "$h0"
range range.heights_negative.onset onset "heights[0] = -1" --set /observables/flux/heights 0 -1
# rolls aborted in GSL (exit 134) on this one finite height
range range.height_1e308.rolls rolls "= 1e+308" --set /observables/flux/heights 7 1e308
range range.frequency_0.onset onset "frequency/value[2] = 0" --set /observables/flux/frequency/value 2 0
range range.frequency_1e30.rolls rolls "frequency/value[2] = 1e+30" --set /observables/flux/frequency/value 2 1e30
range range.param_frequency.onset onset "frequency: expected a number in [0, 1000]" --attr /parameters frequency 1e30
range range.waiting_time.waiting waiting "waiting_time = 1e+09 s, after the run's end" --attr / waiting_time 1e9
range range.surface_0.whale whale "surface_height = 0" --attr / surface_height 0
range range.surface_neg.figures figures "surface_height = -10" --attr / surface_height -10
fresh Y "$ID" --attr / intruder_radius inf
counted range.intruder_radius.whale whale Y "$ID" unusable "intruder_radius = inf"
fresh Y "$ID" --attr / waiting_time 1e9
ingested range.waiting_time.study Y "waiting_time = 1e+09 s, after the run's end"
# waiting left a run with a surface height that is no number out of its second
# definition "without a trajectory"; it is unusable, and says why
fresh Y "$ID" --attr / surface_height nan
counted range.surface_nan.waiting waiting Y "$ID" unusable "surface_height = nan"

# ---- the database's parameters are the file's ----
fresh P && q P/study.db "UPDATE param SET value = 25 WHERE run = '$ID' AND key = 'frequency'"
for t in onset waiting figures; do
	counted params.frequency_edited.$t $t P "$ID" unreadable "frequency = 20 in the file, '25' in the database"
done
# ... and so is its status (make fuzz, family database: figures reported 'nonsense' as
# a used run's status, exit 0)
fresh S && q S/study.db "UPDATE result SET status = 'nonsense' WHERE run = '$ID'"
for t in onset figures; do
	counted params.status_edited.$t $t S "$ID" unreadable "status = 'ok' in the file, 'nonsense' in the database"
done
# ... and every other value of its rows is the one recorded (their row seal, lib/rowseal.h:
# make fuzz, family database, bytes changed in a page of table result: hysteresis used
# the changed values, exit 0); with the seal written again the edit is not seen
# (hysteresis reads the ramp runs: one of them edited too)
RAMP=$(q R/study.db "SELECT run FROM param WHERE key = 'ramp' AND value = 'updown' ORDER BY run LIMIT 1")
fresh RS && q RS/study.db "UPDATE result SET steps = steps + 1 WHERE run IN ('$ID', '$RAMP')"
counted rows.result_edited.waiting waiting RS "$ID" unusable "its rows in the database are not those recorded"
counted rows.result_edited.hysteresis hysteresis RS "$RAMP" unusable "its rows in the database are not those recorded"
reseal_rows RS/study.db
tool_on rows.resealed_used waiting RS
row=$(grep -F ",$ID," RS/out/waiting_accounting.csv 2>/dev/null)
grep -qF ",used," <<<"$row" && ok rows.resealed_used || fail rows.resealed_used "run $ID: '$row' (want used)"

# ---- Fig. 1: a run whose field cannot be used is counted so ----
fresh G1 "$ID" --set /observables/field/count/value 0 inf
counted fig1.count_inf.figures figures G1 "$ID" unusable "not a finite number"
fresh G2 "$ID" --delete /observables/field
counted fig1.deleted.figures figures G2 "$ID" unreadable "no /observables/field"
fresh G3 "$ID" --flip /observables/field/ux/value
counted fig1.flipped_chunk.figures figures G3 "$ID" unreadable "checksum error"
fresh G4 "$ID" --attr /observables/field cell 0
counted fig1.cell_0.figures figures G4 "$ID" unreadable "no field cell size"

# and the unchanged runs are used by every tool
fresh U
for t in $AN_TOOLS; do
	[ $t = hysteresis ] && continue # it reads the ramp runs alone
	counted control.$t $t U "$ID" used ""
done
finish
