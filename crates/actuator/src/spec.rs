//! Scenario-file description of an actuator array ([`ArraySpec`]) and its conversion to a
//! [`GapClosingActuator`].
//!
//! Quantities accept a JSON number (SI), a string with a unit (`"4.83 um"`, `"169 GPa"`,
//! `"1.4e-8 N/V^2"`) or an uncertain-parameter object (nominal value taken), through
//! `stiction_units::de`.
//!
//! Drawn dimensions and the process undercut `u` (m per edge) are separate inputs. The undercut
//! is applied once, in [`ArraySpec::to_model`]:
//!
//! | dimension | as built |
//! |---|---|
//! | front gap, back gap | drawn + 2u |
//! | stop travel | drawn + 2u (the stop gap is a trench too) |
//! | plate overlap length | drawn - u (the tip recedes by u) |
//! | beam widths, finger width (bending), comb finger and electrode widths | drawn - 2u |
//! | thickness, beam length, given stiffness, substrate gap | unchanged |

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::actuator::GapClosingActuator;
use crate::bending::FingerBending;
use crate::cross_section::{CombGeometry, Substrate, SubstratePotential};
use crate::dynamics::{AIR_MEAN_FREE_PATH_M, AIR_VISCOSITY_PA_S, SILICON_DENSITY_KG_PER_M3};
use crate::error::{ActuatorError, nonnegative, positive};
use crate::plates::{BackElectrode, BackPotential, Fringing, PlateArray};
use crate::spring::{BeamKind, BeamSuspension, Suspension};

fn default_fringing() -> Fringing {
    Fringing::Palmer
}
fn default_back_potential() -> BackPotential {
    BackPotential::SameAsFront
}
fn one() -> f64 {
    1.0
}
fn default_beam_kind() -> BeamKind {
    BeamKind::ClampedGuided
}

/// How the pull-in voltage is applied (and so which threshold is observed).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum PullInProtocol {
    /// Slow ramp: the saddle-node of the static equilibrium, `max_x V_eq(x)` (default).
    #[default]
    QuasiStatic,
    /// Voltage step from rest: the lowest step that brings the shuttle to the stop to stay
    /// (needs `shuttle`); see the module docs.
    Step,
}

fn default_density() -> f64 {
    SILICON_DENSITY_KG_PER_M3
}
fn default_viscosity() -> f64 {
    AIR_VISCOSITY_PA_S
}
fn default_mean_free_path() -> f64 {
    AIR_MEAN_FREE_PATH_M
}

/// The moving part of the actuator and its surrounding gas, for the step protocol (drawn
/// dimensions; the array's undercut `u` is applied: widths `-2u`, spine length `-2u`, holes
/// `+2u`; the finger length is the as-built overlap plus `finger_root_length`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub struct ShuttleSpec {
    /// Drawn in-plane width of a movable finger (m).
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub finger_width: f64,
    /// Finger length at the root that does not overlap an electrode (m), default 0.
    #[serde(default, deserialize_with = "stiction_units::de::length_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub finger_root_length: f64,
    /// Drawn spine width (m).
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub spine_width: f64,
    /// Drawn spine length (m).
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub spine_length: f64,
    /// Drawn side of the square etch (release) holes in the spine (m), default 0.
    #[serde(default, deserialize_with = "stiction_units::de::length_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub spine_hole_size: f64,
    /// Number of etch holes in the spine, default 0.
    #[serde(default)]
    pub spine_hole_count: u32,
    /// Other moving planform area, taken as built (m^2), default 0 (e.g. gap-stop bumpers).
    #[serde(default, deserialize_with = "stiction_units::de::area_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub extra_area: f64,
    /// Density of the structural layer (kg/m^3, a plain number), default 2329 (silicon).
    #[serde(default = "default_density")]
    pub density: f64,
    /// Dynamic viscosity of the gas (Pa s, a plain number), default 1.81e-5 (air, 20 degC).
    #[serde(default = "default_viscosity")]
    pub viscosity: f64,
    /// Mean free path of the gas molecules (m), default 68 nm (air, 1 atm); 0 for continuum.
    #[serde(default = "default_mean_free_path", deserialize_with = "stiction_units::de::length_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub mean_free_path: f64,
    /// Gap between the moving structure and the substrate below (m), for Couette shear damping;
    /// absent: no Couette term.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_length_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub substrate_gap: Option<f64>,
}

