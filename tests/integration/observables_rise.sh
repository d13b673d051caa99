#!/usr/bin/env bash
# observables_rise.sh - the intruder's rise and settled depth against independent
# computations from the run's own files: waiting_time against the first crossing in
# /particles/intruder, intruder_settled_depth and surface_height against the settled
# particle file, and the direction in which the depth key moves the intruder.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

# within A B TOL : |A - B| <= TOL (all numbers, compared in awk)
within() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a != "" && b != "" && d <= t) }'; }

# A scene where a big intruder really rises within a few seconds, cheaply: 100 grains in a
# 24 cm box (about 7 rows), an intruder of radius 3 cm (radius_ratio 3) with one row
# beneath it and ~12.7 cm of grains above its centre, shaken at Gamma = A (2 pi f)^2 / g
# = 1.29. The bed leaves the floor every period, but its flight lifts the intruder only
# ~2 cm, a third of the rise threshold (one diameter, 6 cm): it climbs by steps and
# crosses the threshold after ~3.6 s of 4 (about 1 s of CPU in the sanitizer build).
# Weaker shaking (Gamma <= 1) or narrower boxes did not rise within 5 s; stronger shaking
# (Gamma 1.5 in a 60-grain bed) crossed it in the bed's first flight, which is not a rise.
tiny_bed n_grains=100 width=24 radius_ratio=3
RISE=("${BEDARGS[@]}"
	frequency=4 amplitude=2 duration=4 traj_rate=200 progress=no)

shake_run rise.log "${RISE[@]}" write_particles=rise.txt output=rise.h5 ||
	fail rise.run "exit $?: $(head -c 200 rise.log)"
[ "$(attr rise.h5 /status)" = ok ] && ok rise.status_ok || fail rise.status_ok "status '$(attr rise.h5 /status)'"

wt=$(attr rise.h5 /waiting_time)
y0=$(attr rise.h5 /intruder_settled_y)
dur=$(h5param rise.h5 duration)
rate=$(h5param rise.h5 traj_rate)
[ "$(attr rise.h5 /risen)" = 1 ] && awk -v w="$wt" -v d="$dur" 'BEGIN { exit !(w > 0 && w < d) }' &&
	ok rise.risen || fail rise.risen "risen '$(attr rise.h5 /risen)' waiting_time '$wt' (duration $dur): the scene no longer rises"

"$REPO/scripts/traj.sh" rise.h5 >traj.tsv 2>traj.err || fail rise.trajectory "$(head -c 200 traj.err)"

# The tolerance below is one sample interval, so check that the samples are that far
# apart (1/traj_rate, to within one time step of the integer schedule).
awk -v rate="$rate" -v dt="$(h5param rise.h5 dt)" '!/^#/ { if (n++ && ($1 - p > 1 / rate + dt || $1 - p < 1 / rate - dt)) bad = 1; p = $1 }
	END { exit !(n > 1 && !bad) }' traj.tsv && ok rise.trajectory_sampled_at_traj_rate ||
	fail rise.trajectory_sampled_at_traj_rate "sample spacing is not 1/traj_rate = $(awk -v r="$rate" 'BEGIN { print 1 / r }') s"

# At t = 0 the box is at its rest position (y_box(0) = 0): the first sample is the settled height.
t0y=$(awk '!/^#/ { printf "%.17g %.17g\n", $1, $3; exit }' traj.tsv)
set -- $t0y
[ "${1:-x}" = 0 ] && within "${2:-}" "$y0" 1e-12 && ok rise.trajectory_starts_at_settled_y ||
	fail rise.trajectory_starts_at_settled_y "first sample '$t0y', intruder_settled_y $y0"

