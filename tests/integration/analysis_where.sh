#!/usr/bin/env bash
# analysis_where.sh - figures on a campaign that sweeps another key (depth) besides
# frequency and radius ratio: without a selection it refuses (naming the key) instead
# of averaging over it; --where depth=VALUE draws only those runs (the stored panel's
# run count says so); bad --where selections are usage errors.
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
cd "$TMP" || exit 1
printf '[campaign]\nname = w\nseed = 5\n[scene]\n'"$(tiny_scene n_grains=40 width=16 radius_ratio=- depth=-)"'\namplitude = 1\nduration = 0.5\nflux = yes\nfield = yes\nfield_periods = 1\n[grid]\nradius_ratio = 0, 2\ndepth = 0, 1\nfrequency = 4\n' >w.campaign
"$STUDY" run w.campaign --runs "$TMP/R" --jobs 2 --no-progress >study.log 2>&1 &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 4 ] && ok where.setup ||
	{ fail where.setup "$(tail -c 300 study.log)"; finish; }

"$BINDIR/figures" w --runs R --no-plot >f0.out 2>f0.err
rc=$?
[ "$rc" -eq 1 ] && grep -q "sweeps depth" f0.err && grep -q -- "--where depth=" f0.err &&
	ok where.pooling_refused || fail where.pooling_refused "exit $rc: $(cat f0.err)"

"$BINDIR/figures" w --runs R --no-plot --where depth=1 >f1.out 2>f1.err
rc=$?
[ "$rc" -eq 0 ] && ok where.selected_runs || fail where.selected_runs "exit $rc: $(cat f1.err)"
# one run per panel: the stored run count of every Fig. 3 panel is 1, not the 2 of both depths
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE tool = 'figures' AND key = 'runs' AND value = 1")" -ge 1 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE tool = 'figures' AND key = 'runs' AND value <> 1")" = 0 ] &&
	ok where.one_depth_per_panel || fail where.one_depth_per_panel "$(q R/study.db "SELECT grp, key, value FROM analysis WHERE tool = 'figures'")"

"$BINDIR/figures" w --runs R --no-plot --where depth=7 >f2.out 2>f2.err
[ $? -eq 1 ] && grep -q "matches --where" f2.err && ok where.no_match || fail where.no_match "$(cat f2.err)"
"$BINDIR/figures" w --runs R --no-plot --where nosuchkey=1 >f3.out 2>f3.err
[ $? -eq 1 ] && grep -q "nosuchkey" f3.err && ok where.unknown_key || fail where.unknown_key "$(cat f3.err)"
"$BINDIR/figures" w --runs R --no-plot --where depth >f4.out 2>f4.err
[ $? -eq 1 ] && grep -q "KEY=VALUE" f4.err && ok where.malformed || fail where.malformed "$(cat f4.err)"
finish
