#!/usr/bin/env bash
# lammps_collisions.sh - the two-disk collisions of every contact law (hooke, restitution,
# hertz, and the shear spring with history: spring, hertz_spring) agree with LAMMPS:
# tests/bench/lammps_collisions.sh (`make validate-collisions`, its header states the
# cases and tolerances: restitution, contact time, rebound spin) run on the sanitizer build
# of its engine side, every law's rows present; and the comparison can fail: a shear
# stiffness 1 % off on the engine's side alone is caught in the oblique collision.
# tier: slow: 35 collisions in both codes, each engine run at two steps (about three minutes)
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

command -v lmp >/dev/null || { fail setup "lmp (Debian package lammps) is not installed: make deps"; finish; }
BIN=$(dirname "$SHAKE")/../tests/bench/lammps_collision
[ -x "$BIN" ] || { fail setup "$BIN is not built (make tests)"; finish; }

COLL_BIN=$BIN bash "$REPO/tests/bench/lammps_collisions.sh" >all.txt 2>&1
rc=$?
[ "$rc" = 0 ] && ok collisions.agree || fail collisions.agree "exit $rc: $(grep -v ' agree$' all.txt | head -c 1500)"
for law in hooke restitution hertz spring hertz_spring; do
	n=$(awk -v l="$law" '$1 == l && $NF == "agree"' all.txt | wc -l)
	[ "$n" = 7 ] && ok "collisions.$law.all_cases" || fail "collisions.$law.all_cases" "$n of 7 cases agree"
done

# k_t 1 % off (2/7 of 3e6 is 857142.857): the oblique collision's spin and e move
COLL_LAWS=spring COLL_CASES=oblique COLL_ENGINE_ARGS=shear_stiffness=865714.2857 COLL_BIN=$BIN \
	bash "$REPO/tests/bench/lammps_collisions.sh" >kt.txt 2>&1
rc=$?
[ "$rc" = 1 ] && grep -q '^spring .*DIFFER$' kt.txt && ok collisions.spring.kt_change_caught ||
	fail collisions.spring.kt_change_caught "exit $rc: $(head -c 600 kt.txt)"
finish
