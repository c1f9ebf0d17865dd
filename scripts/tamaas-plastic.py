#!/usr/bin/env python3
"""Perfectly plastic rough contact, stiction against Tamaas's KatoSaturated, on the same heights.

The surface is that of scripts/tamaas-adhesion.py (stiction's self-affine generator, H = 0.8,
roll-off L/4, short cut-off 4 dx, seed 1, cell 100 um, scaled to a spectral rms slope), E* = 1 GPa,
the pressure capped at the hardness H; load control at the given mean pressures, each solved
cold. stiction: `cargo run --release -p stiction-bem --example plastic_load`
(BemSolver::solve_load_plastic). Tamaas 2.9 (PyPI): `KatoSaturated(model, surface, tol, pmax)`,
run in units of the cell size and E* (its iteration stalls in SI units: error 3.13 for 3500
iterations at the first load of the 128^2 case).

Usage:
    /tmp/tamaas-venv/bin/python scripts/tamaas-plastic.py --n 128 --slope 0.1 --hardness 5e7 \
        --loads 1e6 5e6 2e7 4e7 --out data/tamaas-plastic
Writes OUT/plastic-N-SLOPE-H.csv, one row per load, both codes.
"""

import argparse
import csv
import json
import os
import re
import subprocess
import sys
import tempfile
import time

import numpy as np
import tamaas as tm

CELL_M = 100e-6
E_STAR_PA = 1e9
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "target", "release", "examples", "plastic_load")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=128)
    ap.add_argument("--slope", type=float, default=0.1)
    ap.add_argument("--hardness", type=float, default=5e7)
    ap.add_argument("--tol", type=float, default=1e-6)
    ap.add_argument("--loads", type=float, nargs="+", default=[1e6, 5e6, 2e7, 4e7])
    ap.add_argument("--out", default=os.path.join(ROOT, "data", "tamaas-plastic"))
    a = ap.parse_args()
    n = a.n
    with tempfile.TemporaryDirectory() as d:
        hp = os.path.join(d, "h.bin")
        args = [EXAMPLE, str(n), repr(a.slope), repr(a.hardness), repr(a.tol), hp] + [repr(p) for p in a.loads]
        out = subprocess.run(args, env=dict(os.environ, RAYON_NUM_THREADS="1"), capture_output=True, text=True, check=True)
        st = [json.loads(line) for line in out.stdout.splitlines()]
        h = np.fromfile(hp, "<f8").reshape(n, n)
    tm.set_log_level(tm.LogLevel.info)
    rows = []
    for p, s in zip(a.loads, st):
        model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
        model.E = 1.0
        model.nu = 0.0
        solver = tm.KatoSaturated(model, h / CELL_M, a.tol, a.hardness / E_STAR_PA)
        solver.max_iter = 50_000
        log_fd = tempfile.TemporaryFile(mode="w+")
        saved = os.dup(2)
        os.dup2(log_fd.fileno(), 2)
        t0 = time.perf_counter()
        err = solver.solve(p / E_STAR_PA)
        dt = time.perf_counter() - t0
        os.dup2(saved, 2)
        os.close(saved)
        log_fd.seek(0)
        its = re.findall(r"^\s*(\d+)\s+\S+\s+\S+\s*$", log_fd.read(), re.M)
        tr = np.array(model.traction) * E_STAR_PA
        rows.append(
            {
                "mean_pressure_pa": p,
                "stiction_contact_fraction": s["contact_fraction"],
                "tamaas_contact_fraction": float(np.mean(tr > 0.0)),
                "stiction_plastic_fraction": s["plastic_fraction"],
                "tamaas_plastic_fraction": float(np.mean(tr >= a.hardness * (1.0 - 1e-9))),
                "tamaas_mean_pressure_pa": float(tr.mean()),
                "stiction_iterations": s["iterations"],
                "tamaas_iterations": max(int(i) for i in its) if its else -1,
                "stiction_seconds": s["seconds"],
                "tamaas_seconds": dt,
                "tamaas_error": float(err),
            }
        )
        print(json.dumps(rows[-1]), flush=True)
    os.makedirs(a.out, exist_ok=True)
    path = os.path.join(a.out, f"plastic-{n}-{a.slope}-{a.hardness:g}.csv")
    with open(path, "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(rows[0].keys()), lineterminator="\n")
        wr.writeheader()
        for r in rows:
            wr.writerow({k: (repr(v) if isinstance(v, float) else v) for k, v in r.items()})
    print(path, file=sys.stderr)


if __name__ == "__main__":
    main()
