#!/usr/bin/env bash
# intruders.sh - several intruders (docs/model.md, "Several intruders"). Known answers: a
# particle file's intruders thrown upward in free flight (no contact, no drive) follow
# y0 + v t - g t^2 / 2 in their height series (/particles/intruders), rise one
# diameter 2R at t = (v - sqrt(v^2 - 4 g R)) / g, each found within a step or two of it, one
# too slow never rises (censored at the end), and the summaries (number risen, first,
# median, last) follow; the first in the file keeps the single intruder's records. A
# generated bed's n_intruders stand in a row at one height or in a column at the centre;
# a row too crowded is refused naming its keys; one intruder's run file has none of the
# new records; a checkpoint resumes them; a campaign's runs hold the summaries.
# tier: slow: a run of several intruders stopped and resumed, and a campaign
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1

# four intruders of R 1 at 200 cm, thrown up at 150, 0, 100 and 120 cm/s; four wall disks
printf '%s\n' '10 200 1 intruder 0 150 0' '30 200 1 intruder 0 0 0' '50 200 1 intruder 0 100 0' \
	'70 200 1 intruder 0 120 0' '0 0 1 wall' '80 0 1 wall' '0 400 1 wall' '80 400 1 wall' >fly.txt
shake_run fly.log particles=fly.txt settle=no amplitude=0 duration=0.5 snapshots=no traj_rate=100 progress=no \
	output=fly.h5 || fail fly.run "exit $?: $(tail -n 2 fly.log)"
# every intruder's height series (/particles/intruders, 100 Hz): y = 200 + v t - g t^2 / 2
paste <(h5vals fly.h5 /particles/intruders/position/time) <(h5vals fly.h5 /particles/intruders/position/value | paste - - - - - - - -) |
	awk 'BEGIN { split("150 0 100 120", v, " ") }
		{ for (k = 1; k <= 4; k++) { w = 200 + v[k] * $1 - 981 * $1 * $1 / 2; d = ($(2 * k + 1) - w) / w
			d = d < 0 ? -d : d; m = d > m ? d : m; if ($(2 * k) != 20 * k - 10) bad = 1 } n++ }
		END { exit !(n == 51 && m < 1e-9 && !bad) }' && [ "$(h5vals fly.h5 /particles/intruders/id | tr '\n' ' ')" = "0 1 2 3 " ] &&
	ok free_flight.heights || fail free_flight.heights "$(h5vals fly.h5 /particles/intruders/position/value | head -n 16 | tr '\n' ' ')"
rise() { awk -v v="$1" 'BEGIN { printf "%.17g", (v - sqrt(v * v - 4 * 981)) / 981 }'; }
t150=$(rise 150) t100=$(rise 100) t120=$(rise 120)
# near A B : within two steps (1e-4 s) of each other
near() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; exit !(a != "" && d < 1e-4 && d > -1e-4) }'; }
w=($(h5vals fly.h5 /intruders/waiting_time)) r=$(h5vals fly.h5 /intruders/risen | tr '\n' ' ')
[ "$r" = "1 0 1 1 " ] && near "${w[0]}" "$t150" && near "${w[2]}" "$t100" && near "${w[3]}" "$t120" &&
	near "${w[1]}" 0.5 && ok free_flight.each || fail free_flight.each "risen $r, waiting ${w[*]}, want $t150 0.5 $t100 $t120"
[ "$(attr fly.h5 /intruders)" = 4 ] && [ "$(attr fly.h5 /intruders_risen)" = 3 ] &&
	near "$(attr fly.h5 /rise_first)" "$t150" && near "$(attr fly.h5 /rise_last)" "$t100" &&
	near "$(attr fly.h5 /rise_median)" "$(awk -v a="$t120" -v b="$t100" 'BEGIN { print (a + b) / 2 }')" &&
	ok free_flight.summaries ||
	fail free_flight.summaries "$(attr fly.h5 /intruders) $(attr fly.h5 /intruders_risen) first $(attr fly.h5 /rise_first) median $(attr fly.h5 /rise_median) last $(attr fly.h5 /rise_last)"
# (the median of four, the unrisen last: the mean of the second and third, t120 and t100)
# the first in the file is the single intruder's records
[ "$(attr fly.h5 /risen)" = 1 ] && near "$(attr fly.h5 /waiting_time)" "$t150" && ok free_flight.first ||
	fail free_flight.first "risen $(attr fly.h5 /risen), waiting_time $(attr fly.h5 /waiting_time)"
# the median needs more than half risen: two of four is none
awk 'NR == 3 || NR == 4 { $6 = 0 } 1' fly.txt >slow.txt
shake_run slow.log particles=slow.txt settle=no amplitude=0 duration=0.5 snapshots=no traj_rate=0 progress=no output=slow.h5
[ $? = 0 ] && [ "$(attr slow.h5 /intruders_risen)" = 1 ] && [ -z "$(attr slow.h5 /rise_median)" ] &&
	near "$(attr slow.h5 /rise_first)" "$t150" && ok free_flight.median_undefined ||
	fail free_flight.median_undefined "risen $(attr slow.h5 /intruders_risen), median '$(attr slow.h5 /rise_median)'"

