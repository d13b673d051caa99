#!/usr/bin/env bash
# energy.sh - the energy series (energy_rate): without damping, friction or drive, the
# total energy (kinetic, elastic and potential m g y) of a bed of falling, colliding
# grains is conserved to 1e-3 (gear5 at 5e-5 s resolves a contact in ~60 steps; the
# drift measured is 7e-5); with the paper's damping and a drive the series has one row
# per sample with units, its largest overlap never exceeds the run's record, a restart
# gives the same series to the bit, and without energy_rate there is no series.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1
# a dataset's values, one per line (its own DATA block, not its attributes')
col() { h5vals "$@"; } # lib.sh
E=/observables/energy

shake_run c.log n_grains=40 width=16 radius_ratio=0 settle=no amplitude=0 gamma_n=0 gamma_s=0 duration=1 \
	energy_rate=50 snapshots=no output=c.h5 progress=no || fail conservation.run "exit $?: $(tail -n 2 c.log)"
M=$(col c.h5 /particles/bed/mass | head -n 40 | awk '{ s += $1 } END { printf "%.17g", s }')
drift=$(paste <(col c.h5 $E/kinetic_translational/value) <(col c.h5 $E/kinetic_rotational/value) <(col c.h5 $E/elastic/value) \
	<(col c.h5 $E/com_height_box/value) | awk -v M="$M" '{ e = $1 + $2 + $3 + M * 981 * $4; if (NR == 1) e0 = e;
		d = (e - e0) / e0; d = d < 0 ? -d : d; w = d > w ? d : w; n++ } END { if (n < 51) print "rows", n; else print w }')
awk -v d="$drift" 'BEGIN { exit !(d + 0 == d && d < 1e-3) }' && ok conservation.total_energy ||
	fail conservation.total_energy "largest relative change of the total energy: $drift"
# the grains fell and collided: kinetic and elastic energy were not zero all along
awk 'BEGIN { m = 0 } { m = $1 > m ? $1 : m } END { exit !(m > 0) }' <(col c.h5 $E/elastic/value) &&
	ok conservation.contacts_happened || fail conservation.contacts_happened "no elastic energy at any sample"

shake_run d.log "${FAST[@]}" "${GENTLE[@]}" duration=1 energy_rate=20 checkpoint_every=0.3 output=d.h5 ||
	fail driven.run "exit $?: $(tail -n 2 d.log)"
n=$(col d.h5 $E/elastic/time | wc -l)
[ "$n" = 21 ] && [ "$(attr d.h5 $E/elastic/value/unit)" = erg ] && [ "$(attr d.h5 $E/com_height_box/value/unit)" = cm ] &&
	ok driven.rows_and_units || fail driven.rows_and_units "$n rows, units '$(attr d.h5 $E/elastic/value/unit)'"
rec=$(attr d.h5 /overlap_max)
awk -v r="$rec" 'BEGIN { m = 0 } { m = $1 > m ? $1 : m } END { exit !(m > 0 && m <= r / 0.99 + 1e-12) }' <(col d.h5 $E/max_overlap/value) &&
	ok driven.sample_overlap_within_record || fail driven.sample_overlap_within_record "record $rec"
LONG=("${FAST[@]}" "${GENTLE[@]}" duration=8 energy_rate=20 checkpoint_every=0.2)
shake_run u.log "${LONG[@]}" output=u.h5 || fail restart.uninterrupted "exit $?"
# interrupted once its first checkpoint is written, well before its end
term_at_checkpoint r1.log r.h5 "${LONG[@]}"
rc=$?
if [ $rc = 7 ] && [ -f r.h5.ckpt ]; then
	shake_run r2.log "${LONG[@]}" output=r.h5 restart=yes
	same_output u.h5 r.h5 output restart && ok restart.same_series || fail restart.same_series "the resumed run differs"
else
	fail restart.setup "exit $rc (want 7: stopped with a checkpoint): $(tail -n 1 r1.log)"
fi
# off by default: the run ends well and its file is whole, without the series
shake_run o.log "${FAST[@]}" duration=0.1 output=o.h5
[ $? = 0 ] && [ -n "$(attr o.h5 /format)" ] && [ -z "$(dims o.h5 $E/elastic/time)" ] && ok off_by_default || fail off_by_default "an energy series without energy_rate"
finish