/// A gap-closing plate array with its suspension, as written in a scenario file.
///
/// Either `front_gap` (geometry) or `conversion_factor` (the paper's `a = F/V^2`, section 5, at
/// `operating_travel`) defines the electrostatics; from a conversion factor the front gap that the
/// plate geometry implies is inferred ([`crate::plates::infer_front_gap_m`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub struct ArraySpec {
    /// Free text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// Number of movable plates (fingers) `n`.
    pub plate_count: u32,
    /// Drawn overlap length of a plate with its electrode `l` (m).
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub overlap_length: f64,
    /// Plate (structural layer) thickness `t` (m).
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub thickness: f64,
    /// Drawn front gap `g_f` at zero travel (m). Give this or `conversion_factor`.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_length_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub front_gap: Option<f64>,
    /// Conversion factor `a = F/V^2` at `operating_travel` (N/V^2), paper section 5. Give this
    /// or `front_gap`.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_force_per_voltage_squared_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub conversion_factor: Option<f64>,
    /// The plate geometry `conversion_factor` was measured on (a calibration states what it
    /// calibrates). The conversion factor fixes the as-built front gap of that geometry; when the
    /// array's own `plate_count`, `overlap_length` or `thickness` differ, the same gap is carried
    /// over and the conversion factor is re-derived for the array's geometry
    /// ([`ArraySpec::calibration_rederived`] says so). Absent: the calibration is taken as
    /// measured on this array's geometry (and cannot be checked).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub calibrated_on: Option<CalibrationGeometry>,
    /// Travel at which the conversion factor is defined/evaluated (m), default 0 (initial gap).
    /// For the meter's clamp array: the travel at which the shoe touches the wall.
    #[serde(default, deserialize_with = "stiction_units::de::length_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub operating_travel: f64,
    /// Drawn back (anti-gap) electrode gap `g_b` (m); absent: no back electrode.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_length_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub back_gap: Option<f64>,
    /// Potential of the back electrode, default `same_as_front` (pulls the other way).
    #[serde(default = "default_back_potential")]
    pub back_potential: BackPotential,
    /// Capacitance model, default `palmer`.
    #[serde(default = "default_fringing")]
    pub fringing: Fringing,
    /// Relative permittivity of the gap medium, default 1.
    #[serde(default = "one", deserialize_with = "stiction_units::de::dimensionless_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub relative_permittivity: f64,
    /// Process undercut per edge `u` (m), default 0; see the module table.
    #[serde(default, deserialize_with = "stiction_units::de::length_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub undercut: f64,
    /// The suspension.
    pub spring: SpringSpec,
    /// Optional gap stop.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stop: Option<StopSpec>,
    /// Optional finger bending (absent: rigid plates).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub finger_bending: Option<FingerBendingSpec>,
    /// Cross-section of the comb (drawn finger and electrode widths, substrate), needed by
    /// `fringing: "cross_section"` and ignored by the other models; default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub comb: Option<CombSpec>,
    /// How pull-in is applied and observed, default `quasi_static` (slow ramp); `step` (voltage
    /// step from rest, dynamic pull-in) needs `shuttle` and `stop`. See [`crate::protocol`].
    #[serde(default, skip_serializing_if = "is_quasi_static")]
    pub pull_in_protocol: PullInProtocol,
    /// Moving mass and air-damping inputs for `pull_in_protocol: "step"`; ignored otherwise;
    /// default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shuttle: Option<ShuttleSpec>,
}

/// The plate geometry a conversion factor was measured on (drawn dimensions, like the array's).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub struct CalibrationGeometry {
    /// Number of movable plates of the calibrated array.
    pub plate_count: u32,
    /// Drawn overlap length of the calibrated array (m).
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub overlap_length: f64,
    /// Plate thickness of the calibrated array (m).
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub thickness: f64,
}

