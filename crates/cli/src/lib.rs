//! The library half of the `stiction` command: the subcommands' composition of results, shared by
//! the `stiction` binary (which parses arguments and prints) and the Python module (crates/py).
//!
//! [`api`] is the stable surface for other front ends: each function returns the same JSON value
//! that the matching subcommand prints with `--json`.

pub mod api;
// The subcommands, their shared flags and the output layer: the binary's own modules, public so
// that the binary (src/main.rs) and `api` reach them; not a stable interface.
#[allow(missing_docs)]
#[doc(hidden)]
pub mod charts;
#[allow(missing_docs)]
#[doc(hidden)]
pub mod cmd;
#[allow(missing_docs)]
#[doc(hidden)]
pub mod figargs;
#[allow(missing_docs)]
#[doc(hidden)]
pub mod format;
#[allow(missing_docs)]
#[doc(hidden)]
pub mod output;
