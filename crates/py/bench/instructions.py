"""What the Python binding adds to a call, in instructions (valgrind's callgrind): a measure that
does not depend on the load of the machine, unlike wall time.

For each call, Python runs it 1 + N1 and 1 + N2 times under callgrind (one warm-up first, so
imports and first-call caches are paid in both runs); the difference of the two totals divided by
N2 - N1 is the instructions of one whole call from Python. The engine's share is the inclusive
count of the engine's own entry point (the `stiction_cli::api` function the command line calls
too, or the model's solve for `gw`) divided by the number of calls. The binding's added work is
the rest: argument conversion and checks, the worker thread, the JSON text into Python objects
and NumPy arrays, the Python wrapper.

    python crates/py/bench/instructions.py          # from the repository root, package installed

Needs valgrind (callgrind, callgrind_annotate). Takes a few minutes.
"""

import os
import re
import subprocess
import sys
import tempfile

# name: (Python statement, engine symbols whose inclusive counts add up to the engine's work, N1, N2)
CALLS = {
    "gw(2.0, 0.5)": (
        "stiction.gw(2.0, 0.5)",
        ["stiction_contact::gw::GwModel::new", "stiction_contact::gw::GwModel::solve"],
        20,
        120,
    ),
    "run(tas2000)": ("stiction.run(TAS)", ["stiction_cli::cmd::run::run_json"], 1, 3),
    "contact(tas2000, 50 loads)": (
        "stiction.contact(TAS, LOADS)",
        ["stiction_cli::cmd::contact::contact_json"],
        1,
        3,
    ),
    "bem(128^2, 3 pressures)": (
        "stiction.bem(HEIGHTS, [5e6, 2e7, 8e7], pixel_size='0.1 um', height_unit='nm')",
        ["stiction_cli::cmd::bem::bem_json_of_map"],
        1,
        3,
    ),
    "study(tas2000, 8 samples, 1 thread)": (
        "stiction.study(TAS, samples=8, seed=1, threads=1, as_pandas=False)",
        ["stiction_cli::cmd::study::study_json_of"],
        1,
        3,
    ),
}

PRELUDE = """
import numpy as np
import stiction
TAS = "scenarios/tas2000.json"
LOADS = np.linspace(0, 5e-6, 50)
y, x = np.mgrid[0:128, 0:128] / 128.0
HEIGHTS = 30 * np.sin(2 * np.pi * 3 * x) * np.cos(2 * np.pi * 2 * y)
"""


def callgrind(statement: str, n: int, out: str) -> None:
    script = PRELUDE + f"{statement}\nfor _ in range({n}):\n    {statement}\n"
    subprocess.run(
        ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", sys.executable, "-c", script],
        check=True,
        capture_output=True,
    )


def total(out: str) -> int:
    text = subprocess.run(["callgrind_annotate", out], check=True, capture_output=True, text=True).stdout
    m = re.search(r"^\s*([\d,]+) \(100\.0%\)\s+PROGRAM TOTALS", text, re.M)
    if not m:
        m = re.search(r"^\s*([\d,]+)\s+PROGRAM TOTALS", text, re.M)
    return int(m.group(1).replace(",", ""))


def inclusive(out: str, symbols) -> int:
    text = subprocess.run(
        ["callgrind_annotate", "--inclusive=yes", "--threshold=100", out], check=True, capture_output=True, text=True
    ).stdout
    count = 0
    for symbol in symbols:
        best = 0
        for line in text.splitlines():
            m = re.match(r"^\s*([\d,]+) \([\s\d.]+%\)\s+\S*:(.*)$", line) or re.match(r"^\s*([\d,]+)\s+\S*:(.*)$", line)
            if m and m.group(2).startswith(symbol) and m.group(2)[len(symbol):len(symbol) + 1] in ("", " ", "<", "("):
                best = max(best, int(m.group(1).replace(",", "")))
        count += best
    return count


def main() -> None:
    only = sys.argv[1:]
    print(f"{'call':38s} {'whole call':>14s} {'engine':>14s} {'binding':>12s} {'share':>7s}")
    with tempfile.TemporaryDirectory() as tmp:
        for name, (statement, symbols, n1, n2) in CALLS.items():
            if only and not any(o in name for o in only):
                continue
            a, b = os.path.join(tmp, "a.out"), os.path.join(tmp, "b.out")
            callgrind(statement, n1, a)
            callgrind(statement, n2, b)
            per_call = (total(b) - total(a)) / (n2 - n1)
            engine = (inclusive(b, symbols) - inclusive(a, symbols)) / (n2 - n1)
            over = per_call - engine
            print(f"{name:38s} {per_call:14,.0f} {engine:14,.0f} {over:12,.0f} {100 * over / per_call:6.2f}%")


if __name__ == "__main__":
    main()
