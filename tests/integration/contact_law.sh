#!/usr/bin/env bash
# contact_law.sh - what the contact law gives each class of pair (docs/model.md,
# "Restitution"), against the damped oscillator computed here: `shake --contacts` for the
# paper's law (the restitution varies with the pair's masses) and with restitution = 0.8
# (every pair of mobile disks 0.8, a grain on a wall 0.8 only with wall_mass = infinite);
# a run file's /contact_law holds the same numbers for a bed of equal grains; restitution
# beside gamma_n is refused naming both; a shaken bed with restitution runs. The tangential
# law and its k_t are shown and recorded, a shear stiffness beside the viscous law refused.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

# oscillator M C: e and t_c of m xi'' = -Y xi - c xi' (Y = 3e6), m = M, c = C
oscillator() {
	awk -v m="$1" -v c="$2" 'BEGIN { Y = 3e6; pi = atan2(0, -1); b = c / (2 * m); w = sqrt(Y / m - b * b)
		printf "%.5g %.5g\n", exp(-b * pi / w), pi / w }'
}
# row FILE PAIR: "restitution contact_time" of a pair's line of --contacts
row() { awk -v p="$2" '$1 == p { printf "%s %s\n", $4, $5 }' "$1"; }
pi=$(awk 'BEGIN { printf "%.17g", atan2(0, -1) }')

# --- the paper's law: unit grains (m = 2 pi), an intruder of R = 4 (m = 32 pi), a wall disk
# of the grain's radius (wall_radius 1), gamma_n = 100 ---
"$SHAKE" --contacts r_min=1 r_max=1 wall_radius=1 >paper.txt 2>paper.err
rc=$?
gg=$(oscillator "$pi" "$(awk -v p="$pi" 'BEGIN { printf "%.17g", 100 * p }')") # m_eff = pi
gi=$(awk -v p="$pi" 'BEGIN { m = 2 * p * 32 * p / (34 * p); printf "%.17g %.17g", m, 100 * m }')
gi=$(oscillator $gi)
gw=$(awk -v p="$pi" 'BEGIN { printf "%.17g %.17g", 2 * p, 100 * p }') # moves: the grain; c = gamma_n m_eff
gw=$(oscillator $gw)
[ "$rc" -eq 0 ] && [ "$(row paper.txt grain_grain)" = "$gg" ] && [ "$(row paper.txt grain_intruder)" = "$gi" ] &&
	[ "$(row paper.txt grain_wall)" = "$gw" ] && ok contacts.paper_law ||
	fail contacts.paper_law "exit $rc; want $gg | $gi | $gw; got $(tr '\n' '|' <paper.txt) $(cat paper.err)"
# the numbers docs/model.md quotes for the paper's bed (mean radius 1 cm)
"$SHAKE" --contacts >bed.txt 2>&1
awk '$1 == "grain_grain" && $4 > 0.845 && $4 < 0.855 && $5 > 0.00315 && $5 < 0.00325 { a = 1 }
	$1 == "grain_intruder" && $4 > 0.795 && $4 < 0.805 { b = 1 } END { exit !(a && b) }' bed.txt &&
	ok contacts.paper_bed_as_documented || fail contacts.paper_bed_as_documented "$(cat bed.txt)"

# --- restitution = 0.8: every pair of mobile disks 0.8; a wall of infinite mass too ---
"$SHAKE" --contacts r_min=1 r_max=1 wall_radius=1 restitution=0.8 wall_mass=infinite >e.txt 2>&1
rc=$?
[ "$rc" -eq 0 ] && [ "$(awk '$1 ~ /_/ && $1 != "pair" { print $4 }' e.txt | sort -u)" = 0.8 ] &&
	[ "$(awk '$1 ~ /_/ && $1 != "pair"' e.txt | wc -l)" = 4 ] && ok contacts.restitution_every_pair ||
	fail contacts.restitution_every_pair "exit $rc: $(tr '\n' '|' <e.txt)"
# a wall disk of finite mass does not move: its grain rebounds more (m_eff = pi, m = 2 pi)
"$SHAKE" --contacts r_min=1 r_max=1 wall_radius=1 restitution=0.8 >ed.txt 2>&1
want=$(awk -v p="$pi" 'BEGIN { l = log(0.8); z = -l / sqrt(p * p + l * l); printf "%.17g %.17g", 2 * p, 2 * z * sqrt(3e6 * p) }')
want=$(oscillator $want)
[ "$(row ed.txt grain_wall)" = "$want" ] && awk -v w="${want% *}" 'BEGIN { exit !(w > 0.84) }' &&
	ok contacts.restitution_wall_disk || fail contacts.restitution_wall_disk "want $want: $(tr '\n' '|' <ed.txt)"

