"""shakebox - read shakebox's run files and study database from Python.

    import shakebox
    run = shakebox.Run("runs/demo/0123abcd.h5")      # a run file as arrays with units
    rows = shakebox.runs("runs/study.db", "demo")    # the database's runs view
    u = shakebox.universe("runs/demo/0123abcd.h5")   # an MDAnalysis Universe of the snapshots

    python3 -m shakebox.h5md_check RUN.h5            # the file against H5MD 1.1

Standard library, numpy and h5py; pandas and MDAnalysis only when asked for. It only
reads. docs/output.md, "From Python"; docs/database.md, "From Python".
"""
from .run import Element, Run, RunFileError, FORMATS
from .db import runs, run_path
from .mda import universe

__all__ = ["Element", "Run", "RunFileError", "FORMATS", "runs", "run_path", "universe"]
