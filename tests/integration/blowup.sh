#!/usr/bin/env bash
# blowup.sh - a run that goes wrong numerically is stopped, not written as if fine:
# exit code 3 (NaN), 4 (overlap) or 5 (left the box), a message with the simulated time
# and step, an output file whose status says so (status_time, status_step) and that
# holds no NaN or Inf. Cases: too large dt while settling and while shaking, a NaN
# from an unstable drag without walls, a grain placed outside the box.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

# no_nonfinite FILE : no nan/inf number anywhere in the dump (attributes and datasets;
# quoted strings such as the status name "nan" are not numbers)
no_nonfinite() {
	! h5dump -m %.17g "$1" | tail -n +2 | sed 's/"[^"]*"//g' | grep -Eiq '(^|[^a-z_])-?(nan|inf)([^a-z_]|$)'
}

# expect_blowup ID CODES DT args... : CODES like "3 4 5"; DT is the run's dt
expect_blowup() {
	local id=$1 codes=$2 dt=$3
	shift 3
	local out="$TMP/$id.h5" log="$TMP/$id.log"
	shake_run "$log" "$@" dt="$dt" dt_guard=off output="$out"
	local rc=$?
	if [[ " $codes " != *" $rc "* ]]; then
		fail "$id.code" "exit $rc, expected one of $codes: $(head -c 300 "$log")"
		return
	fi
	ok "$id.code"
	local msg t step
	msg=$(grep -E 't = [0-9.e+-]+ s, step [0-9]+' "$log" | head -n 1)
	t=$(sed -nE 's/.*t = ([0-9.e+-]+) s, step ([0-9]+).*/\1/p' <<<"$msg")
	step=$(sed -nE 's/.*t = ([0-9.e+-]+) s, step ([0-9]+).*/\2/p' <<<"$msg")
	if [ -n "$msg" ]; then ok "$id.message_time_step"; else
		fail "$id.message_time_step" "stderr does not give 't = T s, step N': $(head -c 300 "$log")"; fi
	if [ ! -s "$out" ]; then
		fail "$id.output" "no output file $out after the failure"
		return
	fi
	ok "$id.output"
	local st sc stime sstep
	st=$(attr "$out" /status) sc=$(attr "$out" /exit_code) stime=$(attr "$out" /status_time) sstep=$(attr "$out" /status_step)
	[ -n "$st" ] && [ "$st" != ok ] && [ "$sc" = "$rc" ] && ok "$id.status" ||
		fail "$id.status" "status '$st', exit_code '$sc' (process exit $rc)"
	if [ -n "$stime" ] && [ -n "$sstep" ] && [ "$sstep" = "$step" ] &&
		awk -v a="$stime" -v b="$t" -v n="$sstep" -v dt="$dt" 'BEGIN {
			d = a - n * dt; if (d < 0) d = -d; e = a - b; if (e < 0) e = -e
			exit !(n > 0 && d <= 1e-9 * (1 + a) && e <= 1e-6 * (1 + a)) }'; then
		ok "$id.status_time_step"
	else
		fail "$id.status_time_step" "status_time '$stime', status_step '$sstep' vs message t = $t, step $step (dt $dt)"
	fi
	check "$id.no_nan" "NaN or Inf in $out" no_nonfinite "$out"
	# an overlap message must report the overlap that stopped the run (> max_overlap)
	if [ "$rc" -eq 4 ]; then
		local frac mo
		frac=$(sed -nE 's/.*overlap of disks [0-9]+ and [0-9]+ is ([0-9.]+) of the smaller radius \(max_overlap ([0-9.e+-]+)\).*/\1 \2/p' "$log" | head -n 1)
		if [ -n "$frac" ] && awk -v f="${frac% *}" -v m="${frac#* }" 'BEGIN { exit !(f + 0 > m + 0) }'; then
			ok "$id.overlap_reported"
		else
			fail "$id.overlap_reported" "message reports an overlap not above max_overlap: $(grep -o 'overlap of .*)' "$log" | head -n 1)"
		fi
	fi
}

# 1. settling with a time step 40x too large
expect_blowup settle_dt "3 4 5" 0.002 "${FAST[@]}"

# 2. a settled bed shaken with dt = 1e-3 (20x too large)
shake_run "$TMP/prep.log" "${FAST[@]}" duration=0 write_particles="$TMP/bed.txt" output="$TMP/prep.h5"
rc=$?
if [ "$rc" -ne 0 ] || [ ! -s bed.txt ]; then
	fail prep "exit $rc: $(head -c 300 "$TMP/prep.log")"
	finish
fi
expect_blowup shake_dt "3 4 5" 0.001 particles="$TMP/bed.txt" settle=no duration=1 "${GENTLE[@]}" traj_rate=200 progress=no
# the control: the same bed with the paper's dt runs fine
shake_run "$TMP/ctl.log" particles="$TMP/bed.txt" settle=no duration=0.2 "${GENTLE[@]}" output="$TMP/ctl.h5"
rc=$?
[ "$rc" -eq 0 ] && [ "$(attr ctl.h5 /status)" = ok ] && no_nonfinite ctl.h5 && ok control.dt_5e-5 ||
	fail control.dt_5e-5 "exit $rc, status $(attr ctl.h5 /status)"

# 3. NaN: no walls (nothing to leave), an explicit drag of 1e6/s with dt = 1e-2 makes
#    the velocity grow by 1e4 per step until it overflows
printf '10 5 1 grain\n14 5 2 intruder\n' >nowall.txt
expect_blowup nan 3 0.01 particles=nowall.txt settle=yes settle_drag=1e6 settle_min=10 settle_max=20 duration=0.1
contains nan.log "non-finite" && ok nan.message || fail nan.message "no 'non-finite' in: $(head -c 200 nan.log)"

# 4. a grain outside the box (left of the left wall) and one below the bottom
{ cat bed.txt; echo "-30 5 1 grain 0 0 0"; } >outside.txt
expect_blowup outside_x 5 5e-5 particles=outside.txt settle=no duration=0.1 "${GENTLE[@]}"
contains outside_x.log "left the box" && ok outside_x.message || fail outside_x.message "no 'left the box' in: $(head -c 200 outside_x.log)"
{ cat bed.txt; echo "10 -20 1 grain 0 0 0"; } >below.txt
expect_blowup below 5 5e-5 particles=below.txt settle=no duration=0.1 "${GENTLE[@]}"
finish
