//! Why a scenario cannot be loaded.

use std::path::PathBuf;

/// Why `material.relative_humidity` is refused (in a file and with `--set` alike).
pub const RELATIVE_HUMIDITY_MESSAGE: &str = "the humidity belongs to the air, not the material: give it as \
     `environment.relative_humidity` (like 0.35 or \"35 %\"; with `--set environment.relative_humidity=0.35`), and \
     the water contact angle as `material.contact_angle` (default 0 deg)";

/// A scenario loading error: where (file and JSON path), what was given and what was expected.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read (missing, not a regular file, too large, not UTF-8).
    #[error("cannot read scenario {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        source: stiction_units::io::FileError,
    },
    /// The file is not JSON.
    #[error("{path}: not valid JSON at line {line}, column {column}: {message}")]
    Syntax {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// Parser message.
        message: String,
    },
    /// A field has a wrong value, type or name.
    #[error("{path}: at `{json_path}`: {message}")]
    Field {
        /// The file.
        path: PathBuf,
        /// The JSON path of the offending field, such as `surface.summit_sd`.
        json_path: String,
        /// What is wrong and what was expected.
        message: String,
    },
    /// A `--set PATH=VALUE` override is malformed or names no field.
    #[error("--set {set}: {message}")]
    Set {
        /// The override as given.
        set: String,
        /// What is wrong, with the near names where the path is wrong.
        message: String,
    },
}
