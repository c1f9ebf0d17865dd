#!/usr/bin/env bash
# Every test of stiction: the Rust workspace (cargo test), then the Python package built as a
# wheel into a fresh virtual environment and its pytest tests (crates/py/tests), which compare
# the module's results with the built `stiction` binary's --json.
#
# Needs python3 (>= 3.9, with venv) and network access to PyPI for maturin, pytest, numpy and the
# optional companions the tests exercise: pandas (study samples as a DataFrame), mypy (its
# stubtest checks the type stubs against the module), and nbclient,
# nbformat, ipykernel and matplotlib, which execute docs/notebooks/paper-experiment.ipynb.
# The wheel is built by maturin in this workspace's target/ folder, so it reuses the Rust build.
set -euo pipefail
cd "$(dirname "$0")/.."

# Everything the tests print also goes to a log, from which the last line counts the tests.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
log=$tmp/test.log

# No module of any crate imports, through others, a module that imports it (issue: no import
# circles): the script lists each cycle and fails when there is one.
python3 scripts/module-cycles.py

cargo test --workspace --release 2>&1 | tee "$log"

venv=$tmp/venv
python3 -m venv "$venv"
"$venv/bin/pip" install -q --upgrade pip
"$venv/bin/pip" install -q maturin pytest numpy pandas nbclient nbformat ipykernel matplotlib mypy
# The binding with clippy (it is behind the `python` feature, so the workspace lint skips it).
cargo clippy -p stiction-py --all-targets --release --features python -- -D warnings
# The wheel (abi3: one wheel for CPython >= 3.9), installed as a user would install it.
"$venv/bin/maturin" build --release -q -m crates/py/Cargo.toml --out "$tmp/wheels"
"$venv/bin/pip" install -q --no-deps "$tmp"/wheels/stiction-*.whl
cargo build --release -q -p stiction-cli
# The atlas of published experiments (docs/published.md): every row recomputed, none changed.
python3 scripts/published-atlas.py --check
"$venv/bin/python" -m pytest -q -p no:cacheprovider crates/py/tests 2>&1 | tee -a "$log"

# One closing line over every test binary (cargo's own last line is often a doc-test run of 0) and
# pytest's summary ("15 passed in 0.6s", "1 failed, 14 passed ..."); no test run at all, or none
# from Python, is a failure too.
awk '/^test result:/ { p += $4; f += $6; i += $8 }
     /^[0-9]+ (passed|failed).* in [0-9.]+s/ { for (k = 1; k < NF; k++) { if ($(k+1) ~ /^passed/) yp += $k; if ($(k+1) ~ /^failed/) yf += $k; if ($(k+1) ~ /^skipped/) ys += $k } }
     END { p += yp; f += yf; i += ys; printf "tests: %d passed, %d failed, %d skipped (python: %d passed)\n", p, f, i, yp; if (p == 0 || f > 0 || yp == 0) exit 1 }' "$log"
