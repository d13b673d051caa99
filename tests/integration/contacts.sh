#!/usr/bin/env bash
# contacts.sh - the contact dump (contact_rate): in a settled bed at rest the walls'
# contacts carry the weight of the mobile disks (the vertical force the walls exert,
# summed from each contact's normal and tangential force and its normal, equals M g to
# 1e-3: measured 1e-6), each frame has as many contacts as the energy series counts at
# the same moment, the datasets carry units, and without contact_rate there is no dump.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1
col() { h5vals "$@"; } # lib.sh
C=/observables/contacts
shake_run r.log n_grains=100 width=20 radius_ratio=2 depth=1 settle_ke=0.01 amplitude=0 duration=0.2 \
	contact_rate=10 energy_rate=10 snapshots=no output=r.h5 || fail run "exit $?: $(tail -n 2 r.log)"
[ "$(col r.h5 $C/count | tr '\n' ' ')" = "$(col r.h5 /observables/energy/contacts/value | tr '\n' ' ')" ] &&
	[ "$(col r.h5 $C/time | wc -l)" = 3 ] && ok frames_match_energy_series ||
	fail frames_match_energy_series "counts $(col r.h5 $C/count | tr '\n' ' ') vs $(col r.h5 /observables/energy/contacts/value | tr '\n' ' ')"
[ "$(attr r.h5 $C/normal_force/unit)" = dyn ] && [ "$(attr r.h5 $C/y_box/unit)" = cm ] && ok units ||
	fail units "normal_force unit '$(attr r.h5 $C/normal_force/unit)'"
paste <(col r.h5 /final/id) <(col r.h5 /final/species) <(col r.h5 /final/mass) >parts.tsv
n0=$(col r.h5 $C/count | head -n 1)
paste <(col r.h5 $C/id_a) <(col r.h5 $C/id_b) <(col r.h5 $C/normal_force) <(col r.h5 $C/tangential_force) \
	<(col r.h5 $C/normal_x) <(col r.h5 $C/normal_y) | head -n "$n0" >f0.tsv
ratio=$(awk 'FNR == NR { kind[$1] = $2; if ($2 != 2) M += $3; next }
	{ fy = $3 * $6 + $4 * $5; if (kind[$2] == 2 && kind[$1] != 2) up += fy; else if (kind[$1] == 2 && kind[$2] != 2) up -= fy }
	END { printf "%.9f", up / (M * 981) }' parts.tsv f0.tsv)
awk -v r="$ratio" 'BEGIN { d = r - 1; d = d < 0 ? -d : d; exit !(d < 1e-3) }' && ok walls_carry_the_weight ||
	fail walls_carry_the_weight "support / weight = $ratio"
# off by default: the run ends well and its file is whole, without the dump
shake_run o.log "${FAST[@]}" duration=0.1 output=o.h5
[ $? = 0 ] && [ -n "$(attr o.h5 /format)" ] && [ -z "$(dims o.h5 $C/time)" ] && ok off_by_default || fail off_by_default "a contact dump without contact_rate"
finish
