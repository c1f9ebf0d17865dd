//! Physical invariants of every contact state before it is used, printed or written.
//!
//! A contact model run outside its validity (a summit radius of metres, a work of adhesion far
//! beyond any solid's) can return numbers that no contact can have: a real area 95,070 times the
//! apparent area, more summits in contact than the surface holds. Such a result is an error that
//! names the inputs driving it ([`MeterError::Invariant`]), never a printed number. The bounds:
//!
//! * `0 <= A_r <= A_a` (the real area is part of the apparent one), with a relative slack of
//!   [`RELATIVE_SLACK`] for rounding;
//! * `0 <= contacts <= summits` (the summits the model holds);
//! * every force and pressure finite, the contacts' elastic load `L + L_adh >= 0` (they can only
//!   push), the adhesive load `>= 0`, and the capillary load within `[0, L_adh]` (the menisci
//!   are part of the adhesion);
//! * with the hardness cap, `0 <= A_p <= A_r` (the plastic area is part of the real one);
//! * a structure's friction reading within one protocol step of the contact's capacity
//!   ([`check_reading`]).

use crate::MeterError;
use crate::contact_model::ContactState;

/// Relative slack of the bounds, for rounding: 1e-9.
pub const RELATIVE_SLACK: f64 = 1e-9;

/// The inputs that set the real area, the contact count and the adhesive load of a state: named
/// in every invariant error.
pub const AREA_INPUTS: &str = "surface.summit_radius, surface.summit_density, surface.summit_sd, \
     material.compliance (or youngs_modulus), material.work_of_adhesion, environment.relative_humidity and the clamp \
     load (actuators.clamp, meter.clamp_voltages)";

fn broken(what: String, at: &str) -> MeterError {
    MeterError::Invariant(format!(
        "the contact model's result at {at} breaks a physical invariant: {what}; the inputs lie outside what the \
         model describes (check {AREA_INPUTS})"
    ))
}

/// Checks a contact state against the invariants of the module documentation; `apparent_area_m2`
/// is A_a, `summits` the number of summits the model holds, `v_clamp` (V) the clamp voltage the
/// error names.
pub fn check_state(state: &ContactState, apparent_area_m2: f64, summits: f64, v_clamp: f64) -> Result<(), MeterError> {
    let at = format!("V_clamp = {} V", stiction_scenario::domain::short(v_clamp));
    check_state_at(state, apparent_area_m2, summits, &at)
}

/// As [`check_state`], the error naming the point as `at` (e.g. "a load of 1e-6 N").
pub fn check_state_at(state: &ContactState, apparent_area_m2: f64, summits: f64, at: &str) -> Result<(), MeterError> {
    let short = stiction_scenario::domain::short;
    let values = [
        ("real area", state.real_area_m2),
        ("contacts", state.contacts),
        ("adhesive load", state.adhesive_load_n),
        ("capillary load", state.capillary_load_n),
        ("largest pressure", state.max_pressure_pa),
        ("tilt", state.tilt_x_rad),
        ("tilt", state.tilt_y_rad),
    ];
    if let Some((name, v)) = values.iter().find(|(_, v)| !v.is_finite()) {
        return Err(broken(format!("the {name} is {v}, not a finite number"), at));
    }
    if state.real_area_m2 < 0.0 || state.real_area_m2 > apparent_area_m2 * (1.0 + RELATIVE_SLACK) {
        return Err(broken(
            format!(
                "a real contact area of {} m^2 is {} times the apparent area {} m^2 (it must lie within it)",
                short(state.real_area_m2),
                short(state.real_area_m2 / apparent_area_m2),
                short(apparent_area_m2)
            ),
            at,
        ));
    }
    if state.contacts < 0.0 || state.contacts > summits * (1.0 + RELATIVE_SLACK) {
        return Err(broken(
            format!("{} summits in contact of the {} the surface holds", short(state.contacts), short(summits)),
            at,
        ));
    }
    let scale = state.load_n.abs().max(state.adhesive_load_n.abs()) * RELATIVE_SLACK;
    if state.adhesive_load_n < -scale || state.elastic_load_n() < -scale {
        return Err(broken(
            format!(
                "the contacts carry {} N at a load of {} N with an adhesive load of {} N (contacts only push, \
                 adhesion only pulls)",
                short(state.elastic_load_n()),
                short(state.load_n),
                short(state.adhesive_load_n)
            ),
            at,
        ));
    }
    if state.capillary_load_n < -scale || state.capillary_load_n > state.adhesive_load_n + scale {
        return Err(broken(
            format!(
                "a capillary load of {} N outside [0, the adhesive load {} N]",
                short(state.capillary_load_n),
                short(state.adhesive_load_n)
            ),
            at,
        ));
    }
    if let Some(a_p) = state.plastic_area_m2
        && !(a_p.is_finite() && a_p >= 0.0 && a_p <= state.real_area_m2 * (1.0 + RELATIVE_SLACK))
    {
        return Err(broken(
            format!(
                "a plastic area of {} m^2 outside [0, the real area {} m^2] (the points at the hardness are part \
                 of the contact)",
                short(a_p),
                short(state.real_area_m2)
            ),
            at,
        ));
    }
    if state.max_pressure_pa < 0.0 {
        return Err(broken(format!("a largest pressure of {} Pa", short(state.max_pressure_pa)), at));
    }
    Ok(())
}