# one intruder: none of the new records
awk 'NR != 2 && NR != 3 && NR != 4' fly.txt >one.txt
shake_run one.log particles=one.txt settle=no amplitude=0 duration=0.2 snapshots=no traj_rate=100 progress=no output=one.h5
[ $? = 0 ] && [ -z "$(attr one.h5 /intruders)" ] && [ -z "$(dims one.h5 /intruders/risen)" ] && [ "$(attr one.h5 /risen)" = 1 ] &&
	[ -z "$(dims one.h5 /particles/intruders/position/value)" ] &&
	ok one_intruder.as_before || fail one_intruder.as_before "intruders '$(attr one.h5 /intruders)', risen '$(attr one.h5 /risen)'"

# a generated bed: three intruders in a row at one height, x = W/4, W/2, 3W/4; in a column at W/2
# species FILE: the intruders' x and y at the first snapshot, "x y" a line
species() {
	paste <(h5vals "$1" /particles/bed/species) <(h5vals "$1" /particles/bed/position/value | paste - - | head -n "$(h5vals "$1" /particles/bed/species | wc -l)") |
		awk '$1 == 1 { print $2, $3 }'
}
tiny_bed width=40 duration=0 snapshots=yes traj_rate=0 progress=no settle=no
shake_run row.log "${BEDARGS[@]}" n_intruders=3 output=row.h5 || fail row.run "exit $?: $(tail -n 2 row.log)"
species row.h5 | awk '{ x[NR] = $1; y[NR] = $2 } END { exit !(NR == 3 && x[1] == 10 && x[2] == 20 && x[3] == 30 && y[1] == y[2] && y[2] == y[3]) }' &&
	[ "$(attr row.h5 /intruders)" = 3 ] && ok place.row || fail place.row "$(species row.h5 | tr '\n' ';')"
shake_run col.log "${BEDARGS[@]}" n_intruders=3 intruder_place=column output=col.h5 || fail col.run "exit $?: $(tail -n 2 col.log)"
species col.h5 | awk '{ x[NR] = $1; y[NR] = $2 } END { exit !(NR == 3 && x[1] == 20 && x[2] == 20 && x[3] == 20 && y[1] < y[2] && y[2] < y[3] && y[2] - y[1] > 2 * 2 * 1) }' &&
	ok place.column || fail place.column "$(species col.h5 | tr '\n' ';')"
shake_run crowd.log "${BEDARGS[@]}" n_intruders=6 output=none
[ $? = 1 ] && contains crowd.log "n_intruders" && contains crowd.log "intruder_place" && contains crowd.log "width" &&
	ok place.row_crowded_refused || fail place.row_crowded_refused "$(head -c 300 crowd.log)"

# a checkpoint holds every intruder's settled height, rise and waiting time: a run of two
# intruders stopped at a checkpoint (SIGTERM, exit 7) and resumed is the uninterrupted run
tiny_bed n_grains=150 width=24 duration=2.5 "${GENTLE[@]}" traj_rate=200 snapshots=no progress=no \
	checkpoint_every=0.125 n_intruders=2 intruder_place=column
shake_run full.log "${BEDARGS[@]}" output=full.h5 || fail restart.run "exit $?: $(tail -n 2 full.log)"
term_at_checkpoint term.log "$TMP/cut.h5" "${BEDARGS[@]}"
rc=$?
shake_run again.log "${BEDARGS[@]}" output=cut.h5
[ "$rc" = 7 ] && [ $? = 0 ] && [ "$(attr cut.h5 /intruders)" = 2 ] && same_output full.h5 cut.h5 output &&
	ok restart.identical || fail restart.identical "TERM exit $rc; $(tail -n 2 again.log)"

# a campaign: the summaries are result columns of its runs (two intruders in a column)
tiny_campaign two 5 'n_intruders = 2' 'intruder_place = column' >two.campaign
"$STUDY" run two.campaign --runs "$TMP/R" --jobs 2 --no-progress >study.log 2>&1 || fail campaign.run "exit $?: $(tail -n 3 study.log)"
rows=$(q R/study.db "SELECT id, intruders, intruders_risen, COALESCE(rise_first, 'null') FROM runs WHERE campaign = 'two'")
n=0 good=0
while IFS='|' read -r id ni nr first; do
	n=$((n + 1))
	h=$(ls R/two/"$id"*.h5 2>/dev/null | head -n 1)
	[ "$ni" = 2 ] && [ -n "$h" ] && [ "$nr" = "$(attr "$h" /intruders_risen)" ] &&
		{ [ "$first" = null ] && [ "$nr" = 0 ] || near "$first" "$(attr "$h" /rise_first)"; } && good=$((good + 1))
done <<<"$rows"
[ "$n" = 4 ] && [ "$good" = 4 ] && ok campaign.runs_columns || fail campaign.runs_columns "$good of $n runs agree: $rows"
finish
