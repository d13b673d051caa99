#!/usr/bin/env bash
# sliding.sh - the fraction of contacts at the Coulomb limit per drive period
# (sliding_samples; docs/model.md, "Sliding contacts"), on a settled bed at rest (no drive
# amplitude): with the paper's law every contact holds below mu |F_N| (its slips are
# tiny against mu g / gamma_S), so every period's fraction is 0, under the shear spring
# too; with mu = 0 the limit is zero and every contact is at it: 1. The run's mean,
# sliding_mean, is the mean of the periods; without the key there is neither series
# nor summary.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1
G=/observables/sliding
BED=("${FAST[@]}" width=15 radius_ratio=0 settle_ke=0.01 amplitude=0 frequency=5 duration=0.8 snapshots=no
	traj_rate=0 progress=no)
# run ID WANT args... : every period's fraction is WANT, 4 periods, the mean WANT
run() {
	local id=$1 want=$2
	shift 2
	shake_run "$id.log" "${BED[@]}" sliding_samples=4 "$@" output="$id.h5" || { fail "$id.run" "exit $?: $(tail -n 2 "$id.log")"; return; }
	local vals
	vals=$(h5vals "$id.h5" $G/sliding_fraction/value | tr '\n' ' ')
	[ "$vals" = "$want $want $want $want " ] && ok "$id.periods" || fail "$id.periods" "fractions '$vals', want 4 x $want"
	[ "$(attr "$id.h5" /sliding_mean)" = "$want" ] && [ "$(attr "$id.h5" $G/samples_per_period)" = 4 ] &&
		[ "$(attr "$id.h5" $G/sliding_fraction/value/unit)" = 1 ] && ok "$id.summary" ||
		fail "$id.summary" "sliding_mean '$(attr "$id.h5" /sliding_mean)', samples '$(attr "$id.h5" $G/samples_per_period)'"
}
run rest 0
run rest_spring 0 tangential=spring
run frictionless 1 mu=0

# off by default: a whole file without the series or the summary
shake_run o.log "${BED[@]}" duration=0.2 output=o.h5
[ $? = 0 ] && [ -n "$(attr o.h5 /format)" ] && [ -z "$(dims o.h5 $G/sliding_fraction/value)" ] &&
	[ -z "$(attr o.h5 /sliding_mean)" ] && ok off_by_default || fail off_by_default "a series or a summary without sliding_samples"
finish
