#!/usr/bin/env bash
# grid_bounds.sh - campaign files cannot make the driver work without end: a line past
# the reader's limit and a NUL byte are errors naming the file, the line (and the
# limit); each axis is bounded before its values are made; the grid is counted from the
# axes' sizes (overflow-checked) before it is expanded, against max_runs, which the
# [campaign] section can raise; duplicates go in O(n log n); range arithmetic does not
# overflow (UBSan). Every case runs under `timeout`, so one that would hang fails.
. "$(dirname "$0")/lib.sh"
study_setup
# seconds a case may take: every one of them answers in well under a second (the
# sanitizer build included) when the bounds are checked before the work
LIMIT="${GRID_BOUNDS_TIMEOUT:-10}"
cd "$TMP" || exit 1

H=('[campaign]' 'name = b' 'seed = 1')

# sanitizer_free FILE : no ASan/UBSan report in FILE
sanitizer_free() { ! grep -qE 'runtime error:|AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer' "$1"; }

# refused ID LINE TEXT CONTENT... : `study expand` of the CONTENT lines exits 1 within
# LIMIT seconds with "FILE:LINE: " and TEXT in its message
refused() {
	local id=$1 line=$2 text=$3
	shift 3
	printf '%s\n' "$@" >"$id.campaign"
	refused_file "$id" "$line" "$text"
}
# refused_file ID LINE TEXT : the same for a file ID.campaign written by the caller
refused_file() {
	local id=$1 line=$2 text=$3 rc
	timeout -k 2 "$LIMIT" "$STUDY" expand "$id.campaign" >"$id.out" 2>"$id.err"
	rc=$?
	if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
		fail "$id" "still running after $LIMIT s (expected: $id.campaign:$line: ... $text)"
	elif [ "$rc" -eq 1 ] && grep -qF "$id.campaign:$line: " "$id.err" && grep -qF -- "$text" "$id.err" &&
		sanitizer_free "$id.err"; then
		ok "$id"
	else
		fail "$id" "exit $rc, expected '$id.campaign:$line: ... $text': $(head -c 400 "$id.err")"
	fi
}
# accepted ID RUNS CONTENT... : `study expand` gives RUNS runs within LIMIT seconds
accepted() {
	local id=$1 want=$2 rc n
	shift 2
	printf '%s\n' "$@" >"$id.campaign"
	timeout -k 2 "$LIMIT" "$STUDY" expand "$id.campaign" >"$id.out" 2>"$id.err"
	rc=$?
	n=$(($(wc -l <"$id.out") - 1))
	if [ "$rc" -eq 0 ] && [ "$n" = "$want" ] && sanitizer_free "$id.err"; then ok "$id"; else
		fail "$id" "exit $rc, $n runs (want $want): $(head -c 400 "$id.err")"; fi
}
long() { head -c "$1" /dev/zero | tr '\0' x; } # a string of N characters

# --- the reader: line length and NUL bytes ---
# inih hands the reader a 200-byte buffer: 199 characters and the terminating NUL
{ printf '%s\n' "${H[@]}" "description = $(long 185)" '[grid]' 'frequency = 2, 3'; } >cp.line_at_limit.campaign
timeout -k 2 "$LIMIT" "$STUDY" expand cp.line_at_limit.campaign >cp.line_at_limit.out 2>cp.line_at_limit.err &&
	[ "$(awk 'NR == 4 { print length }' cp.line_at_limit.campaign)" = 199 ] &&
	[ "$(($(wc -l <cp.line_at_limit.out) - 1))" = 2 ] && ok cp.line_at_limit ||
	fail cp.line_at_limit "a line of 199 characters must be read whole: $(head -c 300 cp.line_at_limit.err)"
refused cp.line_too_long 4 "line too long (the limit is 199 characters)" \
	"${H[@]}" "description = $(long 186)" '[grid]' 'frequency = 2, 3'
refused cp.line_too_long_1024 5 "line too long (the limit is 199 characters)" \
	"${H[@]}" '[grid]' "frequency = 2$(printf ', 2%.0s' $(seq 1 340))"
# the rest of a long line used to come back as a line of its own: here a key
refused cp.line_too_long_last 4 "line too long (the limit is 199 characters)" \
	"${H[@]}" "description = $(long 185)frequency = 3"
