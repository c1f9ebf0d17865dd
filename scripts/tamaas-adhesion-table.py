#!/usr/bin/env python3
"""Tables of the adhesive comparison against Tamaas from data/tamaas-adhesion (the CSVs written
by scripts/tamaas-adhesion.py): per case, on the states Tamaas converged (its error below the
tolerance): the median and largest relative differences of the mean traction (relative to
max(|p|, 1 % of w/rho)), the repulsive area and the cohesive-zone area (relative to the larger
of Tamaas's value and one pixel), the pull-off of each code (most tensile mean traction on the
retraction), the iterations of each code on those states, and the states where the two differ by
more than 1 % with both energies `Pi = U_el + mean(phi(g))` (J/m^2; the lower one is the more
stable equilibrium of the two).

    python3 scripts/tamaas-adhesion-table.py [data/tamaas-adhesion] [--states]
"""

import csv
import glob
import os
import statistics
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def rel(a, b, floor):
    return abs(a - b) / max(abs(b), floor)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    folder = args[0] if args else os.path.join(ROOT, "data", "tamaas-adhesion")
    show_states = "--states" in sys.argv
    print(
        "| case (N, slope, w, points, range) | Tamaas states converged | traction median / max | repulsive area "
        "median / max | zone median / max | pull-off stiction / Tamaas (MPa) | iterations stiction / Tamaas |"
    )
    print("|---|---|---|---|---|---|---|")
    split = []
    for path in sorted(glob.glob(os.path.join(folder, "adhesion-*.csv"))):
        rows = list(csv.DictReader(open(path)))
        stem = os.path.basename(path)[len("adhesion-") : -len(".csv")]
        parts = stem.split("-")
        n = int(parts[0])
        rng = float(parts[4][1:]) * 1e-6 if len(parts) > 4 else 0.3e-6
        w = float(parts[2])
        sigma0 = w / rng
        pix = 1.0 / (n * n)
        ok = [r for r in rows if float(r["tamaas_error"]) < 1e-6]
        f = lambda r, k: float(r[k])
        dp = [rel(f(r, "stiction_mean_pressure_pa"), f(r, "tamaas_mean_pressure_pa"), 0.01 * sigma0) for r in ok]
        da = [
            rel(f(r, "stiction_repulsive_fraction"), f(r, "tamaas_repulsive_fraction"), pix)
            for r in ok
            if f(r, "tamaas_repulsive_fraction") > 0 or f(r, "stiction_repulsive_fraction") > 0
        ]
        dz = [rel(f(r, "stiction_cohesive_fraction"), f(r, "tamaas_cohesive_fraction"), pix) for r in ok]
        retr = [r for r in rows if r["branch"] == "retraction"]
        po_s = min(f(r, "stiction_mean_pressure_pa") for r in retr)
        po_t = min(f(r, "tamaas_mean_pressure_pa") for r in retr)
        it_s = sum(int(r["stiction_iterations"]) for r in ok)
        it_t = sum(int(r["tamaas_iterations"]) for r in ok)

        def mm(v):
            return f"{100 * statistics.median(v):.2f} % / {100 * max(v):.1f} %" if v else "-"

        print(
            f"| {n}, {parts[1]}, {w:g}, {parts[3]}, {rng * 1e6:g} um | {len(ok)}/{len(rows)} | {mm(dp)} | {mm(da)} | "
            f"{mm(dz)} | {po_s / 1e6:.3f} / {po_t / 1e6:.3f} ({100 * (po_s / po_t - 1):+.2f} %) | {it_s} / {it_t} "
            f"({it_s / max(it_t, 1):.2f}x) |"
        )
        for r, e in zip(ok, dp):
            if e > 0.01:
                split.append((stem, r, e))
    if show_states:
        print()
        print("| case | state | mean gap (um) | traction stiction / Tamaas (MPa) | difference | energy stiction / Tamaas (J/m^2) | lower |")
        print("|---|---|---|---|---|---|---|")
        for stem, r, e in split:
            es, et = float(r["stiction_energy_j_per_m2"]), float(r["tamaas_energy_j_per_m2"])
            print(
                f"| {stem} | {r['index']} {r['branch']} | {float(r['mean_gap_m']) * 1e6:.4f} | "
                f"{float(r['stiction_mean_pressure_pa']) / 1e6:.3f} / {float(r['tamaas_mean_pressure_pa']) / 1e6:.3f} | "
                f"{100 * e:.1f} % | {es:.4f} / {et:.4f} | {'stiction' if es < et else 'Tamaas'} |"
            )


if __name__ == "__main__":
    main()
