#!/usr/bin/env python3
"""A tuned NumPy solve of the explicit solver's flat DMT loading curve, for the comparison in
docs/performance.md (issue 16). Same summits, same method as `stiction contact --mode flat`:

* the summits sorted by descending height once; at separation d the summits that can touch are
  the prefix with h > d (one binary search), so each pass touches only that prefix;
* DMT per summit (eq. 4): z = h - d, P = R^1/2 z^3/2 / D - 2 pi dgamma R, k = 3/2 (R z)^1/2 / D;
  the contact set of a flat DMT shoe is {z >= 0} (jump-in and release both at z = 0);
* Newton on the force balance sum P - L = 0 (d <- d + F/K), halving the step while the residual
  grows (summits jumping in), to |residual| <= 1e-9 x max(|L|, sum |P|, one summit's adhesion),
  each load from the previous equilibrium (the solver's relative tolerance is 1e-9 as well).

Usage (the commands in docs/performance.md):
  stiction surface benches/numpy-1e6.json --npy /tmp/numpy-1e6-summits.npy
  python3 benches/numpy_flat_dmt.py /tmp/numpy-1e6-summits.npy 0 62 100
  (or --csv /tmp/numpy-1e6-summits.csv and the .csv: a name ending in .npy is read with np.load as
  the N x 4 float64 array x, y, height, radius, as a researcher holds it; otherwise np.loadtxt)
prints one line per load (L, d, N, A_r, F_cap, passes) and the time of the curve in process.
Material as in scenarios/tas2000.json: D = 9.1e-12 1/Pa, dgamma = 0.1 J/m^2, s = 1.4 GPa.
"""
import sys
import time

import numpy as np

D = 9.1e-12
DGAMMA = 0.1
SHEAR = 1.4e9
TOL = 1e-9


def main():
    path, l_from, l_to, steps = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
    t0 = time.perf_counter()
    if path.endswith(".npy"):
        data = np.load(path)
        h = np.ascontiguousarray(data[:, 2])
        radii = data[:, 3]
    else:
        data = np.loadtxt(path, delimiter=",", skiprows=1, usecols=(2, 3))
        h = np.ascontiguousarray(data[:, 0])
        radii = data[:, 1]
    radius = float(radii[0])
    if not np.all(radii == radius):
        sys.exit("this comparison is for one summit radius")
    t_read = time.perf_counter()
    h = -np.sort(-h)  # descending
    neg_h = -h  # ascending, for searchsorted
    inv_d = 1.0 / D
    c = 2.0 * np.pi * DGAMMA * radius
    sqrt_r = np.sqrt(radius)
    loads = np.linspace(l_from, l_to, steps)

    def evaluate(d):
        k = int(np.searchsorted(neg_h, -d, side="right"))  # summits with h >= d
        z = h[:k] - d
        s = np.sqrt(z)
        p = sqrt_r * s * z * inv_d - c
        return k, float(p.sum()), float(np.abs(p).sum()), 1.5 * sqrt_r * inv_d * float(s.sum()), float(z.sum())

    d = float(h[0])  # just touching the highest summit
    passes_total = 0
    out = []
    t1 = time.perf_counter()
    c1 = time.process_time()
    for load in loads:
        k, f, fabs, kk, zsum = evaluate(d)
        passes = 1
        while True:
            resid = f - load
            scale = max(abs(load), fabs, c)
            if abs(resid) <= TOL * scale:
                break
            step = resid / kk if kk > 0 else -1e-3 * (h[0] - h[-1])
            for _ in range(60):
                dn = d + step
                kn, fn, fabsn, kkn, zsumn = evaluate(dn)
                passes += 1
                if abs(fn - load) < abs(resid) or kk == 0:
                    break
                step *= 0.5
            d, k, f, fabs, kk, zsum = dn, kn, fn, fabsn, kkn, zsumn
            if passes > 500:
                sys.exit(f"no convergence at L = {load}")
        passes_total += passes
        area = np.pi * radius * zsum
        out.append((load, d, k, area, SHEAR * area, passes))
    t2 = time.perf_counter()
    c2 = time.process_time()
    print("  L (N)         d (nm)      N   A_r (um^2)   F_cap (N)   passes")
    for load, d, k, area, cap, passes in out:
        print(f"  {load:10.4f} {d * 1e9:12.4f} {k:8d} {area * 1e12:12.5e} {cap:11.4f} {passes:4d}")
    print(
        f"# summits {h.size}, read {t_read - t0:.3f} s, sort {t1 - t_read:.3f} s, curve {t2 - t1:.3f} s "
        f"({(t2 - t1) / steps * 1e3:.3f} ms per point, {passes_total} passes), curve CPU {c2 - c1:.3f} s",
        file=sys.stderr,
    )


if __name__ == "__main__":
    main()
