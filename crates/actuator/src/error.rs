//! Errors of the actuator crate.

use thiserror::Error;

/// Everything that can go wrong when building or solving an actuator model.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ActuatorError {
    /// A model or specification field has a value outside its physical range.
    #[error("invalid `{field}` = {value}: expected {expected}")]
    InvalidField {
        /// The field name as written in the scenario file (dotted path where nested).
        field: String,
        /// The offending value (SI units).
        value: f64,
        /// What the field must satisfy.
        expected: String,
    },
    /// Two or more fields that are each valid are inconsistent with each other.
    #[error("inconsistent specification: {0}")]
    Inconsistent(String),
    /// A quantity was requested that the model cannot give (e.g. release without a stop).
    #[error("not available: {0}")]
    NotAvailable(String),
    /// A numerical solver failed to converge.
    #[error("solver failed: {0}")]
    Solver(String),
    /// A measured-data file could not be read or parsed.
    #[error("{path}: line {line}: {message}")]
    Data {
        /// File path (or `<input>`).
        path: String,
        /// 1-based line number (0 when the whole file is concerned).
        line: usize,
        /// What is wrong.
        message: String,
    },
}

/// Checks `value > 0` and finite, naming the field otherwise.
pub(crate) fn positive(field: &str, value: f64) -> Result<f64, ActuatorError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ActuatorError::InvalidField { field: field.to_string(), value, expected: "a finite value > 0".to_string() })
    }
}

/// Checks `value >= 0` and finite, naming the field otherwise.
pub(crate) fn nonnegative(field: &str, value: f64) -> Result<f64, ActuatorError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(ActuatorError::InvalidField {
            field: field.to_string(),
            value,
            expected: "a finite value >= 0".to_string(),
        })
    }
}
