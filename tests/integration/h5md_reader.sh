#!/usr/bin/env bash
# h5md_reader.sh - a run file opened by readers no one here wrote: MDAnalysis' H5MD reader
# (Debian python3-mdanalysis) sees every snapshot's positions, velocities, times and steps
# as the file holds them; h5py resolves the XDMF sidecar's hyperslabs (what ParaView
# reads) to the same positions, radii and species, and the walls to theirs.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1
# Debian's python3 (not a virtualenv's or pyenv's): the packages make deps installs live there
PY=/usr/bin/python3
if ! "$PY" -c 'import MDAnalysis, h5py' 2>/dev/null; then
	fail setup "$PY cannot import MDAnalysis and h5py (Debian python3-mdanalysis, python3-h5py): run make deps"
	finish
fi
shake_run s.log "${FAST[@]}" "${GENTLE[@]}" duration=1 snapshots=yes output=s.h5 || { fail run "exit $?: $(tail -n 2 s.log)"; finish; }
shake_run f.log "${FAST[@]}" "${GENTLE[@]}" duration=1 snapshots=yes snapshot_precision=double output=f.h5 ||
	{ fail run_single "exit $?: $(tail -n 2 f.log)"; finish; }

"$PY" - s.h5 f.h5 >py.out 2>py.err <<'PY'
import sys, warnings
warnings.filterwarnings("ignore")
import numpy as np, h5py
from MDAnalysis.coordinates.H5MD import H5MDReader

path = sys.argv[1]
def check(name, cond, why=""):
    print(("ok " + name) if cond else ("FAIL %s: %s" % (name, why)))

with h5py.File(path, "r") as f:
    bed = f["particles/bed"]
    P = bed["position/value"][...]
    V = bed["velocity/value"][...]
    T = bed["position/time"][...]
    S = bed["position/step"][...]
    want = {"bed": {"radius": bed["radius"][...], "species": bed["species"][...], "id": bed["id"][...]},
            "walls": {"radius": f["particles/walls/radius"][...], "species": f["particles/walls/species"][...],
                      "id": f["particles/walls/id"][...]}}
    # per snapshot: the angle, and the velocity as the 3-vector of the bed_xyz view
    per_frame = {"angle": bed["angle/value"][...], "velocity": f["particles/bed_xyz/velocity/value"][...]}
    W = f["particles/walls/position"][...]
    check("h5py.first_group_is_xyz_view", list(f["particles"])[0] == "bed_xyz", list(f["particles"]))

r = H5MDReader(path, convert_units=False)
check("mda.n_atoms", r.n_atoms == P.shape[1], "%d vs %d" % (r.n_atoms, P.shape[1]))
check("mda.n_frames", r.n_frames == P.shape[0] and r.n_frames >= 4, "%d vs %d" % (r.n_frames, P.shape[0]))
bad = []
for ts in r:
    k = ts.frame
    # MDAnalysis holds coordinates in float32: compare with the file's values rounded so
    if not np.array_equal(ts.positions[:, :2], P[k].astype(np.float32)):
        bad.append("positions of frame %d" % k)
    if not np.all(ts.positions[:, 2] == 0):
        bad.append("z of frame %d" % k)
    if not np.array_equal(ts.velocities[:, :2], V[k].astype(np.float32)):
        bad.append("velocities of frame %d" % k)
    if ts.time != T[k] or ts.data["step"] != S[k]:
        bad.append("time/step of frame %d: %r %r" % (k, ts.time, ts.data.get("step")))
check("mda.frames_are_the_files", not bad, "; ".join(bad[:3]))
r.close()

# XDMF: each grid's geometry is a hyperslab (start, stride, count) of a dataset of the file
import xml.etree.ElementTree as ET
root = ET.parse(path[:-3] + ".xmf").getroot()
times = root.findall("./Domain/Grid/Grid")
check("xdmf.one_time_per_snapshot", len(times) == P.shape[0], "%d times" % len(times))
bad = []
def resolve(f, item):
    # a DataItem: a plain HDF reference, or a HyperSlab of one (start, stride, count)
    if item.get("ItemType") == "HyperSlab":
        sel, src = item.findall("DataItem")
        start, stride, count = np.array(sel.text.split(), dtype=int).reshape(3, -1)
        fname, dpath = src.text.strip().split(":")
        idx = tuple(slice(a, a + s * c, s) for a, s, c in zip(start, stride, count))
        return fname, f[dpath][...][idx].reshape([int(x) for x in item.get("Dimensions").split()])
    fname, dpath = item.text.strip().split(":")
    return fname, f[dpath][...]
with h5py.File(path, "r") as f:
    for k, tg in enumerate(times):
        if abs(float(tg.find("Time").get("Value")) - T[k]) > 1e-9 * max(1, T[k]):
            bad.append("time of grid %d" % k)
        grids = {g.get("Name"): g for g in tg.findall("Grid")}
        if sorted(grids) != ["bed", "walls"]:
            bad.append("grids %s at time %d" % (sorted(grids), k))
            continue
        for name, pos in (("bed", P[k]), ("walls", W)):
            fname, got = resolve(f, grids[name].find("Geometry/DataItem"))
            if fname != "s.h5" or not np.array_equal(got, pos):
                bad.append("geometry of %s at time %d" % (name, k))
            names = []
            for att in grids[name].findall("Attribute"):
                a = att.get("Name")
                names.append(a)
                fname, got = resolve(f, att.find("DataItem"))
                ref = per_frame[a][k] if name == "bed" and a in per_frame else want[name].get(a)
                if ref is None or not np.array_equal(got, ref):
                    bad.append("%s of %s at time %d" % (a, name, k))
            need = sorted(want[name]) + (sorted(per_frame) if name == "bed" else [])
            if sorted(names) != sorted(need):
                bad.append("attributes of %s: %s, not %s" % (name, sorted(names), sorted(need)))
            if name == "bed" and grids[name].find("Attribute[@Name='velocity']").get("AttributeType") != "Vector":
                bad.append("velocity is no vector")
check("xdmf.resolves_to_the_snapshots", not bad, "; ".join(bad[:3]))

# snapshot_precision: single (the default, s.h5) holds the double run's values (f.h5) rounded
with h5py.File(sys.argv[2], "r") as f:
    D = f["particles/bed/position/value"]
    check("double.float64", D.dtype == np.float64 and f["particles/bed_xyz/position/value"].dtype == np.float64,
          str(D.dtype))
    D = D[...]
with h5py.File(sys.argv[1], "r") as f:
    v = f["particles/bed/position/value"]
    check("single.float32", v.dtype == np.float32 and f["particles/bed_xyz/position/value"].dtype == np.float32,
          str(v.dtype))
    check("single.is_double_rounded", np.array_equal(v[...], D.astype(np.float32)))
    check("single.rest_stays_double", f["final/x"].dtype == np.float64 and
          f["particles/intruder/position/value"].dtype == np.float64)
r = H5MDReader(sys.argv[2], convert_units=False)
check("double.mda_reads", all(np.array_equal(ts.positions[:, :2], D[ts.frame].astype(np.float32)) for ts in r))
PY
rc=$?
# the checks Python made, counted here as this script's own (finish fails a script
# that made none)
while IFS= read -r l; do
	case $l in
	"ok "*) ok "${l#ok }" ;;
	"FAIL "*) l=${l#FAIL }; fail "${l%%: *}" "${l#*: }" ;;
	*) echo "$l" ;;
	esac
done <py.out
[ "$rc" -eq 0 ] || fail python "exit $rc: $(grep -v xdrlib py.err | tail -n 3)"
finish
