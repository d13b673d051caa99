#!/usr/bin/env bash
# stop_rules.sh - a run ends when its question is answered (stop = risen | flux): the
# file says which rule stopped it and when, everything recorded before the stop is
# bit-identical to the same run without the rule, a checkpoint/restart across the stop
# ends bit-identical to an uninterrupted stopped run, a run whose rule never fires is
# the plain run (censored when its intruder never rose), and the rules' preconditions
# are input errors.
# tier: slow: runs long enough for the stop rules to act
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

rows() { h5vals "$@"; }

# a 2x intruder under one row, shaken hard: it rises within a fraction of a second
RISE=("${FAST[@]}" frequency=5 amplitude=2 duration=3 traj_rate=200 snapshots=yes)
shake_run a.log "${RISE[@]}" output=a.h5 || fail risen.plain_run "exit $?: $(tail -n 2 a.log)"
W=$(attr a.h5 /waiting_time)
[ "$(attr a.h5 /risen)" = 1 ] && ok risen.setup_rises || fail risen.setup_rises "the intruder of the test scene did not rise"
shake_run b.log "${RISE[@]}" stop=risen stop_after=0.3 output=b.h5
rc=$?
st=$(attr b.h5 /stop_time) end=$(attr b.h5 /status_time)
[ "$rc" = 0 ] && [ "$(attr b.h5 /status)" = ok ] && [ "$(attr b.h5 /stopped_by)" = risen ] &&
	awk -v s="$st" -v e="$end" -v w="$W" 'BEGIN { exit !(s == e && s > w + 0.3 - 1e-9 && s < w + 0.3 + 1e-4) }' &&
	ok risen.stops_after_the_rise || fail risen.stops_after_the_rise "exit $rc, stopped_by '$(attr b.h5 /stopped_by)', stop_time $st, end $end, waiting_time $W"
# the stopped run's records are the plain run's, to the bit, up to its end
nb=$(h5traj b.h5 | wc -l)
if [ "$nb" -gt 1 ] && cmp -s <(h5traj b.h5) <(h5traj a.h5 | head -n "$nb"); then
	ok risen.trajectory_prefix_identical
else
	fail risen.trajectory_prefix_identical "$nb values; the first rows differ from the plain run's"
fi
P=/particles/bed/position/value V=/particles/bed/velocity/value
ns=$(rows b.h5 $P | wc -l)
[ "$ns" -gt 0 ] && cmp -s <(rows b.h5 $P) <(rows a.h5 $P | head -n "$ns") && cmp -s <(rows b.h5 $V) <(rows a.h5 $V | head -n "$ns") &&
	ok risen.snapshots_prefix_identical || fail risen.snapshots_prefix_identical "snapshots differ ($ns values)"
[ "$(attr b.h5 /risen)" = 1 ] && [ "$(attr b.h5 /waiting_time)" = "$W" ] && ok risen.waiting_time_kept ||
	fail risen.waiting_time_kept "risen $(attr b.h5 /risen), waiting_time $(attr b.h5 /waiting_time) vs $W"

# a checkpoint/restart across the stop ends as the uninterrupted stopped run
LONG=("${RISE[@]}" stop=risen stop_after=2.5 duration=5 checkpoint_every=0.05)
shake_run u.log "${LONG[@]}" output=u.h5 || fail restart.uninterrupted "exit $?"
# interrupted at its first checkpoint: the resumed run crosses the stop
term_at_checkpoint r1.log r.h5 "${LONG[@]}"
rc=$?
if [ $rc = 7 ] && [ -f r.h5.ckpt ]; then
	shake_run r2.log "${LONG[@]}" output=r.h5 restart=yes || fail restart.resume "exit $?: $(tail -n 2 r2.log)"
	same_output u.h5 r.h5 output restart && [ "$(attr r.h5 /stopped_by)" = risen ] && ok restart.across_the_stop_identical ||
		fail restart.across_the_stop_identical "the resumed run differs from the uninterrupted one"
else
	fail restart.setup "exit $rc (want 7: stopped with a checkpoint): $(tail -n 1 r1.log)"
fi