fn is_quasi_static(p: &PullInProtocol) -> bool {
    *p == PullInProtocol::QuasiStatic
}

/// The comb's cross-section for `fringing: "cross_section"` (drawn widths; the undercut narrows
/// both by `2u`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub struct CombSpec {
    /// Drawn in-plane width of a movable finger (m).
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub finger_width: f64,
    /// Drawn in-plane width of a fixed electrode finger (m).
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub electrode_width: f64,
    /// Conducting substrate (handle wafer) below the device layer; absent: open below.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub substrate: Option<SubstrateSpec>,
}

/// Substrate under the device layer.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub struct SubstrateSpec {
    /// Distance from the bottom of the device layer to the substrate (m), e.g. the buried oxide
    /// thickness (the oxide is etched away under released structures).
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub gap: f64,
    /// `plates` (default: the spine's potential, usually ground) or `electrodes`.
    #[serde(default = "default_substrate_potential")]
    pub potential: SubstratePotential,
}

fn default_substrate_potential() -> SubstratePotential {
    SubstratePotential::Plates
}

/// Suspension: exactly one of `stiffness` and `beams`, plus optional extra stiffness.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub struct SpringSpec {
    /// Given main stiffness (N/m).
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_stiffness_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub stiffness: Option<f64>,
    /// Main stiffness from beam geometry.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub beams: Option<BeamsSpec>,
    /// Extra stiffness in parallel (N/m), default 0 (e.g. the paper's pull connection beam).
    #[serde(default, deserialize_with = "stiction_units::de::stiffness_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub parallel_stiffness: f64,
    /// Extra stiffness in series (N/m), default none (rigid link).
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_stiffness_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub series_stiffness: Option<f64>,
}

/// Suspension beams (drawn dimensions; the array's undercut narrows the width by `2u`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub struct BeamsSpec {
    /// `clamped_guided` (default) or `folded`.
    #[serde(default = "default_beam_kind")]
    pub kind: BeamKind,
    /// Number of beams (clamped-guided) or folds (folded) in parallel.
    pub count: u32,
    /// Beam length (m).
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub length: f64,
    /// Drawn in-plane beam width (m).
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub width: f64,
    /// Beam thickness (m), default: the array's `thickness`.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_length_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub thickness: Option<f64>,
    /// Young's modulus (Pa).
    #[serde(deserialize_with = "stiction_units::de::pressure_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub youngs_modulus: f64,
    /// Poisson's ratio; when given the plane-strain modulus `E/(1-nu^2)` is used.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_dimensionless",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub poisson_ratio: Option<f64>,
}

/// Gap stop.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub struct StopSpec {
    /// Drawn travel to the stop (m); the undercut adds `2u`.
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub travel: f64,
    /// Contact standoff at the stop (m), default 0: the stop faces touch this much before the
    /// nominal (mean-plane) stop travel, through sidewall roughness, etch taper or debris, so the
    /// plates stop at `travel + 2u - contact_standoff` and keep a gap larger by the standoff.
    #[serde(default, deserialize_with = "stiction_units::de::length_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub contact_standoff: f64,
}

/// Finger bending inputs (drawn width; the undercut narrows it by `2u`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub struct FingerBendingSpec {
    /// Whether bending is modelled, default true (false keeps the inputs but rigid fingers).
    #[serde(default = "yes")]
    pub enabled: bool,
    /// Non-overlapping length at the finger root (m).
    #[serde(deserialize_with = "stiction_units::de::length_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub root_length: f64,
    /// Drawn in-plane finger width (m).
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub width: f64,
    /// Young's modulus (Pa).
    #[serde(deserialize_with = "stiction_units::de::pressure_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub youngs_modulus: f64,
}

fn yes() -> bool {
    true
}

