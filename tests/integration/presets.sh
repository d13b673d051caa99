#!/usr/bin/env bash
# presets.sh - nothing given explicitly is undone by a preset: the preset is applied
# first and integrator or dt given explicitly win wherever they appear (docs/model.md,
# "Units and the paper's values"), the same in a scene file, in key=value arguments,
# across the two, and in a campaign's [scene] and [grid]; what the run files record
# is what ran. A later preset still replaces an earlier one's values
# (scenes/paper.scene says preset = paper; preset=fast on top of it is verlet at 2e-4,
# as scripts/reproduce.sh and campaigns/reproduce/ use it).
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1

# ran ID WANT-INTEGRATOR WANT-DT SHAKE-ARGS... : a settle-only run; its file records
# the integrator and dt wanted
ran() {
	local id=$1 ig=$2 dt=$3
	shift 3
	rm -f "$id.h5"
	"$SHAKE" "$@" "${FAST[@]}" duration=0 output="$id.h5" >"$id.log" 2>&1
	local rc=$? gi gd
	gi=$(h5param "$id.h5" integrator)
	gd=$(h5param "$id.h5" dt)
	if [ "$rc" = 0 ] && [ "$gi" = "$ig" ] && awk -v a="$gd" -v b="$dt" 'BEGIN { exit !(a == b) }'; then
		ok "$id"
	else
		fail "$id" "exit $rc, integrator '$gi' dt '$gd', want $ig $dt: $(tail -n 1 "$id.log")"
	fi
}

printf 'dt = 1e-5\npreset = fast\n' >dt_first.scene
printf 'preset = fast\ndt = 1e-5\n' >dt_after.scene
printf 'integrator = gear4\n' >ig.scene
ran scene.dt_before_preset verlet 1e-5 dt_first.scene
ran scene.dt_after_preset verlet 1e-5 dt_after.scene
ran cli.dt_before_preset verlet 1e-5 dt=1e-5 preset=fast
ran cli.dt_after_preset verlet 1e-5 preset=fast dt=1e-5
ran scene_then_cli.explicit_integrator_stays gear4 2e-4 ig.scene preset=fast
ran paper_scene_then_cli.preset_replaces_preset verlet 2e-4 "$REPO/scenes/paper.scene" preset=fast
ran paper_scene_then_cli.explicit_dt_stays verlet 1e-4 "$REPO/scenes/paper.scene" dt=1e-4 preset=fast

# a campaign: a fixed dt under a preset axis, a dt axis beside a preset
cat >p.campaign <<EOF
[campaign]
name = p
seed = 1
[scene]
dt = 1e-4
$(tiny_scene n_grains=40 depth=-)
duration = 0.1
[grid]
preset = paper, fast
EOF
cat >a.campaign <<EOF
[campaign]
name = a
seed = 1
[scene]
$(tiny_scene n_grains=40 depth=-)
duration = 0.1
[grid]
dt = 1e-4, 5e-5
preset = fast
EOF
for c in p a; do
	"$STUDY" run $c.campaign --runs "$TMP/R" --jobs 2 >$c.log 2>&1 || fail "campaign.$c.ran" "exit $?: $(tail -n 2 $c.log)"
done
rows=$(q R/study.db "SELECT group_concat(x, ' ') FROM (SELECT preset || ':' || integrator || ':' || dt AS x FROM runs
	WHERE campaign = 'p' ORDER BY x)")
files=$(for f in R/p/*.h5; do echo "$(h5param "$f" preset):$(h5param "$f" integrator):$(h5param "$f" dt)"; done | sort | tr '\n' ' ')
[ "$rows" = "fast:verlet:0.0001 paper:gear5:0.0001" ] && [ "$files" = "fast:verlet:0.0001 paper:gear5:0.0001 " ] &&
	ok campaign.fixed_dt_stays_on_a_preset_axis || fail campaign.fixed_dt_stays_on_a_preset_axis "rows '$rows', files '$files'"
rows=$(q R/study.db "SELECT group_concat(x, ' ') FROM (SELECT preset || ':' || integrator || ':' || dt AS x FROM runs
	WHERE campaign = 'a' ORDER BY x)")
[ "$rows" = "fast:verlet:0.0001 fast:verlet:5.0e-05" ] && ok campaign.dt_axis_stays_under_a_preset ||
	fail campaign.dt_axis_stays_under_a_preset "rows '$rows'"
finish
