#!/usr/bin/env python3
"""Regenerates the table of docs/experiment.md, "Which structure measures mu_e,a most narrowly on a
given wall": the three bundled test structures on the same wall (Table 1, R = 0.5 um lognormal with
sd 0.3 um, the explicit solver), a Monte Carlo study of SAMPLES devices each (seed 1), and for each
structure the spread of mu_e,a across devices and the median width of the 95 % interval a lab
quotes for one device (its eq. 10 regression, `lab_intervals`).

    scripts/structure-comparison.py [SAMPLES]        # default 40
    STICTION=path/to/stiction scripts/structure-comparison.py

Needs the release binary (`cargo build --release -p stiction-cli`); prints the Markdown table.
"""

import json
import os
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
RADIUS = 'surface.summit_radius={"value":"0.5 um","sd":"0.3 um","distribution":"lognormal"}'
FLAT = ["--set", RADIUS, "--set", "contact.model=explicit", "--set", "contact.mode=flat"]
STRUCTURES = [
    ("comb sidewall tester", "scenarios/comb-sidewall.json", [], "1000 um^2 shoe, tilt free"),
    ("plate, released spring", "scenarios/plate-released-spring.json", FLAT, "2500 um^2 plate, flat"),
    ("pad, uniform pressure", "scenarios/pad-uniform-pressure.json", FLAT, "100 um^2 pad, flat"),
]


def stiction() -> str:
    return os.environ.get("STICTION") or str(ROOT / "target" / "release" / "stiction")


def study(path: str, sets: list, samples: int) -> dict:
    cmd = [stiction(), "study", path, "--samples", str(samples), "--seed", "1", "--json", *sets]
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)}: {p.stderr.strip()}")
    return json.loads(p.stdout)


def median(spread) -> str:
    return "n/a" if not spread else f"{spread['median']:.2g}"


def main() -> None:
    samples = int(sys.argv[1]) if len(sys.argv) > 1 else 40
    print("| structure | contact | loads | devices with a fit | mu_e,a mean | sd across devices | 5-95 % | "
          "lab 95 % CI width of mu_e,a (median) | F_a0 mean (sd) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, path, sets, contact in STRUCTURES:
        s = study(path, sets, samples)
        run = subprocess.run([stiction(), "run", path, "--json", *sets], cwd=ROOT, capture_output=True, text=True)
        loads = [p["load_n"] for p in json.loads(run.stdout)["points"] if p.get("friction_n") is not None]
        mu, fa = s["mu_apparent"], s["apparent_adhesion_force_n"]
        li = s["lab_intervals"]
        print(
            f"| {name} | {contact} | {min(loads) * 1e6:.3g}-{max(loads) * 1e6:.3g} uN | {s['with_fit']} of {samples} | "
            f"{mu['mean']:.2f} | {mu['sd']:.2f} | {mu['p05']:.2f}-{mu['p95']:.2f} | {median(li['mu_ci95_width'])} | "
            f"{fa['mean'] * 1e6:.1f} ({fa['sd'] * 1e6:.1f}) uN |"
        )


if __name__ == "__main__":
    main()
