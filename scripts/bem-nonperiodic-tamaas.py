#!/usr/bin/env python3
"""Reference values for stiction's non-periodic (zero-padded) boundary-element operator from
Tamaas's non-periodic `dcfft` operator (Tamaas 2.9, PyPI: `pip install tamaas==2.9.0 numpy`).

Three problems on a square grid of square pixels, solved by Tamaas's PolonskyKeerRey (pressure
primal, load control) with the integral operator `dcfft` (registered by
`ModelFactory.registerNonPeriodic`), E* = E (nu = 0):

* `punch`: a rigid flat circular punch (heights 0 inside radius 0.3 L, -1 um outside);
* `hertz`: a sphere (heights -r^2/(2R)) whose contact radius is about a quarter of the patch;
* `rough`: a seeded Gaussian random patch (heights stored in the file).

For each it writes the grid, the load, the heights (rough only), and Tamaas's contact pressure
field (row-major, the first array index is the row) and the flat's height over the contact
`mean_{p > 0}(h - u)` with `u` the dcfft displacement. The test
`crates/bem/tests/nonperiodic.rs` reads the file and holds stiction's solution to it.

Usage: python3 scripts/bem-nonperiodic-tamaas.py data/bem-nonperiodic-tamaas/reference.json
"""
import json
import sys

import numpy as np
import tamaas as tm

N = 48
L = 12e-6  # patch side, m
E_STAR = 100e9  # Pa
TOL = 1e-12


def solve(heights, mean_pressure):
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [L, L], [N, N])
    model.E = E_STAR
    model.nu = 0.0
    tm.ModelFactory.registerNonPeriodic(model, "dcfft")
    heights = np.ascontiguousarray(heights, dtype=np.float64)
    solver = tm.PolonskyKeerRey(model, heights, TOL)
    solver.setIntegralOperator("dcfft")
    solver.max_iter = 100000
    solver.solve(mean_pressure)
    p = np.array(model.traction, copy=True)
    u = np.zeros_like(p)
    model.operators["dcfft"](p, u)
    contact = p > 0
    flat = float(np.mean((heights - u)[contact]))
    return p, flat, int(contact.sum())


def main():
    out = sys.argv[1]
    dx = L / N
    c = (np.arange(N) + 0.5) * dx - 0.5 * L
    y, x = np.meshgrid(c, c, indexing="ij")
    r = np.hypot(x, y)
    cases = {}
    punch = np.where(r < 0.3 * L, 0.0, -1e-6)
    radius = 200e-6
    hertz = -(r**2) / (2 * radius)
    rng = np.random.default_rng(38)
    noise = rng.standard_normal((N, N))
    q = np.hypot(*np.meshgrid(np.fft.fftfreq(N), np.fft.fftfreq(N), indexing="ij"))
    filt = np.where(q > 0, (np.maximum(q, 1.0 / 12) / (1.0 / 12)) ** -1.8, 0.0)
    rough = np.real(np.fft.ifft2(np.fft.fft2(noise) * filt))
    rough *= 20e-9 / rough.std()
    for name, h, pm in [("punch", punch, 20e6), ("hertz", hertz, 125e6), ("rough", rough, 150e6)]:
        p, flat, n_contact = solve(h, pm)
        case = {
            "mean_pressure_pa": pm,
            "contact_points": n_contact,
            "flat_height_m": flat,
            "pressure_pa": [float(f"{v:.12e}") for v in p.ravel()],
        }
        if name == "rough":
            case["heights_m"] = [float(f"{v:.15e}") for v in h.ravel()]
        cases[name] = case
    doc = {
        "source": "Tamaas " + tm.__version__ + " PolonskyKeerRey with the dcfft operator, tolerance 1e-12",
        "n": N,
        "pixel_m": dx,
        "e_star_pa": E_STAR,
        "punch_radius_m": 0.3 * L,
        "sphere_radius_m": radius,
        "cases": cases,
    }
    with open(out, "w") as f:
        json.dump(doc, f, separators=(",", ":"))
        f.write("\n")


if __name__ == "__main__":
    main()
