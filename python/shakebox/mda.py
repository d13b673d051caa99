"""mda.py - a run file's snapshots as an MDAnalysis Universe (docs/output.md, "From Python").

MDAnalysis 2.4's H5MD reader cannot open a run file itself: it reads every entry of
/observables as a series of one row per snapshot (flux, field, ring, energy and
contacts are not), and Universe("run.h5") has no H5MD topology parser. So the reader
here is given, instead of the run file, a small HDF5 file held in memory (nothing on
disk, opened read-only) whose only particle group is an external link to the run file's
/particles/bed_xyz (the 3-D view of the snapshots: docs/output.md): the reader sees the
snapshots and nothing of /observables, and reads each frame from the run file as it
goes, never the whole trajectory at once. The in-memory file is made again whenever
MDAnalysis reopens its trajectory (it does at every iteration), which a file handed to
it as an h5py.File would not survive.
"""
import io
import os

import h5py
import numpy as np

from .run import Run

_VIEW = "/particles/bed_xyz"
_reader = None


def _image(path):
    """The bytes of the small HDF5 file MDAnalysis is given: /h5md and /particles/bed,
    an external link to path's /particles/bed_xyz. It is opened read-only, so the run
    file is too (HDF5 opens a link's file with its parent's access)."""
    buf = io.BytesIO()
    with h5py.File(buf, "w") as f:
        f.create_group("h5md").attrs["version"] = np.array([1, 1], dtype=np.int32)
        f.create_group("particles")["bed"] = h5py.ExternalLink(path, _VIEW)
    return buf.getvalue()


def _mdanalysis():
    try:
        import MDAnalysis
        from MDAnalysis.coordinates.H5MD import H5MDReader
    except ImportError:
        raise ImportError("shakebox.universe needs MDAnalysis, which is not installed "
                          "(Debian: apt-get install python3-mdanalysis)") from None
    return MDAnalysis, H5MDReader


def _reader_class():
    """The H5MD reader reading a run file through an in-memory file (made once; not
    registered as a format of MDAnalysis: it defines no `format`)."""
    global _reader
    if _reader is None:
        _, H5MDReader = _mdanalysis()

        class RunReader(H5MDReader):
            def open_trajectory(self):
                self._frame = -1
                if not hasattr(self, "_image"):
                    self._image = _image(self.filename)
                self._file = h5py.File(io.BytesIO(self._image), "r")
                self._driver = None
                self._particle_group = self._file["particles/bed"]

            def close(self):
                # the group reached through the link holds the run file open
                self._particle_group = None
                self._file.close()

        _reader = RunReader
    return _reader


def universe(path):
    """An MDAnalysis Universe of a run file with snapshots (snapshots = yes), whatever
    else it holds: one atom per mobile disk with its id, mass, radius and type (its
    species' name in the file: grain, intruder), one frame per snapshot with the
    positions and velocities of /particles/bed_xyz (z = 0), its time and step
    (ts.data["step"]). Units are the file's (cm, cm s-1, s), not converted.
    RunFileError naming the file when it is not a run file or has no snapshots."""
    mda, _ = _mdanalysis()
    path = os.path.abspath(os.fspath(path))
    with Run(path) as run:
        run.require_snapshots("trajectory")
        bed = run.bed
        names = run.species_names
        species = np.asarray(bed["species"])
        n = len(species)
        ids, masses, radii = np.asarray(bed["id"]), np.asarray(bed["mass"]), np.asarray(bed["radius"])
    u = mda.Universe.empty(n, trajectory=False)
    u.add_TopologyAttr("ids", ids)
    u.add_TopologyAttr("masses", masses)
    u.add_TopologyAttr("radii", radii)
    u.add_TopologyAttr("types", np.array([names[int(s)] for s in species], dtype=object))
    u.load_new(path, format=_reader_class(), convert_units=False)
    return u
