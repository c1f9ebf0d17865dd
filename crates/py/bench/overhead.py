"""Python call overhead of the stiction package.

Cheap calls: the whole time of `stiction.gw(theta, L)` at one load (an upper bound of the
binding's overhead), best of 7 runs of 2000 calls. Long calls (> 10 ms): the wall time of the
Python call against the engine time of the same call measured on its worker thread
(`_stiction._last_engine_seconds`), so that the difference is what the binding adds (arguments,
the worker thread, the result's JSON into Python objects and arrays); median of 7 calls.

    python crates/py/bench/overhead.py           # from the repository root, the package installed
"""

import statistics
import time
import timeit

import numpy as np

import stiction
from stiction import _stiction

TAS = "scenarios/tas2000.json"


def cheap():
    stiction.gw(2.0, 0.5)  # warm
    n = 2000
    per_call = min(timeit.repeat(lambda: stiction.gw(2.0, 0.5), number=n, repeat=7)) / n
    print(f"gw at one load:            {per_call * 1e6:7.2f} us per call (whole call, best of 7 x {n})")
    d = min(timeit.repeat(lambda: stiction.asperity(5e-7, 0.1, 9.1e-12, 1.4e9, 1e-6), number=500, repeat=7)) / 500
    print(f"asperity (DMT) at one load: {d * 1e6:7.2f} us per call (whole call, best of 7 x 500)")


def long_call(name, call):
    call()
    walls, overheads = [], []
    for _ in range(7):
        t0 = time.perf_counter()
        call()
        wall = time.perf_counter() - t0
        engine = _stiction._last_engine_seconds()
        walls.append(wall)
        overheads.append(wall - engine)
    wall, over = statistics.median(walls), statistics.median(overheads)
    print(f"{name:26s} {wall * 1e3:8.2f} ms per call, binding {over * 1e3:6.3f} ms = {100 * over / wall:5.2f} %")


def main():
    cheap()
    long_call("run (tas2000)", lambda: stiction.run(TAS))
    long_call("contact sweep, 50 loads", lambda: stiction.contact(TAS, np.linspace(0, 5e-6, 50)))
    long_call("contact sweep, 400 loads", lambda: stiction.contact(TAS, np.linspace(0, 5e-6, 400)))
    y, x = np.mgrid[0:128, 0:128] / 128.0
    heights = 30 * np.sin(2 * np.pi * 3 * x) * np.cos(2 * np.pi * 2 * y)
    long_call("bem 128^2, 3 pressures", lambda: stiction.bem(heights, [5e6, 2e7, 8e7], pixel_size="0.1 um", height_unit="nm"))
    long_call("study, 8 samples, 1 thread", lambda: stiction.study(TAS, samples=8, seed=1, threads=1, as_pandas=False))


if __name__ == "__main__":
    main()
