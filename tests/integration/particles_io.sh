#!/usr/bin/env bash
# particles_io.sh - write_particles / write_lammps after preparation give the same state
# in two formats: the files have the documented layout, agree with each other and with
# the run's /final state at t = 0, and runs started from either (settle = no) give
# identical /final and /particles data. Text files round-trip through a second write.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

shake_run prep.log "${FAST[@]}" duration=0 write_particles="$TMP/F.txt" write_lammps="$TMP/G.data" output="$TMP/prep.h5"
rc=$?
if [ "$rc" -ne 0 ] || [ ! -s F.txt ] || [ ! -s G.data ]; then
	fail write "exit $rc, F.txt/G.data missing: $(head -c 300 prep.log)"
	finish
fi
ok write
nm=$(attr prep.h5 /n_mobile) nw=$(attr prep.h5 /n_walls)
n=$((nm + nw))

# --- text format: x y r kind vx vy omega m, kinds grain/intruder/wall ---
awk '!/^[ \t]*(#|$)/' F.txt >F.rows
awk -v n="$n" 'NF != 8 { bad = "line " NR " has " NF " fields" }
	$4 !~ /^(grain|intruder|wall)$/ { bad = "line " NR " kind " $4 }
	{ for (i = 1; i <= 8; i++) if (i != 4 && $i !~ /^-?[0-9.]+(e[-+]?[0-9]+)?$/) bad = "line " NR " field " i " = " $i }
	END { if (NR != n) bad = NR " rows, expected " n; if (bad) { print bad; exit 1 } }' F.rows >fmt.err &&
	ok text.format || fail text.format "$(cat fmt.err)"
counts=$(awk '{ c[$4]++ } END { printf "%d %d %d", c["grain"], c["intruder"], c["wall"] }' F.rows)
[ "$counts" = "60 1 $nw" ] && ok text.kinds || fail text.kinds "grain/intruder/wall counts $counts, expected 60 1 $nw"
grep -q '^#.*x y r kind vx vy omega m' F.txt && ok text.header || fail text.header "no '# ... x y r kind vx vy omega m' header line"

# --- LAMMPS format ---
grep -qx "$n atoms" G.data && ok lammps.natoms || fail lammps.natoms "no '$n atoms' line"
grep -qx "3 atom types" G.data && ok lammps.ntypes || fail lammps.ntypes "no '3 atom types' line"
grep -q '^Atoms # sphere' G.data && ok lammps.atoms_section || fail lammps.atoms_section "no 'Atoms # sphere' section"
grep -qx 'Velocities' G.data && ok lammps.velocities_section || fail lammps.velocities_section "no 'Velocities' section"
grep -Eq '^-?[0-9.e+-]+ -?[0-9.e+-]+ xlo xhi$' G.data && grep -Eq '^-?[0-9.e+-]+ -?[0-9.e+-]+ ylo yhi$' G.data &&
	ok lammps.box || fail lammps.box "no xlo xhi / ylo yhi lines"
awk '/^Atoms/ { s = "A"; next } /^Velocities/ { s = "V"; next } /^[A-Za-z]/ { s = ""; next } NF == 0 { next }
	s == "A" { print > "G.atoms" } s == "V" { print > "G.vel" }' G.data
[ "$(wc -l <G.atoms)" = "$n" ] && [ "$(wc -l <G.vel)" = "$n" ] && ok lammps.rows ||
	fail lammps.rows "$(wc -l <G.atoms) Atoms and $(wc -l <G.vel) Velocities rows, expected $n"
# the two files hold the same state, in the same order: x, y exact, diameter = 2 r,
# type = kind + 1, velocities and omega exact, the density column 3 m / (4 pi r^3) of the
# text file's mass m to rounding
paste -d' ' F.rows G.atoms G.vel | awk '
	function rel(a, b) { d = a - b; if (d < 0) d = -d; return d / b }
	{ k = ($4 == "grain") ? 1 : ($4 == "intruder") ? 2 : 3
	  if ($9 != NR || $16 != NR) bad = "row " NR ": ids " $9 ", " $16
	  else if ($10 != k) bad = "row " NR ": type " $10 " for kind " $4
	  else if ($13 != $1 || $14 != $2) bad = "row " NR ": position differs"
	  else if ($11 + 0 != 2 * $3) bad = "row " NR ": diameter " $11 " radius " $3
	  else if (rel($12 * 4 * 3.141592653589793 * $3 ^ 3 / 3, $8) > 1e-12) bad = "row " NR ": density " $12 " for mass " $8
	  else if ($17 != $5 || $18 != $6 || $22 != $7) bad = "row " NR ": velocity differs" }
	END { if (bad) { print bad; exit 1 } }' >same.err && ok formats.same_state || fail formats.same_state "$(cat same.err)"
