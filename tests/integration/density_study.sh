#!/usr/bin/env bash
# density_study.sh - docs/density.md as a reader follows it: every "$ " command of the page,
# in order and as written, run on a tiny version of campaigns/examples/density.campaign
# (the tiny bed with its 2x intruder, 3 s runs, 2 replicates per density ratio) in a
# directory laid out like the repository (bin/, campaigns/examples/, scenes/). Each
# command must succeed and print what the page says it prints: the cost, the runs, the
# waiting times per intruder density with the differences, the query's ratios; a command
# added to the page without a check here fails the test.
# tier: slow: a campaign of 10 runs of the release engine
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
command -v sqlite3 >/dev/null || { fail setup "sqlite3 is needed"; finish; }
DOC=$REPO/docs/density.md
cd "$TMP" || exit 1

data_driver_setup
mkdir -p bin campaigns/examples scenes &&
	cp "$DATA_STUDY" bin/study && cp "$TMP/data/shake" bin/shake && cp "$BINDIR/waiting" bin/waiting &&
	cp "$REPO/scenes/paper.scene" scenes/ || { fail setup "cannot lay out $TMP"; finish; }
# the tiny campaign: the shipped file with these lines changed (each must match once)
tiny() {
	sed -e 's/^duration = 60 .*/duration = 3/' -e 's/^replicates = 12 .*/replicates = 2/' \
		-e 's/^\[scene\]$/[scene]\n'"$(tiny_scene | awk '{ printf "%s%s", (NR > 1 ? "\\n" : ""), $0 }')"'/' \
		"$REPO/campaigns/examples/density.campaign"
}
tiny >campaigns/examples/density.campaign
[ "$(diff "$REPO/campaigns/examples/density.campaign" campaigns/examples/density.campaign | grep -c '^>')" = $((2 + ${#TINY_BED[@]})) ] &&
	ok density.tiny_campaign || fail density.tiny_campaign "the shipped campaign changed: a line tiny() edits is gone"

# the page's commands, in order
page_commands "$DOC" 4 density
for i in "${!CMDS[@]}"; do
	page_run density "$i" || continue
	case "${CMDS[i]}" in
	*"--dry-run"*)
		page_expect density "$i" '^  total: 10 runs, at most 30 s of simulated shaking' ;;
	"bin/study run "*)
		page_expect density "$i" '^study: density: 10 done, 0 failed, 0 pending' ;;
	"bin/waiting "*)
		# one group per density ratio, as intruder_density (density = 1), each with its runs;
		# the differences against the smallest
		page_expect density "$i" 'intruder_density=0\.25 ' 'intruder_density=0\.5 ' 'intruder_density=1 ' 'intruder_density=2 ' \
			'intruder_density=4 ' 'diff'
		[ -s runs/density/analysis/waiting_summary.csv ] && ok density.summary_csv ||
			fail density.summary_csv "no runs/density/analysis/waiting_summary.csv" ;;
	"sqlite3 "*)
		page_expect density "$i" '^density_ratio +intruder_density +runs +risen' '^0\.25 +0\.25 +2 +[0-2] *$' '^4\.0 +4\.0 +2 +[0-2] *$' ;;
	*) fail "density.cmd$i" "no check for '${CMDS[i]}'" ;;
	esac
done

# the tools group a derived axis's runs by the scene key it sets, which the runs record:
# density_ratio by intruder_density (above), a gamma grid by the frequency it sets
ax=$(q runs/study.db "SELECT axes FROM campaign WHERE name = 'density'")
[ "$ax" = "intruder_density seed" ] && ok derived.axes_density || fail derived.axes_density "campaign.axes '$ax'"
{
	printf '[campaign]\nname = g\nseed = 4\nreplicates = 2\n[scene]\n'
	tiny_scene
	printf 'duration = 0.3\nsnapshots = no\n[grid]\ngamma = 1, 1.5\n'
} >g.campaign
bin/study run g.campaign --no-progress >g.out 2>&1 || fail derived.gamma_run "$(tail -n 3 g.out)"
ax=$(q runs/study.db "SELECT axes FROM campaign WHERE name = 'g'")
[ "$ax" = "frequency seed" ] && ok derived.axes_gamma || fail derived.axes_gamma "campaign.axes '$ax'"
bin/waiting g --no-plot --no-store >gw.out 2>&1 && [ "$(grep -E '^radius_ratio=2 frequency=[0-9.]+ +2 ' gw.out | cut -d' ' -f2 | sort -u | wc -l)" = 2 ] &&
	ok derived.gamma_waiting || fail derived.gamma_waiting "$(head -n 5 gw.out)"
finish
