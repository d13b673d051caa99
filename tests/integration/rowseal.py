"""rowseal.py - the row seal of lib/rowseal.h written a second time, from its
definition, to check the C one (tests/integration/db_damage.sh) and to seal again the
rows a test edits on purpose (a run file changed and its new file seal recorded, as the
database would if the engine had written it):

    python3 rowseal.py check DB     # print "RUN STORED COMPUTED" for each result row
    python3 rowseal.py write DB     # write the computed seal into every result row
"""
import sqlite3
import struct
import sys

BASIS = 1469598103934665603  # core/base/fnv.h
PRIME = 1099511628211
MASK = (1 << 64) - 1
COLUMN = "row_seal"


def fnv(h, data):
    for b in data:
        h = ((h ^ b) * PRIME) & MASK
    return h


def mix(h, name, v):
    h = fnv(h, name.encode() + b"\0")
    payload = b""
    if v is None:
        tag, word = b"N", 0
    elif isinstance(v, int):
        tag, word = b"I", v & MASK
    elif isinstance(v, float):
        tag, word = b"R", struct.unpack("<Q", struct.pack("<d", v))[0]
    elif isinstance(v, bytes):
        tag, payload = b"B", v
        word = len(v)
    else:
        tag, payload = b"T", v.encode()
        word = len(payload)
    h = fnv(h, tag)
    h = fnv(h, word.to_bytes(8, "little"))
    return fnv(h, payload)


def mix_row(h, cur, row):
    for d, v in zip(cur.description, row):
        if d[0] != COLUMN:
            h = mix(h, d[0], v)
    return h


def seal(db, campaign, run):
    c = db.execute("SELECT * FROM result WHERE campaign = ? AND run = ?", (campaign, run))
    row = c.fetchone()
    h = fnv(fnv(BASIS, campaign.encode() + b"\0"), run.encode() + b"\0")
    h = mix_row(h, c, row)
    c = db.execute("SELECT replicate, seed, cache_key FROM run WHERE campaign = ? AND id = ?", (campaign, run))
    r = c.fetchone()
    if r:
        h = mix_row(h, c, r)
    c = db.execute("SELECT key, value FROM param WHERE campaign = ? AND run = ? ORDER BY key", (campaign, run))
    for r in c.fetchall():
        h = mix_row(h, c, r)
    return "%016x" % h


def main():
    what, path = sys.argv[1], sys.argv[2]
    db = sqlite3.connect(path)
    rows = db.execute("SELECT campaign, run, %s FROM result ORDER BY campaign, run" % COLUMN).fetchall()
    for campaign, run, stored in rows:
        s = seal(db, campaign, run)
        if what == "check":
            print(run, stored, s)
        else:
            db.execute("UPDATE result SET %s = ? WHERE campaign = ? AND run = ?" % COLUMN, (s, campaign, run))
    db.commit()


if __name__ == "__main__":
    main()