impl ArraySpec {
    /// The as-built plate array (undercut applied, front gap inferred from the conversion factor
    /// when that is what the spec gives). Errors name the field.
    pub fn plates(&self) -> Result<PlateArray, ActuatorError> {
        let u = nonnegative("undercut", self.undercut)?;
        nonnegative("operating_travel", self.operating_travel)?;
        if self.plate_count == 0 {
            return Err(ActuatorError::InvalidField {
                field: "plate_count".into(),
                value: 0.0,
                expected: "at least 1 plate".into(),
            });
        }
        let mut plates = PlateArray {
            plate_count: self.plate_count,
            overlap_length_m: positive("overlap_length", self.overlap_length)? - u,
            thickness_m: positive("thickness", self.thickness)?,
            front_gap_m: 1.0, // set below
            back: match self.back_gap {
                Some(g) => {
                    Some(BackElectrode { gap_m: positive("back_gap", g)? + 2.0 * u, potential: self.back_potential })
                }
                None => None,
            },
            fringing: self.fringing,
            relative_permittivity: positive("relative_permittivity", self.relative_permittivity)?,
            comb: match &self.comb {
                Some(c) => Some(CombGeometry {
                    finger_width_m: positive("comb.finger_width (after undercut)", c.finger_width - 2.0 * u)?,
                    electrode_width_m: positive("comb.electrode_width (after undercut)", c.electrode_width - 2.0 * u)?,
                    substrate: match &c.substrate {
                        Some(sb) => {
                            Some(Substrate { gap_m: positive("comb.substrate.gap", sb.gap)?, potential: sb.potential })
                        }
                        None => None,
                    },
                }),
                None => None,
            },
        };
        if plates.overlap_length_m <= 0.0 {
            return Err(ActuatorError::Inconsistent(format!(
                "undercut = {u:e} m consumes the whole overlap_length = {:e} m",
                self.overlap_length
            )));
        }
        plates.front_gap_m = match (self.front_gap, self.conversion_factor) {
            (Some(g), None) => positive("front_gap", g)? + 2.0 * u,
            (None, Some(a)) => {
                // The calibration fixes the as-built gap of the geometry it was measured on; the
                // same gap (same process) serves the array's own geometry.
                let mut calibrated = plates;
                if let Some(c) = &self.calibrated_on {
                    if c.plate_count == 0 {
                        return Err(ActuatorError::InvalidField {
                            field: "calibrated_on.plate_count".into(),
                            value: 0.0,
                            expected: "at least 1 plate".into(),
                        });
                    }
                    calibrated.plate_count = c.plate_count;
                    calibrated.overlap_length_m = positive("calibrated_on.overlap_length", c.overlap_length)? - u;
                    calibrated.thickness_m = positive("calibrated_on.thickness", c.thickness)?;
                    if calibrated.overlap_length_m <= 0.0 {
                        return Err(ActuatorError::Inconsistent(format!(
                            "undercut = {u:e} m consumes the whole calibrated_on.overlap_length = {:e} m",
                            c.overlap_length
                        )));
                    }
                }
                crate::plates::infer_front_gap_m(&calibrated, self.operating_travel, positive("conversion_factor", a)?)?
            }
            (Some(_), Some(_)) => {
                return Err(ActuatorError::Inconsistent(
                    "give either `front_gap` or `conversion_factor`, not both".into(),
                ));
            }
            (None, None) => {
                return Err(ActuatorError::Inconsistent(
                    "one of `front_gap` or `conversion_factor` is required".into(),
                ));
            }
        };
        if self.calibrated_on.is_some() && self.conversion_factor.is_none() {
            return Err(ActuatorError::Inconsistent(
                "`calibrated_on` is given without `conversion_factor`: it states the geometry a conversion factor \
                 was measured on; remove it, or give the measured `conversion_factor`"
                    .into(),
            ));
        }
        if self.operating_travel >= plates.front_gap_m {
            return Err(ActuatorError::InvalidField {
                field: "operating_travel".into(),
                value: self.operating_travel,
                expected: format!("less than the as-built front gap {:e} m", plates.front_gap_m),
            });
        }
        plates.validate()?;
        Ok(plates)
    }

