//! Errors of the topography crate.

use stiction_units::io::FileError;

/// Everything that can go wrong reading, preparing, analysing or generating a height map.
#[derive(Debug, thiserror::Error)]
pub enum TopographyError {
    /// The file could not be used (missing, not a regular file, too large, unreadable).
    #[error(transparent)]
    File(#[from] FileError),
    /// The file's content is malformed; `origin` names the file and `line` the text line (0 if none).
    #[error("{origin}{}: {message}", line_suffix(*.line))]
    Format {
        /// The file (or "<bytes>").
        origin: String,
        /// 1-based text line, 0 when not a text position.
        line: u64,
        /// What is wrong and what was expected.
        message: String,
    },
    /// The file lacks metadata that no flag or scenario field supplied.
    #[error("{origin}: missing metadata: {missing}")]
    MissingMetadata {
        /// The file.
        origin: String,
        /// What is missing and how to give it.
        missing: String,
    },
    /// A parameter is out of range.
    #[error("invalid `{field}` = {value}: expected {expected}")]
    InvalidParameter {
        /// The field or flag name.
        field: String,
        /// The offending value.
        value: String,
        /// What was expected.
        expected: String,
    },
    /// The grid is larger than the stated limit (checked before allocating).
    #[error("{origin}: a {nx} x {ny} grid is larger than the limit of {limit} pixels")]
    TooLarge {
        /// The file or generator.
        origin: String,
        /// Columns.
        nx: u64,
        /// Rows.
        ny: u64,
        /// The limit, pixels.
        limit: u64,
    },
}

fn line_suffix(line: u64) -> String {
    if line == 0 { String::new() } else { format!(", line {line}") }
}

impl TopographyError {
    pub(crate) fn format(origin: &str, line: u64, message: impl Into<String>) -> Self {
        TopographyError::Format { origin: origin.to_string(), line, message: message.into() }
    }

    pub(crate) fn invalid(field: &str, value: impl ToString, expected: impl Into<String>) -> Self {
        TopographyError::InvalidParameter { field: field.into(), value: value.to_string(), expected: expected.into() }
    }
}

/// Checks a finite, strictly positive parameter.
pub(crate) fn check_positive(field: &str, value: f64, unit: &str) -> Result<(), TopographyError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(TopographyError::invalid(field, format!("{value:e}"), format!("a finite value > 0 {unit}")))
    }
}
