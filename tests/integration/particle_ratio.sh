#!/usr/bin/env bash
# particle_ratio.sh - a particle file's radius_ratio (docs/model.md, "Units and the
# paper's values"): the run file's /parameters/radius_ratio and the study database's
# runs view record the file's first intruder's radius over the scene's mean grain
# radius, 0 for a file without intruder, never the key's default 4. Known answers: R = 2
# among unit grains records 2 (text and LAMMPS), no intruder 0, the scene's mean and not
# the file's grains' divides (r_min/r_max of mean 2 give 1), the first of two intruders
# counts. A radius_ratio given beside the file that disagrees is refused naming the
# file, the intruder's line, the key, where it was set and both values; one that agrees
# is kept. A campaign's runs record the file's; a campaign whose radius_ratio disagrees
# with its file is refused before anything runs. n_intruders is the file's count of
# intruders (two.txt: 2) in the run file and the param rows; given otherwise, refused.
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1

# a floor of wall disks, two unit grains and an intruder of R = 2 (line 13 with the comment)
{
	echo '# unit grains, an intruder of radius 2'
	for x in -1 1 3 5 7 9 11 13 15 17; do echo "$x -1 1 wall"; done
	echo '1 1 1 grain'
	echo '8 2.2 2 intruder'
	echo '15 1 1 grain'
} >a.txt
grep -v intruder a.txt >none.txt
# two intruders, the first of R = 3: the first counts
sed 's/^8 2.2 2 intruder$/8 3.2 3 intruder\n20 2.2 2 intruder/' a.txt | sed 's/^17 -1 1 wall$/17 -1 1 wall\n19 -1 1 wall\n21 -1 1 wall/' >two.txt
RUN=(settle=no amplitude=0 duration=0.02 snapshots=no traj_rate=0 progress=no)

ratio_of() { h5param "$1" radius_ratio; }
# recorded FILE WANT ID [KEY=VALUE...]: the run of FILE records radius_ratio WANT
recorded() {
	local f=$1 want=$2 id=$3
	shift 3
	shake_run "$id.log" particles="$f" "${RUN[@]}" "$@" output="$id.h5"
	local rc=$?
	[ "$rc" -eq 0 ] && [ "$(ratio_of "$id.h5")" = "$want" ] && ok "$id" ||
		fail "$id" "exit $rc, radius_ratio '$(ratio_of "$id.h5" 2>/dev/null)', want $want: $(head -c 300 "$id.log")"
}
recorded a.txt 2 recorded.intruder_2
recorded none.txt 0 recorded.no_intruder
recorded two.txt 3 recorded.first_of_two
# the scene's mean grain radius divides, not the file's grains' (both 1 cm here): a mean of 2 gives 1
recorded a.txt 1 recorded.scene_mean r_min=1.5 r_max=2.5
# a value given beside it that agrees is kept (and the run is the file's)
recorded a.txt 2 accepted.agreeing radius_ratio=2
# the same bed as a LAMMPS data file: the intruder's diameter 4
shake_run w.log particles=a.txt "${RUN[@]}" duration=0 output=none write_lammps="$TMP/a.data" ||
	fail lammps.write "exit $?: $(head -c 300 w.log)"
recorded a.data 2 recorded.lammps

# refused: a radius_ratio that disagrees, on the command line and in a scene file, naming
# the file and the intruder's line, the key, where it was set and both values
shake_run bad.log particles=a.txt "${RUN[@]}" radius_ratio=4 output=bad.h5
rc=$?
[ "$rc" -eq 1 ] && contains bad.log "a.txt:13:" && contains bad.log "radius_ratio 2 " &&
	contains bad.log "radius_ratio = 4 is set at command line" && [ ! -e bad.h5 ] && ok refused.command_line ||
	fail refused.command_line "exit $rc: $(head -c 400 bad.log)"
printf 'particles = a.txt\nradius_ratio = 3\n' >s.ini
shake_run bad2.log s.ini "${RUN[@]}" output=bad2.h5
rc=$?
[ "$rc" -eq 1 ] && contains bad2.log "a.txt:13:" && contains bad2.log "radius_ratio = 3 is set at s.ini:2" &&
	[ ! -e bad2.h5 ] && ok refused.scene_file || fail refused.scene_file "exit $rc: $(head -c 400 bad2.log)"
shake_run bad3.log particles=none.txt "${RUN[@]}" radius_ratio=4 output=bad3.h5
rc=$?
[ "$rc" -eq 1 ] && contains bad3.log "none.txt: no intruder" && contains bad3.log "radius_ratio is 0" &&
	contains bad3.log "radius_ratio = 4 is set at command line" && [ ! -e bad3.h5 ] && ok refused.no_intruder ||
	fail refused.no_intruder "exit $rc: $(head -c 400 bad3.log)"
