#!/usr/bin/env bash
# study_grid.sh - campaign files: grid expansion (counts, float and integer ranges,
# canonical values), run ids and seeds that do not depend on order or spelling,
# extension keeps the ids, malformed files fail with FILE:LINE, shell injection
# attempts are rejected or harmless, and every subcommand has --help.
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1

# camp FILE [grid lines...] : a small campaign with the given [grid] lines
camp() {
	local f=$1
	shift
	{
		printf '[campaign]\nname = g\nseed = 7\n[scene]\nn_grains = 40\nwidth = 20\n[grid]\n'
		printf '%s\n' "$@"
	} >"$f"
}
expand() { "$STUDY" expand "$1" 2>"$1.err"; }

# --- counts and ranges ---
camp a.campaign 'frequency = 2.6, 2.8, 3.0' 'radius_ratio = 2:3:0.5' 'depth = 1..3' 'seed = 1..2'
expand a.campaign >a.tsv && [ "$(($(wc -l <a.tsv) - 1))" = 54 ] && ok grid.count ||
	fail grid.count "expected 54 runs (3 x 3 x 3 x 2), got $(($(wc -l <a.tsv) - 1)): $(cat a.campaign.err)"
camp r.campaign 'frequency = 2.5:3.2:0.05'
expand r.campaign >r.tsv
vals=$(awk 'NR > 1 { print $5 }' r.tsv | sort -g | tr '\n' ' ')
dec="2.5 2.55 2.6 2.65 2.7 2.75 2.8 2.85 2.9 2.95 3 3.05 3.1 3.15 3.2"
# expand prints each value as written (the shortest text of the double it hashes)
want="$dec "
[ "$vals" = "$want" ] && ok grid.float_range.values || fail grid.float_range.values "got '$vals'"
camp l.campaign "frequency = $(echo "$dec" | sed 's/ /, /g')"
expand l.campaign >l.tsv
cmp -s r.tsv l.tsv && ok grid.float_range.same_as_list || fail grid.float_range.same_as_list "range and written-out list give different runs"
camp i.campaign 'depth = 1..8'
[ "$(expand i.campaign | awk 'NR > 1 { print $5 }' | sort -n | tr '\n' ' ')" = "1 2 3 4 5 6 7 8 " ] &&
	ok grid.int_range || fail grid.int_range "1..8 did not give 1 to 8"
camp s.campaign 'frequency = 2.60, 2.6, 2.6e0'
[ "$(($(expand s.campaign | wc -l) - 1))" = 1 ] && ok grid.canonical_duplicates ||
	fail grid.canonical_duplicates "2.60, 2.6, 2.6e0 should be one value"

# --- ids and seeds: independent of order, stable under extension ---
camp b.campaign 'seed = 2, 1' 'depth = 3, 1, 2' 'radius_ratio = 3, 2.5, 2' 'frequency = 3.0, 2.6, 2.8'
expand b.campaign >b.tsv
tail -n +2 a.tsv | cut -f1-4 | sort >a.ids
tail -n +2 b.tsv | cut -f1-4 | sort >b.ids
cmp -s a.ids b.ids && ok grid.ids_independent_of_order || fail grid.ids_independent_of_order "reordered axes/values changed ids or seeds"
camp e.campaign 'frequency = 2.6, 2.8, 3.0, 3.2' 'radius_ratio = 2:3:0.5' 'depth = 1..3' 'seed = 1..3'
expand e.campaign >e.tsv
[ "$(($(wc -l <e.tsv) - 1))" = 108 ] && [ -z "$(comm -23 a.ids <(tail -n +2 e.tsv | cut -f1-4 | sort))" ] &&
	ok grid.extend_keeps_ids || fail grid.extend_keeps_ids "the extended grid lost some of the original ids"
# a new axis whose values include the one the runs had (here gamma_s's default) keeps
# their ids: 54 known runs among 108
camp n.campaign 'frequency = 2.6, 2.8, 3.0' 'radius_ratio = 2:3:0.5' 'depth = 1..3' 'seed = 1..2' 'gamma_s = 1, 2'
expand n.campaign >n.tsv
[ "$(($(wc -l <n.tsv) - 1))" = 108 ] && [ -z "$(comm -23 a.ids <(tail -n +2 n.tsv | cut -f1-4 | sort))" ] &&
	ok grid.new_axis_keeps_ids || fail grid.new_axis_keeps_ids "adding the axis gamma_s = 1, 2 lost some of the original ids"
