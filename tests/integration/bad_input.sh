#!/usr/bin/env bash
# bad_input.sh - every kind of bad input stops bin/shake with exit code 1, a message
# that names the place (FILE:LINE and the key, or the command-line key), and no
# output file (nor sidecar, journal or checkpoint) left behind.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

OUT="$TMP/out.h5"
# expect_bad ID "needle|needle..." args... : exit 1, stderr has every needle, no output
expect_bad() {
	local id=$1 needles=$2
	shift 2
	rm -f "$OUT" "$TMP/out.xmf" "$OUT.journal" "$OUT.ckpt"
	local log="$TMP/$id.log"
	shake_run "$log" "$@" output="$OUT"
	local rc=$? why=""
	[ "$rc" -eq 1 ] || why="exit code $rc, expected 1"
	local IFS='|' n
	for n in $needles; do
		[ -z "$why" ] && ! contains "$log" "$n" && why="message lacks '$n'"
	done
	unset IFS
	[ -z "$why" ] && [ "$(wc -l <"$log")" -lt 1 ] && why="no message"
	for f in "$OUT" "$TMP/out.xmf" "$OUT.journal" "$OUT.ckpt"; do
		[ -z "$why" ] && [ -e "$f" ] && why="bad input left $(basename "$f") behind"
	done
	if [ -z "$why" ]; then ok "$id"; else fail "$id" "$why; stderr: $(head -c 300 "$log" | tr '\n' ' ')"; fi
}

# --- scene files ---
printf 'n_grains = 60\nwidth = 20\nbogus_key = 3\n' >s_unknown.ini
expect_bad scene.unknown_key "s_unknown.ini:3:|bogus_key" s_unknown.ini "${FAST[@]}"

printf '[scene]\n# comment\nfrequency = 2000\n' >s_range.ini
expect_bad scene.out_of_range "s_range.ini:3:|frequency|[0, 1000]|2000" s_range.ini "${FAST[@]}"

printf 'n_grains = 60\nthis line has no equals sign\nwidth = 20\n' >s_malformed.ini
expect_bad scene.malformed "s_malformed.ini:2:" s_malformed.ini "${FAST[@]}"

printf 'n_grains = 60\n[physics]\nmu = 0.4\n' >s_section.ini
expect_bad scene.unknown_section "s_section.ini:2:|physics" s_section.ini "${FAST[@]}"

# an unknown section header followed by nothing is still a mistake in the file
printf 'n_grains = 60\n[physics]\n' >s_section_empty.ini
expect_bad scene.unknown_section_empty "s_section_empty.ini:2:|physics" s_section_empty.ini "${FAST[@]}"

printf 'n_grains = 60\nintegrator = rk4\n' >s_enum.ini
expect_bad scene.bad_enum "s_enum.ini:2:|integrator|gear5|rk4" s_enum.ini "${FAST[@]}"

printf 'n_grains = 6.5\n' >s_int.ini
expect_bad scene.bad_int "s_int.ini:1:|n_grains" s_int.ini "${FAST[@]}"

expect_bad scene.missing "no_such_scene.ini" no_such_scene.ini "${FAST[@]}"

# errors that only a combination of keys shows name where the key at fault was set
printf 'n_grains = 60\nwidth = 20\nr_min = 1.2\n' >s_cross.ini
expect_bad scene.cross_key_names_line "s_cross.ini:3:|r_min|r_max|default" s_cross.ini "${FAST[@]}"
printf 'n_grains = 60\nwidth = 20\ndt = 0.01\n' >s_dt.ini
expect_bad scene.dt_guard_names_line "s_dt.ini:3:|dt|stability limit" s_dt.ini "${FAST[@]}"
expect_bad cmdline.cross_key_names_source "command line|settle_min|settle_max" "${FAST[@]}" settle_min=50 settle_max=40

