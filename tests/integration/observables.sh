#!/usr/bin/env bash
# observables.sh - the observables in a run's output: absent when off, present with
# the documented shapes when on; the waiting time's censoring; a ramp's frequencies.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

has() { h5dump -H -g "$2" "$1" >/dev/null 2>&1; }

# off (the default): no group, and no other output changes
shake_run off.log "${FAST[@]}" "${GENTLE[@]}" duration=1 output=off.h5 || fail off.run "$(head -c 200 off.log)"
for g in /observables/flux /observables/field /ring; do
	has off.h5 $g && fail "off.no$g" "$g exists although it was not asked for" || ok "off.no$g"
done

# on: 1 s at 4 Hz = 4 periods -> 4 flux records, field blocks of 2 periods -> 2
shake_run on.log "${FAST[@]}" "${GENTLE[@]}" duration=1 flux=yes flux_lines=20 field=yes field_periods=2 \
	ring=yes ring_every=5 output=on.h5 || fail on.run "$(head -c 200 on.log)"
F=/observables/flux
[ "$(dims on.h5 $F/phi/value)" = "4 20" ] && ok flux.shape || fail flux.shape "$F/phi/value is $(dims on.h5 $F/phi/value)"
[ "$(dims on.h5 $F/heights)" = "20" ] && ok flux.heights || fail flux.heights "$(dims on.h5 $F/heights)"
# H5MD elements: one clock (step, time) shared by the flux series, each period's end (dt 5e-5)
[ "$(h5vals on.h5 $F/phi/time | tr '\n' ' ')" = "$(h5vals on.h5 $F/j_top/time | tr '\n' ' ')" ] &&
	[ "$(h5vals on.h5 $F/phi/step | tr '\n' ' ')" = "5000 10000 15000 20000 " ] && ok flux.clock ||
	fail flux.clock "steps $(h5vals on.h5 $F/phi/step | tr '\n' ' ')"
set -- $(dims on.h5 /observables/field/ux/value)
[ "${1:-}" = 2 ] && [ "${2:-0}" -gt 0 ] && [ "${3:-0}" -gt 0 ] && ok field.shape || fail field.shape "/observables/field/ux/value is $*"
s=$(attr on.h5 /ring/samples)
[ "$s" = 4000 ] && ok ring.samples || fail ring.samples "samples $s, expected 20000 steps / 5"
mf=$(attr on.h5 /ring/mean_force)
awk -v f="$mf" 'BEGIN { exit !(f > 0) }' && ok ring.force_positive || fail ring.force_positive "mean_force $mf"
# the observables do not change the dynamics
h5diff -q off.h5 on.h5 /final /final >/dev/null 2>&1 && ok on.same_dynamics ||
	fail on.same_dynamics "/final differs when observables are on"
# flux records: phi = j_top - j_bot
paste -d' ' <(h5vals on.h5 $F/phi/value) <(h5vals on.h5 $F/j_top/value) <(h5vals on.h5 $F/j_bot/value) |
	awk '{ if ($1 != $2 - $3) bad = 1 } END { exit bad || NR != 80 }' &&
	ok flux.phi_is_top_minus_bot || fail flux.phi_is_top_minus_bot "phi != j_top - j_bot"

# waiting time: not risen in 1 s -> censored at the end
[ "$(attr on.h5 /risen)" = 0 ] && [ "$(attr on.h5 /waiting_time)" = 1 ] && ok waiting.censored ||
	fail waiting.censored "risen $(attr on.h5 /risen) waiting_time $(attr on.h5 /waiting_time)"
# no intruder: no waiting attributes, and the ring needs a centre
shake_run noi.log "${FAST[@]}" "${GENTLE[@]}" radius_ratio=0 ring=yes output=noi.h5
[ $? -eq 1 ] && contains noi.log ring_y && ok ring.needs_centre || fail ring.needs_centre "$(head -c 200 noi.log)"
shake_run noi2.log "${FAST[@]}" "${GENTLE[@]}" radius_ratio=0 ring=yes ring_y=3 output=noi2.h5 ||
	fail noi.run "$(head -c 200 noi2.log)"
[ -z "$(attr noi2.h5 /waiting_time)" ] && [ -n "$(attr noi2.h5 /ring/mean_force)" ] && ok noi.attributes ||
	fail noi.attributes "waiting_time '$(attr noi2.h5 /waiting_time)' ring '$(attr noi2.h5 /ring/mean_force)'"

# an updown ramp: flux records carry the frequency, which goes up and comes back
shake_run ramp.log "${FAST[@]}" amplitude=1 duration=4 ramp=updown ramp_from=3 ramp_to=5 flux=yes \
	output=ramp.h5 || fail ramp.run "$(head -c 200 ramp.log)"
h5dump -m %.17g -d /observables/flux/frequency/value -y -w 0 ramp.h5 | awk '/^ *[0-9]/ { gsub(/,/, " "); for (i = 1; i <= NF; i++) f[n++] = $i }
	END { m = 0; for (i = 0; i < n; i++) if (f[i] > f[m]) m = i;
	      exit !(n >= 14 && n <= 17 && f[m] > 4.8 && f[0] < 3.4 && f[n - 1] < 3.4 && m > 3 && m < n - 4) }' &&
	ok ramp.frequency_up_and_down || fail ramp.frequency_up_and_down "$(h5dump -d /observables/flux/frequency/value ramp.h5 | tail -4)"
finish
