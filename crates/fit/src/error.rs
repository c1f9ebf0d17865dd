//! Why a fit cannot be made.

use stiction_meter::measured::VoltageCsvError;

/// Why a fit cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum FitError {
    /// The data file cannot be read.
    #[error(transparent)]
    File(#[from] stiction_units::io::FileError),
    /// The data file cannot be read or is wrong at a line (and column): the reader of
    /// `stiction_meter::measured`, shared with `stiction run`.
    #[error(transparent)]
    Data(#[from] VoltageCsvError),
    /// Too few usable rows.
    #[error("{0}")]
    TooFewRows(String),
    /// A setting or the scenario is wrong.
    #[error("{0}")]
    Setting(String),
    /// The meter or contact model could not be built.
    #[error(transparent)]
    Meter(#[from] stiction_meter::MeterError),
    /// A model could not be fitted.
    #[error("model `{model}`: {message}")]
    Model {
        /// Model name.
        model: String,
        /// What went wrong.
        message: String,
    },
}