# --- refused: both keys set ---
"$SHAKE" --contacts restitution=0.8 gamma_n=50 >both.txt 2>&1
rc=$?
[ "$rc" -eq 1 ] && grep -q "restitution = 0.8 sets the normal damping of every pair; gamma_n (command line) cannot be set" both.txt &&
	ok restitution.refused_beside_gamma_n || fail restitution.refused_beside_gamma_n "exit $rc: $(cat both.txt)"
"$SHAKE" --contacts restitution=1.2 >range.txt 2>&1
[ $? -eq 1 ] && grep -q "restitution: expected a number in \[0, 1\], got '1.2'" range.txt && ok restitution.range ||
	fail restitution.range "$(cat range.txt)"

# --- normal = hertz: undamped, the closed form t_c = 2 I dmax / v, dmax = (5 m v^2 / (4 K
# sqrt(R_eff)))^(2/5), I = 1.47164 (the integral of 1 / sqrt(1 - x^5/2) on [0, 1]), at the
# records' 20 cm/s, e = 1; the default hertz_stiffness gives a mean grain pair (m_eff = pi,
# R_eff = 1/2) the hooke law's undamped 3.2149 ms ---
"$SHAKE" --contacts r_min=1 r_max=1 normal=hertz gamma_n=0 >hz.txt 2>&1
rc=$?
want=$(awk -v p="$pi" 'BEGIN { m = p; d = (5 * m * 400 / (4 * 3.15e7 * sqrt(0.5))) ^ 0.4; printf "1 %.5g", 2 * 1.47164 * d / 20 }')
[ "$rc" -eq 0 ] && [ "$(row hz.txt grain_grain)" = "$want" ] &&
	awk '$1 == "grain_grain" { exit !($5 > 0.003213 && $5 < 0.003217) }' hz.txt && ok contacts.hertz_closed_form ||
	fail contacts.hertz_closed_form "exit $rc; want $want: $(tr '\n' '|' <hz.txt)"
"$SHAKE" --contacts normal=hertz restitution=0.8 >hze.txt 2>&1
[ $? -eq 1 ] && grep -q "restitution is for normal = hooke (command line): with hertz the restitution" hze.txt &&
	ok restitution.refused_with_hertz || fail restitution.refused_with_hertz "$(cat hze.txt)"

# --- a run file's /contact_law: a bed of equal grains gives --contacts' numbers ---
tiny_bed r_min=1 r_max=1 wall_radius=1 radius_ratio=4 width=24
shake_run run.log "${BEDARGS[@]}" duration=0.05 snapshots=no output=r.h5 || fail run "exit $?: $(tail -n 2 run.log)"
"$SHAKE" --contacts "${BEDARGS[@]}" >bedc.txt 2>&1
got=""
for p in grain_grain grain_intruder grain_wall lightest_pair; do
	got+="$p $(printf '%.5g %.5g' "$(attr r.h5 /contact_law/$p/restitution)" "$(attr r.h5 /contact_law/$p/contact_time)");"
done
want=$(awk '$1 ~ /_/ && $1 != "pair" { printf "%s %s %s;", $1, $4, $5 }' bedc.txt)
[ "$got" = "$want" ] && [ "$(attr r.h5 /contact_law/damping)" = gamma_n ] && ok runfile.contact_law ||
	fail runfile.contact_law "file $got; --contacts $want"
# with restitution: the bed shakes, and its file says which key set the damping
shake_run e.log "${BEDARGS[@]}" restitution=0.8 frequency=4 amplitude=1 duration=0.3 snapshots=no output=e.h5
rc=$?
[ "$rc" -eq 0 ] && [ "$(attr e.h5 /contact_law/damping)" = restitution ] &&
	[ "$(printf '%.6f' "$(attr e.h5 /contact_law/grain_intruder/restitution)")" = 0.800000 ] && ok runfile.restitution ||
	fail runfile.restitution "exit $rc: $(tail -n 2 e.log)"
