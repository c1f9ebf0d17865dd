//! The outcome of one sample of a study.

use serde::Serialize;

/// The outcome of one sample.
#[derive(Debug, Clone, Serialize)]
pub struct SampleResult {
    /// Sample index.
    pub index: usize,
    /// The drawn parameters, SI (in the order of the study's columns).
    pub draws: Vec<f64>,
    /// mu_e,a of eq. 10.
    pub mu_apparent: Option<f64>,
    /// F_a0 of eq. 10, N.
    pub apparent_adhesion_force_n: Option<f64>,
    /// Mean number of contacts over the clamp voltages in contact.
    pub mean_contacts: Option<f64>,
    /// The interface's own friction coefficient of this sample's device ([`interface_mu`](crate::interface_mu)):
    /// the mean of `s A_r / (L + F_adh)` over its clamp voltages in contact with L > 0.
    pub interface_mu: Option<f64>,
    /// The widths of the 95 % intervals the lab would quote for this experiment's eq. 10 fit.
    pub intervals: FitIntervals,
    /// Why there is no fit (a short code; see [`summary::REASONS`](crate::summary::REASONS)), None when there is one.
    pub reason: Option<String>,
    /// The reason in words (the error message, or what the fit lacked).
    pub detail: Option<String>,
}

/// The widths (upper minus lower end) of the 95 % intervals a lab would quote for one virtual
/// experiment's eq. 10 fit: from the regression alone, and from the regression with the
/// calibration's stated uncertainty (a_clamp, a_pull, F_spring); None where the fit gives none.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct FitIntervals {
    /// Width of the 95 % interval of mu_e,a, regression alone.
    pub mu_ci95_width: Option<f64>,
    /// Width of the 95 % interval of mu_e,a with the calibration uncertainty.
    pub mu_ci95_width_with_calibration: Option<f64>,
    /// Width of the 95 % interval of F_a0, regression alone, N.
    pub fa0_ci95_width_n: Option<f64>,
    /// Width of the 95 % interval of F_a0 with the calibration uncertainty, N.
    pub fa0_ci95_width_with_calibration_n: Option<f64>,
}