# and the writing run's state at t = 0: positions exactly, kinds and radii
h5col() { h5vals "$@"; } # lib.sh
paste -d' ' <(h5col prep.h5 /final/x) <(h5col prep.h5 /final/y) <(h5col prep.h5 /final/radius) <(h5col prep.h5 /final/species) F.rows |
	awk '{ k = ($8 == "grain") ? 0 : ($8 == "intruder") ? 1 : 2
	  if ($1 != $5 || $2 != $6 || $3 != $7 || $4 != k) { print "row " NR ": h5 " $1 " " $2 " " $3 " " $4 " file " $5 " " $6 " " $7 " " $8; exit 1 } }
	END { if (NR != '"$n"') { print NR " rows"; exit 1 } }' >h5.err &&
	ok formats.match_run_final || fail formats.match_run_final "$(cat h5.err)"

# --- runs from either file ---
RUN=(settle=no duration=0.2 "${GENTLE[@]}" traj_rate=200 snapshots=yes progress=no)
shake_run fromF.log particles="$TMP/F.txt" "${RUN[@]}" output="$TMP/fromF.h5"
rcF=$?
shake_run fromG.log particles="$TMP/G.data" "${RUN[@]}" output="$TMP/fromG.h5"
rcG=$?
if [ "$rcF" -ne 0 ] || [ "$rcG" -ne 0 ]; then
	fail runs "exit $rcF from F, $rcG from G: $(head -c 200 fromF.log) $(head -c 200 fromG.log)"
	finish
fi
ok runs
for g in /final /particles/bed /particles/walls /particles/intruder; do
	if h5diff fromF.h5 fromG.h5 "$g" "$g" >diff.out 2>&1; then ok "same_run.$g"; else
		fail "same_run.$g" "runs from the text and the LAMMPS file differ in $g: $(head -n 3 diff.out | tr '\n' ' ')"; fi
done
# the run did move things (so the comparison is not between two copies of the input)
if h5diff -q prep.h5 fromF.h5 /final/y /final/y >/dev/null 2>&1; then
	fail moved "/final/y after 0.2 s of shaking equals the prepared state"
else
	ok moved
fi
# and a physics change in one of them is seen
shake_run fromG2.log particles="$TMP/G.data" "${RUN[@]}" gamma_s=1.5 output="$TMP/fromG2.h5"
if h5diff -q fromF.h5 fromG2.h5 /final /final >/dev/null 2>&1; then
	fail teeth "gamma_s 1.5 gives the same /final as gamma_s 1"
else
	ok teeth
fi

# --- round trip: read F, write it again at once: positions, radii, kinds, masses exact,
#     velocities to rounding (v -> v dt -> v) ---
shake_run rt.log particles="$TMP/F.txt" settle=no duration=0 "${GENTLE[@]}" write_particles="$TMP/F2.txt" output="$TMP/rt.h5"
rc=$?
if [ "$rc" -ne 0 ] || [ ! -s F2.txt ]; then
	fail roundtrip "exit $rc: $(head -c 200 rt.log)"
else
	awk '!/^[ \t]*(#|$)/' F2.txt | paste -d' ' F.rows - | awk '
		function rel(a, b) { d = a - b; if (d < 0) d = -d; s = (a < 0 ? -a : a) + 1e-3; return d / s }
		{ if ($1 != $9 || $2 != $10 || $3 != $11 || $4 != $12 || $8 != $16) { print "row " NR ": position/radius/kind/mass differ"; exit 1 }
		  if ($4 != "wall" && (rel($5, $13) > 1e-12 || rel($6, $14) > 1e-12 || rel($7, $15) > 1e-12)) { print "row " NR ": velocities " $5 " " $6 " " $7 " vs " $13 " " $14 " " $15; exit 1 } }
		END { if (NR != '"$n"') { print NR " rows"; exit 1 } }' >rt.err && ok roundtrip || fail roundtrip "$(cat rt.err)"
fi
# --- a run from its own prepared state equals the run that settled itself: the
#     packing cache of the study driver relies on this (datasets bit-identical; only
#     the parameters naming the source and the settling record differ) ---
shake_run self.log "${FAST[@]}" "${GENTLE[@]}" write_particles="$TMP/self.txt" output="$TMP/self.h5"
rc1=$?
shake_run cached.log "${FAST[@]}" "${GENTLE[@]}" particles="$TMP/self.txt" settle=no output="$TMP/cached.h5"
rc2=$?
if [ "$rc1" -ne 0 ] || [ "$rc2" -ne 0 ]; then
	fail cache_identity "exit $rc1/$rc2: $(head -c 200 self.log cached.log)"
elif same_output "$TMP/self.h5" "$TMP/cached.h5" output particles settle settle_steps settle_time write_particles; then
	ok cache_identity
else
	fail cache_identity "the run from its own particle file differs from the one that settled"
fi
finish
