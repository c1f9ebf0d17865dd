#!/usr/bin/env python3
"""stiction's boundary-element solver against Tamaas, timed side by side on the same problem.

Two problems, each on an N x N grid (N = 1024 by default), same heights, same tolerance (1e-6):

* `non-periodic`: a finite patch on a half-space that goes on (stiction's zero-padded Green's
  function, Tamaas's `dcfft` operator registered by `ModelFactory.registerNonPeriodic`, both
  padded to 2N x 2N), no adhesion, load control: the self-affine surface of
  `cargo run --release -p stiction-bem --example bem_timing -- N non-periodic` (H = 0.8, rms
  0.5 um, 100 um cell, E* = 100 GPa, p = 0.05 E* h'_rms), cold start. Tamaas: `PolonskyKeerRey`
  (pressure primal, load control) with `setIntegralOperator("dcfft")`.
* `adhesive`: the loading branch (approach only) of `scripts/tamaas-adhesion.py`'s case
  (self-affine, spectral rms slope SLOPE, E* = 1 GPa, w = 12 J/m^2, Dugdale range 0.3 um),
  POINTS imposed mean gaps, each state warm-started from the one before, on both sides.

Each side is timed as a whole: stiction's process (setup, surface, solves) with
RAYON_NUM_THREADS=1 and with every core, Tamaas's `solve` calls alone (its PyPI build is serial:
`TamaasInfo.backend == "cpp"`). CPU time is user + system (`resource` for stiction's process,
`time.process_time` for Tamaas's solves).

Usage (Tamaas and NumPy in a venv, a test-time reference like mpmath):
    python3 -m venv /tmp/tamaas-venv && /tmp/tamaas-venv/bin/pip install tamaas==2.9.0 numpy
    cargo build --release -p stiction-bem --examples
    /tmp/tamaas-venv/bin/python scripts/tamaas-speed.py non-periodic [--n 1024]
    /tmp/tamaas-venv/bin/python scripts/tamaas-speed.py adhesive [--n 1024] [--slope 0.1] [--points 4]

Prints one JSON object per problem: both sides' wall and CPU seconds, iterations, and the
agreement of the results (contact fraction; mean traction for the adhesive branch).
"""

import argparse
import importlib.util
import json
import os
import re
import tempfile
import time

import numpy as np
import tamaas as tm

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLES = os.path.join(ROOT, "target", "release", "examples")
CELL_M = 100e-6

# The adhesion comparison's helpers (the child-process timing, Tamaas's adhesive path and its log).
_spec = importlib.util.spec_from_file_location("ta", os.path.join(ROOT, "scripts", "tamaas-adhesion.py"))
ta = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ta)
timed = ta.timed


def non_periodic(n, tol):
    exe = os.path.join(EXAMPLES, "bem_timing")
    with tempfile.TemporaryDirectory() as d:
        hp = os.path.join(d, "h.bin")
        out1, wall1, cpu1, sys1 = timed([exe, str(n), "non-periodic", hp], 1)
        h = np.fromfile(hp, "<f8").reshape(n, n)
    line = out1.stdout.strip()
    p = float(re.search(r"mean pressure (\S+) Pa", line).group(1))
    it = int(re.search(r"(\d+) iterations", line).group(1))
    area = float(re.search(r"A/A0 (\S+),", line).group(1))
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [CELL_M, CELL_M], [n, n])
    model.E = 1e11
    model.nu = 0.0
    tm.ModelFactory.registerNonPeriodic(model, "dcfft")
    solver = tm.PolonskyKeerRey(model, np.ascontiguousarray(h), tol)
    solver.setIntegralOperator("dcfft")
    solver.max_iter = 100_000
    tm.set_log_level(tm.LogLevel.info)
    with ta.CaptureStderr() as log:
        t0, c0 = time.perf_counter(), time.process_time()
        err = solver.solve(p)
        tw, tc = time.perf_counter() - t0, time.process_time() - c0
    tam_area = float(np.mean(np.array(model.traction) > 0))
    out2, wall2, cpu2, sys2 = timed([exe, str(n), "non-periodic"], os.cpu_count())
    return {
        "problem": f"non-periodic {n}x{n} (padded {2 * n}x{2 * n}), load control, tolerance {tol:g}",
        "stiction_1_thread": {"wall_s": wall1, "cpu_s": cpu1, "system_s": sys1, "log": line},
        "stiction_all_threads": {"wall_s": wall2, "cpu_s": cpu2, "system_s": sys2, "log": out2.stdout.strip()},
        "tamaas": {"wall_s": tw, "cpu_s": tc, "iterations": ta.last_iteration(log.text), "error": float(err)},
        "stiction_iterations": it,
        "contact_fraction": {"stiction": area, "tamaas": tam_area},
        "tamaas_over_stiction_1_thread_cpu": tc / cpu1,
        "tamaas_over_stiction_1_thread_wall": tw / wall1,
        "tamaas_over_stiction_machine_wall": tw / wall2,
    }


