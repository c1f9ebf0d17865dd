//! Why the meter cannot run.

/// Why the meter cannot run.
#[derive(Debug, thiserror::Error)]
pub enum MeterError {
    /// The scenario lacks something the meter needs.
    #[error("scenario: {0}")]
    Scenario(String),
    /// An actuator could not be built or solved.
    #[error("actuator `{array}`: {message}")]
    Actuator {
        /// `clamp` or `pull`.
        array: String,
        /// The actuator crate's message.
        message: String,
    },
    /// The surface could not be built.
    #[error("surface: {0}")]
    Surface(String),
    /// The contact model failed.
    #[error("contact: {0}")]
    Contact(String),
    /// A measured-data file is wrong.
    #[error("measured data: {0}")]
    Measured(String),
    /// A result broke a physical invariant (a real area above the apparent one, more contacts
    /// than summits): the inputs lie outside what the model describes; never printed as a number.
    #[error("{0}")]
    Invariant(String),
}
