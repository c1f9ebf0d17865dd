//! stiction in Python: the `stiction._stiction` extension module (PyO3, abi3 for CPython >= 3.9).
//!
//! The binding is thin: every result is composed by the same library code as the command line's
//! `--json` ([`stiction_cli::api`]) and handed to Python as that JSON text (`json.loads` of it is
//! bit for bit what a script reads from `stiction ... --json`), plus NumPy arrays for per-point
//! columns. The Python package (python/stiction/__init__.py) wraps the results in objects.
//!
//! Everything Python is behind the `python` feature (turned on by maturin), so that the
//! workspace builds, tests and lints without a Python installation.

#[cfg(feature = "python")]
mod binding;
#[cfg(feature = "python")]
mod read_map;
