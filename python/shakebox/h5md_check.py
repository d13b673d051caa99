"""h5md_check.py - an HDF5 file against what H5MD 1.1 requires or forbids.

    python3 -m shakebox.h5md_check [--all] FILE...

prints one line per violation, "FILE: violation: WHERE: WHAT (the specification's
section)", and exits 1 when there is one, 2 when a file cannot be read as HDF5, else 0.
The rules are those of the specification, https://www.nongnu.org/h5md/h5md.html (H5MD
1.1: metadata, time-dependent and time-independent elements, particles groups and their
boxes, observables) and of its units module (https://www.nongnu.org/h5md/modules/units.html).
A rule broken by many datasets is one line naming the first three and how many more
(--all: every one). What shakebox's run files do that H5MD does not define, on purpose
and said so in docs/output.md, is printed as "deviation", not a violation
(DEVIATIONS below). docs/output.md, "H5MD conformance".
"""
import re
import sys

import h5py
import numpy as np

SPEC = "H5MD 1.1"

# (path, rule): a rule the file breaks there on purpose, with the doc that says why.
DEVIATIONS = {
    ("/observables/contacts", "element"):
        "every contact of each sample as plain datasets (frame k: rows offset[k] ... offset[k] + count[k], "
        "at time[k]): a number of rows that changes from frame to frame is no H5MD element (docs/output.md)",
}

# The units module's "SI" system: unit symbols, constants, prefixes
_UNITS = {"m", "Ang", "L", "s", "Hz", "kg", "g", "u", "N", "dyn", "Pa", "bar", "atm", "poise", "J", "cal",
          "erg", "eV", "W", "K", "mol", "A", "C", "V", "cd", "rad", "degree"}
_CONSTANTS = {"pi", "kB", "Nav", "c", "e"}
_PREFIXES = ("da", "E", "P", "T", "G", "M", "k", "h", "d", "c", "m", "u", "n", "p", "f", "a")
_NUMBER = re.compile(r"^[0-9]+(\.[0-9]+)?([+-][0-9]+)?$")
_FACTOR = re.compile(r"^([A-Za-z]+)([+-][1-9][0-9]*)?$")

_STANDARD_VECTORS = ("position", "velocity", "force", "image")
_STANDARD_SCALARS = {"mass": ("Float",), "species": ("Enumeration", "Integer"), "id": ("Integer",),
                     "charge": ("Integer", "Float")}
_CLASS = {h5py.h5t.INTEGER: "Integer", h5py.h5t.FLOAT: "Float", h5py.h5t.ENUM: "Enumeration",
          h5py.h5t.STRING: "String"}


def _kind(tid):
    return _CLASS.get(tid.get_class(), "other")


def unit_problem(text):
    """What is wrong with a unit string by the units module's grammar, or None."""
    if not text:
        return "empty"
    seen, factors = set(), text.split(" ")
    for i, f in enumerate(factors):
        if f == "":
            return "factors are separated by one space"
        if _NUMBER.match(f):
            if i:
                return "a number may only be the first factor, got '%s'" % f
            continue
        m = _FACTOR.match(f)
        if not m:
            m2 = re.match(r"^([A-Za-z]+)([0-9]+)$", f)
            if m2:
                return "factor '%s': a power is a signed integer ('%s+%s')" % (f, m2.group(1), m2.group(2))
            return "factor '%s' is neither a number nor a unit symbol with a signed power" % f
        sym = m.group(1)
        if sym not in _UNITS and sym not in _CONSTANTS and not any(
                sym.startswith(p) and sym[len(p):] in _UNITS for p in _PREFIXES):
            return "'%s' is no unit symbol of the SI system (with a prefix) nor a constant" % sym
        if sym in seen:
            return "unit symbol '%s' occurs twice" % sym
        seen.add(sym)
    return None


