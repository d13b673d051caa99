#!/usr/bin/env bash
# figures_run.sh - bin/figures --run RUN.h5: one run's field, Phi(D) and intruder height,
# from its file alone. Each figure (PNG, PDF, script, CSV) is drawn when the run recorded
# what it needs; the Phi(D) table is the file's per-line mean over the periods after the
# skip, with its standard error (recomputed with h5py); the height table is the
# trajectory less the box's motion. A run with nothing to draw: exit 1 and said; a figure
# not drawn is named with the reason; a missing directory or file is refused.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1
FIGURES=$(dirname "$SHAKE")/figures
shake_run a.log "${FAST[@]}" "${GENTLE[@]}" duration=2 flux=yes field=yes field_periods=2 output=a.h5 ||
	{ fail run "exit $?: $(tail -n 2 a.log)"; finish; }
mkdir out
"$FIGURES" --run a.h5 --out out >f.out 2>f.err
rc=$?
[ "$rc" = 0 ] && ok exit_0 || fail exit_0 "exit $rc: $(tail -n 3 f.err)"
for w in field phi height; do
	if [ -s "out/a_$w.png" ] && [ -s "out/a_$w.pdf" ] && [ -s "out/a_$w.csv" ] && grep -q "# figure: out/a_$w.png" f.out; then
		ok "drawn.$w"
	else
		fail "drawn.$w" "$(ls out) $(cat f.out)"
	fi
done
bad=$(/usr/bin/python3 - <<'PY'
import csv, numpy as np, h5py
bad = []
with h5py.File("a.h5", "r") as f:
    phi = f["observables/flux/phi/value"][...]
    h = f["observables/flux/heights"][...]
    p0 = int(np.floor(0.2 * phi.shape[0]))
    m = phi[p0:].mean(0)
    se = phi[p0:].std(0, ddof=1) / np.sqrt(phi.shape[0] - p0)
    rows = np.array([[float(x) for x in r] for r in list(csv.reader(open("out/a_phi.csv")))[1:]])
    if rows.shape != (len(h), 4) or np.abs(rows[:, 0] - h).max() > 1e-4 * max(1, h.max()):
        bad.append("phi heights")
    elif np.abs(rows[:, 1] - m).max() > 1e-5 * max(1, abs(m).max()) or np.abs(rows[:, 3] - rows[:, 1] - se).max() > 1e-5 * max(1, se.max()):
        bad.append("phi means or errors: %s vs %s" % (rows[:3, 1], m[:3]))
    t = f["particles/intruder/position/time"][...]
    y = f["particles/intruder/position/value"][:, 0, 1]
    A, fr = f["parameters"].attrs["amplitude"], f["parameters"].attrs["frequency"]
    hb = np.array([[float(x) for x in r] for r in list(csv.reader(open("out/a_height.csv")))[1:]])
    if hb.shape != (len(t), 2) or np.abs(hb[:, 1] - (y - A * np.sin(2 * np.pi * fr * t))).max() > 1e-4:
        bad.append("height not the trajectory less the box")
print("; ".join(bad))
PY
)
[ -z "$bad" ] && ok tables_are_the_files || fail tables_are_the_files "$bad"

# nothing to draw: no flux, no field, no intruder
shake_run b.log "${FAST[@]}" "${GENTLE[@]}" radius_ratio=0 traj_rate=0 output=b.h5 || fail run_b "exit $?"
"$FIGURES" --run b.h5 --out out >g.out 2>g.err
rc=$?
[ "$rc" = 1 ] && grep -q "b.h5: nothing to draw" g.err && grep -q "not drawn: Phi(D) (b.h5: no /observables/flux" g.out &&
	grep -q "not drawn: the intruder's height" g.out && ok nothing_to_draw || fail nothing_to_draw "exit $rc: $(cat g.out g.err)"
"$FIGURES" --run a.h5 --out nodir >/dev/null 2>h.err
[ $? = 1 ] && grep -q "nodir: no such directory" h.err && ok refuse.no_dir || fail refuse.no_dir "$(cat h.err)"
"$FIGURES" --run nothere.h5 --out out >/dev/null 2>h.err
[ $? = 2 ] && grep -q "nothere.h5" h.err && ok refuse.no_file || fail refuse.no_file "$(cat h.err)"
"$FIGURES" --run a.h5 --skip 1 >/dev/null 2>h.err
[ $? = 1 ] && grep -q "skip: expected a fraction in \[0, 1)" h.err && ok refuse.skip || fail refuse.skip "$(cat h.err)"
finish
