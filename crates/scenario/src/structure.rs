//! The `structure` section: a friction test structure other than the paper's gap-closing meter,
//! built from parts (docs/experiment.md, "Other test structures").
//!
//! * `normal`: what presses the contact: a lateral comb drive pushing a shoe across
//!   `contact_travel` to a sidewall (`L = a V^2 - k_x x_c`), or a plate electrode pulling a plate
//!   or pad onto the substrate (`L = eps0 A V^2 / (2 (g_c + sum t_i/eps_r,i)^2) - k_z g0`; a pad
//!   whose electrode covers it sees the uniform pressure `L / A`);
//! * `tangential`: what loads it sideways: a lateral comb drive (`F = a V^2` while stuck) or a
//!   spring set to a displacement and released (`F = k x`);
//! * `geometry`: the sidewall shoe or a pad of the surface's apparent area (the surface section's
//!   summits, every contact model), or a few dimples (the discrete model's N spheres);
//! * `protocol`: a tangential ramp at fixed normal load, a release from a displacement, or a
//!   normal load lowered at a fixed tangential load;
//! * `lab_reduction`: how the laboratory turned forces into its friction coefficient.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use stiction_actuator::{LateralCombSpec, PlateElectrodeSpec, ReleasedSpringSpec};
use stiction_units::QuantityInput;

pub use crate::lab_reduction::LabReductionSpec;
use crate::spec::{SlipCriterion, VoltageSchedule};

/// A lateral comb drive that pushes a shoe across `contact_travel` onto a sidewall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct NormalCombSpec {
    /// The comb.
    pub comb: LateralCombSpec,
    /// Travel of the comb from rest to the sidewall `x_c` (its spring then holds back `k_x x_c`).
    #[serde(deserialize_with = "stiction_units::de::length_nonnegative")]
    #[schemars(with = "QuantityInput")]
    pub contact_travel: f64,
}

/// What presses the contact.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum NormalActuatorSpec {
    /// A lateral comb drive pressing a shoe onto a sidewall.
    LateralComb(NormalCombSpec),
    /// A plate electrode under the plate or pad.
    PlateElectrode(PlateElectrodeSpec),
}

/// What loads the contact sideways.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum TangentialActuatorSpec {
    /// A lateral comb drive, `F = a V^2` while the contact sticks.
    LateralComb(LateralCombSpec),
    /// A suspension set to a displacement and released, `F = k x`.
    ReleasedSpring(ReleasedSpringSpec),
}

/// The contact's geometry.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum GeometrySpec {
    /// A shoe on a vertical sidewall of the surface's apparent area (the paper's contact).
    SidewallShoe,
    /// A horizontal plate or pad lying on the substrate over the surface's apparent area.
    Pad,
    /// A few dimples under the structure, each a sphere of radius `radius` carrying an equal share
    /// of the load (the discrete model with N = `count`; `contact.model` must be "discrete").
    Dimples {
        /// Number of dimples N: 1, 2 or 3 (equal shares hold by statics only up to three).
        count: u32,
        /// Dimple tip radius.
        #[serde(deserialize_with = "stiction_units::de::length_positive")]
        #[schemars(with = "QuantityInput")]
        radius: f64,
    },
}

fn default_ramp_step() -> f64 {
    0.05
}
fn default_ramp_max() -> f64 {
    200.0
}

/// The measurement protocol.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum ProtocolSpec {
    /// At each normal voltage, ramp the tangential comb's voltage in steps until slip.
    Ramp {
        /// Step of the tangential voltage (default 0.05 V).
        #[serde(default = "default_ramp_step", deserialize_with = "stiction_units::de::voltage_positive")]
        #[schemars(with = "QuantityInput")]
        voltage_step: f64,
        /// Highest tangential voltage tried (default 200 V).
        #[serde(default = "default_ramp_max", deserialize_with = "stiction_units::de::voltage_positive")]
        #[schemars(with = "QuantityInput")]
        voltage_max: f64,
    },
    /// At each normal voltage, set the released spring to displacements `n * displacement_step`
    /// (n = 1, 2, ...) up to `displacement_max`, release, and find the largest that sticks.
    Release {
        /// Displacement step.
        #[serde(deserialize_with = "stiction_units::de::length_positive")]
        #[schemars(with = "QuantityInput")]
        displacement_step: f64,
        /// Largest displacement tried.
        #[serde(deserialize_with = "stiction_units::de::length_positive")]
        #[schemars(with = "QuantityInput")]
        displacement_max: f64,
    },
    /// At each tangential comb voltage, lower the normal voltage through `normal_voltages` (from
    /// the highest) until the contact slips.
    LowerNormal {
        /// The tangential comb's voltages, one point each.
        tangential_voltages: VoltageSchedule,
    },
}