printf '%s\n' "${H[@]}" '[grid]' 'frequency = 2, 3' | sed '5s/, 3/\x00, 3/' >cp.nul_in_value.campaign
refused_file cp.nul_in_value 5 "NUL byte in column 14 (a campaign file is text)"
{ printf '%s\n' "${H[@]}" '[grid]'; printf '\0# a comment\nfrequency = 2\n'; } >cp.nul_line.campaign
refused_file cp.nul_line 5 "NUL byte in column 1"
{ printf '%s\n' "${H[@]}" '[grid]'; printf 'frequency = 2\n\0'; } >cp.nul_at_end.campaign
refused_file cp.nul_at_end 6 "NUL byte in column 1"
# a campaign that is no regular file is refused at once (a pipe could be endless, a
# FIFO without a writer blocked the open for good); a regular one is bounded in lines
for kind in pipe fifo; do
	if [ $kind = fifo ]; then
		mkfifo cp.fifo
		timeout -k 2 "$LIMIT" "$STUDY" expand cp.fifo >cp.$kind.out 2>cp.$kind.err
	else
		timeout -k 2 "$LIMIT" "$STUDY" expand <(printf '%s\n' "${H[@]}"; yes '# a comment') >cp.$kind.out 2>cp.$kind.err
	fi
	rc=$?
	[ "$rc" -eq 1 ] && grep -q 'not a regular file' cp.$kind.err && sanitizer_free cp.$kind.err &&
		ok cp.$kind || fail cp.$kind "exit $rc: $(head -c 300 cp.$kind.err)"
done
{ printf '%s\n' "${H[@]}"; yes '# a comment' | head -n 100000; } >cp.long.campaign
timeout -k 2 "$LIMIT" "$STUDY" expand cp.long.campaign >cp.long.out 2>cp.long.err
rc=$?
[ "$rc" -eq 1 ] && grep -qE ':100001: more than 100000 lines' cp.long.err && sanitizer_free cp.long.err &&
	ok cp.too_many_lines || fail cp.too_many_lines "exit $rc: $(head -c 300 cp.long.err)"

# --- each axis is bounded before its values are made ---
# 100001 values: the count is refused before they are made (it took 24 s to make them,
# one quadratic duplicate check at a time, before saying so)
refused axis.float_range_count 5 "range '0:1:1e-5' has 100001 values, more than 100000 in one axis" \
	"${H[@]}" '[grid]' 'frequency = 0:1:1e-5'
refused axis.float_range_overflow 5 "range '-1e308:1e308:1' has too many values, more than 100000 in one axis" \
	"${H[@]}" '[grid]' 'frequency = -1e308:1e308:1'
refused axis.float_range_tiny_step 5 "range '0:1e308:1e-10' has too many values" \
	"${H[@]}" '[grid]' 'frequency = 0:1e308:1e-10'
refused axis.float_range_huge 5 "range '0:1000:1e-300' has 1e+303 values" \
	"${H[@]}" '[grid]' 'frequency = 0:1000:1e-300'
# hi - lo overflows a long: UBSan stops the sanitizer build, the release build took
# the wrapped difference
refused axis.int_range_overflow 5 "range '-1..9223372036854775807' has 9223372036854775809 values, more than 100000" \
	"${H[@]}" '[grid]' 'seed = -1..9223372036854775807'
refused axis.int_range_whole_long 5 "range '-9223372036854775808..9223372036854775807' has 18446744073709551615 + 1 values" \
	"${H[@]}" '[grid]' 'seed = -9223372036854775808..9223372036854775807'
refused axis.int_range_past_long 5 "bad range '0..9223372036854775808'" \
	"${H[@]}" '[grid]' 'seed = 0..9223372036854775808'
refused axis.ranges_add_up 5 "'50000..100000' takes the axis past 100000 values (50000 before it)" \
	"${H[@]}" '[grid]' 'seed = 0..49999, 50000..100000'
accepted axis.int_range_top 3 "${H[@]}" '[grid]' 'seed = 9007199254740990..9007199254740992'