/// A reported friction reading of a structure's protocol lies within one protocol step of the
/// contact's capacity: a ramp slips at the first step at or above it (`capacity <= F < capacity +
/// step_n`), a release sticks at the last step below it (`capacity - step_n <= F < capacity`);
/// `step_n` is the force of one step at that level (`a_t (V^2 - (V - dV)^2)`, `k dx`), N.
pub fn check_reading(friction_n: f64, capacity_n: f64, step_n: f64, v_normal: f64) -> Result<(), MeterError> {
    let slack = RELATIVE_SLACK * capacity_n.abs().max(friction_n.abs());
    if !(friction_n.is_finite() && (friction_n - capacity_n).abs() <= step_n + slack) {
        return Err(MeterError::Invariant(format!(
            "the friction reading {} N at the normal voltage {} V lies more than one protocol step ({} N) from \
             the contact's friction capacity {} N",
            stiction_scenario::domain::short(friction_n),
            stiction_scenario::domain::short(v_normal),
            stiction_scenario::domain::short(step_n),
            stiction_scenario::domain::short(capacity_n)
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state() -> ContactState {
        ContactState {
            load_n: 3e-6,
            real_area_m2: 1e-14,
            contacts: 3.0,
            adhesive_load_n: 2e-6,
            capillary_load_n: 0.5e-6,
            tilt_x_rad: 1e-4,
            tilt_y_rad: 0.0,
            max_pressure_pa: 5e9,
            plastic_area_m2: Some(0.4e-14),
        }
    }

    /// The paper's state passes; each broken bound is refused naming what broke it and the inputs.
    #[test]
    fn each_invariant_is_enforced() {
        let a_a = 20e-6 * 5e-6;
        assert!(check_state(&state(), a_a, 108.0, 20.0).is_ok());
        type Break = fn(&mut ContactState);
        let cases: [(&str, Break); 8] = [
            ("times the apparent area", |s| s.real_area_m2 = 9.5e-6),
            ("summits in contact", |s| s.contacts = 109.0),
            ("contacts only push", |s| s.adhesive_load_n = -1e-6),
            ("capillary load", |s| s.capillary_load_n = 3e-6),
            ("not a finite number", |s| s.max_pressure_pa = f64::NAN),
            ("largest pressure", |s| s.max_pressure_pa = -1.0),
            ("plastic area", |s| s.plastic_area_m2 = Some(1.1e-14)),
            ("plastic area", |s| s.plastic_area_m2 = Some(-1e-20)),
        ];
        for (needle, breaks) in cases {
            let mut s = state();
            breaks(&mut s);
            let e = check_state(&s, a_a, 108.0, 20.0).unwrap_err().to_string();
            assert!(e.contains(needle) && e.contains("surface.summit_radius") && e.contains("20 V"), "{needle}: {e}");
        }
        // Rounding at the bound is not a violation.
        let mut s = state();
        s.real_area_m2 = a_a * (1.0 + 1e-12);
        assert!(check_state(&s, a_a, 108.0, 20.0).is_ok());
    }
}
