"""What the Python binding adds to a call, in instructions (valgrind's callgrind): a measure that
does not depend on the load of the machine, unlike wall time.

For each call, Python runs it 1 + N1 and 1 + N2 times under callgrind, one file per thread (one
warm-up first, so imports and first-call caches are paid in both runs); differences of the two
runs divided by N2 - N1 give the instructions of one call:

* whole call: every thread's instructions;
* binding: the calling thread's (the Python wrapper, argument conversion and checks, starting the
  worker thread and waiting for it, the JSON text into Python objects and NumPy arrays), for the
  calls that run the engine on a worker thread (run, contact, bem, study); for `gw`, which runs on
  the calling thread, the whole call less the inclusive count of the model's solve;
* engine: the rest (the worker thread and the study's pool threads: the same library function the
  command line calls), and the freeing of the engine's JSON value when the result goes, which
  happens on the calling thread. A result's fields become Python objects when they are read, so
  the figures are those of the call; reading `points` of a sweep adds its conversion.

    python crates/py/bench/instructions.py [NAME...]   # from the repository root, package installed

Needs valgrind (callgrind, callgrind_annotate). Takes a few minutes.
"""

import glob
import os
import re
import subprocess
import sys
import tempfile

# name: (Python statement, for a call on the calling thread the engine symbols whose inclusive
# counts add up to the engine's work (else []: the engine is every other thread), N1, N2)
CALLS = {
    "gw(2.0, 0.5)": (
        "stiction.gw(2.0, 0.5)",
        ["stiction_contact::gw::GwModel::new", "stiction_contact::gw::GwModel::solve"],  # on the calling thread
        20,
        120,
    ),
    "run(tas2000)": ("stiction.run(TAS)", [], 1, 3),
    "contact(tas2000, 50 loads)": (
        "stiction.contact(TAS, LOADS)",
        [],
        1,
        3,
    ),
    "contact(tas2000, 400 loads)": ("stiction.contact(TAS, LOADS400)", [], 1, 2),
    "bem(128^2, 3 pressures)": (
        "stiction.bem(HEIGHTS, [5e6, 2e7, 8e7], pixel_size='0.1 um', height_unit='nm')",
        [],
        1,
        3,
    ),
    "study(tas2000, 8 samples, 1 thread)": (
        "stiction.study(TAS, samples=8, seed=1, threads=1, as_pandas=False)",
        [],
        1,
        3,
    ),
    "study(tas2000, 64 samples, 1 thread)": (
        "stiction.study(TAS, samples=64, seed=1, threads=1, as_pandas=False)",
        [],
        1,
        2,
    ),
}

FREE_RESULT = "core::ptr::drop_in_place<serde_json::value::Value>"

PRELUDE = """
import numpy as np
import stiction
TAS = "scenarios/tas2000.json"
LOADS = np.linspace(0, 5e-6, 50)
LOADS400 = np.linspace(0, 5e-6, 400)
y, x = np.mgrid[0:128, 0:128] / 128.0
HEIGHTS = 30 * np.sin(2 * np.pi * 3 * x) * np.cos(2 * np.pi * 2 * y)
"""


def callgrind(statement: str, n: int, out: str) -> None:
    script = PRELUDE + f"{statement}\nfor _ in range({n}):\n    {statement}\n"
    subprocess.run(
        ["valgrind", "--tool=callgrind", "--separate-threads=yes", f"--callgrind-out-file={out}", sys.executable, "-c",
         script],
        check=True,
        capture_output=True,
        # NumPy's BLAS threads would add their own (spinning) instructions to the other threads'.
        env={**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"},
    )


def thread_totals(out: str):
    """Instructions per thread: (the calling thread's, every other thread's together)."""
    main, other = 0, 0
    for path in glob.glob(out + "-*"):
        with open(path) as f:
            text = f.read()
        m = re.search(r"^(?:totals|summary):\s*(\d+)", text, re.M)
        count = int(m.group(1)) if m else 0
        if path.endswith("-01"):
            main += count
        else:
            other += count
    return main, other


def inclusive(out: str, symbols) -> int:
    text = subprocess.run(
        ["callgrind_annotate", "--inclusive=yes", "--threshold=100", out + "-01"], check=True, capture_output=True,
        text=True,
    ).stdout
    count = 0
    for symbol in symbols:
        best = 0
        for line in text.splitlines():
            m = re.match(r"^\s*([\d,]+) \([\s\d.]+%\)\s+\S*?:(.*)$", line) or re.match(r"^\s*([\d,]+)\s+\S*?:(.*)$", line)
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
            a, b = os.path.join(tmp, f"{n1}.out"), os.path.join(tmp, f"{n2}.out")
            callgrind(statement, n1, a)
            callgrind(statement, n2, b)
            (main_a, other_a), (main_b, other_b) = thread_totals(a), thread_totals(b)
            per_call = (main_b + other_b - main_a - other_a) / (n2 - n1)
            if symbols:
                over = per_call - (inclusive(b, symbols) - inclusive(a, symbols)) / (n2 - n1)
            else:
                # The engine's JSON value is freed on the calling thread when the result goes:
                # engine work (the command line frees it too), not the binding's.
                freed = (inclusive(b, [FREE_RESULT]) - inclusive(a, [FREE_RESULT])) / (n2 - n1)
                over = (main_b - main_a) / (n2 - n1) - freed
            engine = per_call - over
            print(f"{name:38s} {per_call:14,.0f} {engine:14,.0f} {over:12,.0f} {100 * over / per_call:6.2f}%")
            for path in glob.glob(a + "-*") + glob.glob(b + "-*"):
                os.remove(path)


if __name__ == "__main__":
    main()
