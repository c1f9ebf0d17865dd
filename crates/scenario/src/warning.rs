//! A note about a scenario or a result that the user must see.

use serde::Serialize;

/// A note about a scenario or a result that the user must see: a stable `code` and a sentence.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Warning {
    /// Stable identifier, such as `few_points` or `reference_dropped`.
    pub code: String,
    /// What happened, why it matters and what to do.
    pub message: String,
}

impl Warning {
    /// A warning with this code and message.
    pub fn new(code: &str, message: impl Into<String>) -> Warning {
        Warning { code: code.to_string(), message: message.into() }
    }
}