# the seed of a replicate depends on the preparation, not on the frequency: runs that
# differ only in frequency share the seed (and the packing-cache key)
awk 'NR > 1 { k = $3 " " $6 " " $7; s[k] = s[k] " " $4; c[k] = c[k] " " $2 }
	END { for (k in s) { split(s[k], a, " "); split(c[k], b, " "); for (i in a) if (a[i] != a[1] || b[i] != b[1]) bad = 1 }; exit bad }' a.tsv &&
	ok grid.seed_shared_across_frequency || fail grid.seed_shared_across_frequency "seed or cache key differs between frequencies"
[ "$(awk 'NR > 1 { print $4 }' a.tsv | sort -u | wc -l)" = 18 ] && ok grid.seed_distinct ||
	fail grid.seed_distinct "expected 18 distinct seeds (2 replicates x 9 preparations)"
printf '[campaign]\nname = g\nseed = 7\nreplicates = 2\n[scene]\nn_grains = 40\nwidth = 20\n[grid]\nfrequency = 2.6, 2.8, 3.0\nradius_ratio = 2:3:0.5\ndepth = 1..3\n' >rep.campaign
cmp -s a.ids <(expand rep.campaign | tail -n +2 | cut -f1-4 | sort) && ok grid.replicates_is_seed_axis ||
	fail grid.replicates_is_seed_axis "replicates = 2 differs from seed = 1..2"
printf '[campaign]\nname = g\nseed = 7\nseeds = literal\n[scene]\nn_grains = 40\nwidth = 20\n[grid]\nseed = 5, 9\n' >lit.campaign
[ "$(expand lit.campaign | awk 'NR > 1 { print $3 "=" $4 }' | sort | tr '\n' ' ')" = "5=5 9=9 " ] &&
	ok grid.literal_seeds || fail grid.literal_seeds "seeds = literal should pass the seed through"
sed 's/seed = 7/seed = 8/' a.campaign >a8.campaign
[ -z "$(comm -12 a.ids <(expand a8.campaign | tail -n +2 | cut -f1-4 | sort))" ] && ok grid.campaign_seed_changes_runs ||
	fail grid.campaign_seed_changes_runs "another campaign seed gave some of the same runs"
# every key that changes what a run's file holds is part of its id: an axis over a
# recording key (traj_rate) or an observable's setting (ring_inner) gives distinct runs,
# not one run standing for several grid points
camp o.campaign 'traj_rate = 100, 200' 'ring_inner = 4, 5'
[ "$(expand o.campaign | tail -n +2 | cut -f1 | sort -u | wc -l)" = 4 ] && ok grid.output_keys_in_id ||
	fail grid.output_keys_in_id "4 grid points over traj_rate x ring_inner gave $(expand o.campaign | tail -n +2 | cut -f1 | sort -u | wc -l) run ids"
# ... but when checkpoints are written is not: the same runs with checkpoint_every set
printf '[campaign]\nname = g\nseed = 7\n[scene]\nn_grains = 40\nwidth = 20\ncheckpoint_every = 0.5\n[grid]\nfrequency = 2.6, 2.8, 3.0\nradius_ratio = 2:3:0.5\ndepth = 1..3\nseed = 1..2\n' >ck.campaign
cmp -s a.ids <(expand ck.campaign | tail -n +2 | cut -f1-4 | sort) && ok grid.id_ignores_checkpoint_every ||
	fail grid.id_ignores_checkpoint_every "checkpoint_every changed the run ids"
# [scene] overrides the base scene wherever the sections are: a [scene] above
# `scene = FILE` is not undone by FILE (width 20 from [scene], not 30 from the file)
printf 'width = 30\nn_grains = 40\n' >base.scene
printf '[campaign]\nname = g\nseed = 7\n[scene]\nn_grains = 40\nwidth = 20\n[grid]\nfrequency = 2.6, 2.8\n' >plain.campaign
printf '[campaign]\nname = g\nseed = 7\nscene = base.scene\n[scene]\nwidth = 20\n[grid]\nfrequency = 2.6, 2.8\n' >after.campaign
printf '[scene]\nwidth = 20\n[campaign]\nname = g\nseed = 7\nscene = base.scene\n[grid]\nfrequency = 2.6, 2.8\n' >before.campaign
expand plain.campaign >plain.tsv
[ -s plain.tsv ] && cmp -s plain.tsv <(expand after.campaign) && cmp -s plain.tsv <(expand before.campaign) &&
	ok grid.scene_overrides_base_in_any_order ||
	fail grid.scene_overrides_base_in_any_order "[scene] before [campaign] scene = FILE gave other runs: $(expand before.campaign | tail -n 1)"

