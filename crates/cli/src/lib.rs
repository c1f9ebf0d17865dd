//! The library half of the `stiction` command: each subcommand's flags, their conversion into the
//! engine's request (`stiction_engine`), the text tables, figures and output folders. The
//! commands themselves (requests, orchestration, results) are the engine's, which other front
//! ends (the Python module, crates/py) call directly.

// The subcommands, their shared flags and the output layer: the binary's own modules, public so
// that the binary (src/main.rs) reaches them; not a stable interface.
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
