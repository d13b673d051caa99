#!/usr/bin/env bash
# python_reader.sh - the Python package python/shakebox (docs/output.md and
# docs/database.md, "From Python") under Debian's /usr/bin/python3: shakebox.Run gives a
# run with every observable on as h5py reads it raw (positions, times, steps, a flux
# series, the field, the outcome and parameters), each unit the file's own (a unit
# changed in a copy comes back changed); it refuses a file that is no run file (no
# /h5md, another format, not HDF5), naming it; its formats are core/io/h5id.h's.
# shakebox.universe opens that run in MDAnalysis with the bed's atom count, ids, masses,
# radii and types, and frames equal to the file's positions, velocities, times and steps;
# a run without snapshots is refused naming the file. python3 -m shakebox.h5md_check
# reports on the run exactly the violations docs/output.md lists ("H5MD conformance")
# and the contacts group as a deviation, and a copy damaged with h5py (/h5md@version
# deleted, a step of the wrong length) for what was damaged. shakebox.runs gives the tiny
# campaign's rows with the runs view's columns and each run's file, which exists and is
# that run; as a DataFrame with pandas, and without pandas a clear error. Every Python
# example of the two docs' "From Python" sections runs.
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1
PY=/usr/bin/python3
if ! "$PY" -c 'import numpy, h5py, MDAnalysis' 2>/dev/null; then
	fail setup "$PY cannot import numpy, h5py and MDAnalysis (Debian python3-h5py, python3-mdanalysis): run make deps-test"
	finish
fi
# nothing written in the clone (no __pycache__ beside the package)
export PYTHONPATH="$REPO/python" PYTHONDONTWRITEBYTECODE=1

shake_run s.log "${FAST[@]}" "${GENTLE[@]}" duration=1 flux=yes field=yes field_periods=1 energy_rate=20 \
	contact_rate=20 ring=yes bed_kinetic_samples=4 bed_height_samples=4 output=s.h5 ||
	{ fail run "exit $?: $(tail -n 2 s.log)"; finish; }
shake_run n.log "${FAST[@]}" "${GENTLE[@]}" snapshots=no output=n.h5 || { fail run_nosnap "exit $?: $(tail -n 2 n.log)"; finish; }
tiny_campaign t >t.campaign
fixture_runs t.campaign R || { fail setup "exit $?: $(tail -n 3 R.log)"; finish; }