# a hertz bed shakes, and its file says so
shake_run h.log "${BEDARGS[@]}" normal=hertz frequency=4 amplitude=1 duration=0.3 snapshots=no output=h.h5
rc=$?
[ "$rc" -eq 0 ] && [ "$(attr h.h5 /contact_law/normal)" = hertz ] && [ "$(attr h.h5 /contact_law/impact_speed)" = 20 ] &&
	ok runfile.hertz || fail runfile.hertz "exit $rc: $(tail -n 2 h.log)"

# --- the tangential law (docs/model.md, "Tangential law"): k_t's default is 2/7 of the
# normal stiffness, shown by --contacts and recorded in /contact_law; a shear stiffness
# beside the viscous law, or out of its range, is refused naming the key ---
"$SHAKE" --contacts tangential=spring >sp.txt 2>&1
grep -q '^# tangential = spring: shear_stiffness k_t = 857143 ' sp.txt &&
	"$SHAKE" --contacts tangential=spring normal=hertz | grep -q 'k_t = 9e+06 ' && ok tangential.contacts_kt ||
	fail tangential.contacts_kt "$(head -3 sp.txt)"
"$SHAKE" --contacts shear_stiffness=1e6 >sv.txt 2>&1
rc=$?
[ "$rc" = 1 ] && grep -q 'command line: shear_stiffness = 1e+06 is for tangential = spring (default' sv.txt &&
	ok tangential.kt_refused_with_viscous || fail tangential.kt_refused_with_viscous "exit $rc: $(cat sv.txt)"
printf 'tangential = spring\nshear_stiffness = 2e15\n' >kt.ini
"$SHAKE" kt.ini --contacts >sr.txt 2>&1
rc=$?
[ "$rc" = 1 ] && grep -q 'kt.ini:2: shear_stiffness: expected a number in \[0, 1e+15\]' sr.txt &&
	ok tangential.kt_range || fail tangential.kt_range "exit $rc: $(cat sr.txt)"
shake_run t.log "${BEDARGS[@]}" tangential=spring shear_stiffness=5e5 frequency=4 amplitude=1 duration=0.3 snapshots=no output=t.h5
rc=$?
[ "$rc" -eq 0 ] && [ "$(attr t.h5 /contact_law/tangential)" = spring ] && [ "$(attr t.h5 /contact_law/shear_stiffness)" = 500000 ] &&
	[ "$(attr r.h5 /contact_law/tangential)" = viscous ] && [ -z "$(attr r.h5 /contact_law/shear_stiffness)" ] &&
	ok runfile.tangential || fail runfile.tangential "exit $rc: $(tail -n 2 t.log)"

# --- open question 6's law (campaigns/reproduce/q6_*): its gamma_n was found by hand for
# e = 0.900 of a mean grain pair under Hertz at the recorded impact speed; both campaigns
# share it, and --contacts gives the restitutions their header states ---
q6=("$REPO"/campaigns/reproduce/q6_law_onset.campaign "$REPO"/campaigns/reproduce/q6_law_rise.campaign)
key() { awk -F'=' -v k="$1" '$1 ~ "^"k"[ \t]*$" { gsub(/[ \t]/, "", $2); print $2; exit }' "$2"; }
gn=$(key gamma_n "${q6[0]}")
if [ -n "$gn" ] && [ "$gn" = "$(key gamma_n "${q6[1]}")" ] &&
	"$SHAKE" --contacts normal="$(key normal "${q6[0]}")" tangential="$(key tangential "${q6[0]}")" gamma_n="$gn" >q6.txt 2>&1; then
	# the header's "grain-grain 0.900, grain-intruder 0.845, grain-wall 0.923"
	said=$(sed -n 's/^# *//p' "${q6[0]}" | tr '\n' ' ' | grep -o 'grain-grain [0-9.]*, grain-intruder [0-9.]*, grain-wall [0-9.]*' |
		tr -dc '0-9. ' | xargs)
	got=$(awk '$1 == "grain_grain" || $1 == "grain_intruder" || $1 == "grain_wall" { printf "%s%.3f", n++ ? " " : "", $4 }' q6.txt)
	[ "$(awk '$1 == "grain_grain" { print ($4 > 0.8995 && $4 < 0.9005) }' q6.txt)" = 1 ] && [ "$got" = "$said" ] &&
		ok q6.restitution_0.900 || fail q6.restitution_0.900 "gamma_n $gn gives $got, the header says '$said', want grain_grain 0.900"
else
	fail q6.restitution_0.900 "the q6 campaigns' gamma_n '$gn' differ or --contacts failed: $(tail -n 2 q6.txt 2>/dev/null)"
fi
finish
