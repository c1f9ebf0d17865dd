//! stiction in Python: the `stiction._stiction` extension module (PyO3, abi3 for CPython >= 3.9).
//!
//! The binding is thin: it builds each command's request of the engine (`stiction_engine`, the
//! same engine the command line calls) from keyword arguments and NumPy arrays, and hands the
//! result to Python as its JSON value (`json.loads` of `stiction ... --json` bit for bit), plus
//! NumPy arrays for per-point columns. The Python package (python/stiction/__init__.py) wraps the results in objects.
//!
//! Everything Python is behind the `python` feature (turned on by maturin), so that the
//! workspace builds, tests and lints without a Python installation.

#[cfg(feature = "python")]
mod binding;
#[cfg(feature = "python")]
mod module;
#[cfg(feature = "python")]
mod read_map;
#[cfg(feature = "python")]
mod requests;