# within the rounding of a printed radius (1e-6) it agrees, beyond it not
recorded a.txt 2.0000000999999998 accepted.rounding radius_ratio=2.0000001
shake_run bad4.log particles=a.txt "${RUN[@]}" radius_ratio=2.00001 output=bad4.h5
[ $? -eq 1 ] && contains bad4.log "a.txt:13:" && ok refused.beyond_rounding || fail refused.beyond_rounding "$(head -c 300 bad4.log)"
# n_intruders is the file's count: 2 from two.txt, 1 from a.txt; a file without intruder
# leaves the key's default; given beside the file it must be the count
nint() { h5param "$1" n_intruders; }
for c in "two.txt 2 first_of_two" "a.txt 1 intruder_2" "none.txt 1 no_intruder"; do
	set -- $c
	[ "$(nint "recorded.$3.h5")" = "$2" ] && ok "n_intruders.$3" ||
		fail "n_intruders.$3" "n_intruders '$(nint "recorded.$3.h5" 2>/dev/null)', want $2 (from $1)"
done
shake_run n2.log particles=two.txt "${RUN[@]}" n_intruders=2 output=n2.h5
[ $? -eq 0 ] && [ "$(nint n2.h5)" = 2 ] && ok n_intruders.agreeing || fail n_intruders.agreeing "$(head -c 300 n2.log)"
shake_run n3.log particles=two.txt "${RUN[@]}" n_intruders=3 output=n3.h5
rc=$?
[ "$rc" -eq 1 ] && contains n3.log "two.txt:15: the file holds 2 intruders" &&
	contains n3.log "n_intruders = 3 is set at command line" && [ ! -e n3.h5 ] && ok n_intruders.refused ||
	fail n_intruders.refused "exit $rc: $(head -c 400 n3.log)"
# the checks that need an intruder see the file's: stop = risen over a file without one
shake_run risen.log particles=none.txt "${RUN[@]}" stop=risen output=risen.h5
[ $? -eq 1 ] && contains risen.log "stop = risen needs an intruder" && ok refused.stop_risen ||
	fail refused.stop_risen "$(head -c 300 risen.log)"

# --- a campaign: its runs record the file's ratio (param table, runs view, run file) ---
camp() { # NAME [SCENE-LINE...]
	printf '[campaign]\nname = %s\nseed = 1\n[scene]\nparticles = %s\nsettle = no\namplitude = 0\nduration = 0.02\n' \
		"$1" "$TMP/a.txt"
	printf 'snapshots = no\ntraj_rate = 0\n'
	shift
	printf '%s\n' "$@"
}
camp p '[grid]' 'frequency = 3, 4' >p.campaign
"$STUDY" run p.campaign --runs "$TMP/R" >p.log 2>&1
rc=$?
v=$(q R/study.db "SELECT DISTINCT radius_ratio FROM runs WHERE campaign = 'p'")
n=$(q R/study.db "SELECT COUNT(*) FROM runs WHERE campaign = 'p' AND state = 'done'")
f=$(ls R/p/*.h5 2>/dev/null | head -n 1)
[ "$rc" -eq 0 ] && [ "$v" = 2.0 ] && [ "$n" = 2 ] && [ -n "$f" ] && [ "$(ratio_of "$f")" = 2 ] && ok campaign.recorded ||
	fail campaign.recorded "exit $rc, runs view '$v', done $n, run file '$(ratio_of "$f" 2>/dev/null)': $(tail -n 5 p.log)"
# two intruders: the campaign's param rows count them
sed "s|$TMP/a.txt|$TMP/two.txt|; s/^name = p$/name = p2/" p.campaign >p2.campaign
"$STUDY" run p2.campaign --runs "$TMP/R" >p2.log 2>&1
rc=$?
v=$(q R/study.db "SELECT DISTINCT value FROM param WHERE campaign = 'p2' AND key = 'n_intruders'")
[ "$rc" -eq 0 ] && [ "$v" = 2 ] && ok campaign.n_intruders ||
	fail campaign.n_intruders "exit $rc, param rows' n_intruders '$v' (want 2): $(tail -n 3 p2.log)"
# a radius_ratio the campaign sets against the file: refused, nothing run
camp q 'radius_ratio = 4' >q.campaign
"$STUDY" run q.campaign --runs "$TMP/R" >q.log 2>&1
rc=$?
[ "$rc" -ne 0 ] && contains q.log "a.txt:13:" && contains q.log "radius_ratio = 4 is set at q.campaign:11" &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM attempt WHERE campaign = 'q'")" = 0 ] && ok campaign.refused ||
	fail campaign.refused "exit $rc: $(tail -n 3 q.log)"
# swept beside the file: the point that disagrees refuses the campaign
camp g '[grid]' 'radius_ratio = 2, 4' >g.campaign
"$STUDY" run g.campaign --runs "$TMP/R" >g.log 2>&1
rc=$?
[ "$rc" -ne 0 ] && contains g.log "radius_ratio = 4 is set at g.campaign:" && ok campaign.sweep_refused ||
	fail campaign.sweep_refused "exit $rc: $(tail -n 3 g.log)"
finish