# --- malformed files: non-zero exit and FILE:LINE: in the message ---
# bad ID LINE CONTENT... : the campaign made of CONTENT lines must fail at LINE
bad() {
	local id=$1 line=$2
	shift 2
	printf '%s\n' "$@" >"bad_$id.campaign"
	"$STUDY" expand "bad_$id.campaign" >/dev/null 2>"bad_$id.err"
	local rc=$?
	if [ "$rc" -ne 0 ] && grep -q "bad_$id.campaign:$line: " "bad_$id.err"; then ok "malformed.$id"; else
		fail "malformed.$id" "exit $rc, expected 'bad_$id.campaign:$line: ...': $(head -c 200 "bad_$id.err")"; fi
}
H=('[campaign]' 'name = m' 'seed = 1')
bad unknown_section 4 "${H[@]}" '[grids]' 'frequency = 3'
bad unknown_key 5 "${H[@]}" '[grid]' 'frequncy = 3'
bad bad_value 5 "${H[@]}" '[grid]' 'frequency = 2.8, fast'
bad out_of_range 5 "${H[@]}" '[scene]' 'dt = 1'
bad bad_range 5 "${H[@]}" '[grid]' 'frequency = 2.5:3.2'
bad zero_step 5 "${H[@]}" '[grid]' 'frequency = 2.5:3.2:0'
bad reversed_int_range 5 "${H[@]}" '[grid]' 'depth = 8..1'
bad float_int_range 5 "${H[@]}" '[grid]' 'depth = 1:3:0.5'
bad reserved_key 5 "${H[@]}" '[scene]' 'output = /etc/passwd'
bad twice 7 "${H[@]}" '[scene]' 'width = 20' '[grid]' 'width = 20, 30'
bad list_in_scene 5 "${H[@]}" '[scene]' 'frequency = 2.6, 2.8'
bad no_name 1 '[campaign]' 'seed = 1'
bad no_seed 1 '[campaign]' 'name = m'
bad outside_section 1 'frequency = 3' "${H[@]}"
bad no_equals 5 "${H[@]}" '[grid]' 'frequency 3'
bad unknown_campaign_key 4 "${H[@]}" 'colour = blue'
bad replicates_and_seed 6 "${H[@]}" 'replicates = 2' '[grid]' 'seed = 1..3'
bad empty_axis 5 "${H[@]}" '[grid]' 'frequency = ,'
bad missing_scene_file 4 "${H[@]}" 'scene = nowhere.scene'
bad grid_point 5 "${H[@]}" '[grid]' 'radius_ratio = 2, 40' 'width = 20'
bad campaign_key_twice 3 '[campaign]' 'name = m' 'name = n' 'seed = 1'
bad seed_twice 4 "${H[@]}" 'seed = 2'
bad empty_file 1
bad no_campaign_section 1 '[scene]' 'width = 20'
# refusals are exit 1 with the reason: a crash (a sanitizer's abort, a signal) is no refusal
"$STUDY" expand "$TMP/none.campaign" >/dev/null 2>none.err
rc=$?
[ $rc = 1 ] && grep -q "none.campaign: cannot open" none.err && ok malformed.missing_file ||
	fail malformed.missing_file "exit $rc: $(cat none.err)"

# --- injection: nothing in a campaign reaches a shell ---
MARK=/tmp/pwned
rm -f "$MARK"
inj() {
	local id=$1
	shift
	printf '%s\n' "$@" >"inj_$id.campaign"
	"$STUDY" run "inj_$id.campaign" --runs "$TMP/injruns" >"inj_$id.out" 2>&1
	local rc=$?
	if [ "$rc" -ne 0 ] && [ ! -e "$MARK" ]; then ok "injection.$id"; else
		fail "injection.$id" "exit $rc, marker $(ls "$MARK" 2>/dev/null): $(head -c 200 "inj_$id.out")"; fi
}
inj name_subst '[campaign]' 'name = $(touch /tmp/pwned)' 'seed = 1'
inj name_semicolon '[campaign]' 'name = x; rm -rf x' 'seed = 1'
inj name_backquote '[campaign]' 'name = `touch /tmp/pwned`' 'seed = 1'
inj name_dotdot '[campaign]' 'name = ..' 'seed = 1'
inj value_subst "${H[@]}" '[grid]' 'frequency = $(touch /tmp/pwned)'
inj value_semicolon "${H[@]}" '[scene]' 'n_grains = 40; rm -rf x'
inj value_backquote "${H[@]}" '[grid]' 'integrator = `touch /tmp/pwned`'
inj particles_path "${H[@]}" '[scene]' 'particles = x;touch /tmp/pwned'
inj particles_escape "${H[@]}" '[scene]' 'particles = ../../etc/passwd'
inj value_cr "${H[@]}" '[scene]' "$(printf 'integrator = gear5\r$(touch /tmp/pwned)')"
# names and values the driver does pass on: a runs directory and a campaign file name
# full of shell syntax (quotes, $( ), ;, a newline) run normally and touch nothing
weird="$TMP/r \$(touch $MARK); '\`touch $MARK\`'"
cf="$TMP/c \$(touch pwned); \`touch pwned\`
'q'.campaign"
printf '[campaign]\nname = w\nseed = 1\n[scene]\n'"$(tiny_scene n_grains=40 depth=-)"'\nduration = 0.1\n' >"$cf"
"$STUDY" run "$cf" --runs "$weird" --no-progress >weird.out 2>&1
rc=$?
if [ "$rc" -eq 0 ] && [ ! -e "$MARK" ] && [ ! -e pwned ] && ls "$weird/w/"*.h5 >/dev/null 2>&1; then ok injection.quoted_paths; else
	fail injection.quoted_paths "exit $rc, marker $(ls "$MARK" 2>/dev/null): $(tail -c 300 weird.out)"; fi
