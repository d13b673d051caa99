#!/usr/bin/env bash
# determinism.sh - the same scene and seed give the same file apart from /provenance
# (every dataset and root attribute, compared as %.17g text and with h5diff), whatever
# the working directory, relative or absolute output path, scene file or command line,
# progress output or --profile; another seed gives another file.
# tier: slow: the same run a dozen ways, each compared with h5diff
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

# 150 grains, 1 s of gentle shaking: ~1000 neighbour-list builds, 5 snapshots
tiny_bed n_grains=150 width=24
SCENE=("${BEDARGS[@]}" duration=1
	"${GENTLE[@]}" traj_rate=200 snapshots=yes progress=no seed=7)

run() { # ID DIR args...
	local id=$1 dir=$2
	shift 2
	mkdir -p "$dir"
	(cd "$dir" && "$SHAKE" "$@" >"$TMP/$id.log" 2>&1)
	local rc=$?
	[ "$rc" -eq 0 ] || fail "$id.run" "exit $rc: $(head -c 300 "$TMP/$id.log")"
	return $rc
}

mkdir -p "$TMP/a"
# A: absolute output path, run from $TMP
run A "$TMP" "${SCENE[@]}" output="$TMP/a/out.h5" || finish
ok A.run
# B: same command line, another working directory, relative output path
run B "$TMP/b" "${SCENE[@]}" output=out.h5 && ok B.run
# C: from a scene file, relative path with .., progress and --profile on
mkdir -p "$TMP/c/sub"
printf '%s\n' "${SCENE[@]}" | sed 's/=/ = /; s/^progress = no$/progress = yes/' >"$TMP/scene.ini"
run C "$TMP/c/sub" "$TMP/scene.ini" output=../out.h5 --profile && ok C.run
# D: A's command again, same directory, same absolute path (identical attributes too)
mkdir -p "$TMP/d"
run D "$TMP" "${SCENE[@]}" output="$TMP/a/out.h5" && mv "$TMP/a/out.h5" "$TMP/d/out.h5" && mv "$TMP/a/out.xmf" "$TMP/d/out.xmf" && ok D.run
run A "$TMP" "${SCENE[@]}" output="$TMP/a/out.h5"

check same.rerun "rerun of the same command differs (beyond /provenance)" same_output a/out.h5 d/out.h5
check same.cwd_relative_path "relative path from another directory differs" same_output a/out.h5 b/out.h5 output
check same.scene_file_profile "scene file + --profile + progress differs" same_output a/out.h5 c/out.h5 output progress
check same.xdmf "XDMF sidecars differ" cmp -s a/out.xmf b/out.xmf

# E: another seed must change the result (so the comparison can fail)
run E "$TMP/e" "${SCENE[@]/seed=7/seed=8}" output=out.h5 && ok E.run
if same_output a/out.h5 e/out.h5 output 2>/dev/null; then
	fail different.seed "seed 8 gave the same output as seed 7"
else
	ok different.seed
fi
if cmp -s <(h5dump -m %.17g -d /final/x a/out.h5 | tail -n +2) <(h5dump -m %.17g -d /final/x e/out.h5 | tail -n +2); then
	fail different.seed_final "seed 8 gave the same /final/x as seed 7"
else
	ok different.seed_final
fi
# F: a physics change (mu) with the same seed changes the output too
run F "$TMP/f" "${SCENE[@]}" mu=0.49 output=out.h5 && ok F.run
if same_output a/out.h5 f/out.h5 output mu 2>/dev/null; then
	fail different.mu "mu = 0.49 gave the same output as mu = 0.5"
else
	ok different.mu
fi
# G: the fused corrector+predictor (used on steps nobody records) gives exactly the
#    state of the separate passes: recording every step disables the fusion
for integ in gear5 gear4 verlet; do
	shake_run "$TMP/g1.log" "${FAST[@]}" snapshots=no integrator=$integ traj_rate=0 output="$TMP/g1.h5"
	shake_run "$TMP/g2.log" "${FAST[@]}" snapshots=no integrator=$integ traj_rate=20000 output="$TMP/g2.h5"
	if h5diff -q "$TMP/g1.h5" "$TMP/g2.h5" /final /final >/dev/null 2>&1; then
		ok fused_predictor.$integ
	else
		fail fused_predictor.$integ "recording every step changed /final"
	fi
done
finish
