#!/usr/bin/env python3
"""Adhesive rough contact, stiction against Tamaas, side by side on the same heights.

Each case is a Gaussian self-affine surface made by stiction (H = 0.8, roll-off L/4, short
cut-off 4 dx, seed 1, cell 100 um, scaled to a spectral rms slope), E* = 1 GPa, the Dugdale law
of work of adhesion w and range 0.3 um, the same imposed mean gaps on approach (from just out of
reach, max(h) - mean(h) + range, down to a tenth of max(h) - mean(h)) and back on retraction.
stiction: `cargo run --release -p stiction-bem --example adhesive_path` (each state warm-started
from the one before, the cohesive zone updated to a fixed point). Tamaas 2.9 (PyPI):
`PolonskyKeerRey` in its gap formulation (primal and constraint the gap) with a
`MaugisAdhesionFunctional` (Rey, Anciaux & Molinari, Comput. Mech. 60 (2017) 69), warm-started
the same way, at the same tolerance. For each state: mean traction, repulsive area (gap = 0),
cohesive-zone area (gap < range, contact included), the energy per nominal area of the state
`Pi = U_el + mean(phi(g))` with `U_el = mean(p u)/2` and the Dugdale potential
`phi(g) = -(w/rho) max(rho - g, 0)`, and the iterations.

Usage (Tamaas and NumPy in a venv, a test-time reference like mpmath):
    python3 -m venv /tmp/tamaas-venv && /tmp/tamaas-venv/bin/pip install tamaas==2.9.0 numpy
    cargo build --release -p stiction-bem --example adhesive_path
    /tmp/tamaas-venv/bin/python scripts/tamaas-adhesion.py --case 128:0.1:12:12 --out data/tamaas-adhesion
    (--case N:SLOPE:W:POINTS[:RANGE_UM], repeatable, the range 0.3 um by default; --tol 1e-6;
    --threads 1; --refine K: also a stiction path with K times the points, for the step
    convergence; --only tamaas|stiction: run one side, Tamaas's states kept in
    OUT/tamaas-<case>.json and reused by a later run of the other side; --max-iter: Tamaas's
    cap per state)

Writes OUT/adhesion-N-SLOPE-W-POINTS[-rRANGE].csv (one row per state, both codes) and prints a
summary (pull-off, median and largest differences, iterations, times, the surface's rms
curvature and the Maugis parameter of a sphere of that curvature's radius) as JSON on stdout.
"""

import argparse
import csv
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np
import tamaas as tm

CELL_M = 100e-6
E_STAR_PA = 1e9
RANGE_M = 0.3e-6
# Tamaas's cap on iterations per state (a state that reaches it is reported with its error).
MAX_ITER = 20_000
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "target", "release", "examples", "adhesive_path")


def timed(args, threads):
    """Runs `args` with RAYON_NUM_THREADS=threads: (completed process, wall s, CPU s = user +
    system, system s) of the child."""
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    out = subprocess.run(args, env=env, capture_output=True, text=True, check=True)
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    return out, wall, cpu, r1.ru_stime - r0.ru_stime


def run_stiction(n, slope, w, points, tol, threads, heights_path="", range_m=RANGE_M, mode="solve"):
    args = [EXAMPLE, str(n), repr(slope), str(points), repr(tol), repr(w), heights_path or "-", repr(range_m), mode]
    out, wall, cpu, _ = timed(args, threads)
    states = [json.loads(line) for line in out.stdout.splitlines()]
    return states, wall, out.stderr.strip() + f"; CPU (user + system) {cpu:.3f} s"


class CaptureStderr:
    """The text written to file descriptor 2 inside the block (C++ writes it directly)."""

    def __enter__(self):
        sys.stderr.flush()
        self.tmp = tempfile.TemporaryFile(mode="w+")
        self.saved = os.dup(2)
        os.dup2(self.tmp.fileno(), 2)
        return self

    def __exit__(self, *exc):
        sys.stderr.flush()
        os.dup2(self.saved, 2)
        os.close(self.saved)
        self.tmp.seek(0)
        self.text = self.tmp.read()
        self.tmp.close()


def last_iteration(log):
    rows = re.findall(r"^\s*(\d+)\s+\S+\s+\S+\s*$", log, re.M)
    return max(int(r) for r in rows) if rows else -1


def energy(p, u, gap, w, range_m):
    sigma0 = w / range_m
    u0 = u - u.mean()
    return 0.5 * np.mean(p * u0) - sigma0 * np.mean(np.maximum(range_m - gap, 0.0))


