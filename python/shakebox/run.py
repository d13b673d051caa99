"""run.py - a run file of bin/shake as numpy arrays with their units (docs/output.md).

Every unit is the file's own `unit` attribute, never one typed here. The file is opened
read-only with h5py (which skips the 512-byte user block that holds the seal) and
refused, naming it, when it is not a shakebox run file.
"""
import os
from collections.abc import Mapping

import h5py
import numpy as np

# The formats a run file may declare in its root attribute `format`, newest first: the
# engine's H5ID_FORMAT, H5ID_FORMAT_OLD3, H5ID_FORMAT_OLD (core/io/h5id.h;
# tests/integration/python_reader.sh fails when they differ).
FORMATS = ("shakebox-run-4", "shakebox-run-3", "shakebox-run-2")


class RunFileError(Exception):
    """A file that is not a shakebox run file, or lacks what was asked of it. The
    message names the file."""


def _py(v):
    """An attribute's value as Python: str for strings, a number for a scalar, a list
    of those for an array."""
    if isinstance(v, bytes):
        return v.decode("utf-8", "replace")
    if isinstance(v, np.ndarray):
        return [_py(x) for x in v.tolist()] if v.dtype.kind in "SOU" else v.tolist()
    if isinstance(v, np.generic):
        return v.item()
    return v


def _attrs(obj):
    return {k: _py(v) for k, v in obj.attrs.items()}


def _unit(ds):
    u = ds.attrs.get("unit")
    return None if u is None else _py(u)


class Element:
    """One H5MD element of a run file: `value` (a numpy array) and `unit` (the `unit`
    attribute of the dataset, None when it has none); for a time-dependent element also
    `step` (the engine's step of each row), `time` (s) and `time_unit`, else None.
    np.asarray(element) is its value."""

    __slots__ = ("path", "value", "unit", "step", "time", "time_unit")

    def __init__(self, path, value, unit, step=None, time=None, time_unit=None):
        self.path, self.value, self.unit = path, value, unit
        self.step, self.time, self.time_unit = step, time, time_unit

    def __array__(self, dtype=None):
        return np.asarray(self.value, dtype=dtype)

    def __len__(self):
        return len(self.value)

    def __repr__(self):
        shape = "x".join(map(str, np.shape(self.value))) or "scalar"
        return "<Element %s [%s] %s>" % (self.path, shape, self.unit)


class Group(dict):
    """The elements of one group of the file by name, with the group's attributes
    (`definition`, ...) as `attrs`."""

    def __init__(self, elements, attrs):
        super().__init__(elements)
        self.attrs = attrs


class _Lazy(Mapping):
    """A mapping whose values are read on first access."""

    def __init__(self, keys, read):
        self._keys, self._read, self._got = list(keys), read, {}

    def __getitem__(self, k):
        if k not in self._keys:
            raise KeyError(k)
        if k not in self._got:
            self._got[k] = self._read(k)
        return self._got[k]

    def __iter__(self):
        return iter(self._keys)

    def __len__(self):
        return len(self._keys)