    /// When the conversion factor was calibrated on another plate geometry (`calibrated_on`
    /// differs from `plate_count`, `overlap_length` or `thickness`): a sentence naming the fields
    /// that differ and saying how the conversion factor was re-derived. None when it applies as given.
    pub fn calibration_rederived(&self) -> Option<String> {
        let (c, a) = (self.calibrated_on.as_ref()?, self.conversion_factor?);
        let mut diffs = Vec::new();
        if c.plate_count != self.plate_count {
            diffs.push(format!("plate_count = {} (calibrated on {})", self.plate_count, c.plate_count));
        }
        if c.overlap_length != self.overlap_length {
            diffs.push(format!(
                "overlap_length = {} (calibrated on {})",
                stiction_units::format_quantity(self.overlap_length, stiction_units::Dimension::Length),
                stiction_units::format_quantity(c.overlap_length, stiction_units::Dimension::Length)
            ));
        }
        if c.thickness != self.thickness {
            diffs.push(format!(
                "thickness = {} (calibrated on {})",
                stiction_units::format_quantity(self.thickness, stiction_units::Dimension::Length),
                stiction_units::format_quantity(c.thickness, stiction_units::Dimension::Length)
            ));
        }
        if diffs.is_empty() {
            return None;
        }
        Some(format!(
            "conversion_factor = {a:.4e} N/V^2 was measured on another geometry (calibrated_on) than this array's {}: \
             the as-built front gap it implies is kept (same process) and the conversion factor re-derived for \
             this geometry; to use a measurement of this array, state it in `conversion_factor` and set \
             `calibrated_on` to this geometry",
            diffs.join(", ")
        ))
    }

    /// The as-built suspension.
    pub fn suspension(&self) -> Result<Suspension, ActuatorError> {
        let s = &self.spring;
        let main = match (s.stiffness, &s.beams) {
            (Some(k), None) => positive("spring.stiffness", k)?,
            (None, Some(b)) => {
                let beams = BeamSuspension {
                    kind: b.kind,
                    count: b.count,
                    length_m: b.length,
                    width_m: b.width,
                    thickness_m: b.thickness.unwrap_or(self.thickness),
                    youngs_modulus_pa: b.youngs_modulus,
                    plane_strain_poisson: b.poisson_ratio,
                };
                beams.validate()?;
                let built = beams.with_undercut(self.undercut).map_err(|_| {
                    ActuatorError::Inconsistent(format!(
                        "undercut = {:e} m leaves no beam: spring.beams.width = {:e} m",
                        self.undercut, b.width
                    ))
                })?;
                built.stiffness_n_per_m()
            }
            (Some(_), Some(_)) => {
                return Err(ActuatorError::Inconsistent("spring: give either `stiffness` or `beams`, not both".into()));
            }
            (None, None) => {
                return Err(ActuatorError::Inconsistent("spring: one of `stiffness` or `beams` is required".into()));
            }
        };
        let out = Suspension {
            main_stiffness_n_per_m: main,
            parallel_stiffness_n_per_m: s.parallel_stiffness,
            series_stiffness_n_per_m: s.series_stiffness,
        };
        out.validate()?;
        Ok(out)
    }

    /// The as-built stop travel `x_s = travel + 2u - contact_standoff` (m), if any.
    pub fn stop_travel_m(&self) -> Result<Option<f64>, ActuatorError> {
        match &self.stop {
            None => Ok(None),
            Some(s) => {
                positive("stop.travel", s.travel)?;
                nonnegative("stop.contact_standoff", s.contact_standoff)?;
                let x = s.travel + 2.0 * self.undercut - s.contact_standoff;
                positive("stop.travel (after undercut and contact_standoff)", x).map(Some)
            }
        }
    }

    /// Converts to the model (SI, as built). Errors name the field, its value and what was
    /// expected.
    pub fn to_model(&self) -> Result<GapClosingActuator, ActuatorError> {
        let plates = self.plates()?;
        let suspension = self.suspension()?;
        let stop = self.stop_travel_m()?;
        let bending = match &self.finger_bending {
            Some(b) if b.enabled => {
                let w = b.width - 2.0 * self.undercut;
                Some(FingerBending {
                    root_length_m: nonnegative("finger_bending.root_length", b.root_length)?,
                    width_m: positive("finger_bending.width (after undercut)", w)?,
                    youngs_modulus_pa: positive("finger_bending.youngs_modulus", b.youngs_modulus)?,
                })
            }
            _ => None,
        };
        GapClosingActuator::new(plates, suspension, stop, bending)
    }
}
