#!/usr/bin/env python3
"""Regenerates crates/topography/tests/data/formats-reference.json: what an independent reader,
SurfaceTopography (PyPI, version pinned below), reads from each instrument file in
data/topography-formats/, in SI metres.

    python3 -m venv /tmp/st && /tmp/st/bin/pip install SurfaceTopography==1.27.1
    /tmp/st/bin/python scripts/topography-formats-reference.py

Per file and channel: grid (nx, ny), physical size in metres (null if the file has no length
unit), the height unit in metres per value (null if none), the number of missing (masked) pixels,
the sum, sum of squares, min and max of the valid heights in metres, and 200 sample pixels
[ix, iy, height in m] (pixel (ix, iy) is SurfaceTopography's heights()[ix, iy]); for a file
without a length unit, the values as stored (unit 1).
"""
import json
import os
import sys

import numpy as np
import SurfaceTopography
from SurfaceTopography import open_topography
from SurfaceTopography.Support.UnitConversion import get_unit_conversion_factor

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "data", "topography-formats")
OUT = os.path.join(ROOT, "crates", "topography", "tests", "data", "formats-reference.json")

# file -> channel indices to record (the height channels and one other where the file has many)
FILES = {
    "di-1.di": [0, 1, 2],
    "spot_1-1000nm.ibw": [0, 1],
    "10x10-one_channel_without_name.ibw": [0],
    "sdf-1.sdf": [0],
    "x3p-2.x3p": [0],
    "sur-3.sur": [0],
    "opd-1.opd": [0],
    "plu-1.plu": [0],
    "metropro-1.dat": [0],
    "nid-1.nid": [0, 1, 2],
    "stp-1.stp": [0],
    "mi-1.mi": [0, 1],
    "al3d-1.al3d": [0],
    "example_ps.tiff": [0],
    "nc-1.nc": [0],
}


def record(path, index):
    reader = open_topography(path)
    ch = reader.channels[index]
    t = reader.topography(channel_index=index)
    h = np.asarray(t.heights(), dtype=np.float64)
    if np.ma.isMaskedArray(t.heights()):
        mask = np.ma.getmaskarray(t.heights())
        h = np.where(mask, np.nan, np.ma.getdata(t.heights()))
    unit = t.unit if isinstance(t.unit, str) else None
    f = get_unit_conversion_factor(unit, "m") if unit else None
    scale = f if f is not None else 1.0
    z = h * scale
    nx, ny = h.shape
    valid = z[np.isfinite(z)]
    rng = np.random.default_rng(37)
    ix = rng.integers(0, nx, 200)
    iy = rng.integers(0, ny, 200)
    samples = [[int(a), int(b), None if not np.isfinite(z[a, b]) else float(z[a, b])] for a, b in zip(ix, iy)]
    size = None
    if f is not None:
        size = [float(s) * f for s in t.physical_sizes]
    return {
        "channel": index,
        "name": ch.name,
        "channels": len(reader.channels),
        "nx": int(nx),
        "ny": int(ny),
        "size_m": size,
        "unit": unit,
        "unit_m": f,
        "missing": int(np.count_nonzero(~np.isfinite(z))),
        "sum_m": float(valid.sum()),
        "sum_sq_m2": float((valid * valid).sum()),
        "min_m": float(valid.min()),
        "max_m": float(valid.max()),
        "samples": samples,
    }


def main():
    out = {
        "generator": "scripts/topography-formats-reference.py",
        "reader": f"SurfaceTopography {SurfaceTopography.__version__}",
        "files": {},
    }
    for name, channels in FILES.items():
        path = os.path.join(DATA, name)
        out["files"][name] = [record(path, k) for k in channels]
        print(name, [(c["name"], c["nx"], c["ny"], c["size_m"], c["missing"]) for c in out["files"][name]], file=sys.stderr)
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, "w") as fh:
        json.dump(out, fh, indent=1)
        fh.write("\n")


if __name__ == "__main__":
    main()