# what the others say: the engine's formats, the doc's list of violations
sed -n 's/^#define H5ID_FORMAT\(_OLD[0-9]*\)\{0,1\} "\(.*\)"$/\2/p' "$REPO/core/io/h5id.h" >formats.txt
awk '/<!-- h5md_check violations: begin -->/ { on = 1; next } /<!-- h5md_check violations: end -->/ { on = 0 }
	on && /^- / { sub(/^- /, ""); gsub(/`/, ""); print }' "$REPO/docs/output.md" >known.txt
grep -q '<!-- h5md_check violations: begin -->' "$REPO/docs/output.md" ||
	fail setup "docs/output.md has no list between <!-- h5md_check violations: begin/end -->"

# the check on the run and on damaged copies (the command line, as a user runs it)
"$PY" -m shakebox.h5md_check s.h5 >chk.out 2>chk.err
echo $? >chk.rc
cp s.h5 nov.h5 && cp s.h5 step.h5
"$PY" - <<'PY' 2>dmg.err || fail setup "damaging the copies: $(tail -n 2 dmg.err)"
import h5py
with h5py.File("nov.h5", "r+") as f:
    del f["h5md"].attrs["version"]
with h5py.File("step.h5", "r+") as f:
    g = f["observables/flux/phi"]
    s = g["step"][...]
    del g["step"]
    g["step"] = s[:-1]
PY
"$PY" -m shakebox.h5md_check nov.h5 >nov.out 2>&1
rc=$?
check h5md.damaged_version "exit $rc: $(grep -F /h5md: nov.out | head -c 400)" eval '[ $rc = 1 ] &&
	grep -q "^nov.h5: violation: /h5md: no attribute version" nov.out'
"$PY" -m shakebox.h5md_check step.h5 >step.out 2>&1
rc=$?
check h5md.damaged_step "exit $rc: $(grep -F /flux/ step.out | head -c 400)" eval '[ $rc = 1 ] &&
	grep -q "^step.h5: violation: /observables/flux/phi/value: has 4 rows, step 3: the first dimension of value must match" step.out'

"$PY" - s.h5 n.h5 R/study.db >py.out 2>py.err <<'PY'
import os, shutil, sqlite3, sys, warnings
warnings.filterwarnings("ignore")
import numpy as np, h5py
import shakebox
from shakebox import h5md_check

run_h5, nosnap_h5, db = sys.argv[1:4]
def check(name, cond, why=""):
    print(("ok " + name) if cond else ("FAIL %s: %s" % (name, why)))
def refused(name, fn, words):
    try:
        fn()
    except shakebox.RunFileError as e:
        check(name, all(w in str(e) for w in words), "message %r lacks %r" % (str(e), words))
    else:
        check(name, False, "no RunFileError")
def unit(ds):
    u = ds.attrs.get("unit")
    return u.decode() if isinstance(u, bytes) else u

formats = tuple(open("formats.txt").read().split())
check("reader.formats_are_the_engines", shakebox.FORMATS == formats, "%s vs core/io/h5id.h %s" % (shakebox.FORMATS, formats))

# --- the reader against h5py's raw reads ---
run = shakebox.Run(run_h5)
with h5py.File(run_h5, "r") as f:
    pos = f["particles/bed/position"]
    p = run.positions
    check("reader.positions", np.array_equal(p.value, pos["value"][...]) and p.value.dtype == pos["value"].dtype
          and np.array_equal(run.times, pos["time"][...]) and np.array_equal(run.steps, pos["step"][...])
          and len(run.times) >= 4, "%s %s" % (p, run.times))
    check("reader.velocities_angles", np.array_equal(run.velocities.value, f["particles/bed/velocity/value"][...])
          and np.array_equal(run.angles.value, f["particles/bed/angle/value"][...]))
    phi = run.observables["flux"]["phi"]
    raw = f["observables/flux/phi"]
    check("reader.flux_series", np.array_equal(phi.value, raw["value"][...]) and np.array_equal(phi.step, raw["step"][...])
          and np.array_equal(phi.time, raw["time"][...]) and phi.value.shape[0] >= 3, repr(phi))
    ux = run.observables["field"]["ux"]
    check("reader.field", np.array_equal(ux.value, f["observables/field/ux/value"][...]) and ux.value.ndim == 3
          and run.observables["field"].attrs["cell"] == f["observables/field"].attrs["cell"], repr(ux))
    check("reader.observables_present", sorted(run.observables) == sorted(f["observables"]), sorted(run.observables))
    # every unit the reader gives is the file's attribute, as a string
    bad = []
    groups = {"/particles/bed": run.bed, "/particles/walls": run.walls, "/particles/intruder": run.intruder,
              "/particles/bed/box": run.box, "/final": run.final}
    groups.update({"/observables/" + k: run.observables[k] for k in run.observables})
    n = 0
    for g, els in groups.items():
        for k, e in els.items():
            obj = f[g + "/" + k]
            ds = obj if isinstance(obj, h5py.Dataset) else obj["value"]
            n += 1
            if e.unit != unit(ds) or not isinstance(e.unit, str):
                bad.append("%s/%s: %r vs %r" % (g, k, e.unit, unit(ds)))
            if not isinstance(obj, h5py.Dataset) and "time" in obj and e.time_unit != unit(obj["time"]):
                bad.append("%s/%s time: %r" % (g, k, e.time_unit))
    check("reader.units_are_the_files", not bad and n > 40 and p.unit == unit(pos["value"]) and run.times is not None,
          "; ".join(bad[:3]) or "%d elements" % n)
    check("reader.outcome_parameters", run.outcome["status"] == f.attrs["status"].decode()
          and run.outcome["waiting_time"] == f.attrs["waiting_time"] and run.parameters["frequency"] == 4.0
          and run.parameters["flux"] == "yes" and run.format == formats[0], repr((run.outcome["status"], run.parameters["frequency"])))
run.close()
# a unit changed in a copy comes back changed: nothing is typed again in Python
shutil.copy(run_h5, "unit.h5")
with h5py.File("unit.h5", "r+") as f:
    f["particles/bed/position/value"].attrs["unit"] = "m"
    f["observables/flux/phi/time"].attrs["unit"] = "ms"
with shakebox.Run("unit.h5") as r:
    check("reader.units_from_the_file", r.positions.unit == "m" and r.observables["flux"]["phi"].time_unit == "ms",
          "%r %r" % (r.positions.unit, r.observables["flux"]["phi"].time_unit))

# --- files that are no run files, refused with their names ---
with h5py.File("plain.h5", "w") as f:
    f["x"] = np.arange(3)
refused("reader.refuses_no_h5md", lambda: shakebox.Run("plain.h5"), ["plain.h5", "/h5md"])
shutil.copy(run_h5, "other.h5")
with h5py.File("other.h5", "r+") as f:
    f.attrs["format"] = np.bytes_("lammps-run-1")
refused("reader.refuses_other_format", lambda: shakebox.Run("other.h5"), ["other.h5", "lammps-run-1", formats[0]])
refused("reader.refuses_not_hdf5", lambda: shakebox.Run("formats.txt"), ["formats.txt", "not an HDF5 file"])
refused("reader.refuses_missing", lambda: shakebox.Run("gone.h5"), ["gone.h5", "no such file"])
with h5py.File("linked.h5", "w") as f:
    pass
shutil.copy(run_h5, "link.h5")
with h5py.File("link.h5", "r+") as f:
    f["particles/elsewhere"] = h5py.ExternalLink("linked.h5", "/")
refused("reader.refuses_external_link", lambda: shakebox.Run("link.h5"), ["link.h5", "/particles/elsewhere", "link"])

# --- MDAnalysis ---
u = shakebox.universe(run_h5)
with h5py.File(run_h5, "r") as f:
    P, V = f["particles/bed/position/value"][...], f["particles/bed/velocity/value"][...]
    T, S = f["particles/bed/position/time"][...], f["particles/bed/position/step"][...]
    bed = {k: f["particles/bed/" + k][...] for k in ("id", "mass", "radius", "species")}
    has = all(k in f["observables"] for k in ("flux", "field", "energy", "contacts", "ring"))
check("mda.atoms", has and u.atoms.n_atoms == P.shape[1] and np.array_equal(u.atoms.ids, bed["id"])
      and np.array_equal(u.atoms.masses, bed["mass"]) and np.array_equal(u.atoms.radii, bed["radius"]),
      "%d atoms, observables all there: %s" % (u.atoms.n_atoms, has))
check("mda.types", list(u.atoms.types) == ["intruder" if s == 1 else "grain" for s in bed["species"]]
      and list(u.atoms.types).count("intruder") == 1, str(sorted(set(u.atoms.types))))
bad = []
for rnd in range(2):  # twice: MDAnalysis reopens the trajectory at each iteration
    for ts in u.trajectory:
        k = ts.frame
        if not np.array_equal(ts.positions[:, :2], P[k].astype(np.float32)) or np.any(ts.positions[:, 2] != 0):
            bad.append("positions of frame %d" % k)
        if not np.array_equal(ts.velocities[:, :2], V[k].astype(np.float32)):
            bad.append("velocities of frame %d" % k)
        if ts.time != T[k] or ts.data["step"] != S[k]:
            bad.append("time/step of frame %d" % k)
check("mda.frames_are_the_files", not bad and len(u.trajectory) == P.shape[0] >= 4, "; ".join(bad[:3]))
u.trajectory.close()
refused("mda.refuses_no_snapshots", lambda: shakebox.universe(nosnap_h5), [nosnap_h5, "no snapshots"])

# --- the H5MD check: exactly the documented violations, the contacts as a deviation ---
found = h5md_check.check(run_h5)
got = sorted(set(w + ": " + what for kind, w, what, _, _ in found if kind == "violation"))
known = sorted(set(open("known.txt").read().splitlines()))
check("h5md.violations_are_the_documented", got == known, "the check: %s; docs/output.md: %s"
      % (sorted(set(got) - set(known)), sorted(set(known) - set(got))))
check("h5md.contacts_deviation", any(k == "deviation" and w == "/observables/contacts" for k, w, _, _, _ in found),
      str([(k, w) for k, w, _, _, _ in found]))
check("h5md.exit", open("chk.rc").read().strip() == ("1" if known else "0") and
      sum(1 for l in open("chk.out") if ": violation: " in l) == len(known), open("chk.out").read()[:300])

# --- the database ---
con = sqlite3.connect(db)
view = [r[1] for r in con.execute("PRAGMA table_info(runs)")]
n = con.execute("SELECT count(*) FROM runs WHERE campaign = 't'").fetchone()[0]
con.close()
rows = shakebox.runs(db, "t")
check("db.rows", len(rows) == n == 4 and all(list(r) == view + ["run_file"] for r in rows),
      "%d rows of %d; columns %s" % (len(rows), n, list(rows[0])[:5] if rows else None))
bad = []
for r in rows:
    want = os.path.join(os.path.dirname(os.path.abspath(db)), "t", r["id"] + ".h5")
    if r["state"] != "done" or r["run_file"] != want or not os.path.isfile(r["run_file"]):
        bad.append("%s: %s %s" % (r["id"], r["state"], r["run_file"]))
        continue
    with shakebox.Run(r["run_file"]) as x:
        if x.parameters["run_id"] != r["id"] or x.outcome["status"] != r["status"] or x.parameters["frequency"] != r["frequency"]:
            bad.append("%s: the file is not its run" % r["id"])
check("db.run_files", not bad, "; ".join(bad[:3]))
try:
    shakebox.runs(db, "nosuch")
    check("db.unknown_campaign", False, "no error")
except ValueError as e:
    check("db.unknown_campaign", db in str(e) and "nosuch" in str(e), str(e))
try:
    import pandas
except ImportError:
    print("SKIP db.dataframe: no pandas here (Debian python3-pandas: make deps-test)")
else:
    d = shakebox.runs(db, "t", as_dataframe=True)
    check("db.dataframe", list(d.columns) == view + ["run_file"] and len(d) == 4
          and sorted(d["id"]) == sorted(r["id"] for r in rows), str(d.shape))
sys.modules["pandas"] = None  # as if it were not installed
try:
    shakebox.runs(db, as_dataframe=True)
    check("db.no_pandas", False, "no error")
except ImportError as e:
    check("db.no_pandas", "python3-pandas" in str(e), str(e))
PY
rc=$?
# the checks Python made, counted here as this script's own
while IFS= read -r l; do
	case $l in
	"ok "*) ok "${l#ok }" ;;
	"FAIL "*) l=${l#FAIL }; fail "${l%%: *}" "${l#*: }" ;;
	"SKIP "*) l=${l#SKIP }; skip "${l%%: *}" "${l#*: }" ;;
	*) echo "$l" ;;
	esac
done <py.out
[ "$rc" -eq 0 ] || fail python "exit $rc: $(grep -v xdrlib py.err | tail -n 3)"

# every Python example of the docs' "From Python" sections runs, in a directory holding
# what they name: run.h5 (the run above) and runs/study.db (the tiny campaign)
mkdir -p ex && cp s.h5 ex/run.h5 && cp -r R ex/runs
for doc in docs/output.md docs/database.md; do
	# the indented block after each marker line, one file each
	awk -v pre="ex/${doc##*/}." '/<!-- python_reader: example -->/ { on = 1; got = 0; n++; out = pre n ".py"; next }
		on && /^    / { sub(/^    /, ""); print > out; got = 1; next }
		on && /^$/ { if (got) print "" > out; next }
		{ on = 0 }' "$REPO/$doc"
	n=$(ls ex/"${doc##*/}".*.py 2>/dev/null | wc -l)
	[ "$n" -ge 1 ] || { fail "docs.${doc##*/}" "no example marked <!-- python_reader: example --> in $doc"; continue; }
	bad=""
	for e in ex/"${doc##*/}".*.py; do
		(cd ex && "$PY" -W ignore "${e#ex/}" >"${e#ex/}.out" 2>&1) || bad="$bad ${e#ex/}: $(tail -n 2 "$e.out" | tr '\n' ' ')"
	done
	[ -z "$bad" ] && ok "docs.${doc##*/}.examples_run" || fail "docs.${doc##*/}.examples_run" "$bad"
done
finish
