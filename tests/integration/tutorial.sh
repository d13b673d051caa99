#!/usr/bin/env bash
# tutorial.sh - docs/tutorial.md as a reader follows it: every "$ " command of the page, in
# order and as written, run on a tiny version of campaigns/examples/amplitude.campaign
# (100 grains, 6 s runs, a tolerance of 0.3 in Gamma, 3 replicates at a 75 % level, a
# threshold for the tiny bed's flux) in a directory laid out like the repository (bin/,
# campaigns/examples/, scenes/). Each command must succeed and print what the page says
# it prints; a command added to the page without a check here fails the test.
# tier: slow: a search of 27 runs of the release engine
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
command -v sqlite3 >/dev/null || { fail setup "sqlite3 is needed"; finish; }
DOC=$REPO/docs/tutorial.md
cd "$TMP" || exit 1

# the repository's layout: the driver and the tool under test, the release engine beside
# them as data_driver_setup does (the engine's paths are tested elsewhere)
data_driver_setup
mkdir -p bin campaigns/examples scenes &&
	cp "$DATA_STUDY" bin/study && cp "$TMP/data/shake" bin/shake && cp "$BINDIR/onset" bin/onset &&
	cp "$REPO/scenes/paper.scene" scenes/ || { fail setup "cannot lay out $TMP"; finish; }
# the tiny campaign: the shipped file with these lines changed (each must match once)
tiny() {
	sed -e 's/^duration = 120 .*/duration = 6/' -e 's/^stop_skip = 24 .*/stop_skip = 3/' \
		-e 's/^tolerance = 0.01$/tolerance = 0.3/' -e 's/^to = 1.0 .*/to = 2.5/' \
		-e 's/^replicates = 6 .*/replicates = 3\nlevel = 0.75/' -e 's/^threshold = 2 .*/threshold = 0.5/' \
		-e 's/^\[scene\]$/[scene]\n'"$(tiny_scene n_grains=100 radius_ratio=- depth=- | awk '{ printf "%s%s", (NR > 1 ? "\\n" : ""), $0 }')"'\nflux_lines = 20/' \
		"$REPO/campaigns/examples/amplitude.campaign"
}
tiny >campaigns/examples/amplitude.campaign
[ "$(diff "$REPO/campaigns/examples/amplitude.campaign" campaigns/examples/amplitude.campaign | grep -c '^>')" = 12 ] &&
	ok tutorial.tiny_campaign || fail tutorial.tiny_campaign "the shipped campaign changed: a line tiny() edits is gone"

# the page's commands, in order
page_commands "$DOC" 6 tutorial
for i in "${!CMDS[@]}"; do
	page_run tutorial "$i" || continue
	case "${CMDS[i]}" in
	"bin/study expand "*)
		page_expect tutorial "$i" '^group amplitude=1 \(amplitude 1 cm\): first point [0-9.]+ Hz \(Gamma [0-9.]+, v [0-9.]+ cm/s\)' \
			'^group amplitude=3 \(amplitude 3 cm\)' ;;
	*"--dry-run"*)
		page_expect tutorial "$i" '^  total: at most [0-9]+ runs, .*CPU at most ' '^ +\(at least [0-9]+ runs, .*, CPU .*, if no run fails\)$' ;;
	"bin/study run "*)
		page_expect tutorial "$i" 'amplitude=1: onset Gamma [0-9.]+, 75% interval .*: done$' \
			'amplitude=2: onset Gamma .*: done$' 'amplitude=3: onset Gamma .*: done$' ;;
	"bin/study status "*)
		page_expect tutorial "$i" '^  onset search \(done' '^  runs [0-9]+: done [0-9]+, failed 0' ;;
	"sqlite3 "*)
		page_expect tutorial "$i" '^amplitude +f +gamma +v +phi +class +ran_s' '^1\.0 +[0-9.]+ +[0-9.]+ +[0-9.]+ +-?[0-9.]+ +off ' \
			'^3\.0 +[0-9.]+ +[0-9.]+ +[0-9.]+ +-?[0-9.]+ +on ' ;;
	"bin/onset "*)
		page_expect tutorial "$i" "^# onset: first f with mean Φ ≥ 0.5 in band 0.4–0.6, skip 0.2 \(the \[onset\] search's definition\)" \
			'^radius_ratio=0 depth=1 amplitude=2 +[0-9.]+ \[' \
			'threshold_f +3 +-?[0-9.]+ \[-?[0-9.]+, -?[0-9.]+\] .*Γ const \(p = -1/2\) (inside|excluded), v const \(p = -1\) (inside|excluded)'
		[ -s runs/amplitude_onset/analysis/onset.png ] && ok tutorial.figure ||
			fail tutorial.figure "no runs/amplitude_onset/analysis/onset.png" ;;
	*) fail "tutorial.cmd$i" "no check for '${CMDS[i]}'" ;;
	esac
done
finish