/// A friction test structure built from parts (instead of the paper's `actuators` + `meter`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StructureSpec {
    /// What the structure is (printed).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
    /// What presses the contact.
    pub normal: NormalActuatorSpec,
    /// The normal actuator's voltages, one point each (ramp and release protocols), or the values
    /// the normal voltage is lowered through (lower-normal protocol).
    pub normal_voltages: VoltageSchedule,
    /// What loads the contact sideways.
    pub tangential: TangentialActuatorSpec,
    /// The contact's geometry.
    pub geometry: GeometrySpec,
    /// The measurement protocol.
    pub protocol: ProtocolSpec,
    /// Slip criterion (default shear strength times real area).
    #[serde(default)]
    pub slip: SlipCriterion,
    /// How the laboratory reduced its forces (default eq. 10).
    #[serde(default)]
    pub lab_reduction: LabReductionSpec,
}

/// Largest number of protocol steps (displacements of a release, or normal voltages) per point.
pub const MAX_PROTOCOL_STEPS: f64 = 1e7;

impl StructureSpec {
    /// Cross-field checks: the protocol fits the tangential actuator, each part builds, the step
    /// counts are bounded. Returns (path inside `structure`, message).
    pub(crate) fn validate(&self) -> Result<(), (String, String)> {
        match &self.normal {
            NormalActuatorSpec::LateralComb(c) => {
                let comb = c.comb.to_model().map_err(|e| ("normal".to_string(), e.to_string()))?;
                // At and above its side pull-in voltage the comb's fingers snap sideways: no load
                // a_n V^2 - F_0 is applied there, so such a voltage is no point of the experiment.
                if let Some(v_side) = comb.side_pull_in_voltage_at_v(c.contact_travel) {
                    let top = self.normal_voltages.voltages().into_iter().fold(f64::NEG_INFINITY, f64::max);
                    if top >= v_side {
                        return Err((
                            "normal_voltages".into(),
                            format!(
                                "{top} V reaches the normal comb's side pull-in voltage at the wall, {v_side:.3} V \
                                 (from structure.normal.comb.lateral_stiffness and its fingers): its fingers snap \
                                 sideways there and no load a_n V^2 - F_0 is applied; keep the normal voltages below \
                                 it (or stiffen the suspension laterally)"
                            ),
                        ));
                    }
                }
            }
            NormalActuatorSpec::PlateElectrode(p) => {
                p.to_model().map_err(|e| ("normal".to_string(), e.to_string()))?;
            }
        }
        match &self.tangential {
            TangentialActuatorSpec::LateralComb(c) => {
                c.to_model().map_err(|e| ("tangential".to_string(), e.to_string()))?;
            }
            TangentialActuatorSpec::ReleasedSpring(s) => {
                s.to_model().map_err(|e| ("tangential".to_string(), e.to_string()))?;
            }
        }
        let spring = matches!(self.tangential, TangentialActuatorSpec::ReleasedSpring(_));
        match &self.protocol {
            ProtocolSpec::Ramp { voltage_step, voltage_max } => {
                if spring {
                    return Err((
                        "protocol.kind".into(),
                        "\"ramp\" ramps a tangential comb's voltage; a released spring is measured with \"release\""
                            .into(),
                    ));
                }
                if voltage_step >= voltage_max || voltage_max / voltage_step > MAX_PROTOCOL_STEPS {
                    return Err((
                        "protocol.voltage_step".into(),
                        format!(
                            "{voltage_step} V against voltage_max {voltage_max} V: expected a step below the maximum \
                             and at most {MAX_PROTOCOL_STEPS:e} steps"
                        ),
                    ));
                }
            }
            ProtocolSpec::Release { displacement_step, displacement_max } => {
                if !spring {
                    return Err((
                        "protocol.kind".into(),
                        "\"release\" sets and releases a spring: the tangential part must be a \"released_spring\""
                            .into(),
                    ));
                }
                if displacement_step >= displacement_max || displacement_max / displacement_step > MAX_PROTOCOL_STEPS {
                    return Err((
                        "protocol.displacement_step".into(),
                        format!(
                            "{displacement_step} m against displacement_max {displacement_max} m: expected a step \
                             below the maximum and at most {MAX_PROTOCOL_STEPS:e} steps"
                        ),
                    ));
                }
            }
            ProtocolSpec::LowerNormal { tangential_voltages } => {
                if spring {
                    return Err((
                        "protocol.kind".into(),
                        "\"lower_normal\" holds a tangential comb's voltage; a released spring is measured with \
                         \"release\""
                            .into(),
                    ));
                }
                if tangential_voltages.voltages().len() as f64 > MAX_PROTOCOL_STEPS {
                    return Err(("protocol.tangential_voltages".into(), "too many voltages".into()));
                }
            }
        }
        if self.normal_voltages.voltages().len() as f64 > MAX_PROTOCOL_STEPS {
            return Err(("normal_voltages".into(), format!("more than {MAX_PROTOCOL_STEPS:e} voltages")));
        }
        if let GeometrySpec::Dimples { count, .. } = self.geometry
            && !(1..=3).contains(&count)
        {
            return Err((
                "geometry.count".into(),
                format!(
                    "{count} dimples: expected 1, 2 or 3 (a rigid structure shares its load equally only among up to \
                     three dimples, by statics; with more the shares depend on the dimples' heights)"
                ),
            ));
        }
        Ok(())
    }
}
