//! Why a chart could not be written ([`PlotError`]).

/// Why a chart could not be written.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// No finite point to draw.
    #[error("chart {title:?} has no finite point to draw (on a log axis, values must be positive)")]
    Empty {
        /// The chart title.
        title: String,
    },
    /// The output file's extension names no format.
    #[error("cannot write {path}: unknown figure format {extension:?}, expected .svg or .png")]
    UnknownFormat {
        /// Output path.
        path: String,
        /// The extension given.
        extension: String,
    },
    /// A size or font option is out of range.
    #[error("figure {what} {value} is out of range: expected {expected}")]
    Option {
        /// Which option.
        what: &'static str,
        /// The value given.
        value: f64,
        /// What is accepted.
        expected: &'static str,
    },
    /// The drawing backend failed (font missing).
    #[error("could not draw {path}: {message}")]
    Backend {
        /// Output path.
        path: String,
        /// Backend message.
        message: String,
    },
    /// The file could not be written.
    #[error(transparent)]
    File(#[from] stiction_units::io::FileError),
}
