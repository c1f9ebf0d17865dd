//! Conversion factors `a = F/V^2` (paper section 5) and the gaps they imply.

use crate::error::{ActuatorError, nonnegative, positive};
use crate::plates::PlateArray;

/// Front gap at zero travel (m) for which the plate array gives the conversion factor `a`
/// (N/V^2) at travel `x_op` (m): solves `f(x_op; g_f) = a` by bisection on `g_f` (`f` falls
/// monotonically with the gap). Parallel plate, no back electrode:
/// `g_f = x_op + sqrt(n eps l t / (2 a))`.
pub fn infer_front_gap_m(
    template: &PlateArray,
    operating_travel_m: f64,
    conversion_factor: f64,
) -> Result<f64, ActuatorError> {
    nonnegative("operating_travel", operating_travel_m)?;
    positive("conversion_factor", conversion_factor)?;
    let f_at = |gap: f64| {
        let mut p = *template;
        p.front_gap_m = gap;
        p.force_per_volt2(operating_travel_m)
    };
    // Parallel-plate estimate, then a bracket around it.
    let n = f64::from(template.plate_count);
    let pp = (n * template.permittivity() * template.overlap_length_m * template.thickness_m
        / (2.0 * conversion_factor))
        .sqrt();
    let mut lo = operating_travel_m + pp * 1e-3;
    let mut hi = operating_travel_m + pp * 10.0;
    if f_at(lo) < conversion_factor || f_at(hi) > conversion_factor {
        return Err(ActuatorError::Solver(format!(
            "no front gap in [{lo:e}, {hi:e}] m gives conversion_factor = {conversion_factor:e} N/V^2"
        )));
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f_at(mid) > conversion_factor {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}

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