# waiting_time (docs/model.md, "Waiting time"): the first time the intruder's centre is more than one intruder
# diameter above its settled height. Computed here from the trajectory, independently of
# the engine: the diameter from the scene's parameters (the intruder's radius is
# radius_ratio times the mean grain radius (r_min + r_max) / 2), the height relative to
# the box. The engine measures the rise in the box (its state is in the box frame, and the
# settled height is a height above the box floor, taken with the box at rest), while the
# trajectory is in the lab frame, so y_box(t) = A sin(2 pi f t) is taken off each sample;
# in this scene the raw lab-frame height crosses the threshold ~0.3 s before the rise
# relative to the box, so this check also pins the frame.
# Tolerance: the engine tests the rise on every time step, the trajectory holds one sample
# per 1/traj_rate, so the first sample above the threshold comes up to one sample
# interval after the step at which the engine saw the crossing (and the engine tests the
# predicted position of a step, the trajectory the corrected one: the same sample up to
# rounding, far inside the interval).
first=$(awk -v y0="$y0" -v rr="$(h5param rise.h5 radius_ratio)" -v rmin="$(h5param rise.h5 r_min)" \
	-v rmax="$(h5param rise.h5 r_max)" -v A="$(h5param rise.h5 amplitude)" -v f="$(h5param rise.h5 frequency)" '
	BEGIN { pi = atan2(0, -1); dia = 2 * rr * 0.5 * (rmin + rmax) }
	!/^#/ && $3 - A * sin(2 * pi * f * $1) - y0 > dia { printf "%.17g\n", $1; exit }' traj.tsv)
[ -n "$first" ] && within "$wt" "$first" "$(awk -v r="$rate" 'BEGIN { printf "%.17g", 1 / r }')" &&
	ok rise.waiting_time_is_first_crossing_in_trajectory ||
	fail rise.waiting_time_is_first_crossing_in_trajectory "waiting_time $wt, first trajectory sample more than one diameter above the settled height (box frame): '${first:-none}', tolerance 1/traj_rate"

# The engine tests the rise on every step, also on the steps after which nobody reads
# the state: on those, in the AVX-512 build, the positions live in the force kernel's
# records only (core/run/step.c, watch_rise, reads them with kernel_y). Recording every step makes every step an
# ordinary one; the physics is the same to the bit, so the waiting time must be too.
shake_run rise_all.log "${RISE[@]}" traj_rate=20000 output=rise_all.h5 ||
	fail rise.every_step.run "exit $?: $(head -c 200 rise_all.log)"
wt_all=$(attr rise_all.h5 /waiting_time)
[ -n "$wt" ] && [ "$wt_all" = "$wt" ] && ok rise.waiting_time_same_when_every_step_is_recorded ||
	fail rise.waiting_time_same_when_every_step_is_recorded "waiting_time $wt with traj_rate $rate, '$wt_all' with every step recorded"

# ---- the settled depth ----
# h5out.c: intruder_settled_depth = surface_height - intruder_settled_y (the intruder
# centre's depth below the free surface after settling, t = 0 of shaking)
sh=$(attr rise.h5 /surface_height)
sd=$(attr rise.h5 /intruder_settled_depth)
within "$sd" "$(awk -v s="$sh" -v y="$y0" 'BEGIN { printf "%.17g", s - y }')" 1e-12 &&
	ok settled.depth_is_surface_minus_intruder_y ||
	fail settled.depth_is_surface_minus_intruder_y "intruder_settled_depth $sd, surface_height $sh, intruder_settled_y $y0"

# Both from the settled state written by write_particles (x y r kind, %.17g): the
# intruder's y, and the free surface by its definition (core/run/prepare.c, surface_height): over the grains,
# columns one mean grain diameter wide between the leftmost and rightmost grain centre,
# the highest grain top (y + r) in each, and the median of the columns' tops (the upper
# one of the two middle ones for an even count).
iy=$(awk '$4 == "intruder" { printf "%.17g", $2; exit }' rise.txt)
within "$iy" "$y0" 0 && ok settled.intruder_y_is_settled_state ||
	fail settled.intruder_y_is_settled_state "intruder y in the settled particle file '$iy', intruder_settled_y $y0"
surf=$(awk '$4 == "grain" { n++; x[n] = $1; t[n] = $2 + $3; rs += $3
		if (n == 1 || $1 < xmin) xmin = $1; if (n == 1 || $1 > xmax) xmax = $1 }
	END {
		nc = int((xmax - xmin) / (2 * (rs / n))); if (nc < 1) nc = 1
		for (i = 1; i <= n; i++) {
			c = int((x[i] - xmin) / (xmax - xmin + 1e-12) * nc); if (c >= nc) c = nc - 1
			if (!(c in top) || t[i] > top[c]) top[c] = t[i]
		}
		k = 0; for (c = 0; c < nc; c++) if (c in top) v[k++] = top[c]
		for (i = 1; i < k; i++) for (j = i; j > 0 && v[j - 1] > v[j]; j--) { s = v[j]; v[j] = v[j - 1]; v[j - 1] = s }
		printf "%.17g", v[int(k / 2)]
	}' rise.txt)
within "$sh" "$surf" 1e-9 && ok settled.surface_height_from_settled_state ||
	fail settled.surface_height_from_settled_state "surface_height $sh, recomputed from the settled particles '$surf'"

# The depth key is the number of rows of small grains placed beneath the intruder
# (docs/model.md "Preparation", --help; 0 = on the bottom wall). With the same grains, more rows beneath
# put the intruder higher and leave fewer grains above it: intruder_settled_y grows and
# intruder_settled_depth shrinks as depth grows. Settle only (duration = 0).
prev_y='' prev_d='' prev_b='' mono_y=1 mono_d=1 mono_b=1 runs=0 b0=''
for d in 0 2 4 6; do
	shake_run depth$d.log "${RISE[@]}" depth=$d duration=0 write_particles=depth$d.txt output=depth$d.h5 ||
		{ fail "settled.depth$d.run" "exit $?: $(head -c 200 depth$d.log)"; continue; }
	runs=$((runs + 1))
	y=$(attr depth$d.h5 /intruder_settled_y)
	dd=$(attr depth$d.h5 /intruder_settled_depth)
	# grains wholly beneath the intruder's bottom within its width: the rows beneath it
	b=$(awk '$4 == "intruder" { xi = $1; yi = $2; ri = $3 } $4 == "grain" { n++; x[n] = $1; y[n] = $2 }
		END { for (i = 1; i <= n; i++) if (y[i] < yi - ri && (x[i] - xi) ^ 2 < ri ^ 2) c++; print c + 0 }' depth$d.txt)
	[ $d = 0 ] && b0=$b
	if [ -n "$prev_y" ]; then
		awk -v a="$prev_y" -v b="$y" 'BEGIN { exit !(b > a) }' || mono_y=0
		awk -v a="$prev_d" -v b="$dd" 'BEGIN { exit !(b < a) }' || mono_d=0
		[ "$b" -gt "$prev_b" ] || mono_b=0
	fi
	echo "# depth=$d intruder_settled_y $y intruder_settled_depth $dd grains beneath $b"
	prev_y=$y prev_d=$dd prev_b=$b
done
[ $runs = 4 ] && [ $mono_y = 1 ] && ok settled.intruder_y_grows_with_depth_key ||
	fail settled.intruder_y_grows_with_depth_key "intruder_settled_y not increasing over depth = 0, 2, 4, 6 (see the # lines)"
[ $runs = 4 ] && [ $mono_d = 1 ] && ok settled.depth_below_surface_shrinks_with_depth_key ||
	fail settled.depth_below_surface_shrinks_with_depth_key "intruder_settled_depth not decreasing over depth = 0, 2, 4, 6 (see the # lines)"
[ $runs = 4 ] && [ "$b0" = 0 ] && [ $mono_b = 1 ] && ok settled.depth_key_is_rows_beneath ||
	fail settled.depth_key_is_rows_beneath "grains beneath the intruder: '$b0' at depth 0 (want 0), increasing with depth: $mono_b"
finish