def adhesive(n, slope, points, tol, w, range_m, max_iter):
    exe = os.path.join(EXAMPLES, "adhesive_path")
    base = [exe, str(n), repr(slope), str(points), repr(tol), repr(w)]
    with tempfile.TemporaryDirectory() as d:
        hp = os.path.join(d, "h.bin")
        out, _, _, _ = timed(base + [hp, repr(range_m), "approach-path"], 1)
        h = np.fromfile(hp, "<f8").reshape(n, n)
    gaps = [(s["branch"], s["mean_gap_m"]) for s in map(json.loads, out.stdout.splitlines())]
    out1, wall1, cpu1, sys1 = timed(base + ["-", repr(range_m), "approach"], 1)
    st = [json.loads(x) for x in out1.stdout.splitlines()]
    t_cpu0 = time.process_time()
    tam_states, tam_wall = ta.run_tamaas(h, gaps, w, tol, range_m, max_iter)
    tam_cpu = time.process_time() - t_cpu0
    out2, wall2, cpu2, sys2 = timed(base + ["-", repr(range_m), "approach"], os.cpu_count())
    sigma0 = w / range_m
    rows = []
    for a, b in zip(st, tam_states):
        rows.append(
            {
                "mean_gap_m": a["mean_gap_m"],
                "mean_pressure_pa": [a["mean_pressure_pa"], b["mean_pressure_pa"]],
                "repulsive_fraction": [a["repulsive_fraction"], b["repulsive_fraction"]],
                "cohesive_fraction": [a["cohesive_fraction"], b["cohesive_fraction"]],
                "iterations": [a["iterations"], b["iterations"]],
                "traction_diff": ta.rel(a["mean_pressure_pa"], b["mean_pressure_pa"], 0.01 * sigma0),
                "tamaas_error": b["error"],
            }
        )
    return {
        "problem": f"adhesive loading branch {n}x{n}, slope {slope}, {points} mean gaps, w {w} J/m^2, range {range_m:g} m, tolerance {tol:g}",
        "stiction_1_thread": {"wall_s": wall1, "cpu_s": cpu1, "system_s": sys1, "log": out1.stderr.strip()},
        "stiction_all_threads": {"wall_s": wall2, "cpu_s": cpu2, "system_s": sys2, "log": out2.stderr.strip()},
        "tamaas": {"wall_s": tam_wall, "cpu_s": tam_cpu, "unconverged_states": sum(1 for t in tam_states if t["error"] > tol)},
        "iterations": [sum(r["iterations"][0] for r in rows), sum(r["iterations"][1] for r in rows)],
        "states": rows,
        "tamaas_over_stiction_1_thread_cpu": tam_cpu / cpu1,
        "tamaas_over_stiction_1_thread_wall": tam_wall / wall1,
        "tamaas_over_stiction_machine_wall": tam_wall / wall2,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("problem", choices=["non-periodic", "adhesive"])
    ap.add_argument("--n", type=int, default=1024)
    ap.add_argument("--tol", type=float, default=1e-6)
    ap.add_argument("--slope", type=float, default=0.1)
    ap.add_argument("--points", type=int, default=4)
    ap.add_argument("--w", type=float, default=12.0)
    ap.add_argument("--range-um", type=float, default=0.3)
    ap.add_argument("--max-iter", type=int, default=20_000)
    a = ap.parse_args()
    if a.problem == "non-periodic":
        r = non_periodic(a.n, a.tol)
    else:
        r = adhesive(a.n, a.slope, a.points, a.tol, a.w, a.range_um * 1e-6, a.max_iter)
    print(json.dumps(r, indent=1), flush=True)


if __name__ == "__main__":
    main()