class Checker:
    def __init__(self, f):
        self.f = f
        self.found = {}  # (kind, rule, what, section) -> [where]

    def report(self, where, what, section, rule="other"):
        kind = "violation"
        for (p, r), why in DEVIATIONS.items():
            if r == rule and (where == p or where.startswith(p + "/")):
                kind, what = "deviation", "%s: %s" % (what, why)
        self.found.setdefault((kind, what, section), []).append(where)

    # --- attributes ---
    def string_attr(self, obj, name, where, section, vlen=False, shape=()):
        """The attribute is a string of the given kind and dataspace; returns its value."""
        if name not in obj.attrs:
            self.report(where, "no attribute %s" % name, section, "h5md")
            return None
        aid = obj.attrs.get_id(name)
        t = aid.get_type()
        if _kind(t) != "String":
            self.report(where + "@" + name, "is not a String", section, "h5md")
            return None
        if t.is_variable_str() != vlen:
            self.report(where + "@" + name, "is a %s string, not %s" % (
                "variable-length" if t.is_variable_str() else "fixed-length",
                "variable-length" if vlen else "fixed-length"), section, "h5md")
        if aid.shape != shape:
            self.report(where + "@" + name, "has dataspace %s, not %s" % (
                list(aid.shape) or "scalar", list(shape) or "scalar"), section, "h5md")
        return obj.attrs[name]

    def integer_attr(self, obj, name, where, section, shape=()):
        if name not in obj.attrs:
            self.report(where, "no attribute %s" % name, section, "h5md")
            return None
        aid = obj.attrs.get_id(name)
        if _kind(aid.get_type()) != "Integer" or aid.shape != shape:
            self.report(where + "@" + name, "is not an Integer of dataspace %s" % (list(shape) or "scalar"),
                        section, "h5md")
            return None
        return obj.attrs[name]

    # --- /h5md ---
    def h5md(self):
        sec = "H5MD metadata"
        g = self.f.get("h5md")
        if not isinstance(g, h5py.Group):
            self.report("/h5md", "missing: the one mandatory group", "H5MD root level", "h5md")
            return
        v = self.integer_attr(g, "version", "/h5md", sec, (2,))
        if v is not None and list(v) != [1, 1]:
            self.report("/h5md@version", "is %s, not 1, 1 (this check is of %s)" % (list(v), SPEC), sec, "h5md")
        for name, attrs in (("author", ("name",)), ("creator", ("name", "version"))):
            sub = g.get(name)
            if not isinstance(sub, h5py.Group):
                self.report("/h5md/" + name, "missing group", sec, "h5md")
                continue
            for a in attrs:
                self.string_attr(sub, a, "/h5md/" + name, sec)
            if name == "author" and "email" in sub.attrs:
                self.string_attr(sub, "email", "/h5md/author", sec)
        mods = g.get("modules")
        if isinstance(mods, h5py.Group):
            for m in mods:
                self.integer_attr(mods[m], "version", "/h5md/modules/" + m, "Modules", (2,))
            if "units" in mods:
                self.string_attr(mods["units"], "system", "/h5md/modules/units", "units module", vlen=True)

    # --- units ---
    def units(self):
        sec = "units module, Unit attribute"
        used = []

        def visit(name, obj):
            if "unit" not in obj.attrs:
                return
            where = "/" + name
            used.append(where)
            aid = obj.attrs.get_id("unit")
            t = aid.get_type()
            if _kind(t) != "String" or aid.shape != ():
                self.report(where, "unit is not a scalar string", sec, "units")
                return
            if not t.is_variable_str():
                self.report(where, "unit is a fixed-length string, not variable-length", sec, "units")
            if t.get_cset() != h5py.h5t.CSET_ASCII:
                self.report(where, "unit is a UTF-8 string, not ASCII", sec, "units")
            v = obj.attrs["unit"]
            text = v.decode("ascii", "replace") if isinstance(v, bytes) else str(v)
            why = unit_problem(text)
            if why:
                self.report(where, "unit '%s': %s" % (text, why), "units module, Unit string", "units")

        # the elements' datasets: /particles and /observables (other groups are the
        # application's own, which H5MD leaves unspecified)
        for top in ("particles", "observables"):
            if isinstance(self.f.get(top), h5py.Group):
                self.f[top].visititems(lambda name, obj: visit(top + "/" + name, obj))
        mods = self.f.get("h5md/modules")
        if used and not (isinstance(mods, h5py.Group) and "units" in mods):
            self.report("/h5md", "unit attributes are used but /h5md/modules/units, the units module's group "
                        "(version, system), is missing", "Modules", "units")

    # --- elements ---
    def is_element_group(self, g):
        return any(k in g for k in ("step", "time", "value"))

    def element(self, path, g):
        """A time-dependent element: step, (time), value. Returns (step, time) datasets or None."""
        sec = "Time-dependent data"
        miss = [k for k in ("step", "value") if not isinstance(g.get(k), h5py.Dataset)]
        if miss:
            self.report(path, "a group with %s but no %s dataset: neither a time-dependent element nor a group "
                        "of elements" % ("/".join(k for k in ("step", "time", "value") if k in g),
                                         " or ".join(miss)), sec, "element")
            return None
        step, value, time = g["step"], g["value"], g.get("time")
        if value.ndim < 1:
            self.report(path + "/value", "is scalar: value has a [variable] first dimension", sec, "element")
            return None
        if _kind(step.id.get_type()) != "Integer":
            self.report(path + "/step", "is not of Integer type", sec, "element")
        if time is not None and _kind(time.id.get_type()) not in ("Float", "Integer"):
            self.report(path + "/time", "is not Float or Integer", sec, "element")
        if step.ndim == 0:
            if "offset" in step.attrs and _kind(step.attrs.get_id("offset").get_type()) != "Integer":
                self.report(path + "/step@offset", "is not an Integer", "Fixed step and time storage", "element")
            if time is not None and time.ndim != 0:
                self.report(path + "/time", "is not scalar while step is (fixed storage)",
                            "Fixed step and time storage", "element")
        elif step.ndim == 1:
            if value.shape[0] != step.shape[0]:
                self.report(path + "/value", "has %d rows, step %d: the first dimension of value must match step's"
                            % (value.shape[0], step.shape[0]), sec, "element")
            s = step[()]
            if len(s) > 1 and np.any(np.diff(s) < 0):
                self.report(path + "/step", "is not in increasing order", "Explicit step and time storage", "element")
            if time is not None:
                if time.ndim != 1 or time.shape[0] != step.shape[0]:
                    self.report(path + "/time", "has shape %s, step %s: they must have the same one dimension"
                                % (list(time.shape), list(step.shape)), "Explicit step and time storage", "element")
                else:
                    t = time[()]
                    if len(t) > 1 and np.any(np.diff(t) < 0):
                        self.report(path + "/time", "is not in increasing order",
                                    "Explicit step and time storage", "element")
        else:
            self.report(path + "/step", "has rank %d: [variable] or scalar" % step.ndim, sec, "element")
        return step, time

    def tree(self, path, g, skip=()):
        """The elements of a group that holds elements and groups of them (observables,
        a particles group's members but those in skip), each time-dependent one checked;
        returns {name: (dataset or group, time-dependent?)} of its own members."""
        out = {}
        for name in g:
            if name in skip:
                continue
            obj = g[name]
            p = path + "/" + name
            if isinstance(obj, h5py.Dataset):
                out[name] = (obj, False)
            elif self.is_element_group(obj):
                out[name] = (obj, self.element(p, obj) is not None)
            else:
                self.tree(p, obj)
        return out

    # --- /particles ---
    def particles(self):
        top = self.f.get("particles")
        if top is None:
            return
        for name in top:
            path = "/particles/" + name
            pg = top[name]
            if not isinstance(pg, h5py.Group):
                self.report(path, "is a dataset: /particles holds groups of particles", "Particles group", "particles")
                continue
            members = self.tree(path, pg, skip=("box",))
            D = self.box(path, pg.get("box"), members.get("position"))
            self.particle_elements(path, members, D)

    def box(self, path, box, position):
        sec = "Simulation box"
        if not isinstance(box, h5py.Group):
            self.report(path, "has no box group: each particles group has one", sec, "box")
            return None
        D = self.integer_attr(box, "dimension", path + "/box", sec)
        b = self.string_attr(box, "boundary", path + "/box", sec, shape=(int(D),) if D is not None and D > 0 else ())
        periodic = False
        if b is not None:
            vals = [x.decode() if isinstance(x, bytes) else str(x) for x in np.atleast_1d(b)]
            bad = [v for v in vals if v not in ("periodic", "none")]
            if bad:
                self.report(path + "/box@boundary", "holds %s: each is periodic or none" % bad, sec, "box")
            periodic = "periodic" in vals
        edges = box.get("edges")
        if edges is None:
            if periodic:
                self.report(path + "/box", "has no edges while a boundary is periodic", sec, "box")
        elif D is not None:
            shape = edges.shape if isinstance(edges, h5py.Dataset) else (
                edges["value"].shape[1:] if isinstance(edges.get("value"), h5py.Dataset) else None)
            if shape is not None and tuple(shape) not in ((D,), (D, D)):
                self.report(path + "/box/edges", "has shape %s: a vector of D = %d or a D x D matrix"
                            % (list(shape), D), sec, "box")
        # time-dependent data of the box share position's step and time, hard-linked
        pos = position[0] if position and position[1] else None
        for k, (obj, td) in self.tree(path + "/box", box).items():
            if td and pos is not None:
                for t in ("step", "time"):
                    if t in obj and (t not in pos or obj[t].id != pos[t].id):
                        self.report(path + "/box/" + k + "/" + t, "is not a hard link to %s/position/%s"
                                    % (path, t), sec, "box")
        return int(D) if D is not None else None

    def particle_elements(self, path, members, D):
        sec = "Particles group"
        n = {}
        for k, (obj, td) in members.items():
            value = obj["value"] if td else (obj if isinstance(obj, h5py.Dataset) else None)
            if value is None:
                continue
            shape = value.shape[1:] if td else value.shape
            if k in _STANDARD_VECTORS:
                if _kind(value.id.get_type()) not in ("Float", "Integer"):
                    self.report(path + "/" + k, "is not Float or Integer", sec, "particles")
                if D is not None and (len(shape) != 2 or shape[1] != D):
                    self.report(path + "/" + k, "has a particle's shape %s, not [N][%d] (the box's dimension)"
                                % (list(shape), D), sec, "particles")
            elif k in _STANDARD_SCALARS:
                if _kind(value.id.get_type()) not in _STANDARD_SCALARS[k]:
                    self.report(path + "/" + k, "is %s, not %s" % (_kind(value.id.get_type()),
                                                                   " or ".join(_STANDARD_SCALARS[k])), sec, "particles")
            else:
                continue
            if len(shape):
                n[k] = shape[0]
        if len(set(n.values())) > 1:
            self.report(path, "its elements disagree on the number of particles: %s" % n, sec, "particles")
        if "image" in members and "position" not in members:
            self.report(path + "/image", "without position", sec, "particles")

    def observables(self):
        g = self.f.get("observables")
        if isinstance(g, h5py.Group):
            self.tree("/observables", g)

    def run(self):
        self.h5md()
        self.particles()
        self.observables()
        self.units()
        return self.found


