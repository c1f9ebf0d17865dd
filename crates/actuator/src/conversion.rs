//! Conversion factors `a = F/V^2` (paper section 5) and the gaps they imply.

use crate::error::{ActuatorError, positive};

/// Defined with the plate array it inverts ([`crate::plates`]), which the spec calls without this module.
pub use crate::plates::infer_front_gap_m;

/// A conversion factor calibrated on the device itself.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct PullInCalibration {
    /// The as-built front gap that makes the spec's model pull in at the measured voltage, m.
    pub front_gap_m: f64,
    /// The conversion factor a = F / V^2 at the spec's `operating_travel` with that gap, N/V^2.
    pub conversion_factor_n_per_v2: f64,
}

/// Calibrates an array from its measured pull-in voltage: the lab keeps its model of the array
/// (plate count, overlap, thickness, fringing, spring, stop: everything in `spec`) but not the gap,
/// which the etch sets least precisely; it finds the as-built front gap g for which the model's
/// pull-in voltage equals `measured_pull_in_v` (V_pi grows monotonically with g, as g^(3/2) for
/// parallel plates), and returns the conversion factor at `operating_travel` with that gap.
pub fn calibrate_from_pull_in(
    spec: &crate::spec::ArraySpec,
    measured_pull_in_v: f64,
) -> Result<PullInCalibration, ActuatorError> {
    positive("measured_pull_in_voltage", measured_pull_in_v)?;
    let u = spec.undercut;
    let nominal_gap = spec.plates()?.front_gap_m;
    let floor = spec.stop_travel_m()?.unwrap_or(0.0).max(spec.operating_travel);
    let model_at = |gap: f64| -> Result<crate::actuator::GapClosingActuator, ActuatorError> {
        let mut s = spec.clone();
        s.front_gap = Some(gap - 2.0 * u);
        s.conversion_factor = None;
        s.calibrated_on = None;
        s.to_model()
    };
    let v_at = |gap: f64| -> Result<f64, ActuatorError> { Ok(model_at(gap)?.pull_in()?.voltage_v) };
    let mut lo = floor * (1.0 + 1e-6) + 1e-12;
    let mut hi = nominal_gap.max(lo) * 2.0;
    let v_lo = v_at(lo)?;
    let mut v_hi = v_at(hi)?;
    // Widen the bracket (up to 64 x the nominal gap) until it holds the measured voltage.
    while v_hi < measured_pull_in_v && hi < 64.0 * nominal_gap.max(lo) {
        hi *= 2.0;
        v_hi = v_at(hi)?;
    }
    if !(v_lo <= measured_pull_in_v && measured_pull_in_v <= v_hi) {
        return Err(ActuatorError::Solver(format!(
            "no front gap between {lo:e} m and {hi:e} m gives a pull-in voltage of {measured_pull_in_v} V \
             (the model spans {v_lo:.4} V to {v_hi:.4} V)"
        )));
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if v_at(mid)? < measured_pull_in_v {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let gap = 0.5 * (lo + hi);
    Ok(PullInCalibration {
        front_gap_m: gap,
        conversion_factor_n_per_v2: model_at(gap)?.conversion_factor_n_per_v2(spec.operating_travel),
    })
}