# a key given twice in a file (the command line may still override it)
printf 'frequency = 3\nseed = 2\nfrequency = 4\n' >s_twice.ini
expect_bad scene.key_twice "s_twice.ini:3:|frequency|twice|line 1" s_twice.ini "${FAST[@]}"
printf 'frequency = 3\n[scene]\nfrequency = 4\n' >s_twice_section.ini
expect_bad scene.key_twice_across_sections "s_twice_section.ini:3:|frequency|twice" s_twice_section.ini "${FAST[@]}"

# the scene file must come first; a second bare word is an error
printf 'n_grains = 60\n' >s_ok.ini
expect_bad cmdline.stray_word "stray" s_ok.ini stray "${FAST[@]}"

# --- command-line overrides ---
expect_bad cmdline.bad_real "frequency|fast" "${FAST[@]}" frequency=fast
expect_bad cmdline.unknown_key "nokey" "${FAST[@]}" nokey=1
expect_bad cmdline.empty_key "=3" "${FAST[@]}" =3
expect_bad cmdline.out_of_range "dt|(0, 0.01]" "${FAST[@]}" dt=0.1
expect_bad cmdline.zero_exclusive "stiffness|(0, 1e+13]" "${FAST[@]}" stiffness=0
expect_bad cmdline.bad_bool "snapshots|maybe" "${FAST[@]}" snapshots=maybe
expect_bad cmdline.unknown_option "--frobnicate" "${FAST[@]}" --frobnicate

# --- cross-parameter checks ---
expect_bad validate.r_min_gt_r_max "r_min|r_max" "${FAST[@]}" r_min=1.2 r_max=1.0

# --- particle files ---
expect_bad particles.missing "no_such_particles.txt" "${FAST[@]}" particles=no_such_particles.txt
printf '# x y r kind\n10 5 1 grain\n12 5 1 pebble\n' >p_kind.txt
expect_bad particles.bad_kind "p_kind.txt:3:|pebble" "${FAST[@]}" particles=p_kind.txt
printf '10 5 1 grain\n12 5\n' >p_cols.txt
expect_bad particles.too_few_columns "p_cols.txt:2:" "${FAST[@]}" particles=p_cols.txt
printf '10 5 1 grain\n12 5 -1 grain\n' >p_radius.txt
expect_bad particles.negative_radius "p_radius.txt:2:" "${FAST[@]}" particles=p_radius.txt
printf 'LAMMPS data\n\n2 atoms\n3 atom types\n\nAtoms # sphere\n\n1 1 2 1 10 5 0\n2 7 2 1 12 5 0\n' >p_type.data
expect_bad particles.lammps_bad_type "p_type.data:9:|7" "${FAST[@]}" particles=p_type.data

# --- the good case passes through the same helper's checks (so they can pass) ---
log="$TMP/good.log"
shake_run "$log" s_ok.ini "${FAST[@]}" output="$OUT"
rc=$?
if [ "$rc" -eq 0 ] && [ -s "$OUT" ]; then ok control.good_input_runs; else fail control.good_input_runs "exit $rc: $(head -c 300 "$log")"; fi
# --- the dt guard: beyond the measured stability limit is refused before anything runs,
#     with the limit named; dt_guard = warn runs with a warning; a particle file's
#     lightest disk counts too ---
expect_bad dt_guard.refuse "dt|stability limit|gear5|dt_guard" "${FAST[@]}" dt=1e-3
expect_bad dt_guard.refuse_verlet "dt|stability limit|verlet" "${FAST[@]}" integrator=verlet dt=5e-3
shake_run warn.log "${FAST[@]}" dt=5e-4 dt_guard=warn duration=0.05 output="$TMP/warn.h5"
rc=$?
# (whether such a run survives is its own business: it is not refused, and it is warned)
[ "$rc" -ne 1 ] && contains warn.log "warning" && ok dt_guard.warn ||
	fail dt_guard.warn "exit $rc: $(head -c 300 warn.log)"
printf '0 1.5 0.1 grain\n5 1.5 1 grain\n' >light.txt
expect_bad dt_guard.particle_file "dt|stability limit" particles=light.txt settle=no dt=2e-4 duration=0.01
finish
