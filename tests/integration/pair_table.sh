#!/usr/bin/env bash
# pair_table.sh - materials per pair of kinds (docs/model.md, "Materials per pair of
# kinds"): a class's key out of range is refused naming file, line, key and range, and a
# gamma_n_CLASS beside restitution naming both; a class key that resolves to the grains'
# value is the paper's one material to the bit (the vector kernel); a class of its own is
# recorded (/parameters, `same` as -1; /contact_law's materials and the class's mu,
# stiffness, gamma_s and restitution), changes the run, and gives the same bits on every
# kernel path; a campaign sweeps a class key, its runs view holding the values.
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1

# --- refusals ---
printf '%s\n' 'n_grains = 60' 'mu_grain_wall = -0.5' >bad.ini
"$SHAKE" bad.ini >bad.out 2>&1
rc=$?
[ "$rc" -ne 0 ] && grep -q 'bad.ini:2' bad.out && grep -q 'mu_grain_wall' bad.out && grep -qF '[0, 100] or same' bad.out &&
	ok refuse.range || fail refuse.range "exit $rc: $(cat bad.out)"
printf '%s\n' 'restitution = 0.9' 'gamma_n_grain_intruder = 50' >resti.ini
"$SHAKE" resti.ini >resti.out 2>&1
rc=$?
[ "$rc" -ne 0 ] && grep -q 'resti.ini:1' resti.out && grep -q 'gamma_n_grain_intruder (resti.ini:2)' resti.out &&
	ok refuse.beside_restitution || fail refuse.beside_restitution "exit $rc: $(cat resti.out)"
"$SHAKE" stiffness_grain_wall=0 >stiff.out 2>&1
rc=$?
[ "$rc" -ne 0 ] && grep -qF 'stiffness_grain_wall: expected a number in (0, 1e+15] or same' stiff.out &&
	ok refuse.stiffness_zero || fail refuse.stiffness_zero "exit $rc: $(cat stiff.out)"

# --- runs of the tiny bed, shaken ---
tiny_bed duration=0.3 "${GENTLE[@]}" traj_rate=100 snapshots=no progress=no
shake_run a.log "${BEDARGS[@]}" output=a.h5 || fail run.default "exit $?: $(tail -n 2 a.log)"
# the grains' own value written out: still one material, the same bits
shake_run b.log "${BEDARGS[@]}" mu_grain_wall=0.5 gamma_n_intruder_wall=same output=b.h5 ||
	fail run.same "exit $?: $(tail -n 2 b.log)"
[ "$(attr b.h5 /contact_law/materials)" = one ] && same_output a.h5 b.h5 output mu_grain_wall &&
	ok same_value.paper_bits || fail same_value.paper_bits "materials $(attr b.h5 /contact_law/materials)"
# a rough, stiff wall of its own
tab=(mu_grain_wall=0.9 gamma_n_grain_wall=300 stiffness_grain_wall=6e6)
shake_run c.log "${BEDARGS[@]}" "${tab[@]}" output=c.h5 || fail run.table "exit $?: $(tail -n 2 c.log)"
[ "$(attr c.h5 /parameters/mu_grain_wall)" = 0.90000000000000002 ] && [ "$(attr c.h5 /parameters/mu_grain_intruder)" = -1 ] &&
	[ "$(attr c.h5 /parameters/stiffness_grain_wall)" = 6000000 ] && ok table.parameters ||
	fail table.parameters "$(attr c.h5 /parameters/mu_grain_wall) $(attr c.h5 /parameters/mu_grain_intruder)"
# the grain on a wall disk of this bed: m_eff of the wall's own mass; e of m xi'' = -Y xi - c xi'
# with m the grain's (the wall does not move), c = gamma_n m_eff
e_want=$(awk -v me="$(attr c.h5 /contact_law/grain_wall/m_eff)" -v mi="$(attr c.h5 /contact_law/grain_grain/m_eff)" '
	BEGIN { m = 2 * mi; c = 300 * me; b = c / (2 * m); w = sqrt(6e6 / m - b * b); printf "%.6g", exp(-b * atan2(0, -1) / w) }')
[ "$(attr c.h5 /contact_law/materials)" = per_pair_class ] && [ "$(attr c.h5 /contact_law/grain_wall/mu)" = 0.90000000000000002 ] &&
	[ "$(attr c.h5 /contact_law/grain_wall/gamma_n)" = 300 ] && [ "$(attr c.h5 /contact_law/grain_grain/mu)" = 0.5 ] &&
	[ "$(printf '%.6g' "$(attr c.h5 /contact_law/grain_wall/restitution)")" = "$e_want" ] && ok table.contact_law ||
	fail table.contact_law "materials $(attr c.h5 /contact_law/materials), grain_wall e $(attr c.h5 /contact_law/grain_wall/restitution) want $e_want"
# it changes the run (the wall's grains move otherwise)
! same_output a.h5 c.h5 output mu_grain_wall gamma_n_grain_wall stiffness_grain_wall 2>/dev/null && ok table.changes_run ||
	fail table.changes_run "a wall of its own left the run unchanged"
# every kernel path: the same bits
while read -r p runs _; do
	[ "$runs" = yes ] || continue
	SHAKEBOX_KERNEL=$p shake_run "c_$p.log" "${BEDARGS[@]}" "${tab[@]}" output="c_$p.h5" &&
		same_output c.h5 "c_$p.h5" output && ok "table.path_$p" || fail "table.path_$p" "$(tail -n 2 "c_$p.log")"
done < <("$SHAKE" --kernel-paths)

# --- a campaign sweeps a class's friction ---
{
	printf '[campaign]\nname = wall\nseed = 5\nreplicates = 1\n[scene]\n'
	tiny_scene n_grains=40 width=16
	printf '%s\n' 'duration = 0.2' 'traj_rate = 100' 'snapshots = no' 'frequency = 4' '[grid]' 'mu_grain_wall = 0, same'
} >wall.campaign
"$STUDY" run wall.campaign --runs "$TMP/R" --jobs 2 --no-progress >study.log 2>&1 || fail campaign.run "exit $?: $(tail -n 3 study.log)"
got=$(q R/study.db "SELECT mu_grain_wall FROM runs WHERE campaign = 'wall' ORDER BY mu_grain_wall" | tr '\n' ' ')
[ "$got" = "-1.0 0.0 " ] && ok campaign.sweep || fail campaign.sweep "runs' mu_grain_wall: '$got' (want -1 and 0)"
finish
