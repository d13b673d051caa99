#!/usr/bin/env bash
# stress_quick.sh - the short subset of `make stress` for make check:
# every integrator runs a small shaken bed at twice the paper's dt and stops with a clear
# blow-up error (exit 3/4/5, no NaN in the file) at 40x; a settled bed left without
# vibration for 1e5 steps stays at rest (no heating, no creep) for each integrator;
# overlaps in a settled bed stay below 10 % of the radius; violent driving
# (f = 30 Hz, Gamma = 72), a large intruder, zero damping and zero friction end as a valid
# run or a clear blow-up, never with NaN in the output.
# tier: slow: a short round of the numerical stress tests
. "$(dirname "$0")/lib.sh"
. "$REPO/tests/stress/lib.sh"
cd "$TMP" || exit 1

# the bed: FAST (60 grains, 2x intruder) settled with the default criterion (0.01 erg)
tiny_bed settle_ke=-
shake_run prep.log "${BEDARGS[@]}" duration=0 \
	progress=no write_particles=bed.txt output=prep.h5
rc=$?
if [ "$rc" -ne 0 ] || [ ! -s bed.txt ]; then
	fail stress.prep "exit $rc: $(head -c 300 prep.log)"
	finish
fi
BED=(particles=bed.txt settle=no progress=no)

# valid_or_blowup ID args... : exit 0 with status ok, or exit 3/4/5 with a matching status;
# either way an output file without NaN/Inf
valid_or_blowup() {
	local id=$1
	shift
	shake_run "$id.log" "$@" output="$id.h5"
	local rc=$? st
	st=$(attr "$id.h5" /status)
	case "$rc:$st" in
	0:ok | 3:nan | 4:overlap | 5:left_box) ok "$id.ends_cleanly" ;;
	*) fail "$id.ends_cleanly" "exit $rc status '$st': $(head -c 300 "$id.log")" ;;
	esac
	[ -s "$id.h5" ] && no_nonfinite "$id.h5" && ok "$id.no_nan" || fail "$id.no_nan" "NaN/Inf in (or no) $id.h5"
	echo "# $id: exit $rc ($st)"
}

for ig in gear5 gear4 verlet; do
	# 1. stable at 2x the paper's dt, clear error at 40x (t_c = 3.2 ms: dt = t_c / 1.6)
	shake_run "dt2_$ig.log" "${BED[@]}" "${GENTLE[@]}" integrator=$ig dt=1e-4 duration=0.5 output="dt2_$ig.h5"
	rc=$?
	[ "$rc" -eq 0 ] && no_nonfinite "dt2_$ig.h5" && ok "stress.dt.$ig.stable_at_1e-4" ||
		fail "stress.dt.$ig.stable_at_1e-4" "exit $rc: $(head -c 300 "dt2_$ig.log")"
	shake_run "dt40_$ig.log" "${BED[@]}" "${GENTLE[@]}" integrator=$ig dt=2e-3 dt_guard=off duration=0.5 output="dt40_$ig.h5"
	rc=$?
	[[ " 3 4 5 " == *" $rc "* ]] && [ -s "dt40_$ig.h5" ] && no_nonfinite "dt40_$ig.h5" &&
		ok "stress.dt.$ig.blowup_at_2e-3" ||
		fail "stress.dt.$ig.blowup_at_2e-3" "exit $rc (want 3/4/5, NaN-free file): $(head -c 300 "dt40_$ig.log")"

	# 2. rest: 1e5 steps (5 s) without vibration; snapshots once per second
	shake_run "rest_$ig.log" "${BED[@]}" integrator=$ig amplitude=0 frequency=1 duration=5 \
		traj_rate=10 max_overlap=0.1 output="rest_$ig.h5"
	rc=$?
	if [ "$rc" -ne 0 ]; then
		fail "stress.rest.$ig.runs" "exit $rc: $(head -c 300 "rest_$ig.log")"
		continue
	fi
	ok "stress.rest.$ig.runs" # includes: no overlap above 10 % of the smaller radius
	read -r n ke ybar vmax <<<"$(final_stats "rest_$ig.h5")"
	# the bed settled below 0.01 erg per disk; at rest it must keep losing energy
	awk -v k="$ke" 'BEGIN { exit !(k < 1e-3) }' && ok "stress.rest.$ig.no_heating" ||
		fail "stress.rest.$ig.no_heating" "kinetic energy per disk after 1e5 steps $ke erg >= 1e-3 (settled at < 1e-2)"
	# creep: mean height of the grains between t = 1 s and 5 s, intruder height over 5 s
	read -r y1 y5 <<<"$(snap_mobile_y "rest_$ig.h5" | awk -v n="$n" '
		{ s += $1; c++; if (c == n) { m[k++] = s / n; s = c = 0 } }
		END { printf "%.10g %.10g\n", m[1], m[k - 1] }')"
	awk -v a="$y1" -v b="$y5" 'BEGIN { d = b - a; if (d < 0) d = -d; exit !(d < 1e-3) }' &&
		ok "stress.rest.$ig.no_creep.mean_height" ||
		fail "stress.rest.$ig.no_creep.mean_height" "mean height moved from $y1 to $y5 cm (>= 1e-3 cm) between t = 1 and 5 s"
	read -r dyi <<<"$(intruder_rows "rest_$ig.h5" | awk 'NR % 6 == 3 {
		if (!c++) lo = hi = $1; if ($1 < lo) lo = $1; if ($1 > hi) hi = $1 } END { printf "%.6g\n", hi - lo }')"
	awk -v d="$dyi" 'BEGIN { exit !(d < 1e-2) }' && ok "stress.rest.$ig.no_creep.intruder" ||
		fail "stress.rest.$ig.no_creep.intruder" "the intruder's height varied by $dyi cm (>= 1e-2) at rest"
	echo "# rest $ig: ke/disk $ke erg, mean height $y1 -> $y5 cm, intruder range $dyi cm, max speed $vmax cm/s"
done

# 3. violent and degenerate cases (a fraction of a second each)
valid_or_blowup stress.violent_f30 "${BED[@]}" frequency=30 amplitude=2 duration=0.3 max_overlap=0.9
valid_or_blowup stress.violent_f30_verlet "${BED[@]}" frequency=30 amplitude=2 duration=0.3 integrator=verlet max_overlap=0.9
valid_or_blowup stress.zero_damping "${BED[@]}" "${GENTLE[@]}" gamma_n=0 gamma_s=0 duration=0.5
valid_or_blowup stress.zero_friction "${BED[@]}" "${GENTLE[@]}" mu=0 duration=0.5
tiny_bed n_grains=150 width=40 radius_ratio=8
valid_or_blowup stress.large_intruder "${BEDARGS[@]}" "${GENTLE[@]}" duration=0.3 progress=no
finish