class Run:
    """A run file of bin/shake, read-only:

        run = Run("f28.h5")
        run.parameters["frequency"], run.outcome["status"], run.outcome["waiting_time"]
        run.positions.value[k], run.positions.unit     # snapshot k, [n_mobile x 2], "cm"
        run.times, run.steps                           # of the snapshots
        run.observables["flux"]["phi"].value           # [periods x flux_lines]

    A context manager; close() closes the file."""

    def __init__(self, path):
        self.path = os.fspath(path)
        if not os.path.exists(self.path):
            raise RunFileError("%s: no such file" % self.path)
        if not os.path.isfile(self.path):
            raise RunFileError("%s: not a regular file" % self.path)
        try:
            self._f = h5py.File(self.path, "r")
        except OSError as e:
            raise RunFileError("%s: not an HDF5 file (%s)" % (self.path, e)) from None
        try:
            self._check()
        except BaseException:
            self._f.close()
            raise
        self.observables = _Lazy(self._f["observables"] if "observables" in self._f else (),
                                 lambda name: self.group("observables/" + name))

    def _check(self):
        f, p = self._f, self.path
        if not isinstance(f.get("h5md", getlink=False), h5py.Group):
            raise RunFileError("%s: not a shakebox run file: no /h5md group (docs/output.md)" % p)
        fmt = _py(f.attrs.get("format"))
        if fmt not in FORMATS:
            raise RunFileError("%s: not a shakebox run file: its root attribute format is %s, not %s"
                               % (p, "missing" if fmt is None else repr(fmt), " or ".join(FORMATS)))
        # A run file holds only itself (docs/inputs.md, "Run files"): no soft or external
        # link, no virtual dataset of another file, no external storage.
        bad = []

        def link(name, info):
            if info.type != h5py.h5l.TYPE_HARD and not bad:
                bad.append("/%s is a soft or external link" % name.decode())

        f.id.links.visit(link, info=True)

        def data(name, obj):
            if bad or not isinstance(obj, h5py.Dataset):
                return
            if obj.is_virtual and any(s.file_name != "." for s in obj.virtual_sources()):
                bad.append("/%s is a virtual dataset of another file" % name)
            elif obj.id.get_create_plist().get_external_count():
                bad.append("/%s has external storage" % name)

        if not bad:
            f.visititems(data)
        if bad:
            raise RunFileError("%s: %s: a run file holds only itself (docs/inputs.md, \"Run files\")"
                               % (p, bad[0]))

    # --- the file as a whole ---
    def close(self):
        self._f.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self):
        return "<shakebox.Run %s>" % self.path

    @property
    def format(self):
        return _py(self._f.attrs["format"])

    @property
    def parameters(self):
        """Every scene parameter (the attributes of /parameters)."""
        return _attrs(self._f["parameters"])

    @property
    def outcome(self):
        """The run's outcome (the root's attributes: status, risen, waiting_time, ...)."""
        return _attrs(self._f)

    @property
    def provenance(self):
        return _attrs(self._f["provenance"])

    @property
    def ring(self):
        """The ring's averages (attributes of /ring); {} without ring = yes."""
        return _attrs(self._f["ring"]) if "ring" in self._f else {}

    def has(self, path):
        return path.strip("/") in self._f

    # --- elements ---
    def element(self, path):
        """The H5MD element at path: a dataset (time-independent) or a group of value,
        step and time (time-dependent), with the units the file gives them."""
        path = "/" + path.strip("/")
        obj = self._f.get(path)
        if obj is None:
            raise RunFileError("%s: has no %s" % (self.path, path))
        if isinstance(obj, h5py.Dataset):
            return Element(path, obj[()], _unit(obj))
        if "value" not in obj:
            raise RunFileError("%s: %s is a group of elements, not an element" % (self.path, path))
        v = obj["value"]
        step = obj["step"][()] if "step" in obj else None
        time, tunit = (obj["time"][()], _unit(obj["time"])) if "time" in obj else (None, None)
        return Element(path, v[()], _unit(v), step, time, tunit)

    def group(self, path):
        """Every element of a group (the datasets and the time-dependent groups in it) by
        name, with the group's attributes as .attrs."""
        path = "/" + path.strip("/")
        g = self._f.get(path)
        if not isinstance(g, h5py.Group):
            raise RunFileError("%s: has no group %s" % (self.path, path))
        names = [k for k in g if isinstance(g[k], h5py.Dataset) or "value" in g[k]]
        return Group({k: self.element(path + "/" + k) for k in names}, _attrs(g))

    # --- the bed, its snapshots, the walls, the intruder ---
    @property
    def bed(self):
        """The mobile disks: id, species, radius, mass (and, with snapshots, the
        time-dependent elements position, velocity, angle)."""
        return self.group("particles/bed")

    @property
    def species_names(self):
        """{species number: name}, as the file names them (/particles/bed@species_names)."""
        text = _py(self._f["particles/bed"].attrs["species_names"])
        return {int(k): v for k, v in (item.strip().split(" ", 1) for item in text.split(","))}

    @property
    def has_snapshots(self):
        return "particles/bed/position" in self._f

    def require_snapshots(self, what="them"):
        """RunFileError naming the file unless it has snapshots."""
        if not self.has_snapshots:
            raise RunFileError("%s: has no snapshots (its run had snapshots = no), so no %s" % (self.path, what))

    def _snapshot(self, name):
        self.require_snapshots(name)
        return self.element("particles/bed/" + name)

    @property
    def positions(self):
        """Snapshots' positions [K x n_mobile x 2], lab frame."""
        return self._snapshot("position")

    @property
    def velocities(self):
        return self._snapshot("velocity")

    @property
    def angles(self):
        return self._snapshot("angle")

    @property
    def times(self):
        """The snapshots' times (s)."""
        return self._snapshot("position").time

    @property
    def steps(self):
        return self._snapshot("position").step

    @property
    def box(self):
        """edges and, with snapshots, offset and offset_velocity (the box's lower left
        corner and its velocity at each snapshot)."""
        return self.group("particles/bed/box")

    @property
    def walls(self):
        """The wall disks: id, species, radius, mass, position (with the box at rest)."""
        return self.group("particles/walls")

    @property
    def intruder(self):
        """The intruder's trajectory (position, velocity, angular_velocity, lab frame) and
        its id and species; None in a run without intruder."""
        return self.group("particles/intruder") if "particles/intruder" in self._f else None

    @property
    def final(self):
        """Every disk at the end (/final)."""
        return self.group("final")
