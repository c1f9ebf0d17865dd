//! The actuator arrays of the friction meter (paper section 5): the clamp array presses the shoe
//! against the wall, the pull array drags it along.

use serde::{Deserialize, Serialize};

use crate::actuator::GapClosingActuator;
use crate::error::{ActuatorError, nonnegative};

/// Clamp state at one clamp voltage.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ClampForce {
    /// Whether the shoe touches the wall.
    pub in_contact: bool,
    /// Lowest voltage that brings the shoe into contact (V): the equilibrium voltage at the
    /// contact travel, or the pull-in voltage if contact lies beyond the pull-in travel.
    pub contact_voltage_v: f64,
    /// Electrostatic force at the contact travel `F_elec = a(x_c) V^2` (N).
    pub electrostatic_force_n: f64,
    /// Spring force at the contact travel `F_spring = k x_c` (N), suspension plus the pull
    /// connection beam (parallel stiffness).
    pub spring_force_n: f64,
    /// Clamp force on the shoe `L = F_elec - F_spring` (N), 0 when not in contact.
    pub clamp_force_n: f64,
}

/// Clamp force on the shoe once in contact (paper section 5): `L = F_elec - F_spring`, with
/// `F_spring = (k_suspension + k_pull_beam) x_c` (7 +/- 2 uN in the paper) and `x_c` (m) the
/// travel at which the shoe meets the wall.
pub fn clamp_force(
    clamp: &GapClosingActuator,
    contact_travel_m: f64,
    voltage_v: f64,
) -> Result<ClampForce, ActuatorError> {
    nonnegative("contact_travel", contact_travel_m)?;
    nonnegative("clamp_voltage", voltage_v)?;
    if contact_travel_m >= clamp.plates.front_gap_m {
        return Err(ActuatorError::InvalidField {
            field: "contact_travel".into(),
            value: contact_travel_m,
            expected: format!("less than the front gap {:e} m", clamp.plates.front_gap_m),
        });
    }
    let p = clamp.pull_in()?;
    let contact_voltage_v =
        if contact_travel_m <= p.travel_m { clamp.equilibrium_voltage_v(contact_travel_m) } else { p.voltage_v };
    let fe = clamp.electrostatic_force_n(contact_travel_m, voltage_v);
    let fs = clamp.suspension.force_n(contact_travel_m);
    let in_contact = voltage_v >= contact_voltage_v;
    Ok(ClampForce {
        in_contact,
        contact_voltage_v,
        electrostatic_force_n: fe,
        spring_force_n: fs,
        clamp_force_n: if in_contact { (fe - fs).max(0.0) } else { 0.0 },
    })
}

/// Pull force on the shoe while it sticks (N): the pull array cannot move, so its gap stays at
/// the initial value and the spring is undeflected: `F_pull = a_pull V^2`, `a_pull = f(0)`.
pub fn pull_force_stuck_n(pull: &GapClosingActuator, voltage_v: f64) -> Result<f64, ActuatorError> {
    nonnegative("pull_voltage", voltage_v)?;
    Ok(pull.electrostatic_force_n(0.0, voltage_v))
}

/// What the pull array does once the shoe slips.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "outcome", rename_all = "snake_case")]
pub enum SlipResponse {
    /// A stable equilibrium exists: the array moves to `travel_m` and stops there.
    Settles {
        /// Travel (m).
        travel_m: f64,
    },
    /// No equilibrium before the stop (or gap): the array runs away (pull-in) to its stop.
    RunsAway {
        /// Stop travel (m), `None` if the plates close the gap.
        stop_travel_m: Option<f64>,
    },
}

/// Response of the pull array at voltage `V` once the shoe slips and only a constant resisting
/// force `R` (N, e.g. kinetic friction; 0 for none) holds it back: the first travel where
/// `F_e(x, V) = k x + R` with the net force turning from driving to restoring, or a runaway when
/// none exists before the stop. With `R = 0` it runs away exactly when `V > V_pi`.
pub fn slip_response(
    pull: &GapClosingActuator,
    voltage_v: f64,
    resisting_force_n: f64,
) -> Result<SlipResponse, ActuatorError> {
    nonnegative("pull_voltage", voltage_v)?;
    nonnegative("resisting_force", resisting_force_n)?;
    let limit = pull.stop_travel_m.unwrap_or(pull.plates.front_gap_m * (1.0 - 1e-9));
    let net = |x: f64| pull.electrostatic_force_n(x, voltage_v) - pull.suspension.force_n(x) - resisting_force_n;
    if net(0.0) <= 0.0 {
        return Ok(SlipResponse::Settles { travel_m: 0.0 });
    }
    const N: usize = 2000;
    let mut prev = 0.0;
    for i in 1..=N {
        let x = limit * i as f64 / N as f64;
        if net(x) <= 0.0 {
            let (mut a, mut b) = (prev, x);
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if m <= a || m >= b {
                    break;
                }
                if net(m) > 0.0 { a = m } else { b = m }
            }
            return Ok(SlipResponse::Settles { travel_m: 0.5 * (a + b) });
        }
        prev = x;
    }
    Ok(SlipResponse::RunsAway { stop_travel_m: pull.stop_travel_m })
}