# a rule that never fires: the plain run, censored
shake_run c.log "${FAST[@]}" frequency=2 amplitude=0.2 duration=0.5 stop=risen stop_after=0.1 output=c.h5
rc=$?
[ "$rc" = 0 ] && [ "$(attr c.h5 /stopped_by)" = none ] && [ "$(attr c.h5 /risen)" = 0 ] &&
	awk -v w="$(attr c.h5 /waiting_time)" 'BEGIN { exit !(w == 0.5) }' && ok risen.never_fires_censored ||
	fail risen.never_fires_censored "exit $rc, stopped_by '$(attr c.h5 /stopped_by)', risen $(attr c.h5 /risen), waiting_time $(attr c.h5 /waiting_time)"

# the flux rule: a loose threshold ends the run after the transient and 20 periods
FLUX=("${FAST[@]}" "${GENTLE[@]}" radius_ratio=0 duration=20 flux=yes flux_lines=10 snapshots=no)
shake_run f0.log "${FLUX[@]}" duration=12 output=f0.h5 || fail flux.plain_run "exit $?: $(tail -n 2 f0.log)"
shake_run f.log "${FLUX[@]}" stop=flux stop_skip=2 stop_flux_se=1000 output=f.h5
rc=$?
st=$(attr f.h5 /stop_time)
# at 4 Hz: periods end at 0.25 s steps; 2 s of transient, then 20 periods -> 7 s, and the
# run ends one step after the period that answered
[ "$rc" = 0 ] && [ "$(attr f.h5 /stopped_by)" = flux ] && awk -v s="$st" 'BEGIN { exit !(s > 6.99 && s < 7.01) }' &&
	ok flux.stops_after_transient_and_20_periods || fail flux.stops_after_transient_and_20_periods "exit $rc, stopped_by '$(attr f.h5 /stopped_by)', stop_time $st"
J=/observables/flux/j_top/value
nf=$(rows f.h5 $J | wc -l)
[ "$nf" -gt 0 ] && cmp -s <(rows f.h5 $J) <(rows f0.h5 $J | head -n "$nf") &&
	ok flux.prefix_identical || fail flux.prefix_identical "the flux records differ from the plain run's ($nf values)"
# a threshold no run of this length meets (a bed that convects: its flux varies): it
# runs its duration
shake_run g.log "${FLUX[@]}" amplitude=2 duration=8 stop=flux stop_skip=2 stop_flux_se=1e-9 output=g.h5
[ "$(attr g.h5 /stopped_by)" = none ] && [ "$(attr g.h5 /steps)" = 160000 ] && ok flux.tight_threshold_runs_out ||
	fail flux.tight_threshold_runs_out "stopped_by '$(attr g.h5 /stopped_by)', steps $(attr g.h5 /steps)"
# with a class threshold the same bed ends once its mean is 3 SE clear of it: far below a
# threshold of 1e5, at the 20th period (7 s) whatever stop_flux_se asks; a threshold
# its interval straddles (its mean flux is within 3 SE of 0.001 over the whole run)
# keeps it running to its duration
shake_run h.log "${FLUX[@]}" amplitude=2 duration=8 stop=flux stop_skip=2 stop_flux_se=1e-9 stop_flux_threshold=1e5 output=h.h5
st=$(attr h.h5 /stop_time)
[ "$(attr h.h5 /stopped_by)" = flux ] && awk -v s="$st" 'BEGIN { exit !(s > 6.99 && s < 7.01) }' &&
	ok flux.class_clear_of_threshold_stops || fail flux.class_clear_of_threshold_stops "stopped_by '$(attr h.h5 /stopped_by)', stop_time $st"
shake_run k.log "${FLUX[@]}" amplitude=2 duration=8 stop=flux stop_skip=2 stop_flux_se=1e3 stop_flux_threshold=0.001 output=k.h5
[ "$(attr k.h5 /stopped_by)" = none ] && [ "$(attr k.h5 /steps)" = 160000 ] && ok flux.near_threshold_runs_on ||
	fail flux.near_threshold_runs_on "stopped_by '$(attr k.h5 /stopped_by)', steps $(attr k.h5 /steps)"

# preconditions are input errors
shake_run p1.log "${FAST[@]}" stop=flux output=p1.h5
[ $? = 1 ] && grep -q 'stop = flux needs flux = yes' p1.log && ok input.flux_rule_needs_flux || fail input.flux_rule_needs_flux "$(tail -n 1 p1.log)"
shake_run p2.log "${FAST[@]}" radius_ratio=0 stop=risen output=p2.h5
[ $? = 1 ] && grep -q 'stop = risen needs an intruder' p2.log && ok input.risen_rule_needs_intruder || fail input.risen_rule_needs_intruder "$(tail -n 1 p2.log)"
finish