# output paths come from the driver only: a base scene that names its own output,
# checkpoint and particle files outside the campaign's directory writes none of them
mkdir -p esc/a/b
printf 'output = ../../escaped.h5\nwrite_particles = ../../escaped.txt\nwrite_lammps = ../../escaped.data\ncheckpoint = ../../escaped.ckpt\ncheckpoint_every = 0.05\n'"$(tiny_scene n_grains=40 depth=-)"'\nduration = 0.1\n' >esc/esc.scene
printf '[campaign]\nname = esc\nseed = 1\nscene = esc.scene\n' >esc/esc.campaign
"$STUDY" run esc/esc.campaign --runs "$TMP/esc/a/b" --no-progress >esc.out 2>&1
rc=$?
[ "$rc" -eq 0 ] && [ -z "$(find "$TMP" -name 'escaped*')" ] && [ "$(ls esc/a/b/esc/*.h5 2>/dev/null | wc -l)" = 1 ] &&
	ok injection.base_scene_paths_ignored || fail injection.base_scene_paths_ignored "exit $rc: $(find "$TMP" -name 'escaped*') $(tail -c 200 esc.out)"
# a base scene's file names follow the campaign's own rule, named where the scene set them
for v in '../../etc/passwd' 'x;touch /tmp/pwned'; do
	id=base_scene_particles_$( [ "$v" = '../../etc/passwd' ] && echo dotdot || echo shell)
	printf 'n_grains = 40\nparticles = %s\nwidth = 20\n' "$v" >esc/p.scene
	printf '[campaign]\nname = escp\nseed = 1\nscene = p.scene\n' >esc/p.campaign
	"$STUDY" expand esc/p.campaign >"$id.out" 2>&1
	rc=$?
	[ "$rc" -ne 0 ] && grep -q "p.scene:2: particles: .*not a plain path" "$id.out" &&
		grep -q "esc/p.campaign:4" "$id.out" && ok "injection.$id" || fail "injection.$id" "exit $rc: $(head -c 300 "$id.out")"
done
[ ! -e "$MARK" ] && ok injection.no_marker || fail injection.no_marker "$MARK exists"
rm -f "$MARK"

# --- axes in Gamma and v (docs/campaigns.md): gamma = 1.5, 2.5 at A = 1 cm runs at
# f = sqrt(Gamma g / A) / 2 pi = 6.10521, 7.88179 Hz, and the runs table keeps Gamma, v
# and f; velocity with a set frequency sets the amplitude, A = v / (2 pi f) ---
printf '[campaign]\nname = gm\nseed = 1\n[scene]\n'"$(tiny_scene n_grains=40 depth=-)"'\nduration = 0.1\npreset = fast\namplitude = 1\n[grid]\ngamma = 1.5, 2.5\n' >gm.campaign
"$STUDY" run gm.campaign --runs "$TMP/GM" --no-progress >gm.out 2>&1
rc=$?
got=$(sqlite3 GM/study.db "SELECT printf('%.12g|%.12g|%.9g|%g', gamma, frequency, v_box, amplitude) FROM runs
	WHERE campaign = 'gm' ORDER BY frequency" | tr '\n' ' ')
want=$(awk 'BEGIN { for (g = 1.5; g <= 2.5; g += 1) { f = sqrt(g * 981 / 1) / 6.283185307179586
	printf "%.12g|%.12g|%.9g|1 ", g, f, 6.283185307179586 * f } }')
