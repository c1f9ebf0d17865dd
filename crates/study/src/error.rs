//! Why a study failed.

/// Why a study failed.
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    /// An uncertain parameter could not be drawn.
    #[error("at `{path}`: {message}")]
    Sample {
        /// JSON path of the parameter.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// The scenario file could not be read or parsed.
    #[error(transparent)]
    Scenario(#[from] stiction_scenario::ScenarioError),
    /// A study setting is wrong.
    #[error("{0}")]
    Setting(String),
    /// The sample log or an output file.
    #[error("{0}")]
    Log(String),
}
