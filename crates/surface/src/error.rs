//! Errors of the surface crate.

/// Everything that can go wrong when building, generating or reading a surface.
#[derive(Debug, thiserror::Error)]
pub enum SurfaceError {
    /// A parameter is out of its valid range.
    #[error("invalid `{field}` = {value}: expected {expected}")]
    InvalidParameter {
        /// Field name as in the scenario file.
        field: String,
        /// The offending value.
        value: String,
        /// What was expected.
        expected: String,
    },
    /// A required field is missing or fields contradict each other.
    #[error("surface specification: {0}")]
    Spec(String),
    /// Arrays handed to [`crate::Surface::new`] are inconsistent.
    #[error("inconsistent summit arrays: {0}")]
    Inconsistent(String),
    /// A CSV stream could not be parsed.
    #[error("surface CSV, line {line}: {message}")]
    Csv {
        /// 1-based line number in the CSV text (the header is line 1).
        line: u64,
        /// What is wrong.
        message: String,
    },
    /// A CSV file could not be parsed.
    #[error("surface CSV file {path}, line {line}: {message}")]
    CsvFile {
        /// Path of the file.
        path: String,
        /// 1-based line number (the header is line 1).
        line: u64,
        /// What is wrong.
        message: String,
    },
    /// A `.npy` summit file is malformed or holds values that are not summits.
    #[error("summit file {path}: {message}")]
    Npy {
        /// Path of the file.
        path: String,
        /// What is wrong and what was expected.
        message: String,
    },
    /// A height map could not be read, prepared or cut.
    #[error("height map: {0}")]
    HeightMap(#[from] stiction_topography::TopographyError),
    /// A file could not be opened, read or written.
    #[error("{path}: {message}")]
    Io {
        /// Path of the file.
        path: String,
        /// The system's message.
        message: String,
    },
}

impl From<csv::Error> for SurfaceError {
    fn from(e: csv::Error) -> Self {
        let line = e.position().map_or(0, |p| p.line());
        SurfaceError::Csv { line, message: e.to_string() }
    }
}
