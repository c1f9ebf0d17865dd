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
