"""A minimal reader of ECLIPSE unformatted binary files (EGRID, UNRST), numpy only.

Used by compare.py and the opm test to read the simulator's PRESSURE independently of
ugs-import-eclipse (which reads through opm-common's EclIO). Each array is a Fortran record
header (8-character name, int32 count, 4-character type) followed by its data in records of at most
1000 numbers (105 strings), big-endian.
"""
import numpy as np

_TYPES = {b"INTE": (">i4", 1000), b"REAL": (">f4", 1000), b"DOUB": (">f8", 1000),
          b"LOGI": (">i4", 1000), b"CHAR": ("S8", 105), b"MESS": (None, 0)}


def read(path):
    """List of (name, numpy array or list of str) in file order."""
    buf = open(path, "rb").read()
    pos, out = 0, []
    while pos < len(buf):
        n = int.from_bytes(buf[pos:pos + 4], "big")
        if n != 16 or pos + 24 > len(buf):
            raise ValueError("%s: byte %d: not an array header" % (path, pos))
        name = buf[pos + 4:pos + 12].decode().strip()
        count = int.from_bytes(buf[pos + 12:pos + 16], "big", signed=True)
        typ = buf[pos + 16:pos + 20]
        pos += 24
        if typ not in _TYPES:
            raise ValueError("%s: %s: unknown type %r" % (path, name, typ))
        dt, per = _TYPES[typ]
        parts = []
        left = count
        while left > 0:
            m = int.from_bytes(buf[pos:pos + 4], "big")
            if m == 0 or pos + m + 8 > len(buf) or int.from_bytes(buf[pos + 4 + m:pos + 8 + m], "big") != m:
                raise ValueError("%s: %s: truncated or damaged record at byte %d" % (path, name, pos))
            parts.append(np.frombuffer(buf[pos + 4:pos + 4 + m], dtype=dt))
            pos += m + 8
            left -= len(parts[-1])
        a = np.concatenate(parts) if parts else np.zeros(0)
        if typ == b"CHAR":
            a = [s.decode().strip() for s in a]
        out.append((name, a))
    return out


def restart_steps(path):
    """[(date as 'YYYY-MM-DD', PRESSURE array)] of a unified restart, in file order."""
    steps, date = [], None
    for name, a in read(path):
        if name == "INTEHEAD":
            date = "%04d-%02d-%02d" % (a[66], a[65], a[64])
        elif name == "PRESSURE":
            steps.append((date, np.asarray(a, dtype=float)))
    return steps
