//! Errors of the analytic contact models.

use thiserror::Error;

/// Errors of the analytic contact models ([`crate::single`], [`crate::gw`], [`crate::limits`],
/// [`crate::discrete`]).
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ContactError {
    /// A parameter is out of its physical range (negative radius, NaN, infinite compliance...).
    #[error("invalid parameter `{field}` = {value}: expected {expected}")]
    InvalidParameter {
        /// Name of the parameter (the struct field or function argument).
        field: &'static str,
        /// The value that was given (SI units).
        value: f64,
        /// What was expected, e.g. "a finite number > 0 (m)".
        expected: &'static str,
    },
    /// The requested load is below the pull-off (minimum) load: there is no equilibrium.
    #[error("no equilibrium: {quantity} = {value:e} is below the pull-off value {pull_off}")]
    NoEquilibrium {
        /// The load quantity, e.g. "load_n" or "l_star".
        quantity: &'static str,
        /// The requested value.
        value: f64,
        /// The pull-off (minimum) value, formatted (it may be far below f64 range, then given as log10).
        pull_off: String,
    },
    /// A Greenwood-Williamson solve failed for this adhesion parameter and load (named, with the reason).
    #[error("GW solve for theta = {theta}, L* = {l_star}: {reason}")]
    GwSolve {
        /// The adhesion parameter theta (eq. 9), formatted ("inf" without adhesion).
        theta: String,
        /// The normalised load L* (eq. 5c, 8), formatted ("pull-off" or "zero load" for those solves).
        l_star: String,
        /// Why it failed.
        reason: String,
    },
    /// An iterative solver did not converge (never expected for valid input; reported, never hidden).
    #[error("{what} did not converge after {iterations} iterations")]
    NoConvergence {
        /// Which solve.
        what: &'static str,
        /// Iterations spent.
        iterations: usize,
    },
}

/// Check that `value` is finite and > 0.
pub(crate) fn check_positive(field: &'static str, value: f64, expected: &'static str) -> Result<f64, ContactError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ContactError::InvalidParameter { field, value, expected })
    }
}

/// Check that `value` is finite and >= 0.
pub(crate) fn check_nonnegative(field: &'static str, value: f64, expected: &'static str) -> Result<f64, ContactError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(ContactError::InvalidParameter { field, value, expected })
    }
}

/// Check that `value` is finite.
pub(crate) fn check_finite(field: &'static str, value: f64, expected: &'static str) -> Result<f64, ContactError> {
    if value.is_finite() { Ok(value) } else { Err(ContactError::InvalidParameter { field, value, expected }) }
}