def rms_curvature(h):
    """Spectral rms of the mean curvature (Laplacian / 2) of the periodic heights, 1/m."""
    n = h.shape[0]
    q = 2 * np.pi * np.fft.fftfreq(n, CELL_M / n)
    q2 = q[:, None] ** 2 + q[None, :] ** 2
    lap = np.real(np.fft.ifft2(-q2 * np.fft.fft2(h)))
    return float(np.sqrt(np.mean((0.5 * lap) ** 2)))


def run_tamaas(h, gaps, w, tol, range_m, max_iter):
    n = h.shape[0]
    tm.set_log_level(tm.LogLevel.info)
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [CELL_M, CELL_M], [n, n])
    model.E = E_STAR_PA
    model.nu = 0.0
    solver = tm.PolonskyKeerRey(model, h, tol, tm.PolonskyKeerRey.gap, tm.PolonskyKeerRey.gap)
    solver.max_iter = max_iter
    adhesion = tm.MaugisAdhesionFunctional(h)
    adhesion.parameters = {"rho": range_m, "surface_energy": w}
    solver.addFunctionalTerm(adhesion)
    states, solve_s, cpu_s = [], 0.0, 0.0
    for branch, g in gaps:
        # Tamaas writes its iteration log to the standard error (file descriptor 2).
        with CaptureStderr() as log:
            t0, c0 = time.perf_counter(), time.process_time()
            err = solver.solve(g)
            dt, dc = time.perf_counter() - t0, time.process_time() - c0
        solve_s += dt
        cpu_s += dc
        gap = np.array(model["gap"])
        p = np.array(model.traction)
        u = np.array(model.displacement)
        states.append(
            {
                "branch": branch,
                "mean_gap_m": float(gap.mean()),
                "mean_pressure_pa": float(p.mean()),
                "repulsive_fraction": float(np.mean(gap == 0.0)),
                "cohesive_fraction": float(np.mean(gap < range_m)),
                "energy_j_per_m2": float(energy(p, u, gap, w, range_m)),
                "iterations": last_iteration(log.text),
                "seconds": dt,
                "cpu_seconds": dc,
                "error": float(err),
            }
        )
    return states, solve_s


def maugis(sigma0, w, radius):
    """Maugis parameter lambda = 2 sigma0 (R D^2/(pi w))^(1/3), D = 3/(4 E*), of a sphere of radius R."""
    d = 0.75 / E_STAR_PA
    return float(2 * sigma0 * (radius * d * d / (np.pi * w)) ** (1 / 3))


def rel(a, b, floor):
    return abs(a - b) / max(abs(b), floor)


def case_name(n, slope, w, points, range_m):
    tail = "" if range_m == RANGE_M else f"-r{range_m * 1e6:g}"
    return f"{n}-{slope}-{w}-{points}{tail}"