def check(path):
    """[(kind, where, what, section, [paths])] of the file at path: kind "violation" or
    "deviation". OSError when it cannot be opened as HDF5."""
    with h5py.File(path, "r") as f:
        found = Checker(f).run()
    return [(kind, where[0], what, sec, where) for (kind, what, sec), where in found.items()]


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    every = "--all" in argv
    files = [a for a in argv if a != "--all"]
    if not files or any(a.startswith("-") for a in files):
        print("usage: python3 -m shakebox.h5md_check [--all] FILE...", file=sys.stderr)
        return 2
    rc = 0
    for path in files:
        try:
            found = check(path)
        except OSError as e:
            print("h5md_check: %s: cannot be read as HDF5 (%s)" % (path, e), file=sys.stderr)
            rc = 2
            continue
        for kind, _, what, sec, where in sorted(found, key=lambda x: (x[0] != "violation", x[1])):
            if every or len(where) <= 3:
                at = ", ".join(where)
            else:
                at = "%s and %d more" % (", ".join(where[:3]), len(where) - 3)
            print("%s: %s: %s: %s (%s, %s)" % (path, kind, at, what, SPEC, sec))
            if kind == "violation" and rc == 0:
                rc = 1
    return rc


if __name__ == "__main__":
    sys.exit(main())