# the frequencies as the brief computes them by hand: 6.10521 and 7.88179 Hz
[ "$rc" -eq 0 ] && [ "$got" = "$want" ] && case $got in *"|6.10520519167|"*"|7.88178601084|"*) true ;; *) false ;; esac &&
	ok grid.gamma.runs_keep_gamma_v_f || fail grid.gamma.runs_keep_gamma_v_f "exit $rc: got '$got', want '$want': $(tail -c 300 gm.out)"
camp v.campaign 'velocity = 20, 40' 'frequency = 4'
expand v.campaign >v.tsv
got=$(awk -F'\t' 'NR > 1 { print $5 "|" $6 "|" $7 }' v.tsv | sort | tr '\n' ' ')
[ "$got" = "20|4|0.795774715459 40|4|1.59154943092 " ] && head -n 1 v.tsv | grep -q 'amplitude$' &&
	ok grid.velocity.sets_amplitude || fail grid.velocity.sets_amplitude "got '$got': $(cat v.tsv v.campaign.err)"
camp o.campaign 'gamma = 1' 'amplitude = 1' 'frequency = 3'
expand o.campaign >/dev/null
grep -q "o.campaign:8: gamma: amplitude (line 9) and frequency (line 10) are both set" o.campaign.err &&
	ok grid.gamma.overdetermined || fail grid.gamma.overdetermined "$(cat o.campaign.err)"

# --- --help everywhere ---
for c in run status list export expand columns options submit exec; do
	out=$("$STUDY" "$c" --help 2>&1)
	rc=$?
	[ "$rc" -eq 0 ] && case "$out" in *"usage: study $c"*) true ;; *) false ;; esac &&
		ok "help.$c" || fail "help.$c" "exit $rc: $(echo "$out" | head -n 2)"
done
"$STUDY" --help | grep -q "study run CAMPAIGN" && ok help.top || fail help.top "no command list"
"$STUDY" frobnicate >/dev/null 2>cli1.err
rc=$?
[ $rc = 1 ] && grep -q "unknown command 'frobnicate'" cli1.err && ok cli.unknown_command ||
	fail cli.unknown_command "exit $rc: $(head -n 1 cli1.err)"
"$STUDY" run a.campaign --bogus >/dev/null 2>cli2.err
rc=$?
[ $rc = 1 ] && grep -q -- "--bogus" cli2.err && ok cli.unknown_option || fail cli.unknown_option "exit $rc: $(head -n 1 cli2.err)"
# the option table's errors as a user sees them: the option named, what the command takes
out=$("$STUDY" run a.campaign --no-chace 2>&1)
rc=$?
[ "$rc" -eq 1 ] && case "$out" in *"study: run: unknown option '--no-chace'; did you mean --no-cache?"*"--jobs"*) true ;; *) false ;; esac &&
	ok cli.unknown_option_named || fail cli.unknown_option_named "exit $rc: $out"
out=$("$STUDY" list --watch 2>&1)
rc=$?
[ "$rc" -eq 1 ] && case "$out" in *"--watch is an option of study status, not of study list"*) true ;; *) false ;; esac &&
	ok cli.option_of_another_command || fail cli.option_of_another_command "exit $rc: $out"
out=$("$STUDY" status --interval 0 2>&1)
rc=$?
[ "$rc" -eq 1 ] && case "$out" in *"--interval: expected a number in [0.1, 3600], got '0'"*) true ;; *) false ;; esac &&
	ok cli.option_out_of_range || fail cli.option_out_of_range "exit $rc: $out"
# every option of the table in the --help of each command that takes it
"$STUDY" options | sed -n 's/^| `\(-., \)\{0,1\}\(--[a-z-]*\)[^|]*| [^|]*| \([^|]*\) |.*/\2 \3/p' >opts.tsv
nmiss=0
while read -r opt cmds; do
	[ "$cmds" = all ] && cmds="run, status, list, export, expand, columns, options, submit, exec"
	for c in $(echo "$cmds" | tr -d ,); do
		"$STUDY" "$c" --help | grep -qE -- "^  (-., )?$opt( |\$)" || { nmiss=$((nmiss + 1)); echo "# study $c --help lacks $opt"; }
	done
done <opts.tsv
[ "$(wc -l <opts.tsv)" -ge 15 ] && [ "$nmiss" = 0 ] && ok cli.help_lists_table ||
	fail cli.help_lists_table "$(wc -l <opts.tsv) options read, $nmiss missing from a --help"
finish