# --- duplicates: O(n log n), the first of each kept ---
accepted axis.duplicates 3 "${H[@]}" '[grid]' 'frequency = 2.6, 2.60, 2.6e0, 2.5:2.7:0.1, 2.7'
# 100000 values, 50000 of them distinct: read in a moment, and counted after the
# duplicates are gone (the grid is 50000 x 3)
refused axis.duplicates_fast 6 "the grid has 150000 points (frequency 50000 x seed 3), more than the limit of 100000" \
	"${H[@]}" '[grid]' 'frequency = 2e-5:1:2e-5, 2e-5:1:2e-5' 'seed = 1..3'

# --- the grid is counted before it is expanded ---
# 10^6 points: 372 s of `study expand` without a word before
refused grid.count_before_expand 6 "frequency: the grid has 1000000 points (depth 1000 x frequency 1000), more than the limit of 100000; add max_runs = 1000000 under [campaign] to allow them" \
	"${H[@]}" '[grid]' 'depth = 0..999' 'frequency = 0.001:1:0.001'
# 10^5 x 991 x 991 points: past the most max_runs can allow, refused as soon as the
# second axis is read
refused grid.past_any_limit 6 "seed: the grid has 99100000 points (depth 991 x seed 100000), more than the limit of 100000; max_runs under [campaign] raises the limit to at most 10000000" \
	"${H[@]}" '[grid]' 'depth = 0..990' 'seed = 1..100000' 'amplitude = 0:990:1'
# 20 axes of 10 values: reading stops at the axis that takes the grid past 10^7 (the
# most max_runs can allow); the message names the one that passed the limit
ax=()
for k in n_grains depth width r_min r_max wall_radius density mass_factor seed settle_ke \
	settle_min settle_drag amplitude frequency gravity stiffness gamma_n gamma_s mu dt; do
	ax+=("$k = 1, 2, 3, 4, 5, 6, 7, 8, 9, 10")
done
refused grid.many_axes 10 "wall_radius: the grid has 100000000 points" "${H[@]}" '[grid]' "${ax[@]}"
# replicates are the seed axis: the message names the replicates line
refused grid.replicates 4 "replicates: the grid has 200000 points (frequency 2 x seed 100000), more than the limit of 100000" \
	'[campaign]' 'name = b' 'seed = 1' 'replicates = 100000' '[grid]' 'frequency = 2, 3'
# max_runs: raises or lowers the limit, wherever it stands in [campaign]
refused grid.max_runs_lower 6 "frequency: the grid has 11 points (frequency 11), more than max_runs = 10 (line 4); raise max_runs to 11 under [campaign] to allow them" \
	"${H[@]}" 'max_runs = 10' '[grid]' 'frequency = 2:3:0.1'
accepted grid.max_runs_exact 11 "${H[@]}" 'max_runs = 11' '[grid]' 'frequency = 2:3:0.1'
accepted grid.max_runs_after_grid 11 '[grid]' 'frequency = 2:3:0.1' "${H[@]}" 'max_runs = 11'
refused grid.max_runs_zero 4 "max_runs: expected an integer in [1, 10000000], got '0'" "${H[@]}" 'max_runs = 0'
refused grid.max_runs_too_big 4 "max_runs: expected an integer in [1, 10000000], got '10000001'" "${H[@]}" 'max_runs = 10000001'
refused grid.max_runs_text 4 "max_runs: expected an integer in [1, 10000000], got 'lots'" "${H[@]}" 'max_runs = lots'
refused grid.max_runs_twice 5 "max_runs: given twice (first on line 4)" "${H[@]}" 'max_runs = 5' 'max_runs = 6'
refused grid.max_runs_in_scene 5 "unknown key 'max_runs'" "${H[@]}" '[scene]' 'max_runs = 5'
# the driver refuses the same grid before it makes a database or runs anything
printf '%s\n' "${H[@]}" '[grid]' 'depth = 0..999' 'frequency = 0.001:1:0.001' >grid.run.campaign
timeout -k 2 "$LIMIT" "$STUDY" run grid.run.campaign --runs "$TMP/runs" >grid.run.out 2>&1
rc=$?
[ "$rc" -eq 1 ] && grep -qF "grid.run.campaign:6: frequency: the grid has 1000000 points" grid.run.out &&
	sanitizer_free grid.run.out && [ ! -e "$TMP/runs/b" ] && ok grid.run_refuses ||
	fail grid.run_refuses "exit $rc: $(head -c 300 grid.run.out)"
finish
