#!/usr/bin/env bash
# bed_height.sh - the bed's centre-of-mass height per drive period (bed_height_samples):
# one grain dropped from rest in free fall (no contact, no drive) is at
# y0 - g t^2 / 2 at every sample, so each period's mean over its samples at
# t = (pN + k) / (N f), k = 1..N, is known to rounding, and so is the run's mean of the
# periods; the same grain thrown upward is higher by vy t, so the comparison can fail;
# a settled bed holds its height period after period; without the key there is
# neither series nor summary.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1
G=/observables/bed_height
# a grain at (10, 500) at rest, far above a box of four wall disks
printf '10 500 1 grain 0 0 0\n0 0 1 wall\n20 0 1 wall\n0 600 1 wall\n20 600 1 wall\n' >fall.txt
shake_run f.log particles=fall.txt settle=no amplitude=0 frequency=5 duration=0.8 bed_height_samples=8 \
	snapshots=no traj_rate=0 progress=no output=f.h5 || fail free_fall.run "exit $?: $(tail -n 2 f.log)"
# want VY: the analytic period means of a grain thrown at VY cm/s, one a line
want() {
	awk -v vy="$1" 'BEGIN { for (p = 0; p < 4; p++) { s = 0
		for (k = 1; k <= 8; k++) { t = (p * 8 + k) / 40; s += 500 + vy * t - 981 * t * t / 2 }
		printf "%.17g\n", s / 8 } }'
}
# worst A B: the largest relative difference between two columns of numbers
worst() { paste "$1" "$2" | awk '{ d = ($1 - $2) / $2; d = d < 0 ? -d : d; w = d > w ? d : w; n++ } END { print n == 4 ? w : "periods " n }'; }
h5vals f.h5 $G/com_height_box/value >f.got
want 0 >f.want
w=$(worst f.got f.want)
awk -v w="$w" 'BEGIN { exit !(w + 0 == w && w < 1e-9) }' && ok free_fall.analytic ||
	fail free_fall.analytic "largest relative error against the analytic period means: $w"
[ "$(h5vals f.h5 $G/com_height_box/time | awk '{ printf "%.9f ", $1 }')" = "0.200000000 0.400000000 0.600000000 0.800000000 " ] &&
	ok free_fall.period_ends || fail free_fall.period_ends "times $(h5vals f.h5 $G/com_height_box/time | tr '\n' ' ')"
[ "$(attr f.h5 $G/com_height_box/value/unit)" = cm ] && [ "$(h5vals f.h5 $G/frequency/value | sort -u)" = 5 ] &&
	[ "$(attr f.h5 $G/samples_per_period)" = 8 ] && ok free_fall.unit_and_frequency ||
	fail free_fall.unit_and_frequency "unit '$(attr f.h5 $G/com_height_box/value/unit)', samples $(attr f.h5 $G/samples_per_period)"
mean=$(awk '{ s += $1; n++ } END { printf "%.17g", s / n }' f.want)
awk -v a="$(attr f.h5 /bed_height_mean)" -v b="$mean" 'BEGIN { d = (a - b) / b; exit !(a != "" && d < 1e-9 && d > -1e-9) }' &&
	ok free_fall.run_mean || fail free_fall.run_mean "bed_height_mean $(attr f.h5 /bed_height_mean), analytic $mean"
# the comparison can fail: thrown upward at 50 cm/s, the grain is higher by 50 t
sed 's/ 0 0 0$/ 0 50 0/' fall.txt >up.txt
shake_run u.log particles=up.txt settle=no amplitude=0 frequency=5 duration=0.8 bed_height_samples=8 \
	snapshots=no traj_rate=0 progress=no output=u.h5 || fail thrown.run "exit $?: $(tail -n 2 u.log)"
h5vals u.h5 $G/com_height_box/value >u.got
want 50 >u.want
wu=$(worst u.got u.want) wf=$(worst u.got f.want)
awk -v a="$wu" -v b="$wf" 'BEGIN { exit !(a + 0 == a && a < 1e-9 && b > 1e-3) }' && ok thrown.differs ||
	fail thrown.differs "against its own analytic means $wu, against the dropped grain's $wf"

# a settled bed at rest (no drive amplitude) keeps its centre of mass: every period's
# mean equals the first to well under a grain radius, and lies below the free surface
shake_run b.log "${FAST[@]}" width=15 radius_ratio=0 settle_ke=0.01 amplitude=0 \
	frequency=5 duration=1 bed_height_samples=4 snapshots=no progress=no output=b.h5 ||
	fail settled.run "exit $?: $(tail -n 2 b.log)"
h5vals b.h5 $G/com_height_box/value | awk -v hs="$(attr b.h5 /surface_height)" '
	NR == 1 { h0 = $1 } { d = $1 - h0; d = d < 0 ? -d : d; w = d > w ? d : w; n++ }
	END { exit !(n == 5 && w < 0.01 && h0 > 0 && h0 < hs) }' && ok settled.still ||
	fail settled.still "heights $(h5vals b.h5 $G/com_height_box/value | tr '\n' ' '), surface $(attr b.h5 /surface_height)"

# off by default: the run ends well (a crash would leave no series either) and its file
# is whole, without the series or the summary
shake_run o.log particles=fall.txt settle=no amplitude=0 frequency=5 duration=0.4 snapshots=no progress=no output=o.h5
[ $? = 0 ] && [ -n "$(attr o.h5 /format)" ] && [ -z "$(dims o.h5 $G/com_height_box/value)" ] && [ -z "$(attr o.h5 /bed_height_mean)" ] && ok off_by_default ||
	fail off_by_default "a series or a summary without bed_height_samples"
finish
