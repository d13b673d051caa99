"""db.py - the study database's runs view (docs/database.md), read-only, as rows."""
import os
import sqlite3
import urllib.parse


def run_path(db_path, row, runs_dir=None):
    """The run file of a row of the runs view: RUNS/CAMPAIGN/ID.h5, where bin/study
    writes it (lib/layout.h), RUNS being runs_dir or else the database's directory
    (bin/study's RUNS/study.db; give runs_dir for a database kept elsewhere with --db)."""
    root = runs_dir if runs_dir is not None else os.path.dirname(os.path.abspath(os.fspath(db_path)))
    return os.path.join(root, row["campaign"], row["id"] + ".h5")


def _pandas():
    try:
        import pandas
    except ImportError:
        raise ImportError("shakebox.runs(..., as_dataframe=True) needs pandas, which is not installed "
                          "(Debian: apt-get install python3-pandas); without it runs() gives a list of dicts") from None
    return pandas


def runs(db_path, campaign=None, as_dataframe=False, runs_dir=None):
    """The rows of the runs view (one per run, docs/database.md), a dict each, ordered by
    campaign and id; only campaign's when given. Each row also has run_file: its run
    file's path (run_path). as_dataframe=True: a pandas DataFrame of the same columns.
    The database is opened read-only (a study may be writing it: it is in WAL mode)."""
    db = os.fspath(db_path)
    if as_dataframe:
        pandas = _pandas()
    if not os.path.isfile(db):
        raise FileNotFoundError("%s: no such database" % db)
    uri = "file:%s?mode=ro" % urllib.parse.quote(os.path.abspath(db))
    try:
        con = sqlite3.connect(uri, uri=True)
    except sqlite3.Error as e:
        raise ValueError("%s: cannot open the database: %s" % (db, e)) from None
    try:
        if not con.execute("SELECT 1 FROM sqlite_master WHERE type = 'view' AND name = 'runs'").fetchone():
            raise ValueError("%s: not a study database: it has no runs view (docs/database.md)" % db)
        if campaign is not None and not con.execute("SELECT 1 FROM campaign WHERE name = ?", (campaign,)).fetchone():
            names = [r[0] for r in con.execute("SELECT name FROM campaign ORDER BY name")]
            raise ValueError("%s: no campaign %r (it has: %s)" % (db, campaign, ", ".join(names) or "none"))
        cur = con.execute("SELECT * FROM runs" + (" WHERE campaign = ?" if campaign is not None else "")
                          + " ORDER BY campaign, id", () if campaign is None else (campaign,))
        cols = [d[0] for d in cur.description]
        rows = [dict(zip(cols, r)) for r in cur]
    except sqlite3.Error as e:
        raise ValueError("%s: %s" % (db, e)) from None
    finally:
        con.close()
    for r in rows:
        r["run_file"] = run_path(db, r, runs_dir)
    if as_dataframe:
        return pandas.DataFrame.from_records(rows, columns=cols + ["run_file"])
    return rows