def case(n, slope, w, points, range_m, tol, threads, refine, out_dir, only, max_iter):
    stem = case_name(n, slope, w, points, range_m)
    cache = os.path.join(out_dir, f"tamaas-{stem}.json")
    with tempfile.TemporaryDirectory() as d:
        hp = os.path.join(d, "h.bin")
        path, _, _ = run_stiction(n, slope, w, points, tol, threads, hp, range_m, "path")
        h = np.fromfile(hp, "<f8").reshape(n, n)
    gaps = [(s["branch"], s["mean_gap_m"]) for s in path]
    if only != "stiction":
        tam, tam_s = run_tamaas(h, gaps, w, tol, range_m, max_iter)
        os.makedirs(out_dir, exist_ok=True)
        with open(cache, "w") as f:
            json.dump({"case": stem, "tol": tol, "max_iter": max_iter, "solve_s": tam_s, "states": tam}, f, indent=0)
        if only == "tamaas":
            return {"case": stem, "tamaas_solve_s": tam_s, "tamaas_iterations": sum(t["iterations"] for t in tam)}
    else:
        with open(cache) as f:
            c = json.load(f)
        tam, tam_s = c["states"], c["solve_s"]
        assert len(tam) == len(gaps) and all(abs(t["mean_gap_m"] / g - 1) < 1e-6 for t, (_, g) in zip(tam, gaps))
    st, st_wall, st_log = run_stiction(n, slope, w, points, tol, threads, "", range_m)
    rows = []
    for i, (a, b) in enumerate(zip(st, tam)):
        rows.append(
            {
                "index": i,
                "branch": a["branch"],
                "mean_gap_m": a["mean_gap_m"],
                "stiction_mean_pressure_pa": a["mean_pressure_pa"],
                "tamaas_mean_pressure_pa": b["mean_pressure_pa"],
                "stiction_repulsive_fraction": a["repulsive_fraction"],
                "tamaas_repulsive_fraction": b["repulsive_fraction"],
                "stiction_cohesive_fraction": a["cohesive_fraction"],
                "tamaas_cohesive_fraction": b["cohesive_fraction"],
                "stiction_energy_j_per_m2": a["elastic_energy_j_per_m2"] + a["adhesive_energy_j_per_m2"],
                "tamaas_energy_j_per_m2": b["energy_j_per_m2"],
                "stiction_iterations": a["iterations"],
                "tamaas_iterations": b["iterations"],
                "tamaas_seconds": b["seconds"],
                "tamaas_error": b["error"],
            }
        )
    os.makedirs(out_dir, exist_ok=True)
    name = f"adhesion-{stem}.csv"
    with open(os.path.join(out_dir, name), "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(rows[0].keys()), lineterminator="\n")
        wr.writeheader()
        for r in rows:
            wr.writerow({k: (repr(v) if isinstance(v, float) else v) for k, v in r.items()})
    sigma0 = w / range_m
    dp = [rel(r["stiction_mean_pressure_pa"], r["tamaas_mean_pressure_pa"], 0.01 * sigma0) for r in rows]
    da = [
        rel(r["stiction_repulsive_fraction"], r["tamaas_repulsive_fraction"], 1.0 / (n * n))
        for r in rows
        if r["tamaas_repulsive_fraction"] > 0
    ]
    dz = [
        rel(r["stiction_cohesive_fraction"], r["tamaas_cohesive_fraction"], 1.0 / (n * n))
        for r in rows
        if r["tamaas_cohesive_fraction"] > 0
    ]
    retr = [r for r in rows if r["branch"] == "retraction"]
    summary = {
        "case": name,
        "pull_off_stiction_pa": min(r["stiction_mean_pressure_pa"] for r in retr),
        "pull_off_tamaas_pa": min(r["tamaas_mean_pressure_pa"] for r in retr),
        "pressure_diff_median": float(np.median(dp)),
        "pressure_diff_max": float(np.max(dp)),
        "repulsive_diff_median": float(np.median(da)) if da else None,
        "repulsive_diff_max": float(np.max(da)) if da else None,
        "cohesive_diff_median": float(np.median(dz)) if dz else None,
        "cohesive_diff_max": float(np.max(dz)) if dz else None,
        "stiction_iterations": sum(r["stiction_iterations"] for r in rows),
        "tamaas_iterations": sum(r["tamaas_iterations"] for r in rows),
        "stiction_process_s": st_wall,
        "stiction_log": st_log,
        "tamaas_solve_s": tam_s,
        "threads": threads,
        "range_m": range_m,
        "rms_curvature_per_m": rms_curvature(h),
        "maugis_parameter_at_rms_curvature": maugis(sigma0, w, 1.0 / rms_curvature(h)),
        "tamaas_unconverged_states": sum(1 for t in tam if t["error"] > tol),
    }
    if refine > 1:
        fine, fine_wall, _ = run_stiction(n, slope, w, refine * (points - 1) + 1, tol, threads, "", range_m)
        summary["pull_off_stiction_refined_pa"] = min(
            s["mean_pressure_pa"] for s in fine if s["branch"] == "retraction"
        )
        summary["refine"] = refine
    return summary


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--case", action="append", required=True, help="N:SLOPE:W:POINTS")
    ap.add_argument("--tol", type=float, default=1e-6)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--refine", type=int, default=0)
    ap.add_argument("--only", choices=["tamaas", "stiction"], default=None)
    ap.add_argument("--max-iter", type=int, default=MAX_ITER)
    ap.add_argument("--out", default=os.path.join(ROOT, "data", "tamaas-adhesion"))
    a = ap.parse_args()
    for c in a.case:
        parts = c.split(":")
        n, slope, w, points = parts[:4]
        range_m = float(parts[4]) * 1e-6 if len(parts) > 4 else RANGE_M
        s = case(
            int(n), float(slope), float(w), int(points), range_m, a.tol, a.threads, a.refine, a.out, a.only, a.max_iter
        )
        print(json.dumps(s), flush=True)


if __name__ == "__main__":
    main()
